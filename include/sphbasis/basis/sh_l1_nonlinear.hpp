// sphbasis: L1 spherical harmonics with the non-linear irradiance reconstruction of Geomerics
// (Enlighten), a fitted (non-linear) representation: 4 stored values, evaluated through a power
// of a shifted cosine instead of the linear L1 expansion.
//
// Reference: the "Spherical Harmonics L1 [Geomerics]" experiment of Probulator
// (github.com/kayru/Probulator, Source/Probulator/SphericalHarmonics.h,
// shEvaluateDiffuseL1Geomerics), after Geomerics, "Reconstructing Diffuse Lighting from Spherical
// Harmonic Data" (CEDEC 2015).
//
// Model. With R0 the mean of the signal over the sphere and R1 half its linear slope vector
// (the linear L1 expansion is R0 + 2 R1 . n), r = |R1| / R0,
//   p = 1 + 2 r,  a = (1 - r)/(1 + r),  q = (1 + n . R1/|R1|)/2,
//   f(n) = R0 (a + (1 - a) (p + 1) q^p).
// Its mean over the sphere is R0 (int_0^1 (p+1) u^p du = 1), its first moment along R1 is
// R0 (1 - a) p/(p + 2), and for small r it tends to the linear expansion R0 + 2 R1 . n; for
// 0 <= r <= 1 (every non-negative radiance) it is >= R0 a >= 0 and peaks more sharply than the
// linear L1 expansion as r grows.
// Normalisation. The stored values are the signal's own L0/L1 SH coefficients e_0, e_1,-1,
// e_10, e_11 (library convention: ACN, y_11 ~ +x), so R0 = e_0/(2 sqrt(pi)) and
// R1 = sqrt(3/(4 pi)) (e_11, e_1,-1, e_10)/2. (Probulator feeds the raw coefficients, R0 = e_0,
// R1 = (e_11, e_1,-1, e_10)/2, of the radiance, and divides by pi: a constant sky then comes back
// 2/sqrt(pi) = 1.128 times too bright. Here the mean and the small-r limit are exact.)
// Signals of negative mean (possible for the IMSE benchmark's random SH): f(e) = -f(-e), so the
// model is homogeneous for every real scale; R0 = 0: the linear L1 expansion.
// Domain: the sphere. Cost per direction: one dot product and one pow (float: ~20 ns scalar; the
// batch path evaluates pow lane by lane).
#pragma once

#include <cmath>
#include <cstddef>
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
#include "detail/expansion_batch.hpp"
#include "sh.hpp"

