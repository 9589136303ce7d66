// Tests for ops/sh_lights.hpp: analytic lights against numerical integration of their radiance,
// the hemisphere light's exact irradiance, and lat-long / cube-map projection (exact for a
// constant map, O(1/N^2) against quadrature for a smooth one).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "../support/sh_checks.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/ops/sh_convolution.hpp"
#include "sphbasis/ops/sh_lights.hpp"
#include "sphbasis/ops/sh_rotation.hpp"
#include "sphbasis/param/cubemap.hpp"

namespace sh = sphbasis::sh;
using sphbasis::vec3;
using namespace sphbasis::test;

namespace {

/// integral over the cap of half-angle a about d of y_k(w) dw, by a product rule in the cap's
/// frame (Gauss-Legendre in cos theta on [cos a, 1], uniform in phi): exact for polynomials.
std::vector<double> cap_projection(int bands, const vec3<double>& d, double a) {
    std::vector<double> t, w;
    sphbasis::gauss_legendre(bands + 4, t, w);
    const int np = 2 * bands + 4;
    const auto r = sh::frame_to_normal(d.x, d.y, d.z);
    const double c = std::cos(a);
    std::vector<double> out(std::size_t(bands * bands), 0.0), y(out.size());
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double z = c + (1 - c) * 0.5 * (t[i] + 1);
        const double wz = (1 - c) * 0.5 * w[i];
        const double s = std::sqrt((1 - z) * (1 + z));
        for (int j = 0; j < np; ++j) {
            const double p = 2 * pi * (j + 0.5) / np;
            const double lx = s * std::cos(p), ly = s * std::sin(p);
            sh::eval(bands, r[0] * lx + r[1] * ly + r[2] * z, r[3] * lx + r[4] * ly + r[5] * z,
                     r[6] * lx + r[7] * ly + r[8] * z, y.data());
            for (std::size_t k = 0; k < out.size(); ++k) out[k] += wz * (2 * pi / np) * y[k];
        }
    }
    return out;
}

double smooth_env(double x, double y, double z) {
    return std::exp(0.8 * x - 0.5 * y + 0.3 * z) + 0.5 * x * y;
}

/// Projection of smooth_env by a high-degree product rule (converged to rounding).
std::vector<double> smooth_reference(int bands) {
    const auto rule = sphbasis::sphere_rule(80);
    std::vector<double> out(std::size_t(bands * bands), 0.0), y(out.size());
    for (std::size_t i = 0; i < rule.size(); ++i) {
        sh::eval(bands, rule.x[i], rule.y[i], rule.z[i], y.data());
        const double v = smooth_env(rule.x[i], rule.y[i], rule.z[i]) * rule.w[i];
        for (std::size_t k = 0; k < out.size(); ++k) out[k] += v * y[k];
    }
    return out;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    double m = 0;
    for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::fabs(a[i] - b[i]));
    return m;
}

std::vector<double> latlong_smooth(int w, int h) {
    std::vector<double> tex(std::size_t(w * h));
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const double t = pi * (j + 0.5) / h, p = 2 * pi * (i + 0.5) / w;
            tex[std::size_t(j * w + i)] =
                smooth_env(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
        }
    return tex;
}

std::vector<double> cube_smooth(int n) {
    const sphbasis::param::CubeMap<double> cube(n, sphbasis::param::CubeFilter::dx9_clamped);
    std::vector<double> tex(6 * std::size_t(n * n));
    for (int f = 0; f < 6; ++f)
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) {
                const auto d = cube.texel_direction(f, c, r);
                tex[cube.texel_index(f, c, r)] = smooth_env(d.x, d.y, d.z);
            }
    return tex;
}

}  // namespace

