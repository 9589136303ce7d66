// sphbasis: analytic lights and environment maps to spherical harmonics, any band count.
//
// Every function here returns the SH coefficients of a RADIANCE distribution L(w) over
// incoming directions (this library's basis: real, no Condon-Shortley phase, ACN order).
// Convolve with clamped_cosine_kernel (ops/sh_convolution.hpp) for irradiance E(n); a white
// Lambertian surface then reflects E/pi.
//
// Analytic lights are zonal about their direction d, so (addition theorem) their coefficients
// are Lambda_l y_lm(d) with the Funk-Hecke factors Lambda_l of their profile; no rotation
// matrix is needed:
//   * directional: L = E delta(w - d) (E = irradiance on a surface facing the light),
//     Lambda_l = 1, coefficients E y_lm(d);
//   * cone (uniform cap of angular radius a, the D3DX "cone light"), sphere (a ball of radius
//     r at position p: the cap sin a = r/|p|; the whole sphere when the point is inside), and
//     cap by solid angle (Omega = 2 pi (1 - cos a)): uniform radiance L in the cap,
//     Lambda_0 = 2 pi u,  Lambda_l = 2 pi (u P_l(c) - (P_l(c) - P_{l-1}(c))) / (l + 1),
//     with c = cos a, u = 1 - c (from integral_c^1 P_l = (P_{l-1}(c) - c P_l(c))/(l+1)). The
//     differences delta_l = P_l - P_{l-1} are carried by their own recurrence
//       delta_{l+1} = (l delta_l - (2l+1) u P_l)/(l+1),  P_{l+1} = P_l + delta_{l+1},
//     so small caps (u -> 0) keep full relative accuracy: nothing of size 1 is subtracted;
//   * hemisphere (sky radiance in the half-space around d, ground radiance in the other): the
//     ground everywhere plus (sky - ground) on the cap u = 1. Its irradiance is band-limited to
//     l <= 1, E(n) = pi (sky + ground)/2 + pi (sky - ground)(n . d)/2, so 2 bands are exact.
//   DirectXMath's XMSHEval*Light functions use the Condon-Shortley phase and rescale their
//   output to a target brightness (the directional light by pi / sum_l a_l (2l+1)/4, so that a
//   white diffuse surface facing it reflects 1 at that order; directional_light_peak(n) is
//   that sum). These functions keep physical units; to_condon_shortley converts the signs.
//
// Lights and maps take any coefficient/texel type C with C + C and C * S, where
// S = coefficient_scalar<C>::type (C for float/double, C::value_type, else the type of a member
// r or x, else double: core/scalar.hpp; specialise it for other types). Environment maps:
//   * latitude-longitude: ops/sh_latlong.hpp (sh::project_latlong, included here);
//   * cube maps, 6 faces of N x N, face-major then row-major (texel (face, col, row) at
//     (face N + row) N + col), faces +X, -X, +Y, -Y, +Z, -Z oriented as D3D/OpenGL
//     (param/cubemap.hpp: +X: (1, -t, -s), -X: (-1, -t, s), +Y: (s, 1, t), -Y: (s, -1, -t),
//     +Z: (s, -t, 1), -Z: (-s, -t, -1), s = 2u - 1, t = 2v - 1, v down the rows). Each texel
//     is weighted by its exact solid angle (param::CubeMap::texel_solid_angle: atan(st /
//     sqrt(1 + s^2 + t^2)) at the corners; they sum to 4 pi) and its value taken at the texel
//     centre (optionally at k x k sub-texel centres with their own exact solid angles). The
//     solid-angle-weighted mean is projected exactly and only the deviation from it by the
//     texel rule (a control variate), so a constant map gives exactly (c sqrt(4 pi), 0, ...)
//     at every band count: without it the texel rule leaves O(1/N^2) in the coefficients of
//     the cube-invariant harmonics (l = 4, 6, 8, ...). Smooth maps converge as O(1/N^2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/contiguous.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"
#include "../core/scalar.hpp"
#include "../core/small_buffer.hpp"
#include "../core/vec.hpp"
#include "../param/cubemap.hpp"
#include "sh_latlong.hpp"

