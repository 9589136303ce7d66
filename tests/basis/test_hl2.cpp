// Tests for basis/hl2.hpp: the Half-Life 2 basis.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/hl2.hpp>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using namespace sphbasis::test;

namespace {

/// The basis vectors (1.18)-(1.20).
std::array<Dir, 3> vectors() {
    return {Dir{-1 / std::sqrt(6.0), -1 / std::sqrt(2.0), 1 / std::sqrt(3.0)},
            Dir{-1 / std::sqrt(6.0), 1 / std::sqrt(2.0), 1 / std::sqrt(3.0)},
            Dir{std::sqrt(2.0 / 3.0), 0, 1 / std::sqrt(3.0)}};
}

std::array<double, 3> eval_d(double x, double y, double z) {
    std::array<double, 3> v;
    basis_eval<HL2>(3, x, y, z, v.data());
    return v;
}

/// Gram matrix by a product rule of degree 2 (exact for products of linear functions).
std::vector<std::vector<double>> gram(const DirectionalRule& r) {
    return test::gram_matrix<HL2>(3, r);
}

}  // namespace

TEST_CASE("hl2: values are sqrt(3/(2 pi)) n . h_i", "[hl2]") {
    const auto h = vectors();
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            CHECK(std::fabs(h[i][0] * h[j][0] + h[i][1] * h[j][1] + h[i][2] * h[j][2] -
                            (i == j ? 1.0 : 0.0)) < 4 * eps);
    const double c = std::sqrt(3 / (2 * pi));
    auto dirs = random_dirs(100, 1, false);
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    for (const auto& d : dirs) {
        const auto v = eval_d(d[0], d[1], d[2]);
        for (std::size_t i = 0; i < 3; ++i) {
            const double e = c * (d[0] * h[i][0] + d[1] * h[i][1] + d[2] * h[i][2]);
            REQUIRE(std::fabs(v[i] - e) <= 4 * eps);
        }
    }
    // HL2_i(h_j) = sqrt(3/(2 pi)) delta_ij; at the normal all three are 1/sqrt(2 pi).
    for (std::size_t j = 0; j < 3; ++j) {
        const auto v = eval_d(h[j][0], h[j][1], h[j][2]);
        for (std::size_t i = 0; i < 3; ++i) CHECK(std::fabs(v[i] - (i == j ? c : 0.0)) <= 4 * eps);
    }
    for (double x : eval_d(0, 0, 1)) CHECK(x == Approx(1 / std::sqrt(2 * pi)).epsilon(1e-15));
    // h_3 lies in the +x half-plane, h_1 at y < 0, h_2 at y > 0.
    CHECK(eval_d(1, 0, 0)[2] > 0);
    CHECK(eval_d(0, -1, 0)[0] > 0);
    CHECK(eval_d(0, 1, 0)[1] > 0);
    CHECK(std::string(HL2::name) == "hl2");
    CHECK(HL2::domain == Domain::hemisphere);
    CHECK(HL2::orthonormal);
    CHECK(HL2::max_count() == 3);
}

TEST_CASE("hl2: a rotation of the linear SH band, renormalised to the hemisphere", "[hl2]") {
    // HL2_i = sqrt(2) (h_iy y_1-1 + h_iz y_10 + h_ix y_11): sqrt(3/(2 pi)) = sqrt(2) sqrt(3/(4
    // pi)).
    const auto h = vectors();
    for (const auto& d : random_dirs(50, 2, false)) {
        double y[4];
        sh::eval(2, d[0], d[1], d[2], y);
        const auto v = eval_d(d[0], d[1], d[2]);
        for (std::size_t i = 0; i < 3; ++i)
            CHECK(std::fabs(v[i] - std::sqrt(2.0) * (h[i][1] * y[1] + h[i][2] * y[2] +
                                                     h[i][0] * y[3])) <= 8 * eps);
    }
}

TEST_CASE("hl2: orthonormal on the hemisphere, orthogonal with norm^2 = 2 on the sphere", "[hl2]") {
    // int_hemisphere n n^T = (2 pi/3) I, so the Gram matrix is h_i . h_j = delta_ij; on the whole
    // sphere it is 2 delta_ij (Ishmukhametov's "orthonormal ... as well as full sphere" holds for
    // orthogonality only).
    const auto gh = gram(hemisphere_rule(2));
    const auto gs = gram(sphere_rule(2));
    for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t b = 0; b < 3; ++b) {
            CHECK(std::fabs(gh[a][b] - (a == b ? 1.0 : 0.0)) < 1e-14);
            CHECK(std::fabs(gs[a][b] - (a == b ? 2.0 : 0.0)) < 1e-14);
        }
}

TEST_CASE("hl2: values against the mpmath reference", "[hl2][reference]") {
    CHECK(check_reference_values<HL2>("hl2", 3, 4 * eps).first == 3 * 26);
}

TEST_CASE("hl2: below the horizon the linear polynomials are returned", "[hl2]") {
    const auto h = vectors();
    const double c = std::sqrt(3 / (2 * pi));
    for (const auto& d : random_dirs(50, 3, false)) {
        if (d[2] >= 0) continue;
        const auto v = eval_d(d[0], d[1], d[2]);
        for (std::size_t i = 0; i < 3; ++i)
            CHECK(std::fabs(v[i] - c * (d[0] * h[i][0] + d[1] * h[i][1] + d[2] * h[i][2])) <=
                  4 * eps);
    }
    for (double x : eval_d(0, 0, -1)) CHECK(x == Approx(-1 / std::sqrt(2 * pi)).epsilon(1e-15));
}

TEMPLATE_TEST_CASE("hl2: batch path equals scalar path, float within 4 ulp of double", "[hl2]",
                   float, double) {
    using T = TestType;
    // 37: not a multiple of any SIMD width; * 3: non-unit on purpose, both paths normalise.
    const auto in = test::scaled_inputs<T>(random_dirs(37, 5, false), 3);
    const T et = std::numeric_limits<T>::epsilon();
    test::check_batch_equals_scalar<HL2, T>(3, {T(0.5), T(-1.25), T(2)}, in, 2 * et, 4 * double(et),
                                            8 * et);
}

TEST_CASE("hl2: bad sizes throw", "[hl2]") {
    double v[4];
    REQUIRE_THROWS_WITH(basis_eval<HL2>(4, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected 3 functions for basis 'hl2', got 4");
    REQUIRE_THROWS_WITH(basis_eval<HL2>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval_sum<HL2>(9, v, 0.0, 0.0, 1.0),
                        Catch::Contains("basis_eval_sum"));
    CHECK(HL2::valid_count(3));
    CHECK_FALSE(HL2::valid_count(-3));
}
