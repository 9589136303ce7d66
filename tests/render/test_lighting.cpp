// Tests for render/lighting.hpp: the environment lookup (texel centres, bilinear, wrap, clamp,
// rotation, scale, validation), the analytic lights' radiance, closed-form irradiance against
// quadrature (horizon crossings included), SH projections against quadrature of radiance(),
// and light sampling (pdf normalisation, estimator convergence, distances to the emitter).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/basis/sh.hpp"
#include "sphbasis/core/frame.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/core/sampling.hpp"
#include "sphbasis/param/latlong.hpp"
#include "sphbasis/render/bake.hpp"  // beside lighting.hpp: no name of one hides the other's
#include "sphbasis/render/lighting.hpp"

using sphbasis::vec3;
using sphbasis::render::Environment;
using sphbasis::render::Light;
using sphbasis::render::RGB;
namespace render = sphbasis::render;
namespace constants = sphbasis::constants;

namespace {

using sphbasis_test::unit;

/// A direction at angle beta from d, in the plane of d and an arbitrary perpendicular.
vec3<double> tilted(const vec3<double>& d, double beta) {
    const sphbasis::Frame<double> f(d);
    return unit(f.to_world(vec3<double>{std::sin(beta), 0, std::cos(beta)}));
}

/// integral over the band t0 <= w.d <= t1 of max(n.w, 0) dw, cos(beta) = n.d: the azimuthal
/// integral of max(A + B cos(phi), 0) in closed form, then composite Gauss-Legendre in t with
/// panel ends at the t-integrand's kinks (A = 0 and |A| = |B|, i.e. t = 0 and t = +-sin(beta)).
double band_cosine_integral(double t0, double t1, double cb) {
    const double sb = std::sqrt(std::max(0.0, 1 - cb * cb));
    std::vector<double> x, w;
    sphbasis::gauss_legendre(8, x, w);
    std::vector<double> ends{t0, t1};
    for (double k : {0.0, sb, -sb})
        if (k > t0 && k < t1) ends.push_back(k);
    std::sort(ends.begin(), ends.end());
    const int panels = 40;
    double sum = 0;
    for (std::size_t e = 0; e + 1 < ends.size(); ++e)
        for (int p = 0; p < panels; ++p) {
            const double lo = ends[e], hi = ends[e + 1];
            const double a = static_cast<double>(p) / panels,
                         b = static_cast<double>(p + 1) / panels;
            for (std::size_t k = 0; k < x.size(); ++k) {
                // s in [0, 1] -> t = lo + (hi - lo)(1 - cos(pi s))/2 clusters nodes at the kinks.
                const double sp = 0.5 * (a + b) + 0.5 * (b - a) * x[k];
                const double t = lo + (hi - lo) * 0.5 * (1 - std::cos(constants::pi * sp));
                const double jac = (hi - lo) * 0.5 * constants::pi * std::sin(constants::pi * sp);
                const double A = cb * t, B = sb * std::sqrt(std::max(0.0, 1 - t * t));
                double f;
                if (B <= std::fabs(A))
                    f = A > 0 ? constants::two_pi * A : 0;
                else {
                    const double phi0 = std::acos(-A / B);
                    f = 2 * (A * phi0 + B * std::sin(phi0));
                }
                sum += 0.5 * (b - a) * w[k] * jac * f;
            }
        }
    return sum;
}

/// integral over the sphere of f(w) g(w) where f is constant on the bands of w.d split at
/// `splits` (ascending in (-1, 1)): Gauss-Legendre in w.d per band, uniform in the azimuth.
template <class G>
void split_quadrature(const vec3<double>& d, std::vector<double> splits, int nt, int nphi, G&& g) {
    std::vector<double> x, w;
    sphbasis::gauss_legendre(nt, x, w);
    splits.insert(splits.begin(), -1.0);
    splits.push_back(1.0);
    const sphbasis::Frame<double> f(d);
    for (std::size_t s = 0; s + 1 < splits.size(); ++s) {
        const double a = splits[s], b = splits[s + 1];
        for (std::size_t k = 0; k < x.size(); ++k) {
            const double t = 0.5 * (a + b) + 0.5 * (b - a) * x[k];
            const double st = std::sqrt(std::max(0.0, 1 - t * t));
            for (int j = 0; j < nphi; ++j) {
                const double phi = constants::two_pi * (j + 0.5) / nphi;
                const vec3<double> dir =
                    unit(f.to_world(vec3<double>{st * std::cos(phi), st * std::sin(phi), t}));
                g(dir, 0.5 * (b - a) * w[k] * constants::two_pi / nphi);
            }
        }
    }
}

Light cone_light(vec3<double> d, double deg, RGB c) {
    Light l;
    l.type = Light::Type::cone;
    l.direction = d;
    l.angle_deg = deg;
    l.color = c;
    return l;
}

}  // namespace

