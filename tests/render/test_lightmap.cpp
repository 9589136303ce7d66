// Tests for render/lightmap.hpp: conservative UV rasterisation, sample placement on the surface,
// errors, and gutter dilation. Meshes are built inline.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <set>
#include <sphbasis/render/lightmap.hpp>
#include <utility>
#include <vector>

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

// A mesh whose UVs are given in pixel coordinates (X right, Y down) of a W x H lightmap, with
// positions z = 0, (x, y) = (u, v): the map pixel -> UV -> position is affine.
Mesh mesh_from_pixels(const std::vector<std::array<double, 2>>& px, int w, int h,
                      const std::vector<std::uint32_t>& indices) {
    Mesh m;
    for (const auto& p : px) {
        const double u = p[0] / w, v = 1 - p[1] / h;
        m.uvs.push_back(float(u));
        m.uvs.push_back(float(v));
        m.positions.insert(m.positions.end(), {float(u), float(v), 0.0f});
    }
    m.indices = indices;
    return m;
}

// Independent coverage test by separating axes: the interiors of two convex polygons are
// disjoint iff their projections on some edge normal of either polygon overlap with zero length.
bool overlaps_with_area(const std::array<std::array<double, 2>, 3>& tri, int x, int y) {
    const std::array<std::array<double, 2>, 4> sq{
        {{double(x), double(y)}, {x + 1.0, double(y)}, {x + 1.0, y + 1.0}, {double(x), y + 1.0}}};
    std::vector<std::array<double, 2>> axes{{1, 0}, {0, 1}};
    for (int i = 0; i < 3; ++i) {
        const auto& a = tri[static_cast<std::size_t>(i)];
        const auto& b = tri[static_cast<std::size_t>((i + 1) % 3)];
        axes.push_back({-(b[1] - a[1]), b[0] - a[0]});
    }
    for (const auto& ax : axes) {
        double t0 = 1e300, t1 = -1e300, s0 = 1e300, s1 = -1e300;
        for (const auto& p : tri) {
            const double d = p[0] * ax[0] + p[1] * ax[1];
            t0 = std::min(t0, d), t1 = std::max(t1, d);
        }
        for (const auto& p : sq) {
            const double d = p[0] * ax[0] + p[1] * ax[1];
            s0 = std::min(s0, d), s1 = std::max(s1, d);
        }
        if (std::min(t1, s1) - std::max(t0, s0) <= 0) return false;
    }
    return true;
}

// Barycentrics of p in triangle (a, b, c) by Cramer's rule (may be negative outside).
std::array<double, 3> barycentric(const std::array<double, 2>& p, const std::array<double, 2>& a,
                                  const std::array<double, 2>& b, const std::array<double, 2>& c) {
    const double d = (b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]);
    const double l1 = ((p[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (p[1] - a[1])) / d;
    const double l2 = ((b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1])) / d;
    return {1 - l1 - l2, l1, l2};
}

}  // namespace

TEST_CASE("lightmap: a full-square quad covers every texel exactly once", "[render][lightmap]") {
    const int w = 7, h = 5;
    const Mesh m = mesh_from_pixels({{0, 0}, {7, 0}, {7, 5}, {0, 5}}, w, h, {0, 3, 2, 0, 2, 1});
    const LightmapLayout l = layout_lightmap(m.view(), w, h, 1000);
    REQUIRE(l.width == w);
    REQUIRE(l.height == h);
    REQUIRE(l.samples.size() == std::size_t(w * h));
    REQUIRE(l.skipped_triangles == 0);
    for (auto c : l.covered) REQUIRE(c == 1);
    std::set<std::pair<int, int>> seen;
    for (std::size_t i = 0; i < l.samples.size(); ++i) {
        const auto& s = l.samples[i];
        // Row-major order and ids.
        REQUIRE(s.y * w + s.x == int(i));
        REQUIRE(s.point.id == 1000 + std::uint64_t(i));
        REQUIRE(seen.insert({s.x, s.y}).second);
        // The texel centre lies inside the quad: the sample is at the centre.
        CHECK(s.surface.x == Approx((s.x + 0.5) / w).margin(1e-6));
        CHECK(s.surface.y == Approx(1 - (s.y + 0.5) / h).margin(1e-6));
        CHECK(s.point.n.z == 1.0);  // geometric normal of the counter-clockwise quad
    }
}

