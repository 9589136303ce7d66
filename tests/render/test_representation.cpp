// Tests of render/representation.hpp: closed forms under constant and analytic lighting, PRT
// against ao under a constant sky, render-time rotation against re-baking, the bake cache's
// counters, and the bake record's serialisation.
#include <Eigen/Dense>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/ops/sg_fit.hpp"
#include "sphbasis/render/irradiance_fit.hpp"
#include "sphbasis/render/representation.hpp"
#include "sphbasis/render/shapes.hpp"

namespace {

using namespace sphbasis;
using render::Camera;
using render::Environment;
using render::Image;
using render::Light;
using render::Mesh;
using render::RGB;

using sphbasis_test::max_abs;
using sphbasis_test::max_abs_diff;
using sphbasis_test::World;

using sphbasis_test::camera_at;

/// Drops every mesh's UVs and tangents (the bakes then run per vertex).
void strip_uvs(World& w) {
    for (Mesh& m : w.meshes) {
        m.uvs.clear();
        m.tangents.clear();
    }
}

/// Settings with the given rays, bounces and lightmap size, the rest defaults.
render::RepresentationSettings settings(int rays, int bounces, int lightmap_size) {
    render::RepresentationSettings s;
    s.rays = rays;
    s.bounces = bounces;
    s.lightmap_size = lightmap_size;
    return s;
}

/// Sphere of radius 1 at the origin, UVs stripped or kept.
World lone_sphere(int rings, int segments, float albedo) {
    World w;
    w.meshes.push_back(render::shapes::sphere({0, 0, 0}, 1, rings, segments));
    w.meshes[0].albedo = {albedo, albedo, albedo};
    return w;
}

/// A sphere over a plane (both with UVs unless stripped).
World sphere_on_plane(bool uvs) {
    World w = sphbasis_test::sphere_on_plane_meshes();
    if (!uvs) strip_uvs(w);
    return w;
}

bool all_finite(const Image& a) {
    for (float v : a.data)
        if (!std::isfinite(v)) return false;
    return true;
}

/// Rz(a) Rx(b), row-major.
Mat3<double> rotation(double a, double b) {
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
    const Mat3<double> z{ca, -sa, 0, sa, ca, 0, 0, 0, 1};
    const Mat3<double> x{1, 0, 0, 0, cb, -sb, 0, sb, cb};
    Mat3<double> r{};
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            for (int k = 0; k < 3; ++k)
                r[std::size_t(3 * i + j)] += z[std::size_t(3 * i + k)] * x[std::size_t(3 * k + j)];
    return r;
}
vec3<double> mat_apply(const Mat3<double>& r, const vec3<double>& v) {
    return {r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
            r[6] * v.x + r[7] * v.y + r[8] * v.z};
}

/// The value at +z of the fit of (1 + z)/2 over the tangent hemisphere in the lobes of
/// lightmap-sgN[-nnls|-running], by ops/sg_fit.hpp on the bake's fit directions (least squares,
/// NNLS: hemisphere_rule_sqrt(32, 32); running average: render::sg_running_directions()).
double sg_fit_factor(const std::string& name) {
    const bool nnls = name.find("-nnls") != std::string::npos;
    const bool running = name.find("-running") != std::string::npos;
    const int lobes = std::stoi(name.substr(std::string("lightmap-sg").size()));
    const DirectionalRule rule =
        running ? render::sg_running_directions() : hemisphere_rule_sqrt(32, 32);
    Eigen::MatrixXd v(Eigen::Index(rule.size()), 1);
    for (std::size_t i = 0; i < rule.size(); ++i) v(Eigen::Index(i), 0) = 0.5 * (1 + rule.z[i]);
    const auto set = sg::bakinglab_lobes(lobes);
    const Eigen::MatrixXd a =
        sg::fit_function(set, rule, v,
                         running ? sg::Solver::running_average
                                 : (nnls ? sg::Solver::nnls : sg::Solver::least_squares));
    double at_z = 0;
    for (std::size_t k = 0; k < set.size(); ++k)
        at_z += a(Eigen::Index(k), 0) * sg::eval(set[k], 0.0, 0.0, 1.0);
    return at_z;
}

/// A small lat-long map with a smooth gradient and a bright patch.
std::vector<float> latlong_texels(int w, int h) {
    return sphbasis_test::rgb_texels(w, h, [h](int x, int y, float* p) {
        const float base = 0.2f + 0.6f * float(h - y) / float(h);
        const bool patch = x >= 3 && x <= 5 && y >= 2 && y <= 3;
        p[0] = base + (patch ? 4.0f : 0.0f);
        p[1] = 0.8f * base + (patch ? 3.0f : 0.0f);
        p[2] = 0.5f + 0.1f * float(x % 4);
    });
}

}  // namespace

