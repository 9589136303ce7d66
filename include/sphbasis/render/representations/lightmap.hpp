// sphbasis render tier: irradiance lightmaps in a directional basis (representations/
// family.hpp):
//   lightmap-sh4, -sh9, -hbasis4, -hbasis6, -hbasis-mod6, -hl2, -hsh4, -hsh9,
//   lightmap-ambient-cube5, -ambient-dice12 (the hemispherical ambient cube: no -z face),
//   lightmap-ambient-dice-bezier30, -ambient-dice-linear10 (Ambient Dice over the icosahedron's
//                             faces on the upper hemisphere: 30 and 10 functions a channel),
//   lightmap-sg5, -sg6, -sg9, -sg12 (BakingLab's lobes, least squares), -sg9-nnls (non-negative
//                             least squares), -sg9-running (Roughton's running average),
//   lightmap-zh3, -zh3-hallucinate, -sh-l1-nonlinear (the non-linear lightmaps: 5, 4 and 4
//                             values per channel, fitted from the irradiance's SH)
//                             the bake's `irradiance` stored that way (render::
//                             irradiance_storage(), basis/registry.hpp), per
//                             texel, bilinear, evaluated at the normal-mapped normal in the
//                             texel's tangent frame (Ishmukhametov, "Irradiance Normal
//                             Mapping"). Meshes without UVs fall back to irradiance-sh9 (noted).
// Each reads a bake of the irradiance in its basis (bounces, lighting-dependent: static
// lighting, the render-time rotation is ignored).
//   lightmap-ambient-dice-ycocg (LightmapYCoCg) Iwanicki and Sloan's YCoCg variant of Ambient
//                             Dice ("Ambient Dice", EGSR 2017): luma Y in ambient-dice-bezier (30)
//                             and chroma Co, Cg in ambient-dice-linear (10 each), 50 values a
//                             texel instead of 90. The fit is linear, so the least squares of a
//                             channel's irradiance is the transform (rgb_to_ycocg()) of the RGB
//                             fits: it reads the bakes of lightmap-ambient-dice-bezier30 (Y) and
//                             -linear10 (Co, Cg), shared with those when both are rendered (a
//                             shipping bake would fit both from one set of rays), and stores the
//                             50 values per texel at float precision (build()).
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "../../basis/registry.hpp"
#include "../../core/constants.hpp"
#include "family.hpp"

namespace sphbasis::render {

/// The YCoCg transform (Malvar and Sullivan, "YCoCg-R: A Color Space with RGB Reversibility and
/// Low Dynamic Range", 2003): Y = R/4 + G/2 + B/4, Co = R/2 - B/2, Cg = -R/4 + G/2 - B/4, and its
/// inverse R = Y + Co - Cg, G = Y + Cg, B = Y - Co - Cg (exact in exact arithmetic; in floating
/// point a round trip is exact where no sum rounds, e.g. for multiples of 1/4 of small size, and
/// within a few ulps of the largest input otherwise).
template <class T>
constexpr std::array<T, 3> rgb_to_ycocg(T r, T g, T b) noexcept {
    return {r / 4 + g / 2 + b / 4, r / 2 - b / 2, g / 2 - r / 4 - b / 4};
}
template <class T>
constexpr std::array<T, 3> ycocg_to_rgb(T y, T co, T cg) noexcept {
    return {y + co - cg, y + cg, y - co - cg};
}

}  // namespace sphbasis::render

