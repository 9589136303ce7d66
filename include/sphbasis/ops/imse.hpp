// sphbasis: the IMSE basis comparison (integrated mean square error of an irradiance signal
// fitted in a basis over the upper hemisphere), as reusable pieces for the `sphbasis imse`
// benchmark and for users who want to score their own basis or signal.
//
// Reference: Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 3.1, eq. (3.1):
//   IMSE = int_{Omega+} ( sum_i c_i B_i(n) - E(n) )^2 dn,  and section 2.2.1, eq. (2.3):
// the irradiance of radiance L = sum c_lm y_lm is E = sum a_l c_lm y_lm with the normalised
// clamped-cosine factors a_0 = 1, a_1 = 2/3, a_2 = 1/4 (core/clamped_cosine.hpp; Ramamoorthi and
// Hanrahan, "An Efficient Representation for Irradiance Environment Maps", SIGGRAPH 2001, A_l /
// pi; E is the exitant radiance of a white Lambertian surface, the 1/pi folded into the kernel).
//
// This header holds the experiment only. Its general tools live in their own headers:
// the fit (LeastSquares, ops/projection.hpp), the clamped-cosine factors (clamped_cosine(),
// core/clamped_cosine.hpp), the normalised Legendre tables (Legendre, core/legendre.hpp), the
// lat-long projector (LatLongMap, squared_norm, sh::project_latlong: ops/sh_latlong.hpp) and the
// band energies (sh::band_energies, ops/sh_convolution.hpp).
//
// Conventions.
//   * Domain: the upper hemisphere z >= 0 (the tangent-space normals), solid-angle measure,
//     area 2 pi. Inner products <f, g> = int_{Omega+} f g dn are sums over a DirectionalRule.
//   * The fit of E in a basis B of n functions is the least-squares fit over the hemisphere:
//     the orthogonal projection c_i = <B_i, E> when B is orthonormal ON THE HEMISPHERE
//     (hsh, makhotkin, zernike, hbasis, hl2; checked against the Gram matrix), otherwise the
//     Gram solve G c = <B, E> (hbasis-mod; SH, which is orthonormal only on the sphere).
//   * Paper protocol: radiance L = sum_{k<9} c_k y_k (real SH of bands 0-2, ACN, the library's
//     sign convention), c_k i.i.d. uniform on [-1, 1]. Because the fit is linear in c,
//       IMSE(c) = c^T Q c,   Q = A (Y - C^T G^-1 C) A,
//     with Y = <y, y> the 9x9 hemispherical Gram of SH-9, C = <B, y> (n x 9), G = <B, B> and
//     A = diag(a_l(k)). For c_k i.i.d. with variance s^2 = 1/3 the expectation is
//     E[IMSE] = s^2 tr(Q) = tr(Q)/3 and the variance is (mu_4 - s^4) sum Q_ii^2 +
//     2 s^4 sum_{i != j} Q_ij^2 (mu_4 = 1/5), which gives the standard error of a sample mean.
//   * HDRI protocol: the relative IMSE, IMSE / mean_{Omega+}(E^2) with mean(E^2) =
//     int_{Omega+} E^2 / (2 pi): the fraction of the signal's energy the fit misses, times 2 pi.
//   * Fit protocol (the fitted, non-linear representations of basis/registry.hpp: ZH3, ZH3
//     hallucinated, L1 SH with the Geomerics reconstruction): no least squares over the
//     hemisphere; the representation is fitted the way engines fit probes, from the signal's own
//     low-order SH coefficients over the whole sphere (FittedBasisInfo::fit), and its error is
//     integrated over the hemisphere like every other row: the representation's SH expansion r
//     (exact for ZH3, Funk-Hecke moments for the Geomerics model) minus the signal's e, through
//     the hemispherical SH Gram, IMSE = (r - e)^T G (r - e) (fitted_imse()). No closed form
//     ("expected") since the fit is non-linear.
//
// Quadrature. The products of HSH and Makhotkin functions with SH contain sqrt(z) (e.g.
// M_00 = sqrt(z/pi), H_11 ~ x sqrt(z/(1+z))), so Gauss-Legendre in z (hemisphere_rule)
// converges only algebraically, ~n^-3 (relative error ~1e-6 at hemisphere_rule(200)).
// hemisphere_rule_sqrt() substitutes u = sqrt(z): dz = 2u du, sqrt(z) = u, so polynomials times
// powers of sqrt(z) become polynomials in u, and the remaining factors (1+z)^(-1/2), (1+z)^(-1),
// (1-z^2)^(m/2) paired with a function of the same m, are analytic on u in [0, 1] (singular only
// at u = +-i), where Gauss-Legendre converges geometrically. Every function of every basis here
// carries its phi dependence as cos(m phi) or sin(m phi), and the uniform phi rule integrates
// trigonometric polynomials of degree < nphi exactly.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../basis/registry.hpp"
#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/legendre.hpp"
#include "../core/quadrature.hpp"
#include "projection.hpp"
#include "sg_fit.hpp"

