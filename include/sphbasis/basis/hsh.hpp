// sphbasis: hemispherical harmonics (HSH) of any degree, and the shared Jacobi recurrence that
// also evaluates the Makhotkin (makhotkin.hpp) and Zernike (zernike.hpp) bases.
//
// References: P. Gautron, J. Krivanek, S. Pattanaik, K. Bouatouch, "A Novel Hemispherical Basis
// for Accurate and Efficient Rendering", EGSR 2004; the source thesis (Ishmukhametov,
// "Irradiance Normal Mapping") section 1.8.3, whose printed forms (1.22)-(1.32) are only a
// cross-check (see "Misprints" below).
//
// Definition. The SH construction with cos(t) replaced by u = 2 cos(t) - 1, which maps the upper
// hemisphere z = cos(t) in [0, 1] onto u in [-1, 1] (the horizon onto the SH south pole):
//   H_l^m = K_lm P_l^|m|(u) trig(m phi),
//   K_lm^2 = (2l+1) (l-|m|)! / (2 pi (l+|m|)!)  (times 2 if m != 0),
// trig = cos(m phi) for m > 0, sin(|m| phi) for m < 0, 1 for m = 0, P_l^m WITHOUT the
// Condon-Shortley phase (P_1^1(u) = +sqrt(1 - u^2)). Orthonormal on the hemisphere: dz = du/2
// halves the SH normalisation integral, whence 2 pi where SH has 4 pi. Equivalently
//   H_l^m(x, y, z) = sqrt(2) y_l^m(X, Y, u),  (X, Y) = 2 sqrt(z / (1 + z)) (x, y),  u = 2z - 1,
// with y_l^m the library's real SH (sh.hpp): (X, Y, u) is a unit vector (X^2 + Y^2 = 4z(1 - z) =
// 1 - u^2), so "sin" of the mapped angle is 2 sqrt(z (1 - z)) and the azimuth is that of (x, y),
// with no division by zero at the pole (1 + z >= 1). Sign convention as SH: cos(m phi) functions
// (m > 0) are positive multiples of x-like terms, sin(|m| phi) functions (m < 0) of y-like terms.
// Bands 0..2:
//   H_00 = 1/sqrt(2 pi)                          H_1-1 = sqrt(6/pi) y sqrt(z/(1+z))
//   H_10 = sqrt(3/(2pi)) (2z - 1)                H_11  = sqrt(6/pi) x sqrt(z/(1+z))
//   H_2-2 = 2 sqrt(30/pi) x y z/(1+z)            H_2-1 = sqrt(30/pi) y (2z - 1) sqrt(z/(1+z))
//   H_20 = sqrt(5/(2pi)) (6z^2 - 6z + 1)         H_21  = sqrt(30/pi) x (2z - 1) sqrt(z/(1+z))
//   H_22 = sqrt(30/pi) z (x^2 - y^2)/(1+z)
//
// Ordering: ACN, index l(l+1) + m; n bands = l <= n-1 = n^2 functions; 1 <= n <= hsh::max_bands.
// Domain: the upper hemisphere z >= 0. BELOW THE HORIZON (z < 0) every function is 0: the
// functions contain sqrt(z) and have no natural extension. The pole z = 1 and the horizon z = 0
// are regular points (at the horizon only the m = 0 functions are non-zero, H_l0 = K_l0 (-1)^l).
//
// Misprints in the thesis' printed forms (derive, do not transcribe):
//   (1.23) H_1-1 = -sqrt(6/pi) y sqrt(z/(1+z)): spurious minus (its own left side is positive);
//   (1.26) H_2-2 = sqrt(30/pi)(cos^2 t - cos t) sin 2phi: the sign is reversed, it is
//          sqrt(30/pi)(cos t - cos^2 t) sin 2phi = 2 sqrt(30/pi) x y z/(1+z) (the printed right
//          side also puts the whole fraction under the root);
//   (1.30) H_21 printed with sin(phi); it is cos(phi) (the right side (1.31) has x);
//   (1.32) H_22 = sqrt(30/pi) cos 2phi (cos^2 t - cos t): reversed sign on the left side, the
//          right side sqrt(30/pi) z (x^2 - y^2)/(1+z) is right; (1.28) the root covers too much.
//
// Evaluation (no factorials, no pow; Holmes & Featherstone 2002 style normalised recurrences):
//   * bands <= 8: sh.hpp's unrolled kernels at the mapped direction (X, Y, u), times sqrt(2);
//   * bands <= 64: a normalised row recurrence (below, detail::hemi) on Q = H / sin'^m, times
//     Re/Im (X + iY)^m; any value type (float, double, batch);
//   * more bands: the column recurrence in extended precision (detail::hemi::wide) with a binary
//     exponent carried beside each sectoral start (nothing underflows), lane by lane for batches.
// The recurrences use z itself, never a rounded u = 2z - 1, so that the accuracy near the
// horizon (u -> -1, where degree-l functions have slope ~ l^2) is that of z. Cost: one division
// and one square root per direction, then ~n^2 multiply-adds (~n^2 divisions and square roots
// more above 64 bands, where the coefficients are computed on the fly: ~10 ns per function).
// Accuracy (double, against mpmath; tests/basis/test_hsh.cpp), relative to the scale
// S_l = sqrt((2l+1)/(2 pi)) of degree l: <= 2e-15 below 64 bands, <= 3e-14 at l = 2047, except
// within ~0.01 of the pole, where the input's own rounding dominates (slope ~l^2 S_l in z: one
// ulp of z moves a degree-l function by up to ~l^2 1e-16 S_l; measured 1.3e-11 S_l at l = 2047,
// t = 1e-3). Where long double is double, the column recurrence loses up to ~2e-11 S_l at the
// horizon and pole at l = 2047 (see detail::hemi::wide).
//
// detail::hemi: the orthonormal Jacobi polynomials p_k^(a,b)(w), weight (1-w)^a (1+w)^b on
// [-1, 1], by their three-term recurrence (Szego; Gautschi, "Orthogonal Polynomials", 2004, tables
// 1.1): w p_k = a_{k+1} p_{k+1} + b_k p_k + a_k p_{k-1},
//   b_k = (b^2 - a^2) / ((2k+a+b)(2k+a+b+2)),
//   a_k = 2/(2k+a+b) sqrt(k (k+a) (k+b) (k+a+b) / ((2k+a+b-1)(2k+a+b+1))).
// HSH are (a, b) = (|m|, |m|) in w = u, Makhotkin (|m|, |m|+1) in w = u, Zernike (0, |m|) in
// w = 1 - 2z; each basis is E(z) * q_m * p_k(w) * Re/Im (X + iY)^m for its own E, q_m, (X, Y).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../config.hpp"
#include "../core/constants.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"
#include "sh.hpp"

