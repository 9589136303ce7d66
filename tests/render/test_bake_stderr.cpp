// The standard errors of irradiance and radiance (render/bake.hpp): closed forms of the sample
// variance where the incoming radiance is known, agreement of a bake with a 16x-ray bake of
// another seed within a few standard errors at an occluded point under a non-constant sky, the
// 1/sqrt(N) law, and zero error on the quadrature and closed-form paths.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

using sphbasis::constants::pi;

/// A smooth lat-long sky whose channels differ (64 x 32 texels).
std::vector<float> gradient_sky() {
    const int w = 64, h = 32;
    std::vector<float> t(std::size_t(w * h * 3));
    for (int r = 0; r < h; ++r)
        for (int c = 0; c < w; ++c) {
            const double u = (c + 0.5) / w, v = (r + 0.5) / h;
            float* p = &t[std::size_t((r * w + c) * 3)];
            p[0] = static_cast<float>(0.3 + 1.5 * (1 - v));
            p[1] = static_cast<float>(1.0 + 0.6 * std::sin(2 * pi * u));
            p[2] = static_cast<float>(0.5 + 0.4 * std::cos(2 * pi * u) * (1 - v));
        }
    return t;
}

std::vector<PointResult> bake_one(const SceneDesc& d, BakeSettings s, int rays, std::uint64_t seed,
                                  const BakePoint& p) {
    s.rays = rays;
    s.seed = seed;
    Baker b(d, s);
    return b.bake({p});
}

}  // namespace

TEST_CASE("bake stderr: irradiance and radiance at an occluded point under a non-constant sky",
          "[render][bake]") {
    // The sphere (r = 1, centre height 2) over a plane; a point on the plane beside the shadow
    // axis, a sky that varies with direction and channel, a directional light, one bounce.
    const sphbasis_test::SphereOverPlane sp(32, 64);
    const std::vector<float> sky = gradient_sky();
    SceneDesc d = sp.meshes();
    d.environment = sphbasis_test::latlong_environment(sky, 64, 32);
    d.lights = {sphbasis_test::directional_light({0.6, 0, 0.8}, {1, 0.5, 0.2})};
    BakeSettings s;
    s.quantities = Quantity::irradiance | Quantity::radiance;
    s.bands = 3;
    s.basis = "hbasis";
    s.coeffs = 6;
    s.bounces = 1;
    BakePoint p;
    p.p = {0.7, 0, 0};
    p.n = {0, 0, 1};
    p.id = 11;
    const int n = 1024;
    const PointResult a = bake_one(d, s, n, 1, p)[0];
    const PointResult q = bake_one(d, s, 4 * n, 1, p)[0];
    const PointResult ref = bake_one(d, s, 16 * n, 2, p)[0];

    REQUIRE(a.irradiance_stderr.size() == 6);
    REQUIRE(a.radiance_stderr.size() == 9);
    auto check = [](const char* what, const std::array<std::vector<double>, 3>& v,
                    const std::vector<double>& se, const std::array<std::vector<double>, 3>& vr,
                    const std::vector<double>& ser, const std::vector<double>& se4) {
        std::vector<double> ratio;
        for (std::size_t k = 0; k < se.size(); ++k) {
            INFO(what << " coefficient " << k);
            CHECK(se[k] > 0);
            CHECK(std::isfinite(se[k]));
            // The bake and the 16x bake (another seed) differ by at most 4 joint standard errors
            // in every channel (the stderr is the max over channels: an upper bound for each).
            const double joint = std::sqrt(se[k] * se[k] + ser[k] * ser[k]);
            for (std::size_t c = 0; c < 3; ++c) CHECK(std::abs(v[c][k] - vr[c][k]) <= 4 * joint);
            // 4x the rays: the stderr halves (the sample variance is an estimate; 15%).
            CHECK(se[k] / se4[k] == Approx(2).epsilon(0.15));
            // 16x the rays: a quarter.
            CHECK(se[k] / ser[k] == Approx(4).epsilon(0.2));
            ratio.push_back(se[k] / se4[k]);
        }
        std::sort(ratio.begin(), ratio.end());
        CHECK(ratio[ratio.size() / 2] == Approx(2).epsilon(0.06));
    };
    check("irradiance", a.irradiance, a.irradiance_stderr, ref.irradiance, ref.irradiance_stderr,
          q.irradiance_stderr);
    check("radiance", a.radiance, a.radiance_stderr, ref.radiance, ref.radiance_stderr,
          q.radiance_stderr);
    // A change of seed moves the estimate by about the QMC error, below the Monte Carlo stderr
    // reported: the reported error is not too small by much either (the 16x bake's own stderr
    // is a quarter of it).
    CHECK(a.irradiance_stderr[0] < 0.2 * std::abs(a.irradiance[0][0]));
}

