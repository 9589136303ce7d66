// Tests of Ambient Dice over the icosahedron's faces in the bake and the render representations
// (lightmap-ambient-dice-bezier30, -linear10, -ycocg, volume-ambient-dice-bezier;
// representations/lightmap.hpp, representations/volume_engine.hpp). They go through the registry
// names "ambient-dice-bezier" and "ambient-dice-linear" only: every reference is the library's own
// least-squares fit (render::IrradianceFit) of a closed-form irradiance, never a property of the
// basis's construction (which need not reproduce constants).
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "../render_test_support.hpp"
#include "sky_probes_for_tests.hpp"
#include "sphbasis/core/constants.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/bake_points.hpp"
#include "sphbasis/render/irradiance_fit.hpp"
#include "sphbasis/render/representation.hpp"

namespace {

using namespace sphbasis;
using render::Quantity;
using render::RGB;

/// A 2 x 2 quad at z = 0 (nothing occludes it), albedo 0.8, under a constant sky.
sphbasis_test::World sky_quad(RGB sky) {
    sphbasis_test::World w;
    w.meshes.push_back(sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1));
    w.meshes[0].albedo = {0.8f, 0.8f, 0.8f};
    w.desc.environment = sphbasis_test::constant_environment(sky);
    w.build();
    return w;
}

struct Face {
    const char* basis;
    int coeffs;
};
constexpr std::array<Face, 2> faces{{{"ambient-dice-bezier", 30}, {"ambient-dice-linear", 10}}};

}  // namespace

TEST_CASE("dice lightmaps: the YCoCg transform and its exact inverse", "[render]") {
    // The definition on the unit colours.
    CHECK(render::rgb_to_ycocg(1.0, 0.0, 0.0) == std::array<double, 3>{0.25, 0.5, -0.25});
    CHECK(render::rgb_to_ycocg(0.0, 1.0, 0.0) == std::array<double, 3>{0.5, 0.0, 0.5});
    CHECK(render::rgb_to_ycocg(0.0, 0.0, 1.0) == std::array<double, 3>{0.25, -0.5, -0.25});
    // Multiples of 1/4 below 2^40: every sum is exact, so the round trip is bit-exact.
    for (double r : {0.0, 0.25, 3.0, -7.75, 1e6})
        for (double g : {0.0, 1.0, -2.5, 12345.0})
            for (double b : {0.0, 0.5, 99.25, -1e6}) {
                const auto v = render::rgb_to_ycocg(r, g, b);
                CHECK(render::ycocg_to_rgb(v[0], v[1], v[2]) == std::array<double, 3>{r, g, b});
            }
    // Any doubles: within a few ulps of the largest input.
    std::uint64_t s = 12345;
    auto next = [&s] {
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        return double(s >> 11) * 0x1.0p-53 * 200 - 100;
    };
    for (int i = 0; i < 1000; ++i) {
        const std::array<double, 3> x{next(), next(), next()};
        const auto v = render::rgb_to_ycocg(x[0], x[1], x[2]);
        const auto y = render::ycocg_to_rgb(v[0], v[1], v[2]);
        const double m = std::max({std::fabs(x[0]), std::fabs(x[1]), std::fabs(x[2])});
        for (std::size_t c = 0; c < 3; ++c)
            CHECK(std::fabs(y[c] - x[c]) <= 4 * std::numeric_limits<double>::epsilon() * m);
    }
}

