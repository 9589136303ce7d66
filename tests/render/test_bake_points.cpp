// The bake points (render/bake_points.hpp): the id scheme, normals, the tangent rule against
// render::Scene's hits (the frame a renderer shades with), the lightmap assembly's gutter
// (render/lightmap.hpp), and a Baker borrowing a built Scene giving the building Baker's bits.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/bake_points.hpp"
#include "sphbasis/render/lightmap.hpp"
#include "sphbasis/render/scene.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

/// Two triangles of a tilted square, UVs mirrored in u (u decreases along the first edge), so
/// the bitangent sign of dp/du is -1; normals given, tangents optional.
Mesh mirrored_square(bool tangents) {
    Mesh m;
    const double c = std::cos(0.4), s = std::sin(0.4);
    // Corners (0,0), (1,0), (1,1), (0,1) of the square, rotated by 0.4 rad about x.
    for (const auto& q : {std::array<double, 2>{0, 0}, std::array<double, 2>{1, 0},
                          std::array<double, 2>{1, 1}, std::array<double, 2>{0, 1}}) {
        m.positions.insert(m.positions.end(), {float(q[0]), float(c * q[1]), float(s * q[1])});
        m.normals.insert(m.normals.end(), {0.0f, float(-s), float(c)});
        m.uvs.insert(m.uvs.end(), {float(0.9 - 0.8 * q[0]), float(0.1 + 0.8 * q[1])});
        if (tangents) m.tangents.insert(m.tangents.end(), {-1.0f, 0.3f, 0.2f, -1.0f});
    }
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

}  // namespace

TEST_CASE("bake points: ids follow the documented scheme", "[render][bake]") {
    const Mesh a = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 3);
    const Mesh b = shapes::sphere({0, 0, 2}, 0.5, 4, 8);
    const std::vector<MeshView> meshes = {a.view(), b.view()};
    const std::vector<BakePoint> all = vertex_points(meshes);
    REQUIRE(all.size() == a.vertex_count() + b.vertex_count());
    for (std::size_t i = 0; i < all.size(); ++i) CHECK(all[i].id == i);
    const std::vector<BakePoint> second = vertex_points(meshes, 1);
    REQUIRE(second.size() == b.vertex_count());
    CHECK(second.front().id == a.vertex_count());
    CHECK(vertex_id_base(meshes, 1) == a.vertex_count());

    const int res = 8;
    const LightmapLayout lay = texel_layout(meshes, 1, res);
    REQUIRE(!lay.samples.empty());
    for (const LightmapSample& s : lay.samples)
        CHECK(s.point.id == std::uint64_t(res * res + s.y * res + s.x));
    CHECK(texel_id_base(3, 16) == 3u * 256u);

    ProbeGrid g;
    g.lo = {0, 0, 0};
    g.hi = {1, 2, 3};
    g.counts = {2, 3, 4};
    const std::vector<BakePoint> probes = probe_points(g);
    REQUIRE(probes.size() == 24);
    CHECK(probes[g.index(1, 2, 3)].id == g.index(1, 2, 3));
    CHECK(probes[g.index(1, 2, 3)].p.z == Approx(3));
    CHECK(probes[5].n.x == 0.0);

    CHECK_THROWS_AS(vertex_points(meshes, 2), std::invalid_argument);
    CHECK_THROWS_AS(texel_layout(meshes, 2, res), std::invalid_argument);
}

TEST_CASE("bake points: normals are the mesh's, else area-weighted, else +z", "[render][bake]") {
    Mesh m;
    // Two triangles folded along x (areas 1/2 and 1, normals +z and +y) and a lone vertex.
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 2, 5, 5, 5};
    m.indices = {0, 1, 2, 0, 3, 1};
    const std::vector<double> n = vertex_normals(m.view());
    // Vertex 0: cross products (0, 0, 1) and (0, 2, 0): area-weighted sum (0, 2, 1).
    CHECK(n[0] == 0.0);
    CHECK(n[1] == 2.0);
    CHECK(n[2] == 1.0);
    CHECK(n[12] == 0.0);  // vertex 4 is in no triangle
    CHECK(n[13] == 0.0);
    CHECK(n[14] == 1.0);
    const std::vector<BakePoint> p = vertex_points({m.view()}, 0);
    CHECK(p[4].n.z == 1.0);
    CHECK(p[0].tangent.x == 0.0);  // no UVs, no tangents: zero (the Baker's tangent_frame(n))
}

