// sphbasis: analytic lights and environment maps to spherical harmonics, any band count.
//
// Every function here returns the SH coefficients of a RADIANCE distribution L(w) over
// incoming directions (this library's basis: real, no Condon-Shortley phase, ACN order).
// Convolve with clamped_cosine_kernel (ops/sh_convolution.hpp) for irradiance E(n); a white
// Lambertian surface then reflects E/pi.
//
// Analytic lights are zonal about their direction d, so (addition theorem) their coefficients
// are Lambda_l y_lm(d) with the Funk-Hecke factors Lambda_l of their profile; no rotation
// matrix is needed:
//   * directional: L = E delta(w - d) (E = irradiance on a surface facing the light),
//     Lambda_l = 1, coefficients E y_lm(d);
//   * cone (uniform cap of angular radius a, the D3DX "cone light"), sphere (a ball of radius
//     r at position p: the cap sin a = r/|p|; the whole sphere when the point is inside), and
//     cap by solid angle (Omega = 2 pi (1 - cos a)): uniform radiance L in the cap,
//     Lambda_0 = 2 pi u,  Lambda_l = 2 pi (u P_l(c) - (P_l(c) - P_{l-1}(c))) / (l + 1),
//     with c = cos a, u = 1 - c (from integral_c^1 P_l = (P_{l-1}(c) - c P_l(c))/(l+1)). The
//     differences delta_l = P_l - P_{l-1} are carried by their own recurrence
//       delta_{l+1} = (l delta_l - (2l+1) u P_l)/(l+1),  P_{l+1} = P_l + delta_{l+1},
//     so small caps (u -> 0) keep full relative accuracy: nothing of size 1 is subtracted;
//   * hemisphere (sky radiance in the half-space around d, ground radiance in the other): the
//     ground everywhere plus (sky - ground) on the cap u = 1. Its irradiance is band-limited to
//     l <= 1, E(n) = pi (sky + ground)/2 + pi (sky - ground)(n . d)/2, so 2 bands are exact.
//   DirectXMath's XMSHEval*Light functions use the Condon-Shortley phase and rescale their
//   output to a target brightness (the directional light by pi / sum_l a_l (2l+1)/4, so that a
//   white diffuse surface facing it reflects 1 at that order; directional_light_peak(n) is
//   that sum). These functions keep physical units; to_condon_shortley converts the signs.
//
// Lights and maps take any coefficient/texel type C with C + C and C * S, where
// S = coefficient_scalar<C>::type (C for float/double, C::value_type, else the type of a member
// r or x, else double; specialise it for other types). Environment maps:
//   * latitude-longitude, W x H texels, row-major, texel (col, row) covering
//     phi in [2 pi col/W, 2 pi (col+1)/W], theta in [pi row/H, pi (row+1)/H] from +z (row 0 at
//     the north pole), phi = atan2(y, x): param/latlong.hpp's convention (which uses W = 2H).
//     The map is read as piecewise constant and projected EXACTLY: the phi integrals of cos(m
//     phi), sin(m phi) over a column are closed form, and the theta integrals of each
//     y_lm(theta, 0) sin(theta) over a row use Gauss-Legendre in theta with enough nodes to be
//     exact to rounding. A constant map gives exactly (c sqrt(4 pi), 0, ...); cost O(W H n)
//     plus O(H n^2);
//   * cube maps, 6 faces of N x N, face-major then row-major (texel (face, col, row) at
//     (face N + row) N + col), faces +X, -X, +Y, -Y, +Z, -Z oriented as D3D/OpenGL
//     (param/cubemap.hpp: +X: (1, -t, -s), -X: (-1, -t, s), +Y: (s, 1, t), -Y: (s, -1, -t),
//     +Z: (s, -t, 1), -Z: (-s, -t, -1), s = 2u - 1, t = 2v - 1, v down the rows). Each texel
//     is weighted by its exact solid angle (param::CubeMap::texel_solid_angle: atan(st /
//     sqrt(1 + s^2 + t^2)) at the corners; they sum to 4 pi) and its value taken at the texel
//     centre (optionally at k x k sub-texel centres with their own exact solid angles). The
//     solid-angle-weighted mean is projected exactly and only the deviation from it by the
//     texel rule (a control variate), so a constant map gives exactly (c sqrt(4 pi), 0, ...)
//     at every band count: without it the texel rule leaves O(1/N^2) in the coefficients of
//     the cube-invariant harmonics (l = 4, 6, 8, ...). Smooth maps converge as O(1/N^2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/constants.hpp"
#include "../core/quadrature.hpp"
#include "../core/vec.hpp"
#include "../param/cubemap.hpp"

