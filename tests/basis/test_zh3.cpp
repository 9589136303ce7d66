// Tests for basis/zh3.hpp: ZH3 (Roughton et al. 2024) and its hallucinated variant.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/basis/zh3.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <vector>

#include "../support/basis_checks.hpp"
#include "../support/engine_reference.hpp"

using namespace sphbasis;

TEST_CASE("zh3: constants, fits and values against the reference generator", "[zh3]") {
    CHECK(zh3::detail::y00 == test::engine_constant("zh3.y00"));
    CHECK(zh3::detail::y1 == test::engine_constant("zh3.y1"));
    CHECK(zh3::detail::y20 == test::engine_constant("zh3.y20"));
    CHECK(zh3::detail::y2xy == test::engine_constant("zh3.y2xy"));
    CHECK(zh3::detail::y2xx == test::engine_constant("zh3.y2xx"));
    CHECK(zh3::detail::sqrt4pi_5 == test::engine_constant("zh3.sqrt4pi_5"));
    std::vector<std::array<double, 5>> full, halluc;
    for (const auto& r : test::engine_reference("fit-zh3")) {
        REQUIRE(r.size() == 15);
        std::array<double, 5> c;
        zh3::fit(r.data() + 1, c.data());
        for (int k = 0; k < 5; ++k)
            CHECK(c[std::size_t(k)] == Approx(r[std::size_t(10 + k)]).margin(1e-15));
        full.push_back(c);
    }
    for (const auto& r : test::engine_reference("fit-zh3-hallucinate")) {
        REQUIRE(r.size() == 10);
        std::array<double, 5> c;
        zh3::hallucinate(r.data() + 1, c.data());
        for (int k = 0; k < 5; ++k)
            CHECK(c[std::size_t(k)] == Approx(r[std::size_t(5 + k)]).margin(1e-15));
        halluc.push_back(c);
    }
    REQUIRE(full.size() == 6);
    REQUIRE(halluc.size() == 6);
    int n = 0;
    for (const auto& r : test::engine_reference("eval-zh3")) {
        const auto& c = full[std::size_t(r[0])];
        CHECK(zh3::eval(c.data(), r[1], r[2], r[3]) == Approx(r[4]).margin(2e-15));
        ++n;
    }
    for (const auto& r : test::engine_reference("eval-zh3-hallucinate")) {
        const auto& c = halluc[std::size_t(r[0])];
        CHECK(zh3::eval(c.data(), r[1], r[2], r[3]) == Approx(r[4]).margin(2e-15));
        ++n;
    }
    CHECK(n >= 40);
}

TEST_CASE("zh3: reproduces signals whose band 2 is zonal about the L1 axis; projection identity",
          "[zh3]") {
    // f = L0 + L1 along a + band 2 zonal about a: the SH coefficients of Y20(a . n) are
    // sqrt(4 pi/5) y_2m(a) (addition theorem), so ZH3 must reproduce f exactly.
    const double ax = 0.36, ay = -0.48, az = 0.8;  // unit
    std::array<double, 9> ya;
    sh::eval(3, ax, ay, az, ya.data());
    std::array<double, 9> sh;
    sh[0] = 1.3;
    sh[1] = 0.7 * ay, sh[2] = 0.7 * az, sh[3] = 0.7 * ax;
    for (int k = 4; k < 9; ++k)
        sh[std::size_t(k)] = -0.45 * std::sqrt(4 * M_PI / 5) * ya[std::size_t(k)];
    std::array<double, 5> c;
    zh3::fit(sh.data(), c.data());
    CHECK(c[4] == Approx(-0.45).epsilon(1e-14));
    for (const auto& d : test::random_dirs(40, 12, false)) {
        std::array<double, 9> y;
        sh::eval(3, d[0], d[1], d[2], y.data());
        double f = 0;
        for (int k = 0; k < 9; ++k) f += sh[std::size_t(k)] * y[std::size_t(k)];
        CHECK(zh3::eval(c.data(), d[0], d[1], d[2]) == Approx(f).margin(1e-14));
    }
    // General band 2: z is the projection of the band-2 part onto Y20(a . n) (sphere quadrature),
    // and the residual of the band-2 part is orthogonal to it.
    const std::array<double, 9> g = {0.2, -0.1, 0.4, 0.3, 0.25, -0.35, 0.15, 0.05, -0.2};
    zh3::fit(g.data(), c.data());
    const DirectionalRule rule = sphere_rule(6);
    const double l = std::sqrt(g[3] * g[3] + g[1] * g[1] + g[2] * g[2]);
    double proj = 0;
    for (std::size_t i = 0; i < rule.size(); ++i) {
        std::array<double, 9> y;
        sh::eval(3, rule.x[i], rule.y[i], rule.z[i], y.data());
        double b2 = 0;
        for (int k = 4; k < 9; ++k) b2 += g[std::size_t(k)] * y[std::size_t(k)];
        const double t = (g[3] * rule.x[i] + g[1] * rule.y[i] + g[2] * rule.z[i]) / l;
        proj += rule.w[i] * b2 * zh3::detail::y20 * (3 * t * t - 1);
    }
    CHECK(c[4] == Approx(proj).epsilon(1e-13));
}

