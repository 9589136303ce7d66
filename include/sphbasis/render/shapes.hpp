// sphbasis render tier: procedural meshes (sphere, box, quad) as render::Mesh, so tests,
// examples and scene files need no mesh files.
//
// Every shape has positions, unit normals, one UV set in [0, 1]^2 whose triangles do not
// overlap (usable as a lightmap layout) and tangents (4 floats per vertex: the unit tangent
// along increasing u and the handedness sign w of the bitangent, bitangent = w cross(n, t), as
// glTF stores them; here w = +1 everywhere, the bitangent pointing along increasing v).
// Orientation: triangles are counter-clockwise seen from the side the normals point to
// (outside for the closed sphere and box; the side of cross(u_axis, v_axis) for the quad), so
// the winding's geometric normal agrees with the shading normals. UV convention of render::
// TextureView: v = 1 is the top row of an image.
//
// Albedo is left at render::Mesh's default; the caller sets it.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/vec.hpp"
#include "mesh.hpp"

namespace sphbasis::render::shapes {

namespace detail {

inline bool finite3(const vec3<double>& v) noexcept {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

inline std::string str3(const vec3<double>& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}

/// Appends one vertex: position, normal, uv and tangent (w = +1).
inline void push_vertex(Mesh& m, const vec3<double>& p, const vec3<double>& n, double u, double v,
                        const vec3<double>& t) {
    m.positions.insert(m.positions.end(),
                       {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)});
    m.normals.insert(m.normals.end(),
                     {static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z)});
    m.uvs.insert(m.uvs.end(), {static_cast<float>(u), static_cast<float>(v)});
    m.tangents.insert(m.tangents.end(), {static_cast<float>(t.x), static_cast<float>(t.y),
                                         static_cast<float>(t.z), 1.0f});
}

inline void push_triangle(Mesh& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m.indices.insert(m.indices.end(), {a, b, c});
}

}  // namespace detail

/// A UV sphere of `rings` latitude bands (>= 2) and `segments` longitude sectors (>= 3) about
/// `center`. Vertex (i, j), i = 0..rings, j = 0..segments, sits at polar angle theta = pi i/rings
/// from +z and azimuth phi = 2 pi j/segments: position center + radius (sin(theta) cos(phi),
/// sin(theta) sin(phi), cos(theta)), normal the radial direction, uv = (j/segments, 1 - i/rings)
/// (the lat-long layout: north pole at the top row, seam at phi = 0 duplicated at u = 0 and 1),
/// tangent (-sin(phi), cos(phi), 0). The pole rows hold one vertex per sector at the sector's
/// middle azimuth (u = (j + 1/2)/segments), so no triangle is degenerate: 2 rings segments -
/// 2 segments triangles, (rings + 1)(segments + 1) vertices (the last pole column unused).
/// Vertex index i (segments + 1) + j. Throws std::invalid_argument for a non-finite centre,
/// radius not finite and > 0, rings outside [2, 32768] or segments outside [3, 65536].
inline Mesh sphere(const vec3<double>& center, double radius, int rings, int segments) {
    const char* fn = "render::shapes::sphere";
    if (!detail::finite3(center))
        sphbasis::detail::throw_invalid(fn, "a finite centre, got " + detail::str3(center));
    if (!(radius > 0) || !std::isfinite(radius))
        sphbasis::detail::throw_invalid(fn, "a finite radius > 0, got " + std::to_string(radius));
    sphbasis::detail::check_range(fn, "rings", rings, 2, 32768);
    sphbasis::detail::check_range(fn, "segments", segments, 3, 65536);
    Mesh m;
    const std::size_t nv =
        static_cast<std::size_t>(rings + 1) * static_cast<std::size_t>(segments + 1);
    m.positions.reserve(3 * nv);
    m.normals.reserve(3 * nv);
    m.uvs.reserve(2 * nv);
    m.tangents.reserve(4 * nv);
    for (int i = 0; i <= rings; ++i) {
        const bool pole = i == 0 || i == rings;
        const double theta = constants::pi * i / rings;
        // Exact poles, so the pole vertices coincide in float.
        const double st = pole ? 0.0 : std::sin(theta);
        const double ct = i == 0 ? 1.0 : (i == rings ? -1.0 : std::cos(theta));
        for (int j = 0; j <= segments; ++j) {
            // The seam column repeats column 0's position bit for bit (phi of j % segments).
            const double jj = pole ? j + 0.5 : static_cast<double>(j % segments);
            const double phi = constants::two_pi * jj / segments;
            const double cp = std::cos(phi), sp = std::sin(phi);
            const vec3<double> n{st * cp, st * sp, ct};
            const vec3<double> p{center.x + radius * n.x, center.y + radius * n.y,
                                 center.z + radius * n.z};
            const double u = pole ? (j + 0.5) / segments : static_cast<double>(j) / segments;
            const double v = 1.0 - static_cast<double>(i) / rings;
            detail::push_vertex(m, p, n, u > 1 ? 1.0 : u, v, vec3<double>{-sp, cp, 0});
        }
    }
    const std::uint32_t row = static_cast<std::uint32_t>(segments + 1);
    m.indices.reserve(6 * static_cast<std::size_t>(rings) * static_cast<std::size_t>(segments));
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const std::uint32_t v00 =
                static_cast<std::uint32_t>(i) * row + static_cast<std::uint32_t>(j);
            const std::uint32_t v01 = v00 + 1, v10 = v00 + row, v11 = v10 + 1;
            // (theta, phi) increasing is counter-clockwise seen from outside.
            // The pole rows keep one triangle per sector, with the pole vertex of that sector.
            if (i == 0)
                detail::push_triangle(m, v00, v10, v11);
            else if (i + 1 == rings)
                detail::push_triangle(m, v00, v10, v01);
            else {
                detail::push_triangle(m, v00, v10, v11);
                detail::push_triangle(m, v00, v11, v01);
            }
        }
    return m;
}

