// Checks shared by the dual-hemisphere tests (test_dual_paraboloid.cpp,
// test_dual_orthographic.cpp).
#pragma once

#include <sphbasis/param/dual_hemisphere.hpp>
#include <string>

#include "param_checks.hpp"

namespace sphbasis_test {

/// The equator lies exactly on the outer ring of texel centres, the pole at the centre.
template <class P>
void check_equator_on_outer_ring(const P& p, double dir_tol) {
    using T = decltype(p.texel_direction(0, 0, 0).x);
    const double ring = 0.5 - 0.5 / p.resolution();
    for (int k = 0; k < 360; ++k) {
        const double phi = 2 * 3.141592653589793 * k / 360;
        const auto t = p.direction_to_uv(T(std::cos(phi)), T(std::sin(phi)), T(0));
        CHECK(t.face == 0);
        const double cheb = std::fmax(std::fabs(t.u - 0.5), std::fabs(t.v - 0.5));
        CHECK(cheb == Approx(ring).margin(8 * std::numeric_limits<T>::epsilon()));
    }
    for (int face = 0; face < 2; ++face) {
        const auto t = p.direction_to_uv(T(0), T(0), T(face == 0 ? 1 : -1));
        CHECK(t.face == face);
        CHECK(t.u == Approx(0.5));
        CHECK(t.v == Approx(0.5));
    }
    // Every outer-ring texel centre is on the equator, on both faces, with the same direction.
    const int n = p.resolution();
    for (int k = 0; k < n; ++k) {
        const int cells[4][2] = {{k, 0}, {k, n - 1}, {0, k}, {n - 1, k}};
        for (const auto& c : cells) {
            const auto a = p.texel_direction(0, c[0], c[1]);
            const auto b = p.texel_direction(1, c[0], c[1]);
            CHECK(std::fabs(a.z) < dir_tol);
            CHECK(angle_between(a, b) < 2 * dir_tol);
        }
    }
}

/// C0 across the equator: the reconstruction just above and just below agree.
template <class P>
void check_equator_continuity(const P& p) {
    const auto table = smooth_table<double>(p);
    std::vector<vec3<double>> base, normal;
    for (int k = 0; k < 997; ++k) {
        const double phi = 2 * 3.141592653589793 * (k + 0.37) / 997;
        base.push_back({std::cos(phi), std::sin(phi), 0.0});
        normal.push_back({0.0, 0.0, 1.0});
    }
    const double jump = max_jump(p, table, base, normal, 1e-10);
    INFO("largest jump across the equator " << jump);
    CHECK(jump < 1e-7);
}

/// The texels inside the square block of Chebyshev radius R (in [-1, 1]^2 square coordinates,
/// R on a cell boundary) cover the polar cap whose disk radius is R: compare their summed
/// solid angles with the cap's, cap(R), computed from the projection's geometry.
template <class P, class Cap>
void check_caps(const P& p, Cap&& cap, double tol) {
    const int n = p.resolution();
    const double h = 0.5 / n;
    for (int k = 1; 2 * k < n; ++k) {
        // Cells k .. n-1-k: their outer edges are at u = k/n and (n - k)/n.
        const double u_edge = double(k) / n;
        const double R = 1 - 2 * (u_edge - h) / (1 - 2 * h);
        double sum = 0;
        for (int r = k; r < n - k; ++r)
            for (int c = k; c < n - k; ++c) sum += double(p.texel_solid_angle(1, c, r));
        CHECK(sum == Approx(cap(R)).epsilon(tol));
    }
}

/// uv -> direction -> uv is the identity on both faces away from the redundant outer ring.
template <class P>
void check_uv_round_trip_inside(const P& p) {
    const double h = 0.5 / p.resolution();
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

/// Texel solid angles of the dual map Map: the whole sphere and one face (a hemisphere) sum
/// exactly, the polar caps match cap(R) (check_caps), single texels match their subdivided
/// solid angle within texel_tol, and in float the sphere sums to 4 pi within 1e-6.
template <template <class> class Map, class Cap>
void check_dual_solid_angles(Cap&& cap, double texel_tol) {
    for (int n : {2, 3, 8, 64}) {
        const Map<double> p(n);
        CHECK(total_solid_angle(p) == Approx(4 * 3.141592653589793).epsilon(1e-12));
        double face0 = 0;
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) face0 += p.texel_solid_angle(0, c, r);
        CHECK(face0 == Approx(2 * 3.141592653589793).epsilon(1e-12));
    }
    for (int n : {2, 5, 12}) {
        const Map<double> p(n);
        const double h = 0.5 / n;
        check_caps(p, cap, 1e-12);
        check_texel_solid_angles(p, h, 1 - h, 16, texel_tol);
    }
    const Map<float> pf(32);
    CHECK(total_solid_angle(pf) == Approx(4 * 3.141592653589793).epsilon(1e-6));
}

/// The hemisphere pdf of a square-to-hemisphere map integrates to one and is 1/|Jacobian|, and
/// to_square inverts to_dir.
template <class ToDir, class Pdf, class ToSquare>
void check_hemisphere_pdf(ToDir&& to_dir, Pdf&& pdf, ToSquare&& to_square) {
    const double integral = integrate_sphere(pdf, true, 800);
    CHECK(integral == Approx(1.0).epsilon(1e-5));
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> U(0.02, 0.98);
    for (int k = 0; k < 1000; ++k) {
        const double u = U(rng), v = U(rng);
        if (std::fabs(std::fabs(2 * u - 1) - std::fabs(2 * v - 1)) < 1e-4) continue;
        const double jac = jacobian(to_dir, u, v, 1e-6);
        const auto d = to_dir(u, v);
        CHECK(pdf(d.x, d.y, d.z) * jac == Approx(1.0).epsilon(1e-6));
        const auto s = to_square(d.x, d.y, d.z);
        CHECK(s.x == Approx(u).margin(1e-13));
        CHECK(s.y == Approx(v).margin(1e-13));
    }
}

/// Reconstruction of the dual map Map: exact at texel centres, continuous across the equator,
/// and the smooth function's MSE falls by more than min_ratio from 16 to 32 texels.
template <template <class> class Map>
void check_dual_reconstruction(double min_ratio) {
    for (int n : {2, 7, 16}) {
        const Map<double> p(n);
        check_interpolates_at_centres(p, 1e-12);
        check_equator_continuity(p);
    }
    const double m16 = smooth_mse(Map<double>(16), 20000);
    const double m32 = smooth_mse(Map<double>(32), 20000);
    INFO("MSE n=16 " << m16 << ", n=32 " << m32);
    CHECK(m16 / m32 > min_ratio);
}

/// Bad resolutions and subtexel bits throw with the class' name; a zero or NaN vector is read
/// as the pole (0, 0, 1).
template <template <class> class Map>
void check_dual_bad_input(const std::string& name) {
    REQUIRE_THROWS_WITH(Map<double>(1), Catch::Contains("sphbasis::param::" + name +
                                                        "(): expected 2 <= resolution"));
    REQUIRE_THROWS_WITH(Map<double>(8, 25), Catch::Contains("subtexel_bits"));
    const Map<float> p(8);
    const auto t = p.direction_to_uv(0.0f, 0.0f, 0.0f);
    CHECK(t.face == 0);
    CHECK(t.u == Approx(0.5f));
    const auto q = p.direction_to_uv(std::nanf(""), 1.0f, 0.0f);
    CHECK(q.face == 0);
    CHECK(q.v == Approx(0.5f));
}

}  // namespace sphbasis_test
