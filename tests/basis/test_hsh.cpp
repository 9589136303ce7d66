// Tests for basis/hsh.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/hsh.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using namespace sphbasis::test;

namespace {

/// The scale of degree l: |H_l0| at the pole, the largest value of the band's functions.
double scale(int l) { return std::sqrt((2 * l + 1) / (2 * pi)); }

/// What the shared checks (tests/support/basis_checks.hpp) need to know of HSH.
using Traits = HemiTraits<HSH, hsh::detail::RowKernel, hsh::detail::ColumnKernel, scale,
                          sh::degree_of, hsh::index>;

}  // namespace

TEST_CASE("hsh: bands 0-2 closed forms and band-1 signs pin the convention", "[hsh]") {
    const auto closed_forms = [](double x, double y, double z) {
        const double q = std::sqrt(z / (1 + z));
        return std::array<double, 9>{1 / std::sqrt(2 * pi),
                                     std::sqrt(6 / pi) * y * q,
                                     std::sqrt(3 / (2 * pi)) * (2 * z - 1),
                                     std::sqrt(6 / pi) * x * q,
                                     2 * std::sqrt(30 / pi) * x * y * z / (1 + z),
                                     std::sqrt(30 / pi) * y * (2 * z - 1) * q,
                                     std::sqrt(5 / (2 * pi)) * (6 * z * z - 6 * z + 1),
                                     std::sqrt(30 / pi) * x * (2 * z - 1) * q,
                                     std::sqrt(30 / pi) * z * (x * x - y * y) / (1 + z)};
    };
    check_closed_forms<HSH>(closed_forms, 64 * eps * scale(2));
    // Band 1: H_1-1 ~ +y, H_10 ~ +(2z - 1), H_11 ~ +x (no Condon-Shortley phase).
    const auto a = check_band1_signs<HSH>(3, std::sqrt(6 / pi) * 0.6 * std::sqrt(0.8 / 1.8));
    CHECK(a[2] > 0);
    check_square_counts<Traits>();
    check_declared<HSH>("hsh", 2048 * 2048);
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
    check_gram_identity<HSH>(
        band_range(10), [](int bands) { return 2 * (bands - 1); }, 1e-13, false);
}

TEST_CASE("hsh: Gram matrix is the identity by exact quadrature, 16 to 33 bands", "[hsh][slow]") {
    check_gram_identity<HSH>(
        {16, 24, 33}, [](int bands) { return 2 * (bands - 1); }, 1e-12, true);
}

TEST_CASE("hsh: column recurrence is orthonormal per order to 512 bands", "[hsh][slow]") {
    // At phi = 0 the m >= 0 functions are g_lm(z) cos(0) = g_lm(z), and the hemisphere integral of
    // H_lm H_l'm is pi (1 + delta_m0) int_0^1 g_lm g_l'm dz: a polynomial of degree <= 2(bands-1)
    // in z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    check_column_orthonormal<Traits>({0, 1, 2, 100, 300, 510, 511}, 1);
}

// The shared cases: reference, kernels, prefix, batch, float (measured worst 3.2 (l + 1)^1.5, near
// the pole), below the horizon, hard directions.
SPHBASIS_HEMI_BASIS_TESTS("hsh", Traits, 16)

TEST_CASE("hsh: pole and horizon are finite and exact", "[hsh]") {
    // Pole: only m = 0 survives, H_l0(1) = S_l. Horizon (u = -1): only m = 0, H_l0 = (-1)^l S_l.
    check_pole_and_horizon<Traits>(
        1, [](int l, int m) { return m == 0 ? scale(l) : 0.0; },
        [](int l, int m) { return m == 0 ? (l % 2 ? -scale(l) : scale(l)) : 0.0; }, false);
}

TEST_CASE("hsh: bad sizes throw", "[hsh]") {
    check_bad_counts<HSH>("a square number", "(bands^2, bands <= 2048)", -4, 2049 * 2049, 4, 3);
}
