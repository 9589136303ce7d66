// sphbasis: fitting the amplitudes of fixed spherical Gaussian lobes (basis/spherical_gaussian.hpp)
// to radiance, by the three solvers BakingLab offers for SG lightmaps (Pettineo, "SG Series"
// part 5, 2016; Pettineo and Neubelt, BakingLab):
//   * least squares: min_a sum_i w_i (sum_k a_k G_k(d_i) - f_i)^2 (BakingLab solves it by SVD;
//     here column-pivoted QR of the weighted design matrix, the same solution at full rank);
//   * non-negative least squares: the same with a_k >= 0 (Lawson and Hanson, "Solving Least
//     Squares Problems", 1974, chapter 23, algorithm NNLS, here on the K x K normal equations),
//     so that no lobe subtracts light;
//   * the running average (T. Roughton, "Spherical Gaussians", blog, 2018, as in BakingLab): one
//     pass over the samples, each lobe's amplitude a running mean of
//       (f_i - sum_{j != k} a_j G_j(d_i)) G_k(d_i) / mean(G_k^2),
//     whose fixed point solves the least-squares normal equations <f - sum a_j G_j, G_k> = 0 over
//     the sampled domain; mean(G_k^2) is the running mean of G_k(d_i)^2 clamped from below by
//     its exact value over the domain (BakingLab's variance guard). Optionally each amplitude is
//     clamped to >= 0 after every update (BakingLab's "running average, non-negative").
// Samples are directions (3 x S, unit) with values (S x C, C channels: 1 for a scalar signal,
// 3 for RGB) and optional weights (S; quadrature weights fit a function over a domain: use
// fit_function()). Amplitudes come back as K x C (K lobes).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "../basis/spherical_gaussian.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"

