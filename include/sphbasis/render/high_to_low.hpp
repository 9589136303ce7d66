// sphbasis render tier: high- to low-poly bakes: the detail of a high-poly `source` mesh baked
// into the vertices or the lightmap of a low-poly `target` mesh (Hill, "Hardware Accelerating
// Art Production", Gamasutra 2004, "Texture Baking II": the normal map and the occlusion of the
// high-poly model sampled per texel of the low-poly one; the ray-casting transfer of attributes
// between the two surfaces follows Cignoni, Montani, Rocchini and Scopigno, "A general method
// for preserving attribute values on simplified meshes", IEEE Visualization 1998). The options
// are those of the artists' tools (Blender Cycles' "Selected to Active" bake: a cage or a
// maximum ray distance).
//
// Projection. Every bake point of the target (render/bake_points.hpp: vertices, or texel samples
// on the surface, before the lightmap's normal offset) looks for the source along a ray:
//   * without a cage: along the line p + t n of its interpolated unit normal n, |t| <=
//     max_ray_distance (infinite: unbounded), both ways; the hit nearest to p wins (the outward
//     one on a tie). A source that lies partly above and partly below the target (bumps and
//     pits of a height field) is found either way, as Blender's "max ray distance" and xNormal's
//     front and rear distances do;
//   * with a cage (a mesh of the target's vertex count and triangles, usually the target pushed
//     outwards): from the cage point (the same vertex, or the same barycentric point of the same
//     triangle) towards the target point and beyond, at most max_ray_distance from the cage; the
//     first hit wins (where the cage point is the target point, the rule without a cage).
// A point whose ray misses the source is not covered: it is baked at the target point itself
// (so that every texel and vertex holds a value) and its tangent-space normal is (0, 0, 1).
//
// The point baked is the hit on the source: its position, and its interpolated shading normal
// turned to the side of n (a hit on the source's back face, from a ray going outwards, would
// otherwise face into the model; a normal map cannot hold a normal below the low-poly surface
// anyway). Its id is the target point's id, so results stay a pure function of (seed, id).
//
// Tangent-space normal map (the basis). The source normal n_h is written in the target point's
// tangent frame (T, B, n): T the tangent of render/bake_points.hpp's rule (the mesh's
// interpolated tangents, else the triangle's dp/du, Gram-Schmidt against n; else
// coordinate_system(n) of core/frame.hpp) and B = bitangent_sign n x T, so
// normal = (n_h.T, n_h.B, n_h.n), a unit vector. This is exactly the frame render::Scene gives a
// hit on the target (Scene::normal_mapped() decodes a map in it), per pixel and without a
// MikkTSpace-style per-vertex tangent rule: a map baked here and stored as c = (normal + 1) / 2
// reproduces n_h when the renderer applies it to the target (tests/render/test_high_to_low.cpp).
//
// Occlusion. The target stands in for the source and must not shadow it: a high-to-low bake
// traces its occlusion and transfer rays in the scene without the targets
// (high_to_low_occluders(): every target's mesh left empty), so the rays from the hit on the
// source see the whole scene, the source included, but no low-poly mesh. The same scene serves
// every point of the bake (the other meshes are occluded by the source, not its stand-in).
//
// Cost: one source scene build (Embree) per target, then one ray per point with a cage, two
// without (three times that where the ray misses: two retries against cracks); in parallel on
// oneTBB, results independent of the thread count.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../core/vec.hpp"
#include "bake.hpp"
#include "bake_points.hpp"
#include "detail/rt_math.hpp"
#include "lightmap.hpp"
#include "mesh.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// How a target finds its source (header comment).
struct HighToLowSettings {
    std::size_t target = 0, source = 0;  // mesh indices in the scene, different
    /// Rays search this far (both ways without a cage, from the cage with one); > 0, may be
    /// infinite.
    double max_ray_distance = std::numeric_limits<double>::infinity();
    /// Optional cage: positions (null: none) of target.vertex_count vertices; the target's
    /// triangles are used. Borrowed until the points are made.
    const float* cage_positions = nullptr;
};

/// A target point to project: the bake point (on the surface for vertices; texels: with the
/// lightmap's offset, baked where the ray misses), the surface point the ray starts from and
/// its cage point (when a cage is given).
struct LowPolyPoint {
    BakePoint point;
    vec3<double> surface{0, 0, 0}, cage{0, 0, 0};
    bool has_cage = false;
};