TEST_CASE("bake stderr: radiance stderr is the closed-form sqrt(var / N) under a constant sky",
          "[render][bake]") {
    // No geometry, forced rays: L_in = c everywhere, s_j = 4pi c y_i(w_j) with w_j uniform on
    // the sphere, so var(s_0) = 0 and var(s_i) = 4pi c^2 for i > 0 (int y_i^2 = 1, mean 0).
    SceneDesc d;
    d.environment = sphbasis_test::constant_environment({1, 2, 3});
    BakeSettings s;
    s.quantities = Quantity::radiance;
    s.bands = 3;
    s.rays = 4096;
    BakePoint p;
    SECTION("forced rays") {
        s.force_all_passes = true;
        Baker b(d, s);
        const PointResult r = b.bake({p})[0];
        REQUIRE(r.radiance_stderr.size() == 9);
        CHECK(r.radiance_stderr[0] < 1e-6);  // 0 up to the rounding of the one-pass variance
        for (std::size_t k = 1; k < 9; ++k) {
            INFO("coefficient " << k);
            CHECK(r.radiance_stderr[k] == Approx(3 * std::sqrt(4 * pi / 4096)).epsilon(0.03));
        }
    }
    SECTION("closed forms: no rays, no error") {
        d.lights = {sphbasis_test::directional_light({0, 0.6, 0.8}, {2, 2, 2})};
        Baker b(d, s);
        const PointResult r = b.bake({p})[0];
        CHECK(b.rays_traced() == 0);
        CHECK(r.radiance_stderr == std::vector<double>(9, 0.0));
    }
}

TEST_CASE("bake stderr: irradiance stderr against quadrature of the estimator's variance",
          "[render][bake]") {
    // A point on a face of a lone box under a constant sky 1: L_in = 1 on the upper hemisphere, so
    // s_j,k = 2pi g_k(w_j), g = M y(w) with M = P C (P the fit's projector over its rule, C the
    // clamped-cosine map of 8-band SH to irradiance at the rule's normals), and
    // var_k = (1 / 2pi) int_{z > 0} (2pi g_k)^2 dw - (int_{z > 0} g_k dw)^2, by quadrature.
    const Mesh box = shapes::box({0, 0, 0}, {1, 1, 1});
    SceneDesc d;
    d.meshes = {box.view()};
    d.environment = sphbasis_test::constant_environment({1, 1, 1});
    BakeSettings s;
    s.quantities = Quantity::irradiance;
    s.basis = "sh";
    s.coeffs = 9;
    s.rays = 4096;
    BakePoint p;
    p.p = {0.3, -0.2, 1};
    p.n = {0, 0, 1};
    p.id = 5;
    SECTION("unoccluded: quadrature, stderr 0") {
        Baker b(d, s);
        const PointResult r = b.bake({p})[0];
        CHECK(b.rays_traced() == 0);
        CHECK(r.irradiance_stderr == std::vector<double>(9, 0.0));
    }
    SECTION("forced rays: the stderr is sqrt(var / N)") {
        s.force_all_passes = true;
        Baker b(d, s);
        const PointResult r = b.bake({p})[0];
        REQUIRE(b.rays_traced() == 4096);
        const IrradianceFit fit("sh", 9, hemisphere_rule_sqrt(32, 32));
        const DirectionalRule& fr = fit.rule();
        const Eigen::Index m = Eigen::Index(fr.size());
        const Eigen::MatrixXd P = Eigen::Map<
            const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            fit.projector().data(), 9, m);
        double a[8];
        clamped_cosine_factors(8, a);
        Eigen::MatrixXd C(m, 64);
        std::vector<double> y(64);
        for (Eigen::Index i = 0; i < m; ++i) {
            const std::size_t ii = std::size_t(i);
            sh::eval(8, fr.x[ii], fr.y[ii], fr.z[ii], y.data());
            for (int l = 0; l < 8; ++l)
                for (int k = l * l; k < (l + 1) * (l + 1); ++k)
                    C(i, k) = pi * a[l] * y[std::size_t(k)];
        }
        const Eigen::MatrixXd M = P * C;
        const DirectionalRule q = hemisphere_rule(40);
        Eigen::VectorXd mean = Eigen::VectorXd::Zero(9), sq = Eigen::VectorXd::Zero(9);
        Eigen::VectorXd yv(64);
        for (std::size_t j = 0; j < q.size(); ++j) {
            sh::eval(8, q.x[j], q.y[j], q.z[j], yv.data());
            const Eigen::VectorXd g = M * yv;
            mean += q.w[j] * g;
            sq += q.w[j] * (2 * pi) * g.cwiseProduct(g);
        }
        for (Eigen::Index k = 0; k < 9; ++k) {
            INFO("coefficient " << k);
            const double var = sq(k) - mean(k) * mean(k);
            CHECK(r.irradiance[0][std::size_t(k)] == Approx(mean(k)).margin(0.02));
            CHECK(r.irradiance_stderr[std::size_t(k)] ==
                  Approx(std::sqrt(var / 4096)).epsilon(0.03));
        }
    }
}

