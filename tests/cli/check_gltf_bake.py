#!/usr/bin/env python3
"""Checks `sphbasis bake --format gltf` against the native bake of the same scene and settings
(docs/export-format.md): reads OUT/scene.glb with a reader written here from the glTF 2.0
specification (GLB header, JSON chunk, BIN chunk, accessors) and the native PLY files, and
requires, for every mesh, the PLY's positions and every exported attribute's values equal to
the float (the glTF stores the baked value rounded to float, as the PLY does).

Usage: check_gltf_bake.py GLTF_DIR NATIVE_DIR ATTR=PLY_PROPS... (e.g. _AO=ao
_BENT=bent_x,bent_y,bent_z); prints "gltf-bake-ok MESHES VALUES" on success.
"""
import json
import struct
import sys


def read_glb(path):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<4sII", data, 0)
    assert magic == b"glTF" and version == 2 and length == len(data), "not a GLB 2.0 file"
    jlen, jtype = struct.unpack_from("<I4s", data, 12)
    assert jtype == b"JSON"
    doc = json.loads(data[20:20 + jlen])
    blen, btype = struct.unpack_from("<I4s", data, 20 + jlen)
    assert btype == b"BIN\x00"
    return doc, data[28 + jlen:28 + jlen + blen]


def accessor(doc, binary, index):
    a = doc["accessors"][index]
    assert a["componentType"] == 5126, "expected FLOAT"
    n = {"SCALAR": 1, "VEC2": 2, "VEC3": 3}[a["type"]]
    v = doc["bufferViews"][a["bufferView"]]
    off = v.get("byteOffset", 0) + a.get("byteOffset", 0)
    vals = struct.unpack_from("<%df" % (a["count"] * n), binary, off)
    return [vals[i * n:(i + 1) * n] for i in range(a["count"])]


def read_ply(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode().split("\n")
    count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    props = [line.split()[2] for line in header if line.startswith("property float")]
    row = struct.Struct("<%df" % len(props))
    rows = [row.unpack_from(data, end + i * row.size) for i in range(count)]
    return props, rows


def main():
    doc, binary = read_glb(sys.argv[1] + "/scene.glb")
    wanted = [a.split("=") for a in sys.argv[3:]]
    checked = 0
    for mesh in doc["meshes"]:
        props, rows = read_ply(sys.argv[2] + "/" + mesh["name"] + ".ply")
        attrs = mesh["primitives"][0]["attributes"]
        pos = accessor(doc, binary, attrs["POSITION"])
        assert len(pos) == len(rows), "%s: vertex counts differ" % mesh["name"]
        for i, p in enumerate(pos):
            assert list(p) == list(rows[i][0:3]), "%s: vertex %d moved" % (mesh["name"], i)
        for name, cols in wanted:
            if name not in attrs:
                print("FAIL: %s: no attribute %s in %s" % (mesh["name"], name, sorted(attrs)))
                sys.exit(1)
            vals = accessor(doc, binary, attrs[name])
            idx = [props.index(c) for c in cols.split(",")]
            for i, v in enumerate(vals):
                want = [rows[i][k] for k in idx]
                if list(v) != want:
                    print("FAIL: %s: %s of vertex %d: %s, PLY %s" % (mesh["name"], name, i, v, want))
                    sys.exit(1)
                checked += len(want)
    print("gltf-bake-ok %d %d" % (len(doc["meshes"]), checked))


if __name__ == "__main__":
    main()
