// sphbasis: the shared interface of the spherical parameterizations (param/*.hpp).
//
// Every parameterization class (DualParaboloid, DualOrthographic, CubeMap, Octahedral, LatLong)
// stores a function of direction in `faces()` images of width() x height() texels, face-major
// and row-major: texel_index(face, col, row) = (face * height + row) * width + col. Texture
// coordinates (u, v) are in [0, 1] per face; texel (col, row) has its centre at
// ((col + 0.5)/width, (row + 0.5)/height), as on GPUs (D3D10+, GL). Each class provides
//
//   FaceUV<T>    direction_to_uv(x, y, z)      the face and (u, v) of a direction
//   vec3<T>      uv_to_direction(face, u, v)   the unit direction of (face, u, v)
//   vec3<T>      texel_direction(face, c, r)   the direction of a texel centre
//   T            texel_solid_angle(face, c, r) the solid angle of the texel's cell (sums to 4 pi)
//   Footprint<T> footprint(x, y, z)            the texels and weights of a bilinear fetch
//
// and the free functions reconstruct(), tabulate() and lookup() below work on any of them.
// The bilinear footprint is the one texture hardware computes: x = u * width - 0.5,
// i0 = floor(x), weights (1 - frac, frac), the out-of-range taps resolved by the
// parameterization's addressing (clamp per face, wrap, or a neighbouring face). Hardware
// quantises frac to a few bits (8 on current GPUs); set subtexel_bits to emulate that.
//
// Directions passed to the class methods need not be unit length: any finite non-zero vector
// is normalised, and a zero or non-finite vector is read as the pole (0, 0, 1)
// (normalize_or_pole). The Mitsuba-style free functions (square_to_X, X_to_square, X_pdf)
// take unit vectors.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "../config.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/vec.hpp"

/// Defines fn(const D& d) for any 3-vector type D (glm::vec3, Eigen::Vector3f, ...) as
/// fn<T>(x, y, z) in D's scalar type T: the direction overloads of the free functions
/// (X_to_square, square_to_X_pdf) of the parameterization headers.
// clang-format off
#define SPHBASIS_PARAM_DIRECTION_OVERLOAD(fn)                                                      \
    template <class D>                                                                             \
    SPHBASIS_FORCEINLINE auto fn(const D& d) noexcept {                                            \
        ::sphbasis::detail::static_check_direction<D>();                                           \
        using T = ::sphbasis::direction_scalar_t<D>;                                               \
        return fn<T>(::sphbasis::component<0>(d), ::sphbasis::component<1>(d),                     \
                     ::sphbasis::component<2>(d));                                                 \
    }                                                                                              \
    static_assert(true, "SPHBASIS_PARAM_DIRECTION_OVERLOAD ends with a semicolon")
// clang-format on

