// sphbasis render tier: importance sampling of an environment (render::Environment) by its
// luminance, for next-event estimation in the path tracer.
//
// A lat-long map is sampled by a piecewise-constant 2D distribution over its texels (Pharr,
// Jakob and Humphreys, "Physically Based Rendering", 3rd ed., 2016, sections 13.6.7 and 14.2.4):
// texel (col, row) gets the weight w = l * Omega_row, l the largest Rec. 709 luminance (of the
// absolute RGB values) among the texel and its 8 neighbours (columns wrapping, rows clamped) and
// Omega_row = (2 pi / width) (cos(theta_row) - cos(theta_row+1)) the texel's exact solid angle
// (the integral of sin(theta) over it). The neighbourhood maximum covers Environment::radiance()'s
// bilinear footprint: wherever radiance() is non-zero the density is positive, so the estimator
// is unbiased on its own. A row is chosen from the marginal CDF with u1, a column from the row's
// conditional CDF with u2, and the remainders of u1 and u2 place the direction uniformly in
// solid angle within the texel (uniform in phi and in cos(theta)): the density is exactly
// P(texel) / Omega_row, and pdf(w) returns the same value for any w. The map's rotation
// applies (world = rotation * map). A constant environment (or a black map) is sampled
// uniformly over the sphere (pdf 1 / (4 pi)); Kind::none has pdf 0 and radiance 0.
//
// Cost: construction O(width height) (one pass, two doubles per texel); sample() two binary
// searches, pdf() one atan2 and an acos-free table lookup.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "../core/constants.hpp"
#include "../core/sampling.hpp"
#include "../core/vec.hpp"
#include "../param/latlong.hpp"
#include "lighting.hpp"

namespace sphbasis::render {

class EnvironmentSampler {
  public:
    struct Sample {
        vec3<double> w{0, 0, 1};  // unit, world space, toward the sky
        double pdf = 0;           // solid angle
        RGB radiance{0, 0, 0};    // Environment::radiance(w)
    };

    /// Copies the environment struct (texels stay borrowed) and builds the distribution.
    /// Throws std::invalid_argument for an environment that render::validate() rejects.
    explicit EnvironmentSampler(const Environment& env) : env_(env) {
        validate(env);
        if (env.kind != Environment::Kind::latlong) return;
        const std::size_t W = std::size_t(env.width), H = std::size_t(env.height);
        cos_row_.resize(H + 1);
        for (std::size_t j = 0; j <= H; ++j)
            cos_row_[j] = std::cos(constants::pi * double(j) / double(H));
        cos_row_[0] = 1;
        cos_row_[H] = -1;
        std::vector<double> lum(W * H);
        for (std::size_t i = 0; i < W * H; ++i) {
            const float* t = env.texels + 3 * i;
            lum[i] = 0.2126 * std::fabs(double(t[0])) + 0.7152 * std::fabs(double(t[1])) +
                     0.0722 * std::fabs(double(t[2]));
        }
        col_cdf_.assign((W + 1) * H, 0.0);
        row_cdf_.assign(H + 1, 0.0);
        const double dphi = constants::two_pi / double(W);
        std::vector<double> rowmax(W);
        for (std::size_t j = 0; j < H; ++j) {
            // Largest luminance over rows j-1..j+1 per column, then over columns i-1..i+1.
            for (std::size_t i = 0; i < W; ++i) {
                double m = lum[j * W + i];
                if (j > 0) m = std::max(m, lum[(j - 1) * W + i]);
                if (j + 1 < H) m = std::max(m, lum[(j + 1) * W + i]);
                rowmax[i] = m;
            }
            const double omega = dphi * (cos_row_[j] - cos_row_[j + 1]);
            double* cdf = &col_cdf_[j * (W + 1)];
            cdf[0] = 0;
            for (std::size_t i = 0; i < W; ++i) {
                const double m =
                    std::max({rowmax[i], rowmax[(i + W - 1) % W], rowmax[(i + 1) % W]});
                cdf[i + 1] = cdf[i] + m * omega;
            }
            row_cdf_[j + 1] = row_cdf_[j] + cdf[W];
        }
        total_ = row_cdf_[H];
        if (!(total_ > 0) || !std::isfinite(total_)) {
            black_ = true;  // sampled uniformly
            return;
        }
        for (auto& c : row_cdf_) c /= total_;
        row_cdf_[H] = 1;
    }

    const Environment& environment() const noexcept { return env_; }
    /// Whether the environment can contribute light (not Kind::none, not all zero, scale != 0).
    bool emits() const noexcept {
        if (env_.scale == 0) return false;
        if (env_.kind == Environment::Kind::constant)
            return env_.constant[0] != 0 || env_.constant[1] != 0 || env_.constant[2] != 0;
        return env_.kind == Environment::Kind::latlong && !black_;
    }
    /// Whether the environment is the same in every direction (constant).
    bool is_constant() const noexcept { return env_.kind == Environment::Kind::constant; }

