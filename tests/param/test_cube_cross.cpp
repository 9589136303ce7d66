// Tests of param/cube_cross.hpp: the texel solid angles against closed forms (a face sums to
// 4 pi / 6, a lat-long map to 4 pi, a texel against a fine midpoint quadrature of 1/|p|^3), and
// the cross layouts against the sphere (image neighbours are sphere neighbours, every face texel
// has its own pixel inside its cell).
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <sphbasis/param/cube_cross.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace sphbasis;
using namespace sphbasis::param;

TEST_CASE("cube cross: texel solid angles of a face sum to 4 pi / 6", "[param][cube_cross]") {
    for (int n : {1, 2, 3, 7, 64, 513}) {
        double sum = 0;
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c) sum += cube_texel_solid_angle(n, c, r);
        CHECK(sum == Approx(4 * constants::pi / 6).epsilon(1e-14));
    }
    // One texel of a whole face is the face.
    CHECK(cube_texel_solid_angle(1, 0, 0) == Approx(2 * constants::pi / 3).epsilon(1e-15));
    // Symmetric under the face's mirror and diagonal symmetries; the same as CubeMap's member.
    const CubeMap<double> cube(9, CubeFilter::dx9_clamped);
    for (int r = 0; r < 9; ++r)
        for (int c = 0; c < 9; ++c) {
            const double w = cube_texel_solid_angle(9, c, r);
            CHECK(w == Approx(cube_texel_solid_angle(9, 8 - c, r)).epsilon(1e-14));
            CHECK(w == Approx(cube_texel_solid_angle(9, r, c)).epsilon(1e-14));
            CHECK(w == Approx(cube.texel_solid_angle(0, c, r)).epsilon(1e-14));
        }
}

TEST_CASE("cube cross: a texel's solid angle is the integral of 1/|p|^3 over its square",
          "[param][cube_cross]") {
    // d omega = ds dt / (1 + s^2 + t^2)^(3/2) on the plane at distance 1; a 400 x 400 midpoint
    // rule on the texel's square is accurate to ~1e-6 relative.
    const int n = 5, q = 400;
    for (auto [c, r] : {std::pair<int, int>{0, 0}, {2, 2}, {4, 1}}) {
        const double s0 = 2.0 * c / n - 1, t0 = 2.0 * r / n - 1, h = 2.0 / n / q;
        double sum = 0;
        for (int i = 0; i < q; ++i)
            for (int j = 0; j < q; ++j) {
                const double s = s0 + (i + 0.5) * h, t = t0 + (j + 0.5) * h;
                sum += h * h / std::pow(1 + s * s + t * t, 1.5);
            }
        CHECK(cube_texel_solid_angle(n, c, r) == Approx(sum).epsilon(1e-5));
    }
}

TEST_CASE("cube cross: lat-long texel solid angles sum to 4 pi", "[param][cube_cross]") {
    for (auto [w, h] : {std::pair<int, int>{2, 1}, {8, 4}, {2048, 1024}, {3, 7}}) {
        double sum = 0;
        for (int r = 0; r < h; ++r) sum += w * latlong_texel_solid_angle(w, h, r);
        CHECK(sum == Approx(4 * constants::pi).epsilon(1e-13));
    }
    // Row 0 of 2 rows is the northern hemisphere: 2 pi over the width.
    CHECK(latlong_texel_solid_angle(4, 2, 0) == Approx(constants::pi / 2).epsilon(1e-15));
}

TEST_CASE("cube cross: layouts by aspect, bad shapes refused", "[param][cube_cross]") {
    int n = 0;
    CHECK(cross_layout_of(64, 48, n) == CrossLayout::horizontal);
    CHECK(n == 16);
    CHECK(cross_layout_of(48, 64, n) == CrossLayout::vertical);
    CHECK(n == 16);
    CHECK_THROWS_WITH(cross_layout_of(64, 64, n), Catch::Contains("got 64 x 64"));
    CHECK_THROWS_AS(cross_layout_of(66, 48, n), std::invalid_argument);
    CHECK_THROWS_AS(cross_layout_of(0, 0, n), std::invalid_argument);
    CHECK_THROWS_AS(cross_layout_of(-4, -3, n), std::invalid_argument);
}

TEST_CASE("cube cross: image neighbours are sphere neighbours, pixels unique",
          "[param][cube_cross]") {
    const int n = 8;
    for (CrossLayout layout : {CrossLayout::horizontal, CrossLayout::vertical}) {
        const int w = layout == CrossLayout::horizontal ? 4 * n : 3 * n;
        const int h = layout == CrossLayout::horizontal ? 3 * n : 4 * n;
        // Direction of every pixel that holds a face texel; -1 marks unused cells.
        std::vector<vec3<double>> dir(static_cast<std::size_t>(w * h));
        std::vector<int> used(static_cast<std::size_t>(w * h), 0);
        for (int f = 0; f < 6; ++f)
            for (int r = 0; r < n; ++r)
                for (int c = 0; c < n; ++c) {
                    int x = 0, y = 0;
                    cross_pixel(layout, n, f, c, r, x, y);
                    REQUIRE(x >= 0);
                    REQUIRE(x < w);
                    REQUIRE(y >= 0);
                    REQUIRE(y < h);
                    const std::size_t i = static_cast<std::size_t>(y * w + x);
                    ++used[i];
                    dir[i] = square_to_cube(f, (c + 0.5) / n, (r + 0.5) / n);
                }
        int count = 0;
        for (int u : used) {
            CHECK(u <= 1);
            count += u;
        }
        CHECK(count == 6 * n * n);
        // Neighbouring pixels (right and down), both used: their directions are at most about
        // 2 / n apart (texel pitch at a face centre; smaller near edges), across cell
        // boundaries too. A wrongly placed or turned face puts them 45+ degrees apart.
        int seams = 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const std::size_t i = static_cast<std::size_t>(y * w + x);
                if (!used[i]) continue;
                for (auto [dx, dy] : {std::pair<int, int>{1, 0}, {0, 1}}) {
                    if (x + dx >= w || y + dy >= h) continue;
                    const std::size_t j = static_cast<std::size_t>((y + dy) * w + x + dx);
                    if (!used[j]) continue;
                    const double d = dot(dir[i], dir[j]);
                    CHECK(std::acos(std::min(1.0, d)) < 2.0 / n);
                    if ((x + dx) % n == 0 && dx == 1) ++seams;
                    if ((y + dy) % n == 0 && dy == 1) ++seams;
                }
            }
        // Seams inside the image: horizontal cross 3 vertical seams in the middle band and 2
        // horizontal ones; vertical cross 2 + 3 (the -Y / -Z seam included).
        CHECK(seams == 5 * n);
    }
}
