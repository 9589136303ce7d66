// sphbasis: Ambient Dice, the icosahedral irradiance basis of Iwanicki and Sloan (its "SRBF"
// variant: one value per icosahedron vertex, cos^2 and cos^4 lobes on the vertex's hemisphere).
//
// Reference: M. Iwanicki and P.-P. Sloan, "Ambient Dice", Eurographics Symposium on Rendering
// 2017 (Experimental Ideas & Implementations). The paper gives three variants, all storing
// coefficients at the 12 vertices of an icosahedron: values plus directional derivatives
// interpolated by hybrid cubic Bezier triangles (36 coefficients, 9 per direction), the same
// with linear chromaticity in YCoCg (both in basis/ambient_dice_bezier.hpp), and the one
// implemented here, which "exploits the partition of unity formed by cos^2 and cos^4 restricted
// to a hemisphere oriented along the directions of the icosahedron vertices" (12 coefficients, 6
// read per direction). Each of c^2/2 and 5 c^4/6 alone is such a partition (below), so any blend
// w c^2/2 + (1 - w) 5 c^4/6 is; w = 0.7 is the blend of Probulator (Y. O'Donnell et al.,
// github.com/kayru/Probulator, Source/Probulator/ExperimentAmbientDice.cpp, srbfWeights). The
// paper's body was not at hand (only its abstract): w is not checked against it.
//
// Definition. t = (sqrt(5) - 1)/2 (the golden ratio's inverse); the 6 axes, each the unit vector
// of an icosahedron vertex (one of each antipodal pair),
//   a_0 = (A, B, 0), a_1 = (-A, B, 0), a_2 = (0, A, B), a_3 = (0, -A, B),
//   a_4 = (B, 0, A), a_5 = (B, 0, -A),
//   A = 1/sqrt(1 + t^2) = 2/sqrt(10 - 2 sqrt(5)), B = t A;
// the lobe w(c) = 0.35 c^2 + 0.25 c^4 (= 0.7 (c^2/2) + 0.3 (5 c^4/6)); functions
//   D_{2i}(n)   = w(n . a_i) where n . a_i > 0, else 0      (vertex +a_i)
//   D_{2i+1}(n) = w(n . a_i) where n . a_i < 0, else 0      (vertex -a_i).
// Partition of unity: the 6 axes are a tight frame, sum_i (n . a_i)^2 = 2, and the 12 vertices a
// spherical 5-design, sum_i (n . a_i)^4 = 6/5; so sum_k D_k(n) = 0.7 + 0.3 = 1 for every unit n.
// At a vertex its function is 0.6 and the five neighbours' (n . a = +-1/sqrt(5)) 0.08 each.
// Not orthonormal (the fits solve the Gram matrix). Domain: the whole sphere; on the upper
// hemisphere all 12 functions are non-zero somewhere (no vertex is -z). Continuous, C^1.
// Cost: 6 dot products, 6 lobes (4 multiply-adds each), 12 selects.
#pragma once

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "basis.hpp"

namespace sphbasis::ambient_dice {

/// The icosahedron's constants (tools/gen/gen_engine_bases_reference.py checks them).
inline constexpr double axis_a = 0.85065080835203988;  // 2/sqrt(10 - 2 sqrt(5))
inline constexpr double axis_b = 0.52573111211913359;  // (sqrt(5) - 1)/2 * axis_a
/// The lobe w(c) = w2 c^2 + w4 c^4.
inline constexpr double w2 = 0.35;  // 0.7 / 2
inline constexpr double w4 = 0.25;  // 0.3 * 5/6

namespace detail {

struct Kernel {
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        const V a = V(S(axis_a)), b = V(S(axis_b)), zero = V(S(0));
        const V c[6] = {a * x + b * y, b * y - a * x, a * y + b * z,
                        b * z - a * y, b * x + a * z, b * x - a * z};
        for (int i = 0; i < 6; ++i) {
            const V c2 = c[i] * c[i];
            const V w = c2 * (V(S(w2)) + V(S(w4)) * c2);
            store(2 * i, select(c[i] > zero, w, zero));
            store(2 * i + 1, select(c[i] > zero, zero, w));
        }
    }
};

}  // namespace detail
}  // namespace sphbasis::ambient_dice

namespace sphbasis {

/// Ambient Dice (SRBF variant) as a basis (basis/basis.hpp): 12 functions on the sphere, function
/// 2i at vertex +a_i, 2i+1 at -a_i; not orthonormal.
struct AmbientDice {
    static constexpr const char* name = "ambient-dice";
    static constexpr Domain domain = Domain::sphere;
    static constexpr bool orthonormal = false;
    static bool valid_count(int n) noexcept { return n == 12; }
    static int max_count() noexcept { return 12; }
    static const char* count_rule() noexcept { return "12"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        (void)n;
        return f(ambient_dice::detail::Kernel{});
    }
};

}  // namespace sphbasis
