// tests/runtime/temp_dir.hpp — a fresh directory per test, removed afterwards.
#pragma once

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

namespace penumbra::playground::testing {

class TempDir {
public:
    TempDir() {
        // Unique per process and per instance, so parallel test runs do not collide.
        std::random_device rd;
        path_ = std::filesystem::temp_directory_path() /
                ("penumbra-runtime-" + std::to_string(rd()) + "-" + std::to_string(rd()));
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    std::string file(const std::string& name) const { return (path_ / name).string(); }

    // Writes `text` to `name` in this directory and returns the full path.
    std::string write(const std::string& name, const std::string& text) const {
        std::ofstream(file(name), std::ios::binary) << text;
        return file(name);
    }

private:
    std::filesystem::path path_;
};

} // namespace penumbra::playground::testing
