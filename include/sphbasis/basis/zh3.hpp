// sphbasis: ZH3, linear spherical harmonics plus one quadratic zonal harmonic along their
// direction, and its "hallucinated" variant that derives the zonal coefficient from the linear
// ones. A fitted (non-linear) representation: a fit from SH coefficients and an evaluation.
//
// Reference: T. Roughton, P.-P. Sloan, A. Silvennoinen, M. Iwanicki and P. Shirley, "ZH3:
// Quadratic Zonal Harmonics", i3D 2024 (Proc. ACM Comput. Graph. Interact. Tech. 7(1)). The
// hallucination constants 0.08 and 0.6 as in Probulator (github.com/kayru/Probulator,
// Source/Probulator/SphericalHarmonics.h, shEvaluateDiffuseL1ZH3Hallucinate, contributed by
// the paper's first author).
//
// Conventions (the library's real SH, ACN, no Condon-Shortley phase: y_1,-1 ~ +y, y_10 ~ +z,
// y_11 ~ +x). The coefficients are those of the signal being stored, one channel (irradiance for
// lightmaps and probes; any function on the sphere):
//   stored (5 values): e_0, e_1,-1, e_10, e_11 (the signal's own L0/L1 SH coefficients) and z;
//   axis a = (e_11, e_1,-1, e_10) / |.|  (the L1 direction; (0, 0, 1) when the L1 part is zero);
//   f(n) = e_0 y_00 + sum_m e_1m y_1m(n) + z Y_20(a . n),  Y_20(t) = sqrt(5/(16 pi)) (3 t^2 - 1).
// fit() from 9 SH coefficients: z = <f_2, Y_20(a . )> = sqrt(4 pi/5) sum_m e_2m y_2m(a) (the
// addition theorem), the least-squares best zonal harmonic along a for the band-2 part: so ZH3
// reproduces every signal whose band 2 is zonal about its L1 direction, and in general keeps
// the energy sum_m e_2m^2 only along a.
// hallucinate() from 4 SH coefficients (storage 4): for the irradiance of a radiance,
//   r = |radiance L1| / radiance L0 = (3/2) |e_1| / |e_0|   (irradiance e_1 = 2/3 radiance L1),
//   radiance zonal coefficient = L0 (0.08 r + 0.6 r^2),  z = 1/4 of it (the clamped-cosine factor
//   of band 2), z = 0 when e_0 = 0; r is clamped to sqrt(3), its largest value for a
//   non-negative radiance (signed signals such as the IMSE benchmark's random SH exceed it).
// Both are homogeneous: f(lambda e) = lambda f(e) for every real lambda (the axis flips with the
// sign and Y_20 is even). Domain: the sphere. Cost per direction: 2 dot products, 6 multiply-adds;
// per coefficient set: one normalisation (the axis), done once in Expansion.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"
#include "detail/expansion_batch.hpp"

