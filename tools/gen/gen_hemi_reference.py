#!/usr/bin/python3
"""Generates tests/data/hemi_reference.txt: high-precision reference values of the hemispherical bases.

"The thesis" below is Ishmukhametov, "Irradiance Normal Mapping" (docs/references.md); equation
numbers are its numbers.

Bases (definitions as in the library headers, x = sin(t)cos(p), y = sin(t)sin(p), z = cos(t), and the
library's sign convention: cos(m p) functions (m > 0) are positive multiples of x-like terms,
sin(|m| p) functions (m < 0) of y-like terms; no Condon-Shortley phase):
  hsh        H_l^m = K_lm P_l^|m|(u) trig(m p), u = 2z - 1,
             K_lm^2 = (2l+1)(l-|m|)! / (2 pi (l+|m|)!) (x 2 for m != 0);
             P_l^m(u) = (1-u^2)^(m/2) d^m/du^m P_l(u) with the explicit power sum of P_l
             (Rodrigues), NOT a recurrence;
  makhotkin  M_l^m = N_lm sqrt(z) (1-u^2)^(|m|/2) P_{l-|m|}^(|m|,|m|+1)(u) trig(m p),
             N_lm^2 = 4 / (pi (1 + delta_m0) h_n), h_n the Jacobi norm; the Jacobi polynomial by its
             explicit binomial sum;
  zernike    Z_n^m = sqrt((n+1)(2 - delta_m0)/(2 pi)) R_n^|m|(rho) trig(m p), rho = sqrt(1 - z),
             R_n^m by the factorial sum (Zernike 1934); index n(n+1)/2 + (n+m)/2;
  hbasis     H1..H6 of Habel & Wimmer 2010 from the thesis' (theta, phi) forms (1.52)-(1.57);
  hbasis-mod the same with H3 = sqrt(3/(2 pi)) (1 - cos t);
  hl2        sqrt(3/(2 pi)) n . h_i with the vectors (1.18)-(1.20).
Below the horizon (z < 0) hsh, makhotkin and zernike are 0 (the library's documented outcome);
hbasis, hbasis-mod and hl2 are their polynomials.

Directions: IEEE double triples written with '%.17g' and taken as EXACT; each value is for the exact
normalisation (x, y, z)/sqrt(x^2+y^2+z^2), computed in mpmath. Working precision: mp.dps =
50 + 0.8 * degree (the explicit sums cancel ~0.6 * degree digits); every value is recomputed at
dps + 40 and the two must agree to >= 20 significant digits (relative to max(|value|, 1e-30)) or
the script aborts; the dps + 40 value is written with 25 significant digits.

Self-checks (sympy, exact; the script aborts on failure, results go to stderr and the file header):
  * the closed forms of bands 0..2 documented in hsh.hpp / makhotkin.hpp / zernike.hpp equal the
    definitions (50-digit evaluation at 12 points);
  * exact Gram matrices on the hemisphere: identity for hsh, makhotkin (3 bands), zernike
    (4 bands), hbasis (6), hl2 (3); the hbasis-mod Gram matrix (written as 'gram' lines);
  * the thesis misprints named in the headers: each printed form differs from the definition and
    its corrected form equals it;
  * mpmath.legenp (hypergeometric, Condon-Shortley phase removed) and mpmath.jacobi agree with the
    explicit sums at sample (l, m).

Output: '#' header lines, then
  'basis k l m x y z value'   (k the function's index in the basis, l = band/degree, m the order;
                               for hbasis, hbasis-mod and hl2: l = k, m = 0)
  'gram hbasis-mod i j value' (exact Gram matrix entries, 6 x 6).

Regenerate (from the repository root; Debian python3-sympy and python3-mpmath, 2 worker processes,
about 5 minutes):
  /usr/bin/python3 tools/gen/gen_hemi_reference.py > tests/data/hemi_reference.txt
"""
import math
import multiprocessing
import os
import random
import sys
import time

import mpmath
import sympy as sp
from mpmath import mp, mpf

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
# The directions' normalisation and the value format are the SH reference's (same DIGITS_OUT
# and DBL_MIN), so both files print numbers the same way.
from gen_sh_reference import _clean, _unit, fmt_value  # noqa: E402,F401

