#!/usr/bin/python3
"""Generates tests/data/gaunt_reference.txt: exact real Gaunt (SH tripling) coefficients.

    Gamma(l1 m1, l2 m2, l3 m3) = integral over the unit sphere of y_l1m1 y_l2m2 y_l3m3 dOmega

for the real SH of this library: orthonormal, NO Condon-Shortley phase,
    y_lm = sqrt(2) N_lm P_l^m(cos t) cos(m phi)      (m > 0)
    y_lm = sqrt(2) N_lm P_l^|m|(cos t) sin(|m| phi)  (m < 0),   y_l0 = N_l0 P_l(cos t),
P_l^m without the (-1)^m phase, N_lm = sqrt((2l+1)/(4 pi) (l-m)!/(l+m)!); y_1-1 = +0.4886 y.

Exact values come from sympy.physics.wigner.gaunt (Debian python3-sympy 1.11), which integrates
three COMPLEX harmonics Y_l^m with the Condon-Shortley phase (Y_l^-m = (-1)^m conj(Y_l^m)).
In terms of those, with a = |m| > 0:
    y_l,+a = (Y_l^-a + (-1)^a Y_l^a) / sqrt(2)
    y_l,-a = i (Y_l^-a - (-1)^a Y_l^a) / sqrt(2),        y_l0 = Y_l^0,
so Gamma = sum over mu_i = +-|m_i| with mu_1 + mu_2 + mu_3 = 0 of U_1 U_2 U_3 gaunt(l, mu).
Consequences (used by include/sphbasis/ops/sh_product.hpp and checked here): Gamma != 0 needs
l1 + l2 + l3 even, the triangle inequality, |m_k| = |m_i| + |m_j| for some labelling, and an
even number (0 or 2) of negative m. These rules are necessary, not sufficient: some triples
that pass them are exactly zero because a Wigner 3j symbol has a non-trivial zero, the first
being Gamma(2 0, 3 -2, 3 -2) = 0 from (2 3 3; 0 2 -2) = 0. They are listed with value 0.

Gamma^2 * pi is rational, so each value is also written exactly as  sign * p/q  meaning
Gamma = sign * sqrt(p / (q pi)).

Cross-checks before anything is written (the script fails if one does not hold):
  1. for every triple with l <= 3 (all of them, no selection rule applied), the exact integral
     of the product of the three real SH written as polynomials in x, y, z (monomial integrals
     over the sphere), which needs neither Wigner symbols nor the complex basis;
  2. for a seeded sample with l <= 8 and for every spot value up to l = 40, a numerical product
     quadrature (Gauss-Legendre in cos t times the uniform rule in phi, exact for these
     band-limited integrands) of y evaluated from scipy's lpmv with its Condon-Shortley phase
     removed, to 1e-12 relative to the largest value.

Output lines:  l1 m1 l2 m2 l3 m3 value exact
  * section "all": every canonical triple (ACN index i <= j <= k) with all l <= 8 that passes
    the selection rules, including the non-trivial zeros (value 0);
  * section "zero": a seeded sample of triples with l <= 8 that each violate exactly one rule;
  * section "spot": seeded nonzero triples with l up to 40, and some zeros;
  * section "count": nonzero counts of the n x n -> n tensor (ordered triples i, j, k < n^2)
    and of the symmetric pairs (i <= j, k), n = 1..9.

Usage: /usr/bin/python3 tools/gen/gen_gaunt_reference.py > tests/data/gaunt_reference.txt
(about a minute).
"""
import random
import sys
from fractions import Fraction
from functools import lru_cache
from itertools import product as iproduct

import numpy as np
import sympy as sp
from scipy.special import gammaln, lpmv
from sympy.physics.wigner import gaunt

MAX_L = 8
SPOT_MAX_L = 40
DIGITS = 25


def acn(l, m):
    return l * (l + 1) + m


def lm_of(k):
    l = int(k ** 0.5)
    while l * l > k:
        l -= 1
    while (l + 1) * (l + 1) <= k:
        l += 1
    return l, k - l * (l + 1)


def components(m):
    """The complex components (mu, U) of the real y_lm: y_lm = sum U * Y_l^mu."""
    a = abs(m)
    s2 = sp.sqrt(2)
    if m == 0:
        return [(0, sp.Integer(1))]
    if m > 0:
        return [(-a, 1 / s2), (a, (-1) ** a / s2)]
    return [(-a, sp.I / s2), (a, -sp.I * (-1) ** a / s2)]