namespace sphbasis::sh_l1_nonlinear {

/// Values stored per channel: the L0 and L1 SH coefficients.
inline constexpr int stored = 4;

namespace detail {
inline constexpr double y00 = 0.28209479177387814;      // 1/(2 sqrt(pi))
inline constexpr double half_y1 = 0.24430125595145996;  // sqrt(3/(4 pi))/2

template <class V>
SPHBASIS_FORCEINLINE V vpow(const V& q, scalar_t<V> p) noexcept {
    if constexpr (std::is_floating_point_v<V>) {
        return std::pow(q, p);
    } else {
        V r = q;
        for (int i = 0; i < V::size; ++i) r.v[i] = std::pow(q.v[i], p);
        return r;
    }
}
}  // namespace detail

/// The fit: the 4 stored values are the first 4 SH coefficients of the signal (its projection
/// onto L0 and L1 over the sphere). sh and out may alias.
template <class T>
void fit(const T* sh, T* out) {
    sphbasis::detail::check_buffer("sh_l1_nonlinear::fit", "sh", sh, 4);
    sphbasis::detail::check_buffer("sh_l1_nonlinear::fit", "out", out, stored);
    for (int k = 0; k < 4; ++k) out[k] = sh[k];
}

/// The model of 4 stored values, ready to evaluate (R0, the unit R1 direction, a, p, computed
/// once). operator() takes a UNIT direction as float, double or batch<T> components.
template <class T>
struct Expansion {
    T sign = 1, r0 = 0, dx = 0, dy = 0, dz = 0, a = 1, p = 1, scale = 0;
    bool linear = false;
    explicit Expansion(const T* c) {
        sphbasis::detail::check_buffer("sh_l1_nonlinear::Expansion", "coefficients", c, stored);
        const double e0 = double(c[0]);
        const double hx = detail::half_y1 * c[3], hy = detail::half_y1 * c[1],
                     hz = detail::half_y1 * c[2];
        const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
        if (e0 == 0 || !std::isfinite(len) || !std::isfinite(e0)) {
            // The linear L1 expansion R0 + 2 R1 . n (R0 = 0 here unless non-finite input).
            linear = true;
            r0 = T(detail::y00 * e0);
            dx = T(2 * hx), dy = T(2 * hy), dz = T(2 * hz);
            return;
        }
        sign = e0 < 0 ? T(-1) : T(1);
        const double R0 = std::fabs(detail::y00 * e0);
        const double s = double(sign);
        r0 = T(R0);
        if (len > 0) dx = T(s * hx / len), dy = T(s * hy / len), dz = T(s * hz / len);
        const double r = len / R0;
        const double aa = (1 - r) / (1 + r), pp = 1 + 2 * r;
        a = T(aa), p = T(pp);
        scale = T(R0 * (1 - aa) * (pp + 1));
    }
    template <class V>
    SPHBASIS_FORCEINLINE V operator()(const V& x, const V& y, const V& z) const noexcept {
        const V t = V(dx) * x + V(dy) * y + V(dz) * z;
        if (linear) return V(r0) + t;
        const V q = vmax(V(T(0)), V(T(0.5)) * (V(T(1)) + t));
        return V(sign) * (V(r0 * a) + V(scale) * detail::vpow(q, p));
    }
};

/// f(n) for the 4 stored values c at direction (x, y, z) (normalised; zero or non-finite -> +z).
template <class T>
T eval(const T* c, T x, T y, T z) {
    normalize_or_pole(x, y, z);
    return Expansion<T>(c)(x, y, z);
}

/// f at `directions` directions (SoA, normalised as by eval); the batch path evaluates pow lane
/// by lane.
template <class T>
void eval_batch(const T* c, std::size_t directions, const T* xs, const T* ys, const T* zs, T* out) {
    sphbasis::detail::eval_expansion_batch<Expansion>("sh_l1_nonlinear::eval_batch", c, directions,
                                                      xs, ys, zs, out);
}

/// The SH coefficients (ACN, library convention) of the model of 4 values c, to `bands` bands
/// (bands^2 values to out), by the Funk-Hecke theorem: the model is a zonal function g(d . n)
/// about its unit R1 direction d, so its coefficients are lambda_l y_lm(d) with
/// lambda_l = 2 pi int_{-1}^{1} g(t) P_l(t) dt, integrated by `nodes` Gauss-Legendre nodes in
/// u = sqrt((1 + t)/2) (g has the factor u^(2p), 2p >= 2, smooth in u). Returns the squared
/// norm over the sphere of the part above `bands`, 2 pi int g^2 dt - sum_l (2l+1)/(4 pi)
/// lambda_l^2 (>= 0, by the same rule). Cost: nodes * bands + bands^2 (the SH at d).
template <class T>
double sh_expansion(const T* c, int bands, double* out, int nodes = 128) {
    constexpr const char* fn = "sh_l1_nonlinear::sh_expansion";
    if (bands < 0 || bands > 1024)
        sphbasis::detail::throw_invalid(fn, "0 <= bands <= 1024, got " + std::to_string(bands));
    if (nodes < 1 || nodes > 100000)
        sphbasis::detail::throw_invalid(fn, "1 <= nodes <= 100000, got " + std::to_string(nodes));
    sphbasis::detail::check_buffer(fn, "out", out, static_cast<std::size_t>(bands * bands));
    const Expansion<double> e = [&] {
        double cd[stored];
        sphbasis::detail::check_buffer(fn, "coefficients", c, stored);
        for (int k = 0; k < stored; ++k) cd[k] = double(c[k]);
        return Expansion<double>(cd);
    }();
    for (int k = 0; k < bands * bands; ++k) out[k] = 0;
    if (bands == 0) return 0;
    if (e.linear) {  // a linear L1 expansion: exact in 2 bands
        for (int k = 0; k < 4 && k < bands * bands; ++k) out[k] = double(c[k]);
        double t = 0;
        for (int k = bands * bands; k < 4; ++k) t += double(c[k]) * double(c[k]);
        return t;
    }
    std::vector<double> nu, wu;
    gauss_legendre(nodes, nu, wu);
    std::vector<double> lambda(static_cast<std::size_t>(bands), 0.0);
    double norm2 = 0;
    for (std::size_t i = 0; i < nu.size(); ++i) {
        const double u = 0.5 * (nu[i] + 1), w = 0.5 * wu[i] * 4 * u;  // dt = 4 u du
        const double t = 2 * u * u - 1;
        const double g = e.r0 * e.a + e.scale * std::pow(u * u, e.p);
        norm2 += w * g * g;
        double p0 = 1, p1 = t;
        for (int l = 0; l < bands; ++l) {
            lambda[static_cast<std::size_t>(l)] += w * g * p0;
            const double p2 = ((2 * l + 3) * t * p1 - (l + 1) * p0) / (l + 2);
            p0 = p1, p1 = p2;
        }
    }
    double dx = e.dx, dy = e.dy, dz = e.dz;
    if (dx == 0 && dy == 0 && dz == 0) dz = 1;  // constant model: only l = 0 is non-zero
    std::vector<double> y(static_cast<std::size_t>(bands * bands));
    sh::eval(bands, dx, dy, dz, y.data());
    double kept = 0;
    for (int l = 0; l < bands; ++l) {
        const double lam = constants::two_pi * lambda[static_cast<std::size_t>(l)];
        kept += (2 * l + 1) * lam * lam / constants::four_pi;
        for (int m = -l; m <= l; ++m) {
            const int k = l * (l + 1) + m;
            out[k] = e.sign * lam * y[static_cast<std::size_t>(k)];
        }
    }
    const double tail = constants::two_pi * norm2 - kept;
    return tail > 0 ? tail : 0;
}

}  // namespace sphbasis::sh_l1_nonlinear