TEST_CASE("representations: names, unknown and duplicate names, bad settings", "[render]") {
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({1, 1, 1});
    w.build();
    render::RepresentationSettings s;
    const auto& names = render::representation_names();
    REQUIRE(names.size() == 53);
    // Every lightmap basis exists in the registry.
    for (const char* b : {"sh", "hbasis", "hbasis-mod", "hl2", "hsh"}) CHECK_NOTHROW(find_basis(b));
    CHECK_THROWS_WITH(render::Representations(w.desc, *w.rt, s, {"ao", "nonsense"}),
                      Catch::Contains("nonsense") && Catch::Contains("prt-texel") &&
                          Catch::Contains("lightmap-hsh9"));
    CHECK_THROWS_AS(render::Representations(w.desc, *w.rt, s, {"ao", "nonsense"}),
                    std::invalid_argument);
    CHECK_THROWS_WITH(render::Representations(w.desc, *w.rt, s, {"ao", "bent", "ao"}),
                      Catch::Contains("'ao' twice") && Catch::Contains("volume"));
    render::RepresentationSettings bad = s;
    bad.prt_bands = 0;
    CHECK_THROWS_AS(render::Representations(w.desc, *w.rt, bad, {"prt-vertex"}),
                    std::invalid_argument);
    bad = s;
    bad.lighting_rotation = {1, 0, 0, 0, 2, 0, 0, 0, 1};
    CHECK_THROWS_AS(render::Representations(w.desc, *w.rt, bad, {"ao"}), std::invalid_argument);
    // Rendering before prepare() is an error for representations that read bakes.
    render::Representations r(w.desc, *w.rt, s, {"irradiance-sh9", "ao"});
    CHECK(r.names().size() == 2);
    CHECK_NOTHROW(r.render(0, camera_at({0, -3, 1}, {0, 0, 0.3}, 4, 4), 1));
    CHECK_THROWS_AS(r.render(1, camera_at({0, -3, 1}, {0, 0, 0.3}, 4, 4), 1), std::runtime_error);
    CHECK_THROWS_AS(r.render(2, camera_at({0, -3, 1}, {0, 0, 0.3}, 4, 4), 1),
                    std::invalid_argument);
}

TEST_CASE("representations: the bake plan reads only what is requested", "[render]") {
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({1, 1, 1});
    w.build();
    render::RepresentationSettings s;
    s.rays = 16;
    s.lightmap_size = 8;
    {
        render::Representations r(w.desc, *w.rt, s, {"irradiance-sh9", "irradiance-sh9-windowed"});
        CHECK(r.bakes().empty());
    }
    {
        // ao and bent share one bake per mesh; prt-vertex adds one per mesh.
        render::Representations r(w.desc, *w.rt, s, {"ao", "bent", "prt-vertex"});
        REQUIRE(r.bakes().size() == 4);
        CHECK(r.bakes()[0].where == render::BakeRequest::Where::texel);
        CHECK(r.bakes()[2].where == render::BakeRequest::Where::vertex);
        CHECK_FALSE(r.bakes()[0].lighting_dependent);
        CHECK(r.bakes()[2].settings.quantities == render::Quantity::transfer);
        using V = std::vector<std::size_t>;
        CHECK(r.reads(0) == V{0, 1});  // ao
        CHECK(r.reads(1) == V{0, 1});  // bent: the same bakes
        CHECK(r.reads(2) == V{2, 3});  // prt-vertex
        CHECK_THROWS_AS(r.reads(3), std::invalid_argument);
    }
    {
        render::Representations r(w.desc, *w.rt, s, {"irradiance-sh9"});
        CHECK(r.reads(0).empty());
    }
    {
        render::Representations r(w.desc, *w.rt, s, {"lightmap-hl2", "volume"});
        REQUIRE(r.bakes().size() == 3);
        for (const auto& q : r.bakes()) CHECK(q.lighting_dependent);
        CHECK(r.bakes()[0].settings.basis == "hl2");
        CHECK(r.bakes()[0].settings.coeffs == 3);
        CHECK(r.bakes()[2].where == render::BakeRequest::Where::probes);
        CHECK(r.bakes()[2].probes.size() == 64);
    }
}

