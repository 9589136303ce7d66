// sphbasis render tier: the distant lighting of a scene (an environment and analytic lights).
//
// What is here, all in double precision, all radiances in linear RGB:
//   * Environment::radiance(w): a constant, or a lat-long RGB image in the library's lat-long
//     convention (param/latlong.hpp: u = phi/(2 pi), v = theta/pi, row 0 at +z), bilinear
//     between texel centres with wrap addressing in u and clamp-to-edge in v, rotated by
//     `rotation` (world = rotation * map, so the map is read at rotation^T w) and times `scale`.
//     validate(Environment) checks the struct once; radiance() itself never throws.
//   * Analytic lights (struct Light): light_radiance(light, w[, x]), the closed-form unoccluded
//     irradiance light_irradiance(light, n[, x]) of a surface with unit normal n (at point x for
//     the sphere light), sample_light(light, x, u1, u2) and sample_light_pdf(light, x, w) for
//     Monte Carlo with occlusion (direction, pdf, radiance, distance to the emitter), and
//     project_sh(light, bands[, x]), the SH coefficients of the light's radiance
//     (ops/sh_lights.hpp does the work); project_sh(environment, bands) likewise.
//     (The free functions carry a light_ prefix, apart from the bake quantities
//     render::Quantity::radiance and ::irradiance of bake.hpp.)
//
// Irradiance of a uniform spherical cap. A cap of angular radius a about the unit direction d,
// of radiance L, seen from a surface with unit normal n, cos(beta) = n . d, delivers
//   E = L integral_cap max(n . w, 0) dw.
// Fully above the horizon (beta <= pi/2 - a, i.e. cos(beta) >= sin(a)) the clamp is inactive
// and E = L (n . integral_cap w dw) = L pi sin^2(a) cos(beta); fully below (beta >= pi/2 + a)
// E = 0. Across the horizon, with x = cot(a), y = -cot(a) cot(beta) (|y| <= 1 there) and
// s = sin(beta) sqrt(1 - y^2),
//   E = L [ (cos(beta) acos(y) - x s) sin^2(a) + atan(s / x) ],
// the form factor of a sphere to a tilted differential area: J. Snyder, "Area Light Sources
// for Real-Time Graphics" (Microsoft Research tech. report MSR-TR-96-11, 1996), and in this form
// S. Lagarde and C. de Rousiers, "Moving Frostbite to Physically Based Rendering" (SIGGRAPH
// 2014 course notes, section 4.7.2, sphere and disk illuminance). It is continuous with both
// other cases and atan(s/x) is taken as atan2(s, x), so a = pi/2 (x = 0) gives the hemisphere's
// pi (1 + cos(beta))/2. Caps wider than a hemisphere are the sphere (E = L pi) minus the
// complementary cap about -d. The tests compare it with quadrature, horizon crossings included.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../core/sampling.hpp"
#include "../core/vec.hpp"
#include "../ops/sh_latlong.hpp"
#include "../ops/sh_lights.hpp"
#include "../ops/sh_rotation.hpp"
#include "../param/latlong.hpp"

namespace sphbasis::render {

using RGB = std::array<double, 3>;

/// Distant radiance L(w) arriving from direction w (unit, pointing away from the scene toward
/// the sky). Either a constant or a lat-long RGB image in the library's lat-long convention
/// (param/latlong.hpp: row 0 at +z), rotated by `rotation` (world = rotation * map) and
/// multiplied by `scale`. The texels are borrowed.
struct Environment {
    enum class Kind { none, constant, latlong };
    Kind kind = Kind::none;
    RGB constant{0, 0, 0};
    const float* texels = nullptr;  // RGB, width * height * 3, row-major
    int width = 0, height = 0;
    Mat3<double> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
    double scale = 1.0;

