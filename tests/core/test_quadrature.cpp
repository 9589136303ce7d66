// Tests for core/quadrature.hpp and core/sampling.hpp.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/core/sampling.hpp>
#include <vector>

using namespace sphbasis;

namespace {
// Exact integral of x^a y^b z^c over the unit sphere (Folland 2001): 0 unless a, b, c are all
// even; then 2 G(b1) G(b2) G(b3) / G(b1 + b2 + b3) with b_i = (a_i + 1)/2.
double sphere_monomial(int a, int b, int c) {
    if (a % 2 || b % 2 || c % 2) return 0;
    const double b1 = (a + 1) / 2.0, b2 = (b + 1) / 2.0, b3 = (c + 1) / 2.0;
    return 2 * std::exp(std::lgamma(b1) + std::lgamma(b2) + std::lgamma(b3) -
                        std::lgamma(b1 + b2 + b3));
}
// Over the upper hemisphere: half of the sphere's for even c; for odd c (a, b even), the
// integral of z^c over z >= 0 doubles what symmetry would cancel: computed by the 1-D formula
// int_0^1 z^c (1-z^2)^((a+b)/2) dz * int_0^2pi cos^a sin^b.
double hemisphere_monomial(int a, int b, int c) {
    if (a % 2 || b % 2) return 0;
    if (c % 2 == 0) return 0.5 * sphere_monomial(a, b, c);
    // Beta function B((c+1)/2, (a+b)/2 + 1) / 2 times the phi integral.
    const double p = (a + b) / 2.0;
    const double zint = 0.5 * std::exp(std::lgamma((c + 1) / 2.0) + std::lgamma(p + 1) -
                                       std::lgamma((c + 1) / 2.0 + p + 1));
    const double phint = 2 * std::exp(std::lgamma((a + 1) / 2.0) + std::lgamma((b + 1) / 2.0) -
                                      std::lgamma((a + b) / 2.0 + 1));
    return zint * phint;
}
}  // namespace

TEST_CASE("quadrature: Gauss-Legendre integrates polynomials of degree 2n-1 exactly",
          "[quadrature]") {
    for (int n : {1, 2, 3, 7, 20, 100, 1000}) {
        std::vector<double> t, w;
        gauss_legendre(n, t, w);
        for (int k = 0; k <= std::min(2 * n - 1, 60); ++k) {
            double s = 0;
            for (std::size_t i = 0; i < t.size(); ++i) s += w[i] * std::pow(t[i], k);
            const double exact = k % 2 ? 0.0 : 2.0 / (k + 1);
            INFO("n=" << n << " k=" << k);
            REQUIRE(std::fabs(s - exact) <= 1e-14 * n);
        }
    }
    std::vector<double> t, w;
    REQUIRE_THROWS_AS(gauss_legendre(0, t, w), std::invalid_argument);
}

TEST_CASE("quadrature: sphere and hemisphere rules are exact to their degree", "[quadrature]") {
    for (int degree : {0, 1, 2, 5, 8, 13}) {
        const auto s = sphere_rule(degree), h = hemisphere_rule(degree);
        for (int a = 0; a <= degree; ++a)
            for (int b = 0; a + b <= degree; ++b)
                for (int c = 0; a + b + c <= degree; ++c) {
                    double qs = 0, qh = 0;
                    for (std::size_t i = 0; i < s.size(); ++i)
                        qs += s.w[i] * std::pow(s.x[i], a) * std::pow(s.y[i], b) *
                              std::pow(s.z[i], c);
                    for (std::size_t i = 0; i < h.size(); ++i)
                        qh += h.w[i] * std::pow(h.x[i], a) * std::pow(h.y[i], b) *
                              std::pow(h.z[i], c);
                    INFO("degree " << degree << " monomial " << a << " " << b << " " << c);
                    REQUIRE(std::fabs(qs - sphere_monomial(a, b, c)) <= 1e-13);
                    REQUIRE(std::fabs(qh - hemisphere_monomial(a, b, c)) <= 1e-13);
                }
    }
    // One degree too many is not exact (the test can fail): z^(d+1) or x^(d+1) breaks.
    const auto h = hemisphere_rule(4);
    double q = 0;
    for (std::size_t i = 0; i < h.size(); ++i) q += h.w[i] * std::pow(h.x[i], 6);
    CHECK(std::fabs(q - hemisphere_monomial(6, 0, 0)) > 1e-6);
    REQUIRE_THROWS_AS(sphere_rule(-1), std::invalid_argument);
}

