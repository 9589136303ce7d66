// sphbasis: the interface every basis shares, and the drivers that evaluate any basis at one
// direction, over arrays of directions (SIMD across directions), or as an expansion sum.
//
// A basis is a type B with
//   static constexpr const char* name;    // "sh", "hsh", "makhotkin", "zernike", "hbasis",
//                                         // "hbasis-mod", "hl2" (the CLI names)
//   static constexpr Domain domain;       // sphere or hemisphere (z >= 0)
//   static constexpr bool orthonormal;    // on its domain
//   static bool valid_count(int n);       // n functions is a size this basis has
//   static const char* count_rule();      // "a square number", "4 or 6", ... for messages
//   static int max_count();               // largest supported number of functions
//   template <class F> static decltype(auto) with_kernel(int n, F&& f);
//       calls f(kernel) with kernel(x, y, z, store) templated on the value type V (float,
//       double, batch<T>) for a UNIT direction; the kernel calls store(k, value) once per k.
//       Precondition: valid_count(n).
// and optionally
//   template <class T, class F> static bool with_sum_kernel(int n, const T* coeffs, F&& f);
//       for sizes with a cheaper expansion than sum_k c_k * kernel value k: calls f(sk) with
//       sk(x, y, z) = sum_k coeffs[k] B_k(x, y, z) for unit directions (V as above) and returns
//       true, or returns false to use the generic sum. basis_eval_sum_batch uses it.
// The free functions below check n and normalise directions (normalize_or_pole), so all bases
// share one documented behaviour for bad input and one SIMD batch path.
#pragma once

#include <algorithm>
#include <cstddef>
#include <functional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "../core/vec.hpp"

namespace sphbasis {

/// Where a basis lives: the whole sphere or the upper hemisphere z >= 0.
enum class Domain { sphere, hemisphere };

namespace detail {
template <class B>
[[noreturn]] SPHBASIS_NOINLINE void throw_bad_count(int n, const char* fn) {
    throw std::invalid_argument(std::string("sphbasis::") + fn + "(): expected " + B::count_rule() +
                                " functions for basis '" + B::name + "', got " + std::to_string(n));
}
}  // namespace detail

/// Throws std::invalid_argument unless B has n functions. The check is inlined; the message is
/// built out of line, so the one-call paths keep the direction in registers.
template <class B>
SPHBASIS_FORCEINLINE void check_count(int n, const char* fn) {
    if (!B::valid_count(n)) detail::throw_bad_count<B>(n, fn);
}

namespace detail {

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

}  // namespace detail

/// Evaluates the n functions of basis B at direction (x, y, z) into out[0..n). The input is
/// normalised; zero or non-finite vectors are taken as the pole (0, 0, 1). Throws
/// std::invalid_argument if B has no size n.
template <class B, class T>
void basis_eval(int n, T x, T y, T z, T* out) {
    static_assert(std::is_floating_point_v<T>, "sphbasis::basis_eval: T is float or double.");
    check_count<B>(n, "basis_eval");
    normalize_or_pole(x, y, z);
    B::with_kernel(n, [&](auto kernel) { kernel(x, y, z, [&](int k, T v) { out[k] = v; }); });
}

/// basis_eval for any 3-vector type (glm::vec3, Eigen::Vector3d, sphbasis::vec3, ...).
template <class B, class D, class T>
void basis_eval(int n, const D& d, T* out) {
    basis_eval<B>(n, T(component<0>(d)), T(component<1>(d)), T(component<2>(d)), out);
}

/// Evaluates basis B at `count` directions given as x, y, z arrays, SIMD across directions.
/// Output is function-major: function k of direction i goes to out[k * stride + i], stride >=
/// count. Directions are normalised as by basis_eval. Throws std::invalid_argument for a bad n
/// or stride.
template <class B, class T>
void basis_eval_batch(int n, std::size_t count, const T* xs, const T* ys, const T* zs, T* out,
                      std::size_t stride) {
    check_count<B>(n, "basis_eval_batch");
    if (stride < count)
        throw std::invalid_argument("sphbasis::basis_eval_batch(): expected stride >= count");
    if (count == 0) return;
    B::with_kernel(n, [&](auto kernel) {
        detail::for_each_direction(
            count, xs, ys, zs,
            [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                kernel(x, y, z, detail::SoaStore<T>{out, stride, i});
            },
            [&](T x, T y, T z, std::size_t i) {
                kernel(x, y, z,
                       [&](int k, T v) { out[static_cast<std::size_t>(k) * stride + i] = v; });
            });
    });
}

/// The expansion f(d) = sum_k coeffs[k] B_k(d) at one direction (normalised as by basis_eval).
/// C is any coefficient type with C + C and C * T (float, double, an RGB type); the basis
/// values are not stored. Throws std::invalid_argument for a bad n.
template <class B, class C, class T>
C basis_eval_sum(int n, const C* coeffs, T x, T y, T z) {
    check_count<B>(n, "basis_eval_sum");
    normalize_or_pole(x, y, z);
    C acc = C{};
    B::with_kernel(
        n, [&](auto kernel) { kernel(x, y, z, [&](int k, T v) { acc = acc + coeffs[k] * v; }); });
    return acc;
}

/// The expansion sum_k coeffs[k] B_k(d_i) at `count` directions into out[i], SIMD across
/// directions, without storing the basis values.
template <class B, class T>
void basis_eval_sum_batch(int n, const T* coeffs, std::size_t count, const T* xs, const T* ys,
                          const T* zs, T* out) {
    check_count<B>(n, "basis_eval_sum_batch");
    if (count == 0) return;
    if constexpr (detail::has_sum_kernel<B>::value) {
        const bool done = B::with_sum_kernel(n, coeffs, [&](const auto& sum) {
            detail::for_each_direction(
                count, xs, ys, zs,
                [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                    sum(x, y, z).store(out + i);
                },
                [&](T x, T y, T z, std::size_t i) { out[i] = sum(x, y, z); });
        });
        if (done) return;
    }
    B::with_kernel(n, [&](auto kernel) {
        detail::for_each_direction(
            count, xs, ys, zs,
            [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
                batch<T> acc(T(0));
                kernel(x, y, z, detail::SumStore<batch<T>>{coeffs, &acc});
                acc.store(out + i);
            },
            [&](T x, T y, T z, std::size_t i) {
                T acc = 0;
                kernel(x, y, z, [&](int k, T v) { acc += coeffs[k] * v; });
                out[i] = acc;
            });
    });
}

/// A basis of a given size as a runtime object: n functions and an evaluator for unit
/// directions. Made from a basis type by evaluator<B>(n), or by hand for any function set.
struct BasisFunctions {
    int n = 0;
    std::function<void(double, double, double, double*)> eval;  // unit (x, y, z) -> out[0..n)
};

/// The evaluator of basis B with n functions (throws std::invalid_argument for a bad n).
template <class B>
BasisFunctions evaluator(int n) {
    check_count<B>(n, "evaluator");
    return {n, [n](double x, double y, double z, double* out) { basis_eval<B>(n, x, y, z, out); }};
}

}  // namespace sphbasis
