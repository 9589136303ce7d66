// sphbasis: Zernike polynomials adapted to the hemisphere (Koenderink), of any degree.
//
// References: F. Zernike, Physica 1, 1934 (the disk polynomials); J. J. Koenderink, A. J. van
// Doorn, M. Stavridi, "Bidirectional reflection distribution function expressed in terms of
// surface scattering modes", ECCV 1996 (the hemispherical adaptation); G. J. Kintner, Optica Acta
// 23, 1976 and the Jacobi form below (the recurrence); Ishmukhametov,
// "Irradiance Normal Mapping" (thesis), section 1.8.5, whose printed forms (1.46)-(1.51) are only a
// cross-check (see "Misprints" below).
//
// Definition. The hemisphere is mapped onto the unit disk by rho = sqrt(1 - cos t) (pole -> centre,
// horizon -> rim) keeping the azimuth phi. Since rho^2 = 1 - z, dOmega = sin t dt dphi =
// d(rho^2) dphi = 2 rho drho dphi, i.e. twice the disk's area element, so the disk's orthonormal
// Zernike functions divided by sqrt(2) are orthonormal on the hemisphere:
//   Z_n^m = sqrt((n+1) (2 - delta_m0) / (2 pi)) R_n^|m|(rho) trig(m phi),
//   R_n^m(rho) = sum_s (-1)^s (n-s)! / (s! ((n+m)/2-s)! ((n-m)/2-s)!) rho^(n-2s),  R_n^m(1) = 1,
// n >= 0, m = -n, -n+2, ..., n; trig = cos(m phi) for m > 0, sin(|m| phi) for m < 0, 1 for m = 0.
// (Disk: int R_n^m R_n'^m rho drho = delta_nn' / (2(n+1)), int trig^2 dphi = pi (1 + delta_m0).)
// In Cartesian form rho cos(phi) = x / sqrt(1+z), rho sin(phi) = y / sqrt(1+z), so
// rho^|m| trig(m phi) = Re/Im ((x + iy) / sqrt(1+z))^|m| and the functions are polynomials in
// x/sqrt(1+z), y/sqrt(1+z) (rho^2 = 1 - z). Sign convention as SH: cos(m phi) functions (m > 0)
// are positive multiples of x-like terms, sin(|m| phi) functions (m < 0) of y-like terms. Bands
// 0..2:
//   Z_00 = 1/sqrt(2 pi)
//   Z_1-1 = sqrt(2/pi) y / sqrt(1+z)          Z_11 = sqrt(2/pi) x / sqrt(1+z)
//   Z_2-2 = 2 sqrt(3/pi) x y / (1+z)          Z_20 = sqrt(3/(2 pi)) (1 - 2z)
//   Z_22 = sqrt(3/pi) (x^2 - y^2) / (1+z)
//
// Ordering: band n holds the n+1 functions m = -n, -n+2, ..., n; functions are ordered by n, then
// m ascending: index(n, m) = n(n+1)/2 + (n+m)/2. n bands (n <= bands-1) = bands(bands+1)/2
// functions (1, 3, 6, 10, 15, ...); 1 <= bands <= zernike::max_bands.
// Domain: the upper hemisphere z >= 0. BELOW THE HORIZON (z < 0) every function is 0: such
// directions map outside the unit disk (rho > 1), where the polynomials are not the basis. The
// pole z = 1 (rho = 0) and the horizon z = 0 (rho = 1, where the functions still vary with phi)
// are regular points.
//
// Misprints in Ishmukhametov's printed forms (derive, do not transcribe):
//   (1.48) Z_11 = (2/sqrt(pi)) cos(phi) sin(t/2) = -sqrt(2/pi) x / sqrt(1+z): spurious minus on
//          the right side (2 sin(t/2) cos(phi) / sqrt(2) = rho cos(phi) = x / sqrt(1+z) > 0 for
//          x > 0);
//   (1.47), (1.49) print the sin functions Z_1-1, Z_2-2 with a minus sign on both sides: a
//          Condon-Shortley-like phase; with this library's convention they are positive multiples
//          of y and xy.
//
// Evaluation: R_n^m(rho) = rho^m P_k^(0,m)(2 rho^2 - 1), k = (n-m)/2, and 2 rho^2 - 1 = 1 - 2z, so
//   Z_n^m = sqrt((2 - delta_m0)/pi) 2^(m/2) rho^m p_k^(0,m)(1 - 2z) trig(m phi)
// with p_k the orthonormal Jacobi polynomials (the normalisation no longer depends on n), by the
// shared normalised three-term recurrence of basis/detail/jacobi.hpp (detail::hemi, advanced in z
// itself): a row recurrence for bands <= 64 (any value type), the exponent-carrying column
// recurrence in extended precision above. No factorial sums, no pow. Cost: one square root and one
// division per direction, then ~bands^2/2 multiply-adds (plus as many square roots and divisions
// above 64 bands, ~10 ns per function). Accuracy (double, against mpmath's factorial sums;
// tests/basis/test_zernike.cpp), relative to the scale S_n = sqrt((n+1)/pi) of band n: <= 1e-14
// below 64 bands, <= 1.5e-13 at n = 2047 (rho^m with m ~ 2000 amplifies the input's rounding m
// times), and within ~0.01 of the pole, where one ulp of z moves a band-n function by up to
// ~n^2 1e-16 S_n, 2e-12 S_n at n = 2047, t = 1e-3.
#pragma once

