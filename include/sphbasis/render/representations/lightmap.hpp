// sphbasis render tier: irradiance lightmaps in a directional basis (representations/
// family.hpp):
//   lightmap-sh4, -sh9, -hbasis4, -hbasis6, -hbasis-mod6, -hl2, -hsh4, -hsh9,
//   lightmap-ambient-cube5, -ambient-dice12 (the hemispherical ambient cube: no -z face),
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
#pragma once

#include <algorithm>
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "../../basis/registry.hpp"
#include "../../core/constants.hpp"
#include "family.hpp"

namespace sphbasis::render::representations {

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
        const char* no_bounce = ctx.settings.bounces > 0 ? "" : "; no interreflection";
        const std::string b = name.substr(9);
        for (const auto& t : table())
            if (b == t.first) storage_ = irradiance_storage(t.second.first, t.second.second);
        if (storage_.coeffs == 0)  // the table and accepts() disagree
            sphbasis::detail::throw_invalid("render::Representations",
                                            "a lightmap basis, got '" + b + "'");
        element = "texel";
        bytes_per_element = 3 * std::size_t(storage_.coeffs) * sizeof(float);
        cannot_show =
            std::string("static lighting (ignores the render-time rotation)") +
            "; directional detail beyond " + std::to_string(storage_.coeffs) + " " + storage_.name +
            (storage_.fitted ? " values (non-linear reconstruction)" : " functions") + no_bounce;
        for (const MeshView& m : ctx.scene.meshes)
            if (!has_uvs(m)) {
                cannot_show += "; meshes without UVs fall back to irradiance-sh9";
                break;
            }
    }
    void plan(Context& ctx) override {
        const std::size_t nm = ctx.scene.meshes.size();
        mesh_bake.assign(nm, -1);
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
            q.settings.basis = storage_.name;
            q.settings.coeffs = storage_.coeffs;
            mesh_bake[m] = ctx.add_request(q);
        }
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        std::array<double, 3 * 16> e;
        lookup(ctx.fields[std::size_t(b)], hit, e.data());
        using namespace detail::rt;
        const V3 nm = Scene::normal_mapped(hit);
        const V3 ns = hit.shading_normal, t = hit.tangent;
        const V3 bt = cross(ns, t) * hit.bitangent_sign;
        // The basis lives on the tangent hemisphere: a mapped normal below it (a steep
        // map) is read at the horizon.
        V3 local{dot(nm, t), dot(nm, bt), std::max(dot(nm, ns), 0.0)};
        local = normalized(local, {0, 0, 1});
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

}  // namespace sphbasis::render::representations
