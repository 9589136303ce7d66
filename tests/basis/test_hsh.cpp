// Tests for basis/hsh.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/hsh.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <string>
#include <utility>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;

namespace {

using test::Dir;
using test::random_dirs;
constexpr double pi = constants::pi;
constexpr double eps = std::numeric_limits<double>::epsilon();

/// The scale of degree l: |H_l0| at the pole, the largest value of the band's functions.
double scale(int l) { return std::sqrt((2 * l + 1) / (2 * pi)); }

std::vector<double> eval_d(int bands, double x, double y, double z) {
    return test::eval_bands<HSH>(bands, x, y, z);
}

/// What the shared checks (tests/support/basis_checks.hpp) need to know of HSH.
struct Traits {
    using Basis = HSH;
    using RowKernel = hsh::detail::RowKernel;
    using ColumnKernel = hsh::detail::ColumnKernel;
    static double scale(int l) { return ::scale(l); }
    static int degree_of(int k) { return sh::degree_of(k); }
    static int index(int l, int m) { return hsh::index(l, m); }
    template <class F>
    static void with_kernel(int bands, F&& f) {
        hsh::detail::with_bands_kernel(bands, std::forward<F>(f));
    }
};

}  // namespace

TEST_CASE("hsh: bands 0-2 closed forms and band-1 signs pin the convention", "[hsh]") {
    auto dirs = random_dirs(50, 1);
    dirs.push_back({0.48, -0.6, 0.64});
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0, -1, 0});
    for (const auto& d : dirs) {
        const double x = d[0], y = d[1], z = d[2], q = std::sqrt(z / (1 + z));
        const double c[9] = {1 / std::sqrt(2 * pi),
                             std::sqrt(6 / pi) * y * q,
                             std::sqrt(3 / (2 * pi)) * (2 * z - 1),
                             std::sqrt(6 / pi) * x * q,
                             2 * std::sqrt(30 / pi) * x * y * z / (1 + z),
                             std::sqrt(30 / pi) * y * (2 * z - 1) * q,
                             std::sqrt(5 / (2 * pi)) * (6 * z * z - 6 * z + 1),
                             std::sqrt(30 / pi) * x * (2 * z - 1) * q,
                             std::sqrt(30 / pi) * z * (x * x - y * y) / (1 + z)};
        const auto v = eval_d(3, x, y, z);
        for (int k = 0; k < 9; ++k) {
            INFO("k=" << k << " dir=" << x << "," << y << "," << z);
            REQUIRE(std::fabs(v[static_cast<std::size_t>(k)] - c[k]) <= 64 * eps * scale(2));
        }
    }
    // Band 1: H_1-1 ~ +y, H_10 ~ +(2z - 1), H_11 ~ +x (no Condon-Shortley phase).
    const auto a = eval_d(2, 0.6, 0.0, 0.8);
    CHECK(a[3] > 0);
    CHECK(a[1] == 0);
    CHECK(a[2] > 0);
    const auto b = eval_d(2, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(std::fabs(b[3]) < 1e-16);
    CHECK(a[3] == Approx(std::sqrt(6 / pi) * 0.6 * std::sqrt(0.8 / 1.8)).epsilon(1e-15));
    CHECK(hsh::index(2, -1) == 5);
    CHECK(HSH::count(4) == 16);
    CHECK(HSH::bands_of(16) == 4);
    CHECK(HSH::bands_of(15) == -1);
    CHECK(std::string(HSH::name) == "hsh");
    CHECK(HSH::domain == Domain::hemisphere);
    CHECK(HSH::orthonormal);
    CHECK(HSH::max_count() == 2048 * 2048);
}

// Why the product rule is exact: H_l^m = K P_l^|m|(u) trig(m phi) with u = 2z - 1. For two
// functions of orders m, m' the product is (1-u^2)^((|m|+|m'|)/2) times a polynomial in u times
// trig(m phi) trig(m' phi). If |m| + |m'| is even, (1-u^2)^(...) = (4z(1-z))^(...) is a polynomial
// and the product is a polynomial in z of degree <= l + l' <= 2(bands-1), integrated exactly by
// the (bands)-point Gauss-Legendre rule in z; the phi factor is a trigonometric polynomial of
// degree <= 2(bands-1) < the 2 bands - 1 uniform points in phi. If |m| + |m'| is odd then m != m'
// and the uniform phi rule sums cos/sin((m -+ m') phi), 0 < |m -+ m'| < 2 bands - 1, to exactly 0
// at every z node. Hence hemisphere_rule(2(bands-1)) gives the exact Gram matrix.
TEST_CASE("hsh: Gram matrix is the identity by exact quadrature", "[hsh]") {
    test::check_gram_identity<HSH>(
        test::band_range(10), [](int bands) { return 2 * (bands - 1); }, 1e-13, false);
}

