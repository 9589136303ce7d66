// GPU/C++ agreement of the shader twins: runs the functions of shaders/sphbasis.glsl as an OpenGL
// 4.3 compute shader on Mesa's llvmpipe (EGL surfaceless: no display, no GPU) over a grid of
// directions including the poles, the horizon and x = y = 0, reads the values back and compares
// them with the C++ kernels in float: sh::eval_unit<N>, sh::irradiance, the H-basis, modified
// H-basis and HL2 kernels and expansion sums (basis/hbasis.hpp, basis/hl2.hpp), clamped_cosine,
// toksvig::factor / specular / specular_from_dots; the param/ direction <-> texture mappings
// (octahedral, cube map, concentric, paraboloid, the dual paraboloid layout); and Ishmukhametov's
// Listing 2.1/2.2 shader functions against a double reference from ops/projection.hpp.
//
// Error measure: |gpu - cpu| in units of the float ulp of max(|cpu|, scale), where scale is the
// largest magnitude the function reaches in its band (sqrt((2l+1)/(4 pi)) for y_lm; for the
// irradiance, the sum of its nine terms' magnitudes): a plain relative ulp count is meaningless
// where a function crosses zero (at x = y = 0 the m != 0 functions are exactly 0 on both sides).
//
// Not a Catch2 test: it needs a driver, so it is its own executable and ctest (label shaders).
// If no context can be created it says why and fails: a missing driver is never a pass.
//
// Usage: sphbasis_shader_test [path/to/sphbasis.glsl] (default: the source tree's shaders/).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "gl_harness.hpp"
#include "sphbasis/basis/hbasis.hpp"
#include "sphbasis/basis/hl2.hpp"
#include "sphbasis/basis/sh.hpp"
#include "sphbasis/core/clamped_cosine.hpp"
#include "sphbasis/core/quadrature.hpp"
#include "sphbasis/ops/projection.hpp"
#include "sphbasis/ops/sh_convolution.hpp"
#include "sphbasis/param/concentric.hpp"
#include "sphbasis/param/cubemap.hpp"
#include "sphbasis/param/dual_paraboloid.hpp"
#include "sphbasis/param/octahedral.hpp"
#include "sphbasis/shading/toksvig.hpp"

// The example's C++ mirror (examples/shader_mirror/) and its procedural textures.
#include "irradiance_normal_map.hpp"
#include "procedural_textures.hpp"

