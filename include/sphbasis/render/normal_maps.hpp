// sphbasis render tier: procedural tangent-space normal maps for tests and scenes.
//
// bumpy_normal_map() encodes the normals of a periodic height field, a sum of K = 16 sine
// waves with integer wave vectors (so the map tiles without a seam),
//   h(u, v) = sum_k a_k sin(2 pi (p_k u + q_k v) + phi_k),
// |(p_k, q_k)| about `frequency` (drawn in [0.5, 1.5] x frequency, random direction, rounded to
// integers, never (0, 0)), a_k proportional to 1/|(p_k, q_k)| (every wave contributes the same
// slope), scaled so that the root-mean-square slope sqrt(E |grad h|^2) over the map equals
// `amplitude` exactly (E over a period: sum_k a_k^2 (2 pi)^2 (p_k^2 + q_k^2) / 2, the waves
// being orthogonal; two draws with the same wave vector are merged first). The gradient is
// analytic (no finite differences), in UV units, i.e. as if the map covered one world unit
// square. The tangent-space normal is n = normalize(-dh/du, -dh/dv, 1) (x along the tangent =
// increasing u, y along the bitangent = increasing v, z along the surface normal), stored as
// the colour c = (n + 1)/2 (mesh.hpp's encoding), 3 floats per texel, row-major from the top
// row; texel (x, y) is sampled at its centre uv ((x + 0.5)/width, 1 - (y + 0.5)/height).
// Deterministic for a seed (SplitMix64).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "../core/constants.hpp"
#include "../core/error.hpp"

namespace sphbasis::render {

/// A flat tangent-space normal map (every texel (0.5, 0.5, 1), the unperturbed normal), RGB.
/// Throws std::invalid_argument unless 1 <= width, height <= 16384.
inline std::vector<float> flat_normal_map(int width, int height) {
    sphbasis::detail::check_range("render::flat_normal_map", "width", width, 1, 16384);
    sphbasis::detail::check_range("render::flat_normal_map", "height", height, 1, 16384);
    std::vector<float> out(std::size_t(width) * std::size_t(height) * 3);
    for (std::size_t i = 0; i < out.size(); i += 3) {
        out[i] = 0.5f;
        out[i + 1] = 0.5f;
        out[i + 2] = 1.0f;
    }
    return out;
}

/// The RGB normal map of a random periodic height field (header comment): `frequency` bumps
/// across the map (cycles per unit UV, > 0), root-mean-square slope `amplitude` (>= 0; 0 gives
/// the flat map), fixed by `seed`. Throws std::invalid_argument unless 1 <= width, height <=
/// 16384, frequency is finite in (0, 1e4] and amplitude finite in [0, 1e3]. Cost: 16 sin/cos
/// per texel.
inline std::vector<float> bumpy_normal_map(int width, int height, double frequency,
                                           double amplitude, std::uint64_t seed) {
    constexpr const char* fn = "render::bumpy_normal_map";
    sphbasis::detail::check_range(fn, "width", width, 1, 16384);
    sphbasis::detail::check_range(fn, "height", height, 1, 16384);
    if (!(frequency > 0 && frequency <= 1e4))
        sphbasis::detail::throw_invalid(
            fn, "a frequency in (0, 1e4], got " + std::to_string(frequency));
    if (!(amplitude >= 0 && amplitude <= 1e3))
        sphbasis::detail::throw_invalid(
            fn, "an amplitude in [0, 1e3], got " + std::to_string(amplitude));
    const double two_pi = 2 * sphbasis::constants::pi;
    std::uint64_t state = seed;
    auto next = [&state]() {  // SplitMix64 (Steele, Lea and Flood, OOPSLA 2014)
        std::uint64_t z = (state += 0x9e3779b97f4a7c15ull);
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
        z ^= z >> 31;
        return static_cast<double>(z >> 11) * 1.1102230246251565e-16;  // [0, 1)
    };
    struct Wave {
        double p, q, a, phase;
    };
    std::vector<Wave> waves;
    constexpr int K = 16;
    for (int k = 0; k < K; ++k) {
        const double r = frequency * (0.5 + next());
        const double phi = two_pi * next();
        double p = std::round(r * std::cos(phi)), q = std::round(r * std::sin(phi));
        if (p == 0 && q == 0) p = 1;
        const double phase = two_pi * next();
        // Merge a repeated wave vector into one wave (sum of two sines of one frequency), so
        // the waves stay orthogonal and the RMS slope below is exact.
        bool merged = false;
        for (auto& w : waves) {
            const bool same = w.p == p && w.q == q, opposite = w.p == -p && w.q == -q;
            if (same || opposite) {
                const double a = 1 / std::sqrt(p * p + q * q);
                const double s = same ? 1.0 : -1.0;  // sin(-x + f) = -sin(x - f)
                const double ph = s > 0 ? phase : -phase;
                const double re = w.a * std::cos(w.phase) + s * a * std::cos(ph);
                const double im = w.a * std::sin(w.phase) + s * a * std::sin(ph);
                w.a = std::hypot(re, im);
                w.phase = std::atan2(im, re);
                merged = true;
                break;
            }
        }
        if (!merged) waves.push_back({p, q, 1 / std::sqrt(p * p + q * q), phase});
    }
    double energy = 0;  // E |grad h|^2
    for (const auto& w : waves)
        energy += 0.5 * w.a * w.a * two_pi * two_pi * (w.p * w.p + w.q * w.q);
    const double scale = energy > 0 ? amplitude / std::sqrt(energy) : 0.0;
    std::vector<float> out(std::size_t(width) * std::size_t(height) * 3);
    for (int y = 0; y < height; ++y) {
        const double v = 1 - (y + 0.5) / height;
        for (int x = 0; x < width; ++x) {
            const double u = (x + 0.5) / width;
            double gu = 0, gv = 0;
            for (const auto& w : waves) {
                const double c = w.a * two_pi * std::cos(two_pi * (w.p * u + w.q * v) + w.phase);
                gu += c * w.p;
                gv += c * w.q;
            }
            gu *= scale;
            gv *= scale;
            const double inv = 1 / std::sqrt(gu * gu + gv * gv + 1);
            float* t = &out[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
            t[0] = static_cast<float>(0.5 * (-gu * inv + 1));
            t[1] = static_cast<float>(0.5 * (-gv * inv + 1));
            t[2] = static_cast<float>(0.5 * (inv + 1));
        }
    }
    return out;
}

}  // namespace sphbasis::render
