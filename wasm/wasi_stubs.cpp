// wasi_stubs.cpp — the three WASI calls libc's stdio links in (reached only when the C++ code
// aborts and writes its message to stderr), defined here so that the module imports nothing: a
// page or node instantiates it with no import object at all. Writes fail with EBADF (nothing is
// shown; the abort itself still traps, and penumbra_emitter.js reports the trap).
#include <cstdint>

extern "C" {

std::int32_t __imported_wasi_snapshot_preview1_fd_write(std::int32_t, std::int32_t, std::int32_t, std::int32_t) {
    return 8; // __WASI_ERRNO_BADF
}

std::int32_t __imported_wasi_snapshot_preview1_fd_seek(std::int32_t, std::int64_t, std::int32_t, std::int32_t) {
    return 70; // __WASI_ERRNO_SPIPE
}

std::int32_t __imported_wasi_snapshot_preview1_fd_close(std::int32_t) { return 0; }

} // extern "C"