TEST_CASE("zh3: hallucination constants, homogeneity, zero L1, batch and float", "[zh3]") {
    // A delta radiance toward +z: radiance L1/L0 = sqrt(3), so r = sqrt(3) and the radiance
    // zonal coefficient is L0 (0.08 sqrt(3) + 0.6 * 3) (Roughton et al. 2024).
    const double y0 = zh3::detail::y00, y1 = zh3::detail::y1;
    const std::array<double, 4> e = {y0, 0, 2.0 / 3.0 * y1, 0};  // irradiance of the delta
    std::array<double, 5> c;
    zh3::hallucinate(e.data(), c.data());
    CHECK(c[4] == Approx(0.25 * y0 * (0.08 * std::sqrt(3.0) + 1.8)).epsilon(1e-15));
    // Beyond a delta's ratio (signed signals) r is clamped at sqrt(3): the same coefficient.
    const std::array<double, 4> big = {y0, 0, 2 * y1, 0};
    std::array<double, 5> cb;
    zh3::hallucinate(big.data(), cb.data());
    CHECK(cb[4] == Approx(c[4]).epsilon(1e-15));
    // Homogeneous of degree 1 for negative scales too.
    const std::array<double, 9> g = {0.2, -0.1, 0.4, 0.3, 0.25, -0.35, 0.15, 0.05, -0.2};
    std::array<double, 9> gn;
    for (std::size_t k = 0; k < 9; ++k) gn[k] = -2 * g[k];
    std::array<double, 5> a, b;
    zh3::fit(g.data(), a.data());
    zh3::fit(gn.data(), b.data());
    for (const auto& d : test::random_dirs(10, 2, false))
        CHECK(zh3::eval(b.data(), d[0], d[1], d[2]) ==
              Approx(-2 * zh3::eval(a.data(), d[0], d[1], d[2])).margin(1e-14));
    // No L1: the axis is +z, finite everywhere.
    const std::array<double, 9> flat = {1, 0, 0, 0, 0, 0, 0.5, 0, 0};
    zh3::fit(flat.data(), c.data());
    CHECK(c[4] == Approx(0.5).epsilon(1e-15));
    CHECK(std::isfinite(zh3::eval(c.data(), 0.0, 0.0, 0.0)));
    // Batch equals scalar; float near double.
    const auto dirs = test::random_dirs(37, 21, false);
    const auto in = test::scaled_inputs<float>(dirs, 2);
    std::array<float, 5> cf;
    for (int k = 0; k < 5; ++k) cf[std::size_t(k)] = float(a[std::size_t(k)]);
    std::vector<float> out(dirs.size());
    zh3::eval_batch(cf.data(), dirs.size(), in.xs.data(), in.ys.data(), in.zs.data(), out.data());
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        const float s = zh3::eval(cf.data(), in.xs[i], in.ys[i], in.zs[i]);
        CHECK(out[i] == Approx(s).margin(1e-6));
        CHECK(double(s) ==
              Approx(zh3::eval(a.data(), dirs[i][0], dirs[i][1], dirs[i][2])).margin(2e-6));
    }
    CHECK_THROWS_WITH(zh3::fit(static_cast<const double*>(nullptr), c.data()),
                      Catch::Contains("zh3::fit(): expected a non-null sh buffer"));
    const FittedBasisInfo* f = find_fitted_basis("zh3");
    REQUIRE(f != nullptr);
    CHECK(f->stored == 5);
    CHECK(find_fitted_basis("zh3-hallucinate")->stored == 4);
    CHECK(find_fitted_basis("nope") == nullptr);
}
