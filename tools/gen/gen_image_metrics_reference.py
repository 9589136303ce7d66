#!/usr/bin/python3
"""Generates tests/data/image_metrics_reference.txt: reference values of the image metrics of
include/sphbasis/render/image_metrics.hpp, computed here in numpy/scipy from the definitions
(an implementation independent of the C++ one: full 2-D kernels and scipy.ndimage.correlate where
the library filters separably; the sRGB/XYZ matrices derived here from the IEC 61966-2-1
chromaticities where the library has them as literals).

Definitions (m = mean of |r| over the selected pixels and the 3 channels, 1 if 0):
  relative_mse   mean over pixels, channels of (t - r)^2 / (r^2 + 1e-2 m^2)
                 (Rousselle, Knaus and Zwicker, "Adaptive Sampling and Reconstruction using
                 Greedy Error Minimization", 2011);
  smape          mean of 2 |t - r| / (|t| + |r| + 1e-2 m);
  outside        fraction of pixels with |t_c - r_c| > 3 max(s_c, 1e-4 m) for some channel c;
  flip           LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild,
                 "FLIP: A Difference Evaluator for Alternating Images", HPG 2020): linear RGB in
                 [0, 1] -> XYZ -> YyCxCz; CSF filters S(x) = a1 sqrt(pi/b1) exp(-pi^2 x^2/b1) +
                 a2 sqrt(pi/b2) exp(-pi^2 x^2/b2), x the distance in degrees, radius
                 ceil(3 sqrt(0.04/(2 pi^2)) ppd), normalised to sum 1; back to RGB clamped to
                 [0, 1]; CIELAB; Hunt (a, b *= 0.01 L); HyAB; ^0.7; remap p_c = 0.4, p_t = 0.95
                 against HyAB^0.7 of Hunt green and blue; features on Y/Yn: sigma = 0.5 * 0.082
                 ppd, radius ceil(3 sigma), first/second Gaussian derivatives with positive
                 weights summing to 1 and negative to -1; dE_f = (max(|d edge|, |d point|) /
                 sqrt 2)^0.5; dE = dE_c^(1 - dE_f). Borders: nearest pixel (clamp to edge).

Cases: 'random16' (16x16 random pair, random stderr with zeros, a mask), 'structured32x24'
(gradient, disc and step edge against a shifted, tinted copy), 'dark16' (an HDR pair of values
about 1e-4 with black pixels). Images are float32 values (written with %.9g, exact).

Output: '#' header lines, then
  'image CASE ROLE W H C v...'   ROLE test, ref, stderr or mask (C channels, row-major)
  'value CASE METRIC MASKED PPD v'  METRIC relative_mse, smape, outside, flip; MASKED 0 or 1
  'flipmap CASE PPD v...'        the FLIP map, row-major
Regenerate (from the repository root, numpy and scipy, a second):
  /usr/bin/python3 tools/gen/gen_image_metrics_reference.py > tests/data/image_metrics_reference.txt
"""
import math
import sys

import numpy as np
import scipy
from scipy import ndimage

# --- colour -------------------------------------------------------------------------------
PRIMARIES = [(0.64, 0.33), (0.30, 0.60), (0.15, 0.06)]
WHITE = (0.3127, 0.3290)


def xyz_of(x, y):
    return np.array([x / y, 1.0, (1 - x - y) / y])


P = np.stack([xyz_of(*c) for c in PRIMARIES], axis=1)
M = P * np.linalg.solve(P, xyz_of(*WHITE))  # linear sRGB -> XYZ; M @ (1,1,1) = D65 white, Y = 1
MINV = np.linalg.inv(M)
WN = M @ np.ones(3)


def to_xyz(rgb):  # (..., 3)
    return rgb @ M.T


def lab_hunt(rgb):
    xyz = to_xyz(rgb) / WN
    d = 6.0 / 29.0
    f = np.where(xyz > d ** 3, np.cbrt(xyz), xyz / (3 * d * d) + 4.0 / 29.0)
    L = 116 * f[..., 1] - 16
    a = 500 * (f[..., 0] - f[..., 1])
    b = 200 * (f[..., 1] - f[..., 2])
    return np.stack([L, 0.01 * L * a, 0.01 * L * b], axis=-1)


def hyab(p, q):
    return np.abs(p[..., 0] - q[..., 0]) + np.sqrt((p[..., 1] - q[..., 1]) ** 2 +
                                                   (p[..., 2] - q[..., 2]) ** 2)


