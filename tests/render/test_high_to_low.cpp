// High- to low-poly bakes (render/high_to_low.hpp): a flat low-poly quad over analytic surfaces.
// The normal map against the analytic normals of a height field, directly and through the
// renderer's decoding of the map on the low-poly mesh (Scene::normal_mapped); ambient occlusion
// in a hemispherical pit against its closed form; misses flagged where the quad overhangs the
// source; the cage and the maximum ray distance.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <random>
#include <vector>

#include "sphbasis/core/constants.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/bake_points.hpp"
#include "sphbasis/render/high_to_low.hpp"
#include "sphbasis/render/lightmap.hpp"
#include "sphbasis/render/scene.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;
using namespace sphbasis::render::detail::rt;

namespace {

using V = vec3<double>;

double angle_deg(const V& a, const V& b) {
    const double c = dot(a, b) / std::sqrt(dot(a, a) * dot(b, b));
    return std::acos(std::min(1.0, std::max(-1.0, c))) * 180 / constants::pi;
}

// h(x, y) = a sin(pi x) sin(pi y) over [-1, 1]^2: slopes up to a pi (25 degrees for a = 0.15).
constexpr double bump_a = 0.15;
double bump_h(double x, double y) {
    return bump_a * std::sin(constants::pi * x) * std::sin(constants::pi * y);
}
V bump_n(double x, double y) {
    const double k = bump_a * constants::pi;
    const double hx = k * std::cos(constants::pi * x) * std::sin(constants::pi * y);
    const double hy = k * std::sin(constants::pi * x) * std::cos(constants::pi * y);
    const double l = std::sqrt(hx * hx + hy * hy + 1);
    return {-hx / l, -hy / l, 1 / l};
}

/// The height field tessellated as an n x n grid over [-1, 1]^2 with the analytic normals.
Mesh height_field(int n) {
    Mesh m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
            const V nn = bump_n(x, y);
            m.positions.insert(m.positions.end(), {float(x), float(y), float(bump_h(x, y))});
            m.normals.insert(m.normals.end(), {float(nn.x), float(nn.y), float(nn.z)});
        }
    const std::uint32_t row = std::uint32_t(n + 1);
    for (std::uint32_t j = 0; j < std::uint32_t(n); ++j)
        for (std::uint32_t i = 0; i < std::uint32_t(n); ++i) {
            const std::uint32_t a = j * row + i;
            m.indices.insert(m.indices.end(), {a, a + 1, a + row + 1, a, a + row + 1, a + row});
        }
    return m;
}

/// A plane z = 0 of radius `outer` around the origin with a hemispherical pit of radius R
/// (centre at the origin, bottom at z = -R), as polar grids sharing the rim's positions (a hard
/// edge: the pit's normals point to the centre, the plane's up).
Mesh pitted_disk(double R, double outer, int segments, int pit_rings, int plane_rings) {
    Mesh m;
    auto vertex = [&](const V& p, const V& n) {
        m.positions.insert(m.positions.end(), {float(p.x), float(p.y), float(p.z)});
        m.normals.insert(m.normals.end(), {float(n.x), float(n.y), float(n.z)});
        return std::uint32_t(m.vertex_count() - 1);
    };
    const std::uint32_t S = std::uint32_t(segments);
    // Rings of S vertices; ring_of(k) gives the first vertex of ring k.
    std::vector<std::uint32_t> first;
    const std::uint32_t bottom = vertex({0, 0, -R}, {0, 0, 1});
    for (int k = 1; k <= pit_rings; ++k) {
        const double th = constants::pi / 2 * k / pit_rings;
        first.push_back(std::uint32_t(m.vertex_count()));
        for (std::uint32_t s = 0; s < S; ++s) {
            const double ph = 2 * constants::pi * s / S;
            const V p{R * std::sin(th) * std::cos(ph), R * std::sin(th) * std::sin(ph),
                      -R * std::cos(th)};
            vertex(p, V{-p.x / R, -p.y / R, -p.z / R});
        }
    }
    const std::size_t rim_plane = first.size();
    for (int k = 0; k <= plane_rings; ++k) {
        const double r = R + (outer - R) * k / plane_rings;
        first.push_back(std::uint32_t(m.vertex_count()));
        for (std::uint32_t s = 0; s < S; ++s) {
            const double ph = 2 * constants::pi * s / S;
            vertex({r * std::cos(ph), r * std::sin(ph), 0}, {0, 0, 1});
        }
    }
    auto strip = [&](std::uint32_t a, std::uint32_t b) {
        for (std::uint32_t s = 0; s < S; ++s) {
            const std::uint32_t s1 = (s + 1) % S;
            m.indices.insert(m.indices.end(), {a + s, b + s, b + s1, a + s, b + s1, a + s1});
        }
    };
    for (std::uint32_t s = 0; s < S; ++s)
        m.indices.insert(m.indices.end(), {bottom, first[0] + s, first[0] + (s + 1) % S});
    for (std::size_t k = 0; k + 1 < rim_plane; ++k) strip(first[k], first[k + 1]);
    for (std::size_t k = rim_plane; k + 1 < first.size(); ++k) strip(first[k], first[k + 1]);
    return m;
}

