#!/usr/bin/python3
"""Generates the tables of the Ambient Dice variants over the icosahedron's faces
(include/sphbasis/basis/ambient_dice_bezier_tables.hpp) and, with --reference, reference values
of their basis functions (tests/data/ambient_dice_bezier_reference.txt).

Ambient Dice (M. Iwanicki and P.-P. Sloan, "Ambient Dice", EGSR 2017, Experimental Ideas &
Implementations): values stored at the 12 icosahedron vertices, with their two directional
derivatives (the "Bezier" variant: hybrid cubic Bezier triangles over the 20 faces) or alone (the
linear interpolation that the paper's YCoCg variant uses for chroma). Two constructions share the
geometry, in mpmath at 40 digits:
  * vertices v_k: the unit icosahedron vertices in the order of ambient_dice.hpp (2i = +a_i,
    2i+1 = -a_i); tangent frame u_k = the unit component of v_m orthogonal to v_k (m the
    vertex's lowest-numbered neighbour), w_k = v_k x u_k;
  * faces: the 20 triples of mutually neighbouring vertices, ascending, in lexicographic order;
    a direction d lies in the face whose cone contains it (the face maximising d . normal; found
    by the octant and three plane tests, see below); b = the coordinates of d in the face's three
    unit vertices (d = sum b_a v_a; rows of the inverse vertex matrix).
The paper's rule (ambient-dice-bezier, ambient-dice-linear), as in T. Roughton's implementation
of the paper in Probulator (2019): b is used as is, so each patch is a homogeneous polynomial of d
on its face's cone (constants are not reproduced exactly, linear functions of d are):
  * linear: sum_a f_a b_a;
  * Bezier: the cubic Bezier triangle over b with vertex points f_a, edge points
    c_ab = f_a (v_a . v_b) + (1/3) g_a . v_b (g_a the tangential gradient at v_a): the blossom
    B(v_a, v_a, v_b) of a homogeneous cubic F with F(v_a) = f_a and gradient 3 f_a v_a + g_a (Euler),
    so values and derivatives at the vertices are reproduced; and, as in Foley and Opitz's hybrid
    cubic Bezier triangles ("Hybrid cubic Bezier triangle patches", 1992), one interior point per
    edge, blended by b_b b_c / (b_0 b_1 + b_1 b_2 + b_2 b_0) for the edge (b, c) opposite a:
      c111_a = a0 (f_b + f_c) + a1 (c_bc + c_cb) + a2 (c_ba + c_ca).
    a2 = sqrt(5)/10 is Probulator's value. a0 and a1 follow (derived below, exactly, in sympy):
    with v_a' the vertex across the edge, v_a + v_a' = mu (v_b + v_c), mu = 2/(1 + sqrt 5); the
    edge points of the neighbouring face then satisfy c_ba' = -c_ba + mu f_b + mu c_bc (the edge
    points are linear in their second argument), and the two cubics meet C1 along the whole edge
    iff c111_a' = -c111_a + mu (c_bc + c_cb), for every data iff 2 a0 + a2 mu = 0 and
    2 a1 + a2 mu = mu. That leaves a2 free; reproducing the restrictions of L(x)|x|^2 (L linear:
    the linear functions of the direction) fixes it: a2 = (v_a . v_b)/2 = sqrt(5)/10, Probulator's
    value, and then the C1 values of a0 and a1 are Probulator's too. No rule from vertex data can
    reproduce every cubic: b_0 b_1 b_2 of a face vanishes with its gradient at the face's vertices.
The normalised rule (ambient-dice-bezier-normalized, ambient-dice-linear-normalized), this
library's construction from before the paper's rule was known: b divided by its sum (the planar
barycentrics of d's central projection onto the face's plane), so constants are reproduced exactly;
edge points c_ab = f_a + (1/3) g_a . v_b; one interior point per edge chosen so that the derivative
across the edge at its midpoint equals the mean of the two vertex gradients along the edge's
normal (C1 at vertices and edge midpoints, C0 elsewhere on the edges).
Face location: the octant of d (sign bits) picks one of the 8 faces whose normal lies in it;
three plane tests on (|x|, |y|, |z|) against the planes through the origin and that face's edges
(in the positive octant) switch to the face across an edge. The tables hold the positive octant's
planes and, per octant, the face and its three neighbours (reflections of the positive octant's).
Self-checks (printed in the reference file and the header): interpolation of values and gradients
of a test function at every vertex from every face around it (numerical differentiation at 40
digits), continuity of value along every edge and of the cross derivative (several points per
edge for the paper's rule, the midpoints for the normalised one), the exact derivation above,
linear functions (paper) or constants (normalised) reproduced, face location against the
maximum over the face normals.

Regenerate from the repo root with:
  /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py > include/sphbasis/basis/ambient_dice_bezier_tables.hpp
  /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py --reference > tests/data/ambient_dice_bezier_reference.txt
"""
import random
import sys

