// sphbasis render tier, internal: small vector arithmetic, hashing and SH helpers shared by
// render/scene.hpp and render/bake.hpp. Not part of the API.
#pragma once

#include <cmath>
#include <cstdint>

#include "../../core/vec.hpp"

namespace sphbasis::render::detail::rt {

using V3 = vec3<double>;

inline V3 operator+(const V3& a, const V3& b) noexcept { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(const V3& a, const V3& b) noexcept { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator-(const V3& a) noexcept { return {-a.x, -a.y, -a.z}; }
inline V3 operator*(const V3& a, double s) noexcept { return {a.x * s, a.y * s, a.z * s}; }
inline V3 operator*(double s, const V3& a) noexcept { return {a.x * s, a.y * s, a.z * s}; }
inline double length(const V3& a) noexcept { return std::sqrt(dot(a, a)); }
/// a / |a|, or `fallback` when |a| is zero or not finite.
inline V3 normalized(const V3& a, const V3& fallback = {0, 0, 1}) noexcept {
    const double l = length(a);
    return (l > 0 && std::isfinite(l)) ? a * (1.0 / l) : fallback;
}
inline bool finite(const V3& a) noexcept {
    return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}

/// Two-sided diffuse reflection with a shading normal ns that differs from the geometric
/// normal ng (interpolated or normal-mapped normals; both unit and facing the side the ray
/// arrived on, Scene::hit). A cosine-lobe direction about ns may lie below the geometric
/// surface; ending the path there loses energy (a white furnace reads less than 1). Instead the
/// direction is folded: reflected in the geometric tangent plane, w' = w - 2 (ng.w) ng. The
/// folded lobe's density at a direction w above the surface is folded_cosine(ns, ng, w) / pi,
/// folded_cosine = max(ns.w, 0) + max(ns.w', 0), whose integral over the upper hemisphere is
/// pi (the reflection maps the lower hemisphere onto the upper one and preserves solid angle),
/// so the diffuse kernel albedo / pi * folded_cosine reflects exactly the albedo, its sampled
/// weight is the albedo, and it equals the Lambertian albedo / pi * max(n.w, 0) where ns = ng.
inline V3 fold_above(const V3& ng, const V3& w) noexcept {
    const double a = dot(ng, w);
    return a < 0 ? w - ng * (2 * a) : w;
}
/// The folded cosine of fold_above(): 0 for w on or below the geometric surface (ng.w <= 0).
inline double folded_cosine(const V3& ns, const V3& ng, const V3& w) noexcept {
    const double a = dot(ng, w);
    if (!(a > 0)) return 0;
    const double c = dot(ns, w);
    const double r = c - 2 * a * dot(ns, ng);  // ns . (w - 2 (ng.w) ng)
    return (c > 0 ? c : 0) + (r > 0 ? r : 0);
}

/// SplitMix64 finaliser (Steele, Lea and Flood, "Fast Splittable Pseudorandom Number
/// Generators", OOPSLA 2014): a bijective 64-bit mixer.
inline std::uint64_t mix64(std::uint64_t z) noexcept {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}
inline std::uint64_t hash(std::uint64_t a, std::uint64_t b) noexcept {
    return mix64(mix64(a) ^ (b + 0x632be59bd9b4e019ull));
}
inline std::uint64_t hash(std::uint64_t a, std::uint64_t b, std::uint64_t c) noexcept {
    return hash(hash(a, b), c);
}
/// A double in [0, 1) from the top 53 bits.
inline double unit(std::uint64_t h) noexcept {
    return static_cast<double>(h >> 11) * 1.1102230246251565e-16;  // 2^-53
}
/// x + r mod 1, in [0, 1).
inline double rotate01(double x, double r) noexcept {
    double y = x + r;
    y -= std::floor(y);
    return y < 1.0 ? y : 0.0;
}

}  // namespace sphbasis::render::detail::rt
