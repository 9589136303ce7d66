// sphbasis CLI support: check_stdout (see stdout_check.hpp).
#include "stdout_check.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#endif

namespace sphbasis::cli {

bool stdout_is_open() noexcept {
#if defined(__unix__) || defined(__APPLE__)
    return fcntl(1, F_GETFD) != -1 || errno != EBADF;
#else
    return true;
#endif
}

void check_stdout(bool flush) {
    bool failed = false;
    int err = 0;
    if (flush) {
        // stdout first (errno then names the reason), then std::cout, which is synchronised
        // with stdio and writes through stdout's buffer.
        errno = 0;
        if (std::fflush(stdout) != 0) {
            failed = true;
            err = errno;
        }
        errno = 0;
        std::cout.flush();
        if (!failed && !std::cout) {
            failed = true;
            err = errno;
        }
    }
    if (!failed && (std::ferror(stdout) || !std::cout)) {
        // An earlier implicit flush failed; errno may have changed since. Flushing again
        // retries what is left in the buffer and gives the reason afresh (if anything is).
        failed = true;
        std::clearerr(stdout);
        errno = 0;
        if (std::fflush(stdout) != 0) err = errno;
    }
    if (!failed) return;
    std::string msg = "cannot write standard output";
    if (err != 0) msg += std::string(": ") + std::strerror(err);
    throw OutputError(msg);
}

}  // namespace sphbasis::cli
