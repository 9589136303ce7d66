// GPU/C++ agreement of the renderer's shader twins (shaders/sphbasis_render.glsl) and of the
// hemispherical bases' twins (sphbasis_hsh_eval, sphbasis_makhotkin_eval, sphbasis_zernike_eval
// of shaders/sphbasis.glsl): each runs as an OpenGL 4.3 compute shader on Mesa's llvmpipe
// (gl_harness.hpp) and is compared with the C++ it mirrors:
//   - HSH, Makhotkin, Zernike, 1..8 bands, against HSH/Makhotkin/Zernike::with_kernel in float
//     (the same row recurrence and table), in ulps of the band's scale;
//   - the cube-map footprint against param::CubeMap<float>(n).footprint (indices exactly, the
//     weights in ulps of 1), and lxh-unc shading V . (L x H)(n) against Lxh::shade_unc's
//     arithmetic in double on param::lookup's filtered table;
//   - PCA / CPCA shading against compress::shade (ops/compression.hpp) of a CPCA model of
//     random transfer, with the float weights and exit values the shader reads;
//   - the SVD normal basis against PrtNormalMap::shade_svd's arithmetic in double with the V of
//     normal_basis() (3 bands, unclamped, cosine-weighted);
//   - the ratio method against PrtNormalMap::shade_ratio's arithmetic in double;
//   - trilinear probe-volume interpolation (valid corners renormalised) and the volume's
//     shading against render::ProbeGrid::interpolate_valid and Volume::shade's arithmetic;
//   - the engine bases' twins (sphbasis.glsl, tools/gen/engine_shader.py) against the float C++:
//     the ambient cube (6 and 5) and Ambient Dice values and RGB sums (its SRBF variant and the
//     paper's Bezier and linear face variants), the SG lobe and the
//     BakingLab sets (their constant tables bit for bit), Hill's fitted irradiance, ZH3, ZH3
//     hallucinated and L1 SH with the Geomerics reconstruction, on the directions above plus
//     cube face boundaries (+-0 components), dice vertices, their planes and the faces' edges, SG
//     lobe axes.
// Error measure: |gpu - ref| in float ulps of max(|ref|, scale), scale the sum of the terms'
// magnitudes (a sum's rounding error is relative to it, not to a cancelling result). The C++
// references of the shading are double: the bound covers the float arithmetic of the shader.
//
// Not a Catch2 test (it needs a driver): its own executable and ctest (label shaders). A missing
// driver fails it, never skips it.
// Usage: sphbasis_shader_twins_test [path/to/shaders/] (default: the source tree's shaders/).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "gl_harness.hpp"
#include "sphbasis/basis/ambient_cube.hpp"
#include "sphbasis/basis/ambient_dice.hpp"
#include "sphbasis/basis/ambient_dice_bezier.hpp"
#include "sphbasis/basis/hsh.hpp"
#include "sphbasis/basis/makhotkin.hpp"
#include "sphbasis/basis/sh.hpp"
#include "sphbasis/basis/sh_l1_nonlinear.hpp"
#include "sphbasis/basis/spherical_gaussian.hpp"
#include "sphbasis/basis/zernike.hpp"
#include "sphbasis/basis/zh3.hpp"
#include "sphbasis/core/clamped_cosine.hpp"
#include "sphbasis/ops/compression.hpp"
#include "sphbasis/ops/normal_basis.hpp"
#include "sphbasis/param/cubemap.hpp"
#include "sphbasis/param/param.hpp"
#include "sphbasis/render/probe_grid.hpp"

