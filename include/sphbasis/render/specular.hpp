// sphbasis render tier: Blinn-Phong specular from mipmapped normal maps, with and without
// Toksvig's factor, and its supersampled reference.
//
// CONTRACT (written by the lead; the specular helper implements it and may add members and
// functions, but keeps these names and meanings: representation.hpp and the tool use them).
//
// Source: M. Toksvig, "Mipmapping Normal Maps" (NVIDIA technical brief, 2004); the factor and
// the widened lobe are shading/toksvig.hpp. A normal map's mip chain averages the decoded
// tangent-space normals (2c - 1) without renormalising (box filter, 2x2 per level, down to
// 1x1); the length |Na| <= 1 of the averaged normal measures the spread the level hides.
// Shading at a pixel whose footprint covers many texels reads the level (trilinear) whose
// texels match the footprint (lod = log2(footprint in texels)), then:
//   aliased:   k_s (s + 8) / (8 pi) (n.h)^s (n.l), n = normalize(Na) (the spread is lost:
//              sparkling and too-bright highlights under minification);
//   toksvig:   k_s (s + 8) / (8 pi) * toksvig::specular(Na.h / ..., |Na|, s) * (n.l), the lobe
//              widened by f_t (Toksvig eq. 6-8, with the brief's energy scaling);
//   reference: the finest level, normalised, averaged over ss x ss subpixel camera rays
//              (render_specular_reference), i.e. what the pixel should show.
// Lights: the scene's directional lights (radiance `color` from one direction), times the
// shadow-free n.l; other lights and the environment are not part of the specular comparison.
// Meshes with shininess 0 contribute 0; without a normal map the shading normal is used.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../shading/toksvig.hpp"
#include "bake.hpp"
#include "camera.hpp"
#include "image.hpp"
#include "lighting.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// A box-filtered mip chain of a tangent-space normal map, averages not renormalised.
class NormalMipChain {
  public:
    explicit NormalMipChain(const TextureView& normal_map) {
        (void)normal_map;
        sphbasis::detail::throw_runtime("render::NormalMipChain",
                                        "an implementation, got the contract stub");
    }
    int levels() const noexcept { return 0; }
    /// The averaged tangent-space normal at uv, level `lod` >= 0 (fractional: trilinear).
    vec3<double> average(double u, double v, double lod) const noexcept {
        (void)u, (void)v, (void)lod;
        return {0, 0, 1};
    }
};

class SpecularShading {
  public:
    enum class Mode { aliased, toksvig, reference };
    /// Builds the mip chains of every mesh with a normal map; keeps the directional lights.
    explicit SpecularShading(const SceneDesc& scene) {
        (void)scene;
        sphbasis::detail::throw_runtime("render::SpecularShading",
                                        "an implementation, got the contract stub");
    }
    /// Specular radiance toward `view` (unit, hit to eye) at a hit; footprint = the pixel's
    /// world-space width at the hit.
    RGB shade(Mode mode, const Hit& hit, const vec3<double>& view, double footprint) const {
        (void)mode, (void)hit, (void)view, (void)footprint;
        return {0, 0, 0};
    }
};

/// The supersampled reference of the specular comparison (header comment).
inline Image render_specular_reference(const SceneDesc& scene, const Scene& rt,
                                       const Camera& camera, int ss) {
    (void)scene, (void)rt, (void)camera, (void)ss;
    sphbasis::detail::throw_runtime("render::render_specular_reference",
                                    "an implementation, got the contract stub");
}

}  // namespace sphbasis::render
