// Tests for render/path_tracer.hpp against closed forms: a lone convex sphere under a constant
// sky (albedo times the sky at every bounce count), under a sun (albedo/pi E max(n.l, 0) with n
// from the analytic sphere), a sphere over a plane (the shadowed point sees the sky minus the
// sphere's cap; a lit point adds the sun), a white furnace in an open box (albedo 1, unbounded
// bounces: 1 everywhere), a tilted normal map and the Blinn-Phong lobe under a sun, the MIS
// irradiance of a lat-long map against quadrature, convergence (error halves when samples
// quadruple), determinism across thread counts, the counters of work not called for, and the
// cosine lobe's generated polynomial cos/sin (max error) and its vectorised batch form.
#include <tbb/task_arena.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <memory>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/core/constants.hpp"
#include "sphbasis/render/path_tracer.hpp"
#include "sphbasis/render/shapes.hpp"

namespace render = sphbasis::render;
using render::Camera;
using render::Environment;
using render::Light;
using render::Mesh;
using render::PathTracer;
using render::RGB;
using render::Scene;
using render::TraceSettings;
using sphbasis::vec3;
namespace constants = sphbasis::constants;

namespace {

using sphbasis_test::unit;

Environment constant_sky(double L) { return sphbasis_test::constant_environment({L, L, L}); }

Light sun(vec3<double> d, double E) { return sphbasis_test::directional_light(d, {E, E, E}); }

std::unique_ptr<Scene> make_scene(const std::vector<Mesh>& meshes) {
    std::vector<render::MeshView> views;
    for (const auto& m : meshes) views.push_back(m.view());
    return std::make_unique<Scene>(views);
}

/// Mean and standard error of n radiance() estimates (channel 0) along one ray.
struct Estimate {
    double mean = 0, se = 0;
};
Estimate estimate(const PathTracer& t, vec3<double> o, vec3<double> d, int n,
                  std::uint64_t pixel = 0) {
    double s = 0, q = 0;
    for (int i = 0; i < n; ++i) {
        const double v = t.radiance(o, d, pixel, std::uint64_t(i))[0];
        s += v;
        q += v * v;
    }
    Estimate e;
    e.mean = s / n;
    e.se = std::sqrt(std::max(0.0, q / n - e.mean * e.mean) / (n - 1));
    return e;
}

using sphbasis_test::camera_at;
using sphbasis_test::latlong_environment;
using sphbasis_test::rmse;

/// The scene of the image tests: a ball of radius 0.6 resting on a 10 x 10 plane at z = 0.
std::unique_ptr<Scene> ball_on_plane(int rings, int segments) {
    return make_scene({render::shapes::sphere({0, 0, 0.6}, 0.6, rings, segments),
                       sphbasis_test::quad_grid(-5, 5, -5, 5, 0, 1)});
}
/// A w x h camera looking down at ball_on_plane().
Camera ball_camera(int w, int h, double fov = 35) {
    return camera_at({2.5, -2.5, 1.8}, {0, 0, 0.4}, w, h, fov);
}

/// Integral of g(w) over the hemisphere z > 0 by 256 x 512 midpoint cells, uniform in z = cos
/// theta and phi.
template <class G>
double hemisphere_integral(G&& g) {
    double sum = 0;
    const int nt = 256, np = 512;
    for (int a = 0; a < nt; ++a)
        for (int b = 0; b < np; ++b) {
            const double z = (a + 0.5) / nt, phi = 2 * constants::pi * (b + 0.5) / np;
            const double rr = std::sqrt(1 - z * z);
            sum += g(vec3<double>{rr * std::cos(phi), rr * std::sin(phi), z});
        }
    return sum * (2 * constants::pi / (double(nt) * np));
}

/// Analytic ray-sphere hit: the unit normal at the near intersection (false on a miss).
bool sphere_normal(vec3<double> o, vec3<double> d, vec3<double> c, double r, vec3<double>& n) {
    const vec3<double> oc{o.x - c.x, o.y - c.y, o.z - c.z};
    const double b = sphbasis::dot(oc, d), cc = sphbasis::dot(oc, oc) - r * r;
    const double disc = b * b - cc;
    if (disc < 0) return false;
    const double t = -b - std::sqrt(disc);
    n = unit({o.x + t * d.x - c.x, o.y + t * d.y - c.y, o.z + t * d.z - c.z});
    return true;
}

}  // namespace

