"""Shader twins of the engine bases, imported by gen_sh_fixed.py --glsl / --hlsl: the ambient cube
(basis/ambient_cube.hpp), Ambient Dice (basis/ambient_dice.hpp; its Bezier and linear variants,
the paper's rule, basis/ambient_dice_bezier.hpp), spherical Gaussians and
BakingLab's lobe sets with Hill's fitted irradiance (basis/spherical_gaussian.hpp), ZH3 and its
hallucinated variant (basis/zh3.hpp), and L1 SH with the Geomerics reconstruction
(basis/sh_l1_nonlinear.hpp).

Each shader function has the operation order of the C++ kernel it mirrors (float path). Each
constant is the float nearest to its exact value, computed here in mpmath (50 digits) from the
closed form; where the C++ header writes the constant as a literal, the literal must round to the
same float or the generator fails (so editing either side alone fails). The C++ builds the lobe
sets' axes and sharpness at run time in double (sg::bakinglab_axes / bakinglab_sharpness) and
rounds them to float; here they are built from the same construction exactly (the sharpness by
gen_sg_reference.py's bakinglab_sharpness) and rounded once; tests/shaders/twins_test.cpp checks
that the shader's tables equal the C++ floats bit for bit.
"""
import os
import re

import mpmath as mp

from gen_sh_fixed import _f32, _f32_step as _step  # float rounding: tools/gen/gen_sh_fixed.py

mp.mp.dps = 50

_ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SG_COUNTS = (5, 6, 9, 12)


def f32_nearest(v):
    """The float nearest to the mpmath value v (among the double's float and its neighbours)."""
    v = mp.mpf(v)
    f = _f32(v)
    return min([f, _step(f, True), _step(f, False)], key=lambda c: abs(mp.mpf(c) - v))


def _cxx_const(header, name):
    """The double literal of `name = <literal>;` in include/sphbasis/<header>."""
    with open(os.path.join(_ROOT, "include", "sphbasis", header)) as f:
        m = re.search(r"\b%s = ([-0-9.eE+]+);" % re.escape(name), f.read())
    if not m:
        raise SystemExit("engine_shader.py: include/sphbasis/%s has no constant %s" % (header, name))
    return float(m.group(1))


def checked(v, header, name):
    """f32_nearest(v), after checking that the C++ constant `name` of `header` rounds to it."""
    f = f32_nearest(v)
    cxx = _cxx_const(header, name)
    if _f32(cxx) != f or abs(mp.mpf(cxx) - v) > mp.mpf(4e-16) * abs(v):
        raise SystemExit("engine_shader.py: %s::%s = %r is not %s to double precision (or rounds "
                         "to another float)" % (header, name, cxx, mp.nstr(v, 20)))
    return f


def lit(f, lang):
    s = "%.9g" % f
    assert _f32(float(s)) == f
    if "e" not in s and "." not in s:
        s += ".0"
    return s + ("f" if lang == "hlsl" else "")


class _Lang:
    def __init__(self, lang):
        self.lang = lang
        self.vec3 = "vec3" if lang == "glsl" else "float3"
        self.const = "const float" if lang == "glsl" else "static const float"
        self.sfx = "" if lang == "glsl" else "f"

    def n(self, text):
        """A plain numeric literal ("1.0") in the language."""
        return text + self.sfx

    def v3(self, x, y, z):
        return "%s(%s, %s, %s)" % (self.vec3, lit(x, self.lang), lit(y, self.lang),
                                   lit(z, self.lang))

    def v3_array(self, name, vs):
        n = len(vs)
        body = ",\n".join("    " + self.v3(*v) for v in vs)
        if self.lang == "glsl":
            return "const vec3 %s[%d] = vec3[%d](\n%s);" % (name, n, n, body)
        return "static const float3 %s[%d] = {\n%s};" % (name, n, body)

    def not_finite(self, v):
        return "(isinf(%s) || isnan(%s))" % (v, v)


