#!/usr/bin/python3
"""Generates include/sphbasis/basis/sh_fixed.hpp: unrolled real SH kernels for 1..8 bands.

Exact arithmetic with sympy; every constant is printed with 17 significant digits.

The kernels evaluate the same normalised recurrence as the runtime code (basis/sh.hpp), unrolled
with folded constants:
  y_lm = Q_l^|m|(z) * C_m(x, y)  (m > 0),   Q_l^|m|(z) * S_|m|(x, y)  (m < 0),   Q_l^0(z)  (m = 0)
  C_m + i S_m = (x + i y)^m
  Q_m^m = sqrt(2) / sqrt(4 pi) * prod_{k=1..m} sqrt((2k+1)/(2k))     (no sqrt(2) for m = 0)
  Q_{m+1}^m = sqrt(2m+3) z Q_m^m
  Q_l^m = a_lm z Q_{l-1}^m - a_lm b_lm Q_{l-2}^m,
  a_lm = sqrt((4l^2-1)/(l^2-m^2)),  b_lm = sqrt(((l-1)^2-m^2)/(4(l-1)^2-1)).
No Condon-Shortley phase; ACN index l(l+1)+m.
eval_fixed_scaled_N(x, y, z, inv, store) gives the same values at a direction of any length r
with inv = 1/r (sh::eval<N>'s normalising kernel for N = 4..8): C_m, S_m from the raw x, y,
then times inv^m; only z is normalised before the z recurrence. The powers of (x + i y) do not
wait for the square root, which the one-call benchmark measured 1.1-1.5x faster at 4-8 bands.
eval_fixed_vec8_N (4..8 bands, float into an array, GCC/clang with AVX2 + FMA): the same
operations as eval_fixed_N lane by lane in 8-lane vectors, each output Q_l^|m|(z) times 1, C_m
or S_m (permuted from two vectors of the scalar C_m, S_m), the short columns as a z^2 + b (times
z) on constant vectors, the longer ones from eval_fixed_N's scalar recurrence; a scalar kernel
is bound by its ~N^2 multiplies and stores, the vector one does 8 at a time (shared harness,
-march=x86-64-v3: eval_unit<4..6> 1.4-1.7x DirectXMath's XMSHEvalDirection, was 1.1x).
In every kernel (eval_fixed_N, eval_fixed_scaled_N and the shader twins) Q_{m+2}^m and
Q_{m+3}^m are written out as polynomials in z^2 (an FMA, or an FMA and a product, after one
shared z^2, as Sloan's generated code does; the recurrence from Q_{m+4}^m): 2-9% at 4-8 bands.
The shader twins emit the same short columns as eval_fixed_N (shader_kernel below): with the
short columns in C++ only, the shaders' recurrence and the C++ polynomials differed by 7 ulps at
7 bands, beyond the shader test's 4-ulp bound; with the same form on both sides only the
driver's fused multiply-adds remain.

Usage: /usr/bin/python3 tools/gen/gen_sh_fixed.py > include/sphbasis/basis/sh_fixed.hpp
       /usr/bin/python3 tools/gen/gen_sh_fixed.py --glsl > shaders/sphbasis.glsl
       /usr/bin/python3 tools/gen/gen_sh_fixed.py --hlsl > shaders/sphbasis.hlsl
The shader twins (--glsl, --hlsl) carry the same kernels with the same operation order, each
constant the float nearest to the exact sympy value (9 significant digits identify it), plus the
Ramamoorthi-Hanrahan irradiance of sh::irradiance (ops/sh_convolution.hpp), the H-basis,
modified H-basis and HL2 kernels and expansion sums (basis/hbasis.hpp, basis/hl2.hpp: their
hand-written C++ literals are read and must round to the same floats as the exact values), the
clamped-cosine factors (core/clamped_cosine.hpp), the SH -> modified H-basis irradiance of
Ishmukhametov's Listings 2.1 and 2.2 (correctly rounded) and Toksvig's eqs. 6, 8 and 9
(shading/toksvig.hpp), and the direction <-> texture mappings of param/ (octahedral, cube map with
the D3D10/OpenGL face selection, concentric, paraboloid and the dual paraboloid texel layout),
and the HSH, Makhotkin and Zernike evaluation of 1..8 bands (tools/gen/hemi_shader.py: the
row-recurrence table of basis/detail/jacobi.hpp, built exactly and rounded to float), and the
engine bases: ambient cube, Ambient Dice, spherical Gaussians with BakingLab's lobe sets and Hill's
fitted irradiance, ZH3 (fitted and hallucinated), L1 SH with the Geomerics reconstruction
(tools/gen/engine_shader.py).
"""
import re
import struct
import sys

import sympy as sp

MAX_BANDS = 8


def lit(v):
    f = sp.N(v, 30)
    s = "%.17g" % float(f)
    if "e" not in s and "." not in s:
        s += ".0"
    return "S(%s)" % s


def closed(v):
    return str(sp.nsimplify(v))


def sectoral(m):
    v = sp.sqrt(1 / (4 * sp.pi))
    for k in range(1, m + 1):
        v *= sp.sqrt(sp.Rational(2 * k + 1, 2 * k))
    if m > 0:
        v *= sp.sqrt(2)
    return sp.simplify(v)


def a(l, m):
    return sp.sqrt(sp.Rational(4 * l * l - 1, l * l - m * m))


def b(l, m):
    return sp.sqrt(sp.Rational((l - 1) ** 2 - m * m, 4 * (l - 1) ** 2 - 1))


_Z = sp.Symbol("z")


def column_poly(l, m):
    """Q_l^m as an exact polynomial in z (the recurrence of the docstring)."""
    q = [sectoral(m), sp.sqrt(2 * m + 3) * sectoral(m) * _Z]
    for k in range(m + 2, l + 1):
        A = a(k, m)
        q.append(sp.expand(A * _Z * q[-1] - A * b(k, m) * q[-2]))
    return sp.Poly(q[l - m], _Z)


def short_column(l, m, z, z2):
    """Q_l^m for l = m + 2 and m + 3 as explicit polynomials in z^2 (one FMA, or an FMA and a
    multiplication, after the shared z^2, as Sloan's generated code does), else None."""
    if l - m == 2:
        p = column_poly(l, m)
        al, be = p.coeff_monomial(_Z ** 2), p.coeff_monomial(1)
        return "V(%s) * %s + V(%s);  // %s z^2 + %s" % (lit(al), z2, lit(be), closed(sp.simplify(al)), closed(sp.simplify(be)))
    if l - m == 3:
        p = column_poly(l, m)
        ga, de = p.coeff_monomial(_Z ** 3), p.coeff_monomial(_Z)
        return "%s * (V(%s) * %s + V(%s));  // z (%s z^2 + %s)" % (z, lit(ga), z2, lit(de), closed(sp.simplify(ga)), closed(sp.simplify(de)))
    return None


