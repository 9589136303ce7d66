// Tests of render/specular.hpp and render/normal_maps.hpp: the normal mip chain, Blinn-Phong
// specular (aliased, Toksvig, supersampled reference) and the procedural normal maps.
#include <tbb/task_arena.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/render/normal_maps.hpp"
#include "sphbasis/render/specular.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

constexpr double kPi = 3.14159265358979323846;

vec3<double> unit3(double x, double y, double z) {
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}

/// Encodes unit normals as a normal-map colour (n + 1)/2.
void put(std::vector<float>& tex, int w, int x, int y, const vec3<double>& n) {
    float* t = &tex[3 * (std::size_t(y) * std::size_t(w) + std::size_t(x))];
    t[0] = float(0.5 * (n.x + 1));
    t[1] = float(0.5 * (n.y + 1));
    t[2] = float(0.5 * (n.z + 1));
}

/// A quad mesh (z = 0, [-h, h]^2, UVs scaled by `tiles`) with a normal map and a material.
Mesh mapped_quad(double h, double tiles, std::vector<float> texels, int w, int hgt, float shininess,
                 std::array<float, 3> ks) {
    Mesh m = sphbasis_test::quad_grid(-h, h, -h, h, 0, 1);
    for (auto& uv : m.uvs) uv = float(uv * tiles);
    auto owned = std::make_shared<const std::vector<float>>(std::move(texels));
    m.normal_texels = owned;
    m.normal_map = TextureView{owned->data(), w, hgt, 3};
    m.shininess = shininess;
    m.specular = ks;
    return m;
}

/// A value in [0, 1) from a SplitMix64-style state.
double next01(std::uint64_t& st) {
    st = sphbasis::render::detail::rt::mix64(st);
    return sphbasis::render::detail::rt::unit(st);
}

double rms(const Image& a) {
    double s = 0;
    for (float x : a.data) s += double(x) * double(x);
    return std::sqrt(s / double(a.data.size()));
}

/// Closed form of (lobe) (n.l) integrated over the lit hemisphere with the view along n.
double lobe_energy(double s) {
    return (s + 8) * (2 * (1 - std::pow(2.0, -(s + 4) / 2)) / (s + 4) -
                      (1 - std::pow(2.0, -(s + 2) / 2)) / (s + 2));
}

struct Comparison {
    double aliased, toksvig, reference_rms, reference_change;
};

/// The comparison: a bumpy plane seen from far (the map minified), light in the mirror
/// direction of the camera (angle `elevation_deg` from the normal, plus `light_offset_deg`).
Comparison toksvig_vs_aliased(int size, int ss, double distance, float shininess,
                              double light_offset_deg, double amplitude,
                              bool check_reference = false) {
    const int n = 256;
    auto tex = bumpy_normal_map(n, n, 24, amplitude, 7);
    // A 40 x 40 quad tiled 40 times: one tile per world unit, so the view is all quad.
    Mesh quad = mapped_quad(20, 40, std::move(tex), n, n, shininess, {1, 1, 1});
    SceneDesc desc;
    desc.meshes = {quad.view()};
    const double a = 30 * kPi / 180, b = (30 + light_offset_deg) * kPi / 180;
    desc.lights = {sphbasis_test::directional_light({0, std::sin(b), std::cos(b)}, {1, 1, 1})};
    Scene rt(desc.meshes);
    Camera cam;
    cam.position = {0, -distance * std::sin(a), distance * std::cos(a)};
    cam.look_at = {0, 0, 0};
    cam.up = {0, 0, 1};
    cam.fov_deg = 20;
    cam.width = cam.height = size;
    const Image ref = render_specular_reference(desc, rt, cam, ss);
    const Image al = render_specular(desc, rt, cam, SpecularShading::Mode::aliased);
    const Image tk = render_specular(desc, rt, cam, SpecularShading::Mode::toksvig);
    // The reference's own error: its change when ss doubles (only when asked: 4x the rays).
    double change = -1;
    if (check_reference)
        change = sphbasis_test::rmse(ref, render_specular_reference(desc, rt, cam, 2 * ss));
    return {sphbasis_test::rmse(al, ref), sphbasis_test::rmse(tk, ref), rms(ref), change};
}

}  // namespace

