// sphbasis: the interface every basis shares, and the drivers that evaluate any basis at one
// direction, over arrays of directions (SIMD across directions), or as an expansion sum.
//
// Sizes: one rule, visible in the names. A size is a plain int in one of two units, and the
// parameter (and function) name says which:
//   * `bands` in the namespaces of the banded bases (sh::, hsh::, makhotkin::, zernike::):
//     n bands = degrees l <= n-1; `<ns>::count(bands)` is the number of functions (n^2 for SH,
//     HSH and Makhotkin, n(n+1)/2 for Zernike), `<ns>::max_bands` the largest band count.
//   * `count`, the number of functions, in the generic API templated on a basis type
//     (basis_eval<B>(count, ...), evaluator<B>(count), B::valid_count, BasisInfo), because the
//     H-basis (4 or 6 functions) and HL2 (3) have no bands. B::bands_of(count) converts back.
// Directions count in the batch paths is `directions`. A basis type's `with_kernel(count, f)`
// takes a count; the banded bases' `with_bands_kernel(bands, f)` takes bands.
//
// Arguments as users hold them: a direction is either three components x, y, z (any arithmetic
// types) or any 3-vector type (glm::vec3, Eigen::Vector3f, sphbasis::vec3, std::array; read by
// component<I>(), core/vec.hpp). Output and coefficient buffers are a pointer (checked for null)
// or a contiguous range (.data() and .size(): std::vector, std::array, std::span; checked for
// size), and the scalar is deduced: basis values are computed in the output's scalar type (float
// or double); an expansion sum (eval_sum) in the direction's scalar type. Misuse (an int
// output, a type that is no 3-vector) stops at one static_assert sentence.
//
// A basis is a type B with
//   static constexpr const char* name;    // "sh", "hsh", "makhotkin", "zernike", "hbasis",
//                                         // "hbasis-mod", "hl2" (the CLI names)
//   static constexpr Domain domain;       // sphere or hemisphere (z >= 0)
//   static constexpr bool orthonormal;    // on its domain
//   static bool valid_count(int count);   // `count` functions is a size this basis has
//   static const char* count_rule();      // "a square number (bands^2, bands <= 8192) of",
//                                         // "4 or 6", ... for messages ("<rule> functions")
//   static int max_count();               // largest supported number of functions
//   template <class F> static decltype(auto) with_kernel(int count, F&& f);
//       calls f(kernel) with kernel(x, y, z, store) templated on the value type V (float,
//       double, batch<T>) for a UNIT direction; the kernel calls store(k, value) once per k.
//       Precondition: valid_count(count).
// and optionally
//   template <class T, class F> static bool with_sum_kernel(int count, const T* coeffs, F&& f);
//       for sizes with a cheaper expansion than sum_k c_k * kernel value k: calls f(sk) with
//       sk(x, y, z) = sum_k coeffs[k] B_k(x, y, z) for unit directions (V as above) and returns
//       true, or returns false to use the generic sum. basis_eval_sum_batch uses it.
// A banded basis (detail::Banded, the namespace functions) also has
//   static constexpr int max_bands; static constexpr int count(int bands);
//   static int bands_of(int count);       // -1 if count is no size of the basis
//   template <class F> static decltype(auto) with_bands_kernel(int bands, F&& f);  // bands >= 1
//   template <int N> static auto fixed_kernel();   // the kernel of exactly N <= 64 bands
// The free functions below check sizes and buffers and normalise directions (normalize_or_pole),
// so all bases share one documented behaviour for bad input and one SIMD batch path.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "../config.hpp"
#include "../core/contiguous.hpp"
#include "../core/error.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "../core/vec.hpp"

