#!/usr/bin/python3
"""Generates include/sphbasis/ops/sh_rotation_fixed.hpp: SH rotation matrices for 1..8 bands as
straight-line code.

Band 1 of D(R) is R with rows and columns permuted to (y, z, x). Band l >= 2 follows from band
l - 1 and band 1 by the Ivanic-Ruedenberg recurrence (J. Ivanic, K. Ruedenberg, J. Phys. Chem.
100 (1996) 6342, eqs. 5.1-5.6 and Table 2, with the corrections of J. Phys. Chem. A 102 (1998)
9099), the same recurrence as the run-time sh::Rotation (ops/sh_rotation.hpp), unrolled here at
generation time: every entry is written out with its factors folded into constants computed
exactly with sympy (17 significant digits, closed form in a comment), and the subexpressions that
several entries share are formed once:
  * per row m, the products g = (row factor) * R(i, 0) (i = -1, 0, 1), shared by the 2l - 1
    interior columns |n| < l, where P(i, a, n) = R(i, 0) D^{l-1}(a, n), so that
        D^l(m, n) = (sum_k g_k D^{l-1}(a_k, n)) / sqrt((l + n)(l - n));
  * per band, the edge terms P(i, a, +-l) = R(i, 1) D^{l-1}(a, +-(l-1)) -+ R(i, -1) D^{l-1}(a,
    -+(l-1)) (only those some entry uses), shared by the rows that need them.
The alternative, each entry as an explicit polynomial of degree l in the nine entries of R, has
far more terms from band 3 on (hundreds of monomials per entry at l = 5); the recurrence needs
at most five products per entry. The recurrence is homogeneous of degree l in R, so an improper
orthogonal matrix gives (-1)^l D(-R) per band, as the run-time code does.

Usage (from the repository root):
    /usr/bin/python3 tools/gen/gen_sh_rotation.py > include/sphbasis/ops/sh_rotation_fixed.hpp
"""
import sympy as sp

MAX_BANDS = 8


def lit(v):
    s = "%.17g" % float(sp.N(v, 40))
    if "e" not in s and "." not in s:
        s += ".0"
    return "T(%s)" % s


def closed(v):
    return str(sp.nsimplify(v))


def factors(l):
    """Row factors u, v, w (per m) and 1/sqrt(denominator) (per n) of band l, exact."""
    invd, us, vs, ws = {}, {}, {}, {}
    for n in range(-l, l + 1):
        den = (l + n) * (l - n) if -l < n < l else (2 * l) * (2 * l - 1)
        invd[n] = 1 / sp.sqrt(sp.Integer(den))
    for m in range(-l, l + 1):
        am = abs(m)
        d0 = 1 if m == 0 else 0
        us[m] = sp.sqrt(sp.Integer((l + m) * (l - m)))
        vs[m] = sp.Rational(1, 2) * sp.sqrt(sp.Integer((1 + d0) * (l + am - 1) * (l + am))) * (1 - 2 * d0)
        ws[m] = -sp.Rational(1, 2) * sp.sqrt(sp.Integer((l - am - 1) * (l - am))) if (m != 0 and am < l - 1) else sp.Integer(0)
    return invd, us, vs, ws


def row_terms(l, m, us, vs, ws):
    """The terms (factor, i, a) of row m: D^l(m, n) = invd(n) sum factor * P(i, a, n)."""
    am = abs(m)
    s2 = sp.sqrt(2)
    t = []
    if am < l:
        t.append((us[m], 0, m))
    v = vs[m]
    if m == 0:
        t += [(v, 1, 1), (v, -1, -1)]
    elif m == 1:
        t.append((v * s2, 1, 0))
    elif m == -1:
        t.append((v * s2, -1, 0))
    elif m > 0:
        t += [(v, 1, m - 1), (-v, -1, 1 - m)]
    else:
        t += [(v, 1, m + 1), (v, -1, -m - 1)]
    if m != 0 and am < l - 1:
        w = ws[m]
        if m > 0:
            t += [(w, 1, m + 1), (w, -1, -m - 1)]
        else:
            t += [(w, 1, m - 1), (-w, -1, 1 - m)]
    return [x for x in t if x[0] != 0]


