// sphbasis CLI support: engine exports of a bake (see engine_export.hpp).
#include "engine_export.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <map>
#include <sphbasis/ops/compression.hpp>
#include <sphbasis/ops/lxh_table.hpp>
#include <sphbasis/ops/normal_basis.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/render/bake_file.hpp>
#include <sphbasis/render/bake_points.hpp>
#include <sphbasis/render/lighting.hpp>
#include <sphbasis/shading/toksvig.hpp>
#include <stdexcept>
#include <type_traits>

#include "args.hpp"
#include "exr.hpp"
#include "gltf_export.hpp"
#include "png.hpp"

namespace sphbasis::cli {

ImageEncoding parse_image_encoding(const std::string& s) {
    if (s == "png8") return ImageEncoding::png8;
    if (s == "png16") return ImageEncoding::png16;
    if (s == "half") return ImageEncoding::half;
    if (s == "float") return ImageEncoding::float32;
    throw UsageError("--encoding: expected png8, png16, half or float, got '" + quote_input(s) +
                     "'");
}

const char* image_encoding_name(ImageEncoding e) noexcept {
    switch (e) {
        case ImageEncoding::png8:
            return "png8";
        case ImageEncoding::png16:
            return "png16";
        case ImageEncoding::half:
            return "half";
        case ImageEncoding::float32:
            return "float";
    }
    return "";
}

double quantization_step(ImageEncoding e) noexcept {
    switch (e) {
        case ImageEncoding::png8:
            return 1.0 / 510.0;
        case ImageEncoding::png16:
            return 1.0 / 131070.0;
        case ImageEncoding::half:
            return std::ldexp(1.0, -12);
        case ImageEncoding::float32:
            return std::ldexp(1.0, -25);
    }
    return 0;
}

ChannelRange fit_range(const std::vector<float>& values, std::size_t channels, std::size_t c) {
    if (channels == 0 || c >= channels || values.size() % channels != 0 || values.empty())
        throw std::invalid_argument(
            "sphbasis::cli::fit_range(): expected a channel of a non-empty "
            "interleaved image");
    double lo = values[c], hi = values[c];
    for (std::size_t i = c; i < values.size(); i += channels) {
        if (!std::isfinite(values[i]))
            throw std::invalid_argument("sphbasis::cli::fit_range(): expected finite values");
        lo = std::min(lo, double(values[i]));
        hi = std::max(hi, double(values[i]));
    }
    return {hi - lo, lo};
}

double compress(double v, const ChannelRange& r) noexcept {
    if (!(r.scale > 0)) return 0;
    return std::clamp((v - r.bias) / r.scale, 0.0, 1.0);
}

namespace {

/// t in [0, 1] rounded to the nearest half-precision number (binary16: 10 fraction bits,
/// normal down to 2^-14, subnormal spacing 2^-24), computed in double so that the one rounding
/// is to half (OpenEXR's float-to-half conversion of the result is then exact).
double round_to_half(double t) {
    if (t <= 0) return 0;
    const int e = std::max(std::ilogb(t), -14);
    const double step = std::ldexp(1.0, e - 10);
    return std::nearbyint(t / step) * step;
}

void put_u32(std::string& s, std::uint32_t v) {
    for (int k = 3; k >= 0; --k) s.push_back(static_cast<char>((v >> (8 * k)) & 0xFF));
}

void put_chunk(std::string& out, const char* type, const std::string& data) {
    put_u32(out, static_cast<std::uint32_t>(data.size()));
    std::string body(type, 4);
    body += data;
    out += body;
    put_u32(out, static_cast<std::uint32_t>(
                     crc32(0L, reinterpret_cast<const Bytef*>(body.data()), uInt(body.size()))));
}

std::string lower_name(const std::string& attr) {
    std::string s = attr.substr(attr.size() > 0 && attr[0] == '_' ? 1 : 0);
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

std::string upper_name(const std::string& s) {
    std::string r;
    for (char c : s)
        r.push_back(c == '-' ? '_'
                             : static_cast<char>(std::toupper(static_cast<unsigned char>(c))));
    return r;
}

const char* extension(ImageEncoding e) {
    return e == ImageEncoding::png8 || e == ImageEncoding::png16 ? ".png" : ".exr";
}

std::string hex64(std::uint64_t v) {
    char buf[17];
    std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
    return buf;
}

/// The ranges of an image's channels: the attribute's fixed one, or each channel's [min, max].
std::vector<ChannelRange> ranges_of(const EngineAttribute& a, const std::vector<float>& img) {
    std::vector<ChannelRange> r;
    for (std::size_t c = 0; c < a.offsets.size(); ++c)
        r.push_back(a.fixed ? a.range : fit_range(img, a.offsets.size(), c));
    return r;
}

/// The decoding of an image as JSON: channels, scale, bias and the error bound per channel.
Json range_json(const EngineAttribute& a, const std::vector<ChannelRange>& r, ImageEncoding e) {
    Json scale = Json::array(), bias = Json::array(), err = Json::array();
    for (const ChannelRange& x : r) {
        scale.push_back(x.scale);
        bias.push_back(x.bias);
        err.push_back(x.scale * quantization_step(e));
    }
    return {{"attribute", a.name},
            {"channels", a.channels},
            {"scale", scale},
            {"bias", bias},
            {"max_error", err}};
}

std::vector<float> gather(const EngineInput& in, const EngineAttribute& a, std::size_t first,
                          std::size_t count) {
    std::vector<float> v;
    v.reserve(count * a.offsets.size());
    for (std::size_t i = 0; i < count; ++i)
        for (std::size_t off : a.offsets)
            v.push_back(static_cast<float>((*in.records)[(first + i) * in.stride + off]));
    return v;
}

/// Appends a file to `files`; its name and XXH3-64 as JSON.
Json add_file(std::vector<EngineFile>& files, const std::string& name, std::string bytes) {
    const std::string hash = hex64(render::InputHash().str(bytes).value());
    files.push_back({name, std::move(bytes)});
    return {{"file", name}, {"xxh3", hash}};
}

/// An image of the table exports: its channels fitted per channel, encoded, added; its JSON
/// entry (attribute, channels, scale, bias, max_error, file, xxh3).
Json add_table_image(std::vector<EngineFile>& files, const std::string& file,
                     const EngineAttribute& a, const std::vector<float>& img, int w, int h,
                     ImageEncoding e) {
    const std::size_t ch = a.channels.size();
    std::vector<ChannelRange> r;
    for (std::size_t c = 0; c < ch; ++c) r.push_back(fit_range(img, ch, c));
    Json j = range_json(a, r, e);
    j.update(add_file(files, file, encode_compressed(img, w, h, ch, r, e)));
    return j;
}

void check_input(const EngineInput& in, bool need_records) {
    const char* fn = "sphbasis::cli::export_engine(): ";
    if (in.meshes == nullptr) throw std::invalid_argument(std::string(fn) + "expected meshes");
    if (in.target == EngineTarget::probes && in.probes == nullptr)
        throw std::invalid_argument(std::string(fn) + "expected a probe grid");
    if (in.target == EngineTarget::texels &&
        (in.layouts == nullptr || in.layouts->size() != in.meshes->size()))
        throw std::invalid_argument(std::string(fn) + "expected one lightmap layout per mesh");
    if (!need_records) return;
    std::size_t points = 0;
    if (in.target == EngineTarget::probes) {
        points = in.probes->size();
    } else {
        if (in.mesh_begin == nullptr || in.mesh_begin->size() != in.meshes->size() + 1)
            throw std::invalid_argument(std::string(fn) + "expected meshes + 1 mesh offsets");
        points = in.mesh_begin->back();
    }
    if (in.records == nullptr || in.stride == 0 || in.records->size() != points * in.stride)
        throw std::invalid_argument(std::string(fn) + "expected one record per point");
    for (const auto& c : in.columns)
        if (c.second >= in.stride)
            throw std::invalid_argument(std::string(fn) + "column '" + c.first +
                                        "' outside the record");
}

template <class T>
void append_le(std::string& out, T v) {
    static_assert(std::is_arithmetic_v<T>, "append_le: a number");
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    out.append(reinterpret_cast<const char*>(b), sizeof(T));  // x86-64 and ARM: little-endian
}

/// A texel bake's CPCA as images on the lightmap UV set (docs/export-format.md): per mesh the
/// cluster ids (8-bit grey PNG for at most 256 clusters, else 16-bit) and one grey image per
/// weight, the dequantized weights range-compressed. Gutters: lightmap_gutter rings, each
/// texel copying id and weights of its first covered neighbour (ids cannot be averaged); 0
/// farther away. Returns the "textures" entry of cpca.json.
Json export_cpca_textures(const EngineInput& in, const compress::QuantizedWeights<double>& q,
                          std::vector<EngineFile>& files) {
    const std::size_t M = std::size_t(q.vectors);
    const double levels = q.levels();
    Json meshes = Json::array();
    for (std::size_t k = 0; k < in.meshes->size(); ++k) {
        const render::LightmapLayout& lay = (*in.layouts)[k];
        const std::size_t first = (*in.mesh_begin)[k], w = std::size_t(lay.width),
                          n = w * std::size_t(lay.height);
        std::vector<int> id(n, -1);
        std::vector<float> wt(n * M, 0.f);
        for (std::size_t i = 0; i < lay.samples.size(); ++i) {
            const std::size_t t = std::size_t(lay.samples[i].y) * w + std::size_t(lay.samples[i].x),
                              p = first + i;
            const int c = q.cluster[p];
            id[t] = c;
            for (std::size_t j = 0; j < M; ++j)
                wt[t * M + j] = static_cast<float>(q.codes[p * M + j] / levels *
                                                   q.scales(Eigen::Index(c), Eigen::Index(j)));
        }
        for (int ring = 0; ring < render::lightmap_gutter; ++ring) {
            std::vector<int> from(n, -1);
            for (std::size_t t = 0; t < n; ++t) {
                if (id[t] >= 0) continue;
                const long x = long(t % w), y = long(t / w);
                for (int d = 0; d < 9 && from[t] < 0; ++d) {
                    const long nx = x + d % 3 - 1, ny = y + d / 3 - 1;
                    if (nx < 0 || ny < 0 || nx >= long(w) || ny >= long(lay.height)) continue;
                    const std::size_t u = std::size_t(ny) * w + std::size_t(nx);
                    if (id[u] >= 0) from[t] = int(u);
                }
            }
            for (std::size_t t = 0; t < n; ++t)
                if (from[t] >= 0) {
                    id[t] = id[std::size_t(from[t])];
                    std::copy_n(wt.begin() + std::ptrdiff_t(std::size_t(from[t]) * M), M,
                                wt.begin() + std::ptrdiff_t(t * M));
                }
        }
        const SceneMesh& sm = (*in.meshes)[k];
        const bool wide = q.scales.rows() > 256;
        std::string png;
        if (wide) {
            std::vector<std::uint16_t> px(n);
            for (std::size_t t = 0; t < n; ++t)
                px[t] = static_cast<std::uint16_t>(std::max(id[t], 0));
            png = encode_png16(px, lay.width, lay.height, 1);
        } else {
            std::vector<std::uint8_t> px(n);
            for (std::size_t t = 0; t < n; ++t)
                px[t] = static_cast<std::uint8_t>(std::max(id[t], 0));
            png = encode_png(px, lay.width, lay.height, 1);
        }
        Json cluster = add_file(files, sm.name + ".cpca_cluster.png", std::move(png));
        cluster["bits"] = wide ? 16 : 8;
        Json weights = Json::array();
        for (std::size_t j = 0; j < M; ++j) {
            std::vector<float> img(n);
            for (std::size_t t = 0; t < n; ++t) img[t] = wt[t * M + j];
            const std::string i = std::to_string(j);
            const EngineAttribute a{"_CPCA_W" + i, {}, {"weight_" + i}, false, {}};
            weights.push_back(add_table_image(files,
                                              sm.name + ".cpca_w" + i + extension(in.encoding), a,
                                              img, lay.width, lay.height, in.encoding));
        }
        meshes.push_back({{"mesh", sm.name},
                          {"width", lay.width},
                          {"height", lay.height},
                          {"cluster", cluster},
                          {"weights", weights}});
    }
    return {{"uv_set", "the lightmaps' (lightmaps.json)"},
            {"encoding", image_encoding_name(in.encoding)},
            {"decode",
             "c = the cluster image's integer texel (nearest filtering); w_j = bias + scale * t "
             "of weight image j; x = means[c] + sum_j w_j basis[c][j]"},
            {"meshes", meshes}};
}

/// cpca.json and cpca.bin (see docs/export-format.md).
void export_cpca(const EngineInput& in, const std::vector<EngineAttribute>& attrs,
                 std::vector<EngineFile>& files, Json& outputs) {
    std::vector<const EngineAttribute*> prt;
    for (const EngineAttribute& a : attrs)
        if (a.name.rfind("_PRT", 0) == 0) prt.push_back(&a);
    if (prt.empty())
        throw UsageError("--export: compresses transfer vectors; give --quantities transfer");
    const std::size_t comps = prt[0]->offsets.size(), n = prt.size() * comps;
    const std::size_t points = in.records->size() / in.stride;
    Json columns = Json::array();
    for (const EngineAttribute* a : prt)
        for (const std::string& c : a->channels) columns.push_back(c);
    compress::MatrixX<double> x(static_cast<Eigen::Index>(points), static_cast<Eigen::Index>(n));
    for (std::size_t p = 0; p < points; ++p)
        for (std::size_t i = 0; i < prt.size(); ++i)
            for (std::size_t c = 0; c < comps; ++c)
                x(Eigen::Index(p), Eigen::Index(i * comps + c)) =
                    (*in.records)[p * in.stride + prt[i]->offsets[c]];
    compress::CpcaSettings cs;
    cs.clusters = in.compression.clusters;
    cs.vectors = in.compression.vectors;
    cs.seed = in.seed;
    compress::Cpca<double> model;
    try {
        model = compress::cpca_iterative(x, cs);
    } catch (const std::invalid_argument& e) {
        throw UsageError(std::string("--export: ") + e.what());
    }
    const compress::QuantizedWeights<double> q = compress::quantize(model, in.compression.bits);
    const std::size_t C = std::size_t(model.clusters()), M = std::size_t(model.vectors());
    std::string bin;
    for (std::size_t c = 0; c < C; ++c)
        for (std::size_t k = 0; k < n; ++k)
            append_le(bin, static_cast<float>(model.means(Eigen::Index(c), Eigen::Index(k))));
    for (std::size_t c = 0; c < C; ++c)
        for (std::size_t j = 0; j < M; ++j)
            for (std::size_t k = 0; k < n; ++k)
                append_le(bin,
                          static_cast<float>(model.bases[c](Eigen::Index(k), Eigen::Index(j))));
    for (std::size_t c = 0; c < C; ++c)
        for (std::size_t j = 0; j < M; ++j)
            append_le(bin, static_cast<float>(q.scales(Eigen::Index(c), Eigen::Index(j))));
    for (int c : model.cluster) append_le(bin, static_cast<std::uint16_t>(c));
    for (std::int16_t code : q.codes) append_le(bin, static_cast<std::int8_t>(code));
    Json texels = nullptr;
    if (in.target == EngineTarget::texels) {
        // Where each point lies: (mesh, x, y) of its texel, u16 each.
        for (std::size_t k = 0; k < in.layouts->size(); ++k)
            for (const render::LightmapSample& s : (*in.layouts)[k].samples) {
                append_le(bin, static_cast<std::uint16_t>(k));
                append_le(bin, static_cast<std::uint16_t>(s.x));
                append_le(bin, static_cast<std::uint16_t>(s.y));
            }
        texels = {{"type", "uint16"}, {"shape", {points, 3}}};
    }
    const Json textures =
        in.target == EngineTarget::texels ? export_cpca_textures(in, q, files) : Json();
    const double err = compress::squared_error(x, model.reconstruct());
    const double qerr = compress::squared_error(x, compress::with_weights(model, q).reconstruct());
    std::size_t off = 0;
    auto section = [&](const char* name, const char* type, std::size_t bytes, Json shape) {
        Json s = {{"name", name}, {"type", type}, {"offset", off}, {"shape", shape}};
        off += bytes;
        return s;
    };
    Json sections = Json::array();
    sections.push_back(section("means", "float32", 4 * C * n, {C, n}));
    sections.push_back(section("basis", "float32", 4 * C * M * n, {C, M, n}));
    sections.push_back(section("scales", "float32", 4 * C * M, {C, M}));
    sections.push_back(section("cluster", "uint16", 2 * points, {points}));
    sections.push_back(section("codes", "int8", points * M, {points, M}));
    if (!texels.is_null()) sections.push_back(section("texel", "uint16", 6 * points, {points, 3}));
    const std::string hash = hex64(render::InputHash().str(bin).value());
    Json doc = {{"format", "sphbasis cpca"},
                {"version", 1},
                {"clusters", C},
                {"vectors", M},
                {"coefficients", n},
                {"points", points},
                {"bits", in.compression.bits},
                {"levels", q.levels()},
                {"columns", columns},
                {"points_order", in.target == EngineTarget::vertices
                                     ? "global vertex index (meshes in scene order)"
                                     : "texel samples, meshes in scene order (section texel)"},
                {"decode",
                 "x[p] = means[c] + sum_j codes[p][j] / levels * scales[c][j] * basis[c][j], c = "
                 "cluster[p]; shading with light L: x[p] . L"},
                {"squared_error", {{"model", err}, {"quantized", qerr}}},
                {"file", "cpca.bin"},
                {"bytes", bin.size()},
                {"xxh3", hash},
                {"sections", sections}};
    if (!textures.is_null()) doc["textures"] = textures;
    files.push_back({"cpca.json", dump_json(doc, {{"sections", 2}, {"meshes", 3}}) + "\n"});
    files.push_back({"cpca.bin", std::move(bin)});
    outputs.push_back({{"file", "cpca.json"},
                       {"kind", "cpca"},
                       {"clusters", C},
                       {"vectors", M},
                       {"squared_error", qerr}});
}

/// lxh.json and lxh.k<k>.<ext> (docs/export-format.md).
void export_lxh(const EngineInput& in, std::vector<EngineFile>& files, Json& outputs) {
    const int K = in.compression.lxh_visibility_bands, N = in.compression.lxh_lighting_bands,
              R = in.compression.lxh_resolution;
    if (in.lighting.size() != 3 * std::size_t(N) * std::size_t(N))
        throw std::invalid_argument(
            "sphbasis::cli::export_engine(): expected 3 N^2 lighting coefficients for lxh");
    // The renderer's table (render/representations/lxh.hpp): a float cube map, seamless
    // filtering, the symmetric construction, exact H (C = N + K - 1).
    using Param = param::CubeMap<float>;
    const LxhTable<Param> t =
        build_lxh_table(Param(R), lxh_matrix(N, in.lighting.data(), K), LxhConstruction::symmetric);
    const char* ext = extension(in.encoding);
    const std::size_t kk = std::size_t(K) * std::size_t(K), w = 6 * std::size_t(R);
    Json images = Json::array();
    for (std::size_t k = 0; k < kk; ++k) {
        const std::string i = std::to_string(k);
        const EngineAttribute a{
            "_LXH" + i, {}, {"lxh_r_" + i, "lxh_g_" + i, "lxh_b_" + i}, false, {}};
        std::vector<float> img(w * std::size_t(R) * 3);
        for (int f = 0; f < 6; ++f)
            for (int row = 0; row < R; ++row)
                for (int col = 0; col < R; ++col)
                    for (std::size_t c = 0; c < 3; ++c)
                        img[(std::size_t(row) * w + std::size_t(f * R + col)) * 3 + c] =
                            t.data[(t.param.texel_index(f, col, row) * kk + k) * 3 + c];
        Json e = add_table_image(files, "lxh.k" + i + ext, a, img, int(w), R, in.encoding);
        e["coefficient"] = k;
        images.push_back(e);
    }
    Json lighting = Json::array();
    for (double v : in.lighting) lighting.push_back(v);
    const Json doc = {
        {"format", "sphbasis lxh table"},
        {"version", 1},
        {"visibility_bands", K},
        {"lighting_bands", N},
        {"cosine_bands", t.cosine_bands},
        {"face_size", R},
        {"lighting", lighting},
        {"layout",
         "image k holds RGB coefficient k (ACN) of (L x H)(n); the six faces +X, -X, +Y, -Y, "
         "+Z, -Z side by side, face f in columns [f * face_size, (f + 1) * face_size); within a "
         "face, column c and row r (from the top) are the texel at face coordinates "
         "(sc, tc) = (2 (c + 0.5) / face_size - 1, 2 (r + 0.5) / face_size - 1) of the OpenGL "
         "cube map's face selection (+X: (1, -tc, -sc), -X: (-1, -tc, sc), +Y: (sc, 1, tc), "
         "-Y: (sc, -1, -tc), +Z: (sc, -tc, 1), -Z: (-sc, -tc, -1)): uploaded face by face, "
         "row 0 first, it is a samplerCube / TextureCube"},
        {"encoding", image_encoding_name(in.encoding)},
        {"decode", "v = bias[c] + scale[c] * t, t the stored value in [0, 1]"},
        {"shade",
         "I(n) = sum_k V_k T_k(n) per channel, V the K^2 SH visibility of the point, T_k the "
         "decoded image k at the normal n; a white Lambertian surface reflects I / pi"},
        {"quantization_step", quantization_step(in.encoding)},
        {"images", images}};
    files.push_back({"lxh.json", dump_json(doc, {{"images", 2}}) + "\n"});
    outputs.push_back({{"file", "lxh.json"},
                       {"kind", "lxh table"},
                       {"visibility_bands", K},
                       {"lighting_bands", N},
                       {"face_size", R}});
}

/// svd.json and svd.b<k>.<ext> (docs/export-format.md).
void export_svd(const EngineInput& in, std::vector<EngineFile>& files, Json& outputs) {
    const int M = in.compression.svd_vectors, R = in.compression.svd_resolution;
    NormalBasisSettings nbs;  // the renderer's (render/representations/prt_normalmap.hpp)
    nbs.bands = 3;
    nbs.clamped = false;
    nbs.weighting = NormalWeighting::cosine;
    const NormalBasis nb = normal_basis(nbs);
    const int nc = nbs.bands * nbs.bands;
    const std::size_t texels = std::size_t(R) * std::size_t(R);
    std::vector<double> a(texels * std::size_t(nc));
    for (int row = 0; row < R; ++row)
        for (int col = 0; col < R; ++col) {
            double x = 2 * (col + 0.5) / R - 1, y = 2 * (row + 0.5) / R - 1;
            const double r2 = x * x + y * y;
            if (r2 > 1) {  // outside the disk of normals: the rim's value
                x /= std::sqrt(r2);
                y /= std::sqrt(r2);
            }
            const double z = std::sqrt(std::max(0.0, 1 - x * x - y * y));
            convolved_lighting_columns(
                nbs.bands, nbs.clamped, x, y, z,
                a.data() +
                    (std::size_t(row) * std::size_t(R) + std::size_t(col)) * std::size_t(nc));
        }
    const char* ext = extension(in.encoding);
    Json images = Json::array();
    for (int k = 0; k < M; ++k) {
        const std::string i = std::to_string(k);
        std::vector<float> img(texels);
        for (std::size_t p = 0; p < texels; ++p) {
            double b = 0;
            for (int j = 0; j < nc; ++j) b += a[p * std::size_t(nc) + std::size_t(j)] * nb.v(j, k);
            img[p] = static_cast<float>(b);
        }
        const EngineAttribute attr{"_SVD" + i, {}, {"b_" + i}, false, {}};
        Json e = add_table_image(files, "svd.b" + i + ext, attr, img, R, R, in.encoding);
        e["function"] = k;
        images.push_back(e);
    }
    Json v = Json::array(), s = Json::array(), energy = Json::array();
    for (int j = 0; j < nc; ++j) {
        Json row = Json::array();
        for (int k = 0; k < nc; ++k) row.push_back(nb.v(j, k));
        v.push_back(row);
        s.push_back(nb.singular_values(j));
        energy.push_back(nb.energy_percent[std::size_t(j)]);
    }
    const Json doc = {
        {"format", "sphbasis normal basis"},
        {"version", 1},
        {"bands", nbs.bands},
        {"clamped", nbs.clamped},
        {"weighting", "cosine"},
        {"vectors", M},
        {"size", R},
        {"singular_values", s},
        {"energy_percent", energy},
        {"v", v},
        {"layout",
         "image k holds b_k(n) = sum_j A_j(n) v[j][k], A_j(n) = pi a_l y_j(n) (the clamped "
         "cosine's SH at the tangent-space normal n, ACN); column c and row r (from the top) "
         "are the normal with (x, y) = (2 (c + 0.5) / size - 1, 2 (r + 0.5) / size - 1), z = "
         "sqrt(1 - x^2 - y^2); texels outside the unit disk hold the value at (x, y) / |(x, y)|. "
         "A shader samples at uv = (n.xy + 1) / 2 (v = 0 the top row, as glTF)"},
        {"encoding", image_encoding_name(in.encoding)},
        {"decode", "v = bias[c] + scale[c] * t, t the stored value in [0, 1]"},
        {"shade",
         "e(n) ~ sum_{k < vectors} b_k(n) g_k, g = v^T l', l' the 9 SH coefficients of the "
         "transferred incident radiance in the tangent frame (exact with all 9)"},
        {"quantization_step", quantization_step(in.encoding)},
        {"images", images}};
    files.push_back({"svd.json", dump_json(doc, {{"images", 2}, {"v", 2}}) + "\n"});
    outputs.push_back({{"file", "svd.json"},
                       {"kind", "normal basis"},
                       {"vectors", M},
                       {"energy_percent", nb.energy_percent[std::size_t(M - 1)]}});
}

}  // namespace

std::string encode_png16(const std::vector<std::uint16_t>& samples, int width, int height,
                         int channels) {
    if (width < 1 || height < 1 || width > (1 << 20) || height > (1 << 20) ||
        (channels != 1 && channels != 3) ||
        samples.size() != std::size_t(width) * std::size_t(height) * std::size_t(channels))
        throw std::invalid_argument(
            "sphbasis::cli::encode_png16(): expected width * height * channels samples (channels "
            "1 or 3)");
    const std::size_t row = std::size_t(width) * std::size_t(channels);
    std::string raw;
    raw.reserve((2 * row + 1) * std::size_t(height));
    for (std::size_t y = 0; y < std::size_t(height); ++y) {
        raw.push_back(0);  // filter type None
        for (std::size_t i = 0; i < row; ++i) {
            const std::uint16_t v = samples[y * row + i];
            raw.push_back(static_cast<char>(v >> 8));
            raw.push_back(static_cast<char>(v & 0xFF));
        }
    }
    uLongf size = compressBound(uLong(raw.size()));
    std::string z(size, '\0');
    if (compress2(reinterpret_cast<Bytef*>(&z[0]), &size,
                  reinterpret_cast<const Bytef*>(raw.data()), uLong(raw.size()), 6) != Z_OK)
        throw std::runtime_error("cannot encode a 16-bit PNG image (zlib failed)");
    z.resize(size);
    std::string out("\x89PNG\r\n\x1a\n", 8);
    std::string ihdr;
    put_u32(ihdr, static_cast<std::uint32_t>(width));
    put_u32(ihdr, static_cast<std::uint32_t>(height));
    ihdr += {16, static_cast<char>(channels == 1 ? 0 : 2), 0, 0, 0};  // depth, colour, ...
    put_chunk(out, "IHDR", ihdr);
    put_chunk(out, "IDAT", z);
    put_chunk(out, "IEND", "");
    return out;
}

std::string encode_compressed(const std::vector<float>& values, int width, int height,
                              std::size_t channels, const std::vector<ChannelRange>& ranges,
                              ImageEncoding e) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    if (width < 1 || height < 1 || (channels != 1 && channels != 3) || ranges.size() != channels ||
        values.size() != n * channels)
        throw std::invalid_argument(
            "sphbasis::cli::encode_compressed(): expected width * height * channels values "
            "(channels 1 or 3) and one range per channel");
    switch (e) {
        case ImageEncoding::png8: {
            std::vector<std::uint8_t> px(values.size());
            for (std::size_t i = 0; i < values.size(); ++i)
                px[i] = static_cast<std::uint8_t>(
                    std::lround(255.0 * compress(values[i], ranges[i % channels])));
            return encode_png(px, width, height, static_cast<int>(channels));
        }
        case ImageEncoding::png16: {
            std::vector<std::uint16_t> px(values.size());
            for (std::size_t i = 0; i < values.size(); ++i)
                px[i] = static_cast<std::uint16_t>(
                    std::lround(65535.0 * compress(values[i], ranges[i % channels])));
            return encode_png16(px, width, height, static_cast<int>(channels));
        }
        case ImageEncoding::half:
        case ImageEncoding::float32: {
            std::vector<float> t(values.size());
            for (std::size_t i = 0; i < values.size(); ++i) {
                const double x = compress(values[i], ranges[i % channels]);
                t[i] = static_cast<float>(e == ImageEncoding::half ? round_to_half(x) : x);
            }
            const std::vector<std::string> names = channels == 1
                                                       ? std::vector<std::string>{"Y"}
                                                       : std::vector<std::string>{"R", "G", "B"};
            return encode_exr(width, height, names, t, e == ImageEncoding::half);
        }
    }
    return {};
}

namespace {
std::vector<std::string> split_colons(const std::string& s) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    for (std::size_t k = 0; k <= s.size(); ++k)
        if (k == s.size() || s[k] == ':') {
            parts.push_back(s.substr(start, k - start));
            start = k + 1;
        }
    return parts;
}

/// parts[1..] as integers within [lo[i], hi[i]] (missing trailing ones keep `out`'s values);
/// false when malformed.
bool parse_ints(const std::vector<std::string>& parts, std::size_t required,
                const std::vector<long long>& lo, const std::vector<long long>& hi,
                std::vector<long long>& out) {
    if (parts.size() < 1 + required || parts.size() > 1 + lo.size()) return false;
    for (std::size_t i = 1; i < parts.size(); ++i)
        if (!parse_integer(parts[i], out[i - 1]) || out[i - 1] < lo[i - 1] ||
            out[i - 1] > hi[i - 1])
            return false;
    return true;
}

/// One "lxh:K[:N[:RES]]" or "svd:M[:RES]" item of --export into e.
void parse_table_item(const std::vector<std::string>& parts, const std::string& s,
                      CompressionExport& e) {
    if (parts[0] == "lxh") {
        std::vector<long long> v{0, 0, 32};
        if (!parse_ints(parts, 1, {1, 1, 1}, {max_lxh_bands, max_lxh_bands, 1024}, v))
            throw UsageError(
                "--export: expected lxh:K[:N[:RES]] (1 <= K, N <= 16 visibility and lighting "
                "bands, 1 <= RES <= 1024 texels a cube face edge), got '" +
                quote_input(s) + "'");
        e.lxh_visibility_bands = int(v[0]);
        e.lxh_lighting_bands = int(v[1] > 0 ? v[1] : v[0]);
        e.lxh_resolution = int(v[2]);
        return;
    }
    std::vector<long long> v{0, 64};
    if (!parse_ints(parts, 1, {1, 2}, {9, 4096}, v))
        throw UsageError(
            "--export: expected svd:M[:RES] (1 <= M <= 9 normal-basis functions, 2 <= RES <= "
            "4096 texels a side), got '" +
            quote_input(s) + "'");
    e.svd_vectors = int(v[0]);
    e.svd_resolution = int(v[1]);
}

/// One "pca:M" or "cpca:C:M" item of --export.
CompressionExport parse_cpca_item(const std::string& s) {
    CompressionExport e;
    const std::string what =
        "--export: expected pca:M or cpca:C:M (1 <= C <= 65535 clusters, 1 <= M <= 64 "
        "vectors), lxh:K[:N[:RES]], svd:M[:RES] or toksvig:S, got '" +
        quote_input(s) + "'";
    const std::vector<std::string> parts = split_colons(s);
    long long c = 1, m = 0;
    const bool ok = (parts.size() == 2 && parts[0] == "pca" && parse_integer(parts[1], m)) ||
                    (parts.size() == 3 && parts[0] == "cpca" && parse_integer(parts[1], c) &&
                     parse_integer(parts[2], m));
    if (!ok || c < 1 || c > 65535 || m < 1 || m > 64) throw UsageError(what);
    e.clusters = static_cast<int>(c);
    e.vectors = static_cast<int>(m);
    return e;
}
}  // namespace

