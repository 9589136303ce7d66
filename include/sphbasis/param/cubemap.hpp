// sphbasis: cube maps, with DX9-class filtering (bilinear within a face, clamp-to-edge per
// face, discontinuous across faces) and DX10-class seamless filtering (the bilinear footprint
// continues onto the neighbouring face; at a cube corner, where only three texels exist, the
// missing fourth is their average).
//
// References: the OpenGL 4.6 specification, section 8.13 (cube map face selection, table 8.19)
// and ARB_seamless_cube_map (the corner rule: "average the values of the three available
// samples"); Direct3D 10 functional specification (cube filtering across faces); Iwanicki
// and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT 2009), section 3.2
// and appendix A, which compares both behaviours.
//
// Faces in the D3D/GL order +X, -X, +Y, -Y, +Z, -Z. For a direction r with major axis ma,
// (sc, tc) from table 8.19 and (u, v) = ((sc/|ma| + 1)/2, (tc/|ma| + 1)/2):
//   +X: sc = -rz, tc = -ry     -X: sc = +rz, tc = -ry
//   +Y: sc = +rx, tc = +rz     -Y: sc = +rx, tc = -rz
//   +Z: sc = +rx, tc = -ry     -Z: sc = -rx, tc = -ry
// Ties between axes go to x, then y (|x| >= |y|, |z| picks x; else |y| >= |z| picks y).
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include "param.hpp"

namespace sphbasis::param {

/// How a cube map is filtered at face edges.
enum class CubeFilter {
    dx9_clamped,   ///< bilinear within the face, clamp-to-edge per face (DX9 class)
    dx10_seamless  ///< bilinear across faces, corner texel = average of the three (DX10+)
};

namespace detail {

/// The (unnormalised) point of face `face` at face coordinates (sc, tc) in [-1, 1]^2 (or
/// beyond, on the face's plane).
template <class T>
SPHBASIS_FORCEINLINE vec3<T> cube_face_point(int face, T sc, T tc) noexcept {
    switch (face) {
        case 0:
            return {T(1), -tc, -sc};
        case 1:
            return {T(-1), -tc, sc};
        case 2:
            return {sc, T(1), tc};
        case 3:
            return {sc, T(-1), -tc};
        case 4:
            return {sc, -tc, T(1)};
        default:
            return {-sc, -tc, T(-1)};
    }
}

/// Face and face coordinates (sc, tc) in [-1, 1]^2 of a non-zero vector; also |ma|.
template <class T>
struct CubeCoord {
    int face;
    T sc, tc, ma;
};
template <class T>
SPHBASIS_FORCEINLINE CubeCoord<T> cube_select(T x, T y, T z) noexcept {
    const T ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
    CubeCoord<T> c;
    T sc, tc;
    if (ax >= ay && ax >= az) {
        c.face = x >= T(0) ? 0 : 1;
        c.ma = ax;
        sc = x >= T(0) ? -z : z;
        tc = -y;
    } else if (ay >= az) {
        c.face = y >= T(0) ? 2 : 3;
        c.ma = ay;
        sc = x;
        tc = y >= T(0) ? z : -z;
    } else {
        c.face = z >= T(0) ? 4 : 5;
        c.ma = az;
        sc = z >= T(0) ? x : -x;
        tc = -y;
    }
    const T inv = c.ma > T(0) ? T(1) / c.ma : T(0);
    auto clamp1 = [](T t) { return t > T(1) ? T(1) : (t < T(-1) ? T(-1) : t); };
    c.sc = clamp1(sc * inv);
    c.tc = clamp1(tc * inv);
    return c;
}

inline double cube_rect_solid_angle_corner(double s, double t) noexcept {
    return std::atan2(s * t, std::sqrt(s * s + t * t + 1.0));
}

}  // namespace detail

/// Unit direction -> cube face and (u, v) in [0, 1]^2 (table above). The zero vector gives
/// face +X, (0.5, 0.5).
template <class T>
SPHBASIS_FORCEINLINE FaceUV<T> cube_to_square(T x, T y, T z) noexcept {
    const detail::CubeCoord<T> c = detail::cube_select(x, y, z);
    return {c.face, T(0.5) * (c.sc + T(1)), T(0.5) * (c.tc + T(1))};
}

/// cube_to_square() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(cube_to_square);

/// Cube face (0..5) and (u, v) in [0, 1]^2 -> unit direction.
template <class T>
SPHBASIS_FORCEINLINE vec3<T> square_to_cube(int face, T u, T v) noexcept {
    vec3<T> p = detail::cube_face_point(face, T(2) * u - T(1), T(2) * v - T(1));
    const T inv = T(1) / std::sqrt(dot(p, p));
    return {p.x * inv, p.y * inv, p.z * inv};
}

/// Density w.r.t. solid angle of picking a face uniformly and (u, v) uniformly on it,
/// at the unit direction (x, y, z): (1 + sc^2 + tc^2)^(3/2)/24 = 1/(24 |ma|^3).
template <class T>
SPHBASIS_FORCEINLINE T square_to_cube_pdf(T x, T y, T z) noexcept {
    const T ma = std::fmax(std::fabs(x), std::fmax(std::fabs(y), std::fabs(z)));
    return T(1) / (T(24) * ma * ma * ma);
}

/// square_to_cube_pdf() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar
/// type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(square_to_cube_pdf);

/// A cube map of 6 faces of n x n texels, filtered as `filter` says.
template <class T>
class CubeMap : public detail::TexelGrid, public detail::MapMethods<CubeMap<T>, T> {
  public:
    using detail::MapMethods<CubeMap<T>, T>::direction_to_uv;
    using detail::MapMethods<CubeMap<T>, T>::footprint;

