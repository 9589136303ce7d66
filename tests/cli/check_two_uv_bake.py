#!/usr/bin/env python3
"""A texel bake on a mesh file's second UV set (docs/scene-format.md "lightmap_uv",
docs/export-format.md "UV sets"), end to end through `sphbasis bake --format gltf`.

  check_two_uv_bake.py write DIR   writes DIR/two_uv.gltf (a unit quad whose set 0 spans
                                   [0, 1]^2 and whose set 1 maps it into [0.25, 0.75] x
                                   [0.1, 0.6]) and DIR/scene.json
  check_two_uv_bake.py check OUT RES
                                   checks the bake's files: the .glb has TEXCOORD_0 and
                                   TEXCOORD_1, the lightmaps use texCoord 1, and the AO lightmap
                                   (an open quad: AO 1, stored 255 in png8) covers set 1's
                                   rectangle: 255 at every texel inside it, 0 at every texel more
                                   than the gutter (4 texels) outside it.
Prints "two-uv-ok COVERED" on success.
"""
import base64
import json
import os
import struct
import sys
import zlib


def write(d):
    pos = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]
    nrm = [0, 0, 1] * 4
    uv0 = [0, 0, 1, 0, 1, 1, 0, 1]
    uv1 = [0.25, 0.1, 0.75, 0.1, 0.75, 0.6, 0.25, 0.6]
    # glTF's v runs from the top of an image: store 1 - v (the loader, Assimp, turns it back).
    flip = lambda uv: [x if i % 2 == 0 else 1 - x for i, x in enumerate(uv)]
    idx = [0, 1, 2, 0, 2, 3]
    blobs = [struct.pack("<12f", *pos), struct.pack("<12f", *nrm),
             struct.pack("<8f", *flip(uv0)), struct.pack("<8f", *flip(uv1)),
             struct.pack("<6I", *idx)]
    data, views = b"", []
    for b in blobs:
        views.append({"buffer": 0, "byteOffset": len(data), "byteLength": len(b)})
        data += b
    acc = [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
            "min": [0, 0, 0], "max": [1, 1, 0]},
           {"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3"},
           {"bufferView": 2, "componentType": 5126, "count": 4, "type": "VEC2"},
           {"bufferView": 3, "componentType": 5126, "count": 4, "type": "VEC2"},
           {"bufferView": 4, "componentType": 5125, "count": 6, "type": "SCALAR"}]
    doc = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
           "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1,
                                                      "TEXCOORD_0": 2, "TEXCOORD_1": 3},
                                       "indices": 4}]}],
           "accessors": acc, "bufferViews": views,
           "buffers": [{"byteLength": len(data), "uri": "data:application/octet-stream;base64,"
                        + base64.b64encode(data).decode()}]}
    os.makedirs(d, exist_ok=True)
    json.dump(doc, open(os.path.join(d, "two_uv.gltf"), "w"))
    json.dump({"meshes": [{"name": "q", "file": "two_uv.gltf"}],
               "environment": {"constant": [1, 1, 1]}}, open(os.path.join(d, "scene.json"), "w"))


def read_png_grey8(path):
    """An 8-bit grey PNG (IHDR, IDAT, the five row filters of the PNG specification)."""
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w, h = 8, b"", 0, 0
    while pos < len(data):
        n, kind = struct.unpack_from(">I4s", data, pos)
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, colour = struct.unpack_from(">IIBB", body)
            assert depth == 8 and colour == 0, "expected 8-bit grey"
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, rows, prev = zlib.decompress(idat), [], [0] * w
    for y in range(h):
        f, line = raw[y * (w + 1)], list(raw[y * (w + 1) + 1:(y + 1) * (w + 1)])
        for x in range(w):
            a = line[x - 1] if x > 0 else 0
            b, c = prev[x], prev[x - 1] if x > 0 else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows


def check(out, res):
    data = open(os.path.join(out, "scene.glb"), "rb").read()
    jlen = struct.unpack_from("<I", data, 12)[0]
    doc = json.loads(data[20:20 + jlen])
    prim = doc["meshes"][0]["primitives"][0]
    assert "TEXCOORD_0" in prim["attributes"] and "TEXCOORD_1" in prim["attributes"], prim
    assert prim["extras"]["sphbasis_lightmaps"]["_AO"]["texCoord"] == 1
    assert doc["materials"][0]["occlusionTexture"]["texCoord"] == 1
    lm = json.load(open(os.path.join(out, "lightmaps.json")))
    assert lm["meshes"][0]["texCoord"] == 1
    w, h, rows = read_png_grey8(os.path.join(out, "q.ao.png"))
    assert (w, h) == (res, res)
    covered = 0
    for y in range(res):
        for x in range(res):
            u, v = (x + 0.5) / res, 1 - (y + 0.5) / res  # scene UVs: v from the bottom
            inside = 0.25 < u < 0.75 and 0.1 < v < 0.6
            far = (u < 0.25 - 5.0 / res or u > 0.75 + 5.0 / res or
                   v < 0.1 - 5.0 / res or v > 0.6 + 5.0 / res)
            if inside:
                assert rows[y][x] == 255, (x, y, rows[y][x])
                covered += 1
            if far:
                assert rows[y][x] == 0, (x, y, rows[y][x])
    print("two-uv-ok", covered)


if __name__ == "__main__":
    if sys.argv[1] == "write":
        write(sys.argv[2])
    else:
        check(sys.argv[2], int(sys.argv[3]))