TEST_CASE("lightmap: conservative coverage counts of known triangles", "[render][lightmap]") {
    // Right triangle with legs of 4 texels from a texel corner: texels with x + y <= 3 overlap
    // its interior (10), those with x + y = 4 only touch the hypotenuse at a corner (not covered).
    // Centre sampling would cover 6 to 10 depending on ties; conservative coverage gives 10.
    {
        const Mesh m = mesh_from_pixels({{0, 0}, {4, 0}, {0, 4}}, 8, 8, {0, 1, 2});
        const LightmapLayout l = layout_lightmap(m.view(), 8, 8);
        REQUIRE(l.samples.size() == 10);
        for (const auto& s : l.samples) CHECK(s.x + s.y <= 3);
    }
    // A generic triangle: the covered set equals the separating-axis test's.
    {
        const std::array<std::array<double, 2>, 3> tri{{{0.3, 0.2}, {5.7, 1.1}, {2.2, 4.9}}};
        const Mesh m = mesh_from_pixels({tri[0], tri[1], tri[2]}, 8, 6, {0, 1, 2});
        // Compare against the float UVs actually stored (the pixel positions round-trip).
        std::array<std::array<double, 2>, 3> stored;
        for (int k = 0; k < 3; ++k)
            stored[static_cast<std::size_t>(k)] = {double(m.uvs[2 * std::size_t(k)]) * 8,
                                                   (1 - double(m.uvs[2 * std::size_t(k) + 1])) * 6};
        const LightmapLayout l = layout_lightmap(m.view(), 8, 6);
        std::size_t expected = 0;
        for (int y = 0; y < 6; ++y)
            for (int x = 0; x < 8; ++x) {
                const bool cov = overlaps_with_area(stored, x, y);
                expected += cov ? 1 : 0;
                CHECK(int(l.covered[std::size_t(y * 8 + x)]) == int(cov));
            }
        CHECK(l.samples.size() == expected);
        CHECK(expected > 20);
    }
}

TEST_CASE("lightmap: a sliver narrower than a texel covers every texel it crosses",
          "[render][lightmap]") {
    const int w = 16, h = 16;
    // Horizontal sliver 0.01 texel high inside row 4, away from the texel centres.
    {
        const Mesh m = mesh_from_pixels({{0.5, 4.2}, {15.5, 4.2}, {15.5, 4.21}}, w, h, {0, 1, 2});
        const LightmapLayout l = layout_lightmap(m.view(), w, h);
        REQUIRE(l.samples.size() == 16);
        for (const auto& s : l.samples) CHECK(s.y == 4);
    }
    // A diagonal sliver 1e-3 texel wide: the texels the centre line passes through.
    {
        const std::array<double, 2> a{1.13, 2.29}, b{14.71, 11.37};
        const double nx = -(b[1] - a[1]), ny = b[0] - a[0];
        const double len = std::hypot(nx, ny);
        const std::array<double, 2> c{b[0] + 1e-3 * nx / len, b[1] + 1e-3 * ny / len};
        const Mesh m = mesh_from_pixels({a, b, c}, w, h, {0, 1, 2});
        const LightmapLayout l = layout_lightmap(m.view(), w, h);
        std::set<std::pair<int, int>> crossed;
        for (int i = 0; i <= 200000; ++i) {
            const double t = i / 200000.0;
            crossed.insert({int(a[0] + t * (b[0] - a[0])), int(a[1] + t * (b[1] - a[1]))});
        }
        std::set<std::pair<int, int>> got;
        for (const auto& s : l.samples) got.insert({s.x, s.y});
        CHECK(got == crossed);
        CHECK(crossed.size() > 20);
    }
}

