// Tests for render/camera.hpp: the image centre looks along the view direction, the top and
// bottom edges are fov/2 above and below it, the horizontal field follows the aspect, rows run
// downward and columns rightward, pixel_angle(), and validation.
#include <catch2/catch.hpp>
#include <cmath>

#include "sphbasis/core/constants.hpp"
#include "sphbasis/render/camera.hpp"

namespace render = sphbasis::render;
using render::Camera;
using render::PinholeCamera;
using sphbasis::vec3;

namespace {
double angle(const vec3<double>& a, const vec3<double>& b) {
    return std::acos(std::max(-1.0, std::min(1.0, sphbasis::dot(a, b))));
}
}  // namespace

TEST_CASE("PinholeCamera: centre, edges, orientation", "[render][camera]") {
    Camera c;
    c.position = {1, 2, 3};
    c.look_at = {1, 7, 3};  // looking along +y, z up: right is +x
    c.up = {0, 0.3, 2};     // not orthogonal to the view: only its component matters
    c.fov_deg = 60;
    c.width = 200;
    c.height = 100;
    const PinholeCamera cam(c);
    const auto mid = cam.ray(100, 50);
    CHECK(mid.direction.x == Approx(0).margin(1e-12));
    CHECK(mid.direction.y == Approx(1));
    CHECK(mid.origin.x == 1);
    const double half = 30 * sphbasis::constants::pi / 180;
    const auto top = cam.ray(100, 0), bottom = cam.ray(100, 100);
    CHECK(angle(top.direction, mid.direction) == Approx(half));
    CHECK(top.direction.z > 0);  // row 0 is the top
    CHECK(bottom.direction.z < 0);
    const auto right = cam.ray(200, 50);
    CHECK(right.direction.x > 0);  // x grows to the right
    CHECK(std::tan(angle(right.direction, mid.direction)) == Approx(2 * std::tan(half)));
    CHECK(cam.pixel_angle() == Approx(2 * std::tan(half) / 100));
    CHECK(sphbasis::dot(cam.up(), cam.forward()) == Approx(0).margin(1e-12));
    CHECK(cam.up().z > 0);
}

TEST_CASE("PinholeCamera: validation", "[render][camera]") {
    Camera c;
    c.look_at = c.position;
    CHECK_THROWS_AS(PinholeCamera(c), std::invalid_argument);
    c = Camera{};
    c.up = {0, 0, -1};
    c.look_at = {0, 0, 5};  // up parallel to the view
    CHECK_THROWS_AS(PinholeCamera(c), std::invalid_argument);
    c = Camera{};
    c.fov_deg = 180;
    CHECK_THROWS_AS(PinholeCamera(c), std::invalid_argument);
    c = Camera{};
    c.width = 0;
    CHECK_THROWS_AS(PinholeCamera(c), std::invalid_argument);
    c = Camera{};
    c.position.x = std::nan("");
    CHECK_THROWS_WITH(PinholeCamera(c), Catch::Contains("finite"));
}