TEST_CASE("render::NormalMipChain: each texel is the mean of its 2x2 children", "[render]") {
    const int w = 16, h = 8;
    std::vector<float> tex(std::size_t(w * h * 3));
    std::uint64_t st = 1;
    for (auto& t : tex) t = float(next01(st));
    const NormalMipChain chain(TextureView{tex.data(), w, h, 3});
    REQUIRE(chain.levels() == 5);  // 16x8, 8x4, 4x2, 2x1, 1x1
    CHECK(chain.level_width(3) == 2);
    CHECK(chain.level_height(3) == 1);
    // Level 0 is the decoded map.
    const auto t0 = chain.texel(0, 3, 5);
    CHECK(t0.x == Approx(2.0 * tex[3 * (5 * w + 3)] - 1).margin(1e-7));
    CHECK(t0.z == Approx(2.0 * tex[3 * (5 * w + 3) + 2] - 1).margin(1e-7));
    double mean0[3] = {0, 0, 0};
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const auto t = chain.texel(0, x, y);
            mean0[0] += t.x / (w * h);
            mean0[1] += t.y / (w * h);
            mean0[2] += t.z / (w * h);
        }
    for (int k = 1; k < chain.levels(); ++k) {
        const int pw = chain.level_width(k - 1), ph = chain.level_height(k - 1);
        for (int y = 0; y < chain.level_height(k); ++y)
            for (int x = 0; x < chain.level_width(k); ++x) {
                double e[3] = {0, 0, 0};
                const int nx = pw > 1 ? 2 : 1, ny = ph > 1 ? 2 : 1;
                for (int b = 0; b < ny; ++b)
                    for (int a = 0; a < nx; ++a) {
                        const auto c = chain.texel(k - 1, nx * x + a, ny * y + b);
                        e[0] += c.x / (nx * ny);
                        e[1] += c.y / (nx * ny);
                        e[2] += c.z / (nx * ny);
                    }
                const auto t = chain.texel(k, x, y);
                CHECK(t.x == Approx(e[0]).margin(1e-6));
                CHECK(t.y == Approx(e[1]).margin(1e-6));
                CHECK(t.z == Approx(e[2]).margin(1e-6));
            }
    }
    const auto top = chain.texel(chain.levels() - 1, 0, 0);
    CHECK(top.x == Approx(mean0[0]).margin(1e-6));
    CHECK(top.z == Approx(mean0[2]).margin(1e-6));

    // An odd size keeps the mean exactly at every level (area-weighted footprints).
    const int ow = 5, oh = 3;
    std::vector<float> odd(std::size_t(ow * oh * 3));
    for (auto& t : odd) t = float(next01(st));
    const NormalMipChain oc(TextureView{odd.data(), ow, oh, 3});
    CHECK(oc.levels() == 3);  // 5x3, 2x1, 1x1
    double om = 0;
    for (int i = 0; i < ow * oh; ++i) om += (2.0 * odd[std::size_t(3 * i)] - 1) / (ow * oh);
    double m1 = 0;
    for (int x = 0; x < 2; ++x) m1 += oc.texel(1, x, 0).x / 2;
    CHECK(m1 == Approx(om).margin(1e-6));
    CHECK(oc.texel(2, 0, 0).x == Approx(om).margin(1e-6));
}

