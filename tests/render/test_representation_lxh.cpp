// Tests of the lxh-* representations of render/representation.hpp (precomputed SH visibility
// shaded through L x H tables, uncompressed and PCA-compressed): the bake plan, a convex sphere
// against the irradiance of the same lighting, PCA at full rank against the uncompressed
// visibility, the error falling with the number of PCA vectors, and M above the rank. Then
// normal-mapped PRT (prt-normalmap, its SVD forms, prt-ratio) on a convex and a shadowed scene.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/core/clamped_cosine.hpp"
#include "sphbasis/render/representation.hpp"
#include "sphbasis/render/shapes.hpp"

namespace {

using namespace sphbasis;
using render::Camera;
using render::Environment;
using render::Image;
using render::Mesh;

using sphbasis_test::max_abs;
using sphbasis_test::max_abs_diff;
using sphbasis_test::World;

/// A smooth lat-long sky (brighter towards +z, tinted towards +x): low-frequency, so a few SH
/// bands hold most of it.
void smooth_sky(World& w) {
    const int W = 16, H = 8;
    w.env_texels = sphbasis_test::rgb_texels(W, H, [](int x, int y, float* p) {
        const double th = constants::pi * (y + 0.5) / H, ph = 2 * constants::pi * (x + 0.5) / W;
        const double dz = std::cos(th), dx = std::sin(th) * std::cos(ph);
        p[0] = float(0.6 + 0.4 * dz + 0.3 * dx * dx);
        p[1] = float(0.5 + 0.3 * dz);
        p[2] = float(0.4 + 0.2 * dz * dz);
    });
    w.desc.environment = sphbasis_test::latlong_environment(w.env_texels, W, H);
}

World lone_sphere() {
    World w;
    w.meshes.push_back(render::shapes::sphere({0, 0, 0}, 1, 16, 32));
    w.meshes[0].albedo = {0.8f, 0.8f, 0.8f};
    smooth_sky(w);
    w.build();
    return w;
}

World sphere_on_plane() {
    World w = sphbasis_test::sphere_on_plane_meshes();
    smooth_sky(w);
    w.build();
    return w;
}

render::RepresentationSettings small_settings() {
    render::RepresentationSettings s;
    s.rays = 64;
    s.bounces = 0;
    s.lightmap_size = 16;
    s.lxh_table_size = 8;
    return s;
}

/// Root-mean-square difference over pixels where `mask` hits, relative to the RMS of b.
double rel_rms(const Image& a, const Image& b) {
    double d = 0, n = 0;
    for (std::size_t i = 0; i < a.data.size(); ++i) {
        const double x = double(a.data[i]) - double(b.data[i]);
        d += x * x;
        n += double(b.data[i]) * double(b.data[i]);
    }
    return n > 0 ? std::sqrt(d / n) : 0;
}

/// The image of a white-sky irradiance reference: albedo / pi * E_N(n) at each hit's shading
/// normal, E_N the exact irradiance of the lighting's first N SH bands (Funk-Hecke).
Image irradiance_image(const World& w, const Camera& cam, int bands) {
    const std::vector<render::RGB> L = render::project_sh(w.desc.environment, bands);
    std::vector<double> a(static_cast<std::size_t>(bands));
    clamped_cosine_factors(bands, a.data());
    const render::PinholeCamera pc(cam);
    Image img(cam.width, cam.height, 3);
    std::vector<double> y(std::size_t(bands * bands));
    for (int py = 0; py < cam.height; ++py)
        for (int px = 0; px < cam.width; ++px) {
            const auto ray = pc.ray(px + 0.5, py + 0.5);
            const render::Hit h = w.rt->intersect(ray.origin, ray.direction);
            float* p = img.at(px, py);
            if (!h.valid) {
                const render::RGB bg = w.desc.environment.radiance(ray.direction);
                for (std::size_t c = 0; c < 3; ++c) p[c] = float(bg[c]);
                continue;
            }
            const vec3<double> n = render::Scene::normal_mapped(h);
            sh::eval(bands, n.x, n.y, n.z, y.data());
            for (std::size_t c = 0; c < 3; ++c) {
                double e = 0;
                for (int l = 0; l < bands; ++l)
                    for (int m = -l; m <= l; ++m)
                        e += a[std::size_t(l)] * L[std::size_t(sh::index(l, m))][c] *
                             y[std::size_t(sh::index(l, m))];
                p[c] = float(h.albedo[c] * e);
            }
        }
    return img;
}

}  // namespace

