// Tests of param/dual_orthographic.hpp: the dual orthographic map through the concentric map,
// shrunk so the equator lies on the outer ring of texel centres (Iwanicki and Sloan,
// "Normal Mapping with Low-Frequency Precomputed Visibility", JGT 2009, appendix A).
// The orthographic lift z = sqrt(1 - r^2) is ill-conditioned at the equator: (u, v) carries r,
// and an error eps in r becomes sqrt(2 eps) in z there, so round trips are only good to
// sqrt(2 eps) radians in the worst case (about 2e-8 in double, 5e-4 in float).
#include <sphbasis/param/dual_orthographic.hpp>

#include "dual_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

TEMPLATE_TEST_CASE("dual orthographic: round trips incl. poles and equator",
                   "[param][dual_orthographic]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-3 : 3e-8;
    for (int n : {2, 3, 8, 33}) check_map_round_trips<T>(DualOrthographic<T>(n), tol, false);
}

TEMPLATE_TEST_CASE("dual orthographic: equator on the outer ring of texel centres",
                   "[param][dual_orthographic]", float, double) {
    for (int n : {2, 5, 16})
        check_equator_on_outer_ring(DualOrthographic<TestType>(n),
                                    sizeof(TestType) == 4 ? 1e-3 : 1e-7);
}

TEST_CASE("dual orthographic: uv -> direction -> uv away from the redundant ring",
          "[param][dual_orthographic]") {
    check_uv_round_trip_inside(DualOrthographic<double>(16));
}

TEST_CASE("dual orthographic: texel solid angles", "[param][dual_orthographic]") {
    check_dual_solid_angles<DualOrthographic>(
        [](double R) { return 2 * 3.141592653589793 * (1 - std::sqrt(1 - R * R)); }, 2e-3);
}

TEST_CASE("dual orthographic: pdf integrates to one and is 1/|Jacobian|",
          "[param][dual_orthographic]") {
    check_hemisphere_pdf(
        [](double u, double v) { return square_to_orthographic(u, v); },
        [](double x, double y, double z) { return square_to_orthographic_pdf(x, y, z); },
        [](double x, double y, double z) { return orthographic_to_square(x, y, z); });
}

TEST_CASE("dual orthographic: reconstruction", "[param][dual_orthographic]") {
    // Bilinear reconstruction of a smooth function converges at second order: MSE ~ h^4.
    // Only first order: the orthographic lift z = sqrt(1 - r^2) has an infinite slope at the
    // equator, so bilinear interpolation in r is off by O(sqrt(h)) on the outer ring of width h
    // and the MSE falls as ~h^2 (measured ratio 3.2 per halving of h).
    check_dual_reconstruction<DualOrthographic>(2.5);
}

TEST_CASE("dual orthographic: bad input", "[param][dual_orthographic]") {
    check_dual_bad_input<DualOrthographic>("DualOrthographic");
}
