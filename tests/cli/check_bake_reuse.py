#!/usr/bin/env python3
"""Checks that `sphbasis render --bake BAKE` reused what `sphbasis bake --out BAKE` stored
(tests/cli/render_tests.cmake, docs/bake-format.md "Reuse by render").

Usage: check_bake_reuse.py BAKE RENDER FRESH; prints "bake-reuse-ok" when every check holds, else
one line saying what failed (exit 1).
  BAKE    the --out of `sphbasis bake` (bake.json lists its entries under "render_cache")
  RENDER  the --out of `sphbasis render --bake BAKE`
  FRESH   the --out of the same render without --bake (it baked everything itself)
Checks: every entry BAKE/bake.json lists is in BAKE/cache; RENDER's report.json ran no bake and
every bake it read has the status "from bake BAKE"; FRESH baked the same keys, and each of its cache
entries holds, byte for byte, the request, the lightmap layout and the results of BAKE's entry
(the payload of render/bake_cache.hpp's serialize() up to the pass plan, whose times differ);
and every representation image of RENDER equals FRESH's byte for byte.
"""
import json
import os
import struct
import sys


def fail(msg):
    print("bake-reuse-FAILED: " + msg)
    sys.exit(1)


class Reader:
    def __init__(self, b, pos):
        self.b, self.pos = b, pos

    def take(self, n):
        if self.pos + n > len(self.b):
            fail("truncated entry")
        self.pos += n
        return self.b[self.pos - n:self.pos]

    def u8(self):
        return self.take(1)[0]

    def u32(self):
        return struct.unpack("<I", self.take(4))[0]

    def u64(self):
        return struct.unpack("<Q", self.take(8))[0]

    def f64(self):
        return struct.unpack("<d", self.take(8))[0]

    def vec(self):
        return [self.f64() for _ in range(self.u64())]


def results_span(path):
    """(request + layout + results bytes, number of results) of a cache entry."""
    b = open(path, "rb").read()
    if b[:8] != b"SPHBFILE" or struct.unpack("<I", b[12:16])[0] != 2:
        fail("%s: not a bake cache entry" % path)
    r = Reader(b, 40)
    if r.take(8) != b"SPHBBAKE":
        fail("%s: payload without the magic SPHBBAKE" % path)
    r.u32()  # version
    start = r.pos
    r.u8(), r.u64()  # where, mesh
    r.u32(), r.u32(), r.take(r.u64()), r.u32(), r.u32(), r.u32(), r.u64(), r.f64(), r.f64(), r.u8()
    r.take(56), r.u32()  # adaptive sampling: 7 targets, max rays
    r.u32(), r.u8(), r.take(48), r.take(12)  # lightmap size, lighting dependent, grid
    r.u64()  # high to low
    r.u32(), r.u32()  # layout width, height
    r.take(180 * r.u64())  # samples
    r.take(r.u64())  # covered
    r.u64(), r.u64()
    n = r.u64()
    for _ in range(n):
        r.take(8 * 6)  # ao, ao_stderr, bent, bent_stderr
        r.vec(), r.vec()  # visibility and its stderr
        for _ in range(4):
            r.vec()  # transfer R, G, B, stderr
        r.u8()
        for _ in range(4):
            r.vec()  # irradiance
        for _ in range(4):
            r.vec()  # radiance
        for _ in range(4):
            r.vec()  # transfer matrix
        r.u8()
    return b[start:r.pos], n


def main():
    if len(sys.argv) != 4:
        fail("usage: check_bake_reuse.py BAKE RENDER FRESH")
    bake, render, fresh = sys.argv[1:]
    listed = {e["key"] for e in json.load(open(os.path.join(bake, "bake.json")))["render_cache"]}
    for key in listed:
        if not os.path.isfile(os.path.join(bake, "cache", key + ".bin")):
            fail("%s/bake.json lists %s, which is not in %s/cache" % (bake, key, bake))
    rep = json.load(open(os.path.join(render, "report.json")))
    if rep["bakes_run"] != 0:
        fail("the render ran %d bakes" % rep["bakes_run"])
    if not rep["bakes"]:
        fail("the render read no bakes")
    points = 0
    for b in rep["bakes"]:
        if b["status"] != "from bake " + bake:
            fail("bake %s: status '%s'" % (b["key"], b["status"]))
        mine, n = results_span(os.path.join(bake, "cache", b["key"] + ".bin"))
        theirs, _ = results_span(os.path.join(fresh, "cache", b["key"] + ".bin"))
        if mine != theirs:
            fail("bake %s: the bake command's values differ from render's own bake" % b["key"])
        points += n
    images = 0
    for row in rep["representations"]:
        a = open(os.path.join(render, row["exr"]), "rb").read()
        f = open(os.path.join(fresh, row["exr"]), "rb").read()
        if a != f:
            fail("%s differs from the render that baked itself" % row["exr"])
        images += 1
    print("bake-reuse-ok: %d bakes, %d points, %d images identical" % (len(rep["bakes"]), points,
                                                                      images))


main()
