// Tests for ops/sh_convolution.hpp: kernel closed forms against quadrature, Funk-Hecke against
// direct integration over the sphere, the Ramamoorthi-Hanrahan quadratic form, and the
// certified minimum.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "../support/sh_checks.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/ops/sh_convolution.hpp"
#include "sphbasis/ops/sh_minimum.hpp"
#include "sphbasis/ops/sh_rotation.hpp"

namespace sh = sphbasis::sh;
using sphbasis::vec3;
using namespace sphbasis::test;

namespace {

/// integral over the sphere of h(n . w) f(w) dw, with the quadrature's pole at n and the two
/// hemispheres integrated separately (so a kink of h at n . w = 0 costs no accuracy).
template <class H>
double direct_convolution(int bands, const std::vector<double>& f, const vec3<double>& n, H&& h,
                          int degree) {
    const auto rule = sphbasis::hemisphere_rule(degree);
    const auto r = sh::frame_to_normal(n.x, n.y, n.z);
    double acc = 0;
    for (int side = 0; side < 2; ++side)
        for (std::size_t i = 0; i < rule.size(); ++i) {
            const double lx = rule.x[i], ly = rule.y[i], lz = side ? -rule.z[i] : rule.z[i];
            const double wx = r[0] * lx + r[1] * ly + r[2] * lz;
            const double wy = r[3] * lx + r[4] * ly + r[5] * lz;
            const double wz = r[6] * lx + r[7] * ly + r[8] * lz;
            acc += rule.w[i] * h(lz) * sh::eval_sum(bands, f.data(), wx, wy, wz);
        }
    return acc;
}

/// Dense-sampling estimate of the minimum (an upper bound of the true minimum).
double sampled_min(int bands, const std::vector<double>& c, int res) {
    double m = 1e300;
    for (int i = 0; i <= res; ++i) {
        const double t = pi * i / res;
        const int np = std::max(1, int(2 * res * std::sin(t)) + 1);
        for (int j = 0; j < np; ++j) {
            const double p = 2 * pi * j / np;
            m = std::min(m, sh::eval_sum(bands, c.data(), std::sin(t) * std::cos(p),
                                         std::sin(t) * std::sin(p), std::cos(t)));
        }
    }
    return m;
}

}  // namespace

TEST_CASE("convolution: clamped cosine closed form", "[convolution]") {
    const auto a = sh::clamped_cosine_kernel(9);
    CHECK(a[0] == Approx(pi).epsilon(1e-15));
    CHECK(a[1] == Approx(2 * pi / 3).epsilon(1e-15));
    CHECK(a[2] == Approx(pi / 4).epsilon(1e-15));
    CHECK(a[4] == Approx(-pi / 24).epsilon(1e-15));
    CHECK(a[6] == Approx(pi / 64).epsilon(1e-15));
    CHECK(a[8] == Approx(-pi / 128).epsilon(1e-14));  // 2 pi (-1)^5/(10*7) * 70/256
    for (int l = 3; l < 9; l += 2) CHECK(a[std::size_t(l)] == 0.0);
    const auto an = sh::clamped_cosine_kernel<float>(3, sh::KernelScale::normalized);
    CHECK(an[0] == 1.0f);
    CHECK(an[1] == Approx(2.0 / 3).epsilon(1e-7));
    CHECK(an[2] == Approx(0.25).epsilon(1e-7));
    // Closed form = Phong s = 1 recurrence = Funk-Hecke quadrature, to 60 bands.
    const auto c = sh::clamped_cosine_kernel(60);
    const auto p = sh::phong_kernel(60, 1.0);
    const auto q = sh::zonal_kernel(60, [](double t) { return t > 0 ? t : 0.0; });
    for (std::size_t l = 0; l < 60; ++l) {
        CHECK(p[l] == Approx(c[l]).margin(1e-15));
        CHECK(q[l] == Approx(c[l]).margin(1e-13));
    }
    // High degree: no overflow, decays like l^(-5/2).
    const auto big = sh::clamped_cosine_kernel(4001);
    CHECK(std::isfinite(big[4000]));
    CHECK(std::fabs(big[4000]) > 0);
    CHECK(std::fabs(big[4000]) < 1e-8);
}

TEST_CASE("convolution: Phong lobes against quadrature", "[convolution]") {
    for (double s : {0.0, 2.0, 7.0, 20.0, 2.5, 0.3}) {
        const int bands = 16;
        const auto p = sh::phong_kernel(bands, s);
        const auto q = sh::zonal_kernel(
            bands, [s](double t) { return t > 0 ? std::pow(t, s) : 0.0; },
            sh::KernelScale::unnormalized, 400);
        // Integer s: exact quadrature; fractional s: t^s is not smooth at 0, so looser.
        const double tol = s == std::floor(s) ? 1e-13 : 1e-7;
        for (std::size_t l = 0; l < std::size_t(bands); ++l) {
            INFO("s = " << s << ", l = " << l);
            CHECK(p[l] == Approx(q[l]).margin(tol));
        }
        const auto pn = sh::phong_kernel(bands, s, sh::KernelScale::normalized);
        CHECK(pn[0] == 1.0);
        CHECK(pn[1] == Approx((s + 1) / (s + 2)));
    }
}

