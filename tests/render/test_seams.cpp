// render/seams.hpp: seam edges of a UV sphere and a box, and stitching their lightmaps.
#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/lightmap.hpp"
#include "sphbasis/render/seams.hpp"
#include "sphbasis/render/shapes.hpp"

using namespace sphbasis;
using namespace sphbasis::render;

namespace {

/// A smooth function of position (continuous across every seam, creases included).
double field(const vec3<double>& p) { return 0.8 * p.x + 0.5 * p.y - 0.3 * p.z + 0.2 * p.x * p.z; }

/// A lightmap of `field` at the texels' surface points, gutters dilated.
std::vector<float> field_map(const LightmapLayout& lay) {
    return assemble_lightmap(lay, 1, [&](std::size_t i, float* px) {
        px[0] = static_cast<float>(field(lay.samples[i].surface));
    });
}

}  // namespace

TEST_CASE("render::find_seams: a UV sphere's meridian and a box's chart edges", "[render]") {
    const Mesh sphere = shapes::sphere({0, 0, 0}, 1, 8, 16);
    const auto seams = find_seams(sphere.view());
    // The meridian u = 0 / u = 1 (one edge per ring band), plus the fans at the poles, whose
    // apex is one position with a u per segment.
    std::size_t meridian = 0;
    for (const SeamEdge& e : seams) {
        CHECK_FALSE(e.crease);
        const bool u0 = e.uv[0][0][0] == 0 && e.uv[0][1][0] == 0;
        const bool u1 = e.uv[1][0][0] == 1 && e.uv[1][1][0] == 1;
        const bool u0b = e.uv[1][0][0] == 0 && e.uv[1][1][0] == 0;
        const bool u1b = e.uv[0][0][0] == 1 && e.uv[0][1][0] == 1;
        if ((u0 && u1) || (u0b && u1b)) ++meridian;
    }
    CHECK(meridian >= 6);
    // A box: 12 edges between differently charted faces, all creases (flat face normals).
    const Mesh box = shapes::box({0, 0, 0}, {1, 0.5, 0.75});
    CHECK(find_seams(box.view()).empty());
    const auto box_seams = find_seams(box.view(), true);
    CHECK(box_seams.size() == 12);
    for (const SeamEdge& e : box_seams) CHECK(e.crease);
    // A quad grid has no seam.
    CHECK(find_seams(shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4).view()).empty());
}

TEST_CASE("render::stitch_seams: the sphere's seam and the box's edges agree after", "[render]") {
    struct Case {
        const char* name;
        Mesh mesh;
        int res;
        bool creases;
    };
    std::vector<Case> cases;
    cases.push_back({"sphere", shapes::sphere({0, 0, 0}, 1, 16, 32), 64, false});
    cases.push_back({"box", shapes::box({0, 0, 0}, {1, 0.5, 0.75}), 64, true});
    for (Case& c : cases) {
        INFO(c.name);
        const LightmapLayout lay = layout_lightmap(c.mesh.view(), c.res, c.res);
        std::vector<float> img = field_map(lay);
        const std::vector<float> baked = img;
        const auto seams = find_seams(c.mesh.view(), c.creases);
        REQUIRE(!seams.empty());
        // Before: the two sides read texels baked half a texel inside their charts; the field's
        // gradient (about 1 per unit) times a texel (about 0.05-0.1 units) apart.
        const double before = seam_jump(img.data(), c.res, c.res, 1, 1, seams);
        CHECK(before > 0.02);
        const SeamStats st = stitch_seams(img.data(), c.res, c.res, 1, 1, seams);
        CHECK(st.max_jump_before == Approx(before));
        CHECK(st.max_jump_after == Approx(seam_jump(img.data(), c.res, c.res, 1, 1, seams)));
        // After: the jump is a small fraction of what it was, the texels moved by at most
        // about the jump (corner texels of the box, read by two seams, somewhat more), and
        // only texels next to the seams moved.
        CHECK(st.max_jump_after < 0.03 * before);
        std::size_t moved = 0;
        for (std::size_t i = 0; i < img.size(); ++i) {
            CHECK(std::fabs(img[i] - baked[i]) <= 1.5 * before);
            moved += img[i] != baked[i] ? 1 : 0;
        }
        CHECK(moved <= st.texels);
        CHECK(moved > 0);
    }
}

TEST_CASE("render::stitch_seams: a baked sphere's seam agrees within the bake's noise",
          "[render][bake]") {
    // Sphere of radius 1 beside a wall y = 1.3: ao varies with longitude at the seam (u = 0,
    // the +x meridian, not a mirror plane of the scene), so the two sides' texels, half a texel
    // either side of the meridian, differ by the gradient before stitching.
    const Mesh sphere = shapes::sphere({0, 0, 0}, 1, 16, 32);
    const Mesh wall = shapes::quad({0, 1.3, 0}, {0, 0, 10}, {10, 0, 0}, 1);
    SceneDesc d;
    d.meshes = {sphere.view(), wall.view()};
    const int res = 64;
    const LightmapLayout lay = layout_lightmap(sphere.view(), res, res);
    // Only the texels near the seam are baked (columns within 3 of the image's sides).
    std::vector<BakePoint> pts;
    std::vector<std::size_t> which;
    for (std::size_t i = 0; i < lay.samples.size(); ++i)
        if (lay.samples[i].x < 3 || lay.samples[i].x >= res - 3) {
            pts.push_back(lay.samples[i].point);
            which.push_back(i);
        }
    BakeSettings s;
    s.quantities = Quantity::ao;
    s.rays = 4096;
    const auto r = Baker(d, s).bake(pts);
    std::vector<double> ao(lay.samples.size(), 0.0);
    double se = 0;
    for (std::size_t k = 0; k < pts.size(); ++k) {
        ao[which[k]] = r[k].ao;
        se = std::max(se, r[k].ao_stderr);
    }
    std::vector<float> img =
        assemble_lightmap(lay, 1, [&](std::size_t i, float* px) { px[0] = float(ao[i]); });
    const auto seams = find_seams(sphere.view());
    // The noise of a jump: a difference of two bilinear means of texels with errors <= se.
    const double noise = 2 * se;
    const SeamStats st = stitch_seams(img.data(), res, res, 1, 1, seams);
    INFO("before " << st.max_jump_before << ", after " << st.max_jump_after << ", se " << se);
    CHECK(st.max_jump_before > 3 * noise);
    CHECK(st.max_jump_after < noise);
}

TEST_CASE("render::stitch_seams: bad input", "[render]") {
    std::vector<float> img(16, 0.0f);
    const std::vector<SeamEdge> none;
    CHECK_THROWS_WITH(stitch_seams(img.data(), 0, 4, 1, 1, none), Catch::Contains("width"));
    CHECK_THROWS_WITH(stitch_seams(img.data(), 4, 4, 1, 2, none), Catch::Contains("stitched"));
    SeamOptions o;
    o.weight = -1;
    CHECK_THROWS_WITH(stitch_seams(img.data(), 4, 4, 1, 1, none, o), Catch::Contains("weight"));
    Mesh m = shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
    m.uvs.clear();
    CHECK_THROWS_WITH(find_seams(m.view()), Catch::Contains("UVs"));
    // No seams: nothing changes.
    const SeamStats st = stitch_seams(img.data(), 4, 4, 1, 1, none);
    CHECK(st.points == 0);
    CHECK(st.max_jump_after == 0);
}
