#!/usr/bin/python3
"""Generates include/sphbasis/ops/sh_rotation_fixed.hpp: SH rotation matrices for 1..8 bands as
straight-line code (FixedRotation), and the direct rotation of a coefficient vector by a matrix
without forming D (sh::rotate<N>).

sh::rotate<N>: band 1 is R, band 2 the quadratic form R Q R^T, bands l >= 3 the Euler
factorisation D^l(R) = Z(alpha) D^l(X) Z(beta) D^l(X)^T Z(gamma), X the quarter turn about x
taking z to y. D^l(X) is computed here exactly (sympy, the recurrence below applied to X's
integer entries) and written out with zeros skipped; self_check() verifies the factorisation
against the recurrence for a sample rotation before anything is written. Two forms: scalar
straight-line code for any coefficient type (rotate_zyz_band_l) and, for C = T, 16-lane GNU
vectors (rotate_zyz_vec_N: the pairs (m, -m) in the same lane of two vectors so that a z rotation
is lane-wise; X maps each of the two vectors to itself, a sum of at most K lane permutations
times constant vectors).

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

    def prev(a, n):  # blocks are stored column-major
        return "p[%d]" % ((n + l - 1) * pw + (a + l - 1))

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
            out = "c[%d]" % ((n + l) * w + m + l)
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
    out.append("/// Band %d of D(R) (%dx%d, column-major) from band %d in p and band 1 in r1." % (l, w, w, l - 1))
    out.append("template <class T>")
    out.append("SPHBASIS_FORCEINLINE void rotation_band_%d(const T* SPHBASIS_RESTRICT r1, const T* SPHBASIS_RESTRICT p, T* SPHBASIS_RESTRICT c) noexcept {" % l)
    out.append("    const T rnn = r1[0], rnz = r1[3], rnp = r1[6];")
    out.append("    const T rzn = r1[1], rzz = r1[4], rzp = r1[7];")
    out.append("    const T rpn = r1[2], rpz = r1[5], rpp = r1[8];")
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



# ------------------------------------------------------------------------------------------
# Direct rotation of coefficients (sh::rotate<N>): band 1 is R, band 2 the tensor R Q R^T,
# bands >= 3 the factorisation R = Rz(a) X Rz(b) X^T Rz(c), X the quarter turn about x that
# takes z to y (X Rz(b) X^T = Ry(b)).

XMAT = [[1, 0, 0], [0, 0, 1], [0, -1, 0]]  # Rx(-pi/2): x -> x, y -> -z, z -> y


def dmat(lmax, r):
    """D^0..D^lmax of the 3x3 matrix r (row-major nested lists, exact sympy or float entries) by
    the recurrence above (band 1 = r permuted to (y, z, x))."""
    p = [1, 2, 0]
    b1 = [[r[p[i]][p[j]] for j in range(3)] for i in range(3)]

    def R(i, j):
        return b1[i + 1][j + 1]
    ds = [[[sp.Integer(1)]], b1]
    for l in range(2, lmax + 1):
        invd, us, vs, ws = factors(l)
        prevm = ds[l - 1]

        def M(a, n):
            return prevm[a + l - 1][n + l - 1]

        def P(i, a, n):
            if -l < n < l:
                return R(i, 0) * M(a, n)
            if n == l:
                return R(i, 1) * M(a, l - 1) - R(i, -1) * M(a, 1 - l)
            return R(i, 1) * M(a, 1 - l) + R(i, -1) * M(a, l - 1)
        d = [[None] * (2 * l + 1) for _ in range(2 * l + 1)]
        for m in range(-l, l + 1):
            terms = row_terms(l, m, us, vs, ws)
            for n in range(-l, l + 1):
                d[m + l][n + l] = sp.expand(invd[n] * sum(f * P(i, a, n) for (f, i, a) in terms))
        ds.append(d)
    return ds


def zmat(l, t):
    """D^l(Rz(t)): c'_m = c_m cos(mt) - c_-m sin(mt), c'_-m = c_-m cos(mt) + c_m sin(mt)."""
    w = 2 * l + 1
    z = [[0.0] * w for _ in range(w)]
    z[l][l] = 1.0
    import math
    for m in range(1, l + 1):
        c, s = math.cos(m * t), math.sin(m * t)
        z[l + m][l + m] = c
        z[l + m][l - m] = -s
        z[l - m][l - m] = c
        z[l - m][l + m] = s
    return z


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(len(b))) for j in range(len(b[0]))] for i in range(len(a))]


def transpose(a):
    return [list(x) for x in zip(*a)]


def self_check(dx):
    """The factorisation reproduces the recurrence's D for a sample rotation (float)."""
    import math
    al, be, ga = 0.7, 1.1, -2.3

    def rz(t):
        return [[math.cos(t), -math.sin(t), 0], [math.sin(t), math.cos(t), 0], [0, 0, 1]]
    xm = [[float(v) for v in row] for row in XMAT]
    ry = [[math.cos(be), 0, math.sin(be)], [0, 1, 0], [-math.sin(be), 0, math.cos(be)]]
    assert max(abs(a - b) for ra, rb in zip(matmul(matmul(xm, rz(be)), transpose(xm)), ry) for a, b in zip(ra, rb)) < 1e-15
    r = matmul(matmul(rz(al), ry), rz(ga))
    ref = dmat(MAX_BANDS - 1, [[sp.Float(v, 30) for v in row] for row in r])
    for l in range(3, MAX_BANDS):
        x = [[float(v) for v in row] for row in dx[l]]
        f = matmul(zmat(l, al), matmul(x, matmul(zmat(l, be), matmul(transpose(x), zmat(l, ga)))))
        err = max(abs(float(a) - b) for ra, rb in zip(ref[l], f) for a, b in zip(ra, rb))
        assert err < 1e-12, (l, err)


