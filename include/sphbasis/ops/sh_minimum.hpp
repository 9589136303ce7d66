// sphbasis: a certified lower bound of a spherical-harmonic expansion's minimum over the sphere
// (e.g. to prove that a reconstructed irradiance is non-negative everywhere).
//
// minimum(): a certified lower bound by subdivision. For a spherical polynomial f of degree L,
// restricted to any great circle it is a trigonometric polynomial of degree L in arc length, so
// Bernstein's inequality gives |g''| <= L^2 ||f - c||_inf for any constant c. At a global minimiser
// w* the gradient vanishes, so every point p at geodesic distance d from w* has f(p) <= f(w*) + L^2
// F d^2 / 2, F >= ||f - f_00 y_00||_inf. The sphere is covered by latitude-longitude cells; if w*
// is in a cell with centre c and radius delta (the largest distance from c to the cell, attained at
// a corner), then
//   f(w*) >= f(c) - L^2 F delta^2 / 2.
// The bound is the minimum of that over the cells that can still hold w*; cells whose bound
// exceeds the best value found are dropped and the rest split in four, so the gap shrinks by
// ~4 per level. F is the smaller of a Cauchy-Schwarz bound (sum_m y_lm^2 = (2l+1)/(4 pi)) and
// the sampled maximum inflated by the same argument; a rounding margin is subtracted. Cost:
// about 60 L^2 evaluations for the first grid plus 4 per surviving cell per level, each O(n^2).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/vec.hpp"

namespace sphbasis::sh {

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
    if (bands < 1) sphbasis::detail::throw_invalid("sh::minimum", "bands >= 1, got 0");
    sphbasis::detail::check_buffer("sh::minimum", "coeffs", coeffs, 1);
    if (!(rel_tolerance > 0))
        sphbasis::detail::throw_invalid("sh::minimum",
                                        "rel_tolerance > 0, got " + std::to_string(rel_tolerance));
    const int n = bands, L = bands - 1;
    const std::size_t nc = static_cast<std::size_t>(n) * static_cast<std::size_t>(n);
    std::vector<double> c(nc);
    // Work on coefficients scaled to max |c| = 1 (so no square overflows), scale back at the end.
    double cmax = 0;
    for (std::size_t k = 0; k < nc; ++k) {
        c[k] = static_cast<double>(coeffs[k]);
        if (!std::isfinite(c[k]))
            sphbasis::detail::throw_invalid("sh::minimum", "finite coefficients, got a NaN or Inf");
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