def correlate(plane, k):
    return ndimage.correlate(plane, k, mode="nearest")


def csf_kernel(a1, b1, a2, b2, r, ppd):
    i = np.arange(-r, r + 1) / ppd
    xx, yy = np.meshgrid(i, i)
    d2 = xx ** 2 + yy ** 2
    k = a1 * np.sqrt(np.pi / b1) * np.exp(-np.pi ** 2 * d2 / b1) + \
        a2 * np.sqrt(np.pi / b2) * np.exp(-np.pi ** 2 * d2 / b2)
    return k / k.sum()


def split_normalise(k):
    pos, neg = k[k > 0].sum(), -k[k < 0].sum()
    return np.where(k > 0, k / pos, k / neg)


def flip_map(test, ref, ppd):
    r = int(math.ceil(3 * math.sqrt(0.04 / (2 * math.pi ** 2)) * ppd))
    kernels = [csf_kernel(1, 0.0047, 0, 1e-5, r, ppd), csf_kernel(1, 0.0053, 0, 1e-5, r, ppd),
               csf_kernel(34.1, 0.04, 13.5, 0.025, r, ppd)]
    sigma = 0.5 * 0.082 * ppd
    rf = int(math.ceil(3 * sigma))
    i = np.arange(-rf, rf + 1, dtype=float)
    xx, yy = np.meshgrid(i, i)  # xx varies along a row (x), yy down the columns (y)
    g = np.exp(-(xx ** 2 + yy ** 2) / (2 * sigma ** 2))
    edge_x = split_normalise(-xx * g)
    point_x = split_normalise((xx ** 2 / sigma ** 2 - 1) * g)
    edge_y, point_y = edge_x.T, point_x.T

    def prepare(img):
        img = np.clip(img, 0, 1)
        xyz = to_xyz(img) / WN
        ycc = [116 * xyz[..., 1] - 16, 500 * (xyz[..., 0] - xyz[..., 1]),
               200 * (xyz[..., 1] - xyz[..., 2])]
        f = [correlate(c, k) for c, k in zip(ycc, kernels)]
        yn = (f[0] + 16) / 116
        xyz_f = np.stack([(f[1] / 500 + yn) * WN[0], yn * WN[1], (yn - f[2] / 200) * WN[2]], -1)
        rgb = np.clip(xyz_f @ MINV.T, 0, 1)
        y = xyz[..., 1]
        edge = np.hypot(correlate(y, edge_x), correlate(y, edge_y))
        point = np.hypot(correlate(y, point_x), correlate(y, point_y))
        return lab_hunt(rgb), edge, point

    lt, et, pt = prepare(test)
    lr, er, pr = prepare(ref)
    cmax = hyab(lab_hunt(np.array([0.0, 1, 0])), lab_hunt(np.array([0.0, 0, 1]))) ** 0.7
    e = hyab(lt, lr) ** 0.7
    pc, ptt = 0.4, 0.95
    dc = np.where(e < pc * cmax, ptt / (pc * cmax) * e,
                  ptt + (e - pc * cmax) / (cmax - pc * cmax) * (1 - ptt))
    df = (np.maximum(np.abs(er - et), np.abs(pr - pt)) / math.sqrt(2)) ** 0.5
    return dc ** (1 - df)


# --- the other metrics ------------------------------------------------------------------------
def scale(ref, sel):
    m = np.abs(ref[sel]).mean() if sel.any() else 0.0
    return m if m > 0 else 1.0


def relative_mse(t, r, sel):
    m = scale(r, sel)
    return float((((t - r) ** 2) / (r ** 2 + 1e-2 * m * m))[sel].mean())


def smape(t, r, sel):
    m = scale(r, sel)
    return float((2 * np.abs(t - r) / (np.abs(t) + np.abs(r) + 1e-2 * m))[sel].mean())


def outside(t, r, s, sel):
    m = scale(r, sel)
    o = (np.abs(t - r) > 3 * np.maximum(s, 1e-4 * m)).any(axis=-1)
    return float(o[sel].mean())


# --- cases ------------------------------------------------------------------------------------
def f32(a):
    return np.asarray(a, dtype=np.float32).astype(np.float64)


