// sphbasis render tier: the ground truth, a Monte Carlo path tracer of exactly the effects a
// scene enables.
//
// Light transport (all radiances linear RGB, surfaces two-sided, albedo from render::Hit):
//   * Primary rays from render::ImageLoop (image_loop.hpp, the loop every image of the library
//     comes from): `spp` samples per pixel at the loop's positions (a per-pixel scrambled R2
//     sequence; the pixel centre when spp_max = 1), a box filter; every random number is a hash
//     of (seed, pixel, sample, dimension), so images do not depend on threads or tile order.
//     The tracer is the loop's `li`: what one camera ray's path brings back.
//   * Camera rays that escape show the environment's radiance (the background); analytic lights
//     are not visible to camera rays (a sphere light is a light, not geometry).
//   * At a hit the shading normal is Scene::normal_mapped(hit) when the mesh has a normal map
//     (no normal-map work otherwise). BRDF (render::Bsdf, bsdf.hpp): Lambertian albedo / pi,
//     plus, only for meshes with shininess s > 0, the energy-normalised Blinn-Phong lobe
//     k_s (s + 8) / (8 pi) (n.h)^s (mesh.hpp). Two-sided: a hit is shaded from the side the
//     ray arrived on (Scene::hit turns the geometric and the shading normal to it together,
//     whatever the winding). Light below
//     the geometric surface is not gathered. The diffuse lobe is the cosine about the shading
//     normal folded above the geometric surface: a direction of the lobe below it is reflected
//     in the geometric tangent plane (render/detail/rt_math.hpp, fold_above and folded_cosine),
//     so the diffuse weight f cos / pdf is exactly the albedo even where interpolated or mapped
//     normals tilt the lobe under the surface, and a white furnace (albedo 1, unit sky) is 1.
//     Why folding: ending such paths loses energy (a box with normals smoothed across its edges
//     read 0.73 in a white furnace); sampling about the geometric normal instead would ignore
//     the shading normal for indirect light; rejection and resampling costs rays at grazing
//     tilts. Folding keeps the lobe's shape where it is above the surface, costs one dot
//     product, and equals the Lambertian lobe where the two normals agree. The Blinn-Phong lobe
//     uses the shading normal, clamped at 0; a specular direction below the geometric surface
//     ends the path (that lobe is not energy-conserving anyway).
//   * Direct light (next-event estimation with shadow rays): the environment is importance
//     sampled from its luminance (a piecewise-constant distribution over the lat-long texels
//     weighted by sin(theta); a constant environment is sampled by the cosine lobe) and
//     combined by multiple importance sampling (the balance heuristic; Veach, "Robust Monte
//     Carlo Methods for Light Transport Simulation", PhD thesis, 1997, ch. 9) with BRDF
//     sampling (cosine-weighted, or the Blinn-Phong lobe for shiny materials). Directional
//     lights: one shadow ray, no MIS (deltas). Cone, sphere and hemisphere lights:
//     render::sample_light() with MIS against the BRDF sample.
//   * Interreflection: the path continues by BRDF sampling up to `bounces` diffuse bounces
//     (bounces = 0: direct light only; the path depth is the scene's bounce count). bounces < 0
//     means unbounded with Russian roulette (survival probability min(0.95, max throughput)
//     after the third bounce). Nothing else is simulated (no emission from surfaces, no
//     transmission, no volumes).
//   * Progressive: passes of samples per pixel (spp_min, then doubling) until the relative
//     standard error of the image (the RMS of per-pixel stderr / max(luminance, floor), over
//     pixels, floor 1e-3 of the mean luminance) is at most target_noise, or spp_max is reached.
//     The per-pixel standard error (RGB, of the pixel's mean) is returned with the image.
//
// Counters (TraceCounters) are exact and let tests prove that no work the scene does not call
// for was done (no shadow rays without lights or environment, no normal-map lookups without
// normal maps, no specular evaluations without shiny materials, no bounce rays with bounces = 0).
//
// Implementation notes (what the tests and counters rely on):
//   * Random numbers: the pixel position of sample i is ImageLoop's (render::pixel_sample():
//     point i of the R2 sequence, core/sampling.hpp, with a per-pixel Cranley-Patterson rotation
//     hashed from (seed, pixel)); every other dimension is
//     rt::unit(hash(hash(hash(seed, pixel), sample), dimension)), so the progressive passes
//     continue one sequence and nothing depends on threads or tiles.
//   * Per path vertex: one environment sample (lat-long maps only), one sample per analytic
//     light, then one BRDF sample. The BRDF-sampled ray continues the path (a bounce ray) while
//     bounces remain; at the last vertex it is traced only when an emitter can be reached by it
//     (the environment or a non-delta light) and is then counted as a shadow ray. A constant
//     environment gets no environment sample: the BRDF sample alone estimates it (weight 1).
//   * Tracing order (it changes no result): the paths of a tile (one sample each) advance
//     together a vertex at a time. At each depth the shadow rays of all live paths are traced
//     as one stream (rtcOccluded1M), their BRDF rays as another (rtcIntersect1M; occlusion
//     queries at the last vertex when no non-delta light needs the hit distance), and each
//     path then adds its contributions in the order above. Camera rays are ImageLoop's: one
//     coherent stream per tile and sample (RTC_INTERSECT_CONTEXT_FLAG_COHERENT: Embree traces
//     them as packets). Buffers are per thread, reused across tiles and samples. Hit records
//     (Scene::shading_hit: no tangent frame without a normal map) are made with their triangles'
//     data prefetched a few hits ahead (Scene::prefetch_hit).
//   * Cosine-lobe BRDF samples take the azimuth's cosine and sine from a polynomial
//     (sphbasis::detail::cos_sin_turn, core/cos_sin_turn.hpp, within 2e-9 of libm's, far below
//     any estimate's noise). Lambertian vertices draw them for all of a tile's paths at once in
//     loops the compiler vectorises (detail::pt::cosine_lobe); their weight f cos / pdf is the
//     albedo itself.
//   * Unbounded paths (bounces < 0): Russian roulette at every vertex from the fourth on.
//   * No emitter at all (no environment, no lights): surfaces are black and no secondary ray
//     is traced.
#pragma once

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../core/constants.hpp"
#include "../core/cos_sin_turn.hpp"
#include "../core/error.hpp"
#include "../core/sampling.hpp"
#include "../core/simd.hpp"
#include "bsdf.hpp"
#include "camera.hpp"
#include "detail/rt_math.hpp"
#include "environment_sampler.hpp"
#include "image.hpp"
#include "image_loop.hpp"
#include "lighting.hpp"
#include "scene.hpp"

