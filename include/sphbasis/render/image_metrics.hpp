// sphbasis render tier: image-comparison metrics, one home for all of them.
//
// Every function compares a test image t with a reference r of the same size (render::Image,
// 1 (grey), 3 or 4 channels; the first three are RGB, linear radiance) over a set of pixels (a
// `mask`: 1 channel, nonzero selects; null: every pixel). Sums are in double; every result is
// finite for finite input, including black, dark and huge (up to FLT_MAX) images; a non-finite
// pixel value throws std::invalid_argument (a NaN is a bug upstream, not an error of 0).
//
// Scale. m = the mean of |r| over the selected pixels and the three channels (m = 1 when it is
// 0: a black reference is judged on the absolute scale of the published constants).
//
// relative_mse(): the relative MSE with a denominator floor of Rousselle, Knaus and Zwicker,
//   "Adaptive Sampling and Reconstruction using Greedy Error Minimization", ACM TOG 30(6)
//   (SIGGRAPH Asia 2011), sec. 4: mean over pixels and channels of (t - r)^2 / (r^2 + eps),
//   eps = 1e-2 m^2. The paper's eps = 1e-2 is for images of values about 1; scaling it with m^2
//   makes the metric invariant under a common scale of both images (exposure), and keeps the
//   pixels darker than a tenth of the mean from dominating: below r = 0.1 m the error counts as
//   absolute, which is what a viewer sees in the dark parts of a frame. Bounded by
//   100 max(t - r)^2 / m^2. Not symmetric.
// smape(): the symmetric mean absolute percentage error, mean over pixels and channels of
//   2 |t - r| / (|t| + |r| + eps), eps = 1e-2 m. In [0, 2); symmetric in t and r only when eps is
//   computed from the same image (here always from the reference).
// outside_stderr_fraction(): the fraction of selected pixels where, in some channel,
//   |t - r| > k s', s' = max(s, 1e-4 m), s the reference's per-pixel standard error (the path
//   tracer's stderr image; null: s = 0 everywhere). A pixel with zero standard error (the
//   reference is exact there: the background, a constant integrand, or a deterministic
//   reference) therefore counts when the difference exceeds k 1e-4 m: float rounding of an exact
//   answer does not count, any visible difference does. An exact test image exceeds k = 3 on
//   about 0.27% of the pixels per independent channel (a normal tail), not 0.
//
// FLIP (flip_error_map(), flip_mean()): LDR-FLIP of Andersson, Nilsson, Akenine-Möller,
//   Oskarsson, Åström and Fairchild, "FLIP: A Difference Evaluator for Alternating Images",
//   Proc. ACM Comput. Graph. Interact. Tech. 3(2) (HPG 2020), sec. 3-4, implemented from the
//   paper's definitions. Input: linear RGB in [0, 1] (an HDR image is tone-mapped first:
//   tone_mapped(), the operator and exposure of the report's PNGs; values are clamped to
//   [0, 1]). p = pixels per degree (default flip_default_ppd: a 0.7 m wide 3840-pixel monitor
//   seen from 0.7 m, 3840 pi / 180 = 67.02). Per pixel:
//   colour: linear sRGB -> XYZ (D65) -> YyCxCz (Yy = 116 Y/Yn - 16, Cx = 500 (X/Xn - Y/Yn),
//     Cz = 200 (Y/Yn - Z/Zn)); each channel filtered by its contrast sensitivity function in the
//     spatial domain, S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2 / b1) + a2 sqrt(pi/b2) exp(-pi^2 x^2 /
//     b2), x the distance in degrees, (a1, b1, a2, b2) = (1, 0.0047, 0, 1e-5) achromatic,
//     (1, 0.0053, 0, 1e-5) red-green, (34.1, 0.04, 13.5, 0.025) blue-yellow; kernel radius
//     ceil(3 sqrt(0.04 / (2 pi^2)) p) pixels, weights normalised to sum 1; back to linear RGB,
//     clamped to [0, 1]; CIELAB (D65); Hunt adjustment a*, b* *= 0.01 L*; HyAB distance
//     |dL| + sqrt(da^2 + db^2); raised to q_c = 0.7 and remapped with p_c = 0.4, p_t = 0.95:
//     e < p_c c: e p_t / (p_c c), else p_t + (e - p_c c) (1 - p_t) / (c - p_c c), c the HyAB^q_c
//     distance of Hunt-adjusted green (0, 1, 0) and blue (0, 0, 1): dE_c in [0, 1].
//   features: on Y/Yn of the unfiltered images, sigma = 0.5 w p pixels, w = 0.082 degrees,
//     radius ceil(3 sigma); edges: the first partial derivatives of the Gaussian, points: the
//     second, each kernel's positive weights scaled to sum 1 and its negative weights to -1;
//     |edge| = |(g_x * Y, g_y * Y)|, |point| likewise; dE_f = (max(| |edge_r| - |edge_t| |,
//     | |point_r| - |point_t| |) / sqrt(2))^q_f, q_f = 0.5.
//   dE = dE_c^(1 - dE_f), in [0, 1]; symmetric in t and r. Filters read clamped-to-edge pixels.
//   Checked against the authors' reference implementation (NVIDIA's flip, Python version 1.3,
//   run outside the project on the test pairs of tools/gen/gen_image_metrics_reference.py at 67,
//   20 and 5 ppd): the same filters, kernels and radii, error maps within 6e-5 per pixel, all of
//   it from the sRGB -> XYZ matrix (derived here from the IEC 61966-2-1 primaries and D65 white;
//   the reference uses slightly different rational constants, up to 1.6e-4 per element).
//   Cost: separable filtering, about (8 (2 r_c + 1) + 8 (2 r_f + 1)) w h multiply-adds (r_c = 10,
//   r_f = 9 at 67 ppd) and about 40 transcendental functions per pixel, in parallel on oneTBB:
//   1920 x 1080 in 3.5 s on two cores shared with other jobs.
//
// compare() and error_image() (the report's rmse, rel_mse, smape and the false-colour error
// images) are defined below, over the "judged" pixels where the reference's noise allows a
// verdict:
//   a pixel is judged when the reference's standard error there (luminance) is at most
//   `noise_limit` times max(reference luminance, floor), floor = 1e-3 times the mean reference
//   luminance (so black pixels are judged by an absolute noise). Over judged pixels:
//   rmse    = sqrt(mean over pixels and the 3 channels of (t - r)^2),
//   rel_mse = mean over pixels of sum_c (t_c - r_c)^2 / (sum_c r_c^2 + eps), eps = (floor)^2
//             (a floor so small that dark pixels dominate it: kept for continuity; prefer
//             rel_mse_floored),
//   smape   = mean over pixels of sum_c |t_c - r_c| / sum_c (|t_c| + |r_c| + eps')
//             (Probulator's sMAPE), eps' = floor,
//   rel_mse_floored, smape_floored = relative_mse() and smape() over the judged pixels.
// error_image() gives the per-pixel relative error |t - r|_2 / (|r|_2 + floor) (NaN-free; an
// unjudged pixel gets -1).
#pragma once

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "image.hpp"