namespace {

using namespace shader_harness;

// Stated bound. Measured on Mesa 22.3.6 llvmpipe (LLVM 15, x86-64) against g++ 12 -O3
// -march=native -ffp-contract=off: eval1..8 bit-identical since both sides write Q_{m+2}^m and
// Q_{m+3}^m as polynomials in z^2 (with the recurrence there: up to 3 ulps), irradiance 3 ulps
// (llvmpipe fuses some multiply-adds). The worst case is printed every run.
// (With the C++ side also fusing, -ffp-contract=fast, the two disagree by up to 6 ulps.)
constexpr double max_ulps = 4.0;
// The other families, measured on the same driver and compiler:
//  - H-basis 4/6, modified H-basis 4/6, HL2, and their RGB expansion sums: bit-identical to the
//    C++ kernels at every direction (0 ulps). Bound 1 ulp for a kernel value (room for one fused
//    multiply-add in the driver), 2 for a sum; a constant one float away from the C++ one
//    already gives 1 ulp at many directions (the bit-identical count drops), a constant
//    mis-typed in the 6th digit (Listing 2.2's 1.54509) gives tens of ulps.
//  - Listing 2.1/2.2 (SH -> modified H-basis) against a double reference built from the library's
//    least-squares matrix: coefficients 0.77, irradiance 2.35-3.05 ulps of the terms' magnitude
//    sum; bound 4.
//  - Toksvig: the factor (eq. 6) bit-identical (bound 3: GLSL's division is 2.5 ulps); eq. 8 and
//    eq. 9 16.5 and 6 ulps of the lobe's peak (1 + f_t s)/(1 + s): llvmpipe's pow, which GLSL
//    specifies only as exp2(y log2 x) (error growing with |y log2 x|, here up to s = 1000);
//    bound 64.
//  - The clamped-cosine factors a_0..a_7: exactly float(clamped_cosine(l)) (bound 0).
constexpr double max_ulps_hbasis = 1.0;
constexpr double max_ulps_hbasis_sum = 2.0;
constexpr double max_ulps_listing22 = 4.0;
constexpr double max_ulps_toksvig_factor = 3.0;
constexpr double max_ulps_toksvig_specular = 64.0;
//  - The param/ mappings, every component (in [-1, 1]) in ulps of 1 (2^-23), over the directions
//    above plus the cube-face edges and corners, and a 17 x 17 grid of texture points on each face
//    (corners, edges, centre) plus random ones; faces must agree exactly (0 of 5308 differ):
//    octahedral and cube map both ways: bit-identical (0 ulps; bound 1 for one fused
//    multiply-add). square_to_uniform_disk_concentric 0.5, square_to_paraboloid 1.5, the dual
//    paraboloid uv_to_direction 1.25 ulps (llvmpipe's sin/cos; bound 4).
//    uniform_disk_to_square_concentric 18, paraboloid_to_square 18, the dual paraboloid
//    direction_to_uv 17 ulps (llvmpipe's atan, a polynomial: ~2e-6 absolute in the texture
//    coordinate, 3e-5 of a texel of a 16-texel face; bound 32).
constexpr double max_ulps_map_rational = 1.0;
constexpr double max_ulps_map_sincos = 4.0;
constexpr double max_ulps_map_atan = 32.0;
//    The same six with the driver's atan/sin/cos substituted on the C++ side
//    (check_maps_same_libm): bound 1.
constexpr double max_ulps_map_same_libm = 1.0;
//  - The example's fragment shader against its GLM mirror (check_example), 16 x 16 pixels x 3
//    channels in ulps of the sum of the terms' magnitudes: max 1 ulp (642/768 bit-identical;
//    GLSL normalize vs glm::normalize then normalize_or_pole); bound 4.
constexpr double max_ulps_example = 4.0;

constexpr int max_n = 8;
constexpr int sh_values = 204;  // sum_{n=1..8} n^2
// Per direction, after the SH values: the SH irradiance (3), the H-basis family (23 values), their
// expansion sums (5 x 3), the Listing 2.2 block (27), Toksvig (3), the clamped-cosine factors (8).
constexpr int irr_at = sh_values;
constexpr int hb_at = irr_at + 3;    // hbasis4 (4), hbasis6 (6), mod4 (4), mod6 (6), hl2 (3)
constexpr int sum_at = hb_at + 23;   // the same five, RGB expansion sums
constexpr int l22_at = sum_at + 15;  // mod6 irradiance, mod4 irradiance, SH -> modH
                                     // irradiance (3 each), SH -> modH coefficients (18)
constexpr int tk_at = l22_at + 27;   // factor, specular, specular_from_dots
constexpr int cc_at = tk_at + 3;     // a_0..a_7
// The param/ mappings: octahedral_to_square (2), square_to_octahedral (3), cube_to_square (u, v,
// face), square_to_cube (3), square_to_uniform_disk_concentric (2),
// uniform_disk_to_square_concentric (2), paraboloid_to_square (2), square_to_paraboloid (3),
// the dual paraboloid layout's direction_to_uv (u, v, face) and uv_to_direction (3).
constexpr int map_at = cc_at + 8;
constexpr int map_values = 26;
constexpr int dual_paraboloid_n = 16;
// The driver's own atan, sin, cos at arguments the CPU computed (see check_maps_same_libm).
constexpr int libm_at = map_at + map_values;
constexpr int stride = libm_at + 6;
constexpr int hb_sizes[5] = {4, 6, 4, 6, 3};
const char* const hb_names[5] = {"hbasis4", "hbasis6", "hbasis_mod4", "hbasis_mod6", "hl2"};

int offset_of(int n) {
    int o = 0;
    for (int k = 1; k < n; ++k) o += k * k;
    return o;
}

std::string compute_source(const std::string& library) {
    std::ostringstream s;
    s << "#version 430\n" << library << "\n";
    s << "layout(local_size_x = 64) in;\n"
         "layout(std430, binding = 0) readonly buffer Dirs { vec4 dirs[]; };\n"
         "layout(std430, binding = 1) readonly buffer Coef { vec4 coef[]; };\n"
         "layout(std430, binding = 2) writeonly buffer Vals { float vals[]; };\n"
         "layout(std430, binding = 3) readonly buffer Tk { vec4 tk[]; };\n"
         "layout(std430, binding = 4) readonly buffer Uv { vec4 uvs[]; };\n"
         "layout(std430, binding = 5) readonly buffer Args { vec4 args[]; };\n"
         "uniform uint count;\n"
         "void main() {\n"
         "    uint i = gl_GlobalInvocationID.x;\n"
         "    if (i >= count) return;\n"
         "    vec3 d = dirs[i].xyz;\n"
         "    uint base = i * "
      << stride << "u;\n";
    for (int n = 1; n <= max_n; ++n) {
        s << "    { float s[" << n * n << "]; sphbasis_sh_eval" << n << "(d, s);\n"
          << "      for (int k = 0; k < " << n * n << "; ++k) vals[base + " << offset_of(n)
          << "u + uint(k)] = s[k]; }\n";
    }
    s << "    vec3 L[9];\n"
         "    for (int k = 0; k < 9; ++k) L[k] = coef[k].xyz;\n"
         "    vec3 e = sphbasis_sh_irradiance(L, d);\n"
      << "    vals[base + " << sh_values << "u] = e.x; vals[base + " << sh_values + 1
      << "u] = e.y; vals[base + " << sh_values + 2 << "u] = e.z;\n";
    s << "    uint o = base + " << hb_at << "u;\n";
    for (int b = 0; b < 5; ++b)
        s << "    { float h[" << hb_sizes[b] << "]; sphbasis_" << hb_names[b] << "_eval(d, h);\n"
          << "      for (int k = 0; k < " << hb_sizes[b]
          << "; ++k) vals[o + uint(k)] = h[k]; o += " << hb_sizes[b] << "u; }\n";
    s << "    vec3 c6[6];\n"
         "    for (int k = 0; k < 6; ++k) c6[k] = coef[9 + k].xyz;\n"
         "    vec3 c4[4];\n"
         "    for (int k = 0; k < 4; ++k) c4[k] = c6[k];\n"
         "    vec3 c3[3];\n"
         "    for (int k = 0; k < 3; ++k) c3[k] = c6[k];\n";
    for (int b = 0; b < 5; ++b) {
        const int n = hb_sizes[b];
        s << "    { vec3 f = sphbasis_" << hb_names[b] << "_eval_sum(c" << n << ", d);\n"
          << "      vals[o] = f.x; vals[o + 1u] = f.y; vals[o + 2u] = f.z; o += 3u; }\n";
    }
    s << "    { vec3 f = sphbasis_hbasis_mod6_irradiance(c6, d);\n"
         "      vals[o] = f.x; vals[o + 1u] = f.y; vals[o + 2u] = f.z; o += 3u; }\n"
         "    { vec3 f = sphbasis_hbasis_mod4_irradiance(c4, d);\n"
         "      vals[o] = f.x; vals[o + 1u] = f.y; vals[o + 2u] = f.z; o += 3u; }\n"
         "    { vec3 f = sphbasis_sh_irradiance_hbasis_mod6(L, d);\n"
         "      vals[o] = f.x; vals[o + 1u] = f.y; vals[o + 2u] = f.z; o += 3u; }\n"
         "    { vec3 h[6]; sphbasis_sh_to_hbasis_mod6(L, h);\n"
         "      for (int k = 0; k < 6; ++k) { vals[o] = h[k].x; vals[o + 1u] = h[k].y;\n"
         "          vals[o + 2u] = h[k].z; o += 3u; } }\n"
         "    vec4 t = tk[i];\n"
         "    vals[o] = sphbasis_toksvig_factor(t.y, t.z);\n"
         "    vals[o + 1u] = sphbasis_toksvig_specular(t.x, t.y, t.z);\n"
         "    vals[o + 2u] = sphbasis_toksvig_specular_from_dots(t.x, t.w, t.z);\n"
         "    o += 3u;\n"
         "    for (int l = 0; l < 8; ++l) vals[o + uint(l)] = sphbasis_clamped_cosine(l);\n"
         "    o += 8u;\n"
         "    vec2 uv = uvs[i].xy; int uvface = int(uvs[i].z);\n"
         "    int face;\n"
         "    vec2 q; vec3 r;\n"
         "    q = sphbasis_octahedral_to_square(d); vals[o] = q.x; vals[o + 1u] = q.y;\n"
         "    r = sphbasis_square_to_octahedral(uv);\n"
         "    vals[o + 2u] = r.x; vals[o + 3u] = r.y; vals[o + 4u] = r.z;\n"
         "    q = sphbasis_cube_to_square(d, face);\n"
         "    vals[o + 5u] = q.x; vals[o + 6u] = q.y; vals[o + 7u] = float(face);\n"
         "    r = sphbasis_square_to_cube(uvface, uv);\n"
         "    vals[o + 8u] = r.x; vals[o + 9u] = r.y; vals[o + 10u] = r.z;\n"
         "    q = sphbasis_square_to_uniform_disk_concentric(uv); vals[o + 11u] = q.x;\n"
         "    vals[o + 12u] = q.y;\n"
         "    q = sphbasis_uniform_disk_to_square_concentric(d.xy); vals[o + 13u] = q.x;\n"
         "    vals[o + 14u] = q.y;\n"
         "    q = sphbasis_paraboloid_to_square(d); vals[o + 15u] = q.x; vals[o + 16u] = q.y;\n"
         "    r = sphbasis_square_to_paraboloid(uv);\n"
         "    vals[o + 17u] = r.x; vals[o + 18u] = r.y; vals[o + 19u] = r.z;\n"
         "    q = sphbasis_dual_paraboloid_direction_to_uv(d, "
      << dual_paraboloid_n
      << ", face);\n"
         "    vals[o + 20u] = q.x; vals[o + 21u] = q.y; vals[o + 22u] = float(face);\n"
         "    r = sphbasis_dual_paraboloid_uv_to_direction(uvface % 2, uv, "
      << dual_paraboloid_n
      << ");\n"
         "    vals[o + 23u] = r.x; vals[o + 24u] = r.y; vals[o + 25u] = r.z;\n"
         "    o += 26u;\n"
         "    vec4 a = args[i];\n"
         "    vals[o] = atan(a.x); vals[o + 1u] = atan(a.y);\n"
         "    vals[o + 2u] = sin(a.z); vals[o + 3u] = cos(a.z);\n"
         "    vals[o + 4u] = sin(a.w); vals[o + 5u] = cos(a.w);\n"
         "}\n";
    return s.str();
}

// Texture coordinates for the inverse mappings, with a face (0..5) each: a 17 x 17 grid on every
// face (corners, edges and the centre on it), then random points (fixed seed).
std::vector<float> texture_points(unsigned count) {
    std::vector<float> uv;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j <= 16; ++j)
            for (int i = 0; i <= 16; ++i)
                uv.insert(uv.end(), {float(i) / 16.0f, float(j) / 16.0f, float(f), 0});
    std::mt19937 rng(1234u);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    while (uv.size() < std::size_t(count) * 4) {
        const float a = u(rng), b = u(rng);
        uv.insert(uv.end(), {a, b, float(uv.size() / 4 % 6), 0});
    }
    uv.resize(std::size_t(count) * 4);
    return uv;
}

