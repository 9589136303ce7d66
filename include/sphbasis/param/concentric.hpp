// sphbasis: Shirley and Chiu's concentric map between the unit square and the unit disk.
//
// Reference: P. Shirley and K. Chiu, "A Low Distortion Map Between Disk and Square", Journal
// of Graphics Tools 2(3), 1997; the single-branch form is Mitsuba's (warp.h). The map sends
// the square ring max(|a|, |b|) = r of [-1, 1]^2 onto the disk circle of radius r and is
// area-preserving up to the constant pi/4 (pi per unit area of [0, 1]^2). It is continuous
// and bijective; the dual-hemisphere parameterizations (dual_paraboloid.hpp,
// dual_orthographic.hpp) use it to store a hemisphere in a square texture without wasting the
// corners, as Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT
// 2009), section 3.2, do.
#pragma once

#include <cmath>

#include "param.hpp"

namespace sphbasis::param {

namespace detail {

/// [-1, 1]^2 -> unit disk.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> square_to_disk_pm(T a, T b) noexcept {
    const T quarter_pi = T(0.78539816339744831);  // pi/4
    if (a == T(0) && b == T(0)) return {T(0), T(0)};
    if (std::fabs(a) > std::fabs(b)) {
        const T phi = quarter_pi * (b / a);
        return {a * std::cos(phi), a * std::sin(phi)};
    }
    // phi = pi/2 - (pi/4)(a/b); cos(phi) = sin((pi/4) a/b), sin(phi) = cos((pi/4) a/b)
    const T psi = quarter_pi * (a / b);
    return {b * std::sin(psi), b * std::cos(psi)};
}

/// Unit disk -> [-1, 1]^2 (inverse of square_to_disk_pm). Points outside the disk are taken
/// at their radius and the result is clamped to [-1, 1]^2.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> disk_to_square_pm(T px, T py) noexcept {
    const T four_over_pi = T(1.2732395447351627);  // 4/pi
    const T r = std::sqrt(px * px + py * py);
    if (!(r > T(0))) return {T(0), T(0)};
    T a, b;
    if (std::fabs(px) >= std::fabs(py)) {
        a = std::copysign(r, px);
        b = a * four_over_pi * std::atan(py / px);
    } else {
        b = std::copysign(r, py);
        a = b * four_over_pi * std::atan(px / py);
    }
    auto clamp1 = [](T t) { return t > T(1) ? T(1) : (t < T(-1) ? T(-1) : t); };
    return {clamp1(a), clamp1(b)};
}

}  // namespace detail

/// Concentric map [0, 1]^2 -> unit disk (Shirley-Chiu). Continuous, area-preserving up to pi.
/// Cost: one sin, one cos, one division.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> square_to_uniform_disk_concentric(T u, T v) noexcept {
    return detail::square_to_disk_pm(T(2) * u - T(1), T(2) * v - T(1));
}

/// Inverse concentric map, unit disk -> [0, 1]^2. The centre maps to (0.5, 0.5); points
/// outside the disk are clamped onto the square's border. Cost: one sqrt, one atan, a division.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> uniform_disk_to_square_concentric(T px, T py) noexcept {
    const Point2<T> s = detail::disk_to_square_pm(px, py);
    return {T(0.5) * (s.x + T(1)), T(0.5) * (s.y + T(1))};
}

/// Density of square_to_uniform_disk_concentric() w.r.t. area on the disk: 1/pi inside the
/// unit disk, 0 outside.
template <class T>
SPHBASIS_FORCEINLINE T square_to_uniform_disk_concentric_pdf(T px, T py) noexcept {
    return px * px + py * py <= T(1) ? T(0.31830988618379067) : T(0);  // 1/pi
}

}  // namespace sphbasis::param