namespace sphbasis::render {

/// FLIP's default pixels per degree: a 0.7 m wide 3840-pixel monitor at 0.7 m, 3840 pi / 180.
inline constexpr double flip_default_ppd = 67.020643276582248;  // 3840 pi / 180

namespace detail {

/// The selected pixels: `mask` null or its channel 0 nonzero.
inline std::vector<char> selection(const Image* mask, std::size_t n) {
    std::vector<char> s(n, 1);
    if (mask)
        for (std::size_t i = 0; i < n; ++i) s[i] = mask->data[i * std::size_t(mask->channels)] != 0;
    return s;
}

inline void check_finite(const char* fn, const char* what, const Image& im) {
    for (std::size_t i = 0; i < im.data.size(); ++i)
        if (!std::isfinite(im.data[i])) {
            const std::size_t p = i / std::size_t(im.channels);
            sphbasis::detail::throw_invalid(fn,
                                            std::string("finite values in ") + what + ", got " +
                                                std::to_string(im.data[i]) + " at pixel (" +
                                                std::to_string(p % std::size_t(im.width)) + ", " +
                                                std::to_string(p / std::size_t(im.width)) + ")");
        }
}

/// The checks every metric makes of its inputs: valid images of one size, finite values.
inline void check_metric_input(const char* fn, const Image& test, const Image& reference,
                               const Image* mask) {
    check_image(fn, "as the test image", test);
    check_image(fn, "as the reference image", reference);
    check_same_size(fn, "a test image", test, reference);
    if (mask) {
        check_image(fn, "as the mask", *mask);
        check_same_size(fn, "a mask", *mask, reference);
    }
    check_finite(fn, "the test image", test);
    check_finite(fn, "the reference image", reference);
}

/// m of the header comment: the mean |r| over the selected pixels and 3 channels, 1 if 0.
inline double metric_scale(const Image& reference, const std::vector<char>& sel) {
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < sel.size(); ++i) {
        if (!sel[i]) continue;
        double r[3];
        pixel_rgb(reference, i, r);
        sum += std::fabs(r[0]) + std::fabs(r[1]) + std::fabs(r[2]);
        count += 3;
    }
    const double m = count ? sum / double(count) : 0;
    return m > 0 ? m : 1;
}

/// The mean of term(t_c, r_c) over the selected pixels and their 3 channels (0 if none).
template <class Term>
double mean_over_channels(const Image& test, const Image& reference, const std::vector<char>& sel,
                          Term term) {
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < sel.size(); ++i) {
        if (!sel[i]) continue;
        double t[3], r[3];
        pixel_rgb(test, i, t);
        pixel_rgb(reference, i, r);
        for (int c = 0; c < 3; ++c) sum += term(t[c], r[c]);
        count += 3;
    }
    return count ? sum / double(count) : 0;
}

