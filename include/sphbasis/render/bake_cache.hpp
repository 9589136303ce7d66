// sphbasis render tier: the bakes a representation reads (render/representation.hpp), their
// identity and where they are kept between runs.
//
//   BakeRequest       one bake: where (vertices or lightmap texels of a mesh, or the probes of
//                     a grid), the bake settings (adaptive sampling included), the lightmap size,
//                     whether it depends on the lighting, the high-to-low projections.
//   BakeData          a bake's results with its lightmap layout, pass plan, time and rays.
//   bake_key()        a hash of everything a bake depends on: the request, the geometry of
//                     every mesh (they occlude), the albedos and albedo maps when it has
//                     bounces, the lighting (environment texels, rotation, scale; lights) only
//                     for lighting-dependent quantities (irradiance, radiance). Re-rendering
//                     with a rotated environment therefore re-bakes nothing for PRT and only
//                     lightmaps and probes for a changed light.
//   serialize(), deserialize()
//                     the versioned bytes of a BakeData and back (render/bake_file.hpp's
//                     ByteWriter and bounds-checked ByteReader).
//   BakeCache         where bakes are kept (the tool keeps files: tools/support/bake_cache.hpp);
//                     MemoryBakeCache keeps them in memory (tests).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "bake.hpp"
#include "bake_file.hpp"
#include "detail/rt_math.hpp"
#include "high_to_low.hpp"
#include "lighting.hpp"
#include "lightmap.hpp"
#include "mesh.hpp"
#include "probe_grid.hpp"

