// Tests for basis/zernike.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/zernike.hpp>
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

/// The scale of band n: sqrt((n+1)/pi), the largest value of the band's functions (m != 0 at the
/// rim, where |R_n^m| = 1).
double scale(int n) { return std::sqrt((n + 1) / pi); }

/// The band of function index k.
int band_of(int k) {
    int n = static_cast<int>(std::sqrt(2.0 * k));
    while (n > 0 && zernike::count(n) > k) --n;
    while (zernike::count(n + 1) <= k) ++n;
    return n;
}

std::vector<double> eval_d(int bands, double x, double y, double z) {
    return test::eval_bands<Zernike>(bands, x, y, z);
}

/// What the shared checks (tests/support/basis_checks.hpp) need to know of Zernike.
struct Traits {
    using Basis = Zernike;
    using RowKernel = zernike::detail::RowKernel;
    using ColumnKernel = zernike::detail::ColumnKernel;
    static double scale(int l) { return ::scale(l); }
    static int degree_of(int k) { return band_of(k); }
    static int index(int l, int m) { return zernike::index(l, m); }
    template <class F>
    static void with_kernel(int bands, F&& f) {
        zernike::detail::with_bands_kernel(bands, std::forward<F>(f));
    }
};

}  // namespace

TEST_CASE("zernike: bands 0-2 closed forms and band-1 signs pin the convention", "[zernike]") {
    auto dirs = random_dirs(50, 1);
    dirs.push_back({0.48, -0.6, 0.64});
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0, -1, 0});
    for (const auto& d : dirs) {
        const double x = d[0], y = d[1], z = d[2], r = std::sqrt(1 + z);
        const double c[6] = {1 / std::sqrt(2 * pi),
                             std::sqrt(2 / pi) * y / r,
                             std::sqrt(2 / pi) * x / r,
                             2 * std::sqrt(3 / pi) * x * y / (1 + z),
                             std::sqrt(3 / (2 * pi)) * (1 - 2 * z),
                             std::sqrt(3 / pi) * (x * x - y * y) / (1 + z)};
        const auto v = eval_d(3, x, y, z);
        for (int k = 0; k < 6; ++k) {
            INFO("k=" << k << " dir=" << x << "," << y << "," << z);
            REQUIRE(std::fabs(v[static_cast<std::size_t>(k)] - c[k]) <= 16 * eps * scale(2));
        }
    }
    // Band 1: Z_1-1 ~ +y, Z_11 ~ +x (Ishmukhametov's (1.48) prints -sqrt(2/pi) x/sqrt(1+z), a
    // spurious minus; its (1.47), (1.49) carry a Condon-Shortley-like minus on the sin functions).
    const auto a = eval_d(2, 0.6, 0.0, 0.8);
    CHECK(a[2] > 0);
    CHECK(a[1] == 0);
    const auto b = eval_d(2, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(std::fabs(b[2]) < 1e-16);
    CHECK(a[2] == Approx(std::sqrt(2 / pi) * 0.6 / std::sqrt(1.8)).epsilon(1e-15));
    // (2/sqrt(pi)) cos(phi) sin(t/2), Ishmukhametov's left side of (1.48), is the same function.
    CHECK(a[2] == Approx(2 / std::sqrt(pi) * std::sin(0.5 * std::acos(0.8))).epsilon(1e-14));
    CHECK(eval_d(3, 0.0, 0.6, 0.8)[3] == 0);
    CHECK(eval_d(3, 0.6, 0.6, std::sqrt(0.28))[3] > 0);  // Z_2-2 ~ +xy
    CHECK(zernike::index(0, 0) == 0);
    CHECK(zernike::index(1, -1) == 1);
    CHECK(zernike::index(1, 1) == 2);
    CHECK(zernike::index(2, 0) == 4);
    CHECK(zernike::index(3, -1) == 7);
    CHECK(Zernike::count(4) == 10);
    for (int b2 = 1; b2 <= 100; ++b2) {
        CHECK(Zernike::bands_of(Zernike::count(b2)) == b2);
        CHECK(Zernike::bands_of(Zernike::count(b2) + 1) == -1);
    }
    CHECK(std::string(Zernike::name) == "zernike");
    CHECK(Zernike::domain == Domain::hemisphere);
    CHECK(Zernike::orthonormal);
    CHECK(Zernike::max_count() == 2048 * 2049 / 2);
}

// Why the product rule is exact: Z_n^m = N R_n^|m|(rho) trig(m phi) with rho^2 = 1 - z, and
// R_n^m(rho) = rho^m times a polynomial in rho^2 of degree (n - m)/2. For two functions of orders
// m, m' the product is rho^(|m|+|m'|) times a polynomial in rho^2 times trig(m phi) trig(m' phi).
// If |m| + |m'| is even, it is a polynomial in z = 1 - rho^2 of degree (n + n')/2 <= bands - 1,
// integrated exactly by the (bands)-point Gauss-Legendre rule in z; the phi factor is a
// trigonometric polynomial of degree <= 2(bands-1) < the 2 bands - 1 uniform points in phi. If
// |m| + |m'| is odd then m != m' and the uniform phi rule sums cos/sin((m -+ m') phi),
// 0 < |m -+ m'| < 2 bands - 1, to exactly 0 at every z node. Hence hemisphere_rule(2(bands-1))
// (even hemisphere_rule(bands - 1) for the z part) gives the exact Gram matrix.
TEST_CASE("zernike: Gram matrix is the identity by exact quadrature", "[zernike]") {
    test::check_gram_identity<Zernike>(
        test::band_range(10), [](int bands) { return 2 * (bands - 1); }, 1e-13, false);
}