namespace sphbasis::sh {

/// The scalar a coefficient type C is multiplied by: C itself for float and double, else
/// C::value_type (glm::vec3, Eigen vectors), else the type of a member `r` or `x` (RGB-like
/// structs), else double. Specialise it for other types.
template <class C, class = void>
struct coefficient_scalar {
    using type = double;
};

namespace detail {
template <class C, class = void>
struct has_value_type : std::false_type {};
template <class C>
struct has_value_type<C, std::void_t<typename C::value_type>> : std::true_type {};
template <class C, class = void>
struct has_member_r : std::false_type {};
template <class C>
struct has_member_r<C, std::void_t<decltype(std::declval<const C&>().r)>> : std::true_type {};
template <class C, class = void>
struct has_member_x : std::false_type {};
template <class C>
struct has_member_x<C, std::void_t<decltype(std::declval<const C&>().x)>> : std::true_type {};
template <class C>
constexpr auto coefficient_scalar_probe() {
    if constexpr (std::is_floating_point_v<C>)
        return C{};
    else if constexpr (has_value_type<C>::value)
        return typename C::value_type{};
    else if constexpr (has_member_r<C>::value)
        return std::decay_t<decltype(std::declval<const C&>().r)>{};
    else if constexpr (has_member_x<C>::value)
        return std::decay_t<decltype(std::declval<const C&>().x)>{};
    else
        return double{};
}
}  // namespace detail

template <class C>
struct coefficient_scalar<
    C,
    std::enable_if_t<std::is_floating_point_v<decltype(detail::coefficient_scalar_probe<C>())>>> {
    using type = decltype(detail::coefficient_scalar_probe<C>());
};

namespace detail {

template <class C>
using coeff_scalar_t = typename coefficient_scalar<C>::type;

/// Small buffer of doubles: on the stack up to 8 bands.
class LightBuf {
  public:
    explicit LightBuf(std::size_t n) {
        if (n > stack_.size()) heap_.resize(n);
        p_ = n > stack_.size() ? heap_.data() : stack_.data();
    }
    double* data() noexcept { return p_; }
    double& operator[](std::size_t i) noexcept { return p_[i]; }