/// One projected point: the point to bake, whether the ray hit the source (coverage), the
/// source normal in the target's tangent frame ((0, 0, 1) on a miss) and the signed distance
/// from the target surface to the hit along n (positive outwards; 0 on a miss).
struct ProjectedPoint {
    BakePoint point;
    bool hit = false;
    vec3<double> normal{0, 0, 1};
    double height = 0;
};

namespace high_to_low_detail {

inline void check(const std::vector<MeshView>& meshes, const HighToLowSettings& s) {
    const char* fn = "render::high_to_low";
    const std::size_t n = meshes.size();
    if (s.target >= n || s.source >= n || s.target == s.source)
        sphbasis::detail::throw_invalid(fn, "a target and a source that are different meshes < " +
                                                std::to_string(n) + ", got target " +
                                                std::to_string(s.target) + " and source " +
                                                std::to_string(s.source));
    if (!(s.max_ray_distance > 0))
        sphbasis::detail::throw_invalid(fn, "max_ray_distance > 0 (infinite: unbounded), got " +
                                                std::to_string(s.max_ray_distance));
    if (s.cage_positions != nullptr) {
        const MeshView& t = meshes[s.target];
        for (std::size_t i = 0; i < 3 * t.vertex_count; ++i)
            if (!std::isfinite(s.cage_positions[i]))
                sphbasis::detail::throw_invalid(
                    fn, "finite cage positions, got a NaN or an infinity at vertex " +
                            std::to_string(i / 3));
    }
}

inline vec3<double> cage_at(const HighToLowSettings& s, const MeshView& t, std::uint32_t tri,
                            const std::array<double, 3>& b) noexcept {
    using namespace detail::rt;
    const std::uint32_t* v = t.indices + 3 * std::size_t(tri);
    return lightmap_detail::load3(s.cage_positions, v[0]) * b[0] +
           lightmap_detail::load3(s.cage_positions, v[1]) * b[1] +
           lightmap_detail::load3(s.cage_positions, v[2]) * b[2];
}

/// The unit tangent of the target frame at a point: its own, else coordinate_system(n).
inline vec3<double> frame_tangent(const BakePoint& p, const vec3<double>& n) noexcept {
    using namespace detail::rt;
    if (dot(p.tangent, p.tangent) > 0) return p.tangent;
    return Frame<double>(n).s;
}

}  // namespace high_to_low_detail

/// The target's vertex points (render::vertex_points) with their cage points. Throws
/// std::invalid_argument for bad indices or settings.
inline std::vector<LowPolyPoint> low_poly_vertex_points(const std::vector<MeshView>& meshes,
                                                        const HighToLowSettings& s) {
    high_to_low_detail::check(meshes, s);
    const std::vector<BakePoint> pts = vertex_points(meshes, s.target);
    std::vector<LowPolyPoint> out(pts.size());
    for (std::size_t v = 0; v < pts.size(); ++v) {
        out[v].point = pts[v];
        out[v].surface = pts[v].p;
        if (s.cage_positions != nullptr) {
            out[v].cage = lightmap_detail::load3(s.cage_positions, v);
            out[v].has_cage = true;
        }
    }
    return out;
}

/// The target's texel points of a layout (render::texel_layout of the target) with their
/// surface and cage points. Throws std::invalid_argument for bad indices or settings.
inline std::vector<LowPolyPoint> low_poly_texel_points(const std::vector<MeshView>& meshes,
                                                       const HighToLowSettings& s,
                                                       const LightmapLayout& layout) {
    high_to_low_detail::check(meshes, s);
    const MeshView& t = meshes[s.target];
    std::vector<LowPolyPoint> out(layout.samples.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        const LightmapSample& smp = layout.samples[i];
        out[i].point = smp.point;
        out[i].surface = smp.surface;
        if (s.cage_positions != nullptr && smp.triangle < t.triangle_count) {
            out[i].cage = high_to_low_detail::cage_at(s, t, smp.triangle, smp.barycentric);
            out[i].has_cage = true;
        }
    }
    return out;
}

/// Casts the target points' rays to the source (header comment). Builds the source's Embree
/// scene once; one project() at a time (it counts its rays and seconds). Cost per point: one
/// ray with a cage, two without; a miss is retried twice.
class SourceProjector {
  public:
    SourceProjector(const std::vector<MeshView>& meshes, const HighToLowSettings& s)
        : settings_((high_to_low_detail::check(meshes, s), s)), source_({meshes[s.source]}) {}

