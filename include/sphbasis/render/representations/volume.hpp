// sphbasis render tier: the irradiance volume (representations/family.hpp):
//   volume                    irradiance-volume probes (render/probe_grid.hpp, SH radiance,
//                             3 bands) interpolated trilinearly at the hit, convolved with the
//                             clamped cosine at the normal.
// Reads the radiance at the probes (3 bands, bounces, lighting-dependent): the probe grid of
// RepresentationSettings, or 4 x 4 x 4 over the scene's bounding box.
// Greger, Shirley, Hubbard and Greenberg, "The Irradiance Volume" (IEEE CG&A 1998).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "family.hpp"

namespace sphbasis::render::representations {

/// Plans the bake every volume reads: the 3-band radiance at the probes of RepresentationSettings
/// (or 4 x 4 x 4 over the scene's bounding box), bounces, lighting-dependent; sets ctx.needs_sh
/// (the clamped-cosine factors ctx.sh.cosine9). Returns the request's index.
inline int plan_probe_radiance(Context& ctx) {
    ctx.needs_sh = true;
    BakeRequest q;
    q.where = BakeRequest::Where::probes;
    q.lighting_dependent = true;
    q.settings = ctx.base_settings(Quantity::radiance, ctx.settings.bounces);
    q.settings.bands = 3;
    if (ctx.settings.has_probes) {
        q.probes = ctx.settings.probes;
    } else {
        q.probes.lo = ctx.rt.bounds_min();
        q.probes.hi = ctx.rt.bounds_max();
        q.probes.counts = {4, 4, 4};
    }
    return ctx.add_request(q);
}

class Volume : public Representation {
  public:
    static void list(std::vector<std::string>& out) { out.push_back("volume"); }
    static bool accepts(const std::string& name) { return name == "volume"; }
    Volume(const std::string& name, const Context& ctx) : Representation(name) {
        element = "probe";
        bytes_per_element = 27 * sizeof(float);
        cannot_show =
            "static lighting (ignores the render-time rotation); shadows and occlusion finer "
            "than the probe spacing; light leaks where probes straddle walls" +
            std::string(ctx.settings.bounces > 0 ? "" : "; no interreflection");
    }
    void plan(Context& ctx) override { probe_bake = plan_probe_radiance(ctx); }
    RGB shade(const Context& ctx, const Hit& hit, const vec3<double>&, double) const override {
        const Field& f = ctx.fields[std::size_t(probe_bake)];
        std::array<double, 27> v;
        f.grid.interpolate_valid(f.probe_values.data(), 27, f.inside.data(), hit.position,
                                 v.data());
        std::array<std::array<double, 9>, 3> cc;
        for (std::size_t c = 0; c < 3; ++c)
            for (std::size_t k = 0; k < 9; ++k) cc[c][k] = ctx.sh.cosine9[k] * v[c * 9 + k];
        return sh_shade(cc, Scene::normal_mapped(hit), hit.albedo);
    }
};

}  // namespace sphbasis::render::representations