    /// L(w), bilinear in the image; 0 for Kind::none.
    ///   constant: `constant * scale` for every w.
    ///   latlong:  m = rotation^T w (normalised; a zero or non-finite w reads the pole +z),
    ///             (u, v) = param::latlong_to_square(m), texel (col, row) has its centre at
    ///             ((col + 1/2)/width, (row + 1/2)/height); bilinear between the four nearest
    ///             centres, columns wrapping (the seam phi = 0 is continuous), rows clamped
    ///             (within half a texel of a pole the first/last row of centres is read).
    /// Exactly the texel value at a texel centre. Never throws; call validate() once on a struct
    /// from outside (a latlong map with null texels or no size reads 0 here). Cost: one atan2,
    /// one 3x3 product, four texel reads.
    RGB radiance(const vec3<double>& w) const noexcept;
};

/// Throws std::invalid_argument ("sphbasis::render::validate(): expected ...") unless the
/// environment is usable: scale finite; rotation finite and orthonormal (max |R R^T - I| <=
/// 1e-6); for Kind::constant a finite constant; for Kind::latlong non-null texels, width >= 1,
/// height >= 1, width * height < 2^31, and every texel value finite (one pass over the image).
inline void validate(const Environment& env) {
    const char* fn = "render::validate";
    if (!std::isfinite(env.scale))
        sphbasis::detail::throw_invalid(
            fn, "a finite environment scale, got " + std::to_string(env.scale));
    sphbasis::detail::check_orthonormal(env.rotation, 1e-6, fn);
    if (env.kind == Environment::Kind::constant) {
        for (double c : env.constant)
            if (!std::isfinite(c))
                sphbasis::detail::throw_invalid(
                    fn, "a finite constant environment radiance, got " + std::to_string(c));
    } else if (env.kind == Environment::Kind::latlong) {
        if (env.width < 1 || env.height < 1 ||
            static_cast<long long>(env.width) * env.height >= (1LL << 31))
            sphbasis::detail::throw_invalid(fn,
                                            "a lat-long environment of width >= 1 and height >= 1 "
                                            "texels (fewer than 2^31), got " +
                                                std::to_string(env.width) + " x " +
                                                std::to_string(env.height));
        if (env.texels == nullptr)
            sphbasis::detail::throw_invalid(fn,
                                            "non-null texels for a lat-long environment, got null");
        const std::size_t n =
            static_cast<std::size_t>(env.width) * static_cast<std::size_t>(env.height) * 3;
        for (std::size_t i = 0; i < n; ++i)
            if (!std::isfinite(env.texels[i]))
                sphbasis::detail::throw_invalid(fn, "finite environment texels, got " +
                                                        std::to_string(env.texels[i]) +
                                                        " at float " + std::to_string(i));
    }
}

inline RGB Environment::radiance(const vec3<double>& w) const noexcept {
    if (kind == Kind::constant)
        return {constant[0] * scale, constant[1] * scale, constant[2] * scale};
    if (kind != Kind::latlong || texels == nullptr || width < 1 || height < 1) return {0, 0, 0};
    // Map direction m = R^T w.
    const Mat3<double>& r = rotation;
    double mx = r[0] * w.x + r[3] * w.y + r[6] * w.z;
    double my = r[1] * w.x + r[4] * w.y + r[7] * w.z;
    double mz = r[2] * w.x + r[5] * w.y + r[8] * w.z;
    normalize_or_pole(mx, my, mz);
    const param::Point2<double> uv = param::latlong_to_square(mx, my, mz);
    const double fxw = uv.x * width - 0.5, fyh = uv.y * height - 0.5;
    const double x0 = std::floor(fxw), y0 = std::floor(fyh);
    const double fx = fxw - x0, fy = fyh - y0;
    // uv in [0, 1] and width, height < 2^31 keep these in int range.
    int i0 = static_cast<int>(x0), j0 = static_cast<int>(y0);
    int i1 = i0 + 1, j1 = j0 + 1;
    auto wrap = [this](int i) { return i < 0 ? i + width : (i >= width ? i - width : i); };
    auto clamp = [this](int j) { return j < 0 ? 0 : (j >= height ? height - 1 : j); };
    i0 = wrap(i0);
    i1 = wrap(i1);
    j0 = clamp(j0);
    j1 = clamp(j1);
    const std::size_t W = static_cast<std::size_t>(width);
    const float* t00 =
        texels + 3 * (static_cast<std::size_t>(j0) * W + static_cast<std::size_t>(i0));
    const float* t10 =
        texels + 3 * (static_cast<std::size_t>(j0) * W + static_cast<std::size_t>(i1));
    const float* t01 =
        texels + 3 * (static_cast<std::size_t>(j1) * W + static_cast<std::size_t>(i0));
    const float* t11 =
        texels + 3 * (static_cast<std::size_t>(j1) * W + static_cast<std::size_t>(i1));
    const double w00 = (1 - fx) * (1 - fy), w10 = fx * (1 - fy), w01 = (1 - fx) * fy, w11 = fx * fy;
    RGB out;
    for (std::size_t c = 0; c < 3; ++c)
        out[c] = scale * (w00 * static_cast<double>(t00[c]) + w10 * static_cast<double>(t10[c]) +
                          w01 * static_cast<double>(t01[c]) + w11 * static_cast<double>(t11[c]));
    return out;
}

/// SH coefficients (real, no Condon-Shortley phase, ACN, bands^2 RGB values) of the
/// environment's radiance: Kind::none gives zeros; Kind::constant exactly
/// (constant scale sqrt(4 pi), 0, ...); Kind::latlong the exact projection of the
/// piecewise-constant map (every texel constant over its solid angle: ops/sh_latlong.hpp),
/// times scale, then rotated by `rotation` (ops/sh_rotation.hpp). radiance() interpolates the
/// same texels bilinearly; the two differ by O(1/height) in the coefficients of the highest
/// bands (and not at all for a constant map). Cost O(width height bands) + O(bands^3).
/// Throws std::invalid_argument for an environment validate() rejects, bands outside sh's
/// range or a map larger than 2^20 texels on a side.
inline std::vector<RGB> project_sh(const Environment& env, int bands) {
    validate(env);
    sh::check_bands(bands, "render::project_sh");
    const std::size_t n = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    std::vector<RGB> out(n, RGB{0, 0, 0});
    if (bands == 0 || env.kind == Environment::Kind::none) return out;
    if (env.kind == Environment::Kind::constant) {
        const double s = env.scale * constants::four_pi * constants::inv_sqrt_four_pi;
        out[0] = {env.constant[0] * s, env.constant[1] * s, env.constant[2] * s};
        return out;
    }
    std::vector<double> a(n), b(n);
    const std::size_t W = static_cast<std::size_t>(env.width);
    for (std::size_t c = 0; c < 3; ++c) {
        sh::project_latlong_fn(
            bands, env.width, env.height,
            [&](int col, int row) {
                return static_cast<double>(env.texels[3 * (static_cast<std::size_t>(row) * W +
                                                           static_cast<std::size_t>(col)) +
                                                      c]);
            },
            a.data());
        sh::rotate(bands, env.rotation, a.data(), b.data(), 1e-6);
        for (std::size_t k = 0; k < n; ++k) out[k][c] = env.scale * b[k];
    }
    return out;
}

/// An analytic distant light. `direction` points toward the light (unit).
///   directional: irradiance `color` on a surface facing it (a delta light).
///   sphere:      a sphere of radiance `color` at `position` with `radius` (local light).
///   cone:        distant constant radiance `color` within `angle_deg` (half-angle) of direction.
///   hemisphere:  radiance `color` from the hemisphere around direction, `ground` from the other.
/// The functions below normalise `direction` themselves (a zero or non-finite one reads +z);
/// validate(Light) rejects such lights with a message.
struct Light {
    enum class Type { directional, sphere, cone, hemisphere };
    Type type = Type::directional;
    vec3<double> direction{0, 0, 1};
    vec3<double> position{0, 0, 0};
    double radius = 0, angle_deg = 0;
    RGB color{1, 1, 1}, ground{0, 0, 0};
};

/// The name of a light type: "directional", "sphere", "cone", "hemisphere".
inline const char* light_type_name(Light::Type t) noexcept {
    switch (t) {
        case Light::Type::directional:
            return "directional";
        case Light::Type::sphere:
            return "sphere";
        case Light::Type::cone:
            return "cone";
        case Light::Type::hemisphere:
            return "hemisphere";
    }
    return "unknown";
}

/// Throws std::invalid_argument ("sphbasis::render::validate(): expected ...") unless the light
/// is usable: a known type; finite colours (and ground); for directional, cone and hemisphere a
/// finite non-zero direction (it need not be unit: the functions normalise it); for the sphere
/// a finite position and a finite radius > 0; for the cone 0 < angle_deg <= 180.
inline void validate(const Light& light) {
    const char* fn = "render::validate";
    const int t = static_cast<int>(light.type);
    if (t < 0 || t > 3)
        sphbasis::detail::throw_invalid(
            fn, "a light type directional, sphere, cone or hemisphere, got " + std::to_string(t));
    const std::string name = std::string(light_type_name(light.type)) + " light";
    for (double c : light.color)
        if (!std::isfinite(c))
            sphbasis::detail::throw_invalid(
                fn, "a finite color for a " + name + ", got " + std::to_string(c));
    if (light.type == Light::Type::hemisphere)
        for (double c : light.ground)
            if (!std::isfinite(c))
                sphbasis::detail::throw_invalid(
                    fn, "a finite ground color for a hemisphere light, got " + std::to_string(c));
    if (light.type == Light::Type::sphere) {
        const vec3<double>& p = light.position;
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            sphbasis::detail::throw_invalid(fn, "a finite position for a sphere light");
        if (!(light.radius > 0) || !std::isfinite(light.radius))
            sphbasis::detail::throw_invalid(
                fn, "a finite radius > 0 for a sphere light, got " + std::to_string(light.radius));
        return;
    }
    const vec3<double>& d = light.direction;
    if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z) ||
        (d.x == 0 && d.y == 0 && d.z == 0))
        sphbasis::detail::throw_invalid(
            fn, "a finite non-zero direction for a " + name + ", got (" + std::to_string(d.x) +
                    ", " + std::to_string(d.y) + ", " + std::to_string(d.z) + ")");
    if (light.type == Light::Type::cone && !(light.angle_deg > 0 && light.angle_deg <= 180))
        sphbasis::detail::throw_invalid(
            fn, "0 < angle_deg <= 180 for a cone light, got " + std::to_string(light.angle_deg));
}

