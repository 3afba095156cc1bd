// Placeholder until the window lands (issue 4): says so and points to --headless.
#include "options.hpp"

#include <iostream>

namespace penumbra::playground {

int run_window(const PlaygroundOptions&) {
    std::cerr << "error: the interactive window is not built yet; use --headless\n";
    return 1;
}

} // namespace penumbra::playground