namespace sphbasis::render {

struct TraceSettings {
    int bounces = 1;             // diffuse interreflection bounces; < 0: unbounded (roulette)
    int spp_min = 16;            // samples per pixel of the first pass (>= 1)
    int spp_max = 1024;          // at most this many (>= spp_min)
    double target_noise = 0.01;  // relative standard error to stop at (> 0; 0 runs spp_max)
    std::uint64_t seed = 0;
    int tile = 16;      // tile size in pixels
    bool aovs = false;  // also fill normal, albedo and position images
};

struct TraceCounters {
    std::uint64_t camera_rays = 0, shadow_rays = 0, bounce_rays = 0;
    std::uint64_t normal_map_lookups = 0, specular_evaluations = 0;
    std::uint64_t environment_samples = 0, light_samples = 0;
    TraceCounters& operator+=(const TraceCounters& o) noexcept {
        camera_rays += o.camera_rays;
        shadow_rays += o.shadow_rays;
        bounce_rays += o.bounce_rays;
        normal_map_lookups += o.normal_map_lookups;
        specular_evaluations += o.specular_evaluations;
        environment_samples += o.environment_samples;
        light_samples += o.light_samples;
        return *this;
    }
    /// Every ray traced.
    std::uint64_t rays() const noexcept { return camera_rays + shadow_rays + bounce_rays; }
};

struct TraceResult {
    Image color;                     // mean radiance per pixel
    Image stderr_;                   // its standard error per channel (+inf with one sample)
    Image normal, albedo, position;  // first-hit AOVs when requested (background: 0)
    Image coverage;  // 1 channel, always: the fraction of a pixel's camera rays that hit geometry
    int spp = 0;
    double relative_noise = 0;  // the image's relative standard error at the end
    double seconds = 0;         // wall-clock
    TraceCounters counters;
};

/// Throws std::invalid_argument ("sphbasis::render::PathTracer(): expected ...") unless
/// spp_min >= 1, spp_max >= spp_min, spp_max <= 2^24, target_noise finite and >= 0 and
/// 1 <= tile <= 16384.
inline void validate(const TraceSettings& s) {
    constexpr const char* fn = "render::PathTracer";
    sphbasis::detail::check_range(fn, "spp_min", s.spp_min, 1, 1 << 24);
    sphbasis::detail::check_range(fn, "spp_max", s.spp_max, s.spp_min, 1 << 24);
    if (!(s.target_noise >= 0) || !std::isfinite(s.target_noise))
        sphbasis::detail::throw_invalid(
            fn, "a finite target_noise >= 0, got " + std::to_string(s.target_noise));
    sphbasis::detail::check_range(fn, "tile", s.tile, 1, 16384);
}

namespace detail::pt {

using rt::V3;

/// Scene material accessors, when render::Scene has them (mesh_normal_map, mesh_shininess).
template <class S, class = void>
struct has_materials : std::false_type {};
template <class S>
struct has_materials<S, std::void_t<decltype(std::declval<const S&>().mesh_normal_map(0)),
                                    decltype(std::declval<const S&>().mesh_shininess(0))>>
    : std::true_type {};
/// Meshes with a normal map and with shininess > 0; -1 when the scene cannot say.
template <class S>
std::pair<int, int> count_materials(const S& scene) {
    if constexpr (has_materials<S>::value) {
        int nm = 0, sp = 0;
        for (std::size_t m = 0; m < scene.mesh_count(); ++m) {
            if (scene.mesh_normal_map(m)) ++nm;
            if (scene.mesh_shininess(m) > 0) ++sp;
        }
        return {nm, sp};
    } else {
        (void)scene;
        return {-1, -1};
    }
}

/// cos(2 pi v), sin(2 pi v) on [0, 1] (core/cos_sin_turn.hpp, generated): a polynomial without
/// branches or libm calls (libm's sincos was 4-5% of the tracer's time).
using sphbasis::detail::cos_sin_turn;

/// rt::hash(a, b) with mix64(a) already computed (mixed_a): a path's random numbers share a.
/// A test pins it to rt::hash.
inline std::uint64_t hash_mixed(std::uint64_t mixed_a, std::uint64_t b) noexcept {
    return rt::mix64(mixed_a ^ (b + 0x632be59bd9b4e019ull));
}

/// out[k] = sqrt(in[k]) for in[k] >= 0, k < n (in place allowed), by the library's SIMD batch
/// (core/simd.hpp: std::sqrt in a loop stays a libm call while math sets errno).
inline void sqrt_array(const double* in, double* out, std::size_t n) noexcept {
    using B = batch<double>;
    std::size_t k = 0;
    for (; k + B::size <= n; k += B::size) vsqrt(B::load(in + k)).store(out + k);
    for (; k < n; ++k) out[k] = std::sqrt(in[k]);
}

/// w[k] = Frame(n[k]).to_world(l[k]) for unit normals n and local directions
/// l = (r cs, r sn, z), k < n, the frame by coordinate_system (Duff et al.) written out: GCC
/// does not vectorise the loop through a Frame object. No array overlaps another.
inline void lobe_to_world(std::size_t n, const double* SPHBASIS_RESTRICT nx,
                          const double* SPHBASIS_RESTRICT ny, const double* SPHBASIS_RESTRICT nz,
                          const double* SPHBASIS_RESTRICT r, const double* SPHBASIS_RESTRICT cs,
                          const double* SPHBASIS_RESTRICT sn, const double* SPHBASIS_RESTRICT z,
                          double* SPHBASIS_RESTRICT wx, double* SPHBASIS_RESTRICT wy,
                          double* SPHBASIS_RESTRICT wz) noexcept {
    for (std::size_t k = 0; k < n; ++k) {
        const double x = nx[k], y = ny[k], zn = nz[k];
        const double sign = std::copysign(1.0, zn);
        const double a = -1.0 / (sign + zn);
        const double b = x * y * a;
        const double sx = 1.0 + sign * x * x * a, sy = sign * b, sz = -sign * x;
        const double tx = b, ty = sign + y * y * a, tz = -y;
        const double lx = r[k] * cs[k], ly = r[k] * sn[k], lz = z[k];
        wx[k] = sx * lx + tx * ly + x * lz;
        wy[k] = sy * lx + ty * ly + y * lz;
        wz[k] = sz * lx + tz * ly + zn * lz;
    }
}

/// The cosine-lobe samples of n paths (render::PathTracer::shade), as arrays: for path k, with
/// u = unit(hash_mixed(key[k], d0 + 3)) and v = unit(hash_mixed(key[k], d0 + 4)), the
/// world direction w = Frame(n_k).to_world(cosine_hemisphere(u, v)) (frame of the unit normal
/// (nx, ny, nz)[k]) into (wx, wy, wz)[k] and its local z (the cosine with n_k) into cz[k].
/// tmp holds 3 n doubles; no array overlaps another.
inline void cosine_lobe(std::size_t n, std::uint64_t d0, const std::uint64_t* key, const double* nx,
                        const double* ny, const double* nz, double* wx, double* wy, double* wz,
                        double* cz, double* tmp) noexcept {
    double *r = tmp, *cs = tmp + n, *sn = tmp + 2 * n;
    for (std::size_t k = 0; k < n; ++k) {
        const double uk = rt::unit(hash_mixed(key[k], d0 + 3));
        r[k] = uk;
        cz[k] = 1 - uk;  // >= 2^-53
        cos_sin_turn(rt::unit(hash_mixed(key[k], d0 + 4)), cs[k], sn[k]);
    }
    sqrt_array(r, r, n);
    sqrt_array(cz, cz, n);
    lobe_to_world(n, nx, ny, nz, r, cs, sn, cz, wx, wy, wz);
}

inline RGB mul(const RGB& a, const RGB& b) noexcept {
    return {a[0] * b[0], a[1] * b[1], a[2] * b[2]};
}
inline bool is_zero(const RGB& a) noexcept { return a[0] == 0 && a[1] == 0 && a[2] == 0; }

/// The distance along x + t w (unit w) to the near side of a ball; 0 inside, infinity on a miss.
inline double ball_distance(const V3& x, const V3& w, const V3& c, double r) noexcept {
    using namespace rt;
    const V3 d = c - x;
    const double c2 = dot(d, d) - r * r;
    if (c2 <= 0) return 0;
    const double b = dot(d, w), disc = b * b - c2;
    if (b <= 0) return std::numeric_limits<double>::infinity();
    return disc > 0 ? b - std::sqrt(disc) : b;
}

}  // namespace detail::pt

/// The effects the tracer simulates for a scene, in order (the plan a report prints): e.g.
/// "environment: importance-sampled (512x256 lat-long), MIS with the BRDF",
/// "directional lights: 1, shadow rays", "interreflection: 2 bounces",
/// "normal maps: 1 mesh", "Blinn-Phong specular: 1 mesh". An effect the scene does not call
/// for is absent.
class PathTracer {
  public:
    /// Borrows the scene and copies the lighting. Throws std::invalid_argument for invalid
    /// settings or lighting (render::validate).
    PathTracer(const Scene& scene, const Environment& environment, const std::vector<Light>& lights,
               const TraceSettings& settings)
        : scene_(scene),
          env_(environment),
          lights_(lights),
          settings_(settings),
          sampler_(environment),
          mutex_(std::make_unique<std::mutex>()) {
        validate(settings);
        for (const Light& l : lights_) validate(l);
        env_nee_ = sampler_.emits() && !sampler_.is_constant();
        env_any_ = sampler_.emits();
        env_constant_ = env_.kind == Environment::Kind::constant;
        if (env_constant_) env_c_ = env_.radiance({0, 0, 1});
        int directional = 0, other = 0;
        for (const Light& l : lights_) {
            if (l.type == Light::Type::directional)
                ++directional;
            else
                ++other;
        }
        nondelta_ = other > 0;
        fixed_samples_.resize(lights_.size());
        for (std::size_t li = 0; li < lights_.size(); ++li)
            if (lights_[li].type == Light::Type::directional)
                fixed_samples_[li] = sample_light(lights_[li], {0, 0, 0}, 0.5, 0.5);
        fixed_ok_.resize(lights_.size());
        for (std::size_t li = 0; li < lights_.size(); ++li)
            fixed_ok_[li] = usable(fixed_samples_[li]);
        emitters_ = env_any_ || !lights_.empty();
        if (env_nee_)
            effects_.push_back("environment: importance-sampled (" + std::to_string(env_.width) +
                               "x" + std::to_string(env_.height) + " lat-long), MIS with the BRDF");
        else if (env_any_)
            effects_.push_back("environment: constant, sampled by the BRDF (cosine lobe)");
        if (directional)
            effects_.push_back("directional lights: " + std::to_string(directional) +
                               ", shadow rays");
        if (other)
            effects_.push_back("cone, sphere and hemisphere lights: " + std::to_string(other) +
                               ", light sampling with MIS, shadow rays");
        if (emitters_ && settings_.bounces > 0)
            effects_.push_back("interreflection: " + std::to_string(settings_.bounces) +
                               (settings_.bounces == 1 ? " bounce" : " bounces"));
        if (emitters_ && settings_.bounces < 0)
            effects_.push_back("interreflection: unbounded (Russian roulette from the 4th vertex)");
        const auto [nm, sp] = detail::pt::count_materials(scene_);
        if (nm > 0)
            effects_.push_back("normal maps: " + std::to_string(nm) +
                               (nm == 1 ? " mesh" : " meshes"));
        if (sp > 0)
            effects_.push_back("Blinn-Phong specular: " + std::to_string(sp) +
                               (sp == 1 ? " mesh" : " meshes"));
    }
    const std::vector<std::string>& effects() const noexcept { return effects_; }