CompressionExport parse_compression_export(const std::string& list) {
    CompressionExport e;
    std::size_t from = 0;
    while (from < list.size()) {
        std::size_t comma = list.find(',', from);
        if (comma == std::string::npos) comma = list.size();
        const std::string s = list.substr(from, comma - from);
        from = comma + 1;
        if (s.rfind("toksvig:", 0) == 0) {
            const double v = to_real(s.substr(8), "--export: toksvig:S");
            if (!(v > 0 && v <= 1e6))
                throw UsageError("--export: expected toksvig:S with 0 < S <= 1e6, got '" +
                                 quote_input(s) + "'");
            e.toksvig_shininess = v;
            continue;
        }
        const std::vector<std::string> parts = split_colons(s);
        if (parts[0] == "lxh" || parts[0] == "svd") {
            parse_table_item(parts, s, e);
            continue;
        }
        const CompressionExport c = parse_cpca_item(s);
        e.clusters = c.clusters;
        e.vectors = c.vectors;
    }
    return e;
}

std::vector<double> distant_lighting_sh(const SceneFile& scene, int bands) {
    vec3<double> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (const SceneMesh& m : scene.meshes)
        for (std::size_t i = 0; i + 2 < m.mesh.positions.size(); i += 3) {
            lo = {std::min(lo.x, double(m.mesh.positions[i])),
                  std::min(lo.y, double(m.mesh.positions[i + 1])),
                  std::min(lo.z, double(m.mesh.positions[i + 2]))};
            hi = {std::max(hi.x, double(m.mesh.positions[i])),
                  std::max(hi.y, double(m.mesh.positions[i + 1])),
                  std::max(hi.z, double(m.mesh.positions[i + 2]))};
        }
    const vec3<double> centre =
        lo.x <= hi.x ? vec3<double>{0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y), 0.5 * (lo.z + hi.z)}
                     : vec3<double>{0, 0, 0};
    std::vector<render::RGB> L = render::project_sh(scene.environment, bands);
    for (const render::Light& l : scene.lights) {
        const std::vector<render::RGB> s = render::project_sh(l, bands, centre);
        for (std::size_t k = 0; k < L.size(); ++k)
            for (std::size_t c = 0; c < 3; ++c) L[k][c] += s[k][c];
    }
    std::vector<double> out;
    for (const render::RGB& v : L) out.insert(out.end(), {v[0], v[1], v[2]});
    return out;
}

