// sphbasis render tier: the one image loop. Every image the library makes (the path-traced
// reference, each baked representation, the specular images and their reference) comes from
// ImageLoop, so two images compared with each other have the same pixel sample positions, the
// same reconstruction filter and, when made with the same seed and count, the same samples.
//
// The split follows pbrt-v4 (M. Pharr, W. Jakob and G. Humphreys, "Physically Based Rendering",
// 4th ed., 2023, section 1.3.4: ImageTileIntegrator's tile loop calling RayIntegrator::Li) and
// Mitsuba 3 (SamplingIntegrator::render calling sample()): the loop owns tiles, sample
// positions, camera rays and the film; the caller's `li` owns only what a camera ray shows.
//
// Sample positions (image coordinates as camera.hpp: pixel (x, y) covers [x, x + 1) x
// [y, y + 1)): sample i of pixel p is at (x, y) + (R2 point i of core/sampling.hpp, rotated by
// a per-pixel Cranley-Patterson offset hashed from (seed, p)), i.e. a per-pixel scrambled
// low-discrepancy sequence; every image with one sample per pixel uses the pixel centre
// instead (the frame a game draws and the closed forms tests check). Nothing depends on threads
// or tile order, and a count n image's samples are the first n of a larger count's (passes of a
// progressive renderer continue one sequence).
//
// Filter: a box over the pixel, every sample of a pixel weighted equally (Film::mean()). The
// loop also keeps each pixel's sum of squares (the standard error of the mean, Film) and the
// fraction of camera rays that hit geometry (coverage).
//
// Camera rays: one coherent stream per tile and sample index (Embree's coherent flag: packets);
// with `hits` the loop also makes the hit records (Scene::hit, tangent frame included) for the
// caller, so that several callers shading the same rays (ImageLoop::run with several films)
// pay for the rays and the records once. The loop measures that shared part (camera_seconds)
// apart from each film's `li` (shade_seconds): thread-seconds, summed over threads.
#pragma once

#include <embree3/rtcore.h>
#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "../core/sampling.hpp"
#include "camera.hpp"
#include "detail/rt_math.hpp"
#include "image.hpp"
#include "lighting.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// The random-number key of pixel `pixel` (y * width + x) of an image seeded `seed`: every
/// random number of the pixel's samples derives from it.
inline std::uint64_t pixel_key(std::uint64_t seed, std::uint64_t pixel) noexcept {
    return detail::rt::hash(seed, pixel);
}

/// The per-pixel Cranley-Patterson offset of the pixel with key `key` (pixel_key()).
inline std::array<double, 2> pixel_offset(std::uint64_t key) noexcept {
    return {detail::rt::unit(detail::rt::hash(key, 0x6a09e667u)),
            detail::rt::unit(detail::rt::hash(key, 0xbb67ae85u))};
}

/// Where sample `sample` of a pixel lies inside it, in [0, 1)^2 from its top-left corner, for
/// an image of `spp` samples per pixel: the pixel centre when spp == 1, else R2 point `sample`
/// rotated by `offset` (pixel_offset()).
inline std::array<double, 2> pixel_sample(const std::array<double, 2>& offset, std::uint64_t sample,
                                          int spp) noexcept {
    if (spp == 1) return {0.5, 0.5};
    double u, v;
    r2_sequence(sample, u, v);
    return {detail::rt::rotate01(u, offset[0]), detail::rt::rotate01(v, offset[1])};
}

/// The samples of an image, per pixel: their sums (box filter), optionally sums of squares,
/// and the count of camera rays that hit geometry. Pixel p = y * width + x.
struct Film {
    int width = 0, height = 0;
    int spp = 0;  // samples added to every pixel
    std::vector<double> sum, sq, hits;