TEST_CASE("lightmap: overlapping triangles take the largest overlap, ties the lowest index",
          "[render][lightmap]") {
    // Triangles 0 and 1 identical: every overlap ties and goes to triangle 0.
    const Mesh m = mesh_from_pixels({{0, 0}, {4, 0}, {0, 4}}, 8, 8, {0, 1, 2, 0, 1, 2});
    const LightmapLayout l = layout_lightmap(m.view(), 8, 8);
    REQUIRE(l.samples.size() == 10);
    for (const auto& s : l.samples) CHECK(s.triangle == 0);
    // A quad split into two triangles along its diagonal: texels on the diagonal go to the
    // triangle with the larger overlap; off-diagonal texels to the one containing them.
    const Mesh q = mesh_from_pixels({{0, 0}, {4, 0}, {4, 4}, {0, 4}}, 4, 4, {0, 1, 2, 0, 2, 3});
    const LightmapLayout lq = layout_lightmap(q.view(), 4, 4);
    REQUIRE(lq.samples.size() == 16);
    for (const auto& s : lq.samples) {
        // Triangle 0 is (0,0),(4,0),(4,4) in pixels: the texels with x > y.
        if (s.x != s.y) CHECK(s.triangle == (s.x > s.y ? 0u : 1u));
    }
    // A small triangle inside a texel and a large one covering a quarter of it: the large one.
    const Mesh t =
        mesh_from_pixels({{0.1, 0.1}, {0.2, 0.1}, {0.1, 0.2}, {0.5, 0.5}, {1.5, 0.5}, {0.5, 1.5}},
                         2, 2, {0, 1, 2, 3, 4, 5});
    const LightmapLayout lt = layout_lightmap(t.view(), 2, 2);
    REQUIRE(lt.samples.size() == 3);  // texels (0,0), (1,0), (0,1)
    CHECK(lt.samples[0].triangle == 1);
}