TEST_CASE("Environment: none and constant", "[render][lighting]") {
    Environment e;
    const RGB z = e.radiance({0, 0, 1});
    CHECK(z[0] == 0);
    CHECK(z[2] == 0);
    e.kind = Environment::Kind::constant;
    e.constant = {1, 2, 3};
    e.scale = 0.5;
    const RGB c = e.radiance({0.3, -0.2, 0.1});
    CHECK(c[0] == 0.5);
    CHECK(c[1] == 1.0);
    CHECK(c[2] == 1.5);
    CHECK_NOTHROW(render::validate(e));
}

TEST_CASE("Environment: lat-long texel centres, bilinear, wrap in u, clamp in v",
          "[render][lighting]") {
    const int W = 8, H = 4;
    std::vector<float> tex(W * H * 3);
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> U(0.f, 4.f);
    for (float& t : tex) t = U(rng);
    Environment e = sphbasis_test::latlong_environment(tex, W, H);
    e.scale = 2.0;
    REQUIRE_NOTHROW(render::validate(e));
    auto texel = [&](int i, int j, int c) {
        return 2.0 * static_cast<double>(tex[static_cast<std::size_t>(3 * (j * W + i) + c)]);
    };
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const vec3<double> d = sphbasis::param::square_to_latlong((i + 0.5) / W, (j + 0.5) / H);
            const RGB r = e.radiance(d);
            for (int c = 0; c < 3; ++c)
                CHECK(r[static_cast<std::size_t>(c)] == Approx(texel(i, j, c)).epsilon(1e-12));
        }
    // Halfway between two centres of a row: their mean.
    {
        const vec3<double> d = sphbasis::param::square_to_latlong(3.0 / W, 1.5 / H);
        const RGB r = e.radiance(d);
        CHECK(r[1] == Approx(0.5 * (texel(2, 1, 1) + texel(3, 1, 1))).epsilon(1e-12));
    }
    // Centre of four texels.
    {
        const vec3<double> d = sphbasis::param::square_to_latlong(5.0 / W, 2.0 / H);
        const RGB r = e.radiance(d);
        CHECK(r[0] ==
              Approx(0.25 * (texel(4, 1, 0) + texel(5, 1, 0) + texel(4, 2, 0) + texel(5, 2, 0)))
                  .epsilon(1e-12));
    }
    // The seam phi = 0 (u = 0): the mean of the last and first columns, from both sides.
    {
        const vec3<double> d = sphbasis::param::square_to_latlong(0.0, 1.5 / H);
        const RGB r = e.radiance(d);
        CHECK(r[2] == Approx(0.5 * (texel(W - 1, 1, 2) + texel(0, 1, 2))).epsilon(1e-12));
        const vec3<double> dm = sphbasis::param::square_to_latlong(1.0 - 1e-9, 1.5 / H);
        CHECK(e.radiance(dm)[2] == Approx(r[2]).epsilon(1e-6));
    }
    // Near the poles rows are clamped: bilinear in u along row 0 (row H - 1).
    {
        const vec3<double> d = sphbasis::param::square_to_latlong(1.0 / W, 0.1 / H);
        CHECK(e.radiance(d)[0] == Approx(0.5 * (texel(0, 0, 0) + texel(1, 0, 0))).epsilon(1e-9));
        const vec3<double> s = sphbasis::param::square_to_latlong(1.0 / W, 1 - 0.1 / H);
        CHECK(e.radiance(s)[0] ==
              Approx(0.5 * (texel(0, H - 1, 0) + texel(1, H - 1, 0))).epsilon(1e-9));
    }
    // Non-unit and degenerate input: a scaled direction reads the same; zero reads the pole.
    {
        const vec3<double> d = sphbasis::param::square_to_latlong(0.3, 0.6);
        const RGB a = e.radiance(d), b = e.radiance({7 * d.x, 7 * d.y, 7 * d.z});
        CHECK(a[0] == Approx(b[0]).epsilon(1e-12));
        const RGB z = e.radiance({0, 0, 0}), p = e.radiance({0, 0, 1});
        CHECK(z[1] == p[1]);
        const RGB q = e.radiance({std::nan(""), 0, 0});
        CHECK(std::isfinite(q[0]));
    }
}

