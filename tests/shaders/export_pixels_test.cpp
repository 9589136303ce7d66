// A shader that reads the files of `sphbasis bake --format gltf` (docs/export-format.md)
// reproduces pixels of `sphbasis render`'s image of the same bake (`render --bake`).
//
//   sphbasis_shader_export_pixels_test KIND BAKE_DIR RENDER_DIR SCENE.json [GLB [SHADERS_DIR]]
//
// KIND is lightmap-sh9 (BAKE_DIR: `--target texels:RES --quantities irradiance --basis sh
// --coeffs 9`) or volume (`--target probes --quantities radiance`); RENDER_DIR holds KIND.exr,
// report.json and the first-hit AOVs of `sphbasis render --representations KIND --bake BAKE_DIR
// --aovs` (tests/shaders/CMakeLists.txt gives the commands). What the program reads, as an
// engine would:
//   - scene.glb (tinygltf; GLB, default BAKE_DIR/scene.glb: a probe bake writes none, so the
//     volume reads a texel bake's): the meshes' positions, normals, indices and TEXCOORD_0;
//   - lightmaps.json / probes.grid.json (nlohmann-json): sizes, files, the per-channel scale and
//     bias of the range compression and its max_error;
//   - the lightmap images or probe slices (stb_image for PNG, OpenEXR for half/float), uploaded
//     to OpenGL textures as stored (GL_RGB8, GL_RGB16, GL_RGB16F, GL_RGB32F) and decoded in the
//     shader, v = bias + scale t;
//   - from the scene file what an engine's material and camera hold and the export does not:
//     each mesh's albedo and normal map, and the camera.
// The G-buffer: the render's camera rays (render::ImageLoop's sample positions for the seed and
// sample count of report.json) cast with Embree on the .glb's triangles: per sample the
// position, shading normal, glTF uv (TEXCOORD_0 at the hit's barycentrics) and mesh, checked
// against the render's aov_position.exr and aov_albedo.exr. A compute shader on llvmpipe then
// shades every sample of the pixels whose samples all see geometry with the twins of
// shaders/sphbasis.glsl and shaders/sphbasis_render.glsl, and the mean of a pixel's samples (the
// render's box filter) is compared with the render's KIND.exr.
//
// How the render shades, and so the shader (where an engine may differ):
//   - lightmap-sh9 (representations/lightmap.hpp, field.hpp): bilinear at the glTF uv with texel
//     centres at (x + 0.5, y + 0.5) / RES and clamp to edge, with the weights in full precision:
//     the shader fetches the 4 texels (texelFetch) and weighs them itself, since hardware
//     filtering may round the weights (8 fractional bits on most GPUs, and on llvmpipe for
//     8-bit textures: the hardware-filtered result is printed for comparison, not checked). The SH
//     are evaluated in the hit's tangent frame at the normal-mapped normal (bilinear, wrapping,
//     render::Scene:: normal_mapped), clamped to the upper hemisphere: this tangent-space normal is
//     computed on the CPU into the G-buffer ((0, 0, 1) without a normal map). The .glb has no
//     TANGENT: the frame here is the UVs' (tangent along increasing u, bitangent along the scene's
//     v, glTF's 1 - v), which on the normal-mapped quad of scenes/normal_wall.json equals the
//     scene's tangents up to rounding, as an engine's MikkTSpace frame would on a planar chart. E =
//     albedo sum_k e_k y_k / pi.
//   - volume (representations/volume.hpp): trilinear over the probes of the point's cell,
//     leaving out the probes inside geometry (_INSIDE) and renormalising (ProbeGrid::
//     interpolate_valid), else the nearest valid probe (found here on the CPU, from the exported
//     _INSIDE slices); weights from sphbasis_probe_weights, the 8 probes read with texelFetch:
//     hardware trilinear filtering at uvw = ((p - origin) / spacing + 0.5) / counts would also
//     blend the probes inside geometry. E = albedo sum_k a_l L_k y_k(n) at the shading normal.
//
// Bound, per pixel and channel (B below): the range compression's |v' - v| <= max_error per
// texel or probe channel (docs/export-format.md) carried through the shading, which is linear in
// the stored values with weights summing to 1:
//   lightmap  B_q = albedo / pi * sum_k |y_k| max_error_k
//   volume    B_q = albedo * sum_k a_l |y_k(n)| max_error_k
// plus the float arithmetic of the shader and of its float inputs (hit position and uv rounded
// to float, decoded values, weights, sums), allowed as kFloatUlps float ulps of the same sums
// with max_error replaced by |bias| + scale (the magnitude of a decoded value). With float
// encoding B_q is 2^-25 scale (the EXR's rounding), so the allowance dominates; with png8 it is
// scale / 510 and B_q dominates.
//
// Not a Catch2 test (it needs a driver): its own executable and ctests (label shaders), which
// skip (exit 77) where EGL offers no surfaceless platform.
#include <stb/stb_image.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gl_harness.hpp"
#include "sphbasis/core/clamped_cosine.hpp"
#include "sphbasis/render/camera.hpp"
#include "sphbasis/render/image_loop.hpp"
#include "sphbasis/render/probe_grid.hpp"
#include "sphbasis/render/scene.hpp"
#include "support/exr.hpp"
#include "support/gltf.hpp"
#include "support/scene_file.hpp"

