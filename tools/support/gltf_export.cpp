// sphbasis CLI support: encode_glb (see gltf_export.hpp). The one translation unit that compiles
// tinygltf's implementation (its image decoding and encoding are left out: the images are files
// this tool encodes itself; tests read them back with stb_image and OpenEXR).
#include "gltf_export.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <sstream>
#include <stdexcept>

#define TINYGLTF_IMPLEMENTATION
#include "gltf.hpp"

namespace sphbasis::cli {

namespace {

tinygltf::Value to_value(const Json& j) {
    if (j.is_object()) {
        tinygltf::Value::Object o;
        for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_value(it.value());
        return tinygltf::Value(std::move(o));
    }
    if (j.is_array()) {
        tinygltf::Value::Array a;
        for (const Json& x : j) a.push_back(to_value(x));
        return tinygltf::Value(std::move(a));
    }
    if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
    if (j.is_number_integer() && j.get<long long>() >= std::numeric_limits<int>::min() &&
        j.get<long long>() <= std::numeric_limits<int>::max())
        return tinygltf::Value(j.get<int>());
    if (j.is_number()) return tinygltf::Value(j.get<double>());
    if (j.is_string()) return tinygltf::Value(j.get<std::string>());
    return tinygltf::Value();
}

/// Appends `bytes` to buffer 0 at a 4-byte boundary as a new buffer view; returns its index.
int add_view(tinygltf::Model& m, const void* bytes, std::size_t size, int target) {
    std::vector<unsigned char>& b = m.buffers[0].data;
    while (b.size() % 4 != 0) b.push_back(0);
    tinygltf::BufferView v;
    v.buffer = 0;
    v.byteOffset = b.size();
    v.byteLength = size;
    v.target = target;
    const auto* p = static_cast<const unsigned char*>(bytes);
    b.insert(b.end(), p, p + size);
    m.bufferViews.push_back(v);
    return static_cast<int>(m.bufferViews.size() - 1);
}

int add_float_accessor(tinygltf::Model& m, const std::vector<float>& values, int components,
                       bool bounds) {
    const std::size_t count = values.size() / std::size_t(components);
    tinygltf::Accessor a;
    a.bufferView =
        add_view(m, values.data(), values.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
    a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    a.count = count;
    a.type = components == 1   ? TINYGLTF_TYPE_SCALAR
             : components == 2 ? TINYGLTF_TYPE_VEC2
                               : TINYGLTF_TYPE_VEC3;
    if (bounds) {  // POSITION needs min and max
        a.minValues.assign(std::size_t(components), std::numeric_limits<double>::infinity());
        a.maxValues.assign(std::size_t(components), -std::numeric_limits<double>::infinity());
        for (std::size_t i = 0; i < values.size(); ++i) {
            const std::size_t c = i % std::size_t(components);
            a.minValues[c] = std::min(a.minValues[c], double(values[i]));
            a.maxValues[c] = std::max(a.maxValues[c], double(values[i]));
        }
    }
    m.accessors.push_back(a);
    return static_cast<int>(m.accessors.size() - 1);
}

}  // namespace

std::string encode_glb(const std::vector<GltfMesh>& meshes, const Json& asset_extras) {
    tinygltf::Model m;
    m.asset.version = "2.0";
    m.asset.generator = "sphbasis bake";
    m.asset.extras = to_value(asset_extras);
    m.buffers.emplace_back();
    m.scenes.emplace_back();
    m.defaultScene = 0;
    tinygltf::Sampler lin;
    lin.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    lin.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    lin.wrapS = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    lin.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    bool sampler = false;
    for (const GltfMesh& gm : meshes) {
        const render::Mesh& mesh = *gm.mesh;
        const std::size_t nv = mesh.vertex_count();
        const std::string fn = "sphbasis::cli::encode_glb(): mesh '" + gm.name + "': ";
        if (gm.normals.size() != 3 * nv)
            throw std::invalid_argument(fn + "expected 3 normal components per vertex");
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.attributes["POSITION"] = add_float_accessor(m, mesh.positions, 3, true);
        prim.attributes["NORMAL"] = add_float_accessor(
            m, std::vector<float>(gm.normals.begin(), gm.normals.end()), 3, false);
        int set = 0;  // the lightmaps' texCoord
        for (const std::vector<float>* uvs : {&mesh.uvs, gm.lightmap_uvs}) {
            if (uvs == nullptr || uvs->size() != 2 * nv) continue;
            if (uvs == gm.lightmap_uvs && mesh.uvs.size() != 2 * nv)
                throw std::invalid_argument(fn + "a second UV set needs a first");
            std::vector<float> uv(*uvs);
            for (std::size_t i = 1; i < uv.size(); i += 2) uv[i] = 1.0f - uv[i];
            set = uvs == gm.lightmap_uvs ? 1 : 0;
            prim.attributes["TEXCOORD_" + std::to_string(set)] =
                add_float_accessor(m, uv, 2, false);
        }
        for (const GltfAttribute& a : gm.attributes) {
            if (a.name.empty() || a.name[0] != '_' || (a.components != 1 && a.components != 3) ||
                a.values.size() != nv * std::size_t(a.components))
                throw std::invalid_argument(fn + "attribute '" + a.name +
                                            "': expected a name starting with '_' and 1 or 3 "
                                            "floats per vertex");
            prim.attributes[a.name] = add_float_accessor(m, a.values, a.components, false);
        }
        {
            tinygltf::Accessor idx;
            idx.bufferView =
                add_view(m, mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                         TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            idx.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
            idx.count = mesh.indices.size();
            idx.type = TINYGLTF_TYPE_SCALAR;
            m.accessors.push_back(idx);
            prim.indices = static_cast<int>(m.accessors.size() - 1);
        }
        tinygltf::Material mat;
        mat.name = gm.name;
        mat.doubleSided = true;
        Json lightmaps = Json::object();
        for (const GltfLightmap& lm : gm.lightmaps) {
            Json e = lm.extras;
            e["file"] = lm.uri;
            e["texCoord"] = set;
            e["texture"] = -1;
            if (lm.png) {
                if (!sampler) {
                    m.samplers.push_back(lin);
                    sampler = true;
                }
                tinygltf::Image img;
                img.uri = lm.uri;
                img.mimeType = "image/png";
                img.name = lm.uri;
                m.images.push_back(img);
                tinygltf::Texture tex;
                tex.sampler = 0;
                tex.source = static_cast<int>(m.images.size() - 1);
                tex.name = lm.uri;
                m.textures.push_back(tex);
                const int t = static_cast<int>(m.textures.size() - 1);
                e["texture"] = t;
                if (lm.attribute == "_AO") {
                    mat.occlusionTexture.index = t;
                    mat.occlusionTexture.texCoord = set;
                    mat.occlusionTexture.strength = 1.0;
                }
            }
            lightmaps[lm.attribute] = e;
        }
        m.materials.push_back(mat);
        prim.material = static_cast<int>(m.materials.size() - 1);
        if (!lightmaps.empty()) prim.extras = to_value(Json{{"sphbasis_lightmaps", lightmaps}});
        tinygltf::Mesh gmesh;
        gmesh.name = gm.name;
        gmesh.primitives.push_back(prim);
        m.meshes.push_back(gmesh);
        tinygltf::Node node;
        node.name = gm.name;
        node.mesh = static_cast<int>(m.meshes.size() - 1);
        m.nodes.push_back(node);
        m.scenes[0].nodes.push_back(static_cast<int>(m.nodes.size() - 1));
    }
    tinygltf::TinyGLTF writer;
    writer.SetImageWriter(nullptr, nullptr);  // images are URIs of files written beside
    std::ostringstream os;
    if (!writer.WriteGltfSceneToStream(&m, os, false, true))
        throw std::runtime_error("cannot encode the glTF file (tinygltf failed)");
    return os.str();
}

}  // namespace sphbasis::cli