TEST_CASE("lights: cap kernel", "[lights]") {
    // Whole sphere, hemisphere (= Phong s = 0), and quadrature for a general cap.
    const auto full = sh::cap_kernel(6, 2.0);
    CHECK(full[0] == Approx(4 * pi));
    for (std::size_t l = 1; l < 6; ++l) CHECK(full[l] == Approx(0).margin(1e-14));
    const auto half = sh::cap_kernel(30, 1.0);
    const auto ph = sh::phong_kernel(30, 0.0);
    for (std::size_t l = 0; l < 30; ++l) CHECK(half[l] == Approx(ph[l]).margin(1e-14));
    const double u = 0.3;
    const auto cap = sh::cap_kernel(40, u);
    std::vector<double> t, w;
    sphbasis::gauss_legendre(40, t, w);
    for (int l = 0; l < 40; ++l) {
        double s = 0;
        for (std::size_t i = 0; i < t.size(); ++i) {
            const double x = 1 - u + u * 0.5 * (t[i] + 1);
            double p0 = 1, p1 = x, pl = l == 0 ? 1 : x;
            for (int k = 2; k <= l; ++k) {
                pl = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = pl;
            }
            s += u * 0.5 * w[i] * pl;
        }
        CHECK(cap[std::size_t(l)] == Approx(2 * pi * s).margin(1e-14));
    }
    // Tiny caps keep full relative accuracy: Lambda_l / (2 pi u) = 1 - l(l+1) u/4 + O(u^2).
    const double tiny = 1e-9;
    const auto small = sh::cap_kernel(20, tiny);
    for (int l = 0; l < 20; ++l)
        CHECK(small[std::size_t(l)] / (2 * pi * tiny) ==
              Approx(1 - l * (l + 1) * tiny / 4).epsilon(1e-13));
    CHECK_THROWS_WITH(sh::cap_kernel(3, 2.5),
                      Catch::Contains("sphbasis::sh::cap_kernel(): expected"));
}

TEMPLATE_TEST_CASE(
    "lights: cone, spherical and directional lights against integration of their "
    "radiance",
    "[lights]", float, double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 3e-6 : 1e-13;
    // 8 bands: the unrolled fixed-band path; 10: the run-time factors and basis in double.
    for (const int bands : {8, 10}) {
        const auto d = unit(0.3, -0.4, 0.6);
        std::vector<T> out(std::size_t(bands * bands));
        for (double a : {0.05, 0.4, 1.3, 2.8}) {
            const double L = 2.5;
            sh::cone_light(bands, T(d.x), T(d.y), T(d.z), T(a), T(L), out.data());
            const auto ref = cap_projection(bands, d, a);
            for (std::size_t k = 0; k < out.size(); ++k) {
                INFO("angle " << a << " k " << k);
                CHECK(double(out[k]) == Approx(L * ref[k]).margin(tol * L * (1 + a * a)));
            }
            // The same cap as a ball at distance 3, and by solid angle.
            std::vector<T> ball(out.size()), sa(out.size());
            if (a < pi / 2) {
                const double dist = 3, r = dist * std::sin(a);
                sh::spherical_light(bands, T(dist * d.x), T(dist * d.y), T(dist * d.z), T(r), T(L),
                                    ball.data());
                for (std::size_t k = 0; k < out.size(); ++k)
                    CHECK(double(ball[k]) == Approx(double(out[k])).margin(tol * 10));
            }
            sh::spherical_light_solid_angle(bands, T(d.x), T(d.y), T(d.z),
                                            T(2 * pi * (1 - std::cos(a))), T(L), sa.data());
            for (std::size_t k = 0; k < out.size(); ++k)
                CHECK(double(sa[k]) == Approx(double(out[k])).margin(tol * 10));
        }
        // Inside the ball: uniform radiance everywhere.
        sh::spherical_light(bands, T(0.1), T(0), T(0), T(1), T(1), out.data());
        CHECK(double(out[0]) == Approx(std::sqrt(4 * pi)).epsilon(1e-6));
        for (std::size_t k = 1; k < out.size(); ++k) CHECK(double(out[k]) == Approx(0).margin(tol));
        // Directional: E y(d); reconstructed irradiance facing it is E * peak.
        sh::directional_light(bands, T(2 * d.x), T(2 * d.y), T(2 * d.z), T(3), out.data());
        std::vector<T> y(out.size());
        sh::eval(bands, T(d.x), T(d.y), T(d.z), y.data());
        for (std::size_t k = 0; k < out.size(); ++k)
            CHECK(double(out[k]) == Approx(3 * double(y[k])).margin(tol));
        const auto a = sh::clamped_cosine_kernel<T>(bands);
        sh::convolve(bands, a.data(), out.data(), out.data());
        CHECK(double(sh::eval_sum(bands, out.data(), T(d.x), T(d.y), T(d.z))) ==
              Approx(3 * sh::directional_light_peak(bands))
                  .epsilon(std::is_same_v<T, float> ? 1e-5 : 1e-13));
    }
    CHECK(sh::directional_light_peak(3) == Approx(17.0 / 16));
    CHECK(sh::directional_light_peak(1) == Approx(0.25));
}

