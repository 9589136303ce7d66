// sphbasis CLI support: the JSON scene file of `sphbasis bake` (docs/scene-format.md).
//
// load_scene() reads the file with nlohmann-json, loads meshes with Assimp (OBJ, glTF 2.0, FBX,
// PLY, OFF, ...), images with stb_image (PNG, JPEG, TGA, BMP, HDR) and OpenEXR, builds the
// procedural shapes, applies the transforms, and returns owning arrays. scene_desc() lends them
// to the library as render::SceneDesc (render/bake.hpp). Paths in the file are relative to the
// directory of the scene file.
//
// Every problem is a std::runtime_error with one line naming the file and the place in it:
//   "scenes/a.json: meshes[1].transform.scale: expected a finite number, got inf"
//   "scenes/a.json: meshes[0]: unknown key 'albdo' (did you mean 'albedo'?)"
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/bake_file.hpp>
#include <sphbasis/render/lighting.hpp>
#include <sphbasis/render/mesh.hpp>
#include <sphbasis/render/probe_grid.hpp>
#include <string>
#include <vector>

namespace sphbasis::cli {

/// An image kept for the renderer (normal maps): linear floats, row-major from the top row.
struct SceneTexture {
    std::string path;  // as resolved (empty: none)
    int width = 0, height = 0, channels = 0;
    std::shared_ptr<const std::vector<float>> texels;
    explicit operator bool() const noexcept { return texels != nullptr; }
};

/// One entry of "meshes", loaded and transformed to world space.
struct SceneMesh {
    std::string name;    // "name" or "mesh<k>"
    std::string source;  // the resolved file, or "shape:<kind>"
    render::Mesh mesh;
    SceneTexture normal_map;  // tangent-space normal map, [0, 1] per channel (also in mesh)
    std::size_t dropped_triangles = 0;  // zero-area or non-finite triangles removed on load
    /// High to low (render/high_to_low.hpp): the "source" mesh's name and index (-1: none), the
    /// "cage" positions (null: none; same vertices and triangles as `mesh`) and
    /// "max_ray_distance" (infinite: none).
    std::string source_mesh;
    long bake_source = -1;
    /// The mesh file's second UV set (Assimp channel 1, 2 per vertex; empty: none) and the set
    /// lightmaps are laid out in ("lightmap_uv": 0 or 1; default 1 when the file has one). The
    /// renderer's arrays (mesh.uvs) keep set 0, the material UVs.
    std::vector<float> uvs1;
    int lightmap_uv = 0;
    const std::vector<float>& lightmap_uvs() const noexcept {
        return lightmap_uv == 1 ? uvs1 : mesh.uvs;
    }
    std::shared_ptr<const std::vector<float>> cage;
    double max_ray_distance = std::numeric_limits<double>::infinity();
};

/// "camera": kept for the renderer (the bake does not use it).
struct SceneCamera {
    bool present = false;
    vec3<double> position{0, 0, 0}, look_at{0, 0, -1}, up{0, 0, 1};
    double fov_deg = 45;
    int width = 320, height = 240;  // pixels
};

/// "render": the renderer's settings (`sphbasis render`; the bake ignores them). Options on
/// the command line override them.
struct SceneRender {
    bool present = false;
    int bounces = 1;            // diffuse interreflection bounces; -1: unbounded
    bool auto_exposure = true;  // "exposure": "auto" (default) or a number
    double exposure = 1;        // when !auto_exposure
    std::string tonemap = "aces";
    int spp = 0;       // 0: not given (progressive until `noise`)
    double noise = 0;  // 0: not given
};

struct SceneFile {
    std::string path;  // the scene file as given
    std::vector<SceneMesh> meshes;
    render::Environment environment;  // texels borrowed from environment_texels
    std::shared_ptr<const std::vector<float>> environment_texels;
    std::vector<render::Light> lights;
    SceneCamera camera;
    SceneRender render;
    bool has_probes = false;
    render::ProbeGrid probes;  // "probes": {"min", "max", "counts"}
    /// Every file the load read besides the scene file (meshes and what their importer opened,
    /// images, the environment map), in the order read; repeats possible.
    std::vector<std::string> inputs;

    /// Views of the meshes and the lighting for render::Baker (valid while *this lives).
    render::SceneDesc scene_desc() const;
    /// scene_desc() with each mesh's UVs its lightmap set (what texel bakes lay out).
    render::SceneDesc lightmap_desc() const;
};

/// Loads a scene file (see the file comment). Throws std::runtime_error with one line.
SceneFile load_scene(const std::string& path);

/// XXH3-64 (render::InputHash) of the bytes of the scene file and of every file it read
/// (SceneFile::inputs, each once, in order): what a bake's results depend on besides the
/// settings. Reads the files again; throws std::runtime_error if one cannot be read.
std::uint64_t input_hash(const SceneFile& scene);

/// Loads an image as linear floats with 3 channels: 8- and 16-bit formats through stb_image,
/// converted from sRGB when `srgb`; .hdr and .exr as stored. Throws std::runtime_error.
SceneTexture load_texture(const std::string& path, bool srgb);

/// The key of `candidates` closest to `key` by edit distance, or "" if none is close.
std::string closest_key(const std::string& key, const std::vector<std::string>& candidates);

}  // namespace sphbasis::cli
