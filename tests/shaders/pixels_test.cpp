// A shader reproduces pixels of the CPU renderer's image: the irradiance volume ("volume",
// representations/volume.hpp) of a ball over a plane under a sky and a sun is baked and rendered
// by render::Representations (1 sample per pixel: the pixel centre), then a compute shader on
// llvmpipe shades every pixel that sees geometry with the twins of shaders/sphbasis_render.glsl
// (sphbasis_probe_weights, sphbasis_probe_weights_valid, sphbasis_volume_shade) from what an
// engine would hold: the probe grid (box and counts), the baked probes' SH radiance and inside
// flags as float buffers, and per pixel the G-buffer's position, normal and albedo (floats).
// Where every corner of a point's cell is inside geometry the shader reads the nearest valid
// probe, found on the CPU (ProbeGrid::nearest_valid), as sphbasis_probe_weights_valid's
// contract says.
//
// Error: |gpu - cpu pixel| in float ulps of the pixel's magnitude scale, albedo sum_k a_l |y_k|
// interp(|L_k|) (interpolated |radiance|): the float inputs (positions, radiance) and the
// shader's float arithmetic against the renderer's double.
//
// Not a Catch2 test (it needs a driver): its own executable and ctest (label shaders).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "gl_harness.hpp"
#include "render_test_support.hpp"
#include "sphbasis/core/clamped_cosine.hpp"
#include "sphbasis/render/camera.hpp"
#include "sphbasis/render/representation.hpp"

namespace {

using namespace shader_harness;
namespace render = sphbasis::render;

// Stated bound, measured on Mesa 22.3.6 llvmpipe against g++ 12 (printed every run): 4 ulps of
// the pixel's scale, 2069 of 4686 values bit-identical. Bound 16: the shader's float sums (as
// sphbasis_shader_twins_test's volume check, 6 ulps) plus the float G-buffer position, which
// moves the trilinear weights by its rounding times the field's slope across a cell.
constexpr double max_ulps_pixel = 16.0;

}  // namespace