namespace {

using namespace shader_harness;

// Stated bounds, measured on Mesa 22.3.6 llvmpipe (LLVM 15, x86-64) against g++ 12 -O3
// -ffp-contract=off (the measured worst case is printed every run):
//  - HSH / Makhotkin / Zernike (float recurrence vs float recurrence, same table): llvmpipe fuses
//    the recurrence's multiply-adds and its sqrt and division may differ by an ulp; errors then
//    grow along the recurrence. Bound 8 ulps of the band's scale.
constexpr double max_ulps_hemi = 8.0;
//  - Cube footprint: the same float operations, 0 differing taps; the weights within n ulps of 1
//    for n texels a face edge (measured 5 for n = 8): llvmpipe fuses the texel coordinate
//    u n - 1/2 into one rounding, which moves the fraction by up to an ulp of n.
constexpr double max_ulps_footprint = 8.0;  // n = 8
//  - Shading (float shader vs double C++, over sums of up to 36 / 65 / 9 terms): the float
//    rounding of each product and partial sum, a few ulps of the terms' magnitude sum; bound 16.
//    The ratio method divides two such sums: bound 16 ulps of its first-order error scale.
constexpr double max_ulps_shading = 16.0;

//  - The tangent-space normal (3 dot products in float, normalised) against double: a few ulps
//    of 1/|u| (|u| its length before normalisation); bound 8.
constexpr double max_ulps_tangent = 8.0;

std::string g_dir;  // shaders/ with a trailing slash

// A compute program of `body` (one invocation per item i, `uint i` in scope) with the twins and
// float input buffers in0.. (bindings 0..), output buffer `outv` (binding inputs.size()); returns
// outputs_per_item floats per item.
std::vector<float> run(const Gl& gl, const std::string& body,
                       const std::vector<const std::vector<float>*>& inputs, unsigned items,
                       unsigned outputs_per_item) {
    std::string src = "#version 430\n" + read_file(g_dir + "sphbasis.glsl") + "\n" +
                      read_file(g_dir + "sphbasis_render.glsl") + "\n" +
                      "layout(local_size_x = 64) in;\n";
    for (std::size_t b = 0; b < inputs.size(); ++b)
        src += "layout(std430, binding = " + std::to_string(b) + ") readonly buffer B" +
               std::to_string(b) + " { float in" + std::to_string(b) + "[]; };\n";
    src += "layout(std430, binding = " + std::to_string(inputs.size()) +
           ") writeonly buffer Bout { float outv[]; };\n"
           "uniform uint count;\n"
           "void main() {\n"
           "    uint i = gl_GlobalInvocationID.x;\n"
           "    if (i >= count) return;\n" +
           body + "}\n";
    const unsigned prog = compile_program(gl, src);
    std::vector<unsigned> buf(inputs.size() + 1);
    gl.GenBuffers(int(buf.size()), buf.data());
    for (std::size_t b = 0; b < inputs.size(); ++b) {
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[b]);
        gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(inputs[b]->size() * sizeof(float)),
                      inputs[b]->data(), GL_STATIC_DRAW);
        gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, unsigned(b), buf[b]);
    }
    const std::size_t n = std::size_t(items) * outputs_per_item;
    std::vector<float> out(n, std::nanf(""));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf.back());
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(n * sizeof(float)), out.data(),
                  GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, unsigned(inputs.size()), buf.back());
    gl.UseProgram(prog);
    gl.Uniform1ui(gl.GetUniformLocation(prog, "count"), items);
    gl.DispatchCompute((items + 63) / 64, 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(n * sizeof(float)), out.data());
    gl.Finish();
    if (const unsigned err = gl.GetError(); err != GL_NO_ERROR) {
        char b[64];
        std::snprintf(b, sizeof b, "OpenGL error 0x%x", err);
        fail(b);
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// HSH, Makhotkin, Zernike.

template <class B>
bool check_hemi(const Gl& gl, const char* name, const std::vector<float>& dirs,
                double (*scale)(int band), int (*band_of)(int k)) {
    const unsigned count = unsigned(dirs.size() / 4);
    int per = 0;
    for (int b = 1; b <= 8; ++b) per += B::count(b);
    const int nmax = B::count(8);
    const std::string body =
        "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
        "    uint o = i * " +
        std::to_string(per) +
        "u;\n"
        "    for (int b = 1; b <= 8; ++b) {\n"
        "        float h[" +
        std::to_string(nmax) + "]; sphbasis_" + name +
        "_eval(d, b, h);\n"
        "        int n = " +
        (B::count(2) == 4 ? std::string("b * b") : std::string("b * (b + 1) / 2")) +
        ";\n"
        "        for (int k = 0; k < n; ++k) outv[o + uint(k)] = h[k];\n"
        "        o += uint(n);\n"
        "    }\n";
    const std::vector<float> gpu = run(gl, body, {&dirs}, count, unsigned(per));
    Worst w;
    std::vector<float> h(std::size_t(nmax), 0.0f);
    for (unsigned i = 0; i < count; ++i) {
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        std::size_t o = std::size_t(i) * std::size_t(per);
        for (int b = 1; b <= 8; ++b) {
            const int n = B::count(b);
            B::with_kernel(n, [&](auto kernel) {
                kernel(x, y, z, [&](int k, float v) { h[std::size_t(k)] = v; });
            });
            for (int k = 0; k < n; ++k)
                w.add(gpu[o + std::size_t(k)], h[std::size_t(k)], scale(band_of(k)));
            o += std::size_t(n);
        }
    }
    return w.report((std::string("sphbasis_") + name + "_eval, 1..8 bands").c_str(), max_ulps_hemi);
}

int band_acn(int k) { return int(std::sqrt(double(k) + 0.5)); }
int band_tri(int k) {
    int n = 0;
    while ((n + 1) * (n + 2) / 2 <= k) ++n;
    return n;
}
constexpr double pi = 3.14159265358979323846;
double scale_hsh(int l) { return std::sqrt((2 * l + 1) / (2 * pi)); }
double scale_makhotkin(int l) { return std::sqrt((l + 1) / pi); }
double scale_zernike(int n) { return std::sqrt((n + 1) / pi); }

// ---------------------------------------------------------------------------------------------
// Cube-map footprint and lxh-unc.

// lxh-pcaM: the mean's and the M vectors' RGB tables (texel x (M + 1) x 3) blended at the
// normal, then albedo (T_0 + sum_j w_j T_j) / pi, as Lxh::shade_pca.
bool check_lxh_pca(const Gl& gl, const std::vector<float>& dirs,
                   const sphbasis::param::CubeMap<float>& cube, std::mt19937& rng) {
    const unsigned count = unsigned(dirs.size() / 4);
    constexpr int m = 8, ch = 3 * (m + 1);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.2f, 1.0f);
    std::vector<float> table(cube.texel_count() * std::size_t(ch)), table_abs(table.size());
    for (std::size_t k = 0; k < table.size(); ++k)
        table[k] = u(rng), table_abs[k] = std::abs(table[k]);
    std::vector<float> w(std::size_t(count) * m), albedo(std::size_t(count) * 3);
    for (float& v : w) v = 2.0f * u(rng);
    for (float& v : albedo) v = pos(rng);
    const std::string body =
        "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
        "    int idx[4]; float wt[4];\n"
        "    sphbasis_cube_footprint(d, " +
        std::to_string(cube.width()) +
        ", idx, wt);\n"
        "    vec3 t[" +
        std::to_string(m + 1) +
        "];\n"
        "    for (int j = 0; j <= " +
        std::to_string(m) +
        "; ++j) {\n"
        "        t[j] = vec3(0.0);\n"
        "        for (int q = 0; q < 4; ++q) {\n"
        "            uint b = uint(idx[q] * " +
        std::to_string(ch) +
        " + 3 * j);\n"
        "            t[j] += wt[q] * vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n"
        "        }\n"
        "    }\n"
        "    vec3 e[SPHBASIS_MAX_VECTORS]; float w[SPHBASIS_MAX_VECTORS];\n"
        "    for (int j = 0; j < " +
        std::to_string(m) + "; ++j) { e[j] = t[j + 1]; w[j] = in2[i * " + std::to_string(m) +
        "u + uint(j)]; }\n"
        "    vec3 a = vec3(in3[3u * i], in3[3u * i + 1u], in3[3u * i + 2u]);\n"
        "    vec3 s = a * sphbasis_pca_exit(t[0], e, w, " +
        std::to_string(m) +
        ") * sphbasis_inv_pi;\n"
        "    outv[3u * i] = s.x; outv[3u * i + 1u] = s.y; outv[3u * i + 2u] = s.z;\n";
    const std::vector<float> gpu = run(gl, body, {&dirs, &table, &w, &albedo}, count, 3);
    Worst wst;
    std::vector<float> t(static_cast<std::size_t>(ch)), tabs(t.size());
    for (unsigned i = 0; i < count; ++i) {
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        sphbasis::param::lookup(cube, table.data(), std::size_t(ch), x, y, z, t.data());
        sphbasis::param::lookup(cube, table_abs.data(), std::size_t(ch), x, y, z, tabs.data());
        for (std::size_t c = 0; c < 3; ++c) {
            double e = t[c], mag = tabs[c];
            for (std::size_t j = 0; j < std::size_t(m); ++j) {
                const double wj = w[std::size_t(i) * m + j];
                e += wj * double(t[3 * (j + 1) + c]);
                mag += std::abs(wj) * double(tabs[3 * (j + 1) + c]);
            }
            const double a = albedo[3 * i + c];
            wst.add(gpu[3 * std::size_t(i) + c], a * e / pi, a * mag / pi);
        }
    }
    return wst.report("lxh-pca8: sphbasis_pca_exit on the blended tables, vs double",
                      max_ulps_shading);
}

bool check_lxh(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    constexpr int n = 8;  // texels a face edge: a third of the directions read across a seam
    const sphbasis::param::CubeMap<float> cube(n);
    std::mt19937 rng(24u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.2f, 1.0f);
    bool ok = true;
    Worst fw;
    std::size_t taps_differ = 0;
    for (int kb : {3, 4, 6}) {
        const int kk = kb * kb;
        std::vector<float> table(cube.texel_count() * std::size_t(3 * kk));
        for (float& t : table) t = u(rng);
        std::vector<float> table_abs(table.size());
        for (std::size_t k = 0; k < table.size(); ++k) table_abs[k] = std::abs(table[k]);
        std::vector<float> vis(std::size_t(count) * std::size_t(kk)), albedo(4 * count);
        for (float& v : vis) v = u(rng);
        for (float& a : albedo) a = pos(rng);
        const std::string body =
            "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
            "    int idx[4]; float wt[4];\n"
            "    sphbasis_cube_footprint(d, " +
            std::to_string(n) +
            ", idx, wt);\n"
            "    const int kk = " +
            std::to_string(kk) +
            ";\n"
            "    vec3 t[36]; float vis[36];\n"
            "    for (int k = 0; k < kk; ++k) {\n"
            "        vec3 s = vec3(0.0);\n"
            "        for (int q = 0; q < 4; ++q) {\n"
            "            uint b = uint((idx[q] * kk + k) * 3);\n"
            "            s += wt[q] * vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n"
            "        }\n"
            "        t[k] = s; vis[k] = in2[i * uint(kk) + uint(k)];\n"
            "    }\n"
            "    vec3 a = vec3(in3[4u * i], in3[4u * i + 1u], in3[4u * i + 2u]);\n"
            "    vec3 e = sphbasis_lxh_shade(vis, t, kk, a);\n"
            "    uint o = i * 11u;\n"
            "    for (int q = 0; q < 4; ++q) { outv[o + uint(q)] = float(idx[q]);\n"
            "        outv[o + 4u + uint(q)] = wt[q]; }\n"
            "    outv[o + 8u] = e.x; outv[o + 9u] = e.y; outv[o + 10u] = e.z;\n";
        const std::vector<float> gpu = run(gl, body, {&dirs, &table, &vis, &albedo}, count, 11);
        Worst sw;
        std::vector<float> t(std::size_t(3 * kk)), tabs(t.size());
        for (unsigned i = 0; i < count; ++i) {
            const float* g = &gpu[std::size_t(i) * 11];
            const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
            if (kb == 3) {
                const sphbasis::param::Footprint<float> fp = cube.footprint(x, y, z);
                for (int q = 0; q < 4; ++q) {
                    taps_differ += std::size_t(g[q]) != fp.index[q];
                    fw.add(g[4 + q], fp.weight[q], 1.0);
                }
            }
            sphbasis::param::lookup(cube, table.data(), std::size_t(3 * kk), x, y, z, t.data());
            // The scale: the blend of |table| (the filtered values cancel).
            sphbasis::param::lookup(cube, table_abs.data(), std::size_t(3 * kk), x, y, z,
                                    tabs.data());
            for (int c = 0; c < 3; ++c) {
                double e = 0, mag = 0;
                for (int k = 0; k < kk; ++k) {
                    const double term =
                        double(vis[std::size_t(i) * std::size_t(kk) + std::size_t(k)]) *
                        double(t[std::size_t(3 * k + c)]);
                    e += term;
                    mag +=
                        std::abs(double(vis[std::size_t(i) * std::size_t(kk) + std::size_t(k)])) *
                        double(tabs[std::size_t(3 * k + c)]);
                }
                const double a = albedo[4 * i + unsigned(c)];
                sw.add(g[8 + c], a * e / pi, a * mag / pi);
            }
        }
        ok = sw.report(("sphbasis_lxh_shade, " + std::to_string(kb) +
                        " bands (cube 8 x 8, DX10 seamless), vs double")
                           .c_str(),
                       max_ulps_shading) &&
             ok;
    }
    std::printf("  sphbasis_cube_footprint: %zu of %u x 4 taps differ from CubeMap<float>  %s\n",
                taps_differ, count, taps_differ == 0 ? "ok" : "FAIL");
    ok = fw.report("sphbasis_cube_footprint weights (ulps of 1)", max_ulps_footprint) && ok;
    return check_lxh_pca(gl, dirs, cube, rng) && ok && taps_differ == 0;
}