namespace sphbasis::imse {

// ---------------------------------------------------------------------------------------------
// Kernel factors and quadrature

// hemisphere_rule_sqrt(nu, nphi) lives in core/quadrature.hpp; the name is kept here too.
using sphbasis::hemisphere_rule_sqrt;

/// The rule of the paper protocol (nu = nphi = 32, 1024 points): bases up to 25 functions
/// against SH-9 signals (trigonometric degree <= 8, polynomial degree <= 8 in z) are integrated
/// to rounding; paper_check_rule() (nu = 64, nphi = 48) is the finer rule that demonstrates it.
inline DirectionalRule paper_rule() { return hemisphere_rule_sqrt(32, 32); }
inline DirectionalRule paper_check_rule() { return hemisphere_rule_sqrt(64, 48); }

// ---------------------------------------------------------------------------------------------
// The signal space and the fit

/// One row of the benchmark's table: a registered basis (registry name) and its number of
/// functions.
struct Row {
    std::string basis;
    int n;
};

/// The rows of the paper protocol, in table order: SH 4, 9, 16, 25; HSH 4, 9, 16; Makhotkin 4,
/// 9, 16; Zernike 3, 6, 10, 15; H-basis 4, 6; modified H-basis 4, 6; HL2 3; ambient cube 5 (its
/// hemispherical restriction: the -z face is zero on z >= 0); ambient dice 12; SG 9, 12 (the
/// irradiance fitted in the span of BakingLab's lobes; sg_pipeline_imse() scores BakingLab's own
/// pipeline, radiance fitted and irradiance by Hill's approximation); Ambient Dice's face variants,
/// Bezier 30 and linear 10 (without the 2 vertices that have no support on z >= 0), the paper's
/// rule and then the normalised one. The fitted rows (fitted_rows()) follow them.
inline std::vector<Row> paper_rows() {
    std::vector<Row> rows{{"sh", 4},         {"sh", 9},           {"sh", 16},
                          {"sh", 25},        {"hsh", 4},          {"hsh", 9},
                          {"hsh", 16},       {"makhotkin", 4},    {"makhotkin", 9},
                          {"makhotkin", 16}, {"zernike", 3},      {"zernike", 6},
                          {"zernike", 10},   {"zernike", 15},     {"hbasis", 4},
                          {"hbasis", 6},     {"hbasis-mod", 4},   {"hbasis-mod", 6},
                          {"hl2", 3},        {"ambient-cube", 5}, {"ambient-dice", 12},
                          {"sg", 9},         {"sg", 12}};
    rows.insert(rows.end(), {{"ambient-dice-bezier", 30},
                             {"ambient-dice-linear", 10},
                             {"ambient-dice-bezier-normalized", 30},
                             {"ambient-dice-linear-normalized", 10}});
    return rows;
}

/// The rows of the HDRI protocol, in table order: the same rows as paper_rows().
inline std::vector<Row> hdri_rows() { return paper_rows(); }

/// Number of radiance coefficients of the paper protocol: SH bands 0-2.
inline constexpr int signal_coeffs = 9;

/// The clamped-cosine factors per ACN coefficient, a_{l(k)} for k < count (count a square).
inline Eigen::VectorXd irradiance_factors(int count = signal_coeffs) {
    if (!SH::valid_count(count))
        sphbasis::detail::throw_invalid(
            "imse::irradiance_factors",
            "a square number of coefficients, got " + std::to_string(count));
    Eigen::VectorXd a(count);
    for (int k = 0; k < count; ++k) a(k) = clamped_cosine(sh::degree_of(k));
    return a;
}

/// Whether the least-squares fit of `info` over the hemisphere is an orthogonal projection:
/// the basis is orthonormal and its domain is the hemisphere (SH is orthonormal on the sphere
/// only, so it takes the Gram solve).
inline bool orthonormal_on_hemisphere(const BasisInfo& info) {
    return info.orthonormal && info.domain == Domain::hemisphere;
}

/// The least-squares fit of the experiment: LeastSquares (ops/projection.hpp) with the IMSE of
/// each sampled signal, the squared residual of its fit integrated by the rule.
class Fit : public LeastSquares {
  public:
    using LeastSquares::LeastSquares;
    /// IMSE of each of S sampled signals (samples: rule.size() x S), Ishmukhametov eq. 3.1:
    /// sum_i w_i (sum_k c_k B_k(d_i) - f(d_i))^2. Never negative.
    Eigen::VectorXd imse(const Eigen::MatrixXd& samples) const {
        return squared_residuals(samples);
    }
};

/// The irradiance of the paper protocol sampled on the rule's points: for radiance SH-9
/// coefficients (9 x S), E(d_i) = sum_k a_l(k) c_k y_k(d_i) (rule.size() x S).
inline Eigen::MatrixXd irradiance_samples(const Eigen::MatrixXd& radiance,
                                          const DirectionalRule& rule) {
    if (radiance.rows() != signal_coeffs)
        sphbasis::detail::throw_invalid(
            "imse::irradiance_samples",
            "9 radiance coefficients per column, got " + std::to_string(radiance.rows()));
    return evaluation_matrix(evaluator<SH>(signal_coeffs), rule) *
           (irradiance_factors().asDiagonal() * radiance);
}

/// The 9 x 9 residual form Q of the paper protocol: IMSE(c) = c^T Q c for radiance SH-9
/// coefficients c, Q = A (Y - C^T G^-1 C) A (see the header), computed from the Gram matrices
/// over `rule` (paper_rule() by default). For orthonormal bases G = I is checked, not assumed
/// away. Symmetric positive semidefinite up to rounding; for a basis whose span contains SH-9
/// on the hemisphere Q is zero to ~1e-16 (cancellation, entries may be slightly negative).
inline Eigen::MatrixXd residual_form(const BasisFunctions& b, bool orthonormal,
                                     const DirectionalRule& rule = paper_rule()) {
    const Fit fit(b, orthonormal, rule);
    const BasisFunctions s = evaluator<SH>(signal_coeffs);
    const Eigen::MatrixXd ys = evaluation_matrix(s, rule);
    const Eigen::Map<const Eigen::VectorXd> w(rule.w.data(),
                                              static_cast<Eigen::Index>(rule.w.size()));
    const Eigen::MatrixXd y = ys.transpose() * w.asDiagonal() * ys;                // <y, y>
    const Eigen::MatrixXd c = fit.evaluation().transpose() * w.asDiagonal() * ys;  // <B, y>
    const Eigen::MatrixXd k = c.transpose() * fit.solve(c);
    const Eigen::VectorXd a = irradiance_factors();
    Eigen::MatrixXd q = a.asDiagonal() * (y - k) * a.asDiagonal();
    return 0.5 * (q + q.transpose());
}

/// residual_form() for a registered basis with n functions.
inline Eigen::MatrixXd residual_form(const BasisInfo& info, int n,
                                     const DirectionalRule& rule = paper_rule()) {
    return residual_form(info.functions(n), orthonormal_on_hemisphere(info), rule);
}

/// The expected IMSE s^2 tr(Q) for coefficients with mean 0 and variance s^2, uncorrelated
/// (1/3 for uniform on [-1, 1], the paper protocol).
inline double expected(const Eigen::MatrixXd& q, double variance = 1.0 / 3.0) {
    return variance * q.trace();
}

/// The standard deviation of c^T Q c for c_k i.i.d. uniform on [-1, 1] (s^2 = 1/3, fourth
/// moment 1/5): sqrt((1/5 - 1/9) sum Q_ii^2 + (2/9) sum_{i != j} Q_ij^2). Divided by sqrt(N)
/// it is the standard error of the mean over N signals.
inline double stddev_uniform(const Eigen::MatrixXd& q) {
    const double diag = q.diagonal().squaredNorm();
    const double off = q.squaredNorm() - diag;
    return std::sqrt((1.0 / 5.0 - 1.0 / 9.0) * diag + (2.0 / 9.0) * off);
}

/// IMSE of one signal by the closed form c^T Q c (radiance SH-9 coefficients c).
inline double imse_of(const Eigen::MatrixXd& q, const Eigen::VectorXd& radiance) {
    return radiance.dot(q * radiance);
}

/// IMSE of one signal computed the long way (Ishmukhametov, eq. 3.1): irradiance sampled on the
/// rule, least-squares fit, squared residual integrated by the rule.
inline double imse_direct(const BasisFunctions& b, bool orthonormal,
                          const Eigen::VectorXd& radiance,
                          const DirectionalRule& rule = paper_rule()) {
    const Fit fit(b, orthonormal, rule);
    return fit.imse(irradiance_samples(radiance, rule))(0);
}

/// count paper-protocol signals (9 x count): c_k i.i.d. uniform on [-1, 1) from a 64-bit
/// Mersenne Twister seeded with `seed`, drawn signal by signal, coefficient by coefficient
/// (u = top 53 bits / 2^53, c = 2u - 1): the same numbers on every platform and library.
inline Eigen::MatrixXd random_radiance(std::uint64_t seed, int count) {
    if (count < 0)
        sphbasis::detail::throw_invalid("imse::random_radiance",
                                        "count >= 0, got " + std::to_string(count));
    std::mt19937_64 gen(seed);
    Eigen::MatrixXd c(signal_coeffs, count);
    for (int s = 0; s < count; ++s)
        for (int k = 0; k < signal_coeffs; ++k)
            c(k, s) = 2 * (static_cast<double>(gen() >> 11) * 0x1.0p-53) - 1;
    return c;
}

/// Mean and standard error (sample standard deviation / sqrt(N)) of a set of values.
struct Summary {
    double mean = 0, standard_error = 0;
};
inline Summary summarize(const Eigen::VectorXd& v) {
    Summary s;
    const double n = static_cast<double>(v.size());
    if (v.size() == 0) return s;
    s.mean = v.mean();
    if (v.size() > 1)
        s.standard_error = std::sqrt((v.array() - s.mean).square().sum() / (n - 1) / n);
    return s;
}

// ---------------------------------------------------------------------------------------------
// HDRI protocol: radiance from latitude-longitude maps, irradiance in SH of high degree

/// Upper bound on the squared L2 norm over the sphere of the irradiance left out when the
/// irradiance of a radiance L is truncated to `bands` bands:
///   sum_{l >= bands} a_l^2 e_l  <=  sum_{bands <= l < known} a_l^2 e_l
///                                   + max_{l >= known} a_l^2 * (||L||^2 - sum_{l < known} e_l),
/// with e_l the radiance band energies known for l < known = energies.size() and ||L||^2 the
/// radiance's squared norm (Parseval; |a_l| decreases for even l >= 2). Rotation invariant, and
/// a bound on the hemisphere too.
inline double truncation_bound(const std::vector<double>& energies, double squared_norm,
                               int bands) {
    const int known = static_cast<int>(energies.size());
    if (bands < 1 || bands > known)
        sphbasis::detail::throw_invalid("imse::truncation_bound",
                                        "1 <= bands <= energies.size() = " + std::to_string(known) +
                                            ", got " + std::to_string(bands));
    double tail = 0, seen = 0;
    for (int l = 0; l < known; ++l) {
        seen += energies[static_cast<std::size_t>(l)];
        if (l >= bands) {
            const double a = clamped_cosine(l);
            tail += a * a * energies[static_cast<std::size_t>(l)];
        }
    }
    double amax = 0;
    for (int l = known; l <= known + 2; ++l) amax = std::max(amax, std::fabs(clamped_cosine(l)));
    return tail + amax * amax * std::max(0.0, squared_norm - seen);
}

/// The hemispherical Gram matrix of the SH of `bands` bands, which is block diagonal: only
/// functions of the same signed m overlap on z >= 0. Block |m| (the same for +m and -m) holds
/// <y_lm, y_l'm> = 2 pi int_0^1 Pbar_l^m Pbar_l'^m dz for l, l' in [|m|, bands), computed by
/// Gauss-Legendre in z with bands + 1 nodes (exact: the integrand is a polynomial of degree
/// <= 2 bands - 2). energy(c) = int_{Omega+} (sum c_k y_k)^2 in O(bands^3 / 3).
class HemisphereShGram {
  public:
    explicit HemisphereShGram(int bands) : bands_(bands) {
        if (bands < 1 || bands > 1024)
            sphbasis::detail::throw_invalid("imse::HemisphereShGram",
                                            "1 <= bands <= 1024, got " + std::to_string(bands));
        std::vector<double> t, w;
        gauss_legendre(bands + 1, t, w);
        const Legendre leg(bands);  // core/legendre.hpp
        std::vector<double> p(leg.size());
        blocks_.resize(static_cast<std::size_t>(bands));
        for (int m = 0; m < bands; ++m)
            blocks_[static_cast<std::size_t>(m)] = Eigen::MatrixXd::Zero(bands - m, bands - m);
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double z = 0.5 * (t[i] + 1);
            const double wz = 0.5 * w[i] * constants::two_pi;
            leg.eval(z, std::sqrt((1 - z) * (1 + z)), p.data());
            for (int m = 0; m < bands; ++m) {
                Eigen::VectorXd v(bands - m);
                for (int l = m; l < bands; ++l) v(l - m) = p[leg.index(l, m)];
                blocks_[static_cast<std::size_t>(m)] += wz * v * v.transpose();
            }
        }
    }
    int bands() const noexcept { return bands_; }
    /// Block |m|: rows and columns l = |m| .. bands - 1.
    const Eigen::MatrixXd& block(int m) const {
        return blocks_[static_cast<std::size_t>(m < 0 ? -m : m)];
    }
    /// int_{Omega+} E^2 for E = sum_k c_k y_k, c of bands^2 values (ACN).
    double energy(const double* c) const {
        double s = 0;
        Eigen::VectorXd v(bands_);
        for (int m = -(bands_ - 1); m < bands_; ++m) {
            const int am = m < 0 ? -m : m, len = bands_ - am;
            for (int l = am; l < bands_; ++l) v(l - am) = c[sh::index(l, m)];
            const auto seg = v.head(len);
            s += seg.dot(block(m) * seg);
        }
        return s;
    }