// The H-basis family against basis_eval / basis_eval_sum in float (same kernels, same operation
// order). Scale of each function: its largest magnitude on the upper hemisphere, 1/sqrt(2 pi)
// for H1 and sqrt(3/(2 pi)) (> sqrt(15/(2 pi))/2) for the rest; of a sum, sum_k |c_k B_k|.
template <class B>
bool check_hbasis_one(int which, int n, const std::vector<float>& dirs,
                      const std::vector<float>& coef, const std::vector<float>& gpu) {
    const unsigned count = unsigned(dirs.size() / 4);
    int off = hb_at;
    for (int b = 0; b < which; ++b) off += hb_sizes[b];
    const int sum_off = sum_at + 3 * which;
    Worst eval, sum;
    float c[3][6];
    for (int k = 0; k < n; ++k)
        for (int ch = 0; ch < 3; ++ch) c[ch][k] = coef[std::size_t(4 * (9 + k) + ch)];
    for (unsigned i = 0; i < count; ++i) {
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        // The kernel itself (basis_eval would first renormalise the direction, and a few of these
        // float directions are not fixed points of normalize_or_pole: it moves them by an ulp).
        float h[6];
        B::with_kernel(n, [&](auto kernel) { kernel(x, y, z, [&](int k, float v) { h[k] = v; }); });
        const float* g = &gpu[std::size_t(i) * stride];
        for (int k = 0; k < n; ++k)
            eval.add(g[off + k], h[k], (k == 0 && n != 3) ? 0.3989422804 : 0.6909882989);
        for (int ch = 0; ch < 3; ++ch) {
            // basis_eval_sum's accumulation (basis.hpp, sum_at) without the renormalisation.
            float ref = 0;
            for (int k = 0; k < n; ++k) ref = ref + c[ch][k] * h[k];
            double scale = 0;
            for (int k = 0; k < n; ++k) scale += std::abs(double(c[ch][k]) * h[k]);
            sum.add(g[sum_off + ch], ref, scale);
        }
    }
    const std::string name = std::string("sphbasis_") + hb_names[which];
    return eval.report((name + "_eval").c_str(), max_ulps_hbasis) &&
           sum.report((name + "_eval_sum").c_str(), max_ulps_hbasis_sum);
}

