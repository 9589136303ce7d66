// sphbasis: spherical Gaussians (SG): one lobe, its closed forms, the lobe sets BakingLab bakes
// into lightmaps, the fitted irradiance approximation it shades with, and the exact irradiance of
// a lobe by quadrature. The fits (least squares, non-negative least squares, running average)
// live in ops/sg_fit.hpp (Eigen tier).
//
// References:
//   M. Pettineo, "SG Series" (blog, 2016), parts 2 (SG definition, product, integral, inner
//     product), 3 (irradiance: the fitted approximation by S. Hill) and 5 (baking SG lightmaps:
//     the lobe sets and the solvers);
//   M. Pettineo and D. Neubelt, BakingLab (MIT-licensed demo, 2016-2018): the lobe sets SG5, SG6,
//     SG9 and SG12 and the running-average solver of T. Roughton ("Spherical Gaussians", blog,
//     2018);
//   J. Wang, P. Ren, M. Gong, J. Snyder and B. Guo, "All-Frequency Rendering of Dynamic,
//     Spatially-Varying Reflectance", SIGGRAPH Asia 2009, section 4 (SG product and integral).
//
// Definition: G(v; mu, lambda, a) = a exp(lambda (mu . v - 1)) for unit v and unit axis mu,
// sharpness lambda >= 0, amplitude a; G(mu) = a. Closed forms (Wang et al. section 4):
//   integral over the sphere   int G = 2 pi a (1 - exp(-2 lambda)) / lambda   (4 pi a at 0),
//   product                    G1 G2 = G(v; u/|u|, |u|, a1 a2 exp(|u| - l1 - l2)),
//                              u = l1 mu1 + l2 mu2 (a constant when u = 0),
//   inner product              <G1, G2> = int (G1 G2).
// Irradiance of one lobe of radiance at a unit normal n, E(n) = int G(v) max(0, n . v) dv: no
// elementary closed form. With c = mu . n, s = sqrt(1 - c^2), the polar angle t from n:
//   E = a int_0^{pi/2} sin t cos t exp(lambda (c cos t - 1)) 2 pi I0(lambda s sin t) dt,
// computed here by quadrature (hemisphere_integral()). Closed forms at c = +1 and c = -1:
//   E(+1) = 2 pi a (lambda - 1 + exp(-lambda)) / lambda^2,
//   E(-1) = 2 pi a exp(-lambda) (1 - (1 + lambda) exp(-lambda)) / lambda^2.
// irradiance_fitted() is Hill's fitted approximation (Pettineo part 3), which BakingLab uses to
// shade SG lightmaps; its error against the exact integral is tabulated by
// tools/gen/gen_sg_reference.py and bounded in tests/basis/test_spherical_gaussian.cpp: at most
// 0.020 of 2 pi a / lambda for 1 <= lambda <= 64 (0.019 at lambda = 2), 0.005 to 0.014 on the
// lobe sets' sharpness 3.6 to 6.7; below lambda = 1 it fails (negative facing the lobe at
// lambda = 0.5).
//
// The lobe sets (bakinglab_axes(), bakinglab_sharpness()), as BakingLab builds them: for count
// lobes on the hemisphere z >= 0, N = 2 count points of a Fibonacci spiral on the sphere,
//   z_k = (2k + 1)/N - 1, r_k = sqrt(1 - z_k^2), phi_k = k pi (3 - sqrt 5) (the golden angle),
//   p_k = (r_k cos phi_k, r_k sin phi_k, z_k),  k = 0 .. N - 1,
// keeping the count points with z_k >= 0 (k = count .. N - 1, in that order); on the whole sphere
// N = count and every point is kept. One sharpness for all lobes: with h the smallest cosine of
// the half angle between lobe 0 and another lobe, h = min_i normalize(mu_i + mu_0) . mu_0,
//   lambda = count ln(0.65) / (h - 1.0001),
// i.e. at the midpoint between lobe 0 and its nearest neighbour a lobe has fallen to
// 0.65^count exp(0.0001 lambda) (the 1.0001 keeps lambda finite). BakingLab evaluates this in
// float; here it is double (the axes differ from BakingLab's by float rounding, ~1e-5). Hemisphere
// sets:
//   count 5: lambda = 3.6272, count 6: 4.2595, count 9: 5.5135, count 12: 6.6914.
//
// SphericalGaussian is the basis (basis/basis.hpp) of the unit-amplitude lobes of the
// hemisphere sets, 5, 6, 9 or 12 functions, not orthogonal; it is what the IMSE benchmark and
// the bake fit by least squares. Cost: count dot products and count exp per direction; the SIMD
// batch path uses a polynomial exp (detail::vexp, within 2 ulp of std::exp).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "../config.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"

