// Adaptive sampling of render::Baker (BakeSettings::adaptive): the stopping rule, the error it
// reaches against a closed form, determinism and the summary's bookkeeping.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <vector>

#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

/// A ground plane z = 0 and a wall x = 1 (both 2e5 wide, the wall as high), white sky. A
/// point on the ground at x < 1 sees the wall over exactly the directions with w_x > 0 (the
/// wall is infinite to within (1 - x) / 1e5), so its ambient occlusion is 1/2 (the cosine
/// weight is symmetric in w_x).
struct WallScene {
    Mesh ground = shapes::quad({0, 0, 0}, {1e5, 0, 0}, {0, 1e5, 0}, 1);
    Mesh wall = shapes::quad({1, 0, 0}, {0, 1e5, 0}, {0, 0, 1e5}, 1);
    SceneDesc desc() const {
        SceneDesc d;
        d.meshes = {ground.view(), wall.view()};
        d.environment.kind = Environment::Kind::constant;
        d.environment.constant = {1, 1, 1};
        return d;
    }
    static std::vector<BakePoint> points(std::size_t n, std::uint64_t id0 = 0) {
        std::vector<BakePoint> pts(n);
        for (std::size_t i = 0; i < n; ++i) {
            pts[i].p = {1 - 0.05 - 2.0 * double(i) / double(n), 0.37 * double(i), 0};
            pts[i].n = {0, 0, 1};
            pts[i].id = id0 + i;
        }
        return pts;
    }
    /// Appends the first `count` points of pts lifted to z = 2e5, above everything (ids id0 + i):
    /// they see no occluder, report a standard error of 0 and stop after one batch.
    static void add_open_points(std::vector<BakePoint>& pts, std::size_t count, std::uint64_t id0) {
        for (std::size_t i = 0; i < count; ++i) {
            BakePoint p = pts[i];
            p.p.z = 2e5;
            p.id = id0 + i;
            pts.push_back(p);
        }
    }
};

/// Settings baking ao with `rays` rays per batch and `seed`; an adaptive target `target` for ao
/// up to `batches` batches when target > 0.
BakeSettings ao_settings(int rays, std::uint64_t seed, double target = 0, int batches = 0) {
    BakeSettings s;
    s.quantities = Quantity::ao;
    s.rays = rays;
    s.seed = seed;
    if (target > 0) {
        s.adaptive[Quantity::ao] = target;
        s.adaptive.max_rays = rays * batches;
    }
    return s;
}

}  // namespace

TEST_CASE("render::Baker adaptive: one batch is the fixed bake, bit for bit", "[render][bake]") {
    WallScene w;
    BakeSettings s;
    s.quantities = Quantity::ao | Quantity::bent | Quantity::transfer | Quantity::irradiance;
    s.rays = 64;
    s.seed = 3;
    const auto pts = WallScene::points(8);
    const auto fixed = Baker(w.desc(), s).bake(pts);
    s.adaptive[Quantity::ao] = 1e-9;  // never met: every point stops at max_rays
    s.adaptive.max_rays = 64;
    Baker b(w.desc(), s);
    const auto one = b.bake(pts);
    std::uint64_t rays = 0;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        CHECK(one[i].batches == 1);
        CHECK(one[i].ao == fixed[i].ao);
        CHECK(one[i].ao_stderr == fixed[i].ao_stderr);
        CHECK(one[i].bent.x == fixed[i].bent.x);
        CHECK(one[i].transfer[0] == fixed[i].transfer[0]);
        CHECK(one[i].irradiance[2] == fixed[i].irradiance[2]);
        CHECK(one[i].rays == fixed[i].rays);
        rays += one[i].rays;
    }
    CHECK(rays == b.rays_traced());
}

