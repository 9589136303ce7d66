// sphbasis: quadrature on the sphere and the upper hemisphere.
//
// Product rules: Gauss-Legendre in z = cos(theta) times the uniform (trapezoidal) rule in phi.
// sphere_rule(d) integrates every polynomial in (x, y, z) of total degree <= d over the unit
// sphere exactly (up to rounding); hemisphere_rule(d) does the same over z >= 0 (Gauss-Legendre
// mapped to z in [0, 1]). Why that holds on the hemisphere: a monomial x^i y^j z^k equals
// sin^(i+j)(t) cos^i(phi) sin^j(phi) z^k; for i+j even, sin^(i+j) is a polynomial of degree
// i+j in z, so the z integrand has degree <= d; for i+j odd the phi integral vanishes and the
// uniform rule with more than d points reproduces that zero.
// The same rules are exact for the hemispherical bases' Gram matrices (HSH, Makhotkin, Zernike),
// whose pairwise products are polynomials in z times trigonometric polynomials in phi.
//
// Gauss-Legendre nodes by Newton's method on the three-term recurrence from Tricomi's initial
// guesses (Numerical Recipes; Hale & Townsend 2013 for the asymptotics): nodes and weights
// are accurate to a few ulp for n up to several thousand. Cost O(n^2) to build.
#pragma once

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "constants.hpp"
#include "error.hpp"

namespace sphbasis {

/// Gauss-Legendre nodes t_i (ascending) and weights w_i on [-1, 1]: exact for polynomials of
/// degree <= 2n - 1. Throws std::invalid_argument for n < 1.
inline void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
    if (n < 1) throw std::invalid_argument("sphbasis::gauss_legendre(): expected n >= 1");
    const std::size_t un = static_cast<std::size_t>(n);
    nodes.assign(un, 0.0);
    weights.assign(un, 0.0);
    const int half = (n + 1) / 2;
    for (int i = 0; i < half; ++i) {
        // Tricomi's approximation of the i-th largest root.
        const double k = i + 1;
        double t = std::cos(constants::pi * (k - 0.25) / (n + 0.5));
        t *= 1 - (1 - 1.0 / n) / (8.0 * n * n);
        double dp = 1;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = t;
            for (int j = 2; j <= n; ++j) {
                const double p2 = ((2 * j - 1) * t * p1 - (j - 1) * p0) / j;
                p0 = p1;
                p1 = p2;
            }
            if (n == 1) p0 = 1, p1 = t;
            dp = n * (t * p1 - p0) / (t * t - 1);
            const double dt = p1 / dp;
            t -= dt;
            if (std::fabs(dt) <= 1e-16 * std::fabs(t) + 1e-300) {
                // One more evaluation for the weight at the converged node.
                p0 = 1, p1 = t;
                for (int j = 2; j <= n; ++j) {
                    const double p2 = ((2 * j - 1) * t * p1 - (j - 1) * p0) / j;
                    p0 = p1;
                    p1 = p2;
                }
                dp = n == 1 ? 1.0 : n * (t * p1 - p0) / (t * t - 1);
                break;
            }
        }
        if (2 * i + 1 == n) t = 0;  // the middle node of an odd rule is exactly 0
        const double w = 2 / ((1 - t * t) * dp * dp);
        nodes[static_cast<std::size_t>(n - 1 - i)] = t;
        nodes[static_cast<std::size_t>(i)] = -t;
        weights[static_cast<std::size_t>(n - 1 - i)] = w;
        weights[static_cast<std::size_t>(i)] = w;
    }
}

/// A set of weighted unit directions (SoA): sum_i w[i] f(x[i], y[i], z[i]) approximates the
/// integral of f over the rule's domain with respect to solid angle.
struct DirectionalRule {
    std::vector<double> x, y, z, w;
    std::size_t size() const noexcept { return w.size(); }
};

