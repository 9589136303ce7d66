"""Shader twins of the hemispherical bases HSH, Makhotkin and Zernike (basis/hsh.hpp,
basis/makhotkin.hpp, basis/zernike.hpp), imported by gen_sh_fixed.py --glsl / --hlsl.

The C++ kernels of up to 8 bands run the normalised Jacobi row recurrence of
basis/detail/jacobi.hpp (detail::hemi) on a table of constants built once at run time in
sphbasis::extended and rounded to float (RowTable<float, 8>). This module builds the same table
exactly (mpmath, 50 digits, from the same formulas: Gautschi's recurrence coefficients a_k, b_k
of the orthonormal Jacobi polynomials, and the families' q0, q1 literals as the doubles the C++
reads) and rounds each entry to the nearest float; the shaders loop over it in the C++ order.
"""
import struct

import mpmath as mp

mp.mp.dps = 50

# name: (sigma, step, a0, am, b0, bm, q0, q1, ratio), as the C++ families' hemi::Family.
FAMILIES = {
    "hsh": (1, 1, 0, 1, 0, 1, 0.39894228040143268, 0.69098829894267096, 0),
    "makhotkin": (1, 1, 0, 1, 1, 1, 0.56418958354775629, 0.97720502380583984, 0),
    "zernike": (-1, 2, 0, 0, 0, 1, 0.39894228040143268, 0.79788456080286536, 1),
}
BANDS = 8  # RowTable<float, 8>: the unrolled kernels' table


def _f32(v):
    return struct.unpack("<f", struct.pack("<f", float(v)))[0]


def _f32_exact(v):
    """The float nearest to the mpmath value v (checked among the double's float and its two
    neighbours)."""
    f = _f32(v)
    bits = struct.unpack("<I", struct.pack("<f", f))[0]
    cands = [f] + [struct.unpack("<f", struct.pack("<I", b))[0] for b in (bits - 1, bits + 1)
                   if f != 0]
    return min(cands, key=lambda c: abs(mp.mpf(c) - v))


def _jacobi_a(k, al, be):
    s = mp.mpf(2 * k + al + be)
    return 2 / s * mp.sqrt(mp.mpf(k) * (k + al) / ((s - 1) * (s + 1)) * ((k + be) * (k + al + be)))


def _sigma_plus_b(k, al, be, sigma):
    s = mp.mpf(2 * k + al + be)
    if s == 0:
        return mp.mpf(sigma)
    den = s * (s + 2)
    return (sigma * den + (be * be - al * al)) / den


def table(name):
    """(pz, d, c, start) of the family, as RowTable<float, 8> holds them (floats)."""
    sigma, step, a0, am, b0, bm, q0, q1, ratio = FAMILIES[name]
    start = []
    q = mp.mpf(q0)
    for m in range(BANDS):
        if m == 1:
            q *= mp.mpf(q1) / mp.mpf(q0)
        elif m > 1:
            q *= mp.sqrt(mp.mpf(2 * m + 1) / (2 * m)) if ratio == 0 else mp.sqrt(mp.mpf(m + 1) / m)
        start.append(_f32_exact(q))
    pz, d, c = [], [], []
    for b in range(BANDS):
        m = 0 if step == 1 else b % 2
        while m + step <= b:
            k, al, be = (b - m) // step, a0 + am * m, b0 + bm * m
            ak = _jacobi_a(k, al, be)
            akm1 = _jacobi_a(k - 1, al, be) if k >= 2 else mp.mpf(0)
            pz.append(_f32_exact(2 * sigma / ak))
            d.append(_f32_exact(_sigma_plus_b(k - 1, al, be, sigma) / ak))
            c.append(_f32_exact(akm1 / ak))
            m += step
    return pz, d, c, start


def _lit(f, lang):
    s = "%.9g" % f
    if "e" not in s and "." not in s:
        s += ".0"
    return s + ("f" if lang == "hlsl" else "")


def _array(name, values, lang):
    body = ", ".join(_lit(v, lang) for v in values)
    n = len(values)
    if lang == "glsl":
        return "const float %s[%d] = float[%d](%s);" % (name, n, n, body)
    return "static const float %s[%d] = {%s};" % (name, n, body)


_DOC = {
    "hsh": ("Hemispherical harmonics (Gautron et al., EGSR 2004)", "hsh", "bands^2", "ACN",
            "0 below the horizon"),
    "makhotkin": ("The Makhotkin basis (JQSRT 1996)", "makhotkin", "bands^2", "ACN",
                  "0 below the horizon"),
    "zernike": ("Koenderink's hemispherical Zernike basis (ECCV 1996)", "zernike",
                "bands(bands+1)/2", "index n(n+1)/2 + (n+m)/2", "0 below the horizon"),
}


