// Engine exports of a bake (tools/support/engine_export.hpp, gltf_export.hpp): the range
// compression's error bound for every encoding, with the images decoded by readers other than
// the writers (stb_image for 8- and 16-bit PNG, OpenEXR for half and float); the glTF read back
// with tinygltf and with Assimp (geometry, the UV convention, the application-specific
// attributes, the lightmap textures and their scale and bias); the probe grid's slices against
// the grid's index order. Records are made up (a function of the point), so the expected value
// of every texel, vertex and probe is known.
#include <assimp/material.h>
#include <assimp/mesh.h>
#include <assimp/scene.h>
#include <stb/stb_image.h>
#include <unistd.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/clamped_cosine.hpp>
#include <sphbasis/ops/compression.hpp>
#include <sphbasis/ops/lxh_table.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/render/bake_points.hpp>
#include <sphbasis/render/lightmap.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/engine_export.hpp"
#include "support/exr.hpp"
#include "support/gltf.hpp"
#include "support/gltf_export.hpp"
#include "support/scene_file.hpp"

using namespace sphbasis;
using namespace sphbasis::cli;

namespace {

struct TempDir {
    std::string path;
    TempDir() {
        char tmpl[] = "/tmp/sphbasis-engine-test-XXXXXX";
        const char* p = ::mkdtemp(tmpl);
        REQUIRE(p != nullptr);
        path = p;
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    void write(const std::vector<EngineFile>& files) const {
        for (const EngineFile& f : files) {
            std::ofstream o(path + "/" + f.name, std::ios::binary);
            o.write(f.bytes.data(), std::streamsize(f.bytes.size()));
            REQUIRE(o.good());
        }
    }
};

/// Decoded stored values t in [0, 1] of an image file (PNG by stb_image, EXR by OpenEXR).
std::vector<double> decode_t(const std::string& bytes, ImageEncoding e, std::size_t channels,
                             int& w, int& h, const std::string& tmp) {
    std::vector<double> t;
    int n = 0;
    if (e == ImageEncoding::png8) {
        unsigned char* p = stbi_load_from_memory(
            reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h, &n, 0);
        REQUIRE(p != nullptr);
        REQUIRE(std::size_t(n) == channels);
        for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h) * channels; ++i)
            t.push_back(p[i] / 255.0);
        stbi_image_free(p);
    } else if (e == ImageEncoding::png16) {
        REQUIRE(stbi_is_16_bit_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                                           int(bytes.size())) == 1);
        unsigned short* p = stbi_load_16_from_memory(
            reinterpret_cast<const unsigned char*>(bytes.data()), int(bytes.size()), &w, &h, &n, 0);
        REQUIRE(p != nullptr);
        REQUIRE(std::size_t(n) == channels);
        for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h) * channels; ++i)
            t.push_back(p[i] / 65535.0);
        stbi_image_free(p);
    } else {
        const std::string f = tmp + "/decode.exr";
        std::ofstream(f, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        const RgbImage img = read_exr_rgb_as_stored(f);  // "Y" comes back as grey RGB
        w = img.width;
        h = img.height;
        for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i)
            for (std::size_t c = 0; c < channels; ++c) t.push_back(img.rgb[3 * i + c]);
    }
    return t;
}

/// The stated bound: scale * q, with room for double arithmetic.
double bound(const ChannelRange& r, ImageEncoding e) {
    return r.scale * quantization_step(e) * (1 + 1e-9) + 1e-12 * (std::fabs(r.bias) + r.scale);
}

constexpr ImageEncoding kEncodings[] = {ImageEncoding::png8, ImageEncoding::png16,
                                        ImageEncoding::half, ImageEncoding::float32};

/// A made-up record for a point: ao in [0, 1], a bent normal, SH irradiance of 2 coefficients,
/// one visibility coefficient and standard errors (which the export leaves out).
const std::vector<std::pair<std::string, std::size_t>> kColumns = {
    {"ao", 0},       {"ao_stderr", 1}, {"bent_x", 2},       {"bent_y", 3},  {"bent_z", 4},
    {"irr_r_0", 5},  {"irr_r_1", 6},   {"irr_g_0", 7},      {"irr_g_1", 8}, {"irr_b_0", 9},
    {"irr_b_1", 10}, {"vis_0", 11},    {"vis_stderr_0", 12}};
constexpr std::size_t kStride = 13;

void fill_record(double* r, const vec3<double>& p, std::size_t id) {
    r[0] = 0.5 + 0.5 * std::sin(1.3 * p.x + 0.7 * p.y + 0.1 * double(id % 7));
    r[1] = 0.01;
    const double n = std::sqrt(1 + p.x * p.x * 0.01 + p.y * p.y * 0.04);
    r[2] = 0.1 * p.x / n;
    r[3] = 0.2 * p.y / n;
    r[4] = 1 / n;
    for (int k = 0; k < 6; ++k) r[5 + k] = 3.0 * std::cos(0.9 * p.x + 0.4 * k) - 1.0 * k + p.z;
    r[11] = -0.25 + 1e-3 * double(id % 13);
    r[12] = 0;
}

/// An export of `records` (stride values per point) of the meshes' points (mesh_begin: the first
/// point of each mesh and the end) in the named columns; layouts for texels, else nullptr.
EngineInput engine_input(EngineTarget target, const std::vector<SceneMesh>& meshes,
                         const std::vector<std::size_t>& mesh_begin,
                         const std::vector<render::LightmapLayout>* layouts,
                         std::vector<std::pair<std::string, std::size_t>> columns,
                         const std::vector<double>& records, std::size_t stride) {
    EngineInput in;
    in.target = target;
    in.meshes = &meshes;
    in.mesh_begin = &mesh_begin;
    in.layouts = layouts;
    in.columns = std::move(columns);
    in.records = &records;
    in.stride = stride;
    return in;
}

/// The export's CPCA input (the records' transfer_k columns, one row a point) and the library's
/// model of it, fitted as `in` exports it once with_cpca() set cpca:C:M and the seed.
struct CpcaFit {
    compress::MatrixX<double> x;
    compress::Cpca<double> model;
};

