// sphbasis render tier: the points a bake is made at (vertices, lightmap texels, probes), with
// one id scheme and one tangent rule, so that every caller (the `sphbasis bake` and `sphbasis
// render` commands, a user's program) bakes the same point with the same samples.
//
// Point ids. A Baker result depends only on (seed, point id, settings, scene) (render/bake.hpp:
// the id seeds the point's Cranley-Patterson rotation), so two bakes of one point agree bit for
// bit exactly when they give it the same id. The scheme, for a scene of meshes 0 .. M-1:
//   vertex   vertex v of mesh k: id = (vertices of meshes 0 .. k-1) + v, the global vertex
//            index in scene order (vertex_id_base());
//   texel    texel (x, y) of mesh k's RES x RES lightmap: id = k RES^2 + y RES + x
//            (texel_id_base(); x right, y down from the top row, render/lightmap.hpp);
//   probe    probe (i, j, k) of a ProbeGrid: its index i + nx (j + ny k).
// Ids of different targets overlap; a bake holds points of one target.
//
// Normals: the mesh's shading normals, else area-weighted face normals (the sum of the
// adjacent triangles' cross products), not normalised (the Baker normalises); a vertex whose
// normal is zero or not finite (one no triangle uses) gets (0, 0, 1), so every vertex is a
// valid surface point.
//
// Tangents (the frame of tangent-space irradiance, BakePoint::tangent): the rule of
// render::Scene's hits, so a baked frame is the frame a renderer shades with. Mesh tangents
// (interpolated at texels), Gram-Schmidt against n, handedness from their w; else the UV
// derivative dp/du (Pharr, Jakob and Humphreys, "Physically Based Rendering", 3rd ed., 2016,
// section 3.6.2) of the triangle (texels: the sample's triangle; vertices: the area-weighted sum
// over the triangles at the vertex), Gram-Schmidt against n, handedness from dp/dv against the
// geometric normal; else zero (the Baker's tangent_frame(n)).
//
// Cost: O(vertices + triangles) per mesh for vertex points; texel points are
// render::layout_lightmap() (see its cost) plus O(samples).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/vec.hpp"
#include "bake.hpp"
#include "detail/rt_math.hpp"
#include "lightmap.hpp"
#include "mesh.hpp"
#include "probe_grid.hpp"