namespace {

/// The angle between unit vectors a and b (radians), accurate for small angles.
double bent_angle(const vec3<double>& a, const vec3<double>& b) {
    const vec3<double> c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    return std::atan2(std::sqrt(dot(c, c)), dot(a, b));
}

}  // namespace

TEST_CASE("bake stderr: bent normal stderr, closed form on an unoccluded face", "[render][bake]") {
    // A face of a lone box, forced rays: V = 1, the cosine-weighted w_j have mean (0, 0, 2/3)
    // in the tangent frame and E[w_x^2] = E[w_y^2] = 1/4, so trace(P S P) -> 1/2 and
    // bent_stderr -> sqrt(1 / (2N)) / (2/3).
    const Mesh box = shapes::box({0, 0, 0}, {1, 1, 1});
    SceneDesc d;
    d.meshes = {box.view()};
    BakeSettings s;
    s.quantities = Quantity::bent;
    BakePoint p;
    p.p = {0.3, -0.2, 1};
    p.n = {0, 0, 1};
    p.id = 9;
    SECTION("forced rays") {
        s.force_all_passes = true;
        for (int n : {256, 4096}) {
            INFO(n << " rays");
            s.rays = n;
            Baker b(d, s);
            const PointResult r = b.bake({p})[0];
            REQUIRE(b.rays_traced() == std::uint64_t(n));
            CHECK(r.bent_stderr == Approx(std::sqrt(0.5 / n) / (2.0 / 3)).epsilon(0.03));
            CHECK(bent_angle(r.bent, {0, 0, 1}) < 3 * r.bent_stderr);
        }
    }
    SECTION("analytic pass: bent = n exactly, stderr 0, no rays") {
        s.quantities = Quantity::bent | Quantity::ao;
        Baker b(d, s);
        const PointResult r = b.bake({p})[0];
        CHECK(b.rays_traced() == 0);
        CHECK(r.bent.z == 1);
        CHECK(r.bent_stderr == 0);
    }
    SECTION("no unoccluded sample: bent = n, stderr pi") {
        // The centre of the closed box: every ray hits a wall.
        BakePoint q;
        q.p = {0, 0, 0};
        q.n = {0, 0.6, 0.8};
        s.rays = 64;
        Baker b(d, s);
        const PointResult r = b.bake({q})[0];
        CHECK(b.rays_traced() == 64);
        CHECK(r.bent.y == Approx(0.6));
        CHECK(r.bent.z == Approx(0.8));
        CHECK(r.bent_stderr == pi);
    }
    SECTION("one ray: no variance estimate, stderr pi") {
        s.force_all_passes = true;
        s.rays = 1;
        Baker b(d, s);
        CHECK(b.bake({p})[0].bent_stderr == pi);
    }
}