CpcaFit with_cpca(EngineInput& in, int clusters, int vectors, std::uint64_t seed) {
    in.compression = parse_compression_export("cpca:" + std::to_string(clusters) + ":" +
                                              std::to_string(vectors));
    in.seed = seed;
    std::vector<std::size_t> at;  // record offset of transfer_k
    for (std::size_t k = 0;; ++k) {
        const auto c = std::find_if(in.columns.begin(), in.columns.end(), [&](const auto& col) {
            return col.first == "transfer_" + std::to_string(k);
        });
        if (c == in.columns.end()) break;
        at.push_back(c->second);
    }
    const std::size_t P = in.records->size() / in.stride;
    CpcaFit fit;
    fit.x.resize(static_cast<Eigen::Index>(P), static_cast<Eigen::Index>(at.size()));
    for (std::size_t p = 0; p < P; ++p)
        for (std::size_t k = 0; k < at.size(); ++k)
            fit.x(Eigen::Index(p), Eigen::Index(k)) = (*in.records)[p * in.stride + at[k]];
    compress::CpcaSettings cs;
    cs.clusters = clusters;
    cs.vectors = vectors;
    cs.seed = seed;
    fit.model = compress::cpca_iterative(fit.x, cs);
    return fit;
}

}  // namespace

TEST_CASE("engine export: range compression within scale * q for every encoding", "[tool]") {
    TempDir tmp;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    const int w = 37, h = 11;
    for (std::size_t ch : {std::size_t(1), std::size_t(3)}) {
        std::vector<float> v(std::size_t(w * h) * ch);
        for (std::size_t i = 0; i < v.size(); ++i) {
            const std::size_t c = i % ch;
            v[i] = c == 2 ? 4.25f  // a constant channel: decoded exactly
                          : static_cast<float>(100.0 * double(c + 1) * u(rng) - 30.0);
        }
        std::vector<ChannelRange> r;
        for (std::size_t c = 0; c < ch; ++c) r.push_back(fit_range(v, ch, c));
        for (ImageEncoding e : kEncodings) {
            INFO(image_encoding_name(e) << ", " << ch << " channels");
            int dw = 0, dh = 0;
            const std::vector<double> t =
                decode_t(encode_compressed(v, w, h, ch, r, e), e, ch, dw, dh, tmp.path);
            REQUIRE(dw == w);
            REQUIRE(dh == h);
            double worst = 0;
            for (std::size_t i = 0; i < v.size(); ++i) {
                const ChannelRange& x = r[i % ch];
                const double err = std::fabs(x.bias + x.scale * t[i] - double(v[i]));
                REQUIRE(err <= bound(x, e));
                if (x.scale > 0) worst = std::max(worst, err / (x.scale * quantization_step(e)));
                if (x.scale == 0) REQUIRE(x.bias + x.scale * t[i] == double(v[i]));
            }
            // The bound is the quantisation's: random data comes close to it.
            CHECK(worst > 0.5);
        }
    }
    CHECK_THROWS_WITH(parse_image_encoding("png12"),
                      "--encoding: expected png8, png16, half or float, got 'png12'");
    CHECK(quantization_step(ImageEncoding::png8) == 1.0 / 510);
}

TEST_CASE("engine export: attribute names from the bake's channels", "[tool]") {
    const std::vector<EngineAttribute> a = engine_attributes(kColumns, "sh");
    REQUIRE(a.size() == 5);
    CHECK(a[0].name == "_AO");
    CHECK(a[0].fixed);
    CHECK(a[1].name == "_BENT");
    CHECK(a[1].offsets == std::vector<std::size_t>{2, 3, 4});
    CHECK(a[2].name == "_SH0");
    CHECK(a[2].offsets == std::vector<std::size_t>{5, 7, 9});
    CHECK(a[3].name == "_SH1");
    CHECK(a[4].name == "_VIS0");
    CHECK(engine_attributes(kColumns, "hbasis-mod")[2].name == "_HBASIS_MOD0");
    const std::vector<EngineAttribute> t = engine_attributes({{"transfer_r_0", 0},
                                                              {"transfer_g_0", 1},
                                                              {"transfer_b_0", 2},
                                                              {"rad_r_0", 3},
                                                              {"rad_g_0", 4},
                                                              {"rad_b_0", 5},
                                                              {"inside", 6}},
                                                             "sh");
    REQUIRE(t.size() == 3);
    CHECK(t[0].name == "_PRT0");
    CHECK(t[0].offsets.size() == 3);
    CHECK(t[1].name == "_RAD0");
    CHECK(t[2].name == "_INSIDE");
}

