#!/usr/bin/env python3
"""Checks of `sphbasis project` on the maps of make_envmaps.py: check_project.py BIN MAPDIR MODE.
Prints "project-MODE-ok" when every check of MODE passes, else the first failure.

The engine modes test each layout against values and formulas of the engine's own source:
  three.js   src/math/SphericalHarmonics3.js (r160+): getAt() = 0.282095 c0 + 0.488603 (c1 y +
             c2 z + c3 x) + 1.092548 (c4 xy + c5 yz + c7 xz) + 0.315392 c6 (3z^2 - 1) +
             0.546274 c8 (x^2 - y^2) (radiance); getIrradianceAt() uses 0.886227 = pi 0.282095
             for c0 (getIrradianceAt = 0.886227 c0 + 2 0.511664 (c1 y + c2 z + c3 x) + 2 0.429043
             (c4 xy + c5 yz + c7 xz) + c6 (0.743125 z^2 - 0.247708) + 0.429043 c8 (x^2 - y^2),
             the irradiance E), so a constant radiance L gives coefficient 0 = sqrt(4 pi) L,
             getAt = L and getIrradianceAt = pi L.
  Filament   libs/ibl/src/CubemapSH.cpp, computeIrradianceSH3Bands() and
             renderPreScaledSH3Bands(): sh.txt holds 9 RGB lines "(r, g, b); // Llm, irradiance,
             pre-scaled base" (tools/cmgen/src/cmgen.cpp outputSh, %18.15f) that a shader sums as
             sh0 + sh1 y + sh2 z + sh3 x + sh4 yx + sh5 yz + sh6 (3z^2 - 1) + sh7 zx +
             sh8 (x^2 - y^2) = E/pi; A[0] = c0/(4 pi^2) with c0 = pi makes a constant radiance L
             give sh0 = L.
  Unity      SphericalHarmonicsL2[rgb, k] (Unity C# reference source,
             Runtime/Export/Math/SphericalHarmonicsL2.bindings.cs: field rgb * 9 + k), k in the
             order of the Unity Manual, "Light Probes: technical information": L00, L1-1 (y),
             L10 (z), L11 (x), L2-2 (xy), L2-1 (yz), L20 (zz), L21 (xz), L22 (xx - yy). The
             values, per the C# reference source (UnityEngine.LightTransport.PostProcessing.
             IProbePostProcessor.ConvertToUnityFormat): irradiance SH with "the SH standard
             normalization terms folded into them" and "divided by Pi". The shader constants, per
             GetShaderConstantsFromNormalizedSH (the C# reference source's LookDev view, "copy/
             paste from SHConstantCache.cpp"): SHA = (sh3, sh1, sh2, sh0 - sh6), SHB = (sh4, sh5,
             3 sh6, sh7), SHC = sh8, and UnityCG.cginc's ShadeSH9 = SHA.(n, 1) + SHB.(xy, yz, zz,
             xz) + SHC (x^2 - y^2). Worked value: a constant radiance L gives ShadeSH9 = L (E = pi L).

Frames (mode "frames" and the engine modes): a map direction d is shown by the engine at the
world direction w(d), computed here from each engine's own image-sampling formula (not from the
signed permutations of project.cpp):
  three.js   equirectUv(): u = atan(w.z, w.x)/2pi + 1/2, v = asin(w.y)/pi + 1/2 (v = 1 at the top
             row); cube textures: textureCube(envMap, (flipEnvMap w.x, w.y, w.z)), flipEnvMap = -1.
  Filament   cmgen equirectangularToCubemap(): u = (atan2(s.x, s.z)/pi + 1)/2, row = (1 -
             asin(s.y) 2/pi)/2, then mirrorCubemap() (on by default): w = (-s.x, s.y, s.z).
  Unity      Skybox-Panoramic ToRadialCoords(): u = 1/2 - atan2(w.z, w.x)/2pi, v = 1 - acos(w.y)/pi
             (v = 1 at the top row); cubemaps are sampled with the world direction (w = d).
"""
import json
import math
import os
import re
import subprocess
import sys

