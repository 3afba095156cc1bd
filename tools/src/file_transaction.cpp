#include "file_transaction.hpp"

#include "printable.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <set>

namespace penumbra_gen {
namespace fs = std::filesystem;
namespace {

// 'path', escaped (built with append: GCC 12 warns wrongly on "'" + std::string, bug 105329).
std::string quoted(const fs::path& path) {
    std::string out(1, '\'');
    out += printable(path.string(), 200);
    out += '\'';
    return out;
}

std::string reason() { return std::strerror(errno); }

bool exists_no_follow(const fs::path& path, struct stat* info = nullptr) {
    struct stat local {};
    return ::lstat(path.c_str(), info ? info : &local) == 0;
}

// A name next to `path` that no other writer uses: ".NAME.penumbra-KIND-PID-N".
fs::path side_name(const fs::path& path, const char* kind) {
    static std::atomic<unsigned> counter{0};
    std::string name(1, '.');
    name += path.filename().string();
    name += ".penumbra-";
    name += kind;
    name += '-';
    name += std::to_string(::getpid());
    name += '-';
    name += std::to_string(counter++);
    return path.parent_path() / name;
}

// Writes `bytes` to a new file at `temp`; errno is kept for the message on failure.
bool write_new_file(const fs::path& temp, const std::string& bytes) {
    const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0) return false;
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            if (n == 0) errno = EIO;
            const int saved = errno;
            ::close(fd);
            errno = saved;
            return false;
        }
        done += static_cast<std::size_t>(n);
    }
    return ::close(fd) == 0; // a network file system may report a failed write only here
}

struct Placed {
    fs::path shown;            // the destination as the caller named it, for messages
    fs::path path, temp, backup; // path: the file replaced (a symbolic link resolved)
    bool temp_written = false;
    bool had_old = false;   // `backup` holds the previous file
    bool moved_old = false; // the previous file was renamed away (no hard link): `path` is missing
    bool placed = false;    // `temp` was renamed to `path`
};

} // namespace

std::string commit(const FileChanges& changes) {
    std::vector<fs::path> made_directories;
    std::vector<Placed> steps(changes.writes.size());
    std::vector<std::pair<fs::path, fs::path>> removed; // original, backup

    auto roll_back = [&](std::string message) {
        for (auto it = removed.rbegin(); it != removed.rend(); ++it) ::rename(it->second.c_str(), it->first.c_str());
        for (auto it = steps.rbegin(); it != steps.rend(); ++it) {
            if (it->had_old) {
                if (it->placed || it->moved_old) ::rename(it->backup.c_str(), it->path.c_str());
                else ::unlink(it->backup.c_str());
            } else if (it->placed) {
                ::unlink(it->path.c_str());
            }
            if (it->temp_written && !it->placed) ::unlink(it->temp.c_str());
        }
        for (auto it = made_directories.rbegin(); it != made_directories.rend(); ++it) ::rmdir(it->c_str());
        return message;
    };

    // 1. Missing parent directories, outermost first.
    if (changes.create_directories) {
        std::set<fs::path> parents;
        for (const FileWrite& w : changes.writes) parents.insert(w.path.parent_path());
        for (const fs::path& parent : parents) {
            std::vector<fs::path> missing;
            for (fs::path p = parent; !p.empty() && !exists_no_follow(p); p = p.parent_path()) {
                missing.push_back(p);
                if (p == p.parent_path()) break;
            }
            for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
                if (::mkdir(it->c_str(), 0777) != 0)
                    return roll_back("cannot create directory " + quoted(*it) + ": " + reason());
                made_directories.push_back(*it);
            }
        }
    }

    // 2. Every destination can take a file, then every file to its temporary name.
    for (std::size_t i = 0; i < changes.writes.size(); ++i) {
        const fs::path& path = changes.writes[i].path;
        fs::path target = path;
        struct stat info {};
        if (exists_no_follow(path, &info)) {
            // Only a regular file is replaced (a link to one: the file it leads to). Renaming over
            // a device, a FIFO or a socket (/dev/stdout, /dev/full) would remove the node itself.
            if (S_ISLNK(info.st_mode)) {
                std::error_code ec;
                if (::stat(path.c_str(), &info) != 0 || (target = fs::canonical(path, ec), ec))
                    return roll_back("cannot write " + quoted(path) +
                                     ": it is a symbolic link that leads nowhere; allowed: a regular file or "
                                     "nothing at that path");
            }
            if (!S_ISREG(info.st_mode))
                return roll_back("cannot write " + quoted(path) + ": it is " +
                                 (S_ISDIR(info.st_mode) ? "a directory" : "not a regular file (a device, FIFO or socket)") +
                                 "; allowed: a regular file or nothing at that path");
        }
        steps[i].shown = path;
        steps[i].path = target;
        steps[i].temp = side_name(target, "tmp");
        if (!write_new_file(steps[i].temp, changes.writes[i].bytes)) {
            const std::string why = reason();
            ::unlink(steps[i].temp.c_str());
            return roll_back("cannot write " + quoted(path) + ": " + why);
        }
        steps[i].temp_written = true;
    }

    // 3. Into place. A previous file is kept under a backup name (a hard link, so that the
    // destination never goes missing; renamed away where links are not allowed) until the end.
    for (Placed& step : steps) {
        if (exists_no_follow(step.path)) {
            step.backup = side_name(step.path, "old");
            if (::link(step.path.c_str(), step.backup.c_str()) == 0) {
                step.had_old = true;
            } else if (::rename(step.path.c_str(), step.backup.c_str()) == 0) {
                step.had_old = step.moved_old = true;
            } else {
                return roll_back("cannot replace " + quoted(step.shown) + ": " + reason());
            }
        }
        if (::rename(step.temp.c_str(), step.path.c_str()) != 0)
            return roll_back("cannot write " + quoted(step.shown) + ": " + reason());
        step.placed = true;
    }

    // 4. Removals, renamed away first so that they can come back.
    for (const fs::path& path : changes.removals) {
        if (!exists_no_follow(path)) continue;
        const fs::path backup = side_name(path, "old");
        if (::rename(path.c_str(), backup.c_str()) != 0)
            return roll_back("cannot remove " + quoted(path) + ": " + reason());
        removed.emplace_back(path, backup);
    }

    // 5. Done: the previous versions go.
    for (const Placed& step : steps)
        if (step.had_old) ::unlink(step.backup.c_str());
    for (const auto& [path, backup] : removed) ::unlink(backup.c_str());
    return {};
}

std::string write_file_atomically(const fs::path& path, std::string bytes) {
    FileChanges changes;
    changes.writes.push_back({path, std::move(bytes)});
    return commit(changes);
}

} // namespace penumbra_gen