TEST_CASE("render::NormalMipChain: constant and alternating normals", "[render]") {
    const int w = 8, h = 8;
    SECTION("a constant unit normal keeps |Na| = 1 at every level") {
        const vec3<double> n = unit3(0.3, -0.4, 0.8);
        std::vector<float> tex(std::size_t(w * h * 3));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) put(tex, w, x, y, n);
        const NormalMipChain chain(TextureView{tex.data(), w, h, 3});
        REQUIRE(chain.levels() == 4);
        for (double lod : {0.0, 0.5, 1.0, 2.3, 3.0, 7.0}) {
            const auto a = chain.average(0.37, 0.81, lod);
            CHECK(std::sqrt(dot(a, a)) == Approx(1).margin(3e-7));
            CHECK(a.x == Approx(n.x).margin(3e-7));
        }
    }
    SECTION("a checkerboard of two normals averages to the analytic mean, |Na| < 1") {
        const double ang = 0.6;
        const vec3<double> n1{std::sin(ang), 0, std::cos(ang)},
            n2{0, -std::sin(ang), std::cos(ang)};
        std::vector<float> tex(std::size_t(w * h * 3));
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) put(tex, w, x, y, (x + y) % 2 ? n1 : n2);
        const NormalMipChain chain(TextureView{tex.data(), w, h, 3});
        const double ex = std::sin(ang) / 2, ey = -std::sin(ang) / 2, ez = std::cos(ang);
        for (int k = 1; k < chain.levels(); ++k)
            for (int y = 0; y < chain.level_height(k); ++y)
                for (int x = 0; x < chain.level_width(k); ++x) {
                    const auto t = chain.texel(k, x, y);
                    CHECK(t.x == Approx(ex).margin(1e-6));
                    CHECK(t.y == Approx(ey).margin(1e-6));
                    CHECK(t.z == Approx(ez).margin(1e-6));
                }
        const auto a = chain.average(0.3, 0.6, 1.5);
        const double len = std::sqrt(dot(a, a));
        CHECK(len == Approx(std::sqrt(ex * ex + ey * ey + ez * ez)).margin(1e-6));
        CHECK(len < 0.95);
    }
    SECTION("trilinear lookups: texel centres, fractional lods, wrapping") {
        std::vector<float> tex(std::size_t(w * h * 3));
        std::uint64_t st = 5;
        for (auto& t : tex) t = float(next01(st));
        const NormalMipChain chain(TextureView{tex.data(), w, h, 3});
        // Texel (x, y) of level 0 sits at uv ((x + 0.5)/w, 1 - (y + 0.5)/h).
        const auto c = chain.average((2 + 0.5) / w, 1 - (5 + 0.5) / h, 0);
        const auto t = chain.texel(0, 2, 5);
        CHECK(c.x == Approx(t.x).margin(1e-12));
        CHECK(c.y == Approx(t.y).margin(1e-12));
        const double u = 0.41, v = 0.27;
        const auto a0 = chain.bilinear(1, u, v), a1 = chain.bilinear(2, u, v);
        const auto m = chain.average(u, v, 1.25);
        CHECK(m.x == Approx(0.75 * a0.x + 0.25 * a1.x).margin(1e-12));
        CHECK(m.z == Approx(0.75 * a0.z + 0.25 * a1.z).margin(1e-12));
        const auto wr = chain.average(u + 3, v - 2, 0.7);
        const auto nw = chain.average(u, v, 0.7);
        CHECK(wr.x == Approx(nw.x).margin(1e-9));
        CHECK(wr.y == Approx(nw.y).margin(1e-9));
        // Between texel centres across the seam: the wrap neighbour contributes.
        const auto seam = chain.average(0, 1 - 0.5 / h, 0);
        CHECK(seam.x ==
              Approx(0.5 * (chain.texel(0, 0, 0).x + chain.texel(0, w - 1, 0).x)).margin(1e-7));
        // Beyond the top level and negative or NaN lods clamp.
        const auto top = chain.texel(chain.levels() - 1, 0, 0);
        CHECK(chain.average(u, v, 99).x == Approx(top.x).margin(1e-12));
        CHECK(chain.average(u, v, -3).x == Approx(chain.average(u, v, 0).x).margin(1e-12));
        CHECK(chain.average(u, v, std::nan("")).x == Approx(chain.average(u, v, 0).x));
        const auto bad = chain.average(std::nan(""), v, 0);
        CHECK(bad.z == 1);
    }
}

