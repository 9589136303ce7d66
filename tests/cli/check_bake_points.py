#!/usr/bin/env python3
"""Checks `sphbasis bake --points -` output for a sphere hovering over a plane.

Reads the JSON lines of points on the plane z = 0 (normal +z) under a sphere of radius R with
centre (0, 0, H) (H > R: the sphere is above the horizon of every point) and checks, per point:
  ao   = 1 - H R^2 / D^3   (D = distance from the point to the centre), the cosine-weighted
         visible fraction of the hemisphere (Hill, "Hardware Accelerating Art Production",
         eq. 1-3, with the sphere's projected solid angle subtracted);
  bent = normalize(int_H w cos dw - int_cap w cos dw), where for the cap of half-angle a
         (sin a = R / D) around the unit direction c to the centre,
         int_cap w w^T dw = A c c^T + B (I - c c^T), A = 2 pi (1 - cos^3 a) / 3,
         B = pi ((1 - cos a) - (1 - cos^3 a) / 3), and int_H w cos dw = (0, 0, 2 pi / 3).
Tolerances: ao within 5 reported standard errors plus 0.004 (the tessellated sphere is
slightly smaller than the true one); bent within 0.05 per component and, when the line has
"bent_stderr" (radians), its angle to the closed form within 5 reported standard errors plus
0.01, with 0 < bent_stderr < 0.5.
Usage: check_bake_points.py H R < lines; prints "points-closed-form-ok N" on success.
       check_bake_points.py format BANDS < lines: checks the line format of
       --quantities ao,bent,visibility,transfer: the keys in order (p, n, ao, ao_stderr, bent,
       bent_stderr, visibility, visibility_stderr, transfer, transfer_stderr), "n" only for
       surface points, list lengths, no spaces; prints "points-format-ok N".
"""
import json
import math
import sys


def check_format(bands):
    n = 0
    for line in sys.stdin:
        o = json.loads(line, object_pairs_hook=lambda kv: kv)
        keys = [k for k, _ in o]
        d = dict(o)
        want = ["p", "n"] if "n" in d else ["p"]
        want += ["ao", "ao_stderr", "bent", "bent_stderr", "visibility", "visibility_stderr",
                 "transfer", "transfer_stderr"]
        if keys != want or len(d["p"]) != 3 or len(d["bent"]) != 3:
            print(f"FAIL keys {keys}")
            sys.exit(1)
        if not isinstance(d["bent_stderr"], (int, float)) or not 0 <= d["bent_stderr"] <= math.pi:
            print(f"FAIL bent_stderr in {line}")
            sys.exit(1)
        for k in ["visibility", "visibility_stderr", "transfer", "transfer_stderr"]:
            if len(d[k]) != bands * bands:
                print(f"FAIL length of {k} in {line}")
                sys.exit(1)
        if " " in line.strip():
            print("FAIL: spaces in the line")
            sys.exit(1)
        n += 1
    print(f"points-format-ok {n}")


def main():
    if sys.argv[1] == "format":
        check_format(int(sys.argv[2]))
        return
    h, r = float(sys.argv[1]), float(sys.argv[2])
    n = 0
    for line in sys.stdin:
        line = line.strip()
        if not line:
            continue
        o = json.loads(line)
        x, y, z = o["p"]
        d = math.sqrt(x * x + y * y + (h - z) ** 2)
        expect = 1 - h * r * r / d ** 3
        se = o["ao_stderr"]
        if not abs(o["ao"] - expect) <= 5 * se + 0.004:
            print(f"FAIL ao at {o['p']}: {o['ao']} vs closed form {expect} (stderr {se})")
            sys.exit(1)
        if "bent" in o:
            c = [-x / d, -y / d, h / d]
            cos_a = math.sqrt(1 - (r / d) ** 2)
            a_ = 2 * math.pi * (1 - cos_a ** 3) / 3
            b_ = math.pi * ((1 - cos_a) - (1 - cos_a ** 3) / 3)
            cn = c[2]  # c . n with n = +z
            cap = [a_ * c[i] * cn + b_ * ((1.0 if i == 2 else 0.0) - c[i] * cn) for i in range(3)]
            v = [-cap[0], -cap[1], 2 * math.pi / 3 - cap[2]]
            L = math.sqrt(sum(t * t for t in v))
            v = [t / L for t in v]
            if max(abs(v[i] - o["bent"][i]) for i in range(3)) > 0.05:
                print(f"FAIL bent at {o['p']}: {o['bent']} vs closed form {v}")
                sys.exit(1)
            if "bent_stderr" in o:
                b = o["bent"]
                cr = [b[1] * v[2] - b[2] * v[1], b[2] * v[0] - b[0] * v[2],
                      b[0] * v[1] - b[1] * v[0]]
                ang = math.atan2(math.sqrt(sum(t * t for t in cr)), sum(b[i] * v[i] for i in range(3)))
                se = o["bent_stderr"]
                if not (0 < se < 0.5 and ang <= 5 * se + 0.01):
                    print(f"FAIL bent_stderr at {o['p']}: angle {ang} to the closed form, "
                          f"stderr {se}")
                    sys.exit(1)
        n += 1
    if n == 0:
        print("FAIL: no points")
        sys.exit(1)
    print(f"points-closed-form-ok {n}")


if __name__ == "__main__":
    main()