namespace sphbasis {

/// Where a basis lives: the whole sphere or the upper hemisphere z >= 0.
enum class Domain { sphere, hemisphere };

namespace detail {
template <class B>
[[noreturn]] SPHBASIS_NOINLINE void throw_bad_count(int count, const char* fn) {
    throw_invalid(fn, std::string(B::count_rule()) + " functions for basis '" + B::name +
                          "', got " + std::to_string(count));
}
[[noreturn]] SPHBASIS_NOINLINE inline void throw_bad_bands(const char* fn, int bands,
                                                           int max_bands) {
    throw_invalid(fn,
                  "0 <= bands <= " + std::to_string(max_bands) + ", got " + std::to_string(bands));
}
/// The failure of the one-call check: bad bands, else the null output buffer.
[[noreturn]] SPHBASIS_NOINLINE inline void throw_bad_bands_or_buffer(const char* fn, int bands,
                                                                     int max_bands) {
    if (bands < 0 || bands > max_bands) throw_bad_bands(fn, bands, max_bands);
    throw_invalid(fn, "a non-null output buffer");
}

/// The basis interface members of a hemispherical basis with a few fixed function counts (the
/// H-bases: 4 or 6, HL2: 3); the basis adds name, count_rule() and with_kernel().
template <bool Orthonormal, int... Counts>
struct HemiFixedCounts {
    static constexpr Domain domain = Domain::hemisphere;
    static constexpr bool orthonormal = Orthonormal;
    static bool valid_count(int n) noexcept { return ((n == Counts) || ...); }
    static int max_count() noexcept { return std::max({Counts...}); }
};

/// The failure of basis_eval's one check: a bad count, else a null output buffer.
template <class B>
[[noreturn]] SPHBASIS_NOINLINE void throw_count_or_null(const char* fn, int count) {
    if (!B::valid_count(count)) throw_bad_count<B>(count, fn);
    throw_invalid(fn, "a non-null output buffer");
}
}  // namespace detail

/// Throws std::invalid_argument unless B has `count` functions. The check is inlined; the
/// message is built out of line, so the one-call paths keep the direction in registers.
template <class B>
SPHBASIS_FORCEINLINE void check_count(int count, const char* fn) {
    if (!B::valid_count(count)) detail::throw_bad_count<B>(count, fn);
}

namespace detail {

// ---- Buffers and directions as users hold them -------------------------------------------------

/// The scalar in which a direction given as components is evaluated: their common type, which
/// must be float or double.
template <class X, class Y, class Z>
using components_scalar_t = std::common_type_t<X, Y, Z>;

template <class T>
SPHBASIS_FORCEINLINE void static_check_scalar() {
    static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>,
                  "sphbasis: directions and basis values are float or double (convert integer "
                  "or long double input first).");
}

template <class X, class Y, class Z>
SPHBASIS_FORCEINLINE void static_check_components() {
    static_assert(std::is_arithmetic_v<X> && std::is_arithmetic_v<Y> && std::is_arithmetic_v<Z>,
                  "sphbasis: direction components x, y, z are numbers (or pass a 3-vector "
                  "type).");
}

/// The output element type of an evaluation: a non-const float or double.
template <class Out>
SPHBASIS_FORCEINLINE void static_check_output() {
    static_assert(is_buffer_v<Out>,
                  "sphbasis: an output buffer is a T* or a contiguous range of T (std::vector, "
                  "std::array, std::span) with T float or double.");
    if constexpr (is_buffer_v<Out>) {
        using T = buffer_element_t<Out>;
        static_assert(!std::is_const_v<T>, "sphbasis: the output buffer must be writable.");
        static_check_scalar<std::remove_const_t<T>>();
    }
}

/// c * v for a coefficient c and a basis value v: C * T where that is defined (float, double),
/// else C * coefficient_scalar_t<C>(v) (glm::vec3 with double values).
template <class C, class T, class = void>
struct has_times : std::false_type {};
template <class C, class T>
struct has_times<C, T, std::void_t<decltype(std::declval<const C&>() * std::declval<T>())>>
    : std::true_type {};
template <class C, class T>
SPHBASIS_FORCEINLINE C times(const C& c, T v) {
    if constexpr (has_times<C, T>::value)
        return C(c * v);
    else
        return C(c * coefficient_scalar_t<C>(v));
}
template <class C, class T>
SPHBASIS_FORCEINLINE void static_check_coefficient() {
    static_assert(has_times<C, T>::value || has_times<C, coefficient_scalar_t<C>>::value,
                  "sphbasis: a coefficient type C needs C + C and C * scalar (float, double, "
                  "glm::vec3, an RGB type).");
}

/// Store policy for SoA batches: function k of lane i goes to out[k * stride + base + i].
template <class T>
struct SoaStore {
    T* out;
    std::size_t stride, base;
    SPHBASIS_FORCEINLINE void operator()(int k, const batch<T>& v) const noexcept {
        v.store(out + static_cast<std::size_t>(k) * stride + base);
    }
    SPHBASIS_FORCEINLINE void lane(int k, int i, T v) const noexcept {
        out[static_cast<std::size_t>(k) * stride + base + static_cast<std::size_t>(i)] = v;
    }
};

/// Store policy that accumulates sum_k c[k] * value_k instead of storing the values.
template <class V>
struct SumStore {
    const scalar_t<V>* c;
    V* acc;
    SPHBASIS_FORCEINLINE void operator()(int k, const V& v) const noexcept { *acc += V(c[k]) * v; }
    SPHBASIS_FORCEINLINE void lane(int k, int j, scalar_t<V> v) const noexcept {
        acc->v[j] += c[k] * v;
    }
};

template <class B, class = void>
struct has_sum_kernel : std::false_type {};
template <class B>
struct has_sum_kernel<B, std::void_t<decltype(&B::template with_sum_kernel<float, int (*)(int)>)>>
    : std::true_type {};

/// Runs kernel over n SoA directions: whole SIMD batches, then a scalar tail.
/// body(V x, V y, V z, std::size_t i) for batches, tail(T x, T y, T z, std::size_t i).
template <class T, class Body, class Tail>
SPHBASIS_FORCEINLINE void for_each_direction(std::size_t n, const T* xs, const T* ys, const T* zs,
                                             Body&& body, Tail&& tail) {
    using V = batch<T>;
    constexpr std::size_t W = static_cast<std::size_t>(V::size);
    const std::size_t full = n - n % W;
    for (std::size_t i = 0; i < full; i += W) {
        V x = V::load(xs + i), y = V::load(ys + i), z = V::load(zs + i);
        normalize_or_pole(x, y, z);
        body(x, y, z, i);
    }
    // The tail as a count below W: with a running index GCC 12 loses the bound after inlining
    // an out-of-line kernel and warns (-Waggressive-loop-optimizations) in callers' builds.
    for (std::size_t j = 0; j < n % W; ++j) {
        const std::size_t i = full + j;
        T x = xs[i], y = ys[i], z = zs[i];
        normalize_or_pole(x, y, z);
        tail(x, y, z, i);
    }
}

template <class Out>
constexpr bool output_ok_v = [] {
    if constexpr (is_buffer_v<Out>) {
        using T = buffer_element_t<Out>;
        return std::is_same_v<T, float> || std::is_same_v<T, double>;
    } else {
        return false;
    }
}();

/// The scalar of an output buffer (float for float* and std::vector<float>).
template <class Out>
using output_scalar_t = buffer_element_t<Out>;

/// The element type of an input buffer without const (the coefficient type of an expansion).
template <class In>
using input_element_t = std::remove_const_t<buffer_element_t<In>>;

/// Stores basis values: value k to out[k].
template <class T>
struct PointerStore {
    T* out;
    SPHBASIS_FORCEINLINE void operator()(int k, T v) const noexcept { out[k] = v; }
};

/// Throws std::invalid_argument unless 0 <= bands <= max_bands.
SPHBASIS_FORCEINLINE void check_bands_of(int bands, int max_bands, const char* fn) {
    if (bands < 0 || bands > max_bands) throw_bad_bands(fn, bands, max_bands);
}

/// The one-direction evaluation at a direction already converted (and, for eval, normalised):
/// checks bands and a null out, then B's kernel for `bands`. Not forced inline: the caller's
/// conversion and normalisation stay in registers and the dispatch is one call, as the
/// one-call benchmarks measured best.
template <class B, class T>
SPHBASIS_FORCEINLINE void bands_eval_at(const char* fn, int bands, T x, T y, T z, T* out) {
    // Bands and the null buffer in one cold branch: the one-call paths are that sensitive.
    if (bands < 0 || bands > B::max_bands || (out == nullptr && bands != 0))
        throw_bad_bands_or_buffer(fn, bands, B::max_bands);
    if (bands == 0) return;
    B::with_bands_kernel(bands, [&](auto kernel) { kernel(x, y, z, PointerStore<T>{out}); });
}

/// The one-direction evaluation of `bands` bands of a banded basis B into out: static checks,
/// a range's size, conversion to out's scalar, normalisation (Normalize), then bands_eval_at.
template <class B, bool Normalize, class X, class Y, class Z, class Out>
SPHBASIS_FORCEINLINE void bands_eval(const char* fn, int bands, X x, Y y, Z z, Out& out) {
    static_check_components<X, Y, Z>();
    static_check_output<Out>();
    if constexpr (output_ok_v<Out> && std::is_arithmetic_v<std::common_type_t<X, Y, Z>>) {
        using T = output_scalar_t<Out>;
        if constexpr (!std::is_pointer_v<std::remove_reference_t<Out>>) {
            check_bands_of(bands, B::max_bands, fn);
            check_buffer_size(fn, "output", out, static_cast<std::size_t>(B::count(bands)));
        }
        T tx = static_cast<T>(x), ty = static_cast<T>(y), tz = static_cast<T>(z);
        if constexpr (Normalize)
            normalize_or_pole(tx, ty, tz);
        else
            SPHBASIS_ASSERT(std::fabs(tx * tx + ty * ty + tz * tz - T(1)) <= T(1e-3));
        bands_eval_at<B>(fn, bands, tx, ty, tz, static_cast<T*>(buffer_data(out)));
    }
}

/// bands_eval for a direction given as any 3-vector type.
template <class B, bool Normalize, class D, class Out>
SPHBASIS_FORCEINLINE void bands_eval_dir(const char* fn, int bands, const D& d, Out& out) {
    static_check_direction<D>();
    if constexpr (is_direction_v<D>)
        bands_eval<B, Normalize>(fn, bands, component<0>(d), component<1>(d), component<2>(d), out);
}

/// Whether B has a kernel of exactly N bands that normalises the direction itself
/// (B::fixed_normalizing_kernel<N>(), called with the raw components).
template <class B, int N, class = void>
struct has_fixed_normalizing_kernel : std::false_type {};
template <class B, int N>
struct has_fixed_normalizing_kernel<
    B, N, std::void_t<decltype(B::template fixed_normalizing_kernel<N>())>> : std::true_type {};

/// Compile-time band count N: B's kernel for exactly N bands, no dispatch. Out as bands_eval.
/// Normalising evaluation goes to B's normalising kernel where it has one (SH, 3..8 bands).
template <class B, int N, bool Normalize, class X, class Y, class Z, class Out>
SPHBASIS_FORCEINLINE void fixed_bands_eval(const char* fn, X x, Y y, Z z, Out& out) {
    static_check_components<X, Y, Z>();
    static_check_output<Out>();
    if constexpr (output_ok_v<Out> && std::is_arithmetic_v<std::common_type_t<X, Y, Z>>) {
        using T = output_scalar_t<Out>;
        if constexpr (!std::is_pointer_v<std::remove_reference_t<Out>>)
            check_buffer_size(fn, "output", out, static_cast<std::size_t>(B::count(N)));
        (void)fn;
        T tx = static_cast<T>(x), ty = static_cast<T>(y), tz = static_cast<T>(z);
        if constexpr (Normalize && has_fixed_normalizing_kernel<B, N>::value) {
            B::template fixed_normalizing_kernel<N>()(tx, ty, tz,
                                                      PointerStore<T>{buffer_data(out)});
            return;
        }
        if constexpr (Normalize)
            normalize_or_pole(tx, ty, tz);
        else
            SPHBASIS_ASSERT(std::fabs(tx * tx + ty * ty + tz * tz - T(1)) <= T(1e-3));
        B::template fixed_kernel<N>()(tx, ty, tz, PointerStore<T>{buffer_data(out)});
    }
}

template <class B, int N, bool Normalize, class D, class Out>
SPHBASIS_FORCEINLINE void fixed_bands_eval_dir(const char* fn, const D& d, Out& out) {
    static_check_direction<D>();
    if constexpr (is_direction_v<D>)
        fixed_bands_eval<B, N, Normalize>(fn, component<0>(d), component<1>(d), component<2>(d),
                                          out);
}

/// acc + c * v (see times()), with the rounding of the plain expression for float and double.
template <class C, class T>
SPHBASIS_FORCEINLINE C accumulate(const C& acc, const C& c, T v) {
    if constexpr (has_times<C, T>::value)
        return acc + c * v;
    else
        return acc + c * coefficient_scalar_t<C>(v);
}

/// The expansion sum_k coeffs[k] B_k(d) at one direction, the size given by `with` (a call
/// with(f) that passes f the kernel) and checked by the caller. T float or double.
template <class C, class T, class With>
SPHBASIS_FORCEINLINE C sum_at(const C* coeffs, T x, T y, T z, With&& with) {
    normalize_or_pole(x, y, z);
    C acc = C{};
    with([&](auto kernel) {
        kernel(x, y, z, [&](int k, T v) { acc = accumulate(acc, coeffs[k], v); });
    });
    return acc;
}

/// Front end of the one-direction expansion: static checks, then sum_at with `size` functions.
template <class Coeffs, class X, class Y, class Z, class Check, class With>
SPHBASIS_FORCEINLINE auto eval_sum_front(const char* fn, const Coeffs& coeffs, X x, Y y, Z z,
                                         Check&& check, With&& with) {
    static_assert(is_buffer_v<const Coeffs&>,
                  "sphbasis: coefficients are a const C* or a contiguous range of C (std::vector, "
                  "std::array, std::span).");
    static_check_components<X, Y, Z>();
    using T = std::common_type_t<X, Y, Z>;
    static_check_scalar<T>();
    if constexpr (is_buffer_v<const Coeffs&>) {
        using C = input_element_t<const Coeffs&>;
        static_check_coefficient<C, T>();
        const C* c = buffer_data(coeffs);
        const std::size_t size = check();
        check_buffer_size(fn, "coefficient", coeffs, size);
        if (size == 0) return C{};
        return sum_at(c, static_cast<T>(x), static_cast<T>(y), static_cast<T>(z), with);
    }
}

/// Runs kernel over `directions` SoA directions into out (function-major, stride), the kernel
/// given by `with`. Sizes checked by the caller.
template <class T, class With>
void eval_batch_at(std::size_t directions, const T* xs, const T* ys, const T* zs, T* out,
                   std::size_t stride, With&& with) {
    if (directions == 0) return;
    with([&](auto kernel) {
        for_each_direction(
            directions, xs, ys, zs,
            [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                kernel(x, y, z, SoaStore<T>{out, stride, i});
            },
            [&](T x, T y, T z, std::size_t i) {
                kernel(x, y, z,
                       [&](int k, T v) { out[static_cast<std::size_t>(k) * stride + i] = v; });
            });
    });
}

/// Checks of the batch paths: x, y, z arrays of `directions` elements of the output's scalar,
/// an output of `count` functions at `stride` (stride >= directions).
template <class Xs, class Ys, class Zs, class Out>
SPHBASIS_FORCEINLINE void check_batch(const char* fn, int count, std::size_t directions,
                                      const Xs& xs, const Ys& ys, const Zs& zs, const Out& out,
                                      std::size_t stride) {
    if (stride < directions)
        throw_invalid(fn, "stride >= directions, got stride " + std::to_string(stride) + " and " +
                              std::to_string(directions) + " directions");
    check_buffer_size(fn, "x", xs, directions);
    check_buffer_size(fn, "y", ys, directions);
    check_buffer_size(fn, "z", zs, directions);
    const std::size_t need =
        count > 0 && directions > 0 ? static_cast<std::size_t>(count - 1) * stride + directions : 0;
    check_buffer_size(fn, "output", out, need);
}

template <class Xs, class Ys, class Zs, class Out>
SPHBASIS_FORCEINLINE void static_check_batch() {
    static_check_output<Out>();
    if constexpr (output_ok_v<Out>) {
        using T = output_scalar_t<Out>;
        static_assert(is_buffer_v<const Xs&> && is_buffer_v<const Ys&> && is_buffer_v<const Zs&>,
                      "sphbasis: the batch paths take x, y, z as const T* or contiguous ranges "
                      "of T, T the output's scalar.");
        if constexpr (is_buffer_v<const Xs&> && is_buffer_v<const Ys&> && is_buffer_v<const Zs&>)
            static_assert(std::is_same_v<input_element_t<const Xs&>, T> &&
                              std::is_same_v<input_element_t<const Ys&>, T> &&
                              std::is_same_v<input_element_t<const Zs&>, T>,
                          "sphbasis: the batch paths take x, y, z arrays of the output's scalar "
                          "type (float with float, double with double).");
    }
}

template <class Xs, class Ys, class Zs, class Out>
constexpr bool batch_ok_v = [] {
    if constexpr (output_ok_v<Out> && is_buffer_v<const Xs&> && is_buffer_v<const Ys&> &&
                  is_buffer_v<const Zs&>) {
        using T = output_scalar_t<Out>;
        return std::is_same_v<input_element_t<const Xs&>, T> &&
               std::is_same_v<input_element_t<const Ys&>, T> &&
               std::is_same_v<input_element_t<const Zs&>, T>;
    } else {
        return false;
    }
}();

/// The expansion at `directions` SoA directions into out[i], with B's cheaper sum kernel where
/// it has one (with_sum_kernel), else the generic sum. Sizes checked by the caller.
template <class B, class T, class With>
void eval_sum_batch_at(int count, const T* coeffs, std::size_t directions, const T* xs, const T* ys,
                       const T* zs, T* out, With&& with) {
    if (directions == 0) return;
    if constexpr (has_sum_kernel<B>::value) {
        const bool done = B::with_sum_kernel(count, coeffs, [&](const auto& sum) {
            for_each_direction(
                directions, xs, ys, zs,
                [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                    sum(x, y, z).store(out + i);
                },
                [&](T x, T y, T z, std::size_t i) { out[i] = sum(x, y, z); });
        });
        if (done) return;
    }
    with([&](auto kernel) {
        for_each_direction(
            directions, xs, ys, zs,
            [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                batch<T> acc(T(0));
                kernel(x, y, z, SumStore<batch<T>>{coeffs, &acc});
                acc.store(out + i);
            },
            [&](T x, T y, T z, std::size_t i) {
                T acc = 0;
                kernel(x, y, z, [&](int k, T v) { acc += coeffs[k] * v; });
                out[i] = acc;
            });
    });
}

template <class Cs, class Xs, class Ys, class Zs, class Out>
SPHBASIS_FORCEINLINE void static_check_sum_batch() {
    static_check_batch<Xs, Ys, Zs, Out>();
    static_assert(is_buffer_v<const Cs&>,
                  "sphbasis: coefficients are a const T* or a contiguous range of T.");
    if constexpr (output_ok_v<Out> && is_buffer_v<const Cs&>)
        static_assert(std::is_same_v<input_element_t<const Cs&>, output_scalar_t<Out>>,
                      "sphbasis: the batch expansion takes coefficients of the output's scalar "
                      "type.");
}

template <class Cs, class Xs, class Ys, class Zs, class Out>
constexpr bool sum_batch_ok_v = [] {
    if constexpr (batch_ok_v<Xs, Ys, Zs, Out> && is_buffer_v<const Cs&>)
        return std::is_same_v<input_element_t<const Cs&>, output_scalar_t<Out>>;
    else
        return false;
}();

/// Sum-batch front end shared by basis_eval_sum_batch and the banded eval_sum_batch.
template <class B, class Cs, class Xs, class Ys, class Zs, class Out, class With>
void eval_sum_batch_front(const char* fn, int count, const Cs& coeffs, std::size_t directions,
                          const Xs& xs, const Ys& ys, const Zs& zs, Out& out, With&& with) {
    static_check_sum_batch<Cs, Xs, Ys, Zs, Out>();
    if constexpr (sum_batch_ok_v<Cs, Xs, Ys, Zs, Out>) {
        using T = output_scalar_t<Out>;
        check_buffer_size(fn, "coefficient", coeffs, directions > 0 ? std::size_t(count) : 0);
        check_buffer_size(fn, "x", xs, directions);
        check_buffer_size(fn, "y", ys, directions);
        check_buffer_size(fn, "z", zs, directions);
        check_buffer_size(fn, "output", out, directions);
        T* o = buffer_data(out);
        if (count == 0) {
            std::fill(o, o + directions, T(0));
            return;
        }
        eval_sum_batch_at<B>(count, buffer_data(coeffs), directions, buffer_data(xs),
                             buffer_data(ys), buffer_data(zs), o, with);
    }
}

/// Batch front end shared by basis_eval_batch and the banded eval_batch.
template <class Xs, class Ys, class Zs, class Out, class With>
void eval_batch_front(const char* fn, int count, std::size_t directions, const Xs& xs, const Ys& ys,
                      const Zs& zs, Out& out, std::size_t stride, With&& with) {
    static_check_batch<Xs, Ys, Zs, Out>();
    if constexpr (batch_ok_v<Xs, Ys, Zs, Out>) {
        check_batch(fn, count, directions, xs, ys, zs, out, stride);
        if (count == 0) return;
        eval_batch_at(directions, buffer_data(xs), buffer_data(ys), buffer_data(zs),
                      buffer_data(out), stride, with);
    }
}

}  // namespace detail