def zyz_band_function(l, dx):
    """Straight-line out = Z(a) X Z(b) X^T Z(c) in for band l (2l + 1 values each)."""
    w = 2 * l + 1
    x = dx[l]
    consts = {}

    def const(v):
        key = sp.srepr(v)
        if key not in consts:
            consts[key] = ("x%d" % len(consts), v)
        return consts[key][0]

    body = []
    body.append("    const C %s;" % ", ".join("i%d = in[%d]" % (j, j) for j in range(w)))

    def zrot(src, dst, ang):
        # dst = Z(ang) src; cos/sin of m*ang in c<ang>[m - 1], s<ang>[m - 1]
        lines = ["    const C %s%d = %s%d;" % (dst, l, src, l)]
        for m in range(1, l + 1):
            cm, sm = "c%s[%d]" % (ang, m - 1), "s%s[%d]" % (ang, m - 1)
            lines.append("    const C %s%d = %s%d * %s + %s%d * (-%s);" % (dst, l + m, src, l + m, cm, src, l - m, sm))
            lines.append("    const C %s%d = %s%d * %s + %s%d * %s;" % (dst, l - m, src, l - m, cm, src, l + m, sm))
        return lines

    def xmul(src, dst, mat):
        lines = []
        for i in range(w):
            parts = []
            for j in range(w):
                v = mat[i][j]
                if v == 0:
                    continue
                if v == 1:
                    parts.append("%s%d" % (src, j))
                else:
                    parts.append("%s%d * %s" % (src, j, const(v)))
            assert parts
            lines.append("    const C %s%d = %s;" % (dst, i, " + ".join(parts)))
        return lines

    body += zrot("i", "a", "g")
    body += xmul("a", "b", transpose(x))
    body += zrot("b", "e", "b")
    body += xmul("e", "f", x)
    zl = zrot("f", "h", "a")
    body += zl
    body.append("    " + " ".join("out[%d] = h%d;" % (j, j) for j in range(w)))
    out = []
    out.append("/// Band %d of out = Z(alpha) X Z(beta) X^T Z(gamma) in; c<a>[m-1], s<a>[m-1] = cos, sin of m a." % l)
    out.append("template <class T, class C>")
    out.append("SPHBASIS_FORCEINLINE void rotate_zyz_band_%d(const T* ca, const T* sa, const T* cb, const T* sb, const T* cg, const T* sg, const C* in, C* out) noexcept {" % l)
    for key, (nm, v) in sorted(consts.items(), key=lambda kv: int(kv[1][0][1:])):
        out.append("    const T %s = %s;  // %s" % (nm, lit(v), closed(v)))
    out += body
    out.append("}")
    return "\n".join(out)



# ------------------------------------------------------------------------------------------
# The same factorisation in 16-lane vectors (GNU vector extensions, float or double): per band
# l the coefficients sit in two vectors U, V of l + 1 lanes each, lane k = 0..l holding the pair
# of |m| = k: U = c_{+k} (k odd) or c_{-k} (k even, k > 0; lane 0 is padding), V = the partner
# (V lane 0 = c_0). A z rotation is then lane-wise (U' = U cos + V su, V' = V cos + U sv), and
# the quarter turn X maps U to U and V to V (odd-m cosines and even-m sines to themselves,
# the rest with m = 0 to themselves), each output lane a sum of at most K products with
# constants: K lane permutations per vector. Bands are packed into 16-lane groups.

LANES = 16


def vec_groups(N, lanes=LANES):
    groups, cur, used = [], [], 0
    for l in range(3, N):
        if used + l + 1 > lanes:
            groups.append(cur)
            cur, used = [], 0
        cur.append(l)
        used += l + 1
    if cur:
        groups.append(cur)
    return groups


def lane_m(k, which):
    """m of lane k of U (which = 0) or V (which = 1); None for the padding lane."""
    if k == 0:
        return None if which == 0 else 0
    pos = (k % 2 == 1) == (which == 0)
    return k if pos else -k


def shuffle_code(out_name, sources, srcvecs, temps, vt, lanes=LANES):
    """Emit `const V out_name = ...` selecting lane i from srcvecs[sources[i][0]] lane
    sources[i][1] (None: don't care), with 2-operand __builtin_shufflevector steps."""
    used = sorted({s[0] for s in sources if s is not None})
    lines = []

    def build(name, vecs):
        if len(vecs) <= 2:
            a = vecs[0]
            b = vecs[1] if len(vecs) == 2 else vecs[0]
            idx = []
            for s in sources:
                if s is None or s[0] not in vecs:
                    idx.append(0)
                else:
                    idx.append(s[1] + (lanes if (len(vecs) == 2 and s[0] == b) else 0))
            lines.append("    const %s %s = __builtin_shufflevector(%s, %s, %s);" % (vt, name, srcvecs[a], srcvecs[b], ", ".join(map(str, idx))))
            return
        h = len(vecs) // 2
        n1, n2 = name + "_a", name + "_b"
        build(n1, vecs[:h])
        build(n2, vecs[h:])
        idx = []
        for i, s in enumerate(sources):
            if s is None:
                idx.append(0)
            else:
                idx.append(i + (lanes if s[0] in vecs[h:] else 0))
        lines.append("    const %s %s = __builtin_shufflevector(%s, %s, %s);" % (vt, name, n1, n2, ", ".join(map(str, idx))))
    build(out_name, used if used else [0])
    return lines