namespace sphbasis::sh {

namespace detail {

/// Scratch of doubles for the per-call factors and basis values: on the stack up to 8 bands.
using LightScratch = sphbasis::detail::SmallBuffer<double, 64>;

/// Funk-Hecke factors of the indicator of the cap 1 - cos(theta) <= u, 0 <= u <= 2, into
/// out[0..bands). Stable for small u (header comment).
inline void cap_factors(int bands, double u, double* out) noexcept {
    if (bands <= 0) return;
    out[0] = constants::two_pi * u;
    double p = 1, d = 0;  // P_l(c) and delta_l = P_l - P_{l-1}, c = 1 - u
    for (int l = 0; l + 1 < bands; ++l) {
        // Advance to l + 1.
        const double dn = l == 0 ? -u : (l * d - (2 * l + 1) * u * p) / (l + 1);
        p += dn;
        d = dn;
        const int L = l + 1;
        out[L] = constants::two_pi * (u * p - d) / (L + 1);
    }
}

template <class T, class C>
void check_light(int bands, T x, T y, T z, const C* out, const char* fn) {
    static_assert(sphbasis::detail::is_scalable<C, coefficient_scalar_t<C>>::value,
                  "sphbasis::sh lights: the coefficient type C needs C + C and "
                  "C * coefficient_scalar_t<C> (specialise sphbasis::coefficient_scalar).");
    check_bands(bands, fn);
    sphbasis::detail::check_buffer(fn, "out", out, static_cast<std::size_t>(bands));
    // A finite squared length > 0 (the normalising kernels compute it too) settles it at once.
    const T r2 = x * x + y * y + z * z;
    if (r2 > T(0) && r2 <= std::numeric_limits<T>::max()) return;
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
        (x == T(0) && y == T(0) && z == T(0)))
        sphbasis::detail::throw_invalid(fn, "a finite non-zero direction");
}

/// The pointer of an output buffer given as C* or as a contiguous range of >= bands^2 values.
template <class Out>
auto light_out(int bands, Out&& out, const char* fn) {
    check_bands(bands, fn);
    return sphbasis::detail::buffer_data(
        fn, "out", out, static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
}

/// out_k = a_l y_k(d) * colour for l < bands, from the factors a[0..bands).
template <class T, class C>
void zonal_out(int bands, T x, T y, T z, const double* a, const C& colour, C* out) {
    using S = coefficient_scalar_t<C>;
    LightScratch yv(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
    eval(bands, static_cast<double>(x), static_cast<double>(y), static_cast<double>(z), yv.data());
    for (int l = 0; l < bands; ++l)
        for (int k = l * l; k < (l + 1) * (l + 1); ++k)
            out[k] = colour * static_cast<S>(a[l] * yv[static_cast<std::size_t>(k)]);
}

/// sum_i v[i] * w[i] over n >= 1 terms with eight independent partial sums: a single running
/// sum is a chain of dependent additions that the compiler may not reorder (no -ffast-math),
/// and it is the bottleneck of the projections.
template <class C, class S>
C dot_accumulate(std::size_t n, const C* v, const S* w) {
    if (n < 8) {
        C s = v[0] * w[0];
        for (std::size_t i = 1; i < n; ++i) s = s + v[i] * w[i];
        return s;
    }
    C s[8];
    for (std::size_t j = 0; j < 8; ++j) s[j] = v[j] * w[j];
    const std::size_t blocks = n / 8;
    for (std::size_t b = 1; b < blocks; ++b)
        for (std::size_t j = 0; j < 8; ++j) s[j] = s[j] + v[8 * b + j] * w[8 * b + j];
    for (std::size_t i = 8 * blocks; i < n; ++i) s[0] = s[0] + v[i] * w[i];
    return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

/// A light's colour in the output's coefficient type O: the lights deduce the colour type and
/// the output type separately, so directional_light(3, x, y, z, 1.0, float_out) writes floats.
template <class O, class C>
SPHBASIS_FORCEINLINE O light_colour(const C& colour) {
    static_assert(std::is_constructible_v<O, const C&>,
                  "sphbasis::sh lights: the colour must convert to the output's coefficient type "
                  "(a double colour with float outputs converts; an RGB type needs a constructor "
                  "from the colour type).");
    if constexpr (std::is_same_v<O, C>)
        return colour;
    else
        return static_cast<O>(colour);
}

}  // namespace detail

// ---------------------------------------------------------------------------------------------
// The lights with a compile-time band count N (1..8): directional_light<N>, cone_light<N>,
// spherical_light<N>, hemisphere_light<N>. The same coefficients as the run-time forms below
// (which use them for 1..8 bands after their checks), for the hot path: the basis by the
// unrolled normalising kernel (sh::eval<N>'s) in the coefficient's scalar (float for float or
// float RGB coefficients, else double), written straight into out times one colour per band
// (colour * factor, formed once per band), the zonal factors as constants (directional,
// hemisphere; the hemisphere's zero bands are stored as zeros without evaluating them) or by
// the cap recurrence unrolled (cone, sphere), no run-time checks (SPHBASIS_ASSERT in debug
// builds), noexcept. Arguments outside the domain of the run-time forms give finite results
// instead of throwing: a zero direction is taken as +z (sh::eval's pole), a half-angle is
// clamped to [0, pi], a negative radius to 0.

namespace detail {
/// Floating-point type the fixed-band lights evaluate in: float for float coefficients, else
/// double.
template <class C>
using light_eval_t =
    std::conditional_t<std::is_same_v<coefficient_scalar_t<C>, float>, float, double>;

/// The band l of ACN index k < 64 (a table, so a constant k folds).
inline constexpr auto light_band_of = [] {
    std::array<int, 64> b{};
    for (int k = 0; k < 64; ++k)
        while ((b[static_cast<std::size_t>(k)] + 1) * (b[static_cast<std::size_t>(k)] + 1) <= k)
            ++b[static_cast<std::size_t>(k)];
    return b;
}();

/// cap_factors() for a compile-time band count, in E (unrolled).
template <int N, class E>
SPHBASIS_FORCEINLINE void cap_factors_fixed(E u, E* out) noexcept {
    const E two_pi = E(constants::two_pi);
    out[0] = two_pi * u;
    E p = 1, d = 0;
    for (int l = 0; l + 1 < N; ++l) {
        const E dn = l == 0 ? -u : (E(l) * d - E(2 * l + 1) * u * p) / E(l + 1);
        p += dn;
        d = dn;
        out[l + 1] = two_pi * (u * p - d) / E(l + 2);
    }
}

/// The hemisphere's factors (u = 1), exact at compile time: 2 pi, pi, 0, -pi/4, 0, pi/8, 0, ...
/// (zero at every even l >= 2: Lambda_l = 2 pi (P_{l-1}(0) - P_{l+1}(0)) / (2l + 1)).
template <int N>
constexpr std::array<double, N> hemisphere_factors() noexcept {
    std::array<double, N> f{};
    f[0] = constants::two_pi;
    double p = 1, d = 0;
    for (int l = 0; l + 1 < N; ++l) {
        const double dn = l == 0 ? -1.0 : (l * d - (2 * l + 1) * p) / (l + 1);
        p += dn;
        d = dn;
        f[static_cast<std::size_t>(l + 1)] =
            (l + 1) % 2 == 0 ? 0.0 : constants::two_pi * (p - d) / (l + 2);
    }
    return f;
}

/// Bit l set: band l of the hemisphere light is zero (even l >= 2).
inline constexpr unsigned hemisphere_zero_bands = 0x55555554u;

template <class C, class Band, std::size_t... Ls>
SPHBASIS_FORCEINLINE std::array<C, sizeof...(Ls)> light_band_colours(Band&& band,
                                                                     std::index_sequence<Ls...>) {
    return {{band(static_cast<int>(Ls))...}};
}

// SPHBASIS_SH_LIGHTS_VECTOR: the 3-band RGB fan-out in AVX-512 (16-lane) or AVX2 (8-lane)
// registers (GCC/clang); 0 where neither is enabled.
#if (defined(__GNUC__) || defined(__clang__)) && defined(__AVX512F__)
#define SPHBASIS_SH_LIGHTS_VECTOR 512
#elif (defined(__GNUC__) || defined(__clang__)) && defined(__AVX2__)
#define SPHBASIS_SH_LIGHTS_VECTOR 256
#else
#define SPHBASIS_SH_LIGHTS_VECTOR 0
#endif
#if SPHBASIS_SH_LIGHTS_VECTOR
#include <immintrin.h>
#endif

#if SPHBASIS_SH_LIGHTS_VECTOR
/// C is three packed floats that C * float scales one by one: trivially copyable, 12 bytes,
/// float scalar, and (checked once per type at run time, on the values 1, 2, 4 times 0.5) its
/// operator* acting on the three floats of its representation. Such colours (any float RGB
/// struct) take the vector fan-out of zonal_out_fixed at 3 bands.
template <class C>
inline constexpr bool maybe_packed_rgb_v =
    std::is_trivially_copyable_v<C>&& std::is_default_constructible_v<C> &&
    sizeof(C) == 3 * sizeof(float) && std::is_same_v<coefficient_scalar_t<C>, float>;
template <class C>
bool packed_rgb() {
    static const bool ok = [] {
        const float a[3] = {1.0f, 2.0f, 4.0f};
        C c;
        std::memcpy(static_cast<void*>(&c), a, sizeof(c));
        const C d = c * 0.5f;
        float b[3];
        std::memcpy(b, static_cast<const void*>(&d), sizeof(b));
        return b[0] == 0.5f && b[1] == 1.0f && b[2] == 2.0f;
    }();
    return ok;
}

#if SPHBASIS_SH_LIGHTS_VECTOR == 512
/// out (27 floats) = y[k] * colour[band of k][channel] for 3 bands: two 16-lane products of
/// permuted y and colour vectors, stored as 16 + 8 + 2 + 1 floats (no masked store whose
/// 64-byte span would block later loads).
SPHBASIS_FORCEINLINE void fan_out_rgb3(const float* yv, const float* col, float* out) noexcept {
    const __mmask16 all = 0xFFFF;
    const __m512 yvec = _mm512_setr_ps(yv[0], yv[1], yv[2], yv[3], yv[4], yv[5], yv[6], yv[7],
                                       yv[8], 0, 0, 0, 0, 0, 0, 0);
    const __m512 cvec = _mm512_setr_ps(col[0], col[1], col[2], col[3], col[4], col[5], col[6],
                                       col[7], col[8], 0, 0, 0, 0, 0, 0, 0);
    // lane i of the output: y index i / 3, colour index 3 * band(i / 3) + i % 3
    const __m512i iy0 = _mm512_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4, 5);
    const __m512i iy1 = _mm512_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7, 8, 8, 8, 0, 0, 0, 0, 0);
    const __m512i ic0 = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 3, 4, 5, 3, 4, 5, 6, 7, 8, 6);
    const __m512i ic1 = _mm512_setr_epi32(7, 8, 6, 7, 8, 6, 7, 8, 6, 7, 8, 0, 0, 0, 0, 0);
    const __m512 o0 = _mm512_mul_ps(_mm512_maskz_permutexvar_ps(all, iy0, yvec),
                                    _mm512_maskz_permutexvar_ps(all, ic0, cvec));
    const __m512 o1 = _mm512_mul_ps(_mm512_maskz_permutexvar_ps(all, iy1, yvec),
                                    _mm512_maskz_permutexvar_ps(all, ic1, cvec));
    _mm512_storeu_ps(out, o0);
    const __m256d lo = _mm512_maskz_extractf64x4_pd(__mmask8(0xF), _mm512_castps_pd(o1), 0);
    _mm256_storeu_ps(out + 16, _mm256_castpd_ps(lo));
    const __m256d hi = _mm512_maskz_extractf64x4_pd(__mmask8(0xF), _mm512_castps_pd(o1), 1);
    const __m128 h = _mm256_castps256_ps128(_mm256_castpd_ps(hi));  // lanes 8..11 of o1
    _mm_storel_pi(reinterpret_cast<__m64*>(out + 24), h);
    _mm_store_ss(out + 26, _mm_movehl_ps(h, h));
}
#elif SPHBASIS_SH_LIGHTS_VECTOR == 256
/// fan_out_rgb3 in 8-lane registers: y and the colours as lanes 0..7 and 1..8 of their nine
/// values, three 8-lane products of permuted vectors (bands 1..2 read the colours shifted by
/// one), the last three floats y_8 times band 2's colour.
SPHBASIS_FORCEINLINE void fan_out_rgb3(const float* yv, const float* col, float* out) noexcept {
    const __m256 ylo = _mm256_setr_ps(yv[0], yv[1], yv[2], yv[3], yv[4], yv[5], yv[6], yv[7]);
    // from the scalars, not loaded: the colours were just written (no store forwarding)
    const __m256 clo =
        _mm256_setr_ps(col[0], col[1], col[2], col[3], col[4], col[5], col[6], col[7]);
    const __m256 chi =
        _mm256_setr_ps(col[1], col[2], col[3], col[4], col[5], col[6], col[7], col[8]);
    const auto p = [](__m256 v, __m256i idx) { return _mm256_permutevar8x32_ps(v, idx); };
    // lane i of out + 8 c: y index (8 c + i) / 3, colour 3 * band + (8 c + i) % 3
    const __m256 o0 = _mm256_mul_ps(p(ylo, _mm256_setr_epi32(0, 0, 0, 1, 1, 1, 2, 2)),
                                    p(clo, _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 3, 4)));
    const __m256 o1 = _mm256_mul_ps(p(ylo, _mm256_setr_epi32(2, 3, 3, 3, 4, 4, 4, 5)),
                                    p(chi, _mm256_setr_epi32(4, 2, 3, 4, 5, 6, 7, 5)));
    const __m256 o2 = _mm256_mul_ps(p(ylo, _mm256_setr_epi32(5, 5, 6, 6, 6, 7, 7, 7)),
                                    p(chi, _mm256_setr_epi32(6, 7, 5, 6, 7, 5, 6, 7)));
    const __m128 o3 =
        _mm_mul_ps(_mm_set1_ps(yv[8]),
                   _mm256_castps256_ps128(p(chi, _mm256_setr_epi32(5, 6, 7, 7, 7, 7, 7, 7))));
    _mm256_storeu_ps(out, o0);
    _mm256_storeu_ps(out + 8, o1);
    _mm256_storeu_ps(out + 16, o2);
    _mm_storel_pi(reinterpret_cast<__m64*>(out + 24), o3);
    _mm_store_ss(out + 26, _mm_movehl_ps(o3, o3));
}
#endif
#endif