TEST_CASE("PathTracer: a lone sphere under a constant sky is albedo times the sky",
          "[render][path_tracer]") {
    Mesh m = render::shapes::sphere({0, 0, 0}, 1, 48, 96);
    m.albedo = {0.5f, 0.25f, 0.75f};
    const auto scene = make_scene({m});
    const double L = 2;
    for (int bounces : {0, 2, -1}) {
        TraceSettings s;
        s.bounces = bounces;
        s.spp_min = s.spp_max = 4;
        s.target_noise = 0;
        PathTracer t(*scene, constant_sky(L), {}, s);
        const auto r = t.render(camera_at({0, -4, 0}, {0, 0, 0}, 16, 16, 40));
        int inside = 0;
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 16; ++x) {
                const float* c = r.color.at(x, y);
                const float cov = r.coverage.at(x, y)[0];
                if (cov == 1) {
                    ++inside;
                    // Convex: every BRDF sample escapes and carries f cos / pdf = albedo. A few
                    // samples leave below the facet (interpolated normals): under 1%.
                    CHECK(c[0] == Approx(0.5 * L).epsilon(1e-2));
                    CHECK(c[1] == Approx(0.25 * L).epsilon(1e-2));
                    CHECK(c[2] == Approx(0.75 * L).epsilon(1e-2));
                } else if (cov == 0) {
                    CHECK(c[0] == Approx(L));
                }
            }
        CHECK(inside > 60);
        CHECK(r.counters.camera_rays == 16u * 16u * 4u);
        CHECK(r.counters.environment_samples == 0);  // a constant sky: the BRDF sample only
        if (bounces == 0) CHECK(r.counters.bounce_rays == 0);
        if (bounces != 0) CHECK(r.counters.bounce_rays > 0);
    }
}

TEST_CASE("PathTracer: a sphere under a sun, albedo/pi E max(n.l, 0)", "[render][path_tracer]") {
    Mesh m = render::shapes::sphere({0, 0, 0}, 1, 48, 96);
    m.albedo = {0.8f, 0.8f, 0.8f};
    const auto scene = make_scene({m});
    const vec3<double> l = unit({0.3, -0.8, 0.5});
    const double E = 3;
    TraceSettings s;
    s.bounces = 2;  // convex: bounce rays escape into a black sky
    PathTracer t(*scene, Environment{}, {sun(l, E)}, s);
    const vec3<double> o{0.2, -4, 0.1};
    for (int k = 0; k < 25; ++k) {
        const vec3<double> d = unit({-0.05 + 0.06 * (k % 5 - 2), 1, 0.06 * (k / 5 - 2)});
        vec3<double> n{0, 0, 1};
        REQUIRE(sphere_normal(o, d, {0, 0, 0}, 1, n));
        const double expect = 0.8 / constants::pi * E * std::max(0.0, sphbasis::dot(n, l));
        const RGB v = t.radiance(o, d, 0, std::uint64_t(k));
        CHECK(v[0] == Approx(expect).margin(2e-3));
    }
    // One bounce ray a path: it escapes into the black sky (convex), so no second one.
    CHECK(t.counters().bounce_rays <= 25);
    CHECK(t.counters().bounce_rays >= 20);
    CHECK(t.counters().camera_rays == 25);
}

TEST_CASE("PathTracer: a sphere on a plane under a sun and a sky", "[render][path_tracer]") {
    const double r = 0.5, hc = 1.5;
    Mesh ball = render::shapes::sphere({0, 0, hc}, r, 48, 96);
    Mesh plane = sphbasis_test::quad_grid(-30, 30, -30, 30, 0, 1);
    plane.albedo = {0.6f, 0.6f, 0.6f};
    const auto scene = make_scene({ball, plane});
    const double L = 1, E = 4;
    TraceSettings s;
    s.bounces = 0;
    PathTracer t(*scene, constant_sky(L), {sun({0, 0, 1}, E)}, s);
    // The point below the ball: in the sun's shadow; the ball hides a cap of sin(a) = r / hc
    // straight above, pi sin^2(a) of the sky's pi.
    {
        const vec3<double> p{0, 0, 0}, o{3, 0.2, 0.4};
        const Estimate e = estimate(t, o, unit({p.x - o.x, p.y - o.y, p.z - o.z}), 4000);
        const double expect = 0.6 * L * (1 - (r / hc) * (r / hc));
        CHECK(std::fabs(e.mean - expect) < 4 * e.se + 4e-3);
    }
    // A lit point: the sun plus the sky minus the ball's cap (cap_cosine_integral).
    {
        const vec3<double> p{1.5, 0.5, 0}, o{4, -1, 0.6};
        const Estimate e = estimate(t, o, unit({p.x - o.x, p.y - o.y, p.z - o.z}), 4000, 1);
        const vec3<double> c{-p.x, -p.y, hc};
        const double dist = std::sqrt(sphbasis::dot(c, c));
        const double sin_a = r / dist, cos_a = std::sqrt(1 - sin_a * sin_a);
        const double hidden = render::detail::cap_cosine_integral(hc / dist, cos_a, sin_a * sin_a);
        const double expect = 0.6 / constants::pi * (E + L * (constants::pi - hidden));
        CHECK(std::fabs(e.mean - expect) < 4 * e.se + 4e-3);
    }
}