// ---- The generic API: a basis type B and a function count
// ----------------------------------------

/// Evaluates the `count` functions of basis B at direction (x, y, z) into out[0..count). The
/// input is normalised; zero or non-finite vectors are taken as the pole (0, 0, 1). out is a T*
/// (not checked: this is the one-call hot path, where even a null test measured 3-9% at 3 or 4
/// functions) or an array or contiguous range of T (size checked), T float or double; x, y, z
/// are converted to T. Throws std::invalid_argument if B has no size `count` or a range is too
/// small.
template <class B, class X, class Y, class Z, class Out>
void basis_eval(int count, X x, Y y, Z z, Out&& out) {
    detail::static_check_components<X, Y, Z>();
    detail::static_check_output<Out>();
    if constexpr (detail::output_ok_v<Out> && std::is_arithmetic_v<std::common_type_t<X, Y, Z>>) {
        using T = detail::output_scalar_t<Out>;
        check_count<B>(count, "basis_eval");
        if constexpr (!std::is_pointer_v<std::remove_reference_t<Out>>)
            detail::check_buffer_size("basis_eval", "output", out, static_cast<std::size_t>(count));
        T* p = detail::buffer_data(out);
        T tx = static_cast<T>(x), ty = static_cast<T>(y), tz = static_cast<T>(z);
        normalize_or_pole(tx, ty, tz);
        B::with_kernel(count,
                       [&](auto kernel) { kernel(tx, ty, tz, [&](int k, T v) { p[k] = v; }); });
    }
}