bool check_hbasis(const std::vector<float>& dirs, const std::vector<float>& coef,
                  const std::vector<float>& gpu) {
    bool ok = check_hbasis_one<sphbasis::HBasis>(0, 4, dirs, coef, gpu);
    ok = check_hbasis_one<sphbasis::HBasis>(1, 6, dirs, coef, gpu) && ok;
    ok = check_hbasis_one<sphbasis::HBasisMod>(2, 4, dirs, coef, gpu) && ok;
    ok = check_hbasis_one<sphbasis::HBasisMod>(3, 6, dirs, coef, gpu) && ok;
    ok = check_hbasis_one<sphbasis::HL2>(4, 3, dirs, coef, gpu) && ok;
    return ok;
}

// Ishmukhametov's Listings 2.1/2.2 against an independent double reference: the library's
// least-squares SH -> modified H-basis matrix over the hemisphere (ops/projection.hpp), the
// clamped-cosine factors (core/clamped_cosine.hpp) and basis_eval<HBasisMod> in double. The
// shader rounds differently (folded float constants, the listing's (1 - z) H3), so the measure
// is ulps of the float of the sum of the terms' magnitudes.
bool check_listing22(const std::vector<float>& dirs, const std::vector<float>& coef,
                     const std::vector<float>& gpu) {
    using namespace sphbasis;
    const unsigned count = unsigned(dirs.size() / 4);
    const Eigen::MatrixXd t =
        conversion(evaluator<SH>(9), evaluator<HBasisMod>(6), hemisphere_rule(8));
    const int band[9] = {0, 1, 1, 1, 2, 2, 2, 2, 2};
    double hm[3][6], hmag[3][6];  // modified H-basis coefficients of E/pi, and their term sums
    for (int ch = 0; ch < 3; ++ch)
        for (int i = 0; i < 6; ++i) {
            hm[ch][i] = hmag[ch][i] = 0;
            for (int j = 0; j < 9; ++j) {
                const double term =
                    t(i, j) * clamped_cosine(band[j]) * double(coef[std::size_t(4 * j + ch)]);
                hm[ch][i] += term;
                hmag[ch][i] += std::abs(term);
            }
        }
    Worst coeffs, irr6, irr4, sh_irr;
    for (unsigned i = 0; i < count; ++i) {
        const float* g = &gpu[std::size_t(i) * stride];
        const double x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        double h[6];
        basis_eval<HBasisMod>(6, x, y, z, h);
        for (int ch = 0; ch < 3; ++ch) {
            for (int k = 0; k < 6; ++k)
                coeffs.add(g[l22_at + 9 + 3 * k + ch], hm[ch][k], hmag[ch][k]);
            double e6 = 0, s6 = 0, e4 = 0, s4 = 0, e = 0, s = 0;
            for (int k = 0; k < 6; ++k) {
                const double c = coef[std::size_t(4 * (9 + k) + ch)];
                e6 += c * h[k], s6 += std::abs(c * h[k]);
                if (k < 4) e4 += c * h[k], s4 += std::abs(c * h[k]);
                e += hm[ch][k] * h[k], s += hmag[ch][k] * std::abs(h[k]);
            }
            irr6.add(g[l22_at + ch], e6, s6);
            irr4.add(g[l22_at + 3 + ch], e4, s4);
            sh_irr.add(g[l22_at + 6 + ch], e, s);
        }
    }
    bool ok = coeffs.report("sphbasis_sh_to_hbasis_mod6 (vs double)", max_ulps_listing22);
    ok = irr6.report("sphbasis_hbasis_mod6_irradiance (vs double)", max_ulps_listing22) && ok;
    ok = irr4.report("sphbasis_hbasis_mod4_irradiance (vs double)", max_ulps_listing22) && ok;
    ok = sh_irr.report("sphbasis_sh_irradiance_hbasis_mod6 (vs double)", max_ulps_listing22) && ok;
    return ok;
}

// Toksvig's eqs. 6, 8, 9 against shading/toksvig.hpp in float. The factor in ulps of itself;
// the specular in ulps of the lobe's peak (1 + f_t s)/(1 + s): GLSL's pow promises no better
// than exp2(y log2 x) (GLSL 4.50, section 4.7.1), whose error grows with |y log2 x|.
bool check_toksvig(const std::vector<float>& tk, const std::vector<float>& gpu) {
    const unsigned count = unsigned(tk.size() / 4);
    Worst f, spec, dots;
    for (unsigned i = 0; i < count; ++i) {
        const float* g = &gpu[std::size_t(i) * stride];
        const float ndh = tk[4 * i], len = tk[4 * i + 1], s = tk[4 * i + 2], ndn = tk[4 * i + 3];
        f.add(g[tk_at], sphbasis::toksvig::factor(len, s), 0x1p-126);
        spec.add(g[tk_at + 1], sphbasis::toksvig::specular(ndh, len, s),
                 sphbasis::toksvig::relative_intensity(len, s));
        const float l2 = std::sqrt(std::min(std::max(ndn, 0.0f), 1.0f));
        dots.add(g[tk_at + 2], sphbasis::toksvig::specular_from_dots(ndh, ndn, s),
                 sphbasis::toksvig::relative_intensity(l2, s));
    }
    bool ok = f.report("sphbasis_toksvig_factor", max_ulps_toksvig_factor);
    ok = spec.report("sphbasis_toksvig_specular (ulps of the peak)", max_ulps_toksvig_specular) &&
         ok;
    ok = dots.report("sphbasis_toksvig_specular_from_dots (ulps of the peak)",
                     max_ulps_toksvig_specular) &&
         ok;
    return ok;
}

