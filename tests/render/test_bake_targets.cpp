// The bake targets agree: a lightmap texel baked at its sample point gives what the vertex bake
// interpolates there, on a finely tessellated quad under a hovering sphere (Hill, "Hardware
// Accelerating Art Production", Gamasutra 2004: per-vertex against per-texel baking).
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/bake_points.hpp"
#include "sphbasis/render/lightmap.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

TEST_CASE("bake targets: per-texel ao equals per-vertex ao interpolated, on a fine quad",
          "[render][bake]") {
    // A 2 x 2 quad of 32 x 32 cells at z = 0 and a sphere of radius 0.3 at height 0.5.
    const Mesh plane = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 32);
    const Mesh ball = shapes::sphere({0, 0, 0.5}, 0.3, 16, 32);
    SceneDesc scene;
    scene.meshes = {plane.view(), ball.view()};
    BakeSettings settings;
    settings.quantities = Quantity::ao;
    settings.rays = 1024;
    Baker baker(scene, settings);

    const std::vector<PointResult> at_vertices = baker.bake(vertex_points(scene.meshes, 0));

    const LightmapLayout layout = texel_layout(scene.meshes, 0, 24);
    REQUIRE(layout.samples.size() == 24u * 24u);  // the quad's UVs cover the whole map
    const std::vector<PointResult> at_texels = baker.bake(texel_points(layout));

    // Interpolation error of ao over a cell of 1/16 at this height is below 2e-3; the Monte
    // Carlo error of the difference is about sqrt(2) x the standard errors.
    int beyond = 0;
    double worst = 0;
    for (std::size_t i = 0; i < layout.samples.size(); ++i) {
        const LightmapSample& s = layout.samples[i];
        double interpolated = 0, se2 = 0;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t v = plane.indices[3 * s.triangle + static_cast<std::uint32_t>(k)];
            interpolated += s.barycentric[std::size_t(k)] * at_vertices[v].ao;
            se2 +=
                s.barycentric[std::size_t(k)] * at_vertices[v].ao_stderr * at_vertices[v].ao_stderr;
        }
        const double diff = std::fabs(at_texels[i].ao - interpolated);
        const double tol =
            4 * std::sqrt(se2 + at_texels[i].ao_stderr * at_texels[i].ao_stderr) + 2e-3;
        worst = std::max(worst, diff);
        if (diff > tol) ++beyond;
    }
    INFO("largest |texel - interpolated vertex| = " << worst);
    CHECK(beyond <= 2);  // 4 standard errors: about 0.01% each by chance
    CHECK(worst < 0.03);
}
