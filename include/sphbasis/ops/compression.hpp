// sphbasis: compression of per-point bakes (per-vertex or per-texel visibility, transfer vectors,
// transfer matrices) by PCA and clustered PCA (CPCA), quantization of the weights, and rendering
// from the compressed form.
//
// Data: a matrix X with one row per point (vertex or texel) and one column per component of the
// per-point vector (n² visibility coefficients, 3n² RGB transfer, the entries of a transfer
// matrix). A model approximates row p as
//     x_p ~ mu_c + sum_{j<M} w_pj b_cj          (c = the point's cluster; one cluster for PCA)
// with an orthonormal basis b_c0..b_c(M-1) per cluster: Sloan, Lehtinen and Kautz,
// "Precomputed Radiance Transfer: Theory and Practice" (SIGGRAPH 2005 course), the PCA and CPCA
// slides; Sloan, Hall, Hart and Snyder, "Clustered Principal Components for Precomputed Radiance
// Transfer" (SIGGRAPH 2003); Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed
// Visibility" (JGT 2009), eq. 5-6 (mean visibility + M basis vectors, per-texel weights).
//
//   compress::pca():            mean + M principal vectors, per-point weights w = (x - mu) B.
//   compress::cpca_static():    VQ (Lloyd's k-means, k-means++ seeding from a fixed seed) into C
//                               clusters, then one PCA per cluster ("static PCA" of the course).
//   compress::cpca_iterative(): from the static result, reclassify each point to the cluster
//                               whose affine subspace (mean + span of its M vectors) reconstructs
//                               it best, refit each cluster's PCA, repeat ("iterative PCA";
//                               Kambhatla and Leen's VQPCA). Each step cannot raise the squared
//                               error in exact arithmetic (the reclassification picks each point's
//                               best cluster, the refit is optimal for the assignment); a step
//                               that rises by rounding is rejected, so error_history is
//                               non-increasing.
//   compress::quantize():       weights to 8 or 16 bits: per cluster and basis vector the scale
//                               s = max |w| maps the weights into [-1, 1] (the course's "scale the
//                               corresponding basis vector by the inverse"), code = round(w/s * q)
//                               with q = 127 or 32767.
//                               Error bound: |w - dequantized w| <= s / (2q) (half a step) per
//                               weight, so a point's reconstruction moves by at most
//                               sum_j s_j/(2q) * |b_j| (|b_j| = 1, orthonormal), and a shaded value
//                               x.l by at most sum_j s_j/(2q) * |b_j . l| (quantization_bound()).
//   compress::exit_values() / shade(): rendering (the course's "Rendering with CPCA"): for a
//                               lighting matrix L (columns x K; K = 1 for a lighting vector, 3
//                               for RGB), the per-cluster exit values mu_c L and b_cj L are
//                               computed once per lighting, and a point's shaded value is
//                               mu_c L + sum_j w_pj (b_cj L): M multiply-adds per output.
//
// Decomposition (PcaMethod): `svd` runs Eigen's BDCSVD on the centred data (only V is computed):
// backward stable, small singular values accurate to ~eps * s_max, so the rank and the lossless
// full-rank reconstruction are exact to rounding; cost O(P c^2) with a larger constant and a
// P x c copy. The SVD runs in double for float data too, and its results are rounded: one
// BDCSVD instantiation per program, which costs 45 s of compiler time per scalar type at -O3.
// `covariance` forms the c x c scatter matrix (one GEMM, O(P c^2), cache friendly) and runs
// SelfAdjointEigenSolver on it: several times faster for P >> c, but squaring the condition
// number makes singular values below ~sqrt(eps) * s_max unreliable (the rank tolerance is
// raised accordingly). pca() defaults to `svd` (a one-shot call: accuracy first); the CPCA loops
// use `covariance` for the many small per-cluster fits (speed; the span of the leading
// eigenvectors is what matters there, not the small singular values).
//
// Rank: the number of singular values of the centred data above tol * s_max, tol =
// max(P, c) * eps for `svd` and sqrt(max(P, c) * eps) for `covariance` (Scalar's eps). M must be
// <= min(rank, c) (else std::invalid_argument naming which bound).
//
// Costs: pca O(P c^2 + c^3). cpca_static: k-means O(P C c) per Lloyd iteration (one GEMM) +
// per-cluster PCA O(P c^2 + C c^3). cpca_iterative: per iteration O(P C c M) for the
// reclassification + O(P c^2 + C c^3) for the refits: linear in the number of points.
// Stored numbers: PCA c (mean) + M c (vectors) + P M (weights); CPCA C (c + M c) + P M, plus one
// cluster index per point (stored_indices()).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "../core/error.hpp"