namespace {
/// The white furnace of an open box of albedo 1 under a constant sky of 1 with unbounded
/// bounces: rays into the box from above hit its floor and walls, and every estimate's mean is 1.
void check_box_furnace(Mesh box) {
    box.albedo = {1, 1, 1};
    const auto scene = make_scene({box});
    TraceSettings s;
    s.bounces = -1;
    PathTracer t(*scene, constant_sky(1), {}, s);
    const vec3<double> o{0.1, 0.2, 3};
    for (const vec3<double> target :
         {vec3<double>{0, 0, -1}, vec3<double>{0.9, -0.5, -1}, vec3<double>{1, 0.3, 0.2}}) {
        const Estimate e =
            estimate(t, o, unit({target.x - o.x, target.y - o.y, target.z - o.z}), 1500);
        CHECK(std::fabs(e.mean - 1) < 4 * e.se + 1e-3);
    }
    CHECK(t.counters().bounce_rays > 0);
}
}  // namespace

TEST_CASE("PathTracer: white furnace, an open box of albedo 1 with unbounded bounces",
          "[render][path_tracer]") {
    check_box_furnace(sphbasis_test::box(-1, -1, -1, 1, 1, 1, true));
}

TEST_CASE("PathTracer: white furnace with normals smoothed across edges and mixed winding",
          "[render][path_tracer]") {
    // The open box of the case above as files deliver it: vertex normals smoothed across its
    // 90-degree edges (55 degrees from every face: half the cosine lobe about them lies below
    // the surface), alone and with every second triangle wound the other way (normals against
    // the winding). Two-sided shading with the folded lobe keeps every estimate at 1.
    for (bool mixed : {false, true}) {
        INFO("mixed winding " << mixed);
        check_box_furnace(sphbasis_test::with_radial_normals(
            sphbasis_test::box(-1, -1, -1, 1, 1, 1, true), {0, 0, 0}, mixed));
    }
}

TEST_CASE("PathTracer: sphere, cone and hemisphere lights with MIS equal their irradiance",
          "[render][path_tracer]") {
    Mesh q = sphbasis_test::quad_grid(-20, 20, -20, 20, 0, 1);
    q.albedo = {0.9f, 0.9f, 0.9f};
    const auto scene = make_scene({q});
    Light ball = sphbasis_test::sphere_light({0.6, 0.2, 1.2}, 0.5, {3, 3, 3});
    Light cone;
    cone.type = Light::Type::cone;
    cone.direction = unit({1, 0, 0.15});  // straddles the horizon
    cone.angle_deg = 25;
    cone.color = {5, 5, 5};
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = unit({0.3, 0, 1});
    hemi.color = {1, 1, 1};
    hemi.ground = {0.4, 0.4, 0.4};
    TraceSettings s;
    s.bounces = 0;
    int pixel = 0;
    for (const Light& l : {ball, cone, hemi}) {
        PathTracer t(*scene, Environment{}, {l}, s);
        const vec3<double> o{0.3, -1, 1}, p{0, 0, 0};
        const Estimate e =
            estimate(t, o, unit({p.x - o.x, p.y - o.y, p.z - o.z}), 3000, std::uint64_t(pixel++));
        const double expect = 0.9 / constants::pi * render::light_irradiance(l, {0, 0, 1}, p)[0];
        CHECK(std::fabs(e.mean - expect) < 4 * e.se + 1e-3 * expect);
        CHECK(e.se < 0.05 * expect);
    }
}

