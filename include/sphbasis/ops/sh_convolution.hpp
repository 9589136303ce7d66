// sphbasis: convolution of spherical-harmonic expansions with zonal kernels, the
// Ramamoorthi-Hanrahan irradiance formula, and a certified lower bound of an expansion's
// minimum over the sphere.
//
// Funk-Hecke: for a kernel h(cos theta) about the pole, the convolution
//   (h * f)(n) = integral over the sphere of h(n . w) f(w) dw
// multiplies the coefficients of band l by
//   Lambda_l = 2 pi integral_{-1}^{1} h(t) P_l(t) dt                      (P_l Legendre)
// (= sqrt(4 pi/(2l+1)) times the kernel's own zonal coefficient on y_l0). Functions here
// return the per-band factors Lambda_l ("unnormalized") or Lambda_l / Lambda_0 ("normalized",
// a_0 = 1), and convolve() applies them.
//
// Clamped cosine max(cos theta, 0) (Ramamoorthi and Hanrahan, "An efficient representation for
// irradiance environment maps", SIGGRAPH 2001, eq. 8; thesis 001 eq. 2.3):
//   Lambda_0 = pi, Lambda_1 = 2 pi/3, Lambda_l = 0 for odd l > 1, and for even l
//   Lambda_l = 2 pi (-1)^(l/2 + 1) / ((l + 2)(l - 1)) * binom(l, l/2) / 2^l,
// so normalized a_0 = 1, a_1 = 2/3, a_2 = 1/4, a_4 = -1/24, a_6 = 1/64, ...
// binom(l, l/2)/2^l is carried as a running product (it is < 1), so nothing overflows at any l.
// The irradiance of radiance L is E = (Lambda * L); the exit radiance of a white Lambertian
// surface is E/pi, i.e. the normalized factors (thesis 001 builds the 1/pi in).
//
// Phong lobes max(cos theta, 0)^s, any real s > -1: with I_l = integral_0^1 t^s P_l(t) dt,
//   I_0 = 1/(s+1),  I_1 = 1/(s+2),  I_{l+2} = I_l (s - l)/(s + l + 3),   Lambda_l = 2 pi I_l,
// which follows from integral_0^1 x^s P_l = sqrt(pi) 2^(-s-1) Gamma(1+s) /
// (Gamma(1 + (s-l)/2) Gamma((s+l+3)/2)) (Gradshteyn-Ryzhik 7.126.2). s = 1 is the clamped
// cosine; for integer s the factor vanishes for l = s+2, s+4, ...
//
// Any kernel h(t): Funk-Hecke by Gauss-Legendre quadrature on [-1, 0] and [0, 1] separately, so
// kernels with a kink or jump at the horizon (clamped lobes, hemispherical windows) are
// integrated to full accuracy; a kernel polynomial of degree d on each half is exact with
// nodes >= (d + bands)/2.
//
// Irradiance fast path (3 bands): E(n) = n^T M n, n = (x, y, z, 1), Ramamoorthi-Hanrahan
// eqs. 11-13 with c1 = sqrt(15 pi)/16, c2 = sqrt(3 pi)/6, c3 = 3 sqrt(5 pi)/16,
// c4 = sqrt(pi)/2, c5 = sqrt(5 pi)/16 (their 0.429043, 0.511664, 0.743125, 0.886227,
// 0.247708 rounded). The quadratic form equals clamped-cosine convolution + evaluation
// exactly.
//
// Minimum over the sphere (minimum()): a certified lower bound by subdivision. For a spherical
// polynomial f of degree L, restricted to any great circle it is a trigonometric polynomial of
// degree L in arc length, so Bernstein's inequality gives |g''| <= L^2 ||f - c||_inf for any
// constant c. At a global minimiser w* the gradient vanishes, so every point p at geodesic
// distance d from w* has f(p) <= f(w*) + L^2 F d^2 / 2, F >= ||f - f_00 y_00||_inf. The sphere
// is covered by latitude-longitude cells; if w* is in a cell with centre c and radius delta
// (the largest distance from c to the cell, attained at a corner), then
//   f(w*) >= f(c) - L^2 F delta^2 / 2.
// The bound is the minimum of that over the cells that can still hold w*; cells whose bound
// exceeds the best value found are dropped and the rest split in four, so the gap shrinks by
// ~4 per level. F is the smaller of a Cauchy-Schwarz bound (sum_m y_lm^2 = (2l+1)/(4 pi)) and
// the sampled maximum inflated by the same argument; a rounding margin is subtracted. Cost:
// about 60 L^2 evaluations for the first grid plus 4 per surviving cell per level, each O(n^2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/constants.hpp"
#include "../core/quadrature.hpp"
#include "../core/vec.hpp"