TEST_CASE("lightmap: samples lie on the triangle and interpolate attributes linearly",
          "[render][lightmap]") {
    const int w = 13, h = 11;
    // One triangle in space with shading normals and tangents, its UV chart inside the image.
    Mesh m;
    m.positions = {0.2f, -0.1f, 0.3f, 1.7f, 0.4f, -0.2f, 0.5f, 1.3f, 0.9f};
    const std::array<std::array<double, 2>, 3> uv{{{0.11, 0.13}, {0.87, 0.31}, {0.36, 0.92}}};
    for (const auto& t : uv) m.uvs.insert(m.uvs.end(), {float(t[0]), float(t[1])});
    m.normals = {0.1f, 0.2f, 1.0f, -0.3f, 0.1f, 0.9f, 0.2f, -0.4f, 0.8f};
    m.tangents = {1, 0, 0, -1, 0.9f, 0.1f, 0, 1, 1, 0.2f, 0.1f, -1};
    m.indices = {0, 1, 2};
    LightmapOptions opt;
    opt.normal_offset = 0.25;
    const LightmapLayout l = layout_lightmap(m.view(), w, h, 0, opt);
    REQUIRE(l.samples.size() > 30);
    std::array<std::array<double, 2>, 3> fuv;
    std::array<vec3<double>, 3> P, N;
    for (std::size_t k = 0; k < 3; ++k) {
        fuv[k] = {double(m.uvs[2 * k]), double(m.uvs[2 * k + 1])};
        P[k] = {m.positions[3 * k], m.positions[3 * k + 1], m.positions[3 * k + 2]};
        N[k] = {m.normals[3 * k], m.normals[3 * k + 1], m.normals[3 * k + 2]};
    }
    const vec3<double> e1{P[1].x - P[0].x, P[1].y - P[0].y, P[1].z - P[0].z};
    const vec3<double> e2{P[2].x - P[0].x, P[2].y - P[0].y, P[2].z - P[0].z};
    const vec3<double> g = cross(e1, e2);
    const double area3 = 0.5 * std::sqrt(dot(g, g));
    const double area_px = 0.5 *
                           std::abs((fuv[1][0] - fuv[0][0]) * (fuv[2][1] - fuv[0][1]) -
                                    (fuv[2][0] - fuv[0][0]) * (fuv[1][1] - fuv[0][1])) *
                           w * h;
    const double texel = std::sqrt(area3 / area_px);
    int inside = 0, clamped = 0;
    for (const auto& s : l.samples) {
        const std::array<double, 2> centre{(s.x + 0.5) / w, 1 - (s.y + 0.5) / h};
        const auto bc = barycentric(centre, fuv[0], fuv[1], fuv[2]);
        // The sample's UV, located independently.
        const auto bs = barycentric({s.u, s.v}, fuv[0], fuv[1], fuv[2]);
        for (std::size_t k = 0; k < 3; ++k) {
            CHECK(bs[k] >= -1e-12);  // on the triangle
            CHECK(bs[k] == Approx(s.barycentric[k]).margin(1e-9));
        }
        if (bc[0] >= 0 && bc[1] >= 0 && bc[2] >= 0) {
            ++inside;
            CHECK(s.u == Approx(centre[0]).margin(1e-12));
            CHECK(s.v == Approx(centre[1]).margin(1e-12));
        } else {
            ++clamped;
            // The closest point: no point of the triangle's edges is nearer the centre.
            const double d = std::hypot(s.u - centre[0], s.v - centre[1]);
            for (std::size_t e = 0; e < 3; ++e)
                for (int i = 0; i <= 200; ++i) {
                    const double t = i / 200.0;
                    const auto& a = fuv[e];
                    const auto& b = fuv[(e + 1) % 3];
                    const double qx = a[0] + t * (b[0] - a[0]), qy = a[1] + t * (b[1] - a[1]);
                    CHECK(d <= std::hypot(qx - centre[0], qy - centre[1]) + 1e-12);
                }
        }
        // Position and normal: the affine interpolation with the independent barycentrics.
        vec3<double> p{0, 0, 0}, n{0, 0, 0};
        for (std::size_t k = 0; k < 3; ++k) {
            p = {p.x + bs[k] * P[k].x, p.y + bs[k] * P[k].y, p.z + bs[k] * P[k].z};
            n = {n.x + bs[k] * N[k].x, n.y + bs[k] * N[k].y, n.z + bs[k] * N[k].z};
        }
        const double nl = std::sqrt(dot(n, n));
        n = {n.x / nl, n.y / nl, n.z / nl};
        CHECK(s.surface.x == Approx(p.x).margin(1e-9));
        CHECK(s.surface.y == Approx(p.y).margin(1e-9));
        CHECK(s.surface.z == Approx(p.z).margin(1e-9));
        CHECK(s.point.n.x == Approx(n.x).margin(1e-9));
        CHECK(s.point.n.y == Approx(n.y).margin(1e-9));
        CHECK(s.point.n.z == Approx(n.z).margin(1e-9));
        // The offset: a quarter of the texel's world-space size along n.
        CHECK(s.offset == Approx(0.25 * texel).epsilon(1e-9));
        CHECK(s.point.p.x == Approx(p.x + s.offset * n.x).margin(1e-9));
        CHECK(s.point.p.y == Approx(p.y + s.offset * n.y).margin(1e-9));
        CHECK(s.point.p.z == Approx(p.z + s.offset * n.z).margin(1e-9));
        // Tangent: unit, orthogonal to n; the handedness of the interpolated w.
        CHECK(dot(s.point.tangent, s.point.tangent) == Approx(1).epsilon(1e-12));
        CHECK(std::abs(dot(s.point.tangent, s.point.n)) < 1e-12);
        const double wsign = -s.barycentric[0] + s.barycentric[1] - s.barycentric[2];
        CHECK(s.bitangent_sign == (wsign < 0 ? -1.0 : 1.0));
        CHECK(s.point.id == std::uint64_t(s.y * w + s.x));
    }
    CHECK(inside > 10);
    CHECK(clamped > 10);  // the chart's edge texels
}

TEST_CASE("lightmap: no normals gives the geometric normal, no tangents a zero tangent",
          "[render][lightmap]") {
    Mesh m;
    m.positions = {0, 0, 0, 0, 2, 0, 0, 0, 3};  // in the x = 0 plane
    m.uvs = {0.1f, 0.1f, 0.9f, 0.1f, 0.1f, 0.9f};
    m.indices = {0, 1, 2};
    LightmapOptions opt;
    opt.normal_offset = 0;
    const LightmapLayout l = layout_lightmap(m.view(), 4, 4, 0, opt);
    REQUIRE(!l.samples.empty());
    for (const auto& s : l.samples) {
        CHECK(s.point.n.x == 1.0);  // (0,2,0) x (0,0,3) = (6,0,0)
        CHECK(s.point.n.y == 0.0);
        CHECK(s.point.n.z == 0.0);
        CHECK(s.point.tangent.x == 0.0);
        CHECK(s.point.tangent.y == 0.0);
        CHECK(s.point.tangent.z == 0.0);
        CHECK(s.point.p.x == 0.0);  // no offset
    }
}