def vec_function(N, dx, lanes=LANES):
    """rotate_zyz_vec_N (16 lanes) or rotate_zyz_vec8_N (8 lanes: AVX2 registers for float)."""
    LANES = lanes
    groups = vec_groups(N, lanes)
    n2 = N * N
    starts = []
    s = 9
    while s < n2:
        starts.append(min(s, n2 - LANES))
        s += LANES
    # lane tables per group
    lanes = []  # per group: list over lane of (l, k) or None
    for g in groups:
        tab = []
        for l in g:
            tab += [(l, k) for k in range(l + 1)]
        tab += [None] * (LANES - len(tab))
        lanes.append(tab)

    def acn(l, m):
        return l * l + l + m

    def chunk_of(a):
        for c, st in enumerate(starts):
            if st <= a < st + LANES:
                return (c, a - st)
        raise AssertionError
    body = []
    body.append("    using V = typename rot_vec<T>::%s;" % ("v16" if LANES == 16 else "v8"))
    body.append("    using V8 = typename rot_vec<T>::v8;")
    for c, st in enumerate(starts):
        body.append("    V in%d;" % c)
        body.append("    std::memcpy(&in%d, in + %d, sizeof(V));" % (c, st))
    inv = ["in%d" % c for c in range(len(starts))]
    for gi, tab in enumerate(lanes):
        for which, nm in ((0, "u"), (1, "v")):
            src = []
            for e in tab:
                if e is None:
                    src.append(None)
                    continue
                m = lane_m(e[1], which)
                src.append(None if m is None else chunk_of(acn(e[0], m)))
            body += shuffle_code("%s%d_0" % (nm, gi), src, inv, None, "V", LANES)
    # angle vectors: cm8 = (1, cos t, ..., cos 7t), sm8 = (0, sin t, ...)
    for ang in ("a", "b", "g"):
        cs = ", ".join(["T(1)"] + ["c%s[%d]" % (ang, m - 1) if m < N else "T(0)" for m in range(1, 8)])
        ss = ", ".join(["T(0)"] + ["s%s[%d]" % (ang, m - 1) if m < N else "T(0)" for m in range(1, 8)])
        body.append("    const V8 c%s8 = {%s};" % (ang, cs))
        body.append("    const V8 s%s8 = {%s};" % (ang, ss))
        body.append("    const V8 n%s8 = -s%s8;" % (ang, ang))
        for gi, tab in enumerate(lanes):
            kc, ku, kv = [], [], []
            for i, e in enumerate(tab):
                if e is None and LANES == 8:  # padding: the identity, a free lane selection
                    kc.append(i), ku.append(i), kv.append(i)
                    continue
                k = 0 if e is None else e[1]
                kc.append(k)
                odd = k % 2 == 1
                ku.append(k + (8 if odd else 0))   # su = -sin for odd k
                kv.append(k + (0 if odd else 8))   # sv = +sin for odd k
            body.append("    const V c%s%d = __builtin_shufflevector(c%s8, c%s8, %s);" % (ang, gi, ang, ang, ", ".join(map(str, kc))))
            body.append("    const V su%s%d = __builtin_shufflevector(s%s8, n%s8, %s);" % (ang, gi, ang, ang, ", ".join(map(str, ku))))
            body.append("    const V sv%s%d = __builtin_shufflevector(s%s8, n%s8, %s);" % (ang, gi, ang, ang, ", ".join(map(str, kv))))
    cnt = [0]

    def zstep(gi, ang, st):
        u, v = "u%d_%d" % (gi, st), "v%d_%d" % (gi, st)
        body.append("    const V u%d_%d = %s * c%s%d + %s * su%s%d;" % (gi, st + 1, u, ang, gi, v, ang, gi))
        body.append("    const V v%d_%d = %s * c%s%d + %s * sv%s%d;" % (gi, st + 1, v, ang, gi, u, ang, gi))

    def xstep(gi, st, transposed):
        tab = lanes[gi]
        for which, nm in ((0, "u"), (1, "v")):
            rows = []
            for i, e in enumerate(tab):
                terms = []
                if e is not None and lane_m(e[1], which) is not None:
                    l, k = e
                    mi = lane_m(k, which)
                    mat = dx[l]
                    for j, e2 in enumerate(tab):
                        if e2 is None or e2[0] != l:
                            continue
                        mj = lane_m(e2[1], which)
                        if mj is None:
                            continue
                        val = mat[mj + l][mi + l] if transposed else mat[mi + l][mj + l]
                        if val != 0:
                            terms.append((j, val))
                    # completeness: nothing maps across U and V
                    for mj in range(-l, l + 1):
                        val = mat[mj + l][mi + l] if transposed else mat[mi + l][mj + l]
                        if val != 0:
                            assert any(e2 is not None and e2[0] == l and lane_m(e2[1], which) == mj for e2 in tab), (l, mi, mj)
                rows.append(terms)
            K = max(len(t) for t in rows)
            src = "%s%d_%d" % (nm, gi, st)
            parts = []
            for t in range(K):
                perm = [r[t][0] if t < len(r) else i for i, r in enumerate(rows)]
                coef = [lit(r[t][1]) if t < len(r) else "T(0)" for r in rows]
                cnt[0] += 1
                kn = "k%d" % cnt[0]
                body.append("    const V %s = {%s};" % (kn, ", ".join(coef)))
                if perm == list(range(LANES)):
                    parts.append("%s * %s" % (src, kn))
                else:
                    body.append("    const V p%d = __builtin_shufflevector(%s, %s, %s);" % (cnt[0], src, src, ", ".join(map(str, perm))))
                    parts.append("p%d * %s" % (cnt[0], kn))
            body.append("    const V %s%d_%d = %s;" % (nm, gi, st + 1, " + ".join(parts)))

    for gi in range(len(groups)):
        zstep(gi, "g", 0)
        xstep(gi, 1, True)
        zstep(gi, "b", 2)
        xstep(gi, 3, False)
        zstep(gi, "a", 4)
    # output chunks
    srcs = []
    for gi in range(len(groups)):
        srcs += ["u%d_5" % gi, "v%d_5" % gi]
    where = {}
    for gi, tab in enumerate(lanes):
        for i, e in enumerate(tab):
            if e is None:
                continue
            for which in (0, 1):
                m = lane_m(e[1], which)
                if m is not None:
                    where[acn(e[0], m)] = (2 * gi + which, i)
    for c, st in enumerate(starts):
        src = [where.get(st + i) for i in range(LANES)]
        body += shuffle_code("o%d" % c, src, srcs, None, "V", LANES)
    for c, st in enumerate(starts):
        body.append("    std::memcpy(out + %d, &o%d, sizeof(V));" % (st, c))
    out = []
    out.append("/// Bands 3..%d of out = D(R) in, %d bands, in %d-lane vectors (see rotate_direct_vec)." % (N - 1, N, LANES))
    out.append("template <class T>")
    out.append("SPHBASIS_FORCEINLINE void rotate_zyz_vec%s_%d(const T* ca, const T* sa, const T* cb, const T* sb, const T* cg, const T* sg, const T* in, T* out) noexcept {" % ("" if LANES == 16 else "8", N))
    out += body
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
// sh::rotate<N>(R, in, out) rotates one coefficient vector without forming D: band 1 is R, band
// 2 the quadratic form R Q R^T, bands >= 3 the Euler factorisation Z(alpha) X Z(beta) X^T
// Z(gamma) with cos/sin of the angles read from R (robust at beta = 0, pi) and the quarter turn
// X as generated sparse code (see detail::rotate_direct). FixedRotation is for applying one
// rotation to many vectors (blocks stored column-major; 16-lane vector apply for C = T).
//
// Cost (float, one thread): see bench/bench_sh_ops.cpp; the construction has no run-time
// checks (SPHBASIS_ASSERT checks orthonormality in debug builds); from_matrix() is the checked
// entry point.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "../config.hpp"
#include "../core/frame.hpp"
#include "sh_rotation.hpp"