def shader_hemi(name, lang):
    vec3 = "vec3" if lang == "glsl" else "float3"
    f = "f" if lang == "hlsl" else ""
    sigma, step = FAMILIES[name][:2]
    pz, d, c, start = table(name)
    out = []
    w = out.append
    p = "sphbasis_%s_" % name
    title, ns, count, order, below = _DOC[name]
    nmax = BANDS * BANDS if step == 1 else BANDS * (BANDS + 1) // 2
    w("/// Recurrence table of %s: RowTable<float, %d> of basis/detail/jacobi.hpp (the" % (ns, BANDS))
    w("/// normalised Jacobi steps p_k = (pz z - d) p_{k-1} - c p_{k-2} and the sectoral starts),")
    w("/// each entry the float nearest to the exact value (generator: tools/gen/hemi_shader.py).")
    w(_array(p + "pz", pz, lang))
    w(_array(p + "d", d, lang))
    w(_array(p + "c", c, lang))
    w(_array(p + "start", start, lang))
    w("")
    w("/// %s: %s functions" % (title, count))
    w("/// (1 <= bands <= %d) at the unit direction dir, %s order, as" % (BANDS, order))
    w("/// sphbasis::%s::eval_unit(bands, ...) in float (the row recurrence of" % ns)
    w("/// basis/detail/jacobi.hpp, same operation order); %s. Entries from" % below)
    w("/// %s(bands) on are left unwritten." % ("sh::count" if step == 1 else "zernike::count"))
    w("void %seval(%s dir, int bands, out float h[%d])" % (p, vec3, nmax))
    w("{")
    w("    float x = dir.x; float y = dir.y; float z = dir.z;")
    w("    float zc = max(z, 0.0%s);" % f)
    if name == "zernike":
        w("    float g = 1.0%s / sqrt(1.0%s + zc);" % (f, f))
    else:
        w("    float g = 2.0%s * sqrt(zc / (1.0%s + zc));" % (f, f))
    w("    float X = x * g; float Y = y * g;")
    if name == "makhotkin":
        w("    float E = sqrt(zc);")
    else:
        w("    float E = z >= 0.0%s ? 1.0%s : 0.0%s;" % (f, f, f))
    w("    float cm[%d]; float sm[%d]; float cur[%d]; float prev[%d];" % ((BANDS,) * 4))
    w("    cm[0] = 1.0%s; sm[0] = 0.0%s; cm[1] = X; sm[1] = Y;" % (f, f))
    w("    for (int m = 2; m < bands; ++m) {")
    w("        cm[m] = X * cm[m - 1] - Y * sm[m - 1];")
    w("        sm[m] = X * sm[m - 1] + Y * cm[m - 1];")
    w("    }")
    w("    for (int l = 0; l < bands; ++l) {")
    if step == 1:
        w("        int o = l * (l - 1) / 2;")
        w("        for (int m = 0; m < l; ++m) {")
        w("            float v = (%spz[o + m] * zc - %sd[o + m]) * cur[m] - %sc[o + m] * prev[m];" % (p, p, p))
        w("            prev[m] = cur[m]; cur[m] = v;")
        w("        }")
        w("        cur[l] = %sstart[l] * E; prev[l] = 0.0%s;" % (p, f))
        w("        int k = l * (l + 1);")
        w("        h[k] = cur[0];")
        w("        for (int m = 1; m <= l; ++m) { h[k + m] = cur[m] * cm[m]; h[k - m] = cur[m] * sm[m]; }")
    else:
        w("        int par = l % 2; int half_l = l / 2;")
        w("        int o = half_l * (half_l - 1) + par * half_l;")
        w("        for (int j = 0; j < half_l; ++j) {")
        w("            int m = par + 2 * j;")
        w("            float v = (%spz[o + j] * zc - %sd[o + j]) * cur[m] - %sc[o + j] * prev[m];" % (p, p, p))
        w("            prev[m] = cur[m]; cur[m] = v;")
        w("        }")
        w("        cur[l] = %sstart[l] * E; prev[l] = 0.0%s;" % (p, f))
        w("        int base = l * (l + 1) / 2;")
        w("        for (int i = 0; i < (l + 1) / 2; ++i) h[base + i] = cur[l - 2 * i] * sm[l - 2 * i];")
        w("        if (par == 0) h[base + half_l] = cur[0];")
        w("        for (int m = 2 - par; m <= l; m += 2) h[base + (l + m) / 2] = cur[m] * cm[m];")
    w("    }")
    w("}")
    return "\n".join(out)


def shader_hemi_all(lang):
    return "\n\n".join(shader_hemi(n, lang) for n in ("hsh", "makhotkin", "zernike"))
