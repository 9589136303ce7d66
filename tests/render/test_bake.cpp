#include "sphbasis/render/bake.hpp"

#include <catch2/catch.hpp>

#include "render_shapes_for_tests.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

TEST_CASE("render::Baker: compiles", "[render]") {
    auto sphere = sphbasis_test::uv_sphere(0, 0, 0, 1, 12, 24);
    SceneDesc d;
    d.meshes = {sphere.view()};
    BakeSettings s;
    s.quantities = Quantity::ao | Quantity::transfer;
    Baker b(d, s);
    auto r = b.bake({BakePoint{{0, 0, 1}, {0, 0, 1}, {0, 0, 0}, 0}});
    CHECK(r[0].ao == 1);
}
