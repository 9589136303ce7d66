// Tests for basis/makhotkin.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/makhotkin.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using namespace sphbasis::test;

namespace {

/// The scale of degree l: |M_l0| at the pole, sqrt((l+1)/pi), the largest value of the band's
/// functions.
double scale(int l) { return std::sqrt((l + 1) / pi); }

/// What the shared checks (tests/support/basis_checks.hpp) need to know of Makhotkin.
using Traits = HemiTraits<Makhotkin, makhotkin::detail::RowKernel, makhotkin::detail::ColumnKernel,
                          scale, sh::degree_of, makhotkin::index>;

}  // namespace

TEST_CASE("makhotkin: bands 0-2 closed forms and band-1 signs pin the convention", "[makhotkin]") {
    const auto closed_forms = [](double x, double y, double z) {
        const double sz = std::sqrt(z), r = std::sqrt(1 + z);
        return std::array<double, 9>{std::sqrt(z / pi),
                                     2 * std::sqrt(3 / pi) * y * z / r,
                                     std::sqrt(2 / pi) * sz * (3 * z - 2),
                                     2 * std::sqrt(3 / pi) * x * z / r,
                                     4 * std::sqrt(15 / pi) * x * y * z * sz / (1 + z),
                                     std::sqrt(3 / pi) * y * z * (10 * z - 6) / r,
                                     std::sqrt(3 / pi) * sz * (10 * z * z - 12 * z + 3),
                                     std::sqrt(3 / pi) * x * z * (10 * z - 6) / r,
                                     2 * std::sqrt(15 / pi) * z * sz * (x * x - y * y) / (1 + z)};
    };
    check_closed_forms<Makhotkin>(closed_forms, 64 * eps * scale(2));
    // Band 1: M_1-1 ~ +y, M_11 ~ +x (no Condon-Shortley phase; Ishmukhametov labels these the other
    // way round).
    const auto a =
        check_band1_signs<Makhotkin>(3, 2 * std::sqrt(3 / pi) * 0.6 * 0.8 / std::sqrt(1.8));
    CHECK(a[2] > 0);  // sqrt(2/pi) sqrt(z) (3z - 2) at z = 0.8
    // Ishmukhametov's (1.42) M_20 = sqrt(3/pi) sqrt(z) (1 + 16(z-1) + 10(z-1)^2) is a misprint: 8,
    // not 16.
    const double z = 0.8, m20 = std::sqrt(3 / pi) * std::sqrt(z) *
                                (1 + 8 * (z - 1) + 10 * (z - 1) * (z - 1));
    CHECK(a[0] == Approx(std::sqrt(z / pi)).epsilon(1e-15));  // (1.33) prints z, not sqrt(z)
    CHECK(eval_bands<Makhotkin>(3, 0.6, 0.0, 0.8)[6] == Approx(m20).epsilon(1e-14));
    check_square_counts<Traits>();
    check_declared<Makhotkin>("makhotkin", 2048 * 2048);
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
    check_gram_identity<Makhotkin>(
        band_range(10), [](int bands) { return 2 * bands - 1; }, 1e-13, false);
}

TEST_CASE("makhotkin: Gram matrix is the identity by exact quadrature, 16 to 33 bands",
          "[makhotkin][slow]") {
    check_gram_identity<Makhotkin>(
        {16, 24, 33}, [](int bands) { return 2 * bands - 1; }, 1e-12, true);
}

TEST_CASE("makhotkin: column recurrence is orthonormal per order to 512 bands",
          "[makhotkin][slow]") {
    // At phi = 0 the m >= 0 functions are g_lm(z) cos(0) = g_lm(z), and the hemisphere integral of
    // M_lm M_l'm is pi (1 + delta_m0) int_0^1 g_lm g_l'm dz: a polynomial of degree <= 2 bands - 1
    // in z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    check_column_orthonormal<Traits>({0, 1, 2, 100, 300, 510, 511}, 1);
}

// The shared cases: reference, kernels, prefix, batch, float (measured worst 3.2 (l + 1)^1.5, near
// the pole), below the horizon, hard directions.
SPHBASIS_HEMI_BASIS_TESTS("makhotkin", Traits, 16)

TEST_CASE("makhotkin: pole and horizon are finite and exact", "[makhotkin]") {
    // Pole: only m = 0 survives, M_l0(1) = N_l0 P_l^(0,1)(1) = sqrt((l+1)/pi) = S_l. Horizon: the
    // sqrt(z) factor makes every function 0.
    check_pole_and_horizon<Traits>(
        1, [](int l, int m) { return m == 0 ? scale(l) : 0.0; }, [](int, int) { return 0.0; },
        true);
}

TEST_CASE("makhotkin: bad sizes throw", "[makhotkin]") {
    check_bad_counts<Makhotkin>("a square number", "(bands^2, bands <= 2048)", -4, 2049 * 2049, 4,
                                3);
}