TEST_CASE("Environment: rotation is world = rotation * map", "[render][lighting]") {
    const int W = 16, H = 8;
    std::vector<float> tex(W * H * 3);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            for (int c = 0; c < 3; ++c)
                tex[static_cast<std::size_t>(3 * (j * W + i) + c)] =
                    static_cast<float>(1 + i + 0.1 * j * j + c);
    Environment base = sphbasis_test::latlong_environment(tex, W, H);
    Environment rot = base;
    rot.rotation = sphbasis::matrix_from_euler_zyz(0.7, 1.1, -0.4);
    REQUIRE_NOTHROW(render::validate(rot));
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int k = 0; k < 50; ++k) {
        const vec3<double> m = sphbasis::square_to_uniform_sphere(U(rng), U(rng));
        const vec3<double> w = sphbasis::multiply(rot.rotation, m);
        const RGB a = rot.radiance(w), b = base.radiance(m);
        for (std::size_t c = 0; c < 3; ++c) CHECK(a[c] == Approx(b[c]).epsilon(1e-9));
    }
    // A quarter turn about z moves the map's +x (u = 0) to +y.
    Environment q = base;
    q.rotation = {0, -1, 0, 1, 0, 0, 0, 0, 1};
    CHECK(q.radiance({0, 1, 0})[0] == Approx(base.radiance({1, 0, 0})[0]).epsilon(1e-12));
}

TEST_CASE("Environment: validate rejects bad structs", "[render][lighting]") {
    std::vector<float> tex(2 * 1 * 3, 1.f);
    Environment e = sphbasis_test::latlong_environment(tex, 2, 1);
    REQUIRE_NOTHROW(render::validate(e));
    {
        Environment b = e;
        b.texels = nullptr;
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("non-null texels"));
        CHECK(b.radiance({1, 0, 0})[0] == 0);  // never reads through null
    }
    {
        Environment b = e;
        b.width = 0;
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("width >= 1"));
    }
    {
        Environment b = e;
        b.scale = std::nan("");
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("finite environment scale"));
    }
    {
        Environment b = e;
        b.rotation = {2, 0, 0, 0, 1, 0, 0, 0, 1};
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("orthonormal"));
        b.rotation[0] = std::numeric_limits<double>::infinity();
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("orthonormal"));
    }
    {
        std::vector<float> bad = tex;
        bad[4] = std::nanf("");
        Environment b = e;
        b.texels = bad.data();
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("finite environment texels"));
    }
    {
        Environment b = sphbasis_test::constant_environment({1, std::nan(""), 0});
        CHECK_THROWS_WITH(render::validate(b), Catch::StartsWith("sphbasis::render::validate()"));
    }
}

