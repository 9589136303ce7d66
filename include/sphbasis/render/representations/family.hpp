// sphbasis render tier: what every representation family shares. render/representation.hpp's
// Representations renders them; each family is one header beside this one.
//
// A family is a class derived from Representation with
//   static void list(std::vector<std::string>& out)   appends its listed names (report order)
//   static bool accepts(const std::string& name)       whether it builds `name` (listed or not)
//   Family(const std::string& name, const Context&)    parses the name: element, bytes per
//                                                      element, what it cannot show
// and overrides plan() (the bakes it requests), build() (what it derives from them after the
// bakes), shade() and, where needed, stats(). FamilyList<...> (representation.hpp) finds the
// family of a name; representation_names() is the concatenation of list().
//
// Context is what a representation sees of the Representations that owns it: the scene, the
// settings, the planned bakes and (after prepare()) their data and fields, the SH of the
// distant lighting, and work shared between representations (shared()).
//
// Distant lighting for the SH-lit representations (ShLighting): project_sh(environment, n)
// plus project_sh(light, n, c) for every light (c the centre of the scene's bounding box:
// sphere lights are treated as distant from there), then rotated by lighting_rotation. White
// Lambertian shading of SH radiance L is sum a_l L_lm y_lm(n) (core/clamped_cosine.hpp). The
// windowed copy applies Sloan's ringing-minimising window (sh::ringing_window with the
// clamped-cosine kernel and target 0: the smallest window that makes the irradiance
// non-negative everywhere; no window when it already is).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "../../basis/sh.hpp"
#include "../../core/clamped_cosine.hpp"
#include "../../core/frame.hpp"
#include "../../ops/sh_rotation.hpp"
#include "../../ops/sh_windowing.hpp"
#include "../bake.hpp"
#include "../bake_cache.hpp"
#include "../lighting.hpp"
#include "../probe_grid.hpp"
#include "../scene.hpp"
#include "field.hpp"

