// Tests of the engine bases in the bake's irradiance and the render representations that read
// it (render/irradiance_fit.hpp's IrradianceStorage, render/bake.hpp's linear stage and
// finish_point(), representations/lightmap.hpp, representations/volume_engine.hpp): each
// against an independent computation (the fits of ops/sg_fit.hpp, the fitted representations'
// own fit of an SH projection by quadrature, closed forms of the constant sky).
#include <Eigen/Dense>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "../render_test_support.hpp"
#include "sky_probes_for_tests.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/ops/sg_fit.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/irradiance_fit.hpp"
#include "sphbasis/render/representation.hpp"

namespace {

using namespace sphbasis;
using render::Quantity;

/// A lone unit quad (nothing occludes it: the bake's analytic pass), lit by a directional light
/// only, and the one point at its centre facing +z.
struct SunQuad {
    sphbasis_test::World w;
    vec3<double> sun = sphbasis_test::unit({0.6, -0.3, 0.4});
    SunQuad() {
        w.meshes.push_back(sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1));
        render::Light l;
        l.type = render::Light::Type::directional;
        l.direction = sun;
        l.color = {2.0, 1.0, 0.5};
        w.desc.lights.push_back(l);
        w.build();
    }
    render::PointResult bake(const std::string& basis, int coeffs) const {
        render::BakeSettings s;
        s.quantities = Quantity::irradiance;
        s.basis = basis;
        s.coeffs = coeffs;
        s.rays = 16;
        render::BakePoint p;
        p.n = {0, 0, 1};
        p.tangent = {1, 0, 0};
        return render::Baker(w.desc, s).bake({p})[0];
    }
};

/// E(n') = max(n' . l, 0) on a rule's directions (one channel).
Eigen::MatrixXd clamped_cosine_on(const DirectionalRule& r, const vec3<double>& l) {
    Eigen::MatrixXd v(Eigen::Index(r.size()), 1);
    for (std::size_t i = 0; i < r.size(); ++i)
        v(Eigen::Index(i), 0) = std::max(0.0, r.x[i] * l.x + r.y[i] * l.y + r.z[i] * l.z);
    return v;
}

}  // namespace

TEST_CASE("engine irradiance: storage names, counts and errors", "[render]") {
    using K = render::IrradianceStorage::Kind;
    CHECK(render::irradiance_storage("sg", 9).kind == K::linear);
    CHECK(render::irradiance_storage("sg-nnls", 12).kind == K::sg_nnls);
    CHECK(render::irradiance_storage("sg-running", 5).kind == K::sg_running);
    CHECK(render::irradiance_storage("zh3", 5).stage() == 9);
    CHECK(render::irradiance_storage("sh-l1-nonlinear", 4).stage() == 4);
    CHECK(render::irradiance_storage("zh3-hallucinate", 4).stage() == 4);
    CHECK_THROWS_WITH(render::irradiance_storage("zh3", 9), Catch::Contains("5 values for 'zh3'"));
    CHECK_THROWS_WITH(render::irradiance_storage("sg-nnls", 7),
                      Catch::Contains("5, 6, 9 or 12 functions"));
    CHECK_THROWS_WITH(render::irradiance_storage("sg7", 7), Catch::Contains("unknown basis 'sg7'"));
    render::BakeSettings s;
    s.quantities = Quantity::irradiance;
    s.basis = "sh-l1-nonlinear";
    s.coeffs = 9;
    sphbasis_test::World w;
    w.meshes.push_back(sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1));
    w.build();
    CHECK_THROWS_WITH(render::Baker(w.desc, s), Catch::Contains("render::Baker"));
}

TEST_CASE("engine irradiance: the running-average projector is the running average", "[render]") {
    // sg_running_projector() applies Roughton's running average as a matrix (its linearity in
    // the values); ops/sg_fit.hpp's RunningAverage on the same values in the same order is
    // the independent run.
    const DirectionalRule r = render::sg_running_directions(300);
    for (int lobes : {5, 9, 12}) {
        INFO(lobes << " lobes");
        const std::vector<double> p = render::sg_running_projector(lobes, r);
        Eigen::MatrixXd v(Eigen::Index(r.size()), 2);
        for (std::size_t i = 0; i < r.size(); ++i) {
            v(Eigen::Index(i), 0) = 1 + 0.5 * r.z[i] + 0.3 * r.x[i] * r.y[i];
            v(Eigen::Index(i), 1) = std::exp(3 * (r.x[i] - 1));
        }
        const Eigen::MatrixXd ref =
            sg::fit_function(sg::bakinglab_lobes(lobes), r, v, sg::Solver::running_average);
        for (int k = 0; k < lobes; ++k)
            for (Eigen::Index c = 0; c < 2; ++c) {
                double a = 0;
                for (std::size_t i = 0; i < r.size(); ++i)
                    a += p[std::size_t(k) * r.size() + i] * v(Eigen::Index(i), c);
                CHECK(a == Approx(ref(k, c)).margin(1e-12));
            }
    }
}

