// sphbasis: Ambient Dice over the icosahedron's faces: the "Bezier" variant of Iwanicki and Sloan
// (values and two directional derivatives at the 12 vertices, hybrid cubic Bezier triangles over
// the 20 faces) and the linear interpolation of vertex values that their YCoCg variant uses for
// the chroma channels; each in the paper's rule and in this library's earlier normalised rule.
//
// Reference: M. Iwanicki and P.-P. Sloan, "Ambient Dice", Eurographics Symposium on Rendering
// 2017 (Experimental Ideas & Implementations). Its abstract defines the variants: the first
// "stores the values directly, together with their directional derivatives and hybrid Bezier
// patches are used for interpolation" (27 coefficients read per direction for RGB: 3 vertices x
// 3 values x 3 channels; 36 stored per channel); the second keeps that for luma and a linear
// reconstruction for Co and Cg (15 read per direction); the third is the SRBF variant of
// basis/ambient_dice.hpp. The paper's body was not at hand; the paper's rule below is learned from
// T. Roughton's implementation of the paper in Probulator (2019, ExperimentAmbientDice): the
// unnormalised barycentrics (homogeneous patches), the edge points and the interior weight a2;
// a0 and a1 are this library's derivation from C1 continuity (tools/gen/gen_ambient_dice_bezier.py
// derives them exactly; they equal Probulator's), and so is the reason for a2 (linear precision).
//
// Definition (constants: basis/ambient_dice_bezier_tables.hpp,
// tools/gen/gen_ambient_dice_bezier.py).
//   Vertices v_k: the 12 of ambient_dice.hpp (2i = +a_i, 2i+1 = -a_i); at each a tangent frame
//   (u_k, w_k). Function 3k is the value at v_k, 3k+1 and 3k+2 the directional derivatives there
//   along u_k and w_k (d/dt f(cos t v_k + sin t u_k) at t = 0): a coefficient vector is the
//   values and tangential gradients g_k of the function it represents at the vertices.
//   A direction d lies in the face (i, j, k) whose cone contains it; b = the coordinates of d in
//   the face's unit vertices (d = sum b_a v_a).
//   ambient-dice-bezier (the paper's rule): over b a cubic Bezier triangle: vertex points f_a;
//   edge points c_ab = f_a (v_a . v_b) + (1/3) g_a . v_b (the blossom of a homogeneous cubic with
//   those vertex values and gradients); and, as in Foley and Opitz ("Hybrid cubic Bezier triangle
//   patches", 1992), one interior point per edge (b, c), c111_a = a0 (f_b + f_c) + a1 (c_bc + c_cb)
//   + a2 (c_ba + c_ca), blended by b_b b_c / (b_0 b_1 + b_1 b_2 + b_2 b_0); a2 = sqrt5/10,
//   a0 = (sqrt5 - 5)/40, a1 = (11 sqrt5 - 15)/40. Each face's patch is homogeneous in d:
//   vertex values and derivatives are interpolated, the patches meet C1 along every edge, and
//   linear functions of d (SH band 1) are reproduced exactly; constants are not (the value
//   functions sum to 0.938-1 over the sphere; tests/basis/test_ambient_dice_bezier.cpp).
//   ambient-dice-linear (the paper's rule): function k is b_a where v_k is the face's vertex a
//   (continuous, piecewise linear in d; linear functions of d exact, constants not: the
//   functions sum to 1-1.258, the most at the face centres).
//   ambient-dice-bezier-normalized, ambient-dice-linear-normalized (this library's construction
//   from before the paper's rule was known): b divided by its sum (the planar barycentrics of d's
//   central projection onto the face's plane), edge points c_ab = f_a + (1/3) g_a . v_b, interior
//   points chosen so that the derivative across an edge at its midpoint is the mean of the two
//   vertex gradients along the edge's normal. Constants exact (the value functions sum to 1),
//   vertex values and derivatives interpolated, C0 across the edges, C1 at the vertices and the
//   edge midpoints only.
// Not orthonormal (fits solve the Gram matrix). Domain: the whole sphere; on the upper hemisphere
// the vertices 9 = (-B, 0, -A) and 10 = (B, 0, -A) have no support (their faces lie in z <= 0):
// the sizes 30 (Bezier) and 10 (linear) drop them, as the ambient cube's 5 drops its -z face.
// Only the 9 (3) functions of the direction's face are non-zero.
// Cost: the face from the octant's sign bits and 3 plane tests, 3 dot products for b (and a
// division for the normalised rule), the Bernstein terms and ~40 multiply-adds; the SIMD batch
// does the arithmetic across lanes and gathers each lane's face constants (39 numbers per lane
// for the Bezier variant, 9 for the linear one).
#pragma once

