// Tests for basis/zernike.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/zernike.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using namespace sphbasis::test;

namespace {

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

/// What the shared checks (tests/support/basis_checks.hpp) need to know of Zernike.
using Traits = HemiTraits<Zernike, zernike::detail::RowKernel, zernike::detail::ColumnKernel, scale,
                          band_of, zernike::index>;

}  // namespace

TEST_CASE("zernike: bands 0-2 closed forms and band-1 signs pin the convention", "[zernike]") {
    const auto closed_forms = [](double x, double y, double z) {
        const double r = std::sqrt(1 + z);
        return std::array<double, 6>{1 / std::sqrt(2 * pi),
                                     std::sqrt(2 / pi) * y / r,
                                     std::sqrt(2 / pi) * x / r,
                                     2 * std::sqrt(3 / pi) * x * y / (1 + z),
                                     std::sqrt(3 / (2 * pi)) * (1 - 2 * z),
                                     std::sqrt(3 / pi) * (x * x - y * y) / (1 + z)};
    };
    check_closed_forms<Zernike>(closed_forms, 16 * eps * scale(2));
    // Band 1: Z_1-1 ~ +y, Z_11 ~ +x (Ishmukhametov's (1.48) prints -sqrt(2/pi) x/sqrt(1+z), a
    // spurious minus; its (1.47), (1.49) carry a Condon-Shortley-like minus on the sin functions).
    const auto a = check_band1_signs<Zernike>(2, std::sqrt(2 / pi) * 0.6 / std::sqrt(1.8));
    // (2/sqrt(pi)) cos(phi) sin(t/2), Ishmukhametov's left side of (1.48), is the same function.
    CHECK(a[2] == Approx(2 / std::sqrt(pi) * std::sin(0.5 * std::acos(0.8))).epsilon(1e-14));
    CHECK(eval_bands<Zernike>(3, 0.0, 0.6, 0.8)[3] == 0);
    CHECK(eval_bands<Zernike>(3, 0.6, 0.6, std::sqrt(0.28))[3] > 0);  // Z_2-2 ~ +xy
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
    check_declared<Zernike>("zernike", 2048 * 2049 / 2);
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
    check_gram_identity<Zernike>(
        band_range(10), [](int bands) { return 2 * (bands - 1); }, 1e-13, false);
}

TEST_CASE("zernike: Gram matrix is the identity by exact quadrature, 16 to 48 bands",
          "[zernike][slow]") {
    check_gram_identity<Zernike>(
        {16, 32, 48}, [](int bands) { return 2 * (bands - 1); }, 1e-12, true);
}

TEST_CASE("zernike: column recurrence is orthonormal per order to 512 bands", "[zernike][slow]") {
    // At phi = 0 the m >= 0 functions are g_nm(z) cos(0) = g_nm(z), and the hemisphere integral of
    // Z_nm Z_n'm is pi (1 + delta_m0) int_0^1 g_nm g_n'm dz: a polynomial of degree <= bands - 1 in
    // z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    check_column_orthonormal<Traits>({0, 1, 2, 100, 301, 509, 510, 511}, 2);
}

// The shared cases: reference, kernels, prefix, batch, float (measured worst 0.8 (n + 1)^1.5),
// below the horizon, hard directions.
SPHBASIS_HEMI_BASIS_TESTS("zernike", Traits, 15)

TEST_CASE("zernike: pole and horizon are finite and exact", "[zernike]") {
    // Pole (rho = 0): only m = 0 survives, R_n^0(0) = (-1)^(n/2). Horizon (rho = 1): R_n^m(1) = 1,
    // so Z_nm = sqrt((n+1)(2 - delta_m0)/(2 pi)) trig(m phi).
    const double phi = std::atan2(-0.8, 0.6);
    const auto c = [](int n, int m) {
        return std::sqrt((n + 1) * (m == 0 ? 1.0 : 2.0) / (2 * pi));
    };
    check_pole_and_horizon<Traits>(
        2, [&](int n, int m) { return m == 0 ? ((n / 2) % 2 ? -c(n, m) : c(n, m)) : 0.0; },
        [&](int n, int m) {
            return c(n, m) * (m > 0 ? std::cos(m * phi) : m < 0 ? std::sin(-m * phi) : 1.0);
        },
        false);
}

TEST_CASE("zernike: bad sizes throw", "[zernike]") {
    check_bad_counts<Zernike>("a triangular number", "(bands(bands+1)/2, bands <= 2048)", -3,
                              2049 * 2050 / 2, 3, 4);
    double v[16];
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(9, 0.0, 0.0, 1.0, v), Catch::Contains("got 9"));
    CHECK_FALSE(Zernike::valid_count(2147483647));
}