namespace sphbasis::compress {

template <class Scalar>
using MatrixX = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
template <class Scalar>
using RowVectorX = Eigen::Matrix<Scalar, 1, Eigen::Dynamic>;

/// How pca() decomposes the centred data (see the header comment).
enum class PcaMethod { svd, covariance };

/// A PCA model: x_p ~ mean + weights.row(p) * basis^T.
template <class Scalar = double>
struct Pca {
    RowVectorX<Scalar> mean;             ///< 1 x c
    MatrixX<Scalar> basis;               ///< c x M, orthonormal columns, by decreasing energy
    MatrixX<Scalar> weights;             ///< P x M
    RowVectorX<Scalar> singular_values;  ///< all min(P, c) singular values of the centred data
    int rank = 0;                        ///< numerical rank of the centred data

    int vectors() const { return static_cast<int>(basis.cols()); }
    /// P x c reconstruction mean + W B^T.
    MatrixX<Scalar> reconstruct() const { return (weights * basis.transpose()).rowwise() + mean; }
    /// Squared error predicted by the dropped singular values: sum_{i >= M} s_i^2.
    double dropped_energy() const {
        double e = 0;
        for (Eigen::Index i = basis.cols(); i < singular_values.size(); ++i)
            e += static_cast<double>(singular_values(i)) * static_cast<double>(singular_values(i));
        return e;
    }
    /// Numbers stored: c + M c + P M.
    long long stored_numbers() const {
        return static_cast<long long>(mean.size()) * (1 + basis.cols()) +
               static_cast<long long>(weights.rows()) * weights.cols();
    }
};

/// A CPCA model (C clusters x M vectors); a PCA is the case C = 1 (as_cpca()).
template <class Scalar = double>
struct Cpca {
    std::vector<int> cluster;            ///< P cluster indices in [0, C)
    MatrixX<Scalar> means;               ///< C x c
    std::vector<MatrixX<Scalar>> bases;  ///< C matrices c x M, orthonormal columns
    MatrixX<Scalar> weights;             ///< P x M, in the point's cluster's basis
    std::vector<double> error_history;   ///< squared error: [0] static, then each accepted
                                         ///< iteration (non-increasing)
    int iterations = 0;                  ///< accepted reclassification steps
    int lloyd_iterations = 0;            ///< k-means iterations of the static stage