inline double relative_mse_on(const Image& test, const Image& reference,
                              const std::vector<char>& sel) {
    const double m = metric_scale(reference, sel), eps = 1e-2 * m * m;
    return mean_over_channels(test, reference, sel, [eps](double t, double r) {
        return (t - r) * (t - r) / (r * r + eps);
    });
}

inline double smape_on(const Image& test, const Image& reference, const std::vector<char>& sel) {
    const double m = metric_scale(reference, sel), eps = 1e-2 * m;
    return mean_over_channels(test, reference, sel, [eps](double t, double r) {
        return 2 * std::fabs(t - r) / (std::fabs(t) + std::fabs(r) + eps);
    });
}

/// Correlates a w x h plane with kx along rows and ky along columns (odd lengths, centred),
/// reading clamped-to-edge pixels.
inline std::vector<double> filter_separable(const std::vector<double>& in, int w, int h,
                                            const std::vector<double>& kx,
                                            const std::vector<double>& ky) {
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    const std::size_t sw = std::size_t(w);
    std::vector<double> tmp(in.size()), out(in.size());
    // Rows: each copied once with its clamped border, then a branch-free dot product per pixel.
    tbb::parallel_for(0, h, [&](int y) {
        std::vector<double> row(sw + 2 * std::size_t(rx));
        const double* src = in.data() + std::size_t(y) * sw;
        for (int i = 0; i < w + 2 * rx; ++i)
            row[std::size_t(i)] = src[std::clamp(i - rx, 0, w - 1)];
        double* dst = tmp.data() + std::size_t(y) * sw;
        for (std::size_t x = 0; x < sw; ++x) {
            double v = 0;
            for (std::size_t k = 0; k < kx.size(); ++k) v += kx[k] * row[x + k];
            dst[x] = v;
        }
    });
    // Columns: whole rows scaled and added (contiguous, vectorisable).
    tbb::parallel_for(0, h, [&](int y) {
        double* dst = out.data() + std::size_t(y) * sw;
        for (int k = -ry; k <= ry; ++k) {
            const double c = ky[std::size_t(k + ry)];
            const double* src = tmp.data() + std::size_t(std::clamp(y + k, 0, h - 1)) * sw;
            for (std::size_t x = 0; x < sw; ++x) dst[x] += c * src[x];
        }
    });
    return out;
}

// Linear sRGB (Rec. 709 primaries, D65 white) to CIE XYZ and back, from the chromaticities of
// IEC 61966-2-1; the white (Xn, Yn, Zn) is the image of RGB (1, 1, 1).
inline constexpr double rgb_to_xyz[3][3] = {
    {0.41239079926595923, 0.35758433938387801, 0.18048078840183429},
    {0.21263900587151022, 0.71516867876775603, 0.072192315360733714},
    {0.019330818715591818, 0.11919477979462598, 0.9505321522496607}};
inline constexpr double xyz_to_rgb[3][3] = {
    {3.2409699419045235, -1.5373831775700944, -0.49861076029300361},
    {-0.96924363628087973, 1.8759675015077204, 0.041555057407175626},
    {0.055630079696993642, -0.20397695888897652, 1.0569715142428786}};
inline constexpr double white_xyz[3] = {
    0.41239079926595923 + 0.35758433938387801 + 0.18048078840183429,
    0.21263900587151022 + 0.71516867876775603 + 0.072192315360733714,
    0.019330818715591818 + 0.11919477979462598 + 0.9505321522496607};

