// sphbasis: Ambient Dice over the icosahedron's faces: the "Bezier" variant of Iwanicki and Sloan
// (values and two directional derivatives at the 12 vertices, hybrid cubic Bezier triangles over
// the 20 faces) and the linear interpolation of vertex values that their YCoCg variant uses for
// the chroma channels.
//
// Reference: M. Iwanicki and P.-P. Sloan, "Ambient Dice", Eurographics Symposium on Rendering
// 2017 (Experimental Ideas & Implementations). Its abstract defines the variants: the first
// "stores the values directly, together with their directional derivatives and hybrid Bezier
// patches are used for interpolation" (27 coefficients read per direction for RGB: 3 vertices x
// 3 values x 3 channels; 36 stored per channel); the second keeps that for luma and a linear
// reconstruction for Co and Cg (15 read per direction); the third is the SRBF variant of
// basis/ambient_dice.hpp. The paper's body (its interior-point rule) was not at hand: the patch
// below is this library's construction with the abstract's ingredients, and it is pinned by the
// properties a user relies on (tests/basis/test_ambient_dice_bezier.cpp), not by the paper's
// figures.
//
// Definition (constants: basis/ambient_dice_bezier_tables.hpp,
// tools/gen/gen_ambient_dice_bezier.py).
//   Vertices v_k: the 12 of ambient_dice.hpp (2i = +a_i, 2i+1 = -a_i); at each a tangent frame
//   (u_k, w_k). Function 3k is the value at v_k, 3k+1 and 3k+2 the directional derivatives there
//   along u_k and w_k (d/dt f(cos t v_k + sin t u_k) at t = 0): a coefficient vector is the
//   values and tangential gradients of the function it represents at the vertices.
//   A direction d lies in the face (i, j, k) maximising d . normal; beta = the planar barycentrics
//   of d's central projection onto that face's plane (coordinates of d in v_i, v_j, v_k, divided
//   by their sum). Over beta a cubic Bezier triangle: vertex points f_a; edge points
//   c_ab = f_a + (1/3) grad f_a . v_b (the patch reproduces f_a and grad f_a exactly); and, as in
//   Foley and Opitz ("Hybrid cubic Bezier triangle patches", 1992), one interior point per edge
//   blended by beta_a beta_b / (beta_0 beta_1 + beta_1 beta_2 + beta_2 beta_0), chosen so that the
//   derivative across the edge at its midpoint is the mean of the two vertex gradients along the
//   edge's normal, the same from both faces. So: constants reproduced exactly (the value
//   functions sum to 1), vertex values and derivatives interpolated, continuous across every
//   edge (C0; C1 at the vertices and the edge midpoints).
//   The linear variant: function k is beta_a where v_k is the face's vertex a (a hat function;
//   partition of unity, continuous, piecewise rational).
// Not orthonormal (fits solve the Gram matrix). Domain: the whole sphere; on the upper hemisphere
// the vertices 9 = (-B, 0, -A) and 10 = (B, 0, -A) have no support (their faces lie in z <= 0):
// the sizes 30 (Bezier) and 10 (linear) drop them, as the ambient cube's 5 drops its -z face.
// Only the 9 (3) functions of the direction's face are non-zero.
// Cost: 20 dot products to find the face, 3 for the barycentrics, a division, the Bernstein
// terms and ~40 multiply-adds; the SIMD batch runs the scalar code per lane (the faces differ).
#pragma once

#include <type_traits>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "ambient_dice_bezier_tables.hpp"
#include "basis.hpp"