namespace detail {

inline vec3<double> unit_or_pole(vec3<double> v) noexcept {
    normalize_or_pole(v.x, v.y, v.z);
    return v;
}

/// A cap about a unit direction: cos and sin^2 of its angular radius and 1 - cos (all without
/// cancellation).
struct Cap {
    vec3<double> d{0, 0, 1};
    double cos_a = 1, sin2_a = 0, one_minus_cos = 0;
    double dist = std::numeric_limits<double>::infinity();  // to the sphere centre (sphere only)
    bool inside = false;  // the receiver is inside the sphere light: the whole sphere
};

/// The cap of a cone light (half-angle in degrees, clamped to [0, 180]).
inline Cap cone_cap(const Light& l) noexcept {
    Cap c;
    c.d = unit_or_pole(l.direction);
    double a = l.angle_deg * (constants::pi / 180);
    a = a > 0 ? (a < constants::pi ? a : constants::pi) : 0;  // NaN -> 0
    const double s = std::sin(0.5 * a);
    c.one_minus_cos = 2 * s * s;
    c.cos_a = std::cos(a);
    const double sa = std::sin(a);
    c.sin2_a = sa * sa;
    return c;
}

/// The cap a sphere light subtends at x: sin(a) = r / |p - x|; the whole sphere inside.
inline Cap sphere_cap(const Light& l, const vec3<double>& x) noexcept {
    Cap c;
    vec3<double> p{l.position.x - x.x, l.position.y - x.y, l.position.z - x.z};
    const double big = std::max(std::fabs(p.x), std::max(std::fabs(p.y), std::fabs(p.z)));
    double dist = 0;
    if (big > 0 && std::isfinite(big)) {
        const double qx = p.x / big, qy = p.y / big, qz = p.z / big;
        dist = big * std::sqrt(qx * qx + qy * qy + qz * qz);
    }
    c.d = unit_or_pole(p);
    c.dist = dist;
    const double r = std::fabs(l.radius);
    if (!(r < dist)) {  // inside (or NaN): every direction sees the emitter
        c.inside = true;
        c.cos_a = -1;
        c.sin2_a = 0;
        c.one_minus_cos = 2;
        return c;
    }
    const double s = r / dist;
    c.sin2_a = s * s;
    const double ca = std::sqrt((1 - s) * (1 + s));
    c.cos_a = ca;
    c.one_minus_cos = c.sin2_a / (1 + ca);
    return c;
}

/// integral over the cap of max(n . w, 0) dw for cos(beta) = n . d (header comment).
inline double cap_cosine_integral(double cb, double cos_a, double sin2_a) noexcept {
    cb = std::clamp(cb, -1.0, 1.0);
    if (cos_a < 0) {
        // Wider than a hemisphere: the sphere minus the complementary cap about -d.
        return std::max(0.0, constants::pi - cap_cosine_integral(-cb, -cos_a, sin2_a));
    }
    if (!(sin2_a > 0)) return 0;
    if (cb * cb > sin2_a) return cb > 0 ? constants::pi * sin2_a * cb : 0;
    const double sb = std::sqrt((1 - cb) * (1 + cb));
    if (!(sb > 0)) return constants::pi * 0.5 * (1 + cb);  // |cb| = 1 with sin a = 1: hemisphere
    const double sa = std::sqrt(sin2_a);
    const double x = cos_a / sa;
    const double y = std::clamp(-x * cb / sb, -1.0, 1.0);
    const double s = sb * std::sqrt((1 - y) * (1 + y));
    const double e = (cb * std::acos(y) - x * s) * sin2_a + std::atan2(s, x);
    return e > 0 ? e : 0;
}

inline RGB scaled(const RGB& c, double s) noexcept { return {c[0] * s, c[1] * s, c[2] * s}; }

}  // namespace detail

