// sphbasis render tier: the points a representation's bake (BakeRequest, render/bake_cache.hpp)
// is run at: render/bake_points.hpp's, the points `sphbasis bake` uses too (one id scheme: a
// vertex's global index in scene order, texel (x, y) of mesh k's lightmap of size S at
// k S^2 + y S + x, a probe's grid index; one tangent rule, render::Hit's), so a representation's
// bake of a point draws the samples the command's bake of it draws.
#pragma once

#include <vector>

#include "../bake.hpp"
#include "../bake_cache.hpp"
#include "../bake_points.hpp"
#include "../lightmap.hpp"
#include "../mesh.hpp"

namespace sphbasis::render::representations {

/// The points of request q of a scene with meshes `meshes`; texel requests also fill `layout`.
inline std::vector<BakePoint> bake_points(const std::vector<MeshView>& meshes, const BakeRequest& q,
                                          LightmapLayout& layout) {
    if (q.where == BakeRequest::Where::probes) return probe_points(q.probes);
    if (q.where == BakeRequest::Where::vertex) return vertex_points(meshes, q.mesh);
    layout = texel_layout(meshes, q.mesh, q.lightmap_size);
    return texel_points(layout);
}

}  // namespace sphbasis::render::representations
