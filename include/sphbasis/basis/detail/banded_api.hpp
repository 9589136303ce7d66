// sphbasis: the banded entry points of sh::, hsh::, makhotkin:: and zernike:: (sizes in bands),
// written once. Internal: users include basis/sh.hpp, hsh.hpp, makhotkin.hpp or zernike.hpp.
//
// SPHBASIS_BANDED_ENTRY_POINTS(B, "ns"), expanded inside namespace sphbasis::ns after the basis
// type B (basis/basis.hpp) and the namespace's max_bands, defines in that namespace the thin
// forwarding functions below; each passes its name ("ns::eval", ...) on for error messages and
// forwards to sphbasis::detail::Banded<B> (basis/basis.hpp), where the checks and the kernel
// dispatch live. The doc comments of all of them are here (the preprocessor drops comments in a
// macro), with what is particular to a basis in its own header.
//
// Buffers (out, coeffs, xs, ys, zs) are pointers or contiguous ranges (std::vector, std::array,
// std::span; sizes checked), directions three components (x, y, z) or any 3-vector type
// (glm::vec3, glm::dvec3, Eigen::Vector3d, sphbasis::vec3; core/vec.hpp). Misuse is one
// static_assert sentence. count(bands) is the namespace's function count.
//
//   void check_bands(int bands, const char* fn)
//       Throws std::invalid_argument unless 0 <= bands <= max_bands (the message is built out of
//       line, so the check costs a compare in the one-call paths).
//
//   void eval(int bands, x, y, z, out)            void eval(int bands, dir, out)
//       The count(bands) functions at direction (x, y, z) into out, in out's scalar type (float
//       or double). The input is normalised first; a zero vector or one with a NaN/Inf
//       component is taken as the pole (0, 0, 1) (see normalize_or_pole). Throws
//       std::invalid_argument for bands outside [0, max_bands] or a null or too small out.
//   void eval_unit(int bands, x, y, z, out)       void eval_unit(int bands, dir, out)
//       eval() for a direction already of unit length (no normalisation; SPHBASIS_ASSERT
//       checks |d| in debug builds). Same throws.
//   void eval<N>(x, y, z, out)                    void eval<N>(dir, out)
//   void eval_unit<N>(x, y, z, out)               void eval_unit<N>(dir, out)
//       Compile-time band count N (1..64): unrolled code for N <= 8 (no dispatch, no
//       allocation), the row recurrence above. eval_unit<N> is the cheapest call, as a shader
//       would do it. noexcept for a pointer out (a range's size is checked).
//   void eval_batch(int bands, size_t directions, xs, ys, zs, out, size_t stride)
//       `bands` bands at `directions` directions given as separate x, y, z arrays (normalised as
//       by eval()), SIMD across directions. Function-major output (SoA): function k of
//       direction i goes to out[k * stride + i], stride >= directions. Throws
//       std::invalid_argument for bad bands, stride < directions, or a null or too small buffer.
//   auto eval_sum(int bands, coeffs, x, y, z)     auto eval_sum(int bands, coeffs, dir)
//       The expansion sum_k coeffs[k] f_k(d) at one direction (normalised as by eval(),
//       evaluated in its scalar type), without storing the f_k. The coefficients' element type
//       C is any type with C + C and C * scalar (float, double, glm::vec3, an RGB type). Throws
//       std::invalid_argument for bad bands or a null or too small coeffs.
//   void eval_sum_batch(int bands, coeffs, size_t directions, xs, ys, zs, out)
//       The expansion at `directions` directions (separate x, y, z arrays, normalised as by
//       eval()) into out[i], SIMD across directions.
//
// SPHBASIS_FORCEINLINE stands exactly where the one-call paths were measured to want it (eval,
// eval_unit and their compile-time forms): they are benchmarked at the nanosecond level.
#pragma once

#include <cstddef>
#include <type_traits>

#include "../../config.hpp"
#include "../../core/vec.hpp"
#include "../basis.hpp"