namespace detail {
/// A rule of `rings` rings times nphi uniform azimuths (j + 1/2) 2 pi / nphi: ring(i, z, s, w)
/// sets ring i's z, sin(theta) = s and weight per unit azimuth w (the points get w 2 pi / nphi).
template <class Ring>
DirectionalRule azimuthal_rule(int rings, int nphi, Ring&& ring) {
    DirectionalRule r;
    const std::size_t total = static_cast<std::size_t>(rings) * static_cast<std::size_t>(nphi);
    r.x.reserve(total);
    r.y.reserve(total);
    r.z.reserve(total);
    r.w.reserve(total);
    const double dphi = constants::two_pi / nphi;
    for (std::size_t i = 0; i < static_cast<std::size_t>(rings); ++i) {
        double z, s, w;
        ring(i, z, s, w);
        w = w * dphi;
        for (int j = 0; j < nphi; ++j) {
            const double phi = (j + 0.5) * dphi;
            r.x.push_back(s * std::cos(phi));
            r.y.push_back(s * std::sin(phi));
            r.z.push_back(z);
            r.w.push_back(w);
        }
    }
    return r;
}

inline DirectionalRule product_rule(int degree, bool hemisphere, const char* fn) {
    if (degree < 0 || degree > 100000)
        throw std::invalid_argument(std::string("sphbasis::") + fn +
                                    "(): expected 0 <= degree <= 100000, got " +
                                    std::to_string(degree));
    const int nt = degree / 2 + 1;  // 2 nt - 1 >= degree
    const int np = degree + 1;      // uniform phi rule: exact for trig degree <= np - 1
    // 4 doubles (x, y, z, w) a point.
    check_table_bytes(fn, 32.0 * nt * np, "a degree-" + std::to_string(degree) + " rule");
    std::vector<double> t, wt;
    gauss_legendre(nt, t, wt);
    return azimuthal_rule(nt, np, [&](std::size_t i, double& z, double& s, double& w) {
        z = hemisphere ? 0.5 * (t[i] + 1) : t[i];
        w = hemisphere ? 0.5 * wt[i] : wt[i];
        // sin(theta) without cancellation: 1 - z^2 = (1 - z)(1 + z).
        s = std::sqrt((1 - z) * (1 + z));
    });
}
}  // namespace detail

/// Product rule on the unit sphere, exact for polynomials in (x, y, z) of degree <= `degree`
/// (for the product of two SH of degrees l1 and l2: degree >= l1 + l2). Uses
/// (degree/2 + 1) * (degree + 1) points, 32 bytes each (degree 16384: 4.3 GB). Throws
/// std::invalid_argument for degree < 0 or a rule above SPHBASIS_MAX_TABLE_BYTES.
inline DirectionalRule sphere_rule(int degree) {
    return detail::product_rule(degree, false, "sphere_rule");
}

/// Product rule on the upper hemisphere z >= 0, exact for polynomials of degree <= `degree`.
inline DirectionalRule hemisphere_rule(int degree) {
    return detail::product_rule(degree, true, "hemisphere_rule");
}

/// Product rule on the upper hemisphere in u = sqrt(z): nu Gauss-Legendre nodes in u on [0, 1]
/// (weight 2u du) times nphi uniform azimuths (offset by half a step, like hemisphere_rule).
/// Exact for p(x, y, z) z^(j/2) with p of total degree d and j in {0, 1} when
/// 2d + j + 1 <= 2 nu - 1 and d < nphi; converges geometrically for those functions times
/// factors analytic in z on [-1, 1]. Made for bases with a sqrt(z) factor (Makhotkin, HSH). nu *
/// nphi points, all with z > 0. Throws std::invalid_argument unless 1 <= nu, nphi <= 100000.
inline DirectionalRule hemisphere_rule_sqrt(int nu, int nphi) {
    if (nu < 1 || nphi < 1 || nu > 100000 || nphi > 100000)
        throw std::invalid_argument(
            "sphbasis::hemisphere_rule_sqrt(): expected 1 <= nu, nphi <= 100000, got " +
            std::to_string(nu) + ", " + std::to_string(nphi));
    std::vector<double> t, wt;
    gauss_legendre(nu, t, wt);
    return detail::azimuthal_rule(nu, nphi, [&](std::size_t i, double& z, double& s, double& w) {
        const double u = 0.5 * (t[i] + 1);
        z = u * u;
        w = 0.5 * wt[i] * 2 * u;
        s = std::sqrt((1 - u) * (1 + u) * (1 + z));  // sin = sqrt(1 - u^4)
    });
}

}  // namespace sphbasis