namespace {

using namespace shader_harness;
namespace render = sphbasis::render;
using Json = nlohmann::json;

// The float arithmetic's allowance in float ulps of the shading's magnitude (header comment).
// Measured on Mesa 22.3.6 llvmpipe against g++ 12 (printed every run) with float encoding:
// lightmap-sh9 10 ulps (the uv rounded to float moves the bilinear weights by about 2^-24 RES),
// volume 3.1 ulps.
constexpr double kFloatUlps = 32.0;
constexpr double kUlp = 0x1p-24;

Json read_json(const std::string& path) {
    try {
        return Json::parse(read_file(path));
    } catch (const std::exception& e) {
        fail("cannot parse " + path + ": " + e.what());
    }
}

// An image of 3 channels as stored in its file, ready for glTexImage: 8- or 16-bit PNG codes or
// EXR floats.
struct Texels {
    int width = 0, height = 0;
    unsigned type = GL_UNSIGNED_BYTE;  // GL_UNSIGNED_BYTE, GL_UNSIGNED_SHORT or GL_FLOAT
    std::vector<unsigned char> bytes;
    // t of texel i, channel c as the shader reads it (PNG: code / (2^bits - 1)).
    double t(std::size_t i, int c) const {
        const std::size_t k = 3 * i + std::size_t(c);
        if (type == GL_UNSIGNED_BYTE) return bytes[k] / 255.0;
        if (type == GL_UNSIGNED_SHORT) {
            std::uint16_t v;
            std::memcpy(&v, bytes.data() + 2 * k, 2);
            return v / 65535.0;
        }
        float v;
        std::memcpy(&v, bytes.data() + 4 * k, 4);
        return v;
    }
};

Texels load_texels(const std::string& path) {
    Texels t;
    const bool exr = path.size() > 4 && path.compare(path.size() - 4, 4, ".exr") == 0;
    if (exr) {
        const sphbasis::cli::RgbImage img = sphbasis::cli::read_exr_rgb_as_stored(path);
        t.width = img.width, t.height = img.height, t.type = GL_FLOAT;
        t.bytes.resize(img.rgb.size() * sizeof(float));
        std::memcpy(t.bytes.data(), img.rgb.data(), t.bytes.size());
        return t;
    }
    int n = 0;
    if (stbi_is_16_bit(path.c_str())) {
        unsigned short* p = stbi_load_16(path.c_str(), &t.width, &t.height, &n, 3);
        if (!p) fail("cannot read " + path);
        t.type = GL_UNSIGNED_SHORT;
        t.bytes.assign(
            reinterpret_cast<unsigned char*>(p),
            reinterpret_cast<unsigned char*>(p) + std::size_t(t.width) * std::size_t(t.height) * 6);
        stbi_image_free(p);
    } else {
        unsigned char* p = stbi_load(path.c_str(), &t.width, &t.height, &n, 3);
        if (!p) fail("cannot read " + path);
        t.bytes.assign(p, p + std::size_t(t.width) * std::size_t(t.height) * 3);
        stbi_image_free(p);
    }
    return t;
}

// The internal format an engine gives an image of the export's encoding.
unsigned internal_format(const std::string& encoding) {
    if (encoding == "png8") return GL_RGB8;
    if (encoding == "png16") return GL_RGB16;
    if (encoding == "half") return GL_RGB16F;
    if (encoding == "float") return GL_RGB32F;
    fail("unknown encoding '" + encoding + "'");
}

// One exported image's decoding: v = bias + scale t per channel, and its error bound.
struct Decode {
    std::array<double, 3> scale{}, bias{}, max_error{};
};
Decode decode_of(const Json& e) {
    Decode d;
    for (std::size_t c = 0; c < 3; ++c) {
        const std::size_t s = e["scale"].size() == 1 ? 0 : c;  // 1-channel images: grey
        d.scale[c] = e["scale"][s].get<double>();
        d.bias[c] = e["bias"][s].get<double>();
        d.max_error[c] = e["max_error"][s].get<double>();
    }
    return d;
}

// The .glb's meshes as the arrays render::Scene takes (node i = mesh i = the scene's mesh i).
struct GlbMesh {
    std::string name;
    std::vector<float> positions, normals, uvs_gltf, uvs_scene;
    std::vector<std::uint32_t> indices;
};

template <class T>
std::vector<T> accessor_data(const tinygltf::Model& m, int index, int comps, int component_type) {
    const tinygltf::Accessor& a = m.accessors.at(std::size_t(index));
    if (a.componentType != component_type ||
        tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != comps)
        fail("scene.glb: accessor " + std::to_string(index) + " has an unexpected type");
    const tinygltf::BufferView& v = m.bufferViews.at(std::size_t(a.bufferView));
    const std::size_t stride = v.byteStride ? v.byteStride : sizeof(T) * std::size_t(comps);
    const unsigned char* p =
        m.buffers.at(std::size_t(v.buffer)).data.data() + v.byteOffset + a.byteOffset;
    std::vector<T> out(a.count * std::size_t(comps));
    for (std::size_t i = 0; i < a.count; ++i)
        std::memcpy(out.data() + i * std::size_t(comps), p + i * stride,
                    sizeof(T) * std::size_t(comps));
    return out;
}

std::vector<GlbMesh> load_glb(const std::string& path) {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    if (!loader.LoadBinaryFromFile(&model, &err, &warn, path))
        fail("cannot read " + path + ": " + err);
    std::vector<GlbMesh> out;
    for (const tinygltf::Mesh& gm : model.meshes) {
        const tinygltf::Primitive& prim = gm.primitives.at(0);
        GlbMesh m;
        m.name = gm.name;
        m.positions = accessor_data<float>(model, prim.attributes.at("POSITION"), 3,
                                           TINYGLTF_COMPONENT_TYPE_FLOAT);
        m.normals = accessor_data<float>(model, prim.attributes.at("NORMAL"), 3,
                                         TINYGLTF_COMPONENT_TYPE_FLOAT);
        m.indices = accessor_data<std::uint32_t>(model, prim.indices, 1,
                                                 TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
        if (prim.attributes.count("TEXCOORD_0")) {
            m.uvs_gltf = accessor_data<float>(model, prim.attributes.at("TEXCOORD_0"), 2,
                                              TINYGLTF_COMPONENT_TYPE_FLOAT);
            // The scene's UVs, whose v is up (docs/export-format.md): render::Scene's tangent
            // frames follow them.
            m.uvs_scene = m.uvs_gltf;
            for (std::size_t i = 1; i < m.uvs_scene.size(); i += 2)
                m.uvs_scene[i] = 1.0f - m.uvs_scene[i];
        }
        out.push_back(std::move(m));
    }
    return out;
}

// The extra OpenGL entry point the harness does not load.
using TexImage3D = PFNGLTEXIMAGE3DPROC;

// Uploads images as the layers (or depth slices) of one texture of `target`: nearest filtering
// (the shader fetches texels: header comment), or linear (hardware filtering, for comparison).
unsigned upload(const Gl& gl, TexImage3D tex_image_3d, unsigned target, unsigned unit,
                unsigned format, const std::vector<Texels>& layers, unsigned filter = GL_NEAREST) {
    const int w = layers.at(0).width, h = layers.at(0).height;
    std::vector<unsigned char> all;
    for (const Texels& t : layers) {
        if (t.width != w || t.height != h || t.type != layers[0].type)
            fail("the exported images of one texture differ in size or type");
        all.insert(all.end(), t.bytes.begin(), t.bytes.end());
    }
    unsigned tex = 0;
    gl.GenTextures(1, &tex);
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    gl.BindTexture(target, tex);
    gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    tex_image_3d(target, 0, int(format), w, h, int(layers.size()), 0, GL_RGB, layers[0].type,
                 all.data());
    gl.TexParameteri(target, GL_TEXTURE_MIN_FILTER, int(filter));
    gl.TexParameteri(target, GL_TEXTURE_MAG_FILTER, int(filter));
    for (unsigned wrap : {0u + GL_TEXTURE_WRAP_S, 0u + GL_TEXTURE_WRAP_T, 0u + GL_TEXTURE_WRAP_R})
        gl.TexParameteri(target, wrap, GL_CLAMP_TO_EDGE);
    gl.TexParameteri(target, GL_TEXTURE_MAX_LEVEL, 0);
    if (gl.GetError() != GL_NO_ERROR) fail("OpenGL error uploading a texture");
    return tex;
}

void upload_buffer(const Gl& gl, unsigned binding, const std::vector<float>& v) {
    unsigned b = 0;
    gl.GenBuffers(1, &b);
    gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(v.size() * sizeof(float)), v.data(),
                  GL_STATIC_DRAW);
    gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, b);
}