/// out_k = band(l) * y_k(d) for the N^2 functions of N bands (l the band of k), y at the
/// direction (x, y, z) of any length by the unrolled normalising kernel in E (a zero or
/// non-finite direction: the pole). band(l) is called once per band; bands with bit l of
/// ZeroBands set are stored as C{} and not evaluated. VectorFanOut selects the 8-lane fan-out
/// of 3 bands of packed RGB floats, chosen per light by measurement (peer harness, x86-64-v3,
/// one run): directional 6.9 ns with it; sphere 18.1 with, 23.2 without; cone 13.6 with, 7.4
/// without (its sin and cap factors then schedule better).
template <int N, unsigned ZeroBands = 0, bool VectorFanOut = false, class E, class C, class Band>
SPHBASIS_FORCEINLINE void zonal_out_fixed(E x, E y, E z, Band&& band, C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh lights: N is a band count in 1..8.");
    static_assert(sphbasis::detail::is_scalable<C, coefficient_scalar_t<C>>::value,
                  "sphbasis::sh lights: the coefficient type C needs C + C and "
                  "C * coefficient_scalar_t<C> (specialise sphbasis::coefficient_scalar).");
    using S = coefficient_scalar_t<C>;
    const std::array<C, N> colour = light_band_colours<C>(band, std::make_index_sequence<N>{});
#if SPHBASIS_SH_LIGHTS_VECTOR
    if constexpr (VectorFanOut && N == 3 && ZeroBands == 0 && std::is_same_v<E, float> &&
                  maybe_packed_rgb_v<C>) {
        if (packed_rgb<C>()) {
            float yv[9];
            FixedNormalizingKernel<N>{}(x, y, z, [&](int k, E v) { yv[k] = v; });
            float col[9];
            std::memcpy(col, static_cast<const void*>(colour.data()), sizeof(col));
            // the 27 floats of out's representation (the intrinsics' stores may alias C)
            fan_out_rgb3(yv, col, reinterpret_cast<float*>(static_cast<void*>(out)));
            return;
        }
    }
#endif
    FixedNormalizingKernel<N>{}(x, y, z, [&](int k, E v) {
        const int l = light_band_of[static_cast<std::size_t>(k)];
        if ((ZeroBands >> l) & 1u)
            out[k] = C{};
        else
            out[k] = colour[static_cast<std::size_t>(l)] * static_cast<S>(v);
    });
}