/// basis_eval for any 3-vector type (glm::vec3, Eigen::Vector3d, sphbasis::vec3, ...); the
/// values are computed in out's scalar type.
template <class B, class D, class Out>
void basis_eval(int count, const D& d, Out&& out) {
    detail::static_check_direction<D>();
    if constexpr (detail::is_direction_v<D>)
        basis_eval<B>(count, component<0>(d), component<1>(d), component<2>(d), out);
}

/// Evaluates basis B at `directions` directions given as x, y, z arrays, SIMD across
/// directions. Output is function-major: function k of direction i goes to out[k * stride + i],
/// stride >= directions. Directions are normalised as by basis_eval. xs, ys, zs and out are T*
/// or contiguous ranges of T (sizes checked), T float or double. Throws std::invalid_argument for
/// a bad count or stride, a null buffer or a range too small.
template <class B, class Xs, class Ys, class Zs, class Out>
void basis_eval_batch(int count, std::size_t directions, const Xs& xs, const Ys& ys, const Zs& zs,
                      Out&& out, std::size_t stride) {
    check_count<B>(count, "basis_eval_batch");
    detail::eval_batch_front("basis_eval_batch", count, directions, xs, ys, zs, out, stride,
                             [count](auto&& f) { B::with_kernel(count, f); });
}