TEST_CASE(
    "render::SpecularShading: a flat normal map gives the closed-form Blinn-Phong in all "
    "three modes",
    "[render]") {
    const float s = 32;
    const std::array<float, 3> ks{0.04f, 0.5f, 1.0f};
    Mesh quad = mapped_quad(1, 1, flat_normal_map(8, 8), 8, 8, s, ks);
    SceneDesc desc;
    desc.meshes = {quad.view()};
    const vec3<double> ld = unit3(-0.1, 0.6, 0.8);  // near the camera's mirror direction
    const RGB lc{1, 2, 0.5};
    desc.lights = {sphbasis_test::directional_light(ld, lc)};
    Scene rt(desc.meshes);
    const Camera cam = sphbasis_test::camera_at({0.2, -2.5, 2.0}, {0, 0, 0}, 24, 16, 30);
    const PinholeCamera pc(cam);
    const Image al = render_specular(desc, rt, cam, SpecularShading::Mode::aliased);
    const Image tk = render_specular(desc, rt, cam, SpecularShading::Mode::toksvig);
    const Image rf = render_specular_reference(desc, rt, cam, 1);
    int checked = 0;
    double peak = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const CameraRay r = pc.ray(x + 0.5, y + 0.5);
            const double t = -r.origin.z / r.direction.z;
            const double px = r.origin.x + t * r.direction.x, py = r.origin.y + t * r.direction.y;
            if (!(t > 0) || std::fabs(px) > 0.98 || std::fabs(py) > 0.98) {
                if (!(t > 0) || std::fabs(px) > 1.02 || std::fabs(py) > 1.02)
                    CHECK(al.at(x, y)[0] == 0);  // a miss is black
                continue;
            }
            const vec3<double> view = unit3(-r.direction.x, -r.direction.y, -r.direction.z);
            const vec3<double> hv = unit3(view.x + ld.x, view.y + ld.y, view.z + ld.z);
            const double f = (s + 8) / (8 * kPi) * std::pow(hv.z, s) * ld.z;
            for (int k = 0; k < 3; ++k) {
                const double e = ks[std::size_t(k)] * f * lc[std::size_t(k)];
                CHECK(al.at(x, y)[k] == Approx(e).epsilon(2e-5).margin(1e-9));
                CHECK(tk.at(x, y)[k] == Approx(e).epsilon(2e-5).margin(1e-9));
                CHECK(rf.at(x, y)[k] == Approx(e).epsilon(2e-5).margin(1e-9));
                peak = std::max(peak, e);
            }
            ++checked;
        }
    CHECK(checked > 150);
    CHECK(peak > 0.5);  // the view sees the highlight
}

