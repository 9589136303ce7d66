// sphbasis: the H-basis (Habel & Wimmer 2010) and the modified H-basis of Ishmukhametov.
//
// References: R. Habel, M. Wimmer, "Efficient Irradiance Normal Mapping", I3D 2010, pp. 189-195;
// Ishmukhametov, "Irradiance Normal Mapping" (thesis), sections 1.8.6-1.8.7 and the
// shader of its Listing 2.2 (constants 0.39894, 0.69099, 1.54509, 0.77255).
//
// H-basis: 4 or 6 polynomials of degree <= 2, orthonormal on the upper hemisphere:
//   H1 = 1/sqrt(2 pi)                 H2 = sqrt(3/(2 pi)) y     H3 = sqrt(3/(2 pi)) (2z - 1)
//   H4 = sqrt(3/(2 pi)) x             H5 = sqrt(15/(2 pi)) x y  H6 = sqrt(15/(2 pi))/2 (x^2 - y^2)
// stored in that order at indices 0..5 (the SH-like order y, z, x of the linear band). H2, H4,
// H5, H6 are the SH functions y_1-1, y_11, y_2-2, y_22 renormalised to the hemisphere (times
// sqrt(2): their squares are even in z, so the hemisphere holds half of each norm); H1 and H3 are
// the shifted Legendre polynomials P_0, P_1(2z - 1), i.e. the HSH H_00 and H_10.
// Orthonormality, by hand (hemisphere integrals: int 1 = 2 pi, int x^2 = int y^2 = int z^2 =
// 2 pi/3, int x^2 y^2 = 2 pi/15, int x^4 = int y^4 = 2 pi/5, int (2z-1)^2 = 2 pi/3,
// int (2z - 1) = 0): each square integrates to 1; every cross term either has an odd power of x
// or of y (zero by the phi symmetry), or is int (x^2 - y^2) f(z) = 0, or int (2z - 1) = 0.
// The first 4 functions (constant + linear) are a basis of their own (the "middle LOD").
//
// Modified H-basis (Ishmukhametov, section 1.8.7): H3 replaced by
//   H3mod = sqrt(3/(2 pi)) (1 - z),
// which vanishes at the normal (0, 0, 1), so that the constant H1 alone is the light map. NOT
// orthonormal: its Gram matrix on the hemisphere is the identity except
//   <H1, H3mod> = sqrt(3)/(2 pi) * 2 pi * int_0^1 (1 - z) dz = sqrt(3)/2,
//   <H3mod, H3mod> = 3/(2 pi) * 2 pi * int_0^1 (1 - z)^2 dz = 1.
// Ishmukhametov's shader constants are these normalisations: 0.39894 = 1/sqrt(2 pi),
// 0.69099 = sqrt(3/(2 pi)), 1.54509 = sqrt(15/(2 pi)) = 1.5450968... (truncated, not rounded, in
// the listing), 0.77255 = sqrt(15/(2 pi))/2.
// (Misprint in Ishmukhametov: (1.53) typesets the root over y, sqrt(3/(2 pi) y); it is sqrt(3/(2
// pi)) y.)
//
// Domain: the upper hemisphere z >= 0 (orthonormality holds there). BELOW THE HORIZON (z < 0) the
// functions return their polynomials, which extend smoothly to the whole sphere (not orthonormal
// there); callers that want 0 below the horizon mask it themselves. The pole and the horizon are
// ordinary points. Cost: a few multiply-adds, no division, no square root.
#pragma once

#include <utility>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"

namespace sphbasis::hbasis::detail {

/// The 4 or 6 functions at a unit direction; Mod selects the modified H3.
template <int N, bool Mod>
struct Kernel {
    static_assert(N == 4 || N == 6, "sphbasis::hbasis: the H-basis has 4 or 6 functions.");
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        const V c1(S(0.69098829894267096));   // sqrt(3/(2 pi))
        store(0, V(S(0.39894228040143268)));  // 1/sqrt(2 pi)
        store(1, c1 * y);
        if constexpr (Mod)
            store(2, c1 - c1 * z);  // sqrt(3/(2 pi)) (1 - z)
        else
            store(2, V(S(1.3819765978853419)) * z - c1);  // sqrt(3/(2 pi)) (2z - 1)
        store(3, c1 * x);
        if constexpr (N == 6) {
            store(4, V(S(1.5450968080927583)) * x * y);             // sqrt(15/(2 pi))
            store(5, V(S(0.77254840404637916)) * (x * x - y * y));  // sqrt(15/(2 pi))/2
        }
    }
};

template <bool Mod, class F>
inline decltype(auto) with_kernel(int n, F&& f) {
    if (n == 4) return f(Kernel<4, Mod>{});
    return f(Kernel<6, Mod>{});
}

}  // namespace sphbasis::hbasis::detail

namespace sphbasis {

/// The H-basis (Habel & Wimmer 2010; Mod = false) and the modified H-basis (Mod = true) as bases
/// (basis/basis.hpp): 4 or 6 functions on the upper hemisphere; below the horizon the
/// polynomials are returned.
template <bool Mod>
struct HBasisOf : detail::HemiFixedCounts<!Mod, 4, 6> {
    static constexpr const char* name = Mod ? "hbasis-mod" : "hbasis";
    static const char* count_rule() noexcept { return "4 or 6"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        return hbasis::detail::with_kernel<Mod>(n, std::forward<F>(f));
    }
};

/// The H-basis: orthonormal on the upper hemisphere.
using HBasis = HBasisOf<false>;
/// The modified H-basis (H3 = sqrt(3/(2 pi)) (1 - z)): NOT orthonormal (<H1, H3> = sqrt(3)/2).
using HBasisMod = HBasisOf<true>;

}  // namespace sphbasis