TEST_CASE("lxh representations: the plan bakes visibility only for lxh-*, tables only on demand",
          "[render][lxh]") {
    World w = sphere_on_plane();
    render::RepresentationSettings s = small_settings();
    {
        render::Representations r(w.desc, *w.rt, s, {"irradiance-sh9", "ao"});
        r.prepare(nullptr);
        CHECK(r.lxh_tables_built() == 0);
        CHECK(r.compressions_built() == 0);
        for (const auto& q : r.bakes())
            CHECK_FALSE(has(q.settings.quantities, render::Quantity::visibility));
    }
    {
        // unc6 and pca4 read the same 6-band visibility; unc3 its own; one table per bands.
        render::Representations r(w.desc, *w.rt, s, {"lxh-unc3", "lxh-unc6", "lxh-pca4"});
        REQUIRE(r.bakes().size() == 4);
        for (const auto& q : r.bakes()) {
            CHECK(q.settings.quantities == render::Quantity::visibility);
            CHECK(q.where == render::BakeRequest::Where::texel);
            CHECK_FALSE(q.lighting_dependent);
        }
        using V = std::vector<std::size_t>;
        CHECK(r.reads(1) == r.reads(2));
        CHECK(r.reads(0) != r.reads(1));
        CHECK(r.bakes()[r.reads(0)[0]].settings.bands == 3);
        CHECK(r.bakes()[r.reads(1)[0]].settings.bands == 6);
        r.prepare(nullptr);
        CHECK(r.lxh_tables_built() == 2);
        CHECK(r.compressions_built() == 1);
        CHECK(r.stats(0).bytes_per_element == 9 * 4);
        CHECK(r.stats(1).bytes_per_element == 36 * 4);
        CHECK(r.stats(2).bytes_per_element == 4 * 4);
        CHECK(r.stats(2).element == "texel");
        CHECK(r.stats(2).build_seconds > 0);
        CHECK(r.stats(0).build_seconds > 0);
        CHECK(r.compressed_rank(2) == 36);  // Monte Carlo visibility: full rank
        CHECK(r.compressed_rank(0) == 0);
        (void)V{};
    }
    // Names: the listed ones and the lxh-pcaM family; malformed ones are rejected.
    CHECK_NOTHROW(render::Representations(w.desc, *w.rt, s, {"lxh-pca21"}));
    for (const char* bad : {"lxh-pca0", "lxh-pca37", "lxh-pca07", "lxh-unc5", "lxh-pca"})
        CHECK_THROWS_AS(render::Representations(w.desc, *w.rt, s, {bad}), std::invalid_argument);
}

