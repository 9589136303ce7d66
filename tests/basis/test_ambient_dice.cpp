// Tests for basis/ambient_dice.hpp: Ambient Dice, SRBF variant (Iwanicki and Sloan 2017).
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/ambient_dice.hpp>
#include <sphbasis/basis/registry.hpp>
#include <vector>

#include "../support/basis_checks.hpp"
#include "../support/engine_reference.hpp"

using namespace sphbasis;

TEST_CASE("ambient-dice: constants and values against the reference generator", "[ambient-dice]") {
    CHECK(ambient_dice::axis_a == test::engine_constant("ambient_dice.axis_a"));
    CHECK(ambient_dice::axis_b == test::engine_constant("ambient_dice.axis_b"));
    const auto rows = test::engine_reference("ambient-dice");
    REQUIRE(rows.size() >= 20);
    for (const auto& r : rows) {
        REQUIRE(r.size() == 15);
        std::array<double, 12> d;
        basis_eval<AmbientDice>(12, r[0], r[1], r[2], d.data());
        for (int k = 0; k < 12; ++k)
            CHECK(d[std::size_t(k)] == Approx(r[std::size_t(3 + k)]).margin(8e-16));
    }
}

TEST_CASE("ambient-dice: partition of unity, vertex values, 6 non-zero per direction",
          "[ambient-dice]") {
    for (const auto& d : test::random_dirs(100, 4, false)) {
        std::array<double, 12> v;
        basis_eval<AmbientDice>(12, d[0], d[1], d[2], v.data());
        double s = 0;
        int nonzero = 0;
        for (double x : v) {
            CHECK(x >= 0);
            s += x;
            nonzero += x != 0;
        }
        CHECK(s == Approx(1).epsilon(2e-15));
        CHECK(nonzero == 6);
    }
    // At vertex +a_0 = (A, B, 0): its own function 0.6, each of the five neighbours 0.08.
    std::array<double, 12> v;
    basis_eval<AmbientDice>(12, ambient_dice::axis_a, ambient_dice::axis_b, 0.0, v.data());
    CHECK(v[0] == Approx(0.6).epsilon(1e-15));
    int neighbours = 0;
    for (int k = 1; k < 12; ++k)
        if (v[std::size_t(k)] != 0) {
            CHECK(v[std::size_t(k)] == Approx(0.08).epsilon(1e-14));
            ++neighbours;
        }
    CHECK(neighbours == 5);
}

TEST_CASE("ambient-dice: cos^2 and cos^4 on the vertex hemispheres are each a partition of unity",
          "[ambient-dice]") {
    // The paper's premise ("the partition of unity formed by cos^2 and cos^4 restricted to a
    // hemisphere oriented along the directions of the icosahedron vertices"): over the 12
    // vertices, each direction in the hemisphere of 6 of them, sum c^2 = 2 and sum c^4 = 6/5, so
    // c^2/2 and 5 c^4/6 each sum to 1 and any blend w c^2/2 + (1 - w) 5 c^4/6 does; the library's
    // w = 0.7 (w2 = 0.35, w4 = 0.25) is one such blend.
    const double a = ambient_dice::axis_a, b = ambient_dice::axis_b;
    const double axes[6][3] = {{a, b, 0}, {-a, b, 0}, {0, a, b}, {0, -a, b}, {b, 0, a}, {b, 0, -a}};
    for (const auto& d : test::random_dirs(500, 9, false)) {
        double s2 = 0, s4 = 0;
        for (const auto& ax : axes) {
            const double c = ax[0] * d[0] + ax[1] * d[1] + ax[2] * d[2];
            s2 += c * c / 2;
            s4 += 5 * c * c * c * c / 6;
        }
        CHECK(s2 == Approx(1).epsilon(4e-15));
        CHECK(s4 == Approx(1).epsilon(4e-15));
    }
    CHECK(ambient_dice::w2 * 2 + ambient_dice::w4 * 6 / 5 == Approx(1).epsilon(1e-15));
}

TEST_CASE("ambient-dice: batch equals scalar, float near double, registry", "[ambient-dice]") {
    const auto dirs = test::random_dirs(37, 10, false);
    const auto inf = test::scaled_inputs<float>(dirs, 0.5);
    const auto ind = test::scaled_inputs<double>(dirs, 0.5);
    std::vector<float> cf(12);
    for (std::size_t k = 0; k < 12; ++k) cf[k] = float(std::sin(double(k) + 1));
    std::vector<double> cd(cf.begin(), cf.end());
    test::check_batch_equals_scalar<AmbientDice, float>(12, cf, inf, 3e-7f, 3e-7, 4e-6f);
    test::check_batch_equals_scalar<AmbientDice, double>(12, cd, ind, 1e-15, 1e-15, 1e-14);
    const BasisInfo& b = find_basis("ambient-dice");
    CHECK(b.domain == Domain::sphere);
    CHECK(b.valid_count(12));
    std::array<double, 12> v;
    CHECK_THROWS_WITH(basis_eval<AmbientDice>(6, 0.0, 0.0, 1.0, v.data()),
                      Catch::Contains("12 functions for basis 'ambient-dice'"));
}
