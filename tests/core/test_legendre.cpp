// Tests of sphbasis/core/legendre.hpp: the normalised associated Legendre functions, their
// recurrence coefficients and the tables.
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/constants.hpp>
#include <sphbasis/core/legendre.hpp>
#include <vector>

using namespace sphbasis;

TEST_CASE("Legendre: values against closed forms", "[legendre]") {
    const Legendre leg(8);
    REQUIRE(leg.size() == 36);
    std::vector<double> p(leg.size());
    for (double t : {0.0, 0.3, 1.1, 1.5707963267948966, 2.4, 3.0}) {
        const double z = std::cos(t), s = std::sin(t);
        leg.eval(z, s, p.data());
        const double k = 1 / std::sqrt(constants::four_pi);  // Pbar_0^0
        CHECK(p[leg.index(0, 0)] == Approx(k).epsilon(1e-15));
        // Pbar_1^0 = sqrt(3) z k, Pbar_2^0 = sqrt(5) (3 z^2 - 1)/2 k.
        CHECK(p[leg.index(1, 0)] == Approx(std::sqrt(3.0) * z * k).margin(1e-15));
        CHECK(p[leg.index(2, 0)] ==
              Approx(std::sqrt(5.0) * 0.5 * (3 * z * z - 1) * k).margin(1e-15));
        // Pbar_3^3 = sqrt(35/32) s^3 k (no Condon-Shortley phase: y_33 = sqrt(2) Pbar_3^3 cos 3phi
        // = sqrt(35/(32 pi)) s^3 cos 3 phi).
        CHECK(p[leg.index(3, 3)] == Approx(std::sqrt(35.0 / 16.0) * s * s * s * k).margin(1e-15));
        // Pbar_2^1 = sqrt(15/4) z s k / ... : y_21 = sqrt(15/(4 pi)) x z = sqrt(2) Pbar_2^1 cos
        // phi.
        CHECK(p[leg.index(2, 1)] == Approx(std::sqrt(15.0 / 2.0) * z * s * k).margin(1e-15));
    }
    // The coefficients.
    CHECK(legendre_a(2, 0) == Approx(std::sqrt(15.0 / 4.0)).epsilon(1e-15));
    CHECK(legendre_b(2, 0) == Approx(std::sqrt(1.0 / 3.0)).epsilon(1e-15));
    CHECK(legendre_a(5, 2) == Approx(std::sqrt(99.0 / 21.0)).epsilon(1e-15));
    CHECK(legendre_b(5, 2) == Approx(std::sqrt(12.0 / 63.0)).epsilon(1e-15));
}

TEST_CASE("Legendre: weighted sums equal the sum of single evaluations", "[legendre]") {
    const Legendre leg(30);
    std::vector<double> p(leg.size()), sum(leg.size(), 0.0), ws(leg.size());
    double z[8], s[8], w[8];
    for (int g = 0; g < 5; ++g) {
        const double t = 0.2 + 0.55 * g;
        z[g] = std::cos(t);
        s[g] = std::sin(t);
        w[g] = 0.1 + 0.3 * g;
        leg.eval(z[g], s[g], p.data());
        for (std::size_t k = 0; k < p.size(); ++k) sum[k] += w[g] * p[k];
    }
    leg.eval_weighted_sum(5, z, s, w, ws.data());
    for (std::size_t k = 0; k < p.size(); ++k) CHECK(ws[k] == Approx(sum[k]).margin(1e-14));
}

TEST_CASE("Legendre: the SH column recurrence agrees with the table at high degree", "[legendre]") {
    // sh::eval above 256 bands runs the column recurrence (basis/sh.hpp) with legendre_a/b on the
    // fly; the table runs the same recurrence from tabulated coefficients.
    const int bands = 300;
    const Legendre leg(bands);
    std::vector<double> p(leg.size()), y(static_cast<std::size_t>(bands * bands));
    for (double th : {0.4, 1.2, 2.0}) {
        const double ph = 0.7;
        sh::eval(bands, std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th),
                 y.data());
        leg.eval(std::cos(th), std::sin(th), p.data());
        for (int l = 0; l < bands; l += 7)
            for (int m = 0; m <= l; m += 5) {
                const double trig = m > 0 ? constants::sqrt2 * std::cos(m * ph) : 1.0;
                CHECK(p[leg.index(l, m)] * trig ==
                      Approx(y[static_cast<std::size_t>(sh::index(l, m))]).margin(1e-12));
            }
    }
}

TEST_CASE("Legendre tables match the library's SH", "[legendre]") {
    const int bands = 40;
    const Legendre leg(bands);
    std::vector<double> p(leg.size()), y(static_cast<std::size_t>(bands * bands));
    for (int t = 0; t < 12; ++t) {
        const double th = 0.05 + 0.26 * t, ph = 0.3 + 0.7 * t;
        const double x = std::sin(th) * std::cos(ph), yy = std::sin(th) * std::sin(ph),
                     z = std::cos(th);
        sh::eval(bands, x, yy, z, y.data());
        leg.eval(z, std::sin(th), p.data());
        for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; ++m) {
                const int am = m < 0 ? -m : m;
                const double trig = m > 0   ? constants::sqrt2 * std::cos(m * ph)
                                    : m < 0 ? constants::sqrt2 * std::sin(am * ph)
                                            : 1.0;
                CHECK(p[leg.index(l, am)] * trig ==
                      Approx(y[static_cast<std::size_t>(sh::index(l, m))]).margin(1e-12));
            }
    }
}