TEST_CASE("Environment: SH projection, constant and rotated lat-long", "[render][lighting]") {
    Environment c = sphbasis_test::constant_environment({1, 2, 3});
    c.scale = 2;
    c.rotation = sphbasis::matrix_from_euler_zyz(0.3, 0.2, 0.1);
    const std::vector<RGB> pc = render::project_sh(c, 3);
    CHECK(pc[0][2] == Approx(6 * std::sqrt(4 * constants::pi)).epsilon(1e-14));
    CHECK(pc[4][0] == 0);
    // A map sampling f(m) = 1 + m.x at texel centres, rotated: L(w) = 1 + w.(R e_x), whose
    // coefficients are sqrt(4 pi) and (R e_x) sqrt(4 pi / 3) on (y_1-1, y_10, y_11) = (y, z, x).
    const int W = 128, H = 64;
    std::vector<float> tex(W * H * 3);
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i) {
            const vec3<double> m = sphbasis::param::square_to_latlong((i + 0.5) / W, (j + 0.5) / H);
            for (int k = 0; k < 3; ++k)
                tex[static_cast<std::size_t>(3 * (j * W + i) + k)] =
                    static_cast<float>((k + 1) * (1 + m.x));
        }
    Environment e = sphbasis_test::latlong_environment(tex, W, H);
    e.scale = 0.5;
    e.rotation = sphbasis::matrix_from_euler_zyz(0.7, 1.1, -0.4);
    const std::vector<RGB> p = render::project_sh(e, 3);
    const vec3<double> a = sphbasis::multiply(e.rotation, vec3<double>{1, 0, 0});
    const double s0 = std::sqrt(4 * constants::pi), s1 = std::sqrt(4 * constants::pi / 3);
    const double expect[9] = {s0, a.y * s1, a.z * s1, a.x * s1, 0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < 9; ++k)
        for (std::size_t ch = 0; ch < 3; ++ch)
            CHECK(p[k][ch] == Approx(0.5 * static_cast<double>(ch + 1) * expect[k]).margin(2e-3));
    // And against quadrature of radiance() (bilinear, so O(1/H) apart at most).
    std::vector<double> y(9);
    std::vector<double> q(9, 0.0);
    const sphbasis::DirectionalRule rule = sphbasis::sphere_rule(60);
    for (std::size_t i = 0; i < rule.size(); ++i) {
        const RGB L = e.radiance({rule.x[i], rule.y[i], rule.z[i]});
        sphbasis::sh::eval(3, rule.x[i], rule.y[i], rule.z[i], y.data());
        for (std::size_t k = 0; k < 9; ++k) q[k] += rule.w[i] * L[1] * y[k];
    }
    for (std::size_t k = 0; k < 9; ++k) CHECK(p[k][1] == Approx(q[k]).margin(2e-3));
    CHECK_THROWS_WITH(render::project_sh(Environment{Environment::Kind::latlong}, 2),
                      Catch::Contains("sphbasis::render::validate()"));
}

