// sphbasis: sample points on the sphere and the hemisphere for Monte Carlo projection.
//
// Warps from the unit square (named as Mitsuba's warp.h: square_to_X, X_pdf), warps from the
// unit cube to uniformly distributed rotations, and generators of square points: the
// Hammersley point set (low discrepancy, fixed N), the R2 sequence (M. Roberts, "The Unreasonable
// Effectiveness of Quasirandom Sequences", 2018; low discrepancy, extensible) and jittered
// stratification (sqrt(N) x sqrt(N) strata, seeded). Pdfs are with respect to solid angle.
// Uniform rotations: K. Shoemake, "Uniform Random Rotations", Graphics Gems III (1992), 124-132.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "constants.hpp"
#include "error.hpp"
#include "frame.hpp"
#include "vec.hpp"

namespace sphbasis {

namespace detail {
/// The unit direction of height z in [-1, 1] and azimuth phi = 2 pi v.
template <class T>
vec3<T> direction_of_height(T z, T v) noexcept {
    const T s = std::sqrt(std::fmax(T(0), (T(1) - z) * (T(1) + z)));
    const T phi = T(constants::two_pi) * v;
    return {s * std::cos(phi), s * std::sin(phi), z};
}
}  // namespace detail

/// Uniform on the unit sphere (pdf 1/(4 pi)): z = 1 - 2u, phi = 2 pi v.
template <class T>
vec3<T> square_to_uniform_sphere(T u, T v) noexcept {
    return detail::direction_of_height(T(1) - T(2) * u, v);
}
template <class T>
constexpr T uniform_sphere_pdf() noexcept {
    return T(constants::inv_four_pi);
}

/// Uniform on the upper hemisphere z >= 0 (pdf 1/(2 pi)): z = 1 - u.
template <class T>
vec3<T> square_to_uniform_hemisphere(T u, T v) noexcept {
    return detail::direction_of_height(T(1) - u, v);
}
template <class T>
constexpr T uniform_hemisphere_pdf() noexcept {
    return T(constants::inv_two_pi);
}

/// Cosine-weighted on the upper hemisphere (pdf z / pi), Malley's method with the polar map.
template <class T>
vec3<T> square_to_cosine_hemisphere(T u, T v) noexcept {
    const T r = std::sqrt(u);
    const T phi = T(constants::two_pi) * v;
    const T z = std::sqrt(std::fmax(T(0), T(1) - u));
    return {r * std::cos(phi), r * std::sin(phi), z};
}
template <class T>
T cosine_hemisphere_pdf(const vec3<T>& d) noexcept {
    return d.z > T(0) ? d.z * T(constants::inv_pi) : T(0);
}

/// A uniformly distributed rotation (Haar measure on SO(3)) from a point of the unit cube, as
/// a unit quaternion (w, x, y, z), by Shoemake's method (Graphics Gems III, 1992): with
/// r1 = sqrt(1 - u1), r2 = sqrt(u1), t1 = 2 pi u2, t2 = 2 pi u3,
///   q = (r2 cos t2, r1 sin t1, r1 cos t1, r2 sin t2),
/// uniform on the unit 3-sphere, hence (q and -q being one rotation) uniform on SO(3).
/// matrix_from_quaternion() (core/frame.hpp) gives the matrix.
template <class T>
Quat<T> cube_to_rotation(T u1, T u2, T u3) noexcept {
    const T r1 = std::sqrt(std::fmax(T(0), T(1) - u1)), r2 = std::sqrt(std::fmax(T(0), u1));
    const T t1 = T(constants::two_pi) * u2, t2 = T(constants::two_pi) * u3;
    return {r2 * std::cos(t2), r1 * std::sin(t1), r1 * std::cos(t1), r2 * std::sin(t2)};
}

/// A uniformly distributed rotation as ZYZ Euler angles {alpha, beta, gamma} (R = Rz(alpha)
/// Ry(beta) Rz(gamma), core/frame.hpp's matrix_from_euler_zyz and ops/sh_rotation.hpp's
/// rotate_zyz): alpha = 2 pi u1, cos(beta) = 2 u2 - 1, gamma = 2 pi u3 (the Haar measure is
/// sin(beta) dalpha dbeta dgamma / (8 pi^2)).
template <class T>
std::array<T, 3> cube_to_euler_zyz(T u1, T u2, T u3) noexcept {
    const T c = T(2) * u2 - T(1);
    return {T(constants::two_pi) * u1, std::acos(c < T(-1) ? T(-1) : (c > T(1) ? T(1) : c)),
            T(constants::two_pi) * u3};
}

/// Base-2 radical inverse (van der Corput) of i, in [0, 1).
inline double radical_inverse2(std::uint32_t i) noexcept {
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return static_cast<double>(i) * 2.3283064365386963e-10;  // 2^-32
}

/// Point i of the n-point Hammersley set: ((i + 0.5) / n, radical_inverse2(i)).
inline void hammersley(std::uint32_t i, std::uint32_t n, double& u, double& v) noexcept {
    u = (i + 0.5) / n;
    v = radical_inverse2(i);
}

/// Point i of the R2 sequence (Roberts): fractional parts of 0.5 + i (1/g, 1/g^2), g the
/// plastic number 1.32471795724474602596.
inline void r2_sequence(std::uint64_t i, double& u, double& v) noexcept {
    const double a1 = 0.75487766624669276005;  // 1/g
    const double a2 = 0.56984029099805326591;  // 1/g^2
    const double di = static_cast<double>(i);
    u = std::fmod(0.5 + a1 * di, 1.0);
    v = std::fmod(0.5 + a2 * di, 1.0);
}

/// k*k jittered-stratified points in the unit square (one per stratum), seeded.
/// Throws std::invalid_argument for k < 1.
inline void stratified(int k, std::uint64_t seed, std::vector<double>& u, std::vector<double>& v) {
    if (k < 1)
        detail::throw_invalid("stratified", "k >= 1 strata per axis, got " + std::to_string(k));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    u.clear();
    v.clear();
    for (int i = 0; i < k; ++i)
        for (int j = 0; j < k; ++j) {
            u.push_back((i + uni(rng)) / k);
            v.push_back((j + uni(rng)) / k);
        }
}

}  // namespace sphbasis
