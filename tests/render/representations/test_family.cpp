// Tests of render/representations/family.hpp: every name belongs to exactly one family (so the
// family list of render/representation.hpp decides each name), the families beyond the listed
// names stop at their documented bounds, and work shared through Context::shared() is built
// once per key.
#include <catch2/catch.hpp>
#include <cstddef>
#include <set>
#include <string>

#include "../render_test_support.hpp"
#include "sphbasis/render/representation.hpp"

namespace {

using namespace sphbasis;

/// How many families of a FamilyList accept `name`.
template <class... F>
std::size_t claimants(render::representations::FamilyList<F...>, const std::string& name) {
    return (std::size_t(F::accepts(name) ? 1 : 0) + ...);
}

TEST_CASE("representation families: each name belongs to exactly one family", "[render]") {
    const auto& names = render::representation_names();
    CHECK(std::set<std::string>(names.begin(), names.end()).size() == names.size());
    for (const std::string& n : names) {
        INFO(n);
        CHECK(claimants(render::RepresentationFamilies{}, n) == 1);
        CHECK(render::Representations::known_name(n));
    }
    // Members beyond the listed names, at their bounds (lxh-pcaM: 1..36; prt-cpca-C-M:
    // C 1..4096, M 1..64), and names no family builds.
    for (const char* n : {"lxh-pca1", "lxh-pca36", "prt-cpca-1-1", "prt-cpca-4096-64"}) {
        INFO(n);
        CHECK(claimants(render::RepresentationFamilies{}, n) == 1);
    }
    for (const char* n : {"lxh-pca0", "lxh-pca37", "lxh-pca04", "lxh-unc5", "prt-cpca-0-1",
                          "prt-cpca-4097-1", "prt-cpca-1-65", "prt-cpca-4", "prt-normalmap-svd5",
                          "lightmap-sh16", "irradiance", "", "volume2"}) {
        INFO(n);
        CHECK(claimants(render::RepresentationFamilies{}, n) == 0);
        CHECK_FALSE(render::Representations::known_name(n));
    }
}

TEST_CASE("representation families: shared work is built once per kind and key", "[render]") {
    sphbasis_test::World w = sphbasis_test::sphere_on_plane_meshes();
    w.build();
    render::representations::Context ctx(w.desc, *w.rt, render::RepresentationSettings{});
    int builds = 0;
    const auto build = [&] { return ++builds; };
    double seconds = -1;
    const auto a = ctx.shared<int>("table", "3 3", build, &seconds);
    const auto b = ctx.shared<int>("table", "3 3", build);
    const auto c = ctx.shared<int>("table", "4 4", build);
    const auto d = ctx.shared<int>("other", "3 3", build);
    CHECK(builds == 3);
    CHECK(a == b);
    CHECK(*a == 1);
    CHECK(*c == 2);
    CHECK(*d == 3);
    CHECK(seconds >= 0);
    CHECK(ctx.shared_count("table") == 2);
    CHECK(ctx.shared_count("other") == 1);
    ctx.drop_shared();
    CHECK(ctx.shared_count("table") == 0);
    CHECK(*a == 1);  // what a representation holds outlives the drop
    // Equal requests are one bake.
    render::BakeRequest q;
    q.mesh = 1;
    CHECK(ctx.add_request(q) == 0);
    CHECK(ctx.add_request(q) == 0);
    q.mesh = 0;
    CHECK(ctx.add_request(q) == 1);
    CHECK(ctx.requests.size() == 2);
}

}  // namespace