TEST_CASE("Lights: radiance of each type", "[render][lighting]") {
    const vec3<double> d = unit({1, 2, 2});
    const Light cone = cone_light({2, 4, 4}, 20, {1, 2, 3});  // non-unit direction
    CHECK(render::light_radiance(cone, d)[1] == 2);
    CHECK(render::light_radiance(cone, tilted(d, 0.999 * 20 * constants::pi / 180))[2] == 3);
    CHECK(render::light_radiance(cone, tilted(d, 1.001 * 20 * constants::pi / 180))[2] == 0);
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = {0, 0, 3};
    hemi.color = {1, 1, 1};
    hemi.ground = {0.2, 0.3, 0.4};
    CHECK(render::light_radiance(hemi, {0.1, 0, 0.01})[0] == 1);
    CHECK(render::light_radiance(hemi, {0.1, 0, -0.01})[2] == 0.4);
    Light dir;
    dir.direction = d;
    CHECK(render::light_radiance(dir, d)[0] == 0);  // delta: only through irradiance() and sample()
    // Sphere light: radiance where the ray meets the ball (independent ray-ball test).
    Light sph = sphbasis_test::sphere_light({1, -2, 3}, 0.8, {5, 5, 5});
    const vec3<double> x{0.2, 0.1, -0.3};
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    int hits = 0;
    for (int k = 0; k < 4000; ++k) {
        const vec3<double> w = sphbasis::square_to_uniform_sphere(U(rng), U(rng));
        const vec3<double> o{x.x - sph.position.x, x.y - sph.position.y, x.z - sph.position.z};
        const double b = sphbasis::dot(o, w), c = sphbasis::dot(o, o) - sph.radius * sph.radius;
        const bool hit = b * b - c >= 0 && -b > 0;
        if (std::fabs(b * b - c) < 1e-9) continue;  // grazing: either answer
        hits += hit;
        CHECK((render::light_radiance(sph, w, x)[0] == 5) == hit);
    }
    CHECK(hits > 0);
    // Inside the ball: everywhere.
    CHECK(render::light_radiance(sph, {0, 0, -1}, sph.position)[0] == 5);
}

TEST_CASE("Lights: directional and hemisphere irradiance", "[render][lighting]") {
    Light dir;
    dir.direction = {0, 3, 4};  // not unit
    dir.color = {2, 4, 6};
    const vec3<double> n = unit({0, 1, 1});
    const double c = sphbasis::dot(n, unit(dir.direction));
    CHECK(render::light_irradiance(dir, n)[1] == Approx(4 * c).epsilon(1e-14));
    CHECK(render::light_irradiance(dir, {0, -3, -4})[0] == 0);
    // Hemisphere: quadrature of radiance() against the closed form, every tilt.
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = unit({1, -1, 2});
    hemi.color = {1.5, 1, 0.5};
    hemi.ground = {0.25, 0.5, 0.125};
    for (double beta : {0.0, 0.4, 1.2, constants::pi / 2, 2.0, 3.0, constants::pi}) {
        const vec3<double> nn = tilted(hemi.direction, beta);
        const RGB e = render::light_irradiance(hemi, nn);
        // The clamped cosine splits at w.d = 0 where the radiance jumps: integrate each half.
        const double up = band_cosine_integral(0, 1, std::cos(beta));
        const double down = band_cosine_integral(-1, 0, std::cos(beta));
        const RGB rs = render::light_radiance(hemi, hemi.direction);
        const RGB rg =
            render::light_radiance(hemi, {-hemi.direction.x, -hemi.direction.y, -hemi.direction.z});
        for (std::size_t k = 0; k < 3; ++k)
            CHECK(e[k] == Approx(rs[k] * up + rg[k] * down).epsilon(1e-7).margin(1e-9));
        CHECK(e[0] == Approx(constants::pi *
                             (1.5 * (1 + std::cos(beta)) / 2 + 0.25 * (1 - std::cos(beta)) / 2))
                          .epsilon(1e-12));
    }
}

TEST_CASE("Lights: cone irradiance against quadrature, horizon crossings included",
          "[render][lighting]") {
    const vec3<double> d = unit({0.3, -0.5, 0.8});
    for (double deg : {0.5, 5.0, 30.0, 60.0, 89.0, 90.0, 91.0, 135.0, 179.0, 180.0}) {
        const double a = deg * constants::pi / 180;
        const Light l = cone_light(d, deg, {1, 2, 0.5});
        for (double beta :
             {0.0, 0.3, 1.0, 1.4, 1.5, 1.55, 1.5707963267948966, 1.6, 1.8, 2.2, 2.9, 3.14159}) {
            const double cb = std::cos(beta);
            const double ref = band_cosine_integral(std::cos(a), 1, cb);
            const RGB e = render::light_irradiance(l, tilted(d, beta));
            INFO("angle " << deg << " beta " << beta);
            CHECK(e[0] == Approx(ref).epsilon(1e-6).margin(1e-9));
            CHECK(e[1] == Approx(2 * ref).epsilon(1e-6).margin(1e-9));
            // Wholly above the horizon: pi sin^2(a) cos(beta).
            if (beta + a < constants::pi / 2 - 1e-9)
                CHECK(e[0] ==
                      Approx(constants::pi * std::sin(a) * std::sin(a) * cb).epsilon(1e-12));
            if (beta - a > constants::pi / 2 + 1e-9) CHECK(e[0] == 0);
        }
    }
    // A full-sphere cone is the constant sky: pi at every normal.
    CHECK(render::light_irradiance(cone_light(d, 180, {1, 1, 1}), {0, 1, 0})[0] ==
          Approx(constants::pi).epsilon(1e-12));
    // 90 degrees: the hemisphere's pi (1 + cos)/2.
    CHECK(render::light_irradiance(cone_light(d, 90, {1, 1, 1}), tilted(d, 1.0))[0] ==
          Approx(constants::pi * (1 + std::cos(1.0)) / 2).epsilon(1e-12));
}

