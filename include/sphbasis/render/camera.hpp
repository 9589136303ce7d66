// sphbasis render tier: a pinhole camera (the scene file's "camera").
//
// Image coordinates: x to the right in [0, width), y downward in [0, height); pixel (i, j)
// covers [i, i + 1) x [j, j + 1), its centre at (i + 0.5, j + 0.5); row 0 is the top row (as
// image files store it). The camera looks from `position` toward `look_at`; `up` fixes the roll
// (it need not be orthogonal to the view direction, only not parallel to it); fov_deg is the
// vertical field of view, the horizontal one follows from the aspect width / height (square
// pixels). Directions are world space (z-up like the rest of the library).
#pragma once

#include <cmath>
#include <string>

#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/vec.hpp"
#include "detail/rt_math.hpp"

namespace sphbasis::render {

struct Camera {
    vec3<double> position{0, 0, 0}, look_at{0, 0, -1}, up{0, 0, 1};
    double fov_deg = 45;  // vertical, in (0, 180)
    int width = 640, height = 360;
};

/// Throws std::invalid_argument ("sphbasis::render::Camera(): expected ...") for a non-finite
/// vector, look_at == position, up parallel to the view direction (|sin| < 1e-9) or zero,
/// fov_deg outside (0, 180), or width or height outside [1, 16384].
inline void validate(const Camera& c) {
    using namespace detail::rt;
    constexpr const char* fn = "render::Camera";
    if (!finite(c.position) || !finite(c.look_at) || !finite(c.up))
        sphbasis::detail::throw_invalid(
            fn, "finite position, look_at and up, got a NaN or an infinity");
    const V3 f = c.look_at - c.position;
    if (!(length(f) > 0))
        sphbasis::detail::throw_invalid(fn, "look_at != position, got equal points");
    const double s = length(cross(normalized(f), normalized(c.up, {0, 0, 0})));
    if (!(s >= 1e-9))
        sphbasis::detail::throw_invalid(fn, "up not parallel to the view direction and non-zero");
    if (!(c.fov_deg > 0 && c.fov_deg < 180))
        sphbasis::detail::throw_invalid(fn,
                                        "fov_deg in (0, 180), got " + std::to_string(c.fov_deg));
    sphbasis::detail::check_range(fn, "width", c.width, 1, 16384);
    sphbasis::detail::check_range(fn, "height", c.height, 1, 16384);
}

/// A primary ray: origin and unit direction.
struct CameraRay {
    vec3<double> origin{0, 0, 0}, direction{0, 0, -1};
};

/// The camera's orthonormal frame and image-plane scale, computed once (validate() first).
class PinholeCamera {
  public:
    explicit PinholeCamera(const Camera& c) : cam_(c) {
        validate(c);
        using namespace detail::rt;
        forward_ = normalized(c.look_at - c.position);
        right_ = normalized(cross(forward_, c.up));
        up_ = cross(right_, forward_);
        tan_half_ = std::tan(0.5 * c.fov_deg * sphbasis::constants::pi / 180);
    }
    const Camera& camera() const noexcept { return cam_; }
    /// The ray through image point (x, y) (see the header comment), e.g. (i + 0.5, j + 0.5).
    CameraRay ray(double x, double y) const noexcept {
        using namespace detail::rt;
        const double sy = (1 - 2 * y / cam_.height) * tan_half_;
        const double sx = (2 * x / cam_.width - 1) * tan_half_ * cam_.width / cam_.height;
        return {cam_.position, normalized(forward_ + right_ * sx + up_ * sy, forward_)};
    }
    /// The angle (radians) one pixel subtends at the image centre: 2 tan(fov/2) / height
    /// (for texture level selection from a pixel's footprint).
    double pixel_angle() const noexcept { return 2 * tan_half_ / cam_.height; }
    vec3<double> forward() const noexcept { return forward_; }
    vec3<double> right() const noexcept { return right_; }
    vec3<double> up() const noexcept { return up_; }

  private:
    Camera cam_;
    vec3<double> forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
    double tan_half_ = 1;
};

}  // namespace sphbasis::render