    /// Renders the camera's image progressively. progress(done, total) (optional) is called
    /// with the finished sample passes' pixel-samples, from any thread (after each tile of a
    /// pass; total = pixels * spp_max, which an early stop at the target noise ends below).
    /// Throws std::invalid_argument for a camera that validate(Camera) rejects.
    TraceResult render(
        const Camera& camera,
        const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) const {
        const auto t0 = std::chrono::steady_clock::now();
        ImageLoopSettings ls;
        ls.seed = settings_.seed;
        ls.spp = settings_.spp_max;
        ls.tile = settings_.tile;
        ImageLoop loop(scene_, camera, ls);
        if (log_)
            loop.on_camera_rays(
                [this](const RTCRayHit* r, std::size_t n) { record(r, n, 0, true); });
        const int W = camera.width, H = camera.height;
        const std::size_t N = std::size_t(W) * std::size_t(H);
        Film film(W, H, true);
        std::vector<double> aov(settings_.aovs ? 9 * N : 0, 0.0);
        TraceResult res;
        std::atomic<std::uint64_t> done{0};
        const std::uint64_t total = std::uint64_t(N) * std::uint64_t(settings_.spp_max);
        tbb::enumerable_thread_specific<TileBuffers> buffers;
        int spp = 0, target = settings_.spp_min;
        double noise = std::numeric_limits<double>::infinity();
        // Li of a batch of camera rays: the paths, and the first-hit AOVs.
        auto li = [&](const CameraBatch& b, std::size_t, RGB* L) {
            TileBuffers& B = buffers.local();
            if (settings_.aovs && B.first.size() < b.n) B.first.resize(b.n);
            First* first = settings_.aovs ? B.first.data() : nullptr;
            shade(b.rays, b.n, b.mixed_keys, b.sample, B.counters, first, L, B.scratch);
            if (first)
                for (std::size_t k = 0; k < b.n; ++k) {
                    if (!first[k].hit) continue;
                    double* o = &aov[9 * std::size_t(b.pixels[k])];
                    const V3* v[3] = {&first[k].normal, &first[k].albedo, &first[k].position};
                    for (int q = 0; q < 3; ++q) {
                        o[3 * q] += v[q]->x;
                        o[3 * q + 1] += v[q]->y;
                        o[3 * q + 2] += v[q]->z;
                    }
                }
        };
        for (;;) {
            loop.run(spp, target, {&film}, li, [&](std::uint64_t d) {
                const std::uint64_t now = done.fetch_add(d) + d;
                if (progress) progress(now, total);
            });
            spp = target;
            noise = relative_noise(film.sum, film.sq, spp);
            if ((settings_.target_noise > 0 && noise <= settings_.target_noise) ||
                spp >= settings_.spp_max)
                break;
            target = std::min(settings_.spp_max, 2 * spp);
        }
        for (const TileBuffers& B : buffers) res.counters += B.counters;
        res.counters.camera_rays += loop.stats().camera_rays;
        // Images.
        res.color = film.mean();
        res.stderr_ = film.standard_error();
        res.coverage = film.coverage();
        if (settings_.aovs) {
            res.normal = Image(W, H, 3);
            res.albedo = Image(W, H, 3);
            res.position = Image(W, H, 3);
            const double inv = 1.0 / spp;
            for (std::size_t p = 0; p < N; ++p)
                for (std::size_t ch = 0; ch < 3; ++ch) {
                    res.normal.data[3 * p + ch] = static_cast<float>(aov[9 * p + ch] * inv);
                    res.albedo.data[3 * p + ch] = static_cast<float>(aov[9 * p + 3 + ch] * inv);
                    res.position.data[3 * p + ch] = static_cast<float>(aov[9 * p + 6 + ch] * inv);
                }
        }
        res.spp = spp;
        res.relative_noise = noise;
        res.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        {
            std::lock_guard<std::mutex> lock(*mutex_);
            counters_ += res.counters;
        }
        return res;
    }

