// sphbasis: the machinery shared by the dual-hemisphere parameterizations (dual paraboloid,
// dual orthographic): a hemisphere projected onto the unit disk, the disk mapped onto the
// square by the concentric map (concentric.hpp), the square shrunk so that the equator lies
// exactly on the outer ring of texel centres.
//
// Reference: Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009), section 3.2 and appendix A: "shrink the mapping so that the equator maps
// exactly to the outer ring of texel centers on the square. This generates redundant texels
// between hemispheres, but guarantees continuity." Both faces map the equator direction
// (x, y, 0) to the same (u, v), and bilinear filtering on the outer ring reads only ring
// texels, which hold the same directions on both faces, so the reconstruction is C0 across
// the equator with plain clamp-to-edge addressing.
//
// Layout: 2 faces of n x n texels; face 0 is the upper hemisphere z >= 0, face 1 the lower
// one (mirrored through the equator plane: the same (u, v) on both faces differ only in the
// sign of z). A direction on the equator goes to face 0.
#pragma once

#include <cmath>
#include <cstddef>

#include "concentric.hpp"
#include "param.hpp"

namespace sphbasis::param {

/// A dual-hemisphere parameterization with projection Proj (see dual_paraboloid.hpp,
/// dual_orthographic.hpp for the two in the library). Proj provides
///   Point2<T> disk(T x, T y, T z_abs)     direction (unit, z_abs >= 0) -> unit disk
///   vec3<T>   direction(T px, T py)        unit disk -> unit direction with z >= 0
///   double    g0(double r), g1(double r)   antiderivatives of g and r g, where g(r) is the
///                                          solid angle per unit area of [-1, 1]^2 at Chebyshev
///                                          radius r (so that int g(max|a|,|b|) = 2 pi)
template <class T, class Proj>
class DualHemisphere : public detail::TexelGrid,
                       public detail::MapMethods<DualHemisphere<T, Proj>, T> {
  public:
    using detail::MapMethods<DualHemisphere<T, Proj>, T>::direction_to_uv;
    using detail::MapMethods<DualHemisphere<T, Proj>, T>::footprint;

    /// n x n texels per hemisphere, n >= 2 (the shrink needs two rings of centres).
    /// subtexel_bits > 0 quantises bilinear weights as hardware does. Throws
    /// std::invalid_argument outside 2 <= n <= 32768 or 0 <= subtexel_bits <= 24.
    explicit DualHemisphere(int resolution, int subtexel_bits = 0)
        : detail::TexelGrid(Proj::name, 2, resolution, resolution, resolution, 2, subtexel_bits) {}

    /// Face (0: z >= 0, 1: z < 0) and texture coordinates in [0.5/n, 1 - 0.5/n]^2.
    FaceUV<T> direction_to_uv(T x, T y, T z) const noexcept {
        const vec3<T> d = detail::unit(x, y, z);
        const int face = d.z >= T(0) ? 0 : 1;
        const Point2<T> p = Proj::template disk<T>(d.x, d.y, std::fabs(d.z));
        const Point2<T> s = uniform_disk_to_square_concentric(p.x, p.y);
        return {face, detail::shrink(s.x, n_), detail::shrink(s.y, n_)};
    }

    /// Unit direction of (face, u, v); (u, v) outside the shrunk square are clamped onto it
    /// (the border of the square is the equator).
    vec3<T> uv_to_direction(int face, T u, T v) const noexcept {
        const Point2<T> p =
            square_to_uniform_disk_concentric(detail::unshrink(u, n_), detail::unshrink(v, n_));
        vec3<T> d = Proj::template direction<T>(p.x, p.y);
        if (face == 1) d.z = -d.z;
        return d;
    }

    /// Solid angle of the part of the texel's cell inside the shrunk square (the outer ring
    /// cells are half or quarter cells: their other part belongs to the other hemisphere's
    /// copy). Closed form via detail::chebyshev_rect_integral, computed in double.
    T texel_solid_angle(int /*face*/, int col, int row) const noexcept {
        const double n = n_, h = 0.5 / n;
        const double u0 = std::fmax(col / n, h), u1 = std::fmin((col + 1) / n, 1.0 - h);
        const double v0 = std::fmax(row / n, h), v1 = std::fmin((row + 1) / n, 1.0 - h);
        if (!(u0 < u1) || !(v0 < v1)) return T(0);
        auto sq = [h](double u) { return 2.0 * (u - h) / (1.0 - 2.0 * h) - 1.0; };
        return static_cast<T>(detail::chebyshev_rect_integral(
            sq(u0), sq(u1), sq(v0), sq(v1), [](double r) { return Proj::g0(r); },
            [](double r) { return Proj::g1(r); }));
    }

    /// Bilinear footprint on the face of the direction, clamp-to-edge addressing (never
    /// reached: every direction lies within the ring of outer texel centres).
    Footprint<T> footprint(T x, T y, T z) const noexcept {
        const FaceUV<T> t = direction_to_uv(x, y, z);
        return detail::clamped_footprint(
            static_cast<std::size_t>(t.face) * static_cast<std::size_t>(n_) *
                static_cast<std::size_t>(n_),
            detail::axis_taps(t.u, n_, bits_), detail::axis_taps(t.v, n_, bits_), n_, n_);
    }

  private:
};

}  // namespace sphbasis::param
