// sphbasis: the dual paraboloid parameterization through the concentric map.
//
// References: W. Heidrich and H.-P. Seidel, "View-independent Environment Maps", Graphics
// Hardware 1998 (the paraboloid projection p = (x, y)/(1 + z), inverse
// d = (2 px, 2 py, 1 - |p|^2)/(1 + |p|^2), solid angle per disk area 4/(1 + |p|^2)^2);
// Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT 2009),
// section 3.2 and appendix A: the disk is mapped to the square by
// Shirley and Chiu's concentric map and shrunk so that the equator lies on the outer ring of
// texel centres (dual_hemisphere.hpp), which makes the reconstruction C0 across the equator
// on DX9-class hardware.
#pragma once

#include <cmath>

#include "concentric.hpp"
#include "dual_hemisphere.hpp"

namespace sphbasis::param {

/// The paraboloid projection of one hemisphere (the Proj of DualHemisphere).
struct ParaboloidProjection {
    static constexpr const char* name = "DualParaboloid";
    template <class T>
    static SPHBASIS_FORCEINLINE Point2<T> disk(T x, T y, T z_abs) noexcept {
        const T inv = T(1) / (T(1) + z_abs);
        return {x * inv, y * inv};
    }
    template <class T>
    static SPHBASIS_FORCEINLINE vec3<T> direction(T px, T py) noexcept {
        const T r2 = px * px + py * py;
        const T inv = T(1) / (T(1) + r2);
        return {T(2) * px * inv, T(2) * py * inv, (T(1) - r2) * inv};
    }
    // g(r) = (pi/4) * 4/(1 + r^2)^2 = pi/(1 + r^2)^2 per unit area of [-1, 1]^2.
    static double g0(double r) noexcept {
        return 1.5707963267948966 * (r / (1.0 + r * r) + std::atan(r));  // pi/2
    }
    static double g1(double r) noexcept {
        return -1.5707963267948966 / (1.0 + r * r);  // -(pi/2)/(1 + r^2)
    }
};

/// [0, 1]^2 -> upper hemisphere: concentric map to the disk, then the inverse paraboloid
/// projection. The square's border is the equator, its centre the pole (0, 0, 1).
template <class T>
SPHBASIS_FORCEINLINE vec3<T> square_to_paraboloid(T u, T v) noexcept {
    const Point2<T> p = square_to_uniform_disk_concentric(u, v);
    return ParaboloidProjection::direction(p.x, p.y);
}

/// Unit direction -> [0, 1]^2 (inverse of square_to_paraboloid); a lower-hemisphere
/// direction is mirrored through the equator plane (|z| is used), as the back face stores it.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> paraboloid_to_square(T x, T y, T z) noexcept {
    const Point2<T> p = ParaboloidProjection::disk(x, y, std::fabs(z));
    return uniform_disk_to_square_concentric(p.x, p.y);
}

/// paraboloid_to_square() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar
/// type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(paraboloid_to_square);

/// Density of square_to_paraboloid() w.r.t. solid angle at the unit direction (x, y, z),
/// 1/(pi (1 + |z|)^2): 1/(4 pi) at the pole, 1/pi on the equator.
template <class T>
SPHBASIS_FORCEINLINE T square_to_paraboloid_pdf(T x, T y, T z) noexcept {
    (void)x;
    (void)y;
    const T a = T(1) + std::fabs(z);
    return T(0.31830988618379067) / (a * a);  // 1/pi
}

/// square_to_paraboloid_pdf() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its
/// scalar type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(square_to_paraboloid_pdf);

/// The dual paraboloid map: 2 faces of n x n texels (see dual_hemisphere.hpp).
template <class T>
using DualParaboloid = DualHemisphere<T, ParaboloidProjection>;

}  // namespace sphbasis::param