    /// The radiance estimate along one ray with sample index `sample` (for tests: a furnace,
    /// convergence), one path. The ray counts as a camera ray.
    RGB radiance(const vec3<double>& origin, const vec3<double>& direction, std::uint64_t pixel,
                 std::uint64_t sample) const {
        TraceCounters c;
        RTCRayHit r;
        Scene::set_ray(r, origin, detail::rt::normalized(direction));
        if (log_) record(&r, 1, 0, false);
        scene_.intersect(&r, 1);
        ++c.camera_rays;
        RGB L;
        Scratch scratch;
        const std::uint64_t mixed = detail::rt::mix64(pixel_key(settings_.seed, pixel));
        shade(&r, 1, &mixed, sample, c, nullptr, &L, scratch);
        std::lock_guard<std::mutex> lock(*mutex_);
        counters_ += c;
        return L;
    }
    /// Everything this tracer did so far (render() and radiance() calls, summed).
    const TraceCounters& counters() const noexcept { return counters_; }
    const EnvironmentSampler& environment_sampler() const noexcept { return sampler_; }

    /// A traced ray as recorded for benchmarks: kind 0 camera, 1 bounce, 2 an occlusion query
    /// (shadow rays, and the last vertex's BRDF rays when no non-delta light needs their hit
    /// distance; only `ray.ray` is meaningful), 3 the last vertex's BRDF ray traced for its
    /// hit distance (counted as a shadow ray). Rays are traced in streams, in the order
    /// recorded: `stream` is the length of the stream that starts at this record (0 inside
    /// one), traced by rtcIntersect1M (kinds 0, 1, 3) or rtcOccluded1M (kind 2) calls of at
    /// most 1024 rays; `coherent`: with RTC_INTERSECT_CONTEXT_FLAG_COHERENT (render()'s camera
    /// rays).
    struct RayRecord {
        RTCRayHit ray;
        int kind = 0;
        std::uint32_t stream = 0;
        bool coherent = false;
    };
    /// While `log` is non-null, every ray render() and radiance() trace is appended to it as it
    /// was before tracing (a lock per ray: for benchmarks that replay the same rays through a
    /// bare Embree loop, not for production). Null stops recording.
    void record_rays(std::vector<RayRecord>* log) noexcept { log_ = log; }