import mpmath
import numpy as np

BIN, DIR, MODE = sys.argv[1], sys.argv[2], sys.argv[3]
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_envmaps import KNOWN, sh16, sh16_mp  # noqa: E402

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


def map_uv(n):
    """Our lat-long: u = phi/2pi from +x, t = theta/pi from the top row (param/latlong.hpp)."""
    return (np.arctan2(n[:, 1], n[:, 0]) / (2 * math.pi)) % 1.0, np.arccos(np.clip(n[:, 2], -1, 1)) / math.pi


def world(engine, layout, n):
    """The engine's world direction of the map direction n (rows), from its sampling code."""
    if layout != "equirect":
        return n * np.array([1.0, 1.0, 1.0] if engine in ("unity", "sphbasis") else [-1.0, 1.0, 1.0])
    if engine == "sphbasis":
        return n
    u, t = map_uv(n)
    lat = math.pi * (0.5 - t)  # elevation above the horizon, top row = +pi/2
    if engine == "threejs":  # atan(w.z, w.x) = 2pi (u - 1/2)
        a = 2 * math.pi * (u - 0.5)
        return np.stack([np.cos(lat) * np.cos(a), np.sin(lat), np.cos(lat) * np.sin(a)], axis=1)
    if engine == "unity":  # atan2(w.z, w.x) = 2pi (1/2 - u)
        a = 2 * math.pi * (0.5 - u)
        return np.stack([np.cos(lat) * np.cos(a), np.sin(lat), np.cos(lat) * np.sin(a)], axis=1)
    a = math.pi * (2 * u - 1)  # filament: atan2(s.x, s.z), then the mirror x -> -x
    s = np.stack([np.cos(lat) * np.sin(a), np.sin(lat), np.cos(lat) * np.cos(a)], axis=1)
    return s * np.array([-1.0, 1.0, 1.0])


def eval_sh(c, n):
    """sum_k c[:, k] y_k(n): c is [channel][k] (up to 16), n rows of unit directions."""
    b = sh16(n[:, 0], n[:, 1], n[:, 2])
    return sum(np.outer(b[k], c[:, k]) for k in range(c.shape[1]))


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
    w = world("threejs", "equirect", n)  # the default frame of --format threejs
    x, y, z = w[:, 0:1], w[:, 1:2], w[:, 2:3]
    get_at = (0.282095 * sh[0] + 0.488603 * (sh[1] * y + sh[2] * z + sh[3] * x) +
              1.092548 * (sh[4] * x * y + sh[5] * y * z + sh[7] * x * z) +
              0.315392 * sh[6] * (3 * z * z - 1) + 0.546274 * sh[8] * (x * x - y * y))
    near(get_at, truth(n, 3, False), 5e-5, "three.js getAt vs the known radiance (3 bands)")
    irr = (0.886227 * sh[0] + 2 * 0.511664 * (sh[1] * y + sh[2] * z + sh[3] * x) +
           2 * 0.429043 * (sh[4] * x * y + sh[5] * y * z + sh[7] * x * z) +
           sh[6] * (0.743125 * z * z - 0.247708) + 0.429043 * sh[8] * (x * x - y * y))
    near(irr, math.pi * truth(n, 3, True), 5e-5, "three.js getIrradianceAt vs the known E (3 bands)")
    old = np.array(json.loads(run(os.path.join(DIR, "sh_equirect_512.exr"), "--format", "threejs",
                                  "--frame", "sphbasis"))["sh"]).reshape(9, 3)
    near(old.T, coeffs(os.path.join(DIR, "sh_equirect_512.exr")), 0, "--frame sphbasis = json")
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
    w = world(MODE, "equirect", n)  # the default frame of --format unity / filament
    x, y, z = w[:, 0:1], w[:, 1:2], w[:, 2:3]
    if MODE == "filament":  # renderPreScaledSH3Bands
        e = (sh[0] + sh[1] * y + sh[2] * z + sh[3] * x + sh[4] * y * x + sh[5] * y * z +
             sh[6] * (3 * z * z - 1) + sh[7] * z * x + sh[8] * (x * x - y * y))
    else:  # ShadeSH9 with SHTools' packing
        sha = np.stack([sh[3], sh[1], sh[2], sh[0] - sh[6]])
        shb = np.stack([sh[4], sh[5], 3 * sh[6], sh[7]])
        e = (x * sha[0] + y * sha[1] + z * sha[2] + sha[3] + x * y * shb[0] + y * z * shb[1] +
             z * z * shb[2] + x * z * shb[3] + (x * x - y * y) * sh[8])
    near(e, truth(n, 3, True), 2e-5, "%s evaluation vs the known E/pi (3 bands)" % MODE)
