// A consumer of the header-only core alone (add_subdirectory / FetchContent): emits one
// configuration at run time and checks what came out. Needs only a C++20 compiler.
#include <penumbra/emit.hpp>

#include <cstdio>

int main() {
    const penumbra::Config config{.slices = 8, .resolution = 256};
    const penumbra::Result<penumbra::Emission> result = penumbra::emit(config);
    if (!result.errors.empty()) {
        std::fprintf(stderr, "error: %s\n", result.errors.front().message.c_str());
        return 1;
    }
    const penumbra::Emission& emission = *result.value;
    const bool ok = !emission.programs.empty() &&
                    emission.snippet.text.find("float penumbraVisibility(") != std::string::npos &&
                    penumbra::to_json(emission.layout).find("\"layout_version\"") != std::string::npos;
    std::printf("%zu programs, %zu files\n", emission.programs.size(), emission.files().size());
    return ok ? 0 : 1;
}