TEST_CASE("dice lightmaps: a baked texel is the fit of its exact irradiance", "[render]") {
    // A quad under a coloured constant sky L and a sun (colour col, direction l): over the
    // tangent hemisphere of normals E_c(n') = pi L_c (1 + z)/2 + col_c max(n' . l, 0). Every
    // texel must hold IrradianceFit's least squares of E on the bake's rule
    // (hemisphere_rule_sqrt(32, 32)) within 5 of the bake's own standard errors, which follow
    // from the ray count (the sky is sampled by rays; the sun, one shadow ray, adds none).
    const RGB sky{1.0, 0.5, 0.25}, col{2.0, 1.0, 0.5};
    const vec3<double> l = sphbasis_test::unit({0.6, -0.3, 0.4});
    sphbasis_test::World w = sky_quad(sky);
    render::Light sun;
    sun.type = render::Light::Type::directional;
    sun.direction = l;
    sun.color = col;
    w.desc.lights.push_back(sun);
    const std::vector<render::BakePoint> texels =
        render::texel_points(render::texel_layout(w.desc.meshes, 0, 4));
    REQUIRE_FALSE(texels.empty());
    for (const Face& f : faces) {
        INFO(f.basis);
        const render::IrradianceFit fit(f.basis, f.coeffs, hemisphere_rule_sqrt(32, 32));
        const std::size_t n = std::size_t(f.coeffs);
        std::vector<double> ref(3 * n);
        fit.fit_function(
            [&](double x, double y, double z) {
                const double c = std::max(0.0, x * l.x + y * l.y + z * l.z);
                std::array<double, 3> e;
                for (std::size_t k = 0; k < 3; ++k)
                    e[k] = constants::pi * sky[k] * 0.5 * (1 + z) + col[k] * c;
                return e;
            },
            ref.data(), ref.data() + n, ref.data() + 2 * n);
        double scale = 0;
        for (double v : ref) scale = std::max(scale, std::fabs(v));
        render::BakeSettings s;
        s.quantities = Quantity::irradiance;
        s.basis = f.basis;
        s.coeffs = f.coeffs;
        s.rays = 1024;
        double worst = 0, worst_se = 0;
        for (const render::PointResult& r : render::Baker(w.desc, s).bake(texels)) {
            REQUIRE(r.irradiance_stderr.size() == n);
            for (std::size_t c = 0; c < 3; ++c) {
                REQUIRE(r.irradiance[c].size() == n);
                for (std::size_t k = 0; k < n; ++k) {
                    const double d = std::fabs(r.irradiance[c][k] - ref[c * n + k]);
                    const double se = r.irradiance_stderr[k];
                    worst = std::max(worst, d / scale);
                    worst_se = std::max(worst_se, se / scale);
                    CHECK(d <= 5 * se + 1e-9 * scale);
                }
            }
        }
        // Measured at 1024 rays: |baked - fit| 0.7% (Bezier) of the largest coefficient, the
        // standard errors up to 4%.
        INFO("largest |baked - fit| " << worst << ", largest stderr " << worst_se
                                      << " (of the largest coefficient)");
        CHECK(worst < 0.02);
        CHECK(worst_se < 0.1);
    }
}

/// The YCoCg tests' scene, built into w: sphere_on_plane_meshes() with a grey ball (0.6) under
/// the 8 x 4 lat-long sky of texel(x, y, rgb); their settings: 16 rays, one bounce, 8 x 8
/// lightmaps.
template <class Texel>
render::RepresentationSettings ycocg_scene(sphbasis_test::World& w, Texel&& texel) {
    w = sphbasis_test::sphere_on_plane_meshes();
    w.meshes[0].albedo = {0.6f, 0.6f, 0.6f};
    w.env_texels = sphbasis_test::rgb_texels(8, 4, texel);
    w.desc.environment = sphbasis_test::latlong_environment(w.env_texels, 8, 4);
    w.build();
    render::RepresentationSettings s;
    s.rays = 16;
    s.bounces = 1;
    s.lightmap_size = 8;
    return s;
}

