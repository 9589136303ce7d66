// sphbasis render tier: the baked lighting representations a game would ship, rendered from
// the bakes of render/bake.hpp under the same lighting as the ground truth (path_tracer.hpp).
//
// CONTRACT (written by the lead; the representations helper implements it and may add members
// and functions, but keeps these names and meanings: the tool is written against them).
//
// Every representation shades a camera hit as albedo(hit) / pi * E, E the irradiance it
// reconstructs (the diffuse part only; the specular ones below are the exception), with the
// normal-mapped normal (Scene::normal_mapped) wherever the representation can use a per-pixel
// normal. Names (representation_names(), in report order):
//   irradiance-sh9            unshadowed SH irradiance of the distant lighting (environment +
//                             analytic lights projected on 3 bands; Ramamoorthi and Hanrahan,
//                             "An Efficient Representation for Irradiance Environment Maps",
//                             SIGGRAPH 2001); no bake.
//   irradiance-sh9-windowed   the same with the lighting windowed (ops/sh_windowing.hpp).
//   ao                        ao x irradiance-sh9 (ao baked per texel, per vertex without UVs).
//   bent                      ao x the SH irradiance at the bent normal.
//   prt-vertex, prt-texel     diffuse PRT transfer (prt_bands bands, shadows and bounces baked)
//                             dotted with the SH of the distant lighting, interpolated from
//                             vertices or read from a lightmap; the lighting may be rotated at
//                             render time (RepresentationSettings::lighting_rotation): its SH
//                             are rotated (ops/sh_rotation.hpp), nothing is re-baked.
//   lightmap-sh4, -sh9, -hbasis4, -hbasis6, -hbasis-mod6, -hl2, -hsh4, -hsh9
//                             irradiance lightmaps (the bake's `irradiance` in that basis, per
//                             texel, bilinear) evaluated at the normal-mapped normal in the
//                             texel's tangent frame (Ishmukhametov, "Irradiance Normal
//                             Mapping"). Meshes without UVs fall back to irradiance-sh9 (noted).
//   volume                    irradiance-volume probes (render/probe_grid.hpp, SH radiance,
//                             3 bands) interpolated trilinearly at the hit, convolved with the
//                             clamped cosine at the normal.
//   specular-toksvig, specular-aliased
//                             Blinn-Phong specular of the scene's directional lights from the
//                             mipmapped normal map with and without the Toksvig factor
//                             (render/specular.hpp); compared with render_specular_reference()
//                             of specular.hpp, not with the path tracer.
//
// Bakes: each representation declares the bakes it reads (BakeRequest); prepare() runs each
// distinct request once, or loads it from a BakeCache under bake_key(), a hash of everything the
// bake depends on: the geometry of every mesh (they occlude), the albedos and albedo maps when it
// has bounces, the lighting (environment texels, rotation, scale; lights) only for
// lighting-dependent quantities (irradiance, radiance), and the settings. Re-rendering with a
// rotated environment therefore re-bakes nothing for PRT and only lightmaps and probes for a
// changed light.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "bake.hpp"
#include "camera.hpp"
#include "image.hpp"
#include "lightmap.hpp"
#include "probe_grid.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// Every representation name, in report order (header comment).
inline const std::vector<std::string>& representation_names() {
    static const std::vector<std::string> names{"irradiance-sh9",
                                                "irradiance-sh9-windowed",
                                                "ao",
                                                "bent",
                                                "prt-vertex",
                                                "prt-texel",
                                                "lightmap-sh4",
                                                "lightmap-sh9",
                                                "lightmap-hbasis4",
                                                "lightmap-hbasis6",
                                                "lightmap-hbasis-mod6",
                                                "lightmap-hl2",
                                                "lightmap-hsh4",
                                                "lightmap-hsh9",
                                                "volume",
                                                "specular-toksvig",
                                                "specular-aliased"};
    return names;
}