TEST_CASE("render::SpecularShading: no normal map reads the shading normal; shininess 0 is black",
          "[render]") {
    SECTION("tilted vertex normals, no map") {
        Mesh quad = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1);
        const vec3<double> n0 = unit3(0.2, 0.1, 1);
        for (std::size_t i = 0; i < quad.vertex_count(); ++i) {
            quad.normals[3 * i] = float(n0.x);
            quad.normals[3 * i + 1] = float(n0.y);
            quad.normals[3 * i + 2] = float(n0.z);
        }
        quad.shininess = 20;
        quad.specular = {0.3f, 0.3f, 0.3f};
        SceneDesc desc;
        desc.meshes = {quad.view()};
        const vec3<double> ld = unit3(-0.1, 0.4, 1);
        desc.lights = {sphbasis_test::directional_light(ld, {2, 2, 2})};
        // A non-directional light is not part of the specular comparison.
        Light sun2 = sphbasis_test::directional_light({0, 0, 1}, {5, 5, 5});
        sun2.type = Light::Type::hemisphere;
        desc.lights.push_back(sun2);
        Scene rt(desc.meshes);
        const SpecularShading sh(desc);
        CHECK(sh.light_count() == 1);
        CHECK(sh.mip_chains() == 0);
        const vec3<double> o{0.3, -0.7, 1.5};
        const vec3<double> d = unit3(-0.25, 0.5, -1.5);
        const Hit hit = rt.intersect(o, d);
        REQUIRE(hit.valid);
        const vec3<double> view{-d.x, -d.y, -d.z};
        const vec3<double> n{hit.shading_normal.x, hit.shading_normal.y, hit.shading_normal.z};
        CHECK(n.x == Approx(n0.x).margin(1e-6));
        const vec3<double> hv = unit3(view.x + ld.x, view.y + ld.y, view.z + ld.z);
        const double e = 0.3 * (20 + 8) / (8 * kPi) * std::pow(dot(n, hv), 20) * dot(n, ld) * 2;
        for (auto mode : {SpecularShading::Mode::aliased, SpecularShading::Mode::toksvig,
                          SpecularShading::Mode::reference}) {
            const RGB c = sh.shade(mode, hit, view, 0.01);
            CHECK(c[0] == Approx(e).epsilon(1e-6));
            CHECK(c[2] == Approx(e).epsilon(1e-6));
        }
        // A light below the geometric surface contributes nothing.
        SceneDesc below = desc;
        below.lights = {sphbasis_test::directional_light({0.1, 0, -1}, {1, 1, 1})};
        const RGB z = SpecularShading(below).shade(SpecularShading::Mode::aliased, hit, view, 0);
        CHECK(z[0] == 0);
    }
    SECTION("shininess 0 with a normal map: black, and no mip chain is built") {
        Mesh quad = mapped_quad(1, 1, bumpy_normal_map(16, 16, 2, 0.5, 1), 16, 16, 0, {1, 1, 1});
        SceneDesc desc;
        desc.meshes = {quad.view()};
        desc.lights = {sphbasis_test::directional_light({0, 0, 1}, {1, 1, 1})};
        Scene rt(desc.meshes);
        CHECK(SpecularShading(desc).mip_chains() == 0);
        const Camera cam = sphbasis_test::camera_at({0, 0, 3}, {0, 0, 0}, 8, 8, 45);
        for (const Image& img : {render_specular(desc, rt, cam, SpecularShading::Mode::aliased),
                                 render_specular(desc, rt, cam, SpecularShading::Mode::toksvig),
                                 render_specular_reference(desc, rt, cam, 2)})
            for (float v : img.data) CHECK(v == 0);
    }
}

TEST_CASE("render::blinn_phong_lobe: the normalised lobe's energy is about 1", "[render]") {
    // The lobe times n.l integrated over light directions with the view along n, three ways:
    // the closed form, a midpoint quadrature of blinn_phong_lobe, and SpecularShading::shade
    // with one directional light per quadrature cell (colour = its solid angle).
    for (double s : {1.0, 8.0, 64.0, 1000.0}) {
        const int nt = 2000;
        double q = 0;
        for (int i = 0; i < nt; ++i) {
            const double th = (i + 0.5) * (kPi / 2) / nt;
            q += blinn_phong_lobe(std::cos(th / 2), s) * std::cos(th) * std::sin(th) * 2 * kPi *
                 (kPi / 2) / nt;
        }
        const double e = lobe_energy(s);
        CHECK(q == Approx(e).epsilon(1e-5));
        CHECK(e > 0.99);
        CHECK(e < 1.08);  // (s + 8)/(8 pi) is an approximation: 1.024, 1.075, 1.027, 1.002
        INFO("s = " << s << ", energy = " << e);
    }
    CHECK(lobe_energy(1) == Approx(1.02426).margin(1e-5));
    CHECK(lobe_energy(8) == Approx(1.0750).margin(1e-4));
    CHECK(lobe_energy(1000) == Approx(1.0020).margin(1e-4));

    Mesh quad = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1);
    quad.shininess = 64;
    quad.specular = {1, 1, 1};
    SceneDesc desc;
    desc.meshes = {quad.view()};
    const int nt = 600, np = 8;
    for (int i = 0; i < nt; ++i)
        for (int j = 0; j < np; ++j) {
            const double th = (i + 0.5) * (kPi / 2) / nt, ph = (j + 0.5) * 2 * kPi / np;
            const double dw = std::sin(th) * (kPi / 2) / nt * 2 * kPi / np;
            desc.lights.push_back(sphbasis_test::directional_light(
                {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)},
                {dw, dw, dw}));
        }
    Scene rt(desc.meshes);
    const Hit hit = rt.intersect({0.1, 0.2, 1}, {0, 0, -1});
    REQUIRE(hit.valid);
    const RGB c = SpecularShading(desc).shade(SpecularShading::Mode::aliased, hit, {0, 0, 1}, 0);
    CHECK(c[0] == Approx(lobe_energy(64)).epsilon(1e-3));
}

