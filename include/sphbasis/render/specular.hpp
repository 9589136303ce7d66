// sphbasis render tier: Blinn-Phong specular from mipmapped normal maps, with and without
// Toksvig's factor, and its supersampled reference.
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
//   reference: the finest level, normalised, averaged over ss x ss camera rays per pixel
//              (render_specular_reference), i.e. what the pixel should show.
// Every image here comes from render::ImageLoop (image_loop.hpp): an aliased or toksvig image
// compared with the reference is made with the same ss x ss sample positions (same seed), each
// sample reading the mip level of the whole pixel's footprint.
// Lights: the scene's directional lights (irradiance `color` on a surface facing it, as
// lighting.hpp defines), times the shadow-free n.l; other lights and the environment are not part
// of the specular comparison. Meshes with shininess 0 contribute 0; without a normal map the
// shading normal is used.
//
// Implementation notes:
//  - Level of detail: the pixel's footprint (pixel_footprint(): the side of the square with the
//    area of the pixel's footprint on the surface) times the hit triangle's UV length per world
//    length (sqrt(UV area / world area), precomputed per triangle) times max(width, height) of
//    level 0 gives the footprint in level-0 texels; lod = log2 of it, clamped to
//    [0, levels - 1]. Isotropic: an anisotropic footprint is read at its mean width.
//  - The tangent frame is the hit's (tangent, bitangent_sign x (n x tangent), n); it is
//    orthonormal, so |Na| in world space equals |Na| in tangent space.
//  - A light contributes only where it is above the geometric surface (ng.l > 0) and above the
//    shaded normal (n.l > 0, n = normalize(Na)); the same in all three modes.
//  - toksvig: k_s (s + 8)/(8 pi) toksvig::specular(Na.h, |Na|, s) (n.l): eq. 8's factor
//    (1 + f_t s)/(1 + s) preserves the energy of the half-vector lobe, so the outer constant
//    stays the unwidened (s + 8)/(8 pi).
//  - reference: the ss x ss rays sit at ImageLoop's positions (a per-pixel scrambled R2
//    sequence, deterministic; the centre when ss = 1); misses and non-shiny meshes give 0.
//  - The lobe is bsdf.hpp's (the path tracer's): its energy is about 1, not exactly 1
//    (blinn_phong_lobe()).
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../shading/toksvig.hpp"
#include "bake.hpp"
#include "bsdf.hpp"
#include "camera.hpp"
#include "detail/rt_math.hpp"
#include "image.hpp"
#include "image_loop.hpp"
#include "lighting.hpp"
#include "normal_maps.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// A box-filtered mip chain of a tangent-space normal map, averages not renormalised.
/// Level 0 holds the decoded normals 2c - 1 of the map (as stored, not normalised); level k + 1
/// has max(1, floor(size_k / 2)) texels per axis, each the area-weighted mean of the level-k
/// texels its footprint covers: exactly the mean of its 2 x 2 children when the size is even
/// (an odd size gives a footprint of 2 + 1/m texels with fractional edge weights, so every level
/// keeps the map's mean exactly). The chain ends at 1 x 1. Texel (0, 0) of every level is at
/// uv (0, 1), as mesh.hpp's textures; lookups wrap. Stored in float.
class NormalMipChain {
  public:
    /// Throws std::invalid_argument for a null buffer, a width or height outside [1, 16384],
    /// channels other than 3 or 4, or a texel that is not finite.
    explicit NormalMipChain(const TextureView& normal_map) {
        constexpr const char* fn = "render::NormalMipChain";
        const TextureView& t = normal_map;
        if (!t.texels) sphbasis::detail::throw_invalid(fn, "a normal map with texels, got null");
        sphbasis::detail::check_range(fn, "width", t.width, 1, 16384);
        sphbasis::detail::check_range(fn, "height", t.height, 1, 16384);
        if (t.channels != 3 && t.channels != 4)
            sphbasis::detail::throw_invalid(fn,
                                            "3 or 4 channels, got " + std::to_string(t.channels));
        Level l0;
        l0.width = t.width;
        l0.height = t.height;
        const std::size_t n = std::size_t(t.width) * std::size_t(t.height);
        const std::size_t ch = std::size_t(t.channels);
        l0.n.resize(3 * n);
        for (std::size_t i = 0; i < n; ++i)
            for (std::size_t k = 0; k < 3; ++k) {
                const float c = t.texels[i * ch + k];
                if (!std::isfinite(c))
                    sphbasis::detail::throw_invalid(
                        fn,
                        "finite texels, got a NaN or an infinity at texel " + std::to_string(i));
                l0.n[3 * i + k] = 2 * c - 1;
            }
        levels_.push_back(std::move(l0));
        while (levels_.back().width > 1 || levels_.back().height > 1)
            levels_.push_back(downsample(levels_.back()));
    }
    int levels() const noexcept { return static_cast<int>(levels_.size()); }
    int level_width(int level) const noexcept { return levels_[clamp_level(level)].width; }
    int level_height(int level) const noexcept { return levels_[clamp_level(level)].height; }
    /// Texel (x, y) of a level (coordinates wrap, the level is clamped to [0, levels() - 1]).
    vec3<double> texel(int level, long x, long y) const noexcept {
        const Level& l = levels_[clamp_level(level)];
        const std::size_t i = 3 * (wrap(y, l.height) * std::size_t(l.width) + wrap(x, l.width));
        return {l.n[i], l.n[i + 1], l.n[i + 2]};
    }
    /// The averaged tangent-space normal at uv, level `lod` >= 0 (fractional: trilinear).
    /// lod is clamped to [0, levels() - 1] (NaN reads level 0); bilinear within a level,
    /// wrapping. A non-finite u or v gives (0, 0, 1).
    vec3<double> average(double u, double v, double lod) const noexcept {
        if (!std::isfinite(u) || !std::isfinite(v)) return {0, 0, 1};
        const double top = static_cast<double>(levels_.size() - 1);
        const double lo = lod > 0 ? (lod < top ? lod : top) : 0.0;
        const int k = static_cast<int>(std::floor(lo));
        const double f = lo - k;
        const vec3<double> a = bilinear(k, u, v);
        if (f == 0) return a;
        const vec3<double> b = bilinear(k + 1, u, v);
        return {a.x + f * (b.x - a.x), a.y + f * (b.y - a.y), a.z + f * (b.z - a.z)};
    }
    /// Bilinear lookup of one level (wrapping); the level is clamped.
    vec3<double> bilinear(int level, double u, double v) const noexcept {
        const Level& l = levels_[clamp_level(level)];
        const double x = (u - std::floor(u)) * l.width - 0.5;
        const double y = ((1 - v) - std::floor(1 - v)) * l.height - 0.5;
        const double fx = std::floor(x), fy = std::floor(y);
        const double ax = x - fx, ay = y - fy;
        const long ix = static_cast<long>(fx), iy = static_cast<long>(fy);
        const vec3<double> t00 = texel(level, ix, iy), t10 = texel(level, ix + 1, iy);
        const vec3<double> t01 = texel(level, ix, iy + 1), t11 = texel(level, ix + 1, iy + 1);
        auto mix = [&](double c00, double c10, double c01, double c11) {
            return (1 - ay) * ((1 - ax) * c00 + ax * c10) + ay * ((1 - ax) * c01 + ax * c11);
        };
        return {mix(t00.x, t10.x, t01.x, t11.x), mix(t00.y, t10.y, t01.y, t11.y),
                mix(t00.z, t10.z, t01.z, t11.z)};
    }
    /// Bytes held by the chain's texels.
    std::size_t bytes() const noexcept {
        std::size_t b = 0;
        for (const auto& l : levels_) b += l.n.size() * sizeof(float);
        return b;
    }