/// Radiance of the light arriving at point x (used by the sphere light only; the distant lights
/// ignore it) from direction w (normalised here; a zero or non-finite w reads +z):
///   directional: 0 (a delta light: its light arrives only through light_irradiance()
///                and sample_light());
///   cone:        color where w . d >= cos(angle), else 0;
///   hemisphere:  color where w . d >= 0, ground where w . d < 0;
///   sphere:      color where the ray x + t w (t > 0) meets the ball, i.e. w . d >= cos(a) with
///                sin(a) = radius / |position - x|; color everywhere when x is inside the ball.
/// Never throws. Cost: a few flops (one sqrt).
inline RGB light_radiance(const Light& light, const vec3<double>& w,
                          const vec3<double>& x = {0, 0, 0}) noexcept {
    const vec3<double> u = detail::unit_or_pole(w);
    switch (light.type) {
        case Light::Type::directional:
            return {0, 0, 0};
        case Light::Type::hemisphere:
            return dot(u, detail::unit_or_pole(light.direction)) >= 0 ? light.color : light.ground;
        case Light::Type::cone: {
            const detail::Cap c = detail::cone_cap(light);
            // 1 - w.d <= 1 - cos a, written so small cones keep their relative accuracy.
            const vec3<double> e{u.x - c.d.x, u.y - c.d.y, u.z - c.d.z};
            return 0.5 * dot(e, e) <= c.one_minus_cos ? light.color : RGB{0, 0, 0};
        }
        case Light::Type::sphere: {
            const detail::Cap c = detail::sphere_cap(light, x);
            if (c.inside) return light.color;
            const vec3<double> e{u.x - c.d.x, u.y - c.d.y, u.z - c.d.z};
            return 0.5 * dot(e, e) <= c.one_minus_cos ? light.color : RGB{0, 0, 0};
        }
    }
    return {0, 0, 0};
}

