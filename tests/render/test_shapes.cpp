// Tests for render/shapes.hpp: closed meshes (every edge shared by two opposite half-edges after
// welding positions), area and enclosed volume (divergence theorem) against closed forms,
// outward normals agreeing with the winding, UVs in [0, 1]^2 without overlaps, tangents
// orthogonal to normals with handedness matching the UV derivatives, and bad input.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "sphbasis/render/shapes.hpp"

using sphbasis::vec3;
using sphbasis::render::Mesh;
namespace shapes = sphbasis::render::shapes;
namespace constants = sphbasis::constants;

namespace {

vec3<double> pos(const Mesh& m, std::uint32_t i) {
    return {m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]};
}
vec3<double> nrm(const Mesh& m, std::uint32_t i) {
    return {m.normals[3 * i], m.normals[3 * i + 1], m.normals[3 * i + 2]};
}
vec3<double> sub(const vec3<double>& a, const vec3<double>& b) {
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
double len(const vec3<double>& a) { return std::sqrt(sphbasis::dot(a, a)); }

struct Measures {
    double area = 0, volume = 0;
};

/// Structural checks common to every shape; returns area and signed enclosed volume.
Measures check_mesh(const Mesh& m, bool closed) {
    const std::size_t nv = m.vertex_count(), nt = m.triangle_count();
    REQUIRE(nv > 0);
    REQUIRE(nt > 0);
    REQUIRE(m.normals.size() == 3 * nv);
    REQUIRE(m.uvs.size() == 2 * nv);
    REQUIRE(m.tangents.size() == 4 * nv);
    REQUIRE(m.indices.size() == 3 * nt);
    for (std::uint32_t idx : m.indices) REQUIRE(idx < nv);
    // Used vertices: unit normals, unit tangents orthogonal to them, w = +-1, uv in [0, 1].
    std::vector<char> used(nv, 0);
    for (std::uint32_t idx : m.indices) used[idx] = 1;
    int bad_vertices = 0;
    for (std::uint32_t i = 0; i < nv; ++i) {
        if (!used[i]) continue;
        const vec3<double> n = nrm(m, i);
        const vec3<double> t{m.tangents[4 * i], m.tangents[4 * i + 1], m.tangents[4 * i + 2]};
        const float u = m.uvs[2 * i], v = m.uvs[2 * i + 1];
        const bool ok = std::fabs(len(n) - 1) < 1e-6 && std::fabs(len(t) - 1) < 1e-6 &&
                        std::fabs(sphbasis::dot(n, t)) < 1e-6 &&
                        std::fabs(m.tangents[4 * i + 3]) == 1.0f && u >= 0.0f && u <= 1.0f &&
                        v >= 0.0f && v <= 1.0f;
        bad_vertices += !ok;
    }
    CHECK(bad_vertices == 0);
    Measures r;
    using Key = std::array<float, 3>;
    std::map<Key, int> weld;
    auto id = [&](std::uint32_t i) {
        const Key k{m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2]};
        return weld.emplace(k, static_cast<int>(weld.size())).first->second;
    };
    std::map<std::pair<int, int>, int> half_edges;
    int bad_frames = 0, bad_normals = 0;
    for (std::size_t t = 0; t < nt; ++t) {
        const std::uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1],
                            c = m.indices[3 * t + 2];
        const vec3<double> p0 = pos(m, a), p1 = pos(m, b), p2 = pos(m, c);
        const vec3<double> e1 = sub(p1, p0), e2 = sub(p2, p0);
        const vec3<double> g = sphbasis::cross(e1, e2);
        const double ga = len(g);
        REQUIRE(ga > 0);  // no degenerate triangles
        r.area += 0.5 * ga;
        r.volume += sphbasis::dot(p0, sphbasis::cross(p1, p2)) / 6;
        // Winding agrees with the shading normals (counter-clockwise seen from their side).
        for (std::uint32_t v : {a, b, c})
            if (sphbasis::dot(g, nrm(m, v)) <= 0) ++bad_normals;
        // UV derivatives: dP/du, dP/dv from the triangle's uv map.
        const double du1 = m.uvs[2 * b] - m.uvs[2 * a], dv1 = m.uvs[2 * b + 1] - m.uvs[2 * a + 1];
        const double du2 = m.uvs[2 * c] - m.uvs[2 * a], dv2 = m.uvs[2 * c + 1] - m.uvs[2 * a + 1];
        const double det = du1 * dv2 - du2 * dv1;
        REQUIRE(det != 0);  // no zero-area UV triangle
        const vec3<double> dpdu{(dv2 * e1.x - dv1 * e2.x) / det, (dv2 * e1.y - dv1 * e2.y) / det,
                                (dv2 * e1.z - dv1 * e2.z) / det};
        const vec3<double> dpdv{(du1 * e2.x - du2 * e1.x) / det, (du1 * e2.y - du2 * e1.y) / det,
                                (du1 * e2.z - du2 * e1.z) / det};
        for (std::uint32_t v : {a, b, c}) {
            const vec3<double> n = nrm(m, v);
            const vec3<double> tg{m.tangents[4 * v], m.tangents[4 * v + 1], m.tangents[4 * v + 2]};
            const double w = m.tangents[4 * v + 3];
            const vec3<double> bt = sphbasis::cross(n, tg);
            if (!(sphbasis::dot(tg, dpdu) > 0) || !(w * sphbasis::dot(bt, dpdv) > 0)) ++bad_frames;
        }
        const int ia = id(a), ib = id(b), ic = id(c);
        ++half_edges[{ia, ib}];
        ++half_edges[{ib, ic}];
        ++half_edges[{ic, ia}];
    }
    CHECK(bad_normals == 0);
    CHECK(bad_frames == 0);
    if (closed) {
        // Every edge is shared by exactly two triangles, traversed in opposite directions.
        int open = 0, repeated = 0;
        for (const auto& [e, count] : half_edges) {
            if (count != 1) ++repeated;
            const auto it = half_edges.find({e.second, e.first});
            if (it == half_edges.end() || it->second != 1) ++open;
        }
        CHECK(open == 0);
        CHECK(repeated == 0);
    }
    return r;
}