namespace sphbasis::detail::hemi {

/// Band count at or below which the row recurrence on Q = value / sin'^m is used. Q stays below
/// ~1e14 there for every family, so it cannot overflow in float.
inline constexpr int max_row_bands = 64;

/// The type of the high-degree column recurrence: x87 extended precision (64-bit significand)
/// where long double is that format, else double. Near w = +-1 the three-term recurrence turns
/// every rounding of a coefficient into a perturbation of the argument, which degree-l functions
/// amplify ~l^1.5 times (slope ~l^2 at the ends): 2e-11 of the scale at l = 2047 in double,
/// ~1e-14 in extended precision, for ~1.4x the time of the (scalar, division-bound) loop.
using wide =
    std::conditional_t<std::numeric_limits<long double>::digits == 64, long double, double>;

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
    double pz, d, c;
};
inline Step jacobi_step(int k, int al, int be, int sigma) noexcept {
    // Formed in the wide type, so that each table entry is rounded once.
    const wide ak = jacobi_a<wide>(k, al, be);
    const wide akm1 = k >= 2 ? jacobi_a<wide>(k - 1, al, be) : wide(0);
    return {static_cast<double>(wide(2 * sigma) / ak),
            static_cast<double>(sigma_plus_b<wide>(k - 1, al, be, sigma) / ak),
            static_cast<double>(akm1 / ak)};
}

