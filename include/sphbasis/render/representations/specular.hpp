// sphbasis render tier: the specular representations (representations/family.hpp):
//   specular-toksvig, specular-aliased
//                             Blinn-Phong specular of the scene's directional lights from the
//                             mipmapped normal map with and without the Toksvig factor
//                             (render/specular.hpp); compared with render_specular_reference()
//                             of specular.hpp, not with the path tracer.
// No bakes; both share one SpecularShading (the mip chains).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "../specular.hpp"
#include "family.hpp"

namespace sphbasis::render::representations {

class Specular : public Representation {
  public:
    static void list(std::vector<std::string>& out) {
        out.insert(out.end(), {"specular-toksvig", "specular-aliased"});
    }
    static bool accepts(const std::string& name) {
        return name == "specular-toksvig" || name == "specular-aliased";
    }
    Specular(const std::string& name, const Context&)
        : Representation(name),
          mode_(name == "specular-toksvig" ? SpecularShading::Mode::toksvig
                                           : SpecularShading::Mode::aliased) {
        cannot_show =
            "specular of the directional lights only (no diffuse, no environment, no shadows)";
    }
    void plan(Context& ctx) override {
        shading_ =
            ctx.shared<SpecularShading>("specular", "", [&] { return SpecularShading(ctx.scene); });
    }
    RGB shade(const Context&, const Hit& hit, const vec3<double>& view,
              double footprint) const override {
        return shading_->shade(mode_, hit, view, footprint);
    }

  private:
    SpecularShading::Mode mode_;
    std::shared_ptr<const SpecularShading> shading_;
};

}  // namespace sphbasis::render::representations