/// Unoccluded irradiance E(n) = integral L(w) max(n . w, 0) dw at a surface with normal n
/// (normalised here) at point x (used by the sphere light only), in closed form:
///   directional: color max(n . d, 0);
///   hemisphere:  pi (color (1 + n.d)/2 + ground (1 - n.d)/2);
///   cone:        color times the cap's cosine integral (header comment: pi sin^2(a) n.d when
///                the cone is wholly above the horizon, 0 wholly below, Snyder's form across it);
///   sphere:      the same with the cap the ball subtends at x (pi color when x is inside it).
/// A white Lambertian surface reflects E/pi. Never throws. Cost: a few transcendental calls.
inline RGB light_irradiance(const Light& light, const vec3<double>& n,
                            const vec3<double>& x = {0, 0, 0}) noexcept {
    const vec3<double> nn = detail::unit_or_pole(n);
    switch (light.type) {
        case Light::Type::directional: {
            const double c = dot(nn, detail::unit_or_pole(light.direction));
            return detail::scaled(light.color, c > 0 ? c : 0);
        }
        case Light::Type::hemisphere: {
            const double c = std::clamp(dot(nn, detail::unit_or_pole(light.direction)), -1.0, 1.0);
            const double ws = constants::pi * 0.5 * (1 + c), wg = constants::pi * 0.5 * (1 - c);
            return {light.color[0] * ws + light.ground[0] * wg,
                    light.color[1] * ws + light.ground[1] * wg,
                    light.color[2] * ws + light.ground[2] * wg};
        }
        case Light::Type::cone: {
            const detail::Cap c = detail::cone_cap(light);
            return detail::scaled(light.color,
                                  detail::cap_cosine_integral(dot(nn, c.d), c.cos_a, c.sin2_a));
        }
        case Light::Type::sphere: {
            const detail::Cap c = detail::sphere_cap(light, x);
            if (c.inside) return detail::scaled(light.color, constants::pi);
            return detail::scaled(light.color,
                                  detail::cap_cosine_integral(dot(nn, c.d), c.cos_a, c.sin2_a));
        }
    }
    return {0, 0, 0};
}