TEST_CASE("engine export: a vertex bake as glTF, read back with tinygltf and Assimp", "[tool]") {
    const SceneFile scene =
        load_scene(std::string(SPHBASIS_TEST_DATA_DIR) + "/scenes/quad_obj.json");
    std::vector<std::size_t> begin{0};
    for (const SceneMesh& m : scene.meshes) begin.push_back(begin.back() + m.mesh.vertex_count());
    std::vector<double> rec(begin.back() * kStride);
    std::size_t id = 0;
    for (const SceneMesh& m : scene.meshes)
        for (std::size_t v = 0; v < m.mesh.vertex_count(); ++v, ++id)
            fill_record(
                rec.data() + id * kStride,
                {m.mesh.positions[3 * v], m.mesh.positions[3 * v + 1], m.mesh.positions[3 * v + 2]},
                id);
    EngineInput in =
        engine_input(EngineTarget::vertices, scene.meshes, begin, nullptr, kColumns, rec, kStride);
    Json outputs = Json::array();
    const std::vector<EngineFile> files = export_engine(in, outputs);
    REQUIRE(files.size() == 1);
    CHECK(engine_file_names(in) == std::vector<std::string>{"scene.glb"});
    TempDir tmp;
    tmp.write(files);
    const std::string glb = tmp.path + "/scene.glb";

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, glb));
    INFO(err << warn);
    REQUIRE(model.meshes.size() == scene.meshes.size());
    auto floats = [&](int accessor, int comps) {
        const tinygltf::Accessor& a = model.accessors[std::size_t(accessor)];
        REQUIRE(a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT);
        REQUIRE(tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) == comps);
        const tinygltf::BufferView& v = model.bufferViews[std::size_t(a.bufferView)];
        const unsigned char* p =
            model.buffers[std::size_t(v.buffer)].data.data() + v.byteOffset + a.byteOffset;
        std::vector<float> out(a.count * std::size_t(comps));
        std::memcpy(out.data(), p, out.size() * sizeof(float));
        return out;
    };
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
        const render::Mesh& m = scene.meshes[k].mesh;
        const tinygltf::Primitive& prim = model.meshes[k].primitives.at(0);
        CHECK(model.meshes[k].name == scene.meshes[k].name);
        CHECK(floats(prim.attributes.at("POSITION"), 3) == m.positions);
        const std::vector<float> uv = floats(prim.attributes.at("TEXCOORD_0"), 2);
        for (std::size_t i = 0; i < uv.size(); ++i)
            CHECK(uv[i] == (i % 2 == 0 ? m.uvs[i] : 1.0f - m.uvs[i]));
        const std::vector<float> ao = floats(prim.attributes.at("_AO"), 1);
        const std::vector<float> bent = floats(prim.attributes.at("_BENT"), 3);
        const std::vector<float> sh1 = floats(prim.attributes.at("_SH1"), 3);
        const std::vector<float> vis = floats(prim.attributes.at("_VIS0"), 1);
        CHECK(prim.attributes.count("_AO_STDERR") == 0);
        for (std::size_t v = 0; v < m.vertex_count(); ++v) {
            const double* r = rec.data() + (begin[k] + v) * kStride;
            // FLOAT attributes: the record rounded to float, nothing else.
            CHECK(ao[v] == static_cast<float>(r[0]));
            for (std::size_t c = 0; c < 3; ++c) {
                CHECK(bent[3 * v + c] == static_cast<float>(r[2 + c]));
                CHECK(sh1[3 * v + c] == static_cast<float>(r[6 + 2 * c]));
            }
            CHECK(vis[v] == static_cast<float>(r[11]));
        }
    }

    // Assimp: an importer written apart from tinygltf. It reads the geometry (not the
    // application-specific attributes) and turns glTF's v back into the scene's (v up).
    Assimp::Importer importer;
    const aiScene* as = importer.ReadFile(glb, 0);
    INFO(importer.GetErrorString());
    REQUIRE(as != nullptr);
    REQUIRE(as->mNumMeshes == scene.meshes.size());
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
        const render::Mesh& m = scene.meshes[k].mesh;
        const aiMesh* am = as->mMeshes[k];
        REQUIRE(am->mNumVertices == m.vertex_count());
        REQUIRE(am->mNumFaces * 3 == m.indices.size());
        REQUIRE(am->HasTextureCoords(0));
        for (unsigned v = 0; v < am->mNumVertices; ++v) {
            CHECK(am->mVertices[v].x == m.positions[3 * v]);
            CHECK(am->mVertices[v].z == m.positions[3 * v + 2]);
            CHECK(am->mTextureCoords[0][v].x == m.uvs[2 * v]);
            CHECK(std::fabs(am->mTextureCoords[0][v].y - m.uvs[2 * v + 1]) <= 1e-6f);
        }
        for (unsigned f = 0; f < am->mNumFaces; ++f)
            for (unsigned c = 0; c < 3; ++c)
                CHECK(am->mFaces[f].mIndices[c] == m.indices[3 * f + c]);
    }
}

TEST_CASE("engine export: texel lightmaps within the stated bound; glTF textures", "[tool]") {
    const SceneFile scene =
        load_scene(std::string(SPHBASIS_TEST_DATA_DIR) + "/scenes/quad_obj.json");
    const render::SceneDesc desc = scene.scene_desc();
    const int res = 24;
    std::vector<render::LightmapLayout> layouts;
    std::vector<std::size_t> begin{0};
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
        layouts.push_back(render::texel_layout(desc.meshes, k, res));
        begin.push_back(begin.back() + layouts.back().samples.size());
    }
    std::vector<double> rec(begin.back() * kStride);
    for (std::size_t k = 0; k < layouts.size(); ++k)
        for (std::size_t i = 0; i < layouts[k].samples.size(); ++i)
            fill_record(rec.data() + (begin[k] + i) * kStride, layouts[k].samples[i].point.p,
                        begin[k] + i);
    for (ImageEncoding e : kEncodings) {
        INFO(image_encoding_name(e));
        EngineInput in = engine_input(EngineTarget::texels, scene.meshes, begin, &layouts, kColumns,
                                      rec, kStride);
        in.encoding = e;
        Json outputs = Json::array();
        const std::vector<EngineFile> files = export_engine(in, outputs);
        std::vector<std::string> names;
        for (const EngineFile& f : files) names.push_back(f.name);
        std::vector<std::string> declared = engine_file_names(in);
        std::sort(names.begin(), names.end());
        std::sort(declared.begin(), declared.end());
        CHECK(names == declared);
        TempDir tmp;
        tmp.write(files);
        std::ifstream jf(tmp.path + "/lightmaps.json");
        const nlohmann::json doc = nlohmann::json::parse(jf);
        REQUIRE(doc.at("meshes").size() == scene.meshes.size());
        CHECK(doc.at("quantization_step").get<double>() == quantization_step(e));
        const std::vector<EngineAttribute> attrs = engine_attributes(kColumns, "sh");
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const nlohmann::json& mj = doc.at("meshes")[k];
            REQUIRE(mj.at("images").size() == attrs.size());
            for (std::size_t a = 0; a < attrs.size(); ++a) {
                const nlohmann::json& ij = mj.at("images")[a];
                const std::size_t ch = attrs[a].offsets.size();
                CHECK(ij.at("attribute") == attrs[a].name);
                // The expected image: the records assembled as the native EXR does.
                const std::vector<float> want =
                    render::assemble_lightmap(layouts[k], int(ch), [&](std::size_t i, float* px) {
                        for (std::size_t c = 0; c < ch; ++c)
                            px[c] = float(rec[(begin[k] + i) * kStride + attrs[a].offsets[c]]);
                    });
                std::ifstream f(tmp.path + "/" + ij.at("file").get<std::string>(),
                                std::ios::binary);
                const std::string bytes((std::istreambuf_iterator<char>(f)),
                                        std::istreambuf_iterator<char>());
                int w = 0, h = 0;
                const std::vector<double> t = decode_t(bytes, e, ch, w, h, tmp.path);
                REQUIRE(w == res);
                REQUIRE(h == res);
                REQUIRE(t.size() == want.size());
                for (std::size_t i = 0; i < t.size(); ++i) {
                    const ChannelRange r{ij.at("scale")[i % ch].get<double>(),
                                         ij.at("bias")[i % ch].get<double>()};
                    REQUIRE(std::fabs(r.bias + r.scale * t[i] - double(want[i])) <= bound(r, e));
                }
            }
        }
        // The glTF: textures on TEXCOORD_0 (PNG), AO as the occlusion texture, the same scale
        // and bias in the primitive's extras; EXR lightmaps listed there without a texture.
        tinygltf::Model model;
        tinygltf::TinyGLTF loader;
        std::string err, warn;
        REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, tmp.path + "/scene.glb"));
        const bool png = e == ImageEncoding::png8 || e == ImageEncoding::png16;
        CHECK(model.textures.size() == (png ? scene.meshes.size() * attrs.size() : 0));
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const tinygltf::Primitive& prim = model.meshes[k].primitives.at(0);
            const tinygltf::Value& lm = prim.extras.Get("sphbasis_lightmaps");
            REQUIRE(lm.IsObject());
            const tinygltf::Value& sh0 = lm.Get("_SH0");
            CHECK(sh0.Get("texCoord").GetNumberAsInt() == 0);
            CHECK(sh0.Get("scale").Get(1).GetNumberAsDouble() ==
                  doc.at("meshes")[k].at("images")[2].at("scale")[1].get<double>());
            CHECK(sh0.Get("bias").Get(2).GetNumberAsDouble() ==
                  doc.at("meshes")[k].at("images")[2].at("bias")[2].get<double>());
            const tinygltf::Material& mat = model.materials[std::size_t(prim.material)];
            if (png) {
                REQUIRE(mat.occlusionTexture.index >= 0);
                const tinygltf::Texture& tex =
                    model.textures[std::size_t(mat.occlusionTexture.index)];
                CHECK(model.images[std::size_t(tex.source)].uri ==
                      scene.meshes[k].name + ".ao.png");
                CHECK(mat.occlusionTexture.texCoord == 0);
            } else {
                CHECK(mat.occlusionTexture.index == -1);
                CHECK(sh0.Get("file").Get<std::string>() == scene.meshes[k].name + ".sh0.exr");
            }
        }
        if (png) {  // Assimp: glTF's occlusion texture is its lightmap texture, on UV set 0
            Assimp::Importer importer;
            const aiScene* as = importer.ReadFile(tmp.path + "/scene.glb", 0);
            REQUIRE(as != nullptr);
            for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
                const aiMaterial* mat = as->mMaterials[as->mMeshes[k]->mMaterialIndex];
                aiString path;
                REQUIRE(mat->GetTexture(aiTextureType_LIGHTMAP, 0, &path) == AI_SUCCESS);
                CHECK(std::string(path.C_Str()) == scene.meshes[k].name + ".ao.png");
            }
        }
    }
}