namespace sphbasis::zh3 {

/// Values stored by ZH3 per channel, and by its hallucinated variant.
inline constexpr int stored = 5;
inline constexpr int stored_hallucinated = 4;
/// The hallucination's polynomial in the radiance ratio r (Roughton et al. 2024).
inline constexpr double hallucinate_c1 = 0.08;
inline constexpr double hallucinate_c2 = 0.6;
/// The largest radiance ratio |L1|/L0 of a non-negative radiance (a delta), where hallucinate()
/// clamps r.
inline constexpr double max_ratio = 1.7320508075688772;  // sqrt(3)

namespace detail {
inline constexpr double y00 = 0.28209479177387814;       // 1/(2 sqrt(pi))
inline constexpr double y1 = 0.48860251190291992;        // sqrt(3/(4 pi))
inline constexpr double y20 = 0.31539156525251999;       // sqrt(5/(16 pi))
inline constexpr double y2xy = 1.0925484305920792;       // sqrt(15/(4 pi))
inline constexpr double y2xx = 0.54627421529603959;      // sqrt(15/(16 pi))
inline constexpr double sqrt4pi_5 = 1.5853309190424043;  // sqrt(4 pi/5)

/// The unit L1 direction of (e_11, e_1-1, e_10), or +z when it is zero or not finite.
template <class T>
void axis_of(const T* c, T& ax, T& ay, T& az) noexcept {
    const T x = c[3], y = c[1], z = c[2];
    const T len = std::sqrt(x * x + y * y + z * z);
    if (len > T(0) && std::isfinite(len)) {
        ax = x / len, ay = y / len, az = z / len;
    } else {
        ax = T(0), ay = T(0), az = T(1);
    }
}
}  // namespace detail

/// ZH3's 5 values from the first 9 SH coefficients of a signal (ACN): out[0..3] = sh[0..3],
/// out[4] = z (see the header). sh and out may alias. T: float or double.
template <class T>
void fit(const T* sh, T* out) {
    sphbasis::detail::check_buffer("zh3::fit", "sh", sh, 9);
    sphbasis::detail::check_buffer("zh3::fit", "out", out, stored);
    T ax, ay, az;
    detail::axis_of(sh, ax, ay, az);
    const double s = detail::y2xy * (double(sh[4]) * ax * ay + double(sh[5]) * ay * az +
                                     double(sh[7]) * ax * az) +
                     detail::y20 * (3 * double(az) * az - 1) * double(sh[6]) +
                     detail::y2xx * (double(ax) * ax - double(ay) * ay) * double(sh[8]);
    const T z = T(detail::sqrt4pi_5 * s);
    for (int k = 0; k < 4; ++k) out[k] = sh[k];
    out[4] = z;
}

/// ZH3's 5 values from 4 SH coefficients (L0, L1) of an irradiance, the zonal one hallucinated
/// (see the header). sh and out may alias.
template <class T>
void hallucinate(const T* sh, T* out) {
    sphbasis::detail::check_buffer("zh3::hallucinate", "sh", sh, 4);
    sphbasis::detail::check_buffer("zh3::hallucinate", "out", out, stored);
    const double e0 = double(sh[0]);
    const double l1 =
        std::sqrt(double(sh[1]) * sh[1] + double(sh[2]) * sh[2] + double(sh[3]) * sh[3]);
    double z = 0;
    if (e0 != 0 && std::isfinite(l1)) {
        // r <= sqrt(3) for every non-negative radiance (a delta reaches it); larger ratios
        // (signed signals) are clamped there rather than let 0.6 r^2 grow without bound.
        const double r = std::min(1.5 * l1 / std::fabs(e0), max_ratio);
        z = 0.25 * e0 * (hallucinate_c1 * r + hallucinate_c2 * r * r);
    }
    for (int k = 0; k < 4; ++k) out[k] = sh[k];
    out[4] = T(z);
}

/// A ZH3 expansion ready to evaluate: the axis and the scaled coefficients, computed once.
/// operator() takes a UNIT direction as float, double or batch<T> components.
template <class T>
struct Expansion {
    T c0 = 0, lx = 0, ly = 0, lz = 0, ax = 0, ay = 0, az = 1, k = 0;
    /// From ZH3's 5 values (fit() or hallucinate()).
    explicit Expansion(const T* c) {
        sphbasis::detail::check_buffer("zh3::Expansion", "coefficients", c, stored);
        detail::axis_of(c, ax, ay, az);
        c0 = T(detail::y00) * c[0];
        lx = T(detail::y1) * c[3];
        ly = T(detail::y1) * c[1];
        lz = T(detail::y1) * c[2];
        k = T(detail::y20) * c[4];
    }
    template <class V>
    SPHBASIS_FORCEINLINE V operator()(const V& x, const V& y, const V& z) const noexcept {
        const V t = V(ax) * x + V(ay) * y + V(az) * z;
        return V(c0) + V(lx) * x + V(ly) * y + V(lz) * z + V(k) * (V(T(3)) * t * t - V(T(1)));
    }
};

/// f(n) for ZH3's 5 values c at direction (x, y, z) (normalised; zero or non-finite -> +z).
template <class T>
T eval(const T* c, T x, T y, T z) {
    normalize_or_pole(x, y, z);
    return Expansion<T>(c)(x, y, z);
}

/// f at `directions` directions (SoA, normalised as by eval), SIMD across directions.
template <class T>
void eval_batch(const T* c, std::size_t directions, const T* xs, const T* ys, const T* zs, T* out) {
    sphbasis::detail::eval_expansion_batch<Expansion>("zh3::eval_batch", c, directions, xs, ys, zs,
                                                      out);
}

/// The SH coefficients (ACN, library convention) of the ZH3 function of 5 values c, to `bands`
/// bands (bands^2 values to out; the expansion is exact from 3 bands: degree <= 2). Returns the
/// squared norm over the sphere of the part above `bands` (c[4]^2 when bands < 3, else 0).
/// The IMSE benchmark's fit protocol integrates the error of ZH3 through this.
template <class T>
double sh_expansion(const T* c, int bands, double* out) {
    sphbasis::detail::check_buffer("zh3::sh_expansion", "coefficients", c, stored);
    if (bands < 0 || bands > 1024)
        sphbasis::detail::throw_invalid("zh3::sh_expansion",
                                        "0 <= bands <= 1024, got " + std::to_string(bands));
    sphbasis::detail::check_buffer("zh3::sh_expansion", "out", out,
                                   static_cast<std::size_t>(bands * bands));
    for (int k = 0; k < bands * bands; ++k) out[k] = 0;
    for (int k = 0; k < 4 && k < bands * bands; ++k) out[k] = double(c[k]);
    if (bands < 3) return double(c[4]) * double(c[4]);
    T ax, ay, az;
    detail::axis_of(c, ax, ay, az);
    const double x = ax, y = ay, z = az, s = detail::sqrt4pi_5 * double(c[4]);
    out[4] = s * detail::y2xy * x * y;
    out[5] = s * detail::y2xy * y * z;
    out[6] = s * detail::y20 * (3 * z * z - 1);
    out[7] = s * detail::y2xy * x * z;
    out[8] = s * detail::y2xx * (x * x - y * y);
    return 0;
}

}  // namespace sphbasis::zh3