TEST_CASE("render::bumpy_normal_map: unit normals, exact RMS slope, deterministic", "[render]") {
    const int w = 64, h = 32;
    const auto a = bumpy_normal_map(w, h, 6, 0.4, 11);
    REQUIRE(a.size() == std::size_t(w * h * 3));
    CHECK(a == bumpy_normal_map(w, h, 6, 0.4, 11));
    CHECK(a != bumpy_normal_map(w, h, 6, 0.4, 12));
    double ms = 0, mx = 0;
    for (int i = 0; i < w * h; ++i) {
        const double nx = 2.0 * a[std::size_t(3 * i)] - 1, ny = 2.0 * a[std::size_t(3 * i + 1)] - 1,
                     nz = 2.0 * a[std::size_t(3 * i + 2)] - 1;
        CHECK(nx * nx + ny * ny + nz * nz == Approx(1).margin(2e-6));
        CHECK(nz > 0);
        ms += (nx * nx + ny * ny) / (nz * nz) / (w * h);
        mx += nx / (w * h);
    }
    // Integer frequencies below the grid's Nyquist limit: the texel-centre average of the
    // squared slope equals the continuous one.
    CHECK(std::sqrt(ms) == Approx(0.4).epsilon(1e-4));
    CHECK(std::fabs(mx) < 0.05);  // bumps, not a tilt
    for (float v : bumpy_normal_map(4, 4, 1, 0, 3)) CHECK((v == 0.5f || v == 1.0f));
    CHECK_THROWS_AS(bumpy_normal_map(0, 4, 1, 0.1, 1), std::invalid_argument);
    CHECK_THROWS_AS(bumpy_normal_map(4, 4, 0, 0.1, 1), std::invalid_argument);
    CHECK_THROWS_AS(bumpy_normal_map(4, 4, std::nan(""), 0.1, 1), std::invalid_argument);
    CHECK_THROWS_AS(bumpy_normal_map(4, 4, 1, -0.1, 1), std::invalid_argument);
    CHECK_THROWS_AS(bumpy_normal_map(4, 4, 1, std::numeric_limits<double>::infinity(), 1),
                    std::invalid_argument);
}

