// sphbasis: the SH product of two float expansions of N <= 6 bands by Gauss-Legendre rings, for
// AVX2 + FMA (sh::product<N>'s float path where it beats the unrolled Gaunt sums of
// ops/sh_product_fixed.hpp; see sh_product.hpp for the dispatch).
//
// Each real SH factors as y_lm(z, phi) = K_l|m|(z) T_m(phi), T_m = cos(m phi) (m > 0), 1 (m = 0),
// sin(|m| phi) (m < 0). On R Gauss-Legendre nodes z_r (the rings) a = sum a_lm y_lm is the
// trigonometric series sum_m F_m(r) T_m with F_m(r) = sum_l a_lm K_l|m|(z_r), likewise G_m(r) for
// b. The product of the two series on a ring follows from
//     cos p cos q = (cos(p-q) + cos(p+q))/2,   sin p sin q = (cos(p-q) - cos(p+q))/2,
//     cos p sin q = (sin(p+q) - sin(p-q))/2,   sin p cos q = (sin(p+q) + sin(p-q))/2,
// keeping the frequencies below N (the projection drops the rest): H_m(r). The projection is then
//     out_lm = sum_r w_r K_l|m|(z_r) H_m(r) (integral of T_m^2 over phi: 2 pi for m = 0, else pi).
// It is exact: in a Gaunt triple one |m| is the sum of the other two, so the (1-z^2)^(m/2)
// factors of the three K combine to a polynomial in z of degree l1+l2+l3 <= 3(N-1), which
// ceil((3(N-1)+1)/2) nodes (4, 5, 7, 8 for 3..6 bands) integrate exactly. The rings are the 8
// lanes of one AVX2 register: the forward step is 2 N^2 broadcast multiply-adds, the ring
// product about 4 N^2 (8 for a pair p, q with p + q < N, 4 otherwise), the projection N^2
// products and a lane-sum of each (8 at a time, transposed by blends and shuffles). Cost O(N^3)
// against the O(N^5) Gaunt sums (1517 multiply-adds at 6 bands), and no register spilling of a
// 36-output straight-line sum on 16 vector registers. Tables: ops/sh_product_rings_tables.hpp
// (tools/gen/gen_sh_product_rings.py).
#pragma once

#if defined(__AVX2__) && defined(__FMA__)
#define SPHBASIS_SH_PRODUCT_RINGS 1
#include <immintrin.h>

#include "../config.hpp"
#include "sh_product_rings_tables.hpp"

// Every loop below has compile-time bounds and must unroll fully: the arrays of vectors are then
// registers and every table index a constant.
#if defined(__GNUC__)
#define SPHBASIS_RINGS_UNROLL _Pragma("GCC unroll 64")
#else
#define SPHBASIS_RINGS_UNROLL
#endif