  private:
    using V3 = detail::rt::V3;
    struct First {
        bool hit = false;
        V3 normal{0, 0, 0}, albedo{0, 0, 0}, position{0, 0, 0};
    };

    static double stderr_of(double s, double q, int n) noexcept {
        return Film::standard_error(s, q, n);
    }

    static double relative_noise(const std::vector<double>& sum, const std::vector<double>& sq,
                                 int spp) {
        const std::size_t N = sum.size() / 3;
        if (N == 0) return 0;
        double mean = 0;
        for (std::size_t p = 0; p < N; ++p)
            mean += luminance(sum[3 * p], sum[3 * p + 1], sum[3 * p + 2]) / spp;
        mean /= double(N);
        const double floor = 1e-3 * std::fabs(mean);
        double acc = 0;
        for (std::size_t p = 0; p < N; ++p) {
            const double l = luminance(sum[3 * p], sum[3 * p + 1], sum[3 * p + 2]) / spp;
            const double e = luminance(stderr_of(sum[3 * p], sq[3 * p], spp),
                                       stderr_of(sum[3 * p + 1], sq[3 * p + 1], spp),
                                       stderr_of(sum[3 * p + 2], sq[3 * p + 2], spp));
            const double d = std::max(std::fabs(l), floor);
            if (e == 0) continue;
            if (!(d > 0)) return std::numeric_limits<double>::infinity();
            acc += (e / d) * (e / d);
        }
        return std::sqrt(acc / double(N));
    }

    /// The state of one path of a batch (shade()).
    struct PathState {
        bool alive = false;
        std::uint64_t key = 0;  // mix64 of the path's random-number key
        double pb = 0;
        RGB L{0, 0, 0}, beta{1, 1, 1}, w{0, 0, 0};
        V3 wo{0, 0, 1}, wi{0, 0, 1}, x{0, 0, 0};
        Hit h;  // its hot fields first (render::Hit)
    };
    /// A next-event contribution beta f Le (times k) of path `path`, added unless shadow ray
    /// `ray` (none: no shadow test) is occluded.
    struct Pending {
        static constexpr std::uint32_t none = 0xFFFFFFFFu;
        std::uint32_t path = 0, ray = none;
        RGB a{0, 0, 0};
        double k = 0;
    };
    /// Buffers of shade(), reused across calls (no allocation per sample once grown).
    struct Scratch {
        std::vector<PathState> paths;
        std::vector<RTCRay> shadow;
        std::vector<Pending> pending;
        std::vector<RTCRayHit> next;
        std::vector<std::uint32_t> next_path;
        // The BRDF sample's inputs and outputs by path (structure of arrays).
        std::vector<std::uint64_t> key;
        std::vector<double> nx, ny, nz, wx, wy, wz, cz, tmp;
        std::size_t alive = 0;  // live paths
        void kill(PathState& P) noexcept {
            P.alive = false;
            --alive;
        }
        /// Room for n paths and their streams (no allocation once grown).
        void grow(std::size_t n, std::size_t lights) {
            if (paths.size() >= n) return;
            paths.resize(n);
            shadow.reserve(n * (1 + lights));
            pending.reserve(n * (1 + lights));
            next.reserve(n);
            next_path.reserve(n);
            key.assign(n, 0);
            for (auto* v : {&nx, &ny, &wx, &wy, &wz, &cz}) v->assign(n, 0.0);
            nz.assign(n, 1.0);
            tmp.assign(3 * n, 0.0);
        }
    };

    /// A thread's buffers in render(), kept across its batches (no allocation per sample once
    /// grown), and its counters.
    struct TileBuffers {
        std::vector<First> first;
        Scratch scratch;
        TraceCounters counters;
    };

    /// Occlusion queries of n rays of RTCRayHit records (the ray part), as one stream.
    void occluded(RTCRayHit* rays, std::size_t n) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        for (std::size_t i = 0; i < n; i += 1024) {
            const auto m = static_cast<unsigned>(std::min<std::size_t>(1024, n - i));
            rtcOccluded1M(scene_.handle(), &ctx, &rays[i].ray, m, sizeof(RTCRayHit));
        }
    }

