// Tests for basis/makhotkin.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/makhotkin.hpp>
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

/// The scale of degree l: |M_l0| at the pole, sqrt((l+1)/pi), the largest value of the band's
/// functions.
double scale(int l) { return std::sqrt((l + 1) / pi); }

std::vector<double> eval_d(int bands, double x, double y, double z) {
    return test::eval_bands<Makhotkin>(bands, x, y, z);
}

/// What the shared checks (tests/support/basis_checks.hpp) need to know of Makhotkin.
struct Traits {
    using Basis = Makhotkin;
    using RowKernel = makhotkin::detail::RowKernel;
    using ColumnKernel = makhotkin::detail::ColumnKernel;
    static double scale(int l) { return ::scale(l); }
    static int degree_of(int k) { return sh::degree_of(k); }
    static int index(int l, int m) { return makhotkin::index(l, m); }
    template <class F>
    static void with_kernel(int bands, F&& f) {
        makhotkin::detail::with_bands_kernel(bands, std::forward<F>(f));
    }
};

}  // namespace

TEST_CASE("makhotkin: bands 0-2 closed forms and band-1 signs pin the convention", "[makhotkin]") {
    auto dirs = random_dirs(50, 1);
    dirs.push_back({0.48, -0.6, 0.64});
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0, -1, 0});
    for (const auto& d : dirs) {
        const double x = d[0], y = d[1], z = d[2], sz = std::sqrt(z), r = std::sqrt(1 + z);
        const double c[9] = {std::sqrt(z / pi),
                             2 * std::sqrt(3 / pi) * y * z / r,
                             std::sqrt(2 / pi) * sz * (3 * z - 2),
                             2 * std::sqrt(3 / pi) * x * z / r,
                             4 * std::sqrt(15 / pi) * x * y * z * sz / (1 + z),
                             std::sqrt(3 / pi) * y * z * (10 * z - 6) / r,
                             std::sqrt(3 / pi) * sz * (10 * z * z - 12 * z + 3),
                             std::sqrt(3 / pi) * x * z * (10 * z - 6) / r,
                             2 * std::sqrt(15 / pi) * z * sz * (x * x - y * y) / (1 + z)};
        const auto v = eval_d(3, x, y, z);
        for (int k = 0; k < 9; ++k) {
            INFO("k=" << k << " dir=" << x << "," << y << "," << z);
            REQUIRE(std::fabs(v[static_cast<std::size_t>(k)] - c[k]) <= 64 * eps * scale(2));
        }
    }
    // Band 1: M_1-1 ~ +y, M_11 ~ +x (no Condon-Shortley phase; Ishmukhametov labels these the other
    // way round).
    const auto a = eval_d(2, 0.6, 0.0, 0.8);
    CHECK(a[3] > 0);
    CHECK(a[1] == 0);
    CHECK(a[2] > 0);  // sqrt(2/pi) sqrt(z) (3z - 2) at z = 0.8
    const auto b = eval_d(2, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(std::fabs(b[3]) < 1e-16);
    CHECK(a[3] == Approx(2 * std::sqrt(3 / pi) * 0.6 * 0.8 / std::sqrt(1.8)).epsilon(1e-15));
    // Ishmukhametov's (1.42) M_20 = sqrt(3/pi) sqrt(z) (1 + 16(z-1) + 10(z-1)^2) is a misprint: 8,
    // not 16.
    const double z = 0.8, m20 = std::sqrt(3 / pi) * std::sqrt(z) *
                                (1 + 8 * (z - 1) + 10 * (z - 1) * (z - 1));
    CHECK(a[0] == Approx(std::sqrt(z / pi)).epsilon(1e-15));  // (1.33) prints z, not sqrt(z)
    CHECK(eval_d(3, 0.6, 0.0, 0.8)[6] == Approx(m20).epsilon(1e-14));
    CHECK(makhotkin::index(2, -1) == 5);
    CHECK(Makhotkin::count(4) == 16);
    CHECK(Makhotkin::bands_of(16) == 4);
    CHECK(Makhotkin::bands_of(15) == -1);
    CHECK(std::string(Makhotkin::name) == "makhotkin");
    CHECK(Makhotkin::domain == Domain::hemisphere);
    CHECK(Makhotkin::orthonormal);
    CHECK(Makhotkin::max_count() == 2048 * 2048);
}

// Why the product rule is exact: M_l^m = N sqrt(z) (1-u^2)^(|m|/2) P_{l-|m|}(u) trig(m phi), u =
// 2z-1. For two functions of orders m, m' the product is z (1-u^2)^((|m|+|m'|)/2) times a
// polynomial in u times trig(m phi) trig(m' phi). If |m| + |m'| is even, (1-u^2)^(...) =
// (4z(1-z))^(...) is a polynomial and the product is a polynomial in z of degree <= 1 + l + l' <= 2
// bands - 1, integrated exactly by the (bands)-point Gauss-Legendre rule in z; the phi factor is a
// trigonometric polynomial of degree <= 2(bands-1) < the 2 bands uniform points in phi. If |m| +
// |m'| is odd then m != m' and the uniform phi rule sums cos/sin((m -+ m') phi), 0 < |m -+ m'| < 2
// bands, to exactly 0 at every z node. Hence hemisphere_rule(2 bands - 1) gives the exact Gram
// matrix.
TEST_CASE("makhotkin: Gram matrix is the identity by exact quadrature", "[makhotkin]") {
    test::check_gram_identity<Makhotkin>(
        test::band_range(10), [](int bands) { return 2 * bands - 1; }, 1e-13, false);
}