/// No two UV triangles overlap: a grid of points (offset off the edges) is covered at most once,
/// and the covered fraction matches the sum of the UV triangle areas.
void check_uv_overlap(const Mesh& m, int grid) {
    std::vector<int> cover(static_cast<std::size_t>(grid) * static_cast<std::size_t>(grid), 0);
    double uv_area = 0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        double u[3], v[3];
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = m.indices[3 * t + static_cast<std::size_t>(k)];
            u[k] = m.uvs[2 * i];
            v[k] = m.uvs[2 * i + 1];
        }
        const double area2 = (u[1] - u[0]) * (v[2] - v[0]) - (u[2] - u[0]) * (v[1] - v[0]);
        CHECK(area2 > 0);  // every UV triangle counter-clockwise: no flips
        uv_area += 0.5 * std::fabs(area2);
        const int i0 =
            std::max(0, static_cast<int>(std::floor(*std::min_element(u, u + 3) * grid)));
        const int i1 =
            std::min(grid - 1, static_cast<int>(std::floor(*std::max_element(u, u + 3) * grid)));
        const int j0 =
            std::max(0, static_cast<int>(std::floor(*std::min_element(v, v + 3) * grid)));
        const int j1 =
            std::min(grid - 1, static_cast<int>(std::floor(*std::max_element(v, v + 3) * grid)));
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) {
                const double pu = (i + 0.5123) / grid, pv = (j + 0.4871) / grid;
                double s[3];
                for (int k = 0; k < 3; ++k) {
                    const int k1 = (k + 1) % 3;
                    s[k] = (u[k1] - u[k]) * (pv - v[k]) - (v[k1] - v[k]) * (pu - u[k]);
                }
                if (s[0] >= 0 && s[1] >= 0 && s[2] >= 0)
                    ++cover[static_cast<std::size_t>(j) * static_cast<std::size_t>(grid) +
                            static_cast<std::size_t>(i)];
            }
    }
    int multi = 0, covered = 0;
    for (int c : cover) {
        multi += c > 1;
        covered += c > 0;
    }
    CHECK(multi == 0);
    CHECK(uv_area <= 1.0 + 1e-6);
    CHECK(static_cast<double>(covered) / (grid * grid) == Approx(uv_area).margin(0.03));
}

}  // namespace

TEST_CASE("shapes::box: closed, area, volume, outward normals, atlas", "[render][shapes]") {
    const vec3<double> c{0.5, -1, 2}, h{1, 0.5, 0.25};
    const Mesh m = shapes::box(c, h);
    CHECK(m.vertex_count() == 24);
    CHECK(m.triangle_count() == 12);
    const Measures r = check_mesh(m, true);
    CHECK(r.area == Approx(8 * (h.x * h.y + h.y * h.z + h.x * h.z)).epsilon(1e-6));
    CHECK(r.volume == Approx(8 * h.x * h.y * h.z).epsilon(1e-6));  // > 0: outward orientation
    // Normals point away from the centre; flat shading: a face's normal is its axis.
    for (std::uint32_t i = 0; i < 24; ++i) {
        const vec3<double> d = sub(pos(m, i), c);
        CHECK(sphbasis::dot(d, nrm(m, i)) > 0);
    }
    check_uv_overlap(m, 128);
    // One texel density: UV area / world area is the same for every face.
    double ratio0 = 0;
    for (std::size_t f = 0; f < 6; ++f) {
        const std::uint32_t a = m.indices[6 * f], b = m.indices[6 * f + 1],
                            cc = m.indices[6 * f + 2];
        const double wa =
            len(sphbasis::cross(sub(pos(m, b), pos(m, a)), sub(pos(m, cc), pos(m, a))));
        const double ua =
            std::fabs((m.uvs[2 * b] - m.uvs[2 * a]) * (m.uvs[2 * cc + 1] - m.uvs[2 * a + 1]) -
                      (m.uvs[2 * cc] - m.uvs[2 * a]) * (m.uvs[2 * b + 1] - m.uvs[2 * a + 1]));
        if (f == 0) ratio0 = ua / wa;
        CHECK(ua / wa == Approx(ratio0).epsilon(1e-5));
    }
}

