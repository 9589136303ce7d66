// sphbasis: the IMSE basis comparison (integrated mean square error of an irradiance signal
// fitted in a basis over the upper hemisphere), as reusable pieces for the `sphbasis imse`
// benchmark and for users who want to score their own basis or signal.
//
// Reference: the source thesis (Ishmukhametov, "Irradiance Normal Mapping"), section 3.1,
// eq. (3.1):  IMSE = int_{Omega+} ( sum_i c_i B_i(n) - E(n) )^2 dn,  and section 2.2.1, eq. (2.3):
// the irradiance of radiance L = sum c_lm y_lm is E = sum a_l c_lm y_lm with the normalised
// clamped-cosine factors a_0 = 1, a_1 = 2/3, a_2 = 1/4 (Ramamoorthi & Hanrahan 2001, A_l / pi;
// E is the exitant radiance of a white Lambertian surface, the 1/pi folded into the kernel).
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
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../basis/registry.hpp"
#include "../basis/sh.hpp"
#include "../core/constants.hpp"
#include "../core/quadrature.hpp"
#include "projection.hpp"

namespace sphbasis::imse {

// ---------------------------------------------------------------------------------------------
// Kernel factors and quadrature

/// The normalised clamped-cosine factor a_l = A_l / pi of degree l >= 0 (thesis eq. 2.3;
/// Ramamoorthi & Hanrahan 2001): a_0 = 1, a_1 = 2/3, a_l = 0 for odd l > 1 and, for even l,
/// a_l = 2 (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * l! / (2^l ((l/2)!)^2), so a_2 = 1/4,
/// a_4 = -1/24, a_6 = 1/64; |a_l| ~ 1.6 l^(-5/2) decreases for even l >= 2. Throws
/// std::invalid_argument for l < 0.
inline double clamped_cosine(int l) {
    if (l < 0)
        throw std::invalid_argument("sphbasis::imse::clamped_cosine(): expected l >= 0, got " +
                                    std::to_string(l));
    if (l == 0) return 1;
    if (l == 1) return 2.0 / 3.0;
    if (l % 2) return 0;
    double r = 1;  // C(l, l/2) / 2^l, by r_l = r_{l-2} (l - 1) / l
    for (int k = 2; k <= l; k += 2) r *= static_cast<double>(k - 1) / k;
    const double sign = (l / 2) % 2 ? 1.0 : -1.0;  // (-1)^(l/2 - 1)
    return sign * 2 * r / (static_cast<double>(l + 2) * (l - 1));
}

// hemisphere_rule_sqrt(nu, nphi) lives in core/quadrature.hpp; the name is kept here too.
using sphbasis::hemisphere_rule_sqrt;

/// The rule of the paper protocol (nu = nphi = 32, 1024 points): bases up to 25 functions
/// against SH-9 signals (trigonometric degree <= 8, polynomial degree <= 8 in z) are integrated
/// to rounding; paper_check_rule() (nu = 64, nphi = 48) is the finer rule that demonstrates it.
inline DirectionalRule paper_rule() { return hemisphere_rule_sqrt(32, 32); }
inline DirectionalRule paper_check_rule() { return hemisphere_rule_sqrt(64, 48); }

// ---------------------------------------------------------------------------------------------
// The signal space and the fit

/// Number of radiance coefficients of the paper protocol: SH bands 0-2.
inline constexpr int signal_coeffs = 9;

/// The clamped-cosine factors per ACN coefficient, a_{l(k)} for k < count (count a square).
inline Eigen::VectorXd irradiance_factors(int count = signal_coeffs) {
    if (!SH::valid_count(count))
        throw std::invalid_argument(
            "sphbasis::imse::irradiance_factors(): expected a square number of coefficients, "
            "got " +
            std::to_string(count));
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

/// The least-squares fit of functions sampled on a rule's points, for one basis: precomputes
/// the evaluation matrix and the Gram factorisation once; then fits and scores many signals.
/// With orthonormal = true the fit is the orthogonal projection c = <B, f>, after checking that
/// the Gram matrix on the rule is the identity within `tolerance` (std::runtime_error if not:
/// the basis or the rule is wrong); otherwise G c = <B, f> (GramSolver: std::runtime_error if the
/// functions are dependent on the domain). Cost: rule.size() * n evaluations to build.
class Fit {
  public:
    Fit(const BasisFunctions& b, bool orthonormal, const DirectionalRule& rule,
        double tolerance = 1e-10)
        : n_(b.n),
          orthonormal_(orthonormal),
          w_(Eigen::Map<const Eigen::VectorXd>(rule.w.data(),
                                               static_cast<Eigen::Index>(rule.w.size()))),
          phi_(evaluation_matrix(b, rule)) {
        gram_ = phi_.transpose() * w_.asDiagonal() * phi_;
        if (orthonormal_) {
            const double dev = (gram_ - Eigen::MatrixXd::Identity(n_, n_)).cwiseAbs().maxCoeff();
            if (!(dev <= tolerance))
                throw std::runtime_error(
                    "sphbasis::imse::Fit(): expected an orthonormal basis on the rule's domain, "
                    "got max |G - I| = " +
                    std::to_string(dev));
        } else {
            solver_ = std::make_shared<GramSolver>(gram_);
        }
    }

    int size() const noexcept { return n_; }
    bool orthonormal() const noexcept { return orthonormal_; }
    /// Phi(i, k) = B_k(d_i) over the rule's points.
    const Eigen::MatrixXd& evaluation() const noexcept { return phi_; }
    /// G = Phi^T W Phi.
    const Eigen::MatrixXd& gram() const noexcept { return gram_; }

    /// Solves G c = r (or c = r for an orthonormal basis) for the right-hand sides r = <B, f>.
    Eigen::MatrixXd solve(const Eigen::MatrixXd& r) const {
        return orthonormal_ ? r : solver_->solve(r);
    }
    /// Least-squares coefficients (n x S) of S signals sampled on the rule's points
    /// (samples: rule.size() x S).
    Eigen::MatrixXd coefficients(const Eigen::MatrixXd& samples) const {
        check_rows(samples, "coefficients");
        return solve(phi_.transpose() * (w_.asDiagonal() * samples));
    }
    /// IMSE of each of S sampled signals: the squared residual of the fit integrated by the
    /// rule, sum_i w_i (sum_k c_k B_k(d_i) - f(d_i))^2. Never negative.
    Eigen::VectorXd imse(const Eigen::MatrixXd& samples) const {
        check_rows(samples, "imse");
        Eigen::VectorXd out(samples.cols());
        // In blocks of columns: the temporaries stay in cache and allocations small.
        const Eigen::Index block = 64;
        Eigen::MatrixXd r;
        for (Eigen::Index c0 = 0; c0 < samples.cols(); c0 += block) {
            const Eigen::Index len = std::min(block, samples.cols() - c0);
            const auto s = samples.middleCols(c0, len);
            r.noalias() = phi_ * solve(phi_.transpose() * (w_.asDiagonal() * s));
            r -= s;
            out.segment(c0, len) = (w_.asDiagonal() * r.cwiseAbs2()).colwise().sum().transpose();
        }
        return out;
    }
    /// The matrix T (n x m) that maps coefficients of the functions `from` to the fit's
    /// coefficients: T = G^-1 <B, from> (conversion()).
    Eigen::MatrixXd conversion(const Eigen::MatrixXd& from_evaluation) const {
        check_rows(from_evaluation, "conversion");
        return solve(phi_.transpose() * (w_.asDiagonal() * from_evaluation));
    }

  private:
    void check_rows(const Eigen::MatrixXd& m, const char* fn) const {
        if (m.rows() != phi_.rows())
            throw std::invalid_argument(std::string("sphbasis::imse::Fit::") + fn +
                                        "(): expected one row per rule point");
    }
    int n_;
    bool orthonormal_;
    Eigen::VectorXd w_;
    Eigen::MatrixXd phi_, gram_;
    std::shared_ptr<GramSolver> solver_;
};

/// The irradiance of the paper protocol sampled on the rule's points: for radiance SH-9
/// coefficients (9 x S), E(d_i) = sum_k a_l(k) c_k y_k(d_i) (rule.size() x S).
inline Eigen::MatrixXd irradiance_samples(const Eigen::MatrixXd& radiance,
                                          const DirectionalRule& rule) {
    if (radiance.rows() != signal_coeffs)
        throw std::invalid_argument(
            "sphbasis::imse::irradiance_samples(): expected 9 radiance coefficients per column");
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

/// IMSE of one signal computed the long way (thesis eq. 3.1): irradiance sampled on the rule,
/// least-squares fit, squared residual integrated by the rule.
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
        throw std::invalid_argument("sphbasis::imse::random_radiance(): expected count >= 0");
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

namespace detail {

/// Fully normalised associated Legendre functions without the Condon-Shortley phase,
/// Pbar_l^m(cos t) with 2 pi int_{-1}^{1} Pbar^2 dz = 1, so that y_l0 = Pbar_l^0 and
/// y_lm = sqrt(2) Pbar_l^|m| cos(m phi) / sin(|m| phi) are the library's SH (sh.hpp).
/// Values for 0 <= m <= l < bands, order-major: (l, m) at index(l, m), contiguous in l.
/// Sectoral values that underflow (sin^m t below 1e-300 near the poles) end the m loop: the
/// functions they start are negligible there (below ~1e-280 for any l < bands <= 4096).
class Legendre {
  public:
    explicit Legendre(int bands) : bands_(bands) {
        a_.assign(size(), 0.0);
        b_.assign(size(), 0.0);
        for (int m = 0; m < bands; ++m)
            for (int l = m + 2; l < bands; ++l) {
                const double ll = l, mm = m;
                a_[index(l, m)] = std::sqrt((4 * ll * ll - 1) / (ll * ll - mm * mm));
                b_[index(l, m)] =
                    std::sqrt(((ll - 1) * (ll - 1) - mm * mm) / (4 * (ll - 1) * (ll - 1) - 1));
            }
    }
    int bands() const noexcept { return bands_; }
    /// Number of values, bands (bands + 1) / 2.
    std::size_t size() const noexcept {
        return static_cast<std::size_t>(bands_) * static_cast<std::size_t>(bands_ + 1) / 2;
    }
    /// Position of (l, m), 0 <= m <= l < bands: m bands - m (m - 1) / 2 + l - m.
    std::size_t index(int l, int m) const noexcept {
        const long long mm = m;
        return static_cast<std::size_t>(mm * bands_ - mm * (mm - 1) / 2 + (l - m));
    }

    /// Fills out[0 .. size()) from z = cos t and s = sin t >= 0 (zeros where the sectoral
    /// value underflowed); returns the number of orders m computed.
    int eval(double z, double s, double* out) const {
        std::fill(out, out + size(), 0.0);
        double pmm = constants::inv_sqrt_four_pi;
        int m = 0;
        for (; m < bands_; ++m) {
            if (m > 0) pmm *= std::sqrt((2.0 * m + 1) / (2.0 * m)) * s;
            if (std::fabs(pmm) < 1e-300) break;
            double* o = out + index(m, m);
            o[0] = pmm;
            if (m + 1 >= bands_) continue;
            const double* a = a_.data() + index(m, m);
            const double* b = b_.data() + index(m, m);
            double p1 = pmm, p2 = std::sqrt(2.0 * m + 3) * z * pmm;
            o[1] = p2;
            for (int k = 2; k < bands_ - m; ++k) {
                const double p = a[k] * (z * p2 - b[k] * p1);
                o[k] = p;
                p1 = p2;
                p2 = p;
            }
        }
        return m;
    }

    /// out[index(l, m)] = sum_g w[g] Pbar_l^m(z[g]) for up to 8 points at once (the
    /// recurrences run interleaved, which hides their latency). Same underflow rule as eval().
    void eval_weighted_sum(int count, const double* z, const double* s, const double* w,
                           double* out) const {
        constexpr int G = 8;
        SPHBASIS_ASSERT(count >= 1 && count <= G);
        std::fill(out, out + size(), 0.0);
        double zz[G], ss[G], ww[G], pmm[G], p1[G], p2[G];
        for (int g = 0; g < G; ++g) {
            const bool on = g < count;
            zz[g] = on ? z[g] : 0.0;
            ss[g] = on ? s[g] : 0.0;
            ww[g] = on ? w[g] : 0.0;
            pmm[g] = on ? constants::inv_sqrt_four_pi : 0.0;
        }
        for (int m = 0; m < bands_; ++m) {
            double big = 0;
            if (m > 0) {
                const double f = std::sqrt((2.0 * m + 1) / (2.0 * m));
                for (int g = 0; g < G; ++g) {
                    pmm[g] *= f * ss[g];
                    if (std::fabs(pmm[g]) < 1e-300) pmm[g] = 0;  // no denormals
                }
            }
            for (int g = 0; g < G; ++g) big = std::max(big, std::fabs(pmm[g]));
            if (big == 0) break;
            double* o = out + index(m, m);
            const double* a = a_.data() + index(m, m);
            const double* b = b_.data() + index(m, m);
            const double c1 = std::sqrt(2.0 * m + 3);
            double s0 = 0, s1 = 0;
            for (int g = 0; g < G; ++g) {
                p1[g] = pmm[g];
                p2[g] = c1 * zz[g] * pmm[g];
                s0 += ww[g] * p1[g];
                s1 += ww[g] * p2[g];
            }
            o[0] = s0;
            if (m + 1 >= bands_) continue;
            o[1] = s1;
            for (int k = 2; k < bands_ - m; ++k) {
                double acc = 0;
                for (int g = 0; g < G; ++g) {
                    const double p = a[k] * (zz[g] * p2[g] - b[k] * p1[g]);
                    p1[g] = p2[g];
                    p2[g] = p;
                    acc += ww[g] * p;
                }
                o[k] = acc;
            }
        }
    }

  private:
    int bands_;
    std::vector<double> a_, b_;
};

/// In-place radix-2 FFT, X_k = sum_j x_j exp(-2 pi i j k / n), n a power of two.
inline void fft(std::vector<std::complex<double>>& x) {
    const std::size_t n = x.size();
    for (std::size_t i = 1, j = 0; i < n; ++i) {
        std::size_t bit = n >> 1;
        for (; j & bit; bit >>= 1) j ^= bit;
        j ^= bit;
        if (i < j) std::swap(x[i], x[j]);
    }
    for (std::size_t len = 2; len <= n; len <<= 1) {
        const double ang = -constants::two_pi / static_cast<double>(len);
        for (std::size_t i = 0; i < n; i += len)
            for (std::size_t k = 0; k < len / 2; ++k) {
                // Twiddles from std::polar each time: no accumulated rounding.
                const std::complex<double> w = std::polar(1.0, ang * static_cast<double>(k));
                const std::complex<double> a = x[i + k], b = x[i + k + len / 2] * w;
                x[i + k] = a + b;
                x[i + k + len / 2] = a - b;
            }
    }
}

}  // namespace detail

/// A latitude-longitude map of one channel with piecewise-constant texels: texel (i, j)
/// (column i < width, row j < height, row-major values[j * width + i]) is the radiance over
/// phi in [2 pi i / width, 2 pi (i + 1) / width), theta in [pi j / height, pi (j + 1) / height],
/// theta the polar angle from +z (row 0 at the north pole), as param/latlong.hpp.
struct LatLongMap {
    int width = 0, height = 0;
    std::vector<double> values;
};

/// Squared L2 norm over the sphere of the map's piecewise-constant radiance, exact:
/// sum L_ij^2 * (2 pi / width) (cos theta_j - cos theta_j+1).
inline double squared_norm(const LatLongMap& map) {
    if (map.width < 1 || map.height < 1 ||
        map.values.size() !=
            static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height))
        throw std::invalid_argument(
            "sphbasis::imse::squared_norm(): expected width x height values");
    double s = 0;
    for (int j = 0; j < map.height; ++j) {
        const double t0 = constants::pi * j / map.height, t1 = constants::pi * (j + 1) / map.height;
        const double omega = constants::two_pi / map.width * (std::cos(t0) - std::cos(t1));
        double row = 0;
        for (int i = 0; i < map.width; ++i) {
            const double v =
                map.values[static_cast<std::size_t>(j) * static_cast<std::size_t>(map.width) +
                           static_cast<std::size_t>(i)];
            row += v * v;
        }
        s += row * omega;
    }
    return s;
}

/// SH coefficients (bands^2, ACN, the library's convention) of the map's piecewise-constant
/// radiance: L_lm = sum_texels L_ij int_texel y_lm dw with the texel integrals done exactly in
/// phi (int cos(m phi) over a texel = 2 sin(m dphi / 2)/m cos(m phi_centre), via one FFT per row)
/// and by Gauss-Legendre in theta with `theta_nodes` nodes per row (integrand
/// Pbar(cos t) sin t, smooth in t: for a row of height h the relative error is about
/// (l h)^(2 theta_nodes) / (2 theta_nodes)!, below 1e-13 for l h < 1.2 at 6 nodes). Cost
/// O(height * theta_nodes * bands^2) plus one FFT of the width per row (a direct DFT when the
/// width is not a power of two). Throws std::invalid_argument for an empty or inconsistent map
/// or bands < 1.
inline std::vector<double> latlong_to_sh(const LatLongMap& map, int bands, int theta_nodes = 6) {
    if (map.width < 1 || map.height < 1 ||
        map.values.size() !=
            static_cast<std::size_t>(map.width) * static_cast<std::size_t>(map.height) ||
        bands < 1 || bands > 4096 || theta_nodes < 1)
        throw std::invalid_argument(
            "sphbasis::imse::latlong_to_sh(): expected width x height values, 1 <= bands <= "
            "4096 and theta_nodes >= 1");
    const int w = map.width, h = map.height;
    const double dphi = constants::two_pi / w;
    const detail::Legendre leg(bands);
    std::vector<double> gt, gw;
    gauss_legendre(theta_nodes, gt, gw);
    // Accumulators in the Legendre layout (contiguous in l for each m): cos and sin parts.
    const std::size_t ntri = leg.size();
    std::vector<double> cc(ntri, 0.0), ss(ntri, 0.0), p(ntri);
    // Per row: fc[m], fs[m] = sum_i L_ij int_texel (cos m phi, sin m phi) dphi.
    std::vector<double> fc(static_cast<std::size_t>(bands)), fs(static_cast<std::size_t>(bands));
    std::vector<std::complex<double>> buf(static_cast<std::size_t>(w));
    const bool pow2 = (w & (w - 1)) == 0;
    for (int j = 0; j < h; ++j) {
        const double* row =
            map.values.data() + static_cast<std::size_t>(j) * static_cast<std::size_t>(w);
        if (pow2) {
            for (int i = 0; i < w; ++i) buf[static_cast<std::size_t>(i)] = row[i];
            detail::fft(buf);
        } else {
            for (int k = 0; k < std::min(w, bands); ++k) {
                std::complex<double> acc = 0;
                for (int i = 0; i < w; ++i) {
                    const long long ik = (static_cast<long long>(i) * k) % w;
                    acc +=
                        row[i] * std::polar(1.0, -constants::two_pi * static_cast<double>(ik) / w);
                }
                buf[static_cast<std::size_t>(k)] = acc;
            }
        }
        for (int m = 0; m < bands; ++m) {
            // sum_i L_i e^{i m phi_i} with phi_i = (i + 1/2) dphi is e^{i m dphi/2} conj(X_m),
            // X periodic in m with period w.
            const std::complex<double> xm = buf[static_cast<std::size_t>(m % w)];
            const std::complex<double> e = std::polar(1.0, 0.5 * m * dphi) * std::conj(xm);
            const double box = m == 0 ? dphi : 2 * std::sin(0.5 * m * dphi) / m;
            const double norm = m == 0 ? 1.0 : constants::sqrt2;
            fc[static_cast<std::size_t>(m)] = norm * box * e.real();
            fs[static_cast<std::size_t>(m)] = norm * box * e.imag();
        }
        // Row integrals of Pbar_l^m(cos t) sin t over [t0, t1], Gauss-Legendre in t.
        const double t0 = constants::pi * j / h, t1 = constants::pi * (j + 1) / h;
        for (std::size_t g0 = 0; g0 < gt.size(); g0 += 8) {
            const int cnt = static_cast<int>(std::min<std::size_t>(8, gt.size() - g0));
            double zs[8], ssn[8], ws[8];
            for (int g = 0; g < cnt; ++g) {
                const std::size_t ug = g0 + static_cast<std::size_t>(g);
                const double t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * gt[ug];
                zs[g] = std::cos(t);
                ssn[g] = std::sin(t);
                ws[g] = 0.5 * (t1 - t0) * gw[ug] * ssn[g];
            }
            leg.eval_weighted_sum(cnt, zs, ssn, ws, p.data());
            for (int m = 0; m < bands; ++m) {
                const double c = fc[static_cast<std::size_t>(m)];
                const double s = fs[static_cast<std::size_t>(m)];
                const std::size_t k0 = leg.index(m, m);
                double* cm = cc.data() + k0;
                double* sm = ss.data() + k0;
                const double* pm = p.data() + k0;
                for (int k = 0; k < bands - m; ++k) {
                    cm[k] += c * pm[k];
                    sm[k] += s * pm[k];
                }
            }
        }
    }
    std::vector<double> coef(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands),
                             0.0);
    for (int l = 0; l < bands; ++l)
        for (int m = 0; m <= l; ++m) {
            const std::size_t k = leg.index(l, m);
            coef[static_cast<std::size_t>(sh::index(l, m))] = cc[k];
            if (m) coef[static_cast<std::size_t>(sh::index(l, -m))] = ss[k];
        }
    return coef;
}

/// Energy per band, e_l = sum_m c_lm^2, of SH coefficients of `bands` bands.
inline std::vector<double> band_energies(const std::vector<double>& coeffs, int bands) {
    std::vector<double> e(static_cast<std::size_t>(bands), 0.0);
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const double c = coeffs[static_cast<std::size_t>(sh::index(l, m))];
            e[static_cast<std::size_t>(l)] += c * c;
        }
    return e;
}

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
        throw std::invalid_argument(
            "sphbasis::imse::truncation_bound(): expected 1 <= bands <= energies.size()");
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
            throw std::invalid_argument(
                "sphbasis::imse::HemisphereShGram(): expected 1 <= bands <= 1024");
        std::vector<double> t, w;
        gauss_legendre(bands + 1, t, w);
        const detail::Legendre leg(bands);
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
            throw std::invalid_argument(
                "sphbasis::imse::ShFits(): expected one orthonormal flag per basis");
        const DirectionalRule rule = hemisphere_rule_sqrt(nu, nphi);
        const Eigen::Index npts = static_cast<Eigen::Index>(rule.size());
        const int k = bands * bands;
        int total = 0;
        for (const auto& b : bases) {
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
                    throw std::runtime_error(
                        "sphbasis::imse::ShFits(): expected an orthonormal basis on the "
                        "hemisphere, got max |G - I| = " +
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

/// Rule sizes (nu, nphi) for ShFits that integrate <B, y_lm> to rounding for SH of `bands`
/// bands against bases of at most 25 functions: nu = bands + 20 (polynomial degree
/// 2 (bands - 1) + 9 in u, plus 16 nodes for the analytic factors, whose Gauss-Legendre error
/// falls like 4.6^(-2 nu)), nphi = bands + 8 (trigonometric degree <= bands - 1 + 4).
inline std::pair<int, int> hdri_rule_size(int bands) { return {bands + 20, bands + 8}; }

}  // namespace sphbasis::imse
