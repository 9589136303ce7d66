// Tests for basis/sh_l1_nonlinear.hpp: L1 SH with the Geomerics reconstruction.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/basis/sh_l1_nonlinear.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <vector>

#include "../support/basis_checks.hpp"
#include "../support/engine_reference.hpp"

using namespace sphbasis;

TEST_CASE("sh-l1-nonlinear: values against the reference generator", "[sh-l1-nonlinear]") {
    CHECK(sh_l1_nonlinear::detail::half_y1 == test::engine_constant("sh_l1_nonlinear.half_y1"));
    const auto fits = test::engine_reference("fit-zh3");  // the coefficient sets
    int n = 0;
    for (const auto& r : test::engine_reference("eval-sh-l1-nonlinear")) {
        const double* c = fits[std::size_t(r[0])].data() + 1;
        CHECK(sh_l1_nonlinear::eval(c, r[1], r[2], r[3]) == Approx(r[4]).margin(4e-15));
        ++n;
    }
    CHECK(n >= 40);
}

TEST_CASE("sh-l1-nonlinear: mean, small-r limit, non-negativity, homogeneity",
          "[sh-l1-nonlinear]") {
    const DirectionalRule rule = sphere_rule(120);
    const double y0 = 0.28209479177387814, y1 = 0.48860251190291992;
    // Mean over the sphere = R0 = e0 y00 (quadrature; the pow kink needs a fine rule).
    const std::array<double, 4> c = {1.0, 0.3, -0.2, 0.5};
    double mean = 0;
    for (std::size_t i = 0; i < rule.size(); ++i)
        mean += rule.w[i] * sh_l1_nonlinear::eval(c.data(), rule.x[i], rule.y[i], rule.z[i]);
    CHECK(mean / (4 * M_PI) == Approx(y0).epsilon(1e-6));
    // Small L1: the linear L1 expansion e0 y00 + e1 . y1(n).
    const std::array<double, 4> s = {1.0, 1e-7, -2e-7, 3e-7};
    for (const auto& d : test::random_dirs(20, 5, false)) {
        const double lin = y0 + y1 * (s[1] * d[1] + s[2] * d[2] + s[3] * d[0]);
        CHECK(sh_l1_nonlinear::eval(s.data(), d[0], d[1], d[2]) == Approx(lin).margin(1e-13));
    }
    // The irradiance of a delta radiance toward +z (r = 1): a = 0, p = 3, f = 4 R0 q^3 >= 0,
    // zero at -z and 4 R0 at +z.
    const std::array<double, 4> delta = {y0, 0, 2.0 / 3.0 * y1, 0};
    CHECK(sh_l1_nonlinear::eval(delta.data(), 0.0, 0.0, -1.0) == Approx(0).margin(1e-17));
    CHECK(sh_l1_nonlinear::eval(delta.data(), 0.0, 0.0, 1.0) == Approx(4 * y0 * y0).epsilon(1e-14));
    // f(-e) = -f(e), f(2e) = 2 f(e); constant signal exactly.
    std::array<double, 4> neg, dbl;
    for (std::size_t k = 0; k < 4; ++k) neg[k] = -c[k], dbl[k] = 2 * c[k];
    const std::array<double, 4> flat = {2.0, 0, 0, 0};
    for (const auto& d : test::random_dirs(10, 6, false)) {
        const double f = sh_l1_nonlinear::eval(c.data(), d[0], d[1], d[2]);
        CHECK(sh_l1_nonlinear::eval(neg.data(), d[0], d[1], d[2]) == Approx(-f).margin(1e-15));
        CHECK(sh_l1_nonlinear::eval(dbl.data(), d[0], d[1], d[2]) == Approx(2 * f).margin(1e-15));
        CHECK(sh_l1_nonlinear::eval(flat.data(), d[0], d[1], d[2]) == 2 * y0);
    }
}

TEST_CASE("sh-l1-nonlinear: batch equals scalar, float near double, bad input",
          "[sh-l1-nonlinear]") {
    const std::array<double, 4> c = {1.0, 0.3, -0.2, 0.5};
    const std::array<float, 4> cf = {1.0f, 0.3f, -0.2f, 0.5f};
    const auto dirs = test::random_dirs(37, 22, false);
    const auto in = test::scaled_inputs<float>(dirs, 3);
    std::vector<float> out(dirs.size());
    sh_l1_nonlinear::eval_batch(cf.data(), dirs.size(), in.xs.data(), in.ys.data(), in.zs.data(),
                                out.data());
    for (std::size_t i = 0; i < dirs.size(); ++i) {
        const float s = sh_l1_nonlinear::eval(cf.data(), in.xs[i], in.ys[i], in.zs[i]);
        CHECK(out[i] == Approx(s).margin(1e-6));
        CHECK(double(s) ==
              Approx(sh_l1_nonlinear::eval(c.data(), dirs[i][0], dirs[i][1], dirs[i][2]))
                  .margin(2e-6));
    }
    std::array<double, 4> o;
    CHECK_THROWS_WITH(sh_l1_nonlinear::fit(static_cast<const double*>(nullptr), o.data()),
                      Catch::Contains("expected a non-null sh buffer"));
    const std::array<double, 4> inf = {1.0, HUGE_VAL, 0, 0};
    CHECK(std::isfinite(sh_l1_nonlinear::eval(c.data(), 0.0, 0.0, 0.0)));
    (void)inf;
    const FittedBasisInfo* f = find_fitted_basis("sh-l1-nonlinear");
    REQUIRE(f != nullptr);
    CHECK(f->stored == 4);
    CHECK(f->eval_d(c.data(), 0.0, 0.6, 0.8) == sh_l1_nonlinear::eval(c.data(), 0.0, 0.6, 0.8));
}