/// An axis-aligned closed box of half extents h > 0 about `center`: 6 flat-shaded faces of 4
/// vertices and 2 triangles each (24 vertices, 12 triangles), faces in the order +x, -x, +y,
/// -y, +z, -z, vertices of a face at (u, v) corners (0,0), (1,0), (1,1), (0,1) of its chart and
/// triangles (0, 1, 2), (0, 2, 3). Each face has its own rectangular UV chart, all at one texel
/// density (charts keep the faces' aspect ratios): columns x faces | y faces | z faces, the
/// positive faces in the top row, 1/64 of padding around and between charts. Face tangent
/// frames (t along u, b along v, t x b = n): +x (+y, +z), -x (-y, +z), +y (-x, +z),
/// -y (+x, +z), +z (+x, +y), -z (+x, -y). Throws std::invalid_argument for a non-finite centre
/// or a half extent not finite and > 0.
inline Mesh box(const vec3<double>& center, const vec3<double>& half_extents) {
    const char* fn = "render::shapes::box";
    if (!detail::finite3(center))
        sphbasis::detail::throw_invalid(fn, "a finite centre, got " + detail::str3(center));
    const vec3<double>& h = half_extents;
    if (!detail::finite3(h) || !(h.x > 0) || !(h.y > 0) || !(h.z > 0))
        sphbasis::detail::throw_invalid(fn, "finite half extents > 0, got " + detail::str3(h));
    struct Face {
        vec3<double> n, t, b;
        double ht, hb;  // half extents along t and b
        int col, row;
    };
    const Face faces[6] = {
        {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, h.y, h.z, 0, 0},
        {{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}, h.y, h.z, 0, 1},
        {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}, h.x, h.z, 1, 0},
        {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}, h.x, h.z, 1, 1},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, h.x, h.y, 2, 0},
        {{0, 0, -1}, {1, 0, 0}, {0, -1, 0}, h.x, h.y, 2, 1},
    };
    // Atlas in world units: column widths 2 hy, 2 hx, 2 hx; both rows max(2 hz, 2 hy) high.
    const double colw[3] = {2 * h.y, 2 * h.x, 2 * h.x};
    const double rowh = 2 * std::fmax(h.z, h.y);
    const double pad = 1.0 / 64;
    const double s =
        std::fmin((1 - 4 * pad) / (colw[0] + colw[1] + colw[2]), (1 - 3 * pad) / (2 * rowh));
    Mesh m;
    m.positions.reserve(72);
    m.normals.reserve(72);
    m.uvs.reserve(48);
    m.tangents.reserve(96);
    m.indices.reserve(36);
    for (int f = 0; f < 6; ++f) {
        const Face& F = faces[f];
        double u0 = pad;
        for (int c = 0; c < F.col; ++c) u0 += colw[c] * s + pad;
        // Row 0 at the top of the atlas (v near 1).
        const double v1 = 1 - pad - F.row * (rowh * s + pad);
        const double v0 = v1 - 2 * F.hb * s;
        const double du = 2 * F.ht * s;
        const std::uint32_t base = static_cast<std::uint32_t>(m.vertex_count());
        const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const auto& k : corner) {
            // Face point: centre + h_n n + a ht t + b hb b; computed per axis as centre +- h so
            // the corners shared by faces coincide bit for bit.
            const double a = k[0], b = k[1];
            vec3<double> q{F.n.x + a * F.t.x + b * F.b.x, F.n.y + a * F.t.y + b * F.b.y,
                           F.n.z + a * F.t.z + b * F.b.z};  // each component is -1 or +1
            const vec3<double> p{center.x + q.x * h.x, center.y + q.y * h.y, center.z + q.z * h.z};
            const double u = u0 + 0.5 * (a + 1) * du;
            const double v = v0 + 0.5 * (b + 1) * (v1 - v0);
            detail::push_vertex(m, p, F.n, u, v, F.t);
        }
        detail::push_triangle(m, base, base + 1, base + 2);
        detail::push_triangle(m, base, base + 2, base + 3);
    }
    return m;
}