LOW_BANDS = 5  # all functions of bands 0..4 at every direction
HIGH_L = [10, 31, 63, 64, 100, 255, 511, 1000, 2047]
DPS_EXTRA = 40
REQUIRED_DIGITS = 20
DIGITS_OUT = 25
DBL_MIN = 2.2250738585072014e-308
SEED = 20100219
REGEN_CMD = "/usr/bin/python3 tools/gen/gen_hemi_reference.py > tests/data/hemi_reference.txt"


def log(*a):
    print(*a, file=sys.stderr, flush=True)


# --------------------------------------------------------------------------------------------------
# directions
# --------------------------------------------------------------------------------------------------
def _polar(t, p):
    return _unit(math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), math.cos(t))


def directions():
    """(all directions, the subset used for high degrees)."""
    d = [
        (0.0, 0.0, 1.0),  # pole
        (1.0, 0.0, 0.0),  # horizon
        (0.0, 1.0, 0.0),
        (0.6, -0.8, 0.0),
        _unit(math.cos(1.0), math.sin(1.0), 1e-3),  # near the horizon
        _unit(math.cos(-2.5), math.sin(-2.5), 1e-8),
        _polar(1e-6, 2.0),  # near the pole
        _polar(1e-3, -1.0),
        (0.0, 0.6, 0.8),  # x = 0
        (-0.8, 0.0, 0.6),  # y = 0
        (0.5, 0.5, math.sqrt(0.5)),  # x = y
        (0.48, -0.6, 0.64),  # the tests' example direction
        _polar(math.acos(0.5), 0.7),  # z = 1/2: u = 0
        (0.6, 0.0, -0.8),  # below the horizon
        (0.0, 0.0, -1.0),
        _unit(0.3, 0.4, -0.1),
    ]
    rng = random.Random(SEED)
    while len(d) < 26:
        x, y, z = rng.gauss(0, 1), rng.gauss(0, 1), rng.gauss(0, 1)
        if x * x + y * y + z * z < 1e-2:
            continue
        d.append(_unit(x, y, abs(z)))
    high = [d[i] for i in (0, 1, 4, 5, 7, 9, 12, 16, 17, 13)]
    return d, high


# --------------------------------------------------------------------------------------------------
# definitions in mpmath (explicit sums, no recurrences)
# --------------------------------------------------------------------------------------------------
def _setup(x, y, z):
    x, y, z = mpf(x), mpf(y), mpf(z)
    r = mp.sqrt(x * x + y * y + z * z)
    x, y, z = x / r, y / r, z / r
    phi = mp.atan2(y, x) if (x != 0 or y != 0) else mpf(0)
    return x, y, z, phi


def _trig(m, phi):
    if m > 0:
        return mp.cos(m * phi)
    if m < 0:
        return mp.sin(-m * phi)
    return mpf(1)