TEST_CASE("render::Baker adaptive: each point stops at the first batch that meets its target",
          "[render][bake]") {
    WallScene w;
    const double target = 0.02;
    const BakeSettings s = ao_settings(64, 11, target, 40);
    const auto pts = WallScene::points(16);
    const auto r = Baker(w.desc(), s).bake(pts);
    for (std::size_t i = 0; i < pts.size(); ++i) {
        INFO("point " << i << ", " << r[i].batches << " batches");
        const double n = double(r[i].batches) * 64, p = r[i].ao;
        // Pooled batches report the standard error of one sample of n rays.
        CHECK(r[i].ao_stderr == Approx(std::sqrt(p * (1 - p) / (n - 1))).epsilon(1e-12));
        CHECK(r[i].ao_stderr <= target);
        // sqrt(1/4 / (n - 1)) <= 0.02 at n >= 626: at most 10 batches of 64 are ever needed.
        CHECK(r[i].batches <= 10);
        CHECK(r[i].batches > 1);
        // One batch fewer (max_rays cut there) gives the same first batches, above the target.
        BakeSettings s2 = s;
        s2.adaptive.max_rays = 64 * (r[i].batches - 1);
        const auto r2 = Baker(w.desc(), s2).bake({pts[i]});
        CHECK(r2[0].batches == r[i].batches - 1);
        CHECK(r2[0].ao_stderr > target);
        CHECK_FALSE(meets_targets(s2, r2[0]));
    }
}

TEST_CASE("render::Baker adaptive: the measured ao error meets the target (closed form 1/2)",
          "[render][bake]") {
    // A point on the ground next to an infinite wall has ao = 1/2 exactly (WallScene). With
    // the target t met, each error e_i = ao_i - 1/2 has variance at most about t^2 (the batches
    // are randomised QMC, whose variance is at most that of the Monte Carlo estimate the
    // standard error describes, and the pooled estimate of p (1 - p) is within 1% of 1/4 at the
    // counts reached). Over M = 100 independent points sum e_i^2 / t^2 is then dominated by
    // chi-square with 100 degrees of freedom (normal approximation of the binomial), which
    // exceeds 182.13 with probability 1e-6 (scipy.stats.chi2.isf(1e-6, 100)): the false-failure
    // probability of this test. A batch of 32 rays that all agree (probability 2^-31 per
    // point at p = 1/2) would stop a point early. A bake stopped at the first batch (64 rays, a
    // standard error of 0.0625 = 3.1 t) would give a sum near 100 * 9.8 under Monte Carlo.
    WallScene w;
    const double t = 0.02;
    const BakeSettings s = ao_settings(32, 5, t, 100);
    const auto pts = WallScene::points(100, 7000);
    const auto r = Baker(w.desc(), s).bake(pts);
    double chi = 0;
    for (const PointResult& x : r) {
        CHECK(x.ao_stderr <= t);
        chi += (x.ao - 0.5) * (x.ao - 0.5) / (t * t);
    }
    INFO("sum e^2 / t^2 = " << chi);
    CHECK(chi <= 182.13);
}