// ---------------------------------------------------------------------------------------------
// PCA / CPCA.

bool check_cpca(const Gl& gl) {
    namespace cp = sphbasis::compress;
    // Random "transfer" of 3 x 9 numbers a point, clustered as PrtCpca::build does.
    constexpr int points = 1500, cols = 27;
    std::mt19937 rng(2003u);
    std::normal_distribution<double> g;
    cp::MatrixX<double> x(points, cols);
    for (int p = 0; p < points; ++p)
        for (int c = 0; c < cols; ++c) x(p, c) = g(rng) * (1.0 + (p % 5)) / (1 + c % 9);
    bool ok = true;
    for (const auto [clusters, vectors] : {std::array<int, 2>{8, 4}, std::array<int, 2>{4, 16}}) {
        cp::CpcaSettings cs;
        cs.clusters = clusters;
        cs.vectors = vectors;
        cs.seed = 7;
        cp::Cpca<double> model = cp::cpca_iterative(x, cs);
        // The lighting matrix of PrtCpca::build: channel c's 9 coefficients in rows 9c..
        cp::MatrixX<double> light = cp::MatrixX<double>::Zero(cols, 3);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 9; ++k) light(9 * c + k, c) = g(rng);
        cp::ExitValues<double> ev = cp::exit_values(model, light);
        // What the shader reads: float weights (the texel field), float exit values. The
        // reference shades the same floats in double.
        const unsigned m = unsigned(vectors);
        std::vector<float> field(std::size_t(points) * (m + 1)), exitv;
        for (int p = 0; p < points; ++p) {
            // The cluster id as the field stores it, some out of range or fractional (clamped
            // and truncated by both sides).
            const float id = float(model.cluster[std::size_t(p)]) + (p % 7 == 0 ? 0.25f : 0.0f) +
                             (p % 97 == 0 ? 100.0f : 0.0f);
            field[std::size_t(p) * (m + 1)] = id;
            for (unsigned j = 0; j < m; ++j) {
                const float wf = float(model.weights(p, j));
                field[std::size_t(p) * (m + 1) + 1 + j] = wf;
                model.weights(p, j) = wf;
            }
        }
        for (int cl = 0; cl < clusters; ++cl) {
            for (int c = 0; c < 3; ++c) exitv.push_back(float(ev.mean(cl, c)));
            for (unsigned j = 0; j < m; ++j)
                for (int c = 0; c < 3; ++c) exitv.push_back(float(ev.basis[std::size_t(cl)](j, c)));
        }
        for (int cl = 0; cl < clusters; ++cl)
            for (int c = 0; c < 3; ++c) {
                ev.mean(cl, c) = double(float(ev.mean(cl, c)));
                for (unsigned j = 0; j < m; ++j)
                    ev.basis[std::size_t(cl)](j, c) =
                        double(float(ev.basis[std::size_t(cl)](j, c)));
            }
        // The clusters the renderer reads: the stored ids clamped and truncated.
        std::vector<int> read(std::size_t(points), 0);
        for (int p = 0; p < points; ++p)
            read[std::size_t(p)] =
                int(std::clamp(field[std::size_t(p) * (m + 1)], 0.0f, float(clusters - 1)));
        const cp::MatrixX<double> ref = cp::shade(read, model.weights, ev);
        const std::string sm = std::to_string(m), sc = std::to_string(clusters);
        const std::string body =
            "    uint f = i * " + std::to_string(m + 1) +
            "u;\n"
            "    int cl = sphbasis_cpca_cluster(in0[f], " +
            sc +
            ");\n"
            "    uint b = uint(cl) * " +
            std::to_string(3 * (m + 1)) +
            "u;\n"
            "    vec3 e[SPHBASIS_MAX_VECTORS]; float w[SPHBASIS_MAX_VECTORS];\n"
            "    for (int j = 0; j < " +
            sm +
            "; ++j) {\n"
            "        uint q = b + 3u * uint(j + 1);\n"
            "        e[j] = vec3(in1[q], in1[q + 1u], in1[q + 2u]);\n"
            "        w[j] = in0[f + 1u + uint(j)];\n"
            "    }\n"
            "    vec3 s = sphbasis_pca_exit(vec3(in1[b], in1[b + 1u], "
            "in1[b + 2u]), e, w, " +
            sm +
            ");\n"
            "    outv[4u * i] = s.x; outv[4u * i + 1u] = s.y;\n"
            "    outv[4u * i + 2u] = s.z; outv[4u * i + 3u] = float(cl);\n";
        const std::vector<float> gpu = run(gl, body, {&field, &exitv}, points, 4);
        Worst w;
        std::size_t wrong_cluster = 0;
        for (int p = 0; p < points; ++p) {
            const int cl = read[std::size_t(p)];
            wrong_cluster += int(gpu[4 * std::size_t(p) + 3]) != cl;
            for (int c = 0; c < 3; ++c) {
                double mag = std::abs(ev.mean(cl, c));
                for (unsigned j = 0; j < m; ++j)
                    mag += std::abs(model.weights(p, j) * ev.basis[std::size_t(cl)](j, c));
                w.add(gpu[4 * std::size_t(p) + std::size_t(c)], ref(p, c), mag);
            }
        }
        std::printf("  sphbasis_cpca_cluster (%d clusters): %zu of %d clusters differ  %s\n",
                    clusters, wrong_cluster, points, wrong_cluster == 0 ? "ok" : "FAIL");
        ok = w.report(("sphbasis_pca_exit, CPCA " + sc + " clusters x " + sm +
                       " vectors, vs compress::shade (double)")
                          .c_str(),
                      max_ulps_shading) &&
             ok && wrong_cluster == 0;
    }
    return ok;
}

// ---------------------------------------------------------------------------------------------
// SVD normal basis, ratio method.

// A random right-handed orthonormal frame (s, t, n) in float, and float directions.
void random_frame(std::mt19937& rng, float* f) {
    std::normal_distribution<double> g;
    double n[3] = {g(rng), g(rng), g(rng)}, a[3] = {g(rng), g(rng), g(rng)};
    double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& v : n) v /= l;
    const double d = a[0] * n[0] + a[1] * n[1] + a[2] * n[2];
    for (int k = 0; k < 3; ++k) a[k] -= d * n[k];
    l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (double& v : a) v /= l;
    const double b[3] = {n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2],
                         n[0] * a[1] - n[1] * a[0]};
    for (int k = 0; k < 3; ++k) f[k] = float(a[k]), f[3 + k] = float(b[k]), f[6 + k] = float(n[k]);
}