/// Recurrence constants of a family for up to `bands` bands, in precision T. Band b holds the
/// steps of the orders that advance in it, ascending in m (step 1: m = 0..b-1; step 2:
/// m = b-2, b-4, ... >= 0), contiguous from row[b].
template <class T>
struct RowTable {
    std::vector<T> pz, d, c, start;
    std::vector<std::size_t> row;

    RowTable(const Family& f, int bands) {
        const std::size_t nb = static_cast<std::size_t>(bands);
        row.assign(nb + 1, 0);
        start.assign(nb, T(0));
        wide q = f.q0;
        for (int m = 0; m < bands; ++m) {
            if (m > 0) q *= f.start_ratio<wide>(m);
            start[static_cast<std::size_t>(m)] = static_cast<T>(q);
        }
        for (int b = 0; b < bands; ++b) {
            row[static_cast<std::size_t>(b)] = pz.size();
            for (int m = f.step == 1 ? 0 : b % 2; m + f.step <= b; m += f.step) {
                const Step s = jacobi_step((b - m) / f.step, f.alpha(m), f.beta(m), f.sigma);
                pz.push_back(static_cast<T>(s.pz));
                d.push_back(static_cast<T>(s.d));
                c.push_back(static_cast<T>(s.c));
            }
        }
        row[nb] = pz.size();
    }
};