#if !defined(SPHBASIS_SH_ROTATION_VECTOR)
#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_SH_ROTATION_VECTOR 1
#else
#define SPHBASIS_SH_ROTATION_VECTOR 0
#endif
#endif
#if SPHBASIS_SH_ROTATION_VECTOR
#include <cstring>
#if defined(__AVX512F__)
#include <immintrin.h>
#endif
#endif

namespace sphbasis::sh::detail {

#if SPHBASIS_SH_ROTATION_VECTOR
/// GNU vector types of rotate_direct_vec: 16 and 8 lanes.
template <class T>
struct rot_vec;
template <>
struct rot_vec<float> {
    typedef float v16 __attribute__((vector_size(64)));
    typedef float v8 __attribute__((vector_size(32)));
};
template <>
struct rot_vec<double> {
    typedef double v16 __attribute__((vector_size(128)));
    typedef double v8 __attribute__((vector_size(64)));
};
#endif

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
        // band 1: D1[i][j] = R[p(i)][p(j)], p = (y, z, x), column-major (D1[i][j] at 3 j + i)
        T* b1 = d + 1;
        b1[0] = r[4], b1[1] = r[7], b1[2] = r[1];
        b1[3] = r[5], b1[4] = r[8], b1[5] = r[2];
        b1[6] = r[3], b1[7] = r[6], b1[8] = r[0];
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

/// cos(m t), sin(m t) for m = 1..L into cm[m - 1], sm[m - 1], from c = cos t, s = sin t, by the
/// Chebyshev recurrence x_{m+1} = 2 c x_m - x_{m-1} (error O(m^2 eps), a few ulp for m <= 7).
template <int L, class T>
SPHBASIS_FORCEINLINE void rotation_multiples(T c, T s, T* SPHBASIS_RESTRICT cm, T* SPHBASIS_RESTRICT sm) noexcept {
    cm[0] = c;
    sm[0] = s;
    const T c2 = c + c;
    if constexpr (L >= 2) {
        cm[1] = c2 * c - T(1);
        sm[1] = c2 * s;
    }
    for (int m = 2; m < L; ++m) {
        cm[m] = c2 * cm[m - 1] - cm[m - 2];
        sm[m] = c2 * sm[m - 1] - sm[m - 2];
    }
}

/// Bands 0..min(L, 3) - 1 of D(R) in into lo (in read before anything is written).
template <int L, class T, class C>
SPHBASIS_FORCEINLINE void rotate_low_bands(const T* SPHBASIS_RESTRICT r, const C* in, C* lo) noexcept {
    lo[0] = in[0];
    if constexpr (L >= 2) {
        const C y = in[1], z = in[2], x = in[3];
        lo[1] = y * r[4] + z * r[5] + x * r[3];
        lo[2] = y * r[7] + z * r[8] + x * r[6];
        lo[3] = y * r[1] + z * r[2] + x * r[0];
    }
    if constexpr (L >= 3) {
        const T a = T(0.57735026918962576);  // 1/sqrt(3)
        const C c0 = in[6], c2 = in[8];
        const C qxy = in[4], qyz = in[5], qxz = in[7];
        const C qzz = c0 * (a + a);
        const C qxx = c2 + c0 * (-a), qyy = c2 * T(-1) + c0 * (-a);
        const C t00 = qxx * r[0] + qxy * r[1] + qxz * r[2];
        const C t01 = qxy * r[0] + qyy * r[1] + qyz * r[2];
        const C t02 = qxz * r[0] + qyz * r[1] + qzz * r[2];
        const C t10 = qxx * r[3] + qxy * r[4] + qxz * r[5];
        const C t11 = qxy * r[3] + qyy * r[4] + qyz * r[5];
        const C t12 = qxz * r[3] + qyz * r[4] + qzz * r[5];
        const C t20 = qxx * r[6] + qxy * r[7] + qxz * r[8];
        const C t21 = qxy * r[6] + qyy * r[7] + qyz * r[8];
        const C t22 = qxz * r[6] + qyz * r[7] + qzz * r[8];
        const T k = T(0.86602540378443865);  // sqrt(3)/2
        const T h = T(0.5);
        lo[4] = t00 * r[3] + t01 * r[4] + t02 * r[5];
        lo[5] = t10 * r[6] + t11 * r[7] + t12 * r[8];
        lo[6] = t20 * (k * r[6]) + t21 * (k * r[7]) + t22 * (k * r[8]);
        lo[7] = t00 * r[6] + t01 * r[7] + t02 * r[8];
        lo[8] = t00 * (h * r[0]) + t01 * (h * r[1]) + t02 * (h * r[2]) + t10 * (-h * r[3]) + t11 * (-h * r[4]) +
                t12 * (-h * r[5]);
    }
}

/// cos, sin of m alpha, m beta, m gamma (m = 1..L-1) of the Euler factorisation of s R, s the
/// sign of det R; returns true for det R < 0.
template <int L, class T>
SPHBASIS_FORCEINLINE bool zyz_multiples(const T* SPHBASIS_RESTRICT r, T* ca, T* sa, T* cb, T* sb, T* cg, T* sg) noexcept {
    const T det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                  r[2] * (r[3] * r[7] - r[4] * r[6]);
    const T s = det < T(0) ? T(-1) : T(1);
    const T m00 = s * r[0], m01 = s * r[1], m02 = s * r[2];
    const T m10 = s * r[3], m11 = s * r[4], m12 = s * r[5], m22 = s * r[8];
    const T h2 = m02 * m02 + m12 * m12;
    T ca1 = T(1), sa1 = T(0), sb1 = T(0);
    if (h2 >= std::numeric_limits<T>::min()) {
        const T inv = T(1) / std::sqrt(h2);
        ca1 = m02 * inv;
        sa1 = m12 * inv;
        sb1 = h2 * inv;
    }
    rotation_multiples<L - 1>(ca1, sa1, ca, sa);
    rotation_multiples<L - 1>(m22, sb1, cb, sb);
    rotation_multiples<L - 1>(ca1 * m11 - sa1 * m01, ca1 * m10 - sa1 * m00, cg, sg);
    return det < T(0);
}

/// Odd bands >= 3 of out negated (improper R).
template <int L, class T, class C>
SPHBASIS_FORCEINLINE void negate_odd_high_bands(C* out) noexcept {
    for (int l = 3; l < L; l += 2)
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) out[k] = out[k] * T(-1);
}