    /// n paths from traced camera rays (mixed[k] = mix64(pixel_key(seed, pixel)) and `sample`
    /// index the random numbers), one vertex depth at a time: at each depth every live path's
    /// shadow rays are traced as one stream and its BRDF rays as another (the paths stay
    /// independent: every path adds its contributions in the order a path-at-a-time tracer
    /// would). L[k] receives path k's radiance; first (optional) its first-hit AOVs. The stages,
    /// in order, per depth: sample_emitters (next-event estimation), the cosine lobes of all
    /// paths (detail::pt::cosine_lobe), sample_bsdf, trace_streams, add_direct, add_bsdf_hits,
    /// next_vertices.
    void shade(const RTCRayHit* primary, std::size_t n, const std::uint64_t* mixed,
               std::uint64_t sample, TraceCounters& c, First* first, RGB* L, Scratch& sc) const {
        sc.grow(n, lights_.size());
        start_paths(primary, n, mixed, sample, first, sc);
        const std::uint64_t stride = 8 + 2 * lights_.size();
        for (int depth = 0; sc.alive > 0; ++depth) {
            Depth d;
            d.depth = depth;
            d.d0 = 2 + stride * std::uint64_t(depth);
            d.more = settings_.bounces < 0 || depth < settings_.bounces;
            // The last vertex's BRDF rays need a distance only for sphere lights: without
            // non-delta lights they are occlusion queries.
            d.query = !d.more && !nondelta_;
            sc.shadow.clear();
            sc.pending.clear();
            sc.next.clear();
            sc.next_path.clear();
            sample_emitters(d, n, c, first, sc);
            // The cosine-lobe directions of all n paths (dead ones included: no branch), in
            // arrays, by loops the compiler vectorises: hashes, the azimuth's polynomial and the
            // frame of the normal; the square roots by detail::pt::sqrt_array (std::sqrt keeps
            // a libm call for errno, which stops vectorisation).
            detail::pt::cosine_lobe(n, d.d0, sc.key.data(), sc.nx.data(), sc.ny.data(),
                                    sc.nz.data(), sc.wx.data(), sc.wy.data(), sc.wz.data(),
                                    sc.cz.data(), sc.tmp.data());
            sample_bsdf(d, n, c, sc);
            trace_streams(d, sc);
            add_direct(sc);
            add_bsdf_hits(d, sc);
            if (d.more) next_vertices(sc);
        }
        for (std::size_t k = 0; k < n; ++k) L[k] = sc.paths[k].L;
    }

    /// One depth of shade(): the random-number dimension of its first sample (d0), whether
    /// the path continues after it (more) and whether its BRDF rays are occlusion queries.
    struct Depth {
        int depth = 0;
        std::uint64_t d0 = 0;
        bool more = false, query = false;
    };

    /// Stage 1: the paths' first vertices from the camera rays' hits (escaped rays take the
    /// background and end), their random-number keys and first-hit AOVs.
    void start_paths(const RTCRayHit* primary, std::size_t n, const std::uint64_t* mixed,
                     std::uint64_t sample, First* first, Scratch& sc) const {
        using namespace detail::rt;
        sc.alive = 0;
        detail::prefetched(
            n, [&](std::size_t k, int stage) { scene_.prefetch_hit(primary[k], stage); },
            [&](std::size_t k) {
                PathState& P = sc.paths[k];
                const V3 dir0{primary[k].ray.dir_x, primary[k].ray.dir_y, primary[k].ray.dir_z};
                if (first) first[k] = First{};
                scene_.shading_hit(primary[k], P.h);
                if (!P.h.valid) {
                    P.alive = false;
                    P.L = env_radiance(normalized(dir0));
                    return;
                }
                P.alive = true;
                ++sc.alive;
                P.L = {0, 0, 0};
                P.beta = {1, 1, 1};
                // The outgoing direction matters only to the Blinn-Phong lobe.
                P.wo = P.h.shininess > 0 ? -normalized(dir0) : -dir0;
                P.key = mix64(detail::pt::hash_mixed(mixed[k], sample));
                if (first) {
                    first[k].hit = true;
                    first[k].albedo = {P.h.albedo[0], P.h.albedo[1], P.h.albedo[2]};
                    first[k].position = P.h.position;
                }
            });
    }

    /// A path's random numbers: rnd(dim) = unit(hash of (its key, dim)).
    struct PathRandom {
        std::uint64_t key;
        double operator()(std::uint64_t dim) const noexcept {
            return detail::rt::unit(detail::pt::hash_mixed(key, dim));
        }
    };
    /// The per-path preamble of the stages sample_emitters and sample_bsdf: f(P, hit, path
    /// index, random numbers) for every live path of the batch, in path order.
    template <class F>
    static void for_live_paths(std::size_t n, Scratch& sc, F&& f) {
        for (std::size_t k = 0; k < n; ++k) {
            PathState& P = sc.paths[k];
            if (!P.alive) continue;
            f(P, P.h, static_cast<std::uint32_t>(k), PathRandom{P.key});
        }
    }

