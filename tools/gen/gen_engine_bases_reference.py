#!/usr/bin/python3
"""Generates tests/data/engine_bases_reference.txt: reference values of the engine bases
(ambient cube, ambient dice, ZH3, ZH3 hallucinated, L1 SH with the Geomerics reconstruction).

Definitions as in the library headers (include/sphbasis/basis/ambient_cube.hpp, ambient_dice.hpp,
zh3.hpp, sh_l1_nonlinear.hpp), implemented here independently from their mathematical definitions
in mpmath at 40 digits:
  * constants: each library constant from its closed form (sympy, exact, printed to 20 digits);
  * ambient cube: max(+-n_i, 0)^2 and its exact Gram matrix on the sphere (sympy integrals);
  * ambient dice: the 12 icosahedron vertices (+-1, +-t, 0) cyclic, normalised, the lobe
    0.7 c^2/2 + 0.3 (5/6) c^4 on the vertex's hemisphere; self-checks: partition of unity at
    every direction and the exact sums sum_i c_i^2 = 2, sum_i c_i^4 = 6/5 over the 6 axes;
  * ZH3: the zonal coefficient as the band-2 part projected onto Y20(a . n) by a product rule
    exact for the degree-4 integrand (NOT the addition-theorem formula of the header);
  * Geomerics: the model of the header; self-checks by quadrature: its mean over the sphere is R0
    and its first moment along R1 is R0 (1 - a) p / (p + 2) (tanh-sinh quadrature).
Directions and coefficients are doubles written with '%.17g' and taken as exact.

Regenerate from the repo root with:
  /usr/bin/python3 tools/gen/gen_engine_bases_reference.py > tests/data/engine_bases_reference.txt
"""
import sys

import mpmath as mp
import sympy as sp

mp.mp.dps = 40


def out(line):
    sys.stdout.write(line + "\n")


def fmt(v):
    return mp.nstr(mp.mpf(v), 25, min_fixed=-5, max_fixed=5)


def log(msg):
    sys.stderr.write(msg + "\n")
    checks.append(msg)


checks = []

# ---- constants -------------------------------------------------------------------------------
s5 = sp.sqrt(5)
t = (s5 - 1) / 2
A = 1 / sp.sqrt(1 + t**2)
consts = {
    "ambient_dice.axis_a": A,
    "ambient_dice.axis_b": t * A,
    "zh3.y00": 1 / (2 * sp.sqrt(sp.pi)),
    "zh3.y1": sp.sqrt(3 / (4 * sp.pi)),
    "zh3.y20": sp.sqrt(5 / (16 * sp.pi)),
    "zh3.y2xy": sp.sqrt(15 / (4 * sp.pi)),
    "zh3.y2xx": sp.sqrt(15 / (16 * sp.pi)),
    "zh3.sqrt4pi_5": sp.sqrt(4 * sp.pi / 5),
    "sh_l1_nonlinear.half_y1": sp.sqrt(3 / (4 * sp.pi)) / 2,
}
assert sp.simplify(A - 2 / sp.sqrt(10 - 2 * s5)) == 0
log("closed form: axis_a = 1/sqrt(1 + t^2) = 2/sqrt(10 - 2 sqrt(5)) (sympy)")

# ---- directions ------------------------------------------------------------------------------
dirs = []
import random


random.seed(25)
for _ in range(24):
    while True:
        v = [random.gauss(0, 1) for _ in range(3)]
        n = sum(c * c for c in v) ** 0.5
        if n > 1e-3:
            break
    dirs.append([float(c / n) for c in v])
dirs += [[0.0, 0.0, 1.0], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0], [0.0, -1.0, 0.0],
         [float(A.evalf(30)), float((t * A).evalf(30)), 0.0]]


def unit(d):
    v = [mp.mpf(c) for c in d]
    n = mp.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


# ---- ambient cube ----------------------------------------------------------------------------
def cube(n):
    r = []
    for c in n:
        r += [c * c if c >= 0 else mp.mpf(0), c * c if c < 0 else mp.mpf(0)]
    return r