TEST_CASE("lightmap: zero-area UV triangles are skipped and counted", "[render][lightmap]") {
    Mesh m;
    m.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
    // Triangle 1 has collinear UVs (its positions are fine).
    m.uvs = {0.1f, 0.1f, 0.9f, 0.1f, 0.1f, 0.9f, 0.5f, 0.1f};
    m.indices = {0, 1, 2, 0, 3, 1};
    const LightmapLayout l = layout_lightmap(m.view(), 8, 8);
    CHECK(l.skipped_triangles == 1);
    CHECK(l.degenerate_triangles == 0);
    REQUIRE(!l.samples.empty());
    for (const auto& s : l.samples) CHECK(s.triangle == 0);
    // A triangle degenerate in space without normals cannot be given a normal: counted apart.
    Mesh d;
    d.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0};
    d.uvs = {0.1f, 0.1f, 0.9f, 0.1f, 0.1f, 0.9f};
    d.indices = {0, 1, 2};
    const LightmapLayout ld = layout_lightmap(d.view(), 8, 8);
    CHECK(ld.degenerate_triangles == 1);
    CHECK(ld.samples.empty());
}

TEST_CASE("lightmap: bad input throws std::invalid_argument", "[render][lightmap]") {
    Mesh m = mesh_from_pixels({{0, 0}, {4, 0}, {0, 4}}, 8, 8, {0, 1, 2});
    MeshView v = m.view();
    CHECK_NOTHROW(layout_lightmap(v, 1, 1));
    MeshView no_uv = v;
    no_uv.uvs = nullptr;
    CHECK_THROWS_WITH(layout_lightmap(no_uv, 8, 8),
                      Catch::Contains("sphbasis::render::layout_lightmap(): expected a mesh "
                                      "with UVs"));
    CHECK_THROWS_AS(layout_lightmap(v, 0, 8), std::invalid_argument);
    CHECK_THROWS_AS(layout_lightmap(v, 8, 16385), std::invalid_argument);
    CHECK_THROWS_WITH(layout_lightmap(v, 8, -1), Catch::Contains("height"));
    MeshView no_pos = v;
    no_pos.positions = nullptr;
    CHECK_THROWS_AS(layout_lightmap(no_pos, 8, 8), std::invalid_argument);
    MeshView no_idx = v;
    no_idx.indices = nullptr;
    CHECK_THROWS_AS(layout_lightmap(no_idx, 8, 8), std::invalid_argument);
    Mesh bad = m;
    bad.uvs[3] = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH(layout_lightmap(bad.view(), 8, 8), Catch::Contains("finite UVs"));
    bad = m;
    bad.uvs[0] = std::numeric_limits<float>::infinity();
    CHECK_THROWS_AS(layout_lightmap(bad.view(), 8, 8), std::invalid_argument);
    bad = m;
    bad.positions[4] = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_AS(layout_lightmap(bad.view(), 8, 8), std::invalid_argument);
    bad = m;
    bad.indices[2] = 3;
    CHECK_THROWS_WITH(layout_lightmap(bad.view(), 8, 8), Catch::Contains("vertex indices < 3"));
    LightmapOptions opt;
    opt.normal_offset = -1;
    CHECK_THROWS_AS(layout_lightmap(v, 8, 8, 0, opt), std::invalid_argument);
    // UVs outside [0, 1] are fine: the texels outside the image are clipped away.
    Mesh out = mesh_from_pixels({{-3, -3}, {20, -3}, {-3, 20}}, 8, 8, {0, 1, 2});
    const LightmapLayout lo = layout_lightmap(out.view(), 8, 8);
    CHECK(lo.samples.size() == 64);
    // An empty mesh with UVs gives an empty layout.
    MeshView empty;
    const float dummy_uv[2] = {0, 0};
    empty.uvs = dummy_uv;
    CHECK(layout_lightmap(empty, 4, 4).samples.empty());
}

