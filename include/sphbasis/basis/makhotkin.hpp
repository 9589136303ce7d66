// sphbasis: the Makhotkin hemispherical basis of any degree.
//
// References: O. A. Makhotkin, "Analysis of radiative transfer between surfaces by hemispherical
// harmonics", J. Quant. Spectrosc. Radiat. Transfer 56(6), 1996; Ishmukhametov,
// "Irradiance Normal Mapping" (thesis), section 1.8.4, whose printed forms (1.33)-(1.45)
// are only a cross-check (see "Misprints" below).
//
// Definition (u = 2 cos(t) - 1 = 2z - 1, shifted Jacobi polynomials P_n^(a,b)):
//   M_l^m = N_lm sqrt(z) (1 - u^2)^(|m|/2) P_{l-|m|}^(|m|, |m|+1)(u) trig(m phi),
//   N_lm^2 = (l-|m|)! (l+|m|+1)! / (pi (1 + delta_m0) 2^(2|m|-1) (l!)^2),
// trig = cos(m phi) for m > 0, sin(|m| phi) for m < 0, 1 for m = 0.
// Why these are orthonormal on the hemisphere: dOmega = dz dphi and dz = du/2; the product of two
// functions of the same m carries sqrt(z)^2 (1 - u^2)^|m| = ((1 + u)/2) (1 - u)^|m| (1 + u)^|m|,
// i.e. the Jacobi weight (1 - u)^a (1 + u)^b with (a, b) = (|m|, |m| + 1), so the P_{l-|m|} of
// one m are orthogonal; different m are orthogonal in phi. With the Jacobi norm h_n^(a,b) =
// 2^(a+b+1) G(n+a+1) G(n+b+1) / ((2n+a+b+1) n! G(n+a+b+1)) the hemisphere integral is
// N^2 pi (1 + delta_m0) h / 4 = 1, which is N_lm above. (1 - u^2)^(1/2) = 2 sqrt(z (1 - z)), so
// (1 - u^2)^(|m|/2) trig(m phi) = Re/Im (X + iY)^|m| with (X, Y) = 2 sqrt(z/(1+z)) (x, y).
// Sign convention as SH: cos(m phi) functions (m > 0) are positive multiples of x-like terms,
// sin(|m| phi) functions (m < 0) of y-like terms. Bands 0..2:
//   M_00 = sqrt(z/pi)                                M_1-1 = 2 sqrt(3/pi) y z / sqrt(1+z)
//   M_10 = sqrt(2/pi) sqrt(z) (3z - 2)               M_11  = 2 sqrt(3/pi) x z / sqrt(1+z)
//   M_2-2 = 4 sqrt(15/pi) x y z sqrt(z) / (1+z)      M_2-1 = sqrt(3/pi) y z (10z - 6) / sqrt(1+z)
//   M_20 = sqrt(3/pi) sqrt(z) (10z^2 - 12z + 3)      M_21  = sqrt(3/pi) x z (10z - 6) / sqrt(1+z)
//   M_22 = 2 sqrt(15/pi) z sqrt(z) (x^2 - y^2) / (1+z)
//
// Ordering: ACN, index l(l+1) + m; n bands = n^2 functions; 1 <= n <= makhotkin::max_bands.
// Domain: the upper hemisphere z >= 0. BELOW THE HORIZON (z < 0) every function is 0 (the
// sqrt(z) factor has no real extension). At the horizon z = 0 every function is 0; the pole z = 1
// is a regular point.
//
// Misprints in Ishmukhametov's printed forms (derive, do not transcribe):
//   (1.33) M_00 = z/sqrt(pi): the right side drops the root, it is sqrt(z)/sqrt(pi);
//   (1.34)-(1.45) label cos(m phi) functions with negative m and sin(|m| phi) ones with positive
//          m (M_-1^1 = ... cos(phi)): the opposite of Ishmukhametov's own SH/HSH convention; here
//          m > 0 is cos;
//   (1.42) M_20 = sqrt(3/pi) sqrt(z) (1 + 16(z-1) + 10(z-1)^2): 16 must be 8 (its left side
//          (1.41) 1 + 4(2cos t - 2) + 5/2 (2cos t - 2)^2 is right; = 10z^2 - 12z + 3).
//
// Evaluation: the shared normalised Jacobi recurrence of basis/detail/jacobi.hpp (detail::hemi,
// family
// (|m|, |m|+1) in w = u, advanced in z itself): a row recurrence for bands <= 64 (any value type),
// the exponent-carrying column recurrence in extended precision above. No factorials, no pow. Cost:
// two square roots and one division per direction, then ~n^2 multiply-adds (plus ~n^2 square
// roots and divisions above 64 bands, ~10 ns per function). Accuracy (double, against mpmath;
// tests/basis/test_makhotkin.cpp), relative to the scale S_l = sqrt((l+1)/pi) = M_l0(pole):
// <= 2e-15 below 64 bands, <= 3e-14 at l = 2047, except within ~0.01 of the pole, where the
// input's own rounding dominates (one ulp of z moves a degree-l function by up to ~l^2 1e-16 S_l;
// measured 1.3e-11 S_l at l = 2047, t = 1e-3).
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
#include "sh.hpp"

