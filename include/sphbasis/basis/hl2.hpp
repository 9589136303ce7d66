// sphbasis: the Half-Life 2 basis ("radiosity normal mapping" basis of Valve's Source engine).
//
// References: G. McTaggart, "Half-Life 2 / Valve Source Shading", GDC 2004 (Valve technical
// report); Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 1.8.2, eqs.
// (1.18)-(1.21).
//
// Definition: three linear functions (unclamped cosine lobes)
//   HL2_i(n) = sqrt(3/(2 pi)) n . h_i,
//   h_1 = (-1/sqrt(6), -1/sqrt(2), 1/sqrt(3)),
//   h_2 = (-1/sqrt(6),  1/sqrt(2), 1/sqrt(3)),
//   h_3 = ( sqrt(2/3),  0,         1/sqrt(3)),
// indices 0, 1, 2. The h_i are orthonormal vectors, each tilted acos(1/sqrt(3)) = 54.74 degrees
// from the normal, at azimuths -120, 120 and 0 degrees. Expanded:
//   HL2_1 = -x/(2 sqrt(pi)) - sqrt(3/(4 pi)) y + z/sqrt(2 pi)
//   HL2_2 = -x/(2 sqrt(pi)) + sqrt(3/(4 pi)) y + z/sqrt(2 pi)
//   HL2_3 =  x/sqrt(pi) + z/sqrt(2 pi)
// Orthonormality on the hemisphere: <n.a, n.b> = a^T M b with M = int_hemisphere n n^T dOmega =
// (2 pi/3) I (int x z = int y z = int x y = 0 by the phi symmetry, int x^2 = int y^2 = int z^2 =
// 2 pi/3), so the Gram matrix is 3/(2 pi) (2 pi/3) h_i . h_j = delta_ij. (On the whole sphere
// M = (4 pi/3) I and the Gram matrix is 2 I: orthogonal but not normalised; Ishmukhametov's
// "orthonormal over the upper hemisphere as well as full sphere" holds for orthogonality only.) The
// three functions are a rotation of the linear SH band, renormalised to the hemisphere.
//
// Domain: the upper hemisphere z >= 0. BELOW THE HORIZON (z < 0) the linear polynomials are
// returned (they extend to the whole sphere); they are negative wherever n . h_i < 0, above the
// horizon too (no clamping: clamped lobes would not be orthonormal). Cost: 7 multiply-adds.
#pragma once

#include <utility>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"

namespace sphbasis::hl2::detail {

struct Kernel {
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        const V a = V(S(0.39894228040143268)) * z;      // z/sqrt(2 pi)
        const V b = a - V(S(0.28209479177387814)) * x;  // 1/(2 sqrt(pi))
        const V c = V(S(0.48860251190291992)) * y;      // sqrt(3/(4 pi))
        store(0, b - c);
        store(1, b + c);
        store(2, a + V(S(0.56418958354775629)) * x);  // 1/sqrt(pi)
    }
};

}  // namespace sphbasis::hl2::detail

namespace sphbasis {

/// The Half-Life 2 basis as a basis (basis/basis.hpp): 3 functions, orthonormal on the upper
/// hemisphere; below the horizon the linear polynomials are returned.
struct HL2 : detail::HemiFixedCounts<true, 3> {
    static constexpr const char* name = "hl2";
    static const char* count_rule() noexcept { return "3"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        (void)n;
        return f(hl2::detail::Kernel{});
    }
};

}  // namespace sphbasis
