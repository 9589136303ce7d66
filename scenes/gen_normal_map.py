#!/usr/bin/env python3
"""Writes scenes/bumps_normal.png, the tangent-space normal map of scenes/normal_wall.json.

Generated, not drawn: the height field h(x, y) = a cos(2 pi x / P) cos(2 pi y / P) (an egg
crate of period P texels), its normal n = normalize(-dh/dx, -dh/dy, 1) in the tangent frame
(x along u, y along v; image rows run downward, v upward), encoded per channel as
c = (n + 1) / 2 in 8 bits (render/mesh.hpp's convention: read as stored, no sRGB).
The maximum slope is a 2 pi / P. Standard library only (zlib for the PNG).

Usage: python3 scenes/gen_normal_map.py [OUT.png]   (default: beside this script)
"""
import math
import os
import struct
import sys
import zlib

SIZE = 512      # texels per side
PERIOD = 8      # texels per bump
SLOPE = 0.9     # maximum slope a 2 pi / P


def png(path, width, height, rows):
    def chunk(kind, data):
        c = struct.pack(">I", len(data)) + kind + data
        return c + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    raw = b"".join(b"\x00" + bytes(r) for r in rows)
    data = (b"\x89PNG\r\n\x1a\n" +
            chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
            chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(os.path.abspath(__file__)), "bumps_normal.png")
    k = 2 * math.pi / PERIOD
    a = SLOPE / k
    rows = []
    for row in range(SIZE):
        y = SIZE - 1 - row + 0.5  # v grows upward, rows downward
        line = []
        for col in range(SIZE):
            x = col + 0.5
            dx = -a * k * math.sin(k * x) * math.cos(k * y)
            dy = -a * k * math.cos(k * x) * math.sin(k * y)
            nx, ny, nz = -dx, -dy, 1.0
            r = math.sqrt(nx * nx + ny * ny + nz * nz)
            for c in (nx / r, ny / r, nz / r):
                line.append(max(0, min(255, int(round((c + 1) / 2 * 255)))))
        rows.append(line)
    png(out, SIZE, SIZE, rows)


if __name__ == "__main__":
    main()