namespace sphbasis::render {

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

namespace representations {

/// SH of the distant lighting (header comment), rotated; the white Lambertian factors a_l
/// folded in for irr and irr_windowed (3 bands), not for prt (prt_bands bands).
struct ShLighting {
    std::array<double, 9> cosine9{};  // a_l of coefficient k (3 bands)
    std::array<std::array<double, 9>, 3> irr{}, irr_windowed{};
    std::array<std::vector<double>, 3> prt;
    double window_lambda = 0;
};

/// Seconds since t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

inline bool has_uvs(const MeshView& m) noexcept { return m.uvs != nullptr && m.triangle_count > 0; }

/// The decimal number after `prefix` in `name` (digits only, at most 4), else -1.
inline int number_after(const std::string& name, const std::string& prefix) {
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

/// White-Lambertian shading of SH irradiance coefficients C (3 bands, a_l folded in) at n.
inline RGB sh_shade(const std::array<std::array<double, 9>, 3>& C, const vec3<double>& n,
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

/// sum_k t[k] l[k] over n coefficients (a transfer vector applied to the lighting's SH).
inline double transfer_dot(const double* t, const std::vector<double>& l, std::size_t n) noexcept {
    double s = 0;
    for (std::size_t k = 0; k < n; ++k) s += t[k] * l[k];
    return s;
}

/// What a representation sees of the Representations that owns it.
struct Context {
    Context(const SceneDesc& scene_, const Scene& rt_, const RepresentationSettings& settings_)
        : scene(scene_), rt(rt_), settings(settings_) {}

    SceneDesc scene;
    const Scene& rt;
    RepresentationSettings settings;
    std::vector<BakeRequest> requests;  // the plan: distinct bakes, in request order
    bool needs_sh = false;              // plan(): some representation reads `sh`
    ShLighting sh;                      // after planning, when needs_sh
    bool prepared = false;              // prepare() has run: data and fields are set
    std::vector<BakeData> data;         // data[i]: the bake of requests[i]
    std::vector<Field> fields;          // fields[i]: make_field(data[i])

    /// The index of request q in `requests`, added if new.
    int add_request(const BakeRequest& q) {
        const std::vector<std::uint8_t> b = repr_detail::request_bytes(q);
        for (std::size_t i = 0; i < requests.size(); ++i)
            if (repr_detail::request_bytes(requests[i]) == b) return int(i);
        requests.push_back(q);
        return int(requests.size() - 1);
    }
    BakeSettings base_settings(Quantity quantities, int bounces) const {
        BakeSettings s;
        s.quantities = quantities;
        s.rays = settings.rays;
        s.bounces = bounces;
        s.seed = settings.seed;
        return s;
    }
    /// One request per mesh with triangles (the result's [m]; -1 for the others): settings `s`
    /// (with `bands` when positive), at the lightmap's texels where `texels` and the mesh has
    /// UVs, else at the vertices.
    std::vector<int> request_per_mesh(BakeSettings s, bool texels, int bands = 0) {
        if (bands > 0) s.bands = bands;
        const std::size_t nm = scene.meshes.size();
        std::vector<int> mesh_bake(nm, -1);
        for (std::size_t m = 0; m < nm; ++m) {
            if (scene.meshes[m].triangle_count == 0) continue;
            BakeRequest q;
            q.mesh = m;
            q.settings = s;
            if (texels && has_uvs(scene.meshes[m])) {
                q.where = BakeRequest::Where::texel;
                q.lightmap_size = settings.lightmap_size;
            }
            mesh_bake[m] = add_request(q);
        }
        return mesh_bake;
    }

    /// The centre of the scene's bounding box (where sphere lights are projected from).
    vec3<double> centre() const {
        return {0.5 * (rt.bounds_min().x + rt.bounds_max().x),
                0.5 * (rt.bounds_min().y + rt.bounds_max().y),
                0.5 * (rt.bounds_min().z + rt.bounds_max().z)};
    }
    /// The SH of the distant lighting on `bands` bands, not rotated: the environment's plus
    /// every light's seen from centre() (header comment).
    std::vector<RGB> distant_sh(int bands) const {
        std::vector<RGB> L = project_sh(scene.environment, bands);
        const vec3<double> c0 = centre();
        const std::size_t n = std::size_t(bands) * std::size_t(bands);
        for (const Light& l : scene.lights) {
            const std::vector<RGB> s = project_sh(l, bands, c0);
            for (std::size_t k = 0; k < n; ++k)
                for (std::size_t c = 0; c < 3; ++c) L[k][c] += s[k][c];
        }
        return L;
    }
    /// Sets `sh` from the scene's lighting and settings.lighting_rotation.
    void prepare_lighting() {
        const int nb = std::max(3, settings.prt_bands);
        const std::size_t n = std::size_t(nb) * std::size_t(nb);
        const std::vector<RGB> L = distant_sh(nb);
        std::array<std::vector<double>, 3> ch;
        for (std::size_t c = 0; c < 3; ++c) {
            ch[c].resize(n);
            for (std::size_t k = 0; k < n; ++k) ch[c][k] = L[k][c];
        }
        double a[3];
        clamped_cosine_factors(3, a);
        for (std::size_t k = 0; k < 9; ++k) {
            const int l = k == 0 ? 0 : (k < 4 ? 1 : 2);
            sh.cosine9[k] = a[l];
        }
        // Windowed copy (3 bands): Sloan's window making the irradiance non-negative.
        std::vector<double> c9(27);
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < 9; ++k) c9[c * 9 + k] = ch[c][k];
        const auto rw = sphbasis::sh::ringing_window<double>(3, c9.data(), 3, a, 0.0);
        sh.window_lambda = rw.lambda;
        std::array<std::vector<double>, 3> win;
        for (std::size_t c = 0; c < 3; ++c) {
            win[c].assign(ch[c].begin(), ch[c].begin() + 9);
            for (std::size_t k = 0; k < 9; ++k)
                win[c][k] *= rw.window[k == 0 ? 0 : (k < 4 ? 1 : 2)];
        }
        const Mat3<double>& R = settings.lighting_rotation;
        for (std::size_t c = 0; c < 3; ++c) {
            std::vector<double> rot(n), rot9(9);
            sphbasis::sh::rotate(nb, R, ch[c], rot);
            sphbasis::sh::rotate(3, R, win[c], rot9);
            for (std::size_t k = 0; k < 9; ++k) {
                sh.irr[c][k] = sh.cosine9[k] * rot[k];
                sh.irr_windowed[c][k] = sh.cosine9[k] * rot9[k];
            }
            const std::size_t np = std::size_t(settings.prt_bands * settings.prt_bands);
            sh.prt[c].assign(rot.begin(), rot.begin() + std::ptrdiff_t(np));
        }
    }

    /// Work several representations read (an L x H table of lxh-unc4 and lxh-pca4, the
    /// specular mip chains): the item of (kind, key), built by build() and timed the first time
    /// it is asked for; `seconds` (when not null) receives the time it took. Items are dropped
    /// when prepare() starts (the representations keep those they hold).
    template <class T, class Build>
    std::shared_ptr<const T> shared(const std::string& kind, const std::string& key, Build&& build,
                                    double* seconds = nullptr) {
        for (const SharedItem& s : shared_)
            if (s.kind == kind && s.key == key) {
                if (seconds) *seconds = s.seconds;
                return std::static_pointer_cast<const T>(s.value);
            }
        const auto t0 = std::chrono::steady_clock::now();
        std::shared_ptr<const T> v = std::make_shared<const T>(build());
        shared_.push_back({kind, key, v, seconds_since(t0)});
        if (seconds) *seconds = shared_.back().seconds;
        return v;
    }
    /// Shared items of a kind built since prepare() started.
    std::size_t shared_count(const std::string& kind) const {
        return std::size_t(std::count_if(shared_.begin(), shared_.end(),
                                         [&](const SharedItem& s) { return s.kind == kind; }));
    }
    void drop_shared() { shared_.clear(); }

  private:
    struct SharedItem {
        std::string kind, key;
        std::shared_ptr<const void> value;
        double seconds = 0;
    };
    std::vector<SharedItem> shared_;
};

/// One requested representation (a member of a family).
class Representation {
  public:
    explicit Representation(std::string name_) : name(std::move(name_)) {}
    virtual ~Representation() = default;
    Representation(const Representation&) = delete;
    Representation& operator=(const Representation&) = delete;

    /// Requests the bakes it reads (ctx.add_request(), ctx.request_per_mesh(), recorded in
    /// mesh_bake / probe_bake) and sets ctx.needs_sh when it reads ctx.sh. Runs once, in the
    /// order the representations were named.
    virtual void plan(Context& ctx) = 0;
    /// After the bakes (ctx.data, ctx.fields): what it derives from them (tables,
    /// compressions, fields), with build_seconds. Throws std::invalid_argument for what the
    /// bakes cannot support.
    virtual void build(Context&) {}
    /// The outgoing radiance toward the camera at a valid hit (Representations::shade()).
    virtual RGB shade(const Context& ctx, const Hit& hit, const vec3<double>& view,
                      double footprint) const = 0;
    /// Completes the stats Representations::stats() filled from the members below.
    virtual void stats(const Context&, RepresentationStats&) const {}
    /// The numerical rank of what it compressed (lxh-pca*, after prepare()), else 0.
    virtual int compressed_rank() const { return 0; }
    /// Compressions build() made that compressions_built() counts (lxh-pca*: 1).
    virtual std::size_t compressions() const { return 0; }

    /// The distinct bakes it reads (indices into ctx.requests), ascending.
    std::vector<std::size_t> reads() const {
        std::vector<std::size_t> out;
        for (int b : mesh_bake)
            if (b >= 0) out.push_back(std::size_t(b));
        if (probe_bake >= 0) out.push_back(std::size_t(probe_bake));
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
        return out;
    }
    bool reads_bakes() const { return !reads().empty(); }
    /// "texel" when every mesh has UVs, else "vertex".
    static const char* texel_or_vertex(const Context& ctx) {
        for (const MeshView& m : ctx.scene.meshes)
            if (!has_uvs(m)) return "vertex";
        return "texel";
    }

    // Set by the family's constructor (what stats() reports) and by plan() (the bakes).
    std::string name;
    std::string element = "none", cannot_show;
    std::size_t bytes_per_element = 0;
    std::vector<int> mesh_bake;  // per mesh: index into ctx.requests, -1: none (fallback)
    int probe_bake = -1;
    double build_seconds = 0;  // build()'s work (shared work counted for each reader)
};

/// The families a Representations builds, in report order (representation.hpp).
template <class... Family>
struct FamilyList {
    /// Every listed name, family by family.
    static std::vector<std::string> names() {
        std::vector<std::string> out;
        (Family::list(out), ...);
        return out;
    }
    static bool accepts(const std::string& name) { return (Family::accepts(name) || ...); }
    /// The representation of `name` (its family's constructor parses it); null if unknown.
    static std::unique_ptr<Representation> make(const std::string& name, const Context& ctx) {
        std::unique_ptr<Representation> r;
        ((r = !r && Family::accepts(name) ? std::make_unique<Family>(name, ctx) : std::move(r)),
         ...);
        return r;
    }
};

}  // namespace representations
}  // namespace sphbasis::render