/// The expansion f(d) = sum_k coeffs[k] B_k(d) at one direction (normalised as by basis_eval).
/// coeffs is a const C* or a contiguous range of C (size checked), C any coefficient type with
/// C + C and C * scalar (float, double, glm::vec3, an RGB type); the basis values are computed in
/// the direction's scalar type and not stored. Throws std::invalid_argument for a bad count.
template <class B, class Coeffs, class X, class Y, class Z>
auto basis_eval_sum(int count, const Coeffs& coeffs, X x, Y y, Z z) {
    return detail::eval_sum_front(
        "basis_eval_sum", coeffs, x, y, z,
        [count] {
            check_count<B>(count, "basis_eval_sum");
            return static_cast<std::size_t>(count);
        },
        [count](auto&& f) { B::with_kernel(count, f); });
}

/// basis_eval_sum for any 3-vector type; the values are computed in its scalar type.
template <class B, class Coeffs, class D>
auto basis_eval_sum(int count, const Coeffs& coeffs, const D& d) {
    detail::static_check_direction<D>();
    if constexpr (detail::is_direction_v<D>)
        return basis_eval_sum<B>(count, coeffs, component<0>(d), component<1>(d), component<2>(d));
}

/// The expansion sum_k coeffs[k] B_k(d_i) at `directions` directions into out[i], SIMD across
/// directions, without storing the basis values. Buffers as for basis_eval_batch.
template <class B, class Cs, class Xs, class Ys, class Zs, class Out>
void basis_eval_sum_batch(int count, const Cs& coeffs, std::size_t directions, const Xs& xs,
                          const Ys& ys, const Zs& zs, Out&& out) {
    check_count<B>(count, "basis_eval_sum_batch");
    detail::eval_sum_batch_front<B>("basis_eval_sum_batch", count, coeffs, directions, xs, ys, zs,
                                    out, [count](auto&& f) { B::with_kernel(count, f); });
}

