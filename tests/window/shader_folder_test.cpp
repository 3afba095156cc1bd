// The watched folder: own writes are not changes, saves are (once, after the debounce), identical
// saves are not, stale files go, hand edits are detected.
#include "shader_folder.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <thread>

#include <unistd.h>

using penumbra::ShaderFile;
using penumbra::playground::ShaderFolder;
using namespace std::chrono_literals;

namespace {

std::filesystem::path fresh_folder(const char* name) {
    const auto dir =
        std::filesystem::temp_directory_path() / ("penumbra-window-" + std::to_string(::getpid())) / name;
    std::filesystem::remove_all(dir);
    return dir;
}

void save(const std::filesystem::path& path, const std::string& text) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
}

} // namespace

TEST_CASE("shader folder: a save is reported once, after the debounce, with its text") {
    ShaderFolder folder(fresh_folder("save"), 100ms);
    REQUIRE(folder
                .write_generated({{"a.frag", penumbra::Stage::fragment, "void main() {}\n"},
                                  {"b.vert", penumbra::Stage::vertex, "void main() {}\n"}})
                .empty());
    const auto t0 = ShaderFolder::Clock::now();
    CHECK(folder.poll(t0).empty()); // our own writes are not changes
    CHECK(folder.hand_edited().empty());

    save(folder.path("a.frag"), "void main() { /* edited */ }\n");
    CHECK(folder.poll(t0 + 10ms).empty()); // seen, debouncing
    CHECK(folder.has_pending());
    CHECK(folder.poll(t0 + 60ms).empty());
    const auto changes = folder.poll(t0 + 120ms);
    REQUIRE(changes.size() == 1);
    CHECK(changes[0].file_name == "a.frag");
    CHECK(changes[0].text == "void main() { /* edited */ }\n");
    CHECK(folder.poll(t0 + 500ms).empty()); // reported once
    CHECK(folder.hand_edited() == std::vector<std::string>{"a.frag"});
}

TEST_CASE("shader folder: a burst of saves is reported once; saving identical text is no change") {
    ShaderFolder folder(fresh_folder("burst"), 100ms);
    REQUIRE(folder.write_generated({{"a.frag", penumbra::Stage::fragment, "one\n"}}).empty());
    const auto t0 = ShaderFolder::Clock::now();
    save(folder.path("a.frag"), "two\n");
    CHECK(folder.poll(t0).empty());
    save(folder.path("a.frag"), "three!\n"); // another size: seen even within one mtime tick
    CHECK(folder.poll(t0 + 80ms).empty());   // restarts the debounce
    CHECK(folder.poll(t0 + 150ms).empty());
    const auto changes = folder.poll(t0 + 190ms);
    REQUIRE(changes.size() == 1);
    CHECK(changes[0].text == "three!\n");

    std::this_thread::sleep_for(20ms);
    save(folder.path("a.frag"), "three!\n"); // new mtime, same text
    CHECK(folder.poll(t0 + 1s).empty());
    CHECK_FALSE(folder.has_pending());
}

TEST_CASE("shader folder: restore writes the generated text back; a new set removes stale files") {
    ShaderFolder folder(fresh_folder("restore"), 50ms);
    REQUIRE(folder
                .write_generated({{"a.frag", penumbra::Stage::fragment, "generated\n"},
                                  {"old.frag", penumbra::Stage::fragment, "x\n"}})
                .empty());
    const auto t0 = ShaderFolder::Clock::now();
    save(folder.path("a.frag"), "edited\n");
    folder.poll(t0);
    REQUIRE(folder.poll(t0 + 60ms).size() == 1);
    CHECK(folder.restore("a.frag").empty());
    CHECK(folder.restore("nope.frag") == "no generated file nope.frag");
    folder.poll(t0 + 100ms);
    const auto changes = folder.poll(t0 + 200ms);
    REQUIRE(changes.size() == 1);
    CHECK(changes[0].text == "generated\n");
    CHECK(folder.hand_edited().empty());

    REQUIRE(folder.write_generated({{"a.frag", penumbra::Stage::fragment, "generated\n"}}).empty());
    CHECK_FALSE(std::filesystem::exists(folder.path("old.frag")));
    CHECK(std::filesystem::exists(folder.path("a.frag")));
}
