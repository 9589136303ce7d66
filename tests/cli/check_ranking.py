#!/usr/bin/env python3
"""Checks that two reports of `sphbasis render` (one scene at two image sizes) rank their
representations alike.

Usage: check_ranking.py SMALL/report.json LARGE/report.json [CHECK...]
  below=A:B       A's FLIP is above B's (A ranks below B) in both reports
  tie=A:B:R       A and B are within a relative FLIP difference R in both reports (their order
                  may differ: a tie)
  crossing=A:B    A and B may change order (a known crossing, named in the test's comment)
Every other pair of representations present in both reports must keep its order (by FLIP, the
reports' ranking). Prints every pair that changed order with both sizes' FLIP values, then
"ranking-ok" when every check passes.
"""
import itertools
import json
import sys


def load(path):
    with open(path) as f:
        doc = json.load(f)
    return {r["name"]: r["flip"] for r in doc["representations"]}, doc


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    small, ds = load(sys.argv[1])
    large, dl = load(sys.argv[2])
    names = sorted(set(small) & set(large))
    if len(names) < 2:
        sys.exit("check_ranking.py: fewer than two representations in both reports")
    exempt = set()
    ok = True
    for check in sys.argv[3:]:
        kind, _, arg = check.partition("=")
        parts = arg.split(":")
        if kind == "below":
            a, b = parts
            for label, flips in (("small", small), ("large", large)):
                if not flips[a] > flips[b]:
                    print("FAIL %s: %s (FLIP %.4g) does not rank below %s (%.4g)"
                          % (label, a, flips[a], b, flips[b]))
                    ok = False
        elif kind == "tie":
            a, b, r = parts[0], parts[1], float(parts[2])
            exempt.add(frozenset((a, b)))
            for label, flips in (("small", small), ("large", large)):
                gap = abs(flips[a] - flips[b]) / min(flips[a], flips[b])
                if gap > r:
                    print("FAIL %s: %s and %s differ by %.3g, more than the tie %.3g"
                          % (label, a, b, gap, r))
                    ok = False
        elif kind == "crossing":
            exempt.add(frozenset(parts))
        else:
            sys.exit("check_ranking.py: unknown check %r" % check)
    swapped = 0
    for a, b in itertools.combinations(names, 2):
        if (small[a] < small[b]) == (large[a] < large[b]):
            continue
        swapped += 1
        known = frozenset((a, b)) in exempt
        print("%s %s / %s: %dx%d %.4g / %.4g, %dx%d %.4g / %.4g"
              % ("known" if known else "FAIL", a, b, ds["width"], ds["height"], small[a],
                 small[b], dl["width"], dl["height"], large[a], large[b]))
        ok = ok and known
    print("%d of %d pairs changed order" % (swapped, len(names) * (len(names) - 1) // 2))
    if ok:
        print("ranking-ok")


if __name__ == "__main__":
    main()