bool check_svd(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    sphbasis::NormalBasisSettings nbs;
    nbs.bands = 3;
    nbs.clamped = false;
    nbs.weighting = sphbasis::NormalWeighting::cosine;
    const Eigen::MatrixXd v = sphbasis::normal_basis(nbs).v;
    std::vector<float> vf(54);
    for (int k = 0; k < 6; ++k)
        for (int i = 0; i < 9; ++i) vf[std::size_t(9 * k + i)] = float(v(i, k));
    double a[3];
    sphbasis::clamped_cosine_factors(3, a);
    std::mt19937 rng(2005u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.2f, 1.0f);
    // Per item: frame (9), G l (6 RGB = 18), albedo (3).
    std::vector<float> in(std::size_t(count) * 30);
    for (unsigned i = 0; i < count; ++i) {
        float* p = &in[std::size_t(i) * 30];
        random_frame(rng, p);
        for (int k = 9; k < 27; ++k) p[k] = u(rng);
        for (int k = 27; k < 30; ++k) p[k] = pos(rng);
    }
    bool ok = true;
    for (int m : {4, 6}) {
        const std::string body =
            "    uint b = i * 30u;\n"
            "    vec3 nm = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
            "    vec3 s = vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n"
            "    vec3 t = vec3(in1[b + 3u], in1[b + 4u], in1[b + 5u]);\n"
            "    vec3 n = vec3(in1[b + 6u], in1[b + 7u], in1[b + 8u]);\n"
            "    float v[54]; for (int k = 0; k < 54; ++k) v[k] = in2[k];\n"
            "    vec3 u = sphbasis_normal_basis_tangent(nm, s, t, n);\n"
            "    float p[6]; sphbasis_normal_basis_weights(u, v, " +
            std::to_string(m) +
            ", p);\n"
            "    vec3 gl[6];\n"
            "    for (int k = 0; k < 6; ++k) gl[k] = vec3(in1[b + 9u + 3u * uint(k)],\n"
            "        in1[b + 10u + 3u * uint(k)], in1[b + 11u + 3u * uint(k)]);\n"
            "    vec3 e = sphbasis_prt_normalmap_svd(p, gl, " +
            std::to_string(m) +
            ", vec3(in1[b + 27u], in1[b + 28u], in1[b + 29u]));\n"
            "    outv[6u * i] = e.x; outv[6u * i + 1u] = e.y; outv[6u * i + 2u] = e.z;\n"
            "    outv[6u * i + 3u] = u.x; outv[6u * i + 4u] = u.y; outv[6u * i + 5u] = u.z;\n";
        const std::vector<float> gpu = run(gl, body, {&dirs, &in, &vf}, count, 6);
        Worst w, wu;
        for (unsigned i = 0; i < count; ++i) {
            const float* p = &in[std::size_t(i) * 30];
            const double nm[3] = {dirs[4 * i], dirs[4 * i + 1], dirs[4 * i + 2]};
            auto dot3 = [&](const float* f) { return nm[0] * f[0] + nm[1] * f[1] + nm[2] * f[2]; };
            double uu[3] = {dot3(p), dot3(p + 3), std::max(dot3(p + 6), 0.0)};
            const double l = std::sqrt(uu[0] * uu[0] + uu[1] * uu[1] + uu[2] * uu[2]);
            if (l > 0)
                for (double& c : uu) c /= l;
            else
                uu[0] = uu[1] = 0, uu[2] = 1;
            // The tangent-space normal in ulps of 1/|u| before normalisation (normalising a short
            // vector, the mapped normal nearly opposite the frame's, scales up the dot products'
            // rounding); the shading then from the shader's own u
            // (a float normal moves y(u) by its rounding times the functions' slope).
            const float* gu = &gpu[6 * std::size_t(i) + 3];
            for (int c = 0; c < 3; ++c) wu.add(gu[c], uu[c], l > 0 ? std::max(1.0, 1.0 / l) : 1.0);
            double y[9];
            sphbasis::sh::eval_unit(3, double(gu[0]), double(gu[1]), double(gu[2]), y);
            for (int c = 0; c < 3; ++c) {
                double e = 0, mag = 0;
                for (int k = 0; k < m; ++k) {
                    double pk = 0, pmag = 0;
                    for (int q = 0; q < 9; ++q) {
                        const double al = a[q == 0 ? 0 : (q < 4 ? 1 : 2)];
                        const double term = pi * al * y[q] * double(vf[std::size_t(9 * k + q)]);
                        pk += term;
                        pmag += std::abs(term);
                    }
                    const double glk = p[9 + 3 * k + c];
                    e += pk * glk;
                    mag += pmag * std::abs(glk);
                }
                const double alb = p[27 + c];
                w.add(gpu[6 * std::size_t(i) + std::size_t(c)], alb * e / pi, alb * mag / pi);
            }
        }
        if (m == 4)
            ok = wu.report("sphbasis_normal_basis_tangent (ulps of 1/|u|), vs double",
                           max_ulps_tangent) &&
                 ok;
        ok = w.report(("sphbasis_prt_normalmap_svd, M = " + std::to_string(m) +
                       " (V of normal_basis()), vs double")
                          .c_str(),
                      max_ulps_shading) &&
             ok;
    }
    return ok;
}

// 9 RGB radiance coefficients with a dominant constant term (the irradiance stays positive), the
// clamped-cosine factors folded in as render's ctx.sh.irr holds them.
std::vector<float> lighting_coefficients(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-0.3f, 0.3f);
    std::vector<float> c(27);
    double a[3];
    sphbasis::clamped_cosine_factors(3, a);
    for (int k = 0; k < 9; ++k)
        for (int ch = 0; ch < 3; ++ch)
            c[std::size_t(3 * k + ch)] =
                float(a[k == 0 ? 0 : (k < 4 ? 1 : 2)] * (k == 0 ? 2.0 + ch : double(u(rng))));
    return c;
}

bool check_ratio(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    std::mt19937 rng(1999u);
    const std::vector<float> C = lighting_coefficients(rng);
    std::uniform_real_distribution<float> u(-0.2f, 1.2f), pos(0.2f, 1.0f);
    std::uniform_int_distribution<unsigned> pick(0, count - 1);
    // Per item: the surface normal's index, shadowed transfer (3), albedo (3).
    std::vector<float> in(std::size_t(count) * 8);
    for (unsigned i = 0; i < count; ++i) {
        float* p = &in[std::size_t(i) * 8];
        p[0] = float(pick(rng));
        for (int c = 1; c < 4; ++c) p[c] = u(rng);
        for (int c = 4; c < 7; ++c) p[c] = pos(rng);
    }
    const std::string body =
        "    uint b = i * 8u; uint j = uint(in1[b]);\n"
        "    vec3 nm = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
        "    vec3 ns = vec3(in0[4u * j], in0[4u * j + 1u], in0[4u * j + 2u]);\n"
        "    vec3 C[9]; for (int k = 0; k < 9; ++k) C[k] = vec3(in2[3 * k], in2[3 * k + 1],\n"
        "        in2[3 * k + 2]);\n"
        "    vec3 e = sphbasis_prt_ratio(vec3(in1[b + 1u], in1[b + 2u], in1[b + 3u]), C, ns, nm,\n"
        "        vec3(in1[b + 4u], in1[b + 5u], in1[b + 6u]));\n"
        "    outv[3u * i] = e.x; outv[3u * i + 1u] = e.y; outv[3u * i + 2u] = e.z;\n";
    const std::vector<float> gpu = run(gl, body, {&dirs, &in, &C}, count, 3);
    Worst w;
    for (unsigned i = 0; i < count; ++i) {
        const float* p = &in[std::size_t(i) * 8];
        const unsigned j = unsigned(p[0]);
        double ys[9], ym[9];
        sphbasis::sh::eval_unit(3, double(dirs[4 * j]), double(dirs[4 * j + 1]),
                                double(dirs[4 * j + 2]), ys);
        sphbasis::sh::eval_unit(3, double(dirs[4 * i]), double(dirs[4 * i + 1]),
                                double(dirs[4 * i + 2]), ym);
        for (int c = 0; c < 3; ++c) {
            // PrtNormalMap::shade_ratio: u0 = sh_shade(irr, ns, 1), um = sh_shade(irr, nm, albedo).
            double u0 = 0, m0 = 0, um = 0, mm = 0;
            for (int k = 0; k < 9; ++k) {
                const double ck = C[std::size_t(3 * k + c)];
                u0 += ck * ys[k], m0 += std::abs(ck * ys[k]);
                um += ck * ym[k], mm += std::abs(ck * ym[k]);
            }
            const double alb = p[4 + c], sh = std::max(double(p[1 + c]), 0.0);
            um *= alb, mm *= alb;
            const double ref = u0 > 1e-12 ? sh / u0 * um : 0.0;
            // First-order error scale: the relative error of u0 (m0/u0 ulps) and of um (mm).
            const double scale = u0 > 1e-12 ? std::abs(ref) * (m0 / u0) + sh / u0 * mm : 0.0;
            w.add(gpu[3 * std::size_t(i) + std::size_t(c)], ref, scale);
        }
    }
    return w.report("sphbasis_prt_ratio, vs double", max_ulps_shading);
}