def cases():
    rng = np.random.default_rng(20201)
    h, w = 16, 16
    ref = f32(np.round(rng.uniform(0, 1, (h, w, 3)) * 256) / 256)
    test = f32(np.round(np.clip(ref + rng.normal(0, 0.1, ref.shape), 0, 1) * 256) / 256)
    s = f32(np.round(rng.uniform(0, 0.05, ref.shape) * 1024) / 1024)
    s[rng.uniform(size=(h, w)) < 0.2] = 0
    yy, xx = np.mgrid[0:h, 0:w]
    mask = ((xx + yy) % 3 != 0).astype(np.float64)
    yield "random16", test, ref, s, mask, [67.020643276582248, 20.0]

    h, w = 24, 32
    yy, xx = np.mgrid[0:h, 0:w].astype(float)
    ref = np.stack([xx / (w - 1), yy / (h - 1), 0.25 + 0.0 * xx], -1)
    ref[(xx - 20) ** 2 + (yy - 10) ** 2 < 36] = [1.0, 0.9, 0.2]
    ref[:, :6] = [0.05, 0.05, 0.4]
    ref = f32(ref)
    test = np.roll(ref, 1, axis=1) * np.array([1.0, 0.9, 1.1])
    test[18:, 24:] = 0
    test = f32(np.clip(test, 0, 1))
    s = f32(0.01 * ref)
    yield "structured32x24", test, ref, s, None, [67.020643276582248, 20.0, 5.0]

    h, w = 16, 16
    ref = f32(1e-4 * rng.gamma(0.5, 1.0, (h, w, 3)))
    ref[3:6, 3:9] = 0
    test = f32(ref * (1 + rng.normal(0, 0.3, ref.shape)) + 2e-6)
    s = f32(0.1 * ref)
    yield "dark16", test, ref, s, None, []


def fmt(a):
    return " ".join("%.9g" % v for v in np.asarray(a, dtype=np.float32).ravel())


def main():
    out = sys.stdout
    out.write("# sphbasis reference values of the image metrics (render/image_metrics.hpp).\n")
    out.write("# Generated by tools/gen/gen_image_metrics_reference.py (numpy %s, scipy %s).\n"
              % (np.__version__, scipy.__version__))
    out.write("# Regenerate from the repo root with:\n#   /usr/bin/python3 "
              "tools/gen/gen_image_metrics_reference.py > tests/data/image_metrics_reference.txt\n")
    out.write("# Definitions: the generator's docstring. Values: float64 numpy, %.17g.\n")
    # Self-checks: the derived matrix against the rounded one of IEC 61966-2-1, and identities.
    iec = np.array([[0.4124, 0.3576, 0.1805], [0.2126, 0.7152, 0.0722], [0.0193, 0.1192, 0.9505]])
    assert np.abs(M - iec).max() < 1e-4
    for name, test, ref, s, mask, ppds in cases():
        h, w, _ = ref.shape
        for role, im in (("test", test), ("ref", ref), ("stderr", s)):
            out.write("image %s %s %d %d 3 %s\n" % (name, role, w, h, fmt(im)))
        if mask is not None:
            out.write("image %s mask %d %d 1 %s\n" % (name, w, h, fmt(mask)))
        sels = [(0, np.ones((h, w), bool))]
        if mask is not None:
            sels.append((1, mask != 0))
        for masked, sel in sels:
            for metric, v in (("relative_mse", relative_mse(test, ref, sel)),
                              ("smape", smape(test, ref, sel)),
                              ("outside", outside(test, ref, s, sel))):
                assert math.isfinite(v)
                out.write("value %s %s %d 0 %.17g\n" % (name, metric, masked, v))
        for ppd in ppds:
            fm = flip_map(test, ref, ppd)
            assert np.abs(fm - flip_map(ref, test, ppd)).max() < 1e-12  # symmetric
            assert np.abs(flip_map(ref, ref, ppd)).max() == 0  # identical -> 0
            assert fm.min() >= 0 and fm.max() <= 1
            for masked, sel in sels:
                out.write("value %s flip %d %.17g %.17g\n" % (name, masked, ppd, fm[sel].mean()))
            out.write("flipmap %s %.17g %s\n" % (name, ppd, " ".join("%.9g" % v for v in fm.ravel())))
    out.write("# Self-checks passed: derived sRGB matrix within 1e-4 of IEC 61966-2-1's; FLIP "
              "symmetric, 0 for identical images, in [0, 1].\n")


if __name__ == "__main__":
    main()