// The clamped-cosine constants: exactly the float of clamped_cosine(l).
bool check_clamped_cosine(const std::vector<float>& gpu) {
    Worst w;
    for (int l = 0; l < 8; ++l)
        w.add(gpu[std::size_t(cc_at + l)], float(sphbasis::clamped_cosine(l)), 0x1p-126);
    return w.report("sphbasis_clamped_cosine a_0..a_7", 0.0);
}

// The param/ mappings against the C++ free functions (and the DualParaboloid<float> class) in
// float: every component in ulps of 1 (2^-23; the components lie in [-1, 1]), faces exactly.
bool check_maps(const std::vector<float>& dirs, const std::vector<float>& uvs,
                const std::vector<float>& gpu) {
    using namespace sphbasis::param;
    const unsigned count = unsigned(dirs.size() / 4);
    const DualParaboloid<float> dual(dual_paraboloid_n);
    Worst oct_f, oct_i, cube_f, cube_i, disk_f, disk_i, par_f, par_i, dual_f, dual_i;
    std::size_t face_mismatch = 0;
    auto add2 = [](Worst& w, const float* g, float a, float b) {
        w.add(g[0], a, 1.0);
        w.add(g[1], b, 1.0);
    };
    auto add3 = [](Worst& w, const float* g, const sphbasis::vec3<float>& v) {
        w.add(g[0], v.x, 1.0);
        w.add(g[1], v.y, 1.0);
        w.add(g[2], v.z, 1.0);
    };
    for (unsigned i = 0; i < count; ++i) {
        const float* g = &gpu[std::size_t(i) * stride + map_at];
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        const float u = uvs[4 * i], v = uvs[4 * i + 1];
        const int face = int(uvs[4 * i + 2]);
        const Point2<float> o = octahedral_to_square(x, y, z);
        add2(oct_f, g, o.x, o.y);
        add3(oct_i, g + 2, square_to_octahedral(u, v));
        const FaceUV<float> c = cube_to_square(x, y, z);
        if (int(g[7]) != c.face) ++face_mismatch;
        add2(cube_f, g + 5, c.u, c.v);
        add3(cube_i, g + 8, square_to_cube(face, u, v));
        const Point2<float> dk = square_to_uniform_disk_concentric(u, v);
        add2(disk_i, g + 11, dk.x, dk.y);
        const Point2<float> sq = uniform_disk_to_square_concentric(x, y);
        add2(disk_f, g + 13, sq.x, sq.y);
        const Point2<float> p = paraboloid_to_square(x, y, z);
        add2(par_f, g + 15, p.x, p.y);
        add3(par_i, g + 17, square_to_paraboloid(u, v));
        const FaceUV<float> du = dual.direction_to_uv(x, y, z);
        if (int(g[22]) != du.face) ++face_mismatch;
        add2(dual_f, g + 20, du.u, du.v);
        add3(dual_i, g + 23, dual.uv_to_direction(face % 2, u, v));
    }
    bool ok = oct_f.report("sphbasis_octahedral_to_square", max_ulps_map_rational);
    ok = oct_i.report("sphbasis_square_to_octahedral", max_ulps_map_rational) && ok;
    ok = cube_f.report("sphbasis_cube_to_square", max_ulps_map_rational) && ok;
    ok = cube_i.report("sphbasis_square_to_cube", max_ulps_map_rational) && ok;
    ok = disk_i.report("sphbasis_square_to_uniform_disk_concentric", max_ulps_map_sincos) && ok;
    ok = disk_f.report("sphbasis_uniform_disk_to_square_concentric", max_ulps_map_atan) && ok;
    ok = par_f.report("sphbasis_paraboloid_to_square", max_ulps_map_atan) && ok;
    ok = par_i.report("sphbasis_square_to_paraboloid", max_ulps_map_sincos) && ok;
    ok =
        dual_f.report("sphbasis_dual_paraboloid_direction_to_uv (n = 16)", max_ulps_map_atan) && ok;
    ok = dual_i.report("sphbasis_dual_paraboloid_uv_to_direction (n = 16)", max_ulps_map_sincos) &&
         ok;
    std::printf("  cube and dual paraboloid faces: %zu of %u directions differ  %s\n",
                face_mismatch, 2 * count, face_mismatch ? "FAIL" : "ok");
    return ok && face_mismatch == 0;
}