// clang-format off
/// eval or eval_unit (NAME), Normalize = NORMALIZE: runtime and compile-time band counts, three
/// components or a 3-vector.
#define SPHBASIS_BANDED_EVAL_FORMS(B, NS, NAME, NORMALIZE)                                         \
    template <class X, class Y, class Z, class Out>                                                \
    SPHBASIS_FORCEINLINE void NAME(int bands, X x, Y y, Z z, Out&& out) {                          \
        ::sphbasis::detail::bands_eval<B, NORMALIZE>(NS "::" #NAME, bands, x, y, z, out);          \
    }                                                                                              \
    template <class D, class Out>                                                                  \
    SPHBASIS_FORCEINLINE void NAME(int bands, const D& dir, Out&& out) {                           \
        ::sphbasis::detail::bands_eval_dir<B, NORMALIZE>(NS "::" #NAME, bands, dir, out);          \
    }                                                                                              \
    template <int N, class X, class Y, class Z, class Out>                                         \
    SPHBASIS_FORCEINLINE void NAME(X x, Y y, Z z, Out&& out) noexcept(                             \
        std::is_pointer_v<std::remove_reference_t<Out>>) {                                         \
        ::sphbasis::detail::fixed_bands_eval<B, N, NORMALIZE>(NS "::" #NAME, x, y, z, out);        \
    }                                                                                              \
    template <int N, class D, class Out>                                                           \
    SPHBASIS_FORCEINLINE void NAME(const D& dir, Out&& out) noexcept(                              \
        std::is_pointer_v<std::remove_reference_t<Out>>) {                                         \
        ::sphbasis::detail::fixed_bands_eval_dir<B, N, NORMALIZE>(NS "::" #NAME, dir, out);        \
    }

#define SPHBASIS_BANDED_ENTRY_POINTS(B, NS)                                                        \
    SPHBASIS_FORCEINLINE void check_bands(int bands, const char* fn) {                             \
        ::sphbasis::detail::check_bands_of(bands, max_bands, fn);                                  \
    }                                                                                              \
    SPHBASIS_BANDED_EVAL_FORMS(B, NS, eval, true)                                                  \
    SPHBASIS_BANDED_EVAL_FORMS(B, NS, eval_unit, false)                                            \
    template <class Xs, class Ys, class Zs, class Out>                                             \
    void eval_batch(int bands, std::size_t directions, const Xs& xs, const Ys& ys, const Zs& zs,   \
                    Out&& out, std::size_t stride) {                                               \
        ::sphbasis::detail::Banded<B>::eval_batch(NS "::eval_batch", bands, directions, xs, ys,    \
                                                  zs, out, stride);                                \
    }                                                                                              \
    template <class Cs, class X, class Y, class Z>                                                 \
    auto eval_sum(int bands, const Cs& coeffs, X x, Y y, Z z) {                                    \
        return ::sphbasis::detail::Banded<B>::eval_sum(NS "::eval_sum", bands, coeffs, x, y, z);   \
    }                                                                                              \
    template <class Cs, class D>                                                                   \
    auto eval_sum(int bands, const Cs& coeffs, const D& dir) {                                     \
        ::sphbasis::detail::static_check_direction<D>();                                           \
        if constexpr (::sphbasis::detail::is_direction_v<D>)                                       \
            return eval_sum(bands, coeffs, ::sphbasis::component<0>(dir),                          \
                            ::sphbasis::component<1>(dir), ::sphbasis::component<2>(dir));         \
    }                                                                                              \
    template <class Cs, class Xs, class Ys, class Zs, class Out>                                   \
    void eval_sum_batch(int bands, const Cs& coeffs, std::size_t directions, const Xs& xs,         \
                        const Ys& ys, const Zs& zs, Out&& out) {                                   \
        ::sphbasis::detail::Banded<B>::eval_sum_batch(NS "::eval_sum_batch", bands, coeffs,        \
                                                      directions, xs, ys, zs, out);                \
    }                                                                                              \
    static_assert(true, "SPHBASIS_BANDED_ENTRY_POINTS ends with a semicolon")
// clang-format on