elif MODE == "frames":
    # --frame E: the coefficients evaluated at the engine's world direction w(d) give the map's
    # radiance at d, for lat-long and cube maps and for every engine.
    n = dirs()
    for engine in ("sphbasis", "threejs", "filament", "unity"):
        for layout, files in (("equirect", [os.path.join(DIR, "sh_equirect_512.exr")]),
                              ("cross", [os.path.join(DIR, "sh_hcross.exr")]),
                              ("faces", FACES)):
            c = coeffs("--layout", layout, *files, "--bands", "4", "--frame", engine)
            near(eval_sh(c, world(engine, layout, n)), truth(n, 4, False), 5e-5,
                 "--frame %s --layout %s: radiance at w(d) vs the known radiance at d" % (engine, layout))
    # Exactness: band 0 is kept bit for bit and band 1 is a signed permutation of the map's
    # band 1, bit for bit; bands 2 and 3 (weights such as -1/2, sqrt(3)/2) equal the closed form
    # within 8 ulps of the largest coefficient (measured: 1.4e-17, half an ulp of their size).
    base = coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4")
    rng = np.random.default_rng(9)
    p = rng.normal(size=(16, 3))
    p /= np.linalg.norm(p, axis=1)[:, None]
    for engine in ("threejs", "filament", "unity"):
        c = coeffs(os.path.join(DIR, "sh_equirect_512.exr"), "--bands", "4", "--frame", engine)
        if not np.array_equal(c[:, 0], base[:, 0]):
            fail("--frame %s changed band 0" % engine)
        # y_1m = K (y, z, x): the world's (y, z, x) components of the map's axes
        m = np.array([world(engine, "equirect", np.eye(3)[[i]])[0] for i in range(3)]).T  # w = m d
        if not np.allclose(np.abs(m).sum(axis=0), 1) or not np.allclose(np.round(m), m, atol=1e-12):
            fail("--frame %s: the engine's frame is not a signed permutation: %s" % (engine, m))
        m = np.round(m)
        yzx = [1, 2, 0]
        want1 = np.stack([sum(m[yzx[i], yzx[j]] * base[:, 1 + j] for j in range(3)) for i in range(3)], axis=1)
        if not np.array_equal(c[:, 1:4], want1):
            fail("--frame %s: band 1 is not the exact signed permutation (max diff %.3g)"
                 % (engine, np.max(np.abs(c[:, 1:4] - want1))))
        # closed form of bands 2-3 in 40-digit arithmetic: D with y(m d) D = y(d) at 16
        # directions (exact polynomials), c' = D c, rounded once to double
        with mpmath.workdps(40):
            a = mpmath.matrix([sh16_mp(*(m @ v)) for v in p])
            yd = mpmath.matrix([sh16_mp(*v) for v in p])
            d = a**-1 * yd
            want = np.array([[float(sum(d[k, j] * mpmath.mpf(float(base[ch, j])) for j in range(16)))
                              for k in range(16)] for ch in range(3)])
        err = near(c[:, 4:], want[:, 4:], 8 * 2.0 ** -52 * np.max(np.abs(base)),
                   "--frame %s bands 2-3 vs the closed form" % engine)
        print("--frame %s: bands 2-3 within %.3g of the 40-digit closed form" % (engine, err))
    # Cube layouts use the cube frame: three.js's and Filament's x -> -x is a mirror, so their
    # frame of a cross negates exactly the coefficients odd in x (m = 1, -2, 3, ...); Unity's
    # is the identity.
    cross = ["--layout", "cross", os.path.join(DIR, "sh_hcross.exr"), "--bands", "4", "--frame"]
    cb = coeffs(*cross, "sphbasis")
    sign = np.array([(-1) ** abs(m_) if m_ >= 0 else (-1) ** (abs(m_) + 1)
                     for l in range(4) for m_ in range(-l, l + 1)])
    for engine, want in (("threejs", cb * sign), ("filament", cb * sign), ("unity", cb)):
        if not np.array_equal(coeffs(*cross, engine), want):
            fail("--layout cross --frame %s is not the exact signed copy" % engine)
    # A frame on a non-SH basis is refused; the default of an engine format is its engine.
    r = subprocess.run([BIN, "project", os.path.join(DIR, "sh_equirect_512.exr"), "--basis", "hsh",
                        "--coeffs", "9", "--frame", "unity"], capture_output=True, text=True)
    if r.returncode == 0 or "frames work on SH" not in r.stderr:
        fail("--basis hsh --frame unity: %r" % r.stderr)
    for fmt in ("threejs", "unity", "filament"):
        a = run(os.path.join(DIR, "sh_equirect_512.exr"), "--format", fmt)
        b = run(os.path.join(DIR, "sh_equirect_512.exr"), "--format", fmt, "--frame", fmt)
        strip = lambda t: re.sub(r'^// generated by: .*\n|"generator":"[^"]*",', "", t)
        if strip(a) != strip(b) or not strip(a).strip():
            fail("--format %s does not default to --frame %s" % (fmt, fmt))
