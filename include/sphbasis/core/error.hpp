// sphbasis: the one way the library reports bad input at its API boundaries.
//
// Policy (also in docs/conventions.md):
//   * Checked at API boundaries (run-time band or function counts, buffer sizes, null buffers,
//     ranges of parameters, files): std::invalid_argument with the message
//         "sphbasis::<function>(): expected <what was expected>, got <what was passed>"
//     where <function> is the public name as a user writes it after `sphbasis::`
//     (e.g. "sh::eval", "param::LatLong", "imse::Fit::score"). std::runtime_error, with the
//     same shape, for failures that depend on values rather than arguments (a singular Gram
//     matrix, a file that cannot be read).
//   * A null pointer is an error only where it would be read or written: a null buffer with a
//     size of zero is accepted.
//   * Hot per-direction kernels do not throw: SPHBASIS_ASSERT in debug builds, a documented
//     finite result for every finite input, and the pole (0, 0, 1) for directions that are
//     zero or not finite.
//   * Compile-time misuse: one static_assert sentence.
//   * Routines whose tables grow with their size (sphere_rule, sh::Rotation, sh::TripleTable)
//     state their memory in their doc comment and check it before allocating against
//     SPHBASIS_MAX_TABLE_BYTES (default 4 GiB; define it before including sphbasis to change
//     it): std::invalid_argument naming the bytes needed, instead of working for seconds and
//     failing in operator new.
// The message is built out of line (SPHBASIS_NOINLINE), so an inlined check costs one compare.
#pragma once

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

#include "../config.hpp"

/// The largest table (bytes) a routine allocates for its size; see the policy above.
#ifndef SPHBASIS_MAX_TABLE_BYTES
#define SPHBASIS_MAX_TABLE_BYTES (4ull << 30)
#endif

namespace sphbasis::detail {

/// "sphbasis::fn(): expected <expected>" (fn without the "sphbasis::" prefix and the "()").
inline std::string error_message(const char* fn, const std::string& expected) {
    return std::string("sphbasis::") + fn + "(): expected " + expected;
}

/// Throws std::invalid_argument("sphbasis::fn(): expected <expected>").
[[noreturn]] SPHBASIS_NOINLINE inline void throw_invalid(const char* fn,
                                                         const std::string& expected) {
    throw std::invalid_argument(error_message(fn, expected));
}

/// Throws std::runtime_error("sphbasis::fn(): expected <expected>").
[[noreturn]] SPHBASIS_NOINLINE inline void throw_runtime(const char* fn,
                                                         const std::string& expected) {
    throw std::runtime_error(error_message(fn, expected));
}

/// Throws unless lo <= value <= hi: "expected lo <= name <= hi, got value".
template <class I>
SPHBASIS_FORCEINLINE void check_range(const char* fn, const char* name, I value, I lo, I hi) {
    if (value < lo || value > hi)
        throw_invalid(fn, std::to_string(lo) + " <= " + name + " <= " + std::to_string(hi) +
                              ", got " + std::to_string(value));
}

/// Throws unless a table of `bytes` bytes (an estimate in double, so it cannot overflow) fits
/// under SPHBASIS_MAX_TABLE_BYTES: "expected a table of at most <limit> bytes
/// (SPHBASIS_MAX_TABLE_BYTES), got <bytes> bytes for <what>".
SPHBASIS_NOINLINE inline void check_table_bytes(const char* fn, double bytes,
                                                const std::string& what) {
    const double limit = static_cast<double>(SPHBASIS_MAX_TABLE_BYTES);
    if (!(bytes <= limit)) {
        char buf[160];
        std::snprintf(
            buf, sizeof buf,
            "a table of at most %.4g bytes (SPHBASIS_MAX_TABLE_BYTES), got %.4g bytes for ", limit,
            bytes);
        throw_invalid(fn, buf + what);
    }
}

[[noreturn]] SPHBASIS_NOINLINE inline void throw_null_buffer(const char* fn, const char* name) {
    throw_invalid(fn, std::string("a non-null ") + name + " buffer");
}

/// Throws when p is null and n > 0 elements would be accessed through it:
/// "expected a non-null <name> buffer". (core/contiguous.hpp checks arrays and ranges too.)
template <class P>
SPHBASIS_FORCEINLINE void check_buffer(const char* fn, const char* name, const P* p,
                                       std::size_t n) {
    if (p == nullptr && n > 0) throw_null_buffer(fn, name);
}

}  // namespace sphbasis::detail
