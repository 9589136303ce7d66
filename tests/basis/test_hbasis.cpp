// Tests for basis/hbasis.hpp: the H-basis and the modified H-basis.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <sphbasis/basis/hbasis.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using namespace sphbasis::test;

namespace {

/// The six functions from their definitions (Habel & Wimmer 2010; Ishmukhametov,
/// "Irradiance Normal Mapping" (thesis), eqs. 1.52-1.58).
std::array<double, 6> defined(bool mod, double x, double y, double z) {
    const double c3 = std::sqrt(3 / (2 * pi)), c15 = std::sqrt(15 / (2 * pi));
    return {1 / std::sqrt(2 * pi),
            c3 * y,
            mod ? c3 * (1 - z) : c3 * (2 * z - 1),
            c3 * x,
            c15 * x * y,
            c15 / 2 * (x * x - y * y)};
}

template <class B>
std::vector<double> eval_d(int n, double x, double y, double z) {
    std::vector<double> v(static_cast<std::size_t>(n));
    basis_eval<B>(n, x, y, z, v.data());
    return v;
}

/// Gram matrix of B's n functions by the hemisphere rule of degree 4 (exact for their products,
/// polynomials of degree <= 4 in x, y, z).
template <class B>
std::vector<std::vector<double>> gram(int n) {
    return test::gram_matrix<B>(n, hemisphere_rule(4));
}

}  // namespace

TEST_CASE("hbasis: values are the definitions, signs pinned", "[hbasis]") {
    auto dirs = random_dirs(100, 1, false);
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0.48, -0.6, 0.64});
    for (const auto& d : dirs) {
        const auto h = eval_d<HBasis>(6, d[0], d[1], d[2]);
        const auto hm = eval_d<HBasisMod>(6, d[0], d[1], d[2]);
        const auto e = defined(false, d[0], d[1], d[2]);
        const auto em = defined(true, d[0], d[1], d[2]);
        for (std::size_t k = 0; k < 6; ++k) {
            INFO("k=" << k << " dir=" << d[0] << "," << d[1] << "," << d[2]);
            REQUIRE(std::fabs(h[k] - e[k]) <= 4 * eps);
            REQUIRE(std::fabs(hm[k] - em[k]) <= 4 * eps);
        }
    }
    // H2 ~ +y, H4 ~ +x, H5 ~ +xy, H6 ~ +(x^2 - y^2); H3 = +sqrt(3/(2 pi)) at the normal, H3mod = 0.
    const auto a = eval_d<HBasis>(6, 0.6, 0.0, 0.8);
    CHECK(a[3] > 0);
    CHECK(a[1] == 0);
    CHECK(a[5] > 0);
    const auto b = eval_d<HBasis>(6, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(b[5] < 0);
    CHECK(eval_d<HBasis>(6, 0.6, 0.6, std::sqrt(0.28))[4] > 0);
    CHECK(eval_d<HBasis>(4, 0.0, 0.0, 1.0)[2] == Approx(std::sqrt(3 / (2 * pi))).epsilon(1e-15));
    CHECK(eval_d<HBasisMod>(4, 0.0, 0.0, 1.0)[2] == 0);
    CHECK(std::string(HBasis::name) == "hbasis");
    CHECK(std::string(HBasisMod::name) == "hbasis-mod");
    CHECK(HBasis::orthonormal);
    CHECK_FALSE(HBasisMod::orthonormal);
    CHECK(HBasis::domain == Domain::hemisphere);
    CHECK(HBasisMod::domain == Domain::hemisphere);
    CHECK(HBasis::max_count() == 6);
}