// Per pixel: position, shading normal, glTF uv, albedo, index (mesh or nearest valid probe),
// tangent-space normal.
constexpr std::size_t kG = 16;

const char* kLightmapShader = R"(
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2DArray lightmap;  // layer = mesh * 9 + k
layout(binding = 1) uniform sampler2DArray lightmap_linear;  // the same, GL_LINEAR
layout(std430, binding = 0) readonly buffer G { float gbuf[]; };
layout(std430, binding = 1) readonly buffer D { float dec[]; };  // per layer: scale, bias (RGB)
layout(std430, binding = 3) writeonly buffer O { float outv[]; };
layout(std430, binding = 4) writeonly buffer H { float outh[]; };  // hardware filtering
uniform uint count;

vec3 decode(int k, vec3 t) {
    int d = 6 * k;
    return vec3(dec[d + 3], dec[d + 4], dec[d + 5]) + vec3(dec[d], dec[d + 1], dec[d + 2]) * t;
}

vec3 texel(int layer, int x, int y) {
    return decode(layer, texelFetch(lightmap, ivec3(x, y, layer), 0).rgb);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    uint g = 16u * i;
    vec2 uv = vec2(gbuf[g + 6u], gbuf[g + 7u]);
    vec3 albedo = vec3(gbuf[g + 8u], gbuf[g + 9u], gbuf[g + 10u]);
    int mesh = int(gbuf[g + 11u]);
    vec3 tn = vec3(gbuf[g + 12u], gbuf[g + 13u], gbuf[g + 14u]);
    // Bilinear, texel centres at (x + 0.5) / size, clamp to edge (render's Field lookup).
    ivec2 size = textureSize(lightmap, 0).xy;
    float x = clamp(uv.x * float(size.x) - 0.5, 0.0, float(size.x - 1));
    float y = clamp(uv.y * float(size.y) - 0.5, 0.0, float(size.y - 1));
    int x0 = min(int(x), size.x - 1); int y0 = min(int(y), size.y - 1);
    int x1 = min(x0 + 1, size.x - 1); int y1 = min(y0 + 1, size.y - 1);
    float ax = x - float(x0); float ay = y - float(y0);
    float w00 = (1.0 - ax) * (1.0 - ay), w10 = ax * (1.0 - ay);
    float w01 = (1.0 - ax) * ay, w11 = ax * ay;
    float yk[9];
    sphbasis_sh_eval3(tn, yk);
    vec3 s = vec3(0.0), sh = vec3(0.0);
    for (int k = 0; k < 9; ++k) {
        int l = mesh * 9 + k;
        vec3 e = w00 * texel(l, x0, y0) + w10 * texel(l, x1, y0) + w01 * texel(l, x0, y1) +
                 w11 * texel(l, x1, y1);
        s += e * yk[k];
        sh += decode(l, textureLod(lightmap_linear, vec3(uv, float(l)), 0.0).rgb) * yk[k];
    }
    vec3 o = albedo * s * sphbasis_inv_pi;
    outv[3u * i] = o.x; outv[3u * i + 1u] = o.y; outv[3u * i + 2u] = o.z;
    o = albedo * sh * sphbasis_inv_pi;
    outh[3u * i] = o.x; outh[3u * i + 1u] = o.y; outh[3u * i + 2u] = o.z;
}
)";