TEST_CASE("lights: cone light irradiance against direct integration", "[lights]") {
    // A cap entirely above the receiver's horizon: E(n) = L integral_cap (n . w) dw exactly;
    // the SH irradiance converges to it as bands grow.
    const auto d = unit(0.2, 0.1, 1.0);
    const double a = 0.5, L = 1.7;
    const auto n = unit(-0.1, 0.3, 1.0);
    const auto ref = cap_projection(3, d, a);  // bands 2 terms: (n . w) is in span of l <= 1
    // integral_cap (n . w) dw from the l <= 1 projections: n . w = (4 pi/3) sum_m y_1m(n) y_1m(w).
    std::vector<double> yn(4);
    sh::eval(2, n.x, n.y, n.z, yn.data());
    double exact = 0;
    for (int k = 1; k < 4; ++k) exact += (4 * pi / 3) * yn[std::size_t(k)] * ref[std::size_t(k)];
    exact *= L;
    for (int bands : {3, 9, 17, 33}) {
        std::vector<double> c(std::size_t(bands * bands));
        sh::cone_light(bands, d.x, d.y, d.z, a, L, c.data());
        const auto k = sh::clamped_cosine_kernel(bands);
        sh::convolve(bands, k.data(), c.data(), c.data());
        const double e = sh::eval_sum(bands, c.data(), n.x, n.y, n.z);
        INFO("bands " << bands << " E " << e << " exact " << exact);
        CHECK(std::fabs(e - exact) <= 0.3 / std::pow(bands, 2.0) * exact);
    }
}

TEST_CASE("lights: hemisphere light irradiance is exact", "[lights]") {
    const auto up = unit(0.1, 0.9, -0.3);
    const RGB sky{1.0, 2.0, 3.0}, ground{0.25, 0.5, -0.1};
    std::mt19937 rng(3);
    std::normal_distribution<double> nd;
    for (int bands : {2, 3, 6}) {
        std::vector<RGB> c(std::size_t(bands * bands));
        sh::hemisphere_light(bands, up.x, up.y, up.z, sky, ground, c.data());
        const auto k = sh::clamped_cosine_kernel(bands);
        sh::convolve(bands, k.data(), c.data(), c.data());
        for (int i = 0; i < 10; ++i) {
            const auto n = unit(nd(rng), nd(rng), nd(rng));
            const double t = n.x * up.x + n.y * up.y + n.z * up.z;
            const RGB e = sh::eval_sum(bands, c.data(), n.x, n.y, n.z);
            CHECK(e.r == Approx(pi * (sky.r + ground.r) / 2 + pi * (sky.r - ground.r) * t / 2)
                             .margin(1e-13));
            CHECK(e.b == Approx(pi * (sky.b + ground.b) / 2 + pi * (sky.b - ground.b) * t / 2)
                             .margin(1e-13));
        }
        // Radiance coefficients against integration of the two half-spaces.
        const auto hemi = cap_projection(bands, up, pi / 2);
        std::vector<RGB> raw(c.size());
        sh::hemisphere_light(bands, up.x, up.y, up.z, sky, ground, raw.data());
        for (std::size_t kk = 0; kk < raw.size(); ++kk) {
            const double full = kk == 0 ? std::sqrt(4 * pi) : 0.0;
            CHECK(raw[kk].g ==
                  Approx(sky.g * hemi[kk] + ground.g * (full - hemi[kk])).margin(1e-13));
        }
    }
}

