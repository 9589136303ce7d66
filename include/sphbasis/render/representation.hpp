// sphbasis render tier: the baked lighting representations a game would ship, rendered from
// the bakes of render/bake.hpp under the same lighting as the ground truth (path_tracer.hpp).
//
// Every representation shades a camera hit as albedo(hit) / pi * E, E the irradiance it
// reconstructs (the diffuse part only; the specular ones are the exception), with the
// normal-mapped normal (Scene::normal_mapped) wherever the representation can use a per-pixel
// normal. Names (representation_names(), in report order), one family a header under
// render/representations/ (each header's comment says what its members show and read):
//   irradiance.hpp     irradiance-sh9, irradiance-sh9-windowed, ao, bent
//   prt.hpp            prt-vertex, prt-texel
//   lightmap.hpp       lightmap-sh4, -sh9, -hbasis4, -hbasis6, -hbasis-mod6, -hl2, -hsh4, -hsh9,
//                      -ambient-cube5, -ambient-dice12, -ambient-dice-bezier30,
//                      -ambient-dice-linear10, -sg5, -sg6, -sg9, -sg12, -sg9-nnls,
//                      -sg9-running, -zh3, -zh3-hallucinate, -sh-l1-nonlinear;
//                      lightmap-ambient-dice-ycocg
//   volume.hpp         volume
//   volume_engine.hpp  volume-ambient-cube, -ambient-dice, -ambient-dice-bezier,
//                      -sh-l1-nonlinear, -zh3-hallucinate, -zh3, -sg9
//   specular.hpp       specular-toksvig, specular-aliased (compared with
//                      render_specular_reference() of render/specular.hpp, not the path tracer)
//   lxh.hpp            lxh-unc3, -unc4, -unc6, lxh-pcaM (M = 4, 8, 12, 16, 24 listed; 1..36)
//   prt_normalmap.hpp  prt-normalmap, prt-normalmap-svd4, -svd6, prt-ratio
//   prt_cpca.hpp       prt-cpca-C-M (4-2, 8-4, 16-4 listed; C <= 4096, M <= 64)
// Shared by all of them: representations/family.hpp (the base class Representation, the
// Context it sees, the SH of the distant lighting, RepresentationSettings and
// RepresentationStats), representations/field.hpp (baked values laid out for lookups) and
// representations/bake_points.hpp (the points a bake runs at).
//
// Adding a family: one header under render/representations/ with a class derived from
// representations::Representation (family.hpp says what it provides), and its #include and
// class name in RepresentationFamilies below (the place in that list is its place in the
// report order).
//
// Bakes: each representation declares the bakes it reads (BakeRequest, render/bake_cache.hpp)
// in plan(); prepare() runs each distinct request once (requests with equal settings share one
// Baker, and every Baker borrows the renderer's Scene: one Embree build), or loads it from a
// BakeCache under bake_key(). Only what a
// requested representation reads is built after the bakes (tables per distinct (K, N), one PCA
// per lxh-pca, fields per prt-*); lxh_tables_built() and compressions_built() count them.
//
// Camera rays: one per pixel centre (spp = 1) or spp jittered ones, the jitter a hash of
// (seed, pixel, sample); footprint = t * pixel_angle() (the obliquity is ignored).
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "bake.hpp"
#include "bake_cache.hpp"
#include "camera.hpp"
#include "detail/rt_math.hpp"
#include "image.hpp"
#include "image_loop.hpp"
#include "lighting.hpp"
#include "representations/bake_points.hpp"
#include "representations/family.hpp"
#include "representations/field.hpp"
#include "representations/irradiance.hpp"
#include "representations/lightmap.hpp"
#include "representations/lxh.hpp"
#include "representations/prt.hpp"
#include "representations/prt_cpca.hpp"
#include "representations/prt_normalmap.hpp"
#include "representations/specular.hpp"
#include "representations/volume.hpp"
#include "representations/volume_engine.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// The representation families, in report order (header comment: adding one).
using RepresentationFamilies =
    representations::FamilyList<representations::Irradiance, representations::Prt,
                                representations::Lightmap, representations::LightmapYCoCg,
                                representations::Volume, representations::VolumeEngine,
                                representations::Specular, representations::Lxh,
                                representations::PrtNormalMap, representations::PrtCpca>;

/// Every representation name, in report order (header comment).
inline const std::vector<std::string>& representation_names() {
    static const std::vector<std::string> names = RepresentationFamilies::names();
    return names;
}