# ---------------------------------------------------------------------------------------------
# Ambient cube and Ambient Dice.


def shader_ambient_cube(L):
    out = []
    w = out.append
    zero = L.n("0.0")
    for full in (True, False):
        n = 6 if full else 5
        name = "sphbasis_ambient_cube%s_eval" % ("" if full else "5")
        w("/// The ambient cube (McTaggart, \"Half-Life 2 / Valve Source Shading\", GDC 2004)%s" % (
            "" if full else ",\n/// hemispherical (the -z face is 0 for z >= 0: tangent-space light maps store 5),"))
        w("/// at the unit direction d: a[k] = max(+-d_i, 0)^2 in the order +x, -x, +y, -y, +z%s, as" % (
            ", -z" if full else ""))
        w("/// sphbasis::basis_eval<AmbientCube>(%d, ...) (d_i >= 0 selects the + face)." % n)
        w("void %s(%s d, out float a[%d])" % (name, L.vec3, n))
        w("{")
        w("    float x2 = d.x * d.x; float y2 = d.y * d.y; float z2 = d.z * d.z;")
        w("    a[0] = d.x >= %s ? x2 : %s; a[1] = d.x >= %s ? %s : x2;" % (zero, zero, zero, zero))
        w("    a[2] = d.y >= %s ? y2 : %s; a[3] = d.y >= %s ? %s : y2;" % (zero, zero, zero, zero))
        if full:
            w("    a[4] = d.z >= %s ? z2 : %s; a[5] = d.z >= %s ? %s : z2;" % (zero, zero, zero, zero))
        else:
            w("    a[4] = d.z >= %s ? z2 : %s;" % (zero, zero))
        w("}")
        w("")
    return out


def dice_constants():
    s5 = mp.sqrt(5)
    t = (s5 - 1) / 2
    a = 1 / mp.sqrt(1 + t * t)
    hdr = "basis/ambient_dice.hpp"
    return (checked(a, hdr, "axis_a"), checked(t * a, hdr, "axis_b"),
            checked(mp.mpf(7) / 20, hdr, "w2"), checked(mp.mpf(1) / 4, hdr, "w4"))


def shader_ambient_dice(L):
    a, b, w2, w4 = dice_constants()
    out = []
    w = out.append
    zero = L.n("0.0")
    w("/// Ambient Dice (Iwanicki and Sloan, EGSR 2017), SRBF variant: the icosahedron's 6 axes")
    w("/// a_0 = (A, B, 0), a_1 = (-A, B, 0), a_2 = (0, A, B), a_3 = (0, -A, B), a_4 = (B, 0, A),")
    w("/// a_5 = (B, 0, -A) and the lobe w(c) = w2 c^2 + w4 c^4 (basis/ambient_dice.hpp).")
    w("%s sphbasis_ambient_dice_axis_a = %s;  // A = 2/sqrt(10 - 2 sqrt(5))" % (L.const, lit(a, L.lang)))
    w("%s sphbasis_ambient_dice_axis_b = %s;  // B = (sqrt(5) - 1)/2 A" % (L.const, lit(b, L.lang)))
    w("%s sphbasis_ambient_dice_w2 = %s;  // 0.7/2" % (L.const, lit(w2, L.lang)))
    w("%s sphbasis_ambient_dice_w4 = %s;  // 0.3 5/6" % (L.const, lit(w4, L.lang)))
    w("")
    w("/// The 12 Ambient Dice functions at the unit direction d, as")
    w("/// sphbasis::basis_eval<AmbientDice>(12, ...): D[2i] = w(d . a_i) where d . a_i > 0, else 0")
    w("/// (vertex +a_i); D[2i+1] = w(d . a_i) where d . a_i <= 0, else 0 (vertex -a_i).")
    w("void sphbasis_ambient_dice_eval(%s d, out float D[12])" % L.vec3)
    w("{")
    w("    float a = sphbasis_ambient_dice_axis_a; float b = sphbasis_ambient_dice_axis_b;")
    w("    float c[6];")
    w("    c[0] = a * d.x + b * d.y; c[1] = b * d.y - a * d.x; c[2] = a * d.y + b * d.z;")
    w("    c[3] = b * d.z - a * d.y; c[4] = b * d.x + a * d.z; c[5] = b * d.x - a * d.z;")
    w("    for (int i = 0; i < 6; ++i) {")
    w("        float c2 = c[i] * c[i];")
    w("        float v = c2 * (sphbasis_ambient_dice_w2 + sphbasis_ambient_dice_w4 * c2);")
    w("        D[2 * i] = c[i] > %s ? v : %s;" % (zero, zero))
    w("        D[2 * i + 1] = c[i] > %s ? %s : v;" % (zero, zero))
    w("    }")
    w("}")
    w("")
    return out