    Film() = default;
    /// Throws std::invalid_argument unless 1 <= width, height <= 16384. moments: keep the sums
    /// of squares (standard_error()).
    Film(int w, int h, bool moments) : width(w), height(h) {
        sphbasis::detail::check_range("render::Film", "width", w, 1, 16384);
        sphbasis::detail::check_range("render::Film", "height", h, 1, 16384);
        const std::size_t n = std::size_t(w) * std::size_t(h);
        sum.assign(3 * n, 0.0);
        if (moments) sq.assign(3 * n, 0.0);
        hits.assign(n, 0.0);
    }
    std::size_t pixels() const noexcept { return hits.size(); }
    /// The standard error of the mean of n samples with sum s and sum of squares q (+inf for
    /// n < 2).
    static double standard_error(double s, double q, int n) noexcept {
        if (n < 2) return std::numeric_limits<double>::infinity();
        const double m = s / n;
        const double var = std::max(0.0, (q - s * m) / (n - 1));
        return std::sqrt(var / n);
    }
    /// The image: each pixel the mean of its samples (a box filter).
    Image mean() const {
        return image(3, [&](std::size_t i) { return sum[i] / spp; });
    }
    /// Each pixel's standard error per channel (needs moments; +inf below two samples).
    Image standard_error() const {
        return image(3, [&](std::size_t i) { return standard_error(sum[i], sq[i], spp); });
    }
    /// One channel: the fraction of the pixel's camera rays that hit geometry.
    Image coverage() const {
        return image(1, [&](std::size_t i) { return hits[i] / spp; });
    }

  private:
    template <class F>
    Image image(int channels, F&& f) const {
        Image img(width, height, channels);
        for (std::size_t i = 0; i < img.data.size(); ++i) img.data[i] = static_cast<float>(f(i));
        return img;
    }
};

/// One tile's camera rays for one sample index, traced, as ImageLoop hands them to `li`.
struct CameraBatch {
    std::size_t n = 0;
    std::uint64_t sample = 0;                  // the sample index of every ray of the batch
    const RTCRayHit* rays = nullptr;           // traced: hit.geomID is invalid on a miss
    const vec3<double>* directions = nullptr;  // unit, as the camera made them (double)
    const std::uint64_t* pixels = nullptr;     // y * width + x
    /// mix64(pixel_key(seed, pixel)): the seed of the pixel's other random numbers.
    const std::uint64_t* mixed_keys = nullptr;
    const Hit* hits = nullptr;  // Scene::hit of each ray (null unless the loop makes them)
};

namespace detail {
/// body(k) for k in [0, n), with prefetch(k, stage) issued ahead of it: stage 0 at k + 2 d,
/// stage 1 (which reads what stage 0 fetched) at k + d, d = 8 (about a memory latency of
/// hit-record work): Scene::prefetch_hit's two stages, software-pipelined.
template <class Prefetch, class Body>
void prefetched(std::size_t n, Prefetch&& prefetch, Body&& body) {
    constexpr std::size_t d = 8;
    for (std::size_t k = 0; k < std::min(n, 2 * d); ++k) prefetch(k, 0);
    for (std::size_t k = 0; k < std::min(n, d); ++k) prefetch(k, 1);
    for (std::size_t k = 0; k < n; ++k) {
        if (k + 2 * d < n) prefetch(k + 2 * d, 0);
        if (k + d < n) prefetch(k + d, 1);
        body(k);
    }
}
}  // namespace detail

struct ImageLoopSettings {
    std::uint64_t seed = 0;
    int spp = 1;        // the image's samples per pixel (1: the pixel centre; >= 1)
    int tile = 16;      // tile size in pixels
    bool hits = false;  // make the hit records (CameraBatch::hits)
};

/// What a loop did: camera rays traced, and thread-seconds spent on them (ray generation,
/// tracing and, with `hits`, the hit records) and in each film's `li`.
struct ImageLoopStats {
    std::uint64_t camera_rays = 0;
    double camera_seconds = 0;
    std::vector<double> shade_seconds;  // per film
};