TEST_CASE("render::SpecularShading: the level of detail follows the pixel footprint", "[render]") {
    const int n = 64;
    Mesh quad = mapped_quad(2, 4, flat_normal_map(n, n), n, n, 16, {1, 1, 1});  // 1 tile/unit
    SceneDesc desc;
    desc.meshes = {quad.view()};
    desc.lights = {sphbasis_test::directional_light({0, 0, 1}, {1, 1, 1})};
    Scene rt(desc.meshes);
    const SpecularShading sh(desc);
    REQUIRE(sh.mip_chains() == 1);
    REQUIRE(sh.chain(0)->levels() == 7);
    const Hit hit = rt.intersect({0.1, 0.1, 5}, {0, 0, -1});
    REQUIRE(hit.valid);
    // One world unit = one UV unit = 64 texels: a footprint of 1/16 is 4 texels, lod 2.
    CHECK(sh.level_of_detail(hit, 1.0 / 16) == Approx(2).margin(1e-9));
    CHECK(sh.level_of_detail(hit, 1.0 / 128) == 0);
    CHECK(sh.level_of_detail(hit, 100) == Approx(6));
    // The footprint of a pixel straight below a camera at height 5.
    const Camera cam = sphbasis_test::camera_at({0, 0, 5}, {0, 0, 0}, 64, 64, 45);
    const PinholeCamera pc(cam);
    const Hit c = rt.intersect({0, 0, 5}, pc.ray(32, 32).direction);
    REQUIRE(c.valid);
    CHECK(pixel_footprint(pc, pc.ray(32, 32).direction, c) ==
          Approx(5 * pc.pixel_angle()).epsilon(1e-6));
}

TEST_CASE("render::specular: bad input throws", "[render]") {
    Mesh quad = mapped_quad(1, 1, flat_normal_map(4, 4), 4, 4, 8, {1, 1, 1});
    SceneDesc desc;
    desc.meshes = {quad.view()};
    desc.lights = {sphbasis_test::directional_light({0, 0, 1}, {1, 1, 1})};
    Scene rt(desc.meshes);
    const Camera cam = sphbasis_test::camera_at({0, 0, 3}, {0, 0, 0}, 4, 4, 45);
    CHECK_THROWS_WITH(render_specular_reference(desc, rt, cam, 0),
                      Catch::Contains("sphbasis::render::render_specular_reference()"));
    CHECK_THROWS_AS(render_specular_reference(desc, rt, cam, 65), std::invalid_argument);
    Camera bad_cam = cam;
    bad_cam.look_at = cam.position;
    CHECK_THROWS_AS(render_specular_reference(desc, rt, bad_cam, 2), std::invalid_argument);
    SceneDesc two = desc;
    two.meshes.push_back(quad.view());
    CHECK_THROWS_AS(render_specular(two, rt, cam, SpecularShading::Mode::aliased),
                    std::invalid_argument);

    const SpecularShading sh(desc);
    const Hit hit = rt.intersect({0, 0, 1}, {0, 0, -1});
    REQUIRE(hit.valid);
    const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(sh.shade(SpecularShading::Mode::aliased, hit, {nan, 0, 1}, 0),
                    std::invalid_argument);
    CHECK_THROWS_AS(sh.shade(SpecularShading::Mode::toksvig, hit, {0, 0, 1}, nan),
                    std::invalid_argument);
    CHECK_THROWS_AS(sh.shade(SpecularShading::Mode::toksvig, hit, {0, 0, 1}, inf),
                    std::invalid_argument);
    CHECK_THROWS_AS(sh.shade(SpecularShading::Mode::toksvig, hit, {0, 0, 1}, -1),
                    std::invalid_argument);
    Hit other = hit;
    other.mesh = 3;
    CHECK_THROWS_AS(sh.shade(SpecularShading::Mode::aliased, other, {0, 0, 1}, 0),
                    std::invalid_argument);

    SceneDesc bad_light = desc;
    bad_light.lights[0].color = {nan, 1, 1};
    CHECK_THROWS_AS(SpecularShading(bad_light), std::invalid_argument);
    SceneDesc bad_shine = desc;
    bad_shine.meshes[0].shininess = float(nan);
    CHECK_THROWS_AS(SpecularShading(bad_shine), std::invalid_argument);
    SceneDesc bad_ks = desc;
    bad_ks.meshes[0].specular = {1.5f, 0, 0};
    CHECK_THROWS_AS(SpecularShading(bad_ks), std::invalid_argument);
    SceneDesc no_uv = desc;
    no_uv.meshes[0].uvs = nullptr;
    CHECK_THROWS_AS(SpecularShading(no_uv), std::invalid_argument);

    std::vector<float> t = flat_normal_map(2, 2);
    t[4] = float(nan);
    CHECK_THROWS_AS(NormalMipChain(TextureView{t.data(), 2, 2, 3}), std::invalid_argument);
    CHECK_THROWS_AS(NormalMipChain(TextureView{nullptr, 2, 2, 3}), std::invalid_argument);
    CHECK_THROWS_AS(NormalMipChain(TextureView{t.data(), 2, 2, 2}), std::invalid_argument);
    CHECK_THROWS_AS(NormalMipChain(TextureView{t.data(), 0, 2, 3}), std::invalid_argument);
}