X, Y, Z = sp.symbols("x y z", real=True)
th, ph = sp.symbols("theta phi", real=True)
# Gram on the sphere: exact integrals over the positive octant regions.
sub = {X: sp.sin(th) * sp.cos(ph), Y: sp.sin(th) * sp.sin(ph), Z: sp.cos(th)}


def octant_int(expr):
    # integral of expr over x>0 (and y>0 if expr has y) on the sphere, by symmetry from the octant
    e = expr.subs(sub) * sp.sin(th)
    return sp.integrate(sp.integrate(e, (ph, 0, sp.pi / 2)), (th, 0, sp.pi / 2))


g_same = sp.nsimplify(4 * octant_int(X**4))  # x > 0: four octants
g_cross = sp.nsimplify(2 * octant_int(X**2 * Y**2))  # x > 0, y > 0: two octants
assert sp.simplify(g_same - 2 * sp.pi / 5) == 0 and sp.simplify(g_cross - sp.pi / 15) == 0
log("ambient cube Gram on the sphere: diagonal 2 pi/5, different axes pi/15, same axis 0 (sympy)")

# ---- ambient dice ----------------------------------------------------------------------------
tn = mp.mpf((mp.sqrt(5) - 1) / 2)
An = 1 / mp.sqrt(1 + tn * tn)
Bn = tn * An
axes = [[An, Bn, 0], [-An, Bn, 0], [0, An, Bn], [0, -An, Bn], [Bn, 0, An], [Bn, 0, -An]]
# The 12 vertices: the 6 axes and their antipodes; check they are the icosahedron's (+-1, +-t, 0)
verts = []
for a in axes:
    verts += [a, [-c for c in a]]
icos = set()
for a in ([1, tn, 0], [0, 1, tn], [tn, 0, 1]):
    for s1 in (1, -1):
        for s2 in (1, -1):
            v = list(a)
            nz = [i for i in range(3) if v[i] != 0]
            v[nz[0]] *= s1
            v[nz[1]] *= s2
            icos.add(tuple(round(float(c * An), 15) + 0.0 for c in v))
assert icos == set(tuple(round(float(c), 15) + 0.0 for c in v) for v in verts)
log("ambient dice: the 12 vertices are the normalised icosahedron (+-1, +-t, 0) cyclic")


def lobe(c):
    return mp.mpf("0.7") * c * c / 2 + mp.mpf("0.3") * mp.mpf(5) / 6 * c**4


def dice(n):
    r = []
    for a in axes:
        c = sum(x * y for x, y in zip(a, n))
        r += [lobe(c) if c > 0 else mp.mpf(0), lobe(c) if c < 0 else mp.mpf(0)]
    return r


worst = 0
for d in dirs:
    n = unit(d)
    s2 = sum(sum(x * y for x, y in zip(a, n)) ** 2 for a in axes)
    s4 = sum(sum(x * y for x, y in zip(a, n)) ** 4 for a in axes)
    worst = max(worst, abs(s2 - 2), abs(s4 - mp.mpf(6) / 5), abs(sum(dice(n)) - 1))
assert worst < mp.mpf(10) ** -35
log("ambient dice: sum c^2 = 2, sum c^4 = 6/5, partition of unity (max |err| %s)" % mp.nstr(worst, 3))

# ---- SH of bands 0..2 (library convention) ---------------------------------------------------
pi = mp.pi


def sh9(n):
    x, y, z = n
    c1 = mp.sqrt(3 / (4 * pi))
    c2 = mp.sqrt(15 / (4 * pi))
    return [1 / (2 * mp.sqrt(pi)), c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z,
            mp.sqrt(5 / (16 * pi)) * (3 * z * z - 1), c2 * x * z, mp.sqrt(15 / (16 * pi)) * (x * x - y * y)]


def y20(tt):
    return mp.sqrt(5 / (16 * pi)) * (3 * tt * tt - 1)