def kernel(n):
    out = []
    w = out.append
    w("/// %d band%s (%d function%s). Precondition: (x, y, z) unit (see sh::eval_unit)." % (n, "" if n == 1 else "s", n * n, "" if n == 1 else "s"))
    w("template <class V, class Store>")
    w("SPHBASIS_FORCEINLINE void eval_fixed_%d(const V& x, const V& y, const V& z, Store&& store) noexcept {" % n)
    w("    using S = scalar_t<V>;")
    w("    (void)x; (void)y; (void)z;")
    if n > 2:
        w("    const V z2 = z * z;")
    # (x+iy)^m
    if n > 1:
        w("    const V c1 = x, s1 = y;")
    for m in range(2, n):
        w("    const V c%d = x * c%d - y * s%d, s%d = x * s%d + y * c%d;" % (m, m - 1, m - 1, m, m - 1, m - 1))
    for m in range(0, n):
        # Q_m^m constant
        qmm = sectoral(m)
        names = {}
        for l in range(m, n):
            name = "q%d_%d" % (l, m)
            if l == m:
                w("    const V %s = V(%s);  // %s" % (name, lit(qmm), closed(qmm)))
            elif l == m + 1:
                c = sp.sqrt(2 * m + 3) * qmm
                w("    const V %s = V(%s) * z;  // %s z" % (name, lit(c), closed(sp.simplify(c))))
            elif short_column(l, m, "z", "z2"):
                w("    const V %s = %s" % (name, short_column(l, m, "z", "z2")))
            else:
                A = a(l, m)
                B = A * b(l, m)
                w("    const V %s = V(%s) * z * q%d_%d - V(%s) * q%d_%d;" % (name, lit(A), l - 1, m, lit(B), l - 2, m))
            k = l * (l + 1)
            if m == 0:
                w("    store(%d, %s);" % (k, name))
            else:
                w("    store(%d, %s * c%d);" % (k + m, name, m))
                w("    store(%d, %s * s%d);" % (k - m, name, m))
    w("}")
    return "\n".join(out)