TEST_CASE("lxh representations: a convex sphere converges to the irradiance of the lighting",
          "[render][lxh]") {
    World w = lone_sphere();
    render::RepresentationSettings s = small_settings();
    s.lxh_table_size = 16;
    const std::vector<std::string> names{"lxh-unc3", "lxh-unc4", "lxh-unc6", "lxh-pca21"};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    const Camera cam = sphbasis_test::camera_at({0, -4, 1}, {0, 0, 0}, 24, 24);
    std::vector<double> err;
    for (std::size_t i = 0; i < 3; ++i) {
        const int k = i == 0 ? 3 : (i == 1 ? 4 : 6);
        const Image img = r.render(i, cam, 1);
        err.push_back(rel_rms(img, irradiance_image(w, cam, k)));
        std::printf("lxh convex %s: rel rms %.3g\n", names[i].c_str(), err.back());
    }
    // No self-occlusion: V is the tangent hemisphere, and V . (L x H)(n) misses only the
    // product's bands the K-band visibility cannot hold.
    CHECK(err[2] < err[0]);
    CHECK(err[2] < 0.01);
    // The visibility of a convex sphere is analytic (no rays) and has rank 21 on 6 bands
    // (bands 1, 3, 5 of the hemisphere's projection): 21 PCA vectors reproduce it.
    CHECK(r.compressed_rank(3) == 21);
    const Image unc = r.render(2, cam, 1), pca = r.render(3, cam, 1);
    CHECK(max_abs_diff(unc, pca) < 1e-5 * max_abs(unc));
    // One vector more than the rank: a clear error at prepare().
    render::Representations bad(w.desc, *w.rt, s, {"lxh-pca22"});
    CHECK_THROWS_WITH(bad.prepare(nullptr), Catch::Contains("lxh-pca22") &&
                                                Catch::Contains("rank") && Catch::Contains("21"));
    CHECK_THROWS_AS(bad.prepare(nullptr), std::invalid_argument);
}

TEST_CASE("lxh representations: PCA error falls with the number of vectors", "[render][lxh]") {
    World w = sphere_on_plane();
    render::RepresentationSettings s = small_settings();
    const std::vector<std::string> names{"lxh-unc6",  "lxh-pca4",  "lxh-pca8",
                                         "lxh-pca16", "lxh-pca24", "lxh-pca36"};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    CHECK(r.bakes().size() == 2);
    CHECK(r.lxh_tables_built() == 1);
    const Camera cam = sphbasis_test::camera_at({0, -3, 1.5}, {0, 0, 0.3}, 24, 24);
    const Image unc = r.render(0, cam, 1);
    double prev = 1e9;
    for (std::size_t i = 1; i < names.size(); ++i) {
        const double e = rel_rms(r.render(i, cam, 1), unc);
        std::printf("lxh pca %s: rel rms to unc6 %.3g\n", names[i].c_str(), e);
        CHECK(e <= prev * 1.05 + 1e-6);
        prev = e;
    }
    CHECK(prev < 1e-5);  // 36 vectors: lossless up to float rounding
}

TEST_CASE("prt-normalmap, -svd and -ratio on a convex sphere equal the unshadowed irradiance",
          "[render][prt-normalmap]") {
    World w = lone_sphere();
    render::RepresentationSettings s = small_settings();
    const std::vector<std::string> names{"irradiance-sh9",     "prt-normalmap",      "prt-ratio",
                                         "prt-normalmap-svd4", "prt-normalmap-svd6", "prt-texel"};
    render::Representations r(w.desc, *w.rt, s, names);
    // prt-ratio reads prt-texel's transfer; prt-normalmap and its SVD forms one M bake.
    REQUIRE(r.bakes().size() == 2);
    CHECK(r.reads(2) == r.reads(5));
    CHECK(r.reads(1) == r.reads(3));
    CHECK(r.bakes()[r.reads(1)[0]].settings.quantities == render::Quantity::transfer_matrix);
    r.prepare(nullptr);
    const Camera cam = sphbasis_test::camera_at({0, -4, 1}, {0, 0, 0}, 24, 24);
    const Image irr = r.render(0, cam, 1);
    // No occluder: M = I (the analytic pass), the ratio is 1.
    CHECK(max_abs_diff(r.render(1, cam, 1), irr) < 1e-5 * max_abs(irr));
    // prt-ratio: the interpolated transfer over the irradiance at the interpolated normal, 1 up
    // to the lightmap's bilinear interpolation (16 x 16 texels here).
    CHECK(rel_rms(r.render(2, cam, 1), irr) < 5e-3);
    const double e4 = rel_rms(r.render(3, cam, 1), irr), e6 = rel_rms(r.render(4, cam, 1), irr);
    std::printf("prt-normalmap-svd on a convex sphere: rel rms svd4 %.3g, svd6 %.3g\n", e4, e6);
    CHECK(e6 <= e4);
    CHECK(e6 < 0.02);  // measured 0.013
    CHECK(r.stats(1).bytes_per_element == 27 * 9 * 4);
    CHECK(r.stats(3).bytes_per_element == 3 * 4 * 9 * 4);
    CHECK(r.stats(4).bytes_per_element == 3 * 6 * 9 * 4);
    CHECK(r.stats(2).bytes_per_element == 9 * 4);
    CHECK(r.stats(3).build_seconds > 0);
}

