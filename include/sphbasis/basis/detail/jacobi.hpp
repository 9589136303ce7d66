// sphbasis: the orthonormal Jacobi polynomials by their normalised three-term recurrence, advanced
// in z itself: the shared evaluation engine of the hemispherical bases HSH (basis/hsh.hpp),
// Makhotkin (basis/makhotkin.hpp) and Zernike (basis/zernike.hpp).
//
// detail::hemi: the orthonormal Jacobi polynomials p_k^(a,b)(w), weight (1-w)^a (1+w)^b on
// [-1, 1], by their three-term recurrence (Szego; Gautschi, "Orthogonal Polynomials", 2004, tables
// 1.1): w p_k = a_{k+1} p_{k+1} + b_k p_k + a_k p_{k-1},
//   b_k = (b^2 - a^2) / ((2k+a+b)(2k+a+b+2)),
//   a_k = 2/(2k+a+b) sqrt(k (k+a) (k+b) (k+a+b) / ((2k+a+b-1)(2k+a+b+1))).
// HSH are (a, b) = (|m|, |m|) in w = u, Makhotkin (|m|, |m|+1) in w = u, Zernike (0, |m|) in
// w = 1 - 2z; each basis is E(z) * q_m * p_k(w) * Re/Im (X + iY)^m for its own E, q_m, (X, Y).
// Row recurrence (bands <= 64, any value type, tables built once per family) and column
// recurrence (any band count, extended precision, a binary exponent carried beside each sectoral
// start); see basis/hsh.hpp for the accuracy this gives.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>
#include <utility>

#include "../../config.hpp"
#include "../../core/scalar.hpp"
#include "../../core/scaled.hpp"
#include "../../core/simd.hpp"
#include "../../core/vec.hpp"

namespace sphbasis::detail::hemi {

/// Band count at or below which the row recurrence on Q = value / sin'^m is used. Q stays below
/// ~1e14 there for every family, so it cannot overflow in float.
inline constexpr int max_row_bands = 64;

// The high-degree column recurrence runs in sphbasis::extended (core/scalar.hpp): near w = +-1
// the three-term recurrence turns every rounding of a coefficient into a perturbation of the
// argument, which degree-l functions amplify ~l^1.5 times (slope ~l^2 at the ends): 2e-11 of the
// scale at l = 2047 in double, ~1e-14 in x87 extended precision, for ~1.4x the time of the
// (scalar, division-bound) loop.

/// A family of hemispherical functions f = E(z) q_m p_k^(alpha, beta)(w) Re/Im (X + iY)^|m| with
/// w = sigma (2z - 1), alpha = a0 + am |m|, beta = b0 + bm |m|, band = |m| + step k.
/// q_m folds the normalisation of the trig factor, of the change of variables and of p_0:
/// q_0, q_1 given, q_m = q_{m-1} sqrt((2m+1)/(2m)) (ratio 0) or sqrt((m+1)/m) (ratio 1), m >= 2.
struct Family {
    int sigma, step, a0, am, b0, bm;
    double q0, q1;
    int ratio;
    int alpha(int m) const noexcept { return a0 + am * m; }
    int beta(int m) const noexcept { return b0 + bm * m; }
    /// q_m / q_{m-1}, m >= 1, in precision R.
    template <class R>
    R start_ratio(int m) const noexcept {
        if (m == 1) return R(q1) / R(q0);
        const R dm = R(m);
        return ratio == 0 ? std::sqrt((2 * dm + 1) / (2 * dm)) : std::sqrt((dm + 1) / dm);
    }
};

/// a_k (k >= 1) of the orthonormal Jacobi recurrence, weight (1-w)^al (1+w)^be.
template <class R = double>
inline R jacobi_a(int k, int al, int be) noexcept {
    const R dk = R(k), da = R(al), db = R(be), s = 2 * dk + da + db;
    return 2 / s * std::sqrt(dk * (dk + da) / ((s - 1) * (s + 1)) * ((dk + db) * (dk + da + db)));
}

/// sigma + b_k, formed from integers so that 1 - b_k keeps its digits when b_k is close to 1.
template <class R = double>
inline R sigma_plus_b(int k, int al, int be, int sigma) noexcept {
    const R s = R(2 * k + al + be);
    if (s == 0) return R(sigma);  // a = b = 0, k = 0: b_0 = 0
    const R den = s * (s + 2);
    return (R(sigma) * den + (R(be) * R(be) - R(al) * R(al))) / den;
}

/// One step p_k = (pz z - d) p_{k-1} - c p_{k-2}, k >= 1, of the family's recurrence in z:
/// (w - b) / a = (2 sigma z - (sigma + b)) / a, so z enters unrounded.
struct Step {
    extended pz, d, c;
};
inline Step jacobi_step(int k, int al, int be, int sigma) noexcept {
    // Formed in the extended type and rounded once, to the table's type, by the caller.
    const extended ak = jacobi_a<extended>(k, al, be);
    const extended akm1 = k >= 2 ? jacobi_a<extended>(k - 1, al, be) : extended(0);
    return {extended(2 * sigma) / ak, sigma_plus_b<extended>(k - 1, al, be, sigma) / ak, akm1 / ak};
}

/// Number of recurrence steps in bands 0..b-1 (the table offset of band b): band b advances
/// b orders with step 1 (m = 0..b-1), floor(b/2) with step 2 (m = b-2, b-4, ... >= 0).
constexpr int row_offset(int step, int b) noexcept {
    return step == 1 ? b * (b - 1) / 2 : (b / 2) * (b / 2 - 1) + (b % 2) * (b / 2);
}

/// Recurrence constants of a family for up to Bands bands, in precision T, in fixed-size arrays
/// (constant addresses, no pointer to chase). Band b holds the steps of the orders that advance
/// in it, ascending in m, from row_offset(step, b).
template <class T, int Bands>
struct RowTable {
    static constexpr int size = row_offset(1, Bands);  // enough for both steps
    T pz[size], d[size], c[size], start[Bands];

