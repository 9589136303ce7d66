// Normals of meshes read from files (tools/support/mesh_normals.hpp, the scene key
// "smoothing_angle_deg") and two-sided shading (render/scene.hpp, bake.hpp, path_tracer.hpp)
// on meshes as files deliver them: the white furnace (albedo 1 everywhere under a constant unit
// sky: the exit radiance is 1 at every point, whatever the geometry) for an open box read from
// OBJ files with flat normals, without normals, with normals smoothed across its edges and with
// mixed winding (tests/data/scenes/furnace/gen_open_boxes.py writes them), and for models of
// Debian's assimp-testmodels where installed.
//
// The bounds. The bake's exit radiance B = sqrt(4 pi) t_0 is the mean over the point's rays of
// sqrt(4 pi) y_0 (1/(2 sqrt(pi))) = 1 for every path that escapes: with albedo 1 every vertex
// passes on its full weight, so B = 1 up to rounding and to the paths still inside after 24
// bounces. A lost path makes the per-ray terms differ and its share 1/N shows in the reported
// standard error, so |B - 1| <= 5 stderr + 1e-9 per point. The path tracer's pixels (Russian
// roulette: weights 1/q) have a nonzero variance: each pixel within 5 of its own standard errors
// (+1e-6), and the mean over pixels within 4 standard errors of the mean
// (sqrt(sum se^2) / pixels) of 1.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sphbasis/render/path_tracer.hpp>
#include <sphbasis/render/shapes.hpp>
#include <string>
#include <vector>

#include "support/mesh_normals.hpp"
#include "support/scene_file.hpp"

using namespace sphbasis;
using sphbasis::render::Mesh;

#ifndef SPHBASIS_TEST_DATA_DIR
#error "SPHBASIS_TEST_DATA_DIR: the tests/data directory"
#endif