TEST_CASE("representations: irradiance-sh9 of a lone sphere under a constant sky is albedo L",
          "[render]") {
    World w = lone_sphere(12, 24, 0.6f);
    w.desc.environment = sphbasis_test::constant_environment({0.7, 0.8, 0.9});
    w.build();
    render::RepresentationSettings s;
    render::Representations r(w.desc, *w.rt, s,
                              {"irradiance-sh9", "irradiance-sh9-windowed", "volume"});
    r.prepare(nullptr);
    const Camera cam = camera_at({0, -4, 1}, {0, 0, 0}, 16, 16);
    for (std::size_t k = 0; k < 2; ++k) {
        for (int spp : {1, 3}) {
            const Image img = r.render(k, cam, spp);
            const render::PinholeCamera pc(cam);
            int hits = 0;
            for (int y = 0; y < 16; ++y)
                for (int x = 0; x < 16; ++x) {
                    const float* p = img.at(x, y);
                    // Object pixels: 0.6 L; background: L; spp > 1 edge pixels mix both.
                    const auto ray = pc.ray(x + 0.5, y + 0.5);
                    const bool hit = w.rt->intersect(ray.origin, ray.direction).valid;
                    if (spp == 1 || hit) {
                        const double a = hit ? 0.6 : 1.0;
                        if (spp > 1) continue;
                        hits += hit;
                        CHECK(p[0] == Approx(a * 0.7).epsilon(1e-5));
                        CHECK(p[1] == Approx(a * 0.8).epsilon(1e-5));
                        CHECK(p[2] == Approx(a * 0.9).epsilon(1e-5));
                    }
                }
            if (spp == 1) CHECK(hits > 50);
        }
    }
    CHECK(all_finite(r.render(2, cam, 1)));
    CHECK(r.stats(0).element == "none");
    CHECK(r.stats(0).bytes_per_element == 0);
    CHECK(r.stats(2).element == "probe");
    CHECK(r.stats(2).elements == 64);
}

TEST_CASE("representations: irradiance-sh9 under analytic lights against the analytic normal",
          "[render]") {
    const double albedo = 0.8;
    World w = lone_sphere(32, 64, float(albedo));
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = {0.3, -0.2, 0.9};
    hemi.color = {1.0, 0.6, 0.3};
    hemi.ground = {0.1, 0.2, 0.4};
    const Light sun = sphbasis_test::directional_light({-0.4, -0.5, 0.7}, {2.0, 2.0, 1.5});
    const Camera cam = camera_at({0, -4, 0.5}, {0, 0, 0}, 16, 16, 35);
    const render::PinholeCamera pc(cam);
    for (int which = 0; which < 2; ++which) {
        const Light light = which == 0 ? hemi : sun;
        w.desc.lights = {light};
        w.build();
        render::Representations r(w.desc, *w.rt, render::RepresentationSettings{},
                                  {"irradiance-sh9"});
        r.prepare(nullptr);
        const Image img = r.render(0, cam, 1);
        int compared = 0;
        double worst = 0, worst_exact = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const auto ray = pc.ray(x + 0.5, y + 0.5);
                const render::Hit hit = w.rt->intersect(ray.origin, ray.direction);
                if (!hit.valid) continue;
                // The analytic hit of the unit sphere.
                const auto& o = ray.origin;
                const auto& d = ray.direction;
                const double b = dot(o, d), c = dot(o, o) - 1, disc = b * b - c;
                if (disc <= 0) continue;
                const double t = -b - std::sqrt(disc);
                vec3<double> n{o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
                const double len = std::sqrt(dot(n, n));
                n = {n.x / len, n.y / len, n.z / len};
                const vec3<double> l = render::detail::unit_or_pole(light.direction);
                const double cs = dot(n, l);
                const RGB exact = render::light_irradiance(light, n);
                // At the mesh's own shading normal the closed form holds to rounding.
                const double cm = dot(hit.shading_normal, l);
                const RGB exact_mesh = render::light_irradiance(light, hit.shading_normal);
                for (std::size_t k = 0; k < 3; ++k) {
                    const double e3 = 0.25 + 0.5 * cm + 5.0 / 16.0 * (3 * cm * cm - 1) / 2;
                    const double expect =
                        albedo / constants::pi * (which == 0 ? exact_mesh[k] : light.color[k] * e3);
                    CHECK(img.at(x, y)[k] == Approx(expect).margin(1e-6).epsilon(1e-5));
                }
                for (std::size_t k = 0; k < 3; ++k) {
                    double expect;
                    if (which == 0) {
                        // A hemisphere light's irradiance has bands 0 and 1 only: exact in SH9.
                        expect = albedo / constants::pi * exact[k];
                    } else {
                        // The clamped cosine truncated to 3 bands: sum a_l (2l+1)/4 P_l(cos).
                        const double e3 = 0.25 + 0.5 * cs + 5.0 / 16.0 * (3 * cs * cs - 1) / 2;
                        expect = albedo / constants::pi * light.color[k] * e3;
                        worst_exact = std::max(
                            worst_exact,
                            std::fabs(img.at(x, y)[k] - albedo / constants::pi * exact[k]) /
                                (albedo / constants::pi * light.color[k]));
                    }
                    const double scale = albedo / constants::pi * light.color[k];
                    worst = std::max(worst, std::fabs(img.at(x, y)[k] - expect) / scale);
                }
                ++compared;
            }
        CHECK(compared > 80);
        // The tessellated sphere's interpolated normals differ from the analytic ones by a
        // fraction of a degree (measured 8e-3 and 3e-3 of the light's scale at 32 x 64).
        CHECK(worst < 1.5e-2);
        // SH9's clamped cosine is within 0.0938 of the exact one (at the horizon).
        if (which == 1) CHECK(worst_exact < 0.095);
    }
}

