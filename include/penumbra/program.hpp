// penumbra/program.hpp — emitted shader text, as files grouped into programs.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace penumbra {

enum class Stage : std::uint8_t { vertex, fragment, compute };

// glslang picks the stage from the extension, so the file names keep it.
constexpr std::string_view stage_extension(Stage stage) {
    switch (stage) {
    case Stage::vertex: return "vert";
    case Stage::fragment: return "frag";
    case Stage::compute: return "comp";
    }
    return "";
}

// The stage's name in layout.json ("stages"): "vertex", "fragment", "compute".
constexpr std::string_view stage_name(Stage stage) {
    switch (stage) {
    case Stage::vertex: return "vertex";
    case Stage::fragment: return "fragment";
    case Stage::compute: return "compute";
    }
    return "";
}

// One complete shader stage.
struct ShaderFile {
    std::string file_name; // e.g. "penumbra_slicing.frag"; unique within an emission
    Stage stage = Stage::fragment;
    std::string text;

    friend constexpr bool operator==(const ShaderFile&, const ShaderFile&) = default;
};

// Stages that are linked together into one GL program (or one Vulkan pipeline).
struct Program {
    std::string name; // e.g. "slicing", "nbuffer_level", "shading_example", "shading_deferred"
    std::vector<ShaderFile> stages;

    friend constexpr bool operator==(const Program&, const Program&) = default;
};

// Emitted text carries marker comments `// @penumbra:<chunk>` at the start of every chunk an
// emitter function wrote, so a compiler error on line N can be traced back to the C++ that
// wrote it: the chunk is the last marker at or above line N (1-based). Empty when none.
constexpr std::string_view chunk_at_line(std::string_view text, int line) {
    constexpr std::string_view marker = "// @penumbra:";
    std::string_view chunk;
    int current = 1;
    std::size_t start = 0;
    while (start <= text.size() && current <= line) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) end = text.size();
        std::string_view row = text.substr(start, end - start);
        if (std::size_t at = row.find(marker); at != std::string_view::npos) {
            std::string_view rest = row.substr(at + marker.size());
            chunk = rest.substr(0, rest.find_first_of(" \t\r"));
        }
        start = end + 1;
        ++current;
    }
    return chunk;
}

} // namespace penumbra