    /// n >= 1 texels per face edge. Throws std::invalid_argument outside 1 <= n <= 32768 or
    /// 0 <= subtexel_bits <= 24. Cost: O(n) for the seam table of dx10_seamless.
    explicit CubeMap(int resolution, CubeFilter filter = CubeFilter::dx10_seamless,
                     int subtexel_bits = 0)
        : detail::TexelGrid("CubeMap", 6, resolution, resolution, resolution, 1, subtexel_bits),
          filter_(filter) {
        if (filter_ == CubeFilter::dx10_seamless) build_seams();
    }

    CubeFilter filter() const noexcept { return filter_; }

    FaceUV<T> direction_to_uv(T x, T y, T z) const noexcept {
        const vec3<T> d = detail::unit(x, y, z);
        return cube_to_square(d.x, d.y, d.z);
    }
    vec3<T> uv_to_direction(int face, T u, T v) const noexcept {
        return square_to_cube(face, u, v);
    }
    /// Exact solid angle of the texel (the area of its face rectangle projected onto the
    /// sphere, via atan(st/sqrt(1 + s^2 + t^2)) at the corners), in double.
    T texel_solid_angle(int /*face*/, int col, int row) const noexcept {
        const double n = n_;
        const double s0 = 2.0 * col / n - 1.0, s1 = 2.0 * (col + 1) / n - 1.0;
        const double t0 = 2.0 * row / n - 1.0, t1 = 2.0 * (row + 1) / n - 1.0;
        using detail::cube_rect_solid_angle_corner;
        return static_cast<T>(
            cube_rect_solid_angle_corner(s1, t1) - cube_rect_solid_angle_corner(s0, t1) -
            cube_rect_solid_angle_corner(s1, t0) + cube_rect_solid_angle_corner(s0, t0));
    }