TEST_CASE("representations: under a constant sky prt equals ao times the sky", "[render]") {
    for (bool uvs : {true, false}) {
        World w = sphere_on_plane(uvs);
        w.desc.environment = sphbasis_test::constant_environment({0.9, 0.7, 0.5});
        w.build();
        const render::RepresentationSettings s = settings(64, 0, 16);
        render::Representations r(w.desc, *w.rt, s, {"ao", uvs ? "prt-texel" : "prt-vertex"});
        r.prepare(nullptr);
        CHECK(r.bakes_run() == 4);
        const Camera cam = camera_at({0, -3, 1.5}, {0, 0, 0.3}, 16, 16);
        const Image ao = r.render(0, cam, 1);
        const Image prt = r.render(1, cam, 1);
        CHECK(max_abs_diff(ao, prt) < 2e-5 * max_abs(ao));
        // Occlusion is visible: the plane under the sphere is darker than the sky times albedo.
        double lo = 1e9;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) lo = std::min(lo, double(ao.at(x, y)[0]));
        CHECK(lo < 0.5 * 0.9 * 0.9);
        const auto st = r.stats(1);
        CHECK(st.element == (uvs ? "texel" : "vertex"));
        CHECK(st.bytes_per_element == 9 * 4);
        CHECK(st.bake_rays > 0);
        CHECK(r.stats(0).bytes_per_element == 4);
    }
}

TEST_CASE("representations: render-time rotation of prt equals re-baking with rotated lighting",
          "[render]") {
    const std::vector<float> tex = latlong_texels(8, 4);
    const Mat3<double> R = rotation(0.7, 0.4);
    const Light sun = sphbasis_test::directional_light({0.3, -0.4, 0.8}, {1.5, 1.2, 1.0});
    auto make = [&](bool rotate_scene) {
        World w = sphere_on_plane(true);
        Environment e = sphbasis_test::latlong_environment(tex, 8, 4);
        Light l = sun;
        if (rotate_scene) {
            e.rotation = R;
            l.direction = mat_apply(R, sun.direction);
        }
        w.desc.environment = e;
        w.desc.lights = {l};
        w.build();
        return w;
    };
    World a = make(false), b = make(true);
    const render::RepresentationSettings s = settings(32, 1, 8);
    render::RepresentationSettings sa = s;
    sa.lighting_rotation = R;
    const std::vector<std::string> names{"prt-vertex", "prt-texel", "irradiance-sh9"};
    render::MemoryBakeCache cache;
    render::Representations ra(a.desc, *a.rt, sa, names);
    ra.prepare(&cache);
    CHECK(ra.bakes_run() == 4);
    CHECK(ra.bakes_loaded() == 0);
    // Re-baked from scratch with the rotated lighting, and from the warm cache.
    render::Representations rb(b.desc, *b.rt, s, names);
    rb.prepare(nullptr);
    CHECK(rb.bakes_run() == 4);
    render::Representations rc(b.desc, *b.rt, s, names);
    rc.prepare(&cache);
    CHECK(rc.bakes_run() == 0);
    CHECK(rc.bakes_loaded() == 4);
    CHECK(rc.stats(0).cached);
    CHECK_FALSE(ra.stats(0).cached);
    const Camera cam = camera_at({0, -3, 1.5}, {0, 0, 0.3}, 16, 16);
    for (std::size_t k = 0; k < names.size(); ++k) {
        const Image ia = ra.render(k, cam, 1), ib = rb.render(k, cam, 1), ic = rc.render(k, cam, 1);
        INFO(names[k]);
        CHECK(max_abs(ia) > 0.05);
        CHECK(max_abs_diff(ia, ib) < 1e-4 * max_abs(ia));
        CHECK(max_abs_diff(ib, ic) == 0);
    }
    // Without the render-time rotation the image differs (the test can fail).
    render::Representations rn(a.desc, *a.rt, s, names);
    rn.prepare(&cache);
    CHECK(rn.bakes_run() == 0);
    CHECK(max_abs_diff(rn.render(0, cam, 1), ra.render(0, cam, 1)) > 1e-2);
}