TEST_CASE("PathTracer: a tilted normal map and the Blinn-Phong lobe under a sun",
          "[render][path_tracer]") {
    const double alpha = 0.4;  // the map tilts the normal toward the tangent (+x)
    std::vector<float> nm = {float(0.5 * (std::sin(alpha) + 1)), 0.5f,
                             float(0.5 * (std::cos(alpha) + 1))};
    Mesh q = sphbasis_test::quad_grid(-2, 2, -2, 2, 0, 1);
    q.albedo = {0.7f, 0.7f, 0.7f};
    q.normal_map = {nm.data(), 1, 1, 3};
    const auto scene = make_scene({q});
    const vec3<double> l = unit({-0.2, 0.3, 1});
    const double E = 2;
    TraceSettings s;
    s.bounces = 0;
    PathTracer t(*scene, Environment{}, {sun(l, E)}, s);
    const vec3<double> n = unit({std::sin(alpha), 0, std::cos(alpha)});
    const RGB v = t.radiance({0.3, -2, 2}, unit({-0.3, 2, -2}), 0, 0);
    CHECK(v[0] == Approx(0.7 / constants::pi * E * sphbasis::dot(n, l)).epsilon(1e-4));
    CHECK(t.counters().normal_map_lookups == 1);
    CHECK(t.counters().specular_evaluations == 0);

    Mesh p = sphbasis_test::quad_grid(-2, 2, -2, 2, 0, 1);
    p.albedo = {0.3f, 0.3f, 0.3f};
    p.shininess = 20;
    p.specular = {0.5f, 0.5f, 0.5f};
    const auto shiny = make_scene({p});
    PathTracer ts(*shiny, Environment{}, {sun(l, E)}, s);
    const vec3<double> o{0.5, -1.5, 2}, d = unit({-0.5, 1.5, -2});
    const vec3<double> wo{-d.x, -d.y, -d.z};
    const vec3<double> h = unit({wo.x + l.x, wo.y + l.y, wo.z + l.z});
    const double f = 0.3 / constants::pi + 0.5 * 28 / (8 * constants::pi) * std::pow(h.z, 20);
    CHECK(ts.radiance(o, d, 0, 0)[0] == Approx(f * E * l.z).epsilon(1e-4));
    CHECK(ts.counters().specular_evaluations > 0);
    CHECK(ts.counters().normal_map_lookups == 0);
}

TEST_CASE("PathTracer: MIS irradiance of a lat-long map equals quadrature",
          "[render][path_tracer]") {
    const int W = 16, H = 8;
    const std::vector<float> tex = sphbasis_test::rgb_texels(W, H, [](int i, int j, float* p) {
        p[0] = 0.3f + 0.2f * float(std::sin(0.7 * i));
        p[1] = 0.2f;
        p[2] = 0.1f + 0.05f * float(j);
        if (j == 2 && i == 3) p[0] = p[1] = p[2] = 60;  // a sun
    });
    Environment env = latlong_environment(tex, W, H);
    env.rotation = sphbasis::matrix_from_euler_zyz(0.4, 0.3, 0.0);
    for (const vec3<double> n : {vec3<double>{0, 0, 1}, unit({0.5, 0.2, 0.8})}) {
        // A big quad with normal n through the origin.
        const sphbasis::Frame<double> f(n);
        Mesh q = render::shapes::quad({0, 0, 0}, {f.s.x * 50, f.s.y * 50, f.s.z * 50},
                                      {f.t.x * 50, f.t.y * 50, f.t.z * 50}, 1);
        q.albedo = {1, 1, 1};
        const auto scene = make_scene({q});
        TraceSettings s;
        s.bounces = 0;
        PathTracer t(*scene, env, {}, s);
        const vec3<double> o{n.x + 0.1, n.y - 0.2, n.z};
        const Estimate e = estimate(t, o, unit({-o.x, -o.y, -o.z}), 3000);
        // Quadrature of L(w) max(n.w, 0) over the hemisphere of n, 256 x 512 cells in the
        // frame of n (uniform in cos theta and phi).
        const double E = hemisphere_integral(
            [&](const vec3<double>& w) { return env.radiance(f.to_world(w))[0] * w.z; });
        CHECK(std::fabs(e.mean - E / constants::pi) < 4 * e.se + 2e-3 * E);
        CHECK(t.counters().environment_samples == 3000);
    }
}