std::vector<EngineAttribute> engine_attributes(
    const std::vector<std::pair<std::string, std::size_t>>& columns, const std::string& basis) {
    std::map<std::string, std::size_t> at(columns.begin(), columns.end());
    auto offset = [&](const std::string& name) {
        const auto it = at.find(name);
        if (it == at.end())
            throw std::invalid_argument("sphbasis::cli::engine_attributes(): expected channel '" +
                                        name + "'");
        return it->second;
    };
    auto starts = [](const std::string& s, const std::string& p, std::string& rest) {
        if (s.compare(0, p.size(), p) != 0) return false;
        rest = s.substr(p.size());
        return !rest.empty() &&
               std::all_of(rest.begin(), rest.end(), [](char c) { return c >= '0' && c <= '9'; });
    };
    auto rgb = [&](const std::string& attr, const std::string& prefix, const std::string& i) {
        EngineAttribute a;
        a.name = attr;
        for (const char* c : {"r_", "g_", "b_"}) {
            a.channels.push_back(prefix + c + i);
            a.offsets.push_back(offset(a.channels.back()));
        }
        return a;
    };
    const std::string irr = basis == "sh" ? "SH" : upper_name(basis);
    std::vector<EngineAttribute> out;
    for (const auto& c : columns) {
        const std::string& n = c.first;
        std::string i;
        if (n.find("stderr") != std::string::npos || n == "bent_y" || n == "bent_z" ||
            starts(n, "transfer_g_", i) || starts(n, "transfer_b_", i) || starts(n, "irr_g_", i) ||
            starts(n, "irr_b_", i) || starts(n, "rad_g_", i) || starts(n, "rad_b_", i))
            continue;  // standard errors are for the bake's report; g, b join r below
        EngineAttribute a;
        if (n == "ao" || n == "inside") {
            a = {n == "ao" ? "_AO" : "_INSIDE", {c.second}, {n}, true, {1, 0}};
        } else if (n == "bent_x") {
            a = {"_BENT",
                 {c.second, offset("bent_y"), offset("bent_z")},
                 {"bent_x", "bent_y", "bent_z"},
                 true,
                 {2, -1}};
        } else if (starts(n, "vis_", i)) {
            a = {"_VIS" + i, {c.second}, {n}, false, {}};
        } else if (starts(n, "transfer_r_", i)) {
            a = rgb("_PRT" + i, "transfer_", i);
        } else if (starts(n, "transfer_", i)) {
            a = {"_PRT" + i, {c.second}, {n}, false, {}};
        } else if (starts(n, "irr_r_", i)) {
            a = rgb("_" + irr + i, "irr_", i);
        } else if (starts(n, "rad_r_", i)) {
            a = rgb("_RAD" + i, "rad_", i);
        } else {  // a channel this exporter does not know: kept, as a scalar of its own name
            a = {"_" + upper_name(n), {c.second}, {n}, false, {}};
        }
        out.push_back(a);
    }
    return out;
}