TEST_CASE("representations: a changed light re-bakes lightmaps, not the PRT transfer", "[render]") {
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({0.3, 0.3, 0.3});
    const Light sun = sphbasis_test::directional_light({0.3, -0.4, 0.8}, {1.5, 1.2, 1.0});
    w.desc.lights = {sun};
    w.build();
    const render::RepresentationSettings s = settings(8, 1, 4);
    const std::vector<std::string> names{"prt-texel", "lightmap-sh4", "ao"};
    render::MemoryBakeCache cache;
    {
        render::Representations r(w.desc, *w.rt, s, names);
        r.prepare(&cache);
        CHECK(r.bakes_run() == 6);
    }
    {
        render::Representations r(w.desc, *w.rt, s, names);
        r.prepare(&cache);
        CHECK(r.bakes_run() == 0);
        CHECK(r.bakes_loaded() == 6);
    }
    w.desc.lights[0].direction = {-0.5, 0.2, 0.7};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(&cache);
    CHECK(r.bakes_run() == 2);  // the two lightmaps
    CHECK(r.bakes_loaded() == 4);
    CHECK(r.stats(0).cached);
    CHECK_FALSE(r.stats(1).cached);
    CHECK(r.stats(2).cached);
    // A changed albedo re-bakes what has bounces (transfer, lightmaps), not ao.
    w.meshes[1].albedo = {0.2f, 0.2f, 0.2f};
    w.build();
    render::Representations r2(w.desc, *w.rt, s, names);
    r2.prepare(&cache);
    CHECK(r2.bakes_run() == 4);
    CHECK(r2.bakes_loaded() == 2);
}

TEST_CASE("representations: lightmaps of an unoccluded quad under a constant sky", "[render]") {
    World w;
    w.meshes.push_back(sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1));
    w.meshes[0].albedo = {0.8f, 0.8f, 0.8f};
    w.desc.environment = sphbasis_test::constant_environment({1.0, 0.5, 0.25});
    w.build();
    const render::RepresentationSettings s = settings(256, 0, 4);
    std::vector<std::string> names;
    for (const auto& n : render::representation_names())
        if (n.rfind("lightmap-", 0) == 0) names.push_back(n);
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    const Camera cam = camera_at({0.1, 0.2, 3}, {0, 0, 0}, 8, 8, 25);
    const DirectionalRule rule = hemisphere_rule_sqrt(32, 32);
    const double fb = sphbasis_test::fit_at_z("ambient-dice-bezier", 30, rule);
    const double fl = sphbasis_test::fit_at_z("ambient-dice-linear", 10, rule);
    for (std::size_t k = 0; k < names.size(); ++k) {
        INFO(names[k]);
        const Image img = r.render(k, cam, 1);
        REQUIRE(all_finite(img));
        // E(z) = pi L over the upper hemisphere: the pixel is albedo L. The bake fits the sky's
        // E(n') = pi L (1 + cos)/2 over the tangent hemisphere: bases whose span holds 1 and
        // cos(theta) reproduce it up to the bake's quadrature noise (measured 0.5% at 256 rays,
        // 4% at 64, 0.13% at 1024). HL2 spans only x, y, z: the least-squares fit of (1 + z)/2
        // is beta z with beta = <(1+z)/2, z> / <z, z> = (pi/2 + pi/3) / (2 pi/3) = 5/4.
        // The hemispherical ambient cube spans 1 and z^2 along the normal (alpha (1 - z^2) +
        // beta z^2): the fit of (1 + z)/2 in {1, z^2} with the measure dz has a + b = 17/16 at
        // z = 1. Ambient Dice spans 1 and reproduces it to 0.11% (numerical least squares).
        // ZH3 holds E's SH exactly (E is linear in z: band 2 vanishes). Non-linear L1: with
        // R0 = pi L / 2 and r = |R1| / R0 = 1/2, p = 2, a = 1/3, f(+z) = R0 (a + (1 - a) 3) =
        // (7/3) R0 = (7/6) E. ZH3 hallucinated: the radiance ratio r = sqrt(3)/2 gives
        // z = E_00 (0.08 r + 0.6 r^2) / 4, adding 2 z sqrt(5/(16 pi)) = E sqrt(5)/8 (0.08 r +
        // 0.6 r^2) at +z. SG lobes: their least-squares fit of (1 + z)/2 (sg_fit_factor()).
        // Ambient Dice over the faces (-bezier30, -linear10, and -ycocg's luma and chroma): the
        // value at +z of their least-squares fit (fb, fl).
        const double rh = std::sqrt(3.0) / 2;
        const double factor = names[k] == "lightmap-hl2"               ? 1.25
                              : names[k] == "lightmap-ambient-cube5"   ? 17.0 / 16.0
                              : names[k] == "lightmap-sh-l1-nonlinear" ? 7.0 / 6.0
                              : names[k] == "lightmap-zh3-hallucinate"
                                  ? 1 + std::sqrt(5.0) / 8 * (0.08 * rh + 0.6 * rh * rh)
                              : names[k].rfind("lightmap-sg", 0) == 0 ? sg_fit_factor(names[k])
                              : names[k] == "lightmap-ambient-dice-bezier30" ? fb
                              : names[k] == "lightmap-ambient-dice-linear10" ? fl
                                                                             : 1.0;
        const RGB sky{1.0, 0.5, 0.25};
        RGB want{0.8 * sky[0] * factor, 0.8 * sky[1] * factor, 0.8 * sky[2] * factor};
        if (names[k] == "lightmap-ambient-dice-ycocg") {
            const auto v = render::rgb_to_ycocg(sky[0], sky[1], sky[2]);
            want = render::ycocg_to_rgb(fb * v[0], fl * v[1], fl * v[2]);
            for (double& c : want) c *= 0.8;
        }
        double worst = 0;
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x)
                for (std::size_t c = 0; c < 3; ++c)
                    worst = std::max(worst, std::fabs(img.at(x, y)[c] / want[c] - 1));
        CHECK(worst < 0.015);
        CHECK(r.stats(k).element == "texel");
        CHECK(r.stats(k).elements == 16);
    }
}