namespace sphbasis::sh {

/// Unnormalized: the Funk-Hecke factors Lambda_l themselves (pi, 2pi/3, pi/4 for the clamped
/// cosine: irradiance from radiance). Normalized: divided by Lambda_0 (1, 2/3, 1/4: a kernel
/// that integrates to one, e.g. Lambertian exit radiance for albedo 1).
enum class KernelScale { unnormalized, normalized };

namespace detail {

inline void normalize_kernel(std::vector<double>& k, KernelScale scale, const char* fn) {
    if (scale == KernelScale::unnormalized || k.empty()) return;
    if (!(k[0] != 0) || !std::isfinite(k[0]))
        throw std::invalid_argument(std::string("sphbasis::") + fn +
                                    "(): expected a kernel with a finite non-zero integral "
                                    "(Lambda_0) for KernelScale::normalized");
    const double inv = 1 / k[0];
    for (double& v : k) v *= inv;
}

template <class T>
std::vector<T> cast_vector(const std::vector<double>& v) {
    std::vector<T> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = static_cast<T>(v[i]);
    return out;
}

}  // namespace detail

/// Funk-Hecke factors Lambda_l, l < bands, of the clamped cosine max(cos theta, 0) by the
/// closed form (header comment). Throws std::invalid_argument for bad bands.
template <class T = double>
std::vector<T> clamped_cosine_kernel(int bands, KernelScale scale = KernelScale::unnormalized) {
    check_bands(bands, "sh::clamped_cosine_kernel");
    std::vector<double> k(static_cast<std::size_t>(bands), 0.0);
    double c = 1;  // binom(l, l/2) / 2^l for even l
    for (int l = 0; l < bands; ++l) {
        const std::size_t i = static_cast<std::size_t>(l);
        if (l == 1) {
            k[i] = constants::two_pi / 3;
        } else if (l % 2 == 0) {
            if (l >= 2) c *= (l - 1.0) / l;  // c_l = c_{l-2} (l-1)/l
            const double sign = (l / 2) % 2 == 1 ? 1.0 : -1.0;
            k[i] = l == 0 ? constants::pi : constants::two_pi * sign * c / ((l + 2.0) * (l - 1.0));
        }
    }
    detail::normalize_kernel(k, scale, "sh::clamped_cosine_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors of the Phong lobe max(cos theta, 0)^s for real s > -1 (s = 0 is the
/// hemisphere indicator, s = 1 the clamped cosine). Normalized divides by Lambda_0 =
/// 2 pi/(s + 1), i.e. the lobe (s + 1)/(2 pi) cos^s. Throws std::invalid_argument for bad
/// bands or s <= -1.
template <class T = double>
std::vector<T> phong_kernel(int bands, double s, KernelScale scale = KernelScale::unnormalized) {
    check_bands(bands, "sh::phong_kernel");
    if (!(s > -1) || !std::isfinite(s))
        throw std::invalid_argument(
            "sphbasis::sh::phong_kernel(): expected an exponent s > -1, got " + std::to_string(s));
    std::vector<double> k(static_cast<std::size_t>(bands), 0.0);
    double ie = 1 / (s + 1), io = 1 / (s + 2);  // I_l for the current even and odd l
    for (int l = 0; l < bands; ++l) {
        const std::size_t i = static_cast<std::size_t>(l);
        if (l % 2 == 0) {
            k[i] = constants::two_pi * ie;
            ie *= (s - l) / (s + l + 3);
        } else {
            k[i] = constants::two_pi * io;
            io *= (s - l) / (s + l + 3);
        }
    }
    detail::normalize_kernel(k, scale, "sh::phong_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors of any zonal kernel h(t), t = cos theta, by Gauss-Legendre quadrature
/// with `nodes` points on each of [-1, 0] and [0, 1] (0: bands + 32). h is called with double
/// and returns something convertible to double. Exact for h polynomial of degree d on each
/// half when nodes >= (d + bands)/2. Cost O(nodes * bands) plus O(nodes^2) for the rule.
/// Throws std::invalid_argument for bad bands or nodes < 0.
template <class T = double, class F>
std::vector<T> zonal_kernel(int bands, F&& h, KernelScale scale = KernelScale::unnormalized,
                            int nodes = 0) {
    check_bands(bands, "sh::zonal_kernel");
    if (nodes < 0 || nodes > 100000)
        throw std::invalid_argument(
            "sphbasis::sh::zonal_kernel(): expected 0 <= nodes <= 100000 (0: automatic), got " +
            std::to_string(nodes));
    const int nq = nodes > 0 ? nodes : bands + 32;
    std::vector<double> t, w;
    gauss_legendre(nq, t, w);
    std::vector<double> k(static_cast<std::size_t>(bands), 0.0);
    for (int half = 0; half < 2; ++half)
        for (std::size_t i = 0; i < t.size(); ++i) {
            // Map [-1, 1] to [-1, 0] or [0, 1].
            const double x = half == 0 ? 0.5 * (t[i] - 1) : 0.5 * (t[i] + 1);
            const double hw = static_cast<double>(h(x)) * 0.5 * w[i];
            double p0 = 1, p1 = x;
            for (int l = 0; l < bands; ++l) {
                double pl;
                if (l == 0)
                    pl = p0;
                else if (l == 1)
                    pl = p1;
                else {
                    pl = ((2 * l - 1) * x * p1 - (l - 1) * p0) / l;
                    p0 = p1;
                    p1 = pl;
                }
                k[static_cast<std::size_t>(l)] += hw * pl;
            }
        }
    for (double& v : k) v *= constants::two_pi;
    detail::normalize_kernel(k, scale, "sh::zonal_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors from a zonal function's own coefficients z_l (on y_l0):
/// Lambda_l = sqrt(4 pi/(2l+1)) z_l. out may equal z.
template <class T>
void zonal_to_kernel(int bands, const T* z, T* out) {
    check_bands(bands, "sh::zonal_to_kernel");
    for (int l = 0; l < bands; ++l)
        out[l] = z[l] * static_cast<T>(std::sqrt(constants::four_pi / (2 * l + 1)));
}
/// The inverse of zonal_to_kernel: z_l = sqrt((2l+1)/(4 pi)) Lambda_l.
template <class T>
void kernel_to_zonal(int bands, const T* kernel, T* out) {
    check_bands(bands, "sh::kernel_to_zonal");
    for (int l = 0; l < bands; ++l)
        out[l] = kernel[l] * static_cast<T>(std::sqrt((2 * l + 1) / constants::four_pi));
}

/// out_lm = kernel[l] in_lm for `bands` bands (in == out allowed). C is any type with C * T.
template <class T, class C>
void convolve(int bands, const T* kernel, const C* in, C* out) {
    check_bands(bands, "sh::convolve");
    if (bands == 0) return;
    if (!kernel || !in || !out)
        throw std::invalid_argument("sphbasis::sh::convolve(): expected non-null arrays");
    for (int l = 0; l < bands; ++l)
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) out[k] = in[k] * kernel[l];
}

// ---------------------------------------------------------------------------------------------
// Ramamoorthi-Hanrahan irradiance (3 bands)

namespace irradiance_constants {
inline constexpr double c1 = 0.42904276540489172;  // sqrt(15 pi)/16
inline constexpr double c2 = 0.51166335397324424;  // sqrt(3 pi)/6
inline constexpr double c3 = 0.74312386830112707;  // 3 sqrt(5 pi)/16
inline constexpr double c4 = 0.88622692545275801;  // sqrt(pi)/2
inline constexpr double c5 = 0.24770795610037569;  // sqrt(5 pi)/16
}  // namespace irradiance_constants

/// The symmetric 4x4 matrix M (row-major) with irradiance E(n) = n^T M n, n = (x, y, z, 1), from
/// the 9 radiance coefficients L (3 bands, this library's convention), Ramamoorthi-Hanrahan
/// eq. 12. C is any coefficient type with C * T and C + C; T is the scalar of the constants.
template <class T = double, class C>
std::array<C, 16> irradiance_matrix(const C* L) {
    namespace k = irradiance_constants;
    const T c1 = T(k::c1), c2 = T(k::c2), c3 = T(k::c3), c4 = T(k::c4), c5 = T(k::c5);
    // ACN: 0 L00, 1 L1-1, 2 L10, 3 L11, 4 L2-2, 5 L2-1, 6 L20, 7 L21, 8 L22.
    const C m01 = L[4] * c1, m02 = L[7] * c1, m03 = L[3] * c2, m12 = L[5] * c1, m13 = L[1] * c2,
            m23 = L[2] * c2;
    return {L[8] * c1, m01,          m02,       m03,  //
            m01,       L[8] * (-c1), m12,       m13,  //
            m02,       m12,          L[6] * c3, m23,  //
            m03,       m13,          m23,       L[0] * c4 + L[6] * (-c5)};
}

/// n^T M n with n = (x, y, z, 1), (x, y, z) normalised as by sh::eval. 10 multiply-adds.
template <class C, class T>
C eval_irradiance_matrix(const std::array<C, 16>& M, T x, T y, T z) {
    normalize_or_pole(x, y, z);
    // Symmetric: diagonal once, off-diagonal twice.
    C e = M[15] + M[0] * (x * x) + M[5] * (y * y) + M[10] * (z * z);
    e = e + M[1] * (T(2) * x * y) + M[2] * (T(2) * x * z) + M[6] * (T(2) * y * z);
    e = e + M[3] * (T(2) * x) + M[7] * (T(2) * y) + M[11] * (T(2) * z);
    return e;
}

/// Irradiance at normal (x, y, z) from 9 radiance coefficients, Ramamoorthi-Hanrahan eq. 13:
/// c1 L22 (x^2 - y^2) + c3 L20 z^2 + c4 L00 - c5 L20 + 2 c1 (L2-2 xy + L21 xz + L2-1 yz)
/// + 2 c2 (L11 x + L1-1 y + L10 z). Equal to convolve(clamped_cosine_kernel) + eval_sum.
template <class C, class T>
C irradiance(const C* L, T x, T y, T z) {
    namespace k = irradiance_constants;
    normalize_or_pole(x, y, z);
    const T c1 = T(k::c1), c2 = T(k::c2), c3 = T(k::c3), c4 = T(k::c4), c5 = T(k::c5);
    C e = L[8] * (c1 * (x * x - y * y)) + L[6] * (c3 * z * z - c5) + L[0] * c4;
    e = e + L[4] * (T(2) * c1 * x * y) + L[7] * (T(2) * c1 * x * z) + L[5] * (T(2) * c1 * y * z);
    e = e + L[3] * (T(2) * c2 * x) + L[1] * (T(2) * c2 * y) + L[2] * (T(2) * c2 * z);
    return e;
}

// ---------------------------------------------------------------------------------------------
// Minimum over the sphere

/// Result of minimum(): the true minimum m* of the expansion satisfies
/// lower_bound <= m* <= value, and value = f(direction).
template <class T>
struct MinimumBound {
    T lower_bound;          ///< certified: f(w) >= lower_bound for every unit w
    T value;                ///< the smallest value found, attained at `direction`
    vec3<T> direction;      ///< where `value` was found
    long long evaluations;  ///< expansion evaluations spent
    bool converged;         ///< value - lower_bound <= tolerance (else the budget ran out)
};

namespace detail {

struct MinCell {
    double t0, t1, p0, p1;  // theta and phi ranges
    double f;               // value at the centre
    double delta;           // largest geodesic distance from the centre to the cell
};

inline vec3<double> polar_dir(double t, double p) noexcept {
    const double st = std::sin(t);
    return {st * std::cos(p), st * std::sin(p), std::cos(t)};
}

inline double cell_radius(const MinCell& c) noexcept {
    const vec3<double> m = polar_dir(0.5 * (c.t0 + c.t1), 0.5 * (c.p0 + c.p1));
    double r = 0;
    const double ts[2] = {c.t0, c.t1}, ps[2] = {c.p0, c.p1};
    for (double t : ts)
        for (double p : ps) {
            const vec3<double> q = polar_dir(t, p);
            const double dx = q.x - m.x, dy = q.y - m.y, dz = q.z - m.z;
            const double chord = std::sqrt(dx * dx + dy * dy + dz * dz);
            r = std::max(r, 2 * std::asin(std::min(1.0, 0.5 * chord)));
        }
    return r * (1 + 1e-12) + 1e-15;
}

}  // namespace detail

/// A certified lower bound of min over the sphere of f = sum_k coeffs[k] y_k, and the smallest
/// value found, by the subdivision in the header comment. Stops when value - lower_bound <=
/// rel_tolerance * F (F: the bound on |f - mean| it computes) or after about max_evaluations
/// evaluations (then converged = false; the bound is still valid). Work is done in double; for
/// float the bound is rounded down. Use it to detect negative irradiance:
/// minimum(...).lower_bound >= 0 proves the reconstruction non-negative everywhere.
/// Throws std::invalid_argument for bad bands, a null array, non-finite coefficients or
/// rel_tolerance <= 0.
template <class T>
MinimumBound<T> minimum(int bands, const T* coeffs, double rel_tolerance = 1e-6,
                        long long max_evaluations = 4000000) {
    static_assert(std::is_floating_point_v<T>, "sphbasis::sh::minimum: T is float or double.");
    check_bands(bands, "sh::minimum");
    if (bands < 1)
        throw std::invalid_argument("sphbasis::sh::minimum(): expected bands >= 1, got 0");
    if (!coeffs) throw std::invalid_argument("sphbasis::sh::minimum(): expected non-null coeffs");
    if (!(rel_tolerance > 0))
        throw std::invalid_argument("sphbasis::sh::minimum(): expected rel_tolerance > 0");
    const int n = bands, L = bands - 1;
    const std::size_t nc = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    std::vector<double> c(nc);
    // Work on coefficients scaled to max |c| = 1 (so no square overflows), scale back at the end.
    double cmax = 0;
    for (std::size_t k = 0; k < nc; ++k) {
        c[k] = static_cast<double>(coeffs[k]);
        if (!std::isfinite(c[k]))
            throw std::invalid_argument(
                "sphbasis::sh::minimum(): expected finite coefficients, got a NaN or Inf");
        cmax = std::max(cmax, std::fabs(c[k]));
    }
    const double cscale = cmax > 0 ? cmax : 1.0;
    double norm2 = 0, norm2_ac = 0;
    for (std::size_t k = 0; k < nc; ++k) {
        c[k] /= cscale;
        norm2 += c[k] * c[k];
        if (k > 0) norm2_ac += c[k] * c[k];
    }
    const double dc = c[0] * constants::inv_sqrt_four_pi;
    const double bound_all = std::sqrt(norm2) * n * constants::inv_sqrt_four_pi;
    const double eps = std::numeric_limits<double>::epsilon();
    const double rho = 8.0 * (double(nc) + n) * eps * bound_all;  // rounding margin
    // Cauchy-Schwarz: |f - dc| <= ||c_ac|| sqrt((n^2 - 1)/(4 pi)).
    double F = std::sqrt(norm2_ac) * std::sqrt((double(nc) - 1) / constants::four_pi);

    auto finish = [&](double lb, double val, vec3<double> dir, long long evals, bool conv) {
        MinimumBound<T> r;
        lb *= cscale;
        val *= cscale;
        T l = static_cast<T>(lb);
        if (static_cast<double>(l) > lb) l = std::nextafter(l, -std::numeric_limits<T>::infinity());
        r.lower_bound = l;
        r.value = static_cast<T>(val);
        r.direction = {static_cast<T>(dir.x), static_cast<T>(dir.y), static_cast<T>(dir.z)};
        r.evaluations = evals;
        r.converged = conv;
        return r;
    };
    if (L == 0 || !(F > 0)) return finish(dc - rho, dc, {0, 0, 1}, 0, true);

    std::vector<detail::MinCell> cells;
    // First grid: rings of width dt, phi cells no wider (in arc length) than dt.
    const int nt = std::max(2, static_cast<int>(std::ceil(constants::pi * L / 0.45)));
    const double dt = constants::pi / nt;
    for (int i = 0; i < nt; ++i) {
        const double t0 = i * dt, t1 = (i + 1) * dt;
        const double smax = (t0 <= constants::pi / 2 && t1 >= constants::pi / 2)
                                ? 1.0
                                : std::max(std::sin(t0), std::sin(t1));
        const int np = std::max(3, static_cast<int>(std::ceil(constants::two_pi * smax / dt)));
        const double dp = constants::two_pi / np;
        for (int j = 0; j < np; ++j) cells.push_back({t0, t1, j * dp, (j + 1) * dp, 0, 0});
    }
    std::vector<double> xs, ys, zs, fv;
    long long evals = 0;
    double best = std::numeric_limits<double>::infinity();
    vec3<double> best_dir{0, 0, 1};
    auto evaluate = [&](std::vector<detail::MinCell>& cs) {
        xs.resize(cs.size());
        ys.resize(cs.size());
        zs.resize(cs.size());
        fv.resize(cs.size());
        for (std::size_t i = 0; i < cs.size(); ++i) {
            const vec3<double> d =
                detail::polar_dir(0.5 * (cs[i].t0 + cs[i].t1), 0.5 * (cs[i].p0 + cs[i].p1));
            xs[i] = d.x;
            ys[i] = d.y;
            zs[i] = d.z;
            cs[i].delta = detail::cell_radius(cs[i]);
        }
        eval_sum_batch(n, c.data(), cs.size(), xs.data(), ys.data(), zs.data(), fv.data());
        for (std::size_t i = 0; i < cs.size(); ++i) {
            cs[i].f = fv[i];
            if (fv[i] < best) {
                best = fv[i];
                best_dir = {xs[i], ys[i], zs[i]};
            }
        }
        evals += static_cast<long long>(cs.size());
    };
    evaluate(cells);
    {
        // Sampled bound on |f - dc|: its maximum is a critical point too.
        double dmax = 0, hmax = 0;
        for (const auto& cl : cells) {
            dmax = std::max(dmax, cl.delta);
            hmax = std::max(hmax, std::fabs(cl.f - dc));
        }
        const double q = 0.5 * L * L * dmax * dmax;
        if (q < 1) F = std::min(F, (hmax + rho) / (1 - q));
    }
    const double K = 0.5 * double(L) * double(L) * F;  // f(c) - f(w*) <= K delta^2
    const double tol = rel_tolerance * F;
    std::vector<detail::MinCell> next;
    double lb = -std::numeric_limits<double>::infinity();
    for (int level = 0; level < 64; ++level) {
        lb = std::numeric_limits<double>::infinity();
        for (const auto& cl : cells) lb = std::min(lb, cl.f - K * cl.delta * cl.delta);
        lb -= rho;
        if (best - lb <= tol) return finish(lb, best, best_dir, evals, true);
        next.clear();
        for (const auto& cl : cells) {
            if (cl.f - K * cl.delta * cl.delta - rho > best) continue;  // cannot hold w*
            const double tm = 0.5 * (cl.t0 + cl.t1), pm = 0.5 * (cl.p0 + cl.p1);
            next.push_back({cl.t0, tm, cl.p0, pm, 0, 0});
            next.push_back({cl.t0, tm, pm, cl.p1, 0, 0});
            next.push_back({tm, cl.t1, cl.p0, pm, 0, 0});
            next.push_back({tm, cl.t1, pm, cl.p1, 0, 0});
        }
        if (evals + static_cast<long long>(next.size()) > max_evaluations) break;
        evaluate(next);
        cells.swap(next);
    }
    return finish(lb, best, best_dir, evals, best - lb <= tol);
}

}  // namespace sphbasis::sh