TEST_CASE("lights: lat-long projection", "[lights]") {
    // Constant map: exact.
    const int bands = 9;
    std::vector<double> c(std::size_t(bands * bands));
    const std::vector<double> ones(64 * 32, 2.0);
    sh::project_latlong(bands, 64, 32, ones.data(), c.data());
    CHECK(c[0] == Approx(2 * std::sqrt(4 * pi)).epsilon(1e-14));
    for (std::size_t k = 1; k < c.size(); ++k) CHECK(c[k] == Approx(0).margin(1e-14));
    // Tiny maps at many bands: still exact for a constant.
    for (auto wh : {std::pair<int, int>{1, 1}, {3, 2}, {2, 7}}) {
        const int b = 20;
        std::vector<double> tiny(std::size_t(wh.first * wh.second), 1.0), ct(std::size_t(b * b));
        sh::project_latlong(b, wh.first, wh.second, tiny.data(), ct.data());
        CHECK(ct[0] == Approx(std::sqrt(4 * pi)).epsilon(1e-14));
        for (std::size_t k = 1; k < ct.size(); ++k) CHECK(ct[k] == Approx(0).margin(1e-13));
    }
    // Piecewise constant: rows 5..9 of 32 set to 1 is the zone between two caps about +z.
    std::vector<double> zone(64 * 32, 0.0);
    for (int j = 5; j < 10; ++j)
        for (int i = 0; i < 64; ++i) zone[std::size_t(j * 64 + i)] = 1;
    sh::project_latlong(bands, 64, 32, zone.data(), c.data());
    const auto ka = sh::cap_kernel(bands, 1 - std::cos(pi * 10 / 32));
    const auto kb = sh::cap_kernel(bands, 1 - std::cos(pi * 5 / 32));
    std::vector<double> yz(c.size());
    sh::eval(bands, 0.0, 0.0, 1.0, yz.data());
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const std::size_t k = std::size_t(sh::index(l, m));
            CHECK(c[k] == Approx((ka[std::size_t(l)] - kb[std::size_t(l)]) * yz[k]).margin(1e-14));
        }
    // Smooth map: O(1/N^2) against quadrature.
    const auto ref = smooth_reference(bands);
    std::vector<double> c32(c.size()), c64(c.size());
    sh::project_latlong(bands, 64, 32, latlong_smooth(64, 32).data(), c32.data());
    sh::project_latlong(bands, 128, 64, latlong_smooth(128, 64).data(), c64.data());
    const double e32 = max_abs_diff(c32, ref), e64 = max_abs_diff(c64, ref);
    INFO("lat-long errors " << e32 << " " << e64);
    CHECK(e64 < 2e-3);
    CHECK(e32 / e64 == Approx(4).epsilon(0.15));
    // Functor form and RGB.
    std::vector<RGB> crgb(c.size());
    sh::project_latlong_fn(
        bands, 64, 32,
        [](int, int row) {
            return RGB{1.0 * row, 2.0, 0.0};
        },
        crgb.data());
    CHECK(crgb[0].g == Approx(2 * std::sqrt(4 * pi)).epsilon(1e-14));
}

TEMPLATE_TEST_CASE("lights: cube-map projection", "[lights]", float, double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 2e-6 : 1e-13;
    // Constant map: exact at any band count (3: by symmetry; 9: by the control variate).
    for (int bands : {3, 9}) {
        for (int size : {1, 16}) {
            std::vector<T> tex(6 * std::size_t(size * size), T(1.5)), c(std::size_t(bands * bands));
            sh::project_cubemap(bands, size, tex.data(), c.data());
            CHECK(double(c[0]) == Approx(1.5 * std::sqrt(4 * pi)).epsilon(tol));
            for (std::size_t k = 1; k < c.size(); ++k)
                CHECK(double(c[k]) == Approx(0).margin(tol * 3));
        }
    }
    // The definition, at 3 bands: sum over texels of solid angle x value x y_k(centre).
    const int n = 8;
    const sphbasis::param::CubeMap<double> cube(n, sphbasis::param::CubeFilter::dx9_clamped);
    std::vector<T> tex(6 * n * n);
    for (int f = 0; f < 6; ++f)
        for (int r = 0; r < n; ++r)
            for (int col = 0; col < n; ++col) {
                const auto d = cube.texel_direction(f, col, r);
                tex[cube.texel_index(f, col, r)] = T(1 + d.x + 2 * d.y * d.z + 0.5 * d.z);
            }
    std::vector<double> direct(9, 0.0), y(9);
    for (int f = 0; f < 6; ++f)
        for (int r = 0; r < n; ++r)
            for (int col = 0; col < n; ++col) {
                const auto d = cube.texel_direction(f, col, r);
                sh::eval(3, d.x, d.y, d.z, y.data());
                for (std::size_t k = 0; k < 9; ++k)
                    direct[k] += cube.texel_solid_angle(f, col, r) *
                                 double(tex[cube.texel_index(f, col, r)]) * y[k];
            }
    std::vector<T> c(9);
    sh::project_cubemap(3, n, tex.data(), c.data());
    for (std::size_t k = 0; k < 9; ++k) CHECK(double(c[k]) == Approx(direct[k]).margin(tol * 10));
    // A single hot texel is (nearly) a directional light from its centre.
    std::vector<T> hot(6 * 64 * 64, T(0));
    const sphbasis::param::CubeMap<double> c64(64, sphbasis::param::CubeFilter::dx9_clamped);
    hot[c64.texel_index(4, 10, 40)] = T(1000);
    const auto hd = c64.texel_direction(4, 10, 40);
    const double om = c64.texel_solid_angle(4, 10, 40);
    std::vector<T> ch(9), cd(9);
    sh::project_cubemap(3, 64, hot.data(), ch.data());
    sh::directional_light(3, T(hd.x), T(hd.y), T(hd.z), T(1000 * om), cd.data());
    for (std::size_t k = 0; k < 9; ++k)
        CHECK(double(ch[k]) == Approx(double(cd[k])).margin(1e-4 * std::fabs(double(cd[0]))));
}