/// out = D(R) in, scalar straight-line code for any coefficient type C (see rotate_direct).
template <int L, class T, class C>
SPHBASIS_FORCEINLINE void rotate_direct_scalar(const T* SPHBASIS_RESTRICT r, const C* in, C* out) noexcept {
    C lo[9];
    rotate_low_bands<L>(r, in, lo);
    if constexpr (L >= 4) {
        T ca[L - 1], sa[L - 1], cb[L - 1], sb[L - 1], cg[L - 1], sg[L - 1];
        const bool improper = zyz_multiples<L>(r, ca, sa, cb, sb, cg, sg);
        rotate_zyz_band_3(ca, sa, cb, sb, cg, sg, in + 9, out + 9);
        if constexpr (L >= 5) rotate_zyz_band_4(ca, sa, cb, sb, cg, sg, in + 16, out + 16);
        if constexpr (L >= 6) rotate_zyz_band_5(ca, sa, cb, sb, cg, sg, in + 25, out + 25);
        if constexpr (L >= 7) rotate_zyz_band_6(ca, sa, cb, sb, cg, sg, in + 36, out + 36);
        if constexpr (L >= 8) rotate_zyz_band_7(ca, sa, cb, sb, cg, sg, in + 49, out + 49);
        if (improper) negate_odd_high_bands<L, T>(out);
    }
    for (int k = 0; k < (L < 3 ? L * L : 9); ++k) out[k] = lo[k];
}

#if SPHBASIS_SH_ROTATION_VECTOR
/// out = D(R) in for C = T (float or double): bands 0..2 as in rotate_direct_scalar, bands >= 3
/// in 16-lane GNU vectors (rotate_zyz_vec_L). Reads in[0..L^2) and writes out[0..L^2) only,
/// all reads before the first write.
template <int L, class T>
SPHBASIS_FORCEINLINE void rotate_direct_vec(const T* SPHBASIS_RESTRICT r, const T* in, T* out) noexcept {
    static_assert(L >= 4, "rotate_direct_vec: L >= 4");
    T lo[9];
#if SPHBASIS_SH_ROTATION_AVX512
    // float: bands 0..2 in one register (rotate_low_bands_avx512, ops/sh_rotation.hpp)
    constexpr bool low_vec = std::is_same_v<T, float>;
    __m512 lov;
    if constexpr (low_vec)
        lov = rotate_low_bands_avx512(_mm512_setr_ps(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], 0, 0, 0, 0, 0, 0, 0), in);
    else
