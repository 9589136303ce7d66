// sphbasis render tier: the ground truth, a Monte Carlo path tracer of exactly the effects a
// scene enables.
//
// CONTRACT (written by the lead; the tracer helper implements it and may add members and
// functions, but keeps these names and meanings: the tool and the tests are written against
// them).
//
// Light transport (all radiances linear RGB, surfaces two-sided, albedo from render::Hit):
//   * Primary rays from a PinholeCamera, `spp` jittered samples per pixel (stratified by a
//     per-pixel scrambled low-discrepancy sequence; every random number is a hash of
//     (seed, pixel, sample, dimension), so images do not depend on threads or tile order).
//   * Camera rays that escape show the environment's radiance (the background); analytic lights
//     are not visible to camera rays (a sphere light is a light, not geometry).
//   * At a hit the shading normal is Scene::normal_mapped(hit) when the mesh has a normal map
//     (no normal-map work otherwise). BRDF: Lambertian albedo / pi, plus, only for meshes with
//     shininess s > 0, the energy-normalised Blinn-Phong lobe k_s (s + 8) / (8 pi) (n.h)^s
//     (mesh.hpp). Cosines use the shading normal, clamped at 0; light below the geometric
//     surface is not gathered.
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
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "camera.hpp"
#include "image.hpp"
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
};

struct TraceResult {
    Image color;                     // mean radiance per pixel
    Image stderr_;                   // its standard error per channel
    Image normal, albedo, position;  // first-hit AOVs when requested (background: 0)
    Image coverage;  // 1 channel, always: the fraction of a pixel's camera rays that hit geometry
    int spp = 0;
    double relative_noise = 0;  // the image's relative standard error at the end
    double seconds = 0;         // wall-clock
    TraceCounters counters;
};

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
        : scene_(scene), env_(environment), lights_(lights), settings_(settings) {
        sphbasis::detail::throw_runtime("render::PathTracer",
                                        "an implementation, got the contract stub");
    }
    const std::vector<std::string>& effects() const noexcept { return effects_; }
    /// Renders the camera's image progressively. progress(done, total) (optional) is called
    /// with the finished sample passes' pixel-samples, from any thread.
    TraceResult render(
        const Camera& camera,
        const std::function<void(std::uint64_t, std::uint64_t)>& progress = {}) const {
        (void)camera;
        (void)progress;
        sphbasis::detail::throw_runtime("render::PathTracer",
                                        "an implementation, got the contract stub");
    }
    /// The radiance estimate along one ray with sample index `sample` (for tests: a furnace,
    /// convergence), one path.
    RGB radiance(const vec3<double>& origin, const vec3<double>& direction, std::uint64_t pixel,
                 std::uint64_t sample) const {
        (void)origin, (void)direction, (void)pixel, (void)sample;
        sphbasis::detail::throw_runtime("render::PathTracer",
                                        "an implementation, got the contract stub");
    }
    const TraceCounters& counters() const noexcept { return counters_; }

  private:
    const Scene& scene_;
    Environment env_;
    std::vector<Light> lights_;
    TraceSettings settings_;
    std::vector<std::string> effects_;
    mutable TraceCounters counters_;
};

}  // namespace sphbasis::render
