#!/usr/bin/env python3
"""Test maps of `sphbasis project` (tests/cli/project_tests.cmake), written into OUTDIR:

  const_*.exr        constant RGB (1, 2, 3): lat-long 64x32, horizontal cross 64x48, six 16x16
                     faces; const_srgb.png (sRGB 188 everywhere), const.hdr (RGBE 1.0),
                     const_srgb16.png (16-bit sRGB (48000, 30000, 12000)), const.jpg (sRGB
                     (188, 100, 40), JPEG quality 100, no chroma subsampling, by Pillow).
  grad_*             one smooth linear RGB map in [0.02, 0.9], 256x128 lat-long: grad.exr (float),
                     grad8.png and grad16.png (sRGB-encoded and rounded to 8 or 16 bits), grad.jpg
                     (the 8-bit values, JPEG quality 100, 4:4:4, by Pillow).
  sh_*.exr           the radiance of known SH coefficients KNOWN (4 bands, RGB, this library's
                     convention), sampled at texel centres: lat-long 512x256 and 256x128,
                     horizontal cross 512x384, vertical cross 384x512, six 128x128 faces.
  bad_*              a 96x96 "cross", faces of unequal size, a NaN texel, a text file.

Uncompressed scanline OpenEXR (float channels B, G, R), PNG and Radiance HDR are written here
from their specifications (OpenEXR file layout; PNG, ISO/IEC 15948; Radiance RGBE) with numpy
and zlib only. Directions follow param/latlong.hpp (row 0 at +z, phi = atan2(y, x) from the
left edge) and param/cubemap.hpp (D3D/GL faces), crosses param/cube_cross.hpp.
"""
import math
import os
import struct
import sys
import zlib

import numpy as np

# Known coefficients: KNOWN[channel][k], ACN k < 16; a smooth positive-ish radiance.
KNOWN = np.array([
    [2.0, 0.3, 0.5, -0.2, 0.1, -0.15, 0.2, 0.05, -0.1, 0.04, -0.03, 0.02, 0.06, -0.05, 0.03, 0.01],
    [1.5, -0.2, 0.4, 0.3, -0.1, 0.1, -0.05, 0.12, 0.08, -0.02, 0.05, -0.04, 0.03, 0.02, -0.01, 0.05],
    [1.0, 0.1, -0.3, 0.25, 0.05, 0.2, 0.1, -0.1, 0.02, 0.03, 0.01, 0.05, -0.02, 0.04, 0.06, -0.03],
])


def sh16(x, y, z):
    """Real SH, 4 bands, ACN, no Condon-Shortley phase (the library's convention)."""
    pi = math.pi
    c0 = 0.5 / math.sqrt(pi)
    c1 = math.sqrt(3 / (4 * pi))
    c2a, c2b, c2c = 0.5 * math.sqrt(15 / pi), 0.25 * math.sqrt(5 / pi), 0.25 * math.sqrt(15 / pi)
    c3a = 0.25 * math.sqrt(35 / (2 * pi))
    c3b = 0.5 * math.sqrt(105 / pi)
    c3c = 0.25 * math.sqrt(21 / (2 * pi))
    c3d = 0.25 * math.sqrt(7 / pi)
    c3e = 0.25 * math.sqrt(105 / pi)
    return [np.full_like(x, c0), c1 * y, c1 * z, c1 * x,
            c2a * x * y, c2a * y * z, c2b * (3 * z * z - 1), c2a * x * z, c2c * (x * x - y * y),
            c3a * y * (3 * x * x - y * y), c3b * x * y * z, c3c * y * (5 * z * z - 1),
            c3d * z * (5 * z * z - 3), c3c * x * (5 * z * z - 1), c3e * z * (x * x - y * y),
            c3a * x * (x * x - 3 * y * y)]