TEST_CASE("render::Baker adaptive: same results for any thread count and any sharding",
          "[render][bake]") {
    WallScene w;
    SceneDesc d = w.desc();
    BakeSettings s;
    s.quantities = Quantity::ao | Quantity::bent | Quantity::visibility | Quantity::transfer |
                   Quantity::irradiance | Quantity::transfer_matrix;
    s.rays = 32;
    s.bounces = 1;
    s.seed = 9;
    s.adaptive[Quantity::ao] = 0.03;
    s.adaptive[Quantity::irradiance] = 0.15;
    s.adaptive[Quantity::bent] = 0.1;
    s.adaptive.max_rays = 32 * 64;
    auto pts = WallScene::points(20, 500);
    WallScene::add_open_points(pts, 4, 900);  // converged after one batch
    std::vector<PointResult> r1, r2;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        r1 = Baker(d, s).bake(pts);
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        r2 = Baker(d, s).bake(pts);
    }
    // Shards: two bakers over halves, concatenated.
    std::vector<PointResult> r3 = Baker(d, s).bake({pts.begin(), pts.begin() + 10});
    const auto tail = Baker(d, s).bake({pts.begin() + 10, pts.end()});
    r3.insert(r3.end(), tail.begin(), tail.end());
    bool varied = false;
    for (std::size_t i = 0; i < pts.size(); ++i) {
        varied = varied || r1[i].batches != r1[0].batches;
        for (const auto* r : {&r2[i], &r3[i]}) {
            CHECK(r->batches == r1[i].batches);
            CHECK(r->rays == r1[i].rays);
            CHECK(r->ao == r1[i].ao);
            CHECK(r->ao_stderr == r1[i].ao_stderr);
            CHECK(r->bent.y == r1[i].bent.y);
            CHECK(r->bent_stderr == r1[i].bent_stderr);
            CHECK(r->visibility == r1[i].visibility);
            CHECK(r->transfer[1] == r1[i].transfer[1]);
            CHECK(r->irradiance[0] == r1[i].irradiance[0]);
            CHECK(r->irradiance_stderr == r1[i].irradiance_stderr);
            CHECK(r->transfer_matrix[2] == r1[i].transfer_matrix[2]);
        }
        INFO("point " << i << ": ao " << point_error(r1[i], Quantity::ao) << ", bent "
                      << point_error(r1[i], Quantity::bent) << ", irradiance "
                      << point_error(r1[i], Quantity::irradiance));
        CHECK(meets_targets(s, r1[i]));
    }
    CHECK(varied);  // the points did not all take the same number of batches
}

TEST_CASE("render::Baker adaptive: the summary counts rays and estimates the fixed count",
          "[render][bake]") {
    WallScene w;
    const BakeSettings s = ao_settings(64, 0, 0.02, 20);
    // Points beside the wall and points above everything, facing open sky.
    auto pts = WallScene::points(8);
    WallScene::add_open_points(pts, 8, 100);
    Baker b(w.desc(), s);
    const auto r = b.bake(pts);
    AdaptiveSummary sum;
    for (const auto& x : r) sum.add(s, x);
    CHECK(sum.points == 16);
    CHECK(sum.rays == b.rays_traced());
    CHECK(sum.unconverged == 0);
    for (std::size_t i = 8; i < 16; ++i) CHECK(r[i].batches == 1);
    const double worst = sum.worst[quantity_index(Quantity::ao)];
    CHECK(worst <= 0.02);
    // The fixed count: the worst point's n e^2 / E^2, at least its own ray count.
    double R = 0;
    for (const auto& x : r)
        R = std::max(R, double(x.batches) * 64 * x.ao_stderr * x.ao_stderr / (worst * worst));
    CHECK(sum.fixed_rays(s) == Approx(R));
    CHECK(sum.fixed_total(s) > double(sum.rays));  // the open points saved rays
    // Merging two halves gives the same summary.
    AdaptiveSummary a, c;
    for (std::size_t i = 0; i < 16; ++i) (i % 2 ? a : c).add(s, r[i]);
    a.merge(c);
    CHECK(a.rays == sum.rays);
    CHECK(a.fixed_total(s) == Approx(sum.fixed_total(s)));
}

TEST_CASE("render::Baker adaptive: bad settings", "[render][bake]") {
    WallScene w;
    BakeSettings s = ao_settings(64, 0, 0.01, 1);
    s.adaptive.max_rays = 32;
    CHECK_THROWS_WITH(Baker(w.desc(), s), Catch::Contains("adaptive.max_rays"));
    s.adaptive.max_rays = 0;
    CHECK_THROWS_WITH(Baker(w.desc(), s), Catch::Contains("adaptive.max_rays"));
    s.adaptive.max_rays = 640;
    s.adaptive[Quantity::irradiance] = 0.1;
    CHECK_THROWS_WITH(Baker(w.desc(), s), Catch::Contains("only for requested quantities"));
    s.adaptive[Quantity::irradiance] = 0;
    s.adaptive[Quantity::ao] = -1;
    CHECK_THROWS_WITH(Baker(w.desc(), s), Catch::Contains("finite, >= 0"));
    s.adaptive[Quantity::ao] = 0;
    CHECK_THROWS_WITH(Baker(w.desc(), s), Catch::Contains("a target > 0"));
}
