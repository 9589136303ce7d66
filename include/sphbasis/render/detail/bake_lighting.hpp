// sphbasis render tier, internal: the distant lighting as render/bake.hpp samples it.
//
// sky_radiance() is the radiance arriving along a ray that leaves the scene: the environment
// (render/lighting.hpp's Environment, read here with the same convention: a constant, or a
// lat-long image read bilinearly at rotation^T w, times scale) plus the non-delta analytic lights
// (cone, hemisphere, and a sphere light the ray meets before its first hit). Directional lights
// are deltas: the bake handles them with shadow rays or analytically. Not part of the API.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "../../core/constants.hpp"
#include "../../param/latlong.hpp"
#include "../lighting.hpp"
#include "rt_math.hpp"

namespace sphbasis::render::detail::rt {

/// L(w) of the environment (0 for Kind::none).
inline RGB environment_radiance(const Environment& env, const V3& w) noexcept {
    if (env.kind == Environment::Kind::constant)
        return {env.constant[0] * env.scale, env.constant[1] * env.scale,
                env.constant[2] * env.scale};
    if (env.kind != Environment::Kind::latlong || !env.texels || env.width <= 0 || env.height <= 0)
        return {0, 0, 0};
    const auto& r = env.rotation;  // map = R^T world
    const double mx = r[0] * w.x + r[3] * w.y + r[6] * w.z;
    const double my = r[1] * w.x + r[4] * w.y + r[7] * w.z;
    const double mz = r[2] * w.x + r[5] * w.y + r[8] * w.z;
    const auto s = param::latlong_to_square(mx, my, mz);
    const double x = s.x * env.width - 0.5, y = s.y * env.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y), ax = x - fx, ay = y - fy;
    const long ix = static_cast<long>(fx), iy = static_cast<long>(fy);
    auto cx = [&](long i) {
        return static_cast<std::size_t>(((i % env.width) + env.width) % env.width);
    };
    auto cy = [&](long i) {
        return static_cast<std::size_t>(std::clamp<long>(i, 0, env.height - 1));
    };
    const std::size_t x0 = cx(ix), x1 = cx(ix + 1), y0 = cy(iy), y1 = cy(iy + 1);
    const std::size_t W = static_cast<std::size_t>(env.width);
    RGB out{};
    for (std::size_t c = 0; c < 3; ++c) {
        auto at = [&](std::size_t xx, std::size_t yy) {
            return static_cast<double>(env.texels[(yy * W + xx) * 3 + c]);
        };
        out[c] = env.scale * ((1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) +
                              ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1)));
    }
    return out;
}

/// Distance along the unit ray (o, w) to a sphere light, infinity when it misses.
inline double sphere_light_distance(const Light& l, const V3& o, const V3& w) noexcept {
    const V3 oc = o - l.position;
    const double b = dot(oc, w), c = dot(oc, oc) - l.radius * l.radius;
    const double disc = b * b - c;
    if (disc < 0) return std::numeric_limits<double>::infinity();
    const double s = std::sqrt(disc);
    double t = -b - s;
    if (t < 0) t = -b + s;
    return t >= 0 ? t : std::numeric_limits<double>::infinity();
}

/// Radiance of the non-delta lights along the ray (o, w) whose first scene hit is at tmax.
/// `escaped`: the ray left the scene (distant lights count only then).
inline void add_light_radiance(const std::vector<Light>& lights, const V3& o, const V3& w,
                               double tmax, bool escaped, RGB& out) noexcept {
    for (const Light& l : lights) {
        const RGB* c = nullptr;
        switch (l.type) {
            case Light::Type::directional:
                break;
            case Light::Type::cone:
                if (escaped && dot(w, l.direction) >= std::cos(l.angle_deg * constants::pi / 180))
                    c = &l.color;
                break;
            case Light::Type::hemisphere:
                if (escaped) c = dot(w, l.direction) >= 0 ? &l.color : &l.ground;
                break;
            case Light::Type::sphere:
                if (sphere_light_distance(l, o, w) < tmax) c = &l.color;
                break;
        }
        if (c)
            for (std::size_t k = 0; k < 3; ++k) out[k] += (*c)[k];
    }
}

/// Legendre polynomial P_l(x) by the three-term recurrence.
inline double legendre_p(int l, double x) noexcept {
    if (l == 0) return 1;
    double p0 = 1, p1 = x;
    for (int k = 2; k <= l; ++k) {
        const double p2 = ((2 * k - 1) * x * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
    }
    return p1;
}
/// int_c^1 P_l(t) dt: 1 - c for l = 0, (P_{l-1}(c) - P_{l+1}(c)) / (2l + 1) otherwise.
inline double legendre_tail(int l, double c) noexcept {
    if (l == 0) return 1 - c;
    return (legendre_p(l - 1, c) - legendre_p(l + 1, c)) / (2 * l + 1);
}

}  // namespace sphbasis::render::detail::rt