import mpmath as mp
import sympy as sp

mp.mp.dps = 40
reference = "--reference" in sys.argv[1:]
checks = []


def out(line):
    sys.stdout.write(line + "\n")


def log(msg):
    sys.stderr.write(msg + "\n")
    checks.append(msg)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(v):
    n = mp.sqrt(dot(v, v))
    return [c / n for c in v]


# ---- geometry --------------------------------------------------------------------------------
tn = (mp.sqrt(5) - 1) / 2
An = 1 / mp.sqrt(1 + tn * tn)
Bn = tn * An
axes = [[An, Bn, 0], [-An, Bn, 0], [0, An, Bn], [0, -An, Bn], [Bn, 0, An], [Bn, 0, -An]]
V = []
for a in axes:
    V += [[mp.mpf(c) for c in a], [-mp.mpf(c) for c in a]]
cos_edge = 1 / mp.sqrt(5)
nbr = [[j for j in range(12) if abs(dot(V[i], V[j]) - cos_edge) < mp.mpf(10) ** -30] for i in range(12)]
assert all(len(n) == 5 for n in nbr)
U, W = [], []
for k in range(12):
    m = V[nbr[k][0]]
    u = unit([m[i] - dot(m, V[k]) * V[k][i] for i in range(3)])
    U.append(u)
    W.append(cross(V[k], u))
faces = sorted(
    (i, j, k) for i in range(12) for j in nbr[i] for k in nbr[i] if i < j < k and k in nbr[j])
assert len(faces) == 20
normals = [unit([V[i][c] + V[j][c] + V[k][c] for c in range(3)]) for (i, j, k) in faces]
duals = []
for (i, j, k) in faces:
    M = mp.matrix([[V[i][r], V[j][r], V[k][r]] for r in range(3)])
    Mi = M**-1
    duals.append([[Mi[a, r] for r in range(3)] for a in range(3)])
log("ambient dice bezier: 12 vertices with 5 neighbours each at cos = 1/sqrt(5), 20 faces")

# ---- the paper's interior rule, exactly (sympy) ------------------------------------------------
a0s, a1s, a2s, mus = sp.symbols("a0 a1 a2 mu")
fb, fc, cbc, ccb, cba, cca = sp.symbols("f_b f_c c_bc c_cb c_ba c_ca")


def c111_sym(fb_, fc_, cbc_, ccb_, cba_, cca_):
    return a0s * (fb_ + fc_) + a1s * (cbc_ + ccb_) + a2s * (cba_ + cca_)


# Across the edge (b, c): v_a' = -v_a + mu (v_b + v_c), so (blossom linearity) the neighbour's edge
# points towards a' are c_ba' = -c_ba + mu (f_b + c_bc), c_ca' = -c_ca + mu (f_c + c_cb), and its
# cubic continues ours to first order iff c111' = -c111 + mu (c_bc + c_cb).
c1 = sp.expand(c111_sym(fb, fc, cbc, ccb, -cba + mus * (fb + cbc), -cca + mus * (fc + ccb)) +
               c111_sym(fb, fc, cbc, ccb, cba, cca) - mus * (cbc + ccb))
