// sphbasis render tier: the materials' reflectance, written once for every renderer: the
// Lambertian lobe and the energy-normalised Blinn-Phong lobe (the path tracer's Bsdf, the
// specular shading and its reference in specular.hpp).
//
// Blinn-Phong: f_s = k_s (s + 8) / (8 pi) max(n.h, 0)^s, h the half vector of the view and the
// light (J. F. Blinn, "Models of Light Reflection for Computer Synthesized Pictures", SIGGRAPH
// 1977; the factor (s + 8) / (8 pi) is the usual approximation of the exact normalisation,
// T. Akenine-Moller, E. Haines and N. Hoffman, "Real-Time Rendering", 3rd ed., 2008, section
// 7.6). Sampled by drawing the half vector with density (s + 1) / (2 pi) (n.h)^s about n
// and reflecting the view in it (pdf of the direction: that over 4 |wo.h|; B. Walter et al.,
// "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007, eq. 14).
//
// Bsdf (the path tracer's material at a path vertex): albedo / pi folded above the geometric
// surface (render/detail/rt_math.hpp: a direction of the cosine lobe about the shading normal
// that falls below the geometric surface is reflected in its tangent plane, so f cos / pdf is
// the albedo exactly) plus, for shininess > 0, the Blinn-Phong lobe about the shading normal,
// clamped at 0. Lobe selection by luminance: the specular lobe with probability
// lum(k_s) / (lum(albedo) + lum(k_s)).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "../core/constants.hpp"
#include "../core/cos_sin_turn.hpp"
#include "../core/frame.hpp"
#include "detail/rt_math.hpp"
#include "image.hpp"
#include "lighting.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// The Blinn-Phong normalisation (s + 8) / (8 pi) (header comment).
inline double blinn_phong_normalization(double shininess) noexcept {
    return (shininess + 8) / (8 * sphbasis::constants::pi);
}

/// The energy-normalised Blinn-Phong lobe (s + 8)/(8 pi) max(n.h, 0)^s (without k_s and n.l);
/// n.h is clamped to [0, 1]. Over light directions l with the view along n, (lobe) (n.l)
/// integrates to (s + 8) [2 (1 - 2^(-(s+4)/2))/(s + 4) - (1 - 2^(-(s+2)/2))/(s + 2)], about 1
/// but not exactly: 1.024 at s = 1, 1.075 at s = 8, 1.027 at s = 64, 1.002 at s = 1000.
/// s = 0 gives 1/pi (the constant lobe).
inline double blinn_phong_lobe(double n_dot_h, double shininess) noexcept {
    const double c = n_dot_h > 0 ? (n_dot_h < 1 ? n_dot_h : 1.0) : 0.0;
    return blinn_phong_normalization(shininess) * std::pow(c, shininess);
}

namespace detail {
/// square_to_cosine_hemisphere (core/sampling.hpp) with core/cos_sin_turn.hpp's polynomial for
/// the azimuth (no libm call).
inline vec3<double> cosine_hemisphere(double u, double v) noexcept {
    const double r = std::sqrt(u);
    double c, s;
    sphbasis::detail::cos_sin_turn(v, c, s);
    return {r * c, r * s, std::sqrt(std::max(0.0, 1 - u))};
}
}  // namespace detail

/// The material at a path vertex (header comment): n is the shading normal, ng the geometric
/// one, both facing the side the path arrived on; wo and wi unit, pointing away from the
/// surface. `evaluations` counts the Blinn-Phong evaluations (the path tracer's counter).
class Bsdf {
  public:
    /// The material of hit h with shading normal `shading`.
    void init(const Hit& h, const vec3<double>& shading) noexcept {
        albedo_ = h.albedo;
        n_ = shading;
        ng_ = h.geometric_normal;
        spec_ = h.shininess > 0;
        if (spec_) {
            ks_ = h.specular;
            s_ = h.shininess;
            const double a = lum(albedo_), b = lum(ks_);
            p_spec_ = a + b > 0 ? b / (a + b) : 0.5;
        }
    }
    bool specular() const noexcept { return spec_; }
    /// The BRDF times the cosine toward wi above the geometric surface: albedo / pi times the
    /// folded cosine cf = rt::folded_cosine(n, ng, wi) (> 0, computed by the caller), plus the
    /// Blinn-Phong lobe times max(n.wi, 0).
    RGB eval_cos(const vec3<double>& wo, const vec3<double>& wi, double cf,
                 std::uint64_t& evaluations) const noexcept {
        using namespace detail::rt;
        const double d = cf * constants::inv_pi;
        RGB f{albedo_[0] * d, albedo_[1] * d, albedo_[2] * d};
        if (spec_) {
            ++evaluations;
            const V3 h = normalized(wo + wi, n_);
            const double nh = dot(n_, h), cs = dot(n_, wi);
            if (nh > 0 && cs > 0) {
                const double k = blinn_phong_lobe(nh, s_) * cs;
                for (std::size_t i = 0; i < 3; ++i) f[i] += ks_[i] * k;
            }
        }
        return f;
    }
    /// The density of sample() toward wi (solid angle).
    double pdf(const vec3<double>& wo, const vec3<double>& wi,
               std::uint64_t& evaluations) const noexcept {
        using namespace detail::rt;
        const double pd = folded_cosine(n_, ng_, wi) * constants::inv_pi;
        if (!spec_) return pd;
        ++evaluations;
        const V3 h = normalized(wo + wi, n_);
        const double nh = dot(n_, h), oh = std::fabs(dot(wo, h));
        double ps = 0;
        if (nh > 0 && oh > 0) ps = (s_ + 1) * constants::inv_two_pi * std::pow(nh, s_) / (4 * oh);
        return (1 - p_spec_) * pd + p_spec_ * ps;
    }
    /// A direction from three uniform numbers (u0 picks the lobe).
    vec3<double> sample(const vec3<double>& wo, double u0, double u1, double u2) const noexcept {
        using namespace detail::rt;
        const Frame<double> f(n_);
        if (spec_ && u0 < p_spec_) {
            const double ct = std::pow(u1, 1 / (s_ + 1));
            const double st = std::sqrt(std::max(0.0, (1 - ct) * (1 + ct)));
            const double phi = constants::two_pi * u2;
            const V3 h = f.to_world(V3{st * std::cos(phi), st * std::sin(phi), ct});
            return normalized(h * (2 * dot(wo, h)) - wo, n_);
        }
        return fold_above(ng_, normalized(f.to_world(detail::cosine_hemisphere(u1, u2)), n_));
    }

  private:
    static double lum(const RGB& c) noexcept { return luminance(c[0], c[1], c[2]); }
    RGB albedo_{0, 0, 0}, ks_{0, 0, 0};
    double s_ = 0, p_spec_ = 0;
    bool spec_ = false;
    vec3<double> n_{0, 0, 1}, ng_{0, 0, 1};
};

}  // namespace sphbasis::render