/// A basis of a given size as a runtime object: n functions (a function count) and an
/// evaluator for unit directions. Made from a basis type by evaluator<B>(count), or by hand for
/// any function set.
struct BasisFunctions {
    int n = 0;                                                  // the function count
    std::function<void(double, double, double, double*)> eval;  // unit (x, y, z) -> out[0..n)
};

/// The evaluator of basis B with `count` functions (throws std::invalid_argument for a bad
/// count).
template <class B>
BasisFunctions evaluator(int count) {
    check_count<B>(count, "evaluator");
    return {count, [count](double x, double y, double z, double* out) {
                basis_eval<B>(count, x, y, z, out);
            }};
}

// ---- The banded API: a basis type B and a band count (sh::, hsh::, makhotkin::, zernike::) ------

namespace detail {

/// The namespace functions sh::eval_sum, hsh::eval_batch, ... forward here with their name for
/// messages (eval and eval_unit go to bands_eval directly; basis/detail/banded_api.hpp).
template <class B>
struct Banded {
    template <class Cs, class X, class Y, class Z>
    static auto eval_sum(const char* fn, int bands, const Cs& coeffs, X x, Y y, Z z) {
        return eval_sum_front(
            fn, coeffs, x, y, z,
            [&] {
                check_bands_of(bands, B::max_bands, fn);
                return static_cast<std::size_t>(B::count(bands));
            },
            [bands](auto&& f) { B::with_bands_kernel(bands, f); });
    }
    template <class Xs, class Ys, class Zs, class Out>
    static void eval_batch(const char* fn, int bands, std::size_t directions, const Xs& xs,
                           const Ys& ys, const Zs& zs, Out& out, std::size_t stride) {
        check_bands_of(bands, B::max_bands, fn);
        eval_batch_front(fn, B::count(bands), directions, xs, ys, zs, out, stride,
                         [bands](auto&& f) { B::with_bands_kernel(bands, f); });
    }
    template <class Cs, class Xs, class Ys, class Zs, class Out>
    static void eval_sum_batch(const char* fn, int bands, const Cs& coeffs, std::size_t directions,
                               const Xs& xs, const Ys& ys, const Zs& zs, Out& out) {
        check_bands_of(bands, B::max_bands, fn);
        eval_sum_batch_front<B>(fn, B::count(bands), coeffs, directions, xs, ys, zs, out,
                                [bands](auto&& f) { B::with_bands_kernel(bands, f); });
    }
};

}  // namespace detail

}  // namespace sphbasis
