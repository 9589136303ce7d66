// Tests of param/concentric.hpp: Shirley-Chiu's concentric map between square and disk.
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sphbasis/param/concentric.hpp>

using namespace sphbasis::param;

TEMPLATE_TEST_CASE("concentric: square -> disk -> square round trip", "[param][concentric]", float,
                   double) {
    using T = TestType;
    const T tol = std::numeric_limits<T>::epsilon() * 16;
    // A grid that includes the border, the corners, the centre and the diagonals.
    for (int j = 0; j <= 40; ++j)
        for (int i = 0; i <= 40; ++i) {
            const T u = T(i) / T(40), v = T(j) / T(40);
            const Point2<T> p = square_to_uniform_disk_concentric(u, v);
            REQUIRE(p.x * p.x + p.y * p.y <= T(1) + tol);
            const Point2<T> s = uniform_disk_to_square_concentric(p.x, p.y);
            if (i == 20 && j == 20) {
                CHECK(s.x == T(0.5));
                CHECK(s.y == T(0.5));
                continue;
            }
            INFO("u " << u << " v " << v << " back " << s.x << " " << s.y);
            CHECK(std::fabs(s.x - u) <= tol);
            CHECK(std::fabs(s.y - v) <= tol);
        }
}

TEMPLATE_TEST_CASE("concentric: Chebyshev rings map to circles of the same radius",
                   "[param][concentric]", float, double) {
    using T = TestType;
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0, 1);
    for (int k = 0; k < 2000; ++k) {
        const T u = T(U(rng)), v = T(U(rng));
        const Point2<T> p = square_to_uniform_disk_concentric(u, v);
        const double r = std::fmax(std::fabs(2.0 * u - 1), std::fabs(2.0 * v - 1));
        CHECK(std::sqrt(double(p.x) * p.x + double(p.y) * p.y) ==
              Approx(r).margin(sizeof(T) == 4 ? 1e-6 : 1e-13));
    }
    // The border is the unit circle; the four edge midpoints land on the axes.
    const Point2<T> e = square_to_uniform_disk_concentric(T(1), T(0.5));
    CHECK(e.x == Approx(1.0));
    CHECK(std::fabs(e.y) < 1e-7);
    const Point2<T> n = square_to_uniform_disk_concentric(T(0.5), T(1));
    CHECK(std::fabs(n.x) < 1e-7);
    CHECK(n.y == Approx(1.0));
}

TEST_CASE("concentric: area preserving up to pi; pdf 1/pi", "[param][concentric]") {
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    const double h = 1e-6;
    for (int k = 0; k < 2000; ++k) {
        const double u = U(rng), v = U(rng);
        // Skip the diagonals, where the map is only C0 (one-sided derivatives differ).
        if (std::fabs(std::fabs(2 * u - 1) - std::fabs(2 * v - 1)) < 1e-4) continue;
        const auto a = square_to_uniform_disk_concentric(u + h, v);
        const auto b = square_to_uniform_disk_concentric(u - h, v);
        const auto c = square_to_uniform_disk_concentric(u, v + h);
        const auto d = square_to_uniform_disk_concentric(u, v - h);
        const double det = ((a.x - b.x) * (c.y - d.y) - (a.y - b.y) * (c.x - d.x)) / (4 * h * h);
        CHECK(std::fabs(det) == Approx(3.141592653589793).epsilon(1e-6));
        const auto p = square_to_uniform_disk_concentric(u, v);
        CHECK(square_to_uniform_disk_concentric_pdf(p.x, p.y) * std::fabs(det) ==
              Approx(1.0).epsilon(1e-6));
    }
    CHECK(square_to_uniform_disk_concentric_pdf(0.9, 0.9) == 0.0);
}

TEST_CASE("concentric: continuous across the diagonals and the origin", "[param][concentric]") {
    for (int k = 1; k < 50; ++k) {
        const double t = k / 50.0;  // along the diagonal u - 0.5 = v - 0.5 = t/2
        for (double sx : {-1.0, 1.0})
            for (double sy : {-1.0, 1.0}) {
                const double u = 0.5 + sx * t / 2, v = 0.5 + sy * t / 2;
                const auto a = square_to_uniform_disk_concentric(u + 1e-9, v);
                const auto b = square_to_uniform_disk_concentric(u, v + 1e-9);
                CHECK(std::hypot(a.x - b.x, a.y - b.y) < 1e-8);
            }
    }
    const auto c = square_to_uniform_disk_concentric(0.5 + 1e-12, 0.5 - 1e-12);
    CHECK(std::hypot(c.x, c.y) < 1e-11);
    // Points slightly outside the disk (rounding) clamp onto the square's border.
    const auto s = uniform_disk_to_square_concentric(1.0 + 1e-9, 0.0);
    CHECK(s.x == 1.0);
    CHECK(s.y == Approx(0.5));
}
