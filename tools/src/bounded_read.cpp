#include "bounded_read.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

namespace penumbra_gen {
namespace {

std::string kind_of(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    if (S_ISSOCK(mode)) return "a socket";
    return "a special file";
}

} // namespace

std::string size_text(std::size_t bytes) {
    if (bytes >= (std::size_t(1) << 20) && bytes % (std::size_t(1) << 20) == 0)
        return std::to_string(bytes >> 20) + " MiB";
    return std::to_string(bytes) + " bytes";
}

BoundedRead read_bounded_file(const std::string& path, std::size_t limit) {
    const std::string allowed = "; allowed: a regular file of at most " + size_text(limit);
    struct stat info {};
    if (::stat(path.c_str(), &info) != 0)
        return {std::nullopt, errno == ENOENT ? std::string("no such file") : std::string(std::strerror(errno))};
    // Checked before opening, so that opening a FIFO cannot block; O_NONBLOCK and the fstat below
    // cover a file replaced between the two calls.
    if (!S_ISREG(info.st_mode))
        return {std::nullopt, "it is " + kind_of(info.st_mode) + ", not a regular file" + allowed};
    if (static_cast<std::uintmax_t>(info.st_size) > limit)
        return {std::nullopt, "it has " + std::to_string(info.st_size) + " bytes" + allowed};
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return {std::nullopt, std::strerror(errno)};
    std::string text;
    std::string problem;
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        problem = "it is " + kind_of(info.st_mode) + ", not a regular file" + allowed;
    } else {
        // Read at most limit + 1 bytes: a file that grew past the limit is refused, not cut.
        text.resize(std::min<std::size_t>(static_cast<std::size_t>(info.st_size), limit) + 1);
        std::size_t used = 0;
        while (used < text.size()) {
            const ssize_t n = ::read(fd, text.data() + used, text.size() - used);
            if (n < 0 && errno == EINTR) continue;
            if (n < 0) {
                problem = std::strerror(errno);
                break;
            }
            if (n == 0) break;
            used += static_cast<std::size_t>(n);
            if (used == text.size() && used <= limit) text.resize(std::min(limit + 1, text.size() * 2));
        }
        if (problem.empty() && used > limit) problem = "it has more than " + size_text(limit) + allowed;
        text.resize(used);
    }
    ::close(fd);
    if (!problem.empty()) return {std::nullopt, problem};
    return {std::move(text), {}};
}

} // namespace penumbra_gen