def name_i(i):
    return {-1: "n", 0: "z", 1: "p"}[i]


def band_function(l):
    invd, us, vs, ws = factors(l)
    pw, w = 2 * l - 1, 2 * l + 1
    consts = {}  # exact value -> name

    def const(v):
        v = sp.nsimplify(v)
        if v == 1:
            return None
        key = sp.srepr(v)
        if key not in consts:
            consts[key] = ("k%d" % len(consts), v)
        return consts[key][0]

    def prev(a, n):
        return "p[%d]" % ((a + l - 1) * pw + (n + l - 1))

    body = []
    edges = {}  # (sign, i, a) -> name

    def edge(sign, i, a):
        key = (sign, i, a)
        if key not in edges:
            nm = "e%s%s%d" % ("p" if sign > 0 else "n", name_i(i), a + l - 1)
            hi, lo = prev(a, l - 1), prev(a, 1 - l)
            if sign > 0:  # n = +l: R(i,1) M(a,l-1) - R(i,-1) M(a,1-l)
                expr = "r%sp * %s - r%sn * %s" % (name_i(i), hi, name_i(i), lo)
            else:  # n = -l: R(i,1) M(a,1-l) + R(i,-1) M(a,l-1)
                expr = "r%sp * %s + r%sn * %s" % (name_i(i), lo, name_i(i), hi)
            edges[key] = (nm, expr)
        return edges[key][0]

    rows = []
    for m in range(-l, l + 1):
        terms = row_terms(l, m, us, vs, ws)
        lines = []
        gnames = []
        for k, (f, i, a) in enumerate(terms):
            c = const(f)
            g = "g%d" % k
            lines.append("const T %s = %s;" % (g, ("%s * r%sz" % (c, name_i(i))) if c else "r%sz" % name_i(i)))
            gnames.append((g, a))
        for n in range(-l, l + 1):
            out = "c[%d]" % ((m + l) * w + n + l)
            if -l < n < l:
                s = " + ".join("%s * %s" % (g, prev(a, n)) for g, a in gnames)
                ci = const(invd[n])
                expr = "(%s) * %s" % (s, ci) if ci else s
            else:
                sign = 1 if n == l else -1
                parts = []
                for (f, i, a) in terms:
                    c = const(f * invd[n])
                    e = edge(sign, i, a)
                    parts.append("%s * %s" % (c, e) if c else e)
                expr = " + ".join(parts)
            lines.append("%s = %s;" % (out, expr))
        rows.append((m, lines))

    out = []
    out.append("/// Band %d of D(R) (%dx%d, row-major) from band %d in p and band 1 in r1." % (l, w, w, l - 1))
    out.append("template <class T>")
    out.append("SPHBASIS_FORCEINLINE void rotation_band_%d(const T* SPHBASIS_RESTRICT r1, const T* SPHBASIS_RESTRICT p, T* SPHBASIS_RESTRICT c) noexcept {" % l)
    out.append("    const T rnn = r1[0], rnz = r1[1], rnp = r1[2];")
    out.append("    const T rzn = r1[3], rzz = r1[4], rzp = r1[5];")
    out.append("    const T rpn = r1[6], rpz = r1[7], rpp = r1[8];")
    out.append("    (void)rnn; (void)rnz; (void)rnp; (void)rzn; (void)rzz; (void)rzp; (void)rpn; (void)rpz; (void)rpp;")
    for key, (nm, v) in sorted(consts.items(), key=lambda kv: int(kv[1][0][1:])):
        out.append("    const T %s = %s;  // %s" % (nm, lit(v), closed(v)))
    for key in sorted(edges, key=lambda k: edges[k][0]):
        nm, expr = edges[key]
        out.append("    const T %s = %s;" % (nm, expr))
    for m, lines in rows:
        out.append("    {  // m = %d" % m)
        for ln in lines:
            out.append("        " + ln)
        out.append("    }")
    out.append("}")
    return "\n".join(out)


