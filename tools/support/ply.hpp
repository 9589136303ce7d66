// sphbasis CLI support: binary PLY output of per-vertex bakes.
//
// Format: "ply / format binary_little_endian 1.0", optional comments, one vertex element with
// one `float` property per name (in the given order), then `element face` with
// `property list uchar uint vertex_indices` (triangles). Readers: Blender, MeshLab, Open3D,
// numpy (np.fromfile with a structured dtype after the header), Assimp.
//
// The bake's vertex property names (tools/cli/bake.cpp, documented in docs/scene-format.md):
//   x y z nx ny nz               world position and shading normal
//   ao ao_stderr                 ambient occlusion and its standard error
//   bent_x bent_y bent_z         bent normal
//   vis_<i> vis_stderr_<i>       SH visibility, i = 0 .. bands^2 - 1 (ACN)
//   transfer_<i>                 transfer vector when the same for R, G and B, else
//   transfer_r_<i> transfer_g_<i> transfer_b_<i>, and transfer_stderr_<i>
//   irr_r_<i> irr_g_<i> irr_b_<i>   irradiance coefficients in the chosen basis, i < coeffs
//   rad_r_<i> rad_g_<i> rad_b_<i>   SH radiance, i < bands^2
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sphbasis::cli {

/// The bytes of a binary little-endian PLY file. `values` holds vertex_count rows of
/// names.size() floats; `indices` holds 3 per triangle. Throws std::invalid_argument when the
/// sizes disagree or an index is out of range.
std::string ply_binary(const std::vector<std::string>& names, const std::vector<float>& values,
                       std::size_t vertex_count, const std::vector<std::uint32_t>& indices,
                       const std::vector<std::string>& comments = {});

}  // namespace sphbasis::cli