namespace sphbasis::sg {

namespace detail {
inline void check_samples(const char* fn, const std::vector<Lobe<double>>& lobes,
                          const Eigen::Matrix3Xd& dirs, const Eigen::MatrixXd& values,
                          const Eigen::VectorXd* weights) {
    if (lobes.empty()) sphbasis::detail::throw_invalid(fn, "at least one lobe");
    if (values.rows() != dirs.cols())
        sphbasis::detail::throw_invalid(fn, "one row of values per direction (" +
                                                std::to_string(dirs.cols()) + "), got " +
                                                std::to_string(values.rows()));
    if (weights && weights->size() != dirs.cols())
        sphbasis::detail::throw_invalid(fn, "one weight per direction (" +
                                                std::to_string(dirs.cols()) + "), got " +
                                                std::to_string(weights->size()));
    if (!dirs.allFinite() || !values.allFinite() || (weights && !weights->allFinite()))
        sphbasis::detail::throw_invalid(fn, "finite directions, values and weights");
    if (weights && (weights->array() < 0).any())
        sphbasis::detail::throw_invalid(fn, "non-negative weights");
}
}  // namespace detail

/// The design matrix A(i, k) = G_k(d_i) of the lobes' unit-amplitude shapes (S x K).
inline Eigen::MatrixXd design_matrix(const std::vector<Lobe<double>>& lobes,
                                     const Eigen::Matrix3Xd& dirs) {
    Eigen::MatrixXd a(dirs.cols(), static_cast<Eigen::Index>(lobes.size()));
    for (Eigen::Index k = 0; k < a.cols(); ++k) {
        Lobe<double> g = lobes[static_cast<std::size_t>(k)];
        g.amplitude = 1;
        for (Eigen::Index i = 0; i < a.rows(); ++i)
            a(i, k) = eval(g, dirs(0, i), dirs(1, i), dirs(2, i));
    }
    return a;
}

/// Least-squares amplitudes (K x C) of the lobes' shapes for the samples (see the header).
/// Throws std::invalid_argument for mismatched sizes, non-finite input or negative weights.
inline Eigen::MatrixXd fit_least_squares(const std::vector<Lobe<double>>& lobes,
                                         const Eigen::Matrix3Xd& dirs,
                                         const Eigen::MatrixXd& values,
                                         const Eigen::VectorXd& weights = Eigen::VectorXd()) {
    const bool w = weights.size() > 0;
    detail::check_samples("sg::fit_least_squares", lobes, dirs, values, w ? &weights : nullptr);
    Eigen::MatrixXd a = design_matrix(lobes, dirs);
    Eigen::MatrixXd b = values;
    if (w) {
        const Eigen::VectorXd s = weights.cwiseSqrt();
        a = s.asDiagonal() * a;
        b = s.asDiagonal() * b;
    }
    return a.colPivHouseholderQr().solve(b);
}

/// Lawson and Hanson's NNLS in the Gram form: min x^T G x - 2 h^T x subject to x >= 0, for G
/// = A^T A symmetric positive definite (n x n, small n) and h = A^T b, which is
/// min ||A x - b||^2, x >= 0. Active set: a variable enters where the gradient h - G x is
/// largest (above tol = 1e-13 max |h|), the passive set is solved by LDLT and shrunk along the
/// segment to stay feasible. Finite; capped at 3 n outer iterations (then the last feasible x).
inline Eigen::VectorXd nnls_gram(const Eigen::MatrixXd& g, const Eigen::VectorXd& h) {
    const Eigen::Index n = g.cols();
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<bool> passive(static_cast<std::size_t>(n), false);
    const double tol = 1e-13 * h.cwiseAbs().maxCoeff();
    auto is_passive = [&](Eigen::Index j) { return passive[static_cast<std::size_t>(j)]; };
    // The unconstrained minimum on the passive variables; zero elsewhere.
    auto solve_passive = [&]() {
        std::vector<Eigen::Index> idx;
        for (Eigen::Index j = 0; j < n; ++j)
            if (is_passive(j)) idx.push_back(j);
        const Eigen::Index m = static_cast<Eigen::Index>(idx.size());
        Eigen::MatrixXd gp(m, m);
        Eigen::VectorXd hp(m);
        for (Eigen::Index r = 0; r < m; ++r) {
            hp(r) = h(idx[static_cast<std::size_t>(r)]);
            for (Eigen::Index c = 0; c < m; ++c)
                gp(r, c) = g(idx[static_cast<std::size_t>(r)], idx[static_cast<std::size_t>(c)]);
        }
        const Eigen::VectorXd zp = gp.ldlt().solve(hp);
        Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
        for (Eigen::Index r = 0; r < m; ++r) z(idx[static_cast<std::size_t>(r)]) = zp(r);
        return z;
    };
    for (Eigen::Index iter = 0; iter < 3 * n; ++iter) {
        const Eigen::VectorXd w = h - g * x;
        Eigen::Index best = -1;
        for (Eigen::Index j = 0; j < n; ++j)
            if (!is_passive(j) && w(j) > tol && (best < 0 || w(j) > w(best))) best = j;
        if (best < 0) break;  // the Kuhn-Tucker conditions hold
        passive[static_cast<std::size_t>(best)] = true;
        for (Eigen::Index inner = 0; inner <= n; ++inner) {
            const Eigen::VectorXd z = solve_passive();
            double alpha = 1;
            bool feasible = true;
            for (Eigen::Index j = 0; j < n; ++j)
                if (is_passive(j) && z(j) <= 0) {
                    feasible = false;
                    alpha = std::min(alpha, x(j) / (x(j) - z(j)));
                }
            if (feasible) {
                x = z;
                break;
            }
            x += alpha * (z - x);
            for (Eigen::Index j = 0; j < n; ++j)
                if (is_passive(j) && x(j) <= 0) {
                    passive[static_cast<std::size_t>(j)] = false;
                    x(j) = 0;
                }
        }
    }
    return x;
}

/// Non-negative least-squares amplitudes (K x C), each channel on its own (see the header).
inline Eigen::MatrixXd fit_nnls(const std::vector<Lobe<double>>& lobes,
                                const Eigen::Matrix3Xd& dirs, const Eigen::MatrixXd& values,
                                const Eigen::VectorXd& weights = Eigen::VectorXd()) {
    const bool w = weights.size() > 0;
    detail::check_samples("sg::fit_nnls", lobes, dirs, values, w ? &weights : nullptr);
    Eigen::MatrixXd a = design_matrix(lobes, dirs);
    Eigen::MatrixXd b = values;
    if (w) {
        const Eigen::VectorXd s = weights.cwiseSqrt();
        a = s.asDiagonal() * a;
        b = s.asDiagonal() * b;
    }
    const Eigen::MatrixXd g = a.transpose() * a, h = a.transpose() * b;
    Eigen::MatrixXd out(a.cols(), b.cols());
    for (Eigen::Index c = 0; c < b.cols(); ++c) out.col(c) = nnls_gram(g, h.col(c));
    return out;
}

/// The mean of G^2 = exp(2 lambda (mu . v - 1)) over the domain: (1 - exp(-4 lambda)) / (4 lambda)
/// on the sphere; on the hemisphere z >= 0 by hemisphere_integral().
inline double squared_mean(const Lobe<double>& g, Distribution d) {
    if (d == Distribution::sphere) {
        const double l4 = 4 * g.sharpness;
        return l4 > 0 ? -std::expm1(-l4) / l4 : 1.0;
    }
    return hemisphere_integral(2 * g.sharpness, std::clamp(g.z, -1.0, 1.0), 0) / constants::two_pi;
}

/// Roughton's running average as BakingLab runs it (see the header): add() one sample at a time,
/// amplitudes() at any point. Samples should be uniform over the domain (the estimate weights
/// every sample equally).
class RunningAverage {
  public:
    RunningAverage(std::vector<Lobe<double>> lobes, int channels, Distribution domain,
                   bool non_negative = false)
        : lobes_(std::move(lobes)), channels_(channels), non_negative_(non_negative) {
        if (lobes_.empty())
            sphbasis::detail::throw_invalid("sg::RunningAverage", "at least one lobe");
        sphbasis::detail::check_range("sg::RunningAverage", "channels", channels, 1, 64);
        const Eigen::Index k = static_cast<Eigen::Index>(lobes_.size());
        amp_ = Eigen::MatrixXd::Zero(k, channels);
        sq_ = Eigen::VectorXd::Zero(k);
        g_.resize(k);
        estimate_.resize(channels);
        floor_.resize(k);
        for (Eigen::Index j = 0; j < k; ++j)
            floor_(j) = squared_mean(lobes_[static_cast<std::size_t>(j)], domain);
    }
    /// One sample: unit direction (x, y, z) and `channels` values.
    void add(double x, double y, double z, const double* value) {
        const Eigen::Index k = amp_.rows();
        const double scale = 1.0 / static_cast<double>(++count_);
        for (Eigen::Index j = 0; j < k; ++j) {
            Lobe<double> l = lobes_[static_cast<std::size_t>(j)];
            l.amplitude = 1;
            g_(j) = eval(l, x, y, z);
        }
        const Eigen::Map<const Eigen::RowVectorXd> f(value, channels_);
        // As BakingLab: the estimate of the sample stays the one from before its updates.
        estimate_.noalias() = g_.transpose() * amp_;
        for (Eigen::Index j = 0; j < k; ++j) {
            const double gj = g_(j);
            if (gj == 0) continue;
            sq_(j) += (gj * gj - sq_(j)) * scale;
            const double integral = std::max(sq_(j), floor_(j));
            // target = (f - (estimate - g_j a_j)) g_j / integral; a_j += (target - a_j) / n.
            amp_.row(j) +=
                ((f - (estimate_ - gj * amp_.row(j))) * (gj / integral) - amp_.row(j)) * scale;
            if (non_negative_) amp_.row(j) = amp_.row(j).cwiseMax(0.0);
        }
    }
    const Eigen::MatrixXd& amplitudes() const noexcept { return amp_; }
    long long samples() const noexcept { return count_; }