TEST_CASE("convolution: Funk-Hecke against direct integration for random kernels",
          "[convolution]") {
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1, 1);
    const int bands = 7;
    for (int trial = 0; trial < 6; ++trial) {
        // Random smooth kernel, and a random kernel with a kink at the horizon.
        const double k1 = 3 * u(rng), k2 = u(rng), k3 = u(rng);
        auto smooth = [=](double t) { return std::exp(k1 * t) * (1 + k2 * t * t) + k3; };
        auto kinked = [=](double t) { return t > 0 ? std::exp(k1 * t) + k2 * t : k3 * t * t; };
        const auto f = random_coeffs(bands, rng);
        for (int which = 0; which < 2; ++which) {
            const auto kernel =
                which == 0 ? sh::zonal_kernel(bands, smooth) : sh::zonal_kernel(bands, kinked);
            std::vector<double> g(f.size());
            sh::convolve(bands, kernel.data(), f.data(), g.data());
            for (int i = 0; i < 3; ++i) {
                const auto n = random_dir(rng);
                const double expect = which == 0 ? direct_convolution(bands, f, n, smooth, 60)
                                                 : direct_convolution(bands, f, n, kinked, 60);
                CHECK(sh::eval_sum(bands, g.data(), n.x, n.y, n.z) == Approx(expect).margin(1e-11));
            }
        }
    }
    // The clamped cosine gives irradiance: against direct integration of L(w) max(n.w, 0).
    const auto f = random_coeffs(5, rng);
    std::vector<double> e(f.size());
    const auto a = sh::clamped_cosine_kernel(5);
    sh::convolve(5, a.data(), f.data(), e.data());
    const auto n = random_dir(rng);
    CHECK(sh::eval_sum(5, e.data(), n.x, n.y, n.z) ==
          Approx(direct_convolution(
                     5, f, n, [](double t) { return t > 0 ? t : 0.0; }, 20))
              .margin(1e-12));
}

TEST_CASE("convolution: zonal coefficients and kernel factors", "[convolution]") {
    // A zonal function's coefficients z_l on y_l0 and its Funk-Hecke factors.
    const auto k = sh::phong_kernel(6, 3.0);
    std::vector<double> z(6), back(6);
    sh::kernel_to_zonal(6, k.data(), z.data());
    sh::zonal_to_kernel(6, z.data(), back.data());
    for (std::size_t l = 0; l < 6; ++l) CHECK(back[l] == Approx(k[l]));
    // z_0 = integral of cos^3 over the upper hemisphere times y_00 = (2 pi/4) / (2 sqrt(pi)).
    CHECK(z[0] == Approx(pi / 2 / (2 * std::sqrt(pi))));
}

TEMPLATE_TEST_CASE("convolution: Ramamoorthi-Hanrahan quadratic form equals convolution",
                   "[convolution]", float, double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 1e-5 : 1e-14;
    std::mt19937 rng(8);
    const auto a = sh::clamped_cosine_kernel<T>(3);
    for (int trial = 0; trial < 20; ++trial) {
        std::normal_distribution<double> nd;
        std::vector<T> L(9), E(9);
        for (auto& v : L) v = T(nd(rng));
        sh::convolve(3, a.data(), L.data(), E.data());
        const auto M = sh::irradiance_matrix<T>(L.data());
        for (int i = 0; i < 5; ++i) {
            const auto n = random_dir(rng);
            const T x = T(n.x), y = T(n.y), z = T(n.z);
            const double ref = sh::eval_sum(3, E.data(), x, y, z);
            CHECK(double(sh::irradiance(L.data(), x, y, z)) == Approx(ref).margin(tol * 10));
            CHECK(double(sh::eval_irradiance_matrix(M, x, y, z)) == Approx(ref).margin(tol * 10));
        }
        // M is symmetric.
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c)
                CHECK(M[std::size_t(4 * r + c)] == M[std::size_t(4 * c + r)]);
    }
}

