// The probe-volume scene of the engine-basis volume tests: probes (2 x 2 x 2 over
// [-1, 1]^2 x [0.25, 1.25]) above a wide ground under a constant sky L = (1, 0.5, 0.25), no
// bounces. Each probe sees radiance L over its upper hemisphere, so E(n)/pi = L (1 + n_z)/2
// (exactly in 3 SH bands: the step's band 2 vanishes), which `volume` shades; a volume storing
// its least-squares fit over the sphere in another basis shows, at n = +z, the fit's value there.
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "../render_test_support.hpp"
#include "sphbasis/render/representation.hpp"

namespace sphbasis_test {

struct SkyProbesResult {
    double worst;  // max over pixels of |image / (volume's image * at_z) - 1|
    sphbasis::render::RepresentationStats stats;  // the compared representation's
};

/// Renders `volume` and `name` (a volume-* representation) of the scene above and compares
/// `name`'s image with volume's times at_z, the fit's value at +z.
inline SkyProbesResult volume_against_sh(const std::string& name, double at_z) {
    namespace render = sphbasis::render;
    World w;
    w.meshes.push_back(quad_grid(-100, 100, -100, 100, 0, 1));
    w.meshes[0].albedo = {0.8f, 0.8f, 0.8f};
    w.desc.environment = constant_environment({1.0, 0.5, 0.25});
    w.build();
    render::RepresentationSettings s;
    s.rays = 512;
    s.bounces = 0;
    s.has_probes = true;
    s.probes.lo = {-1, -1, 0.25};
    s.probes.hi = {1, 1, 1.25};
    s.probes.counts = {2, 2, 2};
    render::Representations r(w.desc, *w.rt, s, {"volume", name});
    r.prepare(nullptr);
    const render::Camera cam = camera_at({0.1, 0.2, 3}, {0, 0, 0}, 8, 8, 25);
    const render::Image sh = r.render(0, cam, 1), other = r.render(1, cam, 1);
    double worst = 0;
    for (std::size_t i = 0; i < sh.data.size(); ++i)
        worst = std::max(worst, std::fabs(other.data[i] / (sh.data[i] * at_z) - 1));
    return {worst, r.stats(1)};
}

}  // namespace sphbasis_test