def selection_ok(l1, m1, l2, m2, l3, m3):
    """The selection rules stated in the module docstring."""
    if (l1 + l2 + l3) % 2:
        return False
    if l3 > l1 + l2 or l3 < abs(l1 - l2):
        return False
    a1, a2, a3 = abs(m1), abs(m2), abs(m3)
    if not (a1 == a2 + a3 or a2 == a1 + a3 or a3 == a1 + a2):
        return False
    return sum(1 for m in (m1, m2, m3) if m < 0) % 2 == 0


@lru_cache(maxsize=None)
def real_gaunt(l1, m1, l2, m2, l3, m3):
    """Exact real Gaunt coefficient (sympy expression), no selection rules assumed."""
    total = sp.Integer(0)
    for (u1, c1), (u2, c2), (u3, c3) in iproduct(components(m1), components(m2), components(m3)):
        if u1 + u2 + u3 != 0:
            continue
        g = gaunt(l1, l2, l3, u1, u2, u3)
        if g != 0:
            total += c1 * c2 * c3 * g
    total = sp.expand(total)
    re, im = total.as_real_imag()
    if sp.expand(im) != 0:
        raise AssertionError("complex real Gaunt %s" % ((l1, m1, l2, m2, l3, m3),))
    return sp.radsimp(sp.expand(re))


def exact_square_form(v):
    """(sign, Fraction) with v = sign * sqrt(frac / pi)."""
    if v == 0:
        return 0, Fraction(0)
    sq = sp.expand(v * v * sp.pi)
    if not sq.is_Rational:
        raise AssertionError("Gamma^2 pi not rational: %s" % v)
    return (1 if v > 0 else -1), Fraction(int(sq.p), int(sq.q))


def fmt(v):
    if v == 0:
        return "0"
    return sp.N(v, DIGITS + 5).__format__(".%de" % (DIGITS - 1))


# ---------------------------------------------------------------- cross-check 1: polynomials
X, Y, Z = sp.symbols("x y z", real=True)


@lru_cache(maxsize=None)
def real_sh_poly(l, m):
    a = abs(m)
    n = sp.sqrt(sp.Rational(2 * l + 1, 1) / (4 * sp.pi) * sp.factorial(l - a) / sp.factorial(l + a))
    t = sp.symbols("t")
    dp = sp.diff(sp.legendre(l, t), t, a).subs(t, Z)  # P_l^a = sin^a * d^a P_l, no (-1)^a
    cplx = sp.expand((X + sp.I * Y) ** a)
    if m > 0:
        ang = sp.sqrt(2) * sp.re(cplx)
    elif m < 0:
        ang = sp.sqrt(2) * sp.im(cplx)
    else:
        ang = sp.Integer(1)
    return sp.expand(n * dp * ang)


@lru_cache(maxsize=None)
def monomial_integral(a, b, c):
    """Integral of x^a y^b z^c over the unit sphere."""
    if a % 2 or b % 2 or c % 2:
        return sp.Integer(0)
    g = sp.gamma
    return 2 * g(sp.Rational(a + 1, 2)) * g(sp.Rational(b + 1, 2)) * g(sp.Rational(c + 1, 2)) / g(
        sp.Rational(a + b + c + 3, 2)
    )


def poly_integral(p):
    total = sp.Integer(0)
    for (a, b, c), coef in sp.Poly(p, X, Y, Z).terms():
        total += coef * monomial_integral(a, b, c)
    return sp.simplify(total)


# ---------------------------------------------------------------- cross-check 2: quadrature
def real_sh_numeric(l, m, z, phi):
    a = abs(m)
    # lpmv includes the Condon-Shortley phase (-1)^a: remove it.
    p = (-1) ** a * lpmv(a, l, z)
    n = np.sqrt((2 * l + 1) / (4 * np.pi) * np.exp(gammaln(l - a + 1) - gammaln(l + a + 1)))
    if m > 0:
        return np.sqrt(2) * n * p * np.cos(a * phi)
    if m < 0:
        return np.sqrt(2) * n * p * np.sin(a * phi)
    return n * p