/// The shared table of family Fam (a type with `static constexpr Family family`), built once,
/// thread-safe.
template <class T, class Fam>
const RowTable<T>& row_table() {
    static const RowTable<T> t(Fam::family, max_row_bands);
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

/// cos(m phi) and sin(m phi) scaled by S^m: Re/Im (X + iY)^m, m = 0..bands-1.
template <class V>
SPHBASIS_FORCEINLINE void powers(int bands, const V& X, const V& Y, V* cm, V* sm) noexcept {
    using S = scalar_t<V>;
    cm[0] = V(S(1));
    sm[0] = V(S(0));
    for (int m = 1; m < bands; ++m) {
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
    const RowTable<S>& t = row_table<S, Fam>();
    V cm[Cap], sm[Cap], cur[Cap], prev[Cap];
    powers(bands, X, Y, cm, sm);
    for (int l = 0; l < bands; ++l) {
        const std::size_t o = t.row[static_cast<std::size_t>(l)];
        const S* pz = t.pz.data() + o;
        const S* d = t.d.data() + o;
        const S* c = t.c.data() + o;
        for (int m = 0; m < l; ++m) {
            const V v = (splat<V>(pz[m]) * zc - splat<V>(d[m])) * cur[m] - splat<V>(c[m]) * prev[m];
            prev[m] = cur[m];
            cur[m] = v;
        }
        cur[l] = splat<V>(t.start[static_cast<std::size_t>(l)]) * E;
        prev[l] = V(S(0));
        const int k = l * (l + 1);
        store(k, cur[0]);
        for (int m = 1; m <= l; ++m) {
            store(k + m, cur[m] * cm[m]);
            store(k - m, cur[m] * sm[m]);
        }
    }
}

/// A wide value carried with a binary exponent (value = m 2^e), as sh.hpp's Scaled.
struct ScaledW {
    wide m;
    int e;
};
inline constexpr int rescale_bits = 480;  // 2^480 ~ 3e144, far inside the double range

/// Column recurrence of family f, any band count: calls out(band, m, value) for every function,
/// m signed (m > 0: cos, m < 0: sin, 0). zc = max(z, 0), (X, Y) the family's sectoral pair, E the
/// family's factor (0 below the horizon). The sectoral starts carry a binary exponent, so nothing
/// underflows before the recurrence has grown it back; values below the double range come out
/// as 0, never NaN or Inf. Coefficients are computed on the fly: ~1 sqrt and 3 divisions per
/// function, in the `wide` type.
template <class Out>
inline void columns(const Family& f, int bands, wide zc, wide X, wide Y, wide E, Out&& out) {
    using R = wide;
    // sin' = |(X, Y)|, cos(phi), sin(phi) without underflow (as sh::detail::polar_xy).
    R s = 0, cp = 1, sp = 0;
    const R mx = std::max(std::fabs(X), std::fabs(Y));
    if (mx > 0) {
        const R rx = X / mx, ry = Y / mx, r = std::sqrt(rx * rx + ry * ry);
        s = mx * r;
        cp = rx / r;
        sp = ry / r;
    }
    int s_exp = 0;
    const R s_mant = s > 0 ? std::frexp(s, &s_exp) : R(0);
    const R small = std::ldexp(R(1), -rescale_bits), big = std::ldexp(R(1), rescale_bits);
    ScaledW q{R(f.q0) * E, 0};
    R cm = 1, sm = 0;
    const R two_sigma_z = R(2 * f.sigma) * zc;
    for (int m = 0; m < bands; ++m) {
        if (m > 0) {
            q.m *= f.start_ratio<R>(m) * s_mant;
            q.e += s_exp;
            if (q.m != 0 && std::fabs(q.m) < small) {
                int k;
                q.m = std::frexp(q.m, &k);
                q.e += k;
            }
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
            if (e < 0 && std::fabs(p0) > big) {
                // Move magnitude from the mantissas into the exponent, but never above 2^0.
                const int shift = std::min(rescale_bits, -e);
                p0 = std::ldexp(p0, -shift);
                p1 = std::ldexp(p1, -shift);
                e += shift;
            }
            emit(b, p0);
            p2 = p1;
            p1 = p0;
        }
    }
}

/// Runs columns() for a value type V: directly for float/double, lane by lane for batches.
/// prep(x, y, z, zc, X, Y, E) computes the family's inputs in the wide type from the lane's
/// direction (m-th powers of (X, Y) amplify their rounding m times); index(b, m) maps a label to
/// the function index.
template <class V, class Store, class Prep, class Index>
inline void columns_any(const Family& f, int bands, const V& x, const V& y, const V& z,
                        Store&& store, Prep&& prep, Index&& index) {
    auto run = [&](wide dx, wide dy, wide dz, auto&& put) {
        wide zc, X, Y, E;
        prep(dx, dy, dz, zc, X, Y, E);
        columns(f, bands, zc, X, Y, E, [&](int b, int m, double v) { put(index(b, m), v); });
    };
    if constexpr (std::is_floating_point_v<V>) {
        run(wide(x), wide(y), wide(z), [&](int k, double v) { store(k, static_cast<V>(v)); });
    } else {
        using S = scalar_t<V>;
        for (int i = 0; i < V::size; ++i)
            run(wide(x[i]), wide(y[i]), wide(z[i]),
                [&](int k, double v) { store.lane(k, i, static_cast<S>(v)); });
    }
}

/// 1 for z >= 0, else 0.
template <class V>
SPHBASIS_FORCEINLINE V upper(const V& z) noexcept {
    using S = scalar_t<V>;
    return select(z >= V(S(0)), V(S(1)), V(S(0)));
}

}  // namespace sphbasis::detail::hemi

namespace sphbasis::hsh {

/// Largest supported band count (degree 2047, 4194304 functions): the range verified against
/// mpmath (~3e-14 of the functions' scale away from the pole). The bound also keeps one
/// direction's cost (~n^2 square roots, ~45 ms at 2048 bands) and the index range reasonable.
inline constexpr int max_bands = 2048;

/// ACN index of (l, m), |m| <= l.
constexpr int index(int l, int m) noexcept { return l * (l + 1) + m; }
/// Number of functions in `bands` bands.
constexpr int count(int bands) noexcept { return bands * bands; }

namespace detail {

namespace hemi = sphbasis::detail::hemi;

struct HshFamily {
    // clang-format off
    static constexpr hemi::Family family{
        1, 1,                 // sigma, step: w = 2z - 1, band l = |m| + k
        0, 1, 0, 1,           // alpha = |m|, beta = |m|
        0.39894228040143268,  // q0 = 1/sqrt(2 pi)
        0.69098829894267096,  // q1 = sqrt(3/(2 pi))
        0};                   // q_m = q_{m-1} sqrt((2m+1)/(2m)), m >= 2
    // clang-format on
};

/// zc = max(z, 0), (X, Y) = 2 sqrt(zc/(1+zc)) (x, y) = sin' (cos phi, sin phi), E = [z >= 0].
template <class V>
SPHBASIS_FORCEINLINE void prep(const V& x, const V& y, const V& z, V& zc, V& X, V& Y,
                               V& E) noexcept {
    using S = scalar_t<V>;
    zc = vmax(z, V(S(0)));
    const V g = V(S(2)) * vsqrt(zc / (V(S(1)) + zc));
    X = x * g;
    Y = y * g;
    E = hemi::upper(z);
}

/// bands <= 8: sqrt(2) times SH's unrolled kernel at (X, Y, 2 zc - 1).
template <int N>
struct FixedKernel {
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        V zc, X, Y, E;
        prep(x, y, z, zc, X, Y, E);
        const V scale = E * V(S(constants::sqrt2));
        sh::detail::eval_fixed<N>(X, Y, V(S(2)) * zc - V(S(1)),
                                  [&](int k, const V& v) { store(k, v * scale); });
    }
};
struct RowKernel {
    int bands;
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        V zc, X, Y, E;
        prep(x, y, z, zc, X, Y, E);
        hemi::rows_acn<HshFamily>(bands, zc, X, Y, E, store);
    }
};
struct ColumnKernel {
    int bands;
    template <class V, class Store>
    void operator()(const V& x, const V& y, const V& z, Store&& store) const {
        hemi::columns_any(
            HshFamily::family, bands, x, y, z, store,
            [](hemi::wide dx, hemi::wide dy, hemi::wide dz, hemi::wide& zc, hemi::wide& X,
               hemi::wide& Y, hemi::wide& E) { prep(dx, dy, dz, zc, X, Y, E); },
            [](int b, int m) { return index(b, m); });
    }
};

/// Calls f(kernel) with the fastest kernel for 1 <= bands <= max_bands.
template <class F>
inline decltype(auto) with_kernel(int bands, F&& f) {
    switch (bands) {
        case 1:
            return f(FixedKernel<1>{});
        case 2:
            return f(FixedKernel<2>{});
        case 3:
            return f(FixedKernel<3>{});
        case 4:
            return f(FixedKernel<4>{});
        case 5:
            return f(FixedKernel<5>{});
        case 6:
            return f(FixedKernel<6>{});
        case 7:
            return f(FixedKernel<7>{});
        case 8:
            return f(FixedKernel<8>{});
        default:
            break;
    }
    if (bands <= hemi::max_row_bands) return f(RowKernel{bands});
    return f(ColumnKernel{bands});
}

}  // namespace detail
}  // namespace sphbasis::hsh

