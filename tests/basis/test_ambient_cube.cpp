// Tests for basis/ambient_cube.hpp: the ambient cube (McTaggart 2004).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/ambient_cube.hpp>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <vector>

#include "../support/basis_checks.hpp"
#include "../support/engine_reference.hpp"

using namespace sphbasis;

TEST_CASE("ambient-cube: values against the reference generator", "[ambient-cube]") {
    const auto rows = test::engine_reference("ambient-cube");
    REQUIRE(rows.size() >= 20);
    for (const auto& r : rows) {
        REQUIRE(r.size() == 9);
        std::array<double, 6> d;
        std::array<float, 6> f;
        basis_eval<AmbientCube>(6, r[0], r[1], r[2], d.data());
        basis_eval<AmbientCube>(6, float(r[0]), float(r[1]), float(r[2]), f.data());
        for (int k = 0; k < 6; ++k) {
            CHECK(d[std::size_t(k)] == Approx(r[std::size_t(3 + k)]).margin(4e-16));
            CHECK(f[std::size_t(k)] == Approx(r[std::size_t(3 + k)]).margin(4e-7));
        }
    }
}

TEST_CASE("ambient-cube: partition of unity, faces, Gram matrix on the sphere", "[ambient-cube]") {
    for (const auto& d : test::random_dirs(50, 3, false)) {
        std::array<double, 6> v;
        basis_eval<AmbientCube>(6, d[0], d[1], d[2], v.data());
        double s = 0;
        for (double x : v) {
            CHECK(x >= 0);
            s += x;
        }
        CHECK(s == Approx(1).epsilon(1e-15));
    }
    const double faces[6][3] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    for (int f = 0; f < 6; ++f) {
        std::array<double, 6> v;
        basis_eval<AmbientCube>(6, faces[f][0], faces[f][1], faces[f][2], v.data());
        for (int k = 0; k < 6; ++k) CHECK(v[std::size_t(k)] == (k == f ? 1.0 : 0.0));
    }
    // Exact Gram matrix (generator: 2 pi/5, pi/15, 0) against a product rule. The functions are
    // piecewise polynomials with kinks on the coordinate planes, which a product rule with
    // nodes symmetric about them integrates exactly only in z: compare to 1e-3 relative.
    const DirectionalRule rule = sphere_rule(200);
    const auto g = test::gram_matrix<AmbientCube>(6, rule);
    for (const auto& r : test::engine_reference("gram-ambient-cube")) {
        REQUIRE(r.size() == 3);
        CHECK(g[std::size_t(r[0])][std::size_t(r[1])] == Approx(r[2]).margin(1e-3));
    }
}

TEST_CASE("ambient-cube: batch equals scalar, float near double, registry", "[ambient-cube]") {
    const auto dirs = test::random_dirs(37, 9, false);
    const auto inf = test::scaled_inputs<float>(dirs, 2.5);
    const auto ind = test::scaled_inputs<double>(dirs, 2.5);
    std::vector<float> cf = {0.5f, -1, 2, 0.25f, 1, 3};
    std::vector<double> cd(cf.begin(), cf.end());
    // Values in [0, 1]: 4 float ulps of 1 for the batch (its normalisation rounds otherwise:
    // 2.4e-7 measured in the sanitizer build), 2e-7 against double.
    test::check_batch_equals_scalar<AmbientCube, float>(6, cf, inf, 4.8e-7f, 2e-7, 4e-6f);
    test::check_batch_equals_scalar<AmbientCube, double>(6, cd, ind, 1e-15, 1e-15, 1e-14);
    const BasisInfo& b = find_basis("ambient-cube");
    CHECK(b.domain == Domain::sphere);
    CHECK(!b.orthonormal);
    CHECK(b.valid_count(6));
    CHECK(b.valid_count(5));
    CHECK(!b.valid_count(4));
    std::array<double, 6> v;
    CHECK_THROWS_WITH(
        basis_eval<AmbientCube>(4, 0.0, 0.0, 1.0, v.data()),
        Catch::Contains("5 (upper hemisphere) or 6 functions for basis 'ambient-cube'"));
    // 5 functions: the prefix of 6 (the hemispherical cube), written without touching v[5].
    std::array<double, 6> w;
    w[5] = -7;
    basis_eval<AmbientCube>(6, 0.3, -0.4, 0.5, v.data());
    basis_eval<AmbientCube>(5, 0.3, -0.4, 0.5, w.data());
    for (int k = 0; k < 5; ++k) CHECK(w[std::size_t(k)] == v[std::size_t(k)]);
    CHECK(w[5] == -7);
    // Hard input: zero and non-finite directions give finite values (the pole).
    basis_eval<AmbientCube>(6, 0.0, 0.0, 0.0, v.data());
    for (double x : v) CHECK(std::isfinite(x));
}