def sh16_mp(x, y, z):
    """sh16 at one direction in mpmath arithmetic (the test's closed forms)."""
    import mpmath
    x, y, z = (mpmath.mpf(float(t)) for t in (x, y, z))
    r = mpmath.sqrt(x * x + y * y + z * z)  # the polynomials below hold on the unit sphere
    x, y, z = x / r, y / r, z / r
    pi = mpmath.pi
    c0, c1 = 1 / (2 * mpmath.sqrt(pi)), mpmath.sqrt(3 / (4 * pi))
    c2a, c2b, c2c = mpmath.sqrt(15 / pi) / 2, mpmath.sqrt(5 / pi) / 4, mpmath.sqrt(15 / pi) / 4
    c3a, c3b = mpmath.sqrt(35 / (2 * pi)) / 4, mpmath.sqrt(105 / pi) / 2
    c3c, c3d, c3e = mpmath.sqrt(21 / (2 * pi)) / 4, mpmath.sqrt(7 / pi) / 4, mpmath.sqrt(105 / pi) / 4
    return [c0, c1 * y, c1 * z, c1 * x,
            c2a * x * y, c2a * y * z, c2b * (3 * z * z - 1), c2a * x * z, c2c * (x * x - y * y),
            c3a * y * (3 * x * x - y * y), c3b * x * y * z, c3c * y * (5 * z * z - 1),
            c3d * z * (5 * z * z - 3), c3c * x * (5 * z * z - 1), c3e * z * (x * x - y * y),
            c3a * x * (x * x - 3 * y * y)]


def radiance(x, y, z):
    b = sh16(x, y, z)
    return np.stack([sum(KNOWN[c][k] * b[k] for k in range(16)) for c in range(3)], axis=-1)


def latlong_dirs(w, h):
    th = (np.arange(h) + 0.5) * math.pi / h
    ph = (np.arange(w) + 0.5) * 2 * math.pi / w
    th, ph = np.meshgrid(th, ph, indexing="ij")
    return np.sin(th) * np.cos(ph), np.sin(th) * np.sin(ph), np.cos(th)


def face_dirs(face, n):
    s = 2 * (np.arange(n) + 0.5) / n - 1
    t = s.copy()
    t, s = np.meshgrid(t, s, indexing="ij")  # t down the rows
    one = np.ones_like(s)
    p = [(one, -t, -s), (-one, -t, s), (s, one, t), (s, -one, -t), (s, -t, one), (-s, -t, -one)][face]
    r = np.sqrt(p[0] ** 2 + p[1] ** 2 + p[2] ** 2)
    return p[0] / r, p[1] / r, p[2] / r


CELLS = {"h": [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (3, 1)],
         "v": [(2, 1), (0, 1), (1, 0), (1, 2), (1, 1), (1, 3)]}


def cross(faces, n, kind):
    w, h = (4 * n, 3 * n) if kind == "h" else (3 * n, 4 * n)
    img = np.zeros((h, w, 3))
    for f, (cc, cr) in enumerate(CELLS[kind]):
        data = faces[f]
        if kind == "v" and f == 5:
            data = data[::-1, ::-1]
        img[cr * n:(cr + 1) * n, cc * n:(cc + 1) * n] = data
    return img


def write_exr(path, img):
    h, w, _ = img.shape
    img = img.astype(np.float32)

    def attr(name, typ, data):
        return name.encode() + b"\0" + typ.encode() + b"\0" + struct.pack("<i", len(data)) + data

    chl = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", 2, 0, 1, 1) for c in "BGR") + b"\0"
    box = struct.pack("<iiii", 0, 0, w - 1, h - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chl) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1.0)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1.0)) + b"\0")
    line_bytes = 3 * 4 * w
    start = len(header) + 8 * h
    offsets = b"".join(struct.pack("<Q", start + y * (8 + line_bytes)) for y in range(h))
    body = b"".join(struct.pack("<ii", y, line_bytes) + img[y, :, 2].tobytes() +
                    img[y, :, 1].tobytes() + img[y, :, 0].tobytes() for y in range(h))
    with open(path, "wb") as f:
        f.write(header + offsets + body)