// ---------------------------------------------------------------------------------------------
// Probe volume.

bool check_volume(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    bool ok = true;
    std::mt19937 rng(1998u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.2f, 1.0f);
    for (const std::array<int, 3> counts :
         {std::array<int, 3>{4, 3, 5}, std::array<int, 3>{1, 3, 2}}) {
        sphbasis::render::ProbeGrid grid;
        grid.lo = {-1.0, -0.5, 0.0};
        grid.hi = {2.0, 1.5, 1.0};
        grid.counts = counts;
        const std::size_t probes = grid.size();
        std::vector<float> values(probes * 27);  // channel c, coefficient k at 9 c + k
        for (float& v : values) v = 0.3f * u(rng);
        for (std::size_t p = 0; p < probes; ++p)
            for (int c = 0; c < 3; ++c) values[p * 27 + std::size_t(9 * c)] = 2.0f + float(c);
        std::vector<std::uint8_t> inside(probes);
        std::vector<float> insidef(probes);
        for (std::size_t p = 0; p < probes; ++p)
            inside[p] = (p % 5 == 2), insidef[p] = float(inside[p]);
        // Per item: position (3; inside the box, outside, on probe planes), albedo (3).
        std::vector<float> in(std::size_t(count) * 6);
        std::uniform_real_distribution<float> px(-1.5f, 2.5f), py(-1.0f, 2.0f), pz(-0.5f, 1.5f);
        for (unsigned i = 0; i < count; ++i) {
            float* p = &in[std::size_t(i) * 6];
            p[0] = i % 11 == 0 ? -1.0f + float(i % 4) : px(rng);
            p[1] = i % 13 == 0 ? 0.5f : py(rng);
            p[2] = pz(rng);
            for (int c = 3; c < 6; ++c) p[c] = pos(rng);
        }
        const std::string body =
            "    uint b = i * 6u;\n"
            "    vec3 p = vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n"
            "    int idx[8]; float w[8];\n"
            "    sphbasis_probe_weights(p, vec3(-1.0, -0.5, 0.0), vec3(2.0, 1.5, 1.0), ivec3(" +
            std::to_string(counts[0]) + ", " + std::to_string(counts[1]) + ", " +
            std::to_string(counts[2]) +
            "), idx, w);\n"
            "    bool inside[8]; for (int k = 0; k < 8; ++k) inside[k] = in3[idx[k]] != 0.0;\n"
            "    bool valid = sphbasis_probe_weights_valid(w, inside);\n"
            "    vec3 L[9];\n"
            "    for (int k = 0; k < 9; ++k) {\n"
            "        L[k] = vec3(0.0);\n"
            "        for (int q = 0; q < 8; ++q) {\n"
            "            uint v = uint(idx[q] * 27 + k);\n"
            "            L[k] += w[q] * vec3(in2[v], in2[v + 9u], in2[v + 18u]);\n"
            "        }\n"
            "    }\n"
            "    vec3 n = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
            "    vec3 e = sphbasis_volume_shade(L, n, vec3(in1[b + 3u], in1[b + 4u], in1[b + "
            "5u]));\n"
            "    outv[4u * i] = e.x; outv[4u * i + 1u] = e.y; outv[4u * i + 2u] = e.z;\n"
            "    outv[4u * i + 3u] = valid ? 1.0 : 0.0;\n";
        const std::vector<float> gpu = run(gl, body, {&dirs, &in, &values, &insidef}, count, 4);
        std::vector<double> vd(values.begin(), values.end());
        double a[3];
        sphbasis::clamped_cosine_factors(3, a);
        Worst w;
        std::size_t fallback = 0, valid_differs = 0;
        for (unsigned i = 0; i < count; ++i) {
            const float* p = &in[std::size_t(i) * 6];
            const sphbasis::vec3<double> pd{p[0], p[1], p[2]};
            // Does the C++ renormalise (some valid corner with weight > 0) or fall back?
            const sphbasis::render::ProbeGrid::Weights wt = grid.weights(pd);
            double total = 0;
            for (std::size_t k = 0; k < 8; ++k)
                if (!inside[wt.index[k]]) total += wt.w[k];
            if (!(total > 0)) {
                ++fallback;
                valid_differs += gpu[4 * std::size_t(i) + 3] != 0.0f;
                continue;  // the nearest valid probe: the caller's search
            }
            valid_differs += gpu[4 * std::size_t(i) + 3] != 1.0f;
            std::array<double, 27> v, vmag;
            grid.interpolate_valid(vd.data(), 27, inside.data(), pd, v.data());
            // The magnitudes: the same interpolation of |values|.
            std::vector<double> absd(vd.size());
            for (std::size_t k = 0; k < vd.size(); ++k) absd[k] = std::abs(vd[k]);
            grid.interpolate_valid(absd.data(), 27, inside.data(), pd, vmag.data());
            double y[9];
            sphbasis::sh::eval_unit(3, double(dirs[4 * i]), double(dirs[4 * i + 1]),
                                    double(dirs[4 * i + 2]), y);
            for (int c = 0; c < 3; ++c) {
                double s = 0, mag = 0;
                for (int k = 0; k < 9; ++k) {
                    const double al = a[k == 0 ? 0 : (k < 4 ? 1 : 2)];
                    s += al * v[std::size_t(9 * c + k)] * y[k];
                    mag += al * vmag[std::size_t(9 * c + k)] * std::abs(y[k]);
                }
                const double alb = p[3 + c];
                w.add(gpu[4 * std::size_t(i) + std::size_t(c)], alb * s, alb * mag);
            }
        }
        const std::string g = std::to_string(counts[0]) + " x " + std::to_string(counts[1]) +
                              " x " + std::to_string(counts[2]);
        std::printf(
            "  sphbasis_probe_weights_valid (%s probes, every 5th inside): %zu of %u points "
            "differ on renormalise vs fall back (%zu fall back)  %s\n",
            g.c_str(), valid_differs, count, fallback, valid_differs == 0 ? "ok" : "FAIL");
        ok = w.report(("sphbasis_probe_weights + sphbasis_volume_shade (" + g +
                       "), vs ProbeGrid::interpolate_valid (double)")
                          .c_str(),
                      max_ulps_shading) &&
             ok && valid_differs == 0;
    }
    return ok;
}

// ---------------------------------------------------------------------------------------------
// Engine bases (sphbasis.glsl): ambient cube, Ambient Dice, spherical Gaussians, ZH3, L1 SH with
// the Geomerics reconstruction, against the float C++ kernels.

