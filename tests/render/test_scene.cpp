#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "render_shapes_for_tests.hpp"
#include "sphbasis/render/scene.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

TEST_CASE("render::Scene: hits, normals, barycentrics and albedo", "[render]") {
    auto quad = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1);
    quad.albedo = {0.25f, 0.5f, 0.75f};
    Scene s({quad.view()});
    CHECK(s.triangle_count() == 2);
    CHECK(s.degenerate_triangles() == 0);
    const Hit h = s.intersect({0.25, -0.5, 2}, {0, 0, -1});
    REQUIRE(h.valid);
    CHECK(h.mesh == 0);
    CHECK(h.t == Approx(2).epsilon(1e-6));
    CHECK(h.position.x == Approx(0.25).margin(1e-6));
    CHECK(h.position.y == Approx(-0.5).margin(1e-6));
    CHECK(h.position.z == Approx(0).margin(1e-6));
    CHECK(h.geometric_normal.z == Approx(1));
    CHECK(h.shading_normal.z == Approx(1));
    CHECK_FALSE(h.back_face);
    CHECK(h.albedo[0] == Approx(0.25));
    CHECK(h.albedo[2] == Approx(0.75));
    // From below: back face, normals flipped toward the ray.
    const Hit b = s.intersect({0.25, 0.5, -1}, {0, 0, 1});
    REQUIRE(b.valid);
    CHECK(b.back_face);
    CHECK(b.geometric_normal.z == Approx(-1));
    CHECK(b.shading_normal.z == Approx(-1));
    CHECK_FALSE(s.intersect({2, 2, 1}, {0, 0, -1}).valid);
    CHECK(s.occluded({0, 0, 1}, {0, 0, -1}));
    CHECK_FALSE(s.occluded({0, 0, 1}, {0, 0, -1}, 0.5));
    // Barycentrics reproduce the position.
    CHECK(h.u >= 0);
    CHECK(h.v >= 0);
    CHECK(h.u + h.v <= 1 + 1e-6);
}

TEST_CASE("render::Scene: albedo map, bilinear and wrapping", "[render]") {
    // 2x1 texture: left texel 0, right texel 1 (grey). Texel centres at u = 0.25 and 0.75.
    const float tex[2] = {0.f, 1.f};
    TextureView t{tex, 2, 1, 1};
    CHECK(Scene::texture(t, 0.25, 0.5)[0] == Approx(0));
    CHECK(Scene::texture(t, 0.75, 0.5)[0] == Approx(1));
    CHECK(Scene::texture(t, 0.5, 0.5)[0] == Approx(0.5));
    CHECK(Scene::texture(t, 0.0, 0.5)[1] == Approx(0.5));  // wraps between texel 1 and 0
    CHECK(Scene::texture(t, 1.25, 0.5)[2] == Approx(0));
}

TEST_CASE("render::Scene: can_occlude analysis", "[render]") {
    auto sphere = sphbasis_test::uv_sphere(0, 0, 0, 1, 12, 24);
    auto boxm = sphbasis_test::box(0, 0, 0, 1, 2, 3);
    auto open = sphbasis_test::box(0, 0, 0, 1, 1, 1, true);
    auto quad = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 2);
    {
        Scene s({sphere.view()});
        CHECK_FALSE(s.can_occlude());
        CHECK(s.unoccluded({0, 0, 1}, {0, 0, 1}));
        CHECK_FALSE(s.unoccluded({0, 0, 1.5}, {0, 0, -1}));  // faces the sphere
    }
    CHECK_FALSE(Scene({boxm.view()}).can_occlude());
    CHECK(Scene({open.view()}).can_occlude());
    CHECK(Scene({quad.view()}).can_occlude());
    CHECK(Scene({sphere.view(), boxm.view()}).can_occlude());
    CHECK_FALSE(Scene(std::vector<MeshView>{}).can_occlude());
    // A non-convex closed mesh: a box with one corner pushed in.
    auto dent = boxm;
    dent.positions[3 * 7 + 0] = 0.5f;
    dent.positions[3 * 7 + 1] = 1.0f;
    dent.positions[3 * 7 + 2] = 1.5f;
    CHECK(Scene({dent.view()}).can_occlude());
}

