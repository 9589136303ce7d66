// Tests for render/environment_sampler.hpp: the density integrates to one over the sphere,
// sample() and pdf() agree, a histogram of sampled texels matches the density, the density is
// positive wherever the (bilinear) radiance is, rotation, constant and black environments.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/core/constants.hpp"
#include "sphbasis/core/frame.hpp"
#include "sphbasis/param/latlong.hpp"
#include "sphbasis/render/environment_sampler.hpp"

namespace render = sphbasis::render;
using render::Environment;
using render::EnvironmentSampler;
using sphbasis::vec3;
namespace constants = sphbasis::constants;
using sphbasis_test::latlong_environment;

namespace {

/// A 16 x 8 map: a dim coloured gradient, a bright "sun" texel block and a black band.
std::vector<float> test_map(int w, int h) {
    return sphbasis_test::rgb_texels(w, h, [w, h](int i, int j, float* p) {
        const float g = 0.1f + 0.05f * float(i) / float(w);
        p[0] = g;
        p[1] = 0.5f * g;
        p[2] = 0.2f + 0.1f * float(j) / float(h);
        if (j == h - 2) p[0] = p[1] = p[2] = 0;                     // a black band
        if (j == 2 && (i == 5 || i == 6)) p[0] = p[1] = p[2] = 40;  // the sun
    });
}

/// Midpoint quadrature of f over the sphere in (cos theta, phi), n x 2n cells.
template <class F>
double sphere_integral(int n, F&& f) {
    double s = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < 2 * n; ++b) {
            const double z = 1 - 2 * (a + 0.5) / n, phi = constants::pi * (b + 0.5) / n;
            const double r = std::sqrt(1 - z * z);
            s += f(vec3<double>{r * std::cos(phi), r * std::sin(phi), z});
        }
    return s * 4 * constants::pi / (2.0 * n * n);
}

}  // namespace

TEST_CASE("EnvironmentSampler: the density integrates to one", "[render][environment_sampler]") {
    const auto t = test_map(16, 8);
    Environment e = latlong_environment(t, 16, 8);
    const EnvironmentSampler s(e);
    // Quadrature cells aligned with the texels' cos(theta) bands would be exact; a plain grid of
    // 160 x 320 cells misses by about the texel edge fraction.
    CHECK(sphere_integral(160, [&](const vec3<double>& w) { return s.pdf(w); }) ==
          Approx(1).epsilon(5e-3));
    e.rotation = sphbasis::matrix_from_euler_zyz(0.3, 1.1, -0.7);
    const EnvironmentSampler r(e);
    CHECK(sphere_integral(160, [&](const vec3<double>& w) { return r.pdf(w); }) ==
          Approx(1).epsilon(5e-3));
}

TEST_CASE("EnvironmentSampler: sample() and pdf() agree; positive where radiance is",
          "[render][environment_sampler]") {
    const auto t = test_map(16, 8);
    Environment e = latlong_environment(t, 16, 8);
    e.rotation = sphbasis::matrix_from_euler_zyz(0.3, 1.1, -0.7);
    const EnvironmentSampler s(e);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> U(0, 1);
    for (int k = 0; k < 2000; ++k) {
        const auto x = s.sample(U(rng), U(rng));
        REQUIRE(std::fabs(sphbasis::dot(x.w, x.w) - 1) < 1e-12);
        REQUIRE(x.pdf > 0);
        REQUIRE(s.pdf(x.w) == Approx(x.pdf).epsilon(1e-9));
        const auto L = e.radiance(x.w);
        REQUIRE(L[0] == x.radiance[0]);
    }
    // Wherever radiance() is non-zero the density is positive (the neighbourhood maximum).
    int checked = 0;
    sphere_integral(64, [&](const vec3<double>& w) {
        const auto L = e.radiance(w);
        if (L[0] + L[1] + L[2] > 0) {
            CHECK(s.pdf(w) > 0);
            ++checked;
        }
        return 0.0;
    });
    CHECK(checked > 1000);
}

TEST_CASE("EnvironmentSampler: a histogram of sampled texels matches the density",
          "[render][environment_sampler]") {
    const int W = 16, H = 8;
    const auto t = test_map(W, H);
    const Environment e = latlong_environment(t, W, H);
    const EnvironmentSampler s(e);
    const int n = 40000;
    std::vector<double> count(std::size_t(W * H), 0.0);
    for (int k = 0; k < n; ++k) {
        double u, v;
        sphbasis::r2_sequence(std::uint64_t(k), u, v);
        const auto x = s.sample(u, v);
        const auto uv = sphbasis::param::latlong_to_square(x.w.x, x.w.y, x.w.z);
        const int i = std::min(W - 1, int(uv.x * W)), j = std::min(H - 1, int(uv.y * H));
        count[std::size_t(j * W + i)] += 1;
    }
    double total_p = 0;
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            // The texel's probability: its (constant) density times its solid angle.
            const double th0 = constants::pi * j / H, th1 = constants::pi * (j + 1) / H;
            const double omega = 2 * constants::pi / W * (std::cos(th0) - std::cos(th1));
            const double phi = 2 * constants::pi * (i + 0.5) / W, th = 0.5 * (th0 + th1);
            const vec3<double> c{std::sin(th) * std::cos(phi), std::sin(th) * std::sin(phi),
                                 std::cos(th)};
            const double p = s.pdf(c) * omega;
            total_p += p;
            const double expect = n * p;
            CHECK(std::fabs(count[std::size_t(j * W + i)] - expect) <= 5 * std::sqrt(expect) + 3);
        }
    CHECK(total_p == Approx(1).epsilon(1e-9));
    // The sun texels (and their neighbours) carry most of the density: over 8 times uniform.
    CHECK(
        s.pdf(vec3<double>{std::sin(2.5 * constants::pi / H) * std::cos(2 * constants::pi * 6 / W),
                           std::sin(2.5 * constants::pi / H) * std::sin(2 * constants::pi * 6 / W),
                           std::cos(2.5 * constants::pi / H)}) > 8 / (4 * constants::pi));
}

TEST_CASE("EnvironmentSampler: constant, black and absent environments",
          "[render][environment_sampler]") {
    Environment c = sphbasis_test::constant_environment({1, 2, 3});
    const EnvironmentSampler s(c);
    CHECK(s.emits());
    CHECK(s.is_constant());
    const auto x = s.sample(0.3, 0.8);
    CHECK(x.pdf == Approx(1 / (4 * constants::pi)));
    CHECK(x.radiance[2] == 3);
    CHECK(s.pdf(vec3<double>{0, 0, 1}) == Approx(1 / (4 * constants::pi)));

    std::vector<float> black(8 * 4 * 3, 0.0f);
    const EnvironmentSampler b(latlong_environment(black, 8, 4));
    CHECK(!b.emits());
    CHECK(b.sample(0.5, 0.5).pdf == Approx(1 / (4 * constants::pi)));

    const EnvironmentSampler none(Environment{});
    CHECK(!none.emits());
    CHECK(none.pdf(vec3<double>{0, 0, 1}) == 0);
    CHECK(none.sample(0.1, 0.2).pdf == 0);

    Environment bad;
    bad.kind = Environment::Kind::latlong;
    CHECK_THROWS_AS(EnvironmentSampler(bad), std::invalid_argument);
}
