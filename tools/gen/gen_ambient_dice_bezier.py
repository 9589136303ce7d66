#!/usr/bin/python3
"""Generates the tables of the Ambient Dice variants over the icosahedron's faces
(include/sphbasis/basis/ambient_dice_bezier_tables.hpp) and, with --reference, reference values
of their basis functions (tests/data/ambient_dice_bezier_reference.txt).

Ambient Dice (M. Iwanicki and P.-P. Sloan, "Ambient Dice", EGSR 2017, Experimental Ideas &
Implementations): values stored at the 12 icosahedron vertices, with their two directional
derivatives (the "Bezier" variant: hybrid cubic Bezier triangles over the 20 faces) or alone (the
linear interpolation that the paper's YCoCg variant uses for chroma). The construction, in
mpmath at 40 digits:
  * vertices v_k: the unit icosahedron vertices in the order of ambient_dice.hpp (2i = +a_i,
    2i+1 = -a_i); tangent frame u_k = the unit component of v_m orthogonal to v_k (m the
    vertex's lowest-numbered neighbour), w_k = v_k x u_k;
  * faces: the 20 triples of mutually neighbouring vertices, ascending, in lexicographic order;
    a direction d lies in the face maximising d . (face normal); its barycentrics beta are the
    coordinates of d in the face's vertices (rows of the inverse vertex matrix) divided by their
    sum: the planar barycentrics of d's central projection onto the face's plane, so constants
    are reproduced exactly;
  * the cubic Bezier triangle over beta has vertex points f_a, edge points
    c_ab = f_a + (1/3) grad f_a . v_b (the edge's tangent at v_a under the projection is
    v_b - (v_a . v_b) v_a, and grad f_a is tangent), so the patch reproduces the values and the
    derivatives at the vertices; and, as in Foley and Opitz's hybrid cubic Bezier triangles
    ("Hybrid cubic Bezier triangle patches", 1992), one interior point per edge, blended by
    beta_a beta_b / (beta_0 beta_1 + beta_1 beta_2 + beta_2 beta_0), that point chosen so that the
    derivative across the edge at its midpoint equals the mean of the two vertex gradients along
    the edge's normal: the same on both faces of the edge (C1 at vertices and edge midpoints,
    C0 everywhere).
Self-checks (printed in the reference file): interpolation of values and gradients of a test
function at every vertex from every face around it (numerical differentiation), continuity of
value along every edge and of the cross derivative at every edge midpoint, constants exact.

Regenerate from the repo root with:
  /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py > include/sphbasis/basis/ambient_dice_bezier_tables.hpp
  /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py --reference > tests/data/ambient_dice_bezier_reference.txt
"""
import random
import sys

import mpmath as mp

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

EDGES = [(0, 1), (0, 2), (1, 0), (1, 2), (2, 0), (2, 1)]  # control point near a, towards b


def edge_factors(f):
    """c_ab = f_a + e_u g_u(a) + e_w g_w(a) with (e_u, e_w) = (u_a . v_b, w_a . v_b) / 3."""
    vs = faces[f]
    return [[dot(U[vs[a]], V[vs[b]]) / 3, dot(W[vs[a]], V[vs[b]]) / 3] for a, b in EDGES]


def face_beta(f, d):
    b = [dot(duals[f][a], d) for a in range(3)]
    s = sum(b)
    return [x / s for x in b]


def patch(f, ctrl, d):
    """The hybrid cubic at d (any vector: the face formula extended): ctrl = (f0, f1, f2, the six
    edge points in EDGES order, interior points opposite vertex 0, 1, 2)."""
    be = face_beta(f, d)
    val = sum(ctrl[a] * be[a] ** 3 for a in range(3))
    for e, (a, b) in enumerate(EDGES):
        val += 3 * ctrl[3 + e] * be[a] ** 2 * be[b]
    den = be[0] * be[1] + be[1] * be[2] + be[2] * be[0]
    for m in range(3):
        a, b = [x for x in range(3) if x != m]
        if den != 0:  # at a vertex the interior term is 0 (its weights lie in [0, 1])
            val += 6 * be[0] * be[1] * be[2] * (be[a] * be[b] / den) * ctrl[9 + m]
    return val


def local_controls(f, data9, interior):
    """Control values from the 9 local data (f, g_u, g_w of each face vertex); interior: the three
    interior points (None: from interior_factors)."""
    ef = edge_factors(f)
    ctrl = [data9[3 * a] for a in range(3)]
    for e, (a, b) in enumerate(EDGES):
        ctrl.append(data9[3 * a] + ef[e][0] * data9[3 * a + 1] + ef[e][1] * data9[3 * a + 2])
    if interior is None:
        interior = []
        for m in range(3):
            a, b = [x for x in range(3) if x != m]
            edge_data = data9[3 * a:3 * a + 3] + data9[3 * b:3 * b + 3]
            interior.append(dot(interior_factors[f][m], edge_data))
    return ctrl + list(interior)


