// Runs a command line under a virtual display (`xvfb-run -a`) and returns the command's own exit
// status, not xvfb-run's.
//
// Why not xvfb-run's status: it mixes the command's with its own housekeeping. On a fresh CI machine,
// under parallel ctest, xvfb-run has exited 5 ("problem while cleaning up temporary directory") after
// the command under it had finished exactly as the test expected, and the test read 5 for the
// command's status. So the command writes its status to a file in `dir`, and xvfb-run's own messages
// go to a log of their own that a failing test prints.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

namespace penumbra::test {

struct VirtualDisplayRun {
    int exit_code = -1;      // the command's exit status; -1 when it never ran or never reported
    std::string display_log; // what xvfb-run and Xvfb printed, with xvfb-run's own exit status
};

inline bool has_virtual_display() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

// `command_line` runs by `sh` with `dir` as its working folder; it redirects its own output.
// The sanitizer runtimes scripts/sanitize.sh preloads into test drivers are not passed on: neither
// Xvfb nor the (unsanitized) playground may inherit them.
inline VirtualDisplayRun run_under_virtual_display(const std::filesystem::path& dir,
                                                   const std::string& command_line) {
    const std::filesystem::path script = dir / "display_run.sh", status = dir / "display_exit.txt",
                                log = dir / "display_log.txt";
    std::filesystem::remove(status);
    std::ofstream(script) << command_line << "\necho $? > '" << status.string() << "'\n";
    const std::string command = "cd '" + dir.string() + "' && env -u LD_PRELOAD xvfb-run -a sh '" +
                                script.string() + "' > '" + log.string() + "' 2>&1";
    const int display_status = std::system(command.c_str());

    VirtualDisplayRun run;
    std::ifstream status_file(status);
    if (!(status_file >> run.exit_code)) run.exit_code = -1;
    std::ifstream log_file(log);
    run.display_log.assign(std::istreambuf_iterator<char>(log_file), std::istreambuf_iterator<char>());
    run.display_log += "(xvfb-run returned " + std::to_string(display_status) + ")\n";
    return run;
}

} // namespace penumbra::test
