// sphbasis: the octahedral parameterization of the sphere in one square texture.
//
// References: E. Praun and H. Hoppe, "Spherical Parametrization and Remeshing", SIGGRAPH 2003;
// Z. Cigolle et al., "A Survey of Efficient Representations for Independent Unit Vectors",
// JCGT 3(2), 2014 (the encoding used here). A direction d is projected onto the octahedron
// |x| + |y| + |z| = 1, p = d/(|x| + |y| + |z|); the upper half maps to the diamond
// |a| + |b| <= 1 of [-1, 1]^2 as (a, b) = (px, py), the lower half folds out to the corners as
// (a, b) = ((1 - |py|) sgn(px), (1 - |px|) sgn(py)) (sgn(0) = +1). The map is piecewise linear
// onto the octahedron, so texel cells are planar polygons there and their solid angles are
// exact; the solid angle per unit area of [0, 1]^2 is 4/|p|^3, between 4 (vertices) and
// 4 * 3^(3/2) (face centres).
//
// The square's border is the lower half's four meridian arcs, each folded onto itself: (-1, b)
// and (-1, -b) are the same direction (likewise on the other edges), and all four corners are
// the pole (0, 0, -1). Plain hardware (clamp-to-edge) filtering is therefore discontinuous
// there within half a texel of the border; the `seamless` filter reads the mirrored texels
// across the border instead, which is what a one-texel gutter filled with the mirrored texels
// (the usual engine practice) gives, and is C0 everywhere.
#pragma once

#include <cmath>
#include <cstddef>

#include "param.hpp"

namespace sphbasis::param {

/// How an octahedral map is filtered at the square's border.
enum class OctahedralFilter {
    clamp,    ///< hardware clamp-to-edge addressing (discontinuous at the border)
    seamless  ///< taps beyond the border read the mirrored texels (a mirrored gutter)
};

/// Unit direction (or any non-zero vector) -> [0, 1]^2.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> octahedral_to_square(T x, T y, T z) noexcept {
    const T l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    const T inv = l1 > T(0) ? T(1) / l1 : T(0);
    T a = x * inv, b = y * inv;
    if (z < T(0)) {
        const T fa = (T(1) - std::fabs(b)) * (a >= T(0) ? T(1) : T(-1));
        const T fb = (T(1) - std::fabs(a)) * (b >= T(0) ? T(1) : T(-1));
        a = fa;
        b = fb;
    }
    return {T(0.5) * (a + T(1)), T(0.5) * (b + T(1))};
}

/// octahedral_to_square() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar
/// type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(octahedral_to_square);

/// [0, 1]^2 -> unit direction (inverse of octahedral_to_square).
template <class T>
SPHBASIS_FORCEINLINE vec3<T> square_to_octahedral(T u, T v) noexcept {
    T a = T(2) * u - T(1), b = T(2) * v - T(1);
    const T z = T(1) - std::fabs(a) - std::fabs(b);
    if (z < T(0)) {
        const T fa = (T(1) - std::fabs(b)) * (a >= T(0) ? T(1) : T(-1));
        const T fb = (T(1) - std::fabs(a)) * (b >= T(0) ? T(1) : T(-1));
        a = fa;
        b = fb;
    }
    const T inv = T(1) / std::sqrt(a * a + b * b + z * z);
    return {a * inv, b * inv, z * inv};
}

/// Density of square_to_octahedral() w.r.t. solid angle at the unit direction (x, y, z):
/// |p|^3/4 = 1/(4 (|x| + |y| + |z|)^3).
template <class T>
SPHBASIS_FORCEINLINE T square_to_octahedral_pdf(T x, T y, T z) noexcept {
    const T l1 = std::fabs(x) + std::fabs(y) + std::fabs(z);
    return T(1) / (T(4) * l1 * l1 * l1);
}

/// square_to_octahedral_pdf() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its
/// scalar type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(square_to_octahedral_pdf);

/// An octahedral map of n x n texels (one face).
template <class T>
class Octahedral : public detail::TexelGrid, public detail::MapMethods<Octahedral<T>, T> {
  public:
    using detail::MapMethods<Octahedral<T>, T>::direction_to_uv;
    using detail::MapMethods<Octahedral<T>, T>::footprint;

    /// n >= 1. Throws std::invalid_argument outside 1 <= n <= 32768 or
    /// 0 <= subtexel_bits <= 24.
    explicit Octahedral(int resolution, OctahedralFilter filter = OctahedralFilter::seamless,
                        int subtexel_bits = 0)
        : detail::TexelGrid("Octahedral", 1, resolution, resolution, resolution, 1, subtexel_bits),
          filter_(filter) {}

    OctahedralFilter filter() const noexcept { return filter_; }

