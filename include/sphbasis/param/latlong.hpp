// sphbasis: the latitude-longitude (equirectangular) parameterization.
//
// u = phi/(2 pi) with phi = atan2(y, x) in [0, 2 pi), v = theta/pi with theta the polar angle
// from +z, so row 0 is at the north pole (0, 0, 1). One face of 2n x n texels (square texels at
// the equator). Filtering is the hardware's with wrap addressing in u (continuous across the
// seam phi = 0) and clamp-to-edge in v: within half a texel of a pole the lookup returns the
// value along the first ring of centres, so it depends on phi there and is not continuous at
// the pole itself. Solid angle per unit area of [0, 1]^2: 2 pi^2 sin(theta).
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "param.hpp"

namespace sphbasis::param {

/// Unit direction -> [0, 1)x[0, 1]: u = atan2(y, x)/(2 pi) wrapped to [0, 1), v = theta/pi.
/// The poles give u = 0 (atan2(0, 0) = 0) or the u of the sign of a zero x.
template <class T>
SPHBASIS_FORCEINLINE Point2<T> latlong_to_square(T x, T y, T z) noexcept {
    const T inv_two_pi = T(0.15915494309189534);  // 1/(2 pi)
    const T inv_pi = T(0.31830988618379067);      // 1/pi
    T u = std::atan2(y, x) * inv_two_pi;
    if (u < T(0)) u += T(1);
    if (!(u < T(1))) u = T(0);  // -tiny + 1 rounding to 1, or NaN
    const T v = std::atan2(std::sqrt(x * x + y * y), z) * inv_pi;
    return {u, v};
}

/// latlong_to_square() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(latlong_to_square);

/// [0, 1]^2 -> unit direction (sin(theta) cos(phi), sin(theta) sin(phi), cos(theta)) with
/// phi = 2 pi u, theta = pi v.
template <class T>
SPHBASIS_FORCEINLINE vec3<T> square_to_latlong(T u, T v) noexcept {
    const T two_pi = T(6.2831853071795865);  // 2 pi
    const T pi = T(3.1415926535897932);      // pi
    const T phi = two_pi * u, theta = pi * v;
    const T st = std::sin(theta);
    return {st * std::cos(phi), st * std::sin(phi), std::cos(theta)};
}

/// Density of square_to_latlong() w.r.t. solid angle, 1/(2 pi^2 sin(theta)) with
/// sin(theta) = sqrt(x^2 + y^2); sin(theta) is floored at the smallest normal number so the
/// poles give a large finite value.
template <class T>
SPHBASIS_FORCEINLINE T square_to_latlong_pdf(T x, T y, T /*z*/) noexcept {
    const T st = std::fmax(std::sqrt(x * x + y * y), std::numeric_limits<T>::min());
    return T(0.050660591821168886) / st;  // 1/(2 pi^2)
}

/// square_to_latlong_pdf() for any 3-vector type (glm::vec3, Eigen::Vector3f, ...), in its scalar
/// type.
SPHBASIS_PARAM_DIRECTION_OVERLOAD(square_to_latlong_pdf);

/// A latitude-longitude map of 2n x n texels.
template <class T>
class LatLong : public detail::TexelGrid, public detail::MapMethods<LatLong<T>, T> {
  public:
    using detail::MapMethods<LatLong<T>, T>::direction_to_uv;
    using detail::MapMethods<LatLong<T>, T>::footprint;

    /// n >= 1 rows (2n columns). Throws std::invalid_argument outside 1 <= n <= 32768 or
    /// 0 <= subtexel_bits <= 24.
    explicit LatLong(int resolution, int subtexel_bits = 0)
        : detail::TexelGrid("LatLong", 1, 2 * detail::checked_resolution("LatLong", resolution, 1),
                            resolution, resolution, 1, subtexel_bits) {}

    FaceUV<T> direction_to_uv(T x, T y, T z) const noexcept {
        const vec3<T> d = detail::unit(x, y, z);
        const Point2<T> s = latlong_to_square(d.x, d.y, d.z);
        return {0, s.x, s.y};
    }
    vec3<T> uv_to_direction(int /*face*/, T u, T v) const noexcept {
        return square_to_latlong(u, v);
    }
    /// Exact solid angle (2 pi/(2n)) (cos(theta0) - cos(theta1)), in double.
    T texel_solid_angle(int /*face*/, int /*col*/, int row) const noexcept {
        const double pi = 3.1415926535897932;  // pi
        const double n = n_;
        return static_cast<T>(pi / n * (std::cos(pi * row / n) - std::cos(pi * (row + 1) / n)));
    }

    /// Bilinear footprint, wrap addressing in u, clamp-to-edge in v.
    Footprint<T> footprint(T x, T y, T z) const noexcept {
        const FaceUV<T> t = direction_to_uv(x, y, z);
        const int w = 2 * n_;
        const detail::AxisTaps<T> ax = detail::axis_taps(t.u, w, bits_);
        const detail::AxisTaps<T> ay = detail::axis_taps(t.v, n_, bits_);
        auto wrap = [w](int i) { return i < 0 ? i + w : (i >= w ? i - w : i); };
        auto cl = [this](int j) { return j < 0 ? 0 : (j >= n_ ? n_ - 1 : j); };
        const std::size_t i0 = static_cast<std::size_t>(wrap(ax.i0));
        const std::size_t i1 = static_cast<std::size_t>(wrap(ax.i0 + 1));
        const std::size_t r0 = static_cast<std::size_t>(cl(ay.i0)) * static_cast<std::size_t>(w);
        const std::size_t r1 =
            static_cast<std::size_t>(cl(ay.i0 + 1)) * static_cast<std::size_t>(w);
        const T fx = ax.frac, fy = ay.frac;
        return {{r0 + i0, r0 + i1, r1 + i0, r1 + i1},
                {(T(1) - fx) * (T(1) - fy), fx * (T(1) - fy), (T(1) - fx) * fy, fx * fy}};
    }

  private:
};

}  // namespace sphbasis::param
