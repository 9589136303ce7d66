// sphbasis render tier: diffuse precomputed radiance transfer (representations/family.hpp):
//   prt-vertex, prt-texel     diffuse PRT transfer (prt_bands bands, shadows and bounces baked)
//                             dotted with the SH of the distant lighting, interpolated from
//                             vertices or read from a lightmap (meshes without UVs: per vertex);
//                             the lighting may be rotated at render time
//                             (RepresentationSettings::lighting_rotation): its SH are rotated
//                             (ops/sh_rotation.hpp), nothing is re-baked.
// Sloan, Kautz and Snyder, "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic,
// Low-Frequency Lighting Environments" (SIGGRAPH 2002).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "family.hpp"

namespace sphbasis::render::representations {

/// The transfer of the PRT representations: prt_bands^2 coefficients per channel (one channel
/// shared by all three when the bake is white), at float precision; after prepare(), RGB if any
/// bake r reads is.
inline std::size_t transfer_bytes(const Context& ctx, const Representation& r) {
    bool rgb = false;
    if (ctx.prepared)
        for (int b : r.mesh_bake)
            if (b >= 0)
                for (const PointResult& p : ctx.data[std::size_t(b)].results)
                    rgb = rgb || p.transfer_rgb;
    return (rgb ? 3 : 1) * std::size_t(ctx.settings.prt_bands) *
           std::size_t(ctx.settings.prt_bands) * sizeof(float);
}

class Prt : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        out.insert(out.end(), {"prt-vertex", "prt-texel"});
    }
    static bool accepts(const std::string& name) {
        return name == "prt-vertex" || name == "prt-texel";
    }
    Prt(const std::string& name, const Context& ctx)
        : Representation(name), texel_(name == "prt-texel") {
        const char* no_bounce = ctx.settings.bounces > 0 ? "" : "; no interreflection";
        cannot_show = "lighting above " + std::to_string(ctx.settings.prt_bands) +
                      " SH bands (sharp shadows of small lights); no normal-map detail" + no_bounce;
        if (!texel_) cannot_show += "; shadows finer than the vertex spacing";
        element = texel_ ? "texel" : "vertex";
        if (texel_)
            for (const MeshView& m : ctx.scene.meshes)
                if (!has_uvs(m)) {
                    element = "texel";
                    cannot_show += "; meshes without UVs read per-vertex transfer";
                    break;
                }
    }
    void plan(Context& ctx) override {
        ctx.needs_sh = true;  // the lighting's SH (ctx.sh.prt)
        mesh_bake =
            ctx.request_per_mesh(ctx.base_settings(Quantity::transfer, ctx.settings.bounces),
                                 texel_, ctx.settings.prt_bands);
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return {0, 0, 0};
        std::array<double, 3 * 64> t;
        lookup(ctx.fields[std::size_t(b)], hit, t.data());
        const std::size_t n = std::size_t(ctx.settings.prt_bands * ctx.settings.prt_bands);
        RGB out{0, 0, 0};
        for (std::size_t c = 0; c < 3; ++c)
            out[c] = hit.albedo[c] * transfer_dot(t.data() + c * n, ctx.sh.prt[c], n);
        return out;
    }
    void stats(const Context& ctx, RepresentationStats& s) const override {
        s.bytes_per_element = transfer_bytes(ctx, *this);
    }

  private:
    bool texel_ = false;
};

}  // namespace sphbasis::render::representations