TEST_CASE("PathTracer: Blinn-Phong under a lat-long map (MIS with lobe sampling) equals quadrature",
          "[render][path_tracer]") {
    const int W = 16, H = 8;
    const std::vector<float> tex = sphbasis_test::rgb_texels(W, H, [](int i, int j, float* p) {
        p[0] = p[1] = p[2] = 0.2f + 0.1f * float(i % 3);
        if (j == 1 && i == 9) p[0] = p[1] = p[2] = 30;
    });
    Environment env = latlong_environment(tex, W, H);
    Mesh q = sphbasis_test::quad_grid(-50, 50, -50, 50, 0, 1);
    q.albedo = {0.2f, 0.2f, 0.2f};
    q.shininess = 8;
    q.specular = {0.6f, 0.6f, 0.6f};
    const auto scene = make_scene({q});
    TraceSettings s;
    s.bounces = 0;
    PathTracer t(*scene, env, {}, s);
    const vec3<double> o{0.8, -0.6, 0.5};
    const vec3<double> d = unit({-o.x, -o.y, -o.z});
    const Estimate e = estimate(t, o, d, 4000);
    const vec3<double> wo{-d.x, -d.y, -d.z};
    const double ref = hemisphere_integral([&](const vec3<double>& w) {
        const vec3<double> h = unit({wo.x + w.x, wo.y + w.y, wo.z + w.z});
        const double f = 0.2 / constants::pi + 0.6 * 16 / (8 * constants::pi) * std::pow(h.z, 8);
        return f * env.radiance(w)[0] * w.z;
    });
    CHECK(std::fabs(e.mean - ref) < 4 * e.se + 2e-3 * ref);
    CHECK(t.counters().specular_evaluations > 0);
}

TEST_CASE("PathTracer: error halves when samples quadruple", "[render][path_tracer]") {
    const auto scene = ball_on_plane(16, 32);
    TraceSettings s;
    s.bounces = 1;
    s.target_noise = 0;
    auto render_spp = [&](int spp, std::uint64_t seed) {
        TraceSettings q = s;
        q.spp_min = q.spp_max = spp;
        q.seed = seed;
        PathTracer t(*scene, constant_sky(1), {sun(unit({0.5, 0.3, 1}), 2)}, q);
        return t.render(ball_camera(8, 8)).color;
    };
    const auto ref = render_spp(256, 99);
    const double e16 = rmse(render_spp(16, 1), ref), e64 = rmse(render_spp(64, 2), ref);
    // With the reference's own variance: sqrt((1/16 + 1/256) / (1/64 + 1/256)) = 1.84.
    CHECK(e16 / e64 > 1.35);
    CHECK(e16 / e64 < 2.5);
}

TEST_CASE("PathTracer: deterministic for a seed, whatever the thread count",
          "[render][path_tracer]") {
    const auto scene = ball_on_plane(12, 24);
    TraceSettings s;
    s.bounces = 2;
    s.spp_min = 2;
    s.spp_max = 8;
    s.target_noise = 1e-9;
    s.tile = 4;
    s.seed = 5;
    s.aovs = true;
    const Camera cam = ball_camera(12, 10);
    PathTracer t(*scene, constant_sky(1), {sun(unit({0.5, 0.3, 1}), 2)}, s);
    render::TraceResult one, all;
    tbb::task_arena(1).execute([&] { one = t.render(cam); });
    all = t.render(cam);
    CHECK(one.color.data == all.color.data);
    CHECK(one.stderr_.data == all.stderr_.data);
    CHECK(one.normal.data == all.normal.data);
    CHECK(one.counters.shadow_rays == all.counters.shadow_rays);
    CHECK(one.counters.bounce_rays == all.counters.bounce_rays);
    CHECK(one.spp == 8);  // passes 2, 4, 8
    CHECK(one.counters.camera_rays == 12u * 10u * 8u);
    CHECK(t.counters().camera_rays == 2u * 12u * 10u * 8u);
    // A different seed gives a different image.
    TraceSettings s2 = s;
    s2.seed = 6;
    PathTracer t2(*scene, constant_sky(1), {sun(unit({0.5, 0.3, 1}), 2)}, s2);
    CHECK(t2.render(cam).color.data != one.color.data);
}