TEST_CASE("Lights: sphere light irradiance as a function of the point", "[render][lighting]") {
    Light s = sphbasis_test::sphere_light({0, 0, 2}, 1, {3, 3, 3});
    // On the plane z = 0 below the centre facing up: pi L sin^2(a) = pi L r^2 / D^2.
    CHECK(render::light_irradiance(s, {0, 0, 1}, {0, 0, 0})[0] ==
          Approx(3 * constants::pi / 4).epsilon(1e-12));
    // Points on a line, normals fixed: the ball crosses the horizon of the tilted normal.
    for (double xoff : {0.0, 0.5, 1.5, 3.0, 6.0}) {
        const vec3<double> x{xoff, 0.3, 0};
        const vec3<double> n = unit({1, 0.2, 0.4});
        const vec3<double> p{s.position.x - x.x, s.position.y - x.y, s.position.z - x.z};
        const double D = std::sqrt(sphbasis::dot(p, p));
        const double ca = std::sqrt(1 - (s.radius / D) * (s.radius / D));
        const double ref = 3 * band_cosine_integral(ca, 1, sphbasis::dot(n, unit(p)));
        INFO("x offset " << xoff);
        CHECK(render::light_irradiance(s, n, x)[0] == Approx(ref).epsilon(1e-6).margin(1e-9));
    }
    // Far away it is a directional light of irradiance L pi r^2 / D^2.
    Light far = s;
    far.position = {0, 1000, 1000};
    const double D2 = 2e6;
    CHECK(render::light_irradiance(far, {0, 0, 1})[0] ==
          Approx(3 * constants::pi / D2 * unit(far.position).z).epsilon(1e-6));
    // Inside the ball: the whole sphere, pi L.
    CHECK(render::light_irradiance(s, {1, 0, 0}, {0, 0, 2.5})[0] == Approx(3 * constants::pi));
}

