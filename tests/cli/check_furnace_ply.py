#!/usr/bin/env python3
"""Checks a white-furnace bake: `sphbasis bake SCENE --quantities transfer --bands 1` of a scene
whose surfaces all have albedo 1 under a constant unit sky, written as PLY (--target vertices).

The exit radiance at every vertex is B = sqrt(4 pi) transfer_0 (the sky's only SH coefficient is
l_0 = sqrt(4 pi), y_0 = 1 / (2 sqrt(pi))), and it must be 1 (every path escapes with its full
weight). Checked per vertex: |B - 1| <= 5 sqrt(4 pi) transfer_stderr_0 + 1e-6 (the PLY's float
rounding). Usage: check_furnace_ply.py FILE.ply; prints "furnace-ok N MEAN MIN" on success.
"""
import math
import struct
import sys


def main():
    data = open(sys.argv[1], "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    props = [line.split()[2] for line in header if line.startswith("property float")]
    if "transfer_0" not in props or "transfer_stderr_0" not in props:
        print("FAIL: no transfer_0 / transfer_stderr_0 in", props)
        sys.exit(1)
    row = struct.Struct("<%df" % len(props))
    t, s = props.index("transfer_0"), props.index("transfer_stderr_0")
    l0 = math.sqrt(4 * math.pi)
    total, low = 0.0, 1e300
    for i in range(count):
        v = row.unpack_from(data, end + i * row.size)
        b, se = l0 * v[t], l0 * v[s]
        if not abs(b - 1) <= 5 * se + 1e-6:
            print("FAIL: vertex %d: B = %.6f, stderr %.6f" % (i, b, se))
            sys.exit(1)
        total += b
        low = min(low, b)
    print("furnace-ok %d %.6f %.6f" % (count, total / count, low))


if __name__ == "__main__":
    main()