/// The world normal of a tangent-space normal in the frame of a target point.
V world_normal(const BakePoint& p, const V& ts) {
    const V n = p.n * (1 / std::sqrt(dot(p.n, p.n)));
    V t = p.tangent;
    if (dot(t, t) == 0) t = Frame<double>(n).s;
    const V b = cross(n, t) * p.bitangent_sign;
    return {t.x * ts.x + b.x * ts.y + n.x * ts.z, t.y * ts.x + b.y * ts.y + n.y * ts.z,
            t.z * ts.x + b.z * ts.y + n.z * ts.z};
}

}  // namespace

TEST_CASE("high to low: the normal map reproduces the height field's normals",
          "[render][high_to_low]") {
    // Variants of the low-poly frame: mesh tangents along +y (the quad's u axis is +y), no
    // tangents (the triangles' dp/du), and no tangents with mirrored UVs (bitangent sign -1).
    const int variant = GENERATE(0, 1, 2);
    CAPTURE(variant);
    Mesh low = shapes::quad({0, 0, 0}, {0, 1, 0}, {-1, 0, 0}, 1);
    if (variant >= 1) low.tangents.clear();
    if (variant == 2)
        for (std::size_t v = 0; v < low.vertex_count(); ++v) low.uvs[2 * v] = 1 - low.uvs[2 * v];
    const Mesh high = height_field(192);
    const std::vector<MeshView> meshes = {low.view(), high.view()};
    HighToLowSettings hs;
    hs.target = 0;
    hs.source = 1;
    const int res = 64;
    const LightmapLayout layout = texel_layout(meshes, 0, res);
    REQUIRE(layout.samples.size() == std::size_t(res * res));
    SourceProjector proj(meshes, hs);
    const std::vector<ProjectedPoint> pp = proj.project(low_poly_texel_points(meshes, hs, layout));
    REQUIRE(pp.size() == layout.samples.size());
    CHECK(proj.rays() == 2 * pp.size());

    // Per texel: every ray hits (the quad is over the source), the hit lies on the vertical of
    // the texel's surface point, and the tangent-space normal is the analytic normal there.
    double worst = 0;
    std::vector<float> img(std::size_t(res * res * 3), 0.5f);
    for (std::size_t i = 0; i < pp.size(); ++i) {
        const LightmapSample& s = layout.samples[i];
        const ProjectedPoint& p = pp[i];
        REQUIRE(p.hit);
        CHECK(p.point.p.x == Approx(s.surface.x).margin(1e-6));
        CHECK(p.point.p.y == Approx(s.surface.y).margin(1e-6));
        CHECK(p.height == Approx(bump_h(s.surface.x, s.surface.y)).margin(2e-4));
        CHECK(p.point.id == s.point.id);
        const V an = bump_n(p.point.p.x, p.point.p.y);
        worst = std::max(worst, angle_deg(world_normal(s.point, p.normal), an));
        CHECK(std::fabs(dot(p.normal, p.normal) - 1) < 1e-12);
        float* px = img.data() + 3 * std::size_t(s.y * res + s.x);
        px[0] = float((p.normal.x + 1) / 2);
        px[1] = float((p.normal.y + 1) / 2);
        px[2] = float((p.normal.z + 1) / 2);
    }
    INFO("worst texel normal error " << worst << " degrees");
    CHECK(worst < 1.0);
    // The frame matters: the map read in a frame turned by 90 degrees is off by far more.
    if (variant == 0) {
        double swapped = 0;
        for (std::size_t i = 0; i < pp.size(); ++i) {
            const ProjectedPoint& p = pp[i];
            const V turned{p.normal.y, -p.normal.x, p.normal.z};
            swapped = std::max(swapped, angle_deg(world_normal(layout.samples[i].point, turned),
                                                  bump_n(p.point.p.x, p.point.p.y)));
        }
        CHECK(swapped > 20);
    }

    // Through the renderer: the map on the low-poly quad, decoded in the frame of its hits,
    // gives the source's normals at texel centres and between them (bilinear).
    low.normal_map = TextureView{img.data(), res, res, 3};
    const Scene lows({low.view()});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> U(-1 + 2.0 / res, 1 - 2.0 / res);
    double worst_render = 0;
    for (int k = 0; k < 2000; ++k) {
        const double x = U(rng), y = U(rng);
        const Hit h = lows.intersect({x, y, 1}, {0, 0, -1});
        REQUIRE(h.valid);
        worst_render = std::max(worst_render, angle_deg(Scene::normal_mapped(h), bump_n(x, y)));
    }
    INFO("worst rendered normal error " << worst_render << " degrees");
    CHECK(worst_render < 1.0);
}