    /// Stage 2, per live path: the shading normal (normal map), next-event estimation (the
    /// environment's and each analytic light's sample: a shadow ray and a pending contribution
    /// each), and whether a BRDF sample follows (its key and normal into the lobe arrays).
    void sample_emitters(const Depth& d, std::size_t n, TraceCounters& c, First* first,
                         Scratch& sc) const {
        using namespace detail::rt;
        constexpr double inf = std::numeric_limits<double>::infinity();
        Bsdf bsdf;
        const auto per_path = [&](PathState& P, const Hit& h, std::uint32_t path,
                                  const PathRandom& rnd) {
            const std::size_t k = path;
            V3 ns = h.shading_normal;
            if (h.normal_map) {
                ++c.normal_map_lookups;
                ns = Scene::normal_mapped(h);
            }
            if (first && d.depth == 0) first[k].normal = ns;
            if (!emitters_) {
                sc.kill(P);
                return;
            }
            const V3 ng = h.geometric_normal, x = h.position;
            P.x = x;
            bsdf.init(h, ns);
            // Environment: importance sampled, balance heuristic against the BRDF.
            if (env_nee_) {
                ++c.environment_samples;
                const auto es = sampler_.sample(rnd(d.d0), rnd(d.d0 + 1));
                const double cf = folded_cosine(ns, ng, es.w);
                if (es.pdf > 0 && cf > 0 && !detail::pt::is_zero(es.radiance)) {
                    const RGB f = bsdf.eval_cos(P.wo, es.w, cf, c.specular_evaluations);
                    const double pb = bsdf.pdf(P.wo, es.w, c.specular_evaluations);
                    const std::uint32_t ray = shadow_ray(sc, c, x, ng, es.w, inf);
                    Pending& pe = sc.pending.emplace_back();
                    pe.path = path;
                    pe.ray = ray;
                    for (std::size_t i = 0; i < 3; ++i) pe.a[i] = P.beta[i] * f[i] * es.radiance[i];
                    pe.k = 1 / (es.pdf + pb);
                }
            }
            // Analytic lights.
            for (std::size_t li = 0; li < lights_.size(); ++li) {
                const Light& light = lights_[li];
                ++c.light_samples;
                const std::uint64_t dl = d.d0 + 8 + 2 * li;
                // A directional light's sample depends on nothing: computed (and checked) once.
                LightSample drawn;
                const LightSample* lsp = &drawn;
                if (light.type == Light::Type::directional) {
                    if (!fixed_ok_[li]) continue;
                    lsp = &fixed_samples_[li];
                } else {
                    drawn = sample_light(light, x, rnd(dl), rnd(dl + 1));
                    if (!usable(drawn)) continue;
                }
                const LightSample& ls = *lsp;
                const double cf = folded_cosine(ns, ng, ls.w);
                if (!(cf > 0)) continue;
                const RGB f = bsdf.eval_cos(P.wo, ls.w, cf, c.specular_evaluations);
                double kw;
                if (ls.delta) {
                    kw = 1;
                } else {
                    const double pb = bsdf.pdf(P.wo, ls.w, c.specular_evaluations);
                    kw = 1 / (ls.pdf + pb);
                }
                const std::uint32_t ray =
                    ls.distance > 0 ? shadow_ray(sc, c, x, ng, ls.w, ls.distance) : Pending::none;
                Pending& pe = sc.pending.emplace_back();
                pe.path = path;
                pe.ray = ray;
                pe.k = kw;
                for (std::size_t i = 0; i < 3; ++i) pe.a[i] = P.beta[i] * f[i] * ls.radiance[i];
            }
            // BRDF sample: continues the path and/or reaches the emitters. Drawn for every live
            // path at once (cosine_lobe, then sample_bsdf).
            if (!d.more && !env_any_ && !nondelta_) {
                sc.kill(P);
                return;
            }
            sc.key[k] = P.key;
            sc.nx[k] = ns.x;
            sc.ny[k] = ns.y;
            sc.nz[k] = ns.z;
        };
        for_live_paths(n, sc, per_path);
    }

    /// A shadow ray from x (offset along ng) toward w, built in place in the stream (a record
    /// built on the stack and copied reloads its small stores as one wide load, which stalls
    /// store forwarding: measured, the copies were a fifth of shade()'s time); its index.
    std::uint32_t shadow_ray(Scratch& sc, TraceCounters& c, const V3& x, const V3& ng, const V3& w,
                             double tmax) const {
        Scene::set_ray(sc.shadow.emplace_back(), scene_.offset_origin(x, ng, w), w, 0, tmax);
        ++c.shadow_rays;
        return static_cast<std::uint32_t>(sc.shadow.size() - 1);
    }

    /// Stage 3, per live path: the BRDF direction (the cosine lobe's, folded above the
    /// geometric surface, for Lambertian vertices; Bsdf::sample for shiny ones), its weight
    /// f cos / pdf and the ray into the BRDF stream (a bounce ray, or at the last vertex a ray
    /// counted as a shadow ray).
    void sample_bsdf(const Depth& d, std::size_t n, TraceCounters& c, Scratch& sc) const {
        using namespace detail::rt;
        Bsdf bsdf;
        const auto per_path = [&](PathState& P, const Hit& h, std::uint32_t path,
                                  const PathRandom& rnd) {
            const std::size_t k = path;
            const V3 ng = h.geometric_normal, x = P.x;
            V3 wi;
            double pb;
            RGB w;
            if (!(h.shininess > 0)) {
                // Lambertian: the folded cosine lobe's weight f cos / pdf is the albedo (the
                // frame is orthonormal: no renormalisation). Only a direction exactly in the
                // tangent plane (probability 0) ends the path.
                wi = fold_above(ng, {sc.wx[k], sc.wy[k], sc.wz[k]});
                const double cf = folded_cosine({sc.nx[k], sc.ny[k], sc.nz[k]}, ng, wi);
                if (!(cf > 0)) {
                    sc.kill(P);
                    return;
                }
                pb = cf * constants::inv_pi;
                w = detail::pt::mul(P.beta, h.albedo);
            } else {
                const V3 ns{sc.nx[k], sc.ny[k], sc.nz[k]};
                bsdf.init(h, ns);
                wi = bsdf.sample(P.wo, rnd(d.d0 + 2), rnd(d.d0 + 3), rnd(d.d0 + 4));
                // A specular direction below the geometric surface ends the path.
                const double cf = folded_cosine(ns, ng, wi);
                if (!(cf > 0)) {
                    sc.kill(P);
                    return;
                }
                pb = bsdf.pdf(P.wo, wi, c.specular_evaluations);
                if (!(pb > 0)) {
                    sc.kill(P);
                    return;
                }
                const RGB f = bsdf.eval_cos(P.wo, wi, cf, c.specular_evaluations);
                w = {f[0] / pb, f[1] / pb, f[2] / pb};
                for (std::size_t i = 0; i < 3; ++i) w[i] *= P.beta[i];
            }
            P.w = w;
            P.wi = wi;
            P.pb = pb;
            Scene::set_ray(sc.next.emplace_back(), scene_.offset_origin(x, ng, wi), wi);
            sc.next_path.push_back(path);
            if (d.more)
                ++c.bounce_rays;
            else
                ++c.shadow_rays;
        };
        for_live_paths(n, sc, per_path);
    }