c1_sol = sp.solve(sp.Poly(c1, fb, fc, cbc, ccb, cba, cca).coeffs(), [a0s, a1s], dict=True)
assert len(c1_sol) == 1
c1_sol = c1_sol[0]
assert sp.simplify(c1_sol[a0s] + a2s * mus / 2) == 0 and sp.simplify(c1_sol[a1s] - mus * (1 - a2s) / 2) == 0
# Linear precision: the blossom of L(x)|x|^2 is (L(x)(y.z) + L(y)(x.z) + L(z)(x.y))/3; with
# s = v_a . v_b = 1/sqrt(5) the rule must give c111 = s (L_a + L_b + L_c)/3 from its data.
La, Lb, Lc = sp.symbols("L_a L_b L_c")
s_ex, mu_ex = 1 / sp.sqrt(5), 2 / (1 + sp.sqrt(5))
bl = lambda x, y, z: sp.Rational(1, 3) * (x + y + z) * s_ex  # blossom of three distinct vertices
edge = lambda x, y: (2 * x * s_ex + y) / 3  # B(v_x, v_x, v_y)
lin = sp.expand(c111_sym(Lb, Lc, edge(Lb, Lc), edge(Lc, Lb), edge(Lb, La), edge(Lc, La))
                .subs(c1_sol).subs(mus, mu_ex) - bl(La, Lb, Lc))
lin_sol = sp.solve([sp.nsimplify(sp.radsimp(c)) for c in sp.Poly(lin, La, Lb, Lc).coeffs()], [a2s], dict=True)
assert len(lin_sol) == 1 and sp.simplify(lin_sol[0][a2s] - sp.sqrt(5) / 10) == 0
a2_ex = sp.sqrt(5) / 10
a0_ex = sp.radsimp(c1_sol[a0s].subs({a2s: a2_ex, mus: mu_ex}))
a1_ex = sp.radsimp(c1_sol[a1s].subs({a2s: a2_ex, mus: mu_ex}))
assert sp.simplify(a0_ex - (sp.sqrt(5) - 5) / 40) == 0 and sp.simplify(a1_ex - (11 * sp.sqrt(5) - 15) / 40) == 0
log("paper rule: C1 across an edge for all data iff 2 a0 + a2 mu = 0 and 2 a1 + a2 mu = mu "
    "(mu = 2/(1+sqrt 5)); linear functions reproduced iff also a2 = sqrt(5)/10; so a0 = %s, a1 = %s "
    "(sympy, exact)" % (a0_ex, a1_ex))
A0, A1, A2 = (mp.mpf(sp.N(c, 50)) for c in (a0_ex, a1_ex, a2_ex))
MU = 2 / (1 + mp.sqrt(5))
# the geometric relation used above, on all 30 edges
worst = 0
edge_list = []
for f in range(20):
    for g in range(f + 1, 20):
        sh = set(faces[f]) & set(faces[g])
        if len(sh) == 2:
            a, = set(faces[f]) - sh
            a2_, = set(faces[g]) - sh
            b, c = sorted(sh)
            edge_list.append((f, g))
            worst = max(worst, max(abs(V[a][i] + V[a2_][i] - MU * (V[b][i] + V[c][i])) for i in range(3)))
assert len(edge_list) == 30 and worst < mp.mpf(10) ** -35
log("paper rule: v_a + v_a' = mu (v_b + v_c) across all 30 edges (max |err| %s)" % mp.nstr(worst, 3))

EDGES = [(0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)]  # control point near a, towards b
VARIANTS = ("paper", "normalized")


def edge_factors(f):
    """c_ab = s f_a + e_u g_u(a) + e_w g_w(a), (e_u, e_w) = (u_a . v_b, w_a . v_b) / 3; s = 1
    (normalised) or v_a . v_b (paper)."""
    vs = faces[f]
    return [[dot(U[vs[a]], V[vs[b]]) / 3, dot(W[vs[a]], V[vs[b]]) / 3] for a, b in EDGES]


def face_beta(f, d, variant):
    b = [dot(duals[f][a], d) for a in range(3)]
    if variant == "paper":
        return b
    s = sum(b)
    return [x / s for x in b]