namespace {

const std::string furnace_dir = std::string(SPHBASIS_TEST_DATA_DIR) + "/scenes/furnace/";
const std::vector<std::string> box_variants = {"flat", "nonormals", "smooth", "mixed",
                                               "mixed_nonormals"};

using V3 = vec3<double>;
V3 vertex(const std::vector<float>& a, std::size_t i) {
    return {a[3 * i], a[3 * i + 1], a[3 * i + 2]};
}
double dot3(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 face_normal(const Mesh& m, std::size_t t) {
    const V3 p0 = vertex(m.positions, m.indices[3 * t]),
             p1 = vertex(m.positions, m.indices[3 * t + 1]),
             p2 = vertex(m.positions, m.indices[3 * t + 2]);
    const V3 a{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z}, b{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z};
    const V3 c{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
    const double l = std::sqrt(dot3(c, c));
    return {c.x / l, c.y / l, c.z / l};
}

/// A unit cube [0, 1]^3 as the PLY and OFF files store it: 8 shared vertices, 12 triangles
/// wound outward, no normals.
Mesh shared_cube(bool other_diagonals) {
    Mesh m;
    for (int i = 0; i < 8; ++i)
        m.positions.insert(m.positions.end(), {float(i & 1), float((i >> 1) & 1), float(i >> 2)});
    // Quads (outward counter-clockwise), split along one diagonal or the other.
    const std::uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : q) {
        if (other_diagonals)
            m.indices.insert(m.indices.end(), {f[1], f[2], f[3], f[1], f[3], f[0]});
        else
            m.indices.insert(m.indices.end(), {f[0], f[1], f[2], f[0], f[2], f[3]});
    }
    m.normals.assign(m.positions.size(), 0.0f);
    return m;
}

/// Every corner's normal equals its triangle's (flat), within float rounding.
void require_flat(const Mesh& m) {
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
        const V3 f = face_normal(m, t);
        for (int k = 0; k < 3; ++k)
            REQUIRE(dot3(vertex(m.normals, m.indices[3 * t + std::size_t(k)]), f) > 1 - 1e-6);
    }
}

struct Furnace {
    double worst = 0;  // the largest |B - 1| / (5 se + 1e-9) (a pass: below 1)
    double mean = 0, lowest = 1e300, highest = -1e300;
    std::size_t points = 0;
};

/// Bakes `transfer` (1 band, 24 bounces) at every vertex of every mesh (its normal) of a scene
/// file, as `sphbasis bake --quantities transfer --bounces 24` does.
Furnace bake_furnace(const cli::SceneFile& scene, int rays) {
    std::vector<render::BakePoint> pts;
    for (const cli::SceneMesh& sm : scene.meshes) {
        const Mesh& m = sm.mesh;
        REQUIRE(m.normals.size() == m.positions.size());
        for (std::size_t v = 0; v < m.vertex_count(); ++v) {
            render::BakePoint p;
            p.p = vertex(m.positions, v);
            p.n = vertex(m.normals, v);
            p.id = pts.size();
            pts.push_back(p);
        }
    }
    render::BakeSettings s;
    s.quantities = render::Quantity::transfer;
    s.bands = 1;
    s.rays = rays;
    s.bounces = 24;
    s.seed = 7;
    render::Baker b(scene.scene_desc(), s);
    const auto r = b.bake(pts);
    const double l0 = std::sqrt(4 * constants::pi);
    Furnace f;
    for (const auto& x : r) {
        const double B = x.transfer[0][0] * l0, se = x.transfer_stderr[0] * l0;
        f.worst = std::max(f.worst, std::fabs(B - 1) / (5 * se + 1e-9));
        f.mean += B;
        f.lowest = std::min(f.lowest, B);
        f.highest = std::max(f.highest, B);
    }
    f.points = r.size();
    f.mean /= double(r.size());
    return f;
}

struct PtFurnace {
    double worst = 0;  // the largest |L - 1| / (5 se + 1e-6) over pixels
    double mean = 0, se = 0;
    double covered = 0;  // the fraction of camera rays that hit the mesh
};

/// The path tracer's reference image of the scene's camera, unbounded bounces (its own Russian
/// roulette), a fixed spp.
PtFurnace trace_furnace(const cli::SceneFile& scene, const render::Camera& camera, int spp) {
    const render::SceneDesc d = scene.scene_desc();
    const render::Scene rs(d.meshes);
    render::TraceSettings s;
    s.bounces = -1;
    s.spp_min = s.spp_max = spp;
    s.target_noise = 0;
    s.seed = 3;
    const render::PathTracer t(rs, d.environment, d.lights, s);
    const render::TraceResult r = t.render(camera);
    PtFurnace f;
    double var = 0;
    const std::size_t n = std::size_t(camera.width) * std::size_t(camera.height);
    for (std::size_t i = 0; i < n; ++i) {
        const double L = r.color.data[3 * i], se = r.stderr_.data[3 * i];
        f.worst = std::max(f.worst, std::fabs(L - 1) / (5 * se + 1e-6));
        f.mean += L;
        var += se * se;
        f.covered += r.coverage.data[i];
    }
    f.covered /= double(n);
    f.mean /= double(n);
    f.se = std::sqrt(var) / double(n);
    return f;
}

render::Camera scene_camera(const cli::SceneFile& s) {
    render::Camera c;
    c.position = s.camera.position;
    c.look_at = s.camera.look_at;
    c.up = s.camera.up;
    c.fov_deg = s.camera.fov_deg;
    c.width = s.camera.width;
    c.height = s.camera.height;
    return c;
}

/// Writes a one-mesh furnace scene for `model` (an absolute path) to the temporary directory
/// and returns its path.
std::string furnace_scene(const std::string& name, const std::string& model, double angle) {
    const std::string path =
        (std::filesystem::temp_directory_path() / ("sphbasis_normals_furnace_" + name + ".json"))
            .string();
    std::ofstream f(path);
    f << "{\"meshes\": [{\"file\": \"" << model << "\", \"albedo\": [1, 1, 1]";
    if (angle >= 0) f << ", \"smoothing_angle_deg\": " << angle;
    f << "}], \"environment\": {\"constant\": [1, 1, 1]}}\n";
    return path;
}

bool exists(const std::string& p) { return std::ifstream(p).good(); }

}  // namespace