TEST_CASE("Lights: SH projections against quadrature of radiance()", "[render][lighting]") {
    const int bands = 5, n2 = bands * bands;
    auto check_light = [&](const Light& l, const vec3<double>& axis, std::vector<double> splits,
                           const vec3<double>& x) {
        std::vector<RGB> ref(static_cast<std::size_t>(n2), RGB{0, 0, 0});
        std::vector<double> y(static_cast<std::size_t>(n2));
        split_quadrature(axis, splits, 12, 24, [&](const vec3<double>& w, double wt) {
            const RGB L = render::light_radiance(l, w, x);
            sphbasis::sh::eval(bands, w.x, w.y, w.z, y.data());
            for (int k = 0; k < n2; ++k)
                for (int c = 0; c < 3; ++c)
                    ref[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)] +=
                        wt * L[static_cast<std::size_t>(c)] * y[static_cast<std::size_t>(k)];
        });
        const std::vector<RGB> got = render::project_sh(l, bands, x);
        REQUIRE(got.size() == static_cast<std::size_t>(n2));
        for (int k = 0; k < n2; ++k)
            for (int c = 0; c < 3; ++c)
                CHECK(got[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)] ==
                      Approx(ref[static_cast<std::size_t>(k)][static_cast<std::size_t>(c)])
                          .margin(1e-11));
    };
    const vec3<double> d = unit({-0.2, 0.7, 0.4});
    for (double deg : {10.0, 75.0, 120.0}) {
        INFO("cone " << deg);
        check_light(cone_light(d, deg, {1, 0.5, 2}), d, {std::cos(deg * constants::pi / 180)},
                    {0, 0, 0});
    }
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = d;
    hemi.color = {1, 2, 3};
    hemi.ground = {0.5, 0.25, 0.0};
    check_light(hemi, d, {0.0}, {0, 0, 0});
    Light s = sphbasis_test::sphere_light({1, 2, 3}, 1.5, {2, 1, 1});
    const vec3<double> x{0.5, -0.5, 0.2};
    const vec3<double> p{s.position.x - x.x, s.position.y - x.y, s.position.z - x.z};
    const double D = std::sqrt(sphbasis::dot(p, p));
    check_light(s, unit(p), {std::sqrt(1 - s.radius * s.radius / (D * D))}, x);
    // Directional: color y_lm(d).
    Light dir;
    dir.direction = {0, 0, 2};
    dir.color = {1, 2, 3};
    const std::vector<RGB> c = render::project_sh(dir, 2, {0, 0, 0});
    CHECK(c[0][1] == Approx(2 * constants::inv_sqrt_four_pi).epsilon(1e-14));
    CHECK(c[2][2] == Approx(3 * 0.48860251190291992).epsilon(1e-14));  // y_10 = sqrt(3/(4 pi)) z
    CHECK(c[1][2] == Approx(0).margin(1e-15));
    CHECK_THROWS_WITH(render::project_sh(dir, -1), Catch::Contains("bands"));
}

