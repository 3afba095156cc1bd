// bounded_read.hpp — an input file read whole, only if it is a regular file of at most `limit`
// bytes: a FIFO, a device (/dev/zero, /dev/urandom), a directory or a huge (even sparse) file is
// refused at once, before anything is read, and never blocks.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace penumbra_gen {

// Size limits of the inputs of both tools (stated in their --help).
inline constexpr std::size_t config_file_limit = std::size_t(1) << 20;  // --config: 1 MiB
inline constexpr std::size_t script_file_limit = std::size_t(1) << 20;  // --script: 1 MiB
inline constexpr std::size_t shader_file_limit = std::size_t(1) << 20;  // a watched shader file: 1 MiB
inline constexpr std::size_t obj_file_limit = std::size_t(256) << 20;   // an OBJ scene: 256 MiB

struct BoundedRead {
    std::optional<std::string> text; // the whole file, when it could be read
    std::string problem; // otherwise why not, e.g. "no such file", "it is a FIFO; allowed: a regular file of at most 1 MiB"
};

BoundedRead read_bounded_file(const std::string& path, std::size_t limit);

// "1 MiB", "256 MiB", "4096 bytes".
std::string size_text(std::size_t bytes);

} // namespace penumbra_gen