TEST_CASE("bake points: tangents are those of render::Scene's hits at the same point",
          "[render][bake]") {
    for (const bool with_tangents : {false, true}) {
        INFO("mesh tangents: " << with_tangents);
        const Mesh m = mirrored_square(with_tangents);
        const std::vector<MeshView> meshes = {m.view()};
        const Scene scene(meshes);
        const LightmapLayout lay = texel_layout(meshes, 0, 16);
        REQUIRE(lay.samples.size() > 50);
        for (const LightmapSample& s : lay.samples) {
            // Aimed a little inside the sample's triangle: samples clamped onto the square's
            // outer edges would let a ray graze past it.
            const std::uint32_t* tri = m.indices.data() + 3 * s.triangle;
            const auto corner = [&](int k, int d) {
                return double(m.positions[3 * std::size_t(tri[k]) + std::size_t(d)]);
            };
            const vec3<double> c{(corner(0, 0) + corner(1, 0) + corner(2, 0)) / 3,
                                 (corner(0, 1) + corner(1, 1) + corner(2, 1)) / 3,
                                 (corner(0, 2) + corner(1, 2) + corner(2, 2)) / 3};
            const vec3<double> n = s.point.n;
            const vec3<double> q{s.surface.x + 1e-3 * (c.x - s.surface.x),
                                 s.surface.y + 1e-3 * (c.y - s.surface.y),
                                 s.surface.z + 1e-3 * (c.z - s.surface.z)};
            const Hit h = scene.intersect({q.x + 0.5 * n.x, q.y + 0.5 * n.y, q.z + 0.5 * n.z},
                                          {-n.x, -n.y, -n.z});
            REQUIRE(h.valid);
            CHECK(h.primitive == s.triangle);
            CHECK(s.point.tangent.x == Approx(h.tangent.x).margin(1e-5));
            CHECK(s.point.tangent.y == Approx(h.tangent.y).margin(1e-5));
            CHECK(s.point.tangent.z == Approx(h.tangent.z).margin(1e-5));
            CHECK(s.point.bitangent_sign == h.bitangent_sign);
        }
        // Vertices: the square is flat and mapped affinely, so every triangle has one dp/du.
        const std::vector<BakePoint> v = vertex_points(meshes, 0);
        const Hit h = scene.intersect({0.5, 0.2, 1.5}, {0, 0, -1});
        REQUIRE(h.valid);
        for (const BakePoint& p : v) {
            CHECK(p.tangent.x == Approx(h.tangent.x).margin(1e-6));
            CHECK(p.tangent.y == Approx(h.tangent.y).margin(1e-6));
            CHECK(p.tangent.z == Approx(h.tangent.z).margin(1e-6));
            CHECK(p.bitangent_sign == h.bitangent_sign);
            CHECK(p.bitangent_sign == -1.0);  // mirrored UVs (and w = -1)
        }
    }
}

TEST_CASE("lightmap assembly: samples at their texels, a gutter of lightmap_gutter texels",
          "[render][lightmap]") {
    // One small triangle in the middle of a 32 x 32 map; every sample packs (1, 2).
    Mesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    m.uvs = {0.45f, 0.45f, 0.55f, 0.45f, 0.45f, 0.55f};
    m.indices = {0, 1, 2};
    const LightmapLayout lay = layout_lightmap(m.view(), 32, 32);
    REQUIRE(!lay.samples.empty());
    const std::vector<float> img = assemble_lightmap(lay, 2, [](std::size_t, float* out) {
        out[0] = 1;
        out[1] = 2;
    });
    REQUIRE(img.size() == 32u * 32u * 2u);
    // Chebyshev distance of each texel to the covered region.
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            int d = 99;
            for (int yy = 0; yy < 32; ++yy)
                for (int xx = 0; xx < 32; ++xx)
                    if (lay.covered[std::size_t(yy * 32 + xx)])
                        d = std::min(d, std::max(std::abs(xx - x), std::abs(yy - y)));
            const float* px = img.data() + 2 * std::size_t(y * 32 + x);
            INFO("texel " << x << ", " << y << " at distance " << d);
            CHECK(px[0] == (d <= lightmap_gutter ? 1.0f : 0.0f));
            CHECK(px[1] == (d <= lightmap_gutter ? 2.0f : 0.0f));
        }
    CHECK_THROWS_AS(assemble_lightmap(lay, 0, [](std::size_t, float*) {}), std::invalid_argument);
}

TEST_CASE("Baker: borrowing a built Scene gives the building Baker's results bit for bit",
          "[render][bake]") {
    const Mesh plane = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4);
    const Mesh ball = shapes::sphere({0, 0, 0.5}, 0.3, 8, 16);
    SceneDesc desc;
    desc.meshes = {plane.view(), ball.view()};
    BakeSettings s;
    s.quantities = Quantity::ao | Quantity::bent | Quantity::irradiance;
    s.rays = 64;
    const std::vector<BakePoint> pts = vertex_points(desc.meshes);
    Baker own(desc, s);
    const std::vector<PointResult> a = own.bake(pts);
    const Scene built(desc.meshes);
    Baker borrowing(built, desc, s);
    CHECK(&borrowing.scene() == &built);
    CHECK(borrowing.plan().front().reason.rfind("borrowed ", 0) == 0);
    const std::vector<PointResult> b = borrowing.bake(pts);
    REQUIRE(a.size() == b.size());
    for (std::size_t i = 0; i < a.size(); ++i) {
        CHECK(a[i].ao == b[i].ao);
        CHECK(a[i].bent.x == b[i].bent.x);
        CHECK(a[i].irradiance[1] == b[i].irradiance[1]);
    }
    SceneDesc one = desc;
    one.meshes.pop_back();
    CHECK_THROWS_AS(Baker(built, one, s), std::invalid_argument);
}