// The shader-mirror example: examples/shader_mirror/irradiance_normal_map.frag drawn on llvmpipe
// over a 16 x 16 float target (pixel (i, j) reads texel (i, j), nearest filtering) against its
// C++ mirror irradiance_normal_map.hpp. Error per channel in ulps of the sum of the expansion's
// terms' magnitudes, sum_k |c_k H_k(n)|. The #include of sphbasis.glsl is pasted in, as an
// engine's includer would (the GL driver has no GL_GOOGLE_include_directive).
bool check_example(const Gl& gl, const std::string& library) {
    const std::string dir = std::string(SPHBASIS_SOURCE_DIR) + "/examples/shader_mirror/";
    std::string frag = read_file(dir + "irradiance_normal_map.frag");
    auto replace_line = [&frag](const std::string& line, const std::string& with) {
        const std::size_t at = frag.find(line);
        if (at == std::string::npos)
            fail("irradiance_normal_map.frag has no line \"" + line + "\"");
        frag.replace(at, line.size(), with);
    };
    replace_line("#extension GL_GOOGLE_include_directive : require", "");
    replace_line("#include \"sphbasis.glsl\"", library);
    const std::string vert =
        "#version 450\n"
        "layout(location = 0) out vec2 uv;\n"
        "void main() {\n"
        "    vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);\n"
        "    uv = 0.5 * p + 0.5;\n"
        "    gl_Position = vec4(p, 0.0, 1.0);\n"
        "}\n";
    const unsigned prog = compile_program(gl, vert, frag);

    constexpr int n = 16;
    const shader_mirror::Textures t = shader_mirror::procedural_textures(n, n);
    unsigned tex[5];
    gl.GenTextures(5, tex);
    auto upload = [&](int unit, const float* data, unsigned format) {
        gl.ActiveTexture(GL_TEXTURE0 + unsigned(unit));
        gl.BindTexture(GL_TEXTURE_2D, tex[unit]);
        gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
        gl.TexImage2D(GL_TEXTURE_2D, 0, format == GL_RGB ? GL_RGB32F : GL_RGBA32F, n, n, 0, format,
                      GL_FLOAT, data);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
        gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    };
    upload(0, &t.lightmap_r[0].x, GL_RGBA);
    upload(1, &t.lightmap_g[0].x, GL_RGBA);
    upload(2, &t.lightmap_b[0].x, GL_RGBA);
    upload(3, &t.normal_map[0].x, GL_RGB);
    upload(4, nullptr, GL_RGBA);  // the target
    unsigned fbo = 0, vao = 0;
    gl.GenFramebuffers(1, &fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, tex[4], 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        fail("the RGBA32F framebuffer of the example is not complete");
    gl.GenVertexArrays(1, &vao);
    gl.BindVertexArray(vao);
    gl.Viewport(0, 0, n, n);
    gl.UseProgram(prog);
    gl.DrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> img(std::size_t(n * n * 4), std::nanf(""));
    gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl.ReadPixels(0, 0, n, n, GL_RGBA, GL_FLOAT, img.data());
    gl.Finish();
    if (const unsigned err = gl.GetError(); err != GL_NO_ERROR) {
        char b[64];
        std::snprintf(b, sizeof b, "OpenGL error 0x%x in the example pass", err);
        fail(b);
    }
    Worst w;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const std::size_t k = std::size_t(j * n + i);
            const glm::vec3 ref = shader_mirror::shade_pixel(t, i, j);
            const glm::vec3 nn = glm::normalize(t.normal_map[k] * 2.0f - 1.0f);
            double h[4];
            sphbasis::basis_eval<sphbasis::HBasis>(4, double(nn.x), double(nn.y), double(nn.z), h);
            const glm::vec4* lm[3] = {&t.lightmap_r[k], &t.lightmap_g[k], &t.lightmap_b[k]};
            for (int ch = 0; ch < 3; ++ch) {
                double scale = 0;
                for (int q = 0; q < 4; ++q) scale += std::abs(double((*lm[ch])[q]) * h[q]);
                w.add(img[4 * k + std::size_t(ch)], ref[ch], scale);
            }
        }
    return w.report("examples/shader_mirror (16 x 16, vs the GLM mirror)", max_ulps_example);
}

// The arguments of the transcendental functions inside the trigonometric mappings, computed on the
// CPU with the C++ side's operations (the concentric map's branches): per direction and texture
// point, the atan argument of uniform_disk_to_square_concentric(x, y) and of
// paraboloid_to_square(d), the sin/cos argument of square_to_uniform_disk_concentric(u, v) and of
// the dual paraboloid's uv_to_direction (after unshrink).
float atan_argument(float px, float py) {
    const float r = std::sqrt(px * px + py * py);
    if (!(r > 0.0f)) return 0.0f;
    return std::fabs(px) >= std::fabs(py) ? py / px : px / py;
}
float sincos_argument(float u, float v) {
    const float qp = 0.78539816339744831f;  // pi/4, the float of the C++ literal
    const float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
    if (a == 0.0f && b == 0.0f) return 0.0f;
    return std::fabs(a) > std::fabs(b) ? qp * (b / a) : qp * (a / b);
}
std::vector<float> transcendental_arguments(const std::vector<float>& dirs,
                                            const std::vector<float>& uvs) {
    using sphbasis::param::detail::unshrink;
    std::vector<float> args(dirs.size());
    for (std::size_t i = 0; i < dirs.size() / 4; ++i) {
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        const float inv = 1.0f / (1.0f + std::fabs(z));
        const float u = uvs[4 * i], v = uvs[4 * i + 1];
        args[4 * i] = atan_argument(x, y);
        args[4 * i + 1] = atan_argument(x * inv, y * inv);
        args[4 * i + 2] = sincos_argument(u, v);
        args[4 * i + 3] =
            sincos_argument(unshrink(u, dual_paraboloid_n), unshrink(v, dual_paraboloid_n));
    }
    return args;
}