TEST_CASE("lights: cube-map projection of a smooth map converges to quadrature", "[lights]") {
    const int bands = 9;
    const auto ref = smooth_reference(bands);
    std::vector<double> c32(std::size_t(bands * bands)), c64(c32.size()), css(c32.size());
    sh::project_cubemap(bands, 32, cube_smooth(32).data(), c32.data());
    sh::project_cubemap(bands, 64, cube_smooth(64).data(), c64.data());
    const double e32 = max_abs_diff(c32, ref), e64 = max_abs_diff(c64, ref);
    INFO("cube errors " << e32 << " " << e64);
    CHECK(e64 < 1e-3);
    CHECK(e32 / e64 == Approx(4).epsilon(0.15));
    // Supersampling a coarse map converges to the piecewise-constant map's projection, which
    // for a map sampled at texel centres is within O(1/N^2) as well.
    sh::project_cubemap(bands, 32, cube_smooth(32).data(), css.data(), 4);
    CHECK(max_abs_diff(css, ref) < 4 * e32);
    // Bad input.
    CHECK_THROWS_WITH(sh::project_cubemap(3, 0, c32.data(), c64.data()),
                      Catch::Contains("sphbasis::sh::project_cubemap(): expected 1 <= size"));
    CHECK_THROWS_WITH(sh::project_latlong(3, 0, 4, c32.data(), c64.data()),
                      Catch::Contains("sphbasis::sh::project_latlong(): expected 1 <= width"));
    CHECK_THROWS_WITH(
        sh::cone_light(3, 0.0, 0.0, 0.0, 0.5, 1.0, c64.data()),
        Catch::Contains("sphbasis::sh::cone_light(): expected a finite non-zero direction"));
    CHECK_THROWS_WITH(
        sh::cone_light(3, 0.0, 0.0, 1.0, 4.0, 1.0, c64.data()),
        Catch::Contains("sphbasis::sh::cone_light(): expected 0 <= half_angle <= pi"));
    CHECK_THROWS_WITH(sh::spherical_light(3, 0.0, 0.0, 1.0, -1.0, 1.0, c64.data()),
                      Catch::Contains("sphbasis::sh::spherical_light(): expected a finite radius"));
    CHECK_THROWS_WITH(sh::directional_light(-1, 0.0, 0.0, 1.0, 1.0, c64.data()),
                      Catch::Contains("sphbasis::sh::directional_light(): expected 0 <= bands"));
}