    // Out of line: row_table() is inlined into every kernel, its one-time construction is not.
    SPHBASIS_NOINLINE explicit RowTable(const Family& f) noexcept {
        extended q = f.q0;
        for (int m = 0; m < Bands; ++m) {
            if (m > 0) q *= f.start_ratio<extended>(m);
            start[m] = static_cast<T>(q);
        }
        for (int b = 0; b < Bands; ++b) {
            int i = row_offset(f.step, b);
            for (int m = f.step == 1 ? 0 : b % 2; m + f.step <= b; m += f.step, ++i) {
                const Step s = jacobi_step((b - m) / f.step, f.alpha(m), f.beta(m), f.sigma);
                pz[i] = static_cast<T>(s.pz);
                d[i] = static_cast<T>(s.d);
                c[i] = static_cast<T>(s.c);
            }
        }
    }
};

/// The table capacity for kernels of up to Cap bands: 8 for the unrolled kernels, else 64.
constexpr int table_bands(int cap) noexcept { return cap <= 8 ? 8 : max_row_bands; }

/// The shared table of family Fam (a type with `static constexpr Family family`) for up to
/// Bands bands, built once, thread-safe.
template <class T, class Fam, int Bands>
SPHBASIS_FORCEINLINE const RowTable<T, Bands>& row_table() noexcept {
    static const RowTable<T, Bands> t(Fam::family);
    return t;
}

/// s in every lane of V. For batches written as one vector operation (s - 0 is s for every s,
/// -0 included), which compilers emit as a single broadcast even inside unrolled loops, where the
/// lane-by-lane batch(T) constructor can turn into one masked broadcast per lane (GCC 12).
template <class V>
SPHBASIS_FORCEINLINE V splat(scalar_t<V> s) noexcept {
    if constexpr (std::is_floating_point_v<V>) {
        return s;
    } else {
        using N = typename V::native_type;
        return V(N(s - N{}));
    }
}

/// Calls f(i) for i = begin, begin + stride, ... < end: at most Cap values. Cap <= 8 (the
/// kernels with a compile-time band count): a loop the compiler is told to unroll, since GCC
/// leaves the nested loops of the row recurrences (Zernike's step-2 orders, Makhotkin at 3
/// bands and more) rolled, with their state in memory. (A fold over an index sequence unrolled
/// them as well, but took 440 s to compile test_zernike.cpp under ASan.)
template <int Cap, class F>
SPHBASIS_FORCEINLINE void for_each_index(int begin, int end, int stride, F&& f) noexcept {
    if constexpr (Cap <= 8) {
#if defined(__GNUC__) || defined(__clang__)
#pragma GCC unroll 8
#endif
        for (int i = begin; i < end; i += stride) f(i);
    } else {
        for (int i = begin; i < end; i += stride) f(i);
    }
}

/// cos(m phi) and sin(m phi) scaled by S^m: Re/Im (X + iY)^m, m = 0..bands-1.
template <class V>
SPHBASIS_FORCEINLINE void powers(int bands, const V& X, const V& Y, V* cm, V* sm) noexcept {
    using S = scalar_t<V>;
    cm[0] = V(S(1));
    sm[0] = V(S(0));
    if (bands > 1) {
        cm[1] = X;  // = X * 1 - Y * 0 for finite input, without the two multiplications
        sm[1] = Y;
    }
    for (int m = 2; m < bands; ++m) {
        cm[m] = X * cm[m - 1] - Y * sm[m - 1];
        sm[m] = X * sm[m - 1] + Y * cm[m - 1];
    }
}

/// Row recurrence for families with step 1 (HSH, Makhotkin): ACN order, bands <= Cap <=
/// max_row_bands. zc = max(z, 0); E multiplies every function (the family's E(z) and the
/// below-horizon mask). A compile-time Cap = bands lets the compiler unroll everything and keep
/// the state in registers (the small-size kernels).
template <class Fam, int Cap = max_row_bands, class V, class Store>
SPHBASIS_FORCEINLINE void rows_acn(int bands, const V& zc, const V& X, const V& Y, const V& E,
                                   Store&& store) noexcept {
    static_assert(Cap >= 1 && Cap <= max_row_bands, "sphbasis: row recurrence up to 64 bands.");
    using S = scalar_t<V>;
    SPHBASIS_ASSERT(bands >= 1 && bands <= Cap);
    const RowTable<S, table_bands(Cap)>& t = row_table<S, Fam, table_bands(Cap)>();
    V cm[Cap], sm[Cap], cur[Cap], prev[Cap];
    powers(bands, X, Y, cm, sm);
    for_each_index<Cap>(0, bands, 1, [&](int l) SPHBASIS_INLINE_LAMBDA {
        const int o = row_offset(1, l);
        const S* pz = t.pz + o;
        const S* d = t.d + o;
        const S* c = t.c + o;
        // Unrolled, the first step of order l-1 (c = 0, p_{-1} = 0) drops the zero term: the same
        // value. The loop keeps it (prev[l] = 0), so that it stays one vectorised loop.
        constexpr bool unroll = Cap <= 8;
        for_each_index<Cap>(0, unroll ? l - 1 : l, 1, [&](int m) SPHBASIS_INLINE_LAMBDA {
            const V v = (splat<V>(pz[m]) * zc - splat<V>(d[m])) * cur[m] - splat<V>(c[m]) * prev[m];
            prev[m] = cur[m];
            cur[m] = v;
        });
        if (unroll && l >= 1) {
            const int m = l - 1;
            prev[m] = cur[m];
            cur[m] = (splat<V>(pz[m]) * zc - splat<V>(d[m])) * cur[m];
        }
        cur[l] = splat<V>(t.start[l]) * E;
        if (!unroll) prev[l] = V(S(0));
        const int k = l * (l + 1);
        store(k, cur[0]);
        for_each_index<Cap>(1, l + 1, 1, [&](int m) SPHBASIS_INLINE_LAMBDA {
            store(k + m, cur[m] * cm[m]);
            store(k - m, cur[m] * sm[m]);
        });
    });
}

/// Column recurrence of family f, any band count: calls out(band, m, value) for every function,
/// m signed (m > 0: cos, m < 0: sin, 0). zc = max(z, 0), (X, Y) the family's sectoral pair, E the
/// family's factor (0 below the horizon). The sectoral starts carry a binary exponent, so nothing
/// underflows before the recurrence has grown it back; values below the double range come out
/// as 0, never NaN or Inf. Coefficients are computed on the fly: ~1 sqrt and 3 divisions per
/// function, in sphbasis::extended.
template <class Out>
inline void columns(const Family& f, int bands, extended zc, extended X, extended Y, extended E,
                    Out&& out) {
    using R = extended;
    R s, cp, sp;  // sin' = |(X, Y)|, cos(phi), sin(phi) without underflow
    polar_xy(X, Y, s, cp, sp);
    int s_exp = 0;
    const R s_mant = s > 0 ? std::frexp(s, &s_exp) : R(0);
    Scaled<R> q{R(f.q0) * E, 0};  // core/scaled.hpp
    R cm = 1, sm = 0;
    const R two_sigma_z = R(2 * f.sigma) * zc;
    for (int m = 0; m < bands; ++m) {
        if (m > 0) {
            q.scale(f.start_ratio<R>(m) * s_mant, s_exp);
            const R c = cm * cp - sm * sp;
            sm = sm * cp + cm * sp;
            cm = c;
        }
        if (q.m == 0) {
            // E = 0 or sin' = 0 exactly: every remaining order vanishes.
            for (int mm = m; mm < bands; ++mm)
                for (int b = mm; b < bands; b += f.step) {
                    out(b, mm, 0.0);
                    if (mm > 0) out(b, -mm, 0.0);
                }
            return;
        }
        const int al = f.alpha(m), be = f.beta(m);
        int e = q.e;
        auto emit = [&](int b, R p) {
            const R v = e == 0 ? p : std::ldexp(p, e);
            if (m == 0) {
                out(b, 0, static_cast<double>(v));
            } else {
                out(b, m, static_cast<double>(v * cm));
                out(b, -m, static_cast<double>(v * sm));
            }
        };
        R p2 = 0, p1 = q.m, a_prev = 0;
        emit(m, p1);
        for (int k = 1, b = m + f.step; b < bands; ++k, b += f.step) {
            const R ak = jacobi_a<R>(k, al, be);
            R p0 =
                ((two_sigma_z - sigma_plus_b<R>(k - 1, al, be, f.sigma)) * p1 - a_prev * p2) / ak;
            a_prev = ak;
            shed_magnitude(p0, p1, e);
            emit(b, p0);
            p2 = p1;
            p1 = p0;
        }
    }
}

/// Runs columns() for a value type V: directly for float/double, lane by lane for batches.
/// prep(x, y, z, zc, X, Y, E) computes the family's inputs in the extended type from the lane's
/// direction (m-th powers of (X, Y) amplify their rounding m times); index(b, m) maps a label to
/// the function index.
template <class V, class Store, class Prep, class Index>
inline void columns_any(const Family& f, int bands, const V& x, const V& y, const V& z,
                        Store&& store, Prep&& prep, Index&& index) {
    auto run = [&](extended dx, extended dy, extended dz, auto&& put) {
        extended zc, X, Y, E;
        prep(dx, dy, dz, zc, X, Y, E);
        columns(f, bands, zc, X, Y, E, [&](int b, int m, double v) { put(index(b, m), v); });
    };
    if constexpr (std::is_floating_point_v<V>) {
        run(extended(x), extended(y), extended(z),
            [&](int k, double v) { store(k, static_cast<V>(v)); });
    } else {
        using S = scalar_t<V>;
        for (int i = 0; i < V::size; ++i)
            run(extended(x[i]), extended(y[i]), extended(z[i]),
                [&](int k, double v) { store.lane(k, i, static_cast<S>(v)); });
    }
}

/// 1 for z >= 0, else 0.
template <class V>
SPHBASIS_FORCEINLINE V upper(const V& z) noexcept {
    using S = scalar_t<V>;
    return select(z >= V(S(0)), V(S(1)), V(S(0)));
}

/// The inputs of the families advanced in w = 2z - 1 (HSH, Makhotkin): zc = max(z, 0) and
/// (X, Y) = 2 sqrt(zc/(1+zc)) (x, y) = sin' (cos phi, sin phi), sin' the sine of the angle
/// whose cosine is 2 zc - 1.
template <class V>
SPHBASIS_FORCEINLINE void shifted_xy(const V& x, const V& y, const V& z, V& zc, V& X,
                                     V& Y) noexcept {
    using S = scalar_t<V>;
    zc = vmax(z, V(S(0)));
    const V g = V(S(2)) * vsqrt(zc / (V(S(1)) + zc));
    X = x * g;
    Y = y * g;
}

}  // namespace sphbasis::detail::hemi