    /// Stage 4: the shadow stream, then the BRDF stream (closest hits, or occlusion queries
    /// when d.query).
    void trace_streams(const Depth& d, Scratch& sc) const {
        if (!sc.shadow.empty()) {
            if (log_) record(sc.shadow.data(), sc.shadow.size());
            scene_.occluded(sc.shadow.data(), sc.shadow.size());
        }
        if (!sc.next.empty()) {
            if (log_) record(sc.next.data(), sc.next.size(), d.more ? 1 : d.query ? 2 : 3, false);
            if (d.query)
                occluded(sc.next.data(), sc.next.size());
            else
                scene_.intersect(sc.next.data(), sc.next.size());
        }
    }

    /// Stage 5: the next-event contributions whose shadow rays were not occluded.
    static void add_direct(Scratch& sc) noexcept {
        for (const Pending& pe : sc.pending) {
            if (pe.ray != Pending::none && Scene::is_occluded(sc.shadow[pe.ray])) continue;
            RGB& Lp = sc.paths[pe.path].L;
            for (std::size_t i = 0; i < 3; ++i) Lp[i] += pe.a[i] * pe.k;
        }
    }

    /// Stage 6, per BRDF ray: the emitters it reaches (the environment on a miss, non-delta
    /// lights), MIS-weighted against their samples; then the path ends (last vertex or a miss)
    /// or continues with the new throughput (Russian roulette when unbounded).
    void add_bsdf_hits(const Depth& d, Scratch& sc) const {
        using namespace detail::rt;
        constexpr double inf = std::numeric_limits<double>::infinity();
        for (std::size_t j = 0; j < sc.next.size(); ++j) {
            PathState& P = sc.paths[sc.next_path[j]];
            const RTCRayHit& r = sc.next[j];
            const V3& wi = P.wi;
            const RGB& w = P.w;
            const double pb = P.pb;
            const bool miss =
                d.query ? !Scene::is_occluded(r.ray) : r.hit.geomID == RTC_INVALID_GEOMETRY_ID;
            const double t = miss ? inf : double(r.ray.tfar);
            if (miss && env_any_) {
                const RGB Le = env_radiance(wi);
                const double k = env_nee_ ? pb / (pb + sampler_.pdf(wi)) : 1.0;
                for (std::size_t i = 0; i < 3; ++i) P.L[i] += w[i] * Le[i] * k;
            }
            if (nondelta_)
                for (const Light& light : lights_) {
                    if (light.type == Light::Type::directional) continue;
                    const RGB Ll = light_radiance(light, wi, P.x);
                    if (detail::pt::is_zero(Ll)) continue;
                    if (light.type == Light::Type::sphere) {
                        const double tb = detail::pt::ball_distance(P.x, wi, light.position,
                                                                    std::fabs(light.radius));
                        if (!(tb < t)) continue;
                    } else if (!miss) {
                        continue;
                    }
                    const double pl = sample_light_pdf(light, P.x, wi);
                    const double k = pb / (pb + pl);
                    for (std::size_t i = 0; i < 3; ++i) P.L[i] += w[i] * Ll[i] * k;
                }
            if (!d.more || miss) {
                sc.kill(P);
                continue;
            }
            P.beta = w;
            if (settings_.bounces < 0 && d.depth >= 3) {
                const double q = std::min(0.95, std::max({P.beta[0], P.beta[1], P.beta[2]}));
                if (!(unit(detail::pt::hash_mixed(P.key, d.d0 + 5)) < q)) {
                    sc.kill(P);
                    continue;
                }
                for (auto& v : P.beta) v /= q;
            }
            P.wo = -wi;
        }
    }

    /// Stage 7: the hit records of the paths that continue, in a loop of their own (their
    /// loads overlap; prefetched a few hits ahead).
    void next_vertices(Scratch& sc) const {
        detail::prefetched(
            sc.next.size(),
            [&](std::size_t j, int stage) { scene_.prefetch_hit(sc.next[j], stage); },
            [&](std::size_t j) {
                PathState& P = sc.paths[sc.next_path[j]];
                if (!P.alive) return;
                scene_.shading_hit(sc.next[j], P.h);
                if (!P.h.valid) sc.kill(P);
            });
    }

    /// A light sample that can contribute: a positive finite pdf and some radiance.
    static bool usable(const LightSample& ls) noexcept {
        return ls.pdf > 0 && std::isfinite(ls.pdf) && !detail::pt::is_zero(ls.radiance);
    }

    /// The environment's radiance towards w (a constant without the call).
    RGB env_radiance(const V3& w) const noexcept {
        return env_constant_ ? env_c_ : env_.radiance(w);
    }

    /// Appends a traced stream (as it was before tracing) to the log under one lock.
    void record(const RTCRayHit* r, std::size_t n, int kind, bool coherent) const {
        std::lock_guard<std::mutex> lock(*mutex_);
        for (std::size_t i = 0; i < n; ++i)
            log_->push_back(RayRecord{r[i], kind, i == 0 ? std::uint32_t(n) : 0u, coherent});
    }
    void record(const RTCRay* r, std::size_t n) const {
        std::lock_guard<std::mutex> lock(*mutex_);
        for (std::size_t i = 0; i < n; ++i) {
            RTCRayHit rh;
            rh.ray = r[i];
            rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            log_->push_back(RayRecord{rh, 2, i == 0 ? std::uint32_t(n) : 0u, false});
        }
    }

    const Scene& scene_;
    Environment env_;
    std::vector<Light> lights_;
    std::vector<LightSample> fixed_samples_;  // of the directional lights (by light index)
    std::vector<char> fixed_ok_;              // usable(fixed_samples_[i])
    TraceSettings settings_;
    EnvironmentSampler sampler_;
    std::vector<std::string> effects_;
    bool env_nee_ = false, env_any_ = false, nondelta_ = false, emitters_ = false;
    bool env_constant_ = false;  // env_.kind == constant: its radiance is env_c_
    RGB env_c_{0, 0, 0};
    std::unique_ptr<std::mutex> mutex_;
    mutable TraceCounters counters_;
    std::vector<RayRecord>* log_ = nullptr;
};

}  // namespace sphbasis::render