// The harness's directions plus the engine bases' hard ones, each a fixed point of the float
// normalisation: the ambient cube's face boundaries (a component exactly +0 or -0), the Ambient
// Dice vertices +-a_i and directions on the planes d . a_i = 0 (where a vertex's function
// switches sides), the SG sets' lobe axes and their antipodes.
std::vector<float> engine_directions(const std::vector<float>& base) {
    std::vector<float> d = base;
    auto push = [&](double x, double y, double z) {
        const double r = std::sqrt(x * x + y * y + z * z);
        float fx = float(x / r), fy = float(y / r), fz = float(z / r);
        if (x == 0) fx = std::signbit(x) ? -0.0f : 0.0f;
        for (int it = 0; it < 8; ++it) {
            float nx = fx, ny = fy, nz = fz;
            sphbasis::normalize_or_pole(nx, ny, nz);
            if (nx == fx && ny == fy && nz == fz) break;
            fx = nx, fy = ny, fz = nz;
        }
        d.insert(d.end(), {fx, fy, fz, 0.0f});
    };
    for (int j = 0; j < 16; ++j) {
        const double c = std::cos(2 * pi * j / 16), s = std::sin(2 * pi * j / 16);
        push(0.0, c, s), push(-0.0, c, s), push(c, 0.0, s), push(c, -0.0, s), push(c, s, 0.0);
        push(c, s, -0.0);
    }
    const double a = sphbasis::ambient_dice::axis_a, b = sphbasis::ambient_dice::axis_b;
    const double ax[6][3] = {{a, b, 0}, {-a, b, 0}, {0, a, b}, {0, -a, b}, {b, 0, a}, {b, 0, -a}};
    for (const auto& v : ax) {
        push(v[0], v[1], v[2]), push(-v[0], -v[1], -v[2]);
        // Two directions perpendicular to the axis: v x e_z and v x (v x e_z), or with e_x.
        const double e[3] = {v[2] != 0 ? 1.0 : 0.0, 0.0, v[2] != 0 ? 0.0 : 1.0};
        const double p[3] = {v[1] * e[2] - v[2] * e[1], v[2] * e[0] - v[0] * e[2],
                             v[0] * e[1] - v[1] * e[0]};
        const double q[3] = {v[1] * p[2] - v[2] * p[1], v[2] * p[0] - v[0] * p[2],
                             v[0] * p[1] - v[1] * p[0]};
        push(p[0], p[1], p[2]), push(q[0], q[1], q[2]), push(-p[0], -p[1], -p[2]);
    }
    for (int n : {5, 6, 9, 12})
        for (const auto& v : sphbasis::sg::bakinglab_axes(n))
            push(v[0], v[1], v[2]), push(-v[0], -v[1], -v[2]);
    // The dice faces' edges (where the face changes): points at 1/4, 1/2, 3/4 of the 30 edges.
    namespace dt = sphbasis::ambient_dice::tables;
    for (int i = 0; i < 12; ++i)
        for (int j = i + 1; j < 12; ++j) {
            const double* p = dt::vertex[i];
            const double* q = dt::vertex[j];
            if (p[0] * q[0] + p[1] * q[1] + p[2] * q[2] < 0.4) continue;  // cos 1/sqrt(5)
            for (double s : {0.25, 0.5, 0.75})
                push((1 - s) * p[0] + s * q[0], (1 - s) * p[1] + s * q[1],
                     (1 - s) * p[2] + s * q[2]);
        }
    return d;
}

// Stated bounds (measured worst cases printed every run; Mesa 22.3.6 llvmpipe, g++ 12 -O3
// -ffp-contract=off), error in float ulps of max(|ref|, scale):
//  - ambient cube values: one correctly rounded square and a select on each side: bit-identical;
//    bound 1 ulp of the value.
constexpr double max_ulps_cube = 1.0;
//  - Ambient Dice values: the dot products d . a_i (llvmpipe fuses them) move by an ulp of 1 and
//    the lobe's multiply-adds by another; the functions are a partition of unity, so the scale
//    is 1. Bound 4 ulps of 1.
constexpr double max_ulps_dice = 4.0;
//  - Ambient Dice's face variants (the paper's rule): the same face from the same float tests
//    (at an edge another face may win by an ulp; the functions are continuous there), b from
//    3-term dot products, then products and sums of terms below 1 (values in [-0.4, 1]), with
//    -ffp-contract=off on both sides: measured 0.5 ulps of 1 (Bezier), bit-identical (linear).
//    Bound 2 ulps of 1.
constexpr double max_ulps_dice_faces = 2.0;
//  - SG values exp(lambda (d - 1)): the dot product's rounding (an ulp of 1) becomes a relative
//    error of lambda ulps, the argument's own rounding one of |lambda (d - 1)| <= 2 lambda ulps,
//    and the driver's exp differs from std::exp by a few ulps: scale |value| (1 + 3 lambda),
//    bound 4. llvmpipe flushes denormal results to zero: the scale is at least |amplitude|
//    2^-102, whose float ulp is |amplitude| FLT_MIN.
constexpr double max_ulps_sg = 4.0;
//  - expansion sums (RGB coefficients), against the float sum of the C++ kernel's values in
//    basis_eval_sum's order: the values' errors weighted by |c_k| plus the sum's fused
//    multiply-adds: scale sum_k |c_k| scale_k, bound 4.
constexpr double max_ulps_sum = 4.0;
//  - Hill's fitted irradiance: exp(-lambda) by the driver and the float products of its fit,
//    in ulps of the lobe's natural size 2 pi |a| / lambda (>= the irradiance for lambda >= 1);
//    bound 8.
constexpr double max_ulps_hill = 8.0;
//  - ZH3 (float on both sides, same operations): the axis normalisation and the sum of five
//    terms, ulps of the terms' magnitude sum; bound 4. The hallucinated z: float here, double
//    rounded to float in the C++ (six roundings); bound 8 ulps of |z|, and 8 for its evaluation.
constexpr double max_ulps_zh3 = 4.0;
constexpr double max_ulps_zh3_hallucinate = 8.0;
//  - L1 Geomerics: the set-up in float (the C++ in double, then rounded) and the driver's pow:
//    first-order error scale R0 (|a| + 1) + S (q^p (1 + p |ln q|) + p q^(p - 1)) (a's
//    cancellation near r = 1, pow's relative error p |log q| ulps, the exponent's rounding, and
//    q's absolute rounding times the slope of q^p), bound 16.
constexpr double max_ulps_l1nl = 16.0;

// GLSL of item i's direction d (in0) and n RGB coefficients vec3 c[n] (in1: 3n floats an item,
// channel ch of c[k] at 3k + ch).
std::string engine_inputs(int n) {
    const std::string N = std::to_string(n);
    return "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n    vec3 c[" + N +
           "];\n    for (int k = 0; k < " + N + "; ++k) {\n        uint b = i * " +
           std::to_string(3 * n) +
           "u + 3u * uint(k);\n        c[k] = vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n    }\n";
}

// Values and RGB expansion sums of a linear engine basis B of n functions: sphbasis_<stem>_eval
// and sphbasis_<stem>_eval_sum against B::with_kernel(n) in float and the float sum of its values
// in basis_eval_sum<B>'s order (not basis_eval_sum itself: it renormalises d, and the float
// normalisation is not idempotent on every harness direction, moving a component by up to 4
// ulps). The error scale of value v: fixed + rel |v|.
template <class B>
bool check_engine_linear(const Gl& gl, const std::vector<float>& dirs, const std::string& stem,
                         int n, double fixed, double rel, double bound) {
    const unsigned count = unsigned(dirs.size() / 4);
    const unsigned per = unsigned(n) + 3;
    std::mt19937 rng(2017u + unsigned(n));
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<float> coeffs(std::size_t(count) * std::size_t(3 * n));
    for (float& c : coeffs) c = u(rng);
    const std::string N = std::to_string(n), P = std::to_string(per);
    const std::string body = engine_inputs(n) + "    float h[" + N + "]; sphbasis_" + stem +
                             "_eval(d, h);\n    for (int k = 0; k < " + N + "; ++k) outv[i * " + P +
                             "u + uint(k)] = h[k];\n    vec3 e = sphbasis_" + stem +
                             "_eval_sum(c, d);\n    uint o = i * " + P + "u + " + N +
                             "u;\n    outv[o] = e.x; outv[o + 1u] = e.y; outv[o + 2u] = e.z;\n";
    const std::vector<float> gpu = run(gl, body, {&dirs, &coeffs}, count, per);
    Worst wv, ws;
    std::vector<float> h(static_cast<std::size_t>(n));
    for (unsigned i = 0; i < count; ++i) {
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        B::with_kernel(n, [&](auto kernel) {
            kernel(x, y, z, [&](int k, float v) { h[std::size_t(k)] = v; });
        });
        const float* g = &gpu[std::size_t(i) * per];
        for (int k = 0; k < n; ++k) {
            const double v = h[std::size_t(k)];
            wv.add(g[k], v, fixed + rel * std::abs(v));
        }
        for (int c = 0; c < 3; ++c) {
            // basis_eval_sum's sum (acc + c_k v_k from 0, in float) of the kernel's values, without
            // its normalisation of d (the shader takes d as unit).
            float ref = 0;
            double scale = 0;
            for (int k = 0; k < n; ++k) {
                const float ck =
                    coeffs[std::size_t(i) * std::size_t(3 * n) + std::size_t(3 * k + c)];
                ref = ref + ck * h[std::size_t(k)];
                scale += std::abs(ck) * (fixed + rel * std::abs(double(h[std::size_t(k)])));
            }
            ws.add(g[n + c], ref, scale);
        }
    }
    const bool ok = wv.report(("sphbasis_" + stem + "_eval, vs C++ float").c_str(), bound);
    return ws.report(("sphbasis_" + stem + "_eval_sum (RGB), vs C++ float").c_str(),
                     max_ulps_sum) &&
           ok;
}