TEST_CASE("hsh: Gram matrix is the identity by exact quadrature, 16 to 33 bands", "[hsh][slow]") {
    test::check_gram_identity<HSH>(
        {16, 24, 33}, [](int bands) { return 2 * (bands - 1); }, 1e-12, true);
}

TEST_CASE("hsh: column recurrence is orthonormal per order to 512 bands", "[hsh][slow]") {
    // At phi = 0 the m >= 0 functions are g_lm(z) cos(0) = g_lm(z), and the hemisphere integral of
    // H_lm H_l'm is pi (1 + delta_m0) int_0^1 g_lm g_l'm dz: a polynomial of degree <= 2(bands-1)
    // in z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    const double worst = test::column_gram_residual<Traits>(512, {0, 1, 2, 100, 300, 510, 511}, 1);
    WARN("hsh per-order Gram residual at 512 bands: " << worst);
    CHECK(worst < 1e-12);
}

TEST_CASE("hsh: values against the mpmath reference (l <= 255)", "[hsh][reference]") {
    test::check_hemi_reference<Traits>(255);
}

TEST_CASE("hsh: values against the mpmath reference (l <= 2047)", "[hsh][reference][slow]") {
    test::check_hemi_reference<Traits>(2047);
}

TEST_CASE("hsh: unrolled kernels, row recurrence and column recurrence agree", "[hsh]") {
    test::check_kernels_agree<Traits>();
}

TEST_CASE("hsh: prefix property", "[hsh]") { test::check_prefix_property<Traits>(); }

TEMPLATE_TEST_CASE("hsh: batch path equals scalar path", "[hsh]", float, double) {
    test::check_batch_equals_scalar<Traits, TestType>();
}

TEST_CASE("hsh: float is within a stated bound of double", "[hsh]") {
    // Bound: |float - double| <= 6 (l + 1)^1.5 ulp(float) * S_l (measured worst 3.2 (l + 1)^1.5,
    // near the pole): the float path normalises the direction in float (near the pole degree-l
    // functions have slope ~l^2 in z) and rounds each recurrence step (~l^1.5 ulp near the ends).
    test::check_float_vs_double<Traits>();
}

TEST_CASE("hsh: below the horizon every function is 0", "[hsh]") {
    test::check_zero_below_horizon<HSH>();
}

TEST_CASE("hsh: pole and horizon are finite and exact", "[hsh]") {
    // Pole: only m = 0 survives, H_l0(1) = S_l. Horizon (u = -1): only m = 0, H_l0 = (-1)^l S_l.
    for (int bands : {1, 3, 8, 20, 64, 65, 300}) {
        const auto p = eval_d(bands, 0, 0, 1);
        const auto h = eval_d(bands, 0.6, -0.8, 0);
        const auto hz = eval_d(bands, 0.6, -0.8, -0.0);  // -0 is on the horizon, not below
        double worst = 0;
        for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; ++m) {
                const std::size_t k = static_cast<std::size_t>(hsh::index(l, m));
                const double s = scale(l);
                REQUIRE(std::isfinite(p[k]));
                REQUIRE(std::isfinite(h[k]));
                worst = std::max(worst, std::fabs(p[k] - (m == 0 ? s : 0.0)) / s);
                worst = std::max(worst, std::fabs(h[k] - (m == 0 ? (l % 2 ? -s : s) : 0.0)) / s);
                REQUIRE(hz[k] == h[k]);
            }
        INFO("bands " << bands);
        CHECK(worst <= 1e-14 + 20 * eps * bands);
    }
}

TEST_CASE("hsh: hard directions stay finite", "[hsh]") {
    test::check_hard_directions_finite<HSH>(16);
}

TEST_CASE("hsh: bad sizes throw", "[hsh]") {
    double v[16];
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval<HSH>(5, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected a square number (bands^2, bands <= 2048) "
                        "of functions for basis 'hsh', got 5");
    REQUIRE_THROWS_WITH(basis_eval<HSH>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval<HSH>(-4, 0.0, 0.0, 1.0, v), Catch::Contains("got -4"));
    REQUIRE_THROWS_WITH(basis_eval<HSH>(2049 * 2049, 0.0, 0.0, 1.0, v),
                        Catch::Contains("bands <= 2048"));
    REQUIRE_THROWS_WITH(basis_eval_batch<HSH>(4, 2, f, f, f, f, 1), Catch::Contains("stride"));
    REQUIRE_THROWS_WITH(basis_eval_sum<HSH>(3, f, 0.f, 0.f, 1.f),
                        Catch::Contains("sphbasis::basis_eval_sum(): expected a square number"));
    CHECK(HSH::valid_count(2048 * 2048));
    CHECK_FALSE(HSH::valid_count(2049 * 2049));
}