TEST_CASE("hbasis: Ishmukhametov's Listing 2.2 shader constants", "[hbasis]") {
    // 0.39894 = 1/sqrt(2 pi), 0.69099 = sqrt(3/(2 pi)), 1.54509 = sqrt(15/(2 pi)),
    // 0.77255 = sqrt(15/(2 pi))/2, the modified H-basis' normalisations rounded to 5 digits, except
    // that 1.54509 is truncated (sqrt(15/(2 pi)) = 1.5450968...): within one unit of the last
    // digit.
    const double x = 0.48, y = -0.6, z = 0.64;
    const auto v = eval_d<HBasisMod>(6, x, y, z);
    CHECK(std::fabs(v[0] - 0.39894) < 5e-6);
    CHECK(std::fabs(v[1] / y - 0.69099) < 5e-6);
    CHECK(std::fabs(v[2] / (1 - z) - 0.69099) < 5e-6);
    CHECK(std::fabs(v[3] / x - 0.69099) < 5e-6);
    CHECK(std::fabs(v[4] / (x * y) - 1.54509) < 1e-5);
    CHECK(std::fabs(v[4] / (x * y) - 1.54510) < 5e-6);
    CHECK(std::fabs(v[5] / (x * x - y * y) - 0.77255) < 5e-6);
    // The shader's irradiance with decoded coefficients c (the range expansion 2*0.75*t - 0.75
    // and the sRGB lookup are the texture decode, not the basis), at its three LODs.
    for (const auto& d : random_dirs(50, 2)) {
        const double c[6] = {0.8, -0.3, 0.25, 0.6, -0.1, 0.05};
        const double n[3] = {d[0], d[1], d[2]};
        const double lod0 = 0.39894 * c[0];
        const double lod1 =
            lod0 + c[1] * 0.69099 * n[1] + c[2] * 0.69099 * (1 - n[2]) + c[3] * 0.69099 * n[0];
        const double lod2 =
            lod1 + c[4] * 1.54509 * n[0] * n[1] + c[5] * 0.77255 * (n[0] * n[0] - n[1] * n[1]);
        CHECK(std::fabs(basis_eval_sum<HBasisMod>(4, c, n[0], n[1], n[2]) - lod1) < 1e-5);
        CHECK(std::fabs(basis_eval_sum<HBasisMod>(6, c, n[0], n[1], n[2]) - lod2) < 1e-5);
        CHECK(std::fabs(eval_d<HBasisMod>(4, n[0], n[1], n[2])[0] * c[0] - lod0) < 1e-5);
    }
}

TEST_CASE("hbasis: Gram matrices by exact quadrature", "[hbasis]") {
    // H-basis: the identity, for 4 and 6 functions.
    for (int n : {4, 6}) {
        const auto g = gram<HBasis>(n);
        for (int a = 0; a < n; ++a)
            for (int b = 0; b < n; ++b)
                CHECK(std::fabs(g[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] -
                                (a == b ? 1.0 : 0.0)) < 1e-14);
    }
    // Modified H-basis: the identity except <H1, H3mod> = sqrt(3)/(2 pi) 2 pi int_0^1 (1 - z) dz
    // = sqrt(3)/2 (and <H3mod, H3mod> = 3/(2 pi) 2 pi int_0^1 (1 - z)^2 dz = 1), by hand ...
    const auto g = gram<HBasisMod>(6);
    double closed[6][6] = {};
    for (int a = 0; a < 6; ++a) closed[a][a] = 1;
    closed[0][2] = closed[2][0] = std::sqrt(3.0) / 2;
    for (int a = 0; a < 6; ++a)
        for (int b = 0; b < 6; ++b)
            CHECK(std::fabs(g[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] -
                            closed[a][b]) < 1e-14);
    // ... and as the generator's exact sympy integrals.
    std::ifstream in(SPHBASIS_TEST_DATA_DIR "/hemi_reference.txt");
    REQUIRE(in.good());
    std::string line, tag, basis;
    int count = 0;
    while (std::getline(in, line)) {
        std::istringstream is(line);
        if (!(is >> tag) || tag != "gram") continue;
        int a, b;
        double v;
        REQUIRE(static_cast<bool>(is >> basis >> a >> b >> v));
        REQUIRE(basis == "hbasis-mod");
        CHECK(std::fabs(v - closed[a][b]) < 1e-15);
        CHECK(std::fabs(g[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] - v) < 1e-14);
        ++count;
    }
    CHECK(count == 36);
}

TEST_CASE("hbasis: values against the mpmath reference", "[hbasis][reference]") {
    const auto [count, worst] = check_reference_values<HBasis>("hbasis", 6, 4 * eps);
    const auto [count_mod, worst_mod] = check_reference_values<HBasisMod>("hbasis-mod", 6, 4 * eps);
    CHECK(count + count_mod == 2 * 6 * 26);
    WARN("hbasis reference: " << count + count_mod
                              << " values, worst |error| = " << std::max(worst, worst_mod));
}

