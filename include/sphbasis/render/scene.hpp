// sphbasis render tier: a ray-tracing scene built from mesh arrays (an RAII wrapper of Embree 3).
//
// render::Scene copies the positions and indices of a list of MeshView into Embree triangle
// geometries (one geometry per mesh, geometry ID = mesh index) and keeps its own copies of the
// normals and UVs it needs for hit records (and each triangle's unit normal in double, 24 bytes
// a triangle, so a hit record does not recompute it), so the MeshView arrays may be freed after
// construction (the albedo_map texels stay borrowed). Queries are batched: occluded() and
// intersect() take arrays of Embree rays and trace them as ray streams (rtcOccluded1M,
// rtcIntersect1M); hit() turns an Embree hit into a Hit record.
//
// Validation (std::invalid_argument, "sphbasis::render::Scene(): expected ..."): null position
// or index arrays with a non-zero count, non-finite positions, normals or UVs, indices out of
// range, albedo outside [0, 1], an albedo map with a null buffer, a bad size or a channel count
// other than 1, 3 or 4. Degenerate triangles (repeated indices, or twice the area below 1e-12
// times the longest squared edge) are skipped, not an error: Embree would never report a hit on
// them and no normal is defined; degenerate_triangles() counts them.
//
// Self-intersection: a ray leaving a surface starts at offset_origin(p, ng, d), p moved along the
// geometric normal (to the side d leaves through) by epsilon() = 1e-5 * extent + 2^-14 * max|c|,
// extent the diagonal of the scene's bounding box and max|c| its largest coordinate magnitude:
// the first term covers the BVH's and the hit point's relative error, the second the absolute
// float rounding of coordinates far from the origin (2^-14 is ~500 float ulps of max|c|). The
// offset shifts a surface point by a relative 1e-5 of the scene, far below the bake's errors.
//
// can_occlude(): false only when the scene cannot occlude any point on its own surface from the
// directions above that point's tangent plane. Detected: no triangles at all, or exactly one mesh
// with triangles that is closed (every edge, after welding vertices at equal positions, shared by
// exactly two triangles traversing it in opposite directions), connected, and convex (at every
// edge the far vertex of one triangle lies on the inner side of the other's plane, within 1e-7
// times the extent; all dihedrals convex for one orientation). A connected closed surface that
// is convex at every edge bounds a convex body. Cost: O(triangles) hash-map work, once.
// unoccluded(p, n) then confirms a given point: every vertex lies on or below p's tangent plane
// (within 0.02 of its distance, about 1.1 degrees: occlusion within that band of the horizon
// weighs under 4e-4 of the cosine-weighted hemisphere), O(vertices) per point.
#pragma once

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../core/vec.hpp"
#include "detail/rt_math.hpp"
#include "lighting.hpp"
#include "mesh.hpp"