TEST_CASE("convolution: certified minimum on known functions", "[convolution]") {
    // y_10: minimum -sqrt(3/(4 pi)) at -z.
    std::vector<double> f(4, 0.0);
    f[2] = 1;
    auto r = sh::minimum(2, f.data());
    const double m10 = -std::sqrt(3 / (4 * pi));
    CHECK(r.converged);
    CHECK(r.lower_bound <= m10);
    CHECK(r.value >= m10 - 1e-15);
    CHECK(r.value - r.lower_bound <= 1e-5);
    CHECK(r.direction.z == Approx(-1).margin(1e-3));
    // Irradiance of a unit directional light at 3 bands: minimum -19/480 at n.d = -8/15.
    const auto a = sh::clamped_cosine_kernel(3);
    std::vector<double> e(9);
    sh::eval(3, 0.3, -0.5, 0.8, e.data());
    sh::convolve(3, a.data(), e.data(), e.data());
    // (Zonal: the minimum is a whole circle n.d = -8/15, the worst case for the subdivision.)
    r = sh::minimum(3, e.data(), 1e-7);
    CHECK(r.converged);
    CHECK(r.lower_bound <= -19.0 / 480);
    CHECK(r.lower_bound >= -19.0 / 480 - 1e-7);
    CHECK(r.value == Approx(-19.0 / 480).margin(1e-7));
    // A constant.
    std::vector<double> c1(9, 0.0);
    c1[0] = 2;
    r = sh::minimum(3, c1.data());
    CHECK(r.lower_bound <= 2 / (2 * std::sqrt(pi)));
    CHECK(r.lower_bound == Approx(2 / (2 * std::sqrt(pi))).epsilon(1e-13));
    // Huge and tiny scales: the same answer, scaled.
    for (double scale : {1e300, 1e-300}) {
        std::vector<double> big(e);
        for (double& v : big) v *= scale;
        const auto rb = sh::minimum(3, big.data(), 1e-6);
        CHECK(rb.lower_bound <= -19.0 / 480 * scale);
        CHECK(rb.value == Approx(-19.0 / 480 * scale).epsilon(1e-5));
    }
    // A ring of minima (y_20 is smallest on the whole equator): still a valid bound.
    std::vector<double> y20(9, 0.0);
    y20[6] = 1;
    r = sh::minimum(3, y20.data(), 1e-6);
    const double m20 = -std::sqrt(5 / (16 * pi));
    CHECK(r.lower_bound <= m20);
    CHECK(r.value == Approx(m20).margin(1e-6));
    CHECK(r.lower_bound >= m20 - 1e-5);
}

TEMPLATE_TEST_CASE("convolution: certified minimum is below and close to the sampled minimum",
                   "[convolution]", float, double) {
    using T = TestType;
    std::mt19937 rng(19);
    for (int bands : {2, 3, 4, 6, 9}) {
        for (int trial = 0; trial < 3; ++trial) {
            const auto c = random_coeffs(bands, rng);
            std::vector<T> ct(c.begin(), c.end());
            std::vector<double> cd(ct.begin(), ct.end());
            const auto r = sh::minimum(bands, ct.data(), 1e-7);
            const double sampled = sampled_min(bands, cd, 400);
            INFO("bands " << bands);
            CHECK(r.converged);
            CHECK(double(r.lower_bound) <= sampled);
            CHECK(double(r.lower_bound) <= double(r.value));
            // The value found is at least as good as dense sampling (it refines locally).
            CHECK(double(r.value) <= sampled + 1e-12);
            double scale = 0;
            for (double v : cd) scale += v * v;
            scale = std::sqrt(scale) * bands;
            CHECK(double(r.value) - double(r.lower_bound) <= 1e-6 * scale);
            // value is really attained.
            const double at = sh::eval_sum(bands, cd.data(), double(r.direction.x),
                                           double(r.direction.y), double(r.direction.z));
            CHECK(at == Approx(double(r.value)).margin(std::is_same_v<T, float> ? 1e-5 : 1e-12));
        }
    }
}

TEST_CASE("convolution: bad input throws", "[convolution]") {
    CHECK_THROWS_WITH(sh::clamped_cosine_kernel(-1),
                      Catch::Contains("sphbasis::sh::clamped_cosine_kernel(): expected"));
    CHECK_THROWS_WITH(sh::phong_kernel(3, -1.0),
                      Catch::Contains("sphbasis::sh::phong_kernel(): expected an exponent s > -1"));
    CHECK_THROWS_WITH(sh::zonal_kernel(
                          3, [](double) { return 1.0; }, sh::KernelScale::normalized, -2),
                      Catch::Contains("sphbasis::sh::zonal_kernel(): expected 0 <= nodes"));
    CHECK_THROWS_WITH(sh::zonal_kernel(
                          3, [](double) { return 0.0; }, sh::KernelScale::normalized),
                      Catch::Contains("finite non-zero integral"));
    std::vector<double> c(9, 0.0);
    CHECK_THROWS_WITH(sh::minimum(0, c.data()),
                      Catch::Contains("sphbasis::sh::minimum(): expected bands >= 1"));
    c[3] = std::nan("");
    CHECK_THROWS_WITH(sh::minimum(3, c.data()), Catch::Contains("expected finite coefficients"));
    CHECK_THROWS_WITH(sh::convolve(3, static_cast<const double*>(nullptr), c.data(), c.data()),
                      Catch::Contains("sphbasis::sh::convolve(): expected a non-null"));
}
