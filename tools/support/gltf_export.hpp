// sphbasis CLI support: glTF 2.0 binary (.glb) output of baked meshes, written with tinygltf
// (Debian's libtinygltf-dev). Layout (docs/export-format.md):
//   one node and one mesh of one triangle primitive per scene mesh, in world space (the scene's
//   transforms applied), with POSITION (with min and max), NORMAL (the bake's shading normals),
//   TEXCOORD_0 = (u, 1 - v) of the mesh's UV set when it has one (glTF puts v = 0 at the top
//   row of an image, the scene's UVs at the bottom), indices as UNSIGNED_INT, and the bake's
//   per-vertex results as application-specific FLOAT attributes (names starting with '_', as
//   glTF requires: "_AO", "_BENT", "_SH0", ...);
//   lightmaps as images referenced by URI (the PNG files beside the .glb) and textures with a
//   linear, clamp-to-edge sampler, on the UV set the bake laid them out in (TEXCOORD_0, or
//   TEXCOORD_1 = (u, 1 - v) of the mesh's second UV set when that is its lightmap set); the
//   "_AO" lightmap is also the material's occlusionTexture (stored with scale 1, bias 0). Every
//   lightmap is listed in the primitive's extras.sphbasis_lightmaps with its texture index (or
//   -1 and its file for EXR, which core glTF cannot reference), texCoord, channels and the
//   per-channel scale and bias of its range compression (support/engine_export.hpp).
#pragma once

#include <sphbasis/render/mesh.hpp>
#include <string>
#include <vector>

#include "json.hpp"

namespace sphbasis::cli {

/// A per-vertex FLOAT attribute: components (1 or 3) floats per vertex.
struct GltfAttribute {
    std::string name;  // starts with '_'
    int components = 1;
    std::vector<float> values;
};

/// A lightmap of a mesh, stored in the file `uri` beside the .glb.
struct GltfLightmap {
    std::string attribute;  // "_AO", ...
    std::string uri;
    bool png = true;  // referenced as a texture (EXR: listed in extras only)
    Json extras;      // channels, scale, bias, ...
};

struct GltfMesh {
    std::string name;
    const render::Mesh* mesh = nullptr;
    std::vector<double> normals;  // 3 per vertex
    /// The lightmap UV set when it is not the material set (mesh->uvs): written as TEXCOORD_1,
    /// and the lightmaps reference texCoord 1; null: the lightmaps are on TEXCOORD_0.
    const std::vector<float>* lightmap_uvs = nullptr;
    std::vector<GltfAttribute> attributes;
    std::vector<GltfLightmap> lightmaps;
};

/// The bytes of a .glb file holding `meshes` as described in the file comment; `asset_extras`
/// goes to asset.extras (generator settings). Throws std::invalid_argument when an attribute's
/// size disagrees with its mesh, std::runtime_error if tinygltf fails.
std::string encode_glb(const std::vector<GltfMesh>& meshes, const Json& asset_extras);

}  // namespace sphbasis::cli