namespace sphbasis::render {

/// The largest magnitude of a vertex coordinate (Scene) or a bake point's coordinate
/// (Baker::bake): Embree builds its bounds in float and squares extents, and aborts on an
/// assertion from about 1.8e18; 1e15 keeps every such product far from overflow.
inline constexpr double coordinate_limit = 1e15;

/// A scene as the library takes it: meshes as arrays (borrowed: they must outlive every user of
/// the description), the distant environment and the analytic lights (render/lighting.hpp).
/// render::Scene is built from `meshes`; render::Baker and the renderers read the lighting.
struct SceneDesc {
    std::vector<MeshView> meshes;
    Environment environment;
    std::vector<Light> lights;
};

/// What a ray hit. Barycentrics: position = (1 - u - v) p0 + u p1 + v p2 of the mesh's
/// triangle `primitive` (index into the mesh's own triangle list, degenerate ones included).
/// The fields a renderer reads at every path vertex come first (two cache lines).
struct Hit {
    bool valid = false;
    /// The ray arrived at the back: the side opposite the counter-clockwise normal
    /// (p1 - p0) x (p2 - p0).
    bool back_face = false;
    /// Interpolated UV (has_uv: the mesh has UVs; otherwise {0, 0}).
    bool has_uv = false;
    std::uint32_t mesh = 0, primitive = 0;
    vec3<double> position{0, 0, 0};
    /// Unit geometric normal, flipped to face the ray (dot(geometric_normal, d) <= 0).
    vec3<double> geometric_normal{0, 0, 1};
    /// Unit interpolated shading normal (geometric without normals), on the geometric normal's
    /// side (dot(shading_normal, geometric_normal) >= 0): meshes are two-sided and shaded from
    /// the side the ray arrives on, whatever the winding of the triangle or the side its vertex
    /// normals point to.
    vec3<double> shading_normal{0, 0, 1};
    /// Mesh albedo times the albedo map at the interpolated UV (bilinear, wrapping), per channel.
    std::array<double, 3> albedo{0, 0, 0};
    /// The mesh's material (mesh.hpp): normal map (null: none), Blinn-Phong exponent (0: none)
    /// and specular reflectance.
    const TextureView* normal_map = nullptr;
    double shininess = 0;
    std::array<double, 3> specular{0, 0, 0};
    double t = 0, u = 0, v = 0;
    /// The triangle's vertex indices in the mesh (for per-vertex data: weights 1 - u - v, u, v).
    std::array<std::uint32_t, 3> vertices{0, 0, 0};
    std::array<double, 2> uv{0, 0};
    /// Unit tangent orthogonal to shading_normal and the bitangent's handedness: bitangent =
    /// bitangent_sign * cross(shading_normal, tangent). From the mesh's tangents (interpolated),
    /// else from the triangle's UV derivative dp/du, else coordinate_system() (core/frame.hpp) of
    /// the normal. Where the normal is flipped to face the ray the tangent is kept, so the sign
    /// flips.
    vec3<double> tangent{1, 0, 0};
    double bitangent_sign = 1;
};

class Scene {
  public:
    /// Builds the Embree scene (validation and degenerate triangles: header comment).
    explicit Scene(const std::vector<MeshView>& meshes) {
        meshes_.resize(meshes.size());
        for (std::size_t m = 0; m < meshes.size(); ++m) copy_mesh(m, meshes[m]);
        bounds();
        device_ = rtcNewDevice(nullptr);
        if (!device_)
            sphbasis::detail::throw_runtime("render::Scene",
                                            "an Embree device, got rtcNewDevice() failing");
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
        for (std::size_t m = 0; m < meshes_.size(); ++m) attach(m);
        rtcCommitScene(scene_);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) {
            release();
            sphbasis::detail::throw_runtime("render::Scene",
                                            "an Embree scene, got an error building it");
        }
        analyse_convexity();
    }
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;
    Scene(Scene&& o) noexcept { swap(o); }
    Scene& operator=(Scene&& o) noexcept {
        if (this != &o) {
            release();
            swap(o);
        }
        return *this;
    }
    ~Scene() { release(); }

    /// The Embree scene (for callers tracing their own rays).
    RTCScene handle() const noexcept { return scene_; }
    std::size_t mesh_count() const noexcept { return meshes_.size(); }
    std::size_t triangle_count() const noexcept { return triangles_; }
    std::size_t degenerate_triangles() const noexcept { return degenerate_; }
    /// Diagonal of the bounding box (0 for an empty scene) and the largest |coordinate|.
    double extent() const noexcept { return extent_; }
    double max_coordinate() const noexcept { return max_abs_; }
    vec3<double> bounds_min() const noexcept { return lo_; }
    vec3<double> bounds_max() const noexcept { return hi_; }
    /// The self-intersection offset (header comment).
    double epsilon() const noexcept { return 1e-5 * extent_ + 0x1p-14 * max_abs_; }
    /// p moved by epsilon() along the geometric normal ng (unit) to the side direction d leaves.
    vec3<double> offset_origin(const vec3<double>& p, const vec3<double>& ng,
                               const vec3<double>& d) const noexcept {
        const double e = dot(ng, d) >= 0 ? epsilon() : -epsilon();
        return {p.x + e * ng.x, p.y + e * ng.y, p.z + e * ng.z};
    }
    /// The largest albedo channel over meshes (albedo maps counted at their maximum texel).
    double max_albedo() const noexcept { return max_albedo_; }
    /// Whether some albedo channel differs between meshes' channels (RGB transfer needed).
    bool albedo_chromatic() const noexcept { return chromatic_; }
    /// Mesh m's normal map (null: none) and Blinn-Phong exponent (0: none); m < mesh_count().
    const TextureView* mesh_normal_map(std::size_t m) const noexcept {
        return meshes_[m].normal_map.texels ? &meshes_[m].normal_map : nullptr;
    }
    double mesh_shininess(std::size_t m) const noexcept { return meshes_[m].shininess; }

    /// Whether the scene can occlude points on its own surface (header comment).
    bool can_occlude() const noexcept { return can_occlude_; }
    /// Why can_occlude() has its value, in one sentence.
    const std::string& occlusion_reason() const noexcept { return occlusion_reason_; }
    /// Whether nothing can occlude the hemisphere of unit normal n at p: !can_occlude() and
    /// every vertex on or below p's tangent plane (header comment). O(vertices).
    bool unoccluded(const vec3<double>& p, const vec3<double>& n) const noexcept {
        if (can_occlude_) return false;
        for (const auto& mesh : meshes_) {
            const std::size_t nv = mesh.positions.size() / 3;
            for (std::size_t i = 0; i < nv; ++i) {
                const vec3<double> d{mesh.positions[3 * i] - p.x, mesh.positions[3 * i + 1] - p.y,
                                     mesh.positions[3 * i + 2] - p.z};
                const double h = dot(n, d);
                if (h > 0.02 * std::sqrt(dot(d, d)) + epsilon()) return false;
            }
        }
        return true;
    }