TEST_CASE("shapes::sphere: closed, on the sphere, area and volume converge", "[render][shapes]") {
    const vec3<double> c{1, 2, -3};
    const double r = 0.75;
    const Mesh m = shapes::sphere(c, r, 12, 24);
    CHECK(m.vertex_count() == 13 * 25);
    CHECK(m.triangle_count() == 2 * 12 * 24 - 2 * 24);
    const Measures s = check_mesh(m, true);
    int off_sphere = 0;
    for (std::uint32_t i = 0; i < m.vertex_count(); ++i) {
        const vec3<double> d = sub(pos(m, i), c);
        off_sphere += std::fabs(len(d) - r) > 1e-6 * r ||
                      std::fabs(sphbasis::dot(d, nrm(m, i)) / r - 1) > 1e-6;
    }
    CHECK(off_sphere == 0);
    // An inscribed polyhedron: a little below the sphere's area and volume, O(1/n^2).
    const double A = 4 * constants::pi * r * r, V = 4 * constants::pi * r * r * r / 3;
    CHECK(s.area < A);
    CHECK(s.area > 0.97 * A);
    CHECK(s.volume < V);
    CHECK(s.volume > 0.95 * V);
    // Finer tessellation gets closer.
    const Mesh f = shapes::sphere(c, r, 18, 36);
    const Measures sf = check_mesh(f, true);
    CHECK(std::fabs(sf.volume - V) < 0.55 * std::fabs(s.volume - V));
    check_uv_overlap(m, 96);
    // Minimal tessellation still closed and valid.
    check_mesh(shapes::sphere({0, 0, 0}, 1, 2, 3), true);
}

TEST_CASE("shapes::quad: tessellated rectangle", "[render][shapes]") {
    const vec3<double> c{0, 1, 0}, U{2, 0, 0}, V{0, 0, -1.5};  // normal U x V = +y
    const Mesh m = shapes::quad(c, U, V, 4);
    CHECK(m.vertex_count() == 25);
    CHECK(m.triangle_count() == 32);
    const Measures r = check_mesh(m, false);
    CHECK(r.area == Approx(4 * 2 * 1.5).epsilon(1e-6));
    for (std::uint32_t i = 0; i < 25; ++i) CHECK(nrm(m, i).y == Approx(1));
    // Corners of the UV square at the corners of the rectangle.
    CHECK(m.uvs[0] == 0.0f);
    CHECK(m.uvs[1] == 0.0f);
    CHECK(m.uvs[2 * 24] == 1.0f);
    CHECK(m.uvs[2 * 24 + 1] == 1.0f);
    CHECK(pos(m, 24).x == Approx(2));
    CHECK(pos(m, 24).z == Approx(-1.5));
    check_uv_overlap(m, 64);
    // A parallelogram keeps a valid frame.
    check_mesh(shapes::quad({0, 0, 0}, {1, 0, 0}, {0.5, 1, 0}, 3), false);
}

TEST_CASE("shapes: bad sizes give clear errors", "[render][shapes]") {
    const double nan = std::nan("");
    CHECK_THROWS_WITH(shapes::sphere({0, 0, 0}, 0, 8, 8), Catch::Contains("finite radius > 0"));
    CHECK_THROWS_WITH(shapes::sphere({0, 0, 0}, nan, 8, 8), Catch::Contains("finite radius > 0"));
    CHECK_THROWS_WITH(shapes::sphere({0, 0, 0}, 1, 1, 8), Catch::Contains("2 <= rings"));
    CHECK_THROWS_WITH(shapes::sphere({0, 0, 0}, 1, 8, 2), Catch::Contains("3 <= segments"));
    CHECK_THROWS_WITH(shapes::sphere({nan, 0, 0}, 1, 8, 8), Catch::Contains("finite centre"));
    CHECK_THROWS_WITH(shapes::box({0, 0, 0}, {1, 0, 1}), Catch::Contains("half extents > 0"));
    CHECK_THROWS_WITH(shapes::box({0, 0, 0}, {1, -1, 1}), Catch::Contains("half extents > 0"));
    CHECK_THROWS_WITH(shapes::box({0, 0, 0}, {1, 1, nan}),
                      Catch::StartsWith("sphbasis::render::shapes::box(): expected"));
    CHECK_THROWS_WITH(shapes::quad({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, 2),
                      Catch::Contains("non-parallel axes"));
    CHECK_THROWS_WITH(shapes::quad({0, 0, 0}, {0, 0, 0}, {0, 1, 0}, 2),
                      Catch::Contains("non-parallel axes"));
    CHECK_THROWS_WITH(shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0),
                      Catch::Contains("1 <= subdivisions"));
}
