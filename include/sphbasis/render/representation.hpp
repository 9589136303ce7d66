// sphbasis render tier: the baked lighting representations a game would ship, rendered from
// the bakes of render/bake.hpp under the same lighting as the ground truth (path_tracer.hpp).
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
//   lxh-unc3, -unc4, -unc6    per-texel SH visibility of 3/4/6 bands (bake quantity visibility,
//                             world frame), shaded as V . (L x H)(n) at the mapped normal with an
//                             L x H cube-map table (ops/lxh_table.hpp; lxh_table_size texels a
//                             face edge, symmetric construction) of the rotated lighting on
//                             lxh_lighting_bands bands (0: the visibility's). Iwanicki and Sloan,
//                             "Normal Mapping with Low-Frequency Precomputed Visibility" (JGT
//                             2009), sec. 3.
//   lxh-pcaM                  M = 4, 8, 12, 16, 24 listed (any 1..36 accepted): PCA (ops/
//                             compression.hpp) of the 6-band visibility of every point, per-texel
//                             weights, one RGB table per basis vector and the mean, T_j(n) =
//                             b_j . (L x H)(n) (ibid., eq. 5-6). M above the data's rank throws
//                             at prepare().
//   prt-normalmap             the incident-transfer matrix M (bake quantity transfer_matrix:
//                             9 x prt_bands^2 RGB per texel) shaded as e(n) = y(n)^T C M l at the
//                             mapped normal in world frame (R = I there); Sloan, Lehtinen and
//                             Kautz, "Precomputed Radiance Transfer: Theory and Practice"
//                             (SIGGRAPH 2005 course), normal mapping for PRT.
//   prt-normalmap-svd4, -svd6 the same through the normal basis (ops/normal_basis.hpp, unclamped,
//                             cosine-weighted): per texel G = V_k^T R M (R: world to the texel's
//                             tangent frame), e(n) = (a(n)^T V_k) G l with a(n) = pi a_l y(n).
//   prt-ratio                 unshadowed irradiance at the mapped normal times the ratio of the
//                             shadowed (PRT transfer) to the unshadowed irradiance at the
//                             surface normal; reads prt-texel's bake.
//   prt-cpca-C-M              4-2, 8-4, 16-4 listed (any C <= 4096, M <= 64 accepted): iterative
//                             CPCA of the PRT transfer (3 prt_bands^2 numbers a point), the
//                             cluster and weights read from the nearest texel (clusters cannot
//                             be filtered), per-cluster exit values computed once.
//   Only what a requested representation reads is built (tables per distinct (K, N), one PCA
//   per lxh-pca, fields per prt-*); lxh_tables_built() and compressions_built() count them.
//
// Bakes: each representation declares the bakes it reads (BakeRequest); prepare() runs each
// distinct request once, or loads it from a BakeCache under bake_key(), a hash of everything the
// bake depends on: the geometry of every mesh (they occlude), the albedos and albedo maps when it
// has bounces, the lighting (environment texels, rotation, scale; lights) only for
// lighting-dependent quantities (irradiance, radiance), and the settings. Re-rendering with a
// rotated environment therefore re-bakes nothing for PRT and only lightmaps and probes for a
// changed light.
//
// Implementation notes:
//   * Distant lighting for the SH-lit representations: project_sh(environment, n) plus
//     project_sh(light, n, c) for every light (c the centre of the scene's bounding box: sphere
//     lights are treated as distant from there), then rotated by lighting_rotation. White
//     Lambertian shading of SH radiance L is sum a_l L_lm y_lm(n) (core/clamped_cosine.hpp).
//     The windowed variant applies Sloan's ringing-minimising window (sh::ringing_window with
//     the clamped-cosine kernel and target 0: the smallest window that makes the irradiance
//     non-negative everywhere; no window when it already is).
//   * Bakes: ao and bent read one bake (ao | bent, no bounces); prt-* the transfer (prt_bands,
//     bounces); lightmap-* the irradiance in their basis (bounces, lighting-dependent);
//     volume the radiance at the probes (3 bands, bounces, lighting-dependent). Vertex points
//     use the mesh normals (area-weighted face normals without them), point id
//     (mesh << 32) + vertex; texel points come from layout_lightmap() (id base mesh << 32),
//     with the tangent of render::Hit where the mesh has no tangents (the triangle's dp/du and
//     its handedness), so the tangent frame of the baked irradiance is the one a camera hit
//     reconstructs. Requests with equal settings share one Baker (one Embree build).
//   * Texel data is laid into a lightmap per mesh at float precision, gutters dilated by 4
//     texels (dilate()), read bilinearly at Hit::uv with clamp-to-edge; vertex data is
//     interpolated with the hit's barycentrics. Lightmaps are baked on the front side of each
//     surface (the side of its normal); a back-face hit reads the front's data.
//   * Camera rays: one per pixel centre (spp = 1) or spp jittered ones, the jitter a hash of
//     (seed, pixel, sample); footprint = t * pixel_angle() (the obliquity is ignored).
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "../basis/registry.hpp"
#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../ops/compression.hpp"
#include "../ops/lxh_table.hpp"
#include "../ops/normal_basis.hpp"
#include "../ops/sh_rotation.hpp"
#include "../ops/sh_windowing.hpp"
#include "../param/cubemap.hpp"
#include "bake.hpp"
#include "camera.hpp"
#include "detail/rt_math.hpp"
#include "image.hpp"
#include "lighting.hpp"
#include "lightmap.hpp"
#include "probe_grid.hpp"
#include "scene.hpp"
#include "specular.hpp"

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
                                                "specular-aliased",
                                                "lxh-unc3",
                                                "lxh-unc4",
                                                "lxh-unc6",
                                                "lxh-pca4",
                                                "lxh-pca8",
                                                "lxh-pca12",
                                                "lxh-pca16",
                                                "lxh-pca24",
                                                "prt-normalmap",
                                                "prt-normalmap-svd4",
                                                "prt-normalmap-svd6",
                                                "prt-ratio",
                                                "prt-cpca-4-2",
                                                "prt-cpca-8-4",
                                                "prt-cpca-16-4"};
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
    /// lxh-*: texels per cube-map face edge of the L x H tables, and the SH bands of the
    /// lighting in them (0: as many as the visibility has).
    int lxh_table_size = 32;
    int lxh_lighting_bands = 0;
};

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
    w.u32(s.quantities);
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
    s.quantities = r.u32();
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
    h.str("sphbasis bake key 1");
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

struct RepresentationStats {
    std::string name;
    double bake_seconds = 0;  // of the bakes it reads (shared bakes counted for each reader)
    std::uint64_t bake_rays = 0;
    bool cached = false;                // every bake it reads came from the cache
    std::string element;                // "texel", "vertex", "probe" or "none"
    std::size_t bytes_per_element = 0;  // at the stored precision (float)
    std::size_t elements = 0;
    /// Seconds spent after the bakes on what the representation reads: L x H tables,
    /// compression, per-basis-vector tables (shared work counted for each reader).
    double build_seconds = 0;
    std::string cannot_show;  // e.g. "no shadows; no interreflection"
};

/// Renders the representations of a scene.
class Representations {
  public:
    /// Borrows `scene` (the arrays) and `rt` (built from scene.meshes). Throws
    /// std::invalid_argument for an unknown name (the message lists representation_names()),
    /// a duplicate, or invalid settings.
    Representations(const SceneDesc& scene, const Scene& rt, const RepresentationSettings& settings,
                    const std::vector<std::string>& names)
        : scene_(scene), rt_(rt), settings_(settings), names_(names) {
        validate_input();
        for (const std::string& n : names_) reps_.push_back(parse(n));
        plan();
        if (needs_sh_) prepare_lighting();
        for (const Rep& r : reps_)
            if (r.kind == Kind::specular_toksvig || r.kind == Kind::specular_aliased) {
                if (!spec_) spec_ = std::make_unique<SpecularShading>(scene_);
            }
    }
    /// The distinct bakes the requested representations read (the plan), before prepare().
    const std::vector<BakeRequest>& bakes() const noexcept { return requests_; }
    /// Runs or loads every planned bake (cache may be null). progress(done, total) in points.
    /// Each distinct request is baked once (or loaded under bake_key()); fresh bakes are
    /// stored in the cache. The counters below count this call only.
    void prepare(BakeCache* cache,
                 const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
        bakes_run_ = bakes_loaded_ = 0;
        data_.assign(requests_.size(), BakeData{});
        std::vector<std::uint64_t> keys(requests_.size());
        std::vector<std::size_t> todo;
        for (std::size_t i = 0; i < requests_.size(); ++i) {
            keys[i] = bake_key(scene_, requests_[i]);
            BakeData d;
            if (cache && cache->load(keys[i], d) && consistent(d, requests_[i])) {
                d.from_cache = true;
                data_[i] = std::move(d);
                ++bakes_loaded_;
            } else {
                todo.push_back(i);
            }
        }
        std::vector<std::vector<BakePoint>> points(todo.size());
        std::vector<LightmapLayout> layouts(todo.size());
        std::uint64_t total = 0;
        for (std::size_t k = 0; k < todo.size(); ++k) {
            points[k] = make_points(requests_[todo[k]], layouts[k]);
            total += points[k].size();
        }
        std::map<std::vector<std::uint8_t>, std::unique_ptr<Baker>> bakers;
        std::atomic<std::uint64_t> done{0};
        std::mutex progress_mutex;
        for (std::size_t k = 0; k < todo.size(); ++k) {
            const std::size_t i = todo[k];
            const BakeRequest& q = requests_[i];
            const auto t0 = std::chrono::steady_clock::now();
            std::unique_ptr<Baker>& baker = bakers[repr_detail::settings_bytes(q.settings)];
            if (!baker) baker = std::make_unique<Baker>(scene_, q.settings);
            const std::uint64_t rays0 = baker->rays_traced();
            BakeData& d = data_[i];
            d.request = q;
            d.results = baker->bake(points[k], [&](std::size_t c) {
                const std::uint64_t now = done.fetch_add(c) + c;
                if (progress) {
                    std::lock_guard<std::mutex> lock(progress_mutex);
                    progress(now, total);
                }
            });
            d.plan = baker->plan();
            d.rays = baker->rays_traced() - rays0;
            d.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            d.layout = std::move(layouts[k]);
            d.from_cache = false;
            if (cache) cache->store(keys[i], d);
            ++bakes_run_;
        }
        fields_.clear();
        for (const BakeData& d : data_) fields_.push_back(make_field(d));
        build_derived();
        build_svd_fields();
        build_cpca();
        prepared_ = true;
    }
    /// L x H tables and visibility compressions built by prepare() (only those a requested
    /// lxh-* reads; each distinct one once).
    std::size_t lxh_tables_built() const noexcept { return lxh_.size(); }
    std::size_t compressions_built() const noexcept { return pcas_.size(); }
    /// The numerical rank of the visibility that lxh-pca representation `index` compressed
    /// (after prepare()); 0 for other representations.
    int compressed_rank(std::size_t index) const {
        const Rep& r = rep(index, "render::Representations::compressed_rank");
        return r.model >= 0 ? pcas_[std::size_t(r.model)].rank : 0;
    }
    /// Bakes run and bakes loaded from the cache by prepare().
    std::size_t bakes_run() const noexcept { return bakes_run_; }
    std::size_t bakes_loaded() const noexcept { return bakes_loaded_; }
    /// The data of bake i (bakes()[i]) after prepare().
    const BakeData& bake_data(std::size_t i) const {
        if (!prepared_ || i >= data_.size())
            sphbasis::detail::throw_invalid("render::Representations::bake_data",
                                            "a bake index below " + std::to_string(data_.size()) +
                                                " after prepare(), got " + std::to_string(i));
        return data_[i];
    }

