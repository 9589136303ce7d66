#!/usr/bin/env python3
"""Checks a high-to-low vertex bake of scenes/high_to_low.json (a quad 0.1 above a disk of
radius 1.2 with a hemispherical pit of radius 0.6 at the origin; scenes/gen_high_to_low.py):
`sphbasis bake scenes/high_to_low.json --quantities ao,normal_map --out DIR`, DIR/panel.ply.

Per vertex of the quad at distance r from the axis (vertices within 0.03 of the pit's rim or
the disk's edge are skipped):
  r > 1.2 (off the disk): coverage 0, normal (0, 0, 1);
  0.6 < r < 1.2 (the flat disk): coverage 1, ao 1, normal (0, 0, 1);
  r < 0.6 (the pit): coverage 1, ao 1/2 within 4 standard errors + 0.02 (the closed form), and
  the normal (the pit's, at the point straight below: -(x, y, -sqrt(R^2 - r^2)) / R, in the
  quad's tangent frame, which is the world frame) within 1 degree.
Usage: check_high_to_low.py DIR/panel.ply; prints "high-to-low-ok PIT DISK MISSED".
"""
import math
import struct
import sys

R, OUTER = 0.6, 1.2


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def main():
    data = open(sys.argv[1], "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    props = [line.split()[2] for line in header if line.startswith("property float")]
    for p in ("ao", "ao_stderr", "normal_x", "normal_y", "normal_z", "coverage"):
        if p not in props:
            fail("no property %s in %s" % (p, props))
    row = struct.Struct("<%df" % len(props))
    ix = {p: props.index(p) for p in props}
    pit = disk = missed = 0
    for i in range(count):
        v = row.unpack_from(data, end + i * row.size)
        x, y = v[ix["x"]], v[ix["y"]]
        r = math.hypot(x, y)
        if abs(r - R) < 0.03 or abs(r - OUTER) < 0.03:
            continue
        n = (v[ix["normal_x"]], v[ix["normal_y"]], v[ix["normal_z"]])
        cov, ao, se = v[ix["coverage"]], v[ix["ao"]], v[ix["ao_stderr"]]
        where = "vertex %d at (%.3f, %.3f)" % (i, x, y)
        if r > OUTER:
            missed += 1
            if cov != 0 or n != (0.0, 0.0, 1.0):
                fail("%s: off the disk, coverage %g normal %s" % (where, cov, n))
            continue
        if cov != 1:
            fail("%s: coverage %g over the disk" % (where, cov))
        if r > R:
            disk += 1
            if ao != 1 or abs(n[2] - 1) > 1e-6:
                fail("%s: flat disk, ao %g normal %s" % (where, ao, n))
            continue
        pit += 1
        if not abs(ao - 0.5) <= 4 * se + 0.02:
            fail("%s: ao %g (stderr %g), expected 1/2" % (where, ao, se))
        want = (-x / R, -y / R, math.sqrt(R * R - r * r) / R)
        c = sum(a * b for a, b in zip(n, want)) / math.sqrt(sum(a * a for a in n))
        if math.degrees(math.acos(min(1.0, c))) > 1:
            fail("%s: normal %s, expected %s" % (where, n, want))
    if pit < 5 or disk < 5 or missed < 5:
        fail("too few vertices: pit %d disk %d missed %d" % (pit, disk, missed))
    print("high-to-low-ok %d %d %d" % (pit, disk, missed))


if __name__ == "__main__":
    main()