def _cxx_table(header, name):
    """The numbers of the table `name[...] = {...};` of include/sphbasis/<header>, in order."""
    with open(os.path.join(_ROOT, "include", "sphbasis", header)) as f:
        m = re.search(r"\b%s(?:\[\d+\])+ = \{(.*?)\};" % re.escape(name), f.read(), re.S)
    if not m:
        raise SystemExit("engine_shader.py: include/sphbasis/%s has no table %s" % (header, name))
    return [float(x) for x in re.findall(r"-?[0-9][-0-9.eE+]*", m.group(1))]


def shader_ambient_dice_faces(L):
    """Ambient Dice over the faces, the paper's rule (basis/ambient_dice_bezier.hpp): the tables of
    ambient_dice_bezier_tables.hpp (generated by gen_ambient_dice_bezier.py), each double rounded
    to float as the C++ float path does (T(double)), and the same operations in the same order."""
    hdr = "basis/ambient_dice_bezier_tables.hpp"
    lang = L.lang
    zero = L.n("0.0")
    out = []
    w = out.append

    def table(kind, name, texts, per_line):
        rows = [", ".join(texts[i:i + per_line]) for i in range(0, len(texts), per_line)]
        body = ",\n".join("    " + r for r in rows)
        n = len(texts)
        if lang == "glsl":
            w("const %s %s[%d] = %s[%d](\n%s);" % (kind, name, n, kind, n, body))
        else:
            w("static const %s %s[%d] = {\n%s};" % (kind, name, n, body))

    def floats(name, values, per_line):
        table("float", name, [lit(_f32(v), lang) for v in values], per_line)

    def ints(name, values, per_line):
        table("int", name, [str(int(v)) for v in values], per_line)

    p = "sphbasis_ambient_dice_"
    w("/// Ambient Dice over the icosahedron's faces (Iwanicki and Sloan, EGSR 2017), the paper's rule")
    w("/// (basis/ambient_dice_bezier.hpp): per face its vertices, the rows of its inverse vertex")
    w("/// matrix (b = coordinates of d in the face's unit vertices), the edge points' derivative")
    w("/// factors (u_a . v_b, w_a . v_b)/3 and value factor v_a . v_b = 1/sqrt(5), the interior")
    w("/// points' linear forms; and the octant + plane tests that find the face.")
    ints(p + "face_vertex", _cxx_table(hdr, "face_vertex"), 12)
    floats(p + "face_dual", _cxx_table(hdr, "face_dual"), 9)
    floats(p + "face_edge", _cxx_table(hdr, "face_edge"), 12)
    floats(p + "face_interior", _cxx_table(hdr, "face_interior"), 6)
    floats(p + "locate_plane", _cxx_table(hdr, "locate_plane"), 3)
    ints(p + "locate_face", _cxx_table(hdr, "locate_face"), 8)
    w("%s %sedge_cos = %s;  // 1/sqrt(5)" % (L.const, p, lit(_f32(_cxx_const(hdr, "edge_cos")), lang)))
    w("")
    w("/// The face of the unit direction d and b, the coordinates of d in its unit vertices (>= 0).")
    w("int %sface(%s d, out float b[3])" % (p, L.vec3))
    w("{")
    w("    int o = (d.x < %s ? 1 : 0) + (d.y < %s ? 2 : 0) + (d.z < %s ? 4 : 0);" % (zero, zero, zero))
    w("    float ax = d.x < %s ? -d.x : d.x; float ay = d.y < %s ? -d.y : d.y;" % (zero, zero))
    w("    float az = d.z < %s ? -d.z : d.z;" % zero)
    w("    int f = %slocate_face[4 * o];" % p)
    w("    for (int e = 0; e < 3; ++e) {")
    w("        int r = 3 * e;")
    w("        float s = %slocate_plane[r] * ax + %slocate_plane[r + 1] * ay +" % (p, p))
    w("                  %slocate_plane[r + 2] * az;" % p)
    w("        if (s < %s) f = %slocate_face[4 * o + 1 + e];" % (zero, p))
    w("    }")
    w("    for (int a = 0; a < 3; ++a) {")
    w("        int r = 9 * f + 3 * a;")
    w("        float c = %sface_dual[r] * d.x + %sface_dual[r + 1] * d.y +" % (p, p))
    w("                  %sface_dual[r + 2] * d.z;" % p)
    w("        b[a] = c > %s ? c : %s;" % (zero, zero))
    w("    }")
    w("    return f;")
    w("}")
    w("")
    w("/// The 36 functions of Ambient Dice's Bezier variant at the unit direction d, as")
    w("/// sphbasis::basis_eval<AmbientDiceBezier>(36, ...): h[3k] the value at vertex k, h[3k+1] and")
    w("/// h[3k+2] its derivatives along tangent_u[k] and tangent_w[k]; 9 of them non-zero.")
    w("void %sbezier_eval(%s d, out float h[36])" % (p, L.vec3))
    w("{")
    w("    float be[3];")
    w("    int f = %sface(d, be);" % p)
    w("    float wt[9];")
    w("    for (int a = 0; a < 3; ++a) {")
    w("        wt[3 * a] = be[a] * be[a] * be[a];")
    w("        wt[3 * a + 1] = %s; wt[3 * a + 2] = %s;" % (zero, zero))
    w("    }")
    w("    for (int e = 0; e < 6; ++e) {  // edge points (a, t): (0,1) (0,2) (1,0) (1,2) (2,0) (2,1)")
    w("        int a = e / 2;")
    w("        int t = (e - 2 * a) == 0 ? (a == 0 ? 1 : 0) : (a == 2 ? 1 : 2);")
    w("        float c = %s * be[a] * be[a] * be[t];" % L.n("3.0"))
    w("        wt[3 * a] += c * %sedge_cos;" % p)
    w("        wt[3 * a + 1] += c * %sface_edge[12 * f + 2 * e];" % p)
    w("        wt[3 * a + 2] += c * %sface_edge[12 * f + 2 * e + 1];" % p)
    w("    }")
    w("    float den = be[0] * be[1] + be[1] * be[2] + be[2] * be[0];")
    w("    float scale = den > %s ? %s * be[0] * be[1] * be[2] / den : %s;" % (zero, L.n("6.0"), zero))
    w("    for (int m = 0; m < 3; ++m) {  // the interior point opposite m, edge (pa, pb)")
    w("        int pa = m == 0 ? 1 : 0; int pb = m == 2 ? 1 : 2;")
    w("        float c = scale * be[pa] * be[pb];")
    w("        int q = 18 * f + 6 * m;")
    w("        for (int i = 0; i < 3; ++i) {")
    w("            wt[3 * pa + i] += c * %sface_interior[q + i];" % p)
    w("            wt[3 * pb + i] += c * %sface_interior[q + 3 + i];" % p)
    w("        }")
    w("    }")
    w("    for (int k = 0; k < 36; ++k) h[k] = %s;" % zero)
    w("    for (int a = 0; a < 3; ++a)")
    w("        for (int i = 0; i < 3; ++i) h[3 * %sface_vertex[3 * f + a] + i] = wt[3 * a + i];" % p)
    w("}")
    w("")
    w("/// The 12 functions of Ambient Dice's linear variant (its YCoCg variant's chroma) at the unit")
    w("/// direction d, as sphbasis::basis_eval<AmbientDiceLinear>(12, ...): h[k] = b_a where vertex")
    w("/// k is the face's vertex a; 3 of them non-zero.")
    w("void %slinear_eval(%s d, out float h[12])" % (p, L.vec3))
    w("{")
    w("    float be[3];")
    w("    int f = %sface(d, be);" % p)
    w("    for (int k = 0; k < 12; ++k) h[k] = %s;" % zero)
    w("    for (int a = 0; a < 3; ++a) h[%sface_vertex[3 * f + a]] = be[a];" % p)
    w("}")
    w("")
    return out