    /// The outgoing radiance toward the camera at a hit for representation `index` (into the
    /// names given), view = unit direction from the hit to the eye, footprint = the pixel's
    /// world-space width at the hit (for the normal map's mip level). Throws
    /// std::invalid_argument for a bad index, std::runtime_error before prepare() for a
    /// representation that reads bakes. An invalid hit gives 0.
    RGB shade(std::size_t index, const Hit& hit, const vec3<double>& view, double footprint) const {
        const Rep& r = rep(index, "render::Representations::shade");
        if (!hit.valid) return {0, 0, 0};
        switch (r.kind) {
            case Kind::irradiance:
                return sh_shade(irr_, Scene::normal_mapped(hit), hit.albedo);
            case Kind::windowed:
                return sh_shade(irr_windowed_, Scene::normal_mapped(hit), hit.albedo);
            case Kind::ao:
            case Kind::bent: {
                const int b = r.mesh_bake[hit.mesh];
                if (b < 0) return sh_shade(irr_, Scene::normal_mapped(hit), hit.albedo);
                double v[4];
                lookup(fields_[std::size_t(b)], hit, v);
                const vec3<double> n =
                    r.kind == Kind::ao
                        ? Scene::normal_mapped(hit)
                        : detail::rt::normalized({v[1], v[2], v[3]}, hit.shading_normal);
                const RGB c = sh_shade(irr_, n, hit.albedo);
                const double ao = std::clamp(v[0], 0.0, 1.0);
                return {ao * c[0], ao * c[1], ao * c[2]};
            }
            case Kind::prt_vertex:
            case Kind::prt_texel: {
                const int b = r.mesh_bake[hit.mesh];
                if (b < 0) return {0, 0, 0};
                std::array<double, 3 * 64> t;
                lookup(fields_[std::size_t(b)], hit, t.data());
                const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double s = 0;
                    for (std::size_t k = 0; k < n; ++k) s += t[c * n + k] * prt_light_[c][k];
                    out[c] = hit.albedo[c] * s;
                }
                return out;
            }
            case Kind::lightmap: {
                const int b = r.mesh_bake[hit.mesh];
                if (b < 0) return sh_shade(irr_, Scene::normal_mapped(hit), hit.albedo);
                std::array<double, 3 * 16> e;
                lookup(fields_[std::size_t(b)], hit, e.data());
                using namespace detail::rt;
                const V3 nm = Scene::normal_mapped(hit);
                const V3 ns = hit.shading_normal, t = hit.tangent;
                const V3 bt = cross(ns, t) * hit.bitangent_sign;
                // The basis lives on the tangent hemisphere: a mapped normal below it (a steep
                // map) is read at the horizon.
                V3 local{dot(nm, t), dot(nm, bt), std::max(dot(nm, ns), 0.0)};
                local = normalized(local, {0, 0, 1});
                std::array<double, 16> y;
                r.basis->eval_d(r.coeffs, local.x, local.y, local.z, y.data());
                const std::size_t n = std::size_t(r.coeffs);
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double s = 0;
                    for (std::size_t k = 0; k < n; ++k) s += e[c * n + k] * y[k];
                    out[c] = hit.albedo[c] * s * constants::inv_pi;
                }
                return out;
            }
            case Kind::volume: {
                const Field& f = fields_[std::size_t(r.probe_bake)];
                std::array<double, 27> v;
                f.grid.interpolate_valid(f.probe_values.data(), 27, f.inside.data(), hit.position,
                                         v.data());
                std::array<std::array<double, 9>, 3> cc;
                for (std::size_t c = 0; c < 3; ++c)
                    for (std::size_t k = 0; k < 9; ++k) cc[c][k] = cosine9_[k] * v[c * 9 + k];
                return sh_shade(cc, Scene::normal_mapped(hit), hit.albedo);
            }
            case Kind::lxh_unc: {
                const int b = r.mesh_bake[hit.mesh];
                if (b < 0) return {0, 0, 0};
                std::array<double, 64> v;
                lookup(fields_[std::size_t(b)], hit, v.data());
                const LxhTable<LxhParam>& tab = *lxh_[std::size_t(r.table)].table;
                const vec3<double> n = Scene::normal_mapped(hit);
                std::array<float, 3 * 64> t;
                tab.lookup(float(n.x), float(n.y), float(n.z), t.data());
                const std::size_t kk = std::size_t(r.vis_bands * r.vis_bands);
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double e = 0;
                    for (std::size_t k = 0; k < kk; ++k) e += v[k] * double(t[3 * k + c]);
                    out[c] = hit.albedo[c] * e * constants::inv_pi;
                }
                return out;
            }
            case Kind::lxh_pca: {
                const PcaBuilt& pb = pcas_[std::size_t(r.model)];
                const int f = pb.mesh_field[hit.mesh];
                if (f < 0) return {0, 0, 0};
                std::array<double, 64> w;
                lookup(fields_[std::size_t(f)], hit, w.data());
                const LxhParam& param = lxh_[std::size_t(r.table)].table->param;
                const vec3<double> n = Scene::normal_mapped(hit);
                const std::size_t m = std::size_t(r.vectors);
                std::array<float, 3 * 65> t;
                param::lookup(param, pb.tables.data(), 3 * (m + 1), float(n.x), float(n.y),
                              float(n.z), t.data());
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double e = t[c];
                    for (std::size_t j = 0; j < m; ++j) e += w[j] * double(t[3 * (j + 1) + c]);
                    out[c] = hit.albedo[c] * e * constants::inv_pi;
                }
                return out;
            }
            case Kind::prt_ratio: {
                const int b = r.mesh_bake[hit.mesh];
                if (b < 0) return {0, 0, 0};
                std::array<double, 3 * 64> t;
                lookup(fields_[std::size_t(b)], hit, t.data());
                const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
                const RGB u0 = sh_shade(irr_, hit.shading_normal, {1, 1, 1});
                const RGB um = sh_shade(irr_, Scene::normal_mapped(hit), hit.albedo);
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double sh = 0;
                    for (std::size_t k = 0; k < n; ++k) sh += t[c * n + k] * prt_light_[c][k];
                    out[c] = u0[c] > 1e-12 ? std::max(sh, 0.0) / u0[c] * um[c] : 0.0;
                }
                return out;
            }
            case Kind::prt_normalmap:
                return r.svd_vectors > 0 ? shade_svd(r, hit) : shade_normalmap(r, hit);
            case Kind::prt_cpca: {
                const int fi = r.mesh_field[hit.mesh];
                if (fi < 0) return {0, 0, 0};
                std::array<double, 65> w;
                lookup_nearest(fields_[std::size_t(fi)], hit, w.data());
                const std::size_t m = std::size_t(r.vectors);
                const std::size_t cl = std::size_t(std::clamp(w[0], 0.0, double(r.clusters - 1)));
                const double* e = r.cpca_exit.data() + cl * (m + 1) * 3;
                RGB out{0, 0, 0};
                for (std::size_t c = 0; c < 3; ++c) {
                    double s = e[c];
                    for (std::size_t j = 0; j < m; ++j) s += w[j + 1] * e[3 * (j + 1) + c];
                    out[c] = hit.albedo[c] * s;
                }
                return out;
            }
            case Kind::specular_toksvig:
                return spec_->shade(SpecularShading::Mode::toksvig, hit, view, footprint);
            case Kind::specular_aliased:
                return spec_->shade(SpecularShading::Mode::aliased, hit, view, footprint);
        }
        return {0, 0, 0};
    }
    /// One image from render::ImageLoop (image_loop.hpp): spp samples per pixel at the loop's
    /// positions for settings.seed (spp = 1: the pixel centre; otherwise the same positions as
    /// every image of that seed and count, the path tracer's included), a box filter; each
    /// sample reads normal maps at the whole pixel's footprint. Escaped rays show the (rotated)
    /// environment like the ground truth. Multithreaded by 16 x 16 tiles; deterministic.
    /// Throws std::invalid_argument for a bad index, camera or spp outside [1, 2^20].
    Image render(std::size_t index, const Camera& camera, int spp = 1) const {
        rep(index, "render::Representations::render");
        sphbasis::detail::check_range("render::Representations::render", "spp", spp, 1, 1 << 20);
        ImageLoopSettings ls;
        ls.seed = settings_.seed;
        ls.spp = spp;
        ls.hits = true;
        ImageLoop loop(rt_, camera, ls);
        const double angle = loop.pinhole().pixel_angle();
        Film film(camera.width, camera.height, false);
        loop.run(0, spp, {&film}, [&](const CameraBatch& b, std::size_t, RGB* out) {
            for (std::size_t k = 0; k < b.n; ++k) {
                const Hit& h = b.hits[k];
                const vec3<double>& d = b.directions[k];
                out[k] = h.valid ? shade(index, h, {-d.x, -d.y, -d.z}, h.t * angle) : background(d);
            }
        });
        return film.mean();
    }
    /// The radiance an escaped camera ray shows: the environment at R^T d (R the render-time
    /// lighting rotation); analytic lights are not visible to camera rays.
    RGB background(const vec3<double>& d) const noexcept {
        const Mat3<double>& R = settings_.lighting_rotation;
        const vec3<double> m{R[0] * d.x + R[3] * d.y + R[6] * d.z,
                             R[1] * d.x + R[4] * d.y + R[7] * d.z,
                             R[2] * d.x + R[5] * d.y + R[8] * d.z};
        return scene_.environment.radiance(m);
    }
    RepresentationStats stats(std::size_t index) const {
        const Rep& r = rep(index, "render::Representations::stats", false);
        RepresentationStats s;
        s.name = r.name;
        s.cannot_show = r.cannot_show;
        std::vector<int> used = r.mesh_bake;
        if (r.probe_bake >= 0) used.push_back(r.probe_bake);
        bool any = false, all_cached = true;
        std::vector<char> seen(requests_.size(), 0);
        for (int b : used) {
            if (b < 0 || seen[std::size_t(b)]) continue;
            seen[std::size_t(b)] = 1;
            any = true;
            if (!prepared_) continue;
            const BakeData& d = data_[std::size_t(b)];
            s.bake_seconds += d.seconds;
            s.bake_rays += d.rays;
            all_cached = all_cached && d.from_cache;
            s.elements += d.results.size();
        }
        s.cached = prepared_ && any && all_cached;
        if (prepared_ && r.table >= 0) s.build_seconds += lxh_[std::size_t(r.table)].seconds;
        if (prepared_ && r.model >= 0) s.build_seconds += pcas_[std::size_t(r.model)].seconds;
        if (prepared_) s.build_seconds += r.build_seconds;
        s.element = r.element;
        s.bytes_per_element = r.bytes_per_element;
        if (r.kind == Kind::prt_vertex || r.kind == Kind::prt_texel || r.kind == Kind::prt_ratio) {
            bool rgb = false;
            if (prepared_)
                for (int b : used)
                    if (b >= 0)
                        for (const PointResult& p : data_[std::size_t(b)].results)
                            rgb = rgb || p.transfer_rgb;
            s.bytes_per_element = (rgb ? 3 : 1) * std::size_t(settings_.prt_bands) *
                                  std::size_t(settings_.prt_bands) * sizeof(float);
        }
        return s;
    }
    const std::vector<std::string>& names() const noexcept { return names_; }
    /// The bakes representation `index` reads: indices into bakes(), ascending, no repeats.
    std::vector<std::size_t> reads(std::size_t index) const {
        return reads_of(rep(index, "render::Representations::reads", false));
    }

    /// Whether `name` is a representation this class builds: one of representation_names(), or
    /// a member of a family beyond the listed ones (lxh-pcaM, 1 <= M <= 36; prt-cpca-C-M,
    /// 1 <= C <= 4096, 1 <= M <= 64). For checking names before any scene is loaded.
    static bool known_name(const std::string& name) {
        const auto& all = representation_names();
        return std::find(all.begin(), all.end(), name) != all.end() || family_member(name);
    }

  private:
    enum class Kind {
        irradiance,
        windowed,
        ao,
        bent,
        prt_vertex,
        prt_texel,
        lightmap,
        volume,
        specular_toksvig,
        specular_aliased,
        lxh_unc,
        lxh_pca,
        prt_ratio,
        prt_normalmap,
        prt_cpca
    };
    struct Rep {
        std::string name;
        Kind kind = Kind::irradiance;
        const BasisInfo* basis = nullptr;
        int coeffs = 0;
        std::vector<int> mesh_bake;  // per mesh: index into requests_, -1: none (fallback)
        int probe_bake = -1;
        bool reads_bakes = false;
        std::string element = "none", cannot_show;
        std::size_t bytes_per_element = 0;
        int vis_bands = 0, vectors = 0;  // lxh-*: visibility bands, PCA vectors
        int table = -1;                  // lxh-*: index into lxh_ (after prepare())
        int model = -1;                  // lxh-pca*: index into pcas_ (after prepare())
        int svd_vectors = 0;             // prt-normalmap-svd*: normal-basis functions kept
        int clusters = 0;                // prt-cpca-C-M: C (vectors: M)
        std::vector<double> cpca_exit;   // prt-cpca: per cluster, (M + 1) x 3 exit values
        double build_seconds = 0;        // prt-normalmap-svd*: projecting the bakes
        std::vector<int> mesh_field;     // prt-normalmap-svd*: per mesh, index into fields_
    };
    /// Baked values laid out for lookups at float precision (probes: double).
    struct Field {
        BakeRequest::Where where = BakeRequest::Where::vertex;
        int channels = 0, width = 0, height = 0;
        std::vector<float> data;  // vertex: vertex_count x channels; texel: width x height x ch
        std::vector<double> probe_values;  // probes x 27 (R, G, B x 9)
        std::vector<std::uint8_t> inside;
        ProbeGrid grid;
    };
    static constexpr int gutter = 4;  // texels dilated around each chart

    /// prt-normalmap: L_in = M l (3 bands, world frame) per channel, shaded at the mapped
    /// normal: e(n) = y(n)^T C M l (the tangent rotation R is the identity in world frame).
    RGB shade_normalmap(const Rep& r, const Hit& hit) const {
        const int b = r.mesh_bake[hit.mesh];
        if (b < 0) return {0, 0, 0};
        const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
        std::array<double, 27 * 64> m;
        lookup(fields_[std::size_t(b)], hit, m.data());
        const vec3<double> nm = Scene::normal_mapped(hit);
        double y[9];
        sh::eval_unit(3, nm.x, nm.y, nm.z, y);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = 0;
            for (std::size_t i = 0; i < 9; ++i) {
                const double* row = m.data() + c * 9 * n + i * n;
                double li = 0;
                for (std::size_t k = 0; k < n; ++k) li += row[k] * prt_light_[c][k];
                e += cosine9_[i] * li * y[i];
            }
            out[c] = hit.albedo[c] * e;
        }
        return out;
    }
    /// The tangent frame a hit reads a prt-normalmap-svd field in: the texel's (tangent,
    /// bitangent, normal) as the lightmaps, Frame(normal) for per-vertex fields.
    static Frame<double> svd_frame(const Field& f, const Hit& hit) {
        using namespace detail::rt;
        const V3 ns = hit.shading_normal;
        if (f.where == BakeRequest::Where::vertex || !(length(hit.tangent) > 0.5))
            return Frame<double>(ns);
        return Frame<double>(hit.tangent, cross(ns, hit.tangent) * hit.bitangent_sign, ns);
    }
    /// prt-normalmap-svdM: per texel G = V_M^T R M (M x N^2 per channel), e(n) =
    /// (a(n)^T V_M) (G l) with a(n) = pi a_l y_lm(n) in the tangent frame.
    RGB shade_svd(const Rep& r, const Hit& hit) const {
        const int fi = r.mesh_field[hit.mesh];
        if (fi < 0) return {0, 0, 0};
        const Field& f = fields_[std::size_t(fi)];
        const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
        const std::size_t mv = std::size_t(r.svd_vectors);
        std::array<double, 3 * 6 * 64> g;
        lookup(f, hit, g.data());
        const Frame<double> fr = svd_frame(f, hit);
        using namespace detail::rt;
        const V3 nm = Scene::normal_mapped(hit);
        V3 u{dot(nm, fr.s), dot(nm, fr.t), std::max(dot(nm, fr.n), 0.0)};
        u = normalized(u, {0, 0, 1});
        double y[9], p[9];
        sh::eval_unit(3, u.x, u.y, u.z, y);
        for (std::size_t k = 0; k < mv; ++k) {
            p[k] = 0;
            for (std::size_t i = 0; i < 9; ++i)
                p[k] += constants::pi * cosine9_[i] * y[i] *
                        normal_v_(Eigen::Index(i), Eigen::Index(k));
        }
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double e = 0;
            for (std::size_t k = 0; k < mv; ++k) {
                const double* row = g.data() + (c * mv + k) * n;
                double h = 0;
                for (std::size_t j = 0; j < n; ++j) h += row[j] * prt_light_[c][j];
                e += p[k] * h;
            }
            out[c] = hit.albedo[c] * e * constants::inv_pi;
        }
        return out;
    }
    /// The fields of each prt-normalmap-svd*: G = V_M^T R M per point, R the SH rotation of
    /// 3 bands from world to the point's tangent frame (by least squares on 25 directions:
    /// exact for 3-band functions, mirrored frames included).
    void build_svd_fields() {
        bool any = false;
        for (const Rep& r : reps_) any = any || (r.kind == Kind::prt_normalmap && r.svd_vectors);
        if (!any) return;
        for (Rep& r : reps_) r.build_seconds = 0;
        NormalBasisSettings nbs;
        nbs.bands = 3;
        nbs.clamped = false;
        nbs.weighting = NormalWeighting::cosine;
        normal_v_ = normal_basis(nbs).v;
        constexpr int S = 25;
        std::array<vec3<double>, S> u;
        Eigen::MatrixXd yl(S, 9);
        for (int s = 0; s < S; ++s) {
            const double z = 1 - (2 * s + 1) / double(S), rr = std::sqrt(1 - z * z);
            const double ph = 2.399963229728653 * s;  // the golden angle
            u[std::size_t(s)] = {rr * std::cos(ph), rr * std::sin(ph), z};
            double y[9];
            sh::eval_unit(3, u[std::size_t(s)].x, u[std::size_t(s)].y, u[std::size_t(s)].z, y);
            for (int i = 0; i < 9; ++i) yl(s, i) = y[i];
        }
        const Eigen::MatrixXd pinv = (yl.transpose() * yl).inverse() * yl.transpose();
        const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
        for (Rep& r : reps_) {
            if (r.kind != Kind::prt_normalmap || r.svd_vectors == 0) continue;
            const std::size_t mv = std::size_t(r.svd_vectors);
            const Eigen::MatrixXd vt = normal_v_.leftCols(Eigen::Index(mv)).transpose();
            r.mesh_field.assign(scene_.meshes.size(), -1);
            for (std::size_t mesh = 0; mesh < scene_.meshes.size(); ++mesh) {
                const int b = r.mesh_bake[mesh];
                if (b < 0) continue;
                const BakeData& d = data_[std::size_t(b)];
                std::vector<double> vn;
                if (d.request.where == BakeRequest::Where::vertex)
                    vn = vertex_normals(scene_.meshes[mesh]);
                const auto t0 = std::chrono::steady_clock::now();
                fields_.push_back(make_field(d, int(3 * mv * n), [&](std::size_t i, float* out) {
                    using namespace detail::rt;
                    Frame<double> fr;
                    if (d.request.where == BakeRequest::Where::vertex) {
                        fr = Frame<double>(
                            normalized(V3{vn[3 * i], vn[3 * i + 1], vn[3 * i + 2]}, {0, 0, 1}));
                    } else {
                        const BakePoint& bp = d.layout.samples[i].point;
                        const V3 nn = normalized(bp.n, {0, 0, 1});
                        fr = length(bp.tangent) > 0.5
                                 ? Frame<double>(bp.tangent,
                                                 cross(nn, bp.tangent) * bp.bitangent_sign, nn)
                                 : Frame<double>(nn);
                    }
                    Eigen::MatrixXd yw(S, 9);
                    for (int s2 = 0; s2 < S; ++s2) {
                        const vec3<double>& q = u[std::size_t(s2)];
                        const V3 w = fr.s * q.x + fr.t * q.y + fr.n * q.z;
                        double y[9];
                        sh::eval_unit(3, w.x, w.y, w.z, y);
                        for (int k = 0; k < 9; ++k) yw(s2, k) = y[k];
                    }
                    const Eigen::MatrixXd vr = vt * (pinv * yw);  // mv x 9
                    const PointResult& pr = d.results[i];
                    for (std::size_t c = 0; c < 3; ++c)
                        for (std::size_t k = 0; k < mv; ++k)
                            for (std::size_t j = 0; j < n; ++j) {
                                double v = 0;
                                for (std::size_t q = 0; q < 9; ++q)
                                    if (q * n + j < pr.transfer_matrix[c].size())
                                        v += vr(Eigen::Index(k), Eigen::Index(q)) *
                                             pr.transfer_matrix[c][q * n + j];
                                out[(c * mv + k) * n + j] = float(v);
                            }
                }));
                r.mesh_field[mesh] = int(fields_.size() - 1);
                r.build_seconds +=
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            }
        }
    }

    /// The field value at the nearest texel, or the vertex of the largest barycentric weight.
    static void lookup_nearest(const Field& f, const Hit& h, double* out) noexcept {
        const std::size_t ch = std::size_t(f.channels);
        const float* p = nullptr;
        if (f.where == BakeRequest::Where::vertex) {
            const double w[3] = {1 - h.u - h.v, h.u, h.v};
            const int k = w[0] >= w[1] && w[0] >= w[2] ? 0 : (w[1] >= w[2] ? 1 : 2);
            const std::size_t v = h.vertices[std::size_t(k)];
            if ((v + 1) * ch <= f.data.size()) p = f.data.data() + v * ch;
        } else {
            double x = h.uv[0] * f.width, y = (1 - h.uv[1]) * f.height;
            if (!std::isfinite(x)) x = 0;
            if (!std::isfinite(y)) y = 0;
            const int xi = std::clamp(int(std::floor(x)), 0, f.width - 1);
            const int yi = std::clamp(int(std::floor(y)), 0, f.height - 1);
            p = f.data.data() + (std::size_t(yi) * std::size_t(f.width) + std::size_t(xi)) * ch;
        }
        for (std::size_t c = 0; c < ch; ++c) out[c] = p ? double(p[c]) : 0.0;
    }
    /// prt-cpca-C-M: iterative CPCA (compress::cpca_iterative) of the transfer of every point
    /// read (3 N^2 numbers, RGB), fields of (cluster, M weights), and the per-cluster exit
    /// values mu_c . l and b_cj . l for the current lighting (the course's CPCA rendering).
    void build_cpca() {
        const std::size_t n = std::size_t(settings_.prt_bands * settings_.prt_bands);
        for (Rep& r : reps_) {
            if (r.kind != Kind::prt_cpca) continue;
            const auto t0 = std::chrono::steady_clock::now();
            std::vector<std::size_t> offset(data_.size(), 0);
            std::size_t rows = 0;
            for (std::size_t b : reads_of(r)) {
                offset[b] = rows;
                rows += data_[b].results.size();
            }
            compress::MatrixX<double> x(static_cast<Eigen::Index>(rows),
                                        static_cast<Eigen::Index>(3 * n));
            for (std::size_t b : reads_of(r))
                for (std::size_t i = 0; i < data_[b].results.size(); ++i)
                    for (std::size_t c = 0; c < 3; ++c)
                        for (std::size_t k = 0; k < n; ++k) {
                            const auto& t = data_[b].results[i].transfer[c];
                            x(Eigen::Index(offset[b] + i), Eigen::Index(c * n + k)) =
                                k < t.size() ? t[k] : 0.0;
                        }
            compress::CpcaSettings cs;
            cs.clusters = r.clusters;
            cs.vectors = r.vectors;
            cs.seed = settings_.seed + 1;
            compress::Cpca<double> model;
            try {
                model = compress::cpca_iterative(x, cs);
            } catch (const std::invalid_argument& e) {
                sphbasis::detail::throw_invalid(
                    "render::Representations::prepare",
                    "clusters and vectors the baked transfer supports for '" + r.name + "' (" +
                        e.what() + ")");
            }
            const std::size_t m = std::size_t(r.vectors);
            r.mesh_field.assign(scene_.meshes.size(), -1);
            for (std::size_t mesh = 0; mesh < scene_.meshes.size(); ++mesh) {
                const int b = r.mesh_bake[mesh];
                if (b < 0) continue;
                const std::size_t off = offset[std::size_t(b)];
                fields_.push_back(
                    make_field(data_[std::size_t(b)], int(m + 1), [&](std::size_t i, float* out) {
                        out[0] = float(model.cluster[off + i]);
                        for (std::size_t j = 0; j < m; ++j)
                            out[j + 1] =
                                float(model.weights(Eigen::Index(off + i), Eigen::Index(j)));
                    }));
                r.mesh_field[mesh] = int(fields_.size() - 1);
            }
            // Exit values: the lighting matrix (3 N^2 x 3), channel c's lighting in rows c N^2..
            compress::MatrixX<double> light =
                compress::MatrixX<double>::Zero(Eigen::Index(3 * n), 3);
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < n; ++k)
                    light(Eigen::Index(c * n + k), Eigen::Index(c)) = prt_light_[c][k];
            const compress::ExitValues<double> ev = compress::exit_values(model, light);
            r.cpca_exit.assign(std::size_t(r.clusters) * (m + 1) * 3, 0.0);
            for (std::size_t cl = 0; cl < std::size_t(model.clusters()); ++cl)
                for (std::size_t c = 0; c < 3; ++c) {
                    double* e = r.cpca_exit.data() + cl * (m + 1) * 3;
                    e[c] = ev.mean(Eigen::Index(cl), Eigen::Index(c));
                    for (std::size_t j = 0; j < m; ++j)
                        e[3 * (j + 1) + c] = ev.basis[cl](Eigen::Index(j), Eigen::Index(c));
                }
            r.build_seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        }
    }

    using LxhParam = param::CubeMap<float>;
    /// An L x H table (visibility bands, lighting bands), shared by the lxh-* that read it.
    struct LxhBuilt {
        int vis_bands = 0, lighting_bands = 0;
        std::shared_ptr<const LxhTable<LxhParam>> table;
        double seconds = 0;
    };
    /// A PCA of the visibility of one lxh-pca*: per-mesh weight fields and, per texel of the
    /// L x H table's cube map, the RGB integrals of L, H and the mean and each basis vector.
    struct PcaBuilt {
        std::vector<int> mesh_field;  // per mesh: index into fields_, -1: none
        std::vector<float> tables;    // texel x (M + 1) x 3: mean, then basis vector j
        int rank = 0;
        double seconds = 0;
    };

    /// The SH of the distant lighting on `bands` bands, rotated by lighting_rotation,
    /// interleaved (coefficient i, channel c at [3 i + c]) as lxh_matrix() reads it.
    std::vector<double> lxh_lighting(int bands) const {
        std::vector<RGB> L = project_sh(scene_.environment, bands);
        const vec3<double> centre{0.5 * (rt_.bounds_min().x + rt_.bounds_max().x),
                                  0.5 * (rt_.bounds_min().y + rt_.bounds_max().y),
                                  0.5 * (rt_.bounds_min().z + rt_.bounds_max().z)};
        const std::size_t n = std::size_t(bands) * std::size_t(bands);
        for (const Light& l : scene_.lights) {
            const std::vector<RGB> s = project_sh(l, bands, centre);
            for (std::size_t k = 0; k < n; ++k)
                for (std::size_t c = 0; c < 3; ++c) L[k][c] += s[k][c];
        }
        std::vector<double> out(3 * n), ch(n), rot(n);
        for (std::size_t c = 0; c < 3; ++c) {
            for (std::size_t k = 0; k < n; ++k) ch[k] = L[k][c];
            sh::rotate(bands, settings_.lighting_rotation, ch, rot);
            for (std::size_t k = 0; k < n; ++k) out[3 * k + c] = rot[k];
        }
        return out;
    }

    /// After the bakes: the L x H tables and compressions the requested lxh-* read, each
    /// built once.
    void build_derived() {
        lxh_.clear();
        pcas_.clear();
        for (Rep& r : reps_) {
            if (r.kind != Kind::lxh_unc && r.kind != Kind::lxh_pca) continue;
            const int nl =
                settings_.lxh_lighting_bands > 0 ? settings_.lxh_lighting_bands : r.vis_bands;
            r.table = -1;
            for (std::size_t i = 0; i < lxh_.size(); ++i)
                if (lxh_[i].vis_bands == r.vis_bands && lxh_[i].lighting_bands == nl)
                    r.table = int(i);
            if (r.table < 0) {
                const auto t0 = std::chrono::steady_clock::now();
                const std::vector<double> L = lxh_lighting(nl);
                LxhBuilt b;
                b.vis_bands = r.vis_bands;
                b.lighting_bands = nl;
                const LxhParam p(settings_.lxh_table_size);
                b.table = std::make_shared<const LxhTable<LxhParam>>(build_lxh_table(
                    p, lxh_matrix(nl, L.data(), r.vis_bands), LxhConstruction::symmetric));
                b.seconds =
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                lxh_.push_back(std::move(b));
                r.table = int(lxh_.size() - 1);
            }
            if (r.kind == Kind::lxh_pca) {
                build_pca(r);
                r.model = int(pcas_.size() - 1);
            }
        }
    }

    /// PCA (mean + M vectors, compress::pca) of the visibility of every point r reads (one
    /// basis for all meshes), its weights as fields, and the per-vector RGB tables
    /// T_j(n) = b_j . (L x H)(n) (Iwanicki and Sloan, eq. 6).
    void build_pca(const Rep& r) {
        const auto t0 = std::chrono::steady_clock::now();
        const std::size_t kk = std::size_t(r.vis_bands * r.vis_bands);
        std::vector<std::size_t> offset(data_.size(), 0);
        std::size_t rows = 0;
        for (std::size_t b : reads_of(r)) {
            offset[b] = rows;
            rows += data_[b].results.size();
        }
        compress::MatrixX<double> x(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(kk));
        for (std::size_t b : reads_of(r))
            for (std::size_t i = 0; i < data_[b].results.size(); ++i) {
                const std::vector<double>& v = data_[b].results[i].visibility;
                for (std::size_t k = 0; k < kk; ++k)
                    x(Eigen::Index(offset[b] + i), Eigen::Index(k)) = k < v.size() ? v[k] : 0.0;
            }
        compress::Pca<double> model;
        try {
            model = compress::pca(x, r.vectors);
        } catch (const std::invalid_argument& e) {
            sphbasis::detail::throw_invalid("render::Representations::prepare",
                                            "no more PCA vectors for '" + r.name +
                                                "' than the baked visibility supports (" +
                                                e.what() + ")");
        }
        PcaBuilt pb;
        pb.rank = model.rank;
        pb.mesh_field.assign(scene_.meshes.size(), -1);
        const std::size_t m = std::size_t(r.vectors);
        for (std::size_t mesh = 0; mesh < scene_.meshes.size(); ++mesh) {
            const int b = r.mesh_bake[mesh];
            if (b < 0) continue;
            const std::size_t off = offset[std::size_t(b)];
            fields_.push_back(
                make_field(data_[std::size_t(b)], r.vectors, [&](std::size_t i, float* out) {
                    for (std::size_t j = 0; j < m; ++j)
                        out[j] = float(model.weights(Eigen::Index(off + i), Eigen::Index(j)));
                }));
            pb.mesh_field[mesh] = int(fields_.size() - 1);
        }
        const LxhTable<LxhParam>& tab = *lxh_[std::size_t(r.table)].table;
        const std::size_t texels = tab.param.texel_count(), e = 3 * kk, o = 3 * (m + 1);
        pb.tables.assign(texels * o, 0.f);
        for (std::size_t t = 0; t < texels; ++t) {
            const float* src = tab.data.data() + t * e;
            float* dst = pb.tables.data() + t * o;
            for (std::size_t c = 0; c < 3; ++c) {
                double s = 0;
                for (std::size_t k = 0; k < kk; ++k)
                    s += model.mean(Eigen::Index(k)) * double(src[3 * k + c]);
                dst[c] = float(s);
                for (std::size_t j = 0; j < m; ++j) {
                    double sj = 0;
                    for (std::size_t k = 0; k < kk; ++k)
                        sj +=
                            model.basis(Eigen::Index(k), Eigen::Index(j)) * double(src[3 * k + c]);
                    dst[3 * (j + 1) + c] = float(sj);
                }
            }
        }
        pb.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        pcas_.push_back(std::move(pb));
    }
    /// The distinct bakes r reads, ascending.
    static std::vector<std::size_t> reads_of(const Rep& r) {
        std::vector<std::size_t> out;
        for (int b : r.mesh_bake)
            if (b >= 0) out.push_back(std::size_t(b));
        if (r.probe_bake >= 0) out.push_back(std::size_t(r.probe_bake));
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }

    /// Representation `index`; with `ready`, also that its bakes are prepared.
    const Rep& rep(std::size_t index, const char* fn, bool ready = true) const {
        if (index >= reps_.size())
            sphbasis::detail::throw_invalid(fn, "a representation index below " +
                                                    std::to_string(reps_.size()) + ", got " +
                                                    std::to_string(index));
        const Rep& r = reps_[index];
        if (ready && r.reads_bakes && !prepared_)
            sphbasis::detail::throw_runtime(
                fn, "prepare() before rendering '" + r.name + "', got no bakes");
        return r;
    }

    void validate_input() {
        constexpr const char* fn = "render::Representations";
        sphbasis::detail::check_range(fn, "settings.rays", settings_.rays, 1, 1 << 20);
        sphbasis::detail::check_range(fn, "settings.bounces", settings_.bounces, 0, 64);
        sphbasis::detail::check_range(fn, "settings.prt_bands", settings_.prt_bands, 1, 8);
        sphbasis::detail::check_range(fn, "settings.lightmap_size", settings_.lightmap_size, 1,
                                      16384);
        sphbasis::detail::check_orthonormal(settings_.lighting_rotation, 1e-6, fn);
        sphbasis::detail::check_range(fn, "settings.lxh_table_size", settings_.lxh_table_size, 1,
                                      1024);
        sphbasis::detail::check_range(fn, "settings.lxh_lighting_bands",
                                      settings_.lxh_lighting_bands, 0, max_lxh_bands);
        if (settings_.has_probes) settings_.probes.validate();
        if (rt_.mesh_count() != scene_.meshes.size())
            sphbasis::detail::throw_invalid(
                fn, "a ray-tracing scene of the scene's " + std::to_string(scene_.meshes.size()) +
                        " meshes, got " + std::to_string(rt_.mesh_count()));
        validate(scene_.environment);
        for (const Light& l : scene_.lights) validate(l);
        std::string known;
        for (const std::string& n : representation_names())
            known += (known.empty() ? "" : ", ") + n;
        for (std::size_t i = 0; i < names_.size(); ++i) {
            const auto& all = representation_names();
            if (std::find(all.begin(), all.end(), names_[i]) == all.end() &&
                !family_member(names_[i]))
                sphbasis::detail::throw_invalid(
                    fn, "representations from: " + known +
                            " (and lxh-pcaM for 1 <= M <= 36); got unknown '" + names_[i] + "'");
            for (std::size_t j = 0; j < i; ++j)
                if (names_[j] == names_[i])
                    sphbasis::detail::throw_invalid(fn, "distinct representations (from: " + known +
                                                            "), got '" + names_[i] + "' twice");
        }
    }

    /// The decimal number after `prefix` in `name` (digits only, at most 4), else -1.
    static int number_after(const std::string& name, const std::string& prefix) {
        if (name.size() <= prefix.size() || name.size() > prefix.size() + 4 ||
            name.compare(0, prefix.size(), prefix) != 0)
            return -1;
        int v = 0;
        for (std::size_t i = prefix.size(); i < name.size(); ++i) {
            if (name[i] < '0' || name[i] > '9') return -1;
            v = 10 * v + (name[i] - '0');
        }
        return name[prefix.size()] == '0' ? -1 : v;
    }
    /// Names of a family beyond the listed ones: lxh-pcaM (1 <= M <= 36).
    static bool family_member(const std::string& name) {
        const int m = number_after(name, "lxh-pca");
        int c = 0, v = 0;
        return (m >= 1 && m <= lxh_pca_bands * lxh_pca_bands) || cpca_name(name, c, v);
    }
    /// prt-cpca-C-M: C clusters (1..4096) of M vectors (1..64).
    static bool cpca_name(const std::string& name, int& c, int& m) {
        const std::string pre = "prt-cpca-";
        if (name.compare(0, pre.size(), pre) != 0) return false;
        const std::size_t dash = name.find('-', pre.size());
        if (dash == std::string::npos) return false;
        c = number_after(name.substr(0, dash), pre);
        m = number_after(name.substr(dash), "-");
        return c >= 1 && c <= 4096 && m >= 1 && m <= 64;
    }
    static constexpr int lxh_pca_bands = 6;  // the visibility lxh-pca* compresses

    static bool has_uvs(const MeshView& m) noexcept {
        return m.uvs != nullptr && m.triangle_count > 0;
    }

    Rep parse(const std::string& name) {
        Rep r;
        r.name = name;
        const char* no_bounce = settings_.bounces > 0 ? "" : "; no interreflection";
        if (name == "irradiance-sh9") {
            r.kind = Kind::irradiance;
            r.cannot_show =
                "no shadows; no interreflection; lighting truncated to 3 SH bands (small lights "
                "blurred, ringing)";
        } else if (name == "irradiance-sh9-windowed") {
            r.kind = Kind::windowed;
            r.cannot_show =
                "no shadows; no interreflection; lighting truncated to 3 SH bands and windowed "
                "(no ringing, more blur)";
        } else if (name == "ao" || name == "bent") {
            r.kind = name == "ao" ? Kind::ao : Kind::bent;
            r.cannot_show = name == "ao"
                                ? "no directional shadows (occlusion ignores where the light is); "
                                  "no interreflection"
                                : "shadows only as one bent direction and the ao fraction; no "
                                  "interreflection; no normal-map detail";
            r.element = "texel";
            for (const MeshView& m : scene_.meshes)
                if (!has_uvs(m)) r.element = "vertex";
            r.bytes_per_element = (r.kind == Kind::ao ? 1 : 4) * sizeof(float);
        } else if (name == "prt-vertex" || name == "prt-texel") {
            r.kind = name == "prt-vertex" ? Kind::prt_vertex : Kind::prt_texel;
            r.cannot_show = "lighting above " + std::to_string(settings_.prt_bands) +
                            " SH bands (sharp shadows of small lights); no normal-map detail" +
                            no_bounce;
            if (r.kind == Kind::prt_vertex)
                r.cannot_show += "; shadows finer than the vertex spacing";
            r.element = r.kind == Kind::prt_vertex ? "vertex" : "texel";
            if (r.kind == Kind::prt_texel)
                for (const MeshView& m : scene_.meshes)
                    if (!has_uvs(m)) {
                        r.element = "texel";
                        r.cannot_show += "; meshes without UVs read per-vertex transfer";
                        break;
                    }
        } else if (name.rfind("prt-cpca-", 0) == 0) {
            r.kind = Kind::prt_cpca;
            if (!cpca_name(name, r.clusters, r.vectors))
                sphbasis::detail::throw_invalid("render::Representations",
                                                "prt-cpca-C-M, got '" + name + "'");
            r.element = "texel";
            r.bytes_per_element = std::size_t(r.vectors) * sizeof(float) + 2;  // + cluster index
            r.cannot_show =
                "lighting above " + std::to_string(settings_.prt_bands) +
                " SH bands; no normal-map detail; transfer beyond " + std::to_string(r.vectors) +
                " vectors in each of " + std::to_string(r.clusters) +
                " clusters (read nearest: clusters cannot be filtered)" + std::string(no_bounce);
            for (const MeshView& m : scene_.meshes)
                if (!has_uvs(m)) r.element = "vertex";
        } else if (name == "prt-ratio") {
            r.kind = Kind::prt_ratio;
            r.element = "texel";
            r.cannot_show =
                "shadowing of the tilted normal taken from the surface normal's "
                "(one ratio per texel)" +
                std::string(no_bounce);
            for (const MeshView& m : scene_.meshes)
                if (!has_uvs(m)) r.element = "vertex";
        } else if (name.rfind("prt-normalmap", 0) == 0) {
            r.kind = Kind::prt_normalmap;
            const int nb = settings_.prt_bands;
            if (name != "prt-normalmap") {
                r.svd_vectors = name == "prt-normalmap-svd4" ? 4 : 6;
                r.bytes_per_element = 3 * std::size_t(r.svd_vectors * nb * nb) * sizeof(float);
            } else {
                r.bytes_per_element = 3 * std::size_t(9 * nb * nb) * sizeof(float);
            }
            r.element = "texel";
            r.cannot_show = "lighting above " + std::to_string(nb) +
                            " SH bands; incident light above 3 bands" + std::string(no_bounce);
            if (r.svd_vectors > 0)
                r.cannot_show += "; normal variation beyond " + std::to_string(r.svd_vectors) +
                                 " normal-basis functions";
            for (const MeshView& m : scene_.meshes)
                if (!has_uvs(m)) r.element = "vertex";
        } else if (name.rfind("lightmap-", 0) == 0) {
            r.kind = Kind::lightmap;
            const std::string b = name.substr(9);
            static const std::pair<const char*, std::pair<const char*, int>> table[] = {
                {"sh4", {"sh", 4}},
                {"sh9", {"sh", 9}},
                {"hbasis4", {"hbasis", 4}},
                {"hbasis6", {"hbasis", 6}},
                {"hbasis-mod6", {"hbasis-mod", 6}},
                {"hl2", {"hl2", 3}},
                {"hsh4", {"hsh", 4}},
                {"hsh9", {"hsh", 9}}};
            for (const auto& t : table)
                if (b == t.first) {
                    r.basis = &find_basis(t.second.first);
                    r.coeffs = t.second.second;
                }
            if (!r.basis)  // representation_names() and the table disagree
                sphbasis::detail::throw_invalid("render::Representations",
                                                "a lightmap basis, got '" + b + "'");
            (void)r.basis->functions(r.coeffs);  // checks the count
            r.element = "texel";
            r.bytes_per_element = 3 * std::size_t(r.coeffs) * sizeof(float);
            r.cannot_show = std::string("static lighting (ignores the render-time rotation)") +
                            "; directional detail beyond " + std::to_string(r.coeffs) + " " +
                            r.basis->name + " functions" + no_bounce;
            for (const MeshView& m : scene_.meshes)
                if (!has_uvs(m)) {
                    r.cannot_show += "; meshes without UVs fall back to irradiance-sh9";
                    break;
                }
        } else if (name == "volume") {
            r.kind = Kind::volume;
            r.element = "probe";
            r.bytes_per_element = 27 * sizeof(float);
            r.cannot_show =
                "static lighting (ignores the render-time rotation); shadows and occlusion finer "
                "than the probe spacing; light leaks where probes straddle walls" +
                std::string(no_bounce);
        } else if (name.rfind("lxh-", 0) == 0) {
            const int k = number_after(name, "lxh-unc"), m = number_after(name, "lxh-pca");
            if (k == 3 || k == 4 || k == 6) {
                r.kind = Kind::lxh_unc;
                r.vis_bands = k;
                r.bytes_per_element = std::size_t(k * k) * sizeof(float);
            } else if (m >= 1) {
                r.kind = Kind::lxh_pca;
                r.vis_bands = lxh_pca_bands;
                r.vectors = m;
                r.bytes_per_element = std::size_t(m) * sizeof(float);
            } else {  // representation_names() and this parser disagree
                sphbasis::detail::throw_invalid("render::Representations",
                                                "an lxh representation, got '" + name + "'");
            }
            r.element = "texel";
            const int nl =
                settings_.lxh_lighting_bands > 0 ? settings_.lxh_lighting_bands : r.vis_bands;
            r.cannot_show = "no interreflection; visibility beyond " + std::to_string(r.vis_bands) +
                            " SH bands (sharp shadows), lighting " + "beyond " +
                            std::to_string(nl) + " bands";
            if (r.kind == Kind::lxh_pca)
                r.cannot_show +=
                    "; visibility beyond " + std::to_string(r.vectors) + " principal components";
            for (const MeshView& mv : scene_.meshes)
                if (!has_uvs(mv)) {
                    r.element = "vertex";
                    r.cannot_show += "; meshes without UVs store visibility per vertex";
                    break;
                }
        } else if (name == "specular-toksvig" || name == "specular-aliased") {
            r.kind = name == "specular-toksvig" ? Kind::specular_toksvig : Kind::specular_aliased;
            r.cannot_show =
                "specular of the directional lights only (no diffuse, no environment, no "
                "shadows)";
        }
        return r;
    }

    int add_request(const BakeRequest& q) {
        const std::vector<std::uint8_t> b = repr_detail::request_bytes(q);
        for (std::size_t i = 0; i < requests_.size(); ++i)
            if (repr_detail::request_bytes(requests_[i]) == b) return int(i);
        requests_.push_back(q);
        return int(requests_.size() - 1);
    }
    BakeSettings base_settings(unsigned quantities, int bounces) const {
        BakeSettings s;
        s.quantities = quantities;
        s.rays = settings_.rays;
        s.bounces = bounces;
        s.seed = settings_.seed;
        return s;
    }
    /// One request per mesh with triangles (r.mesh_bake[m], -1 for the others): settings `s`
    /// (with `bands` when positive), at the lightmap's texels where `texels` and the mesh has
    /// UVs, else at the vertices.
    void request_per_mesh(Rep& r, BakeSettings s, bool texels, int bands = 0) {
        if (bands > 0) s.bands = bands;
        const std::size_t nm = scene_.meshes.size();
        r.mesh_bake.assign(nm, -1);
        for (std::size_t m = 0; m < nm; ++m) {
            if (scene_.meshes[m].triangle_count == 0) continue;
            BakeRequest q;
            q.mesh = m;
            q.settings = s;
            if (texels && has_uvs(scene_.meshes[m])) {
                q.where = BakeRequest::Where::texel;
                q.lightmap_size = settings_.lightmap_size;
            }
            r.mesh_bake[m] = add_request(q);
        }
    }

    void plan() {
        const std::size_t nm = scene_.meshes.size();
        for (Rep& r : reps_) {
            switch (r.kind) {
                case Kind::irradiance:
                case Kind::windowed:
                    needs_sh_ = true;
                    break;
                case Kind::ao:
                case Kind::bent:
                    needs_sh_ = true;
                    request_per_mesh(r, base_settings(Quantity::ao | Quantity::bent, 0), true);
                    break;
                case Kind::prt_vertex:
                case Kind::prt_texel:
                    needs_sh_ = true;  // the lighting's SH (prt_light_)
                    request_per_mesh(r, base_settings(Quantity::transfer, settings_.bounces),
                                     r.kind == Kind::prt_texel, settings_.prt_bands);
                    break;
                case Kind::lightmap:
                    r.mesh_bake.assign(nm, -1);
                    for (std::size_t m = 0; m < nm; ++m) {
                        if (!has_uvs(scene_.meshes[m])) {
                            needs_sh_ = true;
                            continue;
                        }
                        BakeRequest q;
                        q.mesh = m;
                        q.where = BakeRequest::Where::texel;
                        q.lightmap_size = settings_.lightmap_size;
                        q.lighting_dependent = true;
                        q.settings = base_settings(Quantity::irradiance, settings_.bounces);
                        q.settings.basis = r.basis->name;
                        q.settings.coeffs = r.coeffs;
                        r.mesh_bake[m] = add_request(q);
                    }
                    break;
                case Kind::volume: {
                    needs_sh_ = true;  // the clamped-cosine factors (cosine9_)
                    BakeRequest q;
                    q.where = BakeRequest::Where::probes;
                    q.lighting_dependent = true;
                    q.settings = base_settings(Quantity::radiance, settings_.bounces);
                    q.settings.bands = 3;
                    if (settings_.has_probes) {
                        q.probes = settings_.probes;
                    } else {
                        q.probes.lo = rt_.bounds_min();
                        q.probes.hi = rt_.bounds_max();
                        q.probes.counts = {4, 4, 4};
                    }
                    r.probe_bake = add_request(q);
                    break;
                }
                case Kind::lxh_unc:
                case Kind::lxh_pca:
                    request_per_mesh(r, base_settings(Quantity::visibility, 0), true, r.vis_bands);
                    break;
                case Kind::specular_toksvig:
                case Kind::specular_aliased:
                case Kind::prt_ratio:
                case Kind::prt_normalmap:
                case Kind::prt_cpca:
                    break;
            }
            if (r.kind == Kind::prt_ratio || r.kind == Kind::prt_normalmap ||
                r.kind == Kind::prt_cpca) {
                needs_sh_ = true;
                request_per_mesh(
                    r,
                    base_settings(r.kind == Kind::prt_normalmap ? Quantity::transfer_matrix
                                                                : Quantity::transfer,
                                  settings_.bounces),
                    true, settings_.prt_bands);
            }
            r.reads_bakes = r.probe_bake >= 0;
            for (int b : r.mesh_bake) r.reads_bakes = r.reads_bakes || b >= 0;
        }
    }

    /// SH of the distant lighting, rotated; the white Lambertian factors a_l folded in.
    void prepare_lighting() {
        const int nb = std::max(3, settings_.prt_bands);
        const std::size_t n = std::size_t(nb) * std::size_t(nb);
        std::vector<RGB> L = project_sh(scene_.environment, nb);
        const vec3<double> centre{0.5 * (rt_.bounds_min().x + rt_.bounds_max().x),
                                  0.5 * (rt_.bounds_min().y + rt_.bounds_max().y),
                                  0.5 * (rt_.bounds_min().z + rt_.bounds_max().z)};
        for (const Light& l : scene_.lights) {
            const std::vector<RGB> s = project_sh(l, nb, centre);
            for (std::size_t k = 0; k < n; ++k)
                for (std::size_t c = 0; c < 3; ++c) L[k][c] += s[k][c];
        }
        std::array<std::vector<double>, 3> ch;
        for (std::size_t c = 0; c < 3; ++c) {
            ch[c].resize(n);
            for (std::size_t k = 0; k < n; ++k) ch[c][k] = L[k][c];
        }
        double a[3];
        clamped_cosine_factors(3, a);
        for (std::size_t k = 0; k < 9; ++k) {
            const int l = k == 0 ? 0 : (k < 4 ? 1 : 2);
            cosine9_[k] = a[l];
        }
        // Windowed copy (3 bands): Sloan's window making the irradiance non-negative.
        std::vector<double> c9(27);
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < 9; ++k) c9[c * 9 + k] = ch[c][k];
        const auto rw = sh::ringing_window<double>(3, c9.data(), 3, a, 0.0);
        window_lambda_ = rw.lambda;
        std::array<std::vector<double>, 3> win;
        for (std::size_t c = 0; c < 3; ++c) {
            win[c].assign(ch[c].begin(), ch[c].begin() + 9);
            for (std::size_t k = 0; k < 9; ++k)
                win[c][k] *= rw.window[k == 0 ? 0 : (k < 4 ? 1 : 2)];
        }
        const Mat3<double>& R = settings_.lighting_rotation;
        for (std::size_t c = 0; c < 3; ++c) {
            std::vector<double> rot(n), rot9(9);
            sh::rotate(nb, R, ch[c], rot);
            sh::rotate(3, R, win[c], rot9);
            for (std::size_t k = 0; k < 9; ++k) {
                irr_[c][k] = cosine9_[k] * rot[k];
                irr_windowed_[c][k] = cosine9_[k] * rot9[k];
            }
            const std::size_t np = std::size_t(settings_.prt_bands * settings_.prt_bands);
            prt_light_[c].assign(rot.begin(), rot.begin() + std::ptrdiff_t(np));
        }
    }

    static RGB sh_shade(const std::array<std::array<double, 9>, 3>& C, const vec3<double>& n,
                        const std::array<double, 3>& albedo) noexcept {
        double y[9];
        sh::eval_unit(3, n.x, n.y, n.z, y);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) {
            double s = 0;
            for (std::size_t k = 0; k < 9; ++k) s += C[c][k] * y[k];
            out[c] = albedo[c] * s;
        }
        return out;
    }

    /// Vertex normals: the mesh's, else area-weighted face normals.
    static std::vector<double> vertex_normals(const MeshView& m) {
        std::vector<double> n(3 * m.vertex_count, 0.0);
        if (m.normals) {
            for (std::size_t i = 0; i < n.size(); ++i) n[i] = m.normals[i];
            return n;
        }
        for (std::size_t t = 0; t < m.triangle_count; ++t) {
            const std::uint32_t* tri = m.indices + 3 * t;
            using namespace detail::rt;
            const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
            const V3 p1 = lightmap_detail::load3(m.positions, tri[1]);
            const V3 p2 = lightmap_detail::load3(m.positions, tri[2]);
            const V3 c = cross(p1 - p0, p2 - p0);
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = tri[k];
                if (v >= m.vertex_count) continue;
                n[3 * v] += c.x;
                n[3 * v + 1] += c.y;
                n[3 * v + 2] += c.z;
            }
        }
        return n;
    }

    /// The tangent render::Hit gives a point of triangle t without mesh tangents: the
    /// triangle's dp/du, orthogonalised against n, with the handedness of dp/dv.
    static void hit_tangent(const MeshView& m, LightmapSample& s) {
        using namespace detail::rt;
        if (m.tangents || !m.uvs || s.triangle >= m.triangle_count) return;
        const std::uint32_t* tri = m.indices + 3 * std::size_t(s.triangle);
        const V3 p0 = lightmap_detail::load3(m.positions, tri[0]);
        const V3 p1 = lightmap_detail::load3(m.positions, tri[1]);
        const V3 p2 = lightmap_detail::load3(m.positions, tri[2]);
        const float* uv = m.uvs;
        const double du1 = double(uv[2 * tri[1]]) - uv[2 * tri[0]],
                     dv1 = double(uv[2 * tri[1] + 1]) - uv[2 * tri[0] + 1];
        const double du2 = double(uv[2 * tri[2]]) - uv[2 * tri[0]],
                     dv2 = double(uv[2 * tri[2] + 1]) - uv[2 * tri[0] + 1];
        const double det = du1 * dv2 - du2 * dv1;
        if (!(det != 0 && std::isfinite(det))) return;
        const V3 dpdu = ((p1 - p0) * dv2 - (p2 - p0) * dv1) * (1 / det);
        const V3 dpdv = ((p2 - p0) * du1 - (p1 - p0) * du2) * (1 / det);
        const V3 nc = normalized(cross(p1 - p0, p2 - p0));
        const double sign = dot(cross(nc, dpdu), dpdv) < 0 ? -1 : 1;
        const V3 n = normalized(s.point.n);
        const V3 t = dpdu - n * dot(n, dpdu);
        const double tl = length(t);
        if (!(tl > 1e-12 * (length(dpdu) + 1e-300) && std::isfinite(tl))) return;
        s.point.tangent = t * (1 / tl);
        s.point.bitangent_sign = s.bitangent_sign = sign;
    }

    std::vector<BakePoint> make_points(const BakeRequest& q, LightmapLayout& layout) const {
        std::vector<BakePoint> pts;
        if (q.where == BakeRequest::Where::probes) {
            for (std::size_t i = 0; i < q.probes.size(); ++i) {
                BakePoint p;
                p.p = q.probes.position(i);
                p.id = i;
                pts.push_back(p);
            }
            return pts;
        }
        const MeshView& m = scene_.meshes[q.mesh];
        const std::uint64_t base = std::uint64_t(q.mesh) << 32;
        if (q.where == BakeRequest::Where::vertex) {
            const std::vector<double> n = vertex_normals(m);
            pts.resize(m.vertex_count);
            for (std::size_t v = 0; v < m.vertex_count; ++v) {
                BakePoint& p = pts[v];
                p.p = lightmap_detail::load3(m.positions, v);
                p.n = {n[3 * v], n[3 * v + 1], n[3 * v + 2]};
                if (!(dot(p.n, p.n) > 0) || !detail::rt::finite(p.n)) p.n = {0, 0, 1};
                p.id = base + v;
            }
            return pts;
        }
        layout = layout_lightmap(m, q.lightmap_size, q.lightmap_size, base);
        for (LightmapSample& s : layout.samples) {
            hit_tangent(m, s);
            pts.push_back(s.point);
        }
        return pts;
    }

    bool consistent(const BakeData& d, const BakeRequest& q) const {
        if (repr_detail::request_bytes(d.request) != repr_detail::request_bytes(q)) return false;
        switch (q.where) {
            case BakeRequest::Where::probes:
                return d.results.size() == q.probes.size();
            case BakeRequest::Where::vertex:
                return d.results.size() == scene_.meshes[q.mesh].vertex_count;
            case BakeRequest::Where::texel:
                return d.layout.width == q.lightmap_size && d.layout.height == q.lightmap_size &&
                       d.results.size() == d.layout.samples.size() &&
                       d.layout.covered.size() ==
                           std::size_t(d.layout.width) * std::size_t(d.layout.height);
        }
        return false;
    }

    /// Channels of a result: ao + bent (4), transfer (3 bands^2) or irradiance (3 coeffs).
    static int channels_of(const BakeSettings& s) noexcept {
        if (s.quantities & Quantity::transfer_matrix) return 27 * s.bands * s.bands;
        if (s.quantities & Quantity::transfer) return 3 * s.bands * s.bands;
        if (s.quantities & Quantity::irradiance) return 3 * s.coeffs;
        if (s.quantities & Quantity::visibility) return s.bands * s.bands;
        return 4;
    }
    static void pack(const BakeSettings& s, const PointResult& r, float* out) noexcept {
        if (s.quantities & Quantity::transfer_matrix) {
            const std::size_t n = 9 * std::size_t(s.bands * s.bands);
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < n; ++k)
                    out[c * n + k] =
                        k < r.transfer_matrix[c].size() ? float(r.transfer_matrix[c][k]) : 0.f;
        } else if (s.quantities & Quantity::transfer) {
            const std::size_t n = std::size_t(s.bands * s.bands);
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < n; ++k)
                    out[c * n + k] = k < r.transfer[c].size() ? float(r.transfer[c][k]) : 0.f;
        } else if (s.quantities & Quantity::irradiance) {
            const std::size_t n = std::size_t(s.coeffs);
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < n; ++k)
                    out[c * n + k] = k < r.irradiance[c].size() ? float(r.irradiance[c][k]) : 0.f;
        } else if (s.quantities & Quantity::visibility) {
            const std::size_t n = std::size_t(s.bands * s.bands);
            for (std::size_t k = 0; k < n; ++k)
                out[k] = k < r.visibility.size() ? float(r.visibility[k]) : 0.f;
        } else {
            out[0] = float(r.ao);
            out[1] = float(r.bent.x);
            out[2] = float(r.bent.y);
            out[3] = float(r.bent.z);
        }
    }

    Field make_field(const BakeData& d) const {
        Field f;
        const BakeRequest& q = d.request;
        f.where = q.where;
        if (q.where == BakeRequest::Where::probes) {
            f.grid = q.probes;
            f.probe_values.assign(27 * d.results.size(), 0.0);
            f.inside.assign(d.results.size(), 0);
            for (std::size_t i = 0; i < d.results.size(); ++i) {
                const PointResult& r = d.results[i];
                f.inside[i] = r.inside ? 1 : 0;
                for (std::size_t c = 0; c < 3; ++c)
                    for (std::size_t k = 0; k < 9 && k < r.radiance[c].size(); ++k)
                        f.probe_values[27 * i + 9 * c + k] = r.radiance[c][k];
            }
            // Every probe inside geometry: keep them all rather than fail at render time.
            if (std::find(f.inside.begin(), f.inside.end(), 0) == f.inside.end())
                std::fill(f.inside.begin(), f.inside.end(), 0);
            return f;
        }
        return make_field(d, channels_of(q.settings),
                          [&](std::size_t i, float* out) { pack(q.settings, d.results[i], out); });
    }
    /// A vertex or texel field of `channels` values per point of bake d, point i's written by
    /// pack_point(i, out) (texel gutters dilated).
    template <class PackPoint>
    static Field make_field(const BakeData& d, int channels, PackPoint&& pack_point) {
        Field f;
        f.where = d.request.where;
        f.channels = channels;
        const std::size_t ch = std::size_t(f.channels);
        if (f.where == BakeRequest::Where::vertex) {
            f.data.assign(d.results.size() * ch, 0.f);
            for (std::size_t v = 0; v < d.results.size(); ++v)
                pack_point(v, f.data.data() + v * ch);
            return f;
        }
        f.width = d.layout.width;
        f.height = d.layout.height;
        f.data.assign(std::size_t(f.width) * std::size_t(f.height) * ch, 0.f);
        for (std::size_t i = 0; i < d.results.size(); ++i) {
            const LightmapSample& s = d.layout.samples[i];
            pack_point(i, f.data.data() +
                              (std::size_t(s.y) * std::size_t(f.width) + std::size_t(s.x)) * ch);
        }
        dilate(f.data.data(), f.width, f.height, f.channels, d.layout.covered, gutter);
        return f;
    }

    /// Interpolated channels of a field at a hit (vertex: barycentric; texel: bilinear at uv,
    /// clamp to edge; texel (0, 0) at uv (0, 1)).
    static void lookup(const Field& f, const Hit& h, double* out) noexcept {
        const std::size_t ch = std::size_t(f.channels);
        if (f.where == BakeRequest::Where::vertex) {
            const double w[3] = {1 - h.u - h.v, h.u, h.v};
            for (std::size_t c = 0; c < ch; ++c) out[c] = 0;
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = h.vertices[std::size_t(k)];
                if ((v + 1) * ch > f.data.size()) continue;
                const float* p = f.data.data() + v * ch;
                for (std::size_t c = 0; c < ch; ++c) out[c] += w[k] * double(p[c]);
            }
            return;
        }
        double x = h.uv[0] * f.width - 0.5, y = (1 - h.uv[1]) * f.height - 0.5;
        if (!std::isfinite(x)) x = 0;
        if (!std::isfinite(y)) y = 0;
        x = std::clamp(x, 0.0, double(f.width - 1));
        y = std::clamp(y, 0.0, double(f.height - 1));
        const int x0 = std::min(int(x), f.width - 1), y0 = std::min(int(y), f.height - 1);
        const int x1 = std::min(x0 + 1, f.width - 1), y1 = std::min(y0 + 1, f.height - 1);
        const double ax = x - x0, ay = y - y0;
        auto at = [&](int xx, int yy) {
            return f.data.data() + (std::size_t(yy) * std::size_t(f.width) + std::size_t(xx)) * ch;
        };
        const float *p00 = at(x0, y0), *p10 = at(x1, y0), *p01 = at(x0, y1), *p11 = at(x1, y1);
        const double w00 = (1 - ax) * (1 - ay), w10 = ax * (1 - ay), w01 = (1 - ax) * ay,
                     w11 = ax * ay;
        for (std::size_t c = 0; c < ch; ++c)
            out[c] = w00 * p00[c] + w10 * p10[c] + w01 * p01[c] + w11 * p11[c];
    }

    SceneDesc scene_;
    const Scene& rt_;
    RepresentationSettings settings_;
    std::vector<std::string> names_;
    std::vector<Rep> reps_;
    std::vector<BakeRequest> requests_;
    std::vector<BakeData> data_;
    std::vector<Field> fields_;
    bool prepared_ = false, needs_sh_ = false;
    std::size_t bakes_run_ = 0, bakes_loaded_ = 0;
    std::array<double, 9> cosine9_{};
    std::array<std::array<double, 9>, 3> irr_{}, irr_windowed_{};
    std::array<std::vector<double>, 3> prt_light_;
    double window_lambda_ = 0;
    std::unique_ptr<SpecularShading> spec_;
    std::vector<LxhBuilt> lxh_;
    std::vector<PcaBuilt> pcas_;
    Eigen::MatrixXd normal_v_;  // prt-normalmap-svd*: V of the normal basis (9 x 9)
};

}  // namespace sphbasis::render