elif MODE == "inputs":
    # 16-bit PNG: sRGB-encoded like 8-bit (the PNG default; no gAMA/iCCP/sRGB chunk is read),
    # decoded by IEC 61966-2-1 from v / 65535.
    s4pi = math.sqrt(4 * math.pi)

    def lin(v):
        v = np.asarray(v, dtype=np.float64)
        return np.where(v <= 0.04045, v / 12.92, ((v + 0.055) / 1.055) ** 2.4)

    c = coeffs(os.path.join(DIR, "const_srgb16.png"), "--bands", "3")
    near(c[:, 0], s4pi * lin(np.array([48000, 30000, 12000]) / 65535), 3e-7 * s4pi,
         "16-bit PNG constant: band 0 = sqrt(4 pi) c")
    near(c[:, 1:], 0, 1e-12, "16-bit PNG constant: bands 1-2")
    # JPEG (quality 100, 4:4:4): a constant decodes to a constant within one 8-bit level.
    c = coeffs(os.path.join(DIR, "const.jpg"), "--bands", "3")
    want = lin(np.array([188, 100, 40]) / 255)
    step = lin(np.array([189, 101, 41]) / 255) - want
    near(c[:, 0] - s4pi * want, 0, s4pi * float(np.max(step)), "JPEG constant: band 0 within a level")
    near(c[:, 1:], 0, 1e-12, "JPEG constant: bands 1-2")
    # A gradient: |c_k(file) - c_k(EXR)| <= delta * integral |y_k| <= delta sqrt(4 pi), delta the
    # largest texel error: half a code step times the sRGB decoding's largest slope,
    # 2.4/1.055 (at v = 1), for 8 and 16 bits; JPEG: four 8-bit steps, the largest texel error
    # of grad.jpg as Pillow decodes it (mean 0.44 steps).
    exr = coeffs(os.path.join(DIR, "grad.exr"), "--bands", "3")
    slope = 2.4 / 1.055
    for name, delta in (("grad8.png", 0.5 / 255 * slope), ("grad16.png", 0.5 / 65535 * slope),
                        ("grad.jpg", 4 / 255 * slope)):
        err = near(coeffs(os.path.join(DIR, name), "--bands", "3"), exr, delta * s4pi,
                   "%s vs grad.exr (bound %.3g)" % (name, delta * s4pi))
        print("%s: max |c - c_exr| = %.3g, bound %.3g" % (name, err, delta * s4pi))
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