def quadrature_gaunt(l1, m1, l2, m2, l3, m3):
    deg = l1 + l2 + l3
    nt = deg // 2 + 1
    nphi = deg + 1
    t, wt = np.polynomial.legendre.leggauss(nt)
    phi = (np.arange(nphi) + 0.5) * (2 * np.pi / nphi)
    zz, pp = np.meshgrid(t, phi, indexing="ij")
    w = wt[:, None] * (2 * np.pi / nphi)
    f = real_sh_numeric(l1, m1, zz, pp) * real_sh_numeric(l2, m2, zz, pp) * real_sh_numeric(
        l3, m3, zz, pp
    )
    return float(np.sum(w * f))


def main():
    out = []
    w = out.append
    log = lambda *a: print(*a, file=sys.stderr)

    # 1. polynomial cross-check, every triple with l <= 3
    n3 = 16
    checked = 0
    for i in range(n3):
        for j in range(i, n3):
            for k in range(j, n3):
                (l1, m1), (l2, m2), (l3, m3) = lm_of(i), lm_of(j), lm_of(k)
                ref = poly_integral(real_sh_poly(l1, m1) * real_sh_poly(l2, m2) * real_sh_poly(l3, m3))
                g = real_gaunt(l1, m1, l2, m2, l3, m3)
                if sp.simplify(ref - g) != 0:
                    raise AssertionError("polynomial check failed %s: %s vs %s" % ((i, j, k), ref, g))
                if g != 0 and not selection_ok(l1, m1, l2, m2, l3, m3):
                    raise AssertionError("selection rule wrong for %s" % ((i, j, k),))
                checked += 1
    log("polynomial cross-check: %d triples with l <= 3 agree" % checked)

    # 2. all canonical triples with l <= 8 passing the selection rules
    n = (MAX_L + 1) ** 2
    allrows = []
    zeros_found = 0
    for i in range(n):
        for j in range(i, n):
            for k in range(j, n):
                (l1, m1), (l2, m2), (l3, m3) = lm_of(i), lm_of(j), lm_of(k)
                if not selection_ok(l1, m1, l2, m2, l3, m3):
                    continue
                g = real_gaunt(l1, m1, l2, m2, l3, m3)
                if g == 0:
                    zeros_found += 1
                allrows.append(((l1, m1, l2, m2, l3, m3), g))
    log("l <= 8: %d canonical triples pass the selection rules, %d of them are zero" % (len(allrows), zeros_found))

    # nonzero counts for n x n -> n
    nz = {}
    for row, g in allrows:
        if g != 0:
            nz[(acn(row[0], row[1]), acn(row[2], row[3]), acn(row[4], row[5]))] = True

    def counts(nb):
        nn = nb * nb
        ordered = 0
        pairs = 0
        for (i, j, k) in nz:
            if k >= nn:
                continue
            idx = (i, j, k)
            perms = set()
            for p in ((0, 1, 2), (0, 2, 1), (1, 0, 2), (1, 2, 0), (2, 0, 1), (2, 1, 0)):
                perms.add((idx[p[0]], idx[p[1]], idx[p[2]]))
            for a, b, c in perms:
                if a < nn and b < nn and c < nn:
                    ordered += 1
                    if a <= b:
                        pairs += 1
        return ordered, pairs

    # 3. seeded sample, numerical quadrature
    rng = random.Random(20240607)
    sample = rng.sample(allrows, 400)
    worst = 0.0
    for row, g in sample:
        q = quadrature_gaunt(*row)
        worst = max(worst, abs(q - float(g)))
    if worst > 1e-12:
        raise AssertionError("quadrature cross-check failed: %g" % worst)
    log("quadrature cross-check (400 triples, l <= 8): max abs diff %.2e" % worst)

    # zero sample: each violates one rule
    zero_rows = []
    tries = 0
    while len(zero_rows) < 300 and tries < 100000:
        tries += 1
        ls = [rng.randint(0, MAX_L) for _ in range(3)]
        ms = [rng.randint(-l, l) for l in ls]
        row = (ls[0], ms[0], ls[1], ms[1], ls[2], ms[2])
        if selection_ok(*row):
            continue
        zero_rows.append(row)

    # 4. spot values up to l = 40
    spot = []
    fixed = [
        (40, 0, 40, 0, 40, 0), (40, 40, 40, 40, 40, 0),
        (40, -40, 40, -40, 40, 0), (20, 20, 20, 20, 40, 40), (20, -20, 20, 20, 40, -40), (20, -20, 20, -20, 40, 40),
        (40, 1, 39, 2, 1, 1), (40, -17, 40, 23, 40, -40), (33, 33, 7, -7, 40, -40),
        (40, 39, 40, -1, 40, -40), (2, 1, 40, 39, 40, 40), (2, -1, 40, -20, 40, 21),
        (40, 20, 40, 20, 2, 0), (30, 0, 30, 0, 0, 0), (39, 5, 40, 3, 39, 8),
    ]
    for row in fixed:
        assert selection_ok(*row), row
        spot.append(row)
    while len(spot) < 120:
        l1 = rng.randint(0, SPOT_MAX_L)
        l2 = rng.randint(0, SPOT_MAX_L)
        lo, hi = abs(l1 - l2), min(l1 + l2, SPOT_MAX_L)
        if lo > hi:
            continue
        l3 = rng.randint(lo, hi)
        if (l1 + l2 + l3) % 2:
            continue
        m1 = rng.randint(-l1, l1)
        m2 = rng.randint(-l2, l2)
        a3 = rng.choice([abs(m1) + abs(m2), abs(abs(m1) - abs(m2))])
        if a3 > l3:
            continue
        m3 = a3 if ((m1 < 0) + (m2 < 0)) % 2 == 0 else -a3
        if a3 == 0 and ((m1 < 0) + (m2 < 0)) % 2:
            continue
        row = (l1, m1, l2, m2, l3, m3)
        if selection_ok(*row):
            spot.append(row)
    spot_zero = []
    while len(spot_zero) < 30:
        ls = [rng.randint(0, SPOT_MAX_L) for _ in range(3)]
        ms = [rng.randint(-l, l) for l in ls]
        row = (ls[0], ms[0], ls[1], ms[1], ls[2], ms[2])
        if not selection_ok(*row):
            spot_zero.append(row)
    spot_vals = []
    worst = 0.0
    for row in spot:
        g = real_gaunt(*row)
        q = quadrature_gaunt(*row)
        worst = max(worst, abs(q - float(g)) / max(abs(float(g)), 1e-3))
        spot_vals.append((row, g))
    if worst > 1e-11:
        raise AssertionError("spot quadrature cross-check failed: %g" % worst)
    log("quadrature cross-check (%d spot triples, l <= 40): max rel diff %.2e" % (len(spot), worst))

    def line(row, g):
        s, f = exact_square_form(g)
        ex = "0" if s == 0 else ("%s%d/%d" % ("-" if s < 0 else "+", f.numerator, f.denominator))
        return "%d %d %d %d %d %d %s %s" % (row + (fmt(g), ex))

    w("# generated by tools/gen/gen_gaunt_reference.py, do not edit.")
    w("# regenerate: /usr/bin/python3 tools/gen/gen_gaunt_reference.py > tests/data/gaunt_reference.txt")
    w("# Real Gaunt coefficients Gamma = integral of y_l1m1 y_l2m2 y_l3m3 over the sphere, real SH")
    w("# without the Condon-Shortley phase (y_1-1 = +0.4886 y), exact (sympy 1.11 gaunt, converted).")
    w("# columns: l1 m1 l2 m2 l3 m3 value exact, where exact 's p/q' means Gamma = s sqrt(p/(q pi)).")
    w("# Triples are canonical (ACN index i <= j <= k); Gamma is symmetric under permutations.")
    w("section all %d" % len(allrows))
    for row, g in allrows:
        w(line(row, g))
    w("section zero %d" % len(zero_rows))
    for row in zero_rows:
        w("%d %d %d %d %d %d 0 0" % row)
    w("section spot %d" % (len(spot_vals) + len(spot_zero)))
    for row, g in spot_vals:
        w(line(row, g))
    for row in spot_zero:
        w("%d %d %d %d %d %d 0 0" % row)
    w("section count %d" % (MAX_L + 1))
    w("# bands ordered_nonzeros symmetric_pairs(i<=j)")
    for nb in range(1, MAX_L + 2):
        o, p = counts(nb)
        w("%d %d %d" % (nb, o, p))
        log("n = %d: %d nonzero Gamma_ijk (ordered), %d with i <= j" % (nb, o, p))
    sys.stdout.write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
