// tests/hostile/child_process.hpp — a tool run as a user runs it, with the limits a hostile
// environment sets: a timeout, a file-size limit (a "full disk" for every file it writes), another
// user id, no display. The exit status, stdout and stderr (each cut at 1 MiB) come back.
#pragma once

#include <fcntl.h>
#include <grp.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace hostile {

// The tool under test: the built one, or another build of it named by `variable` (scripts/sanitize.sh
// --quick runs these tests against a sanitized penumbra-gen that way).
inline std::string tool_path(const char* variable, const char* built) {
    const char* other = std::getenv(variable);
    return other && *other ? other : built;
}

struct ChildLimits {
    unsigned timeout_s = 20;             // SIGALRM after this
    std::optional<rlim_t> file_size;     // RLIMIT_FSIZE: writes past it fail with EFBIG (SIGXFSZ ignored)
    std::optional<uid_t> uid;            // run as this user (and group), when we are root
    std::filesystem::path cwd;           // working directory (default: the current one)
};

struct ChildRun {
    int exit_code = -1; // when it exited
    int signal = 0;     // when a signal ended it (SIGALRM: past the timeout)
    std::string out, err;

    // Lines of stderr that start with "error:".
    int error_lines() const {
        std::istringstream lines(err);
        int count = 0;
        for (std::string line; std::getline(lines, line);) count += line.rfind("error:", 0) == 0;
        return count;
    }
    std::string first_error_line() const {
        std::istringstream lines(err);
        for (std::string line; std::getline(lines, line);)
            if (line.rfind("error:", 0) == 0) return line;
        return {};
    }
    // AddressSanitizer, LeakSanitizer or UndefinedBehaviorSanitizer wrote a report.
    bool sanitizer_report() const {
        return err.find("Sanitizer") != std::string::npos || err.find("runtime error:") != std::string::npos;
    }
    std::string outcome() const {
        return signal ? "signal " + std::to_string(signal) : "exit " + std::to_string(exit_code);
    }
};

inline std::string read_capped(const std::filesystem::path& path, std::size_t cap = 1u << 20) {
    std::string text;
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return {};
    char buffer[65536];
    for (ssize_t n; text.size() < cap && (n = ::read(fd, buffer, sizeof buffer)) > 0;)
        text.append(buffer, std::min<std::size_t>(std::size_t(n), cap - text.size()));
    ::close(fd);
    return text;
}

// A started child: its pid and where its stdout and stderr go.
struct Started {
    pid_t pid = -1;
    std::string out_file, err_file;
};

// Starts `program` with `args`; stdin is /dev/null, DISPLAY and WAYLAND_DISPLAY are unset.
inline Started start_child(const std::string& program, const std::vector<std::string>& args,
                           const ChildLimits& limits = {}) {
    static int counter = 0;
    const std::filesystem::path base = std::filesystem::temp_directory_path() /
                                       ("penumbra-hostile-io-" + std::to_string(::getpid()) + "-" +
                                        std::to_string(++counter));
    Started started{-1, base.string() + ".out", base.string() + ".err"};
    std::vector<char*> argv{const_cast<char*>(program.c_str())};
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    started.pid = ::fork();
    if (started.pid < 0) throw std::runtime_error("fork failed");
    if (started.pid == 0) {
        const int in = ::open("/dev/null", O_RDONLY);
        const int out = ::open(started.out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        const int err = ::open(started.err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0666);
        if (in < 0 || out < 0 || err < 0 || ::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0) ::_exit(125);
        if (!limits.cwd.empty() && ::chdir(limits.cwd.c_str()) != 0) ::_exit(125);
        ::unsetenv("DISPLAY");
        ::unsetenv("WAYLAND_DISPLAY");
        if (limits.file_size) {
            ::signal(SIGXFSZ, SIG_IGN); // kept across exec: a write past the limit fails with EFBIG
            const rlimit limit{*limits.file_size, *limits.file_size};
            if (::setrlimit(RLIMIT_FSIZE, &limit) != 0) ::_exit(125);
        }
        if (limits.uid && (::setgroups(0, nullptr) != 0 || ::setgid(*limits.uid) != 0 || ::setuid(*limits.uid) != 0))
            ::_exit(125);
        ::alarm(limits.timeout_s); // kept across exec
        ::execv(argv[0], argv.data());
        ::_exit(126);
    }
    return started;
}

// Waits for a started child and collects what it printed.
inline ChildRun finish_child(const Started& started) {
    int status = 0;
    while (::waitpid(started.pid, &status, 0) < 0) {
    }
    ChildRun run;
    if (WIFEXITED(status)) run.exit_code = WEXITSTATUS(status);
    if (WIFSIGNALED(status)) run.signal = WTERMSIG(status);
    run.out = read_capped(started.out_file);
    run.err = read_capped(started.err_file);
    std::filesystem::remove(started.out_file);
    std::filesystem::remove(started.err_file);
    return run;
}

inline ChildRun run_child(const std::string& program, const std::vector<std::string>& args,
                          const ChildLimits& limits = {}) {
    return finish_child(start_child(program, args, limits));
}

// Several runs, as many at a time as there are processors (the fuzz driver's batches).
struct ChildJob {
    std::string program;
    std::vector<std::string> args;
    ChildLimits limits;
};
inline std::vector<ChildRun> run_children(const std::vector<ChildJob>& jobs) {
    const std::size_t parallel = std::max<long>(1, ::sysconf(_SC_NPROCESSORS_ONLN));
    std::vector<ChildRun> runs(jobs.size());
    std::vector<std::pair<std::size_t, Started>> running;
    for (std::size_t next = 0; next < jobs.size() || !running.empty();) {
        while (next < jobs.size() && running.size() < parallel) {
            running.emplace_back(next, start_child(jobs[next].program, jobs[next].args, jobs[next].limits));
            ++next;
        }
        runs[running.front().first] = finish_child(running.front().second);
        running.erase(running.begin());
    }
    return runs;
}

// A scratch directory removed at the end (its files made writable again first).
class Scratch {
public:
    explicit Scratch(const std::string& stem) {
        root_ = std::filesystem::temp_directory_path() / ("penumbra-" + stem + "-" + std::to_string(::getpid()));
        std::filesystem::create_directories(root_);
    }
    ~Scratch() {
        std::error_code ec;
        std::filesystem::remove_all(root_, ec);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;
    const std::filesystem::path& root() const { return root_; }
    // A new path: "mesh.obj" → ROOT/mesh-7.obj.
    std::filesystem::path fresh(const std::string& stem) {
        const std::size_t dot = std::min(stem.find('.'), stem.size());
        return root_ / (stem.substr(0, dot) + "-" + std::to_string(++count_) + stem.substr(dot));
    }
    std::filesystem::path write(const std::string& stem, const std::string& text) {
        const std::filesystem::path path = fresh(stem);
        const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
        if (fd >= 0) {
            for (std::size_t done = 0; done < text.size();) {
                const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
                if (n <= 0) break;
                done += std::size_t(n);
            }
            ::close(fd);
        }
        return path;
    }

private:
    std::filesystem::path root_;
    int count_ = 0;
};

} // namespace hostile