    /// The bilinear footprint as DX9 (clamped per face) or DX10+ (seamless) hardware reads it.
    Footprint<T> footprint(T x, T y, T z) const noexcept {
        const FaceUV<T> t = direction_to_uv(x, y, z);
        const detail::AxisTaps<T> ax = detail::axis_taps(t.u, n_, bits_);
        const detail::AxisTaps<T> ay = detail::axis_taps(t.v, n_, bits_);
        const std::size_t base = texel_index(t.face, 0, 0);
        if (filter_ == CubeFilter::dx9_clamped ||
            (ax.i0 >= 0 && ax.i0 + 1 < n_ && ay.i0 >= 0 && ay.i0 + 1 < n_))
            return detail::clamped_footprint(base, ax, ay, n_, n_);
        const T fx = ax.frac, fy = ay.frac;
        Footprint<T> fp{{0, 0, 0, 0},
                        {(T(1) - fx) * (T(1) - fy), fx * (T(1) - fy), (T(1) - fx) * fy, fx * fy}};
        int missing = -1;
        for (int k = 0; k < 4; ++k) {
            const int i = ax.i0 + (k & 1), j = ay.i0 + (k >> 1);
            const bool in_i = i >= 0 && i < n_, in_j = j >= 0 && j < n_;
            if (in_i && in_j)
                fp.index[k] = texel_index(t.face, i, j);
            else if (in_j)
                fp.index[k] = seam(t.face, i < 0 ? 0 : 1, j);
            else if (in_i)
                fp.index[k] = seam(t.face, j < 0 ? 2 : 3, i);
            else
                missing = k;
        }
        if (missing >= 0) {
            // Cube corner: three texels meet; the fourth tap is their average.
            const T share = fp.weight[missing] / T(3);
            for (int k = 0; k < 4; ++k) fp.weight[k] += share;
            fp.weight[missing] = T(0);
            fp.index[missing] = fp.index[missing ^ 3];
        }
        return fp;
    }

  private:
    // Texel index across edge `edge` of `face` (0: col -1, 1: col n, 2: row -1, 3: row n) at
    // position k along the edge.
    std::size_t seam(int face, int edge, int k) const noexcept {
        return seams_[(static_cast<std::size_t>(face) * 4 + static_cast<std::size_t>(edge)) *
                          static_cast<std::size_t>(n_) +
                      static_cast<std::size_t>(k)];
    }

    // The texel beyond an edge is found by folding its centre, which lies a distance d past the
    // edge on the face's plane, onto the neighbouring face at the same distance d from the edge.
    void build_seams() {
        seams_.resize(static_cast<std::size_t>(6 * 4) * static_cast<std::size_t>(n_));
        const double n = n_;
        for (int face = 0; face < 6; ++face)
            for (int edge = 0; edge < 4; ++edge)
                for (int k = 0; k < n_; ++k) {
                    const int i = edge == 0 ? -1 : (edge == 1 ? n_ : k);
                    const int j = edge == 2 ? -1 : (edge == 3 ? n_ : k);
                    const double sc = 2.0 * (i + 0.5) / n - 1.0, tc = 2.0 * (j + 0.5) / n - 1.0;
                    vec3<double> p = detail::cube_face_point(face, sc, tc);
                    double* c[3] = {&p.x, &p.y, &p.z};
                    const int major = face / 2;
                    for (int a = 0; a < 3; ++a) {
                        if (a == major || std::fabs(*c[a]) <= 1.0) continue;
                        const double over = std::fabs(*c[a]) - 1.0;
                        *c[a] = std::copysign(1.0, *c[a]);
                        *c[major] = std::copysign(1.0 - over, *c[major]);
                    }
                    const detail::CubeCoord<double> q = detail::cube_select(p.x, p.y, p.z);
                    auto texel = [n, this](double s) {
                        const long t = std::lround((s + 1.0) * 0.5 * n - 0.5);
                        return static_cast<int>(t < 0 ? 0 : (t >= n_ ? n_ - 1 : t));
                    };
                    seams_[(static_cast<std::size_t>(face) * 4 + static_cast<std::size_t>(edge)) *
                               static_cast<std::size_t>(n_) +
                           static_cast<std::size_t>(k)] =
                        texel_index(q.face, texel(q.sc), texel(q.tc));
                }
    }

    CubeFilter filter_;
    std::vector<std::size_t> seams_;
};

}  // namespace sphbasis::param