// The trigonometric mappings with the C++ operations but the DRIVER's atan, sin and cos (read
// back at the CPU's arguments): what is left is the shader's arithmetic and constants (pi/4,
// 4/pi), so the bound is 1 ulp of 1 where the plain comparison needs 4 (sin/cos) and 32 (atan).
// Measured: bit-identical (0 ulps) at every point. Perturbed constants fail here: 4/pi written
// 1.27324 and pi/4 written 0.785398 in the GLSL give 2 and 1.5 ulps (the plain comparison above
// passes them: llvmpipe's atan error is larger).
bool check_maps_same_libm(const std::vector<float>& dirs, const std::vector<float>& uvs,
                          const std::vector<float>& gpu) {
    using namespace sphbasis::param;
    const unsigned count = unsigned(dirs.size() / 4);
    // The concentric maps of concentric.hpp with given transcendental values.
    auto disk_to_square = [](float px, float py, float at) {
        const float r = std::sqrt(px * px + py * py);
        if (!(r > 0.0f)) return Point2<float>{0.5f, 0.5f};
        float a, b;
        const float four_over_pi = 1.2732395447351627f;
        if (std::fabs(px) >= std::fabs(py)) {
            a = std::copysign(r, px);
            b = a * four_over_pi * at;
        } else {
            b = std::copysign(r, py);
            a = b * four_over_pi * at;
        }
        auto clamp1 = [](float t) { return t > 1.0f ? 1.0f : (t < -1.0f ? -1.0f : t); };
        return Point2<float>{0.5f * (clamp1(a) + 1.0f), 0.5f * (clamp1(b) + 1.0f)};
    };
    auto square_to_disk = [](float u, float v, float sn, float cs) {
        const float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
        if (a == 0.0f && b == 0.0f) return Point2<float>{0.0f, 0.0f};
        if (std::fabs(a) > std::fabs(b)) return Point2<float>{a * cs, a * sn};
        return Point2<float>{b * sn, b * cs};
    };
    Worst disk_f, disk_i, par_f, par_i, dual_f, dual_i;
    for (unsigned i = 0; i < count; ++i) {
        const float* g = &gpu[std::size_t(i) * stride + map_at];
        const float* t = &gpu[std::size_t(i) * stride + libm_at];
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        const float u = uvs[4 * i], v = uvs[4 * i + 1];
        const int face = int(uvs[4 * i + 2]);
        Point2<float> q = disk_to_square(x, y, t[0]);
        disk_f.add(g[13], q.x, 1.0), disk_f.add(g[14], q.y, 1.0);
        const float inv = 1.0f / (1.0f + std::fabs(z));
        q = disk_to_square(x * inv, y * inv, t[1]);
        par_f.add(g[15], q.x, 1.0), par_f.add(g[16], q.y, 1.0);
        dual_f.add(g[20], detail::shrink(q.x, dual_paraboloid_n), 1.0);
        dual_f.add(g[21], detail::shrink(q.y, dual_paraboloid_n), 1.0);
        Point2<float> p = square_to_disk(u, v, t[2], t[3]);
        disk_i.add(g[11], p.x, 1.0), disk_i.add(g[12], p.y, 1.0);
        sphbasis::vec3<float> d = ParaboloidProjection::direction(p.x, p.y);
        par_i.add(g[17], d.x, 1.0), par_i.add(g[18], d.y, 1.0), par_i.add(g[19], d.z, 1.0);
        p = square_to_disk(detail::unshrink(u, dual_paraboloid_n),
                           detail::unshrink(v, dual_paraboloid_n), t[4], t[5]);
        d = ParaboloidProjection::direction(p.x, p.y);
        if (face % 2 == 1) d.z = -d.z;
        dual_i.add(g[23], d.x, 1.0), dual_i.add(g[24], d.y, 1.0), dual_i.add(g[25], d.z, 1.0);
    }
    const double b = max_ulps_map_same_libm;
    bool ok = disk_i.report("sphbasis_square_to_uniform_disk_concentric (driver's sin/cos)", b);
    ok = disk_f.report("sphbasis_uniform_disk_to_square_concentric (driver's atan)", b) && ok;
    ok = par_f.report("sphbasis_paraboloid_to_square (driver's atan)", b) && ok;
    ok = par_i.report("sphbasis_square_to_paraboloid (driver's sin/cos)", b) && ok;
    ok = dual_f.report("sphbasis_dual_paraboloid_direction_to_uv (driver's atan)", b) && ok;
    ok = dual_i.report("sphbasis_dual_paraboloid_uv_to_direction (driver's sin/cos)", b) && ok;
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    const std::string glsl_path =
        argc > 1 ? argv[1] : std::string(SPHBASIS_SOURCE_DIR) + "/shaders/sphbasis.glsl";
    create_context();
    const Gl gl = load_gl();
    const char* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    const char* version = reinterpret_cast<const char*>(gl.GetString(GL_VERSION));
    std::printf("sphbasis_shader_test: %s, OpenGL %s\n", renderer ? renderer : "?",
                version ? version : "?");
    std::printf("  shader file: %s\n", glsl_path.c_str());

    const unsigned prog = compile_program(gl, compute_source(read_file(glsl_path)));

    const std::vector<float> dirs = directions();
    const unsigned count = unsigned(dirs.size() / 4);
    // RGB radiance coefficients of modest size with every term present.
    // Then 6 RGB coefficients for the H-basis family's expansion sums and Listing 2.2 (the first
    // 4 and 3 of them for the 4- and 3-function sums).
    std::vector<float> coef(15 * 4);
    for (std::size_t k = 0; k < 9; ++k) {
        coef[4 * k + 0] = 1.0f / float(k + 1);
        coef[4 * k + 1] = 0.5f - 0.1f * float(k);
        coef[4 * k + 2] = (k % 2 ? -0.3f : 0.7f) + 0.01f * float(k);
    }
    for (std::size_t k = 0; k < 6; ++k) {
        coef[4 * (9 + k) + 0] = 0.8f - 0.25f * float(k);
        coef[4 * (9 + k) + 1] = 0.3f + 0.05f * float(k * k);
        coef[4 * (9 + k) + 2] = (k % 3 ? -0.45f : 1.1f) + 0.02f * float(k);
    }
    // Toksvig inputs per direction: (Na.H, L, s, Na.Na) over and beyond the clamped ranges.
    std::vector<float> tk(std::size_t(count) * 4);
    {
        std::mt19937 rng(7u);
        std::uniform_real_distribution<float> u(-0.1f, 1.1f);
        const float shin[6] = {0.0f, 1.0f, 8.0f, 32.0f, 128.0f, 1000.0f};
        for (unsigned i = 0; i < count; ++i) {
            tk[4 * i + 0] = u(rng);
            tk[4 * i + 1] = i % 7 == 0 ? 1.0f : u(rng);
            tk[4 * i + 2] = shin[i % 6];
            tk[4 * i + 3] = u(rng);
        }
    }
    const std::vector<float> uvs = texture_points(count);
    const std::vector<float> args = transcendental_arguments(dirs, uvs);
    unsigned buf[6];
    gl.GenBuffers(6, buf);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[0]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(dirs.size() * sizeof(float)), dirs.data(),
                  GL_STATIC_DRAW);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[1]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(coef.size() * sizeof(float)), coef.data(),
                  GL_STATIC_DRAW);
    const std::size_t nvals = std::size_t(count) * stride;
    std::vector<float> gpu(nvals, std::nanf(""));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[2]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(nvals * sizeof(float)), gpu.data(),
                  GL_DYNAMIC_READ);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[3]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(tk.size() * sizeof(float)), tk.data(),
                  GL_STATIC_DRAW);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[4]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(uvs.size() * sizeof(float)), uvs.data(),
                  GL_STATIC_DRAW);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[5]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(args.size() * sizeof(float)), args.data(),
                  GL_STATIC_DRAW);
    for (unsigned i = 0; i < 6; ++i) gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buf[i]);
    gl.UseProgram(prog);
    gl.Uniform1ui(gl.GetUniformLocation(prog, "count"), count);
    gl.DispatchCompute((count + 63) / 64, 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[2]);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(nvals * sizeof(float)), gpu.data());
    gl.Finish();
    if (const unsigned err = gl.GetError(); err != GL_NO_ERROR) {
        char b[64];
        std::snprintf(b, sizeof b, "OpenGL error 0x%x", err);
        fail(b);
    }

    // CPU side, in float, and the comparison.
    const double four_pi = 4 * 3.14159265358979323846;
    bool ok = true;
    std::printf("  %u directions (poles, horizon, x = y = 0 included), bound %.1f ulps\n", count,
                max_ulps);
    for (int n = 1; n <= max_n; ++n) {
        double worst = 0;
        std::size_t identical = 0, total = 0;
        unsigned worst_i = 0;
        int worst_k = 0;
        std::vector<float> cpu(std::size_t(n) * std::size_t(n));
        for (unsigned i = 0; i < count; ++i) {
            const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
            switch (n) {
                case 1:
                    sphbasis::sh::eval_unit<1>(x, y, z, cpu.data());
                    break;
                case 2:
                    sphbasis::sh::eval_unit<2>(x, y, z, cpu.data());
                    break;
                case 3:
                    sphbasis::sh::eval_unit<3>(x, y, z, cpu.data());
                    break;
                case 4:
                    sphbasis::sh::eval_unit<4>(x, y, z, cpu.data());
                    break;
                case 5:
                    sphbasis::sh::eval_unit<5>(x, y, z, cpu.data());
                    break;
                case 6:
                    sphbasis::sh::eval_unit<6>(x, y, z, cpu.data());
                    break;
                case 7:
                    sphbasis::sh::eval_unit<7>(x, y, z, cpu.data());
                    break;
                default:
                    sphbasis::sh::eval_unit<8>(x, y, z, cpu.data());
                    break;
            }
            for (int k = 0; k < n * n; ++k) {
                const int l = int(std::sqrt(double(k)));
                const double scale = std::sqrt((2 * l + 1) / four_pi);
                const double c = cpu[std::size_t(k)];
                const double v = gpu[std::size_t(i) * stride + std::size_t(offset_of(n) + k)];
                const double e = std::isfinite(v)
                                     ? std::abs(v - c) / ulp_of(std::max(std::abs(c), scale))
                                     : 1e30;
                identical += (v == c);
                ++total;
                if (e > worst) worst = e, worst_i = i, worst_k = k;
            }
        }
        const bool pass = worst <= max_ulps;
        ok = ok && pass;
        std::printf(
            "  sphbasis_sh_eval%d: max %.2f ulps (direction %u, function %d), %zu/%zu "
            "bit-identical  %s\n",
            n, worst, worst_i, worst_k, identical, total, pass ? "ok" : "FAIL");
    }
    {
        double worst = 0;
        std::size_t identical = 0, total = 0;
        float L[3][9];
        for (int k = 0; k < 9; ++k)
            for (int c = 0; c < 3; ++c) L[c][k] = coef[std::size_t(4 * k + c)];
        for (unsigned i = 0; i < count; ++i) {
            const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
            for (int c = 0; c < 3; ++c) {
                const double ref = sphbasis::sh::irradiance(L[c], x, y, z);
                // The sum of the terms' magnitudes: the scale of a sum's rounding error.
                const double xd = x, yd = y, zd = z;
                const double scale =
                    0.4290 * std::abs(L[c][8] * (xd * xd - yd * yd)) +
                    std::abs(L[c][6] * (0.7431 * zd * zd - 0.2477)) + 0.8862 * std::abs(L[c][0]) +
                    0.8581 * (std::abs(L[c][4] * xd * yd) + std::abs(L[c][7] * xd * zd) +
                              std::abs(L[c][5] * yd * zd)) +
                    1.0233 *
                        (std::abs(L[c][3] * xd) + std::abs(L[c][1] * yd) + std::abs(L[c][2] * zd));
                const double v = gpu[std::size_t(i) * stride + std::size_t(sh_values + c)];
                const double e = std::isfinite(v)
                                     ? std::abs(v - ref) / ulp_of(std::max(std::abs(ref), scale))
                                     : 1e30;
                identical += (v == ref);
                ++total;
                worst = std::max(worst, e);
            }
        }
        const bool pass = worst <= max_ulps;
        ok = ok && pass;
        std::printf("  sphbasis_sh_irradiance: max %.2f ulps, %zu/%zu bit-identical  %s\n", worst,
                    identical, total, pass ? "ok" : "FAIL");
    }
    ok = check_hbasis(dirs, coef, gpu) && ok;
    ok = check_listing22(dirs, coef, gpu) && ok;
    ok = check_toksvig(tk, gpu) && ok;
    ok = check_clamped_cosine(gpu) && ok;
    ok = check_maps(dirs, uvs, gpu) && ok;
    ok = check_maps_same_libm(dirs, uvs, gpu) && ok;
    ok = check_example(gl, read_file(glsl_path)) && ok;
    std::printf("sphbasis_shader_test: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