def edge_normal_and_mid(f, m):
    vs = faces[f]
    a, b = [x for x in range(3) if x != m]
    va, vb = V[vs[a]], V[vs[b]]
    return unit(cross(va, vb)), unit([va[i] + vb[i] for i in range(3)]), a, b


def cross_derivative(f, ctrl, m):
    n, mid, _, _ = edge_normal_and_mid(f, m)
    return mp.diff(lambda s: patch(f, ctrl, unit([mid[i] + s * n[i] for i in range(3)])), 0)


def grad_along(vertex, gu, gw, n):
    return gu * dot(U[vertex], n) + gw * dot(W[vertex], n)


# interior_factors[f][m]: the interior point opposite local vertex m as a linear form in the data
# (f, g_u, g_w) of the edge's vertices a < b: the cross derivative at the edge midpoint equals the
# mean of the vertex gradients along the edge normal. The cross derivative is affine in that point
# alone (the other interior points' weights vanish to first order on the edge).
interior_factors = []
for f in range(20):
    rows = []
    for m in range(3):
        n, mid, a, b = edge_normal_and_mid(f, m)
        slope = None
        row = []
        for q in range(6):
            data9 = [mp.mpf(0)] * 9
            data9[3 * (a if q < 3 else b) + q % 3] = mp.mpf(1)
            base = local_controls(f, data9, [mp.mpf(0)] * 3)
            d0 = cross_derivative(f, base, m)
            if slope is None:
                one = list(base)
                one[9 + m] = mp.mpf(1)
                slope = cross_derivative(f, one, m) - d0
            va, vb = faces[f][a], faces[f][b]
            target = (grad_along(va, data9[3 * a + 1], data9[3 * a + 2], n) +
                      grad_along(vb, data9[3 * b + 1], data9[3 * b + 2], n)) / 2
            row.append((target - d0) / slope)
        rows.append(row)
    interior_factors.append(rows)


# ---- evaluation of the 36 (bezier) and 12 (linear) basis functions -----------------------------
def locate(d):
    f = max(range(20), key=lambda q: dot(normals[q], d))
    return f, face_beta(f, d)