  private:
    struct Level {
        int width = 0, height = 0;
        std::vector<float> n;  // 3 per texel, row-major from the top row
    };
    std::size_t clamp_level(int level) const noexcept {
        const int top = static_cast<int>(levels_.size()) - 1;
        return static_cast<std::size_t>(level < 0 ? 0 : (level > top ? top : level));
    }
    static std::size_t wrap(long i, int n) noexcept {
        return static_cast<std::size_t>(((i % n) + n) % n);
    }
    /// The 1D box weights of a size-n axis reduced to m texels: per target texel, the source
    /// texels its footprint [i n/m, (i + 1) n/m) overlaps, weighted by overlap / (n/m).
    struct Tap {
        std::size_t src;
        double w;
    };
    static std::vector<std::vector<Tap>> taps(int n, int m) {
        std::vector<std::vector<Tap>> out(static_cast<std::size_t>(m));
        const double r = static_cast<double>(n) / m;
        for (int i = 0; i < m; ++i) {
            const double a = i * r, b = (i + 1) * r;
            for (int s = static_cast<int>(std::floor(a)); s < n && s < b; ++s) {
                const double w = (std::min(b, s + 1.0) - std::max(a, double(s))) / r;
                if (w > 0) out[std::size_t(i)].push_back({std::size_t(s), w});
            }
        }
        return out;
    }
    static Level downsample(const Level& src) {
        Level dst;
        dst.width = std::max(1, src.width / 2);
        dst.height = std::max(1, src.height / 2);
        const auto tx = taps(src.width, dst.width), ty = taps(src.height, dst.height);
        dst.n.resize(std::size_t(dst.width) * std::size_t(dst.height) * 3);
        const std::size_t sw = std::size_t(src.width);
        for (std::size_t y = 0; y < std::size_t(dst.height); ++y)
            for (std::size_t x = 0; x < std::size_t(dst.width); ++x) {
                double acc[3] = {0, 0, 0};
                for (const Tap& b : ty[y])
                    for (const Tap& a : tx[x]) {
                        const float* s = &src.n[3 * (b.src * sw + a.src)];
                        const double w = a.w * b.w;
                        for (int k = 0; k < 3; ++k) acc[k] += w * s[k];
                    }
                float* d = &dst.n[3 * (y * std::size_t(dst.width) + x)];
                for (int k = 0; k < 3; ++k) d[k] = static_cast<float>(acc[k]);
            }
        return dst;
    }
    std::vector<Level> levels_;
};