inline void mat3(const double m[3][3], const double v[3], double out[3]) noexcept {
    for (int i = 0; i < 3; ++i) out[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
}

/// CIELAB of linear RGB (D65), Hunt-adjusted (a*, b* scaled by 0.01 L*).
inline void hunt_lab(const double rgb[3], double lab[3]) noexcept {
    double xyz[3];
    mat3(rgb_to_xyz, rgb, xyz);
    constexpr double d = 6.0 / 29.0;
    double f[3];
    for (int i = 0; i < 3; ++i) {
        const double t = xyz[i] / white_xyz[i];
        f[i] = t > d * d * d ? std::cbrt(t) : t / (3 * d * d) + 4.0 / 29.0;
    }
    lab[0] = 116 * f[1] - 16;
    lab[1] = 0.01 * lab[0] * 500 * (f[0] - f[1]);
    lab[2] = 0.01 * lab[0] * 200 * (f[1] - f[2]);
}

inline double hyab(const double a[3], const double b[3]) noexcept {
    return std::fabs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]);
}

/// A tone-mapped image's three planes of YyCxCz (row-major, w * h each) and Y/Yn.
struct FlipPlanes {
    std::vector<double> yy, cx, cz, y_norm;
};
inline FlipPlanes flip_planes(const Image& im) {
    const std::size_t n = std::size_t(im.width) * std::size_t(im.height);
    FlipPlanes p;
    p.yy.resize(n);
    p.cx.resize(n);
    p.cz.resize(n);
    p.y_norm.resize(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        double rgb[3], xyz[3];
        pixel_rgb(im, i, rgb);
        for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
        mat3(rgb_to_xyz, rgb, xyz);
        const double x = xyz[0] / white_xyz[0], y = xyz[1] / white_xyz[1],
                     z = xyz[2] / white_xyz[2];
        p.yy[i] = 116 * y - 16;
        p.cx[i] = 500 * (x - y);
        p.cz[i] = 200 * (y - z);
        p.y_norm[i] = y;
    });
    return p;
}

/// The CSF kernel of one channel as a sum of two separable 1-D Gaussians: weights c_k g_k(x)
/// g_k(y), normalised so that the 2-D kernel sums to 1 (header comment).
struct CsfKernel {
    std::vector<double> g[2];
    double c[2] = {0, 0};
};
inline CsfKernel csf_kernel(double a1, double b1, double a2, double b2, int radius, double ppd) {
    constexpr double pi = 3.14159265358979324;
    CsfKernel k;
    const double a[2] = {a1, a2}, b[2] = {b1, b2};
    double total = 0;
    for (int j = 0; j < 2; ++j) {
        k.g[j].resize(std::size_t(2 * radius + 1));
        double s = 0;
        for (int i = -radius; i <= radius; ++i) {
            const double x = i / ppd;
            s += k.g[j][std::size_t(i + radius)] = std::exp(-pi * pi * x * x / b[j]);
        }
        k.c[j] = a[j] * std::sqrt(pi / b[j]);
        total += k.c[j] * s * s;
    }
    k.c[0] /= total;
    k.c[1] /= total;
    return k;
}
inline std::vector<double> csf_filter(const std::vector<double>& in, int w, int h,
                                      const CsfKernel& k) {
    std::vector<double> out = filter_separable(in, w, h, k.g[0], k.g[0]);
    for (double& v : out) v *= k.c[0];
    if (k.c[1] != 0) {
        const std::vector<double> second = filter_separable(in, w, h, k.g[1], k.g[1]);
        for (std::size_t i = 0; i < out.size(); ++i) out[i] += k.c[1] * second[i];
    }
    return out;
}

