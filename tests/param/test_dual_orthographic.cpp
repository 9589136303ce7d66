// Tests of param/dual_orthographic.hpp: the dual orthographic map through the concentric map,
// shrunk so the equator lies on the outer ring of texel centres (seed 000, appendix A).
// The orthographic lift z = sqrt(1 - r^2) is ill-conditioned at the equator: (u, v) carries r,
// and an error eps in r becomes sqrt(2 eps) in z there, so round trips are only good to
// sqrt(2 eps) radians in the worst case (about 2e-8 in double, 5e-4 in float).
#include <sphbasis/param/dual_orthographic.hpp>

#include "dual_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

TEMPLATE_TEST_CASE("dual orthographic: round trips incl. poles and equator",
                   "[param][dual_orthographic]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-3 : 3e-8;
    for (int n : {2, 3, 8, 33}) {
        const DualOrthographic<T> p(n);
        check_roundtrip(p, random_dirs<T>(20000, 1), tol);
        check_roundtrip(p, special_dirs<T>(), tol);
        check_footprints(p, random_dirs<T>(5000, 2));
        check_footprints(p, special_dirs<T>());
        check_constant(p, random_dirs<T>(5000, 3));
    }
}

TEMPLATE_TEST_CASE("dual orthographic: equator on the outer ring of texel centres",
                   "[param][dual_orthographic]", float, double) {
    for (int n : {2, 5, 16})
        check_equator_on_outer_ring(DualOrthographic<TestType>(n),
                                    sizeof(TestType) == 4 ? 1e-3 : 1e-7);
}

TEST_CASE("dual orthographic: uv -> direction -> uv away from the redundant ring",
          "[param][dual_orthographic]") {
    const DualOrthographic<double> p(16);
    const double h = 0.5 / 16;
    for (int face = 0; face < 2; ++face)
        for (int j = 0; j <= 50; ++j)
            for (int i = 0; i <= 50; ++i) {
                const double u = h + 1e-6 + (1 - 2 * h - 2e-6) * i / 50;
                const double v = h + 1e-6 + (1 - 2 * h - 2e-6) * j / 50;
                const auto d = p.uv_to_direction(face, u, v);
                const auto t = p.direction_to_uv(d.x, d.y, d.z);
                CHECK(t.face == face);
                CHECK(t.u == Approx(u).margin(1e-12));
                CHECK(t.v == Approx(v).margin(1e-12));
            }
}

TEST_CASE("dual orthographic: texel solid angles", "[param][dual_orthographic]") {
    for (int n : {2, 3, 8, 64}) {
        const DualOrthographic<double> p(n);
        CHECK(total_solid_angle(p) == Approx(4 * 3.141592653589793).epsilon(1e-12));
        double face0 = 0;
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) face0 += p.texel_solid_angle(0, c, r);
        CHECK(face0 == Approx(2 * 3.141592653589793).epsilon(1e-12));
    }
    for (int n : {2, 5, 12}) {
        const DualOrthographic<double> p(n);
        const double h = 0.5 / n;
        check_caps(
            p, [](double R) { return 2 * 3.141592653589793 * (1 - std::sqrt(1 - R * R)); }, 1e-12);
        check_texel_solid_angles(p, h, 1 - h, 16, 2e-3);
    }
    const DualOrthographic<float> pf(32);
    CHECK(total_solid_angle(pf) == Approx(4 * 3.141592653589793).epsilon(1e-6));
}

TEST_CASE("dual orthographic: pdf integrates to one and is 1/|Jacobian|",
          "[param][dual_orthographic]") {
    const double integral = integrate_sphere(
        [](double x, double y, double z) { return square_to_orthographic_pdf(x, y, z); }, true,
        800);
    CHECK(integral == Approx(1.0).epsilon(1e-5));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(0.02, 0.98);
    for (int k = 0; k < 1000; ++k) {
        const double u = U(rng), v = U(rng);
        if (std::fabs(std::fabs(2 * u - 1) - std::fabs(2 * v - 1)) < 1e-4) continue;
        const double jac =
            jacobian([](double a, double b) { return square_to_orthographic(a, b); }, u, v, 1e-6);
        const auto d = square_to_orthographic(u, v);
        CHECK(square_to_orthographic_pdf(d.x, d.y, d.z) * jac == Approx(1.0).epsilon(1e-6));
        const auto s = orthographic_to_square(d.x, d.y, d.z);
        CHECK(s.x == Approx(u).margin(1e-13));
        CHECK(s.y == Approx(v).margin(1e-13));
    }
}

TEST_CASE("dual orthographic: reconstruction", "[param][dual_orthographic]") {
    for (int n : {2, 7, 16}) {
        const DualOrthographic<double> p(n);
        check_interpolates_at_centres(p, 1e-12);
        check_equator_continuity(p);
    }
    // Bilinear reconstruction of a smooth function converges at second order: MSE ~ h^4.
    const double m16 = smooth_mse(DualOrthographic<double>(16), 20000);
    const double m32 = smooth_mse(DualOrthographic<double>(32), 20000);
    INFO("MSE n=16 " << m16 << ", n=32 " << m32);
    // Only first order: the orthographic lift z = sqrt(1 - r^2) has an infinite slope at the
    // equator, so bilinear interpolation in r is off by O(sqrt(h)) on the outer ring of width h
    // and the MSE falls as ~h^2 (measured ratio 3.2 per halving of h).
    CHECK(m16 / m32 > 2.5);
}

TEST_CASE("dual orthographic: bad input", "[param][dual_orthographic]") {
    REQUIRE_THROWS_WITH(
        DualOrthographic<double>(1),
        Catch::Contains("sphbasis::param::DualOrthographic(): expected 2 <= resolution"));
    REQUIRE_THROWS_WITH(DualOrthographic<double>(8, 25), Catch::Contains("subtexel_bits"));
    // A zero or NaN vector is read as the pole (0, 0, 1).
    const DualOrthographic<float> p(8);
    const auto t = p.direction_to_uv(0.0f, 0.0f, 0.0f);
    CHECK(t.face == 0);
    CHECK(t.u == Approx(0.5f));
    const auto q = p.direction_to_uv(std::nanf(""), 1.0f, 0.0f);
    CHECK(q.face == 0);
    CHECK(q.v == Approx(0.5f));
}