TEST_CASE("Lights: sampling pdf integrates to one and the estimator converges",
          "[render][lighting]") {
    const vec3<double> d = unit({0.1, 0.9, 0.3});
    Light sph = sphbasis_test::sphere_light({0.5, 2, 1}, 0.7, {2, 2, 2});
    Light hemi;
    hemi.type = Light::Type::hemisphere;
    hemi.direction = d;
    hemi.color = {1, 1, 1};
    hemi.ground = {0.3, 0.3, 0.3};
    const vec3<double> x{0, 0, 0};
    const vec3<double> n = unit({0.8, 0.2, 0.1});  // the cone and the ball cross its horizon
    const Light lights[] = {cone_light(d, 40, {1, 1, 1}), cone_light(d, 150, {1, 1, 1}), sph, hemi};
    for (const Light& l : lights) {
        INFO(render::light_type_name(l.type) << " angle " << l.angle_deg);
        // The pdf integrates to one over the sphere (split where it jumps).
        vec3<double> axis = d;
        double split = std::cos(l.angle_deg * constants::pi / 180);
        if (l.type == Light::Type::sphere) {
            axis = unit(l.position);
            const double D2 = sphbasis::dot(l.position, l.position);
            split = std::sqrt(1 - l.radius * l.radius / D2);
        }
        if (l.type == Light::Type::hemisphere) split = 0;
        double total = 0;
        split_quadrature(axis, {split}, 8, 16, [&](const vec3<double>& w, double wt) {
            total += wt * render::sample_light_pdf(l, x, w);
        });
        CHECK(total == Approx(1).epsilon(1e-12));
        // The estimator over 4096 Hammersley points converges to the closed form.
        const std::uint32_t N = 4096;
        double sum = 0, sum2 = 0;
        int bad_pdf = 0, bad_unit = 0, bad_radiance = 0, bad_distance = 0;
        for (std::uint32_t i = 0; i < N; ++i) {
            double u1, u2;
            sphbasis::hammersley(i, N, u1, u2);
            const render::LightSample s = render::sample_light(l, x, u1, u2);
            REQUIRE(s.pdf > 0);
            bad_pdf += std::fabs(s.pdf - render::sample_light_pdf(l, x, s.w)) > 1e-12 * s.pdf;
            bad_unit += std::fabs(sphbasis::dot(s.w, s.w) - 1) > 1e-14;
            bad_radiance += s.radiance[0] != render::light_radiance(l, s.w, x)[0];
            if (l.type == Light::Type::sphere) {
                // x + distance w lies on the ball's near surface.
                const vec3<double> q{s.distance * s.w.x - l.position.x,
                                     s.distance * s.w.y - l.position.y,
                                     s.distance * s.w.z - l.position.z};
                bad_distance += std::fabs(std::sqrt(sphbasis::dot(q, q)) - l.radius) > 1e-9 ||
                                !(s.distance < std::sqrt(sphbasis::dot(l.position, l.position)));
            } else {
                bad_distance += !std::isinf(s.distance);
            }
            const double f = s.radiance[0] * std::max(0.0, sphbasis::dot(n, s.w)) / s.pdf;
            sum += f;
            sum2 += f * f;
        }
        CHECK(bad_pdf == 0);
        CHECK(bad_unit == 0);
        CHECK(bad_radiance == 0);
        CHECK(bad_distance == 0);
        const double mean = sum / N;
        const double stderr_ = std::sqrt(std::max(0.0, sum2 / N - mean * mean) / N);
        const double ref = render::light_irradiance(l, n, x)[0];
        CHECK(std::fabs(mean - ref) <= 4 * stderr_ + 1e-12);
        CHECK(std::fabs(mean - ref) <= 0.01 * ref);
    }
    // Directional: delta sample, exact estimator.
    Light dir;
    dir.direction = {0, 0, 2};
    dir.color = {4, 4, 4};
    const render::LightSample s = render::sample_light(dir, x, 0.3, 0.6);
    CHECK(s.delta);
    CHECK(s.pdf == 1);
    CHECK(s.w.z == 1);
    CHECK(s.radiance[0] * std::max(0.0, sphbasis::dot(n, s.w)) ==
          Approx(render::light_irradiance(dir, n)[0]));
}

TEST_CASE("Lights: validate rejects bad lights with clear messages", "[render][lighting]") {
    Light ok = cone_light({0, 0, 5}, 30, {1, 1, 1});
    CHECK_NOTHROW(render::validate(ok));
    {
        Light b = ok;
        b.direction = {0, 0, 0};
        CHECK_THROWS_WITH(render::validate(b),
                          Catch::Contains("finite non-zero direction for a cone light"));
    }
    {
        Light b = ok;
        b.angle_deg = 0;
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("0 < angle_deg <= 180"));
        b.angle_deg = 190;
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("0 < angle_deg <= 180"));
        b.angle_deg = 180;
        CHECK_NOTHROW(render::validate(b));
    }
    {
        Light b = ok;
        b.color[1] = std::nan("");
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("finite color"));
    }
    {
        Light b;
        b.type = Light::Type::sphere;
        b.position = {0, 0, 1};
        b.radius = 0;
        CHECK_THROWS_WITH(render::validate(b),
                          Catch::Contains("finite radius > 0 for a sphere light, got 0"));
        b.radius = 1;
        b.position.y = std::numeric_limits<double>::infinity();
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("finite position"));
    }
    {
        Light b;
        b.type = Light::Type::hemisphere;
        b.ground[2] = std::numeric_limits<double>::infinity();
        CHECK_THROWS_WITH(render::validate(b), Catch::Contains("finite ground color"));
    }
    {
        Light b;
        b.direction = {std::nan(""), 0, 1};
        CHECK_THROWS_WITH(render::validate(b), Catch::StartsWith("sphbasis::render::validate()"));
        // The hot functions stay finite on it (the pole is read).
        CHECK(std::isfinite(render::light_irradiance(b, {0, 0, 1})[0]));
    }
}