/// The comparison's per-pixel state: judged flags and the floor (header comment).
struct Judgement {
    std::vector<char> judged;
    std::size_t total = 0;
    double floor = 0;
};
inline Judgement judge(const char* fn, const Image& test, const Image& reference,
                       const Image* reference_stderr, double noise_limit, const Image* mask) {
    check_image(fn, "as the test image", test);
    check_image(fn, "as the reference image", reference);
    check_same_size(fn, "a test image", test, reference);
    if (reference_stderr) {
        check_image(fn, "as the reference stderr image", *reference_stderr);
        check_same_size(fn, "a reference stderr image", *reference_stderr, reference);
    }
    if (mask) {
        check_image(fn, "as the mask", *mask);
        check_same_size(fn, "a mask", *mask, reference);
    }
    if (!(noise_limit > 0) || !std::isfinite(noise_limit))
        sphbasis::detail::throw_invalid(
            fn, "a finite noise_limit > 0, got " + std::to_string(noise_limit));
    const std::size_t n = std::size_t(reference.width) * std::size_t(reference.height);
    Judgement j;
    j.judged.assign(n, 0);
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        if (mask && !(mask->data[i * std::size_t(mask->channels)] != 0)) continue;
        const double l = pixel_luminance(reference, i);
        if (std::isfinite(l)) {
            sum += l;
            ++count;
        }
    }
    const double mean = count ? sum / double(count) : 0;
    // A black reference has no relative scale: an absolute floor of 1e-6 keeps the ratios finite.
    j.floor = mean > 0 ? 1e-3 * mean : 1e-6;
    for (std::size_t i = 0; i < n; ++i) {
        if (mask && !(mask->data[i * std::size_t(mask->channels)] != 0)) continue;
        ++j.total;
        if (!reference_stderr) {
            j.judged[i] = 1;
            continue;
        }
        const double s = pixel_luminance(*reference_stderr, i);
        const double l = pixel_luminance(reference, i);
        j.judged[i] = s <= noise_limit * std::max(l, j.floor) ? 1 : 0;
    }
    return j;
}

}  // namespace detail

/// Linear RGB in [0, 1] as the report's PNGs show an HDR image, before the sRGB encoding:
/// per channel the tone-mapping operator `op` ("clamp", "reinhard", "aces"; image.hpp) of
/// exposure * max(x, 0), clamped to [0, 1]; NaN maps to 0, +inf to 1. 3 channels out (grey
/// expanded). Throws std::invalid_argument as to_srgb8().
inline Image tone_mapped(const Image& image, double exposure, const std::string& op) {
    constexpr const char* fn = "render::tone_mapped";
    const int k = detail::tone_map_checked(fn, image, exposure, op);
    Image out(image.width, image.height, 3);
    const std::size_t n = std::size_t(image.width) * std::size_t(image.height);
    for (std::size_t i = 0; i < n; ++i) {
        double c[3];
        detail::pixel_rgb(image, i, c);
        for (int ch = 0; ch < 3; ++ch) {
            const double x = c[ch];
            double y = 0;
            if (x == std::numeric_limits<double>::infinity())
                y = 1;
            else if (x > 0)
                y = std::clamp(detail::tone_map(k, x * exposure), 0.0, 1.0);
            out.data[3 * i + std::size_t(ch)] = static_cast<float>(y);
        }
    }
    return out;
}

/// Relative MSE with a floored denominator (header comment: Rousselle et al. 2011; eps =
/// 1e-2 m^2) over the pixels `mask` selects. 0 with no selected pixel. Throws
/// std::invalid_argument for mismatched sizes or a non-finite value. Cost O(w h).
inline double relative_mse(const Image& test, const Image& reference, const Image* mask = nullptr) {
    constexpr const char* fn = "render::relative_mse";
    detail::check_metric_input(fn, test, reference, mask);
    return detail::relative_mse_on(
        test, reference,
        detail::selection(mask, std::size_t(reference.width) * std::size_t(reference.height)));
}

/// sMAPE, mean of 2 |t - r| / (|t| + |r| + 1e-2 m) (header comment), in [0, 2). As
/// relative_mse() otherwise.
inline double smape(const Image& test, const Image& reference, const Image* mask = nullptr) {
    constexpr const char* fn = "render::smape";
    detail::check_metric_input(fn, test, reference, mask);
    return detail::smape_on(
        test, reference,
        detail::selection(mask, std::size_t(reference.width) * std::size_t(reference.height)));
}