/// The world-space width of a pixel's footprint at a hit of the camera ray with unit direction
/// `dir`: the side of the square with the footprint's area, t a c^(3/2) / sqrt(|cos_s|), where
/// a = camera.pixel_angle(), c = dir . forward (a pixel off the axis subtends a solid angle
/// a^2 c^3), t the hit distance and cos_s = dir . geometric normal (floored at 1e-3: grazing
/// hits read the coarsest levels anyway). 0 for an invalid hit.
inline double pixel_footprint(const PinholeCamera& camera, const vec3<double>& dir,
                              const Hit& hit) noexcept {
    if (!hit.valid) return 0;
    const double c = std::fabs(dot(dir, camera.forward()));
    const double cs = std::max(std::fabs(dot(dir, hit.geometric_normal)), 1e-3);
    return hit.t * camera.pixel_angle() * c * std::sqrt(c) / std::sqrt(cs);
}

class SpecularShading {
  public:
    enum class Mode { aliased, toksvig, reference };
    /// Builds the mip chains of every mesh with a normal map; keeps the directional lights.
    /// Meshes with shininess 0 get no chain (they contribute 0). Throws std::invalid_argument
    /// for an invalid light (render::validate), a shininess that is negative or not finite, a
    /// specular reflectance outside [0, 1], a normal map that NormalMipChain rejects or without
    /// UVs, null position, index or UV arrays, or indices out of range.
    explicit SpecularShading(const SceneDesc& scene) {
        constexpr const char* fn = "render::SpecularShading";
        for (const Light& l : scene.lights) {
            validate(l);
            if (l.type != Light::Type::directional) continue;
            lights_.push_back({detail::rt::normalized(l.direction), l.color});
        }
        meshes_.resize(scene.meshes.size());
        for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
            const MeshView& v = scene.meshes[m];
            MeshData& d = meshes_[m];
            if (!(v.shininess >= 0 && std::isfinite(v.shininess)))
                sphbasis::detail::throw_invalid(fn, "a finite shininess >= 0, got " +
                                                        std::to_string(v.shininess) + " (mesh " +
                                                        std::to_string(m) + ")");
            for (float k : v.specular)
                if (!(k >= 0 && k <= 1))
                    sphbasis::detail::throw_invalid(fn, "specular in [0, 1], got " +
                                                            std::to_string(k) + " (mesh " +
                                                            std::to_string(m) + ")");
            const TextureView& nm = v.normal_map;
            const bool has_map = nm.texels || nm.width || nm.height;
            if (!has_map || !(v.shininess > 0)) continue;
            if (!v.uvs)
                sphbasis::detail::throw_invalid(
                    fn, "UVs with a normal map, got none (mesh " + std::to_string(m) + ")");
            sphbasis::detail::check_buffer(fn, "positions", v.positions, v.vertex_count);
            sphbasis::detail::check_buffer(fn, "indices", v.indices, v.triangle_count);
            d.chain = std::make_shared<NormalMipChain>(nm);
            d.uv_scale.resize(v.triangle_count);
            const std::size_t nv = v.vertex_count;
            for (std::size_t f = 0; f < v.triangle_count; ++f) {
                const std::uint32_t* t = &v.indices[3 * f];
                if (t[0] >= nv || t[1] >= nv || t[2] >= nv)
                    sphbasis::detail::throw_invalid(
                        fn, "indices < vertex_count = " + std::to_string(nv) + " (mesh " +
                                std::to_string(m) + ", triangle " + std::to_string(f) + ")");
                d.uv_scale[f] = uv_per_world(v, t);
            }
            ++chains_;
        }
    }
    /// Specular radiance toward `view` (unit, hit to eye) at a hit; footprint = the pixel's
    /// world-space width at the hit (pixel_footprint()). reference mode reads level 0 and
    /// ignores the footprint. Only lights above the geometric surface (ng.l > 0) and above the
    /// shading normal (n.l > 0) contribute. Throws std::invalid_argument for a non-finite view,
    /// a footprint that is negative or not finite, or a hit of a mesh the scene does not have.
    RGB shade(Mode mode, const Hit& hit, const vec3<double>& view, double footprint) const {
        using namespace detail::rt;
        constexpr const char* fn = "render::SpecularShading::shade";
        if (!finite(view))
            sphbasis::detail::throw_invalid(fn, "a finite view direction, got a NaN or infinity");
        if (!(footprint >= 0 && footprint <= std::numeric_limits<double>::max()))
            sphbasis::detail::throw_invalid(
                fn, "a finite footprint >= 0, got " + std::to_string(footprint));
        RGB out{0, 0, 0};
        if (!hit.valid || !(hit.shininess > 0) || lights_.empty()) return out;
        if (hit.mesh >= meshes_.size())
            sphbasis::detail::throw_invalid(
                fn, "a hit of one of the scene's " + std::to_string(meshes_.size()) +
                        " meshes, got mesh " + std::to_string(hit.mesh));
        const MeshData& d = meshes_[hit.mesh];
        const double s = hit.shininess;
        // The averaged normal Na in world space (|Na| <= 1) and its direction n.
        V3 na = hit.shading_normal;
        if (d.chain && hit.has_uv) {
            const double lod = mode == Mode::reference ? 0.0 : level_of_detail(hit, footprint);
            const V3 t = d.chain->average(hit.uv[0], hit.uv[1], lod);
            const V3 n = hit.shading_normal, tg = hit.tangent;
            const V3 bt = cross(n, tg) * hit.bitangent_sign;
            na = tg * t.x + bt * t.y + n * t.z;
        }
        const double len = length(na);
        const V3 n = normalized(na, hit.shading_normal);
        for (const DirLight& l : lights_) {
            if (!(dot(hit.geometric_normal, l.direction) > 0)) continue;
            const double nl = dot(n, l.direction);
            if (!(nl > 0)) continue;
            const V3 hv = l.direction + view;
            const double hl = length(hv);
            if (!(hl > 0)) continue;
            const V3 h = hv * (1 / hl);
            double lobe;
            if (mode == Mode::toksvig)
                lobe = blinn_phong_normalization(s) *
                       toksvig::specular(dot(na, h), std::min(len, 1.0), s);
            else
                lobe = blinn_phong_lobe(dot(n, h), s);
            for (std::size_t k = 0; k < 3; ++k) out[k] += hit.specular[k] * lobe * nl * l.color[k];
        }
        return out;
    }
    /// The mip level a footprint reads at a hit: log2(footprint x UV-per-world of the hit's
    /// triangle x max(width, height) of level 0), clamped to [0, levels - 1]; 0 without a chain.
    double level_of_detail(const Hit& hit, double footprint) const noexcept {
        if (hit.mesh >= meshes_.size()) return 0;
        const MeshData& d = meshes_[hit.mesh];
        if (!d.chain || hit.primitive >= d.uv_scale.size()) return 0;
        const double texels = footprint * d.uv_scale[hit.primitive] *
                              std::max(d.chain->level_width(0), d.chain->level_height(0));
        if (!(texels > 1)) return 0;
        const double lod = std::log2(texels), top = d.chain->levels() - 1;
        return lod < top ? lod : top;
    }
    /// The mip chain of mesh m (null without a normal map or with shininess 0).
    const NormalMipChain* chain(std::size_t m) const noexcept {
        return m < meshes_.size() ? meshes_[m].chain.get() : nullptr;
    }
    /// How many mip chains were built (meshes with a normal map and shininess > 0).
    std::size_t mip_chains() const noexcept { return chains_; }
    /// The directional lights kept.
    std::size_t light_count() const noexcept { return lights_.size(); }

  private:
    struct DirLight {
        vec3<double> direction;
        RGB color;
    };
    struct MeshData {
        std::shared_ptr<const NormalMipChain> chain;
        std::vector<double> uv_scale;  // per triangle: UV length per world length
    };
    /// sqrt(UV area / world area) of a triangle (0 when either is degenerate).
    static double uv_per_world(const MeshView& v, const std::uint32_t* t) noexcept {
        using namespace detail::rt;
        auto p = [&](std::uint32_t i) {
            return V3{v.positions[3 * std::size_t(i)], v.positions[3 * std::size_t(i) + 1],
                      v.positions[3 * std::size_t(i) + 2]};
        };
        const double world = length(cross(p(t[1]) - p(t[0]), p(t[2]) - p(t[0])));
        const float* a = &v.uvs[2 * std::size_t(t[0])];
        const float* b = &v.uvs[2 * std::size_t(t[1])];
        const float* c = &v.uvs[2 * std::size_t(t[2])];
        const double uv = std::fabs(double(b[0] - a[0]) * double(c[1] - a[1]) -
                                    double(c[0] - a[0]) * double(b[1] - a[1]));
        const double r = world > 0 ? std::sqrt(uv / world) : 0.0;
        return std::isfinite(r) ? r : 0.0;
    }
    std::vector<DirLight> lights_;
    std::vector<MeshData> meshes_;
    std::size_t chains_ = 0;
};

