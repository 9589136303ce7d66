// Tests of param/octahedral.hpp: the octahedral map, its exact texel solid angles, and
// bilinear filtering with clamp-to-edge or across the folded border (seamless).
#include <sphbasis/param/octahedral.hpp>

#include "param_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

namespace {
// The four folded border arcs (x = 0 or y = 0 with z < 0) with normals across them, and the
// lower pole, approached from all sides.
void border(std::vector<vec3<double>>& base, std::vector<vec3<double>>& normal) {
    for (int k = 0; k < 101; ++k) {
        const double a = 3.141592653589793 / 2 * (k + 0.29) / 101;  // from the equator to -z
        for (double s : {-1.0, 1.0}) {
            base.push_back({s * std::cos(a), 0.0, -std::sin(a)});
            normal.push_back({0.0, 1.0, 0.0});
            base.push_back({0.0, s * std::cos(a), -std::sin(a)});
            normal.push_back({1.0, 0.0, 0.0});
        }
    }
    for (int k = 0; k < 16; ++k) {
        const double phi = 2 * 3.141592653589793 * (k + 0.1) / 16;
        base.push_back({0.0, 0.0, -1.0});
        normal.push_back({std::cos(phi), std::sin(phi), 0.0});
    }
}
}  // namespace

TEMPLATE_TEST_CASE("octahedral: round trips incl. folds and the lower pole", "[param][octahedral]",
                   float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-6 : 1e-14;
    for (int n : {1, 2, 5, 16}) {
        for (OctahedralFilter f : {OctahedralFilter::clamp, OctahedralFilter::seamless}) {
            check_map_round_trips<T>(Octahedral<T>(n, f), tol);
        }
    }
    // The lower pole is every corner of the square.
    for (T u : {T(0), T(1)})
        for (T v : {T(0), T(1)}) {
            const auto d = square_to_octahedral(u, v);
            CHECK(d.z == Approx(-1.0));
        }
    const auto t = octahedral_to_square(T(0), T(0), T(-1));
    CHECK(t.x == T(1));
    CHECK(t.y == T(1));
}

TEST_CASE("octahedral: uv -> direction -> uv inside the square", "[param][octahedral]") {
    for (int j = 1; j < 60; ++j)
        for (int i = 1; i < 60; ++i) {
            const double u = i / 60.0, v = j / 60.0;
            const auto d = square_to_octahedral(u, v);
            const auto s = octahedral_to_square(d.x, d.y, d.z);
            CHECK(s.x == Approx(u).margin(1e-14));
            CHECK(s.y == Approx(v).margin(1e-14));
        }
    // On the border, (0, v) and (0, 1 - v) are the same direction (the fold).
    for (int k = 0; k <= 20; ++k) {
        const double v = k / 20.0;
        CHECK(angle_between(square_to_octahedral(0.0, v), square_to_octahedral(0.0, 1 - v)) <
              1e-15);
        CHECK(angle_between(square_to_octahedral(v, 1.0), square_to_octahedral(1 - v, 1.0)) <
              1e-15);
    }
}

TEST_CASE("octahedral: texel solid angles", "[param][octahedral]") {
    const double pi = 3.141592653589793;
    const Octahedral<double> one(1), two(2);
    CHECK(one.texel_solid_angle(0, 0, 0) == Approx(4 * pi).epsilon(1e-14));
    for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) CHECK(two.texel_solid_angle(0, c, r) == Approx(pi));
    for (int n : {1, 3, 8, 63, 128})
        CHECK(total_solid_angle(Octahedral<double>(n)) == Approx(4 * pi).epsilon(1e-13));
    for (int n : {1, 3, 4, 7}) check_texel_solid_angles(Octahedral<double>(n), 0, 1, 24, 1e-6);
    CHECK(total_solid_angle(Octahedral<float>(32)) == Approx(4 * pi).epsilon(1e-6));
}

TEST_CASE("octahedral: pdf integrates to one and is 1/|Jacobian|", "[param][octahedral]") {
    const double integral = integrate_sphere(
        [](double x, double y, double z) { return square_to_octahedral_pdf(x, y, z); }, false,
        1000);
    CHECK(integral == Approx(1.0).epsilon(1e-5));
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    for (int k = 0; k < 2000; ++k) {
        const double u = U(rng), v = U(rng);
        const double a = std::fabs(2 * u - 1), b = std::fabs(2 * v - 1);
        if (a < 1e-4 || b < 1e-4 || std::fabs(a + b - 1) < 1e-4) continue;  // the kinks
        const double jac =
            jacobian([](double s, double t) { return square_to_octahedral(s, t); }, u, v, 1e-7);
        const auto d = square_to_octahedral(u, v);
        CHECK(square_to_octahedral_pdf(d.x, d.y, d.z) * jac == Approx(1.0).epsilon(1e-6));
    }
}

TEST_CASE("octahedral: seamless filtering is continuous across the folded border, clamp is not",
          "[param][octahedral]") {
    std::vector<vec3<double>> base, normal;
    border(base, normal);
    for (int n : {2, 8, 33}) {
        const Octahedral<double> ps(n, OctahedralFilter::seamless);
        const double js = max_jump(ps, smooth_table<double>(ps), base, normal, 1e-10);
        INFO("n " << n << " seamless jump " << js);
        CHECK(js < 1e-7);
        check_interpolates_at_centres(ps, 1e-12);
        const Octahedral<double> pc(n, OctahedralFilter::clamp);
        const double jc = max_jump(pc, smooth_table<double>(pc), base, normal, 1e-10);
        INFO("n " << n << " clamp jump " << jc);
        CHECK(jc > 1e-3);
        check_interpolates_at_centres(pc, 1e-12);
    }
    // A tap beyond the left border reads the mirrored texel (0, n - 1 - row).
    const int n = 8;
    const Octahedral<double> p(n);
    for (int row = 0; row < n; ++row) {
        const auto d = square_to_octahedral(0.2 / n, (row + 0.6) / n);  // x = -0.3, y = row + 0.1
        const auto fp = p.footprint(d.x, d.y, d.z);
        CHECK(fp.index[0] == p.texel_index(0, 0, n - 1 - row));  // the tap at column -1
        CHECK(fp.index[1] == p.texel_index(0, 0, row));
        CHECK(fp.weight[0] == Approx(0.3 * 0.9));
    }
}

TEST_CASE("octahedral: convergence", "[param][octahedral]") {
    check_seam_convergence(Octahedral<double>(16), Octahedral<double>(32),
                           Octahedral<double>(16, OctahedralFilter::clamp),
                           Octahedral<double>(32, OctahedralFilter::clamp), "seamless", "clamp");
}

TEST_CASE("octahedral: bad input", "[param][octahedral]") {
    REQUIRE_THROWS_WITH(Octahedral<double>(40000),
                        Catch::Contains("sphbasis::param::Octahedral(): expected 1 <= resolution"));
}