namespace sphbasis::sh::detail {

/// The lane sums of 8 vectors, lane i of the result = sum of the lanes of v[i].
SPHBASIS_FORCEINLINE __m256 ring_lane_sums8(const __m256* v) noexcept {
    // Halves: x_i = [v_i lo + v_i hi | v_(i+4) lo + v_(i+4) hi] (lane groups of 4).
    __m256 x[4];
    SPHBASIS_RINGS_UNROLL
    for (int i = 0; i < 4; ++i)
        x[i] = _mm256_add_ps(_mm256_blend_ps(v[i], v[i + 4], 0xF0),
                             _mm256_permute2f128_ps(v[i], v[i + 4], 0x21));
    // Pairs within each 128-bit half: y0 = [0, 1, 0, 1 | 4, 5, 4, 5] partial sums, y1 likewise
    // 2, 3.
    const __m256 y0 = _mm256_add_ps(_mm256_unpacklo_ps(x[0], x[1]), _mm256_unpackhi_ps(x[0], x[1]));
    const __m256 y1 = _mm256_add_ps(_mm256_unpacklo_ps(x[2], x[3]), _mm256_unpackhi_ps(x[2], x[3]));
    // [0, 1, 2, 3 | 4, 5, 6, 7].
    return _mm256_add_ps(_mm256_shuffle_ps(y0, y1, _MM_SHUFFLE(1, 0, 1, 0)),
                         _mm256_shuffle_ps(y0, y1, _MM_SHUFFLE(3, 2, 3, 2)));
}

/// out = project(a b) onto N bands, a, b, out of N^2 floats (ACN); out must not overlap a or b.
template <int N>
SPHBASIS_FORCEINLINE void product_rings(const float* a, const float* b, float* out) noexcept {
    using Tab = RingTables<N>;
    // Forward: F_m, G_m (m > 0: cosine part c, sine part s) on the 8 rings.
    __m256 fc[N], fs[N], gc[N], gs[N];
    SPHBASIS_RINGS_UNROLL
    for (int m = 0; m < N; ++m) {
        fc[m] = _mm256_setzero_ps();
        fs[m] = _mm256_setzero_ps();
        gc[m] = _mm256_setzero_ps();
        gs[m] = _mm256_setzero_ps();
    }
    SPHBASIS_RINGS_UNROLL
    for (int l = 0; l < N; ++l) {
        const int c = l * (l + 1);
        SPHBASIS_RINGS_UNROLL
        for (int m = 0; m <= l; ++m) {
            const __m256 k = _mm256_load_ps(Tab::k[c / 2 + m]);
            fc[m] = _mm256_fmadd_ps(_mm256_set1_ps(a[c + m]), k, fc[m]);
            gc[m] = _mm256_fmadd_ps(_mm256_set1_ps(b[c + m]), k, gc[m]);
            if (m > 0) {
                fs[m] = _mm256_fmadd_ps(_mm256_set1_ps(a[c - m]), k, fs[m]);
                gs[m] = _mm256_fmadd_ps(_mm256_set1_ps(b[c - m]), k, gs[m]);
            }
        }
    }
    // Ring product, twice the T_m coefficients (the 1/2 is in Tab::w): hc cosine, hs sine. The
    // sum frequencies p + q accumulate apart (hc2, hs2) to halve the dependency chains.
    __m256 hc[N], hs[N], hc2[N], hs2[N];
    SPHBASIS_RINGS_UNROLL
    for (int m = 0; m < N; ++m) {
        hc[m] = _mm256_setzero_ps();
        hs[m] = _mm256_setzero_ps();
        hc2[m] = _mm256_setzero_ps();
        hs2[m] = _mm256_setzero_ps();
    }
    SPHBASIS_RINGS_UNROLL
    for (int p = 0; p < N; ++p) {
        SPHBASIS_RINGS_UNROLL
        for (int q = 0; q < N; ++q) {
            const int s = p + q, d = p > q ? p - q : q - p;
            // Difference frequency: cos gets AC + BD, sin(p-q) gets BC - AD.
            hc[d] = _mm256_fmadd_ps(fc[p], gc[q], hc[d]);
            if (p > 0 && q > 0) hc[d] = _mm256_fmadd_ps(fs[p], gs[q], hc[d]);
            if (p > q) {
                if (q > 0) hs[d] = _mm256_fnmadd_ps(fc[p], gs[q], hs[d]);
                hs[d] = _mm256_fmadd_ps(fs[p], gc[q], hs[d]);
            } else if (q > p) {
                hs[d] = _mm256_fmadd_ps(fc[p], gs[q], hs[d]);
                if (p > 0) hs[d] = _mm256_fnmadd_ps(fs[p], gc[q], hs[d]);
            }
            if (s < N) {
                // Sum frequency: cos gets AC - BD, sin gets AD + BC.
                hc2[s] = _mm256_fmadd_ps(fc[p], gc[q], hc2[s]);
                if (p > 0 && q > 0) hc2[s] = _mm256_fnmadd_ps(fs[p], gs[q], hc2[s]);
                if (q > 0) hs2[s] = _mm256_fmadd_ps(fc[p], gs[q], hs2[s]);
                if (p > 0) hs2[s] = _mm256_fmadd_ps(fs[p], gc[q], hs2[s]);
            }
        }
    }
    SPHBASIS_RINGS_UNROLL
    for (int m = 0; m < N; ++m) {
        hc[m] = _mm256_add_ps(hc[m], hc2[m]);
        hs[m] = _mm256_add_ps(hs[m], hs2[m]);
    }
    // Projection: lane sums of w_lm * H_m, 8 outputs (in ACN order) at a time.
    constexpr int nn = N * N;
    __m256 v[8];
    SPHBASIS_RINGS_UNROLL
    for (int l = 0; l < N; ++l) {
        SPHBASIS_RINGS_UNROLL
        for (int m = -l; m <= l; ++m) {
            const int idx = l * (l + 1) + m, slot = idx % 8, am = m < 0 ? -m : m;
            v[slot] = _mm256_mul_ps(_mm256_load_ps(Tab::w[l * (l + 1) / 2 + am]),
                                    m < 0 ? hs[am] : hc[am]);
            if (slot == 7) {
                _mm256_storeu_ps(out + idx - 7, ring_lane_sums8(v));
            } else if (idx == nn - 1) {
                SPHBASIS_RINGS_UNROLL
                for (int i = slot + 1; i < 8; ++i) v[i] = _mm256_setzero_ps();
                alignas(32) float tmp[8];
                _mm256_store_ps(tmp, ring_lane_sums8(v));
                SPHBASIS_RINGS_UNROLL
                for (int i = 0; i <= slot; ++i) out[idx - slot + i] = tmp[i];
            }
        }
    }
}

}  // namespace sphbasis::sh::detail

#undef SPHBASIS_RINGS_UNROLL
#endif
