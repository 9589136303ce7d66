#!/usr/bin/env python3
"""Checks of `sphbasis project` on the maps of make_envmaps.py: check_project.py BIN MAPDIR MODE.
Prints "project-MODE-ok" when every check of MODE passes, else the first failure.

The engine modes test each layout against values and formulas of the engine's own source:
  three.js   src/math/SphericalHarmonics3.js (r160+): getAt() = 0.282095 c0 + 0.488603 (c1 y +
             c2 z + c3 x) + 1.092548 (c4 xy + c5 yz + c7 xz) + 0.315392 c6 (3z^2 - 1) +
             0.546274 c8 (x^2 - y^2) (radiance); getIrradianceAt() uses 0.886227 = pi 0.282095
             for c0, so a constant radiance L gives coefficient 0 = sqrt(4 pi) L, getAt = L and
             getIrradianceAt = pi L.
  Filament   libs/ibl/src/CubemapSH.cpp, computeIrradianceSH3Bands() and
             renderPreScaledSH3Bands(): sh.txt holds 9 RGB lines "(r, g, b); // Llm, irradiance,
             pre-scaled base" (tools/cmgen/src/cmgen.cpp outputSh, %18.15f) that a shader sums as
             sh0 + sh1 y + sh2 z + sh3 x + sh4 yx + sh5 yz + sh6 (3z^2 - 1) + sh7 zx +
             sh8 (x^2 - y^2) = E/pi; A[0] = c0/(4 pi^2) with c0 = pi makes a constant radiance L
             give sh0 = L.
  Unity      SphericalHarmonicsL2[rgb, k], k in the order of its documentation (the 0th degree
             term, the three 1st degree terms, the five 2nd degree terms); the values (the
             coefficients times the basis constants, divided by pi, of the cosine-convolved
             light) as described by pema99/SHTools (SHUtility.RawCoefficientsToUnityConvention,
             GetShaderCoefficients): ShadeSH9 = SHA.(n, 1) + SHB.(xy, yz, zz, xz) + SHC (x^2 -
             y^2) with SHA = (sh3, sh1, sh2, sh0 - sh6), SHB = (sh4, sh5, 3 sh6, sh7), SHC = sh8.
             No worked number from Unity's own documentation was found.
"""
import json
import math
import os
import re
import subprocess
import sys

import numpy as np

BIN, DIR, MODE = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_envmaps import KNOWN, sh16  # noqa: E402

FACES = [os.path.join(DIR, "sh_face_%s.exr" % f) for f in ("px", "nx", "py", "ny", "pz", "nz")]
CFACES = [os.path.join(DIR, "const_face_%s.exr" % f) for f in ("px", "nx", "py", "ny", "pz", "nz")]
CONST = np.array([1.0, 2.0, 3.0])
# Clamped-cosine factors A_l (E = sum A_l L_lm y_lm): pi, 2 pi/3, pi/4, 0.
A = [math.pi, 2 * math.pi / 3, math.pi / 4, 0.0]


def fail(msg):
    print("FAIL %s: %s" % (MODE, msg))
    sys.exit(1)


def run(*args):
    r = subprocess.run([BIN, "project"] + list(args), capture_output=True, text=True)
    if r.returncode != 0:
        fail("sphbasis project %s: rc %d: %s" % (" ".join(args), r.returncode, r.stderr))
    return r.stdout


def coeffs(*args):
    return np.array(json.loads(run(*args))["coeffs"]).T  # [channel][k]


def dirs(n=60):
    rng = np.random.default_rng(5)
    v = rng.normal(size=(n, 3))
    return v / np.linalg.norm(v, axis=1)[:, None]


def near(a, b, tol, what):
    err = float(np.max(np.abs(np.asarray(a) - np.asarray(b))))
    if not err <= tol:
        fail("%s: max error %.3g > %.3g" % (what, err, tol))
    return err


def truth(n, bands, convolve):
    """KNOWN reconstructed at unit directions n (rows), truncated to `bands`, optionally E/pi."""
    b = sh16(n[:, 0], n[:, 1], n[:, 2])
    out = np.zeros((len(n), 3))
    for k in range(bands * bands):
        l = int(math.isqrt(k))
        out += np.outer(b[k], KNOWN[:, k]) * (A[l] / math.pi if convolve else 1.0)
    return out