TEST_CASE("engine export: a probe grid as slices of a 3D texture", "[tool]") {
    render::ProbeGrid g;
    g.lo = {-1, 0, 2};
    g.hi = {3, 1, 5};
    g.counts = {4, 3, 5};
    const std::vector<std::pair<std::string, std::size_t>> cols = {
        {"rad_r_0", 0}, {"rad_g_0", 1}, {"rad_b_0", 2}, {"rad_stderr_0", 3}, {"inside", 4}};
    std::vector<double> rec(g.size() * 5);
    for (std::size_t i = 0; i < g.size(); ++i) {
        const vec3<double> p = g.position(i);
        rec[5 * i] = p.x + 0.1 * p.y;
        rec[5 * i + 1] = p.y * p.z;
        rec[5 * i + 2] = -p.z;
        rec[5 * i + 4] = i % 5 == 0 ? 1 : 0;
    }
    const std::vector<SceneMesh> none;
    for (ImageEncoding e : {ImageEncoding::png16, ImageEncoding::float32}) {
        EngineInput in;
        in.target = EngineTarget::probes;
        in.meshes = &none;
        in.probes = &g;
        in.columns = cols;
        in.records = &rec;
        in.stride = 5;
        in.encoding = e;
        Json outputs = Json::array();
        const std::vector<EngineFile> files = export_engine(in, outputs);
        CHECK(files.size() == 2 * 5 + 1);
        TempDir tmp;
        tmp.write(files);
        std::ifstream jf(tmp.path + "/probes.grid.json");
        const nlohmann::json doc = nlohmann::json::parse(jf);
        CHECK(doc.at("counts") == nlohmann::json::array({4, 3, 5}));
        CHECK(doc.at("spacing")[2].get<double>() == 0.75);
        const nlohmann::json& rad = doc.at("attributes")[0];
        CHECK(rad.at("attribute") == "_RAD0");
        for (int k = 0; k < 5; ++k) {
            std::ifstream f(
                tmp.path + "/" + rad.at("slices")[std::size_t(k)].at("file").get<std::string>(),
                std::ios::binary);
            const std::string bytes((std::istreambuf_iterator<char>(f)),
                                    std::istreambuf_iterator<char>());
            int w = 0, h = 0;
            const std::vector<double> t = decode_t(bytes, e, 3, w, h, tmp.path);
            REQUIRE(w == 4);
            REQUIRE(h == 3);
            for (int j = 0; j < 3; ++j)
                for (int i = 0; i < 4; ++i)
                    for (std::size_t c = 0; c < 3; ++c) {
                        const ChannelRange r{rad.at("scale")[c].get<double>(),
                                             rad.at("bias")[c].get<double>()};
                        const double got = r.bias + r.scale * t[std::size_t(j * 4 + i) * 3 + c];
                        const double want = float(rec[5 * g.index(i, j, k) + c]);
                        REQUIRE(std::fabs(got - want) <= bound(r, e));
                    }
        }
    }
}