namespace sphbasis::makhotkin {

/// Largest supported band count (degree 2047, 4194304 functions); see hsh::max_bands.
inline constexpr int max_bands = 2048;

// ACN order and count as SH's: index(l, m) = l(l+1) + m, |m| <= l; count(bands) = bands^2.
using sh::count;
using sh::index;

namespace detail {

namespace hemi = sphbasis::detail::hemi;

struct MakhotkinFamily : hemi::Acn<MakhotkinFamily> {
    // clang-format off
    static constexpr hemi::Family family{
        1, 1,                 // sigma, step: w = 2z - 1, band l = |m| + k
        0, 1, 1, 1,           // alpha = |m|, beta = |m| + 1
        0.56418958354775629,  // q0 = 1/sqrt(pi)
        0.97720502380583984,  // q1 = sqrt(3/pi)
        0};                   // q_m = q_{m-1} sqrt((2m+1)/(2m)), m >= 2
    // clang-format on

    /// zc, (X, Y) as hemi::shifted_xy, E = sqrt(zc) (0 below the horizon).
    template <class V>
    static SPHBASIS_FORCEINLINE void prep(const V& x, const V& y, const V& z, V& zc, V& X, V& Y,
                                          V& E) noexcept {
        hemi::shifted_xy(x, y, z, zc, X, Y);
        E = vsqrt(zc);
    }
};

/// bands <= 8: the row recurrence with a compile-time band count.
template <int N>
using FixedKernel = hemi::FixedRowKernel<MakhotkinFamily, N>;
SPHBASIS_HEMI_KERNELS(MakhotkinFamily);

}  // namespace detail
}  // namespace sphbasis::makhotkin

namespace sphbasis {

/// The Makhotkin basis (1996) as a basis (basis/basis.hpp): n = bands^2 functions, ACN order,
/// orthonormal on the upper hemisphere, 0 below the horizon.
struct Makhotkin
    : detail::hemi::HemiBasis<detail::hemi::SquareCount, makhotkin::max_bands,
                              makhotkin::detail::MakhotkinFamily, makhotkin::detail::FixedKernel> {
    static constexpr const char* name = "makhotkin";
};

}  // namespace sphbasis

namespace sphbasis::makhotkin {

// The banded entry points (check_bands, eval, eval_unit, eval<N>, eval_unit<N>, eval_batch,
// eval_sum, eval_sum_batch) as sh:: has them: basis/detail/banded_api.hpp documents them.
SPHBASIS_BANDED_ENTRY_POINTS(Makhotkin, "makhotkin");

}  // namespace sphbasis::makhotkin