// The shader's constant tables of the SG sets and Ambient Dice equal the C++ floats bit for bit.
bool check_engine_constants(const Gl& gl) {
    std::string body = "    if (i != 0u) return;\n    uint o = 0u;\n";
    std::vector<float> ref;
    for (int n : {5, 6, 9, 12}) {
        const std::string p = "sphbasis_sg" + std::to_string(n);
        body += "    outv[o++] = " + p + "_sharpness;\n    for (int k = 0; k < " +
                std::to_string(n) + "; ++k) { outv[o++] = " + p + "_axis[k].x; outv[o++] = " + p +
                "_axis[k].y; outv[o++] = " + p + "_axis[k].z; }\n";
        ref.push_back(float(sphbasis::sg::bakinglab_sharpness(n)));
        for (const auto& a : sphbasis::sg::bakinglab_axes(n))
            for (double c : a) ref.push_back(float(c));
    }
    body +=
        "    outv[o++] = sphbasis_ambient_dice_axis_a; outv[o++] = sphbasis_ambient_dice_axis_b;\n"
        "    outv[o++] = sphbasis_ambient_dice_w2; outv[o++] = sphbasis_ambient_dice_w4;\n";
    namespace ad = sphbasis::ambient_dice;
    for (double c : {ad::axis_a, ad::axis_b, ad::w2, ad::w4}) ref.push_back(float(c));
    const std::vector<float> dummy(4, 0.0f);
    const std::vector<float> gpu = run(gl, body, {&dummy}, 1, unsigned(ref.size()));
    std::size_t differ = 0;
    for (std::size_t k = 0; k < ref.size(); ++k) differ += gpu[k] != ref[k];
    std::printf(
        "  SG sets 5/6/9/12 (axes, sharpness) and Ambient Dice constants: %zu of %zu differ "
        "from the C++ floats  %s\n",
        differ, ref.size(), differ == 0 ? "ok" : "FAIL");
    return differ == 0;
}

// sphbasis_sg_eval and sphbasis_sg_irradiance_fitted on random lobes (sharpness 0..64 for the
// value, 0.25..64 for the irradiance, the sets' sharpness included), and the sets' irradiance sums.
bool check_sg(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    std::mt19937 rng(2016u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), loglam(std::log(0.25f), std::log(64.0f));
    std::normal_distribution<double> g;
    const float sets[4] = {
        float(sphbasis::sg::bakinglab_sharpness(5)), float(sphbasis::sg::bakinglab_sharpness(6)),
        float(sphbasis::sg::bakinglab_sharpness(9)), float(sphbasis::sg::bakinglab_sharpness(12))};
    // Per item: axis (3), sharpness, amplitude; the irradiance of the same lobe uses
    // max(sharpness, 0.25).
    std::vector<float> lobes(std::size_t(count) * 5);
    for (unsigned i = 0; i < count; ++i) {
        float* l = &lobes[std::size_t(i) * 5];
        double a[3] = {g(rng), g(rng), g(rng)};
        const double r = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        for (int c = 0; c < 3; ++c) l[c] = float(a[c] / r);
        l[3] = i % 7 == 0 ? sets[(i / 7) % 4] : i % 11 == 0 ? 0.0f : std::exp(loglam(rng));
        l[4] = 2.0f * u(rng);
    }
    const std::string body =
        "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
        "    uint b = 5u * i;\n"
        "    vec3 axis = vec3(in1[b], in1[b + 1u], in1[b + 2u]);\n"
        "    outv[2u * i] = sphbasis_sg_eval(axis, in1[b + 3u], in1[b + 4u], d);\n"
        "    outv[2u * i + 1u] = sphbasis_sg_irradiance_fitted(axis, max(in1[b + 3u], 0.25), "
        "in1[b + 4u], d);\n";
    const std::vector<float> gpu = run(gl, body, {&dirs, &lobes}, count, 2);
    Worst we, wi;
    for (unsigned i = 0; i < count; ++i) {
        const float* l = &lobes[std::size_t(i) * 5];
        const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
        sphbasis::sg::Lobe<float> lobe{l[0], l[1], l[2], l[3], l[4]};
        const float v = sphbasis::sg::eval(lobe, x, y, z);
        we.add(gpu[2 * i], v,
               std::abs(double(v)) * (1 + 3 * double(l[3])) +
                   std::ldexp(std::abs(double(l[4])), -102));
        lobe.sharpness = std::max(l[3], 0.25f);
        const float e = sphbasis::sg::irradiance_fitted(lobe, x, y, z);
        wi.add(gpu[2 * i + 1], e, 2 * pi * std::abs(double(l[4])) / double(lobe.sharpness));
    }
    bool ok =
        we.report("sphbasis_sg_eval, random lobes (sharpness 0..64), vs C++ float", max_ulps_sg);
    ok = wi.report(
             "sphbasis_sg_irradiance_fitted, sharpness 0.25..64, vs C++ float (ulps of 2 pi "
             "|a| / lambda)",
             max_ulps_hill) &&
         ok;
    for (int n : {5, 6, 9, 12}) {
        std::vector<float> c(std::size_t(count) * std::size_t(3 * n));
        for (float& v : c) v = u(rng);
        const std::string N = std::to_string(n);
        const std::string b2 = engine_inputs(n) + "    vec3 e = sphbasis_sg" + N +
                               "_irradiance(c, d);\n    outv[3u * i] = e.x; outv[3u * i + 1u] = "
                               "e.y; outv[3u * i + 2u] = e.z;\n";
        const std::vector<float> g2 = run(gl, b2, {&dirs, &c}, count, 3);
        const auto lobes_n = sphbasis::sg::bakinglab_lobes<float>(n);
        Worst w;
        for (unsigned i = 0; i < count; ++i) {
            const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
            for (int ch = 0; ch < 3; ++ch) {
                double e = 0, scale = 0;
                for (int k = 0; k < n; ++k) {
                    sphbasis::sg::Lobe<float> lobe = lobes_n[std::size_t(k)];
                    lobe.amplitude =
                        c[std::size_t(i) * std::size_t(3 * n) + std::size_t(3 * k + ch)];
                    e += sphbasis::sg::irradiance_fitted(lobe, x, y, z);
                    scale += 2 * pi * std::abs(double(lobe.amplitude)) / double(lobe.sharpness);
                }
                w.add(g2[3 * std::size_t(i) + std::size_t(ch)], e, scale);
            }
        }
        ok = w.report(("sphbasis_sg" + N +
                       "_irradiance (RGB), vs the C++ float lobes' sum (ulps "
                       "of sum 2 pi |c_k| / lambda)")
                          .c_str(),
                      max_ulps_hill) &&
             ok;
    }
    return ok;
}

// Coefficient sets of the fitted representations (5 values: e_0, e_1-1, e_10, e_11, z): random,
// and the hard ones: L1 zero (ZH3's axis falls back to +z; Geomerics: r = 0), L1 along an axis
// (the axis directions then give a . n = +-1 exactly), e_0 = 0 (hallucinated z = 0; Geomerics'
// linear branch), e_0 < 0, |L1| far above e_0 (the hallucination's ratio clamp; Geomerics with
// r ~ 1e3, a ~ -1), tiny L1.
std::vector<float> fitted_sets() {
    std::vector<float> s = {
        1.0f,  0.0f,   0.0f,   0.0f,    0.3f,   // L1 = 0
        1.0f,  0.0f,   0.0f,   0.0f,    0.0f,   // a constant
        1.0f,  0.0f,   0.5f,   0.0f,    -0.2f,  // L1 along +z
        1.0f,  0.0f,   -0.5f,  0.0f,    0.2f,   // L1 along -z
        2.0f,  0.0f,   0.0f,   1.5f,    0.1f,   // L1 along +x
        1.0f,  -0.7f,  0.0f,   0.0f,    0.4f,   // L1 along -y
        0.0f,  0.3f,   -0.2f,  0.5f,    0.1f,   // e_0 = 0
        -1.0f, 0.3f,   -0.2f,  0.5f,    -0.3f,  // e_0 < 0
        -2.0f, 0.0f,   0.0f,   0.0f,    0.5f,   // e_0 < 0, L1 = 0
        1e-3f, 0.8f,   0.3f,   -0.4f,   0.0f,   // |L1| >> e_0
        1.0f,  1e-18f, 2e-18f, -3e-18f, 0.2f,   // tiny L1
        1.0f,  2.05f,  0.0f,   0.0f,    0.0f,   // r close to 1 (Geomerics a ~ 0)
    };
    std::mt19937 rng(2024u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.5f, 3.0f);
    for (int k = 0; k < 12; ++k) {
        s.push_back(k < 8 ? pos(rng) : u(rng));
        for (int j = 0; j < 3; ++j) s.push_back(u(rng));
        s.push_back(0.5f * u(rng));
    }
    return s;
}