namespace sphbasis::sg {

namespace detail {

/// exp(x), lane-wise for SIMD batches: Cody-Waite reduction x = n ln 2 + r, |r| <= ln 2 / 2,
/// a Taylor polynomial of degree 7 (float) or 13 (double) for exp(r), times 2^n built in the
/// exponent bits. x is clamped to [lo, hi] (lo = -87 / -708, hi = 88 / 709): results below
/// 2^-125 (float) or 2^-1021 (double) are returned as 0, never a denormal or garbage. Within 2
/// ulp of std::exp on [lo, hi]. For float and double it is std::exp.
template <class V>
SPHBASIS_FORCEINLINE V vexp(const V& x) noexcept {
    if constexpr (std::is_floating_point_v<V>) {
        return std::exp(x);
    } else {
        using T = scalar_t<V>;
        using M = typename V::mask_type;
        using N = typename V::native_type;
        constexpr bool is_f = std::is_same_v<T, float>;
        const V lo(is_f ? T(-87) : T(-708)), hi(is_f ? T(88) : T(709));
        const V xc = vmin(vmax(x, lo), hi);
        // Round-to-nearest of x log2(e) by adding 1.5 2^(mantissa bits): the integer lands in
        // the low bits of t, and t - magic is that integer as a float.
        const V magic(is_f ? T(12582912.0) : T(6755399441055744.0));  // 1.5 2^23, 1.5 2^52
        const V t = xc * V(T(1.4426950408889634)) + magic;            // log2(e)
        const V n = t - magic;
        // ln 2 = hi + lo with hi exact in few bits, so n hi is exact.
        const V r = (xc - n * V(is_f ? T(0.693359375) : T(0.693145751953125))) -
                    n * V(is_f ? T(-2.12194440e-4) : T(1.42860682030941723212e-6));
        V p;
        if constexpr (is_f) {
            p = V(T(1.0 / 5040));
            p = p * r + V(T(1.0 / 720));
            p = p * r + V(T(1.0 / 120));
            p = p * r + V(T(1.0 / 24));
            p = p * r + V(T(1.0 / 6));
            p = p * r + V(T(0.5));
            p = p * r + V(T(1));
            p = p * r + V(T(1));
        } else {
            p = V(T(1.0 / 6227020800.0));  // 1/13!
            const T inv_fact[] = {1.0 / 479001600.0,
                                  1.0 / 39916800.0,
                                  1.0 / 3628800.0,
                                  1.0 / 362880.0,
                                  1.0 / 40320.0,
                                  1.0 / 5040.0,
                                  1.0 / 720.0,
                                  1.0 / 120.0,
                                  1.0 / 24.0,
                                  1.0 / 6.0,
                                  0.5,
                                  1.0,
                                  1.0};
            for (T c : inv_fact) p = p * r + V(c);
        }
        // 2^n: (n + bias) in the exponent field. n = bits(t) - bits(magic) exactly.
        const M ni = (M)t.v - (M)magic.v;
        const M scale = (ni + M{} + (is_f ? 127 : 1023)) << (is_f ? 23 : 52);
        const V result = p * V((N)scale);
        return select(x < lo, V(T(0)), result);
    }
}

}  // namespace detail

/// One spherical Gaussian lobe a exp(lambda (mu . v - 1)); the axis (x, y, z) is unit length.
template <class T>
struct Lobe {
    T x = 0, y = 0, z = 1;  // axis mu
    T sharpness = 1;        // lambda >= 0
    T amplitude = 1;        // a
};

/// G(v) for a unit direction v = (vx, vy, vz); V is float, double or a SIMD batch of directions.
/// Finite for finite input; cost: 3 multiply-adds and one exp.
template <class V, class T>
SPHBASIS_FORCEINLINE V eval(const Lobe<T>& g, const V& vx, const V& vy, const V& vz) noexcept {
    using S = scalar_t<V>;
    const V d = V(S(g.x)) * vx + V(S(g.y)) * vy + V(S(g.z)) * vz;
    return V(S(g.amplitude)) * detail::vexp(V(S(g.sharpness)) * (d - V(S(1))));
}

/// The product of two lobes, itself a lobe (Wang et al. 2009, section 4): axis u/|u|, sharpness
/// |u|, amplitude a1 a2 exp(|u| - l1 - l2) with u = l1 mu1 + l2 mu2. When u = 0 (opposite lobes
/// of equal sharpness) the product is the constant a1 a2 exp(-l1 - l2): sharpness 0, axis +z.
template <class T>
Lobe<T> product(const Lobe<T>& a, const Lobe<T>& b) noexcept {
    const T ux = a.sharpness * a.x + b.sharpness * b.x;
    const T uy = a.sharpness * a.y + b.sharpness * b.y;
    const T uz = a.sharpness * a.z + b.sharpness * b.z;
    const T len = std::sqrt(ux * ux + uy * uy + uz * uz);
    Lobe<T> r;
    r.amplitude = a.amplitude * b.amplitude * std::exp(len - a.sharpness - b.sharpness);
    r.sharpness = len;
    if (len > T(0)) {
        r.x = ux / len;
        r.y = uy / len;
        r.z = uz / len;
    }
    return r;
}

/// The integral over the sphere, 2 pi a (1 - exp(-2 lambda)) / lambda (4 pi a at lambda = 0),
/// without cancellation for small lambda (expm1).
template <class T>
T integral(const Lobe<T>& g) noexcept {
    const T l = g.sharpness;
    if (l <= T(0)) return T(constants::four_pi) * g.amplitude;
    return T(constants::two_pi) * g.amplitude * (-std::expm1(T(-2) * l)) / l;
}

/// BakingLab's approximate integral 2 pi a / lambda (exact up to the factor 1 - exp(-2 lambda));
/// the normalisation of irradiance_fitted(). lambda > 0.
template <class T>
T integral_approx(const Lobe<T>& g) noexcept {
    return T(constants::two_pi) * g.amplitude / g.sharpness;
}

/// <G1, G2> = int G1 G2 over the sphere: integral(product(a, b)).
template <class T>
T inner_product(const Lobe<T>& a, const Lobe<T>& b) noexcept {
    return integral(product(a, b));
}

/// Hill's fitted approximation of the irradiance int G(v) max(0, n . v) dv of one lobe of
/// radiance at the unit normal n, as a function of mu_dot_n = mu . n (V: float, double or a
/// SIMD batch of normals) (Pettineo, "SG Series" part 3; the constants 0.36 and 1/(4 0.36) are
/// the fit's). lambda > 0. Its error against hemisphere_integral(): see the header comment.
template <class V, class T>
SPHBASIS_FORCEINLINE V irradiance_fitted(const Lobe<T>& g, const V& mu_dot_n) noexcept {
    using S = scalar_t<V>;
    const T l = g.sharpness;
    const T eml = std::exp(-l), em2l = eml * eml, rl = T(1) / l;
    const T scale = T(1) + T(2) * em2l - rl;
    const T bias = (eml - em2l) * rl - em2l;
    const T x = std::sqrt(T(1) - scale);  // = sqrt(1/l - 2 exp(-2l)) > 0 for every l > 0
    const T c0 = T(0.36), c1 = T(1) / (T(4) * c0);
    const V x0 = V(S(c0)) * mu_dot_n, x1 = V(S(c1 * x));
    const V n = x0 + x1;
    const V sat = vmin(vmax(mu_dot_n, V(S(0))), V(S(1)));
    const V y = select(vabs(x0) <= x1, n * n / V(S(x)), sat);
    return (V(S(scale)) * y + V(S(bias))) * V(S(integral_approx(g)));
}

/// irradiance_fitted() at a unit normal (nx, ny, nz).
template <class V, class T>
SPHBASIS_FORCEINLINE V irradiance_fitted(const Lobe<T>& g, const V& nx, const V& ny,
                                         const V& nz) noexcept {
    using S = scalar_t<V>;
    return irradiance_fitted(g, V(S(g.x)) * nx + V(S(g.y)) * ny + V(S(g.z)) * nz);
}

/// int_{n . v >= 0} exp(lambda (mu . v - 1)) (n . v)^power dv for power 0 or 1, as a function of
/// c = mu . n in [-1, 1], lambda >= 0: power 1 is the exact irradiance of a unit-amplitude lobe
/// (times a for amplitude a), power 0 its integral over the hemisphere around n. Double
/// precision quadrature of E = int_0^{pi/2} sin t cos^power t exp(lambda (c cos t - 1))
/// 2 pi I0(lambda s sin t) dt: the azimuth by the trapezoidal rule (geometric convergence,
/// M >= lambda s + 12 sqrt(lambda s) + 32 points), t by composite Gauss-Legendre (20 nodes per
/// panel, panels no wider than 1 / sqrt(lambda)). Within 1e-12 (relative) of
/// tools/gen/gen_sg_reference.py. Cost: about 30 sqrt(lambda) (lambda + 12 sqrt(lambda) + 32) exp
/// calls; a reference, not a shading function. Throws std::invalid_argument for c outside [-1, 1],
/// lambda < 0 or lambda > 1e4, power not 0 or 1.
inline double hemisphere_integral(double lambda, double c, int power = 1) {
    if (!(c >= -1 && c <= 1))
        sphbasis::detail::throw_invalid("sg::hemisphere_integral",
                                        "-1 <= mu . n <= 1, got " + std::to_string(c));
    if (!(lambda >= 0 && lambda <= 1e4))
        sphbasis::detail::throw_invalid("sg::hemisphere_integral",
                                        "0 <= lambda <= 1e4, got " + std::to_string(lambda));
    if (power != 0 && power != 1)
        sphbasis::detail::throw_invalid("sg::hemisphere_integral",
                                        "power 0 or 1, got " + std::to_string(power));
    const double s = std::sqrt(std::max(0.0, (1 - c) * (1 + c)));
    const double b = lambda * s;
    const int m = 32 + static_cast<int>(std::ceil(b + 12 * std::sqrt(b)));
    const int panels =
        std::max(1, static_cast<int>(std::ceil(constants::pi / 2 * std::sqrt(lambda))));
    std::vector<double> gt, gw;
    gauss_legendre(20, gt, gw);
    const double h = constants::pi / 2 / panels;
    double total = 0;
    for (int p = 0; p < panels; ++p) {
        for (std::size_t i = 0; i < gt.size(); ++i) {
            const double t = h * (p + 0.5 * (gt[i] + 1));
            const double st = std::sin(t), ct = std::cos(t);
            // exp(lambda (c cos t + s sin t - 1)) <= 1 times the azimuthal mean of
            // exp(lambda s sin t (cos phi - 1)) <= 1: no overflow for any lambda.
            const double bt = b * st;
            double az = 0;
            for (int j = 0; j < m; ++j)
                az += std::exp(bt * (std::cos(constants::two_pi * j / m) - 1));
            az *= constants::two_pi / m;
            const double radial = std::exp(lambda * (c * ct + s * st - 1));
            total += 0.5 * h * gw[i] * st * (power ? ct : 1.0) * radial * az;
        }
    }
    return total;
}

/// The exact irradiance of one lobe at a unit normal with mu . n = mu_dot_n (quadrature:
/// hemisphere_integral(), double).
template <class T>
double irradiance_exact(const Lobe<T>& g, double mu_dot_n) {
    return static_cast<double>(g.amplitude) *
           hemisphere_integral(static_cast<double>(g.sharpness), mu_dot_n, 1);
}

// ---------------------------------------------------------------------------------------------
// BakingLab's lobe sets

/// The domain a lobe set covers: the upper hemisphere z >= 0 (tangent-space lightmaps) or the
/// whole sphere (BakingLab's world-space bake).
enum class Distribution { hemisphere, sphere };

/// The axes of BakingLab's lobe set of `count` lobes (see the header), 1 <= count <= 64.
inline std::vector<std::array<double, 3>> bakinglab_axes(
    int count, Distribution d = Distribution::hemisphere) {
    sphbasis::detail::check_range("sg::bakinglab_axes", "count", count, 1, 64);
    const int n = d == Distribution::hemisphere ? 2 * count : count;
    const double golden = constants::pi * (3 - std::sqrt(5.0));
    std::vector<std::array<double, 3>> axes;
    for (int k = 0; k < n; ++k) {
        const double z = (2.0 * k + 1) / n - 1;
        if (d == Distribution::hemisphere && z < 0) continue;
        const double r = std::sqrt((1 - z) * (1 + z)), phi = k * golden;
        axes.push_back({r * std::cos(phi), r * std::sin(phi), z});
    }
    return axes;
}

/// The one sharpness of BakingLab's lobe set: count ln(0.65) / (h - 1.0001), h the smallest
/// cosine of the half angle between lobe 0 and another lobe (lambda = 0 for count = 1).
inline double bakinglab_sharpness(int count, Distribution d = Distribution::hemisphere) {
    const auto axes = bakinglab_axes(count, d);
    double h = 1;
    for (std::size_t i = 1; i < axes.size(); ++i) {
        double m[3], len = 0;
        for (std::size_t j = 0; j < 3; ++j) {
            m[j] = axes[i][j] + axes[0][j];
            len += m[j] * m[j];
        }
        len = std::sqrt(len);
        if (len > 0)
            h = std::min(h, (m[0] * axes[0][0] + m[1] * axes[0][1] + m[2] * axes[0][2]) / len);
    }
    if (count == 1) return 0;
    return count * std::log(0.65) / (h - 1.0001);
}

/// BakingLab's lobe set as lobes of amplitude `amplitude`.
template <class T = double>
std::vector<Lobe<T>> bakinglab_lobes(int count, Distribution d = Distribution::hemisphere,
                                     T amplitude = T(1)) {
    const auto axes = bakinglab_axes(count, d);
    const T l = static_cast<T>(bakinglab_sharpness(count, d));
    std::vector<Lobe<T>> lobes;
    for (const auto& a : axes)
        lobes.push_back(
            {static_cast<T>(a[0]), static_cast<T>(a[1]), static_cast<T>(a[2]), l, amplitude});
    return lobes;
}

namespace detail {
/// The hemisphere sets of the basis, computed once: axes as floats and doubles.
struct LobeTable {
    int count;
    double sharpness_d;
    float sharpness_f;
    std::array<double, 3 * 12> axes_d;
    std::array<float, 3 * 12> axes_f;
};
inline const LobeTable& lobe_table(int count) {
    static const std::array<LobeTable, 4> tables = [] {
        std::array<LobeTable, 4> t{};
        const int counts[4] = {5, 6, 9, 12};
        for (int i = 0; i < 4; ++i) {
            const auto axes = bakinglab_axes(counts[i]);
            t[static_cast<std::size_t>(i)].count = counts[i];
            t[static_cast<std::size_t>(i)].sharpness_d = bakinglab_sharpness(counts[i]);
            t[static_cast<std::size_t>(i)].sharpness_f =
                static_cast<float>(t[static_cast<std::size_t>(i)].sharpness_d);
            for (std::size_t k = 0; k < axes.size(); ++k)
                for (std::size_t j = 0; j < 3; ++j) {
                    t[static_cast<std::size_t>(i)].axes_d[3 * k + j] = axes[k][j];
                    t[static_cast<std::size_t>(i)].axes_f[3 * k + j] =
                        static_cast<float>(axes[k][j]);
                }
        }
        return t;
    }();
    return tables[count <= 5 ? 0 : count <= 6 ? 1 : count <= 9 ? 2 : 3];
}

struct Kernel {
    const LobeTable* t;
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        constexpr bool is_f = std::is_same_v<S, float>;
        const S l = is_f ? S(t->sharpness_f) : S(t->sharpness_d);
        for (int k = 0; k < t->count; ++k) {
            const std::size_t o = 3 * static_cast<std::size_t>(k);
            const S ax = is_f ? S(t->axes_f[o]) : S(t->axes_d[o]);
            const S ay = is_f ? S(t->axes_f[o + 1]) : S(t->axes_d[o + 1]);
            const S az = is_f ? S(t->axes_f[o + 2]) : S(t->axes_d[o + 2]);
            const V d = V(ax) * x + V(ay) * y + V(az) * z;
            store(k, vexp(V(l) * (d - V(S(1)))));
        }
    }
};
}  // namespace detail

}  // namespace sphbasis::sg

namespace sphbasis {

/// The unit-amplitude lobes of BakingLab's hemisphere lobe sets as a basis (basis/basis.hpp):
/// 5, 6, 9 or 12 functions G_k(v) = exp(lambda (mu_k . v - 1)) (sg::bakinglab_axes(count),
/// sg::bakinglab_sharpness(count)), not orthogonal. The lobes extend below the horizon (z < 0),
/// where they are returned as they are.
struct SphericalGaussian : detail::HemiFixedCounts<false, 5, 6, 9, 12> {
    static constexpr const char* name = "sg";
    static const char* count_rule() noexcept { return "5, 6, 9 or 12"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        return f(sg::detail::Kernel{&sg::detail::lobe_table(n)});
    }
};

}  // namespace sphbasis
