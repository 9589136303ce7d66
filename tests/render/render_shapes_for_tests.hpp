// Test meshes for the render tests: the spheres and quads of render/shapes.hpp, and a box with
// shared corners that can be left open (shapes::box is closed, with a chart per face).
#pragma once

#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "sphbasis/render/camera.hpp"
#include "sphbasis/render/mesh.hpp"
#include "sphbasis/render/shapes.hpp"

namespace sphbasis_test {

using sphbasis::render::Mesh;

/// A UV sphere (render::shapes::sphere).
inline Mesh uv_sphere(double cx, double cy, double cz, double r, int rings, int segments) {
    return sphbasis::render::shapes::sphere({cx, cy, cz}, r, rings, segments);
}

/// A quad grid in the plane z = z0 over [x0, x1] x [y0, y1], n x n cells, normal +z, UVs
/// (render::shapes::quad: vertices row by row, x fastest).
inline Mesh quad_grid(double x0, double x1, double y0, double y1, double z0, int n) {
    return sphbasis::render::shapes::quad({(x0 + x1) / 2, (y0 + y1) / 2, z0}, {(x1 - x0) / 2, 0, 0},
                                          {0, (y1 - y0) / 2, 0}, n);
}

/// An axis-aligned box [lo, hi]^3 per axis, outward CCW faces, shared corner vertices (closed,
/// convex). With open_top the +z face is left out.
inline Mesh box(double x0, double y0, double z0, double x1, double y1, double z1,
                bool open_top = false) {
    Mesh m;
    for (int k = 0; k < 8; ++k)
        m.positions.insert(m.positions.end(), {float(k & 1 ? x1 : x0), float(k & 2 ? y1 : y0),
                                               float(k & 4 ? z1 : z0)});
    // Faces as quads (outward CCW).
    const std::uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                                   {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (int f = 0; f < 6; ++f) {
        if (open_top && f == 1) continue;
        m.indices.insert(m.indices.end(), {q[f][0], q[f][1], q[f][2], q[f][0], q[f][2], q[f][3]});
    }
    return m;
}

/// Meshes as files deliver them (white-furnace tests of two-sided shading): every vertex normal
/// set to the unit vector from `center` to the vertex (on box(), whose 8 corners are shared by
/// three faces each: the normals a file smoothed across the 90-degree edges, 55 degrees from
/// every face), and, with `mixed`, every second triangle wound the other way.
inline Mesh with_radial_normals(Mesh m, sphbasis::vec3<double> center, bool mixed) {
    m.normals.clear();
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
        const double x = m.positions[3 * i] - center.x, y = m.positions[3 * i + 1] - center.y,
                     z = m.positions[3 * i + 2] - center.z;
        const double l = std::sqrt(x * x + y * y + z * z);
        m.normals.insert(m.normals.end(), {float(x / l), float(y / l), float(z / l)});
    }
    if (mixed)
        for (std::size_t t = 0; t < m.triangle_count(); t += 2)
            std::swap(m.indices[3 * t + 1], m.indices[3 * t + 2]);
    return m;
}

/// A w x h camera at pos looking at `at` (z up; y up when looking straight along z).
inline sphbasis::render::Camera camera_at(sphbasis::vec3<double> pos, sphbasis::vec3<double> at,
                                          int w, int h, double fov = 40) {
    sphbasis::render::Camera c;
    c.position = pos;
    c.look_at = at;
    c.up = {0, 0, 1};
    if (std::fabs(pos.x - at.x) < 1e-12 && std::fabs(pos.y - at.y) < 1e-12) c.up = {0, 1, 0};
    c.fov_deg = fov;
    c.width = w;
    c.height = h;
    return c;
}

}  // namespace sphbasis_test