    /// Fills an Embree ray (mask all ones, time 0).
    static void set_ray(RTCRay& r, const vec3<double>& o, const vec3<double>& d, double tnear = 0,
                        double tfar = std::numeric_limits<double>::infinity()) noexcept {
        r.org_x = static_cast<float>(o.x);
        r.org_y = static_cast<float>(o.y);
        r.org_z = static_cast<float>(o.z);
        r.dir_x = static_cast<float>(d.x);
        r.dir_y = static_cast<float>(d.y);
        r.dir_z = static_cast<float>(d.z);
        r.tnear = static_cast<float>(tnear);
        r.tfar = tfar > 3e38 ? std::numeric_limits<float>::infinity() : static_cast<float>(tfar);
        r.time = 0;
        r.mask = 0xFFFFFFFFu;
        r.id = 0;
        r.flags = 0;
    }
    static void set_ray(RTCRayHit& r, const vec3<double>& o, const vec3<double>& d,
                        double tnear = 0,
                        double tfar = std::numeric_limits<double>::infinity()) noexcept {
        set_ray(r.ray, o, d, tnear, tfar);
        r.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        r.hit.primID = RTC_INVALID_GEOMETRY_ID;
        r.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    /// Occlusion of n rays as one stream: an occluded ray's tfar becomes -inf.
    void occluded(RTCRay* rays, std::size_t n) const {
        trace_stream("render::Scene::occluded", rays, n,
                     [this](RTCIntersectContext* ctx, RTCRay* r, unsigned m) {
                         rtcOccluded1M(scene_, ctx, r, m, sizeof(RTCRay));
                     });
    }
    static bool is_occluded(const RTCRay& r) noexcept { return !(r.tfar >= 0); }
    /// Closest hits of n rays as one stream (hit.geomID stays RTC_INVALID_GEOMETRY_ID on a miss).
    void intersect(RTCRayHit* rays, std::size_t n) const {
        trace_stream("render::Scene::intersect", rays, n,
                     [this](RTCIntersectContext* ctx, RTCRayHit* r, unsigned m) {
                         rtcIntersect1M(scene_, ctx, r, m, sizeof(RTCRayHit));
                     });
    }
    /// One ray (convenience for tests and tools; the bake uses the streams).
    Hit intersect(const vec3<double>& o, const vec3<double>& d,
                  double tfar = std::numeric_limits<double>::infinity()) const {
        RTCRayHit r;
        set_ray(r, o, d, 0, tfar);
        intersect(&r, 1);
        return hit(r);
    }
    bool occluded(const vec3<double>& o, const vec3<double>& d,
                  double tfar = std::numeric_limits<double>::infinity()) const {
        RTCRay r;
        set_ray(r, o, d, 0, tfar);
        occluded(&r, 1);
        return is_occluded(r);
    }

    /// The hit record of a traced ray (valid = false on a miss).
    Hit hit(const RTCRayHit& r) const noexcept {
        Hit h;
        make_hit(r, true, h);
        return h;
    }
    /// hit() for a renderer that needs the tangent frame only for normal mapping: equal to
    /// hit(r) except that, on a mesh without a normal map, tangent and bitangent_sign keep
    /// their defaults ({1, 0, 0} and 1) and are not computed.
    Hit shading_hit(const RTCRayHit& r) const noexcept {
        Hit h;
        make_hit(r, false, h);
        return h;
    }
    /// shading_hit(r) written into `out` (a renderer's per-path record: no copy of the record).
    void shading_hit(const RTCRayHit& r, Hit& out) const noexcept { make_hit(r, false, out); }
    /// Prefetches the mesh data hit() will read for a traced ray, in two stages: stage 0 the
    /// triangle's entries (indices and original index), stage 1 its vertices' positions,
    /// normals and UVs (it reads the indices). A caller about to turn a batch of hits into
    /// records runs stage 0 over the batch, then stage 1, so the cache misses overlap.
    void prefetch_hit(const RTCRayHit& r, int stage) const noexcept {
        if (r.hit.geomID >= meshes_.size()) return;  // also RTC_INVALID_GEOMETRY_ID
        const MeshData& m = meshes_[r.hit.geomID];
        const std::size_t f = r.hit.primID;
        if (f >= m.prim.size()) return;
        if (stage == 0) {
            prefetch(&m.indices[3 * f]);
            prefetch(&m.prim[f]);
            prefetch(&m.face_normals[3 * f]);
            return;
        }
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t i = m.indices[3 * f + k];
            prefetch(&m.positions[3 * i]);
            if (!m.normals.empty()) prefetch(&m.normals[3 * i]);
            if (!m.uvs.empty()) prefetch(&m.uvs[2 * i]);
        }
    }

