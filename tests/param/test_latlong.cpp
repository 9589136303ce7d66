// Tests of param/latlong.hpp: the latitude-longitude map, wrap filtering across the seam.
#include <climits>
#include <sphbasis/param/latlong.hpp>

#include "param_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

TEMPLATE_TEST_CASE("lat-long: round trips incl. seam and poles", "[param][latlong]", float,
                   double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-6 : 1e-14;
    for (int n : {1, 2, 5, 16}) {
        check_map_round_trips<T>(LatLong<T>(n), tol);
    }
    const auto north = latlong_to_square(T(0), T(0), T(1));
    const auto south = latlong_to_square(T(0), T(0), T(-1));
    CHECK(north.y == T(0));
    CHECK(south.y == T(1));
    // Just below the seam phi = 0 wraps to u < 1, never to 1.
    const auto s = latlong_to_square(T(1), -std::numeric_limits<T>::denorm_min(), T(0));
    CHECK(s.x < T(1));
}

TEST_CASE("lat-long: texel solid angles and pdf", "[param][latlong]") {
    const double pi = 3.141592653589793;
    for (int n : {1, 2, 9, 100})
        CHECK(total_solid_angle(LatLong<double>(n)) == Approx(4 * pi).epsilon(1e-14));
    for (int n : {1, 3, 6}) check_texel_solid_angles(LatLong<double>(n), 0, 1, 16, 1e-7);
    const double integral = integrate_sphere(
        [](double x, double y, double z) { return square_to_latlong_pdf(x, y, z); }, false, 500);
    CHECK(integral == Approx(1.0).epsilon(1e-9));
    std::mt19937 rng(10);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    for (int k = 0; k < 1000; ++k) {
        const double u = U(rng), v = U(rng);
        const double jac =
            jacobian([](double a, double b) { return square_to_latlong(a, b); }, u, v, 1e-6);
        const auto d = square_to_latlong(u, v);
        CHECK(square_to_latlong_pdf(d.x, d.y, d.z) * jac == Approx(1.0).epsilon(1e-6));
    }
    CHECK(std::isfinite(square_to_latlong_pdf(0.0, 0.0, 1.0)));
}

TEST_CASE("lat-long: hardware bilinear, wrap in u, clamp in v", "[param][latlong]") {
    const int n = 8;
    const LatLong<double> p(n);
    check_interpolates_at_centres(p, 1e-12);
    // Linear in v (polar angle) is exact between the first and last ring of centres; linear in
    // u is exact away from the seam, where wrapping blends the last column with the first.
    std::vector<double> table(p.texel_count() * 2);
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < 2 * n; ++c) {
            table[p.texel_index(0, c, r) * 2] = (r + 0.5) / n;
            table[p.texel_index(0, c, r) * 2 + 1] = (c + 0.5) / (2 * n);
        }
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0, 1);
    for (int k = 0; k < 2000; ++k) {
        const double u = U(rng), v = 0.5 / n + (1 - 1.0 / n) * U(rng);
        const auto d = square_to_latlong(u, v);
        double out[2];
        lookup(p, table.data(), 2, d.x, d.y, d.z, out);
        CHECK(out[0] == Approx(v).margin(1e-12));
        if (u > 0.5 / (2 * n) && u < 1 - 0.5 / (2 * n)) {
            CHECK(out[1] == Approx(u).margin(1e-12));
        } else {
            // Across the seam: between the last column (1 - 0.5/w) and the first (0.5/w).
            const double w = 2 * n, x = u * w - 0.5;
            const double frac = x - std::floor(x);
            const double expect = (1 - frac) * (1 - 0.5 / w) + frac * (0.5 / w);
            CHECK(out[1] == Approx(expect).margin(1e-12));
        }
    }
    // Continuous across the seam phi = 0 (wrap addressing).
    std::vector<vec3<double>> base, normal;
    for (int k = 0; k < 99; ++k) {
        const double th = 3.141592653589793 * (k + 0.5) / 99;
        base.push_back({std::sin(th), 0.0, std::cos(th)});
        normal.push_back({0.0, 1.0, 0.0});
    }
    const double jump = max_jump(p, smooth_table<double>(p), base, normal, 1e-10);
    CHECK(jump < 1e-7);
}

TEST_CASE("lat-long: convergence", "[param][latlong]") {
    const double a = smooth_mse(LatLong<double>(16), 20000);
    const double b = smooth_mse(LatLong<double>(32), 20000);
    INFO("MSE " << a << " -> " << b);
    CHECK(a / b > 6);
}

TEST_CASE("lat-long: a resolution near INT_MAX is refused before 2n is formed",
          "[param][latlong]") {
    CHECK_THROWS_WITH(sphbasis::param::LatLong<float>(INT_MAX),
                      Catch::Contains("resolution <= 32768"));
    CHECK_THROWS_AS(sphbasis::param::LatLong<double>(INT_MAX / 2 + 1), std::invalid_argument);
}