def patch(f, ctrl, d, variant):
    """The hybrid cubic at d (any vector: the face formula extended): ctrl = (f0, f1, f2, the six
    edge points in EDGES order, interior points opposite vertex 0, 1, 2)."""
    be = face_beta(f, d, variant)
    val = sum(ctrl[a] * be[a] ** 3 for a in range(3))
    for e, (a, b) in enumerate(EDGES):
        val += 3 * ctrl[3 + e] * be[a] ** 2 * be[b]
    den = be[0] * be[1] + be[1] * be[2] + be[2] * be[0]
    for m in range(3):
        a, b = [x for x in range(3) if x != m]
        if den != 0:  # at a vertex the interior term is 0 (its weights lie in [0, 1])
            val += 6 * be[0] * be[1] * be[2] * (be[a] * be[b] / den) * ctrl[9 + m]
    return val


def edge_points(f, data9, variant):
    ef = edge_factors(f)
    vs = faces[f]
    pts = []
    for e, (a, b) in enumerate(EDGES):
        s = dot(V[vs[a]], V[vs[b]]) if variant == "paper" else 1
        pts.append(s * data9[3 * a] + ef[e][0] * data9[3 * a + 1] + ef[e][1] * data9[3 * a + 2])
    return pts


def local_controls(f, data9, variant, interior=None):
    """Control values from the 9 local data (f, g_u, g_w of each face vertex); interior: the three
    interior points (None: the variant's rule)."""
    ctrl = [data9[3 * a] for a in range(3)] + edge_points(f, data9, variant)
    if interior is None:
        interior = []
        for m in range(3):
            a, b = [x for x in range(3) if x != m]
            if variant == "paper":
                c = lambda p, q: ctrl[3 + EDGES.index((p, q))]
                interior.append(A0 * (ctrl[a] + ctrl[b]) + A1 * (c(a, b) + c(b, a)) +
                                A2 * (c(a, m) + c(b, m)))
            else:
                edge_data = data9[3 * a:3 * a + 3] + data9[3 * b:3 * b + 3]
                interior.append(dot(interior_factors["normalized"][f][m], edge_data))
    return ctrl + list(interior)


def edge_normal_and_point(f, m, s):
    """The unit normal of the edge opposite local vertex m and the point at fraction s along it."""
    vs = faces[f]
    a, b = [x for x in range(3) if x != m]
    va, vb = V[vs[a]], V[vs[b]]
    return unit(cross(va, vb)), unit([(1 - s) * va[i] + s * vb[i] for i in range(3)]), a, b


def cross_derivative(f, ctrl, m, variant, s=mp.mpf(1) / 2):
    n, p, _, _ = edge_normal_and_point(f, m, s)
    return mp.diff(lambda t: patch(f, ctrl, unit([p[i] + t * n[i] for i in range(3)]), variant), 0)


def grad_along(vertex, gu, gw, n):
    return gu * dot(U[vertex], n) + gw * dot(W[vertex], n)


def unit_data(q):
    data9 = [mp.mpf(0)] * 9
    data9[q] = mp.mpf(1)
    return data9