TEST_CASE("high to low: vertices, the cage and the maximum ray distance", "[render][high_to_low]") {
    const Mesh low = shapes::quad({0, 0, 0}, {0.97, 0, 0}, {0, 0.97, 0}, 16);
    const Mesh high = height_field(160);
    const std::vector<MeshView> meshes = {low.view(), high.view()};
    HighToLowSettings hs;
    hs.target = 0;
    hs.source = 1;
    SourceProjector plain(meshes, hs);
    const std::vector<LowPolyPoint> lp = low_poly_vertex_points(meshes, hs);
    const std::vector<ProjectedPoint> a = plain.project(lp);
    REQUIRE(a.size() == low.vertex_count());
    for (std::size_t v = 0; v < a.size(); ++v) {
        REQUIRE(a[v].hit);
        CHECK(angle_deg(world_normal(lp[v].point, a[v].normal),
                        bump_n(lp[v].surface.x, lp[v].surface.y)) < 1.0);
    }

    // A cage 0.5 above the quad: its rays go straight down and meet the same points.
    std::vector<float> cage = low.positions;
    for (std::size_t v = 0; v < low.vertex_count(); ++v) cage[3 * v + 2] += 0.5f;
    HighToLowSettings hc = hs;
    hc.cage_positions = cage.data();
    SourceProjector caged(meshes, hc);
    const std::vector<ProjectedPoint> b = caged.project(low_poly_vertex_points(meshes, hc));
    CHECK(caged.rays() == b.size());
    for (std::size_t v = 0; v < b.size(); ++v) {
        REQUIRE(b[v].hit);
        CHECK(b[v].point.p.z == Approx(a[v].point.p.z).margin(1e-6));
        CHECK(angle_deg(b[v].normal, a[v].normal) < 1e-3);
    }
    // The cage's rays stop after max_ray_distance: 0.4 reaches down to z = 0.1 only.
    hc.max_ray_distance = 0.4;
    SourceProjector short_cage(meshes, hc);
    std::size_t short_hits = 0;
    for (const ProjectedPoint& p : short_cage.project(low_poly_vertex_points(meshes, hc))) {
        CHECK(p.hit == (p.point.p.z >= 0.1 - 1e-5));
        short_hits += p.hit ? 1 : 0;
    }
    CHECK(short_hits > 4);
    CHECK(short_hits < b.size() / 4);

    // Without a cage, |t| <= 0.05 on both sides: a miss exactly where |h| > 0.05.
    HighToLowSettings hd = hs;
    hd.max_ray_distance = 0.05;
    SourceProjector near(meshes, hd);
    const std::vector<ProjectedPoint> c = near.project(lp);
    std::size_t misses = 0;
    for (std::size_t v = 0; v < c.size(); ++v) {
        const double h = bump_h(lp[v].surface.x, lp[v].surface.y);
        if (std::fabs(std::fabs(h) - 0.05) < 1e-3) continue;
        CHECK(c[v].hit == (std::fabs(h) <= 0.05));
        if (!c[v].hit) {
            ++misses;
            CHECK(c[v].normal.z == 1.0);
            CHECK(c[v].point.p.z == lp[v].point.p.z);  // baked at the low-poly point
        }
    }
    CHECK(misses > 20);

    // Bad settings.
    HighToLowSettings bad = hs;
    bad.source = 0;
    CHECK_THROWS_WITH(SourceProjector(meshes, bad),
                      Catch::Contains("a target and a source that are different meshes"));
    bad = hs;
    bad.max_ray_distance = 0;
    CHECK_THROWS_WITH(low_poly_vertex_points(meshes, bad), Catch::Contains("max_ray_distance > 0"));
}