const char* kVolumeShader = R"(
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler3D radiance;  // depth k * nz + slice: SH coefficient k
layout(binding = 1) uniform sampler3D inside;    // _INSIDE, depth = slice
layout(binding = 2) uniform sampler3D radiance_linear;  // radiance, GL_LINEAR
layout(std430, binding = 0) readonly buffer G { float gbuf[]; };
layout(std430, binding = 1) readonly buffer D { float dec[]; };  // per coefficient: scale, bias
layout(std430, binding = 3) writeonly buffer O { float outv[]; };
layout(std430, binding = 4) writeonly buffer H { float outh[]; };  // hardware filtering
uniform uint count;

vec3 decode(int k, vec3 t) {
    int d = 6 * k;
    return vec3(dec[d + 3], dec[d + 4], dec[d + 5]) + vec3(dec[d], dec[d + 1], dec[d + 2]) * t;
}

ivec3 probe(int index) {
    ivec3 n = PROBE_COUNTS;
    return ivec3(index % n.x, (index / n.x) % n.y, index / (n.x * n.y));
}

vec3 rad(int k, int index) {
    ivec3 p = probe(index);
    return decode(k, texelFetch(radiance, ivec3(p.xy, k * PROBE_COUNTS.z + p.z), 0).rgb);
}

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    uint g = 16u * i;
    vec3 p = vec3(gbuf[g], gbuf[g + 1u], gbuf[g + 2u]);
    vec3 n = vec3(gbuf[g + 3u], gbuf[g + 4u], gbuf[g + 5u]);
    vec3 albedo = vec3(gbuf[g + 8u], gbuf[g + 9u], gbuf[g + 10u]);
    int idx[8]; float w[8]; bool ins[8];
    sphbasis_probe_weights(p, PROBE_LO, PROBE_HI, PROBE_COUNTS, idx, w);
    bool any_inside = false;
    for (int q = 0; q < 8; ++q) {
        ins[q] = PROBES_ALL_INSIDE ? false : texelFetch(inside, probe(idx[q]), 0).r > 0.5;
        any_inside = any_inside || ins[q];
    }
    if (!sphbasis_probe_weights_valid(w, ins)) {
        for (int q = 0; q < 8; ++q) { idx[q] = int(gbuf[g + 11u]); w[q] = q == 0 ? 1.0 : 0.0; }
    }
    vec3 L[9];
    for (int k = 0; k < 9; ++k) {
        L[k] = vec3(0.0);
        for (int q = 0; q < 8; ++q) L[k] += w[q] * rad(k, idx[q]);
    }
    vec3 o = sphbasis_volume_shade(L, n, albedo);
    outv[3u * i] = o.x; outv[3u * i + 1u] = o.y; outv[3u * i + 2u] = o.z;
    // Hardware trilinear filtering at uvw = ((p - origin) / spacing + 0.5) / counts (probe
    // k's block of slices at depth k nz): right only where no probe of the cell is inside.
    vec3 c = vec3(PROBE_COUNTS);
    vec3 sp = (PROBE_HI - PROBE_LO) / max(c - 1.0, vec3(1.0));
    vec3 s = (clamp(p, PROBE_LO, PROBE_HI) - PROBE_LO) / max(sp, vec3(1e-30));
    for (int k = 0; k < 9; ++k) {
        vec3 uvw = vec3((s.xy + 0.5) / c.xy, (float(k) * c.z + s.z + 0.5) / (9.0 * c.z));
        L[k] = decode(k, textureLod(radiance_linear, uvw, 0.0).rgb);
    }
    o = any_inside ? vec3(uintBitsToFloat(0x7fc00000u)) : sphbasis_volume_shade(L, n, albedo);
    outh[3u * i] = o.x; outh[3u * i + 1u] = o.y; outh[3u * i + 2u] = o.z;
}
)";