#include <cmath>
#include <type_traits>
#include <utility>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"
#include "detail/banded_api.hpp"
#include "detail/hemi_family.hpp"
#include "detail/jacobi.hpp"

namespace sphbasis::zernike {

/// Largest supported band count (degree n = 2047, 2098176 functions).
inline constexpr int max_bands = 2048;

/// Index of (n, m), |m| <= n, n - m even: n(n+1)/2 + (n+m)/2.
constexpr int index(int n, int m) noexcept { return n * (n + 1) / 2 + (n + m) / 2; }
/// Number of functions in `bands` bands: bands(bands+1)/2.
constexpr int count(int bands) noexcept { return bands * (bands + 1) / 2; }

namespace detail {

namespace hemi = sphbasis::detail::hemi;

struct ZernikeFamily {
    // clang-format off
    static constexpr hemi::Family family{
        -1, 2,                // sigma, step: w = 1 - 2z = 2 rho^2 - 1, band n = |m| + 2k
        0, 0, 0, 1,           // alpha = 0, beta = |m|
        0.39894228040143268,  // q0 = 1/sqrt(2 pi)
        0.79788456080286536,  // q1 = sqrt(2/pi)
        1};                   // q_m = q_{m-1} sqrt((m+1)/m), m >= 2
    // clang-format on

    static constexpr int index(int n, int m) noexcept { return zernike::index(n, m); }

    /// zc = max(z, 0), (X, Y) = (x, y) / sqrt(1 + zc) = rho (cos phi, sin phi), E = [z >= 0].
    template <class V>
    static SPHBASIS_FORCEINLINE void prep(const V& x, const V& y, const V& z, V& zc, V& X, V& Y,
                                          V& E) noexcept {
        using S = scalar_t<V>;
        zc = vmax(z, V(S(0)));
        const V h = V(S(1)) / vsqrt(V(S(1)) + zc);
        X = x * h;
        Y = y * h;
        E = hemi::upper(z);
    }