TEST_CASE("PathTracer: counters of work the scene does not call for", "[render][path_tracer]") {
    const auto scene = ball_on_plane(12, 24);
    const Camera cam = ball_camera(8, 8);
    TraceSettings s;
    s.spp_min = s.spp_max = 2;
    s.target_noise = 0;
    s.bounces = 3;
    {  // No lights, no environment: black, nothing but camera rays.
        PathTracer t(*scene, Environment{}, {}, s);
        const auto r = t.render(cam);
        CHECK(r.counters.camera_rays == 128);
        CHECK(r.counters.shadow_rays == 0);
        CHECK(r.counters.bounce_rays == 0);
        CHECK(r.counters.environment_samples == 0);
        CHECK(r.counters.light_samples == 0);
        for (float v : r.color.data) CHECK(v == 0);
        CHECK(t.effects().empty());
    }
    {  // bounces = 0: no bounce rays; no normal maps, no shininess: no such work.
        TraceSettings z = s;
        z.bounces = 0;
        PathTracer t(*scene, constant_sky(1), {sun({0, 0, 1}, 1)}, z);
        const auto r = t.render(cam);
        CHECK(r.counters.bounce_rays == 0);
        CHECK(r.counters.shadow_rays > 0);
        CHECK(r.counters.normal_map_lookups == 0);
        CHECK(r.counters.specular_evaluations == 0);
        // Every hit takes one light sample.
        double hits = 0;
        for (float c : r.coverage.data) hits += double(c) * 2;
        CHECK(double(r.counters.light_samples) == Approx(hits));
        REQUIRE(t.effects().size() == 2);
        CHECK(t.effects()[0].find("constant") != std::string::npos);
        CHECK(t.effects()[1].find("directional lights: 1") != std::string::npos);
    }
    {  // Bounces: bounce rays, and the effects say so.
        PathTracer t(*scene, constant_sky(1), {}, s);
        const auto r = t.render(cam);
        CHECK(r.counters.bounce_rays > 0);
        CHECK(r.counters.light_samples == 0);
        REQUIRE(t.effects().size() == 2);
        CHECK(t.effects()[1] == "interreflection: 3 bounces");
    }
}

TEST_CASE("PathTracer: progressive passes stop at the target noise; bad settings throw",
          "[render][path_tracer]") {
    const auto scene = ball_on_plane(12, 24);
    const Camera cam = ball_camera(8, 8);
    TraceSettings s;
    s.bounces = 1;
    s.spp_min = 4;
    s.spp_max = 256;
    s.target_noise = 0.05;
    PathTracer t(*scene, constant_sky(1), {sun(unit({0.5, 0.3, 1}), 2)}, s);
    std::uint64_t last = 0;
    const auto r = t.render(cam, [&](std::uint64_t done, std::uint64_t total) {
        CHECK(total == 64u * 256u);
        last = std::max(last, done);
    });
    CHECK(r.relative_noise <= 0.05);
    CHECK(r.spp < 256);
    CHECK(r.spp >= 8);
    CHECK(last == 64u * std::uint64_t(r.spp));
    // The stderr image is the pixel's sample standard error: positive where the scene is lit
    // through noise, and the relative noise is its RMS relative to the luminance.
    double acc = 0;
    for (int i = 0; i < 64; ++i) {
        const float* c = &r.color.data[3 * std::size_t(i)];
        const float* e = &r.stderr_.data[3 * std::size_t(i)];
        const double l = render::luminance(c[0], c[1], c[2]);
        const double le = render::luminance(e[0], e[1], e[2]);
        acc += (le / l) * (le / l);
    }
    CHECK(std::sqrt(acc / 64) == Approx(r.relative_noise).epsilon(1e-3));

    TraceSettings bad = s;
    bad.spp_min = 0;
    CHECK_THROWS_AS(PathTracer(*scene, constant_sky(1), {}, bad), std::invalid_argument);
    bad = s;
    bad.spp_max = 2;
    CHECK_THROWS_AS(PathTracer(*scene, constant_sky(1), {}, bad), std::invalid_argument);
    bad = s;
    bad.target_noise = -1;
    CHECK_THROWS_AS(PathTracer(*scene, constant_sky(1), {}, bad), std::invalid_argument);
    Light l;
    l.type = Light::Type::sphere;
    l.radius = -1;
    CHECK_THROWS_AS(PathTracer(*scene, constant_sky(1), {l}, s), std::invalid_argument);
    Camera c = cam;
    c.fov_deg = 0;
    CHECK_THROWS_AS(t.render(c), std::invalid_argument);
}