TEST_CASE("sqrt(z) hemisphere rule: exact for polynomials times sqrt(z)", "[quadrature]") {
    const DirectionalRule r = hemisphere_rule_sqrt(12, 13);
    double area = 0, sz = 0, z3 = 0, x2y2sz = 0, x3z = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
        area += r.w[i];
        sz += r.w[i] * std::sqrt(r.z[i]);
        z3 += r.w[i] * r.z[i] * r.z[i] * r.z[i];
        x2y2sz += r.w[i] * r.x[i] * r.x[i] * r.y[i] * r.y[i] * std::sqrt(r.z[i]);
        x3z += r.w[i] * r.x[i] * r.x[i] * r.x[i] * r.z[i];
        REQUIRE(r.z[i] > 0);
        REQUIRE(r.x[i] * r.x[i] + r.y[i] * r.y[i] + r.z[i] * r.z[i] == Approx(1).epsilon(1e-15));
    }
    const double two_pi = constants::two_pi;
    CHECK(area == Approx(two_pi).epsilon(1e-14));
    CHECK(sz == Approx(two_pi * 2.0 / 3.0).epsilon(1e-14));  // 2 pi int_0^1 z^(1/2) dz
    CHECK(z3 == Approx(two_pi / 4).epsilon(1e-14));
    // x^2 y^2 = (1 - z^2)^2 cos^2 sin^2: pi/4 int_0^1 (1 - z^2)^2 z^(1/2) dz = pi/4 * 64/231.
    CHECK(x2y2sz == Approx(constants::pi / 4 * 64.0 / 231.0).epsilon(1e-13));
    CHECK(x3z == Approx(0).margin(1e-15));
    CHECK_THROWS_AS(hemisphere_rule_sqrt(0, 4), std::invalid_argument);
}

TEST_CASE("sampling: warps land on their domain and pdfs integrate to one", "[sampling]") {
    const int k = 64;
    std::vector<double> u, v;
    stratified(k, 42, u, v);
    REQUIRE(u.size() == static_cast<std::size_t>(k * k));
    double mean_z_sphere = 0, mean_z_hemi = 0, mean_z_cos = 0, inv_pdf_cos = 0;
    for (std::size_t i = 0; i < u.size(); ++i) {
        const auto a = square_to_uniform_sphere(u[i], v[i]);
        const auto b = square_to_uniform_hemisphere(u[i], v[i]);
        const auto c = square_to_cosine_hemisphere(u[i], v[i]);
        for (const auto& d : {a, b, c}) REQUIRE(std::fabs(dot(d, d) - 1) < 1e-12);
        REQUIRE(b.z >= 0);
        REQUIRE(c.z >= 0);
        mean_z_sphere += a.z;
        mean_z_hemi += b.z;
        mean_z_cos += c.z;
        inv_pdf_cos += c.z > 1e-9 ? 1.0 / cosine_hemisphere_pdf(c) * c.z : 0.0;  // E[f/pdf], f=z
    }
    const double n = double(u.size());
    CHECK(mean_z_sphere / n == Approx(0.0).margin(2e-3));
    CHECK(mean_z_hemi / n == Approx(0.5).margin(2e-3));
    CHECK(mean_z_cos / n == Approx(2.0 / 3.0).margin(2e-3));       // E[z] under z/pi
    CHECK(inv_pdf_cos / n == Approx(constants::pi).margin(1e-9));  // int z dw = pi
    // Low-discrepancy sets: Hammersley and R2 cover the square evenly.
    double su = 0, sv = 0;
    for (std::uint32_t i = 0; i < 1024; ++i) {
        double a, b;
        hammersley(i, 1024, a, b);
        REQUIRE((a >= 0 && a < 1 && b >= 0 && b < 1));
        su += a;
        r2_sequence(i, a, b);
        REQUIRE((a >= 0 && a < 1 && b >= 0 && b < 1));
        sv += b;
    }
    CHECK(su / 1024 == Approx(0.5).margin(1e-3));
    CHECK(sv / 1024 == Approx(0.5).margin(5e-3));
    CHECK(radical_inverse2(1) == 0.5);
    CHECK(radical_inverse2(3) == 0.75);
    REQUIRE_THROWS_AS(stratified(0, 1, u, v), std::invalid_argument);
}

TEST_CASE("quadrature: a rule beyond the table ceiling is refused before allocating",
          "[quadrature]") {
    CHECK_THROWS_WITH(sphbasis::sphere_rule(100000), Catch::Contains("SPHBASIS_MAX_TABLE_BYTES") &&
                                                         Catch::Contains("degree-100000 rule"));
    CHECK_THROWS_AS(sphbasis::hemisphere_rule(20000), std::invalid_argument);
    CHECK(sphbasis::sphere_rule(64).size() == 33u * 65u);
}