TEST_CASE("bake stderr: bent normal stderr, sphere over a plane at 1024, 4096, 16384 rays",
          "[render][bake]") {
    // Points on the plane around the sphere's shadow (r = 1, centre height 2): the bake at N rays
    // and at 16N (another seed) agree within 4 joint standard errors, and the stderr halves
    // with 4x the rays.
    const sphbasis_test::SphereOverPlane sp(32, 64);
    SceneDesc d = sp.meshes();
    BakeSettings s;
    s.quantities = Quantity::bent;
    std::vector<BakePoint> pts;
    for (int i = 0; i < 6; ++i) {
        BakePoint p;
        p.p = {0.25 * i, 0.1 * i, 0};
        p.n = {0, 0, 1};
        p.id = std::uint64_t(20 + i);
        pts.push_back(p);
    }
    auto run = [&](int rays, std::uint64_t seed) {
        s.rays = rays;
        s.seed = seed;
        return Baker(d, s).bake(pts);
    };
    const int n = 1024;
    const auto a = run(n, 1), q = run(4 * n, 1), ref = run(16 * n, 2);
    std::vector<double> ratio;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        INFO("point " << i << ": stderr " << a[i].bent_stderr << ", " << q[i].bent_stderr << ", "
                      << ref[i].bent_stderr << ", angle to 16N "
                      << bent_angle(a[i].bent, ref[i].bent));
        CHECK(a[i].bent_stderr > 0);
        CHECK(a[i].bent_stderr < 0.1);
        const double joint = std::sqrt(a[i].bent_stderr * a[i].bent_stderr +
                                       ref[i].bent_stderr * ref[i].bent_stderr);
        CHECK(bent_angle(a[i].bent, ref[i].bent) <= 4 * joint);
        CHECK(a[i].bent_stderr / q[i].bent_stderr == Approx(2).epsilon(0.15));
        CHECK(a[i].bent_stderr / ref[i].bent_stderr == Approx(4).epsilon(0.2));
        ratio.push_back(a[i].bent_stderr / q[i].bent_stderr);
    }
    std::sort(ratio.begin(), ratio.end());
    CHECK(ratio[ratio.size() / 2] == Approx(2).epsilon(0.06));
}

TEST_CASE("bake stderr: transfer_matrix stderr, closed form and convergence", "[render][bake]") {
    // Sphere (r = 1, centre height 2) over a plane, a point on the plane.
    const sphbasis_test::SphereOverPlane sp(32, 64);
    SceneDesc d = sp.meshes();
    BakeSettings s;
    s.quantities = Quantity::transfer_matrix;
    s.bands = 2;
    BakePoint p;
    p.p = {0.4, 0.2, 0};
    p.n = {0, 0, 1};
    p.id = 4;
    const std::size_t nl = 4;
    SECTION("no bounces: s_j,00 = -1/2 on occluded samples") {
        // M_00 = 1 - p/2 with p the occluded fraction, stderr_00 = (1/2) sqrt(p (1 - p) / (N - 1)).
        const int n = 1024;
        const PointResult r = bake_one(d, s, n, 3, p)[0];
        REQUIRE(r.transfer_matrix_stderr.size() == 9 * nl);
        const double occ = 2 * (1 - r.transfer_matrix[0][0]);
        CHECK(occ > 0.05);
        CHECK(occ < 0.95);
        CHECK(r.transfer_matrix_stderr[0] ==
              Approx(0.5 * std::sqrt(occ * (1 - occ) / (n - 1))).epsilon(1e-9));
    }
    SECTION("one bounce, albedo per channel: N against 16N within 4 joint stderr, 1/sqrt(N)") {
        d.meshes[0].albedo = {0.8f, 0.5f, 0.3f};
        d.meshes[1].albedo = {0.6f, 0.6f, 0.9f};
        s.bounces = 1;
        s.target_error = 0;
        const int n = 1024;
        const PointResult a = bake_one(d, s, n, 1, p)[0];
        const PointResult q = bake_one(d, s, 4 * n, 1, p)[0];
        const PointResult ref = bake_one(d, s, 16 * n, 2, p)[0];
        std::vector<double> ratio;
        for (std::size_t e = 0; e < 9 * nl; ++e) {
            INFO("element " << e / nl << ", " << e % nl << ": stderr "
                            << a.transfer_matrix_stderr[e] << ", " << q.transfer_matrix_stderr[e]);
            const double se = a.transfer_matrix_stderr[e], se4 = q.transfer_matrix_stderr[e],
                         ser = ref.transfer_matrix_stderr[e];
            CHECK(se > 0);
            const double joint = std::sqrt(se * se + ser * ser);
            for (std::size_t c = 0; c < 3; ++c)
                CHECK(std::abs(a.transfer_matrix[c][e] - ref.transfer_matrix[c][e]) <= 4 * joint);
            CHECK(se / se4 == Approx(2).epsilon(0.15));
            ratio.push_back(se / se4);
        }
        std::sort(ratio.begin(), ratio.end());
        CHECK(ratio[ratio.size() / 2] == Approx(2).epsilon(0.06));
    }
    SECTION("analytic M = I: stderr 0") {
        const Mesh box = shapes::box({0, 0, 0}, {1, 1, 1});
        SceneDesc lone;
        lone.meshes = {box.view()};
        BakePoint f;
        f.p = {0.3, -0.2, 1};
        f.n = {0, 0, 1};
        Baker b(lone, s);
        const PointResult r = b.bake({f})[0];
        CHECK(b.rays_traced() == 0);
        CHECK(r.transfer_matrix_stderr == std::vector<double>(9 * nl, 0.0));
    }
}
