// Tests for ops/compression.hpp: PCA against closed forms and an independent eigen
// decomposition, static and iterative CPCA (monotone error, recovery of known affine clusters),
// quantization bounds, rendering from exit values, bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/sampling.hpp>
#include <sphbasis/ops/compression.hpp>

using namespace sphbasis;
using compress::MatrixX;

namespace {

double uni(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
double gauss(std::mt19937_64& rng) {
    // Box-Muller from our own uniforms (std distributions differ between standard libraries).
    const double u = 1 - uni(rng), v = uni(rng);
    return std::sqrt(-2 * std::log(u)) * std::cos(6.283185307179586 * v);
}

Eigen::MatrixXd random_matrix(Eigen::Index r, Eigen::Index c, std::mt19937_64& rng) {
    Eigen::MatrixXd m(r, c);
    for (Eigen::Index j = 0; j < c; ++j)
        for (Eigen::Index i = 0; i < r; ++i) m(i, j) = gauss(rng);
    return m;
}

/// An orthonormal c x r matrix (QR of a random matrix).
Eigen::MatrixXd random_orthonormal(Eigen::Index c, Eigen::Index r, std::mt19937_64& rng) {
    Eigen::HouseholderQR<Eigen::MatrixXd> qr(random_matrix(c, r, rng));
    return qr.householderQ() * Eigen::MatrixXd::Identity(c, r);
}

/// P points with c = 27 columns and a decaying spectrum: scale k ~ 0.7^k along random axes.
Eigen::MatrixXd decaying_data(Eigen::Index p, Eigen::Index c, std::mt19937_64& rng) {
    const Eigen::MatrixXd axes = random_orthonormal(c, c, rng);
    Eigen::MatrixXd w = random_matrix(p, c, rng);
    for (Eigen::Index k = 0; k < c; ++k) w.col(k) *= std::pow(0.7, static_cast<double>(k));
    Eigen::RowVectorXd mean = random_matrix(1, c, rng);
    return (w * axes.transpose()).rowwise() + mean;
}

/// The course's example signal in 9 dimensions: SH (3 bands) of a clamped-cosine-like lobe
/// around a normal that varies smoothly over the points: a curved 2D manifold.
Eigen::MatrixXd manifold_data(int p, std::mt19937_64& rng) {
    Eigen::MatrixXd x(p, 9);
    for (int i = 0; i < p; ++i) {
        const auto d = square_to_uniform_sphere(uni(rng), uni(rng));
        double y[9];
        sh::eval(3, d.x, d.y, d.z, y);
        for (int k = 0; k < 9; ++k) x(i, k) = y[k] * (k == 0 ? 1.0 : k < 4 ? 0.667 : 0.25);
    }
    return x;
}

/// Settings of C clusters and M vectors, the rest defaults.
compress::CpcaSettings cpca_settings(int clusters, int vectors) {
    compress::CpcaSettings s;
    s.clusters = clusters;
    s.vectors = vectors;
    return s;
}

}  // namespace

TEST_CASE("compression: PCA of data = mean + W U^T is exact at M = rank", "[compression]") {
    std::mt19937_64 rng(11);
    const Eigen::Index p = 200, c = 27, r = 5;
    const Eigen::MatrixXd u = random_orthonormal(c, r, rng);
    const Eigen::RowVectorXd mean = random_matrix(1, c, rng);
    Eigen::MatrixXd w = random_matrix(p, r, rng);
    w.rowwise() -= w.colwise().mean();  // centred weights: the mean is exactly `mean`
    const Eigen::MatrixXd x = (w * u.transpose()).rowwise() + mean;
    for (auto method : {compress::PcaMethod::svd, compress::PcaMethod::covariance}) {
        const auto m = compress::pca(x, int(r), method);
        CHECK(m.rank == r);
        CHECK((m.mean - mean).norm() < 1e-12);
        // The basis spans U: the projection of U onto it keeps all of U's energy.
        CHECK((m.basis.transpose() * u).squaredNorm() == Approx(double(r)).epsilon(1e-12));
        CHECK((m.basis.transpose() * m.basis - Eigen::MatrixXd::Identity(r, r)).norm() < 1e-12);
        const double err = compress::squared_error(x, m.reconstruct());
        CHECK(err < 1e-20 * x.squaredNorm());
        CHECK(m.stored_numbers() == c + r * c + p * r);
        // One vector more than the rank: an error naming the rank.
        CHECK_THROWS_WITH(compress::pca(x, int(r) + 1, method),
                          Catch::Contains("rank of the centred data (5)"));
        // One fewer: error is the dropped singular value squared (test can fail).
        const auto m4 = compress::pca(x, int(r) - 1, method);
        CHECK(compress::squared_error(x, m4.reconstruct()) ==
              Approx(m4.dropped_energy()).epsilon(1e-9));
        CHECK(m4.dropped_energy() > 1);
    }
}

TEST_CASE("compression: PCA equals the eigen decomposition of the covariance computed directly",
          "[compression]") {
    std::mt19937_64 rng(5);
    const Eigen::Index p = 300, c = 12;
    const Eigen::MatrixXd x = decaying_data(p, c, rng);
    // Independent reference: loops for the mean and scatter, Jacobi SVD of the scatter
    // (a symmetric positive semidefinite matrix: its singular vectors are its eigenvectors).
    std::vector<double> mu(c, 0.0);
    for (Eigen::Index i = 0; i < p; ++i)
        for (Eigen::Index k = 0; k < c; ++k) mu[std::size_t(k)] += x(i, k) / double(p);
    Eigen::MatrixXd s = Eigen::MatrixXd::Zero(c, c);
    for (Eigen::Index i = 0; i < p; ++i)
        for (Eigen::Index a = 0; a < c; ++a)
            for (Eigen::Index b = 0; b < c; ++b)
                s(a, b) += (x(i, a) - mu[std::size_t(a)]) * (x(i, b) - mu[std::size_t(b)]);
    Eigen::JacobiSVD<Eigen::MatrixXd> ref(s, Eigen::ComputeFullU);
    const int m = 6;
    const auto pc = compress::pca(x, m);
    for (Eigen::Index k = 0; k < c; ++k) {
        CHECK(pc.mean(k) == Approx(mu[std::size_t(k)]).margin(1e-13));
        CHECK(pc.singular_values(k) * pc.singular_values(k) ==
              Approx(ref.singularValues()(k)).epsilon(1e-10));
    }
    for (int j = 0; j < m; ++j)  // same vectors up to sign
        CHECK(std::abs(pc.basis.col(j).dot(ref.matrixU().col(j))) == Approx(1).epsilon(1e-9));
    // Weights are the projections of the centred points.
    const Eigen::MatrixXd centred = x.rowwise() - pc.mean;
    CHECK((pc.weights - centred * pc.basis).norm() < 1e-12);
}

TEST_CASE("compression: PCA error falls with M and is lossless at full rank", "[compression]") {
    std::mt19937_64 rng(7);
    const Eigen::Index p = 120, c = 18;
    const Eigen::MatrixXd x = decaying_data(p, c, rng);
    double prev = x.squaredNorm();
    for (int m = 1; m <= c; ++m) {
        const auto pc = compress::pca(x, m);
        CHECK(pc.rank == c);
        const double e = compress::squared_error(x, pc.reconstruct());
        CHECK(e < prev);  // strictly: every singular value is positive
        CHECK(e == Approx(pc.dropped_energy()).epsilon(1e-8).margin(1e-20 * x.squaredNorm()));
        prev = e;
        if (m == c) CHECK(e <= 1e-20 * x.squaredNorm());  // 1e-10 relative in norm
    }
}

TEMPLATE_TEST_CASE("compression: PCA in float and double", "[compression]", float, double) {
    std::mt19937_64 rng(9);
    const Eigen::MatrixXd xd = decaying_data(400, 9, rng);
    const MatrixX<TestType> x = xd.cast<TestType>();
    const auto pc = compress::pca(x, 9);
    const double tol = std::is_same_v<TestType, float> ? 1e-10 : 1e-26;
    CHECK(compress::squared_error(x, pc.reconstruct()) <= tol * double(x.squaredNorm()));
    const auto p3 = compress::pca(x, 3);
    CHECK(compress::squared_error(x, p3.reconstruct()) ==
          Approx(p3.dropped_energy()).epsilon(std::is_same_v<TestType, float> ? 1e-3 : 1e-9));
}

TEST_CASE("compression: static CPCA is deterministic and its error is its reconstruction's",
          "[compression]") {
    std::mt19937_64 rng(3);
    const Eigen::MatrixXd x = manifold_data(600, rng);
    compress::CpcaSettings s = cpca_settings(8, 2);
    const auto a = compress::cpca_static(x, s);
    const auto b = compress::cpca_static(x, s);
    CHECK(a.cluster == b.cluster);
    CHECK(a.error_history.size() == 1);
    CHECK(compress::squared_error(x, a.reconstruct()) == Approx(a.error_history[0]).epsilon(1e-9));
    CHECK(a.stored_numbers() == 8 * 9 * 3 + 600 * 2);
    // Clustering helps against one PCA with the same M (the signal is curved).
    const auto global = compress::pca(x, 2);
    CHECK(a.error_history[0] < 0.5 * compress::squared_error(x, global.reconstruct()));
    // Every cluster used, orthonormal bases.
    std::vector<int> count(8, 0);
    for (int c : a.cluster) ++count[std::size_t(c)];
    for (int n : count) CHECK(n > 0);
    for (const auto& bb : a.bases)
        CHECK((bb.transpose() * bb - Eigen::MatrixXd::Identity(2, 2)).norm() < 1e-12);
    // Another seed gives another (valid) clustering.
    s.seed = 2;
    const auto d = compress::cpca_static(x, s);
    CHECK(d.cluster != a.cluster);
}

TEST_CASE("compression: iterative CPCA never ends worse than static, error non-increasing",
          "[compression]") {
    std::mt19937_64 rng(4);
    const Eigen::MatrixXd x = manifold_data(400, rng);
    for (int m : {1, 2}) {
        compress::CpcaSettings s = cpca_settings(6, m);
        const auto st = compress::cpca_static(x, s);
        const auto it = compress::cpca_iterative(x, s);
        REQUIRE(!it.error_history.empty());
        CHECK(it.error_history.front() == Approx(st.error_history.front()).epsilon(1e-12));
        for (std::size_t i = 1; i < it.error_history.size(); ++i)
            CHECK(it.error_history[i] <= it.error_history[i - 1]);
        CHECK(it.error_history.back() <= st.error_history.front());
        CHECK(it.iterations >= 1);  // it moved points and gained
        CHECK(it.error_history.back() < 0.99 * st.error_history.front());
        CHECK(compress::squared_error(x, it.reconstruct()) ==
              Approx(it.error_history.back()).epsilon(1e-9));
    }
}

TEST_CASE("compression: iterative CPCA recovers known affine clusters to the noise floor",
          "[compression]") {
    std::mt19937_64 rng(21);
    const int nc = 4, m = 2, per = 150;
    const Eigen::Index c = 12;
    const double sigma = 1e-3;
    Eigen::MatrixXd x(nc * per, c);
    std::vector<int> truth;
    for (int k = 0; k < nc; ++k) {
        // Affine planes through nearby means, long extents: VQ (distance to mean) cuts them
        // across, the affine distance does not.
        const Eigen::MatrixXd u = random_orthonormal(c, m, rng);
        const Eigen::RowVectorXd mu = 0.5 * random_matrix(1, c, rng);
        for (int i = 0; i < per; ++i) {
            const Eigen::VectorXd w = 3.0 * random_matrix(m, 1, rng);
            x.row(k * per + i) = mu + (u * w).transpose() + sigma * random_matrix(1, c, rng);
            truth.push_back(k);
        }
    }
    compress::CpcaSettings s = cpca_settings(nc, m);
    const auto st = compress::cpca_static(x, s);
    const auto it = compress::cpca_iterative(x, s);
    // Noise floor: the noise outside the fitted planes, (c - M) of c components per point.
    const double floor = double(nc * per) * double(c - m) * sigma * sigma;
    INFO("static " << st.error_history.front() << " iterative " << it.error_history.back()
                   << " floor " << floor << " iterations " << it.iterations);
    CHECK(st.error_history.front() > 100 * floor);  // VQ alone does not find them
    CHECK(it.error_history.back() < 1.3 * floor);
    CHECK(it.error_history.back() > 0.7 * floor);
    // The partition is the true one up to relabeling.
    std::vector<int> label(nc, -1);
    int wrong = 0;
    for (std::size_t p = 0; p < truth.size(); ++p) {
        int& l = label[std::size_t(truth[p])];
        if (l < 0) l = it.cluster[p];
        if (it.cluster[p] != l) ++wrong;
    }
    CHECK(wrong == 0);
}

TEST_CASE("compression: shading from exit values equals reconstruct-then-dot", "[compression]") {
    std::mt19937_64 rng(8);
    const Eigen::MatrixXd x = decaying_data(200, 27, rng);
    compress::CpcaSettings s = cpca_settings(5, 3);
    s.max_iterations = 4;
    const auto model = compress::cpca_iterative(x, s);
    const Eigen::MatrixXd light = random_matrix(27, 3, rng);  // RGB: K = 3 outputs
    const auto e = compress::exit_values(model, light);
    const Eigen::MatrixXd shaded = compress::shade(model, e);
    const Eigen::MatrixXd ref = model.reconstruct() * light;
    CHECK((shaded - ref).cwiseAbs().maxCoeff() < 1e-12 * ref.cwiseAbs().maxCoeff());
    // A PCA through as_cpca shades the same way.
    const auto pc = compress::pca(x, 4);
    const auto pm = compress::as_cpca(pc);
    const Eigen::MatrixXd ps = compress::shade(pm, compress::exit_values(pm, light));
    CHECK((ps - pc.reconstruct() * light).cwiseAbs().maxCoeff() < 1e-12 * ps.cwiseAbs().maxCoeff());
}

TEST_CASE("compression: quantized weights and rendering within the stated bound", "[compression]") {
    std::mt19937_64 rng(10);
    const Eigen::MatrixXd x = decaying_data(400, 27, rng);
    compress::CpcaSettings s = cpca_settings(4, 4);
    const auto model = compress::cpca_static(x, s);
    const Eigen::MatrixXd light = random_matrix(27, 3, rng);
    const auto e = compress::exit_values(model, light);
    const Eigen::MatrixXd exact = compress::shade(model, e);
    double ratio8 = 0, err8 = 0, err16 = 0;
    for (int bits : {8, 16}) {
        const auto q = compress::quantize(model, bits);
        const Eigen::MatrixXd w = compress::dequantize(q);
        // Per weight: half a step of the cluster's scale.
        for (Eigen::Index p = 0; p < w.rows(); ++p)
            for (Eigen::Index j = 0; j < w.cols(); ++j) {
                const double half = q.scales(model.cluster[std::size_t(p)], j) / (2.0 * q.levels());
                REQUIRE(std::abs(w(p, j) - model.weights(p, j)) <= half * (1 + 1e-12));
                REQUIRE(std::abs(q.codes[std::size_t(p * w.cols() + j)]) <= q.levels());
            }
        const Eigen::MatrixXd shaded = compress::shade(model.cluster, w, e);
        const Eigen::MatrixXd bound = compress::quantization_bound(q, e);
        const Eigen::MatrixXd diff = (shaded - exact).cwiseAbs();
        for (Eigen::Index p = 0; p < diff.rows(); ++p)
            for (Eigen::Index k = 0; k < diff.cols(); ++k)
                REQUIRE(diff(p, k) <= bound(p, k) * (1 + 1e-9) + 1e-14);
        // Reconstruction: |dx| <= sum_j half_j (orthonormal vectors).
        const Eigen::MatrixXd rq = compress::with_weights(model, q).reconstruct();
        const Eigen::MatrixXd r = model.reconstruct();
        for (Eigen::Index p = 0; p < r.rows(); ++p) {
            const int c = model.cluster[std::size_t(p)];
            const double b = q.scales.row(c).sum() / (2.0 * q.levels());
            REQUIRE((rq.row(p) - r.row(p)).norm() <= b * (1 + 1e-9));
        }
        (bits == 8 ? err8 : err16) = diff.maxCoeff();
        if (bits == 8) ratio8 = (diff.array() / bound.array()).maxCoeff();
    }
    // The bound is not vacuous and 16 bits is ~256x finer (tests can fail).
    CHECK(ratio8 > 0.2);
    CHECK(err16 < err8 / 50);
    CHECK_THROWS_WITH(compress::quantize(model, 12), Catch::Contains("8 or 16 bits, got 12"));
}

TEST_CASE("compression: bad input throws with a message", "[compression]") {
    std::mt19937_64 rng(1);
    const Eigen::MatrixXd x = decaying_data(50, 6, rng);
    using Catch::Contains;
    CHECK_THROWS_WITH(compress::pca(Eigen::MatrixXd(0, 4), 1), Contains("non-empty data"));
    Eigen::MatrixXd bad = x;
    bad(3, 2) = std::nan("");
    CHECK_THROWS_WITH(compress::pca(bad, 1), Contains("finite data, got nan at point 3"));
    bad(3, 2) = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(compress::pca(bad, 1), std::invalid_argument);
    CHECK_THROWS_WITH(compress::pca(x, 0), Contains("M >= 1"));
    CHECK_THROWS_WITH(compress::pca(x, 7), Contains("M <= the number of columns (6)"));
    // Rank: 4 points have a centred rank of 3.
    CHECK_THROWS_WITH(compress::pca(x.topRows(4), 4), Contains("rank of the centred data (3)"));
    compress::CpcaSettings s = cpca_settings(51, 2);
    CHECK_THROWS_WITH(compress::cpca_static(x, s),
                      Contains("C <= the number of points (50) clusters, got C = 51"));
    s.clusters = 0;
    CHECK_THROWS_WITH(compress::cpca_iterative(x, s), Contains("C >= 1"));
    s.clusters = 3;
    s.vectors = 0;
    CHECK_THROWS_WITH(compress::cpca_static(x, s), Contains("M >= 1"));
    s.vectors = 9;
    CHECK_THROWS_WITH(compress::cpca_iterative(x, s), Contains("number of columns (6)"));
    s.vectors = 2;
    CHECK_THROWS_WITH(compress::cpca_static(bad, s), Contains("finite data"));
    const auto model = compress::cpca_static(x, s);
    CHECK_THROWS_WITH(compress::exit_values(model, Eigen::VectorXd::Ones(5)),
                      Contains("lighting matrix of 6 rows, got 5"));
}

TEST_CASE("compression: iterative CPCA on a large curved data set", "[compression][slow]") {
    std::mt19937_64 rng(6);
    const Eigen::MatrixXd x = manifold_data(20000, rng);
    compress::CpcaSettings s = cpca_settings(16, 2);
    const auto st = compress::cpca_static(x, s);
    const auto it = compress::cpca_iterative(x, s);
    for (std::size_t i = 1; i < it.error_history.size(); ++i)
        CHECK(it.error_history[i] <= it.error_history[i - 1]);
    CHECK(it.error_history.back() < st.error_history.front());
}
