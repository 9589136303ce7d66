// Checks shared by the dual-hemisphere tests (test_dual_paraboloid.cpp,
// test_dual_orthographic.cpp).
#pragma once

#include <sphbasis/param/dual_hemisphere.hpp>

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

}  // namespace sphbasis_test