def sphere_quad(f):
    # f(n) integrated over the sphere, exact for polynomials of degree <= 5 in (x, y, z):
    # 3-point Gauss-Legendre in z times 12 uniform azimuths (trigonometric degree < 12)
    nodes = [(-mp.sqrt(mp.mpf(3) / 5), mp.mpf(5) / 9), (mp.mpf(0), mp.mpf(8) / 9),
             (mp.sqrt(mp.mpf(3) / 5), mp.mpf(5) / 9)]
    total = mp.mpf(0)
    for u, w in nodes:
        for j in range(12):
            p = 2 * pi * (j + mp.mpf(1) / 2) / 12
            sn = mp.sqrt(1 - u * u)
            total += w * (2 * pi / 12) * f([sn * mp.cos(p), sn * mp.sin(p), u])
    return total


def zonal_quad(g):
    # the integral over the sphere of a function of t = d . n only: 2 pi int_{-1}^{1} g(t) dt
    return 2 * pi * mp.quad(g, [-1, 1])


def zh3_fit(e):
    l1 = [e[3], e[1], e[2]]
    ln = mp.sqrt(sum(c * c for c in l1))
    a = [c / ln for c in l1] if ln > 0 else [0, 0, 1]

    def band2(n):
        v = sh9(n)
        return sum(e[k] * v[k] for k in range(4, 9))

    zc = sphere_quad(lambda n: band2(n) * y20(sum(p * q for p, q in zip(a, n))))
    return [mp.mpf(c) for c in e[:4]] + [zc], a


def zh3_eval(c, a, n):
    v = sh9(n)
    return sum(c[k] * v[k] for k in range(4)) + c[4] * y20(sum(p * q for p, q in zip(a, n)))


def halluc(e):
    e0 = mp.mpf(e[0])
    l1 = mp.sqrt(sum(mp.mpf(c) ** 2 for c in e[1:4]))
    z = 0
    if e0 != 0:
        r = min(mp.mpf(3) / 2 * l1 / abs(e0), mp.sqrt(3))
        z = e0 / 4 * (mp.mpf("0.08") * r + mp.mpf("0.6") * r * r)
    l1v = [e[3], e[1], e[2]]
    a = [mp.mpf(c) / l1 for c in l1v] if l1 > 0 else [0, 0, 1]
    return [mp.mpf(c) for c in e[:4]] + [z], a


def geomerics(c, n):
    e0 = mp.mpf(c[0])
    h = [mp.sqrt(3 / (4 * pi)) / 2 * mp.mpf(c[k]) for k in (3, 1, 2)]
    ln = mp.sqrt(sum(v * v for v in h))
    if e0 == 0:
        return e0 / (2 * mp.sqrt(pi)) + 2 * sum(p * q for p, q in zip(h, n))
    s = 1 if e0 > 0 else -1
    R0 = abs(e0) / (2 * mp.sqrt(pi))
    r = ln / R0
    p = 1 + 2 * r
    aa = (1 - r) / (1 + r)
    d = [s * v / ln for v in h] if ln > 0 else [0, 0, 0]
    q = (1 + sum(u * v for u, v in zip(d, n))) / 2
    return s * R0 * (aa + (1 - aa) * (p + 1) * q**p)


coeff_sets = [
    [1.0, 0.25, -0.5, 0.75, 0.1, -0.2, 0.3, -0.15, 0.05],
    [0.5, -0.3, 0.2, 0.1, -0.25, 0.05, -0.1, 0.2, 0.3],
    [2.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0],
    [-0.7, 0.4, 0.1, -0.2, 0.3, 0.1, -0.2, 0.05, -0.1],
    [1.0, 0.0, 0.0, 0.0, 0.3, 0.0, 0.0, 0.0, 0.0],
    [0.1, 0.5, -0.4, 0.3, 0.0, 0.2, 0.0, 0.0, 0.1],  # |L1| beyond a delta's: r clamped
]