TEST_CASE("PathTracer: furnace and convergence at scale", "[render][path_tracer][slow]") {
    // The white furnace as an image: every pixel 1 within 5 of its own standard errors.
    Mesh box = sphbasis_test::box(-1, -1, -1, 1, 1, 1, true);
    box.albedo = {1, 1, 1};
    const auto scene = make_scene({box});
    TraceSettings s;
    s.bounces = -1;
    s.spp_min = 64;
    s.spp_max = 256;
    s.target_noise = 0;
    PathTracer t(*scene, constant_sky(1), {}, s);
    const auto r = t.render(camera_at({0.3, -0.4, 4}, {0, 0, -0.5}, 32, 32, 45));
    for (std::size_t i = 0; i < r.color.data.size(); ++i)
        CHECK(std::fabs(r.color.data[i] - 1) <= 5 * r.stderr_.data[i] + 1e-4);

    // Convergence: 64 x 64 pixels, 16 against 64 samples, reference 4096.
    const auto scene2 = ball_on_plane(16, 32);
    auto render_spp = [&](int spp, std::uint64_t seed) {
        TraceSettings q;
        q.bounces = 2;
        q.spp_min = q.spp_max = spp;
        q.target_noise = 0;
        q.seed = seed;
        PathTracer tt(*scene2, constant_sky(1), {sun(unit({0.5, 0.3, 1}), 2)}, q);
        return tt.render(ball_camera(32, 32)).color;
    };
    const auto ref = render_spp(4096, 99);
    const double e16 = rmse(render_spp(16, 1), ref), e64 = rmse(render_spp(64, 2), ref),
                 e256 = rmse(render_spp(256, 3), ref);
    CHECK(e16 / e64 == Approx(2).epsilon(0.15));
    CHECK(e64 / e256 ==
          Approx(std::sqrt((1 / 64.0 + 1 / 4096.0) / (1 / 256.0 + 1 / 4096.0))).epsilon(0.15));
}

TEST_CASE("PathTracer: a tile's paths traced together equal paths traced one at a time",
          "[render][path_tracer]") {
    // render() advances a tile's paths a vertex at a time with streams of shadow and BRDF rays;
    // radiance() traces one path. Same ray, pixel and sample: the same estimate. Lat-long map,
    // a sun and a sphere light, two bounces, 3 x 3 tiles (a partial one at the border).
    const int W = 8, H = 4;
    std::vector<float> tex(std::size_t(W * H * 3));
    for (std::size_t i = 0; i < tex.size(); ++i) tex[i] = 0.2f + 0.1f * float(i % 7);
    tex[3 * 10] = tex[3 * 10 + 1] = tex[3 * 10 + 2] = 40;
    Environment env = latlong_environment(tex, W, H);
    Light ball = sphbasis_test::sphere_light({-1, -1, 2}, 0.3, {4, 4, 4});
    const auto scene = ball_on_plane(12, 24);
    TraceSettings s;
    s.bounces = 2;
    s.spp_min = s.spp_max = 1;
    s.target_noise = 0;
    s.tile = 3;
    s.seed = 11;
    const Camera cam = ball_camera(7, 5, 40);
    PathTracer t(*scene, env, {sun(unit({0.5, 0.3, 1}), 2), ball}, s);
    const render::TraceResult r = t.render(cam);
    const render::PinholeCamera pc(cam);
    namespace rt = render::detail::rt;
    int checked = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const auto p = std::uint64_t(y * cam.width + x);
            // One sample per pixel: the pixel centre (render::ImageLoop).
            const render::CameraRay cr = pc.ray(x + 0.5, y + 0.5);
            const RGB L = t.radiance(cr.origin, cr.direction, p, 0);
            for (std::size_t c = 0; c < 3; ++c) {
                const double v = r.color.data[3 * std::size_t(p) + c];
                CHECK(std::fabs(v - L[c]) <= 1e-5 * std::max(1.0, std::fabs(L[c])));
            }
            ++checked;
        }
    CHECK(checked == 35);
    CHECK(r.counters.bounce_rays > 0);
    CHECK(r.counters.environment_samples > 0);
    // The shared-key hash of the paths' random numbers is rt::hash.
    for (std::uint64_t a : {0ull, 1ull, 0x123456789abcdefull})
        for (std::uint64_t b : {0ull, 7ull, 1ull << 40})
            CHECK(render::detail::pt::hash_mixed(rt::mix64(a), b) == rt::hash(a, b));
}