def shader_sums(L, sums):
    out = []
    w = out.append
    for stem, cxx, n in sums:
        w("/// The expansion sum_k c[k] B_k(d) of RGB coefficients at the unit direction d, as")
        w("/// sphbasis::basis_eval_sum<%s>(%d, c, d) per channel (same order of the sum)." % (cxx, n))
        w("%s sphbasis_%s_eval_sum(%s c[%d], %s d)" % (L.vec3, stem, L.vec3, n, L.vec3))
        w("{")
        w("    float h[%d];" % n)
        w("    sphbasis_%s_eval(d, h);" % stem)
        w("    %s e = c[0] * h[0];" % L.vec3)
        w("    for (int k = 1; k < %d; ++k) e = e + c[k] * h[k];" % n)
        w("    return e;")
        w("}")
        w("")
    return out


# ---------------------------------------------------------------------------------------------
# Spherical Gaussians.




def shader_sg(L):
    import gen_sg_reference  # the sets' axes and sharpness: tools/gen/gen_sg_reference.py

    lang = L.lang
    two_pi = checked(2 * mp.pi, "core/constants.hpp", "two_pi")
    # Hill's fit constants as the C++ float path computes them: c0 = T(0.36), c1 = T(1)/(T(4) c0).
    c0 = f32_nearest(mp.mpf("0.36"))
    assert c0 == _f32(0.36)
    c1 = f32_nearest(1 / (4 * mp.mpf(c0)))  # 4 c0 is exact; one correctly rounded division
    one, zero, two = L.n("1.0"), L.n("0.0"), L.n("2.0")
    out = []
    w = out.append
    w("/// One spherical Gaussian lobe a exp(lambda (mu . v - 1)) at the unit direction v (unit axis mu,")
    w("/// sharpness lambda >= 0, amplitude a), as sphbasis::sg::eval(Lobe<float>{mu, lambda, a}, v).")
    w("float sphbasis_sg_eval(%s axis, float sharpness, float amplitude, %s v)" % (L.vec3, L.vec3))
    w("{")
    w("    float d = axis.x * v.x + axis.y * v.y + axis.z * v.z;")
    w("    return amplitude * exp(sharpness * (d - %s));" % one)
    w("}")
    w("")
    w("/// Hill's fitted approximation of the irradiance int G(v) max(0, n . v) dv of one lobe of")
    w("/// radiance at the unit normal n (Pettineo, \"SG Series\" part 3, 2016), as")
    w("/// sphbasis::sg::irradiance_fitted(Lobe<float>{mu, lambda, a}, n). lambda > 0 (the fit is")
    w("/// meant for lambda >= 1). Divide by pi for the exit radiance of a white Lambertian surface.")
    w("float sphbasis_sg_irradiance_fitted(%s axis, float sharpness, float amplitude, %s n)" % (
        L.vec3, L.vec3))
    w("{")
    w("    float mu_dot_n = axis.x * n.x + axis.y * n.y + axis.z * n.z;")
    w("    float l = sharpness;")
    w("    float eml = exp(-l); float em2l = eml * eml; float rl = %s / l;" % one)
    w("    float scale = %s + %s * em2l - rl;" % (one, two))
    w("    float bias = (eml - em2l) * rl - em2l;")
    w("    float x = sqrt(%s - scale);" % one)
    w("    float x0 = %s * mu_dot_n;  // 0.36" % lit(c0, lang))
    w("    float x1 = %s * x;  // 1/(4 0.36), the float the C++ computes" % lit(c1, lang))
    w("    float s = x0 + x1;")
    w("    float sat = min(max(mu_dot_n, %s), %s);" % (zero, one))
    w("    float y = abs(x0) <= x1 ? s * s / x : sat;")
    w("    return (scale * y + bias) * (%s * amplitude / l);  // 2 pi a / lambda" % lit(two_pi, lang))
    w("}")
    w("")
    for count in SG_COUNTS:
        axes = [tuple(f32_nearest(c) for c in a) for a in gen_sg_reference.bakinglab_axes(count)]
        lam = f32_nearest(gen_sg_reference.bakinglab_sharpness(count))
        p = "sphbasis_sg%d" % count
        w("/// BakingLab's hemisphere set of %d lobes (Pettineo and Neubelt; sg::bakinglab_axes(%d)," % (
            count, count))
        w("/// sg::bakinglab_sharpness(%d)): a Fibonacci spiral of %d points, those with z >= 0, one" % (
            count, 2 * count))
        w("/// sharpness. Each value the float nearest to the exact construction.")
        w("%s %s_sharpness = %s;" % (L.const, p, lit(lam, lang)))
        w(L.v3_array(p + "_axis", axes))
        w("")
        w("/// The %d unit-amplitude lobes of the set at the unit direction d, as" % count)
        w("/// sphbasis::basis_eval<SphericalGaussian>(%d, ...) (below the horizon as they are)." % count)
        w("void %s_eval(%s d, out float g[%d])" % (p, L.vec3, count))
        w("{")
        w("    for (int k = 0; k < %d; ++k) {" % count)
        w("        %s a = %s_axis[k];" % (L.vec3, p))
        w("        float c = a.x * d.x + a.y * d.y + a.z * d.z;")
        w("        g[k] = exp(%s_sharpness * (c - %s));" % (p, one))
        w("    }")
        w("}")
        w("")
        out += shader_sums(L, [("sg%d" % count, "SphericalGaussian", count)])
        w("/// The irradiance of %d RGB radiance lobes of the set (amplitudes c[k]) at the unit" % count)
        w("/// normal n by Hill's fit, as BakingLab shades an SG light map: sum_k c[k]")
        w("/// sphbasis_sg_irradiance_fitted(axis_k, sharpness, 1, n) (sg::irradiance_fitted per lobe).")
        w("%s %s_irradiance(%s c[%d], %s n)" % (L.vec3, p, L.vec3, count, L.vec3))
        w("{")
        w("    %s e = %s(%s);" % (L.vec3, L.vec3, zero) if lang == "glsl" else
          "    float3 e = float3(0.0f, 0.0f, 0.0f);")
        w("    for (int k = 0; k < %d; ++k)" % count)
        w("        e = e + c[k] * sphbasis_sg_irradiance_fitted(%s_axis[k], %s_sharpness, %s, n);" % (
            p, p, one))
        w("    return e;")
        w("}")
        w("")
    return out


