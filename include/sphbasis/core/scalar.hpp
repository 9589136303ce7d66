// sphbasis: scalar traits. Kernels are templates on a value type V, which is float, double or
// a SIMD batch (core/simd.hpp). This header gives the operations kernels use on V for the
// arithmetic types; simd.hpp adds the same names for batches.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "../config.hpp"

namespace sphbasis {

template <class V, class = void>
struct scalar_traits;

template <class T>
struct scalar_traits<T, std::enable_if_t<std::is_floating_point_v<T>>> {
    using scalar = T;
    using mask = bool;
    static constexpr int size = 1;
};

/// The scalar type of a value type: float for float and for a batch of floats.
template <class V>
using scalar_t = typename scalar_traits<V>::scalar;
template <class V>
using mask_t = typename scalar_traits<V>::mask;

template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T select(bool m, T a, T b) noexcept {
    return m ? a : b;
}
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vsqrt(T a) noexcept {
    return std::sqrt(a);
}
/// 1/sqrt(a); batches use a refined hardware estimate (core/simd.hpp).
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vrsqrt(T a) noexcept {
    return T(1) / std::sqrt(a);
}
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vabs(T a) noexcept {
    return std::fabs(a);
}
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vfma(T a, T b, T c) noexcept {
    return a * b + c;  // contracted to an FMA where the target has one
}
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vmax(T a, T b) noexcept {
    return a > b ? a : b;
}
template <class T, std::enable_if_t<std::is_floating_point_v<T>, int> = 0>
inline T vmin(T a, T b) noexcept {
    return a < b ? a : b;
}
/// All lanes true / any lane true; for scalar masks (bool, or the int of `bool & bool`) the
/// value itself.
template <class M, std::enable_if_t<std::is_arithmetic_v<M>, int> = 0>
inline bool all(M m) noexcept {
    return m != 0;
}
template <class M, std::enable_if_t<std::is_arithmetic_v<M>, int> = 0>
inline bool any(M m) noexcept {
    return m != 0;
}

/// The working precision of the library's ill-conditioned recurrences (Wigner 3j symbols of
/// the SH products, the high-degree column recurrence of the hemispherical bases): the x87
/// 80-bit long double where it is a hardware type (64-bit significand), else double (MSVC, and
/// targets whose long double is a software quad).
using extended =
    std::conditional_t<std::numeric_limits<long double>::digits == 64, long double, double>;

/// The scalar a coefficient type C is multiplied by: C itself for float and double, else
/// C::value_type (glm::vec3, Eigen vectors and arrays), else the type of a member `r` or `x`
/// (RGB-like structs), else double. Specialise it for other types.
template <class C, class = void>
struct coefficient_scalar {
    using type = double;
};

namespace detail {
template <class C, class = void>
struct has_value_type : std::false_type {};
template <class C>
struct has_value_type<C, std::void_t<typename C::value_type>> : std::true_type {};
template <class C, class = void>
struct has_member_r : std::false_type {};
template <class C>
struct has_member_r<C, std::void_t<decltype(std::declval<const C&>().r)>> : std::true_type {};
template <class C, class = void>
struct has_member_x : std::false_type {};
template <class C>
struct has_member_x<C, std::void_t<decltype(std::declval<const C&>().x)>> : std::true_type {};
template <class C>
constexpr auto coefficient_scalar_probe() {
    if constexpr (std::is_floating_point_v<C>)
        return C{};
    else if constexpr (has_value_type<C>::value)
        return typename C::value_type{};
    else if constexpr (has_member_r<C>::value)
        return std::decay_t<decltype(std::declval<const C&>().r)>{};
    else if constexpr (has_member_x<C>::value)
        return std::decay_t<decltype(std::declval<const C&>().x)>{};
    else
        return double{};
}
}  // namespace detail

template <class C>
struct coefficient_scalar<
    C,
    std::enable_if_t<std::is_floating_point_v<decltype(detail::coefficient_scalar_probe<C>())>>> {
    using type = decltype(detail::coefficient_scalar_probe<C>());
};

template <class C>
using coefficient_scalar_t = typename coefficient_scalar<C>::type;

}  // namespace sphbasis