TEST_CASE("engine irradiance: SG lobes of a sun by least squares, NNLS and running average",
          "[render]") {
    // The sun's E(n') = col max(n' . l, 0) is integrated exactly by the analytic pass, so the
    // bake's amplitudes equal ops/sg_fit.hpp's fits of the same function on the same directions
    // (column-pivoted QR and NNLS on the weighted design matrix; the running average in
    // sg_running_directions()' order).
    const SunQuad q;
    const DirectionalRule ls_rule = hemisphere_rule_sqrt(32, 32);
    const DirectionalRule run_rule = render::sg_running_directions();
    for (int lobes : {5, 9, 12}) {
        const auto set = sg::bakinglab_lobes(lobes);
        const Eigen::MatrixXd ls = sg::fit_function(set, ls_rule, clamped_cosine_on(ls_rule, q.sun),
                                                    sg::Solver::least_squares);
        const Eigen::MatrixXd nn =
            sg::fit_function(set, ls_rule, clamped_cosine_on(ls_rule, q.sun), sg::Solver::nnls);
        const Eigen::MatrixXd ra = sg::fit_function(
            set, run_rule, clamped_cosine_on(run_rule, q.sun), sg::Solver::running_average);
        INFO("least-squares amplitudes from " << ls.minCoeff() << " to " << ls.maxCoeff());
        CHECK(nn.minCoeff() >= 0);
        const std::array<std::pair<const char*, const Eigen::MatrixXd*>, 3> cases{
            {{"sg", &ls}, {"sg-nnls", &nn}, {"sg-running", &ra}}};
        for (const auto& [name, ref] : cases) {
            INFO(name << " " << lobes);
            const render::PointResult r = q.bake(name, lobes);
            for (std::size_t c = 0; c < 3; ++c) {
                REQUIRE(r.irradiance[c].size() == std::size_t(lobes));
                const double col = c == 0 ? 2.0 : (c == 1 ? 1.0 : 0.5);
                for (int k = 0; k < lobes; ++k)
                    CHECK(r.irradiance[c][std::size_t(k)] ==
                          Approx(col * (*ref)(k, 0)).epsilon(1e-6).margin(1e-8));
            }
            CHECK(r.irradiance_stderr.size() == std::size_t(lobes));
        }
    }
}

TEST_CASE("engine irradiance: ZH3 and non-linear L1 of a sun from the SH of E by quadrature",
          "[render]") {
    // E's SH coefficients by quadrature of col max(n' . l, 0) over the sphere (a fine
    // Gauss-product rule; the kink limits it to ~1e-5), then each representation's own fit.
    const SunQuad q;
    const DirectionalRule rule = sphere_rule(200);
    std::array<double, 9> e{};
    std::array<double, 9> y{};
    for (std::size_t i = 0; i < rule.size(); ++i) {
        const double c =
            std::max(0.0, rule.x[i] * q.sun.x + rule.y[i] * q.sun.y + rule.z[i] * q.sun.z);
        sh::eval_unit(3, rule.x[i], rule.y[i], rule.z[i], y.data());
        for (std::size_t k = 0; k < 9; ++k) e[k] += rule.w[i] * c * y[k];
    }
    for (const char* name : {"zh3", "zh3-hallucinate", "sh-l1-nonlinear"}) {
        INFO(name);
        const FittedBasisInfo& f = *find_fitted_basis(name);
        std::vector<double> want(std::size_t(f.stored));
        f.fit(e.data(), want.data());
        const render::PointResult r = q.bake(name, f.stored);
        for (std::size_t c = 0; c < 3; ++c) {
            REQUIRE(r.irradiance[c].size() == std::size_t(f.stored));
            const double col = c == 0 ? 2.0 : (c == 1 ? 1.0 : 0.5);
            for (std::size_t k = 0; k < want.size(); ++k)
                CHECK(r.irradiance[c][k] == Approx(col * want[k]).margin(1e-4));
        }
        CHECK(r.irradiance_stderr.size() == std::size_t(f.stored));
    }
}

TEST_CASE("engine volumes: volume-sg9 is the SG fit of the volume's irradiance", "[render]") {
    // volume-sg9 stores the least-squares fit over the sphere in BakingLab's 9 world-space
    // lobes (sky_probes_for_tests.hpp): at n = +z the fit's value, from ops/sg_fit.hpp.
    const DirectionalRule rule = sphere_rule(40);
    Eigen::MatrixXd v(Eigen::Index(rule.size()), 1);
    for (std::size_t i = 0; i < rule.size(); ++i) v(Eigen::Index(i), 0) = 0.5 * (1 + rule.z[i]);
    const auto lobes = sg::bakinglab_lobes(9, sg::Distribution::sphere);
    const Eigen::MatrixXd a = sg::fit_function(lobes, rule, v, sg::Solver::least_squares);
    double at_z = 0;
    for (std::size_t k = 0; k < lobes.size(); ++k)
        at_z += a(Eigen::Index(k), 0) * sg::eval(lobes[k], 0.0, 0.0, 1.0);
    INFO("fit at +z " << at_z);
    const auto vol = sphbasis_test::volume_against_sh("volume-sg9", at_z);
    CHECK(vol.worst < 0.02);
    CHECK(vol.stats.element == "probe");
    CHECK(vol.stats.bytes_per_element == 27 * sizeof(float));
    CHECK_FALSE(vol.stats.cannot_show.empty());
}
