// sphbasis: hemispherical harmonics (HSH) of any degree, by the Jacobi recurrence
// (basis/detail/jacobi.hpp) that also evaluates the Makhotkin (makhotkin.hpp) and Zernike
// (zernike.hpp) bases.
//
// References: P. Gautron, J. Krivanek, S. Pattanaik, K. Bouatouch, "A Novel Hemispherical Basis
// for Accurate and Efficient Rendering", EGSR 2004; Ishmukhametov, "Irradiance
// Normal Mapping" (thesis), section 1.8.3, whose printed forms (1.22)-(1.32) are only a
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
// Misprints in Ishmukhametov's printed forms (derive, do not transcribe):
//   (1.23) H_1-1 = -sqrt(6/pi) y sqrt(z/(1+z)): spurious minus (its own left side is positive);
//   (1.26) H_2-2 = sqrt(30/pi)(cos^2 t - cos t) sin 2phi: the sign is reversed, it is
//          sqrt(30/pi)(cos t - cos^2 t) sin 2phi = 2 sqrt(30/pi) x y z/(1+z) (the printed right
//          side also puts the whole fraction under the root);
//   (1.30) H_21 printed with sin(phi); it is cos(phi) (the right side (1.31) has x);
//   (1.32) H_22 = sqrt(30/pi) cos 2phi (cos^2 t - cos t): reversed sign on the left side, the
//          right side sqrt(30/pi) z (x^2 - y^2)/(1+z) is right; (1.28) the root covers too much.
//
// Evaluation (no factorials, no pow; Holmes & Featherstone 2002 style normalised recurrences):
//   * bands <= 8, batches: sh.hpp's unrolled kernels at the mapped direction (X, Y, u), times
//     sqrt(2);
//   * bands <= 64: a normalised row recurrence (basis/detail/jacobi.hpp, detail::hemi) on Q = H /
//   sin'^m,
//     times Re/Im (X + iY)^m; any value type (float, double, batch); fully unrolled for float
//     and double at <= 8 bands, where it is faster per call than sh.hpp's kernels (no scale
//     multiplication per function; 9 functions, float: 10.5 against 13 ns).
//   * more bands: the column recurrence in extended precision (sphbasis::extended) with a binary
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
// horizon and pole at l = 2047 (see sphbasis::extended).
//
// The shared recurrence (detail::hemi) is basis/detail/jacobi.hpp; the kernels and the basis
// interface the three bases share are basis/detail/hemi_family.hpp.
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
#include "detail/banded_api.hpp"
#include "detail/hemi_family.hpp"
#include "detail/jacobi.hpp"
#include "sh.hpp"

namespace sphbasis::hsh {

/// Largest supported band count (degree 2047, 4194304 functions): the range verified against
/// mpmath (~3e-14 of the functions' scale away from the pole). The bound also keeps one
/// direction's cost (~n^2 square roots, ~45 ms at 2048 bands) and the index range reasonable.
inline constexpr int max_bands = 2048;

// ACN order and count as SH's: index(l, m) = l(l+1) + m, |m| <= l; count(bands) = bands^2.
using sh::count;
using sh::index;

namespace detail {

namespace hemi = sphbasis::detail::hemi;

struct HshFamily : hemi::Acn<HshFamily> {
    // clang-format off
    static constexpr hemi::Family family{
        1, 1,                 // sigma, step: w = 2z - 1, band l = |m| + k
        0, 1, 0, 1,           // alpha = |m|, beta = |m|
        0.39894228040143268,  // q0 = 1/sqrt(2 pi)
        0.69098829894267096,  // q1 = sqrt(3/(2 pi))
        0};                   // q_m = q_{m-1} sqrt((2m+1)/(2m)), m >= 2
    // clang-format on

    /// zc, (X, Y) as hemi::shifted_xy, E = [z >= 0].
    template <class V>
    static SPHBASIS_FORCEINLINE void prep(const V& x, const V& y, const V& z, V& zc, V& X, V& Y,
                                          V& E) noexcept {
        hemi::shifted_xy(x, y, z, zc, X, Y);
        E = hemi::upper(z);
    }
};

/// bands <= 8: float and double the row recurrence with a compile-time band count (unrolled);
/// batches sqrt(2) times SH's unrolled kernel at (X, Y, 2 zc - 1), cheaper across lanes.
template <int N>
struct FixedKernel {
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        if constexpr (std::is_floating_point_v<V>) {
            hemi::FixedRowKernel<HshFamily, N>{}(x, y, z, store);
        } else {
            using S = scalar_t<V>;
            V zc, X, Y, E;
            HshFamily::prep(x, y, z, zc, X, Y, E);
            const V scale = E * V(S(constants::sqrt2));
            sh::detail::eval_fixed<N>(X, Y, V(S(2)) * zc - V(S(1)),
                                      [&](int k, const V& v) { store(k, v * scale); });
        }
    }
};
SPHBASIS_HEMI_KERNELS(HshFamily);

}  // namespace detail
}  // namespace sphbasis::hsh

namespace sphbasis {

/// Hemispherical harmonics (Gautron et al. 2004) as a basis (basis/basis.hpp): n = bands^2
/// functions, ACN order, orthonormal on the upper hemisphere, 0 below the horizon.
struct HSH : detail::hemi::HemiBasis<detail::hemi::SquareCount, hsh::max_bands,
                                     hsh::detail::HshFamily, hsh::detail::FixedKernel> {
    static constexpr const char* name = "hsh";
};

}  // namespace sphbasis

namespace sphbasis::hsh {

// The banded entry points (check_bands, eval, eval_unit, eval<N>, eval_unit<N>, eval_batch,
// eval_sum, eval_sum_batch) as sh:: has them: basis/detail/banded_api.hpp documents them.
SPHBASIS_BANDED_ENTRY_POINTS(HSH, "hsh");

}  // namespace sphbasis::hsh