/// The fraction of selected pixels where some channel differs by more than k standard errors
/// of the reference, a zero standard error floored at 1e-4 m (header comment). stderr_image
/// null: 0 everywhere. Throws std::invalid_argument for mismatched sizes, a non-finite value,
/// a negative standard error or k not finite and > 0. 0 with no selected pixel.
inline double outside_stderr_fraction(const Image& test, const Image& reference,
                                      const Image* stderr_image, double k = 3,
                                      const Image* mask = nullptr) {
    constexpr const char* fn = "render::outside_stderr_fraction";
    detail::check_metric_input(fn, test, reference, mask);
    if (!(k > 0) || !std::isfinite(k))
        sphbasis::detail::throw_invalid(fn, "a finite k > 0, got " + std::to_string(k));
    if (stderr_image) {
        detail::check_image(fn, "as the stderr image", *stderr_image);
        detail::check_same_size(fn, "a stderr image", *stderr_image, reference);
        detail::check_finite(fn, "the stderr image", *stderr_image);
        for (float v : stderr_image->data)
            if (v < 0)
                sphbasis::detail::throw_invalid(fn,
                                                "standard errors >= 0, got " + std::to_string(v));
    }
    const std::vector<char> sel =
        detail::selection(mask, std::size_t(reference.width) * std::size_t(reference.height));
    const double s_min = 1e-4 * detail::metric_scale(reference, sel);
    std::size_t count = 0, outside = 0;
    for (std::size_t i = 0; i < sel.size(); ++i) {
        if (!sel[i]) continue;
        ++count;
        double t[3], r[3], s[3] = {0, 0, 0};
        detail::pixel_rgb(test, i, t);
        detail::pixel_rgb(reference, i, r);
        if (stderr_image) detail::pixel_rgb(*stderr_image, i, s);
        bool out = false;
        for (int c = 0; c < 3; ++c) out = out || std::fabs(t[c] - r[c]) > k * std::max(s[c], s_min);
        outside += out ? 1 : 0;
    }
    return count ? double(outside) / double(count) : 0;
}

/// The FLIP error map (header comment; LDR-FLIP of Andersson et al. 2020) of two linear RGB
/// images in [0, 1] (values clamped; tone-map HDR images first: tone_mapped()), 1 channel of
/// values in [0, 1], symmetric in the two images. Throws std::invalid_argument for mismatched
/// sizes, a non-finite value or ppd outside [1, 1e4]. Cost: header comment.
inline Image flip_error_map(const Image& test, const Image& reference,
                            double ppd = flip_default_ppd) {
    constexpr const char* fn = "render::flip_error_map";
    detail::check_metric_input(fn, test, reference, nullptr);
    if (!(ppd >= 1 && ppd <= 1e4))
        sphbasis::detail::throw_invalid(
            fn, "pixels per degree in [1, 1e4], got " + std::to_string(ppd));
    constexpr double pi = 3.14159265358979324;
    const int w = reference.width, h = reference.height;
    const std::size_t n = std::size_t(w) * std::size_t(h);
    const detail::FlipPlanes pt = detail::flip_planes(test), pr = detail::flip_planes(reference);

    // Colour: CSF-filtered opponent channels, back to clamped linear RGB, Hunt-adjusted CIELAB.
    const int rc = int(std::ceil(3 * std::sqrt(0.04 / (2 * pi * pi)) * ppd));
    const detail::CsfKernel ka = detail::csf_kernel(1, 0.0047, 0, 1e-5, rc, ppd);
    const detail::CsfKernel krg = detail::csf_kernel(1, 0.0053, 0, 1e-5, rc, ppd);
    const detail::CsfKernel kby = detail::csf_kernel(34.1, 0.04, 13.5, 0.025, rc, ppd);
    auto filtered_lab = [&](const detail::FlipPlanes& p) {
        const std::vector<double> yy = detail::csf_filter(p.yy, w, h, ka);
        const std::vector<double> cx = detail::csf_filter(p.cx, w, h, krg);
        const std::vector<double> cz = detail::csf_filter(p.cz, w, h, kby);
        std::vector<double> lab(3 * n);
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
            const double y = (yy[i] + 16) / 116;
            const double xyz[3] = {(cx[i] / 500 + y) * detail::white_xyz[0],
                                   y * detail::white_xyz[1],
                                   (y - cz[i] / 200) * detail::white_xyz[2]};
            double rgb[3];
            detail::mat3(detail::xyz_to_rgb, xyz, rgb);
            for (double& c : rgb) c = std::clamp(c, 0.0, 1.0);
            detail::hunt_lab(rgb, &lab[3 * i]);
        });
        return lab;
    };
    const std::vector<double> lab_t = filtered_lab(pt), lab_r = filtered_lab(pr);
    constexpr double qc = 0.7, pc = 0.4, ptc = 0.95;
    const double green[3] = {0, 1, 0}, blue[3] = {0, 0, 1};
    double lg[3], lb[3];
    detail::hunt_lab(green, lg);
    detail::hunt_lab(blue, lb);
    const double cmax = std::pow(detail::hyab(lg, lb), qc);

    // Features: edges and points of Y/Yn.
    const double sigma = 0.5 * 0.082 * ppd;
    const int rf = int(std::ceil(3 * sigma));
    const std::size_t len = std::size_t(2 * rf + 1);
    std::vector<double> gauss(len), d1(len), d2(len);
    double gsum = 0, d1pos = 0, d2pos = 0, d2neg = 0;
    for (int i = -rf; i <= rf; ++i) {
        const std::size_t j = std::size_t(i + rf);
        const double x = i;
        gauss[j] = std::exp(-x * x / (2 * sigma * sigma));
        d1[j] = -x * gauss[j];
        d2[j] = (x * x / (sigma * sigma) - 1) * gauss[j];
        gsum += gauss[j];
        if (d1[j] > 0) d1pos += d1[j];
        (d2[j] > 0 ? d2pos : d2neg) += d2[j];
    }
    // The 2-D kernels are d(x) g(y); the sign of a weight is that of d(x), so scaling the
    // positive and negative parts of d by 1 / (sum of that part of d(x) * sum g) normalises the
    // 2-D kernel's parts to +1 and -1.
    for (std::size_t j = 0; j < len; ++j) {
        d1[j] /= d1pos * gsum;
        d2[j] /= (d2[j] > 0 ? d2pos : -d2neg) * gsum;
    }
    auto features = [&](const detail::FlipPlanes& p, std::vector<double>& edge,
                        std::vector<double>& point) {
        const std::vector<double> ex = detail::filter_separable(p.y_norm, w, h, d1, gauss);
        const std::vector<double> ey = detail::filter_separable(p.y_norm, w, h, gauss, d1);
        const std::vector<double> px = detail::filter_separable(p.y_norm, w, h, d2, gauss);
        const std::vector<double> py = detail::filter_separable(p.y_norm, w, h, gauss, d2);
        edge.resize(n);
        point.resize(n);
        tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
            edge[i] = std::hypot(ex[i], ey[i]);
            point[i] = std::hypot(px[i], py[i]);
        });
    };
    std::vector<double> edge_t, point_t, edge_r, point_r;
    features(pt, edge_t, point_t);
    features(pr, edge_r, point_r);

    Image out(w, h, 1);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
        const double e = std::pow(detail::hyab(&lab_t[3 * i], &lab_r[3 * i]), qc);
        const double dc = e < pc * cmax ? ptc / (pc * cmax) * e
                                        : ptc + (e - pc * cmax) / (cmax - pc * cmax) * (1 - ptc);
        const double df = std::pow(
            std::max(std::fabs(edge_r[i] - edge_t[i]), std::fabs(point_r[i] - point_t[i])) /
                std::sqrt(2.0),
            0.5);
        out.data[i] = static_cast<float>(std::clamp(std::pow(dc, 1 - df), 0.0, 1.0));
    });
    return out;
}