    FaceUV<T> direction_to_uv(T x, T y, T z) const noexcept {
        const vec3<T> d = detail::unit(x, y, z);
        const Point2<T> s = octahedral_to_square(d.x, d.y, d.z);
        return {0, s.x, s.y};
    }
    vec3<T> uv_to_direction(int /*face*/, T u, T v) const noexcept {
        return square_to_octahedral(u, v);
    }
    /// Exact solid angle of the texel: its cell is cut along a = 0, b = 0 and |a| + |b| = 1
    /// into convex pieces that are planar on the octahedron, each measured as spherical
    /// triangles (Van Oosterom-Strackee), in double.
    T texel_solid_angle(int /*face*/, int col, int row) const noexcept {
        const double n = n_;
        const double a0 = 2.0 * col / n - 1.0, a1 = 2.0 * (col + 1) / n - 1.0;
        const double b0 = 2.0 * row / n - 1.0, b1 = 2.0 * (row + 1) / n - 1.0;
        const double as[3] = {a0, 0.0, a1}, bs[3] = {b0, 0.0, b1};
        const bool split_a = a0 < 0 && a1 > 0, split_b = b0 < 0 && b1 > 0;
        double sum = 0;
        for (int ia = 0; ia < (split_a ? 2 : 1); ++ia)
            for (int ib = 0; ib < (split_b ? 2 : 1); ++ib) {
                const double lo_a = split_a ? as[ia] : a0, hi_a = split_a ? as[ia + 1] : a1;
                const double lo_b = split_b ? bs[ib] : b0, hi_b = split_b ? bs[ib + 1] : b1;
                sum += quadrant_rect_solid_angle(lo_a, hi_a, lo_b, hi_b);
            }
        return static_cast<T>(sum);
    }

    /// The bilinear footprint: clamp-to-edge, or across the border through the mirror
    /// symmetry (col -1 - k reads col k of row n - 1 - row, and likewise for rows).
    Footprint<T> footprint(T x, T y, T z) const noexcept {
        const FaceUV<T> t = direction_to_uv(x, y, z);
        const detail::AxisTaps<T> ax = detail::axis_taps(t.u, n_, bits_);
        const detail::AxisTaps<T> ay = detail::axis_taps(t.v, n_, bits_);
        if (filter_ == OctahedralFilter::clamp ||
            (ax.i0 >= 0 && ax.i0 + 1 < n_ && ay.i0 >= 0 && ay.i0 + 1 < n_))
            return detail::clamped_footprint(0, ax, ay, n_, n_);
        const T fx = ax.frac, fy = ay.frac;
        Footprint<T> fp{{0, 0, 0, 0},
                        {(T(1) - fx) * (T(1) - fy), fx * (T(1) - fy), (T(1) - fx) * fy, fx * fy}};
        for (int k = 0; k < 4; ++k) {
            int i = ax.i0 + (k & 1), j = ay.i0 + (k >> 1);
            if (i < 0 || i >= n_) {
                i = i < 0 ? -1 - i : 2 * n_ - 1 - i;
                j = n_ - 1 - j;
            }
            if (j < 0 || j >= n_) {
                j = j < 0 ? -1 - j : 2 * n_ - 1 - j;
                i = n_ - 1 - i;
            }
            fp.index[k] = texel_index(0, i, j);
        }
        return fp;
    }

  private:
    // A rectangle within one quadrant of [-1, 1]^2, cut by the diamond edge |a| + |b| = 1.
    static double quadrant_rect_solid_angle(double a0, double a1, double b0, double b1) {
        const double sa = a0 + a1 >= 0 ? 1.0 : -1.0, sb = b0 + b1 >= 0 ? 1.0 : -1.0;
        const double rect[4][2] = {{a0, b0}, {a1, b0}, {a1, b1}, {a0, b1}};
        // Clip against sa a + sb b <= 1 (inner) and >= 1 (outer), Sutherland-Hodgman.
        double inner[8][2], outer[8][2];
        int ni = 0, no = 0;
        for (int k = 0; k < 4; ++k) {
            const double* p = rect[k];
            const double* q = rect[(k + 1) % 4];
            const double fp = sa * p[0] + sb * p[1] - 1.0, fq = sa * q[0] + sb * q[1] - 1.0;
            if (fp <= 0) inner[ni][0] = p[0], inner[ni][1] = p[1], ++ni;
            if (fp >= 0) outer[no][0] = p[0], outer[no][1] = p[1], ++no;
            if ((fp < 0 && fq > 0) || (fp > 0 && fq < 0)) {
                const double t = fp / (fp - fq);
                const double x = p[0] + t * (q[0] - p[0]), y = p[1] + t * (q[1] - p[1]);
                inner[ni][0] = x, inner[ni][1] = y, ++ni;
                outer[no][0] = x, outer[no][1] = y, ++no;
            }
        }
        vec3<double> poly[8];
        double sum = 0;
        if (ni >= 3) {
            for (int k = 0; k < ni; ++k)
                poly[k] = {inner[k][0], inner[k][1],
                           1.0 - std::fabs(inner[k][0]) - std::fabs(inner[k][1])};
            sum += detail::polygon_solid_angle(poly, ni);
        }
        if (no >= 3) {
            for (int k = 0; k < no; ++k) {
                const double a = std::fabs(outer[k][0]), b = std::fabs(outer[k][1]);
                poly[k] = {sa * (1.0 - b), sb * (1.0 - a), 1.0 - a - b};
            }
            sum += detail::polygon_solid_angle(poly, no);
        }
        return sum;
    }

    OctahedralFilter filter_;
};

}  // namespace sphbasis::param