#endif
        rotate_low_bands<L>(r, in, lo);
    T ca[L - 1], sa[L - 1], cb[L - 1], sb[L - 1], cg[L - 1], sg[L - 1];
    const bool improper = zyz_multiples<L>(r, ca, sa, cb, sb, cg, sg);
    if constexpr (L == 4) rotate_zyz_vec_4(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 5) rotate_zyz_vec_5(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 6) rotate_zyz_vec_6(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 7) rotate_zyz_vec_7(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 8) rotate_zyz_vec_8(ca, sa, cb, sb, cg, sg, in, out);
    if (improper) negate_odd_high_bands<L, T>(out);
#if SPHBASIS_SH_ROTATION_AVX512
    if constexpr (low_vec) {
        store_low_bands_avx512(out, lov);
        return;
    }
#endif
    for (int k = 0; k < 9; ++k) out[k] = lo[k];
}
#endif

#if SPHBASIS_SH_ROTATION_AVX2 && SPHBASIS_SH_ROTATION_VECTOR
/// rotate_direct_vec for float in 8-lane AVX2 registers: bands 1..2 by rotate_low_bands_avx2
/// (ops/sh_rotation.hpp), bands >= 3 by rotate_zyz_vec8_L (one band per 8-lane group). Every
/// read of in before the first write.
template <int L>
SPHBASIS_FORCEINLINE void rotate_direct_avx2(const float* SPHBASIS_RESTRICT r, const float* in, float* out) noexcept {
    static_assert(L >= 4, "rotate_direct_avx2: L >= 4");
    const float c0 = in[0];
    const __m256 lov = rotate_low_bands_avx2(mat3_lo_avx2(r), mat3_r8_avx2(r), in);
    float ca[L - 1], sa[L - 1], cb[L - 1], sb[L - 1], cg[L - 1], sg[L - 1];
    const bool improper = zyz_multiples<L>(r, ca, sa, cb, sb, cg, sg);
    if constexpr (L == 4) rotate_zyz_vec8_4(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 5) rotate_zyz_vec8_5(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 6) rotate_zyz_vec8_6(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 7) rotate_zyz_vec8_7(ca, sa, cb, sb, cg, sg, in, out);
    if constexpr (L == 8) rotate_zyz_vec8_8(ca, sa, cb, sb, cg, sg, in, out);
    if (improper) negate_odd_high_bands<L, float>(out);
    _mm256_storeu_ps(out + 1, lov);
    out[0] = c0;
}
#endif

/// out = D(R) in for L bands of the row-major matrix r, D never formed:
///   * band 1: D^1 = R permuted to (y, z, x);
///   * band 2: the coefficients are a traceless symmetric Q with f(w) = w^T Q w on the sphere
///     (scaled by 2 / sqrt(15 / (4 pi)): Q_xy = c_-2, Q_yz = c_-1, Q_xz = c_1,
///     Q_xx = c_2 - c_0 / sqrt3, Q_yy = -c_2 - c_0 / sqrt3, Q_zz = 2 c_0 / sqrt3); the rotated
///     function is w^T (R Q R^T) w, 45 multiply-adds;
///   * bands l >= 3: R = Rz(alpha) Ry(beta) Rz(gamma) with Ry(beta) = X Rz(beta) X^T, X the
///     quarter turn about x taking z to y, so D^l = Z(alpha) D^l(X) Z(beta) D^l(X)^T Z(gamma):
///     three z rotations (cos, sin of m times each angle on the pairs (m, -m)) and two sparse
///     constant matrices (generated with exact constants, zeros skipped). The angles are never
///     formed: cos beta = R_22, sin beta = |(R_02, R_12)|, (cos alpha, sin alpha) = (R_02,
///     R_12) / sin beta, and (cos gamma, sin gamma) is read from the middle row of
///     Rz(-alpha) R = Ry(beta) Rz(gamma): cos gamma = ca R_11 - sa R_01, sin gamma = ca R_10 -
///     sa R_00. Any unit (ca, sa) makes that row exact, so at and near beta = 0 or pi (sin^2
///     beta below the smallest normal: alpha = 0) the factorisation still reproduces R to
///     rounding: gamma absorbs the error of alpha.
///   * improper R (det < 0): bands >= 3 use -R and negate the odd bands ((-1)^l D(-R), as the
///     recurrence gives); bands 1 and 2 are homogeneous in R and need nothing.
/// For C = T with AVX-512 the bands >= 3 run in 16-lane vectors (rotate_direct_vec; the lanes
/// pair m with -m so that a z rotation is lane-wise and the quarter turn is a few lane
/// permutations times constants), and for C = T = float bands 0..2 in one 16-lane register
/// (rotate_low_bands_avx512, ops/sh_rotation.hpp: R R-permuted for band 1 and the bilinear
/// forms of R Q R^T for band 2, lane-wise). For C = T = float with AVX2 and no AVX-512
/// (SPHBASIS_SH_ROTATION_AVX2) the same in 8-lane registers (rotate_low_bands_avx2,
/// rotate_direct_avx2: one band >= 3 per register). Otherwise straight-line scalar code
/// (rotate_direct_scalar). in == out is allowed: every input is read before the first write.
template <int L, class T, class C>
SPHBASIS_FORCEINLINE void rotate_direct(const T* SPHBASIS_RESTRICT r, const C* in, C* out) noexcept {
#if SPHBASIS_SH_ROTATION_AVX512
    if constexpr (L == 3 && std::is_same_v<T, float> && std::is_same_v<C, float>) {
        const __m512 rv = _mm512_setr_ps(r[0], r[1], r[2], r[3], r[4], r[5], r[6], r[7], r[8], 0, 0, 0, 0, 0, 0, 0);
        store_low_bands_avx512(out, rotate_low_bands_avx512(rv, in));
        return;
    }
#endif
#if SPHBASIS_SH_ROTATION_VECTOR && defined(__AVX512F__)
    if constexpr (L >= 4 && std::is_same_v<C, T>) {
        rotate_direct_vec<L>(r, in, out);
        return;
    }
#endif
#if SPHBASIS_SH_ROTATION_AVX2
    if constexpr (L == 3 && std::is_same_v<T, float> && std::is_same_v<C, float>) {
        rotate_three_bands_avx2(r, in, out);
        return;
    }
#if SPHBASIS_SH_ROTATION_VECTOR
    if constexpr (L >= 4 && std::is_same_v<T, float> && std::is_same_v<C, float>) {
        rotate_direct_avx2<L>(r, in, out);
        return;
    }
#endif
#endif
    rotate_direct_scalar<L>(r, in, out);
}