TEST_CASE("PathTracer: recorded rays are the streams it traced, one record per counted ray",
          "[render][path_tracer]") {
    const auto scene = ball_on_plane(12, 24);
    const Camera cam = ball_camera(9, 7);
    TraceSettings s;
    s.bounces = 1;
    s.spp_min = s.spp_max = 2;
    s.target_noise = 0;
    s.tile = 4;
    Light ball = sphbasis_test::sphere_light({-1, -1, 2}, 0.3, {4, 4, 4});
    for (int lights = 0; lights < 2; ++lights) {
        std::vector<Light> ls = {sun(unit({0.5, 0.3, 1}), 2)};
        if (lights) ls.push_back(ball);
        PathTracer t(*scene, constant_sky(1), ls, s);
        std::vector<PathTracer::RayRecord> log;
        t.record_rays(&log);
        const render::TraceResult r = t.render(cam);
        t.record_rays(nullptr);
        REQUIRE(log.size() == r.counters.rays());
        std::uint64_t kinds[4] = {0, 0, 0, 0};
        for (std::size_t i = 0; i < log.size();) {
            const std::uint32_t len = log[i].stream;
            REQUIRE(len > 0);
            REQUIRE(i + len <= log.size());
            for (std::size_t j = i; j < i + len; ++j) {
                CHECK(log[j].kind == log[i].kind);
                CHECK(log[j].coherent == (log[i].kind == 0));
                CHECK((j == i || log[j].stream == 0));
                ++kinds[log[j].kind];
            }
            i += len;
        }
        CHECK(kinds[0] == r.counters.camera_rays);
        CHECK(kinds[1] == r.counters.bounce_rays);
        CHECK(kinds[2] + kinds[3] == r.counters.shadow_rays);
        // The last vertex's BRDF rays need a hit distance only with a sphere light.
        CHECK((kinds[3] > 0) == (lights == 1));
    }
}

TEST_CASE("PathTracer: the cosine lobe's polynomial cos/sin and its batch form",
          "[render][path_tracer]") {
    // sphbasis::detail::cos_sin_turn (core/cos_sin_turn.hpp) within 2e-9 of libm over [0, 1],
    // the octant boundaries included; detail::pt::cosine_lobe equals Frame(n).to_world of
    // cosine_hemisphere path by path (to rounding), for any array length (SIMD remainders).
    double worst = 0;
    const int N = 1 << 17;
    auto check = [&](double v) {
        double c, s;
        sphbasis::detail::cos_sin_turn(v, c, s);
        const double a = constants::two_pi * v;
        worst = std::max({worst, std::fabs(c - std::cos(a)), std::fabs(s - std::sin(a))});
    };
    for (int i = 0; i <= N; ++i) check(double(i) / N);
    for (int q = 0; q <= 8; ++q)
        for (double e : {-1e-15, 0.0, 1e-15}) check(std::min(1.0, std::max(0.0, q / 8.0 + e)));
    CHECK(worst < 2e-9);
    CHECK(worst > 1e-12);  // a polynomial, not libm

    namespace pt = render::detail::pt;
    for (std::size_t n : {std::size_t(1), std::size_t(7), std::size_t(33)}) {
        std::vector<std::uint64_t> key(n);
        std::vector<double> nx(n), ny(n), nz(n), wx(n), wy(n), wz(n), cz(n), tmp(3 * n);
        for (std::size_t k = 0; k < n; ++k) {
            key[k] = render::detail::rt::mix64(k + 17);
            const auto d = unit({std::sin(1.3 * double(k)), std::cos(0.7 * double(k) + 0.2),
                                 k % 3 == 0 ? -0.9 : 0.4});
            nx[k] = d.x;
            ny[k] = d.y;
            nz[k] = d.z;
        }
        pt::cosine_lobe(n, 42, key.data(), nx.data(), ny.data(), nz.data(), wx.data(), wy.data(),
                        wz.data(), cz.data(), tmp.data());
        for (std::size_t k = 0; k < n; ++k) {
            const sphbasis::Frame<double> f(vec3<double>{nx[k], ny[k], nz[k]});
            const auto l = render::detail::cosine_hemisphere(
                render::detail::rt::unit(pt::hash_mixed(key[k], 45)),
                render::detail::rt::unit(pt::hash_mixed(key[k], 46)));
            const auto w = f.to_world(l);
            CHECK(std::fabs(wx[k] - w.x) < 1e-14);
            CHECK(std::fabs(wy[k] - w.y) < 1e-14);
            CHECK(std::fabs(wz[k] - w.z) < 1e-14);
            CHECK(std::fabs(cz[k] - l.z) < 1e-14);
            // Unit within the polynomial's error (no renormalisation): |w|^2 - 1 ~ 2 (2e-9).
            CHECK(std::fabs(wx[k] * wx[k] + wy[k] * wy[k] + wz[k] * wz[k] - 1) < 5e-9);
        }
    }
}