TEST_CASE("lightmap: dilate fills exactly the gutter ring and keeps covered texels",
          "[render][lightmap]") {
    const int w = 16, h = 12, ch = 3;
    std::vector<std::uint8_t> covered(std::size_t(w * h), 0);
    // An L-shaped chart plus an isolated texel.
    for (int y = 4; y < 8; ++y)
        for (int x = 5; x < 8; ++x) covered[std::size_t(y * w + x)] = 1;
    for (int x = 8; x < 10; ++x) covered[std::size_t(7 * w + x)] = 1;
    covered[std::size_t(1 * w + 14)] = 1;
    std::vector<float> img(std::size_t(w * h * ch), -7.0f);
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> uni(0, 1);
    for (std::size_t i = 0; i < covered.size(); ++i)
        if (covered[i] != 0)
            for (int c = 0; c < ch; ++c) img[i * ch + std::size_t(c)] = uni(rng);
    const std::vector<float> before = img;
    // Chebyshev distance of each texel to the covered set, computed by brute force.
    auto dist = [&](int x, int y) {
        int best = 1 << 20;
        for (int yy = 0; yy < h; ++yy)
            for (int xx = 0; xx < w; ++xx)
                if (covered[std::size_t(yy * w + xx)] != 0)
                    best = std::min(best, std::max(std::abs(xx - x), std::abs(yy - y)));
        return best;
    };
    const int gutter = 2;
    dilate(img.data(), w, h, ch, covered, gutter);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const std::size_t i = std::size_t(y * w + x);
            const int d = dist(x, y);
            if (d == 0) {
                REQUIRE(std::memcmp(&img[i * ch], &before[i * ch], sizeof(float) * ch) == 0);
            } else if (d <= gutter) {
                for (int c = 0; c < ch; ++c) {
                    CHECK(img[i * ch + std::size_t(c)] >= 0.0f);
                    CHECK(img[i * ch + std::size_t(c)] <= 1.0f);
                }
            } else {
                for (int c = 0; c < ch; ++c) CHECK(img[i * ch + std::size_t(c)] == -7.0f);
            }
        }
    // The first ring: the average of the covered 8-neighbours, computed independently.
    {
        const int x = 4, y = 4;  // neighbours (5,3)? no: covered ones are (5,4) and (5,5)
        const std::size_t i = std::size_t(y * w + x);
        for (int c = 0; c < ch; ++c) {
            const double a = before[std::size_t(4 * w + 5) * ch + std::size_t(c)];
            const double b = before[std::size_t(5 * w + 5) * ch + std::size_t(c)];
            CHECK(img[i * ch + std::size_t(c)] == Approx((a + b) / 2).epsilon(1e-6));
        }
        // The isolated texel's ring: all 8 neighbours (inside the image) equal it.
        const std::size_t j = std::size_t(2 * w + 15);
        for (int c = 0; c < ch; ++c)
            CHECK(img[j * ch + std::size_t(c)] ==
                  before[std::size_t(w + 14) * ch + std::size_t(c)]);
    }
    // gutter 0 changes nothing; bad arguments throw.
    std::vector<float> img0 = before;
    dilate(img0.data(), w, h, ch, covered, 0);
    CHECK(img0 == before);
    CHECK_THROWS_AS(dilate(img0.data(), w, h, ch, std::vector<std::uint8_t>(5), 1),
                    std::invalid_argument);
    CHECK_THROWS_AS(dilate(img0.data(), w, h, 0, covered, 1), std::invalid_argument);
    CHECK_THROWS_AS(dilate(img0.data(), w, h, ch, covered, -1), std::invalid_argument);
    CHECK_THROWS_AS(dilate(nullptr, w, h, ch, covered, 1), std::invalid_argument);
    CHECK_THROWS_AS(dilate(img0.data(), 0, h, ch, covered, 1), std::invalid_argument);
}

TEST_CASE("lightmap: layout then dilate on a quad chart", "[render][lightmap]") {
    // A chart in the middle of the image: after layout, dilation fills a one-texel ring and the
    // texels outside the ring stay unbaked.
    const Mesh m = mesh_from_pixels({{4.5, 4.5}, {11.5, 4.5}, {11.5, 11.5}, {4.5, 11.5}}, 16, 16,
                                    {0, 3, 2, 0, 2, 1});
    const LightmapLayout l = layout_lightmap(m.view(), 16, 16);
    REQUIRE(l.samples.size() == 64);  // texels 4..11 in x and y
    std::vector<float> img(256, 0.0f);
    for (const auto& s : l.samples) img[std::size_t(s.y * 16 + s.x)] = 1.0f;
    dilate(img.data(), 16, 16, 1, l.covered, 1);
    int filled = 0;
    for (float v : img) filled += v == 1.0f ? 1 : 0;
    CHECK(filled == 100);  // 10 x 10
}
