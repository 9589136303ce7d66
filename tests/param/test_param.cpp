// Tests of the parameterizations' direction arguments (param/*.hpp) as users hold them:
// glm::vec3/dvec3 and Eigen::Vector3f/3d give what the component form gives.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <glm/glm.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/param/dual_orthographic.hpp>
#include <sphbasis/param/dual_paraboloid.hpp>
#include <sphbasis/param/latlong.hpp>
#include <sphbasis/param/octahedral.hpp>
#include <vector>

using namespace sphbasis;
using namespace sphbasis::param;

namespace {

/// The class methods at d against the component form at d's components converted to T.
template <class Map, class D>
void check_map(const Map& p, const D& d) {
    using T = decltype(p.direction_to_uv(0, 0, 0).u);
    const double x = double(component<0>(d)), y = double(component<1>(d)),
                 z = double(component<2>(d));
    const auto a = p.direction_to_uv(T(x), T(y), T(z));
    const auto b = p.direction_to_uv(d);
    CHECK(a.face == b.face);
    CHECK(a.u == b.u);
    CHECK(a.v == b.v);
    const auto fa = p.footprint(T(x), T(y), T(z));
    const auto fb = p.footprint(d);
    for (int k = 0; k < 4; ++k) {
        CHECK(fa.index[k] == fb.index[k]);
        CHECK(fa.weight[k] == fb.weight[k]);
    }
}

template <class D>
void check_all(const D& d) {
    check_map(LatLong<double>(8), d);
    check_map(Octahedral<float>(8), d);
    check_map(CubeMap<double>(8), d);
    check_map(DualParaboloid<float>(8), d);
    check_map(DualOrthographic<double>(8), d);
    using T = direction_scalar_t<D>;
    const T tx = component<0>(d), ty = component<1>(d), tz = component<2>(d);
    auto same2 = [](auto a, auto b) {
        CHECK(a.x == b.x);
        CHECK(a.y == b.y);
    };
    same2(latlong_to_square(d), latlong_to_square(tx, ty, tz));
    same2(octahedral_to_square(d), octahedral_to_square(tx, ty, tz));
    same2(paraboloid_to_square(d), paraboloid_to_square(tx, ty, tz));
    same2(orthographic_to_square(d), orthographic_to_square(tx, ty, tz));
    CHECK(square_to_latlong_pdf(d) == square_to_latlong_pdf(tx, ty, tz));
    CHECK(square_to_octahedral_pdf(d) == square_to_octahedral_pdf(tx, ty, tz));
    CHECK(square_to_paraboloid_pdf(d) == square_to_paraboloid_pdf(tx, ty, tz));
    CHECK(square_to_orthographic_pdf(d) == square_to_orthographic_pdf(tx, ty, tz));
    CHECK(square_to_cube_pdf(d) == square_to_cube_pdf(tx, ty, tz));
    const auto ca = cube_to_square(d), cb = cube_to_square(tx, ty, tz);
    CHECK(ca.face == cb.face);
    CHECK(ca.u == cb.u);
    // lookup() at a 3-vector.
    const LatLong<T> ll(4);
    std::vector<double> table(ll.texel_count());
    for (std::size_t k = 0; k < table.size(); ++k) table[k] = double(k);
    double va = 0, vb = 0;
    lookup(ll, table.data(), 1, tx, ty, tz, &va);
    lookup(ll, table.data(), 1, d, &vb);
    CHECK(va == vb);
}

}  // namespace

TEST_CASE("param: directions as glm and Eigen vectors", "[param]") {
    check_all(glm::vec3(0.36f, -0.48f, 0.8f));
    check_all(glm::dvec3(0.36, -0.48, 0.8));
    check_all(Eigen::Vector3f(0.36f, -0.48f, 0.8f));
    check_all(Eigen::Vector3d(0.36, -0.48, 0.8));
}