if MODE == "constant":
    s4pi = math.sqrt(4 * math.pi)
    for args in (["const_equirect.exr"], ["--layout", "cross", "const_cross.exr"]):
        c = coeffs(*[a if a.startswith("--") or a == "cross" else os.path.join(DIR, a) for a in args],
                   "--bands", "5")
        near(c[:, 0], s4pi * CONST, 1e-13, "band 0 of %s" % args[-1])
        near(c[:, 1:], 0, 1e-13, "bands 1-4 of %s" % args[-1])
    c = coeffs("--layout", "faces", *CFACES, "--bands", "5")
    near(c[:, 0], s4pi * CONST, 1e-13, "band 0 of faces")
    near(c[:, 1:], 0, 1e-13, "bands 1-4 of faces")
    # PNG: sRGB 188 decoded by IEC 61966-2-1; HDR: RGBE (128, 128, 128, 129) = 1.
    lin = ((188 / 255 + 0.055) / 1.055) ** 2.4
    near(coeffs(os.path.join(DIR, "const_srgb.png"))[:, 0], s4pi * lin, 1e-6, "sRGB PNG")
    near(coeffs(os.path.join(DIR, "const.hdr"))[:, 0], s4pi, 1e-13, "Radiance HDR")
elif MODE == "known":
    # Texel-centre sampling leaves O(h^2) (h the texel size): at 512 x 256 below 2e-5, and
    # halving h divides the error by about 4.
    e512 = near(coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4"), KNOWN, 2e-5,
                "lat-long 512x256 vs known")
    e256 = near(coeffs(os.path.join(DIR, "sh_equirect_256.exr"), "--bands", "4"), KNOWN, 8e-5,
                "lat-long 256x128 vs known")
    if not 3.0 < e256 / e512 < 5.0:
        fail("lat-long error ratio 256 -> 512 is %.3f, expected about 4 (order 2)" % (e256 / e512))
    near(coeffs("--layout", "cross", os.path.join(DIR, "sh_hcross.exr"), "--bands", "4"), KNOWN,
         2e-5, "horizontal cross vs known")
    near(coeffs("--basis", "sh", "--coeffs", "16", os.path.join(DIR, "sh_equirect_512.exr")),
         coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4"), 0, "--coeffs 16 = --bands 4")
elif MODE == "layouts":
    eq = coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4")
    hc = coeffs("--layout", "cross", os.path.join(DIR, "sh_hcross.exr"), "--bands", "4")
    vc = coeffs("--layout", "cross", os.path.join(DIR, "sh_vcross.exr"), "--bands", "4")
    fc = coeffs("--layout", "faces", *FACES, "--bands", "4")
    near(hc, vc, 1e-12, "horizontal vs vertical cross")
    near(hc, fc, 1e-12, "cross vs faces")
    near(eq, fc, 2e-5, "lat-long vs faces")
elif MODE == "irradiance":
    c = coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4", "--irradiance")
    want = KNOWN * np.array([A[int(math.isqrt(k))] for k in range(16)])
    near(c, want, 5e-5, "--irradiance = A_l L_lm")
elif MODE == "rotate":
    # 90 degrees about +z: a lobe at +x moves to +y, so (y, z, x) -> (x, z, -y) in band 1.
    h = math.sqrt(0.5)
    c = coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--rotate", "%.17g,0,0,%.17g" % (h, h))
    near(c[:, 1], KNOWN[:, 3], 2e-5, "rotated y")
    near(c[:, 3], -KNOWN[:, 1], 2e-5, "rotated x")
    near(c[:, 2], KNOWN[:, 2], 2e-5, "rotated z")
elif MODE == "window":
    j = json.loads(run(os.path.join(DIR, "sh_equirect_512.exr"), "--window", "sloan:0.01"))
    w = [1 / (1 + 0.01 * l * l * (l + 1) ** 2) for l in range(3)]
    near(j["window"]["weights"], w, 1e-15, "sloan weights")
    base = coeffs(os.path.join(DIR, "sh_equirect_512.exr"))
    near(np.array(j["coeffs"]).T, base * np.array([w[int(math.isqrt(k))] for k in range(9)]),
         1e-15, "windowed coefficients")
    j = json.loads(run(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4", "--window", "auto"))
    if not (j["window"]["achieved"] and j["window"]["certified_lower_bound"] >= 0):
        fail("auto window: %s" % j["window"])
elif MODE == "threejs":
    j = json.loads(run(os.path.join(DIR, "const_equirect.exr"), "--format", "threejs"))
    sh = np.array(j["sh"]).reshape(9, 3)
    near(0.282095 * sh[0], CONST, 1e-6 * 3, "three.js getAt of a constant")
    near(0.886227 * sh[0], math.pi * CONST, 1e-5, "three.js getIrradianceAt of a constant (pi L)")
    sh = np.array(json.loads(run(os.path.join(DIR, "sh_equirect_512.exr"), "--format",
                                 "threejs"))["sh"]).reshape(9, 3)
    n = dirs()
    x, y, z = n[:, 0:1], n[:, 1:2], n[:, 2:3]
    get_at = (0.282095 * sh[0] + 0.488603 * (sh[1] * y + sh[2] * z + sh[3] * x) +
              1.092548 * (sh[4] * x * y + sh[5] * y * z + sh[7] * x * z) +
              0.315392 * sh[6] * (3 * z * z - 1) + 0.546274 * sh[8] * (x * x - y * y))
    near(get_at, truth(n, 3, False), 5e-5, "three.js getAt vs the known radiance (3 bands)")
elif MODE in ("filament", "unity"):
    def read(path):
        out = run(os.path.join(DIR, path), "--format", MODE)
        if MODE == "filament":
            lines = out.splitlines()
            pat = re.compile(r"^\( *(-?\d+\.\d{15}), *(-?\d+\.\d{15}), *(-?\d+\.\d{15})\); // L(\d)(-?\d), irradiance, pre-scaled base$")
            rows = []
            for k, line in enumerate(lines):
                m = pat.match(line)
                l = int(math.isqrt(k))
                if not m or int(m.group(4)) != l or int(m.group(5)) != k - l * (l + 1):
                    fail("sh.txt line %d: %r" % (k, line))
                rows.append([float(m.group(i)) for i in (1, 2, 3)])
            if len(rows) != 9:
                fail("sh.txt has %d lines" % len(rows))
            return np.array(rows)
        sh = np.zeros((9, 3))
        found = re.findall(r"^sh\[(\d), (\d)\] = (\S+)f;$", out, re.M)
        if len(found) != 27:
            fail("expected 27 assignments sh[c, k] = v;, got %d" % len(found))
        for c, k, v in found:
            sh[int(k), int(c)] = float(v)
        return sh

    sh = read("const_equirect.exr")
    near(sh[0], CONST, 1e-8, "%s: a constant radiance L gives coefficient 0 = L" % MODE)
    near(sh[1:], 0, 1e-8, "%s: a constant has no higher coefficients" % MODE)
    sh = read("sh_equirect_512.exr")
    n = dirs()
    x, y, z = n[:, 0:1], n[:, 1:2], n[:, 2:3]
    if MODE == "filament":  # renderPreScaledSH3Bands
        e = (sh[0] + sh[1] * y + sh[2] * z + sh[3] * x + sh[4] * y * x + sh[5] * y * z +
             sh[6] * (3 * z * z - 1) + sh[7] * z * x + sh[8] * (x * x - y * y))
    else:  # ShadeSH9 with SHTools' packing
        sha = np.stack([sh[3], sh[1], sh[2], sh[0] - sh[6]])
        shb = np.stack([sh[4], sh[5], 3 * sh[6], sh[7]])
        e = (x * sha[0] + y * sha[1] + z * sha[2] + sha[3] + x * y * shb[0] + y * z * shb[1] +
             z * z * shb[2] + x * z * shb[3] + (x * x - y * y) * sh[8])
    near(e, truth(n, 3, True), 2e-5, "%s evaluation vs the known E/pi (3 bands)" % MODE)
elif MODE == "out":
    path = os.path.join(DIR, "out_test.glsl")
    text = run(os.path.join(DIR, "const_equirect.exr"), "--format", "glsl")
    run(os.path.join(DIR, "const_equirect.exr"), "--format", "glsl", "--out", path)
    if open(path).read() != text or "const vec3 sphbasis_coeffs[9] = vec3[9](" not in text:
        fail("--out differs from standard output, or not GLSL")
    for fmt, head in (("hlsl", "static const float3 sphbasis_coeffs[9] = {"),
                      ("cpp", "const float sphbasis_coeffs[9][3] = {")):
        if head not in run(os.path.join(DIR, "const_equirect.exr"), "--format", fmt):
            fail("--format %s lacks %r" % (fmt, head))
    j = json.loads(run(os.path.join(DIR, "sh_equirect_512.exr"), "--basis", "hsh", "--coeffs", "9"))
    if len(j["coeffs"]) != 9 or j["basis"] != "hsh":
        fail("--basis hsh --coeffs 9")
else:
    fail("unknown mode")
print("project-%s-ok" % MODE)