  private:
    /// A prefetch the optimiser keeps: GCC treats __builtin_prefetch as free of side effects,
    /// so a function that only prefetches is found pure and its calls are deleted (measured:
    /// no prefetch was left in PathTracer::shade); a volatile asm is a side effect.
    static void prefetch(const void* p) noexcept {
#if (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
        asm volatile("prefetcht0 %0" : : "m"(*static_cast<const char*>(p)));
#elif defined(__GNUC__) || defined(__clang__)
        __builtin_prefetch(p);
#else
        (void)p;
#endif
    }
    /// The hit record into h (every field written). frame: the tangent frame also without a
    /// normal map.
    void make_hit(const RTCRayHit& r, bool frame, Hit& h) const noexcept {
        h = Hit{};
        if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID || r.hit.geomID >= meshes_.size()) return;
        const MeshData& m = meshes_[r.hit.geomID];
        if (r.hit.primID >= m.prim.size()) return;
        const bool need_frame = frame || m.normal_map.texels;
        using namespace detail::rt;
        h.valid = true;
        h.mesh = r.hit.geomID;
        h.primitive = m.prim[r.hit.primID];
        h.t = r.ray.tfar;
        h.u = r.hit.u;
        h.v = r.hit.v;
        const std::uint32_t* tri = &m.indices[3 * std::size_t(r.hit.primID)];
        const double w0 = 1 - h.u - h.v, w1 = h.u, w2 = h.v;
        const V3 p0 = m.pos(tri[0]), p1 = m.pos(tri[1]), p2 = m.pos(tri[2]);
        h.position = p0 * w0 + p1 * w1 + p2 * w2;
        const V3 d{r.ray.dir_x, r.ray.dir_y, r.ray.dir_z};
        const double* fn = &m.face_normals[3 * std::size_t(r.hit.primID)];
        V3 ng{fn[0], fn[1], fn[2]};
        h.back_face = dot(ng, d) > 0;
        if (h.back_face) ng = -ng;
        h.geometric_normal = ng;
        // Two-sided: the shading normal goes to the side the ray arrived on with the geometric
        // one, by its own sign against ng rather than by the winding, so normals that disagree
        // with their triangle's winding (files with mixed winding) still face the ray.
        // `flipped`: the shading normal points against the mesh's (or, without normals, the
        // counter-clockwise) one, which the tangents' handedness refers to.
        bool flipped = h.back_face;
        if (!m.normals.empty()) {
            const V3 ns = m.nrm(tri[0]) * w0 + m.nrm(tri[1]) * w1 + m.nrm(tri[2]) * w2;
            flipped = dot(ns, ng) < 0;
            h.shading_normal = normalized(flipped ? -ns : ns, ng);
        } else {
            h.shading_normal = ng;
        }
        h.vertices = {tri[0], tri[1], tri[2]};
        h.albedo = {m.albedo[0], m.albedo[1], m.albedo[2]};
        h.shininess = m.shininess;
        h.specular = m.specular;
        h.normal_map = m.normal_map.texels ? &m.normal_map : nullptr;
        const std::size_t a = tri[0], b = tri[1], c = tri[2];
        V3 dpdu{0, 0, 0};
        if (!m.uvs.empty()) {
            h.has_uv = true;
            h.uv = {m.uvs[2 * a] * w0 + m.uvs[2 * b] * w1 + m.uvs[2 * c] * w2,
                    m.uvs[2 * a + 1] * w0 + m.uvs[2 * b + 1] * w1 + m.uvs[2 * c + 1] * w2};
            if (m.map.texels) {
                const auto t = texture(m.map, h.uv[0], h.uv[1]);
                for (int k = 0; k < 3; ++k) h.albedo[std::size_t(k)] *= t[std::size_t(k)];
            }
            if (!need_frame) return;
            if (m.tangents.empty()) {  // dp/du of the triangle from its UVs
                const double du1 = m.uvs[2 * b] - m.uvs[2 * a],
                             dv1 = m.uvs[2 * b + 1] - m.uvs[2 * a + 1];
                const double du2 = m.uvs[2 * c] - m.uvs[2 * a],
                             dv2 = m.uvs[2 * c + 1] - m.uvs[2 * a + 1];
                const double det = du1 * dv2 - du2 * dv1;
                if (det != 0 && std::isfinite(det)) {
                    dpdu = ((p1 - p0) * dv2 - (p2 - p0) * dv1) * (1 / det);
                    // The bitangent dp/dv decides the handedness.
                    const V3 dpdv = ((p2 - p0) * du1 - (p1 - p0) * du2) * (1 / det);
                    const V3 nc{fn[0], fn[1], fn[2]};
                    h.bitangent_sign = dot(cross(nc, dpdu), dpdv) < 0 ? -1 : 1;
                    flipped = dot(h.shading_normal, nc) < 0;  // the sign refers to nc
                }
            }
        }
        if (!need_frame) return;
        if (!m.tangents.empty()) {
            dpdu = m.tan(tri[0]) * w0 + m.tan(tri[1]) * w1 + m.tan(tri[2]) * w2;
            h.bitangent_sign = m.tangents[4 * a + 3] < 0 ? -1 : 1;
        }
        const V3 n = h.shading_normal;
        V3 t = dpdu - n * dot(n, dpdu);
        const double tl = length(t);
        if (tl > 1e-12 * (length(dpdu) + 1e-300) && std::isfinite(tl)) {
            h.tangent = t * (1 / tl);
        } else {
            const Frame<double> f(n);
            h.tangent = f.s;
            h.bitangent_sign = 1;
        }
        if (flipped) h.bitangent_sign = -h.bitangent_sign;
    }

  public:
    /// The normal-mapped shading normal at a hit: the normal map (bilinear, wrapping) decoded
    /// as 2c - 1 in the hit's tangent frame (tangent, bitangent, shading_normal), normalised.
    /// Without a normal map or UVs, or when the decoded vector is zero or not finite, the
    /// shading normal. The result may face away from the geometric normal on a steep map; the
    /// caller decides (the renderer clamps cosines).
    static vec3<double> normal_mapped(const Hit& h) noexcept {
        if (!h.normal_map || !h.has_uv) return h.shading_normal;
        using namespace detail::rt;
        const auto c = texture(*h.normal_map, h.uv[0], h.uv[1]);
        const V3 n = h.shading_normal, t = h.tangent;
        const V3 bt = cross(n, t) * h.bitangent_sign;
        const V3 p = t * (2 * c[0] - 1) + bt * (2 * c[1] - 1) + n * (2 * c[2] - 1);
        return normalized(p, n);
    }

    /// Bilinear lookup of a texture at uv, wrapping (texel (0, 0) at uv (0, 1): mesh.hpp).
    static std::array<double, 3> texture(const TextureView& tex, double u, double v) noexcept {
        std::array<double, 3> out{1, 1, 1};
        if (!tex.texels || tex.width <= 0 || tex.height <= 0 || !std::isfinite(u) ||
            !std::isfinite(v))
            return out;
        const double x = (u - std::floor(u)) * tex.width - 0.5;
        const double y = ((1 - v) - std::floor(1 - v)) * tex.height - 0.5;
        const double fx = std::floor(x), fy = std::floor(y);
        const double ax = x - fx, ay = y - fy;
        auto wrap = [](long i, int n) { return static_cast<std::size_t>(((i % n) + n) % n); };
        const long ix = static_cast<long>(fx), iy = static_cast<long>(fy);
        const std::size_t x0 = wrap(ix, tex.width), x1 = wrap(ix + 1, tex.width);
        const std::size_t y0 = wrap(iy, tex.height), y1 = wrap(iy + 1, tex.height);
        const std::size_t w = static_cast<std::size_t>(tex.width);
        const std::size_t ch = static_cast<std::size_t>(tex.channels);
        for (std::size_t k = 0; k < 3; ++k) {
            const std::size_t kk = ch == 1 ? 0 : k;
            auto at = [&](std::size_t xx, std::size_t yy) {
                return static_cast<double>(tex.texels[(yy * w + xx) * ch + kk]);
            };
            out[k] = (1 - ay) * ((1 - ax) * at(x0, y0) + ax * at(x1, y0)) +
                     ay * ((1 - ax) * at(x0, y1) + ax * at(x1, y1));
        }
        return out;
    }

  private:
    static constexpr std::size_t chunk = 1024;

    /// Checks the buffer, then traces the n rays as streams of at most `chunk`:
    /// trace(ctx, first ray, count) per stream.
    template <class Ray, class Trace>
    void trace_stream(const char* fn, Ray* rays, std::size_t n, Trace trace) const {
        if (n == 0) return;
        sphbasis::detail::check_buffer(fn, "rays", rays, n);
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (std::size_t i = 0; i < n; i += chunk)
            trace(&ctx, rays + i, static_cast<unsigned>(std::min(chunk, n - i)));
    }

    struct MeshData {
        std::vector<float> positions, normals, uvs, tangents;
        std::vector<std::uint32_t> indices;  // kept (non-degenerate) triangles
        std::vector<std::uint32_t> prim;     // kept triangle -> original triangle
        // Unit counter-clockwise normal of each kept triangle, normalized((p1 - p0) x (p2 - p0))
        // in double (hit records read it instead of recomputing it: 24 bytes a triangle).
        std::vector<double> face_normals;
        std::array<double, 3> albedo{0, 0, 0};
        TextureView map{}, normal_map{};
        double shininess = 0;
        std::array<double, 3> specular{0, 0, 0};
        detail::rt::V3 tan(std::uint32_t i) const noexcept {
            return {tangents[4 * std::size_t(i)], tangents[4 * std::size_t(i) + 1],
                    tangents[4 * std::size_t(i) + 2]};
        }
        detail::rt::V3 pos(std::uint32_t i) const noexcept {
            return {positions[3 * std::size_t(i)], positions[3 * std::size_t(i) + 1],
                    positions[3 * std::size_t(i) + 2]};
        }
        detail::rt::V3 nrm(std::uint32_t i) const noexcept {
            return {normals[3 * std::size_t(i)], normals[3 * std::size_t(i) + 1],
                    normals[3 * std::size_t(i) + 2]};
        }
    };

    [[noreturn]] static void bad(std::size_t m, const std::string& what) {
        sphbasis::detail::throw_invalid("render::Scene",
                                        what + " (mesh " + std::to_string(m) + ")");
    }
    static bool all_finite(const float* p, std::size_t n) noexcept {
        for (std::size_t i = 0; i < n; ++i)
            if (!std::isfinite(p[i])) return false;
        return true;
    }

    void copy_mesh(std::size_t m, const MeshView& v) {
        const char* fn = "render::Scene";
        sphbasis::detail::check_buffer(fn, "positions", v.positions, v.vertex_count);
        sphbasis::detail::check_buffer(fn, "indices", v.indices, v.triangle_count);
        if (v.vertex_count > std::size_t(std::numeric_limits<std::uint32_t>::max()))
            bad(m, "fewer than 2^32 vertices, got " + std::to_string(v.vertex_count));
        MeshData& d = meshes_[m];
        const std::size_t nv = v.vertex_count;
        // Copies `per` floats a vertex of an optional array, all finite.
        auto copy = [m, nv](const float* src, std::size_t per, std::vector<float>& dst,
                            const char* what) {
            if (!src || nv == 0) return;
            dst.assign(src, src + per * nv);
            if (!all_finite(dst.data(), dst.size()))
                bad(m, std::string("finite ") + what + ", got a NaN or an infinity");
        };
        copy(v.positions, 3, d.positions, "vertex positions");
        for (const float x : d.positions)
            if (!(std::fabs(x) <= coordinate_limit))
                bad(m, "vertex coordinates within [-1e15, 1e15] (render::coordinate_limit), got " +
                           std::to_string(x));
        copy(v.normals, 3, d.normals, "normals");
        copy(v.uvs, 2, d.uvs, "UVs");
        copy(v.tangents, 4, d.tangents, "tangents");
        if (!(v.shininess >= 0 && std::isfinite(v.shininess)))
            bad(m, "a finite shininess >= 0, got " + std::to_string(v.shininess));
        d.shininess = v.shininess;
        for (std::size_t k = 0; k < 3; ++k) {
            const double s = v.specular[k];
            if (!(s >= 0 && s <= 1)) bad(m, "specular in [0, 1], got " + std::to_string(s));
            d.specular[k] = s;
        }
        const TextureView& nm = v.normal_map;
        if (nm.texels || nm.width || nm.height) {
            if (!nm.texels || nm.width <= 0 || nm.height <= 0 ||
                !(nm.channels == 3 || nm.channels == 4))
                bad(m, "a normal map with texels, width, height > 0 and 3 or 4 channels, got " +
                           std::to_string(nm.width) + "x" + std::to_string(nm.height) + "x" +
                           std::to_string(nm.channels) + (nm.texels ? "" : " without texels"));
            if (!v.uvs) bad(m, "UVs with a normal map, got none");
            const std::size_t n =
                std::size_t(nm.width) * std::size_t(nm.height) * std::size_t(nm.channels);
            if (!all_finite(nm.texels, n))
                bad(m, "finite normal map texels, got a NaN or an infinity");
            d.normal_map = nm;
        }
        for (std::size_t k = 0; k < 3; ++k) {
            const double a = v.albedo[k];
            if (!(a >= 0 && a <= 1)) bad(m, "albedo in [0, 1], got " + std::to_string(a));
            d.albedo[k] = a;
        }
        double map_max = 1;
        const TextureView& t = v.albedo_map;
        if (t.texels || t.width || t.height) {
            if (!t.texels || t.width <= 0 || t.height <= 0 ||
                !(t.channels == 1 || t.channels == 3 || t.channels == 4))
                bad(m, "an albedo map with texels, width, height > 0 and 1, 3 or 4 channels, got " +
                           std::to_string(t.width) + "x" + std::to_string(t.height) + "x" +
                           std::to_string(t.channels) + (t.texels ? "" : " without texels"));
            map_max = 0;
            const std::size_t n = std::size_t(t.width) * std::size_t(t.height);
            const std::size_t ch = std::size_t(t.channels);
            for (std::size_t i = 0; i < n; ++i)
                for (std::size_t k = 0; k < std::min<std::size_t>(ch, 3); ++k) {
                    const double x = t.texels[i * ch + k];
                    if (!(x >= 0 && x <= 1))
                        bad(m, "albedo map texels in [0, 1], got " + std::to_string(x));
                    map_max = std::max(map_max, x);
                }
            d.map = t;
        }
        for (std::size_t k = 0; k < 3; ++k)
            max_albedo_ = std::max(max_albedo_, d.albedo[k] * map_max);
        if (d.albedo[0] != d.albedo[1] || d.albedo[1] != d.albedo[2] ||
            (d.map.texels && d.map.channels != 1))
            chromatic_ = true;
        d.indices.reserve(3 * v.triangle_count);
        for (std::size_t f = 0; f < v.triangle_count; ++f) {
            const std::uint32_t a = v.indices[3 * f], b = v.indices[3 * f + 1],
                                c = v.indices[3 * f + 2];
            if (a >= nv || b >= nv || c >= nv)
                bad(m, "indices < vertex_count = " + std::to_string(nv) + ", got triangle " +
                           std::to_string(f) + " = (" + std::to_string(a) + ", " +
                           std::to_string(b) + ", " + std::to_string(c) + ")");
            using namespace detail::rt;
            const V3 p0 = d.pos(a), p1 = d.pos(b), p2 = d.pos(c);
            const V3 c2 = cross(p1 - p0, p2 - p0);
            const double e =
                std::max({dot(p1 - p0, p1 - p0), dot(p2 - p1, p2 - p1), dot(p0 - p2, p0 - p2)});
            if (a == b || b == c || a == c || !(std::sqrt(dot(c2, c2)) > 1e-12 * e)) {
                ++degenerate_;
                continue;
            }
            d.indices.insert(d.indices.end(), {a, b, c});
            d.prim.push_back(static_cast<std::uint32_t>(f));
            const V3 ng = normalized(c2);
            d.face_normals.insert(d.face_normals.end(), {ng.x, ng.y, ng.z});
        }
        triangles_ += d.prim.size();
    }

    void bounds() {
        const double inf = std::numeric_limits<double>::infinity();
        lo_ = {inf, inf, inf};
        hi_ = {-inf, -inf, -inf};
        bool any = false;
        for (const auto& m : meshes_)
            for (std::uint32_t i : m.indices) {
                const auto p = m.pos(i);
                lo_ = {std::min(lo_.x, p.x), std::min(lo_.y, p.y), std::min(lo_.z, p.z)};
                hi_ = {std::max(hi_.x, p.x), std::max(hi_.y, p.y), std::max(hi_.z, p.z)};
                any = true;
            }
        if (!any) {
            lo_ = hi_ = {0, 0, 0};
            return;
        }
        using namespace detail::rt;
        extent_ = length(hi_ - lo_);
        max_abs_ = std::max({std::fabs(lo_.x), std::fabs(lo_.y), std::fabs(lo_.z), std::fabs(hi_.x),
                             std::fabs(hi_.y), std::fabs(hi_.z)});
    }

    void attach(std::size_t m) {
        const MeshData& d = meshes_[m];
        if (d.prim.empty()) return;
        RTCGeometry g = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        const std::size_t nv = d.positions.size() / 3;
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), d.prim.size()));
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            release();
            sphbasis::detail::throw_runtime("render::Scene", "Embree geometry buffers, got none");
        }
        std::memcpy(vb, d.positions.data(), d.positions.size() * sizeof(float));
        std::memcpy(ib, d.indices.data(), d.indices.size() * sizeof(unsigned));
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene_, g, static_cast<unsigned>(m));
        rtcReleaseGeometry(g);
    }

    void analyse_convexity() {
        std::size_t with = 0, which = 0;
        for (std::size_t m = 0; m < meshes_.size(); ++m)
            if (!meshes_[m].prim.empty()) {
                ++with;
                which = m;
            }
        if (with == 0) {
            can_occlude_ = false;
            occlusion_reason_ = "the scene has no triangles";
            return;
        }
        can_occlude_ = true;
        if (with > 1) {
            occlusion_reason_ = "the scene has " + std::to_string(with) + " meshes";
            return;
        }
        const MeshData& d = meshes_[which];
        // Weld vertices at bit-equal positions (UV seams split vertices).
        struct Key {
            float x, y, z;
            bool operator==(const Key& o) const noexcept {
                return x == o.x && y == o.y && z == o.z;
            }
        };
        struct KeyHash {
            std::size_t operator()(const Key& k) const noexcept {
                std::uint32_t a, b, c;
                const float x = k.x + 0.0f, y = k.y + 0.0f, z = k.z + 0.0f;  // -0 == +0
                std::memcpy(&a, &x, 4);
                std::memcpy(&b, &y, 4);
                std::memcpy(&c, &z, 4);
                return static_cast<std::size_t>(detail::rt::hash(a, b, c));
            }
        };
        const std::size_t nv = d.positions.size() / 3, nf = d.prim.size();
        std::unordered_map<Key, std::uint32_t, KeyHash> weld;
        std::vector<std::uint32_t> id(nv);
        for (std::size_t i = 0; i < nv; ++i) {
            const Key k{d.positions[3 * i], d.positions[3 * i + 1], d.positions[3 * i + 2]};
            id[i] = weld.emplace(k, static_cast<std::uint32_t>(weld.size())).first->second;
        }
        // Directed edges: (a, b) -> triangle; each undirected edge must appear once each way.
        std::unordered_map<std::uint64_t, std::uint32_t> directed;
        directed.reserve(3 * nf);
        auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
        for (std::size_t f = 0; f < nf; ++f)
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t a = id[d.indices[3 * f + std::size_t(e)]];
                const std::uint32_t b = id[d.indices[3 * f + std::size_t((e + 1) % 3)]];
                if (a == b || !directed.emplace(key(a, b), std::uint32_t(f)).second) {
                    occlusion_reason_ = "the mesh is not a closed, consistently oriented manifold";
                    return;
                }
            }
        std::vector<std::uint32_t> parent(nf);
        std::iota(parent.begin(), parent.end(), 0u);
        auto find = [&](std::uint32_t x) {
            while (parent[x] != x) x = parent[x] = parent[parent[x]];
            return x;
        };
        using namespace detail::rt;
        const double tol = 1e-7 * extent_ + epsilon() * 1e-3;
        int sign = 0;
        for (const auto& [k, f] : directed) {
            const std::uint32_t a = std::uint32_t(k >> 32), b = std::uint32_t(k & 0xFFFFFFFFu);
            const auto other = directed.find(key(b, a));
            if (other == directed.end()) {
                occlusion_reason_ = "the mesh is not closed";
                return;
            }
            const std::uint32_t g = other->second;
            parent[find(f)] = find(g);
            // The far vertex of g against f's plane.
            const std::uint32_t* tf = &d.indices[3 * std::size_t(f)];
            const std::uint32_t* tg = &d.indices[3 * std::size_t(g)];
            const V3 p0 = d.pos(tf[0]);
            const V3 nf_ = normalized(cross(d.pos(tf[1]) - p0, d.pos(tf[2]) - p0));
            double s = 0;
            for (int e = 0; e < 3; ++e) {
                const std::uint32_t w = id[tg[e]];
                if (w != a && w != b) s = dot(nf_, d.pos(tg[e]) - p0);
            }
            const int sg = s > tol ? 1 : (s < -tol ? -1 : 0);
            if (sg != 0) {
                if (sign != 0 && sg != sign) {
                    occlusion_reason_ = "the mesh is not convex";
                    return;
                }
                sign = sg;
            }
        }
        const std::uint32_t root = find(0);
        for (std::uint32_t f = 1; f < nf; ++f)
            if (find(f) != root) {
                occlusion_reason_ = "the mesh has several connected components";
                return;
            }
        if (sign == 0) {
            occlusion_reason_ = "the mesh is flat";
            return;
        }
        can_occlude_ = false;
        occlusion_reason_ = "the scene is one closed convex mesh";
    }

    void release() noexcept {
        if (scene_) rtcReleaseScene(scene_);
        if (device_) rtcReleaseDevice(device_);
        scene_ = nullptr;
        device_ = nullptr;
    }
    void swap(Scene& o) noexcept {
        std::swap(device_, o.device_);
        std::swap(scene_, o.scene_);
        std::swap(meshes_, o.meshes_);
        std::swap(triangles_, o.triangles_);
        std::swap(degenerate_, o.degenerate_);
        std::swap(extent_, o.extent_);
        std::swap(max_abs_, o.max_abs_);
        std::swap(lo_, o.lo_);
        std::swap(hi_, o.hi_);
        std::swap(max_albedo_, o.max_albedo_);
        std::swap(chromatic_, o.chromatic_);
        std::swap(can_occlude_, o.can_occlude_);
        std::swap(occlusion_reason_, o.occlusion_reason_);
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<MeshData> meshes_;
    std::size_t triangles_ = 0, degenerate_ = 0;
    double extent_ = 0, max_abs_ = 0;
    vec3<double> lo_{0, 0, 0}, hi_{0, 0, 0};
    double max_albedo_ = 0;
    bool chromatic_ = false;
    bool can_occlude_ = true;
    std::string occlusion_reason_;
};

}  // namespace sphbasis::render