TEST_CASE("prt-normalmap under a shadowing sphere: darker than unshadowed, close to prt-texel",
          "[render][prt-normalmap]") {
    World w = sphere_on_plane();
    render::RepresentationSettings s = small_settings();
    const std::vector<std::string> names{"prt-texel", "prt-normalmap", "prt-ratio",
                                         "prt-normalmap-svd6", "irradiance-sh9"};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    const Camera cam = sphbasis_test::camera_at({0, -3, 1.5}, {0, 0, 0.3}, 24, 24);
    const Image prt = r.render(0, cam, 1), irr = r.render(4, cam, 1);
    for (std::size_t i = 1; i < 4; ++i) {
        const Image img = r.render(i, cam, 1);
        const double e = rel_rms(img, prt), eu = rel_rms(img, irr);
        std::printf("%s: rel rms to prt-texel %.3g, to unshadowed %.3g\n", names[i].c_str(), e, eu);
        // Without a normal map every form reads the shadowed transfer at the surface normal:
        // within the 3-band truncation of the incident light of prt-texel, far from unshadowed.
        CHECK(e < 0.2 * rel_rms(prt, irr));  // measured 0.08-0.09 of it
    }
}

TEST_CASE("prt-cpca: one cluster at full rank equals prt-texel; more clusters and vectors help",
          "[render][cpca]") {
    {
        // A convex sphere's transfer a_l y_lm(n) has rank 8 after centring (bands 1 and 2).
        World w = lone_sphere();
        render::RepresentationSettings s = small_settings();
        render::Representations r(w.desc, *w.rt, s, {"prt-texel", "prt-cpca-1-8"});
        r.prepare(nullptr);
        CHECK(r.bakes().size() == 1);
        const Camera cam = sphbasis_test::camera_at({0, -4, 1}, {0, 0, 0}, 16, 16);
        const Image prt = r.render(0, cam, 1), cp = r.render(1, cam, 1);
        // Nearest-texel weights against bilinear transfer: equal at the texel level only.
        CHECK(rel_rms(cp, prt) < 2e-2);
        CHECK(r.stats(1).bytes_per_element == 8 * 4 + 2);
        render::Representations bad(w.desc, *w.rt, s, {"prt-cpca-1-9"});
        CHECK_THROWS_WITH(bad.prepare(nullptr),
                          Catch::Contains("prt-cpca-1-9") && Catch::Contains("rank"));
        render::Representations many(w.desc, *w.rt, s, {"prt-cpca-4000-1"});
        CHECK_THROWS_WITH(many.prepare(nullptr), Catch::Contains("number of points"));
    }
    World w = sphere_on_plane();
    render::RepresentationSettings s = small_settings();
    const std::vector<std::string> names{"prt-texel", "prt-cpca-1-1", "prt-cpca-8-4"};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    const Camera cam = sphbasis_test::camera_at({0, -3, 1.5}, {0, 0, 0.3}, 24, 24);
    const Image prt = r.render(0, cam, 1);
    const double e1 = rel_rms(r.render(1, cam, 1), prt), e8 = rel_rms(r.render(2, cam, 1), prt);
    std::printf("prt-cpca: rel rms to prt-texel: 1-1 %.3g, 8-4 %.3g\n", e1, e8);
    CHECK(e8 < e1);
    CHECK(r.stats(2).build_seconds > 0);
}