bool check_fitted(const Gl& gl, const std::vector<float>& dirs) {
    const unsigned count = unsigned(dirs.size() / 4);
    const std::vector<float> sets = fitted_sets();
    const unsigned ns = unsigned(sets.size() / 5), per = 4 * ns;
    const std::string body =
        "    vec3 d = vec3(in0[4u * i], in0[4u * i + 1u], in0[4u * i + 2u]);\n"
        "    for (uint s = 0u; s < " +
        std::to_string(ns) +
        "u; ++s) {\n"
        "        float c[5]; float h[4];\n"
        "        for (int k = 0; k < 5; ++k) c[k] = in1[5u * s + uint(k)];\n"
        "        for (int k = 0; k < 4; ++k) h[k] = c[k];\n"
        "        uint o = i * " +
        std::to_string(per) +
        "u + 4u * s;\n"
        "        outv[o] = sphbasis_zh3_eval(c, d);\n"
        "        outv[o + 1u] = sphbasis_zh3_hallucinate(h);\n"
        "        outv[o + 2u] = sphbasis_zh3_hallucinate_eval(h, d);\n"
        "        outv[o + 3u] = sphbasis_sh_l1_nonlinear_eval(h, d);\n"
        "    }\n";
    const std::vector<float> gpu = run(gl, body, {&dirs, &sets}, count, per);
    namespace z3 = sphbasis::zh3;
    namespace gm = sphbasis::sh_l1_nonlinear;
    Worst wz, wh, whe, wl;
    // The terms' magnitude sum of a ZH3 evaluation.
    auto zh3_scale = [](const z3::Expansion<float>& e, double x, double y, double z) {
        const double t = double(e.ax) * x + double(e.ay) * y + double(e.az) * z;
        return std::abs(double(e.c0)) + std::abs(e.lx * x) + std::abs(e.ly * y) +
               std::abs(e.lz * z) + std::abs(double(e.k)) * (3 * t * t + 1);
    };
    for (unsigned s = 0; s < ns; ++s) {
        const float* c = &sets[5 * s];
        float full[z3::stored];
        z3::hallucinate(c, full);
        const z3::Expansion<float> ez(c), eh(full);
        const gm::Expansion<float> eg(c);
        wh.add(gpu[4 * s + 1], full[4], 0.0);
        for (unsigned i = 0; i < count; ++i) {
            const float x = dirs[4 * i], y = dirs[4 * i + 1], z = dirs[4 * i + 2];
            const float* g = &gpu[std::size_t(i) * per + 4 * s];
            if (i > 0) wh.add(g[1], full[4], 0.0);
            wz.add(g[0], ez(x, y, z), zh3_scale(ez, x, y, z));
            whe.add(g[2], eh(x, y, z), zh3_scale(eh, x, y, z));
            // Geomerics' first-order error scale (see max_ulps_l1nl).
            double scale;
            if (eg.linear) {
                scale = std::abs(double(eg.r0)) + std::abs(eg.dx * double(x)) +
                        std::abs(eg.dy * double(y)) + std::abs(eg.dz * double(z));
            } else {
                const double t = double(eg.dx) * x + double(eg.dy) * y + double(eg.dz) * z;
                const double q = std::max(0.0, 0.5 * (1 + t)), p = eg.p;
                const double qp = std::pow(q, p);
                const double slope = q > 0 ? p * qp / q : (p == 1 ? 1.0 : 0.0);
                scale = double(eg.r0) * (std::abs(double(eg.a)) + 1) +
                        std::abs(double(eg.scale)) *
                            (qp * (1 + p * (q > 0 ? std::abs(std::log(q)) : 0.0)) + slope);
            }
            wl.add(g[3], eg(x, y, z), scale);
        }
    }
    std::printf("  %u coefficient sets x %u directions:\n", ns, count);
    bool ok = wz.report("sphbasis_zh3_eval, vs zh3::Expansion<float>", max_ulps_zh3);
    ok = wh.report("sphbasis_zh3_hallucinate (z), vs zh3::hallucinate<float> (double inside)",
                   max_ulps_zh3_hallucinate) &&
         ok;
    ok = whe.report("sphbasis_zh3_hallucinate_eval, vs zh3::eval of zh3::hallucinate<float>",
                    max_ulps_zh3_hallucinate) &&
         ok;
    ok = wl.report(
             "sphbasis_sh_l1_nonlinear_eval, vs sh_l1_nonlinear::Expansion<float> (first-order "
             "scale)",
             max_ulps_l1nl) &&
         ok;
    return ok;
}

bool check_engine(const Gl& gl, const std::vector<float>& base) {
    const std::vector<float> dirs = engine_directions(base);
    std::printf(
        "  engine bases: %zu directions (the above, cube face boundaries +-0, dice "
        "vertices, their planes and edges, SG lobe axes)\n",
        dirs.size() / 4);
    bool ok = check_engine_constants(gl);
    ok = check_engine_linear<sphbasis::AmbientCube>(gl, dirs, "ambient_cube", 6, 0.0, 1.0,
                                                    max_ulps_cube) &&
         ok;
    ok = check_engine_linear<sphbasis::AmbientCube>(gl, dirs, "ambient_cube5", 5, 0.0, 1.0,
                                                    max_ulps_cube) &&
         ok;
    ok = check_engine_linear<sphbasis::AmbientDice>(gl, dirs, "ambient_dice", 12, 1.0, 0.0,
                                                    max_ulps_dice) &&
         ok;
    ok = check_engine_linear<sphbasis::AmbientDiceBezier>(gl, dirs, "ambient_dice_bezier", 36, 1.0,
                                                          0.0, max_ulps_dice_faces) &&
         ok;
    ok = check_engine_linear<sphbasis::AmbientDiceLinear>(gl, dirs, "ambient_dice_linear", 12, 1.0,
                                                          0.0, max_ulps_dice_faces) &&
         ok;
    for (int n : {5, 6, 9, 12}) {
        const double lam = sphbasis::sg::bakinglab_sharpness(n);
        ok = check_engine_linear<sphbasis::SphericalGaussian>(gl, dirs, "sg" + std::to_string(n), n,
                                                              0.0, 1 + 3 * lam, max_ulps_sg) &&
             ok;
    }
    ok = check_sg(gl, dirs) && ok;
    return check_fitted(gl, dirs) && ok;
}

}  // namespace

int main(int argc, char** argv) {
    g_dir = argc > 1 ? argv[1] : std::string(SPHBASIS_SOURCE_DIR) + "/shaders";
    if (g_dir.back() != '/') g_dir += '/';
    create_context();
    const Gl gl = load_gl();
    const char* renderer = reinterpret_cast<const char*>(gl.GetString(GL_RENDERER));
    std::printf("sphbasis_shader_twins_test: %s, shaders in %s\n", renderer ? renderer : "?",
                g_dir.c_str());
    const std::vector<float> dirs = directions();
    std::printf("  %zu directions (poles, horizon, x = y = 0, cube edges and corners)\n",
                dirs.size() / 4);
    bool ok = check_hemi<sphbasis::HSH>(gl, "hsh", dirs, scale_hsh, band_acn);
    ok = check_hemi<sphbasis::Makhotkin>(gl, "makhotkin", dirs, scale_makhotkin, band_acn) && ok;
    ok = check_hemi<sphbasis::Zernike>(gl, "zernike", dirs, scale_zernike, band_tri) && ok;
    ok = check_lxh(gl, dirs) && ok;
    ok = check_cpca(gl) && ok;
    ok = check_svd(gl, dirs) && ok;
    ok = check_ratio(gl, dirs) && ok;
    ok = check_volume(gl, dirs) && ok;
    ok = check_engine(gl, dirs) && ok;
    std::printf("sphbasis_shader_twins_test: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