HEADER = r'''// GENERATED by tools/gen/gen_sh_rotation.py -- do not edit.
// Regenerate: /usr/bin/python3 tools/gen/gen_sh_rotation.py > include/sphbasis/ops/sh_rotation_fixed.hpp
//
// sphbasis: rotation of real spherical-harmonic expansions with a compile-time band count
// (1..8), built as straight-line code.
//
// Convention: that of ops/sh_rotation.hpp (the run-time sh::Rotation). R acts on the function,
// g(w) = f(R^T w); D(R) is block diagonal with y(R w) = D(R) y(w); 3x3 matrices are row-major
// for column vectors (v' = R v). DirectXMath's XMSHRotate takes row-vector matrices (v' = v M)
// and the Condon-Shortley phase: XMSHRotate(M) with M = R^T equals D(R) after
// to_condon_shortley on input and output. Improper orthogonal matrices (det = -1) give
// (-1)^l D(-R) per band, as the run-time code does.
//
// Method: band 1 is R permuted to (y, z, x); band l >= 2 from band l - 1 and band 1 by the
// Ivanic-Ruedenberg recurrence (J. Ivanic, K. Ruedenberg, J. Phys. Chem. 100 (1996) 6342,
// eqs. 5.1-5.6, Table 2; corrections in J. Phys. Chem. A 102 (1998) 9099), unrolled by the
// generator with exact constants and shared subexpressions (see its docstring). Accurate to a
// few ulp per band at these band counts (the recurrence loses accuracy only far above 8 bands).
//
// Cost (float, one thread): see bench/bench_sh_ops.cpp; the construction has no run-time
// checks (SPHBASIS_ASSERT checks orthonormality in debug builds); from_matrix() is the checked
// entry point.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>

#include "../config.hpp"
#include "../core/frame.hpp"
#include "sh_rotation.hpp"

namespace sphbasis::sh::detail {

// clang-format off
'''