namespace detail {
/// The specular image in `mode` from render::ImageLoop: spp samples per pixel (the pixel
/// centre when spp = 1), each shaded with the whole pixel's footprint (pixel_footprint()),
/// averaged (a box filter).
inline Image render_specular_image(const SceneDesc& scene, const Scene& rt, const Camera& camera,
                                   SpecularShading::Mode mode, int spp, std::uint64_t seed) {
    ImageLoopSettings ls;
    ls.seed = seed;
    ls.spp = spp;
    ls.hits = true;
    ImageLoop loop(rt, camera, ls);
    const SpecularShading shading(scene);
    if (rt.mesh_count() != scene.meshes.size())
        sphbasis::detail::throw_invalid("render::render_specular",
                                        "a ray-tracing scene of the description's " +
                                            std::to_string(scene.meshes.size()) + " meshes, got " +
                                            std::to_string(rt.mesh_count()));
    Film film(camera.width, camera.height, false);
    loop.run(0, spp, {&film}, [&](const CameraBatch& b, std::size_t, RGB* out) {
        for (std::size_t k = 0; k < b.n; ++k) {
            const Hit& h = b.hits[k];
            const vec3<double>& d = b.directions[k];
            out[k] = h.valid ? shading.shade(mode, h, {-d.x, -d.y, -d.z},
                                             pixel_footprint(loop.pinhole(), d, h))
                             : RGB{0, 0, 0};
        }
    });
    return film.mean();
}
}  // namespace detail