TEST_CASE("makhotkin: Gram matrix is the identity by exact quadrature, 16 to 33 bands",
          "[makhotkin][slow]") {
    test::check_gram_identity<Makhotkin>(
        {16, 24, 33}, [](int bands) { return 2 * bands - 1; }, 1e-12, true);
}

TEST_CASE("makhotkin: column recurrence is orthonormal per order to 512 bands",
          "[makhotkin][slow]") {
    // At phi = 0 the m >= 0 functions are g_lm(z) cos(0) = g_lm(z), and the hemisphere integral of
    // M_lm M_l'm is pi (1 + delta_m0) int_0^1 g_lm g_l'm dz: a polynomial of degree <= 2 bands - 1
    // in z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    const double worst = test::column_gram_residual<Traits>(512, {0, 1, 2, 100, 300, 510, 511}, 1);
    WARN("makhotkin per-order Gram residual at 512 bands: " << worst);
    CHECK(worst < 1e-12);
}

TEST_CASE("makhotkin: values against the mpmath reference (l <= 255)", "[makhotkin][reference]") {
    test::check_hemi_reference<Traits>(255);
}

TEST_CASE("makhotkin: values against the mpmath reference (l <= 2047)",
          "[makhotkin][reference][slow]") {
    test::check_hemi_reference<Traits>(2047);
}

TEST_CASE("makhotkin: unrolled kernels, row recurrence and column recurrence agree",
          "[makhotkin]") {
    test::check_kernels_agree<Traits>();
}

TEST_CASE("makhotkin: prefix property", "[makhotkin]") { test::check_prefix_property<Traits>(); }

TEMPLATE_TEST_CASE("makhotkin: batch path equals scalar path", "[makhotkin]", float, double) {
    test::check_batch_equals_scalar<Traits, TestType>();
}

TEST_CASE("makhotkin: float is within a stated bound of double", "[makhotkin]") {
    // Bound: |float - double| <= 6 (l + 1)^1.5 ulp(float) * S_l (measured worst 3.2 (l + 1)^1.5,
    // near the pole): the float path normalises the direction in float (near the pole degree-l
    // functions have slope ~l^2 in z) and rounds each recurrence step (~l^1.5 ulp near the ends).
    test::check_float_vs_double<Traits>();
}

TEST_CASE("makhotkin: below the horizon every function is 0", "[makhotkin]") {
    test::check_zero_below_horizon<Makhotkin>();
}

TEST_CASE("makhotkin: pole and horizon are finite and exact", "[makhotkin]") {
    // Pole: only m = 0 survives, M_l0(1) = N_l0 P_l^(0,1)(1) = sqrt((l+1)/pi) = S_l. Horizon: the
    // sqrt(z) factor makes every function 0.
    for (int bands : {1, 3, 8, 20, 64, 65, 300}) {
        const auto p = eval_d(bands, 0, 0, 1);
        const auto h = eval_d(bands, 0.6, -0.8, 0);
        const auto hz = eval_d(bands, 0.6, -0.8, -0.0);  // -0 is on the horizon, not below
        double worst = 0;
        for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; ++m) {
                const std::size_t k = static_cast<std::size_t>(makhotkin::index(l, m));
                const double s = scale(l);
                REQUIRE(std::isfinite(p[k]));
                worst = std::max(worst, std::fabs(p[k] - (m == 0 ? s : 0.0)) / s);
                REQUIRE(h[k] == 0);
                REQUIRE(hz[k] == 0);
            }
        INFO("bands " << bands);
        CHECK(worst <= 1e-14 + 20 * eps * bands);
    }
}

TEST_CASE("makhotkin: hard directions stay finite", "[makhotkin]") {
    test::check_hard_directions_finite<Makhotkin>(16);
}

TEST_CASE("makhotkin: bad sizes throw", "[makhotkin]") {
    double v[16];
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval<Makhotkin>(5, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected a square number (bands^2, bands <= 2048) "
                        "of functions for basis 'makhotkin', got 5");
    REQUIRE_THROWS_WITH(basis_eval<Makhotkin>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval<Makhotkin>(-4, 0.0, 0.0, 1.0, v), Catch::Contains("got -4"));
    REQUIRE_THROWS_WITH(basis_eval<Makhotkin>(2049 * 2049, 0.0, 0.0, 1.0, v),
                        Catch::Contains("bands <= 2048"));
    REQUIRE_THROWS_WITH(basis_eval_batch<Makhotkin>(4, 2, f, f, f, f, 1),
                        Catch::Contains("stride"));
    REQUIRE_THROWS_WITH(basis_eval_sum<Makhotkin>(3, f, 0.f, 0.f, 1.f),
                        Catch::Contains("sphbasis::basis_eval_sum(): expected a square number"));
    CHECK(Makhotkin::valid_count(2048 * 2048));
    CHECK_FALSE(Makhotkin::valid_count(2049 * 2049));
}
