// penumbra-playground — the scenes rendered with the shaders Penumbra emits: headless to files
// (--headless, headless_job.hpp), or in the interactive window (window/). `--help` lists both.
#include "app/headless_job.hpp"
#include "app/options.hpp"

#include <penumbra_tools/cli.hpp>

#include <string>
#include <vector>

int main(int argc, char** argv) {
    using namespace penumbra::playground;
    const ParsedOptions parsed = parse_options(std::vector<std::string>(argv + 1, argv + argc));
    if (parsed.help) return penumbra::cli::print_usage(usage());
    if (!parsed.options)
        return penumbra::cli::fail(parsed.error + "\n(see penumbra-playground --help)", penumbra::cli::bad_arguments);
    if (parsed.options->headless) return run_headless(*parsed.options);
    return run_window(*parsed.options);
}