FOOTER = r'''// clang-format on

/// Number of stored values of D for n bands: sum_l (2l+1)^2 = n (4 n^2 - 1) / 3.
constexpr std::size_t fixed_rotation_size(int n) noexcept {
    return static_cast<std::size_t>(n) * (4 * static_cast<std::size_t>(n) * static_cast<std::size_t>(n) - 1) / 3;
}

/// Bands 1..L-1 of D into d (block l at fixed_rotation_size(l)), from the row-major matrix r.
template <int L, class T>
SPHBASIS_FORCEINLINE void rotation_fixed_bands(const T* SPHBASIS_RESTRICT r, T* SPHBASIS_RESTRICT d) noexcept {
    d[0] = T(1);
    if constexpr (L >= 2) {
        // band 1: D1[i][j] = R[p(i)][p(j)], p = (y, z, x)
        T* b1 = d + 1;
        b1[0] = r[4], b1[1] = r[5], b1[2] = r[3];
        b1[3] = r[7], b1[4] = r[8], b1[5] = r[6];
        b1[6] = r[1], b1[7] = r[2], b1[8] = r[0];
    }
    if constexpr (L >= 3) rotation_band_2(d + 1, d + 1, d + fixed_rotation_size(2));
    if constexpr (L >= 4) rotation_band_3(d + 1, d + fixed_rotation_size(2), d + fixed_rotation_size(3));
    if constexpr (L >= 5) rotation_band_4(d + 1, d + fixed_rotation_size(3), d + fixed_rotation_size(4));
    if constexpr (L >= 6) rotation_band_5(d + 1, d + fixed_rotation_size(4), d + fixed_rotation_size(5));
    if constexpr (L >= 7) rotation_band_6(d + 1, d + fixed_rotation_size(5), d + fixed_rotation_size(6));
    if constexpr (L >= 8) rotation_band_7(d + 1, d + fixed_rotation_size(6), d + fixed_rotation_size(7));
}

/// out = D in (Transposed: D^T in) for the blocks of L bands in d; the input is copied first, so
/// in == out is allowed. C is any type with C + C and C * T.
template <int L, bool Transposed, class T, class C>
SPHBASIS_FORCEINLINE void rotation_fixed_apply(const T* SPHBASIS_RESTRICT d, const C* in, C* out) noexcept {
    C x[L * L];
    for (int k = 0; k < L * L; ++k) x[k] = in[k];
    out[0] = x[0] * d[0];
    for (int l = 1; l < L; ++l) {
        const int w = 2 * l + 1, k0 = l * l;
        const T* b = d + fixed_rotation_size(l);
        for (int i = 0; i < w; ++i) {
            C acc = x[k0] * (Transposed ? b[i] : b[i * w]);
            for (int j = 1; j < w; ++j) acc = acc + x[k0 + j] * (Transposed ? b[j * w + i] : b[i * w + j]);
            out[k0 + i] = acc;
        }
    }
}

}  // namespace sphbasis::sh::detail

namespace sphbasis::sh {

/// D(R) for a compile-time band count N (1..8), stored in a std::array: block l is
/// (2l+1)x(2l+1), row-major, entry (m, n) at offset(l) + (m+l)(2l+1) + n+l, the layout of the
/// run-time sh::Rotation<T>. Built by straight-line code (no allocation, no table, no check in
/// the unchecked constructor); the apply is the block-diagonal product, unrolled.
template <int N, class T>
class FixedRotation {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::FixedRotation: N is a band count in 1..8 (use sh::Rotation<T> above).");
    static_assert(std::is_floating_point_v<T>, "sphbasis::sh::FixedRotation: T is float or double.");

  public:
    using value_type = T;
    /// Number of stored values, N(4N^2 - 1)/3.
    static constexpr std::size_t size_v = detail::fixed_rotation_size(N);

    static constexpr int bands() noexcept { return N; }
    static constexpr std::size_t size() noexcept { return size_v; }
    /// Offset of block l in data().
    static constexpr std::size_t offset(int l) noexcept { return detail::fixed_rotation_size(l); }

    /// The identity.
    FixedRotation() noexcept : d_{} {
        for (int l = 0; l < N; ++l)
            for (int i = 0; i < 2 * l + 1; ++i) d_[offset(l) + static_cast<std::size_t>(i * (2 * l + 2))] = T(1);
    }

    /// D(R) of an orthogonal row-major matrix, unchecked (SPHBASIS_ASSERT in debug builds: max
    /// |R R^T - I| <= default tolerance). A non-orthogonal matrix gives a meaningless but finite
    /// result for finite input. For a checked construction use from_matrix().
    explicit FixedRotation(const Mat3<T>& r) noexcept {
        SPHBASIS_ASSERT(detail::fixed_rotation_orthonormal(r));
        detail::rotation_fixed_bands<N>(r.data(), d_.data());
    }

    /// D(R) of a matrix type (row-major std::array<T, 9> or std::array<S, 9>, glm::mat3 / dmat3,
    /// Eigen::Matrix3f / d), checked: throws std::invalid_argument unless it is orthonormal
    /// within `tolerance` (max |R R^T - I|) and finite.
    template <class M>
    static FixedRotation from_matrix(const M& r, T tolerance = sphbasis::detail::default_orthonormal_tolerance<T>()) {
        const char* fn = "sh::FixedRotation::from_matrix";
        const Mat3<T> m = detail::mat3_cast<T>(to_mat3(r, fn));
        sphbasis::detail::check_orthonormal(m, tolerance, fn);
        return FixedRotation(m);
    }
    /// D of the quaternion (w, x, y, z): normalised if not unit; zero or non-finite throws.
    static FixedRotation from_quaternion(T w, T x, T y, T z) {
        return FixedRotation(matrix_from_quaternion(w, x, y, z));
    }
    /// D of a quaternion type: glm::quat / dquat, Eigen::Quaternionf / d, sphbasis::Quat.
    template <class Q>
    static FixedRotation from_quaternion(const Q& q) {
        const auto p = to_quat(q);
        return from_quaternion(T(p.w), T(p.x), T(p.y), T(p.z));
    }

    const T* data() const noexcept { return d_.data(); }
    /// Block l, (2l+1)^2 values row-major.
    const T* block(int l) const noexcept { return d_.data() + offset(l); }
    /// Entry (m, n) of band l: d y_lm(Rw) / d y_ln(w).
    T operator()(int l, int m, int n) const noexcept {
        SPHBASIS_ASSERT(l >= 0 && l < N && m >= -l && m <= l && n >= -l && n <= l);
        return d_[offset(l) + static_cast<std::size_t>((m + l) * (2 * l + 1) + n + l)];
    }

    /// out = D in, N^2 coefficients each; C is any type with C + C and C * T (float, double,
    /// RGB: all channels in one pass). in == out is allowed. No checks (SPHBASIS_ASSERT on null).
    template <class C>
    SPHBASIS_FORCEINLINE void apply(const C* in, C* out) const noexcept {
        SPHBASIS_ASSERT(in && out);
        detail::rotation_fixed_apply<N, false>(d_.data(), in, out);
    }
    /// out = D^T in: the inverse rotation.
    template <class C>
    SPHBASIS_FORCEINLINE void apply_transposed(const C* in, C* out) const noexcept {
        SPHBASIS_ASSERT(in && out);
        detail::rotation_fixed_apply<N, true>(d_.data(), in, out);
    }
    /// apply() by value.
    template <class C>
    std::array<C, N * N> apply(const std::array<C, N * N>& in) const noexcept {
        std::array<C, N * N> out;
        apply(in.data(), out.data());
        return out;
    }

  private:
    std::array<T, size_v> d_;
};

/// out = D(R) in for N bands without keeping D (D is built on the stack by the straight-line
/// code of FixedRotation, then applied). R is a row-major Mat3<T>, unchecked (SPHBASIS_ASSERT
/// in debug builds); in == out is allowed. C is any type with C + C and C * T.
template <int N, class T, class C>
SPHBASIS_FORCEINLINE void rotate(const Mat3<T>& r, const C* in, C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::rotate<N>: N is a band count in 1..8.");
    SPHBASIS_ASSERT(detail::fixed_rotation_orthonormal(r));
    T d[detail::fixed_rotation_size(N)];
    detail::rotation_fixed_bands<N>(r.data(), d);
    detail::rotation_fixed_apply<N, false>(d, in, out);
}

}  // namespace sphbasis::sh
'''

ORTHO = r'''/// Debug-assert helper: R orthonormal within the default tolerance (never throws).
template <class T>
bool fixed_rotation_orthonormal(const Mat3<T>& r) noexcept {
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            T s = 0;
            for (int k = 0; k < 3; ++k) s += r[static_cast<std::size_t>(3 * i + k)] * r[static_cast<std::size_t>(3 * j + k)];
            if (!(std::fabs(s - (i == j ? T(1) : T(0))) <= sphbasis::detail::default_orthonormal_tolerance<T>())) return false;
        }
    return true;
}

'''


def main():
    parts = [HEADER, ORTHO]
    for l in range(2, MAX_BANDS):
        parts.append(band_function(l))
        parts.append("\n\n")
    parts.append(FOOTER)
    print("".join(parts), end="")


if __name__ == "__main__":
    main()