    int clusters() const { return static_cast<int>(means.rows()); }
    int vectors() const { return static_cast<int>(weights.cols()); }
    MatrixX<Scalar> reconstruct() const {
        MatrixX<Scalar> r(weights.rows(), means.cols());
        for (Eigen::Index p = 0; p < weights.rows(); ++p) {
            const auto c = static_cast<std::size_t>(cluster[static_cast<std::size_t>(p)]);
            r.row(p) =
                means.row(static_cast<Eigen::Index>(c)) + weights.row(p) * bases[c].transpose();
        }
        return r;
    }
    /// Numbers stored: C (c + M c) + P M (the cluster indices are stored_indices()).
    long long stored_numbers() const {
        return static_cast<long long>(means.rows()) * means.cols() * (1 + weights.cols()) +
               static_cast<long long>(weights.rows()) * weights.cols();
    }
    long long stored_indices() const { return static_cast<long long>(cluster.size()); }
};

/// Settings of cpca_static() / cpca_iterative().
struct CpcaSettings {
    int clusters = 16;                    ///< C >= 1, <= number of points
    int vectors = 4;                      ///< M >= 1, <= min(rank, c)
    std::uint64_t seed = 1;               ///< k-means++ seeding (a fixed std::mt19937_64 stream)
    int lloyd_iterations = 100;           ///< k-means iteration cap
    int max_iterations = 30;              ///< iterative CPCA: reclassification cap
    double min_relative_decrease = 1e-9;  ///< iterative CPCA: stop when the error falls less
};

/// ||a - b||_F^2 in double.
template <class A, class B>
double squared_error(const Eigen::MatrixBase<A>& a, const Eigen::MatrixBase<B>& b) {
    double e = 0;
    for (Eigen::Index j = 0; j < a.cols(); ++j)
        for (Eigen::Index i = 0; i < a.rows(); ++i) {
            const double d = static_cast<double>(a(i, j)) - static_cast<double>(b(i, j));
            e += d * d;
        }
    return e;
}

namespace detail {

template <class Derived>
void check_data(const Eigen::MatrixBase<Derived>& x, const char* fn) {
    if (x.rows() < 1 || x.cols() < 1)
        sphbasis::detail::throw_invalid(fn, "non-empty data (points x components), got " +
                                                std::to_string(x.rows()) + " x " +
                                                std::to_string(x.cols()));
    for (Eigen::Index j = 0; j < x.cols(); ++j)
        for (Eigen::Index i = 0; i < x.rows(); ++i)
            if (!std::isfinite(static_cast<double>(x(i, j))))
                sphbasis::detail::throw_invalid(
                    fn, "finite data, got " + std::to_string(static_cast<double>(x(i, j))) +
                            " at point " + std::to_string(i) + ", component " + std::to_string(j));
}

template <class Scalar>
void check_vectors(int m, int rank, Eigen::Index cols, const char* fn) {
    if (m < 1)
        sphbasis::detail::throw_invalid(fn, "M >= 1 basis vectors, got M = " + std::to_string(m));
    if (m > cols)
        sphbasis::detail::throw_invalid(fn, "M <= the number of columns (" + std::to_string(cols) +
                                                ") basis vectors, got M = " + std::to_string(m));
    if (m > rank)
        sphbasis::detail::throw_invalid(fn, "M <= the rank of the centred data (" +
                                                std::to_string(rank) +
                                                ") basis vectors, got M = " + std::to_string(m));
}

/// Full decomposition of the centred data: V (c x k, by decreasing singular value), singular
/// values, rank.
template <class Scalar>
void decompose(const MatrixX<Scalar>& centred, PcaMethod method, MatrixX<Scalar>& v,
               RowVectorX<Scalar>& s, int& rank) {
    const Eigen::Index p = centred.rows(), c = centred.cols();
    const double eps = static_cast<double>(std::numeric_limits<Scalar>::epsilon());
    const double n = static_cast<double>(std::max(p, c));
    double tol;
    if (method == PcaMethod::svd) {
        const Eigen::BDCSVD<MatrixX<double>> svd(centred.template cast<double>(),
                                                 Eigen::ComputeThinV);
        v = svd.matrixV().template cast<Scalar>();
        s = svd.singularValues().transpose().template cast<Scalar>();
        tol = n * eps;
    } else {
        const MatrixX<Scalar> scatter = centred.transpose() * centred;
        Eigen::SelfAdjointEigenSolver<MatrixX<Scalar>> es(scatter);
        // Ascending eigenvalues: reverse.
        v.resize(c, c);
        for (Eigen::Index j = 0; j < c; ++j) v.col(j) = es.eigenvectors().col(c - 1 - j);
        const Eigen::Index k = std::min(p, c);
        s.resize(k);
        for (Eigen::Index i = 0; i < k; ++i)
            s(i) = std::sqrt(std::max(Scalar(0), es.eigenvalues()(c - 1 - i)));
        tol = std::sqrt(n * eps);
    }
    rank = 0;
    const double smax = s.size() > 0 ? static_cast<double>(s(0)) : 0.0;
    for (Eigen::Index i = 0; i < s.size(); ++i)
        if (static_cast<double>(s(i)) > tol * smax && smax > 0) ++rank;
}

/// Per-cluster PCA that never throws: the top-M eigenvectors of the cluster's scatter (any
/// orthonormal completion where the cluster has rank < M: the extra directions cost nothing).
template <class Scalar>
void fit_cluster(const MatrixX<Scalar>& x, const std::vector<Eigen::Index>& members, int m,
                 MatrixX<Scalar>& means, int cl, MatrixX<Scalar>& basis) {
    const Eigen::Index c = x.cols();
    MatrixX<Scalar> centred(static_cast<Eigen::Index>(members.size()), c);
    for (std::size_t i = 0; i < members.size(); ++i)
        centred.row(static_cast<Eigen::Index>(i)) = x.row(members[i]);
    if (members.empty()) {
        basis = MatrixX<Scalar>::Identity(c, m);
        return;
    }
    means.row(cl) = centred.colwise().mean();
    centred.rowwise() -= RowVectorX<Scalar>(means.row(cl));
    const MatrixX<Scalar> scatter = centred.transpose() * centred;
    Eigen::SelfAdjointEigenSolver<MatrixX<Scalar>> es(scatter);
    basis.resize(c, m);
    for (Eigen::Index j = 0; j < m; ++j) basis.col(j) = es.eigenvectors().col(c - 1 - j);
}

/// Fits every cluster and the weights; returns the squared error.
template <class Scalar>
double fit_all(const MatrixX<Scalar>& x, int m, Cpca<Scalar>& model) {
    const int nc = model.clusters();
    std::vector<std::vector<Eigen::Index>> members(static_cast<std::size_t>(nc));
    for (Eigen::Index p = 0; p < x.rows(); ++p)
        members[static_cast<std::size_t>(model.cluster[static_cast<std::size_t>(p)])].push_back(p);
    model.bases.resize(static_cast<std::size_t>(nc));
    model.weights.resize(x.rows(), m);
    double err = 0;
    for (int c = 0; c < nc; ++c) {
        const auto& mem = members[static_cast<std::size_t>(c)];
        MatrixX<Scalar>& b = model.bases[static_cast<std::size_t>(c)];
        fit_cluster<Scalar>(x, mem, m, model.means, c, b);
        for (Eigen::Index p : mem) {
            const RowVectorX<Scalar> d = x.row(p) - model.means.row(c);
            const RowVectorX<Scalar> w = d * b;
            model.weights.row(p) = w;
            const RowVectorX<Scalar> r = d - w * b.transpose();
            err += static_cast<double>(r.squaredNorm());
        }
    }
    return err;
}

/// Uniform double in [0, 1) from the top 53 bits (std distributions differ between standard
/// libraries; this does not).
inline double uniform01(std::mt19937_64& rng) {
    return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

/// Squared distances P x C from the rows of x to the rows of centres (one GEMM).
template <class Scalar>
MatrixX<Scalar> squared_distances(const MatrixX<Scalar>& x, const RowVectorX<Scalar>& xn,
                                  const MatrixX<Scalar>& centres) {
    MatrixX<Scalar> d = Scalar(-2) * (x * centres.transpose());
    d.colwise() += xn.transpose();
    d.rowwise() += centres.rowwise().squaredNorm().transpose();
    return d;
}

/// Lloyd's k-means with k-means++ seeding; fills model.cluster and model.means.
template <class Scalar>
void kmeans(const MatrixX<Scalar>& x, const CpcaSettings& s, Cpca<Scalar>& model) {
    const Eigen::Index np = x.rows(), c = x.cols();
    const int k = s.clusters;
    std::mt19937_64 rng(s.seed);
    MatrixX<Scalar> centres(k, c);
    // k-means++: first centre uniform, the next ones with probability ~ D(x)^2.
    std::vector<double> d2(static_cast<std::size_t>(np));
    Eigen::Index first = std::min<Eigen::Index>(
        np - 1, static_cast<Eigen::Index>(uniform01(rng) * static_cast<double>(np)));
    centres.row(0) = x.row(first);
    for (Eigen::Index p = 0; p < np; ++p)
        d2[static_cast<std::size_t>(p)] =
            static_cast<double>((x.row(p) - centres.row(0)).squaredNorm());
    for (int j = 1; j < k; ++j) {
        double total = 0;
        for (double v : d2) total += v;
        Eigen::Index pick = 0;
        if (total > 0) {
            double t = uniform01(rng) * total;
            pick = np - 1;
            for (Eigen::Index p = 0; p < np; ++p) {
                t -= d2[static_cast<std::size_t>(p)];
                if (t < 0) {
                    pick = p;
                    break;
                }
            }
            // Rounding could land on a point at distance 0: step to one that is not.
            while (d2[static_cast<std::size_t>(pick)] <= 0 && pick > 0) --pick;
        } else {
            pick = std::min<Eigen::Index>(
                np - 1, static_cast<Eigen::Index>(uniform01(rng) * static_cast<double>(np)));
        }
        centres.row(j) = x.row(pick);
        for (Eigen::Index p = 0; p < np; ++p)
            d2[static_cast<std::size_t>(p)] =
                std::min(d2[static_cast<std::size_t>(p)],
                         static_cast<double>((x.row(p) - centres.row(j)).squaredNorm()));
    }
    const RowVectorX<Scalar> xn = x.rowwise().squaredNorm().transpose();
    std::vector<int> assign(static_cast<std::size_t>(np), -1);
    int it = 0;
    for (; it < s.lloyd_iterations; ++it) {
        const MatrixX<Scalar> d = squared_distances(x, xn, centres);
        bool changed = false;
        for (Eigen::Index p = 0; p < np; ++p) {
            Eigen::Index best;
            d.row(p).minCoeff(&best);
            if (assign[static_cast<std::size_t>(p)] != static_cast<int>(best)) {
                assign[static_cast<std::size_t>(p)] = static_cast<int>(best);
                changed = true;
            }
        }
        if (!changed) break;
        MatrixX<Scalar> sum = MatrixX<Scalar>::Zero(k, c);
        std::vector<Eigen::Index> count(static_cast<std::size_t>(k), 0);
        for (Eigen::Index p = 0; p < np; ++p) {
            sum.row(assign[static_cast<std::size_t>(p)]) += x.row(p);
            ++count[static_cast<std::size_t>(assign[static_cast<std::size_t>(p)])];
        }
        for (int j = 0; j < k; ++j) {
            if (count[static_cast<std::size_t>(j)] > 0) {
                centres.row(j) =
                    sum.row(j) / static_cast<Scalar>(count[static_cast<std::size_t>(j)]);
            } else {
                // Empty cluster: move it to the point farthest from its centre.
                Eigen::Index far = 0;
                Scalar best = -1;
                for (Eigen::Index p = 0; p < np; ++p) {
                    const Scalar v =
                        (x.row(p) - centres.row(assign[static_cast<std::size_t>(p)])).squaredNorm();
                    if (v > best) best = v, far = p;
                }
                centres.row(j) = x.row(far);
            }
        }
    }
    model.lloyd_iterations = it;
    model.cluster = std::move(assign);
    model.means = centres;
}

/// The static model of checked data x: k-means, then the per-cluster fits (error_history[0]).
template <class Scalar>
Cpca<Scalar> static_model(const MatrixX<Scalar>& x, const CpcaSettings& settings) {
    Cpca<Scalar> model;
    kmeans(x, settings, model);
    model.error_history = {fit_all(x, settings.vectors, model)};
    return model;
}

template <class Derived>
MatrixX<typename Derived::Scalar> checked_cpca_input(const Eigen::MatrixBase<Derived>& data,
                                                     const CpcaSettings& s, const char* fn) {
    using Scalar = typename Derived::Scalar;
    check_data(data, fn);
    if (s.clusters < 1)
        sphbasis::detail::throw_invalid(fn,
                                        "C >= 1 clusters, got C = " + std::to_string(s.clusters));
    if (s.clusters > data.rows())
        sphbasis::detail::throw_invalid(
            fn, "C <= the number of points (" + std::to_string(data.rows()) +
                    ") clusters, got C = " + std::to_string(s.clusters));
    MatrixX<Scalar> x = data;
    if (s.vectors < 1 || s.vectors > x.cols()) check_vectors<Scalar>(s.vectors, 0, x.cols(), fn);
    MatrixX<Scalar> centred = x.rowwise() - x.colwise().mean();
    MatrixX<Scalar> v;
    RowVectorX<Scalar> sv;
    int rank = 0;
    decompose<Scalar>(centred, PcaMethod::covariance, v, sv, rank);
    check_vectors<Scalar>(s.vectors, rank, x.cols(), fn);
    return x;
}

}  // namespace detail

/// PCA of the rows of `data` (P points x c components) with M = `vectors` principal vectors.
/// Throws std::invalid_argument for empty or non-finite data, M < 1, M > c or M > the rank of
/// the centred data. Cost O(P c^2 + c^3).
template <class Derived>
Pca<typename Derived::Scalar> pca(const Eigen::MatrixBase<Derived>& data, int vectors,
                                  PcaMethod method = PcaMethod::svd) {
    using Scalar = typename Derived::Scalar;
    static_assert(std::is_floating_point_v<Scalar>,
                  "sphbasis::compress::pca: the data must be float or double.");
    const char* fn = "compress::pca";
    detail::check_data(data, fn);
    if (vectors < 1 || vectors > data.cols())
        detail::check_vectors<Scalar>(vectors, 0, data.cols(), fn);
    Pca<Scalar> r;
    r.mean = data.colwise().mean();
    const MatrixX<Scalar> centred = data.rowwise() - r.mean;
    MatrixX<Scalar> v;
    detail::decompose<Scalar>(centred, method, v, r.singular_values, r.rank);
    detail::check_vectors<Scalar>(vectors, r.rank, data.cols(), fn);
    r.basis = v.leftCols(vectors);
    r.weights = centred * r.basis;
    return r;
}

/// The PCA as a one-cluster CPCA model (for quantize(), exit_values(), shade()).
template <class Scalar>
Cpca<Scalar> as_cpca(const Pca<Scalar>& p) {
    Cpca<Scalar> r;
    r.cluster.assign(static_cast<std::size_t>(p.weights.rows()), 0);
    r.means = p.mean;
    r.bases = {p.basis};
    r.weights = p.weights;
    r.error_history = {p.dropped_energy()};
    return r;
}

/// Static CPCA: k-means (k-means++ seeding from settings.seed, Lloyd iterations) into C
/// clusters, then PCA with M vectors per cluster. Throws as pca() does, and for C < 1 or C > P.
template <class Derived>
Cpca<typename Derived::Scalar> cpca_static(const Eigen::MatrixBase<Derived>& data,
                                           const CpcaSettings& settings) {
    using Scalar = typename Derived::Scalar;
    static_assert(std::is_floating_point_v<Scalar>,
                  "sphbasis::compress::cpca_static: the data must be float or double.");
    return detail::static_model(detail::checked_cpca_input(data, settings, "compress::cpca_static"),
                                settings);
}

/// Iterative CPCA: cpca_static(), then reclassification of every point to the cluster whose
/// affine subspace reconstructs it best (ties keep the current cluster) and per-cluster refits,
/// until no point moves, the error falls by less than min_relative_decrease, a step would raise
/// the error (rejected: the previous model is kept), or max_iterations. A cluster left empty is
/// reseeded with the worst-reconstructed point of a cluster that has two or more (its error
/// becomes zero, so the step still cannot rise). Cost per iteration O(P C c M + P c^2 + C c^3).
template <class Derived>
Cpca<typename Derived::Scalar> cpca_iterative(const Eigen::MatrixBase<Derived>& data,
                                              const CpcaSettings& settings) {
    using Scalar = typename Derived::Scalar;
    static_assert(std::is_floating_point_v<Scalar>,
                  "sphbasis::compress::cpca_iterative: the data must be float or double.");
    const MatrixX<Scalar> x =
        detail::checked_cpca_input(data, settings, "compress::cpca_iterative");
    Cpca<Scalar> model = detail::static_model(x, settings);
    const int m = settings.vectors, nc = settings.clusters;
    double err = model.error_history[0];
    const Eigen::Index np = x.rows();
    MatrixX<Scalar> resid(np, nc);
    for (int it = 0; it < settings.max_iterations; ++it) {
        // Residual of every point in every cluster's affine subspace, |d|^2 - |B^T d|^2 with
        // d = x - mu_c, in blocks of rows so the temporaries stay in cache.
        constexpr Eigen::Index block = 1024;
        for (Eigen::Index r0 = 0; r0 < np; r0 += block) {
            const Eigen::Index nr = std::min(block, np - r0);
            for (int c = 0; c < nc; ++c) {
                const auto& b = model.bases[static_cast<std::size_t>(c)];
                const MatrixX<Scalar> d = x.middleRows(r0, nr).rowwise() - model.means.row(c);
                resid.block(r0, c, nr, 1) =
                    d.rowwise().squaredNorm() - (d * b).rowwise().squaredNorm();
            }
        }
        Cpca<Scalar> next = model;
        Eigen::Index moved = 0;
        std::vector<Eigen::Index> count(static_cast<std::size_t>(nc), 0);
        for (Eigen::Index p = 0; p < np; ++p) {
            int& a = next.cluster[static_cast<std::size_t>(p)];
            Eigen::Index best;
            const Scalar bv = resid.row(p).minCoeff(&best);
            if (bv < resid(p, a)) {
                a = static_cast<int>(best);
                ++moved;
            }
            ++count[static_cast<std::size_t>(a)];
        }
        if (moved == 0) break;
        for (int c = 0; c < nc; ++c) {
            if (count[static_cast<std::size_t>(c)] > 0) continue;
            Eigen::Index worst = -1;
            Scalar wv = -1;
            for (Eigen::Index p = 0; p < np; ++p) {
                const int a = next.cluster[static_cast<std::size_t>(p)];
                if (count[static_cast<std::size_t>(a)] < 2) continue;
                if (resid(p, a) > wv) wv = resid(p, a), worst = p;
            }
            if (worst < 0) break;
            --count[static_cast<std::size_t>(next.cluster[static_cast<std::size_t>(worst)])];
            next.cluster[static_cast<std::size_t>(worst)] = c;
            count[static_cast<std::size_t>(c)] = 1;
        }
        const double e = detail::fit_all(x, m, next);
        if (!(e <= err)) break;  // a rise by rounding: keep the best model
        next.error_history.push_back(e);
        next.iterations = model.iterations + 1;
        const double prev = err;
        model = std::move(next);
        err = e;
        if (prev - e <= settings.min_relative_decrease * prev) break;
    }
    return model;
}

/// Quantized weights: codes in [-q, q] (q = 127 for 8 bits, 32767 for 16; an int8_t holds the
/// 8-bit codes), scale per cluster and basis vector; weight ~ code / q * scale.
template <class Scalar = double>
struct QuantizedWeights {
    int bits = 8;
    std::vector<std::int16_t> codes;  ///< P x M, row-major
    MatrixX<Scalar> scales;           ///< C x M: max |w| over the cluster's points
    std::vector<int> cluster;         ///< P cluster indices
    Eigen::Index points = 0, vectors = 0;
    int levels() const { return bits == 8 ? 127 : 32767; }
};

/// Quantizes the model's weights to `bits` = 8 or 16 bits (see the header comment for the
/// bound). Throws std::invalid_argument for other bit counts.
template <class Scalar>
QuantizedWeights<Scalar> quantize(const Cpca<Scalar>& model, int bits) {
    if (bits != 8 && bits != 16)
        sphbasis::detail::throw_invalid("compress::quantize",
                                        "8 or 16 bits, got " + std::to_string(bits));
    QuantizedWeights<Scalar> q;
    q.bits = bits;
    q.points = model.weights.rows();
    q.vectors = model.weights.cols();
    q.cluster = model.cluster;
    q.scales = MatrixX<Scalar>::Zero(model.clusters(), q.vectors);
    for (Eigen::Index p = 0; p < q.points; ++p) {
        const int c = model.cluster[static_cast<std::size_t>(p)];
        q.scales.row(c) = q.scales.row(c).cwiseMax(model.weights.row(p).cwiseAbs());
    }
    const double levels = q.levels();
    q.codes.resize(static_cast<std::size_t>(q.points * q.vectors));
    for (Eigen::Index p = 0; p < q.points; ++p) {
        const int c = model.cluster[static_cast<std::size_t>(p)];
        for (Eigen::Index j = 0; j < q.vectors; ++j) {
            const double s = static_cast<double>(q.scales(c, j));
            const double t = s > 0 ? static_cast<double>(model.weights(p, j)) / s : 0.0;
            const double code = std::clamp(std::round(t * levels), -levels, levels);
            q.codes[static_cast<std::size_t>(p * q.vectors + j)] = static_cast<std::int16_t>(code);
        }
    }
    return q;
}

template <class Scalar>
QuantizedWeights<Scalar> quantize(const Pca<Scalar>& model, int bits) {
    return quantize(as_cpca(model), bits);
}

/// The P x M weights the codes stand for: code / q * scale.
template <class Scalar>
MatrixX<Scalar> dequantize(const QuantizedWeights<Scalar>& q) {
    MatrixX<Scalar> w(q.points, q.vectors);
    const Scalar inv = Scalar(1) / static_cast<Scalar>(q.levels());
    for (Eigen::Index p = 0; p < q.points; ++p) {
        const int c = q.cluster[static_cast<std::size_t>(p)];
        for (Eigen::Index j = 0; j < q.vectors; ++j)
            w(p, j) = static_cast<Scalar>(q.codes[static_cast<std::size_t>(p * q.vectors + j)]) *
                      inv * q.scales(c, j);
    }
    return w;
}

/// The model with its weights replaced by the dequantized ones.
template <class Scalar>
Cpca<Scalar> with_weights(Cpca<Scalar> model, const QuantizedWeights<Scalar>& q) {
    model.weights = dequantize(q);
    return model;
}

/// Per-cluster exit values for the lighting matrix L (c x K): mean[c] = mu_c L (C x K) and
/// basis[c] = B_c^T L (M x K). Computed once per lighting; cost O(C M c K).
template <class Scalar = double>
struct ExitValues {
    MatrixX<Scalar> mean;                ///< C x K
    std::vector<MatrixX<Scalar>> basis;  ///< C matrices M x K
};

template <class Scalar, class Derived>
ExitValues<Scalar> exit_values(const Cpca<Scalar>& model, const Eigen::MatrixBase<Derived>& light) {
    if (light.rows() != model.means.cols())
        sphbasis::detail::throw_invalid(
            "compress::exit_values", "a lighting matrix of " + std::to_string(model.means.cols()) +
                                         " rows, got " + std::to_string(light.rows()));
    const MatrixX<Scalar> l = light.template cast<Scalar>();
    ExitValues<Scalar> e;
    e.mean = model.means * l;
    e.basis.reserve(model.bases.size());
    for (const auto& b : model.bases) e.basis.push_back(b.transpose() * l);
    return e;
}

/// Shaded values P x K: row p = mean[c] + sum_j w_pj basis[c].row(j) (M multiply-adds per
/// output). `weights` may be the model's or dequantized ones (P x M).
template <class Scalar, class Derived>
MatrixX<Scalar> shade(const std::vector<int>& cluster, const Eigen::MatrixBase<Derived>& weights,
                      const ExitValues<Scalar>& e) {
    const Eigen::Index np = weights.rows(), m = weights.cols(), k = e.mean.cols();
    MatrixX<Scalar> out(np, k);
    for (Eigen::Index p = 0; p < np; ++p) {
        const auto c = static_cast<std::size_t>(cluster[static_cast<std::size_t>(p)]);
        const MatrixX<Scalar>& b = e.basis[c];
        for (Eigen::Index o = 0; o < k; ++o) {
            Scalar v = e.mean(static_cast<Eigen::Index>(c), o);
            for (Eigen::Index j = 0; j < m; ++j) v += static_cast<Scalar>(weights(p, j)) * b(j, o);
            out(p, o) = v;
        }
    }
    return out;
}

template <class Scalar>
MatrixX<Scalar> shade(const Cpca<Scalar>& model, const ExitValues<Scalar>& e) {
    return shade(model.cluster, model.weights, e);
}

/// Bound on |shade(exact weights) - shade(dequantized weights)| per point and output: sum_j
/// scale_cj / (2 q) * |b_cj . l_o| (half a quantization step per weight, times the basis
/// vector's exit value). P x K.
template <class Scalar>
MatrixX<Scalar> quantization_bound(const QuantizedWeights<Scalar>& q, const ExitValues<Scalar>& e) {
    const Eigen::Index k = e.mean.cols();
    MatrixX<Scalar> out(q.points, k);
    const Scalar half = Scalar(0.5) / static_cast<Scalar>(q.levels());
    for (Eigen::Index p = 0; p < q.points; ++p) {
        const int c = q.cluster[static_cast<std::size_t>(p)];
        const MatrixX<Scalar>& b = e.basis[static_cast<std::size_t>(c)];
        for (Eigen::Index o = 0; o < k; ++o) {
            Scalar v = 0;
            for (Eigen::Index j = 0; j < q.vectors; ++j)
                v += half * q.scales(c, j) * std::abs(b(j, o));
            out(p, o) = v;
        }
    }
    return out;
}

}  // namespace sphbasis::compress