namespace sphbasis::param {

/// A point of the plane (a square or disk sample).
template <class T>
struct Point2 {
    T x, y;
};

/// Texture coordinates of a direction: a face and (u, v) in [0, 1]^2 on that face.
template <class T>
struct FaceUV {
    int face;
    T u, v;
};

/// The texels of one bilinear fetch and their weights (non-negative, summing to 1). Indices
/// are texel indices (texel_index()); taps may repeat (clamping) or carry weight 0.
template <class T>
struct Footprint {
    std::size_t index[4];
    T weight[4];
};

/// Blends the interleaved table (texel k, channel c at table[k * channels + c]) at a
/// footprint: out[c] = sum_k weight_k * table[index_k * channels + c]. V is float or double.
template <class V, class T>
SPHBASIS_FORCEINLINE void reconstruct(const V* SPHBASIS_RESTRICT table, std::size_t channels,
                                      const Footprint<T>& fp, V* SPHBASIS_RESTRICT out) noexcept {
    const V* t0 = table + fp.index[0] * channels;
    const V* t1 = table + fp.index[1] * channels;
    const V* t2 = table + fp.index[2] * channels;
    const V* t3 = table + fp.index[3] * channels;
    const V w0 = static_cast<V>(fp.weight[0]), w1 = static_cast<V>(fp.weight[1]);
    const V w2 = static_cast<V>(fp.weight[2]), w3 = static_cast<V>(fp.weight[3]);
    for (std::size_t c = 0; c < channels; ++c)
        out[c] = w0 * t0[c] + w1 * t1[c] + w2 * t2[c] + w3 * t3[c];
}

/// Tabulates f at every texel centre of p: f(x, y, z, V* out) writes `channels` values for
/// the unit direction (x, y, z) of type T. Returns texel_count() * channels values,
/// interleaved. Throws std::invalid_argument for channels == 0.
template <class V, class P, class F>
std::vector<V> tabulate(const P& p, std::size_t channels, F&& f) {
    if (channels == 0) sphbasis::detail::throw_invalid("param::tabulate", "channels >= 1, got 0");
    std::vector<V> table(p.texel_count() * channels);
    for (int face = 0; face < p.faces(); ++face)
        for (int row = 0; row < p.height(); ++row)
            for (int col = 0; col < p.width(); ++col) {
                const auto d = p.texel_direction(face, col, row);
                f(d.x, d.y, d.z, table.data() + p.texel_index(face, col, row) * channels);
            }
    return table;
}

/// Bilinear lookup of an interleaved table at a direction, as texture hardware filters it.
template <class V, class P, class T>
SPHBASIS_FORCEINLINE void lookup(const P& p, const V* table, std::size_t channels, T x, T y, T z,
                                 V* out) noexcept {
    reconstruct(table, channels, p.footprint(x, y, z), out);
}
/// lookup() at a direction of any 3-vector type (glm::vec3, Eigen::Vector3f, ...).
template <class V, class P, class D>
SPHBASIS_FORCEINLINE void lookup(const P& p, const V* table, std::size_t channels, const D& d,
                                 V* out) noexcept {
    sphbasis::detail::static_check_direction<D>();
    reconstruct(table, channels, p.footprint(d), out);
}

/// Total solid angle of all texels of p (4 pi up to rounding), summed in double.
template <class P>
double total_solid_angle(const P& p) {
    double sum = 0;
    for (int face = 0; face < p.faces(); ++face)
        for (int row = 0; row < p.height(); ++row)
            for (int col = 0; col < p.width(); ++col)
                sum += static_cast<double>(p.texel_solid_angle(face, col, row));
    return sum;
}

namespace detail {

/// Bilinear taps along one axis of `n` texels: first texel index i0 (may be -1 or n - 1)
/// and the weight frac of texel i0 + 1. Coordinates outside [0, 1] and NaN are clamped to
/// [0, 1] first (callers only pass in-range coordinates; this keeps the result finite).
template <class T>
struct AxisTaps {
    int i0;
    T frac;
};

template <class T>
SPHBASIS_FORCEINLINE AxisTaps<T> axis_taps(T coord, int n, int subtexel_bits) noexcept {
    T c = coord > T(0) ? (coord < T(1) ? coord : T(1)) : T(0);
    const T x = c * static_cast<T>(n) - T(0.5);
    const T f = std::floor(x);
    T frac = x - f;
    int i0 = static_cast<int>(f);
    if (subtexel_bits > 0) {
        const T scale = std::ldexp(T(1), subtexel_bits);
        frac = std::nearbyint(frac * scale) / scale;
        if (frac >= T(1)) {
            frac = T(0);
            ++i0;
        }
    }
    return {i0, frac};
}

/// Texture coordinate of a unit-square coordinate s in [0, 1] shrunk so that s = 0 and s = 1
/// fall on the outer texel centres 0.5/n and 1 - 0.5/n (Iwanicki and Sloan, JGT 2009,
/// appendix A).
template <class T>
SPHBASIS_FORCEINLINE T shrink(T s, int n) noexcept {
    const T h = T(0.5) / static_cast<T>(n);
    return h + (T(1) - T(2) * h) * s;
}
/// Inverse of shrink(), clamped to [0, 1].
template <class T>
SPHBASIS_FORCEINLINE T unshrink(T u, int n) noexcept {
    const T h = T(0.5) / static_cast<T>(n);
    const T s = (u - h) / (T(1) - T(2) * h);
    return s > T(0) ? (s < T(1) ? s : T(1)) : T(0);
}

/// The solid angle of the spherical triangle spanned by directions a, b, c (any lengths),
/// Van Oosterom and Strackee's formula; exact for triangles whose edges are great arcs, which
/// includes any planar polygon not containing the origin.
inline double triangle_solid_angle(const vec3<double>& a, const vec3<double>& b,
                                   const vec3<double>& c) noexcept {
    const double la = std::sqrt(dot(a, a)), lb = std::sqrt(dot(b, b)), lc = std::sqrt(dot(c, c));
    // a . ((b - a) x (c - a)) equals a . (b x c) without its cancellation for small triangles.
    const vec3<double> ab{b.x - a.x, b.y - a.y, b.z - a.z}, ac{c.x - a.x, c.y - a.y, c.z - a.z};
    const double num = std::fabs(dot(a, cross(ab, ac)));
    const double den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    return 2.0 * std::atan2(num, den);
}

/// Solid angle of a convex planar polygon (vertices in order, the plane not through the
/// origin), as a fan of triangles.
inline double polygon_solid_angle(const vec3<double>* v, int count) noexcept {
    double sum = 0;
    for (int k = 1; k + 1 < count; ++k) sum += triangle_solid_angle(v[0], v[k], v[k + 1]);
    return sum;
}

/// Integral over the rectangle [x0, x1] x [y0, y1] (inside [-1, 1]^2) of g(max(|x|, |y|)),
/// given antiderivatives G0 of g and G1 of x g. The density of the dual-hemisphere maps
/// depends on the square only through max(|x|, |y|) (the concentric map sends that square
/// ring to the disk circle of the same radius, preserving area up to pi/4), so this gives
/// their texel solid angles in closed form.
template <class G0, class G1>
double chebyshev_rect_integral(double x0, double x1, double y0, double y1, G0&& g0, G1&& g1) {
    // int_{a0}^{a1} g(x) * |[b0, b1] n [0, x]| dx, the part where x >= y in the first quadrant.
    auto part = [&](double a0, double a1, double b0, double b1) {
        double s = 0;
        double lo = std::fmax(a0, b0), hi = std::fmin(a1, b1);
        if (lo < hi) s += (g1(hi) - g1(lo)) - b0 * (g0(hi) - g0(lo));
        lo = std::fmax(a0, b1);
        hi = a1;
        if (lo < hi) s += (b1 - b0) * (g0(hi) - g0(lo));
        return s;
    };
    // The integrand is even in x and y: fold each interval onto [0, 1] (one or two pieces).
    auto fold = [](double a0, double a1, double(&out)[2][2]) {
        int n = 0;
        if (a0 < 0 && a1 > 0) {
            out[n][0] = 0, out[n][1] = -a0, ++n;
            out[n][0] = 0, out[n][1] = a1, ++n;
        } else if (a1 <= 0) {
            out[n][0] = -a1, out[n][1] = -a0, ++n;
        } else {
            out[n][0] = a0, out[n][1] = a1, ++n;
        }
        return n;
    };
    double xs[2][2], ys[2][2];
    const int nx = fold(x0, x1, xs), ny = fold(y0, y1, ys);
    double sum = 0;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j)
            sum += part(xs[i][0], xs[i][1], ys[j][0], ys[j][1]) +
                   part(ys[j][0], ys[j][1], xs[i][0], xs[i][1]);
    return sum;
}

/// The footprint of a bilinear fetch with clamp-to-edge addressing on a w x h face whose
/// first texel has index `base`.
template <class T>
SPHBASIS_FORCEINLINE Footprint<T> clamped_footprint(std::size_t base, AxisTaps<T> ax,
                                                    AxisTaps<T> ay, int w, int h) noexcept {
    auto cl = [](int i, int n) { return i < 0 ? 0 : (i >= n ? n - 1 : i); };
    const std::size_t i0 = static_cast<std::size_t>(cl(ax.i0, w));
    const std::size_t i1 = static_cast<std::size_t>(cl(ax.i0 + 1, w));
    const std::size_t r0 =
        base + static_cast<std::size_t>(cl(ay.i0, h)) * static_cast<std::size_t>(w);
    const std::size_t r1 =
        base + static_cast<std::size_t>(cl(ay.i0 + 1, h)) * static_cast<std::size_t>(w);
    const T fx = ax.frac, fy = ay.frac;
    return {{r0 + i0, r0 + i1, r1 + i0, r1 + i1},
            {(T(1) - fx) * (T(1) - fy), fx * (T(1) - fy), (T(1) - fx) * fy, fx * fy}};
}

inline void check_resolution(const char* fn, int n, int min_n) {
    if (n < min_n || n > (1 << 15))
        sphbasis::detail::throw_invalid(
            (std::string("param::") + fn).c_str(),
            std::to_string(min_n) + " <= resolution <= 32768, got " + std::to_string(n));
}
/// n after check_resolution(), for constructor initialiser lists that derive sizes from it
/// (2 n) before the body could check.
inline int checked_resolution(const char* fn, int n, int min_n) {
    check_resolution(fn, n, min_n);
    return n;
}
inline void check_subtexel_bits(const char* fn, int bits) {
    if (bits < 0 || bits > 24)
        sphbasis::detail::throw_invalid((std::string("param::") + fn).c_str(),
                                        "0 <= subtexel_bits <= 24, got " + std::to_string(bits));
}

/// Normalises a direction for the class methods (see the header comment).
template <class T>
SPHBASIS_FORCEINLINE vec3<T> unit(T x, T y, T z) noexcept {
    normalize_or_pole(x, y, z);
    return {x, y, z};
}

/// Texel bookkeeping shared by every parameterization: `faces` images of width x height texels,
/// face-major then row-major (the layout the file header describes).
class TexelGrid {
  public:
    int faces() const noexcept { return faces_; }
    int width() const noexcept { return width_; }
    int height() const noexcept { return height_; }
    std::size_t texel_count() const noexcept {
        return static_cast<std::size_t>(faces_) * static_cast<std::size_t>(width_) *
               static_cast<std::size_t>(height_);
    }
    std::size_t texel_index(int face, int col, int row) const noexcept {
        return (static_cast<std::size_t>(face) * static_cast<std::size_t>(height_) +
                static_cast<std::size_t>(row)) *
                   static_cast<std::size_t>(width_) +
               static_cast<std::size_t>(col);
    }

