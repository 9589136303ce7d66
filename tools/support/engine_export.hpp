// sphbasis CLI support: bake results in the forms a game engine loads (`sphbasis bake --format
// gltf`, docs/export-format.md): glTF 2.0 meshes with per-vertex results as application-specific
// attributes, lightmaps as 8- or 16-bit PNG or half or float EXR on the mesh's lightmap UV set,
// probe grids as a 3D texture (one image per slice and a JSON of the grid).
//
// Range compression (Ishmukhametov, "Irradiance Normal Mapping", thesis, undated, section 2.2.3
// and Listing 2.1: coefficients stored as v / (2 r) + 1/2 with a global r = 0.75, decoded as
// 2 r t - r in the shader): generalised here to one scale and bias per channel,
//   stored t = (v - bias) / scale in [0, 1],   decoded v' = bias + scale * t,
// with bias = min and scale = max - min of the channel over the whole image (a constant channel:
// scale 0, t = 0, v' = bias exactly), except for quantities of known range, which keep a fixed
// one so that the image is usable as is: ambient occlusion and the inside flag [0, 1] (scale 1,
// bias 0: the AO lightmap is glTF's occlusion texture), bent normals [-1, 1] (scale 2, bias -1:
// the normal-map convention the thesis starts from). The quantisation of t bounds the error:
//   |v' - v| <= scale * q,  q = 1/510 (png8), 1/131070 (png16), 2^-12 (half), 2^-25 (float),
// in exact arithmetic (t rounded to the nearest code; half and float: t <= 1 rounded to the
// nearest representable number); a shader decoding in float adds its own rounding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <sphbasis/render/lightmap.hpp>
#include <sphbasis/render/probe_grid.hpp>
#include <string>
#include <utility>
#include <vector>

#include "json.hpp"
#include "scene_file.hpp"