TEST_CASE("engine export: CPCA of the transfer vectors, decoded from cpca.bin", "[tool]") {
    // 3 meshes' worth of points: 240 transfer vectors of 9 coefficients near two planes.
    const std::size_t P = 240, n = 9, stride = n + 1;
    std::vector<std::pair<std::string, std::size_t>> cols;
    for (std::size_t k = 0; k < n; ++k) cols.emplace_back("transfer_" + std::to_string(k), k);
    cols.emplace_back("ao", n);
    std::vector<double> rec(P * stride);
    std::mt19937_64 rng(3);
    std::normal_distribution<double> g(0, 1);
    for (std::size_t p = 0; p < P; ++p) {
        const double a = g(rng), b = g(rng), side = p % 2 == 0 ? 1.0 : -2.0;
        for (std::size_t k = 0; k < n; ++k)
            rec[p * stride + k] = side * (1 + 0.1 * double(k)) + a * std::cos(double(k)) +
                                  0.5 * b * std::sin(double(k) * side) + 0.01 * g(rng);
        rec[p * stride + n] = 0.5;
    }
    // Meshes only lend their names and counts here: one mesh of P vertices.
    std::vector<SceneMesh> meshes(1);
    meshes[0].name = "m";
    meshes[0].mesh.positions.assign(3 * P, 0.0f);
    meshes[0].mesh.normals.assign(3 * P, 0.0f);
    for (std::size_t v = 0; v < P; ++v) meshes[0].mesh.normals[3 * v + 2] = 1;
    for (std::uint32_t v = 0; v + 2 < P; v += 3)
        meshes[0].mesh.indices.insert(meshes[0].mesh.indices.end(), {v, v + 1, v + 2});
    const std::vector<std::size_t> begin{0, P};
    EngineInput in =
        engine_input(EngineTarget::vertices, meshes, begin, nullptr, cols, rec, stride);
    const CpcaFit fit = with_cpca(in, 2, 2, 11);
    const compress::MatrixX<double>& x = fit.x;
    const compress::Cpca<double>& model = fit.model;
    Json outputs = Json::array();
    const std::vector<EngineFile> files = export_engine(in, outputs);
    const auto find = [&](const std::string& name) {
        for (const EngineFile& f : files)
            if (f.name == name) return f.bytes;
        FAIL("no " << name);
        return std::string();
    };
    const nlohmann::json doc = nlohmann::json::parse(find("cpca.json"));
    const std::string bin = find("cpca.bin");
    REQUIRE(doc.at("bytes").get<std::size_t>() == bin.size());
    const std::size_t C = doc.at("clusters"), M = doc.at("vectors");
    REQUIRE(C == 2);
    REQUIRE(M == 2);
    REQUIRE(doc.at("coefficients").get<std::size_t>() == n);
    std::map<std::string, std::size_t> at;
    for (const nlohmann::json& s : doc.at("sections")) at[s.at("name")] = s.at("offset");
    auto f32 = [&](std::size_t off) {
        float v;
        std::memcpy(&v, bin.data() + off, 4);
        return double(v);
    };
    const double levels = doc.at("levels");
    // Decoded by the documented layout, against the library's model fitted the same way.
    REQUIRE(x.cols() == Eigen::Index(n));
    const compress::MatrixX<double> want =
        compress::with_weights(model, compress::quantize(model, 8)).reconstruct();
    double sq = 0;
    for (std::size_t p = 0; p < P; ++p) {
        std::uint16_t c = 0;
        std::memcpy(&c, bin.data() + at["cluster"] + 2 * p, 2);
        REQUIRE(c == model.cluster[p]);
        for (std::size_t k = 0; k < n; ++k) {
            double v = f32(at["means"] + 4 * (c * n + k));
            for (std::size_t j = 0; j < M; ++j) {
                const auto code = static_cast<std::int8_t>(bin[at["codes"] + p * M + j]);
                v += double(code) / levels * f32(at["scales"] + 4 * (c * M + j)) *
                     f32(at["basis"] + 4 * ((c * M + j) * n + k));
            }
            REQUIRE(std::fabs(v - want(Eigen::Index(p), Eigen::Index(k))) <= 1e-5);
            sq += (v - x(Eigen::Index(p), Eigen::Index(k))) *
                  (v - x(Eigen::Index(p), Eigen::Index(k)));
        }
    }
    CHECK(sq == Approx(doc.at("squared_error").at("quantized").get<double>()).epsilon(1e-3));
    // Bad values: one line each.
    CHECK_THROWS_WITH(parse_compression_export("cpca:0:2"),
                      Catch::StartsWith("--export: expected pca:M or cpca:C:M"));
    CHECK_THROWS_WITH(parse_compression_export("pca"), Catch::StartsWith("--export: expected"));
    CHECK(parse_compression_export("pca:3").clusters == 1);
    in.columns = {{"ao", n}};
    CHECK_THROWS_WITH(engine_file_names(in),
                      "--export: compresses transfer vectors; give --quantities transfer");
    // The Toksvig table: its row Na.Na = 1 is the plain power (Na.H)^s (the brief's property).
    in.compression = parse_compression_export("toksvig:32");
    in.encoding = ImageEncoding::png16;
    Json out2 = Json::array();
    const std::vector<EngineFile> tf = export_engine(in, out2);
    std::string png;
    for (const EngineFile& f : tf)
        if (f.name == "toksvig.png") png = f.bytes;
    TempDir tmp;
    int w = 0, h = 0;
    const std::vector<double> t = decode_t(png, ImageEncoding::png16, 1, w, h, tmp.path);
    REQUIRE(w == 256);
    REQUIRE(h == 256);
    for (int col : {0, 17, 128, 200, 255})
        CHECK(std::fabs(t[std::size_t(255 * 256 + col)] - std::pow(col / 255.0, 32.0)) <=
              1.0 / 131070 + 1e-7);
    CHECK(std::fabs(t[0] - 1.0 / 33) <= 1.0 / 131070 + 1e-7);  // Na.Na = 0: 1 / (1 + s)
    CHECK_THROWS_WITH(parse_compression_export("toksvig:0"),
                      "--export: expected toksvig:S with 0 < S <= 1e6, got 'toksvig:0'");
}

namespace {
/// The decoded value bias + scale * t of every sample of an image entry of a table export
/// (lxh.json, svd.json), from `files`; width and height as read.
std::vector<double> decode_entry(const std::vector<EngineFile>& files, const nlohmann::json& e,
                                 ImageEncoding enc, std::size_t ch, int& w, int& h,
                                 std::vector<ChannelRange>& ranges) {
    std::string bytes;
    for (const EngineFile& f : files)
        if (f.name == e.at("file").get<std::string>()) bytes = f.bytes;
    REQUIRE(!bytes.empty());
    TempDir tmp;
    std::vector<double> v = decode_t(bytes, enc, ch, w, h, tmp.path);
    ranges.clear();
    for (std::size_t c = 0; c < ch; ++c)
        ranges.push_back({e.at("scale")[c].get<double>(), e.at("bias")[c].get<double>()});
    for (std::size_t i = 0; i < v.size(); ++i)
        v[i] = ranges[i % ch].bias + ranges[i % ch].scale * v[i];
    return v;
}

const EngineFile& find_file(const std::vector<EngineFile>& files, const std::string& name) {
    for (const EngineFile& f : files)
        if (f.name == name) return f;
    FAIL("no " << name);
    return files.front();
}
}  // namespace