/// Renders the representations of a scene.
class Representations {
  public:
    /// Borrows `scene` (the arrays) and `rt` (built from scene.meshes). Throws
    /// std::invalid_argument for an unknown name (the message lists representation_names()),
    /// a duplicate, or invalid settings.
    Representations(const SceneDesc& scene, const Scene& rt, const RepresentationSettings& settings,
                    const std::vector<std::string>& names)
        : ctx_(scene, rt, settings), rt_(rt), settings_(settings), names_(names) {
        validate_input();
        for (const std::string& n : names_) reps_.push_back(RepresentationFamilies::make(n, ctx_));
        for (const auto& r : reps_) r->plan(ctx_);
        if (ctx_.needs_sh) ctx_.prepare_lighting();
    }
    /// The distinct bakes the requested representations read (the plan), before prepare().
    const std::vector<BakeRequest>& bakes() const noexcept { return ctx_.requests; }
    /// Runs or loads every planned bake (cache may be null). progress(done, total) in points.
    /// Each distinct request is baked once (or loaded under bake_key()); fresh bakes are
    /// stored in the cache. The counters below count this call only. Then each
    /// representation builds what it derives from its bakes (Representation::build()).
    void prepare(BakeCache* cache,
                 const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) {
        const std::vector<BakeRequest>& requests_ = ctx_.requests;  // the plan
        std::vector<BakeData>& data_ = ctx_.data;                   // what this call sets
        bakes_run_ = bakes_loaded_ = 0;
        data_.assign(requests_.size(), BakeData{});
        std::vector<std::uint64_t> keys(requests_.size());
        std::vector<std::size_t> todo;
        for (std::size_t i = 0; i < requests_.size(); ++i) {
            keys[i] = bake_key(ctx_.scene, requests_[i]);
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
            points[k] =
                representations::bake_points(ctx_.scene.meshes, requests_[todo[k]], layouts[k]);
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
            // Borrowing the renderer's Scene: a run builds one BVH.
            if (!baker) baker = std::make_unique<Baker>(rt_, ctx_.scene, q.settings);
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
        ctx_.prepared = false;
        ctx_.fields.clear();
        for (const BakeData& d : data_) ctx_.fields.push_back(representations::make_field(d));
        ctx_.drop_shared();
        for (const auto& r : reps_) r->build(ctx_);
        ctx_.prepared = true;
    }
    /// L x H tables and visibility compressions built by prepare() (only those a requested
    /// lxh-* reads; each distinct one once).
    std::size_t lxh_tables_built() const { return ctx_.shared_count("lxh-table"); }
    std::size_t compressions_built() const {
        std::size_t n = 0;
        for (const auto& r : reps_) n += r->compressions();
        return n;
    }
    /// The numerical rank of the visibility that lxh-pca representation `index` compressed
    /// (after prepare()); 0 for other representations.
    int compressed_rank(std::size_t index) const {
        return rep(index, "render::Representations::compressed_rank").compressed_rank();
    }
    /// Bakes run and bakes loaded from the cache by prepare().
    std::size_t bakes_run() const noexcept { return bakes_run_; }
    std::size_t bakes_loaded() const noexcept { return bakes_loaded_; }
    /// The data of bake i (bakes()[i]) after prepare().
    const BakeData& bake_data(std::size_t i) const {
        if (!ctx_.prepared || i >= ctx_.data.size())
            sphbasis::detail::throw_invalid("render::Representations::bake_data",
                                            "a bake index below " +
                                                std::to_string(ctx_.data.size()) +
                                                " after prepare(), got " + std::to_string(i));
        return ctx_.data[i];
    }

    /// The outgoing radiance toward the camera at a hit for representation `index` (into the
    /// names given), view = unit direction from the hit to the eye, footprint = the pixel's
    /// world-space width at the hit (for the normal map's mip level): the representation's
    /// Representation::shade(). Throws std::invalid_argument for a bad index,
    /// std::runtime_error before prepare() for a representation that reads bakes. An invalid
    /// hit gives 0.
    RGB shade(std::size_t index, const Hit& hit, const vec3<double>& view, double footprint) const {
        const representations::Representation& r = rep(index, "render::Representations::shade");
        if (!hit.valid) return {0, 0, 0};
        return r.shade(ctx_, hit, view, footprint);
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
        return ctx_.scene.environment.radiance(m);
    }
    RepresentationStats stats(std::size_t index) const {
        const representations::Representation& r =
            rep(index, "render::Representations::stats", false);
        RepresentationStats s;
        s.name = r.name;
        s.cannot_show = r.cannot_show;
        bool any = false, all_cached = true;
        for (std::size_t b : r.reads()) {
            any = true;
            if (!ctx_.prepared) continue;
            const BakeData& d = ctx_.data[b];
            s.bake_seconds += d.seconds;
            s.bake_rays += d.rays;
            all_cached = all_cached && d.from_cache;
            s.elements += d.results.size();
        }
        s.cached = ctx_.prepared && any && all_cached;
        if (ctx_.prepared) s.build_seconds += r.build_seconds;
        s.element = r.element;
        s.bytes_per_element = r.bytes_per_element;
        r.stats(ctx_, s);
        return s;
    }
    const std::vector<std::string>& names() const noexcept { return names_; }
    /// The bakes representation `index` reads: indices into bakes(), ascending, no repeats.
    std::vector<std::size_t> reads(std::size_t index) const {
        return rep(index, "render::Representations::reads", false).reads();
    }

    /// Whether `name` is a representation this class builds: one of representation_names(), or
    /// a member of a family beyond the listed ones (lxh-pcaM, 1 <= M <= 36; prt-cpca-C-M,
    /// 1 <= C <= 4096, 1 <= M <= 64). For checking names before any scene is loaded.
    static bool known_name(const std::string& name) {
        return RepresentationFamilies::accepts(name);
    }

  private:
    /// Representation `index`; with `ready`, also that its bakes are prepared.
    const representations::Representation& rep(std::size_t index, const char* fn,
                                               bool ready = true) const {
        if (index >= reps_.size())
            sphbasis::detail::throw_invalid(fn, "a representation index below " +
                                                    std::to_string(reps_.size()) + ", got " +
                                                    std::to_string(index));
        const representations::Representation& r = *reps_[index];
        if (ready && r.reads_bakes() && !ctx_.prepared)
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
        if (rt_.mesh_count() != ctx_.scene.meshes.size())
            sphbasis::detail::throw_invalid(fn, "a ray-tracing scene of the scene's " +
                                                    std::to_string(ctx_.scene.meshes.size()) +
                                                    " meshes, got " +
                                                    std::to_string(rt_.mesh_count()));
        validate(ctx_.scene.environment);
        for (const Light& l : ctx_.scene.lights) validate(l);
        std::string known;
        for (const std::string& n : representation_names())
            known += (known.empty() ? "" : ", ") + n;
        for (std::size_t i = 0; i < names_.size(); ++i) {
            if (!RepresentationFamilies::accepts(names_[i]))
                sphbasis::detail::throw_invalid(
                    fn, "representations from: " + known +
                            " (and lxh-pcaM for 1 <= M <= 36); got unknown '" + names_[i] + "'");
            for (std::size_t j = 0; j < i; ++j)
                if (names_[j] == names_[i])
                    sphbasis::detail::throw_invalid(fn, "distinct representations (from: " + known +
                                                            "), got '" + names_[i] + "' twice");
        }
    }

    /// A loaded bake fits its request and the scene: every count, and every texel index, is
    /// checked before use (a cache entry that does not fit is baked again).
    bool consistent(const BakeData& d, const BakeRequest& q) const {
        if (repr_detail::request_bytes(d.request) != repr_detail::request_bytes(q)) return false;
        switch (q.where) {
            case BakeRequest::Where::probes:
                return d.results.size() == q.probes.size();
            case BakeRequest::Where::vertex:
                return d.results.size() == ctx_.scene.meshes[q.mesh].vertex_count;
            case BakeRequest::Where::texel: {
                const LightmapLayout& l = d.layout;
                if (!(l.width == q.lightmap_size && l.height == q.lightmap_size &&
                      d.results.size() == l.samples.size() &&
                      l.covered.size() == std::size_t(l.width) * std::size_t(l.height)))
                    return false;
                for (const LightmapSample& s : l.samples)
                    if (s.x < 0 || s.y < 0 || s.x >= l.width || s.y >= l.height ||
                        s.triangle >= ctx_.scene.meshes[q.mesh].triangle_count)
                        return false;
                return true;
            }
        }
        return false;
    }

    representations::Context ctx_;  // what the representations see (family.hpp)
    const Scene& rt_;               // ctx_.rt and a copy of ctx_.settings, for render()
    RepresentationSettings settings_;
    std::vector<std::string> names_;
    std::vector<std::unique_ptr<representations::Representation>> reps_;
    std::size_t bakes_run_ = 0, bakes_loaded_ = 0;
};

}  // namespace sphbasis::render