#if SPHBASIS_SH_ROTATION_VECTOR
// GCC 12 at -march=x86-64-v3 (16 doubles lowered to four 4-lane registers) reports
// -Warray-bounds and -Wstringop-overflow here when a run-time band count dispatches to these
// kernels and a caller's buffer of fewer coefficients is visible: the band counts that would
// overrun it are never taken (Rotation checks the buffers against its own band count). False
// positives, silenced for these functions only.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#pragma GCC diagnostic ignored "-Wstringop-overflow"
#endif
/// Band l of out = M x in 16 lanes (lanes >= 2l + 1 are garbage): cols holds the block
/// column-major (column j at cols + j (2l + 1)), read 16 values at a time.
template <int l, class T>
SPHBASIS_FORCEINLINE void apply_block_vec(const T* SPHBASIS_RESTRICT cols, const T* x, typename rot_vec<T>::v16& res) noexcept {
    using V = typename rot_vec<T>::v16;
    constexpr int w = 2 * l + 1;
    V c, acc0, acc1;
    std::memcpy(&c, cols, sizeof(V));
    acc0 = c * x[0];
    acc1 = c * T(0);
    for (int j = 1; j < w; ++j) {
        std::memcpy(&c, cols + j * w, sizeof(V));
        if (j % 2) acc1 += c * x[j];
        else acc0 += c * x[j];
    }
    res = acc0 + acc1;
}

/// The first n lanes of v into out (an AVX-512 masked store where available).
template <int n, class T>
SPHBASIS_FORCEINLINE void store_lanes(T* out, const typename rot_vec<T>::v16& v) noexcept {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<T, float>) {
        __m512 x;
        std::memcpy(&x, &v, sizeof(x));
        _mm512_mask_storeu_ps(out, static_cast<__mmask16>((1u << n) - 1u), x);
        return;
    } else {
        __m512d lo, hi;
        std::memcpy(&lo, &v, sizeof(lo));
        std::memcpy(&hi, reinterpret_cast<const char*>(&v) + sizeof(lo), sizeof(hi));
        _mm512_mask_storeu_pd(out, static_cast<__mmask8>(n >= 8 ? 0xffu : (1u << n) - 1u), lo);
        if constexpr (n > 8) _mm512_mask_storeu_pd(out + 8, static_cast<__mmask8>((1u << (n - 8)) - 1u), hi);
        return;
    }
#else
    T tmp[16];
    std::memcpy(tmp, &v, sizeof(tmp));
    for (int k = 0; k < n; ++k) out[k] = tmp[k];
#endif
}

/// vs[l'] = band l' of the product for l' = l..L-1 (16 lanes each).
template <int l, int L, class T>
SPHBASIS_FORCEINLINE void apply_bands_vec(const T* SPHBASIS_RESTRICT cols, const T* in, typename rot_vec<T>::v16* vs) noexcept {
    if constexpr (l < L) {
        apply_block_vec<l>(cols + fixed_rotation_size(l), in + l * l, vs[l]);
        apply_bands_vec<l + 1, L>(cols, in, vs);
    }
}

/// Bands l..L-1 from vs into out + l^2, in ascending order: 16 lanes where that stays inside
/// the L^2 outputs (the garbage lanes are overwritten by the later bands), else 2l + 1 lanes.
template <int l, int L, class T>
SPHBASIS_FORCEINLINE void store_bands_vec(const typename rot_vec<T>::v16* vs, T* out) noexcept {
    if constexpr (l < L) {
        if constexpr (l * l + 16 <= L * L) std::memcpy(out + l * l, &vs[l], sizeof(vs[l]));
        else store_lanes<2 * l + 1>(out + l * l, vs[l]);
        store_bands_vec<l + 1, L>(vs, out);
    }
}

/// out = M in for the block-diagonal M whose blocks are stored column-major in cols (padded by
/// 16 values): per band, 2l + 1 column vectors times broadcast inputs. Every input is read
/// before the first store, so in == out is allowed.
template <int L, class T>
SPHBASIS_FORCEINLINE void rotation_fixed_apply_vec(const T* SPHBASIS_RESTRICT cols, const T* in, T* out) noexcept {
    typename rot_vec<T>::v16 vs[L];
    const T x0 = in[0] * cols[0];
    apply_bands_vec<1, L>(cols, in, vs);
    out[0] = x0;
    store_bands_vec<1, L>(vs, out);
}
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif
#endif

}  // namespace sphbasis::sh::detail