  private:
    std::array<double, 64> stack_;  // not value-initialised: always written before it is read
    std::vector<double> heap_;
    double* p_;
};

/// Funk-Hecke factors of the indicator of the cap 1 - cos(theta) <= u, 0 <= u <= 2, into
/// out[0..bands). Stable for small u (header comment).
inline void cap_factors(int bands, double u, double* out) noexcept {
    if (bands <= 0) return;
    out[0] = constants::two_pi * u;
    double p = 1, d = 0;  // P_l(c) and delta_l = P_l - P_{l-1}, c = 1 - u
    for (int l = 0; l + 1 < bands; ++l) {
        // Advance to l + 1.
        const double dn = l == 0 ? -u : (l * d - (2 * l + 1) * u * p) / (l + 1);
        p += dn;
        d = dn;
        const int L = l + 1;
        out[L] = constants::two_pi * (u * p - d) / (L + 1);
    }
}

template <class T>
void check_light(int bands, T x, T y, T z, const void* out, const char* fn) {
    check_bands(bands, fn);
    if (bands > 0 && !out)
        throw std::invalid_argument(std::string("sphbasis::") + fn +
                                    "(): expected a non-null output array");
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
        (x == T(0) && y == T(0) && z == T(0)))
        throw std::invalid_argument(std::string("sphbasis::") + fn +
                                    "(): expected a finite non-zero direction");
}

/// out_k = a_l y_k(d) * colour for l < bands, from the factors a[0..bands).
template <class T, class C>
void zonal_out(int bands, T x, T y, T z, const double* a, const C& colour, C* out) {
    using S = coeff_scalar_t<C>;
    LightBuf yv(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
    eval(bands, static_cast<double>(x), static_cast<double>(y), static_cast<double>(z), yv.data());
    for (int l = 0; l < bands; ++l)
        for (int k = l * l; k < (l + 1) * (l + 1); ++k)
            out[k] = colour * static_cast<S>(a[l] * yv[static_cast<std::size_t>(k)]);
}

/// sum_i v[i] * w[i] over n >= 1 terms with eight independent partial sums: a single running
/// sum is a chain of dependent additions that the compiler may not reorder (no -ffast-math),
/// and it is the bottleneck of the projections.
template <class C, class S>
C dot_accumulate(std::size_t n, const C* v, const S* w) {
    if (n < 8) {
        C s = v[0] * w[0];
        for (std::size_t i = 1; i < n; ++i) s = s + v[i] * w[i];
        return s;
    }
    C s[8];
    for (std::size_t j = 0; j < 8; ++j) s[j] = v[j] * w[j];
    const std::size_t blocks = n / 8;
    for (std::size_t b = 1; b < blocks; ++b)
        for (std::size_t j = 0; j < 8; ++j) s[j] = s[j] + v[8 * b + j] * w[8 * b + j];
    for (std::size_t i = 8 * blocks; i < n; ++i) s[0] = s[0] + v[i] * w[i];
    return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

}  // namespace detail

/// Funk-Hecke factors Lambda_l (l < bands) of the indicator of a cap with 1 - cos(a) =
/// one_minus_cos in [0, 2] (solid angle 2 pi one_minus_cos). Throws std::invalid_argument for
/// bad bands or one_minus_cos outside [0, 2].
template <class T = double>
std::vector<T> cap_kernel(int bands, double one_minus_cos) {
    check_bands(bands, "sh::cap_kernel");
    if (!(one_minus_cos >= 0 && one_minus_cos <= 2))
        throw std::invalid_argument(
            "sphbasis::sh::cap_kernel(): expected 0 <= 1 - cos(angle) <= 2, got " +
            std::to_string(one_minus_cos));
    std::vector<double> a(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, one_minus_cos, a.data());
    return std::vector<T>(a.begin(), a.end());
}

/// A zonal radiance distribution about d (normalised; must be finite and non-zero) with
/// Funk-Hecke factors kernel[0..bands) (e.g. phong_kernel, zonal_kernel), times colour:
/// out_lm = colour * kernel[l] * y_lm(d).
template <class T, class K, class C>
void zonal_light(int bands, T x, T y, T z, const K* kernel, const C& colour, C* out) {
    detail::check_light(bands, x, y, z, out, "sh::zonal_light");
    if (bands > 0 && !kernel)
        throw std::invalid_argument("sphbasis::sh::zonal_light(): expected a non-null kernel");
    detail::LightBuf a(static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l) a[static_cast<std::size_t>(l)] = static_cast<double>(kernel[l]);
    detail::zonal_out(bands, x, y, z, a.data(), colour, out);
}

/// A directional light from direction (x, y, z) (towards the light; normalised) delivering
/// irradiance `irradiance` to a surface facing it: L = irradiance * delta(w - d), coefficients
/// irradiance * y_lm(d). Throws std::invalid_argument for bad bands, a null out, or a zero or
/// non-finite direction.
template <class T, class C>
void directional_light(int bands, T x, T y, T z, const C& irradiance, C* out) {
    detail::check_light(bands, x, y, z, out, "sh::directional_light");
    detail::LightBuf a(static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l) a[static_cast<std::size_t>(l)] = 1.0;
    detail::zonal_out(bands, x, y, z, a.data(), irradiance, out);
}

/// The irradiance that `bands` bands reconstruct at the normal facing a directional light of
/// unit irradiance: sum_l Lambda_l (2l+1)/(4 pi) with the clamped-cosine Lambda_l: 1/4, 3/4,
/// 17/16 for 1, 2, 3 bands, tending to 1. DirectXMath's XMSHEvalDirectionalLight(order, d, c)
/// is directional_light(order, d, c * pi / directional_light_peak(order)) up to the
/// Condon-Shortley signs (to_condon_shortley).
inline double directional_light_peak(int bands) {
    check_bands(bands, "sh::directional_light_peak");
    double s = 0, c = 1;
    for (int l = 0; l < bands; ++l) {
        double a = 0;
        if (l == 0)
            a = constants::pi;
        else if (l == 1)
            a = constants::two_pi / 3;
        else if (l % 2 == 0) {
            c *= (l - 1.0) / l;
            a = constants::two_pi * ((l / 2) % 2 == 1 ? 1.0 : -1.0) * c / ((l + 2.0) * (l - 1.0));
        }
        s += a * (2 * l + 1) * constants::inv_four_pi;
    }
    return s;
}

/// A cone light: uniform radiance `radiance` within angular radius half_angle (radians, in
/// [0, pi]) of direction (x, y, z). Throws std::invalid_argument for bad bands, out, direction
/// or angle.
template <class T, class C>
void cone_light(int bands, T x, T y, T z, T half_angle, const C& radiance, C* out) {
    detail::check_light(bands, x, y, z, out, "sh::cone_light");
    const double a = static_cast<double>(half_angle);
    if (!(a >= 0 && a <= constants::pi))
        throw std::invalid_argument(
            "sphbasis::sh::cone_light(): expected 0 <= half_angle <= pi, got " + std::to_string(a));
    const double s = std::sin(0.5 * a);
    detail::LightBuf f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, 2 * s * s, f.data());  // 1 - cos a = 2 sin^2(a/2)
    detail::zonal_out(bands, x, y, z, f.data(), radiance, out);
}

/// A spherical light: a ball of radius `radius` at position (px, py, pz) relative to the
/// receiver, of uniform radiance `radiance`; it covers the cap of sin(a) = radius/|p| (the
/// whole sphere when |p| <= radius). Throws std::invalid_argument for bad bands, out, a zero or
/// non-finite position, or radius < 0.
template <class T, class C>
void spherical_light(int bands, T px, T py, T pz, T radius, const C& radiance, C* out) {
    detail::check_light(bands, px, py, pz, out, "sh::spherical_light");
    const double r = static_cast<double>(radius);
    if (!(r >= 0) || !std::isfinite(r))
        throw std::invalid_argument(
            "sphbasis::sh::spherical_light(): expected a finite radius >= 0, got " +
            std::to_string(r));
    const double x = px, y = py, z = pz;
    const double big = std::max(std::fabs(x), std::max(std::fabs(y), std::fabs(z)));
    const double dist =
        big * std::sqrt((x / big) * (x / big) + (y / big) * (y / big) + (z / big) * (z / big));
    double u = 2;  // inside the ball: everything
    if (r < dist) {
        const double s = r / dist;
        u = s * s / (1 + std::sqrt((1 - s) * (1 + s)));  // 1 - cos a without cancellation
    }
    detail::LightBuf f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, u, f.data());
    detail::zonal_out(bands, px, py, pz, f.data(), radiance, out);
}