  private:
    int bands_;
    std::vector<Eigen::MatrixXd> blocks_;
};

/// Relative IMSE of the HDRI protocol: IMSE / mean_{Omega+}(E^2), mean(E^2) = hemisphere
/// energy / (2 pi).
inline double relative(double imse_value, double hemisphere_energy) {
    return imse_value * constants::two_pi / hemisphere_energy;
}

/// Interval bound on the error of a relative IMSE computed from an irradiance truncated to
/// some degree, when the left-out part has squared norm <= tail on the hemisphere: sqrt(IMSE)
/// is a seminorm (the norm of the fit's residual, a projection), so it moves by at most
/// sqrt(tail), and so does sqrt(energy). Returns max |relative_true - relative(imse, energy)|.
inline double relative_error_bound(double imse_value, double hemisphere_energy, double tail) {
    const double st = std::sqrt(std::max(0.0, tail));
    const double si = std::sqrt(std::max(0.0, imse_value)), se = std::sqrt(hemisphere_energy);
    const double ilo = std::max(0.0, si - st), ihi = si + st;
    const double elo = std::max(0.0, se - st), ehi = se + st;
    const double r = relative(imse_value, hemisphere_energy);
    if (elo <= 0) return std::numeric_limits<double>::infinity();
    const double lo = constants::two_pi * ilo * ilo / (ehi * ehi);
    const double hi = constants::two_pi * ihi * ihi / (elo * elo);
    return std::max(hi - r, r - lo);
}

