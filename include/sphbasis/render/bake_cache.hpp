// sphbasis render tier: the bakes a representation reads (render/representation.hpp), their
// identity and where they are kept between runs.
//
//   BakeRequest       one bake: where (vertices or lightmap texels of a mesh, or the probes of
//                     a grid), the bake settings, the lightmap size, whether it depends on the
//                     lighting.
//   BakeData          a bake's results with its lightmap layout, pass plan, time and rays.
//   bake_key()        a hash of everything a bake depends on: the request, the geometry of
//                     every mesh (they occlude), the albedos and albedo maps when it has
//                     bounces, the lighting (environment texels, rotation, scale; lights) only
//                     for lighting-dependent quantities (irradiance, radiance). Re-rendering
//                     with a rotated environment therefore re-bakes nothing for PRT and only
//                     lightmaps and probes for a changed light.
//   serialize(), deserialize()
//                     the versioned bytes of a BakeData and back.
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
#include "detail/rt_math.hpp"
#include "lighting.hpp"
#include "lightmap.hpp"
#include "mesh.hpp"
#include "probe_grid.hpp"

namespace sphbasis::render {

/// One bake a representation reads.
struct BakeRequest {
    enum class Where { vertex, texel, probes } where = Where::vertex;
    std::size_t mesh = 0;  // index into SceneDesc::meshes (probes: 0)
    BakeSettings settings;
    int lightmap_size = 0;  // texel bakes
    bool lighting_dependent = false;
    ProbeGrid probes;  // probe bakes: the grid (part of the key)
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

/// Little-endian writer.
struct Writer {
    std::vector<std::uint8_t> out;
    void u64(std::uint64_t v) {
        for (int k = 0; k < 8; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
    }
    void u32(std::uint32_t v) {
        for (int k = 0; k < 4; ++k) out.push_back(std::uint8_t(v >> (8 * k)));
    }
    void i32(int v) { u32(static_cast<std::uint32_t>(v)); }
    void u8(std::uint8_t v) { out.push_back(v); }
    void f64(double x) {
        std::uint64_t w;
        std::memcpy(&w, &x, 8);
        u64(w);
    }
    void v3(const vec3<double>& v) {
        f64(v.x);
        f64(v.y);
        f64(v.z);
    }
    void str(const std::string& s) {
        u64(s.size());
        out.insert(out.end(), s.begin(), s.end());
    }
    void vec(const std::vector<double>& v) {
        u64(v.size());
        for (double x : v) f64(x);
    }
};

/// Little-endian reader; every read checks the remaining bytes.
struct Reader {
    const std::vector<std::uint8_t>& in;
    std::size_t pos = 0;
    [[noreturn]] void truncated() const {
        sphbasis::detail::throw_runtime("render::deserialize",
                                        "a complete bake record, got " + std::to_string(in.size()) +
                                            " bytes, truncated at byte " + std::to_string(pos));
    }
    void need(std::size_t n) const {
        if (n > in.size() - pos) truncated();
    }
    std::uint64_t u64() {
        need(8);
        std::uint64_t v = 0;
        for (int k = 0; k < 8; ++k) v |= std::uint64_t(in[pos + std::size_t(k)]) << (8 * k);
        pos += 8;
        return v;
    }
    std::uint32_t u32() {
        need(4);
        std::uint32_t v = 0;
        for (int k = 0; k < 4; ++k) v |= std::uint32_t(in[pos + std::size_t(k)]) << (8 * k);
        pos += 4;
        return v;
    }
    int i32() { return static_cast<int>(u32()); }
    std::uint8_t u8() {
        need(1);
        return in[pos++];
    }
    double f64() {
        const std::uint64_t w = u64();
        double x;
        std::memcpy(&x, &w, 8);
        return x;
    }
    vec3<double> v3() {
        const double x = f64(), y = f64();
        return {x, y, f64()};
    }
    /// A count of items of at least `min_bytes` each that must fit in the rest.
    std::size_t count(std::size_t min_bytes) {
        const std::uint64_t n = u64();
        if (min_bytes > 0 && n > (in.size() - pos) / min_bytes) truncated();
        return static_cast<std::size_t>(n);
    }
    std::string str() {
        const std::size_t n = count(1);
        std::string s(in.begin() + std::ptrdiff_t(pos), in.begin() + std::ptrdiff_t(pos + n));
        pos += n;
        return s;
    }
    std::vector<double> vec() {
        const std::size_t n = count(8);
        std::vector<double> v(n);
        for (double& x : v) x = f64();
        return v;
    }
};

inline void write_settings(Writer& w, const BakeSettings& s) {
    w.u32(static_cast<std::uint32_t>(s.quantities));
    w.i32(s.bands);
    w.str(s.basis);
    w.i32(s.coeffs);
    w.i32(s.rays);
    w.i32(s.bounces);
    w.u64(s.seed);
    w.f64(s.max_distance);
    w.f64(s.target_error);
    w.u8(s.force_all_passes ? 1 : 0);
}
inline BakeSettings read_settings(Reader& r) {
    BakeSettings s;
    s.quantities = static_cast<Quantity>(r.u32());  // checked by the Baker and the key
    s.bands = r.i32();
    s.basis = r.str();
    s.coeffs = r.i32();
    s.rays = r.i32();
    s.bounces = r.i32();
    s.seed = r.u64();
    s.max_distance = r.f64();
    s.target_error = r.f64();
    s.force_all_passes = r.u8() != 0;
    return s;
}
inline void write_request(Writer& w, const BakeRequest& q) {
    w.u8(static_cast<std::uint8_t>(q.where));
    w.u64(q.mesh);
    write_settings(w, q.settings);
    w.i32(q.lightmap_size);
    w.u8(q.lighting_dependent ? 1 : 0);
    w.v3(q.probes.lo);
    w.v3(q.probes.hi);
    for (int c : q.probes.counts) w.i32(c);
}
inline BakeRequest read_request(Reader& r) {
    BakeRequest q;
    const std::uint8_t where = r.u8();
    if (where > 2)
        sphbasis::detail::throw_runtime("render::deserialize",
                                        "a bake location 0, 1 or 2, got " + std::to_string(where));
    q.where = static_cast<BakeRequest::Where>(where);
    q.mesh = static_cast<std::size_t>(r.u64());
    q.settings = read_settings(r);
    q.lightmap_size = r.i32();
    q.lighting_dependent = r.u8() != 0;
    q.probes.lo = r.v3();
    q.probes.hi = r.v3();
    for (int& c : q.probes.counts) c = r.i32();
    return q;
}
/// The identity of a request (its bytes), for finding distinct requests.
inline std::vector<std::uint8_t> request_bytes(const BakeRequest& q) {
    Writer w;
    write_request(w, q);
    return std::move(w.out);
}
inline std::vector<std::uint8_t> settings_bytes(const BakeSettings& s) {
    Writer w;
    write_settings(w, s);
    return std::move(w.out);
}

constexpr char magic[8] = {'S', 'P', 'H', 'B', 'B', 'A', 'K', 'E'};
// 2: transfer_matrix; 3: the standard errors bent_stderr, irradiance_stderr, radiance_stderr,
// transfer_matrix_stderr (a cache file of version 2 is refused and baked again).
constexpr std::uint32_t format_version = 3;

}  // namespace repr_detail

/// The hash of everything a bake depends on (header comment): the request (location, mesh,
/// settings, lightmap size, probe grid), the geometry of every mesh (positions, indices,
/// normals, UVs, tangents), the albedos and albedo maps when settings.bounces > 0, and the
/// lighting (environment kind, constant, texels, rotation, scale; every light) only when
/// request.lighting_dependent. FNV-1a over 64-bit words, mixed by SplitMix64. Cost: one pass over
/// the arrays.
inline std::uint64_t bake_key(const SceneDesc& scene, const BakeRequest& request) {
    repr_detail::Hasher h;
    h.str("sphbasis bake key 2");  // 2: the shared point ids (render/bake_points.hpp)
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
    repr_detail::Writer w;
    for (char c : repr_detail::magic) w.u8(static_cast<std::uint8_t>(c));
    w.u32(repr_detail::format_version);
    repr_detail::write_request(w, data.request);
    const LightmapLayout& L = data.layout;
    w.i32(L.width);
    w.i32(L.height);
    w.u64(L.samples.size());
    for (const LightmapSample& s : L.samples) {
        w.i32(s.x);
        w.i32(s.y);
        w.v3(s.point.p);
        w.v3(s.point.n);
        w.v3(s.point.tangent);
        w.f64(s.point.bitangent_sign);
        w.u64(s.point.id);
        w.u32(s.triangle);
        for (double b : s.barycentric) w.f64(b);
        w.v3(s.surface);
        w.f64(s.u);
        w.f64(s.v);
        w.f64(s.bitangent_sign);
        w.f64(s.offset);
    }
    w.u64(L.covered.size());
    w.out.insert(w.out.end(), L.covered.begin(), L.covered.end());
    w.u64(L.skipped_triangles);
    w.u64(L.degenerate_triangles);
    w.u64(data.results.size());
    for (const PointResult& r : data.results) {
        w.f64(r.ao);
        w.f64(r.ao_stderr);
        w.v3(r.bent);
        w.f64(r.bent_stderr);
        w.vec(r.visibility);
        w.vec(r.visibility_stderr);
        for (const auto& v : r.transfer) w.vec(v);
        w.vec(r.transfer_stderr);
        w.u8(r.transfer_rgb ? 1 : 0);
        for (const auto& v : r.irradiance) w.vec(v);
        w.vec(r.irradiance_stderr);
        for (const auto& v : r.radiance) w.vec(v);
        w.vec(r.radiance_stderr);
        for (const auto& v : r.transfer_matrix) w.vec(v);
        w.vec(r.transfer_matrix_stderr);
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
    return std::move(w.out);
}
inline BakeData deserialize(const std::vector<std::uint8_t>& bytes) {
    constexpr const char* fn = "render::deserialize";
    repr_detail::Reader r{bytes};
    if (bytes.size() < 12 || std::memcmp(bytes.data(), repr_detail::magic, 8) != 0)
        sphbasis::detail::throw_runtime(fn, "bytes starting with the magic \"SPHBBAKE\", got " +
                                                std::to_string(bytes.size()) + " bytes without it");
    r.pos = 8;
    const std::uint32_t version = r.u32();
    if (version != repr_detail::format_version)
        sphbasis::detail::throw_runtime(fn, "format version " +
                                                std::to_string(repr_detail::format_version) +
                                                ", got " + std::to_string(version));
    BakeData d;
    d.request = repr_detail::read_request(r);
    LightmapLayout& L = d.layout;
    L.width = r.i32();
    L.height = r.i32();
    L.samples.resize(r.count(8 * 27));
    for (LightmapSample& s : L.samples) {
        s.x = r.i32();
        s.y = r.i32();
        s.point.p = r.v3();
        s.point.n = r.v3();
        s.point.tangent = r.v3();
        s.point.bitangent_sign = r.f64();
        s.point.id = r.u64();
        s.triangle = r.u32();
        for (double& b : s.barycentric) b = r.f64();
        s.surface = r.v3();
        s.u = r.f64();
        s.v = r.f64();
        s.bitangent_sign = r.f64();
        s.offset = r.f64();
    }
    const std::size_t nc = r.count(1);
    L.covered.assign(bytes.begin() + std::ptrdiff_t(r.pos),
                     bytes.begin() + std::ptrdiff_t(r.pos + nc));
    r.pos += nc;
    L.skipped_triangles = static_cast<std::size_t>(r.u64());
    L.degenerate_triangles = static_cast<std::size_t>(r.u64());
    d.results.resize(r.count(8 * 6 + 8 * 18 + 2));
    for (PointResult& p : d.results) {
        p.ao = r.f64();
        p.ao_stderr = r.f64();
        p.bent = r.v3();
        p.bent_stderr = r.f64();
        p.visibility = r.vec();
        p.visibility_stderr = r.vec();
        for (auto& v : p.transfer) v = r.vec();
        p.transfer_stderr = r.vec();
        p.transfer_rgb = r.u8() != 0;
        for (auto& v : p.irradiance) v = r.vec();
        p.irradiance_stderr = r.vec();
        for (auto& v : p.radiance) v = r.vec();
        p.radiance_stderr = r.vec();
        for (auto& v : p.transfer_matrix) v = r.vec();
        p.transfer_matrix_stderr = r.vec();
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
    if (r.pos != bytes.size())
        sphbasis::detail::throw_runtime(
            fn, "a bake record of " + std::to_string(r.pos) + " bytes, got " +
                    std::to_string(bytes.size() - r.pos) + " trailing bytes");
    d.from_cache = true;
    return d;
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