/// A cap light given by its solid angle in [0, 4 pi] about direction (x, y, z), uniform
/// radiance `radiance` (a spherical light seen from outside, by solid angle).
template <class T, class C>
void spherical_light_solid_angle(int bands, T x, T y, T z, T solid_angle, const C& radiance,
                                 C* out) {
    detail::check_light(bands, x, y, z, out, "sh::spherical_light_solid_angle");
    const double om = static_cast<double>(solid_angle);
    if (!(om >= 0 && om <= constants::four_pi))
        throw std::invalid_argument(
            "sphbasis::sh::spherical_light_solid_angle(): expected 0 <= solid_angle <= 4 pi, "
            "got " +
            std::to_string(om));
    detail::LightBuf f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, om * constants::inv_two_pi, f.data());
    detail::zonal_out(bands, x, y, z, f.data(), radiance, out);
}

/// A hemisphere light: radiance `sky` in the hemisphere around (x, y, z) (the "up" direction),
/// `ground` in the opposite one.
template <class T, class C>
void hemisphere_light(int bands, T x, T y, T z, const C& sky, const C& ground, C* out) {
    detail::check_light(bands, x, y, z, out, "sh::hemisphere_light");
    using S = detail::coeff_scalar_t<C>;
    detail::LightBuf f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, 1.0, f.data());
    detail::LightBuf yv(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
    eval(bands, static_cast<double>(x), static_cast<double>(y), static_cast<double>(z), yv.data());
    for (int l = 0; l < bands; ++l) {
        // sky * cap + ground * (sphere - cap); the sphere's factors are 4 pi, 0, 0, ...
        const double cs = f[static_cast<std::size_t>(l)];
        const double cg = (l == 0 ? constants::four_pi : 0.0) - cs;
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
            const double yk = yv[static_cast<std::size_t>(k)];
            out[k] = sky * static_cast<S>(cs * yk) + ground * static_cast<S>(cg * yk);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Environment maps

/// Projects a latitude-longitude map (width x height texels; texel(col, row) returns its
/// radiance, any type C) onto `bands` bands, exactly for the piecewise-constant map (header
/// comment). Throws std::invalid_argument for bad bands, sizes < 1 or a null out.
template <class C, class F>
void project_latlong_fn(int bands, int width, int height, F&& texel, C* out) {
    check_bands(bands, "sh::project_latlong");
    if (width < 1 || height < 1 || width > (1 << 20) || height > (1 << 20))
        throw std::invalid_argument(
            "sphbasis::sh::project_latlong(): expected 1 <= width, height "
            "<= 2^20, got " +
            std::to_string(width) + " x " + std::to_string(height));
    if (bands == 0) return;
    if (!out)
        throw std::invalid_argument("sphbasis::sh::project_latlong(): expected a non-null out");
    using S = detail::coeff_scalar_t<C>;
    const int L = bands - 1;
    const std::size_t n2 = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    const std::size_t nm = static_cast<std::size_t>(L + 1);
    // phi: column centre angles and per-order factors (2/m) sin(m dphi/2) (dphi for m = 0).
    const double dphi = constants::two_pi / width;
    std::vector<double> cosm(static_cast<std::size_t>(width) * nm),
        sinm(static_cast<std::size_t>(width) * nm), sfac(nm);
    for (int m = 0; m <= L; ++m)
        sfac[static_cast<std::size_t>(m)] = m == 0 ? dphi : 2 * std::sin(0.5 * m * dphi) / m;
    for (int i = 0; i < width; ++i) {
        const double pc = (i + 0.5) * dphi;
        for (int m = 0; m <= L; ++m) {
            cosm[static_cast<std::size_t>(i) * nm + static_cast<std::size_t>(m)] = std::cos(m * pc);
            sinm[static_cast<std::size_t>(i) * nm + static_cast<std::size_t>(m)] = std::sin(m * pc);
        }
    }
    // theta: Gauss-Legendre nodes per row, enough for the trigonometric degree L + 1.
    const double dth = constants::pi / height;
    const int q = std::min(1024, 6 + static_cast<int>(std::ceil(1.5 * (L + 2) * dth)));
    std::vector<double> gt, gw;
    gauss_legendre(q, gt, gw);
    std::vector<double> theta_int(n2), yv(n2);
    std::vector<C> rc(nm), rs(nm);  // row sums against cos(m phi) and sin(m phi)
    std::vector<C> acc(n2, C{});
    for (int j = 0; j < height; ++j) {
        // Theta integrals of y_lm(theta, 0) sin(theta) over the row (m >= 0 entries).
        std::fill(theta_int.begin(), theta_int.end(), 0.0);
        const double t0 = j * dth;
        for (int g = 0; g < q; ++g) {
            const double t = t0 + 0.5 * dth * (gt[static_cast<std::size_t>(g)] + 1);
            const double w = 0.5 * dth * gw[static_cast<std::size_t>(g)] * std::sin(t);
            eval_unit(bands, std::sin(t), 0.0, std::cos(t), yv.data());
            for (int l = 0; l <= L; ++l)
                for (int m = 0; m <= l; ++m)
                    theta_int[static_cast<std::size_t>(index(l, m))] +=
                        w * yv[static_cast<std::size_t>(index(l, m))];
        }
        // Row sums.
        for (std::size_t m = 0; m < nm; ++m) rc[m] = rs[m] = C{};
        for (int i = 0; i < width; ++i) {
            const C v = texel(i, j);
            const double* cm = cosm.data() + static_cast<std::size_t>(i) * nm;
            const double* sm = sinm.data() + static_cast<std::size_t>(i) * nm;
            rc[0] = rc[0] + v;
            for (std::size_t m = 1; m < nm; ++m) {
                rc[m] = rc[m] + v * static_cast<S>(cm[m]);
                rs[m] = rs[m] + v * static_cast<S>(sm[m]);
            }
        }
        for (int l = 0; l <= L; ++l) {
            acc[static_cast<std::size_t>(index(l, 0))] =
                acc[static_cast<std::size_t>(index(l, 0))] +
                rc[0] * static_cast<S>(theta_int[static_cast<std::size_t>(index(l, 0))] * sfac[0]);
            for (int m = 1; m <= l; ++m) {
                const double f = theta_int[static_cast<std::size_t>(index(l, m))] *
                                 sfac[static_cast<std::size_t>(m)];
                acc[static_cast<std::size_t>(index(l, m))] =
                    acc[static_cast<std::size_t>(index(l, m))] +
                    rc[static_cast<std::size_t>(m)] * static_cast<S>(f);
                acc[static_cast<std::size_t>(index(l, -m))] =
                    acc[static_cast<std::size_t>(index(l, -m))] +
                    rs[static_cast<std::size_t>(m)] * static_cast<S>(f);
            }
        }
    }
    for (std::size_t k = 0; k < n2; ++k) out[k] = acc[k];
}

/// project_latlong_fn for texels stored row-major: texels[row * width + col].
template <class C>
void project_latlong(int bands, int width, int height, const C* texels, C* out) {
    if (!texels)
        throw std::invalid_argument("sphbasis::sh::project_latlong(): expected non-null texels");
    project_latlong_fn(
        bands, width, height,
        [&](int col, int row) -> const C& {
            return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                          static_cast<std::size_t>(col)];
        },
        out);
}

/// Projects a cube map (6 faces of size x size; texel(face, col, row) returns its radiance)
/// onto `bands` bands: exact texel solid angles, texel values at `supersample`^2 sub-texel
/// centres each with its own exact solid angle, the weighted mean projected exactly (header
/// comment). Cost 6 size^2 supersample^2 evaluations of n^2 functions. Throws
/// std::invalid_argument for bad bands, size < 1, supersample < 1 or a null out.
template <class C, class F>
void project_cubemap_fn(int bands, int size, F&& texel, C* out, int supersample = 1) {
    check_bands(bands, "sh::project_cubemap");
    if (size < 1 || supersample < 1 || size > 32768 || supersample > 64 ||
        static_cast<long long>(size) * supersample > 32768)
        throw std::invalid_argument(
            "sphbasis::sh::project_cubemap(): expected 1 <= size, 1 <= supersample <= 64 and "
            "size * supersample <= 32768, got size " +
            std::to_string(size) + ", supersample " + std::to_string(supersample));
    if (bands == 0) return;
    if (!out)
        throw std::invalid_argument("sphbasis::sh::project_cubemap(): expected a non-null out");
    using S = detail::coeff_scalar_t<C>;
    const int nf = size * supersample;  // fine texels per face edge
    const std::size_t n2 = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    const param::CubeMap<double> cube(nf, param::CubeFilter::dx9_clamped);
    // Solid angles are the same on every face and symmetric under c -> nf-1-c, r -> nf-1-r
    // and c <-> r: one octant is computed (each value costs four atan2).
    std::vector<double> omega(static_cast<std::size_t>(nf) * static_cast<std::size_t>(nf));
    {
        const std::size_t N = static_cast<std::size_t>(nf);
        for (int r = 0; r < (nf + 1) / 2; ++r)
            for (int c = r; c < (nf + 1) / 2; ++c) {
                const double w = cube.texel_solid_angle(0, c, r);
                const std::size_t cs[2] = {static_cast<std::size_t>(c),
                                           N - 1 - static_cast<std::size_t>(c)};
                const std::size_t rs[2] = {static_cast<std::size_t>(r),
                                           N - 1 - static_cast<std::size_t>(r)};
                for (std::size_t a : cs)
                    for (std::size_t b : rs) {
                        omega[b * N + a] = w;
                        omega[a * N + b] = w;
                    }
            }
    }
    // Residual of the texel rule on y_k (needed where the cube's symmetry does not make it
    // vanish: l >= 4).
    const bool need_residual = bands >= 5;
    std::vector<double> resid(need_residual ? n2 : 1, 0.0);
    double wsum = 0;
    std::vector<C> acc(n2, C{});
    const std::size_t nn = static_cast<std::size_t>(nf);
    // Face f's texel directions are a fixed signed permutation of face 0's (each face is
    // (+-1, +-s, +-t) in some order); read it off param::square_to_cube at a point whose
    // components differ in magnitude, so the convention stays the one of param/cubemap.hpp.
    int perm[6][3];
    double sign[6][3];
    {
        const vec3<double> p0 = param::square_to_cube(0, 0.3, 0.8);
        const double a0[3] = {p0.x, p0.y, p0.z};
        for (int f = 0; f < 6; ++f) {
            const vec3<double> pf = param::square_to_cube(f, 0.3, 0.8);
            const double af[3] = {pf.x, pf.y, pf.z};
            for (int i = 0; i < 3; ++i) {
                int best = 0;
                for (int j = 1; j < 3; ++j)
                    if (std::fabs(std::fabs(af[i]) - std::fabs(a0[j])) <
                        std::fabs(std::fabs(af[i]) - std::fabs(a0[best])))
                        best = j;
                perm[f][i] = best;
                sign[f][i] = (af[i] < 0) == (a0[best] < 0) ? 1.0 : -1.0;
            }
        }
    }
    // One row of fine texels at a time: face-0 directions once, then per face the permuted
    // directions, all n^2 functions by the SIMD batch kernel (function-major), weights, sums.
    std::vector<double> d0(3 * nn), xs(nn), ys(nn), zs(nn), yb(n2 * nn);
    std::vector<S> wy(nn);
    std::vector<C> vals(nn);
    for (int r = 0; r < nf; ++r) {
        for (int c = 0; c < nf; ++c) {
            const vec3<double> d = cube.texel_direction(0, c, r);
            d0[3 * static_cast<std::size_t>(c)] = d.x;
            d0[3 * static_cast<std::size_t>(c) + 1] = d.y;
            d0[3 * static_cast<std::size_t>(c) + 2] = d.z;
        }
        const double* om = omega.data() + static_cast<std::size_t>(r) * nn;
        double rw = 0;
        for (std::size_t c = 0; c < nn; ++c) rw += om[c];
        for (int face = 0; face < 6; ++face) {
            double* out3[3] = {xs.data(), ys.data(), zs.data()};
            for (int i = 0; i < 3; ++i) {
                const int j = perm[face][i];
                const double sg = sign[face][i];
                for (std::size_t c = 0; c < nn; ++c)
                    out3[i][c] = sg * d0[3 * c + static_cast<std::size_t>(j)];
            }
            for (int c = 0; c < nf; ++c)
                vals[static_cast<std::size_t>(c)] = texel(face, c / supersample, r / supersample);
            eval_batch(bands, nn, xs.data(), ys.data(), zs.data(), yb.data(), nn);
            wsum += rw;
            for (std::size_t k = 0; k < n2; ++k) {
                const double* yk = yb.data() + k * nn;
                double rk = 0;
                for (std::size_t c = 0; c < nn; ++c) {
                    const double v = om[c] * yk[c];
                    wy[c] = static_cast<S>(v);
                    rk += v;
                }
                if (need_residual) resid[k] += rk;
                acc[k] = acc[k] + detail::dot_accumulate(nn, vals.data(), wy.data());
            }
        }
    }
    // Control variate: f_k = S_k - mean (r_k - sqrt(4 pi) delta_k0), mean = S_0 / (y_00 W).
    // For k = 0 that is S_0 (4 pi / W); for k > 0 with bands <= 4, r_k = 0 by symmetry.
    const double y00 = constants::inv_sqrt_four_pi;
    const double s0 = constants::four_pi / wsum;
    out[0] = acc[0] * static_cast<S>(s0);
    const C mean = acc[0] * static_cast<S>(1 / (y00 * wsum));
    for (std::size_t k = 1; k < n2; ++k)
        out[k] = need_residual ? acc[k] + mean * static_cast<S>(-resid[k]) : acc[k];
}

/// project_cubemap_fn for texels stored face-major, row-major: texels[(face size + row) size +
/// col] (param::CubeMap::texel_index).
template <class C>
void project_cubemap(int bands, int size, const C* texels, C* out, int supersample = 1) {
    if (!texels)
        throw std::invalid_argument("sphbasis::sh::project_cubemap(): expected non-null texels");
    const std::size_t n = static_cast<std::size_t>(size > 0 ? size : 0);
    project_cubemap_fn(
        bands, size,
        [&](int face, int col, int row) -> const C& {
            return texels[(static_cast<std::size_t>(face) * n + static_cast<std::size_t>(row)) * n +
                          static_cast<std::size_t>(col)];
        },
        out, supersample);
}

}  // namespace sphbasis::sh