TEST_CASE("engine export: the L x H table as cube-map images, against the closed form", "[tool]") {
    // A constant environment of radiance c per channel: L = c sqrt(4 pi) y_00 only, so
    // (L x H)(n) has coefficient 0 = c pi y_00 = c sqrt(pi) / 2 and coefficients 1..3 =
    // c (2 pi / 3) y_1m(n) (Funk-Hecke, a_1 = 2/3), whatever the lighting bands.
    const double c[3] = {1.0, 0.5, 0.25};
    const int K = 2, N = 2, R = 6;
    std::vector<SceneMesh> none;
    const std::vector<std::size_t> begin{0};
    const std::vector<double> rec;
    for (ImageEncoding enc : {ImageEncoding::png16, ImageEncoding::float32}) {
        INFO(image_encoding_name(enc));
        EngineInput in;
        in.target = EngineTarget::vertices;
        in.meshes = &none;
        in.mesh_begin = &begin;
        in.records = &rec;
        in.stride = 1;
        in.encoding = enc;
        in.compression = parse_compression_export("lxh:2:2:6");
        REQUIRE(in.compression.lxh_visibility_bands == K);
        in.lighting.assign(3 * std::size_t(N * N), 0.0);
        for (int ch = 0; ch < 3; ++ch)
            in.lighting[std::size_t(ch)] = c[ch] * std::sqrt(4 * constants::pi);
        Json outputs = Json::array();
        const std::vector<EngineFile> files = export_engine(in, outputs);
        std::vector<std::string> names, declared = engine_file_names(in);
        for (const EngineFile& f : files) names.push_back(f.name);
        std::sort(names.begin(), names.end());
        std::sort(declared.begin(), declared.end());
        CHECK(names == declared);
        const nlohmann::json doc = nlohmann::json::parse(find_file(files, "lxh.json").bytes);
        CHECK(doc.at("face_size") == R);
        REQUIRE(doc.at("images").size() == std::size_t(K * K));
        // The library's table, as the renderer builds it.
        using Param = param::CubeMap<float>;
        const LxhTable<Param> lib = build_lxh_table(Param(R), lxh_matrix(N, in.lighting.data(), K),
                                                    LxhConstruction::symmetric);
        const param::CubeMap<double> dirs(R);
        const double y1 = std::sqrt(3 / (4 * constants::pi));
        for (int k = 0; k < K * K; ++k) {
            int w = 0, h = 0;
            std::vector<ChannelRange> r;
            const std::vector<double> v =
                decode_entry(files, doc.at("images")[std::size_t(k)], enc, 3, w, h, r);
            REQUIRE(w == 6 * R);
            REQUIRE(h == R);
            for (int f = 0; f < 6; ++f)
                for (int row = 0; row < R; ++row)
                    for (int col = 0; col < R; ++col) {
                        const vec3<double> n = dirs.texel_direction(f, col, row);
                        const double ylm[4] = {0.5 / std::sqrt(constants::pi), y1 * n.y, y1 * n.z,
                                               y1 * n.x};
                        for (std::size_t ch = 0; ch < 3; ++ch) {
                            const double got =
                                v[(std::size_t(row) * std::size_t(w) + std::size_t(f * R + col)) *
                                      3 +
                                  ch];
                            const double lib_v =
                                lib.data[(lib.param.texel_index(f, col, row) * 4 + std::size_t(k)) *
                                             3 +
                                         ch];
                            REQUIRE(std::fabs(got - lib_v) <= bound(r[ch], enc));
                            const double closed =
                                c[ch] * constants::pi * (k == 0 ? 1.0 : 2.0 / 3.0) * ylm[k];
                            REQUIRE(std::fabs(got - closed) <= bound(r[ch], enc) + 1e-6);
                        }
                    }
        }
    }
    CHECK_THROWS_WITH(parse_compression_export("lxh:0"),
                      Catch::StartsWith("--export: expected lxh:K[:N[:RES]]"));
    CHECK_THROWS_WITH(parse_compression_export("lxh:3:3:32:1"),
                      Catch::StartsWith("--export: expected lxh:K[:N[:RES]]"));
    CHECK(parse_compression_export("lxh:3").lxh_lighting_bands == 3);
    CHECK(parse_compression_export("lxh:3").lxh_resolution == 32);
}