def write_png(path, rgb8):
    h, w, _ = rgb8.shape
    raw = b"".join(b"\0" + rgb8[y].astype(np.uint8).tobytes() for y in range(h))

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def write_png16(path, rgb16):
    """A 16-bit RGB PNG (big-endian samples, ISO/IEC 15948), no colour-space chunks."""
    h, w, _ = rgb16.shape
    raw = b"".join(b"\0" + rgb16[y].astype(">u2").tobytes() for y in range(h))

    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)

    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 16, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


def srgb_encode(lin):
    """IEC 61966-2-1: linear [0, 1] -> encoded [0, 1]."""
    lin = np.asarray(lin, dtype=np.float64)
    return np.where(lin <= 0.0031308, 12.92 * lin, 1.055 * lin ** (1 / 2.4) - 0.055)


def grad_linear(w=256, h=128):
    """The linear content of the grad_* maps: the known radiance squeezed into [0.02, 0.9]."""
    r = radiance(*latlong_dirs(w, h))
    lo, hi = r.min(), r.max()
    return 0.02 + 0.88 * (r - lo) / (hi - lo)


def write_jpeg(path, rgb8):
    from PIL import Image  # Pillow (Debian python3-pil, a dependency of python3-matplotlib)
    Image.fromarray(rgb8.astype(np.uint8), "RGB").save(path, quality=100, subsampling=0)


def write_hdr_one(path, w, h):
    # RGBE (128, 128, 128, 129) = 1.0 exactly; flat (not run-length) scanlines.
    with open(path, "wb") as f:
        f.write(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (h, w))
        f.write(bytes([128, 128, 128, 129]) * (w * h))


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    c = np.array([1.0, 2.0, 3.0])
    write_exr(os.path.join(out, "const_equirect.exr"), np.tile(c, (32, 64, 1)))
    write_exr(os.path.join(out, "const_cross.exr"), np.tile(c, (48, 64, 1)))
    for f, name in enumerate(["px", "nx", "py", "ny", "pz", "nz"]):
        write_exr(os.path.join(out, "const_face_%s.exr" % name), np.tile(c, (16, 16, 1)))
    write_png(os.path.join(out, "const_srgb.png"), np.full((16, 32, 3), 188))
    write_hdr_one(os.path.join(out, "const.hdr"), 32, 16)
    write_png16(os.path.join(out, "const_srgb16.png"),
                np.tile(np.array([48000, 30000, 12000]), (16, 32, 1)))
    write_jpeg(os.path.join(out, "const.jpg"), np.tile(np.array([188, 100, 40]), (16, 32, 1)))
    g = grad_linear()
    write_exr(os.path.join(out, "grad.exr"), g)
    write_png(os.path.join(out, "grad8.png"), np.rint(255 * srgb_encode(g)))
    write_png16(os.path.join(out, "grad16.png"), np.rint(65535 * srgb_encode(g)).astype(np.uint16))
    write_jpeg(os.path.join(out, "grad.jpg"), np.rint(255 * srgb_encode(g)))

    for w, h in ((512, 256), (256, 128)):
        write_exr(os.path.join(out, "sh_equirect_%d.exr" % w), radiance(*latlong_dirs(w, h)))
    n = 128
    faces = [radiance(*face_dirs(f, n)) for f in range(6)]
    write_exr(os.path.join(out, "sh_hcross.exr"), cross(faces, n, "h"))
    write_exr(os.path.join(out, "sh_vcross.exr"), cross(faces, n, "v"))
    for f, name in enumerate(["px", "nx", "py", "ny", "pz", "nz"]):
        write_exr(os.path.join(out, "sh_face_%s.exr" % name), faces[f])

    write_exr(os.path.join(out, "bad_square.exr"), np.ones((96, 96, 3)))
    write_exr(os.path.join(out, "bad_face_small.exr"), np.ones((8, 8, 3)))
    nan = np.ones((32, 64, 3))
    nan[5, 7, 1] = float("nan")
    write_exr(os.path.join(out, "bad_nan.exr"), nan)
    with open(os.path.join(out, "bad_text.exr.txt"), "w") as f:
        f.write("not an image\n")
    np.save(os.path.join(out, "known.npy"), KNOWN)


if __name__ == "__main__":
    main()
