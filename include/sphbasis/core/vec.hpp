// sphbasis: a minimal 3-vector and the direction conventions shared by every basis.
//
// Directions are (x, y, z) with z the pole ("up", the surface normal of the hemispherical
// bases): x = sin(theta) cos(phi), y = sin(theta) sin(phi), z = cos(theta).
//
// Any type with members .x .y .z (glm::vec3, glm::dvec3, sphbasis::vec3), with x() y() z()
// (Eigen::Vector3f/d) or with operator[] can be passed where the API takes a direction;
// component() reads it without this header including GLM or Eigen.
#pragma once

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "../config.hpp"
#include "scalar.hpp"
#include "simd.hpp"  // all()/any() of batch masks must be visible where normalize_or_pole is defined

namespace sphbasis {

template <class T>
struct vec3 {
    T x, y, z;
};

template <class T>
constexpr T dot(const vec3<T>& a, const vec3<T>& b) noexcept {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
constexpr vec3<T> cross(const vec3<T>& a, const vec3<T>& b) noexcept {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

namespace detail {
template <class D, class = void>
struct has_member_xyz : std::false_type {};
template <class D>
struct has_member_xyz<
    D, std::void_t<decltype(std::declval<const D&>().x), decltype(std::declval<const D&>().z)>>
    : std::true_type {};
template <class D, class = void>
struct has_call_xyz : std::false_type {};
template <class D>
struct has_call_xyz<
    D, std::void_t<decltype(std::declval<const D&>().x()), decltype(std::declval<const D&>().z())>>
    : std::true_type {};
}  // namespace detail

/// Component i (0, 1, 2) of any 3-vector type: .x/.y/.z members, x()/y()/z() or operator[].
template <int I, class D>
constexpr auto component(const D& d) noexcept {
    static_assert(I >= 0 && I < 3, "sphbasis::component: a direction has components 0, 1, 2.");
    if constexpr (detail::has_member_xyz<D>::value) {
        if constexpr (I == 0)
            return d.x;
        else if constexpr (I == 1)
            return d.y;
        else
            return d.z;
    } else if constexpr (detail::has_call_xyz<D>::value) {
        if constexpr (I == 0)
            return d.x();
        else if constexpr (I == 1)
            return d.y();
        else
            return d.z();
    } else {
        return d[I];
    }
}

namespace detail {
template <class D, class = void>
struct has_subscript : std::false_type {};
template <class D>
struct has_subscript<D, std::void_t<decltype(std::declval<const D&>()[0])>> : std::true_type {};

/// A direction argument: a 3-vector type that component<I>() reads, with arithmetic components.
template <class D, class U = std::remove_cv_t<std::remove_reference_t<D>>>
constexpr bool is_direction_v =
    !std::is_arithmetic_v<U> && !std::is_pointer_v<U> &&
    (has_member_xyz<U>::value || has_call_xyz<U>::value || has_subscript<U>::value);

template <class D>
constexpr void static_check_direction() {
    static_assert(is_direction_v<D>,
                  "sphbasis: a direction is a 3-vector type with .x/.y/.z, x()/y()/z() or "
                  "operator[] (glm::vec3, Eigen::Vector3f, sphbasis::vec3, std::array).");
}

}  // namespace detail

/// The scalar type of a direction type (float for glm::vec3, double for Eigen::Vector3d).
template <class D>
using direction_scalar_t =
    std::remove_cv_t<std::remove_reference_t<decltype(component<0>(std::declval<const D&>()))>>;

/// |(x, y)| and the unit vector (cos phi, sin phi) along (x, y), without under- or overflow:
/// for a unit direction, s = sin(theta) taken from x and y (never sqrt(1 - z^2)). At x = y = 0
/// the documented outcome is s = 0, phi = 0. R is float, double or long double.
template <class R>
inline void polar_xy(R x, R y, R& s, R& cp, R& sp) noexcept {
    const R big = std::fmax(std::fabs(x), std::fabs(y));
    if (!(big > 0)) {
        s = 0;
        cp = 1;
        sp = 0;
        return;
    }
    const R rx = x / big, ry = y / big;
    const R r = std::sqrt(rx * rx + ry * ry);
    s = big * r;
    cp = rx / r;
    sp = ry / r;
}

/// Normalises (x, y, z) in place. The documented outcome for input that has no direction:
/// a zero vector or a vector with a NaN or infinite component becomes the pole (0, 0, 1).
/// Vectors of any finite non-zero length, denormal or near overflow included, are scaled to
/// unit length (when the squared length is outside [1e-30, 1e30] the components are first
/// divided by the largest magnitude, so nothing under- or overflows). Cost on the common path:
/// one sqrt and one division for float/double; for batches a hardware reciprocal-sqrt estimate
/// refined by Newton steps (within ~2 ulp of 1/sqrt). float, double and batches (lane-wise).
template <class V>
SPHBASIS_FORCEINLINE void normalize_or_pole(V& x, V& y, V& z) noexcept {
    using S = scalar_t<V>;
    const V one(S(1));
    // Fast path: the squared length is a normal number far from under- and overflow (NaN
    // fails the comparisons): one reciprocal square root (for batches a refined estimate).
    const V r2 = x * x + y * y + z * z;
    const auto fine = (r2 > V(S(1e-30))) & (r2 < V(S(1e30)));
    if (all(fine)) {
        const V inv = vrsqrt(r2);
        x = x * inv;
        y = y * inv;
        z = z * inv;
        return;
    }
    V big = vmax(vabs(x), vmax(vabs(y), vabs(z)));
    auto finite_nonzero = (big > V(S(0))) & (big <= V(std::numeric_limits<S>::max()));
    V s = one / select(finite_nonzero, big, one);
    V px = x * s, py = y * s, pz = z * s;
    V q2 = px * px + py * py + pz * pz;  // in [1, 3] for usable input; NaN if any was NaN
    auto ok = finite_nonzero & (q2 < V(S(4)));
    V inv = one / vsqrt(select(ok, q2, one));
    x = select(ok, px * inv, V(S(0)));
    y = select(ok, py * inv, V(S(0)));
    z = select(ok, pz * inv, one);
}

}  // namespace sphbasis