namespace sphbasis::sh {

/// D(R) for a compile-time band count N (1..8), stored in a std::array: block l is
/// (2l+1)x(2l+1), column-major, entry (m, n) at offset(l) + (n+l)(2l+1) + m+l (the transpose
/// of the run-time sh::Rotation<T>'s row-major blocks: apply reads whole columns). Built by
/// straight-line code (no allocation, no table, no check in the unchecked constructor); the
/// apply is the block-diagonal product: for C = T (GCC, clang) per band 2l+1 column vectors of
/// 16 lanes times broadcast inputs, otherwise unrolled scalar code. Build once, apply many: to
/// rotate one vector, sh::rotate<N> is faster than building D.
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
        finish();
    }

    /// D(R) of an orthogonal row-major matrix, unchecked (SPHBASIS_ASSERT in debug builds: max
    /// |R R^T - I| <= default tolerance). A non-orthogonal matrix gives a meaningless but finite
    /// result for finite input. For a checked construction use from_matrix().
    explicit FixedRotation(const Mat3<T>& r) noexcept {
        SPHBASIS_ASSERT(detail::fixed_rotation_orthonormal(r));
        detail::rotation_fixed_bands<N>(r.data(), d_.data());
        finish();
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
    /// Block l, (2l+1)^2 values column-major (entry (m, n) at (n+l)(2l+1) + m+l).
    const T* block(int l) const noexcept { return d_.data() + offset(l); }
    /// Entry (m, n) of band l: d y_lm(Rw) / d y_ln(w).
    T operator()(int l, int m, int n) const noexcept {
        SPHBASIS_ASSERT(l >= 0 && l < N && m >= -l && m <= l && n >= -l && n <= l);
        return d_[offset(l) + static_cast<std::size_t>((n + l) * (2 * l + 1) + m + l)];
    }

    /// out = D in, N^2 coefficients each; C is any type with C + C and C * T (float, double,
    /// RGB: all channels in one pass). in == out is allowed. No checks (SPHBASIS_ASSERT on null).
    template <class C>
    SPHBASIS_FORCEINLINE void apply(const C* in, C* out) const noexcept {
        SPHBASIS_ASSERT(in && out);
#if SPHBASIS_SH_ROTATION_VECTOR
        if constexpr (std::is_same_v<C, T>) {
            detail::rotation_fixed_apply_vec<N>(d_.data(), in, out);
            return;
        }
#endif
        detail::rotation_fixed_apply<N, true>(d_.data(), in, out);  // column-major: D in
    }
    /// out = D^T in: the inverse rotation.
    template <class C>
    SPHBASIS_FORCEINLINE void apply_transposed(const C* in, C* out) const noexcept {
        SPHBASIS_ASSERT(in && out);
        detail::rotation_fixed_apply<N, false>(d_.data(), in, out);  // column-major: D^T in
    }
    /// apply() by value.
    template <class C>
    std::array<C, N * N> apply(const std::array<C, N * N>& in) const noexcept {
        std::array<C, N * N> out;
        apply(in.data(), out.data());
        return out;
    }

  private:
#if SPHBASIS_SH_ROTATION_VECTOR
    static constexpr std::size_t pad_v = 16;  // 16-lane reads past the last block stay inside
#else
    static constexpr std::size_t pad_v = 0;
#endif
    void finish() noexcept {
        for (std::size_t k = size_v; k < size_v + pad_v; ++k) d_[k] = T(0);
    }
    std::array<T, size_v + pad_v> d_;  // D, block after block, column-major (size_v values, then padding)
};

/// out = D(R) in for N bands without forming D: band 1 is R itself, band 2 the quadratic form
/// R Q R^T, bands 3.. the Euler factorisation R = Rz(alpha) X Rz(beta) X^T Rz(gamma) applied
/// as generated straight-line code (see detail::rotate_direct). The result equals
/// FixedRotation<N, T>(r).apply(in, out) and the run-time sh::rotate to rounding, for proper
/// and improper matrices. R is a row-major Mat3<T>, unchecked (SPHBASIS_ASSERT in debug
/// builds); in == out is allowed. C is any type with C + C and C * T. To rotate many vectors by
/// the same R, build a FixedRotation once and apply it.
template <int N, class T, class C>
SPHBASIS_FORCEINLINE void rotate(const Mat3<T>& r, const C* in, C* out) noexcept {
    static_assert(N >= 1 && N <= 8, "sphbasis::sh::rotate<N>: N is a band count in 1..8.");
    static_assert(std::is_floating_point_v<T>, "sphbasis::sh::rotate<N>: T is float or double.");
    SPHBASIS_ASSERT(detail::fixed_rotation_orthonormal(r));
    SPHBASIS_ASSERT(in && out);
    detail::rotate_direct<N>(r.data(), in, out);
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
    dx = dmat(MAX_BANDS - 1, [[sp.Integer(v) for v in row] for row in XMAT])
    self_check(dx)
    for l in range(3, MAX_BANDS):
        parts.append(zyz_band_function(l, dx))
        parts.append("\n\n")
    parts.append("#if SPHBASIS_SH_ROTATION_VECTOR\n")
    for n in range(4, MAX_BANDS + 1):
        parts.append(vec_function(n, dx))
        parts.append("\n\n")
    parts.append("#endif\n\n")
    parts.append("#if SPHBASIS_SH_ROTATION_AVX2 && SPHBASIS_SH_ROTATION_VECTOR\n")
    for n in range(4, MAX_BANDS + 1):
        parts.append(vec_function(n, dx, 8))
        parts.append("\n\n")
    parts.append("#endif\n\n")
    parts.append(FOOTER)
    print("".join(parts), end="")


if __name__ == "__main__":
    main()