namespace sphbasis::render {

/// Whether a bake of `quantities` depends on the lighting (BakeRequest::lighting_dependent, as
/// the representations and `sphbasis bake` set it): irradiance and radiance do; ao, bent,
/// visibility, transfer and transfer_matrix do not.
constexpr bool depends_on_lighting(Quantity quantities) noexcept {
    return has(quantities, Quantity::irradiance | Quantity::radiance);
}

/// One bake a representation reads.
struct BakeRequest {
    enum class Where { vertex, texel, probes } where = Where::vertex;
    std::size_t mesh = 0;  // index into SceneDesc::meshes (probes: 0)
    BakeSettings settings;
    int lightmap_size = 0;  // texel bakes
    bool lighting_dependent = false;
    ProbeGrid probes;  // probe bakes: the grid (part of the key)
    /// A bake whose scene has meshes baked from high-poly sources (render/high_to_low.hpp):
    /// high_to_low_key() of those projections; 0 (no projection, every mesh occludes) for the
    /// bakes the representations make.
    std::uint64_t high_to_low = 0;
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

namespace repr_detail {

/// A 64-bit FNV-1a over 64-bit words (and bytes for the tail), finished by SplitMix64's mixer.
struct Hasher {
    std::uint64_t h = 0xcbf29ce484222325ull;
    void word(std::uint64_t w) noexcept { h = (h ^ w) * 0x100000001b3ull; }
    void bytes(const void* p, std::size_t n) noexcept {
        const unsigned char* c = static_cast<const unsigned char*>(p);
        word(n);
        std::size_t i = 0;
        for (; i + 8 <= n; i += 8) {
            std::uint64_t w;
            std::memcpy(&w, c + i, 8);
            word(w);
        }
        std::uint64_t tail = 0;
        for (std::size_t k = 0; i < n; ++i, ++k) tail |= std::uint64_t(c[i]) << (8 * k);
        word(tail);
    }
    void f64(double x) noexcept {
        if (x == 0) x = 0;  // -0 == +0
        std::uint64_t w;
        std::memcpy(&w, &x, 8);
        word(w);
    }
    void str(const std::string& s) noexcept { bytes(s.data(), s.size()); }
    template <class T>
    void array(const T* p, std::size_t n) noexcept {
        word(p ? 1 : 0);
        if (p) bytes(p, n * sizeof(T));
    }
    std::uint64_t value() const noexcept { return detail::rt::mix64(h); }
};

inline void hash_texture(Hasher& h, const TextureView& t) {
    h.word(std::uint64_t(std::max(t.width, 0)));
    h.word(std::uint64_t(std::max(t.height, 0)));
    h.word(std::uint64_t(std::max(t.channels, 0)));
    const std::size_t n =
        t.texels && t.width > 0 && t.height > 0 && t.channels > 0
            ? std::size_t(t.width) * std::size_t(t.height) * std::size_t(t.channels)
            : 0;
    h.array(t.texels, n);
}

// Payloads are written and read with render/bake_file.hpp's ByteWriter and ByteReader (every
// read bounds-checked); a signed int is its two's-complement u32, a vec3 three f64.
inline void put_i32(ByteWriter& w, int v) { w.u32(static_cast<std::uint32_t>(v)); }
inline int get_i32(ByteReader& r) { return static_cast<int>(r.u32()); }
inline void put_v3(ByteWriter& w, const vec3<double>& v) {
    w.f64(v.x);
    w.f64(v.y);
    w.f64(v.z);
}
inline vec3<double> get_v3(ByteReader& r) {
    const double x = r.f64(), y = r.f64();
    return {x, y, r.f64()};
}

inline void write_settings(ByteWriter& w, const BakeSettings& s) {
    w.u32(static_cast<std::uint32_t>(s.quantities));
    put_i32(w, s.bands);
    w.str(s.basis);
    put_i32(w, s.coeffs);
    put_i32(w, s.rays);
    put_i32(w, s.bounces);
    w.u64(s.seed);
    w.f64(s.max_distance);
    w.f64(s.target_error);
    w.u8(s.force_all_passes ? 1 : 0);
    for (double t : s.adaptive.target) w.f64(t);
    put_i32(w, s.adaptive.max_rays);
}
inline BakeSettings read_settings(ByteReader& r) {
    BakeSettings s;
    s.quantities = static_cast<Quantity>(r.u32());  // checked by the Baker and the key
    s.bands = get_i32(r);
    s.basis = r.str();
    s.coeffs = get_i32(r);
    s.rays = get_i32(r);
    s.bounces = get_i32(r);
    s.seed = r.u64();
    s.max_distance = r.f64();
    s.target_error = r.f64();
    s.force_all_passes = r.u8() != 0;
    for (double& t : s.adaptive.target) t = r.f64();
    s.adaptive.max_rays = get_i32(r);
    return s;
}
inline void write_request(ByteWriter& w, const BakeRequest& q) {
    w.u8(static_cast<std::uint8_t>(q.where));
    w.u64(q.mesh);
    write_settings(w, q.settings);
    put_i32(w, q.lightmap_size);
    w.u8(q.lighting_dependent ? 1 : 0);
    put_v3(w, q.probes.lo);
    put_v3(w, q.probes.hi);
    for (int c : q.probes.counts) put_i32(w, c);
    w.u64(q.high_to_low);
}
inline BakeRequest read_request(ByteReader& r) {
    BakeRequest q;
    const std::uint8_t where = r.u8();
    if (where > 2)
        sphbasis::detail::throw_runtime("render::deserialize",
                                        "a bake location 0, 1 or 2, got " + std::to_string(where));
    q.where = static_cast<BakeRequest::Where>(where);
    q.mesh = static_cast<std::size_t>(r.u64());
    q.settings = read_settings(r);
    q.lightmap_size = get_i32(r);
    q.lighting_dependent = r.u8() != 0;
    q.probes.lo = get_v3(r);
    q.probes.hi = get_v3(r);
    for (int& c : q.probes.counts) c = get_i32(r);
    q.high_to_low = r.u64();
    return q;
}
/// The identity of a request (its bytes), for finding distinct requests.
inline std::vector<std::uint8_t> request_bytes(const BakeRequest& q) {
    ByteWriter w;
    write_request(w, q);
    return w.take();
}
inline std::vector<std::uint8_t> settings_bytes(const BakeSettings& s) {
    ByteWriter w;
    write_settings(w, s);
    return w.take();
}

constexpr char magic[8] = {'S', 'P', 'H', 'B', 'B', 'A', 'K', 'E'};
// 2: transfer_matrix; 3: the standard errors bent_stderr, irradiance_stderr, radiance_stderr,
// transfer_matrix_stderr (a cache file of version 2 is refused and baked again); 4: the adaptive
// sampling settings and BakeRequest::high_to_low.
constexpr std::uint32_t format_version = 4;

}  // namespace repr_detail

/// BakeRequest::high_to_low of a bake in `scene` whose target meshes are baked from their
/// sources as `projections` say (one per target): a hash of every target, source, ray distance
/// and cage (its positions), never 0; 0 when `projections` is empty. Cost: one pass over the
/// cages.
inline std::uint64_t high_to_low_key(const SceneDesc& scene,
                                     const std::vector<HighToLowSettings>& projections) {
    if (projections.empty()) return 0;
    repr_detail::Hasher h;
    h.word(projections.size());
    for (const HighToLowSettings& p : projections) {
        h.word(p.target);
        h.word(p.source);
        h.f64(p.max_ray_distance);
        h.array(p.cage_positions,
                p.target < scene.meshes.size() ? 3 * scene.meshes[p.target].vertex_count : 0);
    }
    const std::uint64_t v = h.value();
    return v != 0 ? v : 1;
}

/// The hash of everything a bake depends on (header comment): the request (location, mesh,
/// settings with the adaptive sampling, lightmap size, probe grid, high-to-low projections),
/// the geometry of every mesh (positions, indices, normals, UVs, tangents), the albedos and
/// albedo maps when settings.bounces > 0, and the lighting (environment kind, constant, texels,
/// rotation, scale; every light) only when request.lighting_dependent. FNV-1a over 64-bit words,
/// mixed by SplitMix64. Cost: one pass over the arrays.
inline std::uint64_t bake_key(const SceneDesc& scene, const BakeRequest& request) {
    repr_detail::Hasher h;
    // 2: the shared point ids (render/bake_points.hpp); 3: adaptive sampling and high to low.
    h.str("sphbasis bake key 3");
    const std::vector<std::uint8_t> req = repr_detail::request_bytes(request);
    h.bytes(req.data(), req.size());
    h.word(scene.meshes.size());
    for (const MeshView& m : scene.meshes) {
        h.word(m.vertex_count);
        h.word(m.triangle_count);
        h.array(m.positions, 3 * m.vertex_count);
        h.array(m.indices, 3 * m.triangle_count);
        h.array(m.normals, 3 * m.vertex_count);
        h.array(m.uvs, 2 * m.vertex_count);
        h.array(m.tangents, 4 * m.vertex_count);
        if (request.settings.bounces > 0) {
            for (float a : m.albedo) h.f64(a);
            repr_detail::hash_texture(h, m.albedo_map);
        }
    }
    if (request.lighting_dependent) {
        const Environment& e = scene.environment;
        h.word(static_cast<std::uint64_t>(e.kind));
        if (e.kind == Environment::Kind::constant)
            for (double c : e.constant) h.f64(c);
        if (e.kind == Environment::Kind::latlong) {
            h.word(std::uint64_t(std::max(e.width, 0)));
            h.word(std::uint64_t(std::max(e.height, 0)));
            h.array(e.texels, e.width > 0 && e.height > 0
                                  ? std::size_t(e.width) * std::size_t(e.height) * 3
                                  : 0);
        }
        for (double r : e.rotation) h.f64(r);
        h.f64(e.scale);
        h.word(scene.lights.size());
        for (const Light& l : scene.lights) {
            h.word(static_cast<std::uint64_t>(l.type));
            h.f64(l.direction.x), h.f64(l.direction.y), h.f64(l.direction.z);
            h.f64(l.position.x), h.f64(l.position.y), h.f64(l.position.z);
            h.f64(l.radius), h.f64(l.angle_deg);
            for (double c : l.color) h.f64(c);
            for (double c : l.ground) h.f64(c);
        }
    }
    return h.value();
}

/// Bytes of a BakeData (versioned, little-endian) and back; deserialize throws
/// std::runtime_error for truncated or foreign bytes. Format: the magic "SPHBBAKE", a 32-bit
/// version (repr_detail::format_version), the request, the layout, the results, the plan, seconds
/// and rays; integers little-endian, doubles as their IEEE-754 bits, vectors and strings
/// length-prefixed (64-bit). from_cache is not stored (deserialize sets it).
inline std::vector<std::uint8_t> serialize(const BakeData& data) {
    ByteWriter w;
    for (char c : repr_detail::magic) w.u8(static_cast<std::uint8_t>(c));
    w.u32(repr_detail::format_version);
    repr_detail::write_request(w, data.request);
    const LightmapLayout& L = data.layout;
    repr_detail::put_i32(w, L.width);
    repr_detail::put_i32(w, L.height);
    w.u64(L.samples.size());
    for (const LightmapSample& s : L.samples) {
        repr_detail::put_i32(w, s.x);
        repr_detail::put_i32(w, s.y);
        repr_detail::put_v3(w, s.point.p);
        repr_detail::put_v3(w, s.point.n);
        repr_detail::put_v3(w, s.point.tangent);
        w.f64(s.point.bitangent_sign);
        w.u64(s.point.id);
        w.u32(s.triangle);
        for (double b : s.barycentric) w.f64(b);
        repr_detail::put_v3(w, s.surface);
        w.f64(s.u);
        w.f64(s.v);
        w.f64(s.bitangent_sign);
        w.f64(s.offset);
    }
    w.u8s(L.covered);
    w.u64(L.skipped_triangles);
    w.u64(L.degenerate_triangles);
    w.u64(data.results.size());
    for (const PointResult& r : data.results) {
        w.f64(r.ao);
        w.f64(r.ao_stderr);
        repr_detail::put_v3(w, r.bent);
        w.f64(r.bent_stderr);
        w.f64s(r.visibility);
        w.f64s(r.visibility_stderr);
        for (const auto& v : r.transfer) w.f64s(v);
        w.f64s(r.transfer_stderr);
        w.u8(r.transfer_rgb ? 1 : 0);
        for (const auto& v : r.irradiance) w.f64s(v);
        w.f64s(r.irradiance_stderr);
        for (const auto& v : r.radiance) w.f64s(v);
        w.f64s(r.radiance_stderr);
        for (const auto& v : r.transfer_matrix) w.f64s(v);
        w.f64s(r.transfer_matrix_stderr);
        w.u8(r.inside ? 1 : 0);
    }
    w.u64(data.plan.size());
    for (const Pass& p : data.plan) {
        w.str(p.name);
        w.str(p.reason);
        w.u64(p.rays);
        w.f64(p.seconds);
    }
    w.f64(data.seconds);
    w.u64(data.rays);
    return w.take();
}
inline BakeData deserialize(const std::uint8_t* bytes, std::size_t size) {
    constexpr const char* fn = "render::deserialize";
    if (size < 12 || std::memcmp(bytes, repr_detail::magic, 8) != 0)
        sphbasis::detail::throw_runtime(fn, "bytes starting with the magic \"SPHBBAKE\", got " +
                                                std::to_string(size) + " bytes without it");
    ByteReader r(bytes + 8, size - 8, fn);
    const std::uint32_t version = r.u32();
    if (version != repr_detail::format_version)
        sphbasis::detail::throw_runtime(fn, "format version " +
                                                std::to_string(repr_detail::format_version) +
                                                ", got " + std::to_string(version));
    BakeData d;
    d.request = repr_detail::read_request(r);
    LightmapLayout& L = d.layout;
    L.width = repr_detail::get_i32(r);
    L.height = repr_detail::get_i32(r);
    L.samples.resize(r.count(8 * 27));
    for (LightmapSample& s : L.samples) {
        s.x = repr_detail::get_i32(r);
        s.y = repr_detail::get_i32(r);
        s.point.p = repr_detail::get_v3(r);
        s.point.n = repr_detail::get_v3(r);
        s.point.tangent = repr_detail::get_v3(r);
        s.point.bitangent_sign = r.f64();
        s.point.id = r.u64();
        s.triangle = r.u32();
        for (double& b : s.barycentric) b = r.f64();
        s.surface = repr_detail::get_v3(r);
        s.u = r.f64();
        s.v = r.f64();
        s.bitangent_sign = r.f64();
        s.offset = r.f64();
    }
    L.covered = r.u8s();
    L.skipped_triangles = static_cast<std::size_t>(r.u64());
    L.degenerate_triangles = static_cast<std::size_t>(r.u64());
    d.results.resize(r.count(8 * 6 + 8 * 18 + 2));
    for (PointResult& p : d.results) {
        p.ao = r.f64();
        p.ao_stderr = r.f64();
        p.bent = repr_detail::get_v3(r);
        p.bent_stderr = r.f64();
        p.visibility = r.f64s();
        p.visibility_stderr = r.f64s();
        for (auto& v : p.transfer) v = r.f64s();
        p.transfer_stderr = r.f64s();
        p.transfer_rgb = r.u8() != 0;
        for (auto& v : p.irradiance) v = r.f64s();
        p.irradiance_stderr = r.f64s();
        for (auto& v : p.radiance) v = r.f64s();
        p.radiance_stderr = r.f64s();
        for (auto& v : p.transfer_matrix) v = r.f64s();
        p.transfer_matrix_stderr = r.f64s();
        p.inside = r.u8() != 0;
    }
    d.plan.resize(r.count(32));
    for (Pass& p : d.plan) {
        p.name = r.str();
        p.reason = r.str();
        p.rays = r.u64();
        p.seconds = r.f64();
    }
    d.seconds = r.f64();
    d.rays = r.u64();
    r.finish();  // "... trailing bytes" for bytes after the record
    d.from_cache = true;
    return d;
}
inline BakeData deserialize(const std::vector<std::uint8_t>& bytes) {
    return deserialize(bytes.data(), bytes.size());
}

/// Where bakes are kept between runs (the tool keeps files; tests keep memory).
class BakeCache {
  public:
    virtual ~BakeCache() = default;
    virtual bool load(std::uint64_t key, BakeData& out) = 0;
    virtual void store(std::uint64_t key, const BakeData& data) = 0;
};

/// A BakeCache in memory that keeps serialize()d bytes (so a round trip is exercised on every
/// load). Not thread-safe (prepare() calls it from one thread).
class MemoryBakeCache : public BakeCache {
  public:
    bool load(std::uint64_t key, BakeData& out) override {
        const auto it = entries_.find(key);
        if (it == entries_.end()) return false;
        out = deserialize(it->second);
        return true;
    }
    void store(std::uint64_t key, const BakeData& data) override {
        entries_[key] = serialize(data);
    }
    std::size_t size() const noexcept { return entries_.size(); }
    void clear() noexcept { entries_.clear(); }

  private:
    std::map<std::uint64_t, std::vector<std::uint8_t>> entries_;
};

}  // namespace sphbasis::render