/// A direction sampled on a light for Monte Carlo: the estimator of the irradiance at a surface
/// with normal n is (radiance * max(n . w, 0) / pdf) times the visibility of w, the visibility
/// ray running from x up to `distance` (infinity for distant lights; for the sphere light the
/// distance to the near side of the ball). For the directional light (delta = true) pdf is 1
/// and radiance is the light's irradiance `color`: the same estimator is then exact.
struct LightSample {
    vec3<double> w{0, 0, 1};  // unit, toward the light
    RGB radiance{0, 0, 0};
    double pdf = 0;  // w.r.t. solid angle (1 for the delta light)
    double distance = std::numeric_limits<double>::infinity();
    bool delta = false;
};

/// Samples a direction toward the light from point x (used by the sphere light only) with
/// (u1, u2) in [0, 1)^2:
///   directional: w = d, pdf 1, delta;
///   cone, sphere: uniform in the cone of directions, cos(theta) = 1 - u1 (1 - cos a),
///                phi = 2 pi u2 about d (core/frame.hpp's Frame), pdf 1/(2 pi (1 - cos a));
///                for x inside the sphere light uniform over the sphere (pdf 1/(4 pi),
///                distance 0: nothing can occlude it);
///   hemisphere:  uniform over the sphere, pdf 1/(4 pi), radiance color or ground.
/// Never throws; a cone of angle 0 gives pdf infinity and radiance 0 (it carries no light).
inline LightSample sample_light(const Light& light, const vec3<double>& x, double u1,
                                double u2) noexcept {
    LightSample s;
    switch (light.type) {
        case Light::Type::directional:
            s.w = detail::unit_or_pole(light.direction);
            s.radiance = light.color;
            s.pdf = 1;
            s.delta = true;
            return s;
        case Light::Type::hemisphere: {
            s.w = square_to_uniform_sphere(u1, u2);
            s.pdf = constants::inv_four_pi;
            s.radiance =
                dot(s.w, detail::unit_or_pole(light.direction)) >= 0 ? light.color : light.ground;
            return s;
        }
        case Light::Type::cone:
        case Light::Type::sphere: {
            const detail::Cap c = light.type == Light::Type::cone ? detail::cone_cap(light)
                                                                  : detail::sphere_cap(light, x);
            if (c.inside) {
                s.w = square_to_uniform_sphere(u1, u2);
                s.pdf = constants::inv_four_pi;
                s.radiance = light.color;
                s.distance = 0;
                return s;
            }
            if (!(c.one_minus_cos > 0)) {
                s.w = c.d;
                s.pdf = std::numeric_limits<double>::infinity();
                return s;
            }
            // 1 - cos(theta) = u1 (1 - cos a); sin(theta) from it without cancellation.
            const double omc = u1 * c.one_minus_cos;
            const double ct = 1 - omc;
            const double st = std::sqrt(std::max(0.0, omc * (2 - omc)));
            const double phi = constants::two_pi * u2;
            const Frame<double> f(c.d);
            s.w = detail::unit_or_pole(
                f.to_world(vec3<double>{st * std::cos(phi), st * std::sin(phi), ct}));
            s.pdf = 1 / (constants::two_pi * c.one_minus_cos);
            s.radiance = light.color;
            if (light.type == Light::Type::sphere) {
                // Near intersection of x + t w with the ball: t = D ct - sqrt(r^2 - D^2 st^2).
                const double D = c.dist, r = std::fabs(light.radius);
                const double h = std::max(0.0, r * r - D * D * st * st);
                s.distance = std::max(0.0, D * ct - std::sqrt(h));
            }
            return s;
        }
    }
    return s;
}