std::vector<std::string> engine_file_names(const EngineInput& in) {
    check_input(in, false);
    const std::vector<EngineAttribute> attrs = engine_attributes(in.columns, in.basis);
    const char* ext = extension(in.encoding);
    std::vector<std::string> f;
    if (in.compression.clusters > 0) {
        if (in.target == EngineTarget::probes)
            throw UsageError("--export: for --target vertices or texels (probes have no transfer)");
        if (std::none_of(attrs.begin(), attrs.end(),
                         [](const EngineAttribute& a) { return a.name.rfind("_PRT", 0) == 0; }))
            throw UsageError("--export: compresses transfer vectors; give --quantities transfer");
        f.push_back("cpca.json");
        f.push_back("cpca.bin");
        if (in.target == EngineTarget::texels)
            for (const SceneMesh& m : *in.meshes) {
                f.push_back(m.name + ".cpca_cluster.png");
                for (int j = 0; j < in.compression.vectors; ++j)
                    f.push_back(m.name + ".cpca_w" + std::to_string(j) + ext);
            }
    }
    if (in.compression.toksvig_shininess > 0) {
        f.push_back("toksvig.json");
        f.push_back(std::string("toksvig") + ext);
    }
    if (in.compression.lxh_visibility_bands > 0) {
        f.push_back("lxh.json");
        for (int k = 0;
             k < in.compression.lxh_visibility_bands * in.compression.lxh_visibility_bands; ++k)
            f.push_back("lxh.k" + std::to_string(k) + ext);
    }
    if (in.compression.svd_vectors > 0) {
        f.push_back("svd.json");
        for (int k = 0; k < in.compression.svd_vectors; ++k)
            f.push_back("svd.b" + std::to_string(k) + ext);
    }
    if (in.target == EngineTarget::probes) {
        for (const EngineAttribute& a : attrs)
            for (int k = 0; k < in.probes->counts[2]; ++k)
                f.push_back("probes." + lower_name(a.name) + ".z" + std::to_string(k) + ext);
        f.push_back("probes.grid.json");
        return f;
    }
    f.push_back("scene.glb");
    if (in.target == EngineTarget::texels) {
        for (const SceneMesh& m : *in.meshes)
            for (const EngineAttribute& a : attrs)
                f.push_back(m.name + "." + lower_name(a.name) + ext);
        f.push_back("lightmaps.json");
    }
    return f;
}