struct RepresentationSettings {
    int rays = 256;           // bake rays per point and pass
    int bounces = 1;          // bake interreflection bounces (the scene's bounce count)
    int prt_bands = 3;        // PRT transfer bands
    int lightmap_size = 128;  // texels per side of each mesh's lightmap
    std::uint64_t seed = 0;
    bool has_probes = false;  // false: a 4 x 4 x 4 grid over the scene's bounding box
    ProbeGrid probes;
    /// Render-time rotation of the distant lighting (environment and lights) for the
    /// SH-lit representations (irradiance-sh9*, ao, bent, prt-*): world = R * baked world.
    Mat3<double> lighting_rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
};

/// One bake a representation reads.
struct BakeRequest {
    enum class Where { vertex, texel, probes } where = Where::vertex;
    std::size_t mesh = 0;  // index into SceneDesc::meshes (probes: 0)
    BakeSettings settings;
    int lightmap_size = 0;  // texel bakes
    bool lighting_dependent = false;
};

struct BakeData {
    BakeRequest request;
    LightmapLayout layout;  // texel bakes
    std::vector<PointResult> results;
    std::vector<Pass> plan;
    double seconds = 0;
    std::uint64_t rays = 0;
    bool from_cache = false;
};

/// The hash of everything a bake depends on (header comment).
inline std::uint64_t bake_key(const SceneDesc& scene, const BakeRequest& request) {
    sphbasis::detail::throw_runtime("render::representation",
                                    "an implementation, got the contract stub");
}
/// Bytes of a BakeData (versioned, little-endian) and back; deserialize throws
/// std::runtime_error for truncated or foreign bytes.
inline std::vector<std::uint8_t> serialize(const BakeData& data) {
    sphbasis::detail::throw_runtime("render::representation",
                                    "an implementation, got the contract stub");
}
inline BakeData deserialize(const std::vector<std::uint8_t>& bytes) {
    sphbasis::detail::throw_runtime("render::representation",
                                    "an implementation, got the contract stub");
}

/// Where bakes are kept between runs (the tool keeps files; tests keep memory).
class BakeCache {
  public:
    virtual ~BakeCache() = default;
    virtual bool load(std::uint64_t key, BakeData& out) = 0;
    virtual void store(std::uint64_t key, const BakeData& data) = 0;
};

struct RepresentationStats {
    std::string name;
    double bake_seconds = 0;  // of the bakes it reads (shared bakes counted for each reader)
    std::uint64_t bake_rays = 0;
    bool cached = false;                // every bake it reads came from the cache
    std::string element;                // "texel", "vertex", "probe" or "none"
    std::size_t bytes_per_element = 0;  // at the stored precision (float)
    std::size_t elements = 0;
    std::string cannot_show;  // e.g. "no shadows; no interreflection"
};

/// Renders the representations of a scene.
class Representations {
  public:
    /// Borrows `scene` (the arrays) and `rt` (built from scene.meshes). Throws
    /// std::invalid_argument for an unknown name (the message lists representation_names()),
    /// a duplicate, or invalid settings.
    Representations(const SceneDesc& scene, const Scene& rt, const RepresentationSettings& settings,
                    const std::vector<std::string>& names) {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    /// The distinct bakes the requested representations read (the plan), before prepare().
    const std::vector<BakeRequest>& bakes() const noexcept {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    /// Runs or loads every planned bake (cache may be null). progress(done, total) in points.
    void prepare(BakeCache* cache,
                 const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    /// Bakes run and bakes loaded from the cache by prepare().
    std::size_t bakes_run() const noexcept {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    std::size_t bakes_loaded() const noexcept {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    /// The outgoing radiance toward the camera at a hit for representation `index` (into the
    /// names given), view = unit direction from the hit to the eye, footprint = the pixel's
    /// world-space width at the hit (for the normal map's mip level).
    RGB shade(std::size_t index, const Hit& hit, const vec3<double>& view, double footprint) const {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    /// One image: a camera ray per pixel centre (spp > 1: jittered, averaged) {
    /// sphbasis::detail::throw_runtime("render::Representations", "an implementation, got the
    /// contract stub"); } escaped rays show the (rotated) environment like the ground truth.
    Image render(std::size_t index, const Camera& camera, int spp = 1) const {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    RepresentationStats stats(std::size_t index) const {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
    const std::vector<std::string>& names() const noexcept {
        sphbasis::detail::throw_runtime("render::Representations",
                                        "an implementation, got the contract stub");
    }
};

}  // namespace sphbasis::render
