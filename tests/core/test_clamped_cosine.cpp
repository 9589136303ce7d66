// Tests of sphbasis/core/clamped_cosine.hpp: the closed form of the clamped-cosine factors
// (Ramamoorthi and Hanrahan, SIGGRAPH 2001, eq. 8; Ishmukhametov, "Irradiance Normal Mapping"
// (thesis), eq. 2.3).
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/core/clamped_cosine.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <stdexcept>
#include <vector>

using namespace sphbasis;

TEST_CASE("clamped-cosine factors: Ishmukhametov eq. 2.3 and Funk-Hecke", "[clamped_cosine]") {
    CHECK(clamped_cosine(0) == 1.0);
    CHECK(clamped_cosine(1) == Approx(2.0 / 3.0).epsilon(1e-15));
    CHECK(clamped_cosine(2) == Approx(0.25).epsilon(1e-15));
    CHECK(clamped_cosine(3) == 0.0);
    CHECK(clamped_cosine(4) == Approx(-1.0 / 24.0).epsilon(1e-15));
    CHECK(clamped_cosine(6) == Approx(1.0 / 64.0).epsilon(1e-15));
    // a_l = (1/pi) 2 pi int_0^1 z P_l(z) dz (Funk-Hecke with the kernel max(0, t)).
    std::vector<double> t, w;
    gauss_legendre(40, t, w);
    for (int l = 0; l <= 30; ++l) {
        double s = 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double z = 0.5 * (t[i] + 1);
            double p0 = 1, p1 = z;  // Legendre P_l(z)
            double pl = l == 0 ? 1 : z;
            for (int k = 2; k <= l; ++k) {
                pl = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = pl;
            }
            s += 0.5 * w[i] * z * pl;
        }
        CHECK(clamped_cosine(l) == Approx(2 * s).margin(1e-15));
    }
    CHECK_THROWS_AS(clamped_cosine(-1), std::invalid_argument);
}

TEST_CASE("clamped-cosine factors: the table equals the single values", "[clamped_cosine]") {
    std::vector<double> a(4001);
    clamped_cosine_factors(4001, a.data());
    for (int l = 0; l < 4001; l += (l < 64 ? 1 : 97)) CHECK(a[std::size_t(l)] == clamped_cosine(l));
    CHECK(std::isfinite(a[4000]));
    CHECK(std::fabs(a[4000]) > 0);
    CHECK_THROWS_WITH(clamped_cosine(-3),
                      Catch::Contains("sphbasis::clamped_cosine(): expected l >= 0, got -3"));
}