TEST_CASE("engine export: the SVD normal basis as images, against the clamped cosine's SH",
          "[tool]") {
    // With all 9 functions, sum_k b_k(n) v[j][k] = A_j(n) = pi a_l y_j(n) (V orthogonal): the
    // decoded images and svd.json's V give back the closed form at every texel's normal.
    const int R = 8;
    std::vector<SceneMesh> none;
    const std::vector<std::size_t> begin{0};
    const std::vector<double> rec;
    EngineInput in;
    in.meshes = &none;
    in.mesh_begin = &begin;
    in.records = &rec;
    in.stride = 1;
    in.encoding = ImageEncoding::png16;
    in.compression = parse_compression_export("svd:9:8");
    Json outputs = Json::array();
    const std::vector<EngineFile> files = export_engine(in, outputs);
    const nlohmann::json doc = nlohmann::json::parse(find_file(files, "svd.json").bytes);
    REQUIRE(doc.at("images").size() == 9);
    // Cosine-weighted, unclamped: 4 functions keep 96.29 % (ops/normal_basis.hpp).
    CHECK(doc.at("energy_percent")[3].get<double>() == Approx(96.29).margin(0.01));
    std::vector<std::vector<double>> b;
    std::vector<double> err(9);
    for (std::size_t k = 0; k < 9; ++k) {
        int w = 0, h = 0;
        std::vector<ChannelRange> r;
        b.push_back(decode_entry(files, doc.at("images")[k], in.encoding, 1, w, h, r));
        REQUIRE(w == R);
        REQUIRE(h == R);
        err[k] = bound(r[0], in.encoding);
    }
    double a[3];
    clamped_cosine_factors(3, a);
    int inside = 0;
    for (int row = 0; row < R; ++row)
        for (int col = 0; col < R; ++col) {
            double x = 2 * (col + 0.5) / R - 1, y = 2 * (row + 0.5) / R - 1;
            const double r2 = x * x + y * y;
            if (r2 > 1) {
                x /= std::sqrt(r2);
                y /= std::sqrt(r2);
            } else {
                ++inside;
            }
            const double z = std::sqrt(std::max(0.0, 1 - x * x - y * y));
            double ys[9];
            sh::eval(3, x, y, z, ys);
            for (int j = 0; j < 9; ++j) {
                const int l = j == 0 ? 0 : j < 4 ? 1 : 2;
                double got = 0, tol = 1e-6;
                for (std::size_t k = 0; k < 9; ++k) {
                    const double vjk = doc.at("v")[std::size_t(j)][k].get<double>();
                    got += b[k][std::size_t(row * R + col)] * vjk;
                    tol += std::fabs(vjk) * err[k];
                }
                REQUIRE(std::fabs(got - constants::pi * a[l] * ys[j]) <= tol);
            }
        }
    CHECK(inside == 52);  // the 8 x 8 texels whose centres lie in the unit disk
    CHECK_THROWS_WITH(parse_compression_export("svd:10"),
                      Catch::StartsWith("--export: expected svd:M[:RES]"));
    CHECK_THROWS_WITH(parse_compression_export("svd:4:1"),
                      Catch::StartsWith("--export: expected svd:M[:RES]"));
}

TEST_CASE("engine export: CPCA cluster ids and weights as lightmap-UV textures", "[tool]") {
    const SceneFile scene =
        load_scene(std::string(SPHBASIS_TEST_DATA_DIR) + "/scenes/quad_obj.json");
    const render::SceneDesc desc = scene.scene_desc();
    const int res = 16;
    const std::size_t n = 9, stride = n;
    std::vector<render::LightmapLayout> layouts;
    std::vector<std::size_t> begin{0};
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
        layouts.push_back(render::texel_layout(desc.meshes, k, res));
        begin.push_back(begin.back() + layouts.back().samples.size());
    }
    const std::size_t P = begin.back();
    std::vector<std::pair<std::string, std::size_t>> cols;
    for (std::size_t k = 0; k < n; ++k) cols.emplace_back("transfer_" + std::to_string(k), k);
    std::vector<double> rec(P * stride);
    for (std::size_t k = 0; k < layouts.size(); ++k)
        for (std::size_t i = 0; i < layouts[k].samples.size(); ++i) {
            const vec3<double>& p = layouts[k].samples[i].point.p;
            const double side = p.x > 0 ? 1.0 : -2.0;
            for (std::size_t j = 0; j < n; ++j)
                rec[(begin[k] + i) * stride + j] =
                    side * (1 + 0.1 * double(j)) + p.y * std::cos(double(j)) + 0.3 * p.z;
        }
    EngineInput base =
        engine_input(EngineTarget::texels, scene.meshes, begin, &layouts, cols, rec, stride);
    const CpcaFit fit = with_cpca(base, 3, 2, 5);
    const compress::Cpca<double>& model = fit.model;
    const compress::QuantizedWeights<double> q = compress::quantize(model, 8);
    for (ImageEncoding e : {ImageEncoding::png8, ImageEncoding::half}) {
        INFO(image_encoding_name(e));
        EngineInput in = base;
        in.encoding = e;
        Json outputs = Json::array();
        const std::vector<EngineFile> files = export_engine(in, outputs);
        std::vector<std::string> names, declared = engine_file_names(in);
        for (const EngineFile& f : files) names.push_back(f.name);
        std::sort(names.begin(), names.end());
        std::sort(declared.begin(), declared.end());
        CHECK(names == declared);
        const nlohmann::json doc = nlohmann::json::parse(find_file(files, "cpca.json").bytes);
        const nlohmann::json& tex = doc.at("textures").at("meshes");
        REQUIRE(tex.size() == scene.meshes.size());
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const nlohmann::json& mj = tex[k];
            CHECK(mj.at("cluster").at("bits") == 8);
            const std::string& png = find_file(files, mj.at("cluster").at("file")).bytes;
            int w = 0, h = 0, c = 0;
            unsigned char* ids = stbi_load_from_memory(
                reinterpret_cast<const unsigned char*>(png.data()), int(png.size()), &w, &h, &c, 0);
            REQUIRE(ids != nullptr);
            REQUIRE(c == 1);
            REQUIRE(w == res);
            std::vector<int> id(ids, ids + w * h);
            stbi_image_free(ids);
            std::vector<std::vector<double>> wt(2);
            std::vector<double> err(2);
            for (std::size_t j = 0; j < 2; ++j) {
                std::vector<ChannelRange> r;
                int ww = 0, hh = 0;
                wt[j] = decode_entry(files, mj.at("weights")[j], e, 1, ww, hh, r);
                REQUIRE(ww == res);
                err[j] = bound(r[0], e);
            }
            std::vector<char> covered(std::size_t(w * h), 0);
            for (std::size_t i = 0; i < layouts[k].samples.size(); ++i) {
                const std::size_t p = begin[k] + i;
                const std::size_t t =
                    std::size_t(layouts[k].samples[i].y * w + layouts[k].samples[i].x);
                covered[t] = 1;
                const int cl = model.cluster[p];
                REQUIRE(id[t] == cl);
                for (std::size_t j = 0; j < 2; ++j) {
                    const double want = float(q.codes[p * 2 + j] / double(q.levels()) *
                                              q.scales(Eigen::Index(cl), Eigen::Index(j)));
                    REQUIRE(std::fabs(wt[j][t] - want) <= err[j]);
                }
            }
            // A gutter texel next to a chart copies one covered neighbour: its id and weights.
            for (int y = 0; y < h; ++y)
                for (int xx = 0; xx < w; ++xx) {
                    const std::size_t t = std::size_t(y * w + xx);
                    if (covered[t]) continue;
                    int next = 0, same = 0;
                    for (int d = 0; d < 9; ++d) {
                        const int nx = xx + d % 3 - 1, ny = y + d / 3 - 1;
                        if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                        const std::size_t u = std::size_t(ny * w + nx);
                        if (!covered[u]) continue;
                        ++next;
                        same += id[u] == id[t] && wt[0][u] == wt[0][t] && wt[1][u] == wt[1][t];
                    }
                    if (next > 0) REQUIRE(same > 0);
                }
        }
    }
}