#include <type_traits>

#include "../config.hpp"
#include "../core/scalar.hpp"
#include "../core/simd.hpp"
#include "ambient_dice_bezier_tables.hpp"
#include "basis.hpp"

namespace sphbasis::ambient_dice {
namespace detail {

/// The face of unit direction (x, y, z) and b, the coordinates of d in its vertices (Normalized:
/// divided by their sum, the barycentrics of d's central projection onto the face's plane). The
/// octant picks its face; a direction beyond one of that face's edges (tested on |x|, |y|, |z|)
/// lies in the face across it.
template <bool Normalized, class T>
SPHBASIS_FORCEINLINE int locate_face(T x, T y, T z, T b[3]) noexcept {
    namespace tb = tables;
    const int octant = int(x < T(0)) | int(y < T(0)) << 1 | int(z < T(0)) << 2;
    const T ax = x < T(0) ? -x : x, ay = y < T(0) ? -y : y, az = z < T(0) ? -z : z;
    int face = tb::locate_face[octant][0];
    for (int e = 0; e < 3; ++e) {
        const auto& p = tb::locate_plane[e];
        if (T(p[0]) * ax + T(p[1]) * ay + T(p[2]) * az < T(0))
            face = tb::locate_face[octant][1 + e];
    }
    T sum = T(0);
    for (int a = 0; a < 3; ++a) {
        const auto& r = tb::face_dual[face][a];
        const T c = T(r[0]) * x + T(r[1]) * y + T(r[2]) * z;
        b[a] = c > T(0) ? c : T(0);  // rounding at the face's edges
        sum += b[a];
    }
    if constexpr (Normalized) {
        // sum >= 1 for a unit direction in the face (|d| <= the sum of its vertex coordinates).
        const T inv = T(1) / sum;
        for (int a = 0; a < 3; ++a) b[a] *= inv;
    }
    return face;
}

/// The weights w of the Bezier variant's 9 local data (f, g_u, g_w of the face's vertices 0, 1, 2)
/// from b (locate_face) and the face's constants: edge(e, j) = face_edge[f][e][j] and
/// interior(m, i) = face_interior(_normalized)[f][m][i], as values of V (a scalar or a batch).
template <bool Normalized, class V, class Edge, class Interior>
SPHBASIS_FORCEINLINE void bezier_weights(const V be[3], Edge&& edge, Interior&& interior,
                                         V w[9]) noexcept {
    using S = scalar_t<V>;
    const V edge_value = Normalized ? S(1) : S(tables::edge_cos);  // c_ab's factor of f_a
    constexpr int edge_from[6] = {0, 0, 1, 1, 2, 2}, edge_to[6] = {1, 2, 0, 2, 0, 1};
    for (int a = 0; a < 3; ++a) {
        w[3 * a] = be[a] * be[a] * be[a];
        w[3 * a + 1] = w[3 * a + 2] = V(S(0));
    }
    for (int e = 0; e < 6; ++e) {
        const int a = edge_from[e];
        const V c = V(S(3)) * be[a] * be[a] * be[edge_to[e]];
        w[3 * a] += c * edge_value;
        w[3 * a + 1] += c * edge(e, 0);
        w[3 * a + 2] += c * edge(e, 1);
    }
    // Interior points: 6 b0 b1 b2 (b_a b_b / den) for the edge (a, b) opposite m; at a vertex
    // den = 0 and the term is 0.
    const V den = be[0] * be[1] + be[1] * be[2] + be[2] * be[0];
    V scale;
    if constexpr (std::is_arithmetic_v<V>)
        scale = den > S(0) ? S(6) * be[0] * be[1] * be[2] / den : S(0);
    else
        scale = select(den > V(S(0)), V(S(6)) * be[0] * be[1] * be[2] / den, V(S(0)));
    constexpr int pa[3] = {1, 0, 0}, pb[3] = {2, 2, 1};
    for (int m = 0; m < 3; ++m) {
        const V c = scale * be[pa[m]] * be[pb[m]];
        for (int i = 0; i < 3; ++i) {
            w[3 * pa[m] + i] += c * interior(m, i);
            w[3 * pb[m] + i] += c * interior(m, 3 + i);
        }
    }
}

/// The interior-point table of the rule.
template <bool Normalized>
SPHBASIS_FORCEINLINE const double (&interior_table(int f) noexcept)[3][6] {
    return Normalized ? tables::face_interior_normalized[f] : tables::face_interior[f];
}

/// The 36 Bezier-variant values at a unit direction.
template <bool Normalized, class T>
SPHBASIS_FORCEINLINE void bezier_values(T x, T y, T z, T* out) noexcept {
    namespace tb = tables;
    T be[3], w[9];
    const int f = locate_face<Normalized>(x, y, z, be);
    const auto& q = interior_table<Normalized>(f);
    bezier_weights<Normalized>(
        be, [&](int e, int j) { return T(tb::face_edge[f][e][j]); },
        [&](int m, int i) { return T(q[m][i]); }, w);
    for (int k = 0; k < 36; ++k) out[k] = T(0);
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i) out[3 * tb::face_vertex[f][a] + i] = w[3 * a + i];
}

/// The 12 linear-variant values at a unit direction.
template <bool Normalized, class T>
SPHBASIS_FORCEINLINE void linear_values(T x, T y, T z, T* out) noexcept {
    T be[3];
    const int f = locate_face<Normalized>(x, y, z, be);
    for (int k = 0; k < 12; ++k) out[k] = T(0);
    for (int a = 0; a < 3; ++a) out[tables::face_vertex[f][a]] = be[a];
}

/// A kernel of Ambient Dice over the faces (per vertex: 3 functions for the Bezier variant, 1 for
/// the linear one; Normalized: the normalised rule) from the scalar evaluator; Hemi drops vertices
/// 9 and 10, which have no support on z >= 0 (the later vertex 11 moves up to 9). Batches gather
/// each lane's face constants and compute across lanes (batch_values).
template <bool Bezier, bool Normalized, bool Hemi>
struct FaceKernel {
    static constexpr int per_vertex = Bezier ? 3 : 1;
    static constexpr int all = 12 * per_vertex;
    static constexpr int count = Hemi ? 10 * per_vertex : all;
    template <class T>
    static SPHBASIS_FORCEINLINE void values(T x, T y, T z, T* out) noexcept {
        T v[all];
        if constexpr (Bezier)
            bezier_values<Normalized>(x, y, z, v);
        else
            linear_values<Normalized>(x, y, z, v);
        for (int k = 0; k < count; ++k)
            out[k] = v[Hemi && k >= 9 * per_vertex ? k + 2 * per_vertex : k];
    }
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        if constexpr (std::is_arithmetic_v<V>) {
            V v[count];
            values(x, y, z, v);
            for (int k = 0; k < count; ++k) store(k, v[k]);
        } else {
            batch_values(x, y, z, store);
        }
    }
    /// A batch: the face per lane (octant and plane tests, its constants gathered per lane),
    /// then b and the weights across lanes, scattered into the lanes' functions.
    template <class V, class Store>
    static SPHBASIS_FORCEINLINE void batch_values(const V& x, const V& y, const V& z,
                                                  Store&& store) noexcept {
        namespace tb = tables;
        using S = scalar_t<V>;
        constexpr int W = V::size;
        const V ax = vabs(x), ay = vabs(y), az = vabs(z);
        V side[3];
        for (int e = 0; e < 3; ++e) {
            const auto& p = tb::locate_plane[e];
            side[e] = V(S(p[0])) * ax + V(S(p[1])) * ay + V(S(p[2])) * az;
        }
        int face[W];
        S dual[3][3][W];
        for (int i = 0; i < W; ++i) {
            const int octant = int(x[i] < S(0)) | int(y[i] < S(0)) << 1 | int(z[i] < S(0)) << 2;
            int f = tb::locate_face[octant][0];
            for (int e = 0; e < 3; ++e)
                if (side[e][i] < S(0)) f = tb::locate_face[octant][1 + e];
            face[i] = f;
            for (int a = 0; a < 3; ++a)
                for (int c = 0; c < 3; ++c) dual[a][c][i] = S(tb::face_dual[f][a][c]);
        }
        V be[3];
        for (int a = 0; a < 3; ++a)
            be[a] =
                vmax(V::load(dual[a][0]) * x + V::load(dual[a][1]) * y + V::load(dual[a][2]) * z,
                     V(S(0)));  // rounding at the face's edges
        if constexpr (Normalized) {
            const V inv = V(S(1)) / (be[0] + be[1] + be[2]);
            for (int a = 0; a < 3; ++a) be[a] *= inv;
        }
        V w[3 * per_vertex];
        if constexpr (Bezier) {
            S edge[6][2][W], interior[3][6][W];
            for (int i = 0; i < W; ++i) {
                const auto& q = interior_table<Normalized>(face[i]);
                for (int e = 0; e < 6; ++e)
                    for (int j = 0; j < 2; ++j) edge[e][j][i] = S(tb::face_edge[face[i]][e][j]);
                for (int m = 0; m < 3; ++m)
                    for (int j = 0; j < 6; ++j) interior[m][j][i] = S(q[m][j]);
            }
            bezier_weights<Normalized>(
                be, [&](int e, int j) { return V::load(edge[e][j]); },
                [&](int m, int j) { return V::load(interior[m][j]); }, w);
        } else {
            for (int a = 0; a < 3; ++a) w[a] = be[a];
        }
        S v[count][W] = {};
        for (int i = 0; i < W; ++i)
            for (int a = 0; a < 3; ++a) {
                int k = tb::face_vertex[face[i]][a];
                if (Hemi && (k == 9 || k == 10)) continue;  // no support on z >= 0: dropped
                if (Hemi && k == 11) k = 9;
                for (int j = 0; j < per_vertex; ++j)
                    v[per_vertex * k + j][i] = w[per_vertex * a + j][i];
            }
        for (int k = 0; k < count; ++k) store(k, V::load(v[k]));
    }
};