# ---------------------------------------------------------------------------------------------
# ZH3 and L1 SH with the Geomerics reconstruction.


def shader_zh3(L):
    lang = L.lang
    hdr = "basis/zh3.hpp"
    y00 = checked(1 / (2 * mp.sqrt(mp.pi)), hdr, "y00")
    y1 = checked(mp.sqrt(3 / (4 * mp.pi)), hdr, "y1")
    y20 = checked(mp.sqrt(5 / (16 * mp.pi)), hdr, "y20")
    hc1 = checked(mp.mpf("0.08"), hdr, "hallucinate_c1")
    hc2 = checked(mp.mpf("0.6"), hdr, "hallucinate_c2")
    rmax = checked(mp.sqrt(3), hdr, "max_ratio")
    one, zero = L.n("1.0"), L.n("0.0")
    out = []
    w = out.append
    w("/// ZH3 (Roughton, Sloan, Silvennoinen, Iwanicki and Shirley, \"ZH3: Quadratic Zonal Harmonics\",")
    w("/// i3D 2024) at the unit direction n from its 5 values c = (e_0, e_1-1, e_10, e_11, z) of one")
    w("/// channel (zh3::fit): e_0 y_00 + sum_m e_1m y_1m(n) + z Y_20(a . n) with the axis a the unit")
    w("/// (e_11, e_1-1, e_10), +z where that is zero or not finite; as zh3::Expansion<float>(c)(n).")
    w("float sphbasis_zh3_eval(float c[5], %s n)" % L.vec3)
    w("{")
    w("    float x = c[3]; float y = c[1]; float z = c[2];")
    w("    float len = sqrt(x * x + y * y + z * z);")
    w("    %s a = %s(%s, %s, %s);" % (L.vec3, L.vec3, zero, zero, one))
    w("    if (len > %s && !isinf(len)) a = %s(x / len, y / len, z / len);" % (zero, L.vec3))
    w("    float t = a.x * n.x + a.y * n.y + a.z * n.z;")
    w("    return %s * c[0] + %s * c[3] * n.x + %s * c[1] * n.y + %s * c[2] * n.z" % (
        lit(y00, lang), lit(y1, lang), lit(y1, lang), lit(y1, lang)))
    w("        + %s * c[4] * (%s * t * t - %s);  // y00, y1, y20: 1/(2 sqrt(pi)), sqrt(3/(4 pi)), sqrt(5/(16 pi))" % (
        lit(y20, lang), L.n("3.0"), one))
    w("}")
    w("")
    w("/// The hallucinated zonal coefficient z of ZH3 from the 4 values sh = (e_0, e_1-1, e_10, e_11)")
    w("/// of an irradiance (Roughton et al. 2024), as zh3::hallucinate's out[4] (which computes in")
    w("/// double; here float): r = min(1.5 |e_1| / |e_0|, sqrt(3)), z = e_0 (0.08 r + 0.6 r^2) / 4,")
    w("/// 0 when e_0 = 0 or |e_1| is not finite in float (|sh| > 1e19).")
    w("float sphbasis_zh3_hallucinate(float sh[4])")
    w("{")
    w("    float e0 = sh[0];")
    w("    float l1 = sqrt(sh[1] * sh[1] + sh[2] * sh[2] + sh[3] * sh[3]);")
    w("    if (e0 == %s || %s) return %s;" % (zero, L.not_finite("l1"), zero))
    w("    float r = min(%s * l1 / abs(e0), %s);  // sqrt(3)" % (L.n("1.5"), lit(rmax, lang)))
    w("    return %s * e0 * (%s * r + %s * r * r);" % (L.n("0.25"), lit(hc1, lang), lit(hc2, lang)))
    w("}")
    w("")
    w("/// ZH3 hallucinated, from the 4 stored values sh of one channel at the unit direction n, as")
    w("/// zh3::eval of zh3::hallucinate(sh) (the representation \"zh3-hallucinate\").")
    w("float sphbasis_zh3_hallucinate_eval(float sh[4], %s n)" % L.vec3)
    w("{")
    w("    float c[5];")
    w("    for (int k = 0; k < 4; ++k) c[k] = sh[k];")
    w("    c[4] = sphbasis_zh3_hallucinate(sh);")
    w("    return sphbasis_zh3_eval(c, n);")
    w("}")
    w("")
    return out


