#!/usr/bin/env python3
"""Checks `sphbasis bake --engine gl` (Hill's depth-map bake, tools/gl/gl_bake.hpp).

check_gl_bake.py points GL.txt EMBREE.txt H R TOL
    Both files: JSON lines of `bake --points -` with ao and transfer, for points on the plane
    z = 0 (normal +z) under a sphere of radius R centred at (0, 0, H). Per point: gl ao within
    TOL of the closed form 1 - H R^2 / D^3 (D the distance to the centre; check_bake_points.py
    derives it) and of Embree's ao, each gl transfer coefficient within TOL of Embree's, and
    transfer_0 / ao = y_00 = 1 / (2 sqrt(pi)) within TOL (a cosine-weighted mean of y_00
    V is y_00 times the visible fraction). Prints "gl-points-ok N".
check_gl_bake.py layout GL/bake.json EMBREE/bake.json
    The two bakes wrote the same files with the same channels (every reader of the Embree
    bake reads the gl one); gl's bake.json has "engine" with name gl, directions, resolution
    and bias; Embree's has none. Prints "gl-layout-ok N" (N files).
"""
import json
import math
import sys


def fail(msg):
    print("FAIL " + msg)
    sys.exit(1)


def points(gl_path, em_path, h, r, tol):
    gl = [json.loads(l) for l in open(gl_path) if l.startswith("{")]
    em = [json.loads(l) for l in open(em_path) if l.startswith("{")]
    if len(gl) != len(em) or not gl:
        fail(f"{len(gl)} gl lines, {len(em)} embree lines")
    y00 = 0.28209479177387814  # 1/(2 sqrt(pi))
    for g, e in zip(gl, em):
        x, y, z = g["p"]
        d = math.sqrt(x * x + y * y + (h - z) ** 2)
        closed = 1 - h * r * r / d ** 3
        if abs(g["ao"] - closed) > tol:
            fail(f"ao {g['ao']} at {g['p']}, closed form {closed}")
        if abs(g["ao"] - e["ao"]) > tol:
            fail(f"ao {g['ao']} at {g['p']}, embree {e['ao']}")
        if len(g["transfer"]) != len(e["transfer"]):
            fail("transfer lengths differ")
        for a, b in zip(g["transfer"], e["transfer"]):
            if abs(a - b) > tol:
                fail(f"transfer {g['transfer']} at {g['p']}, embree {e['transfer']}")
        if abs(g["transfer"][0] - y00 * g["ao"]) > 1e-6:
            fail(f"transfer_0 {g['transfer'][0]} != y_00 ao at {g['p']}")
    print(f"gl-points-ok {len(gl)}")


def layout(gl_path, em_path):
    g, e = json.load(open(gl_path)), json.load(open(em_path))
    eng = g.get("engine")
    if not eng or eng.get("name") != "gl" or "engine" in e:
        fail(f"engine entries: gl {eng}, embree {e.get('engine')}")
    for k in ["directions", "resolution", "bias", "renderer"]:
        if k not in eng:
            fail(f"engine has no {k}")
    go, eo = g["outputs"], e["outputs"]
    if [(o["file"], o["channels"]) for o in go] != [(o["file"], o["channels"]) for o in eo]:
        fail("the files or channels differ")
    print(f"gl-layout-ok {len(go)}")


def main():
    if sys.argv[1] == "points":
        points(sys.argv[2], sys.argv[3], float(sys.argv[4]), float(sys.argv[5]),
               float(sys.argv[6]))
    elif sys.argv[1] == "layout":
        layout(sys.argv[2], sys.argv[3])
    else:
        fail("usage")


if __name__ == "__main__":
    main()