  private:
    std::vector<Lobe<double>> lobes_;
    int channels_;
    bool non_negative_;
    long long count_ = 0;
    Eigen::MatrixXd amp_;
    Eigen::VectorXd sq_, floor_, g_;
    Eigen::RowVectorXd estimate_;
};

/// The solvers by name, for tools: least squares, non-negative least squares, running average.
enum class Solver { least_squares, nnls, running_average, running_average_nn };

/// Fits a function over a domain: f sampled at a DirectionalRule's points (rule.size() x C),
/// the rule's weights as the least-squares weights (least_squares, nnls), or the points in the
/// rule's order as the running average's samples (its weights ignored: use an equal-weight
/// rule, e.g. uniformly random directions).
inline Eigen::MatrixXd fit_function(const std::vector<Lobe<double>>& lobes,
                                    const DirectionalRule& rule, const Eigen::MatrixXd& values,
                                    Solver solver, Distribution domain = Distribution::hemisphere) {
    const Eigen::Index s = static_cast<Eigen::Index>(rule.size());
    Eigen::Matrix3Xd dirs(3, s);
    for (Eigen::Index i = 0; i < s; ++i) {
        const std::size_t u = static_cast<std::size_t>(i);
        dirs.col(i) << rule.x[u], rule.y[u], rule.z[u];
    }
    const Eigen::VectorXd w =
        Eigen::Map<const Eigen::VectorXd>(rule.w.data(), static_cast<Eigen::Index>(s));
    switch (solver) {
        case Solver::least_squares:
            return fit_least_squares(lobes, dirs, values, w);
        case Solver::nnls:
            return fit_nnls(lobes, dirs, values, w);
        default:
            break;
    }
    detail::check_samples("sg::fit_function", lobes, dirs, values, nullptr);
    RunningAverage ra(lobes, static_cast<int>(values.cols()), domain,
                      solver == Solver::running_average_nn);
    const Eigen::MatrixXd rowmajor = values;  // column access per sample below
    std::vector<double> v(static_cast<std::size_t>(values.cols()));
    for (Eigen::Index i = 0; i < s; ++i) {
        for (Eigen::Index c = 0; c < values.cols(); ++c)
            v[static_cast<std::size_t>(c)] = rowmajor(i, c);
        ra.add(dirs(0, i), dirs(1, i), dirs(2, i), v.data());
    }
    return ra.amplitudes();
}

}  // namespace sphbasis::sg
