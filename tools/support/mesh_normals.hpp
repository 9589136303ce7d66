// sphbasis CLI support: vertex normals for meshes read from files without them (the scene key
// "smoothing_angle_deg", docs/scene-format.md).
//
// generate_normals() gives each corner of a flagged triangle the angle-weighted mean of the
// normals of the flagged triangles around its position whose normal lies within the smoothing
// angle of its own triangle's normal (a crease angle: each face smooths only with the faces
// close to it, so a box keeps flat faces and a tessellated sphere becomes smooth); angle 0 gives
// every triangle its own flat normal. Positions are welded by equal coordinates, so files that
// repeat vertices per face (OBJ) or split them at UV seams smooth like shared vertices, and
// vertices are split where their corners get different normals. Corner weights are the
// triangle's angle at the corner: Thürmer and Wüthrich, "Computing Vertex Normals from Polygonal
// Facets", Journal of Graphics Tools 3(1), 1998 (the normal does not depend on how a face is
// triangulated). Triangles are compared by their winding's normal: neighbours wound the other
// way (about 180 degrees apart) are not smoothed together below 180 degrees.
//
// Assimp's own generation (aiProcess_GenSmoothNormals with AI_CONFIG_PP_GSN_MAX_SMOOTHING_ANGLE)
// is not used: on files whose faces share vertices (PLY, OFF) it stores one face's normal per
// shared vertex (a cube of 8 vertices gets three faces' normals at its corners), and
// aiProcess_JoinIdenticalVertices before it joins what a crease must keep apart.
//
// Cost: O(sum over welded positions of k^2), k the triangles around a position (k is about 6
// on ordinary meshes).
#pragma once

#include <sphbasis/render/mesh.hpp>
#include <vector>

namespace sphbasis::cli {

/// The default smoothing angle in degrees (docs/scene-format.md says why).
inline constexpr double default_smoothing_angle_deg = 30;

/// Rebuilds m's vertices so that every triangle t with generate[t] != 0 gets normals by the rule
/// of the file comment (smoothing_angle_deg in [0, 180]; 180 smooths every face around a
/// position); the other triangles keep their vertices and normals. m.normals holds 3 floats a
/// vertex (any values for the vertices of generated triangles); positions, UVs and tangents of
/// a vertex are copied to each of its splits. Vertices no triangle uses are dropped. Throws
/// std::invalid_argument for a size mismatch or an index out of range.
void generate_normals(render::Mesh& m, const std::vector<char>& generate,
                      double smoothing_angle_deg);

}  // namespace sphbasis::cli