def bezier_functions(d):
    f, _ = locate(d)
    r = [mp.mpf(0)] * 36
    for q in range(9):
        data9 = [mp.mpf(0)] * 9
        data9[q] = mp.mpf(1)
        r[3 * faces[f][q // 3] + q % 3] = patch(f, local_controls(f, data9, None), d)
    return r


def linear_functions(d):
    f, be = locate(d)
    r = [mp.mpf(0)] * 12
    for a in range(3):
        r[faces[f][a]] = be[a]
    return r


# ---- self-checks -----------------------------------------------------------------------------
def test_fn(d):
    x, y, z = d
    return 1 + x - 2 * y + x * z + 3 * y * y * z - x**3 / 2


def test_data():
    """Values and tangential derivatives of test_fn at the vertices."""
    data = []
    for k in range(12):
        data.append(test_fn(V[k]))
        for t in (U[k], W[k]):
            data.append(mp.diff(lambda s: test_fn([mp.cos(s) * V[k][i] + mp.sin(s) * t[i]
                                                   for i in range(3)]), 0))
    return data


data36 = test_data()
worst = 0
for f in range(20):
    vs = faces[f]
    ctrl = local_controls(f, [data36[3 * vs[a] + c] for a in range(3) for c in range(3)], None)
    for a in range(3):
        k = vs[a]
        worst = max(worst, abs(patch(f, ctrl, V[k]) - data36[3 * k]))
        for c, t in ((1, U[k]), (2, W[k])):
            # along the great circle from the vertex into this face: the face formula extends
            # analytically, so the two-sided derivative is the patch's
            g = mp.diff(lambda s: patch(f, ctrl, [mp.cos(s) * V[k][i] + mp.sin(s) * t[i]
                                                  for i in range(3)]), 0)
            worst = max(worst, abs(g - data36[3 * k + c]))
assert worst < mp.mpf(10) ** -25, worst
log("bezier: vertex values and both directional derivatives reproduced from every face "
    "(max |err| %s)" % mp.nstr(worst, 3))

worst_c0 = worst_c1 = 0
for f in range(20):
    for g in range(f + 1, 20):
        shared = set(faces[f]) & set(faces[g])
        if len(shared) != 2:
            continue
        cf = local_controls(f, [data36[3 * faces[f][a] + c] for a in range(3) for c in range(3)], None)
        cg = local_controls(g, [data36[3 * faces[g][a] + c] for a in range(3) for c in range(3)], None)
        i, j = sorted(shared)
        for s in (mp.mpf(1) / 7, mp.mpf(1) / 2, mp.mpf(5) / 6):
            d = unit([(1 - s) * V[i][c] + s * V[j][c] for c in range(3)])
            worst_c0 = max(worst_c0, abs(patch(f, cf, d) - patch(g, cg, d)))
        mf = [x for x in range(3) if faces[f][x] not in shared][0]
        mg = [x for x in range(3) if faces[g][x] not in shared][0]
        nf, _, _, _ = edge_normal_and_mid(f, mf)
        ng, _, _, _ = edge_normal_and_mid(g, mg)
        sign = 1 if dot(nf, ng) > 0 else -1
        worst_c1 = max(worst_c1, abs(cross_derivative(f, cf, mf) - sign * cross_derivative(g, cg, mg)))
assert worst_c0 < mp.mpf(10) ** -30 and worst_c1 < mp.mpf(10) ** -25
log("bezier: value continuous along all 30 edges (max |jump| %s), cross derivative at the edge "
    "midpoints (max |jump| %s)" % (mp.nstr(worst_c0, 3), mp.nstr(worst_c1, 3)))

random.seed(2017)
dirs = []
for _ in range(40):
    v = [random.gauss(0, 1) for _ in range(3)]
    n = sum(c * c for c in v) ** 0.5
    dirs.append([float(c / n) for c in v])
dirs += [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0]]
worst = 0
for d in dirs:
    dn = unit([mp.mpf(c) for c in d])
    b = bezier_functions(dn)
    worst = max(worst, abs(sum(b[3 * k] for k in range(12)) - 1), abs(sum(linear_functions(dn)) - 1))
assert worst < mp.mpf(10) ** -30
log("bezier and linear: the value functions sum to 1 (constants exact; max |err| %s)" % mp.nstr(worst, 3))


def cnum(v):
    """A double literal: the nearest double to v, 17 significant digits."""
    s = "%.17g" % float(v)
    return s if ("." in s or "e" in s) else s + ".0"


# ---- output ----------------------------------------------------------------------------------
if reference:
    out("# sphbasis reference values of the Ambient Dice face variants (ambient-dice-bezier: 36")
    out("# functions, ambient-dice-linear: 12). Generated by tools/gen/gen_ambient_dice_bezier.py")
    out("# (mpmath %s, 40 digits). Regenerate from the repo root with:" % mp.__version__)
    out("#   /usr/bin/python3 tools/gen/gen_ambient_dice_bezier.py --reference > tests/data/ambient_dice_bezier_reference.txt")
    out("# Self-checks passed:")
    for c in checks:
        out("#   " + c)
    out("# Lines: BASIS x y z v_0 .. v_{n-1} (directions as doubles, taken as exact; normalised)")
    for d in dirs:
        dn = unit([mp.mpf(c) for c in d])
        xyz = " ".join("%.17g" % c for c in d)
        out("ambient-dice-bezier %s %s" % (xyz, " ".join(mp.nstr(v, 25) for v in bezier_functions(dn))))
        out("ambient-dice-linear %s %s" % (xyz, " ".join(mp.nstr(v, 25) for v in linear_functions(dn))))
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
    out("/// %s" % comment)
    out("inline constexpr double %s[%d][3] = {" % (name, len(rows)))
    for r in rows:
        out("    {%s}," % ", ".join(cnum(c) for c in r))
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
out("inline constexpr double face_dual[20][3][3] = {")
for f in range(20):
    out("    {%s}," % ", ".join("{%s}" % ", ".join(cnum(c) for c in r) for r in duals[f]))
out("};")
out("/// Edge points c_ab = f_a + e_u g_u(a) + e_w g_w(a), (a, b) = (0,1), (0,2), (1,0), (1,2), (2,0),")
out("/// (2,1): {e_u, e_w} = {u_a . v_b, w_a . v_b} / 3.")
out("inline constexpr double face_edge[20][6][2] = {")
for f in range(20):
    out("    {%s}," % ", ".join("{%s}" % ", ".join(cnum(c) for c in r) for r in edge_factors(f)))
out("};")
out("/// The interior point opposite local vertex m: a linear form in (f, g_u, g_w) of the edge's")
out("/// vertices a < b (the other two).")
out("inline constexpr double face_interior[20][3][6] = {")
for f in range(20):
    out("    {%s}," % ", ".join("{%s}" % ", ".join(cnum(c) for c in r) for r in interior_factors[f]))
out("};")
out("")
out("}  // namespace sphbasis::ambient_dice::tables")
out("// clang-format on")