TEST_CASE("representations: every representation renders finite values", "[render]") {
    World w = sphere_on_plane(true);
    const std::vector<float> tex = latlong_texels(8, 4);
    Environment e = sphbasis_test::latlong_environment(tex, 8, 4);
    w.desc.environment = e;
    w.build();
    const render::RepresentationSettings s = settings(8, 1, 4);
    std::vector<std::string> names;
    for (const auto& n : render::representation_names())
        if (n.rfind("specular", 0) != 0) names.push_back(n);
    render::Representations r(w.desc, *w.rt, s, names);
    std::uint64_t last = 0, total = 0;
    r.prepare(nullptr, [&](std::uint64_t d, std::uint64_t t) {
        last = std::max(last, d);
        total = t;
    });
    CHECK(last == total);
    CHECK(total > 0);
    const Camera cam = camera_at({0, -3, 1.5}, {0, 0, 0.3}, 8, 8);
    for (std::size_t k = 0; k < names.size(); ++k) {
        INFO(names[k]);
        const Image img = r.render(k, cam, 1);
        CHECK(all_finite(img));
        CHECK(max_abs(img) > 0);
        const auto st = r.stats(k);
        CHECK(st.name == names[k]);
        CHECK_FALSE(st.cannot_show.empty());
        // Requested alone it plans its own inputs (lighting SH, clamped-cosine factors, bakes)
        // and renders the same image as in the group.
        render::Representations alone(w.desc, *w.rt, s, {names[k]});
        alone.prepare(nullptr);
        const Image a = alone.render(0, cam, 1);
        CHECK(a.data == img.data);
    }
}

TEST_CASE("representations: bake records round-trip and reject bad bytes", "[render]") {
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({1, 1, 1});
    w.build();
    const render::RepresentationSettings s = settings(8, 1, 4);
    render::Representations r(w.desc, *w.rt, s,
                              {"bent", "prt-vertex", "lightmap-hbasis6", "volume"});
    r.prepare(nullptr);
    for (std::size_t i = 0; i < r.bakes().size(); ++i) {
        const render::BakeData& d = r.bake_data(i);
        const std::vector<std::uint8_t> bytes = render::serialize(d);
        const render::BakeData back = render::deserialize(bytes);
        CHECK(back.from_cache);
        CHECK(render::serialize(back) == bytes);
        CHECK(back.results.size() == d.results.size());
        CHECK(back.layout.samples.size() == d.layout.samples.size());
        CHECK(back.rays == d.rays);
        if (!d.results.empty()) {
            CHECK(back.results[0].ao == d.results[0].ao);
            CHECK(back.results[0].transfer[1] == d.results[0].transfer[1]);
            CHECK(back.results[0].irradiance[2] == d.results[0].irradiance[2]);
            CHECK(back.results[0].radiance[0] == d.results[0].radiance[0]);
        }
        // Every truncation throws std::runtime_error (a prefix sample keeps the test fast).
        const std::size_t step = std::max<std::size_t>(1, bytes.size() / 97);
        for (std::size_t n = 0; n < bytes.size(); n += step) {
            const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(n));
            CHECK_THROWS_AS(render::deserialize(cut), std::runtime_error);
        }
        std::vector<std::uint8_t> cut(bytes.begin(), bytes.end() - 1);
        CHECK_THROWS_AS(render::deserialize(cut), std::runtime_error);
        std::vector<std::uint8_t> more = bytes;
        more.push_back(0);
        CHECK_THROWS_WITH(render::deserialize(more), Catch::Contains("trailing"));
        std::vector<std::uint8_t> foreign = bytes;
        foreign[0] = 'X';
        CHECK_THROWS_WITH(render::deserialize(foreign), Catch::Contains("magic"));
        std::vector<std::uint8_t> version = bytes;
        version[8] = 99;
        CHECK_THROWS_WITH(render::deserialize(version), Catch::Contains("version"));
    }
}