namespace sphbasis::render::representations {

/// The largest count of functions a lightmap stores per channel (ambient-dice-bezier's 30, below
/// the full sphere's 36).
inline constexpr int lightmap_max_coeffs = 36;

/// The tangent-space normal of a hit for a lightmap basis on the tangent hemisphere: the
/// normal-mapped normal in the texel's tangent frame, a mapped normal below the hemisphere (a
/// steep map) read at the horizon.
inline vec3<double> lightmap_local_normal(const Hit& hit) noexcept {
    using namespace detail::rt;
    const V3 nm = Scene::normal_mapped(hit);
    const V3 ns = hit.shading_normal, t = hit.tangent;
    const V3 bt = cross(ns, t) * hit.bitangent_sign;
    const V3 local{dot(nm, t), dot(nm, bt), std::max(dot(nm, ns), 0.0)};
    return normalized(local, {0, 0, 1});
}

/// Plans one irradiance bake of `storage` at the lightmap texels of every mesh with UVs
/// (the result's [m]; -1 for meshes without, which set ctx.needs_sh: the irradiance-sh9
/// fallback).
inline std::vector<int> plan_lightmap_bakes(Context& ctx, const IrradianceStorage& storage) {
    const std::size_t nm = ctx.scene.meshes.size();
    std::vector<int> out(nm, -1);
    for (std::size_t m = 0; m < nm; ++m) {
        if (!has_uvs(ctx.scene.meshes[m])) {
            ctx.needs_sh = true;
            continue;
        }
        BakeRequest q;
        q.mesh = m;
        q.where = BakeRequest::Where::texel;
        q.lightmap_size = ctx.settings.lightmap_size;
        q.lighting_dependent = true;
        q.settings = ctx.base_settings(Quantity::irradiance, ctx.settings.bounces);
        q.settings.basis = storage.name;
        q.settings.coeffs = storage.coeffs;
        out[m] = ctx.add_request(q);
    }
    return out;
}

/// What a lightmap cannot show: static lighting, directional detail beyond `detail`, no
/// interreflection without bounces, the fallback of meshes without UVs.
inline std::string lightmap_cannot_show(const Context& ctx, const std::string& detail) {
    std::string s =
        "static lighting (ignores the render-time rotation); directional detail beyond " + detail +
        (ctx.settings.bounces > 0 ? "" : "; no interreflection");
    for (const MeshView& m : ctx.scene.meshes)
        if (!has_uvs(m)) return s + "; meshes without UVs fall back to irradiance-sh9";
    return s;
}

class Lightmap : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        for (const auto& t : table()) out.push_back(std::string("lightmap-") + t.first);
    }
    static bool accepts(const std::string& name) {
        for (const auto& t : table())
            if (name == std::string("lightmap-") + t.first) return true;
        return false;
    }
    Lightmap(const std::string& name, const Context& ctx) : Representation(name) {
        const std::string b = name.substr(9);
        for (const auto& t : table())
            if (b == t.first) storage_ = irradiance_storage(t.second.first, t.second.second);
        if (storage_.coeffs == 0 || storage_.coeffs > lightmap_max_coeffs)
            // the table and accepts() disagree, or the table outgrew shade()'s buffer
            sphbasis::detail::throw_invalid("render::Representations",
                                            "a lightmap basis, got '" + b + "'");
        element = "texel";
        bytes_per_element = 3 * std::size_t(storage_.coeffs) * sizeof(float);
        cannot_show = lightmap_cannot_show(
            ctx, std::to_string(storage_.coeffs) + " " + storage_.name +
                     (storage_.fitted ? " values (non-linear reconstruction)" : " functions"));
    }
    void plan(Context& ctx) override { mesh_bake = plan_lightmap_bakes(ctx, storage_); }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        std::array<double, 3 * lightmap_max_coeffs> e;
        lookup(ctx.fields[std::size_t(b)], hit, e.data());
        const vec3<double> local = lightmap_local_normal(hit);
        const std::size_t n = std::size_t(storage_.coeffs);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c)
            out[c] = hit.albedo[c] * storage_.eval(e.data() + c * n, local.x, local.y, local.z) *
                     constants::inv_pi;
        return out;
    }

  private:
    /// Name suffix -> (basis registry name, coefficients), in report order.
    static const std::vector<std::pair<const char*, std::pair<const char*, int>>>& table() {
        static const std::vector<std::pair<const char*, std::pair<const char*, int>>> t{
            {"sh4", {"sh", 4}},
            {"sh9", {"sh", 9}},
            {"hbasis4", {"hbasis", 4}},
            {"hbasis6", {"hbasis", 6}},
            {"hbasis-mod6", {"hbasis-mod", 6}},
            {"hl2", {"hl2", 3}},
            {"hsh4", {"hsh", 4}},
            {"hsh9", {"hsh", 9}},
            {"ambient-cube5", {"ambient-cube", 5}},
            {"ambient-dice12", {"ambient-dice", 12}},
            {"ambient-dice-bezier30", {"ambient-dice-bezier", 30}},
            {"ambient-dice-linear10", {"ambient-dice-linear", 10}},
            {"sg5", {"sg", 5}},
            {"sg6", {"sg", 6}},
            {"sg9", {"sg", 9}},
            {"sg12", {"sg", 12}},
            {"sg9-nnls", {"sg-nnls", 9}},
            {"sg9-running", {"sg-running", 9}},
            {"zh3", {"zh3", 5}},
            {"zh3-hallucinate", {"zh3-hallucinate", 4}},
            {"sh-l1-nonlinear", {"sh-l1-nonlinear", 4}}};
        return t;
    }
    IrradianceStorage storage_;
};