TEST_CASE("render::Scene: bad input and degenerate triangles", "[render]") {
    auto quad = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 1);
    auto bad = quad;
    bad.positions[4] = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("finite vertex positions"));
    bad = quad;
    bad.indices[2] = 99;
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("indices < vertex_count"));
    MeshView v = quad.view();
    v.positions = nullptr;
    CHECK_THROWS_AS(Scene({v}), std::invalid_argument);
    bad = quad;
    bad.albedo = {1.5f, 0, 0};
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("albedo in [0, 1]"));
    auto deg = sphbasis_test::quad_grid(-1, 1, -1, 1, 0, 2);    // vertices 0, 1, 2: one row
    deg.indices.insert(deg.indices.end(), {0, 0, 1, 0, 1, 2});  // repeated, collinear
    Scene s({deg.view()});
    CHECK(s.degenerate_triangles() == 2);
    CHECK(s.triangle_count() == 8);
    // Offsets scale with the scene.
    auto big = sphbasis_test::quad_grid(1e4, 1e4 + 2, 0, 2, 0, 1);
    CHECK(Scene({big.view()}).epsilon() > 100 * s.epsilon());
}

TEST_CASE("render::Scene: normals against the winding still face the ray (two-sided)", "[render]") {
    // The quad's winding gives +z, its vertex normals say -z (a file with mixed winding): from
    // either side both normals face the ray, and the bitangent (from the UVs: +y) is kept.
    Mesh q = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
    for (std::size_t i = 0; i < q.vertex_count(); ++i) q.normals[3 * i + 2] = -1;
    q.tangents.clear();
    const Scene s({q.view()});
    for (double side : {1.0, -1.0}) {
        const Hit h = s.intersect({0.2, 0.3, side}, {0, 0, -side});
        REQUIRE(h.valid);
        CHECK(h.back_face == (side < 0));
        CHECK(h.geometric_normal.z == Approx(side));
        CHECK(h.shading_normal.z == Approx(side));
        const vec3<double> n = h.shading_normal, t = h.tangent;
        const double by = h.bitangent_sign * (n.z * t.x - n.x * t.z);  // (n x t).y
        CHECK(by == Approx(1));
    }
}

TEST_CASE("render::Scene: UVs, tangent frames and normal maps at hits", "[render]") {
    // A quad in the xy plane, u along +x and v along +y: tangent +x, bitangent +y, sign +1.
    Mesh q = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
    // A 1x1 normal map tilting the normal 45 degrees toward the tangent: (1, 0, 1)/sqrt 2.
    const float s2 = static_cast<float>(0.5 + 0.5 / std::sqrt(2.0));
    std::vector<float> tex{s2, 0.5f, s2};
    q.normal_map = {tex.data(), 1, 1, 3};
    q.shininess = 32;
    q.specular = {0.1f, 0.2f, 0.3f};
    for (bool with_tangents : {true, false}) {
        Mesh m = q;
        if (!with_tangents) m.tangents.clear();
        Scene s({m.view()});
        const Hit h = s.intersect({0.5, -0.5, 1}, {0, 0, -1});
        REQUIRE(h.valid);
        REQUIRE(h.has_uv);
        CHECK(h.uv[0] == Approx(0.75).margin(1e-6));  // u = (x + 1) / 2
        CHECK(h.uv[1] == Approx(0.25).margin(1e-6));  // v = (y + 1) / 2
        CHECK(h.tangent.x == Approx(1).margin(1e-9));
        CHECK(h.bitangent_sign == 1);
        CHECK(h.shininess == 32);
        CHECK(h.specular[2] == Approx(0.3));
        REQUIRE(h.normal_map != nullptr);
        const auto n = Scene::normal_mapped(h);
        CHECK(n.x == Approx(std::sqrt(0.5)).margin(1e-6));
        CHECK(n.y == Approx(0).margin(1e-6));
        CHECK(n.z == Approx(std::sqrt(0.5)).margin(1e-6));
        const Hit v = s.intersect({0.5, -0.5, 1}, {0, 0, -1});
        CHECK(v.vertices[0] < m.vertex_count());
    }
    // A mirrored UV layout (u along -x) flips the handedness derived from the UVs.
    Mesh r = q;
    r.tangents.clear();
    for (std::size_t i = 0; i < r.vertex_count(); ++i) r.uvs[2 * i] = 1 - r.uvs[2 * i];
    Scene sr({r.view()});
    const Hit hr = sr.intersect({0.5, -0.5, 1}, {0, 0, -1});
    CHECK(hr.tangent.x == Approx(-1).margin(1e-9));
    CHECK(hr.bitangent_sign == -1);
    // Bad materials are errors.
    Mesh bad = q;
    bad.shininess = -1;
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("shininess"));
    bad = q;
    bad.normal_map.channels = 2;
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("normal map"));
    bad = q;
    tex[0] = std::numeric_limits<float>::quiet_NaN();
    CHECK_THROWS_WITH(Scene({bad.view()}), Catch::Contains("normal map texels"));
}