TEST_CASE("generate_normals: a crease angle keeps a box flat and a sphere smooth", "[tools]") {
    SECTION("a cube of shared vertices: flat faces at 30 degrees, 24 vertices") {
        for (bool diag : {false, true}) {
            Mesh m = shared_cube(diag);
            cli::generate_normals(m, std::vector<char>(12, 1), 30);
            CHECK(m.vertex_count() == 24);  // 6 faces x 4 corners
            require_flat(m);
        }
    }
    SECTION("0 degrees is flat; 180 smooths every face around a corner, angle-weighted") {
        Mesh m = shared_cube(false);
        cli::generate_normals(m, std::vector<char>(12, 1), 0);
        require_flat(m);
        // At 180 every corner's three faces count by their angle there (90 degrees each,
        // however the face is split): the diagonal, the same for either triangulation.
        for (bool diag : {false, true}) {
            Mesh s = shared_cube(diag);
            cli::generate_normals(s, std::vector<char>(12, 1), 180);
            CHECK(s.vertex_count() == 8);
            for (std::size_t v = 0; v < 8; ++v) {
                const V3 p = vertex(s.positions, v), n = vertex(s.normals, v);
                const V3 diagonal{(2 * p.x - 1) / std::sqrt(3.0), (2 * p.y - 1) / std::sqrt(3.0),
                                  (2 * p.z - 1) / std::sqrt(3.0)};
                CHECK(dot3(n, diagonal) > 1 - 1e-6);
            }
        }
    }
    SECTION("a UV sphere (11.25 degrees between neighbouring faces) stays smooth") {
        Mesh m = render::shapes::sphere({0, 0, 0}, 1, 16, 32);
        const std::size_t V = m.vertex_count();
        m.normals.assign(m.positions.size(), 0.0f);
        m.uvs.clear();
        m.tangents.clear();
        cli::generate_normals(m, std::vector<char>(m.triangle_count(), 1), 30);
        CHECK(m.vertex_count() <= V);
        for (std::size_t v = 0; v < m.vertex_count(); ++v) {
            const V3 p = vertex(m.positions, v), n = vertex(m.normals, v);
            // The radial direction, within a degree (angle-weighted facets of a regular grid).
            CHECK(dot3(n, p) / std::sqrt(dot3(p, p)) > std::cos(constants::pi / 180));
        }
    }
    SECTION("neighbours wound the other way are not smoothed together; given normals stay") {
        Mesh m;
        m.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0, 0, 2, 1, 0};
        m.indices = {0, 1, 2, 0, 2, 3, 1, 2, 4, 4, 2, 5};  // triangle 2 wound the other way
        m.normals.assign(m.positions.size(), 0.0f);
        m.normals[3 * 5 + 0] = 0.6f;  // vertex 5: given, kept
        m.normals[3 * 5 + 2] = 0.8f;
        cli::generate_normals(m, {1, 1, 1, 0}, 60);
        for (std::size_t t = 0; t < 3; ++t) {
            const V3 f = face_normal(m, t);
            for (int k = 0; k < 3; ++k)
                CHECK(dot3(vertex(m.normals, m.indices[3 * t + std::size_t(k)]), f) > 1 - 1e-6);
        }
        const V3 kept = vertex(m.normals, m.indices[11]);
        CHECK(kept.x == 0.6f);
        CHECK(kept.z == 0.8f);
    }
    CHECK_THROWS_WITH(
        [] {
            Mesh m = shared_cube(false);
            cli::generate_normals(m, std::vector<char>(11, 1), 30);
        }(),
        Catch::Contains("sphbasis::cli::generate_normals(): expected one flag per triangle"));
}

TEST_CASE("scene files: normals generated with smoothing_angle_deg, given normals kept",
          "[tools]") {
    // Without normals: flat faces at the default angle (a box's 90-degree edges are creases).
    for (const std::string v : {"nonormals", "mixed_nonormals"}) {
        const cli::SceneFile s = cli::load_scene(furnace_dir + "open_box_" + v + ".json");
        require_flat(s.meshes[0].mesh);
    }
    // Given normals are kept: the smoothed box's corner (-1, -1, 0) has the inward diagonal.
    const cli::SceneFile s = cli::load_scene(furnace_dir + "open_box_smooth.json");
    const Mesh& m = s.meshes[0].mesh;
    bool found = false;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const V3 p = vertex(m.positions, v);
        if (p.x == -1 && p.y == -1 && p.z == 0) {
            found = true;
            CHECK(dot3(vertex(m.normals, v),
                       {1 / std::sqrt(3.0), 1 / std::sqrt(3.0), 1 / std::sqrt(3.0)}) > 1 - 1e-6);
        }
    }
    CHECK(found);
    // 180 degrees smooths the file's box across its edges; 0 and values outside [0, 180].
    const std::string obj = furnace_dir + "open_box_nonormals.obj";
    const cli::SceneFile smooth = cli::load_scene(furnace_scene("smooth180", obj, 180));
    std::size_t tilted = 0;
    for (std::size_t t = 0; t < smooth.meshes[0].mesh.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k)
            tilted += dot3(vertex(smooth.meshes[0].mesh.normals,
                                  smooth.meshes[0].mesh.indices[3 * t + std::size_t(k)]),
                           face_normal(smooth.meshes[0].mesh, t)) < 0.99;
    CHECK(tilted > 0);
    require_flat(cli::load_scene(furnace_scene("flat0", obj, 0)).meshes[0].mesh);
    CHECK_THROWS_WITH(cli::load_scene(furnace_scene("bad", obj, 181)),
                      Catch::Contains("meshes[0].smoothing_angle_deg: expected an angle in [0, "
                                      "180] degrees (0: flat faces), got 181"));
}

namespace {
void check_open_boxes(int rays, int spp) {
    for (const std::string& v : box_variants) {
        INFO("open_box_" << v);
        const cli::SceneFile s = cli::load_scene(furnace_dir + "open_box_" + v + ".json");
        const Furnace b = bake_furnace(s, rays);
        CAPTURE(b.mean, b.lowest, b.highest, b.points);
        CHECK(b.worst < 1);
        CHECK(std::fabs(b.mean - 1) < 1e-3);
        const PtFurnace p = trace_furnace(s, scene_camera(s), spp);
        CAPTURE(p.mean, p.se, p.covered);
        CHECK(p.covered > 0.2);
        CHECK(p.worst < 1);
        CHECK(std::fabs(p.mean - 1) <= 4 * p.se + 1e-9);
    }
}
}  // namespace