/// The basis interface (basis/basis.hpp) shared by the four face variants: 12 per-vertex groups
/// of 3 (Bezier) or 1 (linear) functions, or 10 on the upper hemisphere (vertices 9 and 10
/// dropped, vertex 11's functions moved up); not orthonormal.
template <bool Bezier, bool Normalized>
struct FaceBasis {
    static constexpr Domain domain = Domain::sphere;
    static constexpr bool orthonormal = false;
    static bool valid_count(int n) noexcept { return n == (Bezier ? 30 : 10) || n == max_count(); }
    static int max_count() noexcept { return Bezier ? 36 : 12; }
    static const char* count_rule() noexcept {
        return Bezier ? "30 (upper hemisphere) or 36" : "10 (upper hemisphere) or 12";
    }
    /// Precondition: valid_count(n).
    template <class F>
    static decltype(auto) with_kernel(int n, F&& f) {
        if (n == max_count()) return f(FaceKernel<Bezier, Normalized, false>{});
        return f(FaceKernel<Bezier, Normalized, true>{});
    }
};

}  // namespace detail
}  // namespace sphbasis::ambient_dice

namespace sphbasis {

/// Ambient Dice, Bezier variant, the paper's rule, as a basis (basis/basis.hpp): 36 functions on
/// the sphere, 3k = value at vertex k, 3k+1 / 3k+2 = its directional derivatives along
/// tangent_u[k] / tangent_w[k]; or 30 on the upper hemisphere (vertices 9 and 10 dropped, vertex
/// 11's three functions at 27..29); not orthonormal.
struct AmbientDiceBezier : ambient_dice::detail::FaceBasis<true, false> {
    static constexpr const char* name = "ambient-dice-bezier";
};

/// Ambient Dice's linear interpolation of the 12 vertex values over the faces (the chroma of its
/// YCoCg variant), the paper's rule (homogeneous: linear in d on each face's cone), as a basis;
/// or 10 on the upper hemisphere (vertices 9 and 10 dropped, vertex 11 at 9); not orthonormal.
struct AmbientDiceLinear : ambient_dice::detail::FaceBasis<false, false> {
    static constexpr const char* name = "ambient-dice-linear";
};

/// AmbientDiceBezier's coefficients and sizes with the normalised rule (constants exact, C1 only
/// at the vertices and edge midpoints).
struct AmbientDiceBezierNormalized : ambient_dice::detail::FaceBasis<true, true> {
    static constexpr const char* name = "ambient-dice-bezier-normalized";
};

/// AmbientDiceLinear with the normalised rule (planar barycentrics: hat functions that sum to 1).
struct AmbientDiceLinearNormalized : ambient_dice::detail::FaceBasis<false, true> {
    static constexpr const char* name = "ambient-dice-linear-normalized";
};

}  // namespace sphbasis