/// The tile loop over one camera's image (header comment).
class ImageLoop {
  public:
    /// Borrows the scene. Throws std::invalid_argument for a camera validate(Camera) rejects,
    /// spp outside [1, 2^24] or tile outside [1, 16384].
    ImageLoop(const Scene& scene, const Camera& camera, const ImageLoopSettings& settings)
        : scene_(scene), camera_(camera), settings_(settings) {
        sphbasis::detail::check_range("render::ImageLoop", "spp", settings.spp, 1, 1 << 24);
        sphbasis::detail::check_range("render::ImageLoop", "tile", settings.tile, 1, 16384);
    }
    const Camera& camera() const noexcept { return camera_.camera(); }
    const PinholeCamera& pinhole() const noexcept { return camera_; }
    const ImageLoopSettings& settings() const noexcept { return settings_; }

    /// Adds samples [first, last) of every pixel to each film (films[k] sized like the image).
    /// For each tile and sample index the camera rays are traced once, then
    /// li(batch, k, out) fills out[0 .. batch.n) with the radiance of each ray for film k, for
    /// every k in order. tile_done(pixel_samples) (optional) runs after each tile, from any
    /// thread. li runs concurrently for different tiles. Throws std::invalid_argument unless
    /// 0 <= first <= last <= spp and every film has the camera's size.
    template <class Li>
    void run(int first, int last, const std::vector<Film*>& films, Li&& li,
             const std::function<void(std::uint64_t)>& tile_done = {}) {
        constexpr const char* fn = "render::ImageLoop::run";
        sphbasis::detail::check_range(fn, "last", last, 0, settings_.spp);
        sphbasis::detail::check_range(fn, "first", first, 0, last);
        const Camera& cam = camera_.camera();
        for (const Film* f : films)
            if (!f || f->width != cam.width || f->height != cam.height)
                sphbasis::detail::throw_invalid(fn, "films of the camera's " +
                                                        std::to_string(cam.width) + "x" +
                                                        std::to_string(cam.height) + " pixels");
        if (first == last) return;
        const std::size_t K = films.size();
        tbb::enumerable_thread_specific<Buffers> buffers;
        using Clock = std::chrono::steady_clock;
        for_each_tile(cam.width, cam.height, settings_.tile, [&](int x0, int y0, int x1, int y1) {
            const std::size_t tw = std::size_t(x1 - x0), n = tw * std::size_t(y1 - y0);
            Buffers& B = buffers.local();
            B.reserve(n, K, settings_.hits);
            for (std::size_t k = 0; k < n; ++k) {
                const std::size_t px = std::size_t(x0) + k % tw, py = std::size_t(y0) + k / tw;
                B.pixel[k] = py * std::size_t(cam.width) + px;
                B.corner[k] = {double(px), double(py)};
                const std::uint64_t key = pixel_key(settings_.seed, B.pixel[k]);
                B.mixed[k] = detail::rt::mix64(key);
                B.offset[k] = pixel_offset(key);
            }
            CameraBatch batch;
            batch.n = n;
            batch.rays = B.rays.data();
            batch.directions = B.dirs.data();
            batch.pixels = B.pixel.data();
            batch.mixed_keys = B.mixed.data();
            batch.hits = settings_.hits ? B.hits.data() : nullptr;
            for (int s = first; s < last; ++s) {
                auto t = Clock::now();
                for (std::size_t k = 0; k < n; ++k) {
                    const auto d = pixel_sample(B.offset[k], std::uint64_t(s), settings_.spp);
                    const CameraRay r = camera_.ray(B.corner[k][0] + d[0], B.corner[k][1] + d[1]);
                    B.dirs[k] = r.direction;
                    Scene::set_ray(B.rays[k], r.origin, r.direction);
                }
                if (on_camera_rays_) on_camera_rays_(B.rays.data(), n);
                intersect_coherent(B.rays.data(), n);
                if (settings_.hits)
                    detail::prefetched(
                        n, [&](std::size_t k, int stage) { scene_.prefetch_hit(B.rays[k], stage); },
                        [&](std::size_t k) { B.hits[k] = scene_.hit(B.rays[k]); });
                B.camera_rays += n;
                auto t1 = Clock::now();
                B.camera_seconds += std::chrono::duration<double>(t1 - t).count();
                t = t1;
                batch.sample = std::uint64_t(s);
                for (std::size_t f = 0; f < K; ++f) {
                    li(static_cast<const CameraBatch&>(batch), f, B.out.data());
                    t1 = Clock::now();
                    B.shade_seconds[f] += std::chrono::duration<double>(t1 - t).count();
                    t = t1;
                    Film& film = *films[f];
                    for (std::size_t k = 0; k < n; ++k) {
                        const std::size_t p = std::size_t(B.pixel[k]);
                        const RGB& L = B.out[k];
                        for (std::size_t ch = 0; ch < 3; ++ch) film.sum[3 * p + ch] += L[ch];
                        if (!film.sq.empty())
                            for (std::size_t ch = 0; ch < 3; ++ch)
                                film.sq[3 * p + ch] += L[ch] * L[ch];
                        if (B.rays[k].hit.geomID != RTC_INVALID_GEOMETRY_ID) film.hits[p] += 1;
                    }
                }
            }
            if (tile_done) tile_done(std::uint64_t(n) * std::uint64_t(last - first));
        });
        for (Film* f : films) f->spp += last - first;
        if (stats_.shade_seconds.size() < K) stats_.shade_seconds.resize(K, 0.0);
        for (const Buffers& B : buffers) {
            stats_.camera_rays += B.camera_rays;
            stats_.camera_seconds += B.camera_seconds;
            for (std::size_t f = 0; f < K; ++f) stats_.shade_seconds[f] += B.shade_seconds[f];
        }
    }
    /// Everything run() did so far.
    const ImageLoopStats& stats() const noexcept { return stats_; }
    /// Calls f(rays, n) with each stream of camera rays before it is traced (for benchmarks
    /// that replay the rays; an empty function stops it).
    void on_camera_rays(std::function<void(const RTCRayHit*, std::size_t)> f) {
        on_camera_rays_ = std::move(f);
    }

