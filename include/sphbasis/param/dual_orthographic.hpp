// sphbasis: the dual orthographic parameterization through the concentric map.
//
// Each hemisphere is projected orthographically onto the disk, p = (x, y), inverse
// d = (px, py, sqrt(1 - |p|^2)); solid angle per disk area 1/sqrt(1 - |p|^2), singular (but
// integrable) at the equator, so texels crowd towards the pole's opposite. Together with the
// concentric map this is Malley's cosine-weighted hemisphere sampling. Layout and the shrink
// that puts the equator on the outer ring of texel centres are those of Iwanicki and Sloan,
// "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT 2009), appendix A, shared with
// the dual paraboloid in dual_hemisphere.hpp.
#pragma once

#include <cmath>

#include "concentric.hpp"
#include "dual_hemisphere.hpp"

namespace sphbasis::param {

/// The orthographic projection of one hemisphere (the Proj of DualHemisphere).
struct OrthographicProjection {
    static constexpr const char* name = "DualOrthographic";
    template <class T>
    static SPHBASIS_FORCEINLINE Point2<T> disk(T x, T y, T /*z_abs*/) noexcept {
        return {x, y};
    }
    template <class T>
    static SPHBASIS_FORCEINLINE vec3<T> direction(T px, T py) noexcept {
        const T r = std::sqrt(px * px + py * py);
        const T z2 = (T(1) - r) * (T(1) + r);  // no cancellation near the equator
        if (r > T(1)) return {px / r, py / r, T(0)};
        return {px, py, std::sqrt(z2 > T(0) ? z2 : T(0))};
    }
    // g(r) = (pi/4)/sqrt(1 - r^2) per unit area of [-1, 1]^2.
    static double g0(double r) noexcept {
        return 0.78539816339744831 * std::asin(r > 1.0 ? 1.0 : r);  // pi/4
    }
    static double g1(double r) noexcept {
        return -0.78539816339744831 * std::sqrt(r >= 1.0 ? 0.0 : (1.0 - r) * (1.0 + r));
    }
};

/// [0, 1]^2 -> upper hemisphere: concentric map to the disk, then lift orthographically.
template <class T>
SPHBASIS_FORCEINLINE vec3<T> square_to_orthographic(T u, T v) noexcept {
    const Point2<T> p = square_to_uniform_disk_concentric(u, v);
    return OrthographicProjection::direction(p.x, p.y);
}

/// Unit direction -> [0, 1]^2 (inverse of square_to_orthographic); the sign of z is ignored.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> orthographic_to_square(T x, T y, T z) noexcept {
    (void)z;
    return uniform_disk_to_square_concentric(x, y);
}

/// orthographic_to_square() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar
/// type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(orthographic_to_square);

/// Density of square_to_orthographic() w.r.t. solid angle, |z|/pi (cosine-weighted).
template <class T>
SPHBASIS_FORCEINLINE T square_to_orthographic_pdf(T x, T y, T z) noexcept {
    (void)x;
    (void)y;
    return std::fabs(z) * T(0.31830988618379067);  // 1/pi
}

/// square_to_orthographic_pdf() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its
/// scalar type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(square_to_orthographic_pdf);

/// The dual orthographic map: 2 faces of n x n texels (see dual_hemisphere.hpp).
template <class T>
using DualOrthographic = DualHemisphere<T, OrthographicProjection>;

}  // namespace sphbasis::param