TEST_CASE("hbasis: prefix, below the horizon, pole and horizon", "[hbasis]") {
    for (const auto& d : random_dirs(50, 3, false)) {
        for (bool mod : {false, true}) {
            const auto six =
                mod ? eval_d<HBasisMod>(6, d[0], d[1], d[2]) : eval_d<HBasis>(6, d[0], d[1], d[2]);
            const auto four =
                mod ? eval_d<HBasisMod>(4, d[0], d[1], d[2]) : eval_d<HBasis>(4, d[0], d[1], d[2]);
            CHECK(std::equal(four.begin(), four.end(), six.begin()));
            // Below the horizon the polynomials are returned (they extend to the whole sphere).
            const auto e = defined(mod, d[0], d[1], d[2]);
            for (std::size_t k = 0; k < 6; ++k) CHECK(std::fabs(six[k] - e[k]) <= 4 * eps);
        }
    }
    const double c3 = std::sqrt(3 / (2 * pi)), c15 = std::sqrt(15 / (2 * pi));
    const auto p = eval_d<HBasis>(6, 0, 0, 1);
    const auto h = eval_d<HBasis>(6, 1, 0, 0);
    const auto s = eval_d<HBasis>(6, 0, 0, -1);
    const std::array<double, 6> pe = {1 / std::sqrt(2 * pi), 0, c3, 0, 0, 0};
    const std::array<double, 6> he = {1 / std::sqrt(2 * pi), 0, -c3, c3, 0, c15 / 2};
    const std::array<double, 6> se = {1 / std::sqrt(2 * pi), 0, -3 * c3, 0, 0, 0};
    for (std::size_t k = 0; k < 6; ++k) {
        CHECK(std::fabs(p[k] - pe[k]) <= 4 * eps);
        CHECK(std::fabs(h[k] - he[k]) <= 4 * eps);
        CHECK(std::fabs(s[k] - se[k]) <= 4 * eps);
    }
    CHECK(eval_d<HBasisMod>(6, 1, 0, 0)[2] == Approx(c3).epsilon(1e-15));
    CHECK(eval_d<HBasisMod>(6, 0, 0, -1)[2] == Approx(2 * c3).epsilon(1e-15));
}

TEMPLATE_TEST_CASE("hbasis: batch path equals scalar path, float within 4 ulp of double",
                   "[hbasis]", float, double) {
    using T = TestType;
    // 37: not a multiple of any SIMD width; * 3: non-unit on purpose, both paths normalise.
    const auto in = test::scaled_inputs<T>(random_dirs(37, 5, false), 3);
    const T et = std::numeric_limits<T>::epsilon();
    for (int nf : {4, 6}) {
        std::vector<T> coeffs(static_cast<std::size_t>(nf));
        for (std::size_t k = 0; k < coeffs.size(); ++k) coeffs[k] = T(std::sin(double(k) + 1));
        test::check_batch_equals_scalar<HBasis, T>(nf, coeffs, in, 2 * et, 4 * double(et) * 1.6,
                                                   16 * et);
        test::check_batch_equals_scalar<HBasisMod, T>(nf, coeffs, in, 2 * et, 4 * double(et) * 1.6,
                                                      16 * et);
    }
}

TEST_CASE("hbasis: bad sizes throw", "[hbasis]") {
    double v[9];
    REQUIRE_THROWS_WITH(
        basis_eval<HBasis>(5, 0.0, 0.0, 1.0, v),
        "sphbasis::basis_eval(): expected 4 or 6 functions for basis 'hbasis', got 5");
    REQUIRE_THROWS_WITH(basis_eval<HBasisMod>(9, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected 4 or 6 functions for basis 'hbasis-mod', "
                        "got 9");
    REQUIRE_THROWS_WITH(basis_eval<HBasis>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval_batch<HBasis>(4, 2, f, f, f, f, 1), Catch::Contains("stride"));
    CHECK(HBasis::valid_count(4));
    CHECK(HBasisMod::valid_count(6));
    CHECK_FALSE(HBasis::valid_count(3));
    CHECK_FALSE(HBasisMod::valid_count(7));
}