int main(int argc, char** argv) {
    const std::string dir = argc > 1 ? argv[1] : std::string(SPHBASIS_SOURCE_DIR) + "/shaders";
    create_context();
    const Gl gl = load_gl();

    // The scene, baked and rendered on the CPU.
    sphbasis_test::World w = sphbasis_test::sphere_on_plane_meshes();
    w.desc.environment = sphbasis_test::constant_environment({0.6, 0.7, 0.9});
    w.desc.lights.push_back(
        sphbasis_test::directional_light(sphbasis_test::unit({0.4, -0.3, 1.0}), {2.0, 1.8, 1.5}));
    w.build();
    render::RepresentationSettings s;
    s.rays = 64;
    s.has_probes = true;
    s.probes.lo = {-1.5, -1.5, 0.0};
    s.probes.hi = {1.5, 1.5, 1.2};
    s.probes.counts = {5, 5, 3};
    render::Representations reps(w.desc, *w.rt, s, {"volume"});
    reps.prepare(nullptr);
    const render::Camera cam = sphbasis_test::camera_at({0.5, -3.5, 2.0}, {0, 0, 0.3}, 64, 48);
    const render::Image img = reps.render(0, cam, 1);

    // The probes as an engine holds them (floats), with the renderer's inside rule.
    const render::BakeData& bake = reps.bake_data(reps.reads(0).at(0));
    const render::ProbeGrid grid = bake.request.probes;
    const std::size_t probes = grid.size();
    std::vector<float> values(probes * 27), insidef(probes);
    std::vector<double> vabs(probes * 27);
    std::vector<std::uint8_t> inside(probes);
    for (std::size_t p = 0; p < probes; ++p) {
        const render::PointResult& r = bake.results[p];
        inside[p] = r.inside ? 1 : 0;
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < 9; ++k) {
                values[27 * p + 9 * c + k] = float(r.radiance[c][k]);
                vabs[27 * p + 9 * c + k] = std::abs(r.radiance[c][k]);
            }
    }
    if (std::find(inside.begin(), inside.end(), 0) == inside.end())
        std::fill(inside.begin(), inside.end(), 0);
    std::size_t flagged = 0;
    for (std::size_t p = 0; p < probes; ++p) insidef[p] = float(inside[p]), flagged += inside[p];

    // The G-buffer of the pixels that see geometry: position, normal, albedo, nearest valid probe.
    const render::PinholeCamera pc(cam);
    std::vector<float> gbuf;
    std::vector<int> pixel;
    std::vector<double> scale;
    double a[3];
    sphbasis::clamped_cosine_factors(3, a);
    std::size_t cpu_mismatch = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const render::CameraRay ray = pc.ray(x + 0.5, y + 0.5);
            const render::Hit h = w.rt->intersect(ray.origin, ray.direction);
            if (!h.valid) continue;
            // The image is the representation's shade at this hit (spp = 1: the pixel centre).
            const render::RGB ref =
                reps.shade(0, h, {-ray.direction.x, -ray.direction.y, -ray.direction.z}, 0.0);
            const float* px = img.at(x, y);
            for (int c = 0; c < 3; ++c) cpu_mismatch += float(ref[std::size_t(c)]) != px[c];
            const sphbasis::vec3<double> n = render::Scene::normal_mapped(h);
            const std::size_t nearest = grid.nearest_valid(inside.data(), h.position);
            gbuf.insert(gbuf.end(), {float(h.position.x), float(h.position.y), float(h.position.z),
                                     float(n.x), float(n.y), float(n.z), float(h.albedo[0]),
                                     float(h.albedo[1]), float(h.albedo[2]), float(nearest)});
            pixel.push_back(y * cam.width + x);
            std::array<double, 27> m;
            grid.interpolate_valid(vabs.data(), 27, inside.data(), h.position, m.data());
            double yv[9];
            sphbasis::sh::eval_unit(3, n.x, n.y, n.z, yv);
            for (std::size_t c = 0; c < 3; ++c) {
                double sc = 0;
                for (std::size_t k = 0; k < 9; ++k)
                    sc += a[k == 0 ? 0 : (k < 4 ? 1 : 2)] * m[9 * c + k] * std::abs(yv[k]);
                scale.push_back(h.albedo[c] * sc);
            }
        }
    const unsigned items = unsigned(pixel.size());

    // The shader.
    char box[256];
    std::snprintf(box, sizeof box,
                  "vec3(%.9g, %.9g, %.9g), vec3(%.9g, %.9g, %.9g), ivec3(%d, %d, %d)",
                  double(float(grid.lo.x)), double(float(grid.lo.y)), double(float(grid.lo.z)),
                  double(float(grid.hi.x)), double(float(grid.hi.y)), double(float(grid.hi.z)),
                  grid.counts[0], grid.counts[1], grid.counts[2]);
    const std::string src =
        "#version 430\n" + read_file(dir + "/sphbasis.glsl") + "\n" +
        read_file(dir + "/sphbasis_render.glsl") +
        "\n"
        "layout(local_size_x = 64) in;\n"
        "layout(std430, binding = 0) readonly buffer G { float gbuf[]; };\n"
        "layout(std430, binding = 1) readonly buffer P { float probe[]; };\n"
        "layout(std430, binding = 2) readonly buffer I { float probe_inside[]; };\n"
        "layout(std430, binding = 3) writeonly buffer O { float outv[]; };\n"
        "uniform uint count;\n"
        "void main() {\n"
        "    uint i = gl_GlobalInvocationID.x;\n"
        "    if (i >= count) return;\n"
        "    uint g = 10u * i;\n"
        "    vec3 p = vec3(gbuf[g], gbuf[g + 1u], gbuf[g + 2u]);\n"
        "    vec3 n = vec3(gbuf[g + 3u], gbuf[g + 4u], gbuf[g + 5u]);\n"
        "    vec3 albedo = vec3(gbuf[g + 6u], gbuf[g + 7u], gbuf[g + 8u]);\n"
        "    int idx[8]; float w[8]; bool ins[8];\n"
        "    sphbasis_probe_weights(p, " +
        std::string(box) +
        ", idx, w);\n"
        "    for (int k = 0; k < 8; ++k) ins[k] = probe_inside[idx[k]] != 0.0;\n"
        "    if (!sphbasis_probe_weights_valid(w, ins)) {\n"
        "        for (int k = 0; k < 8; ++k) { idx[k] = int(gbuf[g + 9u]); w[k] = k == 0 ? 1.0 : "
        "0.0; }\n"
        "    }\n"
        "    vec3 L[9];\n"
        "    for (int k = 0; k < 9; ++k) {\n"
        "        L[k] = vec3(0.0);\n"
        "        for (int q = 0; q < 8; ++q) {\n"
        "            uint v = uint(idx[q] * 27 + k);\n"
        "            L[k] += w[q] * vec3(probe[v], probe[v + 9u], probe[v + 18u]);\n"
        "        }\n"
        "    }\n"
        "    vec3 e = sphbasis_volume_shade(L, n, albedo);\n"
        "    outv[3u * i] = e.x; outv[3u * i + 1u] = e.y; outv[3u * i + 2u] = e.z;\n"
        "}\n";
    const unsigned prog = compile_program(gl, src);
    unsigned buf[4];
    gl.GenBuffers(4, buf);
    const std::vector<float>* in[3] = {&gbuf, &values, &insidef};
    for (unsigned b = 0; b < 3; ++b) {
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[b]);
        gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(in[b]->size() * sizeof(float)),
                      in[b]->data(), GL_STATIC_DRAW);
        gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, buf[b]);
    }
    std::vector<float> gpu(std::size_t(items) * 3, std::nanf(""));
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, buf[3]);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(gpu.size() * sizeof(float)), gpu.data(),
                  GL_DYNAMIC_READ);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, buf[3]);
    gl.UseProgram(prog);
    gl.Uniform1ui(gl.GetUniformLocation(prog, "count"), items);
    gl.DispatchCompute((items + 63) / 64, 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(gpu.size() * sizeof(float)),
                        gpu.data());
    gl.Finish();
    if (gl.GetError() != GL_NO_ERROR) fail("OpenGL error");

    Worst wst;
    double lo = 1e30, hi = 0;
    for (unsigned i = 0; i < items; ++i) {
        const float* px = img.at(pixel[i] % cam.width, pixel[i] / cam.width);
        for (std::size_t c = 0; c < 3; ++c) {
            wst.add(gpu[3 * i + c], px[c], scale[3 * i + c]);
            lo = std::min(lo, double(px[c])), hi = std::max(hi, double(px[c]));
        }
    }
    std::printf(
        "sphbasis_shader_pixels_test: 'volume' (%zu probes, %zu inside geometry), %d x %d image, "
        "%u pixels on geometry, values %.3g..%.3g\n",
        probes, flagged, cam.width, cam.height, items, lo, hi);
    std::printf(
        "  the CPU image is Representations::shade at the pixel centres: %zu of %u "
        "values differ  %s\n",
        cpu_mismatch, 3 * items, cpu_mismatch == 0 ? "ok" : "FAIL");
    const bool ok =
        wst.report("GPU pixels (sphbasis_render.glsl) vs the CPU image", max_ulps_pixel) &&
        cpu_mismatch == 0 && items > 1000;
    std::printf("sphbasis_shader_pixels_test: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