namespace sphbasis {

/// Hemispherical harmonics (Gautron et al. 2004) as a basis (basis/basis.hpp): n = bands^2
/// functions, ACN order, orthonormal on the upper hemisphere, 0 below the horizon.
struct HSH {
    static constexpr const char* name = "hsh";
    static constexpr Domain domain = Domain::hemisphere;
    static constexpr bool orthonormal = true;
    /// Number of functions in `bands` bands: bands^2.
    static constexpr int count(int bands) noexcept { return bands * bands; }
    /// The band count of n functions, or -1 if n is not a positive square.
    static int bands_of(int n) noexcept {
        if (n < 1) return -1;
        const int b = sh::degree_of(n - 1) + 1;
        return b * b == n ? b : -1;
    }
    static bool valid_count(int n) noexcept {
        const int b = bands_of(n);
        return b >= 1 && b <= hsh::max_bands;
    }
    static const char* count_rule() noexcept {
        return "a square number (bands^2, bands <= 2048) of";
    }
    static int max_count() noexcept { return hsh::max_bands * hsh::max_bands; }
    /// Precondition: valid_count(n). Batch stores need lane(k, i, v) above 64 bands.
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        return hsh::detail::with_kernel(bands_of(n), std::forward<F>(f));
    }
};

}  // namespace sphbasis
