// sphbasis render tier: linear HDR images, tiles, tone mapping and false colour.
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
// Image comparison (compare(), error_image() and the metrics) lives in image_metrics.hpp;
// false_colour() here maps an error image to 8-bit RGB on a fixed logarithmic scale
// (1e-3 .. 1, a perceptual blue -> yellow ramp: viridis), unjudged pixels in mid grey.
#pragma once

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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

namespace detail {

/// RGB of pixel i: the first three channels, or grey for one channel.
inline void pixel_rgb(const Image& im, std::size_t i, double out[3]) noexcept {
    const float* p = im.data.data() + i * std::size_t(im.channels);
    if (im.channels >= 3) {
        out[0] = p[0];
        out[1] = p[1];
        out[2] = p[2];
    } else {
        out[0] = out[1] = out[2] = p[0];
    }
}
inline double pixel_luminance(const Image& im, std::size_t i) noexcept {
    double c[3];
    pixel_rgb(im, i, c);
    return luminance(c[0], c[1], c[2]);
}
inline void check_image(const char* fn, const char* what, const Image& im) {
    const std::size_t n = std::size_t(im.width) * std::size_t(im.height);
    if (im.width < 1 || im.height < 1 ||
        !(im.channels == 1 || im.channels == 3 || im.channels == 4) ||
        im.data.size() != n * std::size_t(std::max(im.channels, 0)))
        sphbasis::detail::throw_invalid(
            fn, std::string(*what ? std::string(what) + " " : std::string()) +
                    "an image of 1, 3 or 4 channels with width * height * channels floats, got " +
                    std::to_string(im.width) + "x" + std::to_string(im.height) + "x" +
                    std::to_string(im.channels) + " with " + std::to_string(im.data.size()) +
                    " floats");
}
inline void check_same_size(const char* fn, const char* what, const Image& a, const Image& b) {
    if (a.width != b.width || a.height != b.height)
        sphbasis::detail::throw_invalid(
            fn, std::string(what) + " of the reference's size " + std::to_string(b.width) + "x" +
                    std::to_string(b.height) + ", got " + std::to_string(a.width) + "x" +
                    std::to_string(a.height));
}

/// The sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
inline double srgb_encode(double x) noexcept {
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
}

/// Operator 0 clamp, 1 reinhard, 2 aces, on x >= 0 finite.
inline double tone_map(int op, double x) noexcept {
    switch (op) {
        case 1:
            return x / (1 + x);
        case 2: {
            const double y = (x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14);
            return std::clamp(y, 0.0, 1.0);
        }
        default:
            return std::min(x, 1.0);
    }
}

}  // namespace detail

/// Tone-mapping operators by name: "clamp", "reinhard", "aces" (header comment).
inline std::vector<std::string> tone_map_names() { return {"clamp", "reinhard", "aces"}; }
/// The names as a message lists them: "clamp, reinhard or aces".
inline std::string tone_map_list() {
    const auto names = tone_map_names();
    std::string s;
    for (std::size_t i = 0; i < names.size(); ++i)
        s += (i == 0 ? "" : (i + 1 == names.size() ? " or " : ", ")) + names[i];
    return s;
}

/// Exposure that maps the log-average luminance to 0.18 (header comment): 0.18 / exp(mean of
/// log(luminance)) over finite pixels with luminance > 0; 1 without such a pixel. A 1-channel
/// image is grey. Throws std::invalid_argument for an image of 2 channels or inconsistent size.
inline double auto_exposure(const Image& image) {
    detail::check_image("render::auto_exposure", "", image);
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double l = detail::pixel_luminance(image, i);
        if (l > 0 && std::isfinite(l)) {
            sum += std::log(l);
            ++count;
        }
    }
    if (count == 0) return 1;
    return 0.18 / std::exp(sum / double(count));
}

namespace detail {
/// The index of tone-mapping operator `op` (tone_map_names()) after checking it, the exposure
/// (finite, >= 0) and the image: what to_srgb8() and tone_mapped() share. Throws
/// std::invalid_argument from `fn`.
inline int tone_map_checked(const char* fn, const Image& image, double exposure,
                            const std::string& op) {
    const auto names = tone_map_names();
    int k = -1;
    for (std::size_t i = 0; i < names.size(); ++i)
        if (names[i] == op) k = int(i);
    if (k < 0)
        sphbasis::detail::throw_invalid(
            fn, "a tone-mapping operator " + tone_map_list() + ", got \"" + op + "\"");
    if (!(exposure >= 0) || !std::isfinite(exposure))
        sphbasis::detail::throw_invalid(fn,
                                        "a finite exposure >= 0, got " + std::to_string(exposure));
    check_image(fn, "", image);
    return k;
}
}  // namespace detail

/// 8-bit sRGB RGB (3 bytes per pixel, rows from the top). Throws std::invalid_argument for an
/// unknown operator (the message lists the names), a non-finite or negative exposure, or an
/// image with fewer than 3 channels (1 channel is expanded to grey).
inline std::vector<std::uint8_t> to_srgb8(const Image& image, double exposure,
                                          const std::string& op) {
    constexpr const char* fn = "render::to_srgb8";
    const int k = detail::tone_map_checked(fn, image, exposure, op);
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    std::vector<std::uint8_t> out(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        double c[3];
        detail::pixel_rgb(image, i, c);
        for (int ch = 0; ch < 3; ++ch) {
            const double x = c[ch];
            std::uint8_t b = 0;
            if (x == std::numeric_limits<double>::infinity()) {
                b = 255;
            } else if (x > 0) {  // NaN and negatives stay 0
                const double e = x * exposure;
                const double y = detail::srgb_encode(std::clamp(detail::tone_map(k, e), 0.0, 1.0));
                b = static_cast<std::uint8_t>(std::lround(255 * y));
            }
            out[3 * i + std::size_t(ch)] = b;
        }
    }
    return out;
}

namespace detail {
/// The viridis ramp at s in [0, 1], 8-bit RGB into out[0..2].
inline void viridis(double s, std::uint8_t* out) noexcept {
    // Viridis at 0, 1/4, 1/2, 3/4, 1 (van der Walt and Smith, matplotlib, 2015).
    static const double ramp[5][3] = {
        {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
    const double x = std::clamp(s, 0.0, 1.0) * 4;
    const int k = std::min(3, static_cast<int>(x));
    const double f = x - k;
    for (int c = 0; c < 3; ++c)
        out[c] = static_cast<std::uint8_t>(std::lround((1 - f) * ramp[k][c] + f * ramp[k + 1][c]));
}
}  // namespace detail

/// 8-bit RGB false colour of an error_image(): log10 of the error mapped from [-3, 0] onto the
/// viridis ramp (blue -> green -> yellow; errors below 1e-3 at the blue end, above 1 at the
/// yellow end), negative (unjudged) or NaN pixels mid grey (128, 128, 128). Only channel 0 is
/// read.
inline std::vector<std::uint8_t> false_colour(const Image& error) {
    detail::check_image("render::false_colour", "", error);
    const std::size_t n = std::size_t(error.width) * std::size_t(error.height);
    std::vector<std::uint8_t> out(3 * n, 128);
    for (std::size_t i = 0; i < n; ++i) {
        const double e = error.data[i * std::size_t(error.channels)];
        if (!(e >= 0)) continue;
        detail::viridis(e > 0 ? (std::log10(e) + 3) / 3 : 0.0, &out[3 * i]);
    }
    return out;
}

}  // namespace sphbasis::render