# Geomerics self-checks: mean and first moment by quadrature.
for c in coeff_sets[:3]:
    e0 = mp.mpf(c[0])
    h = [mp.sqrt(3 / (4 * pi)) / 2 * mp.mpf(c[k]) for k in (3, 1, 2)]
    ln = mp.sqrt(sum(v * v for v in h))
    R0 = e0 / (2 * mp.sqrt(pi))
    r = ln / R0
    p, aa = 1 + 2 * r, (1 - r) / (1 + r)
    d = [v / ln for v in h]
    # in a frame whose third axis is d the model depends on t = d . n only
    g = lambda tt: R0 * (aa + (1 - aa) * (p + 1) * ((1 + tt) / 2) ** p)
    mean = zonal_quad(g) / (4 * pi)
    mom = zonal_quad(lambda tt: g(tt) * tt) / (4 * pi)
    # and the model itself is that function of d . n
    for dd in dirs[:5]:
        n = unit(dd)
        assert abs(geomerics(c, n) - g(sum(u * v for u, v in zip(d, n)))) < mp.mpf(10) ** -30
    assert abs(mean - R0) < mp.mpf(10) ** -20, (mean, R0)
    assert abs(mom - R0 * (1 - aa) * p / (p + 2)) < mp.mpf(10) ** -20
log("geomerics: mean R0 and first moment R0 (1 - a) p/(p + 2) by tanh-sinh quadrature (3 sets, 1e-20)")

# ---- output ----------------------------------------------------------------------------------
out("# sphbasis reference values of the engine bases (ambient-cube, ambient-dice, zh3,")
out("# zh3-hallucinate, sh-l1-nonlinear). Generated by tools/gen/gen_engine_bases_reference.py")
out("# (sympy %s, mpmath %s). Regenerate from the repo root with:" % (sp.__version__, mp.__version__))
out("#   /usr/bin/python3 tools/gen/gen_engine_bases_reference.py > tests/data/engine_bases_reference.txt")
out("# Self-checks passed:")
for c in checks:
    out("#   " + c)
out("# Formats (directions and coefficients are exact doubles, values 25 digits):")
out("#   const NAME VALUE                         a library constant from its closed form")
out("#   gram-ambient-cube I J VALUE              exact Gram matrix on the sphere")
out("#   BASIS x y z v_0 .. v_{n-1}               ambient-cube (6), ambient-dice (12)")
out("#   FIT c_0 .. c_8 stored_0 .. stored_{k-1}  zh3 (5 stored; zonal by quadrature), zh3-hallucinate (5 after hallucination)")
out("#   EVAL set x y z value                     zh3, zh3-hallucinate, sh-l1-nonlinear at coefficient set `set`")
for k, v in consts.items():
    out("const %s %s" % (k, fmt(sp.N(v, 40))))
for i in range(6):
    for j in range(6):
        if i == j:
            v = 2 * mp.pi / 5
        elif i // 2 == j // 2:
            v = mp.mpf(0)
        else:
            v = mp.pi / 15
        out("gram-ambient-cube %d %d %s" % (i, j, fmt(v)))
for d in dirs:
    n = unit(d)
    out("ambient-cube %s %s" % (" ".join("%.17g" % c for c in d), " ".join(fmt(v) for v in cube(n))))
for d in dirs:
    n = unit(d)
    out("ambient-dice %s %s" % (" ".join("%.17g" % c for c in d), " ".join(fmt(v) for v in dice(n))))
fits = {}
for si, c in enumerate(coeff_sets):
    z, a = zh3_fit([mp.mpf(v) for v in c])
    hz, ha = halluc(c[:4])
    fits[si] = (z, a, hz, ha)
    out("fit-zh3 %d %s %s" % (si, " ".join("%.17g" % v for v in c), " ".join(fmt(v) for v in z)))
    out("fit-zh3-hallucinate %d %s %s" % (si, " ".join("%.17g" % v for v in c[:4]), " ".join(fmt(v) for v in hz)))
for si, c in enumerate(coeff_sets):
    z, a, hz, ha = fits[si]
    for d in dirs[::3]:
        n = unit(d)
        ds = " ".join("%.17g" % v for v in d)
        out("eval-zh3 %d %s %s" % (si, ds, fmt(zh3_eval(z, a, n))))
        out("eval-zh3-hallucinate %d %s %s" % (si, ds, fmt(zh3_eval(hz, ha, n))))
        out("eval-sh-l1-nonlinear %d %s %s" % (si, ds, fmt(geomerics(c[:4], n))))
