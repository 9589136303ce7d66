// sphbasis render tier: linear HDR images, tiles, tone mapping and image comparison.
//
// CONTRACT (written by the lead; the tracer helper implements the bodies and may add members
// and functions, but keeps these names and meanings: the tool and the representations are
// written against them).
//
// Image: width x height pixels of `channels` floats, row-major from the top row (camera.hpp's
// image coordinates), linear radiance. for_each_tile() runs a function over square tiles in
// parallel on oneTBB; a renderer that derives every random number from (seed, pixel, sample)
// is deterministic whatever the thread count.
//
// Tone mapping (to_srgb8): multiply by `exposure`, apply the named operator per channel,
// encode with the sRGB transfer function (IEC 61966-2-1), round to 8 bits. Operators:
//   "clamp"     min(x, 1);
//   "reinhard"  x / (1 + x) (Reinhard et al., "Photographic Tone Reproduction for Digital
//               Images", SIGGRAPH 2002, eq. 3);
//   "aces"      K. Narkowicz's fit of the ACES filmic curve, (x (2.51 x + 0.03)) /
//               (x (2.43 x + 0.59) + 0.14) clamped to [0, 1] ("ACES Filmic Tone Mapping
//               Curve", blog post, 2016).
// NaN and negative values map to 0, +inf to 255. auto_exposure(): 0.18 / (the log-average
// luminance, Reinhard et al. eq. 1, over finite pixels with luminance > 0; Rec. 709 weights);
// 1 for an image with no such pixel.
//
// Comparison against a noisy reference (compare()): a pixel is "judged" when the reference's
// standard error there (the per-pixel stderr image of the path tracer, luminance) is at most
// `noise_limit` times max(reference luminance, floor), floor = 1e-3 times the mean reference
// luminance (so black pixels are judged by an absolute noise). Over judged pixels:
//   rmse    = sqrt(mean over pixels and the 3 channels of (t - r)^2),
//   rel_mse = mean over pixels of sum_c (t_c - r_c)^2 / (sum_c r_c^2 + eps), eps = (floor)^2,
//   smape   = mean over pixels of sum_c |t_c - r_c| / sum_c (|t_c| + |r_c| + eps')
//            (Probulator's sMAPE), eps' = floor.
// error_image() gives the per-pixel relative error |t - r|_2 / (|r|_2 + floor) (NaN-free; an
// unjudged pixel gets -1), false_colour() maps it to 8-bit RGB on a fixed logarithmic scale
// (1e-3 .. 1, a perceptual blue -> yellow ramp), unjudged pixels in mid grey.
#pragma once

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/error.hpp"

namespace sphbasis::render {

struct Image {
    int width = 0, height = 0, channels = 3;
    std::vector<float> data;  // width * height * channels

    Image() = default;
    /// Throws std::invalid_argument unless 1 <= width, height <= 16384 and 1 <= channels <= 4.
    Image(int w, int h, int c = 3) : width(w), height(h), channels(c) {
        sphbasis::detail::check_range("render::Image", "width", w, 1, 16384);
        sphbasis::detail::check_range("render::Image", "height", h, 1, 16384);
        sphbasis::detail::check_range("render::Image", "channels", c, 1, 4);
        data.assign(std::size_t(w) * std::size_t(h) * std::size_t(c), 0.0f);
    }
    float* at(int x, int y) noexcept {
        return data.data() +
               (std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels);
    }
    const float* at(int x, int y) const noexcept {
        return data.data() +
               (std::size_t(y) * std::size_t(width) + std::size_t(x)) * std::size_t(channels);
    }
};

/// Calls f(x0, y0, x1, y1) for every tile [x0, x1) x [y0, y1) of a width x height image, tiles
/// of `tile` x `tile` pixels (the last ones smaller), in parallel on oneTBB (the caller's task
/// arena decides the thread count).
template <class F>
void for_each_tile(int width, int height, int tile, F&& f) {
    sphbasis::detail::check_range("render::for_each_tile", "tile", tile, 1, 1 << 14);
    const int tx = (width + tile - 1) / tile, ty = (height + tile - 1) / tile;
    tbb::parallel_for(tbb::blocked_range2d<int>(0, ty, 1, 0, tx, 1),
                      [&](const tbb::blocked_range2d<int>& r) {
                          for (int j = r.rows().begin(); j != r.rows().end(); ++j)
                              for (int i = r.cols().begin(); i != r.cols().end(); ++i)
                                  f(i * tile, j * tile, std::min(width, (i + 1) * tile),
                                    std::min(height, (j + 1) * tile));
                      });
}

/// Rec. 709 luminance of linear RGB.
inline double luminance(double r, double g, double b) noexcept {
    return 0.2126 * r + 0.7152 * g + 0.0722 * b;
}

/// Tone-mapping operators by name: "clamp", "reinhard", "aces" (header comment).
inline std::vector<std::string> tone_map_names() {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}
/// Exposure that maps the log-average luminance to 0.18 (header comment).
inline double auto_exposure(const Image& image) {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}
/// 8-bit sRGB RGB (3 bytes per pixel, rows from the top). Throws std::invalid_argument for an
/// unknown operator (the message lists the names), a non-finite or negative exposure, or an
/// image with fewer than 3 channels (1 channel is expanded to grey).
inline std::vector<std::uint8_t> to_srgb8(const Image& image, double exposure,
                                          const std::string& op) {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}

struct ImageError {
    double rmse = 0, rel_mse = 0, smape = 0;
    std::size_t judged = 0, total = 0;  // pixels
};
/// Compares `test` with `reference` (header comment). reference_stderr may be null (every
/// pixel judged). Throws std::invalid_argument for mismatched sizes or noise_limit <= 0.
/// `mask` (optional, 1 channel): pixels where it is 0 are left out (not judged, not counted
/// in total), e.g. the background where every method shows the same environment.
inline ImageError compare(const Image& test, const Image& reference, const Image* reference_stderr,
                          double noise_limit = 0.05, const Image* mask = nullptr) {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}
/// Per-pixel relative error (1 channel; -1 where not judged).
inline Image error_image(const Image& test, const Image& reference, const Image* reference_stderr,
                         double noise_limit = 0.05, const Image* mask = nullptr) {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}
/// 8-bit RGB false colour of an error_image().
inline std::vector<std::uint8_t> false_colour(const Image& error) {
    sphbasis::detail::throw_runtime("render::image", "an implementation, got the contract stub");
}

}  // namespace sphbasis::render
