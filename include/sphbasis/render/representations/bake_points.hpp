// sphbasis render tier: the points a representation's bake (BakeRequest, render/bake_cache.hpp)
// is run at.
//
// Vertex points use the mesh normals (area-weighted face normals without them), point id
// (mesh << 32) + vertex; texel points come from layout_lightmap() (id base mesh << 32), with
// the tangent of render::Hit where the mesh has no tangents (the triangle's dp/du and its
// handedness), so the tangent frame of the baked irradiance is the one a camera hit
// reconstructs; probe points are the grid's positions, id the probe index.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "../bake.hpp"
#include "../bake_cache.hpp"
#include "../detail/rt_math.hpp"
#include "../lightmap.hpp"
#include "../mesh.hpp"

namespace sphbasis::render::representations {

/// Vertex normals: the mesh's, else area-weighted face normals.
inline std::vector<double> vertex_normals(const MeshView& m) {
    std::vector<double> n(3 * m.vertex_count, 0.0);
    if (m.normals) {
        for (std::size_t i = 0; i < n.size(); ++i) n[i] = m.normals[i];
        return n;
    }
    for (std::size_t t = 0; t < m.triangle_count; ++t) {
        const std::uint32_t* tri = m.indices + 3 * t;
        using namespace detail::rt;
        const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
        const V3 p1 = lightmap_detail::load3(m.positions, tri[1]);
        const V3 p2 = lightmap_detail::load3(m.positions, tri[2]);
        const V3 c = cross(p1 - p0, p2 - p0);
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = tri[k];
            if (v >= m.vertex_count) continue;
            n[3 * v] += c.x;
            n[3 * v + 1] += c.y;
            n[3 * v + 2] += c.z;
        }
    }
    return n;
}

/// The tangent render::Hit gives a point of triangle t without mesh tangents: the
/// triangle's dp/du, orthogonalised against n, with the handedness of dp/dv.
inline void hit_tangent(const MeshView& m, LightmapSample& s) {
    using namespace detail::rt;
    if (m.tangents || !m.uvs || s.triangle >= m.triangle_count) return;
    const std::uint32_t* tri = m.indices + 3 * std::size_t(s.triangle);
    const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
    const V3 p1 = lightmap_detail::load3(m.positions, tri[1]);
    const V3 p2 = lightmap_detail::load3(m.positions, tri[2]);
    const float* uv = m.uvs;
    const double du1 = double(uv[2 * tri[1]]) - uv[2 * tri[0]],
                 dv1 = double(uv[2 * tri[1] + 1]) - uv[2 * tri[0] + 1];
    const double du2 = double(uv[2 * tri[2]]) - uv[2 * tri[0]],
                 dv2 = double(uv[2 * tri[2] + 1]) - uv[2 * tri[0] + 1];
    const double det = du1 * dv2 - du2 * dv1;
    if (!(det != 0 && std::isfinite(det))) return;
    const V3 dpdu = ((p1 - p0) * dv2 - (p2 - p0) * dv1) * (1 / det);
    const V3 dpdv = ((p2 - p0) * du1 - (p1 - p0) * du2) * (1 / det);
    const V3 nc = normalized(cross(p1 - p0, p2 - p0));
    const double sign = dot(cross(nc, dpdu), dpdv) < 0 ? -1 : 1;
    const V3 n = normalized(s.point.n);
    const V3 t = dpdu - n * dot(n, dpdu);
    const double tl = length(t);
    if (!(tl > 1e-12 * (length(dpdu) + 1e-300) && std::isfinite(tl))) return;
    s.point.tangent = t * (1 / tl);
    s.point.bitangent_sign = s.bitangent_sign = sign;
}

/// The points of request q of a scene with meshes `meshes`; texel requests also fill `layout`.
inline std::vector<BakePoint> bake_points(const std::vector<MeshView>& meshes, const BakeRequest& q,
                                          LightmapLayout& layout) {
    std::vector<BakePoint> pts;
    if (q.where == BakeRequest::Where::probes) {
        for (std::size_t i = 0; i < q.probes.size(); ++i) {
            BakePoint p;
            p.p = q.probes.position(i);
            p.id = i;
            pts.push_back(p);
        }
        return pts;
    }
    const MeshView& m = meshes[q.mesh];
    const std::uint64_t base = std::uint64_t(q.mesh) << 32;
    if (q.where == BakeRequest::Where::vertex) {
        const std::vector<double> n = vertex_normals(m);
        pts.resize(m.vertex_count);
        for (std::size_t v = 0; v < m.vertex_count; ++v) {
            BakePoint& p = pts[v];
            p.p = lightmap_detail::load3(m.positions, v);
            p.n = {n[3 * v], n[3 * v + 1], n[3 * v + 2]};
            if (!(dot(p.n, p.n) > 0) || !detail::rt::finite(p.n)) p.n = {0, 0, 1};
            p.id = base + v;
        }
        return pts;
    }
    layout = layout_lightmap(m, q.lightmap_size, q.lightmap_size, base);
    for (LightmapSample& s : layout.samples) {
        hit_tangent(m, s);
        pts.push_back(s.point);
    }
    return pts;
}

}  // namespace sphbasis::render::representations