# interior_factors[variant][f][m]: the interior point opposite local vertex m as a linear form in
# the data (f, g_u, g_w) of the edge's vertices a < b. Normalised: the cross derivative at the edge
# midpoint equals the mean of the vertex gradients along the edge normal (the cross derivative is
# affine in that point alone: the other interior points' weights vanish to first order on the edge).
interior_factors = {"normalized": [], "paper": []}
for f in range(20):
    rows = []
    for m in range(3):
        n, mid, a, b = edge_normal_and_point(f, m, mp.mpf(1) / 2)
        slope = None
        row = []
        for q in range(6):
            data9 = unit_data(3 * (a if q < 3 else b) + q % 3)
            base = local_controls(f, data9, "normalized", [mp.mpf(0)] * 3)
            d0 = cross_derivative(f, base, m, "normalized")
            if slope is None:
                one = list(base)
                one[9 + m] = mp.mpf(1)
                slope = cross_derivative(f, one, m, "normalized") - d0
            va, vb = faces[f][a], faces[f][b]
            target = (grad_along(va, data9[3 * a + 1], data9[3 * a + 2], n) +
                      grad_along(vb, data9[3 * b + 1], data9[3 * b + 2], n)) / 2
            row.append((target - d0) / slope)
        rows.append(row)
    interior_factors["normalized"].append(rows)
    interior_factors["paper"].append([
        [local_controls(f, unit_data(3 * ([x for x in range(3) if x != m][q // 3]) + q % 3),
                        "paper")[9 + m] for q in range(6)] for m in range(3)])


# ---- face location: octant + three plane tests -------------------------------------------------
def face_of(vset):
    return faces.index(tuple(sorted(vset)))


f0 = [f for f in range(20) if all(c > 0 for c in normals[f])]
assert len(f0) == 1
f0 = f0[0]
planes, across0 = [], []
for m in range(3):
    p, q = [faces[f0][x] for x in range(3) if x != m]
    n = unit(cross(V[p], V[q]))
    if dot(n, V[faces[f0][m]]) < 0:
        n = [-c for c in n]
    planes.append(n)
    across0.append([g for g in range(20) if g != f0 and {p, q} <= set(faces[g])][0])


def reflect_vertex(k, sg):
    r = [sg[i] * V[k][i] for i in range(3)]
    return [j for j in range(12) if max(abs(r[i] - V[j][i]) for i in range(3)) < mp.mpf(10) ** -30][0]


locate_faces = []
for o in range(8):
    sg = [-1 if o & (1 << i) else 1 for i in range(3)]
    locate_faces.append([face_of(reflect_vertex(k, sg) for k in faces[g]) for g in [f0] + across0])


def locate_fast(d):
    o = sum(1 << i for i in range(3) if d[i] < 0)
    ad = [abs(c) for c in d]
    f = locate_faces[o][0]
    for e in range(3):
        if dot(planes[e], ad) < 0:
            f = locate_faces[o][1 + e]
    return f


def locate(d):
    return max(range(20), key=lambda q: dot(normals[q], d))


random.seed(7)
tests = [[random.gauss(0, 1) for _ in range(3)] for _ in range(3000)]
tests += [list(v) for v in V] + [[V[i][c] + V[j][c] for c in range(3)] for i in range(12) for j in nbr[i]]
tests += [[sx * 1, 0, 0] for sx in (1, -1)] + [[0, sy, 0] for sy in (1, -1)] + [[0, 0, 1], [0, 0, -1]]
tests += [[random.gauss(0, 1), random.gauss(0, 1), 0] for _ in range(100)]
tests += [[0, random.gauss(0, 1), random.gauss(0, 1)] for _ in range(100)]
worst_out = 0
for d in tests:
    d = unit([mp.mpf(c) for c in d])
    ff = locate_fast(d)
    worst_out = max(worst_out, -min(dot(duals[ff][a], d) for a in range(3)))
    top = sorted(dot(normals[q], d) for q in range(20))
    if top[-1] - top[-2] > mp.mpf(10) ** -20:
        assert ff == locate(d), d
assert worst_out < mp.mpf(10) ** -30
log("face location: octant + 3 plane tests give the maximum-normal face on %d directions "
    "(incl. vertices, edge midpoints, coordinate planes; at ties a face containing d, "
    "min b >= -%s)" % (len(tests), mp.nstr(worst_out, 3)))


# ---- evaluation of the 36 (bezier) and 12 (linear) basis functions -----------------------------
def bezier_functions(d, variant):
    f = locate(d)
    r = [mp.mpf(0)] * 36
    for q in range(9):
        r[3 * faces[f][q // 3] + q % 3] = patch(f, local_controls(f, unit_data(q), variant), d, variant)
    return r


def linear_functions(d, variant):
    f = locate(d)
    be = face_beta(f, d, variant)
    r = [mp.mpf(0)] * 12
    for a in range(3):
        r[faces[f][a]] = be[a]
    return r


# ---- self-checks -----------------------------------------------------------------------------
def test_fn(d):
    x, y, z = d
    return 1 + x - 2 * y + x * z + 3 * y * y * z - x**3 / 2


def sphere_data(fn):
    """Values and tangential derivatives of fn at the vertices."""
    data = []
    for k in range(12):
        data.append(fn(V[k]))
        for t in (U[k], W[k]):
            data.append(mp.diff(lambda s: fn([mp.cos(s) * V[k][i] + mp.sin(s) * t[i]
                                               for i in range(3)]), 0))
    return data


def face_controls(f, data36, variant):
    return local_controls(f, [data36[3 * faces[f][a] + c] for a in range(3) for c in range(3)], variant)


data36 = sphere_data(test_fn)
random.seed(2017)
dirs = []
for _ in range(40):
    v = [random.gauss(0, 1) for _ in range(3)]
    n = sum(c * c for c in v) ** 0.5
    dirs.append([float(c / n) for c in v])
dirs += [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]


def cross_jump(f, g, data36, variant, s):
    """|jump| of the derivative across the shared edge of faces f and g at fraction s of it (the
    same point from both faces: their local edge orders agree, ascending)."""
    shared = set(faces[f]) & set(faces[g])
    mf = [x for x in range(3) if faces[f][x] not in shared][0]
    mg = [x for x in range(3) if faces[g][x] not in shared][0]
    cf, cg = face_controls(f, data36, variant), face_controls(g, data36, variant)
    nf, pf, _, _ = edge_normal_and_point(f, mf, s)
    ng, pg, _, _ = edge_normal_and_point(g, mg, s)
    assert max(abs(pf[c] - pg[c]) for c in range(3)) < mp.mpf(10) ** -35
    sign = 1 if dot(nf, ng) > 0 else -1
    return abs(cross_derivative(f, cf, mf, variant, s) - sign * cross_derivative(g, cg, mg, variant, s))


for variant in VARIANTS:
    worst = 0
    for f in range(20):
        vs = faces[f]
        ctrl = face_controls(f, data36, variant)
        for a in range(3):
            k = vs[a]
            worst = max(worst, abs(patch(f, ctrl, V[k], variant) - data36[3 * k]))
            for c, t in ((1, U[k]), (2, W[k])):
                # along the great circle from the vertex into this face: the face formula extends
                # analytically, so the two-sided derivative is the patch's
                g = mp.diff(lambda s: patch(f, ctrl, [mp.cos(s) * V[k][i] + mp.sin(s) * t[i]
                                                      for i in range(3)], variant), 0)
                worst = max(worst, abs(g - data36[3 * k + c]))
    assert worst < mp.mpf(10) ** -25, worst
    log("%s bezier: vertex values and both directional derivatives reproduced from every face "
        "(max |err| %s)" % (variant, mp.nstr(worst, 3)))

    worst_c0 = worst_c1 = 0
    fractions = [mp.mpf(1) / 7, mp.mpf(3) / 10, mp.mpf(1) / 2, mp.mpf(5) / 6]
    for f, g in edge_list:
        shared = set(faces[f]) & set(faces[g])
        cf, cg = face_controls(f, data36, variant), face_controls(g, data36, variant)
        i, j = sorted(shared)
        for s in fractions:
            d = unit([(1 - s) * V[i][c] + s * V[j][c] for c in range(3)])
            worst_c0 = max(worst_c0, abs(patch(f, cf, d, variant) - patch(g, cg, d, variant)))
        for s in (fractions if variant == "paper" else [mp.mpf(1) / 2]):
            worst_c1 = max(worst_c1, cross_jump(f, g, data36, variant, s))
    assert worst_c0 < mp.mpf(10) ** -30 and worst_c1 < mp.mpf(10) ** -25, (worst_c0, worst_c1)
    log("%s bezier: value continuous along all 30 edges (max |jump| %s), cross derivative %s "
        "(max |jump| %s)" % (variant, mp.nstr(worst_c0, 3),
                             "at 1/7, 3/10, 1/2, 5/6 of every edge" if variant == "paper"
                             else "at the edge midpoints", mp.nstr(worst_c1, 3)))
    if variant == "paper":
        # the check above fails for a wrong a0 (a0 + 1/100: C1 broken away from the vertices)
        A0 += mp.mpf(1) / 100
        jump = cross_jump(*edge_list[0], data36, variant, mp.mpf(1) / 2)
        A0 -= mp.mpf(1) / 100
        assert jump > mp.mpf(10) ** -4
        log("paper bezier: with a0 + 1/100 the cross derivative jumps by %s at the first edge's "
            "midpoint" % mp.nstr(jump, 3))
    if variant == "normalized":
        # the check above at 3/10 of an edge fails for the normalised rule (C0 there)
        jump = cross_jump(*edge_list[0], data36, variant, mp.mpf(3) / 10)
        assert jump > mp.mpf(10) ** -3
        log("normalized bezier: the cross derivative jumps by %s at 3/10 of the first edge (C0 "
            "there)" % mp.nstr(jump, 3))

    worst = 0
    if variant == "paper":
        L = lambda d: dot([mp.mpf(3) / 10, -mp.mpf(7) / 10, mp.mpf(1) / 2], d)
        lin_data = sphere_data(L)
        lin12 = [lin_data[3 * k] for k in range(12)]
        for d in dirs:
            dn = unit([mp.mpf(c) for c in d])
            worst = max(worst, abs(dot(bezier_functions(dn, variant), lin_data) - L(dn)),
                        abs(dot(linear_functions(dn, variant), lin12) - L(dn)))
        assert worst < mp.mpf(10) ** -30
        log("paper bezier and linear: a linear function of d reproduced (max |err| %s)" % mp.nstr(worst, 3))
    else:
        for d in dirs:
            dn = unit([mp.mpf(c) for c in d])
            b = bezier_functions(dn, variant)
            worst = max(worst, abs(sum(b[3 * k] for k in range(12)) - 1),
                        abs(sum(linear_functions(dn, variant)) - 1))
        assert worst < mp.mpf(10) ** -30
        log("normalized bezier and linear: the value functions sum to 1 (constants exact; max "
            "|err| %s)" % mp.nstr(worst, 3))


def cnum(v):
    """A double literal: the nearest double to v, 17 significant digits (0 for the rounding noise
    of the 40-digit arithmetic, |v| < 1e-30, in place of exact zeros)."""
    s = "%.17g" % (float(v) if abs(v) > mp.mpf(10) ** -30 else 0.0)
    return s if ("." in s or "e" in s) else s + ".0"


NAMES = {"paper": ("ambient-dice-bezier", "ambient-dice-linear"),
         "normalized": ("ambient-dice-bezier-normalized", "ambient-dice-linear-normalized")}

# ---- output ----------------------------------------------------------------------------------
if reference:
    out("# sphbasis reference values of the Ambient Dice face variants (ambient-dice-bezier and")
    out("# ambient-dice-bezier-normalized: 36 functions, ambient-dice-linear and")
    out("# ambient-dice-linear-normalized: 12). Generated by tools/gen/gen_ambient_dice_bezier.py")
    out("# (mpmath %s, 40 digits). Regenerate from the repo root with:" % mp.__version__)
    out("#   /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py --reference > tests/data/ambient_dice_bezier_reference.txt")
    out("# Self-checks passed:")
    for c in checks:
        out("#   " + c)
    out("# Lines: BASIS x y z v_0 .. v_{n-1} (directions as doubles, taken as exact; normalised)")
    for d in dirs:
        dn = unit([mp.mpf(c) for c in d])
        xyz = " ".join("%.17g" % c for c in d)
        for variant in VARIANTS:
            bz, ln = NAMES[variant]
            out("%s %s %s" % (bz, xyz, " ".join(mp.nstr(v, 25) for v in bezier_functions(dn, variant))))
            out("%s %s %s" % (ln, xyz, " ".join(mp.nstr(v, 25) for v in linear_functions(dn, variant))))
    sys.exit(0)

out("// clang-format off")
out("// GENERATED by tools/gen/gen_ambient_dice_bezier.py -- do not edit.")
out("// Regenerate (from the project root):")
out("//   /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py > include/sphbasis/basis/ambient_dice_bezier_tables.hpp")
out("//")
out("// The icosahedron of Ambient Dice (basis/ambient_dice_bezier.hpp) and the per-face constants of")
out("// its hybrid cubic Bezier triangles, each the nearest double to its value computed in mpmath at")
out("// 40 digits. Self-checks of the generator:")
for c in checks:
    out("//   " + c)
out("#pragma once")
out("")
out("namespace sphbasis::ambient_dice::tables {")
out("")


def vec_rows(name, comment, rows):
    if comment:
        out("/// %s" % comment)
    out("inline constexpr double %s[%d][3] = {" % (name, len(rows)))
    for r in rows:
        out("    {%s}," % ", ".join(cnum(c) for c in r))
    out("};")


def face_table(name, inner, rows):
    out("inline constexpr double %s[20][3][%d] = {" % (name, inner))
    for f in range(20):
        out("    {%s}," % ", ".join("{%s}" % ", ".join(cnum(c) for c in r) for r in rows[f]))
    out("};")


vec_rows("vertex", "The unit vertices v_k (2i = +a_i, 2i+1 = -a_i of ambient_dice.hpp).", V)
vec_rows("tangent_u", "u_k: the unit component of v_k's lowest-numbered neighbour orthogonal to v_k.", U)
vec_rows("tangent_w", "w_k = v_k x u_k.", W)
out("/// The faces' vertices, ascending; faces in lexicographic order.")
out("inline constexpr int face_vertex[20][3] = {")
for fc in faces:
    out("    {%d, %d, %d}," % fc)
out("};")
vec_rows("face_normal", "Unit face normals (the direction lies in the face maximising d . normal).", normals)
out("/// Rows of the inverse of the face's vertex matrix: d = sum_a (dual_a . d) v_a.")
face_table("face_dual", 3, duals)
out("/// v_a . v_b of neighbouring vertices, 1/sqrt(5): the paper rule's edge points' value factor.")
out("inline constexpr double edge_cos = %s;" % cnum(cos_edge))
out("/// Edge points c_ab = s f_a + e_u g_u(a) + e_w g_w(a), (a, b) = (0,1), (0,2), (1,0), (1,2),")
out("/// (2,0), (2,1): {e_u, e_w} = {u_a . v_b, w_a . v_b} / 3; s = edge_cos (paper) or 1 (normalised).")
out("inline constexpr double face_edge[20][6][2] = {")
for f in range(20):
    out("    {%s}," % ", ".join("{%s}" % ", ".join(cnum(c) for c in r) for r in edge_factors(f)))
out("};")
out("/// The interior point opposite local vertex m: a linear form in (f, g_u, g_w) of the edge's")
out("/// vertices a < b (the other two). Paper rule: a0 (f_a + f_b) + a1 (c_ab + c_ba) + a2 (c_am + c_bm),")
out("/// a0 = (sqrt5 - 5)/40, a1 = (11 sqrt5 - 15)/40, a2 = sqrt5/10.")
face_table("face_interior", 6, interior_factors["paper"])
out("/// The same for the normalised rule (C1 at the edge midpoints).")
face_table("face_interior_normalized", 6, interior_factors["normalized"])
out("/// Face location: unit normals of the planes through the origin and the positive octant's face's")
out("/// edges opposite its local vertex 0, 1, 2, oriented towards that face; test (|x|, |y|, |z|).")
vec_rows("locate_plane", "", planes)
out("/// Per octant (bit 0: x < 0, bit 1: y < 0, bit 2: z < 0): its face, then the faces across the")
out("/// edges of locate_plane (a direction on the negative side of plane e lies in face 1 + e).")
out("inline constexpr int locate_face[8][4] = {")
for r in locate_faces:
    out("    {%s}," % ", ".join(str(x) for x in r))
out("};")
out("")
out("}  // namespace sphbasis::ambient_dice::tables")
out("// clang-format on")