TEST_CASE("representations: bake_key depends on exactly what a bake reads", "[render]") {
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({1, 1, 1});
    w.build();
    render::BakeRequest q;
    q.settings.quantities = render::Quantity::transfer;
    q.settings.bounces = 0;
    const std::uint64_t k0 = render::bake_key(w.desc, q);
    CHECK(render::bake_key(w.desc, q) == k0);
    render::SceneDesc lit = w.desc;
    lit.environment.constant = {2, 2, 2};
    CHECK(render::bake_key(lit, q) == k0);  // not lighting-dependent
    render::BakeRequest ql = q;
    ql.lighting_dependent = true;
    CHECK(render::bake_key(lit, ql) != render::bake_key(w.desc, ql));
    lit = w.desc;
    lit.environment.rotation = rotation(0.3, 0.1);
    CHECK(render::bake_key(lit, ql) != render::bake_key(w.desc, ql));
    // Albedo only with bounces.
    World w2 = sphere_on_plane(true);
    w2.meshes[1].albedo = {0.1f, 0.1f, 0.1f};
    w2.desc.environment = w.desc.environment;
    w2.build();
    CHECK(render::bake_key(w2.desc, q) == k0);
    render::BakeRequest qb = q;
    qb.settings.bounces = 2;
    CHECK(render::bake_key(w2.desc, qb) != render::bake_key(w.desc, qb));
    // Geometry, settings and the mesh index always.
    World w3 = sphere_on_plane(true);
    w3.meshes[0].positions[5] += 1e-3f;
    w3.desc.environment = w.desc.environment;
    w3.build();
    CHECK(render::bake_key(w3.desc, q) != k0);
    render::BakeRequest qs = q;
    qs.settings.rays = 17;
    CHECK(render::bake_key(w.desc, qs) != k0);
    qs = q;
    qs.mesh = 1;
    CHECK(render::bake_key(w.desc, qs) != k0);
    // Adaptive sampling: equal settings, equal keys; any target or the ray cap changed, another.
    render::BakeRequest qa = q;
    qa.settings.adaptive[render::Quantity::transfer] = 0.01;
    qa.settings.adaptive.max_rays = 4096;
    render::BakeRequest qa2 = q;
    qa2.settings.adaptive = qa.settings.adaptive;
    const std::uint64_t ka = render::bake_key(w.desc, qa);
    CHECK(render::bake_key(w.desc, qa2) == ka);
    CHECK(ka != k0);
    qa2.settings.adaptive.max_rays = 2048;
    CHECK(render::bake_key(w.desc, qa2) != ka);
    qa2 = qa;
    qa2.settings.adaptive[render::Quantity::transfer] = 0.02;
    CHECK(render::bake_key(w.desc, qa2) != ka);
    qa2 = qa;
    qa2.settings.adaptive[render::Quantity::ao] = 0.01;  // a quantity it does not bake: still
    CHECK(render::bake_key(w.desc, qa2) != ka);          // other settings
    // High to low: the projections (target, source, ray distance, cage) enter the key.
    render::HighToLowSettings hs;
    hs.target = 0;
    hs.source = 1;
    const std::uint64_t h = render::high_to_low_key(w.desc, {hs});
    CHECK(render::high_to_low_key(w.desc, {}) == 0);
    CHECK(h != 0);
    CHECK(render::high_to_low_key(w.desc, {hs}) == h);
    render::BakeRequest qh = q;
    qh.high_to_low = h;
    const std::uint64_t kh = render::bake_key(w.desc, qh);
    CHECK(kh != k0);
    qh.high_to_low = render::high_to_low_key(w.desc, {hs});
    CHECK(render::bake_key(w.desc, qh) == kh);
    render::HighToLowSettings other = hs;
    other.max_ray_distance = 0.5;
    CHECK(render::high_to_low_key(w.desc, {other}) != h);
    std::vector<float> cage = w.meshes[0].positions;
    other = hs;
    other.cage_positions = cage.data();
    const std::uint64_t hc = render::high_to_low_key(w.desc, {other});
    CHECK(hc != h);
    cage[4] += 1e-3f;
    CHECK(render::high_to_low_key(w.desc, {other}) != hc);
    other = hs;
    other.source = 0;
    other.target = 1;
    CHECK(render::high_to_low_key(w.desc, {other}) != h);
    CHECK(render::high_to_low_key(w.desc, {hs, other}) != h);
    // Both survive the cache file: the key recomputed from a loaded request is the stored one.
    render::BakeData d;
    d.request = qa;
    d.request.high_to_low = h;
    const render::BakeData back = render::deserialize(render::serialize(d));
    CHECK(back.request.settings.adaptive.max_rays == 4096);
    CHECK(back.request.settings.adaptive[render::Quantity::transfer] == 0.01);
    CHECK(back.request.high_to_low == h);
    CHECK(render::bake_key(w.desc, back.request) == render::bake_key(w.desc, d.request));
}