TEST_CASE("engine export: a second UV set as the lightmap set (scene loader, bake, glTF)",
          "[tool]") {
    // A quad whose set 0 spans [0, 1]^2 and whose set 1 (the lightmap set) maps it into
    // [0.25, 0.75] x [0.1, 0.6], written as glTF by the exporter and read by the scene loader
    // through Assimp (a .glb fixture made here: OBJ holds one UV set).
    render::Mesh q;
    q.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    q.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    q.uvs = {0, 0, 1, 0, 1, 1, 0, 1};
    q.indices = {0, 1, 2, 0, 2, 3};
    const std::vector<float> uv1 = {0.25f, 0.1f, 0.75f, 0.1f, 0.75f, 0.6f, 0.25f, 0.6f};
    GltfMesh gm;
    gm.name = "q";
    gm.mesh = &q;
    gm.normals.assign(q.normals.begin(), q.normals.end());
    gm.lightmap_uvs = &uv1;
    TempDir tmp;
    {
        const std::string glb = encode_glb({gm}, Json::object());
        std::ofstream(tmp.path + "/two_uv.glb", std::ios::binary)
            .write(glb.data(), std::streamsize(glb.size()));
    }
    auto scene_with = [&](const std::string& extra) {
        const std::string f = tmp.path + "/scene.json";
        std::ofstream(f) << "{\"meshes\": [{\"name\": \"q\", \"file\": \"two_uv.glb\"" << extra
                         << "}], \"environment\": {\"constant\": [1, 1, 1]}}";
        return load_scene(f);
    };
    const SceneFile scene = scene_with("");
    const SceneMesh& sm = scene.meshes.at(0);
    REQUIRE(sm.mesh.vertex_count() == 4);
    REQUIRE(sm.uvs1.size() == 8);
    CHECK(sm.lightmap_uv == 1);            // the default when the file has a second set
    for (std::size_t v = 0; v < 4; ++v) {  // matched by position (the importer may reorder)
        std::size_t o = 0;
        while (o < 4 && !(q.positions[3 * o] == sm.mesh.positions[3 * v] &&
                          q.positions[3 * o + 1] == sm.mesh.positions[3 * v + 1]))
            ++o;
        REQUIRE(o < 4);
        for (std::size_t c = 0; c < 2; ++c) {
            CHECK(sm.mesh.uvs[2 * v + c] == Approx(q.uvs[2 * o + c]).margin(1e-6));
            CHECK(sm.uvs1[2 * v + c] == Approx(uv1[2 * o + c]).margin(1e-6));
        }
    }
    CHECK(scene.lightmap_desc().meshes[0].uvs == sm.uvs1.data());
    CHECK(scene.scene_desc().meshes[0].uvs == sm.mesh.uvs.data());
    const SceneFile set0 = scene_with(", \"lightmap_uv\": 0");
    CHECK(set0.meshes[0].lightmap_uv == 0);
    CHECK(set0.lightmap_desc().meshes[0].uvs == set0.meshes[0].mesh.uvs.data());
    CHECK_THROWS_WITH(scene_with(", \"lightmap_uv\": 2"),
                      Catch::Contains("expected the UV set 0 or 1 of the mesh file, got 2"));

    // A texel bake's layout on set 1: every sample's texel lies in set 1's rectangle.
    const int res = 32;
    const render::SceneDesc desc = scene.lightmap_desc();
    std::vector<render::LightmapLayout> layouts{render::texel_layout(desc.meshes, 0, res)};
    REQUIRE(!layouts[0].samples.empty());
    for (const render::LightmapSample& s : layouts[0].samples) {
        const double u = (s.x + 0.5) / res, v = 1 - (s.y + 0.5) / res;  // rows from the top
        REQUIRE(u >= 0.25 - 1.0 / res);
        REQUIRE(u <= 0.75 + 1.0 / res);
        REQUIRE(v >= 0.1 - 1.0 / res);
        REQUIRE(v <= 0.6 + 1.0 / res);
    }
    const std::vector<std::size_t> begin{0, layouts[0].samples.size()};
    const std::vector<std::pair<std::string, std::size_t>> cols{{"ao", 0}};
    const std::vector<double> rec(layouts[0].samples.size(), 0.75);
    EngineInput in =
        engine_input(EngineTarget::texels, scene.meshes, begin, &layouts, cols, rec, 1);
    Json outputs = Json::array();
    const std::vector<EngineFile> files = export_engine(in, outputs);
    TempDir out;
    out.write(files);
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    REQUIRE(loader.LoadBinaryFromFile(&model, &err, &warn, out.path + "/scene.glb"));
    const tinygltf::Primitive& prim = model.meshes.at(0).primitives.at(0);
    CHECK(prim.attributes.count("TEXCOORD_0") == 1);
    CHECK(prim.attributes.count("TEXCOORD_1") == 1);
    CHECK(prim.extras.Get("sphbasis_lightmaps").Get("_AO").Get("texCoord").GetNumberAsInt() == 1);
    CHECK(model.materials.at(0).occlusionTexture.texCoord == 1);
    const nlohmann::json lm = nlohmann::json::parse(find_file(files, "lightmaps.json").bytes);
    CHECK(lm.at("meshes")[0].at("texCoord") == 1);
    // Assimp reads the exported TEXCOORD_1 back as channel 1 (v flipped back).
    Assimp::Importer importer;
    const aiScene* as = importer.ReadFile(out.path + "/scene.glb", 0);
    REQUIRE(as != nullptr);
    REQUIRE(as->mMeshes[0]->HasTextureCoords(1));
    for (unsigned v = 0; v < as->mMeshes[0]->mNumVertices; ++v) {
        const aiVector3D& t = as->mMeshes[0]->mTextureCoords[1][v];
        CHECK(t.x >= 0.25f - 1e-6f);
        CHECK(t.x <= 0.75f + 1e-6f);
        CHECK(t.y >= 0.1f - 1e-6f);
        CHECK(t.y <= 0.6f + 1e-6f);
    }
}