TEST_CASE("zernike: Gram matrix is the identity by exact quadrature, 16 to 48 bands",
          "[zernike][slow]") {
    test::check_gram_identity<Zernike>(
        {16, 32, 48}, [](int bands) { return 2 * (bands - 1); }, 1e-12, true);
}

TEST_CASE("zernike: column recurrence is orthonormal per order to 512 bands", "[zernike][slow]") {
    // At phi = 0 the m >= 0 functions are g_nm(z) cos(0) = g_nm(z), and the hemisphere integral of
    // Z_nm Z_n'm is pi (1 + delta_m0) int_0^1 g_nm g_n'm dz: a polynomial of degree <= bands - 1 in
    // z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    const double worst =
        test::column_gram_residual<Traits>(512, {0, 1, 2, 100, 301, 509, 510, 511}, 2);
    WARN("zernike per-order Gram residual at 512 bands: " << worst);
    CHECK(worst < 1e-12);
}

TEST_CASE("zernike: values against the mpmath reference (l <= 255)", "[zernike][reference]") {
    test::check_hemi_reference<Traits>(255);
}

TEST_CASE("zernike: values against the mpmath reference (l <= 2047)",
          "[zernike][reference][slow]") {
    test::check_hemi_reference<Traits>(2047);
}

TEST_CASE("zernike: unrolled kernels, row recurrence and column recurrence agree", "[zernike]") {
    test::check_kernels_agree<Traits>();
}

TEST_CASE("zernike: prefix property", "[zernike]") { test::check_prefix_property<Traits>(); }

TEMPLATE_TEST_CASE("zernike: batch path equals scalar path", "[zernike]", float, double) {
    test::check_batch_equals_scalar<Traits, TestType>();
}

TEST_CASE("zernike: float is within a stated bound of double", "[zernike]") {
    // Bound: |float - double| <= 6 (n + 1)^1.5 ulp(float) * S_n (measured worst 0.8 (n + 1)^1.5):
    // the float path normalises the direction in float (near the pole band-n functions have slope
    // ~n^2 in z) and rounds each recurrence step (~n^1.5 ulp near the ends).
    test::check_float_vs_double<Traits>();
}

TEST_CASE("zernike: below the horizon every function is 0", "[zernike]") {
    test::check_zero_below_horizon<Zernike>();
}

TEST_CASE("zernike: pole and horizon are finite and exact", "[zernike]") {
    // Pole (rho = 0): only m = 0 survives, R_n^0(0) = (-1)^(n/2). Horizon (rho = 1): R_n^m(1) = 1,
    // so Z_nm = sqrt((n+1)(2 - delta_m0)/(2 pi)) trig(m phi).
    const double phi = std::atan2(-0.8, 0.6);
    for (int bands : {1, 3, 8, 20, 64, 65, 300}) {
        const auto p = eval_d(bands, 0, 0, 1);
        const auto h = eval_d(bands, 0.6, -0.8, 0);
        const auto hz = eval_d(bands, 0.6, -0.8, -0.0);  // -0 is on the horizon, not below
        double worst = 0;
        for (int n = 0; n < bands; ++n)
            for (int m = -n; m <= n; m += 2) {
                const std::size_t k = static_cast<std::size_t>(zernike::index(n, m));
                const double s = scale(n);
                REQUIRE(std::isfinite(p[k]));
                REQUIRE(std::isfinite(h[k]));
                const double c = std::sqrt((n + 1) * (m == 0 ? 1.0 : 2.0) / (2 * pi));
                const double pole = m == 0 ? ((n / 2) % 2 ? -c : c) : 0.0;
                const double rim = c * (m > 0   ? std::cos(m * phi)
                                        : m < 0 ? std::sin(-m * phi)
                                                : 1.0);
                worst = std::max(worst, std::fabs(p[k] - pole) / s);
                worst = std::max(worst, std::fabs(h[k] - rim) / s);
                REQUIRE(hz[k] == h[k]);
            }
        INFO("bands " << bands);
        CHECK(worst <= 1e-14 + 20 * eps * bands);
    }
}

TEST_CASE("zernike: hard directions stay finite", "[zernike]") {
    test::check_hard_directions_finite<Zernike>(15);
}

TEST_CASE("zernike: bad sizes throw", "[zernike]") {
    double v[16];
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(5, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected a triangular number (bands(bands+1)/2, "
                        "bands <= 2048) of functions for basis 'zernike', got 5");
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(-3, 0.0, 0.0, 1.0, v), Catch::Contains("got -3"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(9, 0.0, 0.0, 1.0, v), Catch::Contains("got 9"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(2049 * 2050 / 2, 0.0, 0.0, 1.0, v),
                        Catch::Contains("bands <= 2048"));
    REQUIRE_THROWS_WITH(basis_eval_batch<Zernike>(3, 2, f, f, f, f, 1), Catch::Contains("stride"));
    REQUIRE_THROWS_WITH(
        basis_eval_sum<Zernike>(4, f, 0.f, 0.f, 1.f),
        Catch::Contains("sphbasis::basis_eval_sum(): expected a triangular number"));
    CHECK(Zernike::valid_count(2048 * 2049 / 2));
    CHECK_FALSE(Zernike::valid_count(2049 * 2050 / 2));
    CHECK_FALSE(Zernike::valid_count(2147483647));
}