/// lightmap-ambient-dice-ycocg (header comment): mesh_bake holds the luma bakes
/// (ambient-dice-bezier, 30) of the meshes, then their chroma bakes (ambient-dice-linear, 10),
/// so reads() and the report count both.
class LightmapYCoCg : public Representation {
  public:
    static constexpr const char* listed = "lightmap-ambient-dice-ycocg";
    static void list(std::vector<std::string>& out) { out.push_back(listed); }
    static bool accepts(const std::string& name) { return name == listed; }
    LightmapYCoCg(const std::string& name, const Context& ctx)
        : Representation(name),
          luma_(irradiance_storage("ambient-dice-bezier", 30)),
          chroma_(irradiance_storage("ambient-dice-linear", 10)) {
        element = "texel";
        bytes_per_element = std::size_t(channels) * sizeof(float);
        cannot_show = lightmap_cannot_show(
            ctx,
            "30 ambient-dice-bezier functions in luma and 10 ambient-dice-linear ones in "
            "chroma");
    }
    void plan(Context& ctx) override {
        mesh_bake = plan_lightmap_bakes(ctx, luma_);
        const std::vector<int> c = plan_lightmap_bakes(ctx, chroma_);
        mesh_bake.insert(mesh_bake.end(), c.begin(), c.end());
    }
    void build(Context& ctx) override {
        const auto t0 = std::chrono::steady_clock::now();
        const std::size_t nm = mesh_bake.size() / 2;
        fields_.assign(nm, Field{});
        for (std::size_t m = 0; m < nm; ++m) {
            if (mesh_bake[m] < 0) continue;
            const BakeData& l = ctx.data[std::size_t(mesh_bake[m])];
            const BakeData& c = ctx.data[std::size_t(mesh_bake[nm + m])];
            if (l.results.size() != c.results.size())  // one request's texels, two bases
                sphbasis::detail::throw_invalid("render::Representations",
                                                "the luma and chroma bakes of '" + name +
                                                    "' at the same texels, got " +
                                                    std::to_string(l.results.size()) + " and " +
                                                    std::to_string(c.results.size()));
            fields_[m] = make_field(l, channels, [&](std::size_t i, float* out) {
                const auto& L = l.results[i].irradiance;
                const auto& C = c.results[i].irradiance;
                for (std::size_t j = 0; j < 30; ++j)
                    out[j] = float(rgb_to_ycocg(L[0][j], L[1][j], L[2][j])[0]);
                for (std::size_t j = 0; j < 10; ++j) {
                    const auto v = rgb_to_ycocg(C[0][j], C[1][j], C[2][j]);
                    out[30 + j] = float(v[1]);
                    out[40 + j] = float(v[2]);
                }
            });
        }
        build_seconds = seconds_since(t0);
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        if (mesh_bake[hit.mesh] < 0)
            return sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        std::array<double, channels> e;
        lookup(fields_[hit.mesh], hit, e.data());
        const vec3<double> n = lightmap_local_normal(hit);
        std::array<double, 10> h;  // the chroma functions, evaluated once for Co and Cg
        chroma_.basis->eval_d(10, n.x, n.y, n.z, h.data());
        double co = 0, cg = 0;
        for (std::size_t j = 0; j < 10; ++j) {
            co += e[30 + j] * h[j];
            cg += e[40 + j] * h[j];
        }
        const RGB rgb = ycocg_to_rgb(luma_.eval(e.data(), n.x, n.y, n.z), co, cg);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c) out[c] = hit.albedo[c] * rgb[c] * constants::inv_pi;
        return out;
    }
    /// Texels of the luma bakes only (the chroma bakes are at the same texels).
    void stats(const Context& ctx, RepresentationStats& s) const override {
        if (!ctx.prepared) return;
        s.elements = 0;
        for (std::size_t m = 0; m < mesh_bake.size() / 2; ++m)
            if (mesh_bake[m] >= 0) s.elements += ctx.data[std::size_t(mesh_bake[m])].results.size();
    }

  private:
    static constexpr int channels = 30 + 10 + 10;  // Y, Co, Cg
    IrradianceStorage luma_, chroma_;
    std::vector<Field> fields_;  // per mesh: the 50 values per texel
};

}  // namespace sphbasis::render::representations