namespace {
struct RGBf {
    float r = 0, g = 0, b = 0;
};
RGBf operator+(const RGBf& a, const RGBf& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
RGBf operator*(const RGBf& a, float s) { return {a.r * s, a.g * s, a.b * s}; }

/// Reference coefficients in double, independent of the lights' code paths: factor_l * y_k(d)
/// with y from sh::eval(bands, double) and the factors from sh::cap_kernel (cap lights) or 1.
std::vector<double> zonal_reference(int bands, double x, double y, double z,
                                    const std::vector<double>& factor) {
    std::vector<double> yv(std::size_t(bands * bands)), out(yv.size());
    sh::eval(bands, x, y, z, yv.data());
    for (int l = 0; l < bands; ++l)
        for (int k = l * l; k < (l + 1) * (l + 1); ++k)
            out[std::size_t(k)] = factor[std::size_t(l)] * yv[std::size_t(k)];
    return out;
}

/// The fixed-band lights (and the run-time ones, which use them for 1..8 bands) against
/// zonal_reference.
template <int N, class T>
void check_fixed_lights(std::mt19937& rng) {
    using C = T;  // one channel in T; the RGB case is below
    const double tol = std::is_same_v<T, float> ? 3e-5 : 1e-12;
    std::normal_distribution<double> nd;
    for (int trial = 0; trial < 8; ++trial) {
        const T x = T(nd(rng)), y = T(nd(rng)), z = T(nd(rng));
        const T a = T(0.05 + 0.4 * trial), rad = T(0.3 + 0.5 * trial);
        const double xd = x, yd = y, zd = z;
        C f[N * N], r[N * N];
        auto same = [&](const char* what, const std::vector<double>& ref) {
            INFO(what << " N = " << N << " trial " << trial);
            for (int k = 0; k < N * N; ++k) {
                CHECK(double(f[k]) ==
                      Approx(ref[std::size_t(k)]).margin(tol * 4 * pi).epsilon(tol));
                CHECK(double(r[k]) ==
                      Approx(ref[std::size_t(k)]).margin(tol * 4 * pi).epsilon(tol));
            }
        };
        sh::directional_light<N>(x, y, z, T(1.5), f);
        sh::directional_light(N, x, y, z, T(1.5), r);
        same("directional", zonal_reference(N, xd, yd, zd, std::vector<double>(N, 1.5)));
        const double u_cone = 1 - std::cos(double(a));
        auto fc = sh::cap_kernel(N, u_cone);
        for (auto& v : fc) v *= 0.7;
        sh::cone_light<N>(x, y, z, a, T(0.7), f);
        sh::cone_light(N, x, y, z, a, T(0.7), r);
        same("cone", zonal_reference(N, xd, yd, zd, fc));
        const double dist = std::sqrt(xd * xd + yd * yd + zd * zd);
        const double s = double(rad) / dist;
        auto fs = sh::cap_kernel(N, s >= 1 ? 2.0 : 1 - std::sqrt(1 - s * s));
        for (auto& v : fs) v *= 0.7;
        sh::spherical_light<N>(x, y, z, rad, T(0.7), f);
        sh::spherical_light(N, x, y, z, rad, T(0.7), r);
        same("sphere", zonal_reference(N, xd, yd, zd, fs));
        // sky 1.25 on the cap u = 1 plus ground 0.25 on the rest of the sphere
        auto fh = sh::cap_kernel(N, 1.0);
        for (int l = 0; l < N; ++l)
            fh[std::size_t(l)] =
                1.25 * fh[std::size_t(l)] + 0.25 * ((l == 0 ? 4 * pi : 0.0) - fh[std::size_t(l)]);
        sh::hemisphere_light<N>(x, y, z, T(1.25), T(0.25), f);
        sh::hemisphere_light(N, x, y, z, T(1.25), T(0.25), r);
        same("hemisphere", zonal_reference(N, xd, yd, zd, fh));
    }
}

template <int... Ns, class T>
void fixed_lights_all(std::mt19937& rng, T) {
    (check_fixed_lights<Ns, T>(rng), ...);
}
}  // namespace

TEMPLATE_TEST_CASE(
    "directional/cone/spherical/hemisphere_light<N> and the run-time lights at N bands "
    "equal factor times y in double",
    "[ops][lights]", float, double) {
    std::mt19937 rng(21);
    fixed_lights_all<1, 2, 3, 4, 5, 6, 7, 8>(rng, TestType(0));
}

TEST_CASE("fixed-band lights: RGB in one pass, hemisphere constants, clamped arguments",
          "[ops][lights]") {
    RGBf f[9], r[9];
    const RGBf c{1, 2, 3}, g{0.1f, 0.2f, 0.3f};
    sh::hemisphere_light<3>(0.2f, -0.3f, 0.9f, c, g, f);
    sh::hemisphere_light(3, 0.2f, -0.3f, 0.9f, c, g, r);
    for (int k = 0; k < 9; ++k) {
        CHECK(f[k].r == Approx(r[k].r).margin(1e-6));
        CHECK(f[k].g == Approx(r[k].g).margin(1e-6));
        CHECK(f[k].b == Approx(r[k].b).margin(1e-6));
    }
    // u = 1 cap factors: 2 pi, pi, 0, -pi/4, 0, pi/8, 0, -5 pi/64
    constexpr auto h = sh::detail::hemisphere_factors<8>();
    const double want[8] = {2 * pi, pi, 0, -pi / 4, 0, pi / 8, 0, -5 * pi / 64};
    for (int l = 0; l < 8; ++l) CHECK(h[std::size_t(l)] == Approx(want[l]).margin(1e-15));
    // out-of-domain arguments stay finite: a half-angle above pi is the whole sphere, a zero
    // direction is the pole
    double o[16], w[16];
    sh::cone_light<4>(0.0, 0.0, 1.0, 7.0, 1.0, o);
    sh::cone_light(4, 0.0, 0.0, 1.0, pi, 1.0, w);
    for (int k = 0; k < 16; ++k) CHECK(o[k] == Approx(w[k]).margin(1e-14));
    sh::directional_light<4>(0.0, 0.0, 0.0, 1.0, o);
    sh::directional_light(4, 0.0, 0.0, 1.0, 1.0, w);
    for (int k = 0; k < 16; ++k) CHECK(o[k] == Approx(w[k]).margin(1e-15));
}

namespace {
/// An RGB type that can be made from one grey value (as glm::vec3(1.0f) can).
struct Grey3 {
    double r = 0, g = 0, b = 0;
    Grey3() = default;
    Grey3(double r_, double g_, double b_) : r(r_), g(g_), b(b_) {}
    explicit Grey3(double v) : r(v), g(v), b(v) {}
};
Grey3 operator+(const Grey3& a, const Grey3& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
Grey3 operator*(const Grey3& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
}  // namespace

TEST_CASE("lights: the colour's type and the output's are deduced separately", "[ops][lights]") {
    // directional_light(3, x, y, z, 1.0, float_out): a double colour writes float coefficients,
    // the same as a float colour would. The colour is converted to float first, so both calls
    // run the same float operations; the results are not bit-identical on every target because
    // each call is a separately inlined copy, and g++ (-ffp-contract=fast) may fuse a * b + c
    // into an FMA in one copy and not in the other (seen with -march=x86-64-v3 on an AVX2
    // machine). Bound: 4 float ulp of the largest coefficient.
    const auto same = [](const float* x, const float* y) {
        float big = 0;
        for (int k = 0; k < 9; ++k) big = std::max(big, std::abs(y[k]));
        for (int k = 0; k < 9; ++k)
            CHECK(x[k] == Approx(y[k]).margin(4 * std::numeric_limits<float>::epsilon() * big));
    };
    float a[9], b[9];
    sh::directional_light(3, 0.2f, -0.3f, 0.9f, 1.0, a);
    sh::directional_light(3, 0.2f, -0.3f, 0.9f, 1.0f, b);
    same(a, b);
    sh::cone_light(3, 0.2f, -0.3f, 0.9f, 0.3f, 2.0, a);
    sh::cone_light(3, 0.2f, -0.3f, 0.9f, 0.3f, 2.0f, b);
    same(a, b);
    sh::spherical_light(3, 0.2f, -0.3f, 4.0f, 1.0f, 0.5, a);
    sh::spherical_light(3, 0.2f, -0.3f, 4.0f, 1.0f, 0.5f, b);
    same(a, b);
    sh::spherical_light_solid_angle(3, 0.2f, -0.3f, 0.9f, 0.5f, 3, a);  // an int colour too
    sh::spherical_light_solid_angle(3, 0.2f, -0.3f, 0.9f, 0.5f, 3.0f, b);
    same(a, b);
    sh::hemisphere_light(3, 0.0f, 0.0f, 1.0f, 1.0, 0.25f, a);  // sky double, ground float
    sh::hemisphere_light(3, 0.0f, 0.0f, 1.0f, 1.0f, 0.25f, b);
    same(a, b);
    const double kern[3] = {1, 0.5, 0.25};
    sh::zonal_light(3, 0.2f, -0.3f, 0.9f, kern, 1.0, a);
    sh::zonal_light(3, 0.2f, -0.3f, 0.9f, kern, 1.0f, b);
    same(a, b);
    // The direction overloads with a range out, and the compile-time forms.
    std::vector<float> v(9);
    sh::directional_light(3, vec3<float>{0.2f, -0.3f, 0.9f}, 1.0, v);
    sh::directional_light(3, 0.2f, -0.3f, 0.9f, 1.0f, b);
    same(v.data(), b);
    sh::hemisphere_light(3, vec3<float>{0, 0, 1}, 1.0, 0.25, v);
    sh::hemisphere_light(3, 0.0f, 0.0f, 1.0f, 1.0f, 0.25f, b);
    same(v.data(), b);
    sh::directional_light<3>(0.2f, -0.3f, 0.9f, 1.0, a);
    sh::directional_light<3>(0.2f, -0.3f, 0.9f, 1.0f, b);
    same(a, b);
    sh::cone_light<3>(0.2f, -0.3f, 0.9f, 0.3f, 2.0, a);
    sh::cone_light<3>(0.2f, -0.3f, 0.9f, 0.3f, 2.0f, b);
    same(a, b);
    sh::spherical_light<3>(0.2f, -0.3f, 4.0f, 1.0f, 0.5, a);
    sh::spherical_light<3>(0.2f, -0.3f, 4.0f, 1.0f, 0.5f, b);
    same(a, b);
    sh::hemisphere_light<3>(0.0f, 0.0f, 1.0f, 1.0, 0.25, a);
    sh::hemisphere_light<3>(0.0f, 0.0f, 1.0f, 1.0f, 0.25f, b);
    same(a, b);
    // A float colour into an RGB output that is constructible from it (broadcast).
    Grey3 rgb[9];
    double mono[9];
    sh::directional_light(3, 0.2, -0.3, 0.9, 2.0f, rgb);
    sh::directional_light(3, 0.2, -0.3, 0.9, 2.0, mono);
    for (int k = 0; k < 9; ++k) CHECK(rgb[k].b == Approx(mono[k]).margin(1e-15));
    // A braced colour still takes the output's type (the colour type defaults to it).
    sh::directional_light(3, 0.2, -0.3, 0.9, {1.0, 1.0, 2.0}, rgb);
    for (int k = 0; k < 9; ++k) CHECK(rgb[k].b == Approx(mono[k]).margin(1e-15));
    sh::hemisphere_light(3, 0.0, 0.0, 1.0, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, rgb);
    sh::hemisphere_light<3>(0.0, 0.0, 1.0, {1.0, 1.0, 1.0}, {0.0, 0.0, 0.0}, rgb);
    sh::cone_light<3>(0.0, 0.0, 1.0, 0.3, {1.0, 1.0, 1.0}, rgb);
    CHECK(rgb[0].r > 0);
}

// A float RGB colour (RGBf above) as users write it: the 3-band lights fan it out with 16-lane
// (AVX-512) or 8-lane (AVX2) vector products (detail::fan_out_rgb3); every channel must equal the
// light of that channel alone (the same float basis values times the same float colour: exact).
TEST_CASE("lights: float RGB at 3 bands equals each channel", "[lights]") {
    std::mt19937 rng(1406);
    std::normal_distribution<float> nd;
    for (int trial = 0; trial < 32; ++trial) {
        const float x = nd(rng), y = nd(rng), z = nd(rng);
        const RGBf c{nd(rng), nd(rng), nd(rng)};
        const float ch[3] = {c.r, c.g, c.b};
        RGBf out[4][9];
        sphbasis::sh::directional_light(3, x, y, z, c, out[0]);
        sphbasis::sh::cone_light(3, x, y, z, 0.4f, c, out[1]);
        sphbasis::sh::spherical_light(3, 3 * x, 3 * y, 3 * z, 0.7f, c, out[2]);
        sphbasis::sh::directional_light<3>(x, y, z, c, out[3]);
        for (int k = 0; k < 3; ++k) {
            float ref[4][9];
            sphbasis::sh::directional_light(3, x, y, z, ch[k], ref[0]);
            sphbasis::sh::cone_light(3, x, y, z, 0.4f, ch[k], ref[1]);
            sphbasis::sh::spherical_light(3, 3 * x, 3 * y, 3 * z, 0.7f, ch[k], ref[2]);
            sphbasis::sh::directional_light<3>(x, y, z, ch[k], ref[3]);
            for (int f = 0; f < 4; ++f)
                for (int i = 0; i < 9; ++i) {
                    const float got = k == 0 ? out[f][i].r : k == 1 ? out[f][i].g : out[f][i].b;
                    CHECK(got == ref[f][i]);
                }
        }
    }
}
