// Tests of param/dual_paraboloid.hpp: the dual paraboloid map through the concentric map,
// shrunk so the equator lies on the outer ring of texel centres (Iwanicki and Sloan,
// "Normal Mapping with Low-Frequency Precomputed Visibility", JGT 2009, appendix A).
#include <sphbasis/param/dual_paraboloid.hpp>

#include "dual_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

TEMPLATE_TEST_CASE("dual paraboloid: round trips incl. poles and equator",
                   "[param][dual_paraboloid]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 2e-6 : 1e-13;
    for (int n : {2, 3, 8, 33}) check_map_round_trips<T>(DualParaboloid<T>(n), tol, false);
}

TEMPLATE_TEST_CASE("dual paraboloid: equator on the outer ring of texel centres",
                   "[param][dual_paraboloid]", float, double) {
    for (int n : {2, 5, 16})
        check_equator_on_outer_ring(DualParaboloid<TestType>(n),
                                    sizeof(TestType) == 4 ? 1e-6 : 1e-12);
}

TEST_CASE("dual paraboloid: uv -> direction -> uv away from the redundant ring",
          "[param][dual_paraboloid]") {
    check_uv_round_trip_inside(DualParaboloid<double>(16));
}

TEST_CASE("dual paraboloid: texel solid angles", "[param][dual_paraboloid]") {
    check_dual_solid_angles<DualParaboloid>(
        [](double R) { return 4 * 3.141592653589793 * R * R / (1 + R * R); }, 1e-6);
}

TEST_CASE("dual paraboloid: pdf integrates to one and is 1/|Jacobian|",
          "[param][dual_paraboloid]") {
    check_hemisphere_pdf(
        [](double u, double v) { return square_to_paraboloid(u, v); },
        [](double x, double y, double z) { return square_to_paraboloid_pdf(x, y, z); },
        [](double x, double y, double z) { return paraboloid_to_square(x, y, z); });
}

TEST_CASE("dual paraboloid: reconstruction", "[param][dual_paraboloid]") {
    // Bilinear reconstruction of a smooth function converges at second order: MSE ~ h^4.
    check_dual_reconstruction<DualParaboloid>(10);
}

TEST_CASE("dual paraboloid: bad input", "[param][dual_paraboloid]") {
    check_dual_bad_input<DualParaboloid>("DualParaboloid");
}