  private:
    /// A thread's buffers, kept across its tiles (no allocation per tile).
    struct Buffers {
        std::vector<RTCRayHit> rays;
        std::vector<vec3<double>> dirs;
        std::vector<std::array<double, 2>> corner, offset;
        std::vector<std::uint64_t> pixel, mixed;
        std::vector<Hit> hits;
        std::vector<RGB> out;
        std::uint64_t camera_rays = 0;
        double camera_seconds = 0;
        std::vector<double> shade_seconds;
        void reserve(std::size_t n, std::size_t films, bool with_hits) {
            if (shade_seconds.size() < films) shade_seconds.resize(films, 0.0);
            if (rays.size() < n) {
                rays.resize(n);
                dirs.resize(n);
                corner.resize(n);
                offset.resize(n);
                pixel.resize(n);
                mixed.resize(n);
                out.resize(n);
            }
            if (with_hits && hits.size() < n) hits.resize(n);
        }
    };

    /// One stream with Embree's coherent flag (it traces them as packets).
    void intersect_coherent(RTCRayHit* rays, std::size_t n) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        for (std::size_t i = 0; i < n; i += 1024) {
            const auto m = static_cast<unsigned>(std::min<std::size_t>(1024, n - i));
            rtcIntersect1M(scene_.handle(), &ctx, rays + i, m, sizeof(RTCRayHit));
        }
    }

    const Scene& scene_;
    PinholeCamera camera_;
    ImageLoopSettings settings_;
    ImageLoopStats stats_;
    std::function<void(const RTCRayHit*, std::size_t)> on_camera_rays_;
};

}  // namespace sphbasis::render