    /// The projected points, in the order of `pts`. Cost: one or two rays per point.
    std::vector<ProjectedPoint> project(const std::vector<LowPolyPoint>& pts) {
        const auto t0 = std::chrono::steady_clock::now();
        std::vector<ProjectedPoint> out(pts.size());
        std::atomic<std::uint64_t> rays{0};
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pts.size(), 16),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              std::uint64_t k = 0;
                              for (std::size_t i = r.begin(); i != r.end(); ++i)
                                  out[i] = project_one(pts[i], k);
                              rays += k;
                          });
        rays_ += rays.load();
        seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        return out;
    }
    /// Rays traced and wall seconds spent by project() so far.
    std::uint64_t rays() const noexcept { return rays_; }
    double seconds() const noexcept { return seconds_; }

  private:
    ProjectedPoint project_one(const LowPolyPoint& lp, std::uint64_t& rays) const {
        using namespace detail::rt;
        ProjectedPoint out;
        out.point = lp.point;
        const V3 n = normalized(lp.point.n);
        const V3 t = high_to_low_detail::frame_tangent(lp.point, n);
        const V3 b = cross(n, t) * (lp.point.bitangent_sign < 0 ? -1.0 : 1.0);
        // A ray exactly along an edge the source's triangles share can slip through the crack
        // between them (Embree's default intersector is not watertight): a miss is retried
        // twice from origins moved by epsilon() in the tangent plane.
        Hit h;
        double height = 0;
        for (int attempt = 0; attempt < 3 && !h.valid; ++attempt)
            h = cast(lp, n, (t + b * 0.6180339887498949) * (source_.epsilon() * attempt), height,
                     rays);
        if (!h.valid) return out;
        V3 nh = h.shading_normal;
        if (dot(h.geometric_normal, n) < 0) nh = -nh;
        out.hit = true;
        out.height = height;
        out.point.p = h.position;
        out.point.n = nh;
        out.point.tangent = bake_points_detail::orthonormal_tangent(lp.point.tangent, nh);
        if (dot(out.point.tangent, out.point.tangent) == 0) out.point.bitangent_sign = 1;
        out.normal = normalized(V3{dot(nh, t), dot(nh, b), dot(nh, n)});
        return out;
    }

    /// One try of the header's rule from origins moved by `shift`; height: the signed distance
    /// from the surface point to the hit along n.
    Hit cast(const LowPolyPoint& lp, const detail::rt::V3& n, const detail::rt::V3& shift,
             double& height, std::uint64_t& rays) const {
        using namespace detail::rt;
        const double D = settings_.max_ray_distance;
        const double inf = std::numeric_limits<double>::infinity();
        const V3 to_surface = lp.surface - lp.cage;
        const double cd = length(to_surface);
        if (lp.has_cage && cd > 0 && std::isfinite(cd)) {
            Hit h = source_.intersect(lp.cage + shift, to_surface * (1 / cd), D);
            ++rays;
            if (h.valid) height = dot(h.position - lp.surface, n);
            return h;
        }
        // Both ways, each ray starting epsilon behind the point so that a source through the
        // point itself is seen by both; the hit nearest to the point wins, outwards on a tie.
        const double e = source_.epsilon();
        const V3 o = lp.surface + shift;
        const Hit up = source_.intersect(o - n * e, n, D + e);
        const Hit down = source_.intersect(o + n * e, -n, D + e);
        rays += 2;
        const double du = up.valid ? up.t - e : inf, dd = down.valid ? down.t - e : inf;
        if (up.valid && std::fabs(du) <= std::fabs(dd)) {
            height = du;
            return up;
        }
        height = -dd;
        return down;
    }

    HighToLowSettings settings_;
    Scene source_;
    std::uint64_t rays_ = 0;
    double seconds_ = 0;
};

/// The scene a high-to-low bake traces its occlusion in: `scene` with each target's mesh left
/// empty (no triangles; indices and ids of the other meshes unchanged). Borrows scene's arrays.
inline SceneDesc high_to_low_occluders(const SceneDesc& scene,
                                       const std::vector<std::size_t>& targets) {
    SceneDesc d = scene;
    for (std::size_t t : targets)
        if (t < d.meshes.size()) {
            MeshView empty;
            empty.albedo = d.meshes[t].albedo;
            d.meshes[t] = empty;
        }
    return d;
}

/// The bake points of projected points, in order.
inline std::vector<BakePoint> bake_points_of(const std::vector<ProjectedPoint>& pts) {
    std::vector<BakePoint> out;
    out.reserve(pts.size());
    for (const ProjectedPoint& p : pts) out.push_back(p.point);
    return out;
}

}  // namespace sphbasis::render