// Skips (exit 77) where EGL has no surfaceless platform: no driver to run the shader on.
void skip_without_egl() {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!has_extension(client, "EGL_MESA_platform_surfaceless")) {
        std::printf(
            "sphbasis_shader_export_pixels_test: SKIP: EGL has no "
            "EGL_MESA_platform_surfaceless: install Mesa's EGL (libegl-mesa0, libgl1-mesa-dri)\n");
        std::exit(77);
    }
}

int run(int argc, char** argv) {
    if (argc < 5 || (std::string(argv[1]) != "lightmap-sh9" && std::string(argv[1]) != "volume")) {
        std::fprintf(stderr,
                     "usage: %s lightmap-sh9|volume BAKE_DIR RENDER_DIR SCENE.json "
                     "[GLB [SHADERS_DIR]]\n",
                     argv[0]);
        return 2;
    }
    const std::string kind = argv[1], bake = argv[2], rdir = argv[3], scene_file = argv[4];
    const std::string glb_file = argc > 5 ? argv[5] : bake + "/scene.glb";
    const std::string dir = argc > 6 ? argv[6] : std::string(SPHBASIS_SOURCE_DIR) + "/shaders";
    const bool lightmap = kind == "lightmap-sh9";
    skip_without_egl();
    create_context();
    const Gl gl = load_gl();
    TexImage3D tex_image_3d = nullptr;
    load(tex_image_3d, "glTexImage3D");

    // The .glb's meshes (node i = mesh i = the scene's mesh i).
    const std::vector<GlbMesh> glb = load_glb(glb_file);
    // From the scene file (the export holds no material): each mesh's albedo, as the render's
    // float, and its tangent-space normal map (loaded as the scene loader does).
    const Json sj = read_json(scene_file);
    const std::string scene_dir = [&] {
        const std::size_t slash = scene_file.find_last_of('/');
        return slash == std::string::npos ? std::string(".") : scene_file.substr(0, slash);
    }();
    std::vector<std::array<float, 3>> albedo;
    std::vector<sphbasis::cli::SceneTexture> normal_maps;
    std::vector<render::MeshView> views;
    for (const GlbMesh& m : glb) {
        const Json* mj = nullptr;
        for (const Json& e : sj.at("meshes"))
            if (e.value("name", "") == m.name) mj = &e;
        if (!mj || !mj->contains("albedo")) fail("the scene file gives no albedo for " + m.name);
        const Json& a = mj->at("albedo");
        albedo.push_back({a[0].get<float>(), a[1].get<float>(), a[2].get<float>()});
        normal_maps.emplace_back();
        if (mj->contains("normal_map"))
            normal_maps.back() = sphbasis::cli::load_texture(
                scene_dir + "/" + mj->at("normal_map").get<std::string>(), false);
    }
    // The .glb's geometry in an Embree scene (tangent frames from the UVs: the .glb has no
    // TANGENT; the scene's shapes give the same frames up to rounding).
    for (std::size_t i = 0; i < glb.size(); ++i) {
        const GlbMesh& m = glb[i];
        render::MeshView v;
        v.positions = m.positions.data();
        v.vertex_count = m.positions.size() / 3;
        v.indices = m.indices.data();
        v.triangle_count = m.indices.size() / 3;
        v.normals = m.normals.data();
        if (!m.uvs_scene.empty()) v.uvs = m.uvs_scene.data();
        const sphbasis::cli::SceneTexture& t = normal_maps[i];
        if (t.texels) v.normal_map = {t.texels->data(), t.width, t.height, t.channels};
        views.push_back(v);
    }
    const render::Scene scene(views);

    // The render's image and AOVs; the camera of the scene file at the image's size.
    const sphbasis::cli::RgbImage img =
        sphbasis::cli::read_exr_rgb_as_stored(rdir + "/" + kind + ".exr");
    const sphbasis::cli::RgbImage aov_albedo =
        sphbasis::cli::read_exr_rgb_as_stored(rdir + "/aov_albedo.exr");
    const sphbasis::cli::RgbImage aov_position =
        sphbasis::cli::read_exr_rgb_as_stored(rdir + "/aov_position.exr");
    const Json& cj = sj.at("camera");
    render::Camera cam;
    auto v3 = [](const Json& j) {
        return sphbasis::vec3<double>{j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
    };
    cam.position = v3(cj.at("position"));
    cam.look_at = v3(cj.at("look_at"));
    if (cj.contains("up")) cam.up = v3(cj["up"]);
    if (cj.contains("fov_deg")) cam.fov_deg = cj["fov_deg"].get<double>();
    cam.width = img.width;
    cam.height = img.height;
    const render::PinholeCamera pc(cam);

    // The exported files: decoding per layer (lightmap: mesh * 9 + k; volume: k) and textures.
    std::vector<Decode> dec;
    std::vector<float> decf;
    render::ProbeGrid grid;
    std::vector<std::uint8_t> inside;
    bool all_inside = false;
    std::string encoding;
    auto attr = [](const Json& list, const std::string& name) -> const Json& {
        for (const Json& e : list)
            if (e.at("attribute") == name) return e;
        fail("no attribute " + name + " in the export");
    };
    if (lightmap) {
        const Json j = read_json(bake + "/lightmaps.json");
        encoding = j.at("encoding").get<std::string>();
        std::vector<Texels> layers;
        for (const GlbMesh& m : glb) {
            const Json* mj = nullptr;
            for (const Json& e : j.at("meshes"))
                if (e.at("mesh") == m.name) mj = &e;
            if (!mj) fail("lightmaps.json has no mesh " + m.name);
            for (int k = 0; k < 9; ++k) {
                const Json& e = attr(mj->at("images"), "_SH" + std::to_string(k));
                dec.push_back(decode_of(e));
                layers.push_back(load_texels(bake + "/" + e.at("file").get<std::string>()));
            }
        }
        upload(gl, tex_image_3d, GL_TEXTURE_2D_ARRAY, 0, internal_format(encoding), layers);
        upload(gl, tex_image_3d, GL_TEXTURE_2D_ARRAY, 1, internal_format(encoding), layers,
               GL_LINEAR);
    } else {
        const Json j = read_json(bake + "/probes.grid.json");
        encoding = j.at("encoding").get<std::string>();
        grid.lo = v3(j.at("origin"));
        grid.hi = v3(j.at("max"));
        for (std::size_t a = 0; a < 3; ++a) grid.counts[a] = j.at("counts")[a].get<int>();
        std::vector<Texels> slices, inside_slices;
        for (int k = 0; k < 9; ++k) {
            const Json& e = attr(j.at("attributes"), "_RAD" + std::to_string(k));
            dec.push_back(decode_of(e));
            for (const Json& s : e.at("slices"))
                slices.push_back(load_texels(bake + "/" + s.at("file").get<std::string>()));
        }
        for (const Json& s : attr(j.at("attributes"), "_INSIDE").at("slices"))
            inside_slices.push_back(load_texels(bake + "/" + s.at("file").get<std::string>()));
        upload(gl, tex_image_3d, GL_TEXTURE_3D, 0, internal_format(encoding), slices);
        upload(gl, tex_image_3d, GL_TEXTURE_3D, 1, internal_format(encoding), inside_slices);
        upload(gl, tex_image_3d, GL_TEXTURE_3D, 2, internal_format(encoding), slices, GL_LINEAR);
        // The inside flags on the CPU too: the nearest valid probe where a cell has none.
        inside.assign(grid.size(), 0);
        for (std::size_t p = 0; p < grid.size(); ++p) {
            const std::size_t slice_texels =
                std::size_t(grid.counts[0]) * std::size_t(grid.counts[1]);
            inside[p] = inside_slices.at(p / slice_texels).t(p % slice_texels, 0) > 0.5;
        }
        // Every probe inside: the renderer keeps them all (representations/field.hpp).
        all_inside = std::find(inside.begin(), inside.end(), 0) == inside.end();
        if (all_inside) std::fill(inside.begin(), inside.end(), 0);
    }
    for (const Decode& d : dec)
        for (const auto* a : {&d.scale, &d.bias})
            for (double x : *a) decf.push_back(float(x));

    // The G-buffer: the render's camera rays (render::ImageLoop's sample positions: its seed and
    // sample count from report.json) cast on the .glb's triangles. Pixels whose samples all hit
    // geometry are shaded; the render's pixel is the mean of its samples (box filter).
    const Json report = read_json(rdir + "/report.json");
    const int spp = report.at("sampling").at("representation_spp").get<int>();
    std::uint64_t seed = 0;
    {
        const std::string cmd = report.at("command").get<std::string>();
        const std::size_t at = cmd.find("--seed ");
        if (at != std::string::npos) seed = std::stoull(cmd.substr(at + 7));
    }
    std::vector<float> gbuf;
    std::vector<int> pixel;
    std::vector<double> bound_q, bound_f;  // per sample and channel
    double a_l[3];
    sphbasis::clamped_cosine_factors(3, a_l);
    std::size_t aov_mismatch = 0, coverage_mismatch = 0, albedo_mismatch = 0;
    double worst_position = 0;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const std::size_t px = std::size_t(y) * std::size_t(cam.width) + std::size_t(x);
            const auto offset = render::pixel_offset(render::pixel_key(seed, px));
            std::vector<render::Hit> hs;
            for (int s = 0; s < spp; ++s) {
                const auto d = render::pixel_sample(offset, std::uint64_t(s), spp);
                const render::CameraRay ray = pc.ray(x + d[0], y + d[1]);
                const render::Hit h = scene.intersect(ray.origin, ray.direction);
                if (h.valid) hs.push_back(h);
            }
            const float* alb = &aov_albedo.rgb[3 * px];
            const bool aov_hit = alb[0] != 0 || alb[1] != 0 || alb[2] != 0;
            if (hs.empty() == aov_hit) ++coverage_mismatch;
            if (int(hs.size()) != spp) continue;  // a sample sees the background: not shaded
            const float* ap = &aov_position.rgb[3 * px];
            sphbasis::vec3<double> mean{0, 0, 0};
            for (const render::Hit& h : hs)
                mean = {mean.x + h.position.x / spp, mean.y + h.position.y / spp,
                        mean.z + h.position.z / spp};
            const double dp = std::max(
                {std::abs(ap[0] - mean.x), std::abs(ap[1] - mean.y), std::abs(ap[2] - mean.z)});
            worst_position = std::max(worst_position, dp);
            if (dp > 1e-5) ++aov_mismatch;
            bool one_mesh = true;
            for (const render::Hit& h : hs) one_mesh = one_mesh && h.mesh == hs[0].mesh;
            if (one_mesh)
                for (std::size_t c = 0; c < 3; ++c)
                    albedo_mismatch += alb[c] != albedo[hs[0].mesh][c];
            pixel.push_back(int(px));
            for (const render::Hit& h : hs) {
                // glTF uv: TEXCOORD_0 interpolated with the hit's barycentrics.
                float uv[2] = {0, 0};
                const GlbMesh& m = glb[h.mesh];
                if (lightmap) {
                    if (m.uvs_gltf.empty()) fail("mesh " + m.name + " has no TEXCOORD_0");
                    const double b[3] = {1 - h.u - h.v, h.u, h.v};
                    for (std::size_t c = 0; c < 2; ++c) {
                        double s = 0;
                        for (std::size_t k = 0; k < 3; ++k)
                            s += b[k] * m.uvs_gltf[2 * m.indices[3 * h.primitive + k] + c];
                        uv[c] = float(s);
                    }
                }
                const sphbasis::vec3<double> n = h.shading_normal;
                const double index = lightmap
                                         ? double(h.mesh)
                                         : double(grid.nearest_valid(inside.data(), h.position));
                // The lightmap's evaluation direction: the normal-mapped normal in the hit's
                // tangent frame, clamped to the upper hemisphere, as Lightmap::shade.
                double tn[3];
                {
                    using namespace render::detail::rt;
                    const V3 nm = render::Scene::normal_mapped(h), t = h.tangent;
                    const V3 bt = cross(n, t) * h.bitangent_sign;
                    const V3 l = normalized({dot(nm, t), dot(nm, bt), std::max(dot(nm, n), 0.0)});
                    tn[0] = l.x, tn[1] = l.y, tn[2] = l.z;
                }
                const std::array<float, 3>& a = albedo[h.mesh];
                gbuf.insert(gbuf.end(),
                            {float(h.position.x), float(h.position.y), float(h.position.z),
                             float(n.x), float(n.y), float(n.z), uv[0], uv[1], a[0], a[1], a[2],
                             float(index), float(tn[0]), float(tn[1]), float(tn[2]), 0.0f});
                // The bound (header comment): sum_k f_k |y_k| (max_error_k, |bias_k| + scale_k).
                double yv[9];
                if (lightmap)
                    sphbasis::sh::eval_unit(3, tn[0], tn[1], tn[2], yv);
                else
                    sphbasis::sh::eval_unit(3, n.x, n.y, n.z, yv);
                for (std::size_t c = 0; c < 3; ++c) {
                    double q = 0, f = 0;
                    for (std::size_t k = 0; k < 9; ++k) {
                        const Decode& d = dec[lightmap ? 9 * h.mesh + k : k];
                        const double wk =
                            std::abs(yv[k]) *
                            (lightmap ? 0.31830988618379067 : a_l[k == 0 ? 0 : (k < 4 ? 1 : 2)]);
                        q += wk * d.max_error[c];
                        f += wk * (std::abs(d.bias[c]) + d.scale[c]);
                    }
                    bound_q.push_back(a[c] * q);
                    bound_f.push_back(a[c] * f * kFloatUlps * kUlp);
                }
            }
        }
    const unsigned items = unsigned(gbuf.size() / kG);

    // The shader.
    std::string src = "#version 430\n";
    if (!lightmap) {
        char defs[512];
        std::snprintf(defs, sizeof defs,
                      "#define PROBE_LO vec3(%.9g, %.9g, %.9g)\n"
                      "#define PROBE_HI vec3(%.9g, %.9g, %.9g)\n"
                      "#define PROBE_COUNTS ivec3(%d, %d, %d)\n#define PROBES_ALL_INSIDE %s\n",
                      double(float(grid.lo.x)), double(float(grid.lo.y)), double(float(grid.lo.z)),
                      double(float(grid.hi.x)), double(float(grid.hi.y)), double(float(grid.hi.z)),
                      grid.counts[0], grid.counts[1], grid.counts[2],
                      all_inside ? "true" : "false");
        src += defs;
    }
    src += read_file(dir + "/sphbasis.glsl") + "\n" + read_file(dir + "/sphbasis_render.glsl") +
           "\n" + (lightmap ? kLightmapShader : kVolumeShader);
    const unsigned prog = compile_program(gl, src);
    upload_buffer(gl, 0, gbuf);
    upload_buffer(gl, 1, decf);
    std::vector<float> gpu(std::size_t(items) * 3, std::nanf("")), gpu_hw(gpu);
    unsigned out[2] = {0, 0};
    gl.GenBuffers(2, out);
    for (unsigned b = 0; b < 2; ++b) {
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, out[b]);
        gl.BufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(gpu.size() * sizeof(float)), gpu.data(),
                      GL_DYNAMIC_READ);
        gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 3 + b, out[b]);
    }
    gl.UseProgram(prog);
    gl.Uniform1ui(gl.GetUniformLocation(prog, "count"), items);
    gl.DispatchCompute((items + 63) / 64, 1, 1);
    gl.MemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    for (unsigned b = 0; b < 2; ++b) {
        gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, out[b]);
        gl.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(gpu.size() * sizeof(float)),
                            (b == 0 ? gpu : gpu_hw).data());
    }
    gl.Finish();
    if (gl.GetError() != GL_NO_ERROR) fail("OpenGL error");

    // The comparison: each pixel the mean of its samples, the bound the mean of theirs.
    std::size_t over = 0;
    double worst = 0, worst_abs = 0, worst_q = 0, worst_ulps = 0, lo = 1e30, hi = 0;
    double hw_worst = 0, hw_abs = 0;  // hardware filtering (reported, not asserted)
    std::size_t hw_pixels = 0;
    for (std::size_t i = 0; i < pixel.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) {
            double v = 0, vh = 0, bq = 0, bf = 0;
            for (std::size_t s = 0; s < std::size_t(spp); ++s) {
                const std::size_t k = 3 * (i * std::size_t(spp) + s) + c;
                v += double(gpu[k]) / spp, bq += bound_q[k] / spp, bf += bound_f[k] / spp;
                vh += double(gpu_hw[k]) / spp;
            }
            const double ref = img.rgb[3 * std::size_t(pixel[i]) + c];
            const double e = std::isfinite(v) ? std::abs(v - ref) : 1e30;
            worst = std::max(worst, e / (bq + bf));
            worst_abs = std::max(worst_abs, e);
            if (bq > 0) worst_q = std::max(worst_q, e / bq);
            if (bf > 0) worst_ulps = std::max(worst_ulps, e / bf * kFloatUlps);
            over += e > bq + bf;
            if (std::isfinite(vh)) {
                const double eh = std::abs(vh - ref);
                hw_worst = std::max(hw_worst, eh / (bq + bf));
                hw_abs = std::max(hw_abs, eh);
                hw_pixels += c == 0;
            }
            lo = std::min(lo, ref), hi = std::max(hi, ref);
        }
    std::printf(
        "sphbasis_shader_export_pixels_test: %s from %s (%s), %d x %d image at %d spp, %zu "
        "pixels on geometry, values %.3g..%.3g\n",
        kind.c_str(), bake.c_str(), encoding.c_str(), cam.width, cam.height, spp, pixel.size(), lo,
        hi);
    if (!lightmap)
        std::printf("  %d x %d x %d probes, %zu inside geometry%s\n", grid.counts[0],
                    grid.counts[1], grid.counts[2],
                    std::size_t(std::count(inside.begin(), inside.end(), 1)),
                    all_inside ? " (all: every probe used)" : "");
    const bool gbuf_ok = coverage_mismatch == 0 && aov_mismatch == 0 && albedo_mismatch == 0;
    std::printf(
        "  G-buffer (Embree on scene.glb) vs the render's AOVs: %zu coverage, %zu position "
        "(largest difference %.3g), %zu albedo mismatches  %s\n",
        coverage_mismatch, aov_mismatch, worst_position, albedo_mismatch, gbuf_ok ? "ok" : "FAIL");
    std::printf(
        "  GPU pixels vs %s.exr: max |error| %.3g, max error / bound %.3f (bound: the encoding's "
        "max_error carried through + %.0f float ulps of the magnitude); max error / its "
        "quantisation part %.3f, in ulps of the magnitude %.1f; %zu over  %s\n",
        kind.c_str(), worst_abs, worst, kFloatUlps, worst_q, worst_ulps, over,
        over == 0 ? "ok" : "FAIL");
    std::printf(
        "  for comparison, hardware %s filtering (textureLod, GL_LINEAR) on %zu pixels%s: max "
        "|error| %.3g, max error / bound %.3f (not checked)\n",
        lightmap ? "bilinear" : "trilinear", hw_pixels,
        lightmap ? "" : " (cells without probes inside geometry)", hw_abs, hw_worst);
    const bool ok = over == 0 && gbuf_ok && pixel.size() > 500;
    std::printf("sphbasis_shader_export_pixels_test: %s\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const std::exception& e) {  // a file the export or the render lacks, or malformed
        fail(e.what());
    }
}
