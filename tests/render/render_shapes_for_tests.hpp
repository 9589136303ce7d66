// Test meshes built inline for the render tests (independent of render/shapes.hpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "sphbasis/render/mesh.hpp"

namespace sphbasis_test {

using sphbasis::render::Mesh;

/// UV sphere: `rings` latitude bands, `segments` longitudes, outward CCW triangles, smooth
/// normals, UVs. Vertices on the seam and the poles are duplicated (as loaders do).
inline Mesh uv_sphere(double cx, double cy, double cz, double r, int rings, int segments) {
    Mesh m;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i) {
        const double th = pi * i / rings;
        for (int j = 0; j <= segments; ++j) {
            const double ph = 2 * pi * j / segments;
            const double x = std::sin(th) * std::cos(ph), y = std::sin(th) * std::sin(ph),
                         z = std::cos(th);
            m.positions.insert(m.positions.end(),
                               {float(cx + r * x), float(cy + r * y), float(cz + r * z)});
            m.normals.insert(m.normals.end(), {float(x), float(y), float(z)});
            m.uvs.insert(m.uvs.end(), {float(double(j) / segments), float(1 - double(i) / rings)});
        }
    }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            // Outward: (b - a) x (c - a) points away from the centre.
            if (i != 0) m.indices.insert(m.indices.end(), {a, b, d});
            if (i != rings - 1) m.indices.insert(m.indices.end(), {b, c, d});
        }
    // Pole vertices coincide for all j (exact 0 from sin(0) and sin(pi) ~ 1e-16 -> force).
    for (int j = 0; j <= segments; ++j) {
        m.positions[3 * at(0, j)] = float(cx);
        m.positions[3 * at(0, j) + 1] = float(cy);
        m.positions[3 * at(rings, j)] = float(cx);
        m.positions[3 * at(rings, j) + 1] = float(cy);
    }
    // Seam: j = segments equals j = 0 exactly.
    for (int i = 0; i <= rings; ++i)
        for (int k = 0; k < 3; ++k)
            m.positions[3 * at(i, segments) + std::uint32_t(k)] =
                m.positions[3 * at(i, 0) + std::uint32_t(k)];
    return m;
}

/// A quad grid in the plane z = z0 over [x0, x1] x [y0, y1], n x n cells, normal +z, UVs.
inline Mesh quad_grid(double x0, double x1, double y0, double y1, double z0, int n) {
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            const double u = double(j) / n, v = double(i) / n;
            m.positions.insert(m.positions.end(),
                               {float(x0 + (x1 - x0) * u), float(y0 + (y1 - y0) * v), float(z0)});
            m.normals.insert(m.normals.end(), {0.f, 0.f, 1.f});
            m.uvs.insert(m.uvs.end(), {float(u), float(v)});
        }
    const auto at = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const auto a = at(i, j), b = at(i, j + 1), c = at(i + 1, j + 1), d = at(i + 1, j);
            m.indices.insert(m.indices.end(), {a, b, c, a, c, d});
        }
    return m;
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

}  // namespace sphbasis_test
