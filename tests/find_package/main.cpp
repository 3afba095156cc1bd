// Builds against the installed headers and reads the shaders generated at build time.
#include <penumbra/config.hpp>

#include <cstdio>

int main() {
    constexpr penumbra::Config config{.slices = 8, .resolution = 256};
    std::printf("%d slices at %d², shaders in %s\n", config.slices, config.resolution, PENUMBRA_SHADER_DIR);
    return penumbra::texture_count(config) == 2 ? 0 : 1;
}
