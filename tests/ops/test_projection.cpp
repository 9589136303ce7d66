// Tests for ops/projection.hpp: projection, Monte Carlo projection, least squares, conversion
// matrices (including the thesis's SH -> modified H-basis matrix, Listing 2.1).
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sphbasis/basis/hbasis.hpp>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/sampling.hpp>
#include <sphbasis/ops/projection.hpp>

using namespace sphbasis;

TEST_CASE("projection: a polynomial SH spans is projected exactly", "[projection]") {
    // f = 1 + 2x - z^2 + 3xyz lies in the span of SH of 4 bands (degree 3).
    auto f = [](double x, double y, double z) { return 1 + 2 * x - z * z + 3 * x * y * z; };
    const auto sh4 = evaluator<SH>(16);
    const auto rule = sphere_rule(3 + 3);
    const Eigen::VectorXd c = project(sh4, f, rule);
    // Reconstruction equals f at arbitrary points.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uni(0, 1);
    for (int i = 0; i < 50; ++i) {
        const auto d = square_to_uniform_sphere(uni(rng), uni(rng));
        double y[16];
        sh::eval(4, d.x, d.y, d.z, y);
        double r = 0;
        for (int k = 0; k < 16; ++k) r += c(k) * y[k];
        REQUIRE(r == Approx(f(d.x, d.y, d.z)).margin(1e-13));
    }
    // With 3 bands the degree-3 part is lost: the projection is not exact (test can fail).
    const Eigen::VectorXd c3 = project(evaluator<SH>(9), f, rule);
    CHECK(squared_error(evaluator<SH>(9), c3, f, rule) > 1e-3);
    CHECK(squared_error(sh4, c, f, rule) < 1e-26);
}

TEST_CASE("projection: Monte Carlo projection converges to the exact one", "[projection]") {
    auto f = [](double x, double, double z) { return std::max(0.0, z) + 0.5 * x; };
    const auto sh3 = evaluator<SH>(9);
    const Eigen::VectorXd exact = project(sh3, f, sphere_rule(200));
    std::vector<double> u, v, vals, w;
    std::vector<vec3<double>> dirs;
    stratified(256, 7, u, v);
    for (std::size_t i = 0; i < u.size(); ++i) {
        dirs.push_back(square_to_uniform_sphere(u[i], v[i]));
        vals.push_back(f(dirs.back().x, dirs.back().y, dirs.back().z));
        w.push_back(1.0 / (double(u.size()) * uniform_sphere_pdf<double>()));
    }
    const Eigen::VectorXd mc = project_mc(sh3, dirs, vals, w);
    CHECK((mc - exact).cwiseAbs().maxCoeff() < 2e-3);
    REQUIRE_THROWS_AS(project_mc(sh3, dirs, vals, std::vector<double>{1.0}), std::invalid_argument);
}

TEST_CASE("projection: least squares on the hemisphere for a non-orthogonal set", "[projection]") {
    // SH restricted to the hemisphere is not orthonormal: projection != least squares there,
    // but the least-squares fit reproduces any function in the span exactly.
    const auto sh3 = evaluator<SH>(9);
    const auto rule = hemisphere_rule(8);
    const Eigen::MatrixXd g = gram(sh3, rule);
    CHECK((g - Eigen::MatrixXd::Identity(9, 9)).cwiseAbs().maxCoeff() > 0.1);
    auto f = [](double x, double y, double z) { return 0.3 - x * y + 2 * z * z; };
    const Eigen::VectorXd c = fit(sh3, f, rule);
    CHECK(squared_error(sh3, c, f, rule) < 1e-26);
    const Eigen::VectorXd p = project(sh3, f, rule);
    CHECK(squared_error(sh3, p, f, rule) > 1e-3);
}

TEST_CASE("projection: SH -> modified H-basis matrix reproduces Ishmukhametov, Listing 2.1",
          "[projection]") {
    // Least squares over the upper hemisphere of 3-band SH (irradiance) into the 6-function
    // modified H-basis. Listing 2.1 prints the nonzeros to 5 significant digits.
    const Eigen::MatrixXd t =
        conversion(evaluator<SH>(9), evaluator<HBasisMod>(6), hemisphere_rule(8));
    auto printed = [](double v) { return Approx(v).margin(0.5e-4 * std::max(1.0, std::fabs(v))); };
    CHECK(t(0, 0) == printed(0.70711));
    CHECK(t(0, 2) == printed(1.2247));
    CHECK(t(0, 6) == printed(1.1859));
    CHECK(t(1, 1) == printed(0.70711));
    CHECK(t(1, 5) == printed(0.59293));
    CHECK(t(2, 2) == printed(-0.70711));
    CHECK(t(2, 6) == printed(-1.3693));
    CHECK(t(3, 3) == printed(0.70711));
    CHECK(t(3, 7) == printed(0.59293));
    CHECK(t(4, 4) == printed(0.70711));
    CHECK(t(5, 8) == printed(0.70711));
    // Every other entry is zero.
    int nonzero = 0;
    for (int i = 0; i < 6; ++i)
        for (int j = 0; j < 9; ++j) nonzero += std::fabs(t(i, j)) > 1e-12;
    CHECK(nonzero == 11);
    // Listing 2.2's shader constants are the modified H-basis normalisations.
    double h[6];
    basis_eval<HBasisMod>(6, 0.0, 0.0, 1.0, h);
    CHECK(h[0] == Approx(0.39894).margin(0.5e-5));  // 1/sqrt(2 pi)
    CHECK(h[2] == Approx(0.0).margin(1e-15));       // (1 - z) = 0 at the pole
}

TEST_CASE("projection: conversion between spans that contain each other is exact", "[projection]") {
    // H-basis 4 and SH 4 span the same functions on the hemisphere: converting SH -> H -> SH
    // over the hemisphere reproduces the SH function there.
    const auto rule = hemisphere_rule(6);
    const auto sh2 = evaluator<SH>(4), hb = evaluator<HBasis>(4);
    const Eigen::MatrixXd a = conversion(sh2, hb, rule), b = conversion(hb, sh2, rule);
    CHECK(((b * a) - Eigen::MatrixXd::Identity(4, 4)).cwiseAbs().maxCoeff() < 1e-12);
    REQUIRE_THROWS_AS(evaluator<SH>(5), std::invalid_argument);
    // Linearly dependent functions: the Gram solve refuses.
    BasisFunctions dup{2, [](double, double, double z, double* o) {
                           o[0] = z;
                           o[1] = 2 * z;
                       }};
    REQUIRE_THROWS_AS(fit(
                          dup, [](double, double, double z) { return z; }, rule),
                      std::runtime_error);
}

TEST_CASE("projection: a malformed BasisFunctions is an error message", "[projection]") {
    using namespace sphbasis;
    const DirectionalRule rule = sphere_rule(4);
    const BasisFunctions negative{-1, [](double, double, double, double*) {}};
    const BasisFunctions empty{4, {}};
    CHECK_THROWS_WITH(evaluation_matrix(negative, rule),
                      Catch::Contains("n >= 1 functions, got n = -1"));
    CHECK_THROWS_WITH(evaluation_matrix(empty, rule), Catch::Contains("an evaluation function"));
    CHECK_THROWS_AS(gram(empty, rule), std::invalid_argument);
    CHECK_THROWS_AS(LeastSquares(negative, rule), std::invalid_argument);
}