def legendre_deriv(l, m, u):
    """d^m/du^m P_l(u) from P_l(u) = 2^-l sum_k (-1)^k C(l,k) C(2l-2k,l) u^(l-2k)."""
    s = mpf(0)
    for k in range((l - m) // 2 + 1):
        p = l - 2 * k
        c = (-1) ** k * math.comb(l, k) * math.comb(2 * l - 2 * k, l) * math.perm(p, m)
        s += c * u ** (p - m)
    return s / mpf(2) ** l


def jacobi_sum(n, a, b, zz):
    """P_n^(a,b)(u), u = 2 zz - 1: sum_s C(n+a, n-s) C(n+b, s) ((u-1)/2)^s ((u+1)/2)^(n-s)."""
    s = mpf(0)
    for k in range(n + 1):
        s += math.comb(n + a, n - k) * math.comb(n + b, k) * (zz - 1) ** k * zz ** (n - k)
    return s


def zernike_radial(n, m, rho):
    s = mpf(0)
    for k in range((n - m) // 2 + 1):
        c = math.factorial(n - k) // (
            math.factorial(k) * math.factorial((n + m) // 2 - k) * math.factorial((n - m) // 2 - k))
        s += (-1) ** k * c * rho ** (n - 2 * k)
    return s


def hsh_value(l, m, x, y, z):
    x, y, z, phi = _setup(x, y, z)
    if z < 0:
        return mpf(0)
    am = abs(m)
    u = 2 * z - 1
    sect = (2 * mp.sqrt(z * (1 - z))) ** am  # (1 - u^2)^(m/2)
    k2 = mpf(2 * l + 1) / (2 * mp.pi) * mpf(math.factorial(l - am)) / math.factorial(l + am)
    if am:
        k2 *= 2
    return mp.sqrt(k2) * sect * legendre_deriv(l, am, u) * _trig(m, phi)


def makhotkin_value(l, m, x, y, z):
    x, y, z, phi = _setup(x, y, z)
    if z < 0:
        return mpf(0)
    am = abs(m)
    n, a, b = l - am, am, am + 1
    h = (mpf(2) ** (a + b + 1) / (2 * n + a + b + 1) * math.factorial(n + a) * math.factorial(n + b)
         / (math.factorial(n) * math.factorial(n + a + b)))
    nn = 4 / (mp.pi * (2 if am == 0 else 1) * h)
    sect = (2 * mp.sqrt(z * (1 - z))) ** am
    return mp.sqrt(nn) * mp.sqrt(z) * sect * jacobi_sum(n, a, b, z) * _trig(m, phi)


def zernike_value(n, m, x, y, z):
    x, y, z, phi = _setup(x, y, z)
    if z < 0:
        return mpf(0)
    am = abs(m)
    rho = mp.sqrt(1 - z)
    c = mp.sqrt(mpf(n + 1) * (1 if am == 0 else 2) / (2 * mp.pi))
    return c * zernike_radial(n, am, rho) * _trig(m, phi)


def hbasis_value(k, mod, x, y, z):
    """Thesis (1.52)-(1.58), theta/phi forms."""
    x, y, z, phi = _setup(x, y, z)
    t = mp.acos(z)
    c3 = mp.sqrt(3 / (2 * mp.pi))
    c15 = mp.sqrt(15 / (2 * mp.pi))
    if k == 0:
        return 1 / mp.sqrt(2 * mp.pi)
    if k == 1:
        return c3 * mp.sin(phi) * mp.sin(t)
    if k == 2:
        return c3 * (1 - mp.cos(t)) if mod else c3 * (2 * mp.cos(t) - 1)
    if k == 3:
        return c3 * mp.cos(phi) * mp.sin(t)
    if k == 4:
        return c15 / 2 * mp.sin(2 * phi) * mp.sin(t) ** 2
    return c15 / 2 * mp.cos(2 * phi) * mp.sin(t) ** 2


def hl2_value(k, x, y, z):
    x, y, z, _ = _setup(x, y, z)
    s2, s3, s6 = mp.sqrt(2), mp.sqrt(3), mp.sqrt(6)
    h = [(-1 / s6, -1 / s2, 1 / s3), (-1 / s6, 1 / s2, 1 / s3), (mp.sqrt(mpf(2) / 3), 0, 1 / s3)][k]
    return mp.sqrt(3 / (2 * mp.pi)) * (h[0] * x + h[1] * y + h[2] * z)


def value(basis, l, m, x, y, z):
    if basis == "hsh":
        return hsh_value(l, m, x, y, z)
    if basis == "makhotkin":
        return makhotkin_value(l, m, x, y, z)
    if basis == "zernike":
        return zernike_value(l, m, x, y, z)
    if basis == "hbasis":
        return hbasis_value(l, False, x, y, z)
    if basis == "hbasis-mod":
        return hbasis_value(l, True, x, y, z)
    return hl2_value(l, x, y, z)


def index_of(basis, l, m):
    if basis in ("hsh", "makhotkin"):
        return l * (l + 1) + m
    if basis == "zernike":
        return l * (l + 1) // 2 + (l + m) // 2
    return l


def dps_for(l):
    return 50 + (8 * l) // 10


def compute(job):
    basis, l, m, d = job
    base = dps_for(l)
    with mp.workdps(base):
        v1 = value(basis, l, m, *d)
    with mp.workdps(base + DPS_EXTRA):
        v2 = value(basis, l, m, *d)
        scale = max(abs(v2), mpf("1e-30"))  # below 1e-30 a value is 0 for double tests
        rel = abs(v1 - v2) / scale
        if rel > mpf(10) ** (-REQUIRED_DIGITS):
            raise SystemExit("precision check failed: %s l=%d m=%d d=%r rel=%s" % (basis, l, m, d, rel))
        return (basis, l, m, d, v2, float(rel))


def fmt_dir(d):
    return " ".join("%.17g" % c for c in d)


# --------------------------------------------------------------------------------------------------
# the (l, m) sets
# --------------------------------------------------------------------------------------------------
def high_ms(l, step):
    """m in {0 or +-1 (parity), +-2, +-l/4, +-l/2, +-(l-step), +-l} with the parity rule of step 2."""
    cand = {0, 1, 2, l // 4, l // 2, l - step, l}
    out = set()
    for a in cand:
        if a < 0 or a > l:
            continue
        if step == 2 and (l - a) % 2:
            a += 1 if a < l else -1
        out.add(a)
        out.add(-a)
    return sorted(out)


def jobs():
    dirs, high = directions()
    js = []
    for d in dirs:
        for basis in ("hsh", "makhotkin"):
            for l in range(LOW_BANDS):
                for m in range(-l, l + 1):
                    js.append((basis, l, m, d))
        for n in range(LOW_BANDS):
            for m in range(-n, n + 1, 2):
                js.append(("zernike", n, m, d))
        for k in range(6):
            js.append(("hbasis", k, 0, d))
            js.append(("hbasis-mod", k, 0, d))
        for k in range(3):
            js.append(("hl2", k, 0, d))
    for d in high:
        for l in HIGH_L:
            for basis in ("hsh", "makhotkin"):
                for m in high_ms(l, 1):
                    js.append((basis, l, m, d))
            for m in high_ms(l, 2):
                js.append(("zernike", l, m, d))
    return dirs, high, js


# --------------------------------------------------------------------------------------------------
# sympy self-checks: closed forms, exact Gram matrices, thesis misprints
# --------------------------------------------------------------------------------------------------
zs, ps = sp.symbols("z phi", positive=True)
X, Y, Z = sp.symbols("x y z", real=True)


class SymFn:
    """c * z^(e/2) * (4 z (1 - z))^(m/2)... as parts, so products stay polynomial: f = coef *
    sqrt(z)^ez * sect^am * poly(z) * trig(m phi), where sect = sqrt(1 - u^2) (hsh, makhotkin) or
    rho = sqrt(1 - z) (zernike)."""

    def __init__(self, coef, ez, am, sect2, poly, m):
        self.coef, self.ez, self.am, self.sect2, self.poly, self.m = coef, ez, am, sect2, poly, m

    def expr(self):
        return (self.coef * sp.sqrt(zs) ** self.ez * sp.sqrt(self.sect2) ** self.am * self.poly *
                _sym_trig(self.m))


def _sym_trig(m):
    return sp.cos(m * ps) if m > 0 else (sp.sin(-m * ps) if m < 0 else sp.Integer(1))


def sym_hsh(l, m):
    am = abs(m)
    u = sp.Symbol("u")
    d = sp.diff(sp.legendre(l, u), u, am) if am else sp.legendre(l, u)
    k2 = sp.Rational(2 * l + 1) * sp.factorial(l - am) / (2 * sp.pi * sp.factorial(l + am)) * (2 if am else 1)
    return SymFn(sp.sqrt(k2), 0, am, 4 * zs * (1 - zs), sp.expand(d.subs(u, 2 * zs - 1)), m)


def sym_makhotkin(l, m):
    am = abs(m)
    n, a, b = l - am, am, am + 1
    h = (sp.Integer(2) ** (a + b + 1) / (2 * n + a + b + 1) * sp.factorial(n + a) * sp.factorial(n + b)
         / (sp.factorial(n) * sp.factorial(n + a + b)))
    nn = 4 / (sp.pi * (2 if am == 0 else 1) * h)
    return SymFn(sp.sqrt(nn), 1, am, 4 * zs * (1 - zs), sp.expand(sp.jacobi(n, a, b, 2 * zs - 1)), m)


def sym_zernike(n, m):
    am = abs(m)
    r = sp.Symbol("r")
    R = sum((-1) ** k * sp.factorial(n - k) /
            (sp.factorial(k) * sp.factorial((n + am) // 2 - k) * sp.factorial((n - am) // 2 - k)) *
            r ** (n - 2 * k - am) for k in range((n - am) // 2 + 1))
    # R / rho^am is a polynomial in rho^2 = 1 - z
    poly = sp.expand(sp.expand(R).subs(r, sp.sqrt(1 - zs)))
    c = sp.sqrt(sp.Rational((n + 1) * (1 if am == 0 else 2)) / (2 * sp.pi))
    return SymFn(c, 0, am, 1 - zs, poly, m)


def sym_gram(fns):
    """Exact hemisphere Gram matrix of SymFn functions: phi integral first (exact), then z."""
    n = len(fns)
    G = sp.zeros(n, n)
    for i in range(n):
        for j in range(i + 1):
            a, b = fns[i], fns[j]
            tphi = sp.integrate(_sym_trig(a.m) * _sym_trig(b.m), (ps, 0, 2 * sp.pi))
            if tphi == 0:
                continue
            assert a.am == b.am and a.ez == b.ez
            zpart = (a.coef * b.coef * zs ** a.ez * a.sect2 ** a.am * a.poly * b.poly)
            G[i, j] = G[j, i] = sp.nsimplify(sp.simplify(tphi * sp.integrate(sp.expand(zpart), (zs, 0, 1))))
    return G


def sym_xyz_gram(fns):
    """Exact hemisphere Gram matrix of polynomials in x, y, z (z = cos t in [0, 1])."""
    st = sp.sqrt(1 - zs ** 2)
    sub = {X: st * sp.cos(ps), Y: st * sp.sin(ps), Z: zs}
    n = len(fns)
    G = sp.zeros(n, n)
    for i in range(n):
        for j in range(i + 1):
            e = sp.expand(sp.expand_trig((fns[i] * fns[j]).subs(sub)))
            v = sp.integrate(sp.integrate(e, (ps, 0, 2 * sp.pi)), (zs, 0, 1))
            G[i, j] = G[j, i] = sp.nsimplify(sp.simplify(v))
    return G


# Closed forms documented in the headers, as functions of (x, y, z) on the unit hemisphere.
def closed_forms():
    s = sp.sqrt
    pi = sp.pi
    q = s(Z / (1 + Z))
    hsh = {
        (0, 0): 1 / s(2 * pi), (1, -1): s(6 / pi) * Y * q, (1, 0): s(3 / (2 * pi)) * (2 * Z - 1),
        (1, 1): s(6 / pi) * X * q, (2, -2): 2 * s(30 / pi) * X * Y * Z / (1 + Z),
        (2, -1): s(30 / pi) * Y * (2 * Z - 1) * q, (2, 0): s(5 / (2 * pi)) * (6 * Z ** 2 - 6 * Z + 1),
        (2, 1): s(30 / pi) * X * (2 * Z - 1) * q, (2, 2): s(30 / pi) * Z * (X ** 2 - Y ** 2) / (1 + Z),
    }
    mak = {
        (0, 0): s(Z / pi), (1, -1): 2 * s(3 / pi) * Y * Z / s(1 + Z), (1, 0): s(2 / pi) * s(Z) * (3 * Z - 2),
        (1, 1): 2 * s(3 / pi) * X * Z / s(1 + Z), (2, -2): 4 * s(15 / pi) * X * Y * Z * s(Z) / (1 + Z),
        (2, -1): s(3 / pi) * Y * Z * (10 * Z - 6) / s(1 + Z),
        (2, 0): s(3 / pi) * s(Z) * (10 * Z ** 2 - 12 * Z + 3),
        (2, 1): s(3 / pi) * X * Z * (10 * Z - 6) / s(1 + Z),
        (2, 2): 2 * s(15 / pi) * Z * s(Z) * (X ** 2 - Y ** 2) / (1 + Z),
    }
    zer = {
        (0, 0): 1 / s(2 * pi), (1, -1): s(2 / pi) * Y / s(1 + Z), (1, 1): s(2 / pi) * X / s(1 + Z),
        (2, -2): 2 * s(3 / pi) * X * Y / (1 + Z), (2, 0): s(3 / (2 * pi)) * (1 - 2 * Z),
        (2, 2): s(3 / pi) * (X ** 2 - Y ** 2) / (1 + Z),
    }
    return hsh, mak, zer


def thesis_printed():
    """(name, printed form, the derived function's key, corrected form) in (x, y, z) or (t, p)."""
    s = sp.sqrt
    pi = sp.pi
    t, p = sp.symbols("t p", real=True)
    ct = sp.cos(t)
    return [
        # (label, basis, (l, m), printed-as-function-of-(X,Y,Z,t,p), corrected)
        ("(1.23) H_1-1 right side", "hsh", (1, -1), -s(6 / pi) * Y * s(Z / (1 + Z)),
         s(6 / pi) * Y * s(Z / (1 + Z))),
        ("(1.26) H_2-2 left side", "hsh", (2, -2), s(30 / pi) * (ct ** 2 - ct) * sp.sin(2 * p),
         s(30 / pi) * (ct - ct ** 2) * sp.sin(2 * p)),
        ("(1.30) H_21 left side", "hsh", (2, 1),
         s(30 / pi) * s((1 - ct) * ct) * (2 * ct - 1) * sp.sin(p),
         s(30 / pi) * s((1 - ct) * ct) * (2 * ct - 1) * sp.cos(p)),
        ("(1.32) H_22 left side", "hsh", (2, 2), s(30 / pi) * sp.cos(2 * p) * (ct ** 2 - ct),
         s(30 / pi) * sp.cos(2 * p) * (ct - ct ** 2)),
        ("(1.33) M_00 right side", "makhotkin", (0, 0), Z / s(pi), s(Z) / s(pi)),
        ("(1.34) M_-1^1 label (cos phi)", "makhotkin", (1, -1),
         s(3 / pi) * sp.cos(p) * s(ct) * s(1 - (2 * ct - 1) ** 2),
         s(3 / pi) * sp.sin(p) * s(ct) * s(1 - (2 * ct - 1) ** 2)),
        ("(1.42) M_20 right side", "makhotkin", (2, 0),
         s(3 / pi) * s(Z) * (1 + 16 * (Z - 1) + 10 * (Z - 1) ** 2),
         s(3 / pi) * s(Z) * (1 + 8 * (Z - 1) + 10 * (Z - 1) ** 2)),
        ("(1.48) Z_11 right side", "zernike", (1, 1), -s(2 / pi) * X / s(1 + Z), s(2 / pi) * X / s(1 + Z)),
        ("(1.47) Z_1-1 sign (convention)", "zernike", (1, -1), -s(2 / pi) * Y / s(1 + Z),
         s(2 / pi) * Y / s(1 + Z)),
        ("(1.49) Z_2-2 sign (convention)", "zernike", (2, -2), -2 * s(3 / pi) * X * Y / (1 + Z),
         2 * s(3 / pi) * X * Y / (1 + Z)),
    ], t, p


def self_checks():
    notes = []
    rng = random.Random(7)
    pts = []
    for _ in range(12):
        zz = sp.Rational(rng.randint(1, 999), 1000)
        ph = sp.Rational(rng.randint(-3141, 3141), 1000)
        pts.append((zz, ph))
    symdef = {"hsh": sym_hsh, "makhotkin": sym_makhotkin, "zernike": sym_zernike}

    def at(expr, zz, ph, t=None, p=None):
        st = sp.sqrt(1 - zz ** 2)
        sub = {X: st * sp.cos(ph), Y: st * sp.sin(ph), Z: zz, zs: zz, ps: ph}
        if t is not None:
            sub[t] = sp.acos(zz)
            sub[p] = ph
        return sp.N(expr.subs(sub), 50)

    # 1. closed forms
    worst = 0
    for name, table in zip(("hsh", "makhotkin", "zernike"), closed_forms()):
        for (l, m), cf in table.items():
            f = symdef[name](l, m).expr()
            for zz, ph in pts:
                dv = abs(at(f, zz, ph) - at(cf, zz, ph))
                worst = max(worst, dv)
                if dv > 1e-40:
                    raise SystemExit("closed form of %s (%d, %d) differs: %s" % (name, l, m, dv))
    notes.append("closed forms of bands 0..2 (hsh, makhotkin, zernike) equal the definitions "
                 "(max |diff| %.1e at 12 points, 50 digits)" % worst)
    log(notes[-1])

    # 2. exact Gram matrices
    fh = [sym_hsh(l, m) for l in range(3) for m in range(-l, l + 1)]
    fm = [sym_makhotkin(l, m) for l in range(3) for m in range(-l, l + 1)]
    fz = [sym_zernike(n, m) for n in range(4) for m in range(-n, n + 1, 2)]
    for name, fns in (("hsh", fh), ("makhotkin", fm), ("zernike", fz)):
        G = sym_gram(fns)
        if G != sp.eye(len(fns)):
            raise SystemExit("exact Gram matrix of %s is not the identity:\n%s" % (name, G))
    s = sp.sqrt
    pi = sp.pi
    c3, c15 = s(sp.Rational(3, 2) / pi), s(sp.Rational(15, 2) / pi)
    hb = [1 / s(2 * pi), c3 * Y, c3 * (2 * Z - 1), c3 * X, c15 * X * Y, c15 / 2 * (X ** 2 - Y ** 2)]
    hbm = list(hb)
    hbm[2] = c3 * (1 - Z)
    hl = [s(sp.Rational(3, 2) / pi) * (h[0] * X + h[1] * Y + h[2] * Z) for h in
          [(-1 / s(6), -1 / s(2), 1 / s(3)), (-1 / s(6), 1 / s(2), 1 / s(3)), (s(sp.Rational(2, 3)), 0, 1 / s(3))]]
    if sym_xyz_gram(hb) != sp.eye(6):
        raise SystemExit("exact Gram matrix of hbasis is not the identity")
    if sym_xyz_gram(hl) != sp.eye(3):
        raise SystemExit("exact Gram matrix of hl2 is not the identity")
    gmod = sym_xyz_gram(hbm)
    expect = sp.eye(6)
    expect[0, 2] = expect[2, 0] = s(3) / 2
    if sp.simplify(gmod - expect) != sp.zeros(6, 6):
        raise SystemExit("hbasis-mod Gram matrix is not the closed form:\n%s" % gmod)
    notes.append("exact Gram matrices: identity for hsh (3 bands), makhotkin (3 bands), zernike "
                 "(4 bands), hbasis (6), hl2 (3); hbasis-mod = identity + sqrt(3)/2 at (0, 2), (2, 0)")
    log(notes[-1])

    # 3. thesis misprints
    items, t, p = thesis_printed()
    for label, basis, (l, m), printed, corrected in items:
        f = symdef[basis](l, m).expr()
        dp = max(abs(at(f, zz, ph) - at(printed, zz, ph, t, p)) for zz, ph in pts)
        dc = max(abs(at(f, zz, ph) - at(corrected, zz, ph, t, p)) for zz, ph in pts)
        if not (dp > 1e-3 and dc < 1e-40):
            raise SystemExit("thesis check failed for %s: printed diff %s, corrected diff %s" % (label, dp, dc))
    notes.append("thesis misprints confirmed (printed form differs, corrected form equals the "
                 "definition): " + "; ".join(it[0] for it in items))
    log(notes[-1])

    # 4. mpmath's own special functions against the explicit sums
    worst = mpf(0)
    with mp.workdps(60):
        for (l, m, zz) in [(3, 1, mpf("0.3")), (10, 4, mpf("0.8")), (40, 17, mpf("0.05")), (120, 60, mpf("0.6"))]:
            u = 2 * zz - 1
            a = (-1) ** m * mpmath.legenp(l, m, u, type=2)
            with mp.workdps(60 + l):
                b = (1 - u * u) ** (mpf(m) / 2) * legendre_deriv(l, m, u)
            worst = max(worst, abs(a - b) / abs(b))
            j1 = mpmath.jacobi(l - m, m, m + 1, u)
            with mp.workdps(60 + l):
                j2 = jacobi_sum(l - m, m, m + 1, zz)
            worst = max(worst, abs(j1 - j2) / abs(j2))
    if worst > mpf("1e-40"):
        raise SystemExit("mpmath.legenp/jacobi disagree with the explicit sums: %s" % worst)
    notes.append("mpmath.legenp (phase removed) and mpmath.jacobi agree with the explicit sums "
                 "(max rel diff %s)" % mpmath.nstr(worst, 2))
    log(notes[-1])
    return notes, gmod


def main():
    t0 = time.time()
    notes, gmod = self_checks()
    dirs, high, js = jobs()
    log("%d values, %.0f s for the self-checks" % (len(js), time.time() - t0))
    # Expensive (high-degree) jobs first so the pool stays balanced.
    order = sorted(range(len(js)), key=lambda i: -js[i][1])
    with multiprocessing.Pool(2) as pool:
        res = pool.map(compute, [js[i] for i in order], chunksize=4)
    out = [None] * len(js)
    for i, r in zip(order, res):
        out[i] = r
    worst = max(r[5] for r in out)
    log("max relative disagreement dps vs dps+%d: %.2g; %.0f s" % (DPS_EXTRA, worst, time.time() - t0))

    w = sys.stdout.write
    w("# sphbasis reference values of the hemispherical bases (hsh, makhotkin, zernike, hbasis,\n")
    w("# hbasis-mod, hl2). Generated by tools/gen/gen_hemi_reference.py (sympy %s, mpmath %s).\n"
      % (sp.__version__, mpmath.__version__))
    w("# Regenerate from the repo root with:\n#   %s\n" % REGEN_CMD)
    w("# Definitions: see the generator's docstring and the library headers; x = sin(t)cos(p),\n")
    w("#   y = sin(t)sin(p), z = cos(t); cos(m p) functions (m > 0) ~ +x, sin(|m| p) (m < 0) ~ +y.\n")
    w("#   Below the horizon hsh/makhotkin/zernike are 0, hbasis/hbasis-mod/hl2 their polynomials.\n")
    w("# Directions: doubles printed with %.17g, taken as EXACT; values for the exact normalisation.\n")
    w("# Values: explicit sums (Rodrigues power sum, Jacobi binomial sum, Zernike factorial sum) in\n")
    w("#   mpmath at dps = 50 + 0.8 l and dps + %d; they agree to >= %d digits (max observed relative\n"
      % (DPS_EXTRA, REQUIRED_DIGITS))
    w("#   disagreement %.1e). Written: the dps + %d value, %d significant digits; |v| < DBL_MIN -> 0.\n"
      % (worst, DPS_EXTRA, DIGITS_OUT))
    w("# Self-checks passed:\n")
    for n in notes:
        w("#   %s\n" % n)
    w("# Sets: all functions of bands 0..%d at %d directions; l (n for zernike) in %s with m in\n"
      % (LOW_BANDS - 1, len(dirs), HIGH_L))
    w("#   {0, +-1, +-2, +-l/4, +-l/2, +-(l-1), +-l} (zernike: adjusted to the parity of n) at %d\n" % len(high))
    w("#   directions. %d values.\n" % len(out))
    w("# Format: basis k l m x y z value   (k the function's index; hbasis*/hl2: l = k, m = 0)\n")
    w("#         gram hbasis-mod i j value (exact hemisphere Gram matrix)\n")
    for basis, l, m, d, v, _ in out:
        w("%s %d %d %d %s %s\n" % (basis, index_of(basis, l, m), l, m, fmt_dir(d), fmt_value(v)))
    for i in range(6):
        for j in range(6):
            w("gram hbasis-mod %d %d %s\n" % (i, j, mpmath.nstr(mpf(str(sp.N(gmod[i, j], 40))), DIGITS_OUT,
                                                              min_fixed=0, max_fixed=0)))


if __name__ == "__main__":
    main()