/// The specular image of a mode (aliased or toksvig: the mip level of the pixel's footprint;
/// reference: level 0) from render::ImageLoop with `spp` samples per pixel (1: the pixel
/// centre; more: the loop's positions for `seed`, the same as every other image of that seed
/// and count), each reading the whole pixel's footprint (what a renderer reads at this
/// resolution), averaged. Throws std::invalid_argument for an invalid camera, spp outside
/// [1, 4096], a scene SpecularShading rejects, or `rt` not built from `scene` (different mesh
/// count).
inline Image render_specular(const SceneDesc& scene, const Scene& rt, const Camera& camera,
                             SpecularShading::Mode mode, int spp = 1, std::uint64_t seed = 0) {
    sphbasis::detail::check_range("render::render_specular", "spp", spp, 1, 4096);
    return detail::render_specular_image(scene, rt, camera, mode, spp, seed);
}

/// The supersampled reference of the specular comparison (header comment): ss x ss camera
/// rays per pixel at render::ImageLoop's positions for `seed` (the pixel centre when ss = 1),
/// each shaded with the finest level normalised (Mode::reference), averaged with equal weights
/// (a box pixel filter). Deterministic whatever the thread count. A specular representation
/// compared with it is rendered with the same ss x ss samples and seed (render_specular(...,
/// ss * ss, seed)). Throws std::invalid_argument unless 1 <= ss <= 64, and as
/// render_specular(). Cost: width x height x ss^2 rays, in tiles of 16 x 16 pixels on oneTBB.
inline Image render_specular_reference(const SceneDesc& scene, const Scene& rt,
                                       const Camera& camera, int ss, std::uint64_t seed = 0) {
    sphbasis::detail::check_range("render::render_specular_reference", "ss", ss, 1, 64);
    return detail::render_specular_image(scene, rt, camera, SpecularShading::Mode::reference,
                                         ss * ss, seed);
}

}  // namespace sphbasis::render