TEST_CASE("high to low: ambient occlusion in a hemispherical pit is 1/2, misses flagged",
          "[render][high_to_low]") {
    // Every point inside a hemispherical pit sees the sky through the opening, which from a
    // point on the sphere has the cosine-weighted form factor of the missing upper cap: its
    // area over the sphere's, 1/2 (the form factor of a sphere's interior to a patch of it is
    // the patch's area fraction; Siegel and Howell, "Thermal Radiation Heat Transfer"). The flat
    // part sees the whole sky (1). The quad (half size 1.3) overhangs the disk (radius 1.2): its
    // corners miss. The quad is 0.1 above the plane and would occlude everything below it: the
    // bake must leave it out.
    const double R = 0.6, outer = 1.2;
    const Mesh low = shapes::quad({0, 0, 0.1}, {1.3, 0, 0}, {0, 1.3, 0}, 1);
    const Mesh high = pitted_disk(R, outer, 128, 32, 8);
    const std::vector<MeshView> meshes = {low.view(), high.view()};
    HighToLowSettings hs;
    hs.target = 0;
    hs.source = 1;
    const int res = 40;
    const LightmapLayout layout = texel_layout(meshes, 0, res);
    SourceProjector proj(meshes, hs);
    const std::vector<ProjectedPoint> pp = proj.project(low_poly_texel_points(meshes, hs, layout));

    SceneDesc scene;
    scene.meshes = meshes;
    BakeSettings bs;
    bs.quantities = Quantity::ao | Quantity::transfer;
    bs.bands = 1;
    bs.rays = 1024;
    Baker baker(high_to_low_occluders(scene, {0}), bs);
    const std::vector<PointResult> r = baker.bake(bake_points_of(pp));
    REQUIRE(r.size() == pp.size());

    double pit_sum = 0, pit_worst = 0;
    std::size_t pit = 0, flat = 0, missed = 0;
    for (std::size_t i = 0; i < pp.size(); ++i) {
        const V& s = layout.samples[i].surface;
        const double rr = std::sqrt(s.x * s.x + s.y * s.y);
        // Texels on the disk's or the pit's edge (within two texels) are left out.
        const double edge = 2 * 2.6 / res;
        if (std::fabs(rr - outer) < edge || std::fabs(rr - R) < edge) continue;
        INFO("texel at (" << s.x << ", " << s.y << ")");
        CHECK(pp[i].hit == (rr < outer));
        if (!pp[i].hit) {
            ++missed;
            continue;
        }
        // transfer_0 is the mean of V y_00 over the same cosine samples: ao y_00.
        CHECK(r[i].transfer[0][0] == Approx(r[i].ao * 0.28209479177387814).epsilon(1e-12));
        if (rr < R) {
            ++pit;
            pit_sum += r[i].ao;
            pit_worst = std::max(pit_worst, std::fabs(r[i].ao - 0.5));
            CHECK(std::fabs(r[i].ao - 0.5) < 4 * r[i].ao_stderr + 0.02);
            // The normal map holds the pit's normal (to the centre).
            const V c = pp[i].point.p * (-1 / R);
            CHECK(angle_deg(world_normal(layout.samples[i].point, pp[i].normal), c) < 1.0);
        } else {
            ++flat;
            CHECK(r[i].ao == 1.0);
            CHECK(pp[i].normal.z == Approx(1.0).epsilon(1e-9));
        }
    }
    INFO("pit texels " << pit << ", mean ao " << pit_sum / double(pit) << ", worst |ao - 1/2| "
                       << pit_worst);
    REQUIRE(pit > 100);
    CHECK(flat > 200);
    CHECK(missed > 50);
    CHECK(pit_sum / double(pit) == Approx(0.5).margin(0.005));

    // With the quad left in the occlusion scene it would cover the source: ao near 0.
    bs.quantities = Quantity::ao;
    bs.rays = 64;
    Baker wrong(scene, bs);
    const std::vector<PointResult> rw = wrong.bake(bake_points_of(pp));
    double covered_ao = 0;
    std::size_t covered = 0;
    for (std::size_t i = 0; i < pp.size(); ++i)
        if (pp[i].hit) {
            covered_ao += rw[i].ao;
            ++covered;
        }
    CHECK(covered_ao / double(covered) < 0.2);
}