/// A rectangle center + a u_axis_half + b v_axis_half, a, b in [-1, 1], tessellated into
/// subdivisions x subdivisions cells of two triangles. Vertex (i, j), i along u and j along v
/// in 0..subdivisions, has index j (subdivisions + 1) + i, uv = (i, j)/subdivisions, normal
/// n = normalize(u_axis_half x v_axis_half) (the front side; render meshes are two-sided),
/// tangent normalize(u_axis_half). The axes need not be orthogonal (a parallelogram): then the
/// tangent is still orthogonal to n and the bitangent cross(n, t) has a positive component
/// along v_axis_half. Triangles (v00, v10, v11), (v00, v11, v01), counter-clockwise seen from
/// the side n points to. Throws std::invalid_argument for a non-finite centre or axis, axes
/// that are zero or parallel (|u x v| <= 1e-12 |u| |v|), or subdivisions outside [1, 16384].
inline Mesh quad(const vec3<double>& center, const vec3<double>& u_axis_half,
                 const vec3<double>& v_axis_half, int subdivisions = 1) {
    const char* fn = "render::shapes::quad";
    if (!detail::finite3(center))
        sphbasis::detail::throw_invalid(fn, "a finite centre, got " + detail::str3(center));
    if (!detail::finite3(u_axis_half) || !detail::finite3(v_axis_half))
        sphbasis::detail::throw_invalid(fn, "finite axes, got u " + detail::str3(u_axis_half) +
                                                ", v " + detail::str3(v_axis_half));
    sphbasis::detail::check_range(fn, "subdivisions", subdivisions, 1, 16384);
    const vec3<double>& U = u_axis_half;
    const vec3<double>& V = v_axis_half;
    const vec3<double> c = cross(U, V);
    const double lu = std::sqrt(dot(U, U)), lv = std::sqrt(dot(V, V)), lc = std::sqrt(dot(c, c));
    if (!(lc > 1e-12 * lu * lv) || !(lu > 0) || !(lv > 0))
        sphbasis::detail::throw_invalid(
            fn, "non-zero, non-parallel axes, got u " + detail::str3(U) + ", v " + detail::str3(V));
    const vec3<double> n{c.x / lc, c.y / lc, c.z / lc};
    const vec3<double> t{U.x / lu, U.y / lu, U.z / lu};
    const int S = subdivisions;
    Mesh m;
    const std::size_t nv = static_cast<std::size_t>(S + 1) * static_cast<std::size_t>(S + 1);
    m.positions.reserve(3 * nv);
    m.normals.reserve(3 * nv);
    m.uvs.reserve(2 * nv);
    m.tangents.reserve(4 * nv);
    for (int j = 0; j <= S; ++j)
        for (int i = 0; i <= S; ++i) {
            const double u = static_cast<double>(i) / S, v = static_cast<double>(j) / S;
            const double a = 2 * u - 1, b = 2 * v - 1;
            const vec3<double> p{center.x + a * U.x + b * V.x, center.y + a * U.y + b * V.y,
                                 center.z + a * U.z + b * V.z};
            detail::push_vertex(m, p, n, u, v, t);
        }
    const std::uint32_t row = static_cast<std::uint32_t>(S + 1);
    m.indices.reserve(6 * static_cast<std::size_t>(S) * static_cast<std::size_t>(S));
    for (int j = 0; j < S; ++j)
        for (int i = 0; i < S; ++i) {
            const std::uint32_t v00 =
                static_cast<std::uint32_t>(j) * row + static_cast<std::uint32_t>(i);
            const std::uint32_t v10 = v00 + 1, v01 = v00 + row, v11 = v01 + 1;
            detail::push_triangle(m, v00, v10, v11);
            detail::push_triangle(m, v00, v11, v01);
        }
    return m;
}

}  // namespace sphbasis::render::shapes