TEST_CASE(
    "render::specular: Toksvig is closer to the supersampled reference than the aliased "
    "shading on a bumpy normal map seen from far",
    "[render]") {
    // 16 x 16 pixels at distance 6: each covers about 0.13 world units = 34 texels of the
    // 256^2 map (lod ~5) and 3 bump periods; 16 x 16 rays per pixel for the reference (its own
    // error, measured by the [slow] case as its change from ss 16 to 32, is 0.014 here);
    // shininess 64, light in the camera's mirror direction.
    const Comparison c = toksvig_vs_aliased(16, 16, 6, 64, 0, 0.35);
    INFO("RMS error: aliased " << c.aliased << ", toksvig " << c.toksvig << ", reference RMS "
                               << c.reference_rms);
    CHECK(c.reference_rms > 0.05);
    CHECK(c.toksvig < 0.2 * c.aliased);
    CHECK(c.toksvig < 0.2 * c.reference_rms);
}

TEST_CASE(
    "render::specular: Toksvig against aliased over distances, shininess and light "
    "directions",
    "[render][slow]") {
    // 32 x 32 pixels: distance 4 is about 11 texels (1 bump period) per pixel, 40 about 110
    // texels (10 periods), where 16 x 16 ordered rays no longer resolve the bumps.
    for (double distance : {4.0, 12.0, 40.0})
        for (float s : {16.0f, 64.0f, 256.0f})
            for (double off : {0.0, 10.0}) {
                const Comparison c = toksvig_vs_aliased(32, 16, distance, s, off, 0.35, true);
                INFO("distance " << distance << ", s " << s << ", light offset " << off
                                 << ": aliased " << c.aliased << ", toksvig " << c.toksvig
                                 << ", reference RMS " << c.reference_rms
                                 << ", reference change ss 16 -> 32 " << c.reference_change);
                CHECK(c.toksvig < 0.3 * c.aliased);
                // The reference resolves the difference everywhere, and Toksvig's own error
                // where 16 x 16 rays resolve the bumps.
                CHECK(c.reference_change < 0.2 * c.aliased);
                if (distance < 10) CHECK(c.reference_change < 0.5 * c.toksvig);
            }
}

TEST_CASE("render::render_specular_reference: deterministic whatever the thread count",
          "[render]") {
    Mesh quad = mapped_quad(2, 4, bumpy_normal_map(32, 32, 4, 0.3, 2), 32, 32, 32, {1, 1, 1});
    SceneDesc desc;
    desc.meshes = {quad.view()};
    desc.lights = {sphbasis_test::directional_light({0, 0.5, 0.8}, {1, 1, 1})};
    Scene rt(desc.meshes);
    const Camera cam = sphbasis_test::camera_at({0, -2, 2}, {0, 0, 0}, 40, 20, 45);
    const Image a = render_specular_reference(desc, rt, cam, 3);
    Image b;
    tbb::task_arena one(1);
    one.execute([&] { b = render_specular_reference(desc, rt, cam, 3); });
    CHECK(a.data == b.data);
    CHECK(rms(a) > 0);
}