std::vector<EngineFile> export_engine(const EngineInput& in, Json& outputs) {
    check_input(in, true);
    const std::vector<EngineAttribute> attrs = engine_attributes(in.columns, in.basis);
    const char* ext = extension(in.encoding);
    const double q = quantization_step(in.encoding);
    std::vector<EngineFile> files;
    auto add = [&](const std::string& name, std::string bytes) {
        return add_file(files, name, std::move(bytes));
    };
    Json attr_names = Json::array();
    for (const EngineAttribute& a : attrs) attr_names.push_back(a.name);
    if (in.compression.toksvig_shininess > 0) {
        // Toksvig, "Mipmapping Normal Maps" (2004), eq. 9 (with the power outside the
        // numerator, as shading/toksvig.hpp corrects it): values in [0, 1], stored as is.
        toksvig::SpecularTableOptions o;
        o.shininess = in.compression.toksvig_shininess;
        const toksvig::SpecularTable t = toksvig::make_specular_table(o);
        const EngineAttribute a{"_TOKSVIG", {0}, {"specular"}, true, {1, 0}};
        const std::vector<ChannelRange> r{a.range};
        const std::string file = std::string("toksvig") + ext;
        Json doc = {
            {"format", "sphbasis toksvig table"},
            {"version", 1},
            {"shininess", o.shininess},
            {"width", t.width},
            {"height", t.height},
            {"layout",
             "column c (from the left): Na.H = c / (width - 1); row r (from the top): Na.Na = r / "
             "(height - 1); value = (1 + f s) / (1 + s) * (Na.H / |Na|)^(f s), f = |Na| / (|Na| + "
             "s (1 - |Na|)); cells with Na.H > |Na| (no normal reaches them) hold the value at "
             "Na.H = |Na|"},
            {"lookup", "uv = ((Na.H, Na.Na) * (size - 1) + 0.5) / size, bilinear"},
            {"encoding", image_encoding_name(in.encoding)},
            {"decode", "v = bias + scale * t"}};
        doc.update(range_json(a, r, in.encoding));
        doc.update(add(file, encode_compressed(t.value, t.width, t.height, 1, r, in.encoding)));
        files.push_back({"toksvig.json", dump_json(doc) + "\n"});
        outputs.push_back({{"file", "toksvig.json"}, {"kind", "toksvig"}, {"image", file}});
    }

    if (in.compression.lxh_visibility_bands > 0) export_lxh(in, files, outputs);
    if (in.compression.svd_vectors > 0) export_svd(in, files, outputs);

    if (in.target == EngineTarget::probes) {
        const render::ProbeGrid& g = *in.probes;
        const std::size_t nx = std::size_t(g.counts[0]), ny = std::size_t(g.counts[1]),
                          nz = std::size_t(g.counts[2]), slice = nx * ny;
        const double lo[3] = {g.lo.x, g.lo.y, g.lo.z}, hi[3] = {g.hi.x, g.hi.y, g.hi.z};
        Json spacing = Json::array();
        for (int a = 0; a < 3; ++a)
            spacing.push_back(g.counts[std::size_t(a)] > 1
                                  ? (hi[a] - lo[a]) / double(g.counts[std::size_t(a)] - 1)
                                  : 0.0);
        Json list = Json::array();
        for (const EngineAttribute& a : attrs) {
            const std::vector<float> all = gather(in, a, 0, g.size());
            const std::vector<ChannelRange> r = ranges_of(a, all);  // one range for all slices
            Json entry = range_json(a, r, in.encoding);
            Json slices = Json::array();
            const std::size_t ch = a.offsets.size();
            for (std::size_t k = 0; k < nz; ++k) {
                const std::vector<float> s(all.begin() + std::ptrdiff_t(k * slice * ch),
                                           all.begin() + std::ptrdiff_t((k + 1) * slice * ch));
                slices.push_back(
                    add("probes." + lower_name(a.name) + ".z" + std::to_string(k) + ext,
                        encode_compressed(s, int(nx), int(ny), ch, r, in.encoding)));
            }
            entry["slices"] = slices;
            list.push_back(entry);
        }
        const Json doc = {
            {"format", "sphbasis probe grid"},
            {"version", 1},
            {"origin", {lo[0], lo[1], lo[2]}},
            {"spacing", spacing},
            {"counts", {g.counts[0], g.counts[1], g.counts[2]}},
            {"max", {hi[0], hi[1], hi[2]}},
            {"layout",
             "slice file z<k> holds probes (i, j, k) at origin + spacing * (i, j, k): column i "
             "from the left, row j from the top; as a 3D texture, probe (i, j, k) is texel "
             "(i, j, k) and a point p samples uvw = ((p - origin) / spacing + 0.5) / counts"},
            {"encoding", image_encoding_name(in.encoding)},
            {"decode", "v = bias[c] + scale[c] * t, t the stored value in [0, 1]"},
            {"quantization_step", q},
            {"attributes", list}};
        files.push_back({"probes.grid.json", dump_json(doc, {{"attributes", 2}}) + "\n"});
        outputs.push_back({{"file", "probes.grid.json"},
                           {"kind", "probe grid"},
                           {"encoding", image_encoding_name(in.encoding)},
                           {"attributes", attr_names}});
        return files;
    }

    std::vector<GltfMesh> meshes;
    Json lm_meshes = Json::array();
    for (std::size_t k = 0; k < in.meshes->size(); ++k) {
        const SceneMesh& sm = (*in.meshes)[k];
        GltfMesh gm;
        gm.name = sm.name;
        gm.mesh = &sm.mesh;
        gm.normals = render::vertex_normals(sm.mesh.view());
        if (sm.lightmap_uv == 1) gm.lightmap_uvs = &sm.uvs1;
        const std::size_t first = (*in.mesh_begin)[k], count = (*in.mesh_begin)[k + 1] - first;
        if (in.target == EngineTarget::vertices) {
            if (count != sm.mesh.vertex_count())
                throw std::invalid_argument(
                    "sphbasis::cli::export_engine(): expected one record per vertex");
            for (const EngineAttribute& a : attrs)
                gm.attributes.push_back(
                    {a.name, int(a.offsets.size()), gather(in, a, first, count)});
        } else {
            const render::LightmapLayout& lay = (*in.layouts)[k];
            if (count != lay.samples.size())
                throw std::invalid_argument(
                    "sphbasis::cli::export_engine(): expected one record per texel sample");
            Json images = Json::array();
            for (const EngineAttribute& a : attrs) {
                const std::size_t ch = a.offsets.size();
                const std::vector<float> img =
                    render::assemble_lightmap(lay, int(ch), [&](std::size_t i, float* px) {
                        for (std::size_t c = 0; c < ch; ++c)
                            px[c] = static_cast<float>(
                                (*in.records)[(first + i) * in.stride + a.offsets[c]]);
                    });
                const std::vector<ChannelRange> r = ranges_of(a, img);
                const std::string file = sm.name + "." + lower_name(a.name) + ext;
                Json e = range_json(a, r, in.encoding);
                e.update(
                    add(file, encode_compressed(img, lay.width, lay.height, ch, r, in.encoding)));
                images.push_back(e);
                Json gx = range_json(a, r, in.encoding);
                gx["encoding"] = image_encoding_name(in.encoding);
                gm.lightmaps.push_back({a.name, file, ext[1] == 'p', gx});
            }
            lm_meshes.push_back({{"mesh", sm.name},
                                 {"texCoord", sm.lightmap_uv},
                                 {"width", lay.width},
                                 {"height", lay.height},
                                 {"images", images}});
        }
        meshes.push_back(std::move(gm));
    }
    const Json extras = {{"sphbasis",
                          {{"version", 1},
                           {"target", in.target == EngineTarget::vertices ? "vertices" : "texels"},
                           {"basis", in.basis},
                           {"attributes", attr_names}}}};
    const Json glb = add("scene.glb", encode_glb(meshes, extras));
    outputs.push_back({{"file", "scene.glb"},
                       {"kind", "gltf"},
                       {"meshes", meshes.size()},
                       {"attributes", attr_names},
                       {"xxh3", glb["xxh3"]}});
    if (in.compression.clusters > 0) export_cpca(in, attrs, files, outputs);
    if (in.target == EngineTarget::texels) {
        const Json doc = {{"format", "sphbasis lightmaps"},
                          {"version", 1},
                          {"encoding", image_encoding_name(in.encoding)},
                          {"uv_set",
                           "each mesh's lightmap UV set (glTF TEXCOORD_<texCoord> = (u, 1 - v) "
                           "of the scene's set); image rows from the top, texel (x, y) covers "
                           "uv [x, x + 1] / width, [y, y + 1] / height in glTF's convention"},
                          {"gutter", render::lightmap_gutter},
                          {"decode", "v = bias[c] + scale[c] * t, t the stored value in [0, 1]"},
                          {"quantization_step", q},
                          {"meshes", lm_meshes}};
        files.push_back({"lightmaps.json", dump_json(doc, {{"meshes", 2}}) + "\n"});
        outputs.push_back({{"file", "lightmaps.json"},
                           {"kind", "lightmaps"},
                           {"encoding", image_encoding_name(in.encoding)},
                           {"attributes", attr_names}});
    }
    return files;
}

}  // namespace sphbasis::cli
