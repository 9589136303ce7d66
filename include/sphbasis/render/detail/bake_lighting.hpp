// sphbasis render tier, internal: the distant lighting as render/bake.hpp samples it.
//
// The non-delta analytic lights along a ray (cone, hemisphere, and a sphere light the ray meets
// before its first hit); the environment is Environment::radiance (render/lighting.hpp).
// Directional lights are deltas: the bake handles them with shadow rays or analytically. Not part
// of the API.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "../../core/constants.hpp"
#include "../lighting.hpp"
#include "rt_math.hpp"

namespace sphbasis::render::detail::rt {

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
        RGB c{0, 0, 0};
        if (l.type == Light::Type::sphere) {
            // A local light: it counts where the ray meets it before its first scene hit.
            if (sphere_light_distance(l, o, w) < tmax) c = l.color;
        } else if (escaped) {
            c = light_radiance(l, w);  // cone and hemisphere (directional: 0, a delta)
        }
        for (std::size_t k = 0; k < 3; ++k) out[k] += c[k];
    }
}

}  // namespace sphbasis::render::detail::rt