/// A uniform cap of 1 - cos(a) = u about (x, y, z), N bands, in E: the factors by the cap
/// recurrence unrolled, then zonal_out_fixed.
template <int N, bool VectorFanOut, class E, class C>
SPHBASIS_FORCEINLINE void cap_light_fixed(E x, E y, E z, E u, const C& radiance, C* out) noexcept {
    using S = coefficient_scalar_t<C>;
    E f[N];
    cap_factors_fixed<N>(u, f);
    zonal_out_fixed<N, 0, VectorFanOut>(
        x, y, z, [&](int l) { return radiance * static_cast<S>(f[l]); }, out);
}

/// The run-time cap lights for 1..8 bands after their checks: cap_light_fixed with u given in
/// double (computed there without cancellation), in the coefficient's evaluation type.
template <bool VectorFanOut = true, class T, class U, class C>
SPHBASIS_FORCEINLINE bool cap_light_dispatch(int bands, T x, T y, T z, U u, const C& radiance,
                                             C* out) {
    using E = light_eval_t<C>;
    return with_fixed_bands(bands, [&](auto n) {
        cap_light_fixed<decltype(n)::value, VectorFanOut>(static_cast<E>(x), static_cast<E>(y),
                                                          static_cast<E>(z), static_cast<E>(u),
                                                          radiance, out);
    });
}
}  // namespace detail

/// directional_light() for a compile-time band count N: out_lm = irradiance * y_lm(d), N^2
/// values. Unchecked (see above).
template <int N, class T, class C, class C0 = C>
SPHBASIS_FORCEINLINE void directional_light(T x, T y, T z, const C0& irradiance_in,
                                            C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::directional_light<N>: N is in 1..8.");
    SPHBASIS_ASSERT(out != nullptr);
    using E = detail::light_eval_t<C>;
    const C irradiance = detail::light_colour<C>(irradiance_in);
    detail::zonal_out_fixed<N, 0, true>(
        static_cast<E>(x), static_cast<E>(y), static_cast<E>(z), [&](int) { return irradiance; },
        out);
}