    /// Texels along a face edge as the constructor was given it (cube face edge, rows of the
    /// lat-long map, ...).
    int resolution() const noexcept { return n_; }

  protected:
    /// Checks the resolution (min_resolution <= n <= 32768) and the subtexel bits (0..24) in
    /// `name`'s constructor's messages.
    TexelGrid(const char* name, int faces, int width, int height, int resolution,
              int min_resolution, int subtexel_bits)
        : faces_(faces), width_(width), height_(height), n_(resolution), bits_(subtexel_bits) {
        check_resolution(name, resolution, min_resolution);
        check_subtexel_bits(name, subtexel_bits);
    }

  private:
    int faces_, width_, height_;

  protected:
    int n_;     // resolution()
    int bits_;  // subtexel bits of the bilinear weights
};

/// The methods every parameterization class Map (texel type T) has in the same form: the
/// direction overloads for any 3-vector type (glm::vec3, Eigen::Vector3f, ..., converted to T)
/// and texel_direction(). Map derives from it and says `using MapMethods<Map, T>::...` for the
/// overloads its own (x, y, z) methods would hide.
template <class Map, class T>
class MapMethods {
  public:
    /// direction_to_uv(x, y, z) for any 3-vector type.
    template <class D>
    FaceUV<T> direction_to_uv(const D& d) const noexcept {
        sphbasis::detail::static_check_direction<D>();
        return map().direction_to_uv(static_cast<T>(component<0>(d)),
                                     static_cast<T>(component<1>(d)),
                                     static_cast<T>(component<2>(d)));
    }
    /// footprint(x, y, z) for any 3-vector type.
    template <class D>
    Footprint<T> footprint(const D& d) const noexcept {
        sphbasis::detail::static_check_direction<D>();
        return map().footprint(static_cast<T>(component<0>(d)), static_cast<T>(component<1>(d)),
                               static_cast<T>(component<2>(d)));
    }
    /// The direction of the centre of texel (col, row) of `face`, at texture coordinates
    /// ((col + 0.5)/width, (row + 0.5)/height).
    vec3<T> texel_direction(int face, int col, int row) const noexcept {
        return map().uv_to_direction(
            face, (static_cast<T>(col) + T(0.5)) / static_cast<T>(map().width()),
            (static_cast<T>(row) + T(0.5)) / static_cast<T>(map().height()));
    }

  private:
    const Map& map() const noexcept { return static_cast<const Map&>(*this); }
};

}  // namespace detail
}  // namespace sphbasis::param