namespace sphbasis::cli {

/// How lightmap and probe images are stored (`--encoding`).
enum class ImageEncoding { png8, png16, half, float32 };

/// "png8", "png16", "half" or "float"; UsageError "--encoding: expected png8, png16, half or
/// float, got 'x'" otherwise.
ImageEncoding parse_image_encoding(const std::string& s);
const char* image_encoding_name(ImageEncoding e) noexcept;
/// q of the file comment: the largest |t' - t| of a stored t in [0, 1].
double quantization_step(ImageEncoding e) noexcept;

/// One channel's range compression: v = bias + scale * t.
struct ChannelRange {
    double scale = 1, bias = 0;
};

/// The range of channel c of `values` (interleaved, `channels` per element): bias = min,
/// scale = max - min. Non-finite values are an error (std::invalid_argument).
ChannelRange fit_range(const std::vector<float>& values, std::size_t channels, std::size_t c);
/// t = (v - bias) / scale clamped to [0, 1] (0 when scale is 0).
double compress(double v, const ChannelRange& r) noexcept;

/// A width x height image of `channels` (1 or 3) interleaved channels, range-compressed per
/// channel and encoded as a PNG (grey or RGB, 8 or 16 bits) or an OpenEXR (half or float,
/// channels "Y" or "R", "G", "B"); rows from the top.
std::string encode_compressed(const std::vector<float>& values, int width, int height,
                              std::size_t channels, const std::vector<ChannelRange>& ranges,
                              ImageEncoding e);

/// A 16-bit PNG (grey or RGB: `channels` 1 or 3) of width x height samples, rows from the top,
/// big-endian as PNG stores them, zlib-compressed, no filter. Throws std::invalid_argument on a
/// size mismatch.
std::string encode_png16(const std::vector<std::uint16_t>& samples, int width, int height,
                         int channels);

/// A quantity of the bake as an engine attribute: "_AO", "_BENT", "_VIS<i>", "_PRT<i>",
/// "_SH<i>" (irradiance in SH; other bases "_HBASIS<i>", "_HBASIS_MOD<i>", ...), "_RAD<i>",
/// "_INSIDE"; its 1 or 3 components' offsets in a bake record and their names there; and a
/// fixed range where the quantity has one.
struct EngineAttribute {
    std::string name;
    std::vector<std::size_t> offsets;
    std::vector<std::string> channels;
    bool fixed = false;
    ChannelRange range;  // when fixed
};

/// The attributes of a bake's channels (name and offset in a record, as the PLY properties of
/// support/ply.hpp: ao, bent_x, vis_<i>, transfer_<i> or transfer_r_<i>, irr_r_<i>, rad_r_<i>,
/// inside; the standard errors are left out). `basis`: the irradiance basis.
std::vector<EngineAttribute> engine_attributes(
    const std::vector<std::pair<std::string, std::size_t>>& columns, const std::string& basis);

enum class EngineTarget { vertices, texels, probes };

/// `--export cpca:C:M` (or `pca:M` = cpca:1:M): the baked transfer vectors compressed by CPCA
/// (ops/compression.hpp: k-means, per-cluster PCA, reclassification; Sloan, Lehtinen and Kautz,
/// "Precomputed Radiance Transfer: Theory and Practice", SIGGRAPH 2005 course) with 8-bit
/// weights, written as cpca.json (the layout) and cpca.bin (docs/export-format.md); a texel bake
/// also as images on the lightmap UV set: <mesh>.cpca_cluster.png (ids, 8- or 16-bit) and
/// <mesh>.cpca_w<j>.<ext> (the weights, range-compressed).
/// `--export toksvig:S`: Toksvig's 2D specular table for shininess S (shading/toksvig.hpp:
/// eq. 9, 256 x 256, Na.H along columns, Na.Na along rows) as toksvig.json and an image.
/// `--export lxh:K[:N[:RES]]`: the L x H table of the scene's distant lighting (ops/
/// lxh_table.hpp; Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed
/// Visibility", JGT 2009, sec. 3) for visibility of K bands, lighting of N bands (default K), over
/// a cube map of RES texels a face edge (default 32), as the renderer's lxh-unc* builds it: K^2
/// RGB images lxh.k<k>.<ext> (the six faces side by side) and lxh.json.
/// `--export svd:M[:RES]`: the first M SVD normal-basis functions (ops/normal_basis.hpp; Sloan,
/// Lehtinen and Kautz 2005, normal mapping for PRT; 3 bands, unclamped, cosine-weighted as the
/// renderer's prt-normalmap-svd*) over the tangent-space normal's (x, y), RES x RES (default 64):
/// grey images svd.b<k>.<ext> and svd.json.
struct CompressionExport {
    int clusters = 0;  // 0: none
    int vectors = 0;
    int bits = 8;
    double toksvig_shininess = 0;  // 0: none
    int lxh_visibility_bands = 0;  // 0: none
    int lxh_lighting_bands = 0;
    int lxh_resolution = 32;
    int svd_vectors = 0;  // 0: none
    int svd_resolution = 64;
    bool any() const noexcept {
        return clusters > 0 || toksvig_shininess > 0 || lxh_visibility_bands > 0 || svd_vectors > 0;
    }
};

/// A comma-separated list of "pca:M" or "cpca:C:M" (1 <= C <= 65535, 1 <= M <= 64),
/// "toksvig:S" (0 < S <= 1e6), "lxh:K[:N[:RES]]" (1 <= K, N <= 16, 1 <= RES <= 1024) and
/// "svd:M[:RES]" (1 <= M <= 9, 2 <= RES <= 4096), or "" (none); UsageError "--export: expected
/// ..." otherwise.
CompressionExport parse_compression_export(const std::string& s);

/// The SH of the scene's distant lighting on `bands` bands, interleaved (coefficient i, channel c
/// at [3 i + c]): the environment's plus every light's seen from the centre of the meshes'
/// bounding box, not rotated (as the renderer's representations project it).
std::vector<double> distant_lighting_sh(const SceneFile& scene, int bands);

/// Everything an engine export reads. Pointers are borrowed for the call.
struct EngineInput {
    EngineTarget target = EngineTarget::vertices;
    const std::vector<SceneMesh>* meshes = nullptr;
    const render::ProbeGrid* probes = nullptr;                     // probes
    const std::vector<std::size_t>* mesh_begin = nullptr;          // vertices, texels: meshes + 1
    const std::vector<render::LightmapLayout>* layouts = nullptr;  // texels
    std::vector<std::pair<std::string, std::size_t>> columns;      // channel name, record offset
    const std::vector<double>* records = nullptr;
    std::size_t stride = 0;  // doubles per record
    std::string basis = "sh";
    ImageEncoding encoding = ImageEncoding::png8;
    CompressionExport compression;
    std::uint64_t seed = 1;        // k-means++ seeding of the CPCA
    std::vector<double> lighting;  // lxh: distant_lighting_sh() on the lxh lighting bands
};

struct EngineFile {
    std::string name;  // relative to the output directory
    std::string bytes;
};

/// The file names export_engine() writes for `in` (records not needed): declared before the
/// bake. vertices: scene.glb; texels: scene.glb, <mesh>.<attr>.<png|exr> per mesh and
/// attribute, lightmaps.json; probes: probes.<attr>.z<k>.<png|exr> per attribute and slice,
/// probes.grid.json; with a compression export also cpca.json and cpca.bin (UsageError when the
/// bake has no transfer or the target is probes); lxh.json and lxh.k<k>.<ext>, svd.json and
/// svd.b<k>.<ext> with those exports.
std::vector<std::string> engine_file_names(const EngineInput& in);

/// The files and the "outputs" entries of bake.json. Throws std::invalid_argument when the
/// input's sizes disagree.
std::vector<EngineFile> export_engine(const EngineInput& in, Json& outputs);

}  // namespace sphbasis::cli