/// cone_light() for a compile-time band count N (half_angle in radians, clamped to [0, pi]).
template <int N, class T, class C, class C0 = C>
SPHBASIS_FORCEINLINE void cone_light(T x, T y, T z, T half_angle, const C0& radiance_in,
                                     C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::cone_light<N>: N is in 1..8.");
    SPHBASIS_ASSERT(out != nullptr);
    using E = detail::light_eval_t<C>;
    const E a = std::fmin(std::fmax(static_cast<E>(half_angle), E(0)), E(constants::pi));
    const E s = std::sin(E(0.5) * a);
    detail::cap_light_fixed<N, false>(static_cast<E>(x), static_cast<E>(y), static_cast<E>(z),
                                      E(2) * s * s,  // 1 - cos a = 2 sin^2(a/2)
                                      detail::light_colour<C>(radiance_in), out);
}

/// spherical_light() for a compile-time band count N (a ball of radius `radius` at (px, py, pz)
/// relative to the receiver; the whole sphere when |p| <= radius).
template <int N, class T, class C, class C0 = C>
SPHBASIS_FORCEINLINE void spherical_light(T px, T py, T pz, T radius, const C0& radiance_in,
                                          C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::spherical_light<N>: N is in 1..8.");
    SPHBASIS_ASSERT(out != nullptr);
    using E = detail::light_eval_t<C>;
    const E x = static_cast<E>(px), y = static_cast<E>(py), z = static_cast<E>(pz);
    const E d2 = x * x + y * y + z * z;
    const E r = std::fmax(static_cast<E>(radius), E(0));
    E u = 2;  // inside the ball: everything
    if (r * r < d2) {
        const E s2 = r * r / d2;           // sin^2 a
        u = s2 / (1 + std::sqrt(1 - s2));  // 1 - cos a without cancellation
    }
    detail::cap_light_fixed<N, true>(x, y, z, u, detail::light_colour<C>(radiance_in), out);
}

/// hemisphere_light() for a compile-time band count N: `sky` around the up direction (x, y,
/// z), `ground` opposite; the factors are compile-time constants, the zero bands (even l >= 2)
/// are stored without evaluating them.
template <int N, class T, class C, class C0 = C, class C1 = C>
SPHBASIS_FORCEINLINE void hemisphere_light(T x, T y, T z, const C0& sky_in, const C1& ground_in,
                                           C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::hemisphere_light<N>: N is in 1..8.");
    SPHBASIS_ASSERT(out != nullptr);
    using E = detail::light_eval_t<C>;
    using S = coefficient_scalar_t<C>;
    const C sky = detail::light_colour<C>(sky_in);
    const C ground = detail::light_colour<C>(ground_in);
    // sky * cap + ground * (sphere - cap); the sphere's factors are 4 pi, 0, 0, ..., so band
    // l >= 1 is (sky - ground) * f_l.
    constexpr std::array<double, N> f = detail::hemisphere_factors<N>();
    const C diff = sky + ground * S(-1);
    detail::zonal_out_fixed<N, detail::hemisphere_zero_bands>(
        static_cast<E>(x), static_cast<E>(y), static_cast<E>(z),
        [&](int l) {
            return l == 0 ? sky * static_cast<S>(f[0]) +
                                ground * static_cast<S>(constants::four_pi - f[0])
                          : diff * static_cast<S>(f[static_cast<std::size_t>(l)]);
        },
        out);
}

/// Funk-Hecke factors Lambda_l (l < bands) of the indicator of a cap with 1 - cos(a) =
/// one_minus_cos in [0, 2] (solid angle 2 pi one_minus_cos). Throws std::invalid_argument for
/// bad bands or one_minus_cos outside [0, 2].
template <class T = double>
std::vector<T> cap_kernel(int bands, double one_minus_cos) {
    check_bands(bands, "sh::cap_kernel");
    if (!(one_minus_cos >= 0 && one_minus_cos <= 2))
        sphbasis::detail::throw_invalid(
            "sh::cap_kernel", "0 <= 1 - cos(angle) <= 2, got " + std::to_string(one_minus_cos));
    std::vector<double> a(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, one_minus_cos, a.data());
    return std::vector<T>(a.begin(), a.end());
}

/// A zonal radiance distribution about d (normalised; must be finite and non-zero) with
/// Funk-Hecke factors kernel[0..bands) (e.g. phong_kernel, zonal_kernel), times colour:
/// out_lm = colour * kernel[l] * y_lm(d).
template <class T, class K, class C, class C0 = C>
void zonal_light(int bands, T x, T y, T z, const K* kernel, const C0& colour_in, C* out) {
    const C colour = detail::light_colour<C>(colour_in);
    detail::check_light(bands, x, y, z, out, "sh::zonal_light");
    sphbasis::detail::check_buffer("sh::zonal_light", "kernel", kernel,
                                   static_cast<std::size_t>(bands));
    detail::LightScratch a(static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l) a[static_cast<std::size_t>(l)] = static_cast<double>(kernel[l]);
    detail::zonal_out(bands, x, y, z, a.data(), colour, out);
}

/// A directional light from direction (x, y, z) (towards the light; normalised) delivering
/// irradiance `irradiance` to a surface facing it: L = irradiance * delta(w - d), coefficients
/// irradiance * y_lm(d). Throws std::invalid_argument for bad bands, a null out, or a zero or
/// non-finite direction. The colour may be of another type than the output's coefficients
/// (a double 1.0 with float out): it is converted to the output's type (all the lights do this).
template <class T, class C, class C0 = C>
void directional_light(int bands, T x, T y, T z, const C0& irradiance_in, C* out) {
    const C irradiance = detail::light_colour<C>(irradiance_in);
    detail::check_light(bands, x, y, z, out, "sh::directional_light");
    if (detail::with_fixed_bands(bands, [&](auto n) {
            directional_light<decltype(n)::value>(x, y, z, irradiance, out);
        }))
        return;
    detail::LightScratch a(static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l) a[static_cast<std::size_t>(l)] = 1.0;
    detail::zonal_out(bands, x, y, z, a.data(), irradiance, out);
}