namespace sphbasis::ambient_dice {
namespace detail {

/// The face of unit direction (x, y, z) and the barycentrics beta of its central projection.
template <class T>
SPHBASIS_FORCEINLINE int locate_face(T x, T y, T z, T beta[3]) noexcept {
    namespace tb = tables;
    int face = 0;
    T best = T(-2);
    for (int f = 0; f < 20; ++f) {
        const T d = T(tb::face_normal[f][0]) * x + T(tb::face_normal[f][1]) * y +
                    T(tb::face_normal[f][2]) * z;
        if (d > best) {
            best = d;
            face = f;
        }
    }
    T sum = T(0);
    for (int a = 0; a < 3; ++a) {
        const auto& r = tb::face_dual[face][a];
        const T b = T(r[0]) * x + T(r[1]) * y + T(r[2]) * z;
        beta[a] = b > T(0) ? b : T(0);  // rounding at the face's edges
        sum += beta[a];
    }
    // sum >= 1 for a unit direction in the face (|d| <= the sum of its vertex coordinates).
    const T inv = T(1) / sum;
    for (int a = 0; a < 3; ++a) beta[a] *= inv;
    return face;
}

/// The 36 Bezier-variant values at a unit direction.
template <class T>
SPHBASIS_FORCEINLINE void bezier_values(T x, T y, T z, T* out) noexcept {
    namespace tb = tables;
    T be[3];
    const int f = locate_face(x, y, z, be);
    constexpr int edge_from[6] = {0, 0, 1, 1, 2, 2}, edge_to[6] = {1, 2, 0, 2, 0, 1};
    T w[9];  // weights of (f, g_u, g_w) of the face's vertices
    for (int a = 0; a < 3; ++a) {
        w[3 * a] = be[a] * be[a] * be[a];
        w[3 * a + 1] = w[3 * a + 2] = T(0);
    }
    for (int e = 0; e < 6; ++e) {
        const int a = edge_from[e];
        const T c = T(3) * be[a] * be[a] * be[edge_to[e]];
        w[3 * a] += c;
        w[3 * a + 1] += c * T(tb::face_edge[f][e][0]);
        w[3 * a + 2] += c * T(tb::face_edge[f][e][1]);
    }
    // Interior points: 6 b0 b1 b2 (b_a b_b / den) for the edge (a, b) opposite m; at a vertex
    // den = 0 and the term is 0.
    const T den = be[0] * be[1] + be[1] * be[2] + be[2] * be[0];
    const T scale = den > T(0) ? T(6) * be[0] * be[1] * be[2] / den : T(0);
    constexpr int pa[3] = {1, 0, 0}, pb[3] = {2, 2, 1};
    for (int m = 0; m < 3; ++m) {
        const T c = scale * be[pa[m]] * be[pb[m]];
        const double* q = tb::face_interior[f][m];
        for (int i = 0; i < 3; ++i) {
            w[3 * pa[m] + i] += c * T(q[i]);
            w[3 * pb[m] + i] += c * T(q[3 + i]);
        }
    }
    for (int k = 0; k < 36; ++k) out[k] = T(0);
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) out[3 * tb::face_vertex[f][a] + i] = w[3 * a + i];
}

/// The 12 linear-variant values at a unit direction.
template <class T>
SPHBASIS_FORCEINLINE void linear_values(T x, T y, T z, T* out) noexcept {
    T be[3];
    const int f = locate_face(x, y, z, be);
    for (int k = 0; k < 12; ++k) out[k] = T(0);
    for (int a = 0; a < 3; ++a) out[tables::face_vertex[f][a]] = be[a];
}

/// A kernel of Ambient Dice over the faces (per vertex: 3 functions for the Bezier variant, 1 for
/// the linear one) from the scalar evaluator; Hemi drops vertices 9 and 10, which have no support
/// on z >= 0 (the later vertex 11 moves up to 9). Batches run the scalar code per lane (each lane
/// has its own face) and store whole batches.
template <bool Bezier, bool Hemi>
struct FaceKernel {
    static constexpr int per_vertex = Bezier ? 3 : 1;
    static constexpr int all = 12 * per_vertex;
    static constexpr int count = Hemi ? 10 * per_vertex : all;
    template <class T>
    static SPHBASIS_FORCEINLINE void values(T x, T y, T z, T* out) noexcept {
        T v[all];
        if constexpr (Bezier)
            bezier_values(x, y, z, v);
        else
            linear_values(x, y, z, v);
        for (int k = 0; k < count; ++k)
            out[k] = v[Hemi && k >= 9 * per_vertex ? k + 2 * per_vertex : k];
    }
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        using S = scalar_t<V>;
        if constexpr (std::is_arithmetic_v<V>) {
            S v[count];
            values(x, y, z, v);
            for (int k = 0; k < count; ++k) store(k, v[k]);
        } else {
            constexpr int W = V::size;
            S v[count][W], one[count];
            for (int i = 0; i < W; ++i) {
                values(x[i], y[i], z[i], one);
                for (int k = 0; k < count; ++k) v[k][i] = one[k];
            }
            for (int k = 0; k < count; ++k) store(k, V::load(v[k]));
        }
    }
};

}  // namespace detail
}  // namespace sphbasis::ambient_dice

namespace sphbasis {

/// Ambient Dice, Bezier variant, as a basis (basis/basis.hpp): 36 functions on the sphere,
/// 3k = value at vertex k, 3k+1 / 3k+2 = its directional derivatives along tangent_u[k] /
/// tangent_w[k]; or 30 on the upper hemisphere (vertices 9 and 10 dropped, vertex 11's three
/// functions at 27..29); not orthonormal.
struct AmbientDiceBezier {
    static constexpr const char* name = "ambient-dice-bezier";
    static constexpr Domain domain = Domain::sphere;
    static constexpr bool orthonormal = false;
    static bool valid_count(int n) noexcept { return n == 30 || n == 36; }
    static int max_count() noexcept { return 36; }
    static const char* count_rule() noexcept { return "30 (upper hemisphere) or 36"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        if (n == 30) return f(ambient_dice::detail::FaceKernel<true, true>{});
        return f(ambient_dice::detail::FaceKernel<true, false>{});
    }
};

/// Ambient Dice's linear interpolation of the 12 vertex values over the faces (the chroma of its
/// YCoCg variant) as a basis: function k the hat function of vertex k; or 10 on the upper
/// hemisphere (vertices 9 and 10 dropped, vertex 11 at 9); not orthonormal.
struct AmbientDiceLinear {
    static constexpr const char* name = "ambient-dice-linear";
    static constexpr Domain domain = Domain::sphere;
    static constexpr bool orthonormal = false;
    static bool valid_count(int n) noexcept { return n == 10 || n == 12; }
    static int max_count() noexcept { return 12; }
    static const char* count_rule() noexcept { return "10 (upper hemisphere) or 12"; }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        if (n == 10) return f(ambient_dice::detail::FaceKernel<false, true>{});
        return f(ambient_dice::detail::FaceKernel<false, false>{});
    }
};

}  // namespace sphbasis