TEST_CASE("representations: the windowed SH9 irradiance of a sun is non-negative", "[render]") {
    // SH9's clamped cosine of a delta light is 1/4 + c/2 + 5/32 (3c^2 - 1), whose minimum
    // -0.0396 (at c = -8/15) rings below zero; Sloan's window removes it.
    World w = lone_sphere(16, 32, 0.8f);
    Light sun;
    sun.direction = {0, 1, 0.2};
    sun.color = {1, 1, 1};
    w.desc.lights = {sun};
    w.build();
    render::Representations r(w.desc, *w.rt, render::RepresentationSettings{},
                              {"irradiance-sh9", "irradiance-sh9-windowed"});
    r.prepare(nullptr);
    // Seen from the side away from the sun, where the ringing is.
    const Camera cam = camera_at({0, -4, 0}, {0, 0, 0}, 16, 16);
    const Image plain = r.render(0, cam, 1), windowed = r.render(1, cam, 1);
    double lo_plain = 0, lo_windowed = 0;
    for (std::size_t i = 0; i < plain.data.size(); ++i) {
        lo_plain = std::min(lo_plain, double(plain.data[i]));
        lo_windowed = std::min(lo_windowed, double(windowed.data[i]));
    }
    CHECK(lo_plain < -0.8 / constants::pi * 0.03);
    CHECK(lo_windowed >= -1e-7);
}

TEST_CASE("representations: lightmap texels sit where the UVs say (texel ao against vertex ao)",
          "[render]") {
    // An off-centre sphere over a finely tessellated plane: the contact shadow read from the
    // lightmap must fall where the per-vertex bake puts it (a mirrored v would move it).
    auto make = [](bool uvs) {
        World w;
        w.meshes.push_back(render::shapes::sphere({0.5, 0.3, 0.55}, 0.5, 8, 16));
        w.meshes.push_back(sphbasis_test::quad_grid(-1.5, 1.5, -1.5, 1.5, 0, 24));
        if (!uvs) strip_uvs(w);
        w.desc.environment = sphbasis_test::constant_environment({1, 1, 1});
        w.build();
        return w;
    };
    World a = make(true), b = make(false);
    const render::RepresentationSettings s = settings(64, 0, 32);
    render::Representations ra(a.desc, *a.rt, s, {"ao"}), rb(b.desc, *b.rt, s, {"ao"});
    ra.prepare(nullptr);
    rb.prepare(nullptr);
    CHECK(ra.stats(0).element == "texel");
    CHECK(rb.stats(0).element == "vertex");
    const Camera cam = camera_at({0.2, 0, 5}, {0.2, 0, 0}, 24, 24, 30);
    const Image ia = ra.render(0, cam, 1), ib = rb.render(0, cam, 1);
    double diff = 0, dark = 0;
    for (std::size_t i = 0; i < ia.data.size(); i += 3) {
        diff += std::fabs(double(ia.data[i]) - double(ib.data[i]));
        dark += 0.5 - double(ib.data[i]);  // albedo 0.5: the occluded part
    }
    CHECK(dark > 0);
    CHECK(diff < 0.25 * dark);
}

TEST_CASE("representations: a render's bakes are the bake command's, bit for bit",
          "[render][bake]") {
    // The same settings and points (render/bake_points.hpp: one id scheme, one tangent rule)
    // give the same samples: what `sphbasis render` bakes for a request equals what
    // `sphbasis bake` (a Baker over vertex_points / texel_layout of the whole scene) bakes.
    World w = sphere_on_plane(true);
    w.desc.environment = sphbasis_test::constant_environment({0.4, 0.5, 0.6});
    w.build();
    render::RepresentationSettings s = settings(16, 1, 8);
    s.seed = 11;
    const std::vector<std::string> names{"ao", "prt-texel", "lightmap-hbasis4"};
    render::Representations r(w.desc, *w.rt, s, names);
    r.prepare(nullptr);
    REQUIRE(r.bakes().size() >= 4);
    std::size_t compared = 0;
    for (std::size_t i = 0; i < r.bakes().size(); ++i) {
        const render::BakeRequest& q = r.bakes()[i];
        if (q.where == render::BakeRequest::Where::probes) continue;
        std::vector<render::BakePoint> pts;
        render::LightmapLayout layout;
        if (q.where == render::BakeRequest::Where::vertex) {
            pts = render::vertex_points(w.desc.meshes, q.mesh);
        } else {
            layout = render::texel_layout(w.desc.meshes, q.mesh, q.lightmap_size);
            pts = render::texel_points(layout);
        }
        render::Baker baker(w.desc, q.settings);  // its own BVH, as the command builds
        const std::vector<render::PointResult> want = baker.bake(pts);
        const std::vector<render::PointResult>& got = r.bake_data(i).results;
        INFO("bake " << i << " of mesh " << q.mesh);
        REQUIRE(got.size() == want.size());
        for (std::size_t k = 0; k < got.size(); ++k) {
            CHECK(got[k].ao == want[k].ao);
            CHECK(got[k].bent.z == want[k].bent.z);
            for (std::size_t c = 0; c < 3; ++c) {
                CHECK(got[k].transfer[c] == want[k].transfer[c]);
                CHECK(got[k].irradiance[c] == want[k].irradiance[c]);
            }
        }
        ++compared;
    }
    CHECK(compared >= 4);
}