/// The irradiance that `bands` bands reconstruct at the normal facing a directional light of
/// unit irradiance: sum_l Lambda_l (2l+1)/(4 pi) with the clamped-cosine Lambda_l: 1/4, 3/4,
/// 17/16 for 1, 2, 3 bands, tending to 1. DirectXMath's XMSHEvalDirectionalLight(order, d, c)
/// is directional_light(order, d, c * pi / directional_light_peak(order)) up to the
/// Condon-Shortley signs (to_condon_shortley).
inline double directional_light_peak(int bands) {
    check_bands(bands, "sh::directional_light_peak");
    detail::LightScratch a(static_cast<std::size_t>(bands));
    clamped_cosine_factors(bands, a.data());  // core/clamped_cosine.hpp: Lambda_l = pi a_l
    double s = 0;
    for (int l = 0; l < bands; ++l)
        s += constants::pi * a[static_cast<std::size_t>(l)] * (2 * l + 1) * constants::inv_four_pi;
    return s;
}

/// A cone light: uniform radiance `radiance` within angular radius half_angle (radians, in
/// [0, pi]) of direction (x, y, z). Throws std::invalid_argument for bad bands, out, direction
/// or angle.
template <class T, class C, class C0 = C>
void cone_light(int bands, T x, T y, T z, T half_angle, const C0& radiance_in, C* out) {
    const C radiance = detail::light_colour<C>(radiance_in);
    detail::check_light(bands, x, y, z, out, "sh::cone_light");
    const double a = static_cast<double>(half_angle);
    if (!(a >= 0 && a <= constants::pi))
        sphbasis::detail::throw_invalid("sh::cone_light",
                                        "0 <= half_angle <= pi, got " + std::to_string(a));
    const double s = std::sin(0.5 * a);
    const double u = 2 * s * s;  // 1 - cos a = 2 sin^2(a/2)
    if (detail::cap_light_dispatch<false>(bands, x, y, z, u, radiance, out)) return;
    detail::LightScratch f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, u, f.data());
    detail::zonal_out(bands, x, y, z, f.data(), radiance, out);
}

/// A spherical light: a ball of radius `radius` at position (px, py, pz) relative to the
/// receiver, of uniform radiance `radiance`; it covers the cap of sin(a) = radius/|p| (the
/// whole sphere when |p| <= radius). Throws std::invalid_argument for bad bands, out, a zero or
/// non-finite position, or radius < 0.
template <class T, class C, class C0 = C>
void spherical_light(int bands, T px, T py, T pz, T radius, const C0& radiance_in, C* out) {
    const C radiance = detail::light_colour<C>(radiance_in);
    detail::check_light(bands, px, py, pz, out, "sh::spherical_light");
    const double r = static_cast<double>(radius);
    if (!(r >= 0) || !std::isfinite(r))
        sphbasis::detail::throw_invalid("sh::spherical_light",
                                        "a finite radius >= 0, got " + std::to_string(r));
    if (bands >= 1 && bands <= 8) {
        // 1 - cos a = s^2 / (1 + sqrt(1 - s^2)), s^2 = r^2 / |p|^2, in the evaluation type where
        // |p|^2 neither over- nor underflows.
        using E = detail::light_eval_t<C>;
        const E ex = static_cast<E>(px), ey = static_cast<E>(py), ez = static_cast<E>(pz);
        const E d2 = ex * ex + ey * ey + ez * ez;
        if (d2 > E(1e-30) && d2 < E(1e30)) {
            const E er = static_cast<E>(r);
            E u = 2;  // inside the ball: everything
            if (er * er < d2) {
                const E s2 = er * er / d2;
                u = s2 / (1 + std::sqrt(1 - s2));
            }
            detail::cap_light_dispatch(bands, ex, ey, ez, u, radiance, out);
            return;
        }
    }
    const double x = px, y = py, z = pz;
    const double big = std::max(std::fabs(x), std::max(std::fabs(y), std::fabs(z)));
    const double dist =
        big * std::sqrt((x / big) * (x / big) + (y / big) * (y / big) + (z / big) * (z / big));
    double u = 2;  // inside the ball: everything
    if (r < dist) {
        const double s = r / dist;
        u = s * s / (1 + std::sqrt((1 - s) * (1 + s)));  // 1 - cos a without cancellation
    }
    if (detail::cap_light_dispatch(bands, px, py, pz, u, radiance, out)) return;
    detail::LightScratch f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, u, f.data());
    detail::zonal_out(bands, px, py, pz, f.data(), radiance, out);
}

/// A cap light given by its solid angle in [0, 4 pi] about direction (x, y, z), uniform
/// radiance `radiance` (a spherical light seen from outside, by solid angle).
template <class T, class C, class C0 = C>
void spherical_light_solid_angle(int bands, T x, T y, T z, T solid_angle, const C0& radiance_in,
                                 C* out) {
    const C radiance = detail::light_colour<C>(radiance_in);
    detail::check_light(bands, x, y, z, out, "sh::spherical_light_solid_angle");
    const double om = static_cast<double>(solid_angle);
    if (!(om >= 0 && om <= constants::four_pi))
        sphbasis::detail::throw_invalid("sh::spherical_light_solid_angle",
                                        "0 <= solid_angle <= 4 pi, got " + std::to_string(om));
    if (detail::cap_light_dispatch(bands, x, y, z, om * constants::inv_two_pi, radiance, out))
        return;
    detail::LightScratch f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, om * constants::inv_two_pi, f.data());
    detail::zonal_out(bands, x, y, z, f.data(), radiance, out);
}

