// sphbasis render tier: the SH-irradiance family of representations (representations/
// family.hpp), shaded as albedo(hit) / pi * E with the normal-mapped normal
// (Scene::normal_mapped):
//   irradiance-sh9            unshadowed SH irradiance of the distant lighting (environment +
//                             analytic lights projected on 3 bands; Ramamoorthi and Hanrahan,
//                             "An Efficient Representation for Irradiance Environment Maps",
//                             SIGGRAPH 2001); no bake.
//   irradiance-sh9-windowed   the same with the lighting windowed (ops/sh_windowing.hpp).
//   ao                        ao x irradiance-sh9 (ao baked per texel, per vertex without UVs).
//   bent                      ao x the SH irradiance at the bent normal.
// ao and bent read one bake (ao | bent, no bounces); a mesh without triangles shows
// irradiance-sh9.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "family.hpp"

namespace sphbasis::render::representations {

class Irradiance : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        out.insert(out.end(), {"irradiance-sh9", "irradiance-sh9-windowed", "ao", "bent"});
    }
    static bool accepts(const std::string& name) {
        return name == "irradiance-sh9" || name == "irradiance-sh9-windowed" || name == "ao" ||
               name == "bent";
    }
    Irradiance(const std::string& name, const Context& ctx) : Representation(name) {
        if (name == "irradiance-sh9") {
            mode_ = Mode::irradiance;
            cannot_show =
                "no shadows; no interreflection; lighting truncated to 3 SH bands (small lights "
                "blurred, ringing)";
        } else if (name == "irradiance-sh9-windowed") {
            mode_ = Mode::windowed;
            cannot_show =
                "no shadows; no interreflection; lighting truncated to 3 SH bands and windowed "
                "(no ringing, more blur)";
        } else {
            mode_ = name == "ao" ? Mode::ao : Mode::bent;
            cannot_show = name == "ao"
                              ? "no directional shadows (occlusion ignores where the light is); "
                                "no interreflection"
                              : "shadows only as one bent direction and the ao fraction; no "
                                "interreflection; no normal-map detail";
            element = texel_or_vertex(ctx);
            bytes_per_element = (mode_ == Mode::ao ? 1 : 4) * sizeof(float);
        }
    }
    void plan(Context& ctx) override {
        ctx.needs_sh = true;
        if (mode_ == Mode::ao || mode_ == Mode::bent)
            mesh_bake =
                ctx.request_per_mesh(ctx.base_settings(Quantity::ao | Quantity::bent, 0), true);
    }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        if (mode_ == Mode::irradiance)
            return sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        if (mode_ == Mode::windowed)
            return sh_shade(ctx.sh.irr_windowed, Scene::normal_mapped(hit), hit.albedo);
        const int b = mesh_bake[hit.mesh];
        if (b < 0) return sh_shade(ctx.sh.irr, Scene::normal_mapped(hit), hit.albedo);
        double v[4];
        lookup(ctx.fields[std::size_t(b)], hit, v);
        const vec3<double> n = mode_ == Mode::ao
                                   ? Scene::normal_mapped(hit)
                                   : detail::rt::normalized({v[1], v[2], v[3]}, hit.shading_normal);
        const RGB c = sh_shade(ctx.sh.irr, n, hit.albedo);
        const double ao = std::clamp(v[0], 0.0, 1.0);
        return {ao * c[0], ao * c[1], ao * c[2]};
    }

  private:
    enum class Mode { irradiance, windowed, ao, bent } mode_ = Mode::irradiance;
};

}  // namespace sphbasis::render::representations
