// sphbasis: scalar traits. Kernels are templates on a value type V, which is float, double or
// a SIMD batch (core/simd.hpp). This header gives the operations kernels use on V for the
// arithmetic types; simd.hpp adds the same names for batches.
#pragma once

#include <cmath>
#include <type_traits>

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

}  // namespace sphbasis