/// A hemisphere light: radiance `sky` in the hemisphere around (x, y, z) (the "up" direction),
/// `ground` in the opposite one.
template <class T, class C, class C0 = C, class C1 = C>
void hemisphere_light(int bands, T x, T y, T z, const C0& sky_in, const C1& ground_in, C* out) {
    const C sky = detail::light_colour<C>(sky_in);
    const C ground = detail::light_colour<C>(ground_in);
    detail::check_light(bands, x, y, z, out, "sh::hemisphere_light");
    if (detail::with_fixed_bands(bands, [&](auto n) {
            hemisphere_light<decltype(n)::value>(x, y, z, sky, ground, out);
        }))
        return;
    using S = coefficient_scalar_t<C>;
    detail::LightScratch f(static_cast<std::size_t>(bands));
    detail::cap_factors(bands, 1.0, f.data());
    detail::LightScratch yv(static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands));
    eval(bands, static_cast<double>(x), static_cast<double>(y), static_cast<double>(z), yv.data());
    for (int l = 0; l < bands; ++l) {
        // sky * cap + ground * (sphere - cap); the sphere's factors are 4 pi, 0, 0, ...
        const double cs = f[static_cast<std::size_t>(l)];
        const double cg = (l == 0 ? constants::four_pi : 0.0) - cs;
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
            const double yk = yv[static_cast<std::size_t>(k)];
            out[k] = sky * static_cast<S>(cs * yk) + ground * static_cast<S>(cg * yk);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The lights for the types users hold: a direction (or position) of any 3-vector type
// (glm::vec3, Eigen::Vector3d, sphbasis::vec3, std::array<double, 3>) and the output as C* or
// as a contiguous range of at least bands^2 coefficients (checked). The scalar of the
// direction type is used for the angle or radius.

#define SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D) \
    std::enable_if_t<sphbasis::detail::is_direction_v<D>, int> = 0

/// zonal_light() with a direction of any 3-vector type and out as C* or a range.
template <class D, class K, class C, class Out, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void zonal_light(int bands, const D& dir, const K* kernel, const C& colour, Out&& out) {
    using T = direction_scalar_t<D>;
    zonal_light(bands, T(component<0>(dir)), T(component<1>(dir)), T(component<2>(dir)), kernel,
                colour, detail::light_out(bands, out, "sh::zonal_light"));
}
/// directional_light() with a direction of any 3-vector type and out as C* or a range.
template <class D, class C, class Out, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void directional_light(int bands, const D& dir, const C& irradiance, Out&& out) {
    using T = direction_scalar_t<D>;
    directional_light(bands, T(component<0>(dir)), T(component<1>(dir)), T(component<2>(dir)),
                      irradiance, detail::light_out(bands, out, "sh::directional_light"));
}
/// cone_light() with a direction of any 3-vector type and out as C* or a range.
template <class D, class A, class C, class Out, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void cone_light(int bands, const D& dir, A half_angle, const C& radiance, Out&& out) {
    using T = direction_scalar_t<D>;
    cone_light(bands, T(component<0>(dir)), T(component<1>(dir)), T(component<2>(dir)),
               static_cast<T>(half_angle), radiance,
               detail::light_out(bands, out, "sh::cone_light"));
}
/// spherical_light() with a position of any 3-vector type and out as C* or a range.
template <class D, class A, class C, class Out, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void spherical_light(int bands, const D& position, A radius, const C& radiance, Out&& out) {
    using T = direction_scalar_t<D>;
    spherical_light(bands, T(component<0>(position)), T(component<1>(position)),
                    T(component<2>(position)), static_cast<T>(radius), radiance,
                    detail::light_out(bands, out, "sh::spherical_light"));
}
/// spherical_light_solid_angle() with a direction of any 3-vector type and out as C* or a range.
template <class D, class A, class C, class Out, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void spherical_light_solid_angle(int bands, const D& dir, A solid_angle, const C& radiance,
                                 Out&& out) {
    using T = direction_scalar_t<D>;
    spherical_light_solid_angle(bands, T(component<0>(dir)), T(component<1>(dir)),
                                T(component<2>(dir)), static_cast<T>(solid_angle), radiance,
                                detail::light_out(bands, out, "sh::spherical_light_solid_angle"));
}
/// hemisphere_light() with an up direction of any 3-vector type and out as C* or a range.
template <class D, class C, class Out, class C1 = C, SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES(D)>
void hemisphere_light(int bands, const D& up, const C& sky, const C1& ground, Out&& out) {
    using T = direction_scalar_t<D>;
    hemisphere_light(bands, T(component<0>(up)), T(component<1>(up)), T(component<2>(up)), sky,
                     ground, detail::light_out(bands, out, "sh::hemisphere_light"));
}

#undef SPHBASIS_LIGHT_DIRECTION_OVERLOAD_REQUIRES

// ---------------------------------------------------------------------------------------------
// Environment maps

/// Projects a cube map (6 faces of size x size; texel(face, col, row) returns its radiance)
/// onto `bands` bands: exact texel solid angles, texel values at `supersample`^2 sub-texel
/// centres each with its own exact solid angle, the weighted mean projected exactly (header
/// comment). Cost 6 size^2 supersample^2 evaluations of n^2 functions. Throws
/// std::invalid_argument for bad bands, size < 1, supersample < 1 or a null out.
template <class C, class F>
void project_cubemap_fn(int bands, int size, F&& texel, C* out, int supersample = 1) {
    check_bands(bands, "sh::project_cubemap");
    if (size < 1 || supersample < 1 || size > 32768 || supersample > 64 ||
        static_cast<long long>(size) * supersample > 32768)
        sphbasis::detail::throw_invalid(
            "sh::project_cubemap",
            "1 <= size, 1 <= supersample <= 64 and size * supersample <= 32768, got size " +
                std::to_string(size) + ", supersample " + std::to_string(supersample));
    if (bands == 0) return;
    sphbasis::detail::check_buffer("sh::project_cubemap", "out", out, 1);
    using S = coefficient_scalar_t<C>;
    const int nf = size * supersample;  // fine texels per face edge
    const std::size_t n2 = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    const param::CubeMap<double> cube(nf, param::CubeFilter::dx9_clamped);
    // Solid angles are the same on every face and symmetric under c -> nf-1-c, r -> nf-1-r
    // and c <-> r: one octant is computed (each value costs four atan2).
    std::vector<double> omega(static_cast<std::size_t>(nf) * static_cast<std::size_t>(nf));
    {
        const std::size_t N = static_cast<std::size_t>(nf);
        for (int r = 0; r < (nf + 1) / 2; ++r)
            for (int c = r; c < (nf + 1) / 2; ++c) {
                const double w = cube.texel_solid_angle(0, c, r);
                const std::size_t cs[2] = {static_cast<std::size_t>(c),
                                           N - 1 - static_cast<std::size_t>(c)};
                const std::size_t rs[2] = {static_cast<std::size_t>(r),
                                           N - 1 - static_cast<std::size_t>(r)};
                for (std::size_t a : cs)
                    for (std::size_t b : rs) {
                        omega[b * N + a] = w;
                        omega[a * N + b] = w;
                    }
            }
    }
    // Residual of the texel rule on y_k (needed where the cube's symmetry does not make it
    // vanish: l >= 4).
    const bool need_residual = bands >= 5;
    std::vector<double> resid(need_residual ? n2 : 1, 0.0);
    double wsum = 0;
    std::vector<C> acc(n2, C{});
    const std::size_t nn = static_cast<std::size_t>(nf);
    // Face f's texel directions are a fixed signed permutation of face 0's (each face is
    // (+-1, +-s, +-t) in some order); read it off param::square_to_cube at a point whose
    // components differ in magnitude, so the convention stays the one of param/cubemap.hpp.
    int perm[6][3];
    double sign[6][3];
    {
        const vec3<double> p0 = param::square_to_cube(0, 0.3, 0.8);
        const double a0[3] = {p0.x, p0.y, p0.z};
        for (int f = 0; f < 6; ++f) {
            const vec3<double> pf = param::square_to_cube(f, 0.3, 0.8);
            const double af[3] = {pf.x, pf.y, pf.z};
            for (int i = 0; i < 3; ++i) {
                int best = 0;
                for (int j = 1; j < 3; ++j)
                    if (std::fabs(std::fabs(af[i]) - std::fabs(a0[j])) <
                        std::fabs(std::fabs(af[i]) - std::fabs(a0[best])))
                        best = j;
                perm[f][i] = best;
                sign[f][i] = (af[i] < 0) == (a0[best] < 0) ? 1.0 : -1.0;
            }
        }
    }
    // One row of fine texels at a time: face-0 directions once, then per face the permuted
    // directions, all n^2 functions by the SIMD batch kernel (function-major), weights, sums.
    std::vector<double> d0(3 * nn), xs(nn), ys(nn), zs(nn), yb(n2 * nn);
    std::vector<S> wy(nn);
    std::vector<C> vals(nn);
    for (int r = 0; r < nf; ++r) {
        for (int c = 0; c < nf; ++c) {
            const vec3<double> d = cube.texel_direction(0, c, r);
            d0[3 * static_cast<std::size_t>(c)] = d.x;
            d0[3 * static_cast<std::size_t>(c) + 1] = d.y;
            d0[3 * static_cast<std::size_t>(c) + 2] = d.z;
        }
        const double* om = omega.data() + static_cast<std::size_t>(r) * nn;
        double rw = 0;
        for (std::size_t c = 0; c < nn; ++c) rw += om[c];
        for (int face = 0; face < 6; ++face) {
            double* out3[3] = {xs.data(), ys.data(), zs.data()};
            for (int i = 0; i < 3; ++i) {
                const int j = perm[face][i];
                const double sg = sign[face][i];
                for (std::size_t c = 0; c < nn; ++c)
                    out3[i][c] = sg * d0[3 * c + static_cast<std::size_t>(j)];
            }
            for (int c = 0; c < nf; ++c)
                vals[static_cast<std::size_t>(c)] = texel(face, c / supersample, r / supersample);
            eval_batch(bands, nn, xs.data(), ys.data(), zs.data(), yb.data(), nn);
            wsum += rw;
            for (std::size_t k = 0; k < n2; ++k) {
                const double* yk = yb.data() + k * nn;
                double rk = 0;
                for (std::size_t c = 0; c < nn; ++c) {
                    const double v = om[c] * yk[c];
                    wy[c] = static_cast<S>(v);
                    rk += v;
                }
                if (need_residual) resid[k] += rk;
                acc[k] = acc[k] + detail::dot_accumulate(nn, vals.data(), wy.data());
            }
        }
    }
    // Control variate: f_k = S_k - mean (r_k - sqrt(4 pi) delta_k0), mean = S_0 / (y_00 W).
    // For k = 0 that is S_0 (4 pi / W); for k > 0 with bands <= 4, r_k = 0 by symmetry.
    const double y00 = constants::inv_sqrt_four_pi;
    const double s0 = constants::four_pi / wsum;
    out[0] = acc[0] * static_cast<S>(s0);
    const C mean = acc[0] * static_cast<S>(1 / (y00 * wsum));
    for (std::size_t k = 1; k < n2; ++k)
        out[k] = need_residual ? acc[k] + mean * static_cast<S>(-resid[k]) : acc[k];
}

/// project_cubemap_fn for texels stored face-major, row-major: texels[(face size + row) size +
/// col] (param::CubeMap::texel_index).
template <class C>
void project_cubemap(int bands, int size, const C* texels, C* out, int supersample = 1) {
    if (size > 0) sphbasis::detail::check_buffer("sh::project_cubemap", "texels", texels, 1);
    const std::size_t n = static_cast<std::size_t>(size > 0 ? size : 0);
    project_cubemap_fn(
        bands, size,
        [&](int face, int col, int row) -> const C& {
            return texels[(static_cast<std::size_t>(face) * n + static_cast<std::size_t>(row)) * n +
                          static_cast<std::size_t>(col)];
        },
        out, supersample);
}

}  // namespace sphbasis::sh