/// The fits of all rows of a benchmark against irradiance given as SH coefficients of `bands`
/// bands: for each basis, the n x bands^2 matrix D with ||D e||^2 = <B, E>^T G^-1 <B, E>, the
/// energy of the least-squares fit (D = <B, y> for orthonormal bases, L^-1 <B, y> with
/// G = L L^T otherwise). Then IMSE(e) = energy(e) - ||D e||^2 (Pythagoras: the residual of a
/// least-squares fit is orthogonal to the fit). The cross Gram <B, y> is integrated with
/// hemisphere_rule_sqrt(nu, nphi); see hdri_rule_size() for sizes that are exact to rounding.
class ShFits {
  public:
    ShFits(const std::vector<BasisFunctions>& bases, const std::vector<bool>& orthonormal,
           int bands, int nu, int nphi)
        : bands_(bands) {
        if (bases.size() != orthonormal.size())
            sphbasis::detail::throw_invalid("imse::ShFits", "one orthonormal flag per basis");
        const DirectionalRule rule = hemisphere_rule_sqrt(nu, nphi);
        const Eigen::Index npts = static_cast<Eigen::Index>(rule.size());
        const int k = bands * bands;
        int total = 0;
        for (const auto& b : bases) {
            sphbasis::detail::check_basis_functions(b, "imse::ShFits");
            offsets_.push_back(total);
            total += b.n;
        }
        offsets_.push_back(total);
        // All bases' values at the rule's points, side by side.
        Eigen::MatrixXd phib(npts, total);
        std::vector<double> tmp;
        for (std::size_t r = 0; r < bases.size(); ++r) {
            tmp.resize(static_cast<std::size_t>(bases[r].n));
            for (Eigen::Index i = 0; i < npts; ++i) {
                const std::size_t ui = static_cast<std::size_t>(i);
                bases[r].eval(rule.x[ui], rule.y[ui], rule.z[ui], tmp.data());
                for (int j = 0; j < bases[r].n; ++j)
                    phib(i, offsets_[r] + j) = tmp[static_cast<std::size_t>(j)];
            }
        }
        const Eigen::Map<const Eigen::VectorXd> w(rule.w.data(), npts);
        const Eigen::MatrixXd gram_all = phib.transpose() * w.asDiagonal() * phib;
        // <B, y> in chunks of points (the SH values of a chunk: chunk x bands^2).
        Eigen::MatrixXd cross = Eigen::MatrixXd::Zero(total, k);
        const Eigen::Index chunk = 256;
        Eigen::MatrixXd ys(chunk, k);
        std::vector<double> yrow(static_cast<std::size_t>(k));
        for (Eigen::Index i0 = 0; i0 < npts; i0 += chunk) {
            const Eigen::Index len = std::min(chunk, npts - i0);
            for (Eigen::Index i = 0; i < len; ++i) {
                const std::size_t ui = static_cast<std::size_t>(i0 + i);
                sh::eval_unit(bands, rule.x[ui], rule.y[ui], rule.z[ui], yrow.data());
                for (int c = 0; c < k; ++c)
                    ys(i, c) = w(i0 + i) * yrow[static_cast<std::size_t>(c)];
            }
            cross.noalias() += phib.middleRows(i0, len).transpose() * ys.topRows(len);
        }
        d_.resize(total, k);
        for (std::size_t r = 0; r < bases.size(); ++r) {
            const int o = offsets_[r], n = bases[r].n;
            const Eigen::MatrixXd g = gram_all.block(o, o, n, n);
            const Eigen::MatrixXd c = cross.middleRows(o, n);
            if (orthonormal[r]) {
                const double dev = (g - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff();
                if (!(dev <= 1e-10))
                    sphbasis::detail::throw_runtime(
                        "imse::ShFits",
                        "an orthonormal basis on the hemisphere, got max |G - I| = " +
                            std::to_string(dev));
                d_.middleRows(o, n) = c;
            } else {
                const GramSolver check(g);  // throws for dependent functions
                (void)check;
                Eigen::LLT<Eigen::MatrixXd> llt(g);
                d_.middleRows(o, n) = llt.matrixL().solve(c);
            }
        }
    }
    int bands() const noexcept { return bands_; }
    int rows() const noexcept { return static_cast<int>(offsets_.size()) - 1; }
    /// D of all rows stacked (sum of n x bands^2); rows of basis r start at offset(r).
    const Eigen::MatrixXd& d() const noexcept { return d_; }
    int offset(int r) const { return offsets_[static_cast<std::size_t>(r)]; }
    int size(int r) const {
        return offsets_[static_cast<std::size_t>(r) + 1] - offsets_[static_cast<std::size_t>(r)];
    }
    /// The fitted energy ||D_r e||^2 of every row for the columns of e (bands^2 x S): rows x S.
    Eigen::MatrixXd fitted_energy(const Eigen::MatrixXd& e) const {
        const Eigen::MatrixXd p = d_ * e;
        Eigen::MatrixXd out(rows(), e.cols());
        for (int r = 0; r < rows(); ++r)
            out.row(r) = p.middleRows(offset(r), size(r)).cwiseAbs2().colwise().sum();
        return out;
    }

  private:
    int bands_;
    std::vector<int> offsets_;
    Eigen::MatrixXd d_;
};

// ---------------------------------------------------------------------------------------------
// Fit protocol: fitted (non-linear) representations

/// The fitted rows of both protocols, after the linear ones: registry names of
/// all_fitted_bases() (L1 SH with the Geomerics reconstruction, ZH3 hallucinated, ZH3).
inline std::vector<std::string> fitted_rows() {
    return {"sh-l1-nonlinear", "zh3-hallucinate", "zh3"};
}

/// Funk-Hecke nodes of the fit protocol, and of its check (quad_err).
inline constexpr int fitted_nodes = 128;
inline constexpr int fitted_check_nodes = 256;

/// IMSE over the upper hemisphere of fitted representation f for a signal given as SH
/// coefficients e of gram.bands() bands (bands^2 values; bands >= 3): stored = f.fit(e),
/// r = f.sh_expansion(stored) to gram.bands() bands, IMSE = gram.energy(r - e). `tail` (if not
/// null) receives the squared sphere norm of r above gram.bands() bands, left out (for error
/// bounds: sqrt(IMSE) moves by at most its square root). Cost: O(bands^3) plus the expansion's.
inline double fitted_imse(const FittedBasisInfo& f, const HemisphereShGram& gram, const double* e,
                          int nodes = fitted_nodes, double* tail = nullptr) {
    const int b = gram.bands();
    if (b < 3)
        sphbasis::detail::throw_invalid("imse::fitted_imse",
                                        "a Gram matrix of >= 3 bands, got " + std::to_string(b));
    sphbasis::detail::check_buffer("imse::fitted_imse", "signal", e, std::size_t(b * b));
    double stored[16];
    f.fit(e, stored);
    std::vector<double> r(static_cast<std::size_t>(b * b));
    const double t = f.sh_expansion(stored, b, nodes, r.data());
    if (tail != nullptr) *tail = t;
    for (std::size_t k = 0; k < r.size(); ++k) r[k] -= e[k];
    return gram.energy(r.data());
}

/// The fit protocol on paper-protocol signals (9 x S radiance coefficients): the IMSE of each,
/// with the representation's expansion to `bands` bands (16: the Geomerics model's part above is
/// below 1e-9 of its energy; ZH3 is exact from 3).
inline Eigen::VectorXd fitted_imse_paper(const FittedBasisInfo& f, const Eigen::MatrixXd& radiance,
                                         int bands = 16, int nodes = fitted_nodes) {
    if (radiance.rows() != signal_coeffs)
        sphbasis::detail::throw_invalid(
            "imse::fitted_imse_paper",
            "9 radiance coefficients per column, got " + std::to_string(radiance.rows()));
    const HemisphereShGram gram(bands);
    const Eigen::VectorXd a = irradiance_factors();
    Eigen::VectorXd out(radiance.cols());
    std::vector<double> e(static_cast<std::size_t>(bands * bands), 0.0);
    for (Eigen::Index s = 0; s < radiance.cols(); ++s) {
        for (int k = 0; k < signal_coeffs; ++k)
            e[static_cast<std::size_t>(k)] = a(k) * radiance(k, s);
        out(s) = fitted_imse(f, gram, e.data(), nodes);
    }
    return out;
}

/// Rule sizes (nu, nphi) for ShFits that integrate <B, y_lm> to rounding for SH of `bands`
/// bands against bases of at most 25 functions: nu = bands + 20 (polynomial degree
/// 2 (bands - 1) + 9 in u, plus 16 nodes for the analytic factors, whose Gauss-Legendre error
/// falls like 4.6^(-2 nu)), nphi = bands + 8 (trigonometric degree <= bands - 1 + 4).
inline std::pair<int, int> hdri_rule_size(int bands) { return {bands + 20, bands + 8}; }

// ---------------------------------------------------------------------------------------------
// Spherical Gaussians as BakingLab bakes them (Pettineo, "SG Series" part 5, 2016): radiance
// sampled over the upper hemisphere, the amplitudes of a lobe set fitted to it by one of the
// solvers (ops/sg_fit.hpp), the irradiance at a normal reconstructed by Hill's approximation
// (sg::irradiance_fitted). Unlike the rows of paper_rows(), which fit the irradiance itself, this
// scores the pipeline a lightmap ships: the radiance below the horizon is never seen (the bake
// samples the texel's hemisphere), the fit is of radiance, and the irradiance is approximate.

/// The radiance samples of the SG pipeline: sqrt_count^2 directions on the upper hemisphere, one
/// per cell of a sqrt_count x sqrt_count grid on the square, jittered (mt19937_64, `seed`), mapped
/// by square_to_uniform_hemisphere (BakingLab's default is 25 x 25 samples per texel), 3 x N.
inline Eigen::Matrix3Xd sg_sample_directions(int sqrt_count = 25, std::uint64_t seed = 1) {
    sphbasis::detail::check_range("imse::sg_sample_directions", "sqrt_count", sqrt_count, 1, 4096);
    std::mt19937_64 gen(seed);
    auto u01 = [&] { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
    Eigen::Matrix3Xd d(3, sqrt_count * sqrt_count);
    for (int i = 0; i < sqrt_count; ++i)
        for (int j = 0; j < sqrt_count; ++j) {
            const double u = (i + u01()) / sqrt_count, v = (j + u01()) / sqrt_count;
            const double z = u, r = std::sqrt(std::max(0.0, 1 - z * z));
            const double phi = constants::two_pi * v;
            d.col(i * sqrt_count + j) << r * std::cos(phi), r * std::sin(phi), z;
        }
    return d;
}

/// The residual of BakingLab's SG pipeline for paper-protocol radiance (9 x S SH coefficients):
/// the radiance at `dirs` (3 x N, the hemisphere), the amplitudes of sg::bakinglab_lobes(count) by
/// `solver` (least squares and NNLS with equal weights, the running average in the columns'
/// order), the irradiance at the rule's points sum_k a_k sg::irradiance_fitted(G_k, n) / pi,
/// minus the exact irradiance there (rule.size() x S). Linear in the radiance for least squares
/// and the plain running average: then IMSE(c) = c^T Q c with Q = R^T W R, R the residuals of
/// the 9 unit signals.
inline Eigen::MatrixXd sg_pipeline_residuals(int count, sg::Solver solver,
                                             const Eigen::MatrixXd& radiance,
                                             const Eigen::Matrix3Xd& dirs,
                                             const DirectionalRule& rule = paper_rule()) {
    const auto lobes = sg::bakinglab_lobes(count);
    const Eigen::Index k = static_cast<Eigen::Index>(lobes.size());
    const Eigen::Index npts = static_cast<Eigen::Index>(rule.size());
    // Radiance at the sample directions: N x S.
    Eigen::MatrixXd ys(dirs.cols(), signal_coeffs);
    for (Eigen::Index i = 0; i < dirs.cols(); ++i) {
        double y[signal_coeffs];
        sh::eval_unit(3, dirs(0, i), dirs(1, i), dirs(2, i), y);
        for (int c = 0; c < signal_coeffs; ++c) ys(i, c) = y[c];
    }
    const Eigen::MatrixXd values = ys * radiance;
    Eigen::MatrixXd amp(k, radiance.cols());
    if (solver == sg::Solver::least_squares) {
        amp = sg::fit_least_squares(lobes, dirs, values);
    } else if (solver == sg::Solver::nnls) {
        amp = sg::fit_nnls(lobes, dirs, values);
    } else {
        // One estimator copied per signal: its construction integrates each lobe's square.
        const sg::RunningAverage fresh(lobes, 1, sg::Distribution::hemisphere,
                                       solver == sg::Solver::running_average_nn);
        for (Eigen::Index s = 0; s < radiance.cols(); ++s) {
            sg::RunningAverage ra = fresh;
            for (Eigen::Index i = 0; i < dirs.cols(); ++i) {
                const double v = values(i, s);
                ra.add(dirs(0, i), dirs(1, i), dirs(2, i), &v);
            }
            amp.col(s) = ra.amplitudes().col(0);
        }
    }
    // Hill's irradiance of each unit lobe at the rule's points over pi (the protocol's E is the
    // exitant radiance of a white Lambertian surface): npts x K.
    Eigen::MatrixXd hill(npts, k);
    for (Eigen::Index i = 0; i < npts; ++i) {
        const std::size_t u = static_cast<std::size_t>(i);
        for (Eigen::Index j = 0; j < k; ++j)
            hill(i, j) =
                constants::inv_pi * sg::irradiance_fitted(lobes[static_cast<std::size_t>(j)],
                                                          rule.x[u], rule.y[u], rule.z[u]);
    }
    return hill * amp - irradiance_samples(radiance, rule);
}

/// The IMSE of each signal (S values): the residuals of sg_pipeline_residuals() squared and
/// integrated by the rule.
inline Eigen::VectorXd sg_pipeline_imse(int count, sg::Solver solver,
                                        const Eigen::MatrixXd& radiance,
                                        const Eigen::Matrix3Xd& dirs,
                                        const DirectionalRule& rule = paper_rule()) {
    const Eigen::MatrixXd err = sg_pipeline_residuals(count, solver, radiance, dirs, rule);
    const Eigen::Map<const Eigen::VectorXd> w(rule.w.data(),
                                              static_cast<Eigen::Index>(rule.size()));
    return (w.asDiagonal() * err.cwiseAbs2()).colwise().sum().transpose();
}

/// The residual form Q (9 x 9) of a linear SG pipeline (least squares, plain running average):
/// IMSE(c) = c^T Q c.
inline Eigen::MatrixXd sg_pipeline_residual_form(int count, sg::Solver solver,
                                                 const Eigen::Matrix3Xd& dirs,
                                                 const DirectionalRule& rule = paper_rule()) {
    if (solver != sg::Solver::least_squares && solver != sg::Solver::running_average)
        sphbasis::detail::throw_invalid("imse::sg_pipeline_residual_form",
                                        "a linear solver (least squares, running average)");
    const Eigen::MatrixXd r = sg_pipeline_residuals(
        count, solver, Eigen::MatrixXd::Identity(signal_coeffs, signal_coeffs), dirs, rule);
    const Eigen::Map<const Eigen::VectorXd> w(rule.w.data(),
                                              static_cast<Eigen::Index>(rule.size()));
    const Eigen::MatrixXd q = r.transpose() * w.asDiagonal() * r;
    return 0.5 * (q + q.transpose());
}

}  // namespace sphbasis::imse