TEST_CASE("white furnace: open boxes from OBJ files, bake (24 bounces) and path tracer",
          "[tools][furnace]") {
    check_open_boxes(128, 32);
}

TEST_CASE("white furnace: open boxes from OBJ files, many samples", "[tools][furnace][slow]") {
    check_open_boxes(4096, 1024);
}

TEST_CASE("white furnace: models of assimp-testmodels", "[tools][furnace]") {
    // Debian's assimp-testmodels (an optional package): a PLY cube of 8 shared vertices (the
    // case Assimp's own normal generation gets wrong), the open sphere of an STL file (facet
    // normals as given) and the Wuson character from an OFF file without normals. Wuson's faces
    // are wound clockwise seen from outside, so most of its generated normals point into the
    // closed body: the bake (which bakes the side a vertex normal points to) rightly gives 0
    // there, and only the path tracer's view from outside (back faces, shaded from the side the
    // ray arrives on) is a furnace.
    const std::string dir = "/usr/share/assimp/models/";
    struct Model {
        const char* name;
        const char* file;
        render::Camera camera;
        bool bake;
    };
    render::Camera c;
    c.width = 20;
    c.height = 16;
    c.fov_deg = 50;
    std::vector<Model> models;
    c.position = {2.2, -1.7, 1.9};
    c.look_at = {0.5, 0.5, 0.5};
    c.fov_deg = 30;
    models.push_back({"cube", "PLY/cube.ply", c, true});
    c.position = {3.0, 1.5, 2.5};
    c.look_at = {0, 0.75, 0};
    c.fov_deg = 32;
    c.up = {0, 1, 0};
    models.push_back({"wuson", "OFF/Wuson.off", c, false});
    c.position = {0.8, 3.5, 6};
    c.look_at = {1.5, 1.5, 1.5};
    c.up = {0, 0, 1};
    c.fov_deg = 50;
    models.push_back({"sphere_with_hole", "STL/sphereWithHole.stl", c, true});
    for (const Model& m : models) {
        INFO(m.file);
        if (!exists(dir + m.file)) {
            WARN("skipped: " << dir << m.file << " is not installed (assimp-testmodels)");
            continue;
        }
        const cli::SceneFile s = cli::load_scene(furnace_scene(m.name, dir + m.file, -1));
        if (std::string(m.name) == "cube") require_flat(s.meshes[0].mesh);
        if (m.bake) {
            const Furnace b = bake_furnace(s, 32);
            CAPTURE(b.mean, b.lowest, b.highest, b.points);
            CHECK(b.worst < 1);
            CHECK(std::fabs(b.mean - 1) < 1e-3);
        }
        const PtFurnace p = trace_furnace(s, m.camera, 16);
        CAPTURE(p.mean, p.se, p.covered);
        CHECK(p.covered > 0.2);
        CHECK(p.worst < 1);
        CHECK(std::fabs(p.mean - 1) <= 4 * p.se + 1e-9);
    }
}

TEST_CASE("mesh files: zero normals and the vertices of degenerate triangles", "[tools][normals]") {
    // assimp-testmodels' spider (OBJ and binary STL) gives 0 0 0 as the normal of the vertices of
    // its degenerate triangles: those triangles are dropped, the vertices only they used go with
    // them, and a zero normal at a used vertex is generated like a missing one. Every vertex is
    // then used and has a unit normal, and a vertex bake runs.
    const std::string dir = "/usr/share/assimp/models/";
    for (const char* file : {"OBJ/spider.obj", "STL/Spider_binary.stl"}) {
        INFO(file);
        if (!exists(dir + file)) {
            WARN("skipped: " << dir << file << " is not installed (assimp-testmodels)");
            continue;
        }
        const cli::SceneFile s = cli::load_scene(furnace_scene("spider", dir + file, -1));
        for (const cli::SceneMesh& sm : s.meshes) {
            const Mesh& m = sm.mesh;
            std::vector<char> used(m.vertex_count(), 0);
            for (std::uint32_t i : m.indices) used[i] = 1;
            CHECK(std::count(used.begin(), used.end(), 0) == 0);
            double worst = 0;
            for (std::size_t v = 0; v < m.vertex_count(); ++v) {
                const float* n = &m.normals[3 * v];
                worst =
                    std::max(worst, std::fabs(std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] +
                                                        double(n[2]) * n[2]) -
                                              1));
            }
            CHECK(worst < 1e-5);
        }
        CHECK(bake_furnace(s, 4).points > 0);
    }
}
