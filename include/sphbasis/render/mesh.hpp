// sphbasis render tier: meshes and textures as arrays, the way an engine already holds them.
//
// The render tier (sphbasis::render: Embree 3 and oneTBB) reads no files: the `sphbasis` tool
// loads meshes (Assimp) and images (OpenEXR, stb) and hands the library these views. All
// positions are in world space (the caller applies transforms) and every mesh is two-sided.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "../core/vec.hpp"

namespace sphbasis::render {

/// A linear-RGB texture, row-major, `channels` floats per texel (1, 3 or 4; only the first
/// three are read as RGB, a single channel is grey). Texel (0, 0) is at uv (0, 1) (the top-left
/// of the image, as OpenGL's uv convention seen on an image file); lookups wrap in u and v.
struct TextureView {
    const float* texels = nullptr;
    int width = 0, height = 0, channels = 3;
};

/// A triangle mesh borrowed from the caller: nothing is copied until a render::Scene is built.
/// Required: positions (3 floats per vertex) and indices (3 per triangle). Optional arrays are
/// null when absent: shading normals (3 per vertex; the geometric normal is used without them),
/// one UV set (2 per vertex; needed for texel bakes and albedo maps) and tangents (4 per
/// vertex: xyz and the handedness sign of the bitangent, as glTF stores them; without them the
/// tangent frame is render::tangent_frame() of the normal).
struct MeshView {
    const float* positions = nullptr;
    std::size_t vertex_count = 0;
    const std::uint32_t* indices = nullptr;
    std::size_t triangle_count = 0;
    const float* normals = nullptr;
    const float* uvs = nullptr;
    const float* tangents = nullptr;
    /// Diffuse albedo in [0, 1] per channel; multiplied by albedo_map where one is given.
    std::array<float, 3> albedo{0.5f, 0.5f, 0.5f};
    TextureView albedo_map{};
    /// Tangent-space normal map (needs UVs): channel c in [0, 1] encodes the tangent-frame
    /// component 2c - 1 of the normal (x along the tangent, y along the bitangent, z along the
    /// shading normal), read as stored (no sRGB). Used by the renderer, ignored by the bake.
    TextureView normal_map{};
    /// Blinn-Phong specular: exponent s > 0 enables it (0: the material is purely diffuse);
    /// `specular` is the RGB reflectance k_s in [0, 1] of the energy-normalised lobe
    /// k_s (s + 8) / (8 pi) (n.h)^s (render/bsdf.hpp). The bake ignores both.
    float shininess = 0;
    std::array<float, 3> specular{0.04f, 0.04f, 0.04f};
};

/// An owning mesh: what the tool's loaders and render::shapes produce. view() borrows it.
struct Mesh {
    std::vector<float> positions, normals, uvs, tangents;
    std::vector<std::uint32_t> indices;
    std::array<float, 3> albedo{0.5f, 0.5f, 0.5f};
    std::shared_ptr<const std::vector<float>> albedo_texels;  // owns albedo_map's texels
    TextureView albedo_map{};
    std::shared_ptr<const std::vector<float>> normal_texels;  // owns normal_map's texels
    TextureView normal_map{};
    float shininess = 0;
    std::array<float, 3> specular{0.04f, 0.04f, 0.04f};

    std::size_t vertex_count() const noexcept { return positions.size() / 3; }
    std::size_t triangle_count() const noexcept { return indices.size() / 3; }
    MeshView view() const noexcept {
        MeshView v;
        v.positions = positions.data();
        v.vertex_count = vertex_count();
        v.indices = indices.data();
        v.triangle_count = triangle_count();
        v.normals = normals.empty() ? nullptr : normals.data();
        v.uvs = uvs.empty() ? nullptr : uvs.data();
        v.tangents = tangents.empty() ? nullptr : tangents.data();
        v.albedo = albedo;
        v.albedo_map = albedo_map;
        v.normal_map = normal_map;
        v.shininess = shininess;
        v.specular = specular;
        return v;
    }
};

}  // namespace sphbasis::render