    /// Row recurrence, bands <= Cap <= 64: order n then m ascending. Each order m advances every
    /// second band, so the state is kept per m. A compile-time Cap = bands lets the compiler unroll
    /// everything (the small-size kernels).
    template <int Cap, class V, class Store>
    static SPHBASIS_FORCEINLINE void rows(int bands, const V& zc, const V& X, const V& Y,
                                          const V& E, Store&& store) noexcept {
        static_assert(Cap >= 1 && Cap <= hemi::max_row_bands,
                      "sphbasis: row recurrence up to 64 bands.");
        using S = scalar_t<V>;
        SPHBASIS_ASSERT(bands >= 1 && bands <= Cap);
        constexpr int tb = hemi::table_bands(Cap);
        const hemi::RowTable<S, tb>& t = hemi::row_table<S, ZernikeFamily, tb>();
        V cm[Cap], sm[Cap], cur[Cap], prev[Cap];
        hemi::powers(bands, X, Y, cm, sm);
        hemi::for_each_index<Cap>(0, bands, 1, [&](int n) SPHBASIS_INLINE_LAMBDA {
            const int o = hemi::row_offset(2, n);
            const S* pz = t.pz + o;
            const S* d = t.d + o;
            const S* c = t.c + o;
            const int par = n % 2;
            // Step j of band n is order par + 2j. Unrolled, the first step of order n-2 (c = 0,
            // p_{-1} = 0) drops the zero term: the same value. The loop keeps it (prev[n] = 0).
            constexpr bool unroll = Cap <= 8;
            const int steps = (n - par) / 2;
            hemi::for_each_index<Cap>(
                0, unroll ? steps - 1 : steps, 1, [&](int j) SPHBASIS_INLINE_LAMBDA {
                    const int m = par + 2 * j;
                    const V v = (hemi::splat<V>(pz[j]) * zc - hemi::splat<V>(d[j])) * cur[m] -
                                hemi::splat<V>(c[j]) * prev[m];
                    prev[m] = cur[m];
                    cur[m] = v;
                });
            if (unroll && n >= 2) {
                const int m = n - 2, j = steps - 1;
                prev[m] = cur[m];
                cur[m] = (hemi::splat<V>(pz[j]) * zc - hemi::splat<V>(d[j])) * cur[m];
            }
            cur[n] = hemi::splat<V>(t.start[n]) * E;
            if (!unroll) prev[n] = V(S(0));
            const int base = n * (n + 1) / 2;
            // Functions of band n in index order: sin (m = n, n-2, ... > 0), m = 0, cos.
            hemi::for_each_index<Cap>(0, (n + 1) / 2, 1, [&](int i) SPHBASIS_INLINE_LAMBDA {
                const int m = n - 2 * i;
                store(base + i, cur[m] * sm[m]);
            });
            if (par == 0) store(base + n / 2, cur[0]);
            hemi::for_each_index<Cap>(2 - par, n + 1, 2, [&](int m) SPHBASIS_INLINE_LAMBDA {
                store(base + (n + m) / 2, cur[m] * cm[m]);
            });
        });
    }
};

/// bands <= 8: the row recurrence with a compile-time band count.
template <int N>
using FixedKernel = hemi::FixedRowKernel<ZernikeFamily, N>;
SPHBASIS_HEMI_KERNELS(ZernikeFamily);

/// Triangular function counts: n bands = n(n+1)/2 functions.
struct TriangularCount {
    static constexpr int count(int bands) noexcept { return bands * (bands + 1) / 2; }
    /// The band count of n functions, or -1 if n is not a triangular number >= 1.
    static int bands_of(int n) noexcept {
        if (n < 1) return -1;
        // The unrolled sizes (checked on every one-call evaluation) without a square root.
        for (int b = 1; b <= 8; ++b)
            if (n <= count(b)) return n == count(b) ? b : -1;
        auto tri = [](long long b) { return b * (b + 1) / 2; };
        long long b = static_cast<long long>(std::sqrt(2.0 * n));
        while (b > 0 && tri(b) > n) --b;
        while (tri(b + 1) <= n) ++b;
        return tri(b) == n ? static_cast<int>(b) : -1;
    }
    static constexpr const char* rule = "a triangular number (bands(bands+1)/2";
};

}  // namespace detail
}  // namespace sphbasis::zernike

namespace sphbasis {

/// Koenderink's hemispherical Zernike basis as a basis (basis/basis.hpp): n = bands(bands+1)/2
/// functions ordered by band then m, orthonormal on the upper hemisphere, 0 below the horizon.
struct Zernike
    : detail::hemi::HemiBasis<zernike::detail::TriangularCount, zernike::max_bands,
                              zernike::detail::ZernikeFamily, zernike::detail::FixedKernel> {
    static constexpr const char* name = "zernike";
};

}  // namespace sphbasis

namespace sphbasis::zernike {

// The banded entry points (check_bands, eval, eval_unit, eval<N>, eval_unit<N>, eval_batch,
// eval_sum, eval_sum_batch) as sh:: has them: basis/detail/banded_api.hpp documents them.
SPHBASIS_BANDED_ENTRY_POINTS(Zernike, "zernike");

}  // namespace sphbasis::zernike
