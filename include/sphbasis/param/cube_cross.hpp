// sphbasis: cube maps stored as one image (horizontal and vertical crosses), and the exact
// solid angles of the texels of cube faces and latitude-longitude rows. Standard library only.
//
// Faces are those of param/cubemap.hpp: +X, -X, +Y, -Y, +Z, -Z (0..5), each an n x n image whose
// texel (col, row) covers s in [2 col/n - 1, 2 (col+1)/n - 1], t likewise with row (t down the
// rows), at the direction of the face point (OpenGL 4.6, section 8.13, table 8.19; the D3D order):
//   +X: (1, -t, -s)   -X: (-1, -t, s)   +Y: (s, 1, t)   -Y: (s, -1, -t)   +Z: (s, -t, 1)
//   -Z: (-s, -t, -1).
// The crosses place the faces, n x n cells, as the cube unfolds around +Z:
//   horizontal (4n x 3n)        vertical (3n x 4n)
//       .  +Y  .   .                .  +Y  .
//      -X  +Z  +X  -Z              -X  +Z  +X
//       .  -Y  .   .                .  -Y  .
//                                   .  -Z  .      (-Z turned by 180 degrees)
// so that texels side by side in the image are side by side on the sphere (checked by the tests:
// the shared edges of neighbouring cells are the same cube edges). Every face is stored as its
// face image above, unrotated, except -Z in the vertical cross, turned by 180 degrees (its top
// row is the face's bottom row, read right to left), the layout of AMD's CubeMapGen and of most
// HDR tools. Cells marked '.' are not read.
//
// Solid angles (exact, not approximated by the texel centre):
//   * cube texel: the face rectangle [s0, s1] x [t0, t1] on the plane at distance 1 subtends
//     F(s1, t1) - F(s0, t1) - F(s1, t0) + F(s0, t0) with F(s, t) = atan(s t / sqrt(1 + s^2 +
//     t^2)) (the solid angle of the rectangle [0, s] x [0, t]; e.g. Driscoll, "Cubemap texel
//     solid angle", 2012); the texels of one face sum to 4 pi / 6;
//   * lat-long row j of h rows and w columns: (2 pi / w)(cos(pi j/h) - cos(pi (j+1)/h)); the map
//     sums to 4 pi.
#pragma once

#include <cmath>
#include <cstddef>
#include <string>

#include "../core/constants.hpp"
#include "../core/error.hpp"

namespace sphbasis::param {

/// The two cross layouts of a cube map in one image (see the header comment).
enum class CrossLayout {
    horizontal,  ///< 4n x 3n
    vertical     ///< 3n x 4n, -Z turned by 180 degrees
};

/// Where a face lies in a cross: its cell (column, row, in units of the face size) and whether
/// it is stored turned by 180 degrees.
struct CrossCell {
    int cell_col, cell_row;
    bool rotated_180;
};

/// The cross layout of an image of width x height pixels and its face size n: 4:3 is
/// horizontal, 3:4 vertical. Throws std::invalid_argument for any other shape (naming the
/// aspect it got), or a width that is not a multiple of 4 (3).
inline CrossLayout cross_layout_of(int width, int height, int& face_size) {
    if (width >= 4 && height >= 3 && width % 4 == 0 && 3 * width == 4 * height) {
        face_size = width / 4;
        return CrossLayout::horizontal;
    }
    if (width >= 3 && height >= 4 && width % 3 == 0 && 4 * width == 3 * height) {
        face_size = width / 3;
        return CrossLayout::vertical;
    }
    sphbasis::detail::throw_invalid(
        "param::cross_layout_of",
        "a cross of 4:3 (horizontal, 4n x 3n) or 3:4 (vertical, 3n x 4n) "
        "pixels, got " +
            std::to_string(width) + " x " + std::to_string(height));
}

/// The cell of face `face` (0..5: +X, -X, +Y, -Y, +Z, -Z) in a cross.
constexpr CrossCell cross_cell(CrossLayout layout, int face) noexcept {
    // +X, -X, +Y, -Y, +Z are in the same cells in both layouts; -Z differs.
    constexpr int col[5] = {2, 0, 1, 1, 1};
    constexpr int row[5] = {1, 1, 0, 2, 1};
    if (face >= 0 && face < 5) return {col[face], row[face], false};
    return layout == CrossLayout::horizontal ? CrossCell{3, 1, false} : CrossCell{1, 3, true};
}

/// The image pixel (x, y) (y down) holding texel (col, row) of face `face` of a cross with face
/// size n. Preconditions: 0 <= face < 6, 0 <= col, row < n.
constexpr void cross_pixel(CrossLayout layout, int n, int face, int col, int row, int& x,
                           int& y) noexcept {
    const CrossCell c = cross_cell(layout, face);
    const int u = c.rotated_180 ? n - 1 - col : col;
    const int v = c.rotated_180 ? n - 1 - row : row;
    x = c.cell_col * n + u;
    y = c.cell_row * n + v;
}

/// Exact solid angle of texel (col, row) of an n x n cube face (header comment), the same on
/// every face. Computed in double, returned as T. Preconditions: n >= 1, 0 <= col, row < n.
template <class T = double>
T cube_texel_solid_angle(int n, int col, int row) noexcept {
    auto corner = [](double s, double t) {
        return std::atan2(s * t, std::sqrt(s * s + t * t + 1));
    };
    const double s0 = 2.0 * col / n - 1.0, s1 = 2.0 * (col + 1) / n - 1.0;
    const double t0 = 2.0 * row / n - 1.0, t1 = 2.0 * (row + 1) / n - 1.0;
    return static_cast<T>(corner(s1, t1) - corner(s0, t1) - corner(s1, t0) + corner(s0, t0));
}

/// Exact solid angle of one texel of row `row` of a lat-long map of width x height texels
/// (param/latlong.hpp: row 0 at the north pole), (2 pi / width)(cos theta_0 - cos theta_1).
/// Preconditions: width, height >= 1, 0 <= row < height.
template <class T = double>
T latlong_texel_solid_angle(int width, int height, int row) noexcept {
    const double t0 = constants::pi * row / height, t1 = constants::pi * (row + 1) / height;
    return static_cast<T>(constants::two_pi / width * (std::cos(t0) - std::cos(t1)));
}

}  // namespace sphbasis::param