/// Probability density (solid angle) of sample_light() choosing w at x; 0 outside the cone, 0 for
/// the directional light (a delta: no density over directions).
inline double sample_light_pdf(const Light& light, const vec3<double>& x,
                               const vec3<double>& w) noexcept {
    switch (light.type) {
        case Light::Type::directional:
            return 0;
        case Light::Type::hemisphere:
            return constants::inv_four_pi;
        case Light::Type::cone:
        case Light::Type::sphere: {
            const detail::Cap c = light.type == Light::Type::cone ? detail::cone_cap(light)
                                                                  : detail::sphere_cap(light, x);
            if (c.inside) return constants::inv_four_pi;
            if (!(c.one_minus_cos > 0)) return 0;
            const vec3<double> u = detail::unit_or_pole(w);
            const vec3<double> e{u.x - c.d.x, u.y - c.d.y, u.z - c.d.z};
            return 0.5 * dot(e, e) <= c.one_minus_cos ? 1 / (constants::two_pi * c.one_minus_cos)
                                                      : 0;
        }
    }
    return 0;
}

/// SH coefficients (real, no Condon-Shortley phase, ACN, `bands` bands: bands^2 RGB values) of
/// the light's radiance L(w) as seen from point x (used by the sphere light only), by
/// ops/sh_lights.hpp: directional color y_lm(d) (a delta), cone and sphere the uniform cap's
/// Funk-Hecke factors, hemisphere the sky cap plus the ground. Convolve with the clamped cosine
/// (core/clamped_cosine.hpp) for irradiance. Throws std::invalid_argument for a light that
/// validate() rejects or bands outside sh's range.
inline std::vector<RGB> project_sh(const Light& light, int bands,
                                   const vec3<double>& x = {0, 0, 0}) {
    validate(light);
    sh::check_bands(bands, "render::project_sh");
    const std::size_t n = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    std::vector<RGB> out(n, RGB{0, 0, 0});
    std::vector<double> a(n), b(n);
    const vec3<double> d = detail::unit_or_pole(light.direction);
    switch (light.type) {
        case Light::Type::directional:
            sh::directional_light(bands, d.x, d.y, d.z, 1.0, a.data());
            break;
        case Light::Type::cone:
            sh::cone_light(bands, d.x, d.y, d.z, light.angle_deg * (constants::pi / 180), 1.0,
                           a.data());
            break;
        case Light::Type::sphere: {
            const vec3<double> p{light.position.x - x.x, light.position.y - x.y,
                                 light.position.z - x.z};
            if (p.x == 0 && p.y == 0 && p.z == 0) {
                a[0] = constants::four_pi * constants::inv_sqrt_four_pi;  // inside: everything
            } else {
                sh::spherical_light(bands, p.x, p.y, p.z, light.radius, 1.0, a.data());
            }
            break;
        }
        case Light::Type::hemisphere:
            sh::hemisphere_light(bands, d.x, d.y, d.z, 1.0, 0.0, a.data());
            sh::hemisphere_light(bands, d.x, d.y, d.z, 0.0, 1.0, b.data());
            for (std::size_t k = 0; k < n; ++k)
                for (std::size_t c = 0; c < 3; ++c)
                    out[k][c] = light.color[c] * a[k] + light.ground[c] * b[k];
            return out;
    }
    for (std::size_t k = 0; k < n; ++k)
        for (std::size_t c = 0; c < 3; ++c) out[k][c] = light.color[c] * a[k];
    return out;
}

}  // namespace sphbasis::render