TEST_CASE("dice lightmaps: the YCoCg luma is bezier30's, its chroma linear10's", "[render]") {
    // The fits are linear and the shading is linear in the stored values, so at every pixel
    // the luma of lightmap-ambient-dice-ycocg is that of lightmap-ambient-dice-bezier30 and its
    // chroma that of -linear10, up to the float storage, whatever the lighting (a coloured sky
    // with a bright patch, one bounce); grey albedos, so that a pixel is its irradiance times
    // one number. It reads exactly their two bakes.
    sphbasis_test::World w;
    const render::RepresentationSettings s = ycocg_scene(w, [](int x, int y, float* p) {
        p[0] = 0.3f + 0.2f * float(y) + (x == 3 && y == 1 ? 4.0f : 0.0f);
        p[1] = 0.5f + 0.1f * float(x % 3);
        p[2] = 0.8f - 0.15f * float(y);
    });
    const std::vector<std::string> names{"lightmap-ambient-dice-bezier30",
                                         "lightmap-ambient-dice-linear10",
                                         "lightmap-ambient-dice-ycocg"};
    render::Representations r(w.desc, *w.rt, s, names);
    CHECK(r.bakes().size() == 4);  // two meshes, two bases: the ycocg reads the others' bakes
    CHECK(r.reads(2).size() == 4);
    r.prepare(nullptr);
    const render::Camera cam = sphbasis_test::camera_at({0, -3, 1.5}, {0, 0, 0.3}, 16, 16);
    const render::Image bez = r.render(0, cam, 1), lin = r.render(1, cam, 1),
                        yc = r.render(2, cam, 1);
    const double m = sphbasis_test::max_abs(bez);
    REQUIRE(m > 0);
    double worst = 0;
    for (std::size_t i = 0; i + 2 < yc.data.size(); i += 3) {
        auto ycocg = [&](const render::Image& a) {
            return render::rgb_to_ycocg(double(a.data[i]), double(a.data[i + 1]),
                                        double(a.data[i + 2]));
        };
        const auto a = ycocg(yc), b = ycocg(bez), c = ycocg(lin);
        worst = std::max(
            {worst, std::fabs(a[0] - b[0]), std::fabs(a[1] - c[1]), std::fabs(a[2] - c[2])});
    }
    INFO("largest difference " << worst << " of " << m);
    CHECK(worst <= 1e-5 * m);
    for (std::size_t k = 0; k < names.size(); ++k) {
        INFO(names[k]);
        const render::RepresentationStats st = r.stats(k);
        CHECK(st.element == "texel");
        CHECK(st.elements == r.stats(0).elements);
        CHECK(st.bytes_per_element == (k == 0 ? 90 : (k == 1 ? 30 : 50)) * sizeof(float));
    }
    CHECK(r.stats(2).bake_rays == r.stats(0).bake_rays + r.stats(1).bake_rays);
}

TEST_CASE("dice lightmaps: under a grey sky lightmap-ambient-dice-ycocg is the Bezier lightmap",
          "[render]") {
    // Grey lighting and grey albedos: R = G = B everywhere in the bakes, so chroma is exactly 0
    // and luma is the channels' common value (up to one rounding of R/4 + G/2 + B/4).
    sphbasis_test::World w;
    const render::RepresentationSettings s = ycocg_scene(w, [](int x, int y, float* p) {
        p[0] = p[1] = p[2] = 0.2f + 0.2f * float(y) + (x == 3 && y == 1 ? 3.0f : 0.0f);
    });
    render::Representations r(w.desc, *w.rt, s,
                              {"lightmap-ambient-dice-ycocg", "lightmap-ambient-dice-bezier30"});
    r.prepare(nullptr);
    const render::Camera cam = sphbasis_test::camera_at({0, -3, 1.5}, {0, 0, 0.3}, 16, 16);
    const render::Image a = r.render(0, cam, 1), b = r.render(1, cam, 1);
    REQUIRE(a.data.size() == b.data.size());
    const double m = sphbasis_test::max_abs(b);
    REQUIRE(m > 0);
    CHECK(sphbasis_test::max_abs_diff(a, b) <= 1e-6 * m);
}

TEST_CASE("dice volumes: volume-ambient-dice-bezier is the fit of the volume's irradiance",
          "[render]") {
    // The Bezier volume stores its least squares over the sphere in the 36 functions.
    const double at_z = sphbasis_test::fit_at_z("ambient-dice-bezier", 36, sphere_rule(40));
    INFO("fit at +z " << at_z);
    const auto vol = sphbasis_test::volume_against_sh("volume-ambient-dice-bezier", at_z);
    CHECK(vol.worst < 0.02);
    CHECK(vol.stats.element == "probe");
    CHECK(vol.stats.bytes_per_element == 3 * 36 * sizeof(float));
}