def shader_l1_nonlinear(L):
    lang = L.lang
    hdr = "basis/sh_l1_nonlinear.hpp"
    y00 = checked(1 / (2 * mp.sqrt(mp.pi)), hdr, "y00")
    hy1 = checked(mp.sqrt(3 / (4 * mp.pi)) / 2, hdr, "half_y1")
    one, zero, two = L.n("1.0"), L.n("0.0"), L.n("2.0")
    out = []
    w = out.append
    w("/// L1 SH with the non-linear reconstruction of Geomerics (Probulator's \"Spherical Harmonics")
    w("/// L1 [Geomerics]\") at the unit direction n from the 4 values c = (e_0, e_1-1, e_10, e_11) of one")
    w("/// channel (the signal's own L0/L1 SH coefficients): R0 = |e_0| y_00, R1 = sqrt(3/(4 pi))/2")
    w("/// (e_11, e_1-1, e_10) (times sign(e_0)), r = |R1|/R0, p = 1 + 2r, a = (1 - r)/(1 + r),")
    w("/// f = sign(e_0) R0 (a + (1 - a)(p + 1) q^p), q = max(0, (1 + n . R1/|R1|)/2); the linear L1")
    w("/// expansion when e_0 = 0 or not finite. As sh_l1_nonlinear::Expansion<float>(c)(n), whose")
    w("/// set-up is in double; here float (|c| < 1e18 keeps |R1|^2 finite in float).")
    w("float sphbasis_sh_l1_nonlinear_eval(float c[4], %s n)" % L.vec3)
    w("{")
    w("    float e0 = c[0];")
    w("    float hx = %s * c[3]; float hy = %s * c[1]; float hz = %s * c[2];  // sqrt(3/(4 pi))/2" % (
        lit(hy1, lang), lit(hy1, lang), lit(hy1, lang)))
    w("    float len = sqrt(hx * hx + hy * hy + hz * hz);")
    w("    if (e0 == %s || %s || %s) {" % (zero, L.not_finite("len"), L.not_finite("e0")))
    w("        float tl = (%s * hx) * n.x + (%s * hy) * n.y + (%s * hz) * n.z;" % (two, two, two))
    w("        return %s * e0 + tl;  // 1/(2 sqrt(pi))" % lit(y00, lang))
    w("    }")
    w("    float s = e0 < %s ? -%s : %s;" % (zero, one, one))
    w("    float R0 = abs(%s * e0);" % lit(y00, lang))
    w("    %s d = %s(%s, %s, %s);" % (L.vec3, L.vec3, zero, zero, zero))
    w("    if (len > %s) d = %s(s * hx / len, s * hy / len, s * hz / len);" % (zero, L.vec3))
    w("    float r = len / R0;")
    w("    float a = (%s - r) / (%s + r);" % (one, one))
    w("    float p = %s + %s * r;" % (one, two))
    w("    float scale = R0 * (%s - a) * (p + %s);" % (one, one))
    w("    float t = d.x * n.x + d.y * n.y + d.z * n.z;")
    w("    float q = max(%s, %s * (%s + t));" % (zero, L.n("0.5"), one))
    w("    return s * (R0 * a + scale * pow(q, p));")
    w("}")
    return out


def shader_engine_all(lang):
    L = _Lang(lang)
    out = []
    out += shader_ambient_cube(L)
    out += shader_sums(L, [("ambient_cube", "AmbientCube", 6), ("ambient_cube5", "AmbientCube", 5)])
    out += shader_ambient_dice(L)
    out += shader_sums(L, [("ambient_dice", "AmbientDice", 12)])
    out += shader_ambient_dice_faces(L)
    out += shader_sums(L, [("ambient_dice_bezier", "AmbientDiceBezier", 36),
                           ("ambient_dice_linear", "AmbientDiceLinear", 12)])
    out += shader_sg(L)
    out += shader_zh3(L)
    out += shader_l1_nonlinear(L)
    return "\n".join(out).rstrip()