/// The mean of a flip_error_map() (channel 0) over the pixels `mask` selects (0 with none).
/// Throws std::invalid_argument for a mask of another size.
inline double flip_mean_of(const Image& flip_map, const Image* mask = nullptr) {
    detail::check_image("render::flip_mean_of", "as the FLIP map", flip_map);
    if (mask) {
        detail::check_image("render::flip_mean_of", "as the mask", *mask);
        detail::check_same_size("render::flip_mean_of", "a mask", *mask, flip_map);
    }
    const std::vector<char> sel =
        detail::selection(mask, std::size_t(flip_map.width) * std::size_t(flip_map.height));
    double sum = 0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < sel.size(); ++i)
        if (sel[i]) {
            sum += flip_map.data[i * std::size_t(flip_map.channels)];
            ++count;
        }
    return count ? sum / double(count) : 0;
}

/// The mean FLIP error, in [0, 1]: flip_mean_of(flip_error_map(test, reference, ppd), mask).
inline double flip_mean(const Image& test, const Image& reference, double ppd = flip_default_ppd,
                        const Image* mask = nullptr) {
    if (mask) {
        detail::check_image("render::flip_mean", "as the mask", *mask);
        detail::check_same_size("render::flip_mean", "a mask", *mask, reference);
    }
    return flip_mean_of(flip_error_map(test, reference, ppd), mask);
}