def kernel_scaled(n):
    """n bands at a direction (x, y, z) of any length r, given inv = 1/r: the values of kernel(n)
    at (x, y, z) / r. Only z is normalised before the z recurrence; C_m + i S_m = (x + i y)^m
    are taken from the raw components and scaled by inv^m afterwards, so the complex powers run
    while the square root is computed and only the z column waits for it."""
    out = []
    w = out.append
    w("/// %d band%s at (x, y, z) of any length r, inv = 1/r (r^%d neither over- nor underflows): the" % (n, "" if n == 1 else "s", max(n - 1, 1)))
    w("/// values of eval_fixed_%d at (x, y, z) / r. C_m + i S_m = (x + i y)^m from the raw components," % n)
    w("/// scaled by inv^m; only z is normalised before its recurrence (the powers need no square root).")
    w("template <class V, class Store>")
    w("SPHBASIS_FORCEINLINE void eval_fixed_scaled_%d(const V& x, const V& y, const V& z, const V& inv, Store&& store) noexcept {" % n)
    w("    using S = scalar_t<V>;")
    w("    (void)x; (void)y; (void)z; (void)inv;")
    if n > 1:
        w("    const V zn = z * inv;")
        if n > 2:
            w("    const V zn2 = zn * zn;")
        w("    const V a1 = x, b1 = y;")
    # Even powers by squaring, (a + i b)^2 = (a - b)(a + b) + i (a + a) b: two products and three
    # additions (the additions go to the adder ports), odd ones times (x + i y).
    for m in range(2, n):
        if m % 2 == 0:
            h = m // 2
            w("    const V a%d = (a%d - b%d) * (a%d + b%d), b%d = (a%d + a%d) * b%d;" % (m, h, h, h, h, m, h, h, h))
        else:
            w("    const V a%d = x * a%d - y * b%d, b%d = x * b%d + y * a%d;" % (m, m - 1, m - 1, m, m - 1, m - 1))
    if n > 1:
        w("    const V p1 = inv;")
    for m in range(2, n):
        w("    const V p%d = p%d * p%d;" % (m, m // 2, m - m // 2))
    # The sectoral constant Q_m^m (m >= 1) rides on the scaling: k_m = Q_m^m inv^m, so y_{m,+-m}
    # = (a_m, b_m) k_m directly and the rest of column m uses Q_l^m / Q_m^m (the recurrence is
    # linear): one multiplication per order fewer than scaling (a_m, b_m) and then multiplying by
    # Q_m^m.
    for m in range(1, n):
        qmm = sectoral(m)
        w("    const V k%d = V(%s) * p%d;  // %s inv^%d" % (m, lit(qmm), m, closed(qmm), m))
        w("    const V c%d = a%d * k%d, s%d = b%d * k%d;" % (m, m, m, m, m, m))
    for m in range(0, n):
        qmm = sectoral(m)
        scale = 1 if m == 0 else 1 / qmm  # column m is written as Q_l^m / Q_m^m for m >= 1
        for l in range(m, n):
            name = "q%d_%d" % (l, m)
            k = l * (l + 1)
            if l == m:
                if m == 0:
                    w("    const V %s = V(%s);  // %s" % (name, lit(qmm), closed(qmm)))
                    w("    store(%d, %s);" % (k, name))
                else:
                    w("    store(%d, c%d);" % (k + m, m))
                    w("    store(%d, s%d);" % (k - m, m))
                continue
            if l == m + 1:
                c = sp.simplify(sp.sqrt(2 * m + 3) * qmm * scale)
                w("    const V %s = V(%s) * zn;  // %s z" % (name, lit(c), closed(c)))
            elif l - m in (2, 3):
                p = column_poly(l, m)
                if l - m == 2:
                    al = sp.simplify(p.coeff_monomial(_Z ** 2) * scale)
                    be = sp.simplify(p.coeff_monomial(1) * scale)
                    w("    const V %s = V(%s) * zn2 + V(%s);  // %s z^2 + %s" % (name, lit(al), lit(be), closed(al), closed(be)))
                else:
                    ga = sp.simplify(p.coeff_monomial(_Z ** 3) * scale)
                    de = sp.simplify(p.coeff_monomial(_Z) * scale)
                    w("    const V %s = zn * (V(%s) * zn2 + V(%s));  // z (%s z^2 + %s)" % (name, lit(ga), lit(de), closed(ga), closed(de)))
            else:
                A = a(l, m)
                B = A * b(l, m)
                w("    const V %s = V(%s) * zn * q%d_%d - V(%s) * q%d_%d;" % (name, lit(A), l - 1, m, lit(B), l - 2, m))
            if m == 0:
                w("    store(%d, %s);" % (k, name))
            else:
                w("    store(%d, %s * c%d);" % (k + m, name, m))
                w("    store(%d, %s * s%d);" % (k - m, name, m))
    w("}")
    return "\n".join(out)


VEC_BANDS = (4, 5, 6, 7, 8)


def kernel_vec8(n):
    """eval_fixed_vec8_n: eval_fixed_n for float into an array, 8 outputs per vector operation and
    store, with the operations of eval_fixed_n lane by lane (so the same values, bit for bit, where
    the compiler contracts alike): output k = l(l+1) +- m is Q_l^|m|(z) T, T = 1, c_m or s_m ((x +
    i y)^m by the scalar recurrence, then lane permutations of two vectors (1, c1, s1, c2, s2,
    ...)). The short columns l - |m| <= 3 are lane-wise, a z^2 + b (times z for odd l - |m|), as
    eval_fixed_n writes them; the longer ones come from eval_fixed_n's scalar recurrence, blended
    in from up to two vectors."""
    n2 = n * n
    starts = list(range(0, n2 - 7, 8))
    tail = n2 - (starts[-1] + 8)  # 1..3 last outputs: scalar, as eval_fixed_n; 4..7: one more vector
    if tail >= 4:
        starts.append(n2 - 8)
        tail = 0

    def tlane(m):  # lane of T in (w0, w1): 0 -> 1, 2m - 1 -> c_m, 2m -> s_m
        return 0 if m == 0 else (2 * m - 1 if m > 0 else -2 * m)

    longs = []  # (l, |m|) computed by the scalar recurrence, in order
    for l in range(n):
        for am in range(0, l - 3):
            longs.append((l, am))
    out = []
    w = out.append
    w("/// %d bands for float at a unit direction into out[0..%d), 8 values per vector operation (see" % (n, n2))
    w("/// kernel_vec8 in tools/gen/gen_sh_fixed.py): the operations of eval_fixed_%d lane by lane." % n)
    w("SPHBASIS_FORCEINLINE void eval_fixed_vec8_%d(float x, float y, float z, float* out) noexcept {" % n)
    w("    typedef float v8 __attribute__((vector_size(32)));")
    w("    using V = float;")
    w("    using S = float;")
    w("    const V z2 = z * z;")
    w("    const V c1 = x, s1 = y;")
    for m in range(2, n):
        w("    const V c%d = x * c%d - y * s%d, s%d = x * s%d + y * c%d;" % (m, m - 1, m - 1, m, m - 1, m - 1))
    # the scalar columns that reach l - m >= 4, as eval_fixed_n computes them
    for am in sorted({m for _, m in longs}):
        top = max(l for l, m in longs if m == am)
        for l in range(am + 2, top + 1):  # the recurrence from Q_{m+4}^m reads back to Q_{m+2}^m
            name = "q%d_%d" % (l, am)
            if l == am:
                w("    const V %s = V(%s);" % (name, lit(sectoral(am))))
            elif l == am + 1:
                w("    const V %s = V(%s) * z;" % (name, lit(sp.sqrt(2 * am + 3) * sectoral(am))))
            elif short_column(l, am, "z", "z2"):
                w("    const V %s = %s" % (name, short_column(l, am, "z", "z2")))
            else:
                A = a(l, am)
                w("    const V %s = V(%s) * z * q%d_%d - V(%s) * q%d_%d;" % (name, lit(A), l - 1, am, lit(A * b(l, am)), l - 2, am))
    tv = ["S(1)"] + sum([["c%d" % m, "s%d" % m] for m in range(1, n)], [])
    tv += ["S(0)"] * (16 - len(tv))
    w("    const v8 w0 = {%s};" % ", ".join(tv[:8]))
    w("    const v8 w1 = {%s};" % ", ".join(tv[8:16]))
    qv = ["q%d_%d" % lm for lm in longs]
    nq = (len(qv) + 7) // 8
    qv += ["S(0)"] * (8 * nq - len(qv))
    for j in range(nq):
        w("    const v8 wq%d = {%s};" % (j, ", ".join(qv[8 * j:8 * j + 8])))
    w("    const v8 one = {S(1), S(1), S(1), S(1), S(1), S(1), S(1), S(1)};")
    w("    const v8 zz = one * z2, zv = one * z;")
    for c, st in enumerate(starts):
        lanes = []
        for k in range(st, st + 8):
            l = 0
            while (l + 1) * (l + 1) <= k:
                l += 1
            m = k - l * (l + 1)
            am = abs(m)
            if l - am >= 4:
                lanes.append((l, m, None, None))
                continue
            p = column_poly(l, am)
            par = (l - am) % 2
            coeffs = [p.coeff_monomial(_Z ** (2 * j + par)) for j in range((l - am) // 2 + 1)]
            lanes.append((l, m, par, coeffs))
        deg = max(len(x[3]) for x in lanes if x[3] is not None)
        for j in range(deg):
            vals = [x[3][j] if x[3] is not None and j < len(x[3]) else sp.Integer(0) for x in lanes]
            w("    const v8 a%d_%d = {%s};  // %s" % (c, j, ", ".join(lit(v) for v in vals), ", ".join(closed(v) for v in vals)))
        h = "a%d_%d" % (c, deg - 1)
        for j in range(deg - 2, -1, -1):
            h = "%s * zz + a%d_%d" % (h, c, j)
        w("    v8 h%d = %s;" % (c, h))
        if any(x[2] == 1 for x in lanes):
            w("    h%d = h%d * __builtin_shufflevector(one, zv, %s);" % (c, c, ", ".join(str(8 + i if x[2] == 1 else i) for i, x in enumerate(lanes))))
        for j in range(nq):
            idx = []
            for i, x in enumerate(lanes):
                q = longs.index((x[0], abs(x[1]))) if x[2] is None else -1
                idx.append(str(8 + q - 8 * j) if 8 * j <= q < 8 * j + 8 else str(i))
            if any(int(v) >= 8 for v in idx):
                w("    h%d = __builtin_shufflevector(h%d, wq%d, %s);" % (c, c, j, ", ".join(idx)))
        tidx = [tlane(x[1]) for x in lanes]
        w("    const v8 o%d = h%d * __builtin_shufflevector(w0, w1, %s);" % (c, c, ", ".join(map(str, tidx))))
    for c, st in enumerate(starts):
        w("    std::memcpy(out + %d, &o%d, sizeof(v8));" % (st, c))
    for k in range(n2 - tail, n2):  # sectoral-near outputs of the last band (short columns)
        l = n - 1
        m = k - l * (l + 1)
        am = abs(m)
        assert am >= l - 2 and am > 0
        if l == am:
            q = "V(%s)" % lit(sectoral(am))
        elif l == am + 1:
            q = "(V(%s) * z)" % lit(sp.sqrt(2 * am + 3) * sectoral(am))
        else:
            q = "(%s)" % short_column(l, am, "z", "z2").split(";")[0]
        w("    out[%d] = %s * %s%d;" % (k, q, "c" if m > 0 else "s", am))
    w("}")
    return "\n".join(out)


def main():
    print("// GENERATED by tools/gen/gen_sh_fixed.py -- do not edit.")
    print("// Regenerate: /usr/bin/python3 tools/gen/gen_sh_fixed.py > include/sphbasis/basis/sh_fixed.hpp")
    print("//")
    print("// Unrolled real spherical harmonics for 1..%d bands (graphics convention: no Condon-Shortley" % MAX_BANDS)
    print("// phase, ACN index l(l+1)+m). Each kernel calls store(index, value) once per function, so the")
    print("// caller decides where values go (an array, a strided SoA batch, or a running sum Σ c_i y_i).")
    print("// The value type V is float, double or sphbasis::batch<T>. eval_fixed_scaled_N: the same values")
    print("// at a direction of any length r, given inv = 1/r (the normalising one-call kernels).")
    print("// eval_fixed_vec8_N (SPHBASIS_SH_VEC8_EVAL): eval_fixed_N for float into an array with the same")
    print("// operations lane by lane, 8 values per vector operation and store (sh::eval<N>, eval_unit<N>).")
    print("#pragma once")
    print()
    print("// clang-format off")
    print('#include <cstring>')
    print()
    print('#include "../config.hpp"')
    print('#include "../core/scalar.hpp"')
    print()
    print("// SPHBASIS_SH_VEC8_EVAL: eval_fixed_vec8_N (%s bands), the one-call float kernels with" % ", ".join(map(str, VEC_BANDS)))
    print("// 8-lane vector stores, for GCC/clang with AVX2 + FMA (AVX-512 included); 0: scalar code only.")
    print("#if !defined(SPHBASIS_SH_VEC8_EVAL)")
    print("#if (defined(__GNUC__) || defined(__clang__)) && defined(__AVX2__) && defined(__FMA__)")
    print("#define SPHBASIS_SH_VEC8_EVAL 1")
    print("#else")
    print("#define SPHBASIS_SH_VEC8_EVAL 0")
    print("#endif")
    print("#endif")
    print()
    print("namespace sphbasis::sh::detail {")
    print()
    print("inline constexpr int max_fixed_bands = %d;" % MAX_BANDS)
    print()
    for n in range(1, MAX_BANDS + 1):
        print(kernel(n))
        print()
    for n in range(1, MAX_BANDS + 1):
        print(kernel_scaled(n))
        print()
    print("#if SPHBASIS_SH_VEC8_EVAL")
    for n in VEC_BANDS:
        print(kernel_vec8(n))
        print()
    print("/// eval_fixed_vec8_N dispatched on a compile-time band count (N in %s)." % ", ".join(map(str, VEC_BANDS)))
    print("template <int N>")
    print("SPHBASIS_FORCEINLINE void eval_fixed_vec8(float x, float y, float z, float* out) noexcept {")
    for i, n in enumerate(VEC_BANDS):
        print("    %sif constexpr (N == %d) eval_fixed_vec8_%d(x, y, z, out);" % ("" if i == 0 else "else ", n, n))
    print("}")
    print("#endif")
    print()
    print("/// Dispatch on a compile-time band count.")
    print("template <int N, class V, class Store>")
    print("SPHBASIS_FORCEINLINE void eval_fixed(const V& x, const V& y, const V& z, Store&& store) noexcept {")
    print('    static_assert(N >= 1 && N <= max_fixed_bands, "sphbasis::sh: unrolled kernels exist for 1..%d bands.");' % MAX_BANDS)
    for n in range(1, MAX_BANDS + 1):
        print("    %sif constexpr (N == %d) eval_fixed_%d(x, y, z, store);" % ("" if n == 1 else "else ", n, n))
    print("}")
    print()
    print("/// eval_fixed_scaled_N dispatched on a compile-time band count.")
    print("template <int N, class V, class Store>")
    print("SPHBASIS_FORCEINLINE void eval_fixed_scaled(const V& x, const V& y, const V& z, const V& inv, Store&& store) noexcept {")
    print('    static_assert(N >= 1 && N <= max_fixed_bands, "sphbasis::sh: unrolled kernels exist for 1..%d bands.");' % MAX_BANDS)
    for n in range(1, MAX_BANDS + 1):
        print("    %sif constexpr (N == %d) eval_fixed_scaled_%d(x, y, z, inv, store);" % ("" if n == 1 else "else ", n, n))
    print("}")
    print()
    print("}  // namespace sphbasis::sh::detail")
    print("// clang-format on")


# ---------------------------------------------------------------------------------------------
# Shader twins (GLSL 4.50 / GLSL ES 3.10 and HLSL SM 5.0/6.0).


def _f32(d):
    """The float nearest to the double d (round to nearest even)."""
    return struct.unpack("<f", struct.pack("<f", d))[0]


def _f32_step(f, up):
    bits = struct.unpack("<I", struct.pack("<f", f))[0]
    if f == 0:
        bits = 1 if up else 0x80000001
    elif (f > 0) == up:
        bits += 1
    else:
        bits -= 1
    return struct.unpack("<f", struct.pack("<I", bits))[0]


def f32_nearest(v):
    """The float nearest to the exact value v, chosen by exact comparison among the float of the
    double and its two neighbours. Fails if the C++ kernels' float (the 17-digit double literal
    rounded to float) is a different float: then the two sides would not share one constant."""
    d = float(sp.N(v, 40))
    f = _f32(d)
    cands = [f, _f32_step(f, True), _f32_step(f, False)]
    best = min(cands, key=lambda c: abs(sp.N(sp.Rational(c) - v, 60)))
    cxx = _f32(float("%.17g" % d))
    if best != cxx:
        raise SystemExit("gen_sh_fixed.py: %s rounds to float %r but the C++ literal gives %r"
                         % (v, best, cxx))
    return best


def flit(v, lang):
    s = "%.9g" % f32_nearest(v)
    if "e" not in s and "." not in s:
        s += ".0"
    return s + ("f" if lang == "hlsl" else "")


def shader_kernel(n, lang):
    vec3 = "vec3" if lang == "glsl" else "float3"
    out = []
    w = out.append
    w("/// %d band%s (%d function%s) at the unit direction d: sh[l*(l+1)+m] = y_lm(d), as" % (
        n, "" if n == 1 else "s", n * n, "" if n == 1 else "s"))
    w("/// sphbasis::sh::eval_unit<%d>. Precondition: d unit (z up)." % n)
    w("void sphbasis_sh_eval%d(%s d, out float sh[%d])" % (n, vec3, n * n))
    w("{")
    w("    float x = d.x; float y = d.y; float z = d.z;")
    if n > 2:
        w("    float z2 = z * z;")
    if n > 1:
        w("    float c1 = x; float s1 = y;")
    for m in range(2, n):
        w("    float c%d = x * c%d - y * s%d; float s%d = x * s%d + y * c%d;" % (m, m - 1, m - 1, m, m - 1, m - 1))
    for m in range(0, n):
        qmm = sectoral(m)
        for l in range(m, n):
            name = "q%d_%d" % (l, m)
            if l == m:
                w("    float %s = %s;  // %s" % (name, flit(qmm, lang), closed(qmm)))
            elif l == m + 1:
                c = sp.sqrt(2 * m + 3) * qmm
                w("    float %s = %s * z;  // %s z" % (name, flit(c, lang), closed(sp.simplify(c))))
            elif l - m == 2:
                p = column_poly(l, m)
                al, be = p.coeff_monomial(_Z ** 2), p.coeff_monomial(1)
                w("    float %s = %s * z2 + %s;  // %s z^2 + %s" % (name, flit(al, lang), flit(be, lang), closed(sp.simplify(al)), closed(sp.simplify(be))))
            elif l - m == 3:
                p = column_poly(l, m)
                ga, de = p.coeff_monomial(_Z ** 3), p.coeff_monomial(_Z)
                w("    float %s = z * (%s * z2 + %s);  // z (%s z^2 + %s)" % (name, flit(ga, lang), flit(de, lang), closed(sp.simplify(ga)), closed(sp.simplify(de))))
            else:
                A = a(l, m)
                B = A * b(l, m)
                w("    float %s = %s * z * q%d_%d - %s * q%d_%d;" % (name, flit(A, lang), l - 1, m, flit(B, lang), l - 2, m))
            k = l * (l + 1)
            if m == 0:
                w("    sh[%d] = %s;" % (k, name))
            else:
                w("    sh[%d] = %s * c%d;" % (k + m, name, m))
                w("    sh[%d] = %s * s%d;" % (k - m, name, m))
    w("}")
    return "\n".join(out)


def shader_irradiance(lang):
    vec3 = "vec3" if lang == "glsl" else "float3"
    pi = sp.pi
    cs = [sp.sqrt(15 * pi) / 16, sp.sqrt(3 * pi) / 6, 3 * sp.sqrt(5 * pi) / 16, sp.sqrt(pi) / 2,
          sp.sqrt(5 * pi) / 16]
    two = "2.0f" if lang == "hlsl" else "2.0"
    out = []
    w = out.append
    w("/// Irradiance E(n) at the unit normal n from 9 RGB radiance coefficients L (3 bands, ACN),")
    w("/// Ramamoorthi and Hanrahan, \"An Efficient Representation for Irradiance Environment Maps\"")
    w("/// (SIGGRAPH 2001), eq. 13, as sphbasis::sh::irradiance. Divide by pi for the exit radiance")
    w("/// of a white Lambertian surface.")
    w("%s sphbasis_sh_irradiance(%s L[9], %s n)" % (vec3, vec3, vec3))
    w("{")
    for i, c in enumerate(cs):
        w("    const float c%d = %s;  // %s" % (i + 1, flit(c, lang), c))
    w("    float x = n.x; float y = n.y; float z = n.z;")
    w("    %s e = L[8] * (c1 * (x * x - y * y)) + L[6] * (c3 * z * z - c5) + L[0] * c4;" % vec3)
    w("    e = e + L[4] * (%s * c1 * x * y) + L[7] * (%s * c1 * x * z) + L[5] * (%s * c1 * y * z);" % (two, two, two))
    w("    e = e + L[3] * (%s * c2 * x) + L[1] * (%s * c2 * y) + L[2] * (%s * c2 * z);" % (two, two, two))
    w("    return e;")
    w("}")
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# H-basis, modified H-basis, HL2, clamped-cosine factors, Ishmukhametov's Listing 2.2 and Toksvig.

_ROOT = __import__("os").path.join(__import__("os").path.dirname(__file__), "..", "..")


def _cxx_literals(header):
    """The floating literals S(...) of a C++ kernel header of the library."""
    path = __import__("os").path.join(_ROOT, "include", "sphbasis", header)
    with open(path) as f:
        return [float(t) for t in re.findall(r"\b[ST]\(([-0-9.eE+]+)\)", f.read())]


def flit_cxx(v, lang, header):
    """flit(v), after checking that the hand-written C++ kernel in `header` carries a literal
    for the exact value v that rounds to the same float: the shader and the C++ kernel then
    multiply by one constant, and editing either side alone fails the generator."""
    f = f32_nearest(v)
    d = float(sp.N(v, 40))
    if not any(abs(c - d) <= 4e-16 * abs(d) and _f32(c) == f for c in _cxx_literals(header)):
        raise SystemExit("gen_sh_fixed.py: include/sphbasis/%s has no literal for %s = %.17g"
                         % (header, v, d))
    return flit(v, lang)


def _kw(lang):
    return ("vec3" if lang == "glsl" else "float3",
            "const float" if lang == "glsl" else "static const float",
            (lambda t: t) if lang == "glsl" else (lambda t: t + "f"))


def shader_hbasis(lang):
    vec3, _, _ = _kw(lang)
    pi = sp.pi
    hdr = "basis/hbasis.hpp"
    c1 = flit_cxx(sp.sqrt(3 / (2 * pi)), lang, hdr)
    k0 = flit_cxx(1 / sp.sqrt(2 * pi), lang, hdr)
    k2 = flit_cxx(2 * sp.sqrt(3 / (2 * pi)), lang, hdr)
    k4 = flit_cxx(sp.sqrt(15 / (2 * pi)), lang, hdr)
    k5 = flit_cxx(sp.sqrt(15 / (2 * pi)) / 2, lang, hdr)
    out = []
    w = out.append
    for mod in (False, True):
        for n in (4, 6):
            name = "sphbasis_hbasis%s%d_eval" % ("_mod" if mod else "", n)
            cxx = "HBasisMod" if mod else "HBasis"
            w("/// The %s (%d functions) at the unit direction d, as" % (
                "modified H-basis" if mod else "H-basis", n))
            w("/// sphbasis::basis_eval<%s>(%d, ...), in the order H1 (1), H2 (y), H3 (%s), H4 (x)%s" % (
                cxx, n, "1 - z" if mod else "2z - 1", "," if n == 6 else "."))
            if n == 6:
                w("/// H5 (xy), H6 (x^2 - y^2).")
            w("/// Below the horizon the polynomials are returned. Precondition: d unit (z up).")
            w("void %s(%s d, out float h[%d])" % (name, vec3, n))
            w("{")
            w("    float x = d.x; float y = d.y; float z = d.z;")
            w("    float c1 = %s;  // sqrt(3/(2 pi))" % c1)
            w("    h[0] = %s;  // 1/sqrt(2 pi)" % k0)
            w("    h[1] = c1 * y;")
            if mod:
                w("    h[2] = c1 - c1 * z;")
            else:
                w("    h[2] = %s * z - c1;  // 2 sqrt(3/(2 pi))" % k2)
            w("    h[3] = c1 * x;")
            if n == 6:
                w("    h[4] = %s * x * y;  // sqrt(15/(2 pi))" % k4)
                w("    h[5] = %s * (x * x - y * y);  // sqrt(15/(2 pi))/2" % k5)
            w("}")
            w("")
    hdr = "basis/hl2.hpp"
    w("/// The Half-Life 2 basis (3 functions) at the unit direction d, as")
    w("/// sphbasis::basis_eval<HL2>(3, ...). Below the horizon the linear polynomials are returned.")
    w("void sphbasis_hl2_eval(%s d, out float h[3])" % vec3)
    w("{")
    w("    float x = d.x; float y = d.y; float z = d.z;")
    w("    float a = %s * z;  // 1/sqrt(2 pi)" % flit_cxx(1 / sp.sqrt(2 * pi), lang, hdr))
    w("    float b = a - %s * x;  // 1/(2 sqrt(pi))" % flit_cxx(1 / (2 * sp.sqrt(pi)), lang, hdr))
    w("    float c = %s * y;  // sqrt(3/(4 pi))" % flit_cxx(sp.sqrt(3 / (4 * pi)), lang, hdr))
    w("    h[0] = b - c;")
    w("    h[1] = b + c;")
    w("    h[2] = a + %s * x;  // 1/sqrt(pi)" % flit_cxx(1 / sp.sqrt(pi), lang, hdr))
    w("}")
    w("")
    sums = [("hbasis4", "HBasis", 4), ("hbasis6", "HBasis", 6), ("hbasis_mod4", "HBasisMod", 4),
            ("hbasis_mod6", "HBasisMod", 6), ("hl2", "HL2", 3)]
    for stem, cxx, n in sums:
        w("/// The expansion sum_k c[k] B_k(d) of RGB coefficients at the unit direction d, as")
        w("/// sphbasis::basis_eval_sum<%s>(%d, c, d) per channel (same order of the sum)." % (cxx, n))
        w("%s sphbasis_%s_eval_sum(%s c[%d], %s d)" % (vec3, stem, vec3, n, vec3))
        w("{")
        w("    float h[%d];" % n)
        w("    sphbasis_%s_eval(d, h);" % (stem if stem == "hl2" else stem))
        w("    %s e = c[0] * h[0];" % vec3)
        for k in range(1, n):
            w("    e = e + c[%d] * h[%d];" % (k, k))
        w("    return e;")
        w("}")
        w("")
    return "\n".join(out).rstrip()


CLAMPED_COSINE_BANDS = 8


def clamped_cosine_exact(l):
    """a_l = Lambda_l / pi (core/clamped_cosine.hpp), exact."""
    if l == 0:
        return sp.Integer(1)
    if l == 1:
        return sp.Rational(2, 3)
    if l % 2:
        return sp.Integer(0)
    return sp.Rational(2 * (-1) ** (l // 2 - 1), (l + 2) * (l - 1)) * sp.binomial(l, l // 2) / sp.Integer(2) ** l


def shader_clamped_cosine(lang):
    _, const, _ = _kw(lang)
    out = []
    w = out.append
    w("/// The normalised clamped-cosine (Funk-Hecke) factors a_l = Lambda_l / pi of")
    w("/// sphbasis::clamped_cosine(l), l = 0..%d: the irradiance of radiance sum c_lm y_lm is" % (CLAMPED_COSINE_BANDS - 1))
    w("/// E = pi sum a_l c_lm y_lm (Ramamoorthi and Hanrahan, SIGGRAPH 2001, eq. 8).")
    for l in range(CLAMPED_COSINE_BANDS):
        v = clamped_cosine_exact(l)
        w("%s sphbasis_clamped_cosine_a%d = %s;  // %s" % (const, l, flit(v, lang), v))
    w("")
    w("/// a_l for 0 <= l <= %d (the bands of sphbasis_sh_eval1..%d); 0 outside that range." % (
        CLAMPED_COSINE_BANDS - 1, CLAMPED_COSINE_BANDS))
    w("float sphbasis_clamped_cosine(int l)")
    w("{")
    for l in range(CLAMPED_COSINE_BANDS):
        if clamped_cosine_exact(l) != 0:
            w("    if (l == %d) return sphbasis_clamped_cosine_a%d;" % (l, l))
    w("    return %s;" % flit(sp.Integer(0), lang))
    w("}")
    return "\n".join(out)


def modh_from_sh():
    """The least-squares SH (3 bands) -> modified H-basis matrix over the upper hemisphere
    (Ishmukhametov, Listing 2.1), exact: G^-1 <H_i, y_j> with the Gram matrix G of the modified
    H-basis. Rows: H1..H6; {sh index: exact entry}."""
    r2, r6, r10, r30 = sp.sqrt(2), sp.sqrt(6), sp.sqrt(10), sp.sqrt(30)
    return [{0: r2 / 2, 2: r6 / 2, 6: 3 * r10 / 8}, {1: r2 / 2, 5: 3 * r10 / 16},
            {2: -r2 / 2, 6: -r30 / 4}, {3: r2 / 2, 7: 3 * r10 / 16}, {4: r2 / 2}, {8: r2 / 2}]


def shader_listing22(lang):
    vec3, const, lit = _kw(lang)
    pi = sp.pi
    hdr = "basis/hbasis.hpp"
    band = [0, 1, 1, 1, 2, 2, 2, 2, 2]
    out = []
    w = out.append
    w("/// Radiance SH (3 bands, 9 RGB coefficients L, ACN) to the 6 modified H-basis coefficients h of")
    w("/// the exit radiance E/pi of a white Lambertian surface: the clamped-cosine convolution a_l")
    w("/// (2.3) followed by the least-squares projection over the upper hemisphere of Ishmukhametov,")
    w("/// \"Irradiance Normal Mapping\" (thesis), Listing 2.1, with a_l folded into each exact entry.")
    w("/// Listing 2.1 prints the matrix as 0.70711, 1.2247, 1.1859, 0.59293, -1.3693 (x a_l here);")
    w("/// its convolution line \"SHc[1, 2, 3] = 2.0/3.0 * SHc[2, 3, 4]\" is an index slip for")
    w("/// SHc[1, 2, 3] = 2/3 SHc[1, 2, 3].")
    w("void sphbasis_sh_to_hbasis_mod6(%s L[9], out %s h[6])" % (vec3, vec3))
    w("{")
    for i, row in enumerate(modh_from_sh()):
        terms = []
        notes = []
        for j, v in row.items():
            e = sp.nsimplify(v * clamped_cosine_exact(band[j]))
            terms.append("L[%d] * %s" % (j, flit(e, lang)))
            notes.append(str(e))
        w("    // %s" % ", ".join(notes))
        w("    h[%d] = %s;" % (i, " + ".join(terms)))
    w("}")
    w("")
    c0 = flit_cxx(1 / sp.sqrt(2 * pi), lang, hdr)
    c1 = flit_cxx(sp.sqrt(3 / (2 * pi)), lang, hdr)
    c4 = flit_cxx(sp.sqrt(15 / (2 * pi)), lang, hdr)
    c5 = flit_cxx(sp.sqrt(15 / (2 * pi)) / 2, lang, hdr)
    one = lit("1.0")
    w("/// The modified H-basis expansion of Ishmukhametov, Listing 2.2, at the unit tangent-space")
    w("/// normal n: E/pi = sum h_k H_k(n) for RGB coefficients h (already range-decoded: the")
    w("/// listing's 2 * 0.75 * t - 0.75 is the caller's texture decoding), in the listing's order.")
    w("/// Its constants are the normalisations 1/sqrt(2 pi), sqrt(3/(2 pi)), sqrt(15/(2 pi)),")
    w("/// sqrt(15/(2 pi))/2, each the correctly rounded float here. The listing prints 0.39894,")
    w("/// 0.69099 and 0.77255 correctly rounded to 5 digits but TRUNCATES sqrt(15/(2 pi)) =")
    w("/// 1.5450968... to 1.54509 (correctly rounded: 1.54510). Stopping after the first term gives")
    w("/// the light map, after four terms the listing's middle LOD (sphbasis_hbasis_mod4_irradiance).")
    w("%s sphbasis_hbasis_mod6_irradiance(%s h[6], %s n)" % (vec3, vec3, vec3))
    w("{")
    w("    return h[0] * %s  // 1/sqrt(2 pi)" % c0)
    w("        + h[1] * %s * n.y  // sqrt(3/(2 pi))" % c1)
    w("        + h[2] * %s * (%s - n.z)" % (c1, one))
    w("        + h[3] * %s * n.x" % c1)
    w("        + h[4] * %s * n.x * n.y  // sqrt(15/(2 pi)); Listing 2.2: 1.54509 (truncated)" % c4)
    w("        + h[5] * %s * (n.x * n.x - n.y * n.y);  // sqrt(15/(2 pi))/2" % c5)
    w("}")
    w("")
    w("/// The middle LOD of Listing 2.2: the first four terms of sphbasis_hbasis_mod6_irradiance.")
    w("%s sphbasis_hbasis_mod4_irradiance(%s h[4], %s n)" % (vec3, vec3, vec3))
    w("{")
    w("    return h[0] * %s" % c0)
    w("        + h[1] * %s * n.y" % c1)
    w("        + h[2] * %s * (%s - n.z)" % (c1, one))
    w("        + h[3] * %s * n.x;" % c1)
    w("}")
    w("")
    w("/// SH -> modified H-basis irradiance at the unit tangent-space normal n: the exit radiance E/pi")
    w("/// of a white Lambertian surface lit by the radiance L (9 RGB SH coefficients), through the")
    w("/// 6-coefficient modified H-basis (sphbasis_sh_to_hbasis_mod6, then Listing 2.2). Equals the SH")
    w("/// irradiance / pi only where the quadratic SH irradiance lies in the span of the basis.")
    w("%s sphbasis_sh_irradiance_hbasis_mod6(%s L[9], %s n)" % (vec3, vec3, vec3))
    w("{")
    w("    %s h[6];" % vec3)
    w("    sphbasis_sh_to_hbasis_mod6(L, h);")
    w("    return sphbasis_hbasis_mod6_irradiance(h, n);")
    w("}")
    return "\n".join(out)


def shader_toksvig(lang):
    _, const, lit = _kw(lang)
    one, zero = lit("1.0"), lit("0.0")
    out = []
    w = out.append
    w("/// Toksvig, \"Mipmapping Normal Maps\" (NVIDIA 2004), as sphbasis::toksvig (shading/toksvig.hpp),")
    w("/// with its clamps: lengths and cosines to [0, 1], a negative shininess to 0, +inf to FLT_MAX.")
    w("/// (NaN inputs: GLSL and HLSL do not promise IEEE NaN comparisons, so unlike the C++ side the")
    w("/// result for NaN is not specified.)")
    w("float sphbasis_toksvig_clamp01(float x)")
    w("{")
    w("    return x > %s ? %s : (x > %s ? x : %s);" % (one, one, zero, zero))
    w("}")
    w("")
    w("float sphbasis_toksvig_finite_shininess(float s)")
    w("{")
    w("    return s > %s ? min(s, %s) : %s;" % (zero, lit("3.40282347e+38"), zero))
    w("}")
    w("")
    w("/// eq. 6: the Toksvig factor f_t = L/(L + s(1 - L)), as sphbasis::toksvig::factor.")
    w("float sphbasis_toksvig_factor(float len, float shininess)")
    w("{")
    w("    float s = sphbasis_toksvig_finite_shininess(shininess);")
    w("    float l = sphbasis_toksvig_clamp01(len);")
    w("    float den = l + s * (%s - l);" % one)
    w("    return den > %s ? l / den : %s;" % (zero, one))
    w("}")
    w("")
    w("/// eq. 8: (1 + f_t s)/(1 + s) * (Na.H/L)^(f_t s), as sphbasis::toksvig::specular; pow(0, 0)")
    w("/// is taken as 1 (GLSL's and HLSL's pow leave x <= 0 undefined: handled here).")
    w("float sphbasis_toksvig_specular(float na_dot_h, float len, float shininess)")
    w("{")
    w("    float s = sphbasis_toksvig_finite_shininess(shininess);")
    w("    float l = sphbasis_toksvig_clamp01(len);")
    w("    float e = sphbasis_toksvig_factor(l, s) * s;")
    w("    float c = l > %s ? sphbasis_toksvig_clamp01(na_dot_h / l) : %s;" % (zero, zero))
    w("    float p = e > %s ? (c > %s ? pow(c, e) : %s) : %s;" % (zero, zero, zero, one))
    w("    return (%s + e) / (%s + s) * p;" % (one, one))
    w("}")
    w("")
    w("/// eq. 9: eq. 8 on the table axes Na.H and Na.Na (the square root taken here), as")
    w("/// sphbasis::toksvig::specular_from_dots.")
    w("float sphbasis_toksvig_specular_from_dots(float na_dot_h, float na_dot_na, float shininess)")
    w("{")
    w("    float l = sqrt(sphbasis_toksvig_clamp01(na_dot_na));")
    w("    return sphbasis_toksvig_specular(na_dot_h, l, shininess);")
    w("}")
    return "\n".join(out)


# ---------------------------------------------------------------------------------------------
# Direction <-> texture mappings of param/ (octahedral, cube map, concentric, dual paraboloid).


def shader_param(lang):
    g = lang == "glsl"
    vec2, vec3 = ("vec2", "vec3") if g else ("float2", "float3")
    lit = (lambda t: t) if g else (lambda t: t + "f")
    one, zero, two, half = lit("1.0"), lit("0.0"), lit("2.0"), lit("0.5")
    qp = flit_cxx(sp.pi / 4, lang, "param/concentric.hpp")
    fop = flit_cxx(4 / sp.pi, lang, "param/concentric.hpp")
    out = []
    w = out.append
    w("/// sgn with sgn(0) = +1 (also for -0), as the C++ mappings' (t >= 0 ? 1 : -1); GLSL's and HLSL's")
    w("/// sign() give 0 at 0.")
    w("float sphbasis_sign_not_zero(float t)")
    w("{")
    w("    return t >= %s ? %s : -%s;" % (zero, one, one))
    w("}")
    w("")
    w("/// Octahedral map (Cigolle et al., JCGT 2014), as sphbasis::param::octahedral_to_square: unit")
    w("/// direction (or any non-zero vector) -> [0, 1]^2; the upper half is the inner diamond, the")
    w("/// lower half folds out to the corners.")
    w("%s sphbasis_octahedral_to_square(%s d)" % (vec2, vec3))
    w("{")
    w("    float l1 = abs(d.x) + abs(d.y) + abs(d.z);")
    w("    float inv = l1 > %s ? %s / l1 : %s;" % (zero, one, zero))
    w("    float a = d.x * inv; float b = d.y * inv;")
    w("    if (d.z < %s) {" % zero)
    w("        float fa = (%s - abs(b)) * sphbasis_sign_not_zero(a);" % one)
    w("        float fb = (%s - abs(a)) * sphbasis_sign_not_zero(b);" % one)
    w("        a = fa; b = fb;")
    w("    }")
    w("    return %s(%s * (a + %s), %s * (b + %s));" % (vec2, half, one, half, one))
    w("}")
    w("")
    w("/// [0, 1]^2 -> unit direction, as sphbasis::param::square_to_octahedral.")
    w("%s sphbasis_square_to_octahedral(%s uv)" % (vec3, vec2))
    w("{")
    w("    float a = %s * uv.x - %s; float b = %s * uv.y - %s;" % (two, one, two, one))
    w("    float z = %s - abs(a) - abs(b);" % one)
    w("    if (z < %s) {" % zero)
    w("        float fa = (%s - abs(b)) * sphbasis_sign_not_zero(a);" % one)
    w("        float fb = (%s - abs(a)) * sphbasis_sign_not_zero(b);" % one)
    w("        a = fa; b = fb;")
    w("    }")
    w("    float inv = %s / sqrt(a * a + b * b + z * z);" % one)
    w("    return %s(a * inv, b * inv, z * inv);" % vec3)
    w("}")
    w("")
    w("/// Cube map face selection (OpenGL 4.6, section 8.13, table 8.19; the D3D10 rule), as")
    w("/// sphbasis::param::cube_to_square: unit direction -> face (0..5 = +X, -X, +Y, -Y, +Z, -Z) and")
    w("/// (u, v) in [0, 1]^2. Ties between axes go to x, then y. The zero vector gives +X, (0.5, 0.5).")
    w("%s sphbasis_cube_to_square(%s d, out int face)" % (vec2, vec3))
    w("{")
    w("    float ax = abs(d.x); float ay = abs(d.y); float az = abs(d.z);")
    w("    float ma; float sc; float tc;")
    w("    if (ax >= ay && ax >= az) {")
    w("        face = d.x >= %s ? 0 : 1; ma = ax; sc = d.x >= %s ? -d.z : d.z; tc = -d.y;" % (zero, zero))
    w("    } else if (ay >= az) {")
    w("        face = d.y >= %s ? 2 : 3; ma = ay; sc = d.x; tc = d.y >= %s ? d.z : -d.z;" % (zero, zero))
    w("    } else {")
    w("        face = d.z >= %s ? 4 : 5; ma = az; sc = d.z >= %s ? d.x : -d.x; tc = -d.y;" % (zero, zero))
    w("    }")
    w("    float inv = ma > %s ? %s / ma : %s;" % (zero, one, zero))
    w("    sc = clamp(sc * inv, -%s, %s); tc = clamp(tc * inv, -%s, %s);" % (one, one, one, one))
    w("    return %s(%s * (sc + %s), %s * (tc + %s));" % (vec2, half, one, half, one))
    w("}")
    w("")
    w("/// Cube face (0..5) and (u, v) in [0, 1]^2 -> unit direction, as sphbasis::param::square_to_cube.")
    w("%s sphbasis_square_to_cube(int face, %s uv)" % (vec3, vec2))
    w("{")
    w("    float sc = %s * uv.x - %s; float tc = %s * uv.y - %s;" % (two, one, two, one))
    w("    %s p;" % vec3)
    w("    if (face == 0) p = %s(%s, -tc, -sc);" % (vec3, one))
    w("    else if (face == 1) p = %s(-%s, -tc, sc);" % (vec3, one))
    w("    else if (face == 2) p = %s(sc, %s, tc);" % (vec3, one))
    w("    else if (face == 3) p = %s(sc, -%s, -tc);" % (vec3, one))
    w("    else if (face == 4) p = %s(sc, -tc, %s);" % (vec3, one))
    w("    else p = %s(-sc, -tc, -%s);" % (vec3, one))
    w("    float inv = %s / sqrt(p.x * p.x + p.y * p.y + p.z * p.z);" % one)
    w("    return %s(p.x * inv, p.y * inv, p.z * inv);" % vec3)
    w("}")
    w("")
    w("/// Shirley and Chiu's concentric map (JGT 1997, Mitsuba's single-branch form), as")
    w("/// sphbasis::param::square_to_uniform_disk_concentric: [0, 1]^2 -> unit disk.")
    w("%s sphbasis_square_to_uniform_disk_concentric(%s uv)" % (vec2, vec2))
    w("{")
    w("    float a = %s * uv.x - %s; float b = %s * uv.y - %s;" % (two, one, two, one))
    w("    if (a == %s && b == %s) return %s(%s, %s);" % (zero, zero, vec2, zero, zero))
    w("    if (abs(a) > abs(b)) {")
    w("        float phi = %s * (b / a);  // pi/4" % qp)
    w("        return %s(a * cos(phi), a * sin(phi));" % vec2)
    w("    }")
    w("    float psi = %s * (a / b);" % qp)
    w("    return %s(b * sin(psi), b * cos(psi));" % vec2)
    w("}")
    w("")
    w("/// Inverse concentric map, unit disk -> [0, 1]^2, as")
    w("/// sphbasis::param::uniform_disk_to_square_concentric (points outside the disk are clamped onto")
    w("/// the square's border).")
    w("%s sphbasis_uniform_disk_to_square_concentric(%s p)" % (vec2, vec2))
    w("{")
    w("    float r = sqrt(p.x * p.x + p.y * p.y);")
    w("    if (!(r > %s)) return %s(%s, %s);" % (zero, vec2, half, half))
    w("    float a; float b;")
    w("    if (abs(p.x) >= abs(p.y)) {")
    w("        a = p.x < %s ? -r : r;" % zero)
    w("        b = a * %s * atan(p.y / p.x);  // 4/pi" % fop)
    w("    } else {")
    w("        b = p.y < %s ? -r : r;" % zero)
    w("        a = b * %s * atan(p.x / p.y);" % fop)
    w("    }")
    w("    a = clamp(a, -%s, %s); b = clamp(b, -%s, %s);" % (one, one, one, one))
    w("    return %s(%s * (a + %s), %s * (b + %s));" % (vec2, half, one, half, one))
    w("}")
    w("")
    w("/// Paraboloid map (Heidrich and Seidel 1998) through the concentric map, as")
    w("/// sphbasis::param::square_to_paraboloid: [0, 1]^2 -> upper hemisphere (border = equator).")
    w("%s sphbasis_square_to_paraboloid(%s uv)" % (vec3, vec2))
    w("{")
    w("    %s p = sphbasis_square_to_uniform_disk_concentric(uv);" % vec2)
    w("    float r2 = p.x * p.x + p.y * p.y;")
    w("    float inv = %s / (%s + r2);" % (one, one))
    w("    return %s(%s * p.x * inv, %s * p.y * inv, (%s - r2) * inv);" % (vec3, two, two, one))
    w("}")
    w("")
    w("/// Unit direction -> [0, 1]^2, as sphbasis::param::paraboloid_to_square (|z| is used: a lower")
    w("/// direction is mirrored through the equator plane, as the back face stores it).")
    w("%s sphbasis_paraboloid_to_square(%s d)" % (vec2, vec3))
    w("{")
    w("    float inv = %s / (%s + abs(d.z));" % (one, one))
    w("    return sphbasis_uniform_disk_to_square_concentric(%s(d.x * inv, d.y * inv));" % vec2)
    w("}")
    w("")
    w("/// The texture coordinate of s in [0, 1] shrunk so that 0 and 1 fall on the outer texel centres")
    w("/// of an n-texel axis (Iwanicki and Sloan, JGT 2009, appendix A), as param::detail::shrink.")
    w("float sphbasis_shrink(float s, int n)")
    w("{")
    w("    float h = %s / float(n);" % half)
    w("    return h + (%s - %s * h) * s;" % (one, two))
    w("}")
    w("")
    w("/// Inverse of sphbasis_shrink, clamped to [0, 1], as param::detail::unshrink.")
    w("float sphbasis_unshrink(float u, int n)")
    w("{")
    w("    float h = %s / float(n);" % half)
    w("    float s = (u - h) / (%s - %s * h);" % (one, two))
    w("    return s > %s ? (s < %s ? s : %s) : %s;" % (zero, one, one, zero))
    w("}")
    w("")
    w("/// The dual paraboloid map of n x n texels per face, as")
    w("/// sphbasis::param::DualParaboloid<float>(n).direction_to_uv for a unit direction: face 0 for")
    w("/// z >= 0, 1 below; (u, v) in [0.5/n, 1 - 0.5/n]^2 (the equator on the outer texel centres).")
    w("%s sphbasis_dual_paraboloid_direction_to_uv(%s d, int n, out int face)" % (vec2, vec3))
    w("{")
    w("    face = d.z >= %s ? 0 : 1;" % zero)
    w("    %s s = sphbasis_paraboloid_to_square(d);" % vec2)
    w("    return %s(sphbasis_shrink(s.x, n), sphbasis_shrink(s.y, n));" % vec2)
    w("}")
    w("")
    w("/// Face and (u, v) of an n x n dual paraboloid map -> unit direction, as")
    w("/// sphbasis::param::DualParaboloid<float>(n).uv_to_direction.")
    w("%s sphbasis_dual_paraboloid_uv_to_direction(int face, %s uv, int n)" % (vec3, vec2))
    w("{")
    w("    %s d = sphbasis_square_to_paraboloid(%s(sphbasis_unshrink(uv.x, n), sphbasis_unshrink(uv.y, n)));" % (vec3, vec2))
    w("    if (face == 1) d.z = -d.z;")
    w("    return d;")
    w("}")
    return "\n".join(out)


def main_shader(lang):
    sys.path.insert(0, __import__("os").path.dirname(__file__))
    import hemi_shader  # HSH, Makhotkin, Zernike: tools/gen/hemi_shader.py
    import engine_shader  # ambient cube, Ambient Dice, SG, ZH3, L1 Geomerics: engine_shader.py

    guard = "SPHBASIS_GLSL" if lang == "glsl" else "SPHBASIS_HLSL"
    ext = lang
    print("// GENERATED by tools/gen/gen_sh_fixed.py -- do not edit.")
    print("// Regenerate: /usr/bin/python3 tools/gen/gen_sh_fixed.py --%s > shaders/sphbasis.%s" % (lang, ext))
    print("//")
    if lang == "glsl":
        print("// sphbasis shader twins, GLSL 4.50 (also GLSL ES 3.10). No #version line: include or paste it")
        print("// after your own (#extension GL_GOOGLE_include_directive, or your engine's includer).")
    else:
        print("// sphbasis shader twins, HLSL (Shader Model 5.0 and 6.0): #include \"sphbasis.hlsl\".")
    print("// Each function mirrors a C++ kernel of the sphbasis headers, with the same operation order and")
    print("// each constant the float nearest to the exact value the C++ constant rounds (same generator,")
    print("// same sympy expressions). Real SH without the Condon-Shortley phase, ACN index l(l+1)+m,")
    print("// directions z up.")
    print("#ifndef %s" % guard)
    print("#define %s" % guard)
    print()
    for n in range(1, MAX_BANDS + 1):
        print(shader_kernel(n, lang))
        print()
    print(shader_irradiance(lang))
    print()
    print(shader_clamped_cosine(lang))
    print()
    print(shader_hbasis(lang))
    print()
    print(shader_listing22(lang))
    print()
    print(shader_toksvig(lang))
    print()
    print(shader_param(lang))
    print()
    print(hemi_shader.shader_hemi_all(lang))
    print()
    print(engine_shader.shader_engine_all(lang))
    print()
    print("#endif  // %s" % guard)


if __name__ == "__main__":
    if len(sys.argv) > 1 and sys.argv[1] in ("--glsl", "--hlsl"):
        main_shader(sys.argv[1][2:])
    elif len(sys.argv) > 1:
        raise SystemExit("usage: gen_sh_fixed.py [--glsl | --hlsl]")
    else:
        main()