namespace sphbasis::render {

namespace bake_points_detail {

inline void check_mesh(const char* fn, const std::vector<MeshView>& meshes, std::size_t mesh) {
    if (mesh >= meshes.size())
        sphbasis::detail::throw_invalid(fn, "a mesh index < " + std::to_string(meshes.size()) +
                                                ", got " + std::to_string(mesh));
    const MeshView& m = meshes[mesh];
    sphbasis::detail::check_buffer(fn, "positions", m.positions, m.vertex_count);
    sphbasis::detail::check_buffer(fn, "indices", m.indices, m.triangle_count);
    for (std::size_t i = 0; i < 3 * m.triangle_count; ++i)
        if (m.indices[i] >= m.vertex_count)
            sphbasis::detail::throw_invalid(
                fn, "vertex indices < " + std::to_string(m.vertex_count) + ", got " +
                        std::to_string(m.indices[i]) + " in triangle " + std::to_string(i / 3));
}

/// dp/du of triangle t and the handedness of dp/dv about its geometric normal; false where the
/// mesh has no UVs or the UV triangle is degenerate.
inline bool triangle_dpdu(const MeshView& m, std::size_t t, detail::rt::V3& dpdu,
                          double& sign) noexcept {
    using namespace detail::rt;
    if (m.uvs == nullptr || t >= m.triangle_count) return false;
    const std::uint32_t* tri = m.indices + 3 * t;
    const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
    const V3 p1 = lightmap_detail::load3(m.positions, tri[1]);
    const V3 p2 = lightmap_detail::load3(m.positions, tri[2]);
    const float* uv = m.uvs;
    const double du1 = double(uv[2 * tri[1]]) - uv[2 * tri[0]],
                 dv1 = double(uv[2 * tri[1] + 1]) - uv[2 * tri[0] + 1];
    const double du2 = double(uv[2 * tri[2]]) - uv[2 * tri[0]],
                 dv2 = double(uv[2 * tri[2] + 1]) - uv[2 * tri[0] + 1];
    const double det = du1 * dv2 - du2 * dv1;
    if (!(det != 0 && std::isfinite(det))) return false;
    dpdu = ((p1 - p0) * dv2 - (p2 - p0) * dv1) * (1 / det);
    const V3 dpdv = ((p2 - p0) * du1 - (p1 - p0) * du2) * (1 / det);
    const V3 nc = cross(p1 - p0, p2 - p0);
    sign = dot(cross(nc, dpdu), dpdv) < 0 ? -1 : 1;
    return true;
}

/// `t` orthogonalised against unit n and normalised, or zero where too little is left.
inline vec3<double> orthonormal_tangent(const detail::rt::V3& t, const vec3<double>& n) noexcept {
    using namespace detail::rt;
    const V3 o = t - n * dot(n, t);
    const double tl = length(o);
    if (!(tl > 1e-12 * (length(t) + 1e-300) && std::isfinite(tl))) return {0, 0, 0};
    return o * (1 / tl);
}

}  // namespace bake_points_detail

/// Id of vertex 0 of mesh `mesh` (header comment: the vertices of the meshes before it).
inline std::uint64_t vertex_id_base(const std::vector<MeshView>& meshes, std::size_t mesh) {
    std::uint64_t base = 0;
    for (std::size_t k = 0; k < mesh && k < meshes.size(); ++k) base += meshes[k].vertex_count;
    return base;
}

/// Id of texel (0, 0) of mesh `mesh`'s res x res lightmap: mesh res^2.
inline std::uint64_t texel_id_base(std::size_t mesh, int res) noexcept {
    return std::uint64_t(mesh) * std::uint64_t(res) * std::uint64_t(res);
}

/// Vertex normals of a mesh, 3 per vertex, not normalised (the Baker normalises): the mesh's,
/// else area-weighted face normals; (0, 0, 1) where neither gives a finite direction.
inline std::vector<double> vertex_normals(const MeshView& m) {
    using namespace detail::rt;
    std::vector<double> n(3 * m.vertex_count, 0.0);
    if (m.normals != nullptr) {
        for (std::size_t i = 0; i < n.size(); ++i) n[i] = m.normals[i];
    } else {
        for (std::size_t t = 0; t < m.triangle_count; ++t) {
            const std::uint32_t* tri = m.indices + 3 * t;
            const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
            const V3 c = cross(lightmap_detail::load3(m.positions, tri[1]) - p0,
                               lightmap_detail::load3(m.positions, tri[2]) - p0);
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = tri[k];
                n[3 * v] += c.x;
                n[3 * v + 1] += c.y;
                n[3 * v + 2] += c.z;
            }
        }
    }
    for (std::size_t v = 0; v < m.vertex_count; ++v) {
        const V3 u = lightmap_detail::unit_or_zero({n[3 * v], n[3 * v + 1], n[3 * v + 2]});
        if (dot(u, u) > 0) continue;
        n[3 * v] = n[3 * v + 1] = 0.0;
        n[3 * v + 2] = 1.0;
    }
    return n;
}