/// 8-bit RGB of a FLIP map: its value in [0, 1] linearly on the viridis ramp (image.hpp's
/// false_colour() ramp; 0 blue, 1 yellow); NaN and the pixels `mask` leaves out (the metric's
/// mean skips them) mid grey (128, 128, 128). Only channel 0 is read. Throws
/// std::invalid_argument for a mask of another size.
inline std::vector<std::uint8_t> flip_colour(const Image& flip_map, const Image* mask = nullptr) {
    detail::check_image("render::flip_colour", "", flip_map);
    if (mask) {
        detail::check_image("render::flip_colour", "as the mask", *mask);
        detail::check_same_size("render::flip_colour", "a mask", *mask, flip_map);
    }
    const std::size_t n = std::size_t(flip_map.width) * std::size_t(flip_map.height);
    const std::vector<char> sel = detail::selection(mask, n);
    std::vector<std::uint8_t> out(3 * n, 128);
    for (std::size_t i = 0; i < n; ++i) {
        const double e = flip_map.data[i * std::size_t(flip_map.channels)];
        if (sel[i] && e == e) detail::viridis(e, &out[3 * i]);
    }
    return out;
}

struct ImageError {
    double rmse = 0, rel_mse = 0, smape = 0;
    double rel_mse_floored = 0, smape_floored = 0;  // relative_mse(), smape() over judged pixels
    std::size_t judged = 0, total = 0;              // pixels
};
/// Compares `test` with `reference` (header comment). reference_stderr may be null (every
/// pixel judged). Throws std::invalid_argument for mismatched sizes or noise_limit <= 0.
/// `mask` (optional, 1 channel): pixels where it is 0 are left out (not judged, not counted
/// in total), e.g. the background where every method shows the same environment.
/// Images have 1 (grey), 3 or 4 channels; a black reference uses the floor 1e-6. With no judged
/// pixel the three errors are 0 (judged = 0 says so).
inline ImageError compare(const Image& test, const Image& reference, const Image* reference_stderr,
                          double noise_limit = 0.05, const Image* mask = nullptr) {
    const detail::Judgement j =
        detail::judge("render::compare", test, reference, reference_stderr, noise_limit, mask);
    ImageError e;
    e.total = j.total;
    const double eps = j.floor * j.floor, eps1 = j.floor;
    double se = 0, rel = 0, sm = 0;
    for (std::size_t i = 0; i < j.judged.size(); ++i) {
        if (!j.judged[i]) continue;
        ++e.judged;
        double t[3], r[3];
        detail::pixel_rgb(test, i, t);
        detail::pixel_rgb(reference, i, r);
        double d2 = 0, r2 = 0, ad = 0, as = 0;
        for (int c = 0; c < 3; ++c) {
            const double d = t[c] - r[c];
            d2 += d * d;
            r2 += r[c] * r[c];
            ad += std::fabs(d);
            as += std::fabs(t[c]) + std::fabs(r[c]);
        }
        se += d2;
        rel += d2 / (r2 + eps);
        sm += ad / (as + eps1);
    }
    if (e.judged) {
        const double m = double(e.judged);
        e.rmse = std::sqrt(se / (3 * m));
        e.rel_mse = rel / m;
        e.smape = sm / m;
        detail::check_finite("render::compare", "the test image", test);
        detail::check_finite("render::compare", "the reference image", reference);
        e.rel_mse_floored = detail::relative_mse_on(test, reference, j.judged);
        e.smape_floored = detail::smape_on(test, reference, j.judged);
    }
    return e;
}
/// Per-pixel relative error |t - r|_2 / (|r|_2 + floor) (1 channel; -1 where not judged or
/// masked out). Throws as compare().
inline Image error_image(const Image& test, const Image& reference, const Image* reference_stderr,
                         double noise_limit = 0.05, const Image* mask = nullptr) {
    const detail::Judgement j =
        detail::judge("render::error_image", test, reference, reference_stderr, noise_limit, mask);
    Image out(reference.width, reference.height, 1);
    for (std::size_t i = 0; i < j.judged.size(); ++i) {
        if (!j.judged[i]) {
            out.data[i] = -1;
            continue;
        }
        double t[3], r[3];
        detail::pixel_rgb(test, i, t);
        detail::pixel_rgb(reference, i, r);
        double d2 = 0, r2 = 0;
        for (int c = 0; c < 3; ++c) {
            d2 += (t[c] - r[c]) * (t[c] - r[c]);
            r2 += r[c] * r[c];
        }
        const double e = std::sqrt(d2) / (std::sqrt(r2) + j.floor);
        out.data[i] = std::isfinite(e) ? static_cast<float>(e) : std::numeric_limits<float>::max();
    }
    return out;
}
}  // namespace sphbasis::render