    /// A direction from (u1, u2) in [0, 1)^2 with its solid-angle pdf and the radiance there.
    Sample sample(double u1, double u2) const noexcept {
        Sample s;
        if (env_.kind == Environment::Kind::none) return s;
        if (env_.kind == Environment::Kind::constant || black_) {
            s.w = square_to_uniform_sphere(u1, u2);
            s.pdf = constants::inv_four_pi;
            s.radiance = env_.radiance(s.w);
            return s;
        }
        const std::size_t W = std::size_t(env_.width), H = std::size_t(env_.height);
        double fv, fu;
        const std::size_t j = pick(row_cdf_.data(), H, u1, fv);
        const double* cdf = &col_cdf_[j * (W + 1)];
        // The row's CDF is unnormalised: scale u2 by its total.
        const std::size_t i = pick_scaled(cdf, W, u2 * cdf[W], fu);
        const double z = cos_row_[j] + fv * (cos_row_[j + 1] - cos_row_[j]);
        const double phi = constants::two_pi * (double(i) + fu) / double(W);
        const double st = std::sqrt(std::max(0.0, (1 - z) * (1 + z)));
        const vec3<double> m{st * std::cos(phi), st * std::sin(phi), z};
        const Mat3<double>& r = env_.rotation;
        s.w = {r[0] * m.x + r[1] * m.y + r[2] * m.z, r[3] * m.x + r[4] * m.y + r[5] * m.z,
               r[6] * m.x + r[7] * m.y + r[8] * m.z};
        s.pdf = texel_pdf(i, j);
        s.radiance = env_.radiance(s.w);
        return s;
    }

    /// The solid-angle density of sample() at unit direction w (world space).
    double pdf(const vec3<double>& w) const noexcept {
        if (env_.kind == Environment::Kind::none) return 0;
        if (env_.kind == Environment::Kind::constant || black_) return constants::inv_four_pi;
        const Mat3<double>& r = env_.rotation;
        double mx = r[0] * w.x + r[3] * w.y + r[6] * w.z;
        double my = r[1] * w.x + r[4] * w.y + r[7] * w.z;
        double mz = r[2] * w.x + r[5] * w.y + r[8] * w.z;
        normalize_or_pole(mx, my, mz);
        const std::size_t W = std::size_t(env_.width), H = std::size_t(env_.height);
        const param::Point2<double> uv = param::latlong_to_square(mx, my, mz);
        const std::size_t i =
            std::min(W - 1, static_cast<std::size_t>(std::max(0.0, uv.x) * double(W)));
        // The row from cos(theta) against the table, so sample() and pdf() agree at row edges.
        std::size_t j = std::min(H - 1, static_cast<std::size_t>(std::max(0.0, uv.y) * double(H)));
        if (j > 0 && mz > cos_row_[j]) --j;
        if (j + 1 < H && mz < cos_row_[j + 1]) ++j;
        return texel_pdf(i, j);
    }

  private:
    double texel_pdf(std::size_t i, std::size_t j) const noexcept {
        const std::size_t W = std::size_t(env_.width);
        const double* cdf = &col_cdf_[j * (W + 1)];
        const double omega = constants::two_pi / double(W) * (cos_row_[j] - cos_row_[j + 1]);
        if (!(omega > 0)) return 0;
        return (cdf[i + 1] - cdf[i]) / total_ / omega;
    }
    /// Index k with cdf[k] <= u < cdf[k + 1] (cdf of n + 1 entries, cdf[n] = 1) and the
    /// remainder (u - cdf[k]) / (cdf[k + 1] - cdf[k]) in [0, 1).
    static std::size_t pick(const double* cdf, std::size_t n, double u, double& rest) noexcept {
        return pick_scaled(cdf, n, u, rest);
    }
    static std::size_t pick_scaled(const double* cdf, std::size_t n, double u,
                                   double& rest) noexcept {
        std::size_t k = static_cast<std::size_t>(std::upper_bound(cdf, cdf + n + 1, u) - cdf);
        k = k == 0 ? 0 : k - 1;
        if (k >= n) k = n - 1;
        // Skip zero-width entries at the top (u at the very end).
        while (k > 0 && !(cdf[k + 1] > cdf[k])) --k;
        const double width = cdf[k + 1] - cdf[k];
        rest = width > 0 ? std::clamp((u - cdf[k]) / width, 0.0, 0x1.fffffffffffffp-1) : 0.5;
        return k;
    }

    Environment env_;
    std::vector<double> cos_row_, row_cdf_, col_cdf_;
    double total_ = 0;
    bool black_ = false;
};

}  // namespace sphbasis::render
