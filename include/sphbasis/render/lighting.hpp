// sphbasis render tier: the distant lighting of a scene (an environment and analytic lights).
//
// CONTRACT (written by the lead; the engine helper implements the bodies and may add members,
// but keeps these names and meanings): the tool fills these structs from the scene file.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "../core/frame.hpp"
#include "../core/vec.hpp"

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
    RGB radiance(const vec3<double>& w) const;
};

/// An analytic distant light. `direction` points toward the light (unit).
///   directional: irradiance `color` on a surface facing it (a delta light).
///   sphere:      a sphere of radiance `color` at `position` with `radius` (local light).
///   cone:        distant constant radiance `color` within `angle_deg` (half-angle) of direction.
///   hemisphere:  radiance `color` from the hemisphere around direction, `ground` from the other.
struct Light {
    enum class Type { directional, sphere, cone, hemisphere };
    Type type = Type::directional;
    vec3<double> direction{0, 0, 1};
    vec3<double> position{0, 0, 0};
    double radius = 0, angle_deg = 0;
    RGB color{1, 1, 1}, ground{0, 0, 0};
};

}  // namespace sphbasis::render
