// Procedural inputs of the shader-mirror example: a normal map of bumps quantised to 8 bits per
// channel as an RGB8 normal map stores them, and an H-basis light map of a smooth field of
// coefficients (a sky brightening along u, a directional term turning across the image).
#pragma once

#include <cmath>

#include "irradiance_normal_map.hpp"

namespace shader_mirror {

inline Textures procedural_textures(int w, int h) {
    Textures t;
    t.width = w, t.height = h;
    const double two_pi = 6.283185307179586;
    for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; ++i) {
            const double u = (i + 0.5) / w, v = (j + 0.5) / h;
            // Height field 0.25 sin(2 pi 2u) sin(2 pi 2v): the normal (-dh/du, -dh/dv, 1), steep
            // (up to ~70 degrees) at the bumps' flanks, the flat tangent-space z axis between them.
            const double du =
                0.25 * 2 * two_pi * std::cos(2 * two_pi * u) * std::sin(2 * two_pi * v);
            const double dv =
                0.25 * 2 * two_pi * std::sin(2 * two_pi * u) * std::cos(2 * two_pi * v);
            const double r = std::sqrt(du * du + dv * dv + 1);
            auto q8 = [](double c) {  // n/2 + 1/2 in 8 bits, read back as k/255
                return float(std::lround((0.5 * c + 0.5) * 255)) / 255.0f;
            };
            t.normal_map.push_back({q8(-du / r), q8(-dv / r), q8(1 / r)});
            const double a = two_pi * (u + 0.5 * v);
            const glm::vec4 base(float(0.9 + 0.6 * u), float(0.25 * std::cos(a)),
                                 float(-0.15 + 0.3 * v), float(0.25 * std::sin(a)));
            t.lightmap_r.push_back(base);
            t.lightmap_g.push_back(base * glm::vec4(0.9f, 1.2f, 1.0f, 0.8f));
            t.lightmap_b.push_back(base * glm::vec4(0.7f, -0.5f, 1.3f, 1.1f));
        }
    return t;
}

}  // namespace shader_mirror
