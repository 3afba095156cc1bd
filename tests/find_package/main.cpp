// Builds against the installed headers and reads the shaders generated at build time: two
// configurations on one target, each under its own macro.
#include <penumbra/config.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

static std::string read(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

int main() {
    constexpr penumbra::Config config{.slices = 8, .resolution = 256};
    const std::string occlusion = read(std::string(PENUMBRA_SHADER_DIR) + "/layout.json");
    const std::string pcss = read(std::string(PENUMBRA_SHADER_DIR_PCSS) + "/layout.json");
    std::printf("%d slices at %d², shaders in %s and %s\n", config.slices, config.resolution, PENUMBRA_SHADER_DIR,
                PENUMBRA_SHADER_DIR_PCSS);
    const bool ok = penumbra::texture_count(config) == 2 &&
                    occlusion.find("\"slice_placement\": \"adaptive\"") != std::string::npos &&
                    pcss.find("\"technique\": \"pcss\"") != std::string::npos &&
                    pcss.find("\"filter_samples\": 24") != std::string::npos &&
                    pcss.find("\"blocker_samples\": 12") != std::string::npos &&
                    pcss.find("\"rotate\": false") != std::string::npos;
    if (!ok) std::fprintf(stderr, "error: the generated layout.json files do not hold the configurations asked for\n");
    return ok ? 0 : 1;
}