/// The bake points of mesh `mesh`'s vertices (ids, normals and tangents: header comment).
/// Throws std::invalid_argument for a mesh index out of range, a null array or a vertex index
/// out of range.
inline std::vector<BakePoint> vertex_points(const std::vector<MeshView>& meshes, std::size_t mesh) {
    using namespace detail::rt;
    bake_points_detail::check_mesh("render::vertex_points", meshes, mesh);
    const MeshView& m = meshes[mesh];
    const std::vector<double> n = vertex_normals(m);
    // Without mesh tangents: the area-weighted dp/du of the triangles at each vertex (the
    // cross product's length is twice the area), and the sign of the larger weight.
    std::vector<V3> dpdu;
    std::vector<double> sign_weight;
    if (m.tangents == nullptr && m.uvs != nullptr) {
        dpdu.assign(m.vertex_count, V3{0, 0, 0});
        sign_weight.assign(m.vertex_count, 0.0);
        for (std::size_t t = 0; t < m.triangle_count; ++t) {
            V3 d{0, 0, 0};
            double sign = 1;
            if (!bake_points_detail::triangle_dpdu(m, t, d, sign)) continue;
            const std::uint32_t* tri = m.indices + 3 * t;
            const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
            const double area = length(cross(lightmap_detail::load3(m.positions, tri[1]) - p0,
                                             lightmap_detail::load3(m.positions, tri[2]) - p0));
            const double dl = length(d);
            if (!(dl > 0) || !std::isfinite(dl) || !std::isfinite(area)) continue;
            for (int k = 0; k < 3; ++k) {
                dpdu[tri[k]] = dpdu[tri[k]] + d * (area / dl);
                sign_weight[tri[k]] += sign * area;
            }
        }
    }
    const std::uint64_t base = vertex_id_base(meshes, mesh);
    std::vector<BakePoint> pts(m.vertex_count);
    for (std::size_t v = 0; v < m.vertex_count; ++v) {
        BakePoint& p = pts[v];
        p.p = lightmap_detail::load3(m.positions, v);
        p.n = {n[3 * v], n[3 * v + 1], n[3 * v + 2]};
        const V3 un = lightmap_detail::unit_or_zero(p.n);
        if (m.tangents != nullptr) {
            const float* t = m.tangents + 4 * v;
            p.tangent = bake_points_detail::orthonormal_tangent(V3{t[0], t[1], t[2]}, un);
            p.bitangent_sign = t[3] < 0 ? -1 : 1;
        } else if (!dpdu.empty()) {
            p.tangent = bake_points_detail::orthonormal_tangent(dpdu[v], un);
            p.bitangent_sign = sign_weight[v] < 0 ? -1 : 1;
        }
        if (dot(p.tangent, p.tangent) == 0) p.bitangent_sign = 1;
        p.id = base + v;
    }
    return pts;
}

/// The bake points of every vertex of every mesh, in scene order (ids 0 .. total - 1).
inline std::vector<BakePoint> vertex_points(const std::vector<MeshView>& meshes) {
    std::vector<BakePoint> all;
    for (std::size_t k = 0; k < meshes.size(); ++k) {
        std::vector<BakePoint> p = vertex_points(meshes, k);
        all.insert(all.end(), p.begin(), p.end());
    }
    return all;
}

/// The res x res lightmap layout of mesh `mesh` (render::layout_lightmap with id base
/// texel_id_base(mesh, res)), its samples given the tangents of the header's rule: where the
/// mesh has no tangents, the dp/du of the sample's triangle. Throws std::invalid_argument as
/// layout_lightmap() does, and for a mesh index out of range.
inline LightmapLayout texel_layout(const std::vector<MeshView>& meshes, std::size_t mesh, int res) {
    bake_points_detail::check_mesh("render::texel_layout", meshes, mesh);
    const MeshView& m = meshes[mesh];
    LightmapLayout layout = layout_lightmap(m, res, res, texel_id_base(mesh, res));
    if (m.tangents == nullptr)
        for (LightmapSample& s : layout.samples) {
            detail::rt::V3 d{0, 0, 0};
            double sign = 1;
            if (!bake_points_detail::triangle_dpdu(m, s.triangle, d, sign)) continue;
            s.point.tangent = bake_points_detail::orthonormal_tangent(
                d, lightmap_detail::unit_or_zero(s.point.n));
            if (dot(s.point.tangent, s.point.tangent) == 0) continue;
            s.point.bitangent_sign = s.bitangent_sign = sign;
        }
    return layout;
}

/// The bake points of a layout's samples, in its (row-major) order.
inline std::vector<BakePoint> texel_points(const LightmapLayout& layout) {
    std::vector<BakePoint> pts;
    pts.reserve(layout.samples.size());
    for (const LightmapSample& s : layout.samples) pts.push_back(s.point);
    return pts;
}

/// The bake points of a probe grid (free points: normal 0), in index order.
inline std::vector<BakePoint> probe_points(const ProbeGrid& grid) {
    std::vector<BakePoint> pts(grid.size());
    for (std::size_t i = 0; i < pts.size(); ++i) {
        pts[i].p = grid.position(i);
        pts[i].id = i;
    }
    return pts;
}

}  // namespace sphbasis::render
