// Tests of param/cubemap.hpp: face selection (GL/D3D table), solid angles, DX9 clamped and DX10
// seamless bilinear filtering (the seam texels against a brute-force nearest-texel search, the
// corner rule, continuity across every edge).
#include <set>
#include <sphbasis/param/cubemap.hpp>

#include "param_checks.hpp"

using namespace sphbasis::param;
using namespace sphbasis_test;

namespace {

// The GL table 8.19 retyped: face point for face coordinates (sc, tc).
vec3<double> gl_face_point(int face, double sc, double tc) {
    switch (face) {
        case 0:
            return {1, -tc, -sc};  // +X: sc = -rz, tc = -ry
        case 1:
            return {-1, -tc, sc};  // -X: sc = +rz, tc = -ry
        case 2:
            return {sc, 1, tc};  // +Y: sc = +rx, tc = +rz
        case 3:
            return {sc, -1, -tc};  // -Y: sc = +rx, tc = -rz
        case 4:
            return {sc, -tc, 1};  // +Z: sc = +rx, tc = -ry
        default:
            return {-sc, -tc, -1};  // -Z: sc = -rx, tc = -ry
    }
}

// All 12 cube edges as (point on the edge at parameter t, unit normal across the edge).
void cube_edges(std::vector<vec3<double>>& base, std::vector<vec3<double>>& normal, int per_edge) {
    for (int a = 0; a < 3; ++a)
        for (int b = a + 1; b < 3; ++b)
            for (double sa : {-1.0, 1.0})
                for (double sb : {-1.0, 1.0})
                    for (int k = 0; k < per_edge; ++k) {
                        const double t = -1 + 2 * (k + 0.31) / per_edge;
                        double p[3] = {t, t, t}, n[3] = {0, 0, 0};
                        p[a] = sa;
                        p[b] = sb;
                        n[a] = sa / std::sqrt(2.0);
                        n[b] = -sb / std::sqrt(2.0);
                        base.push_back(normalized<double>(p[0], p[1], p[2]));
                        normal.push_back({n[0], n[1], n[2]});
                    }
}

}  // namespace

TEMPLATE_TEST_CASE("cube map: round trips incl. edges and corners", "[param][cubemap]", float,
                   double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-6 : 1e-14;
    for (int n : {1, 2, 5, 16}) {
        for (CubeFilter f : {CubeFilter::dx9_clamped, CubeFilter::dx10_seamless}) {
            check_map_round_trips<T>(CubeMap<T>(n, f), tol);
        }
    }
}

TEST_CASE("cube map: face selection follows the GL/D3D table", "[param][cubemap]") {
    const double sc = -0.4, tc = 0.2;
    for (int face = 0; face < 6; ++face) {
        const auto d = gl_face_point(face, sc, tc);
        const auto t = cube_to_square(d.x, d.y, d.z);
        CHECK(t.face == face);
        CHECK(t.u == Approx(0.5 * (sc + 1)));
        CHECK(t.v == Approx(0.5 * (tc + 1)));
        const auto back = square_to_cube(face, t.u, t.v);
        CHECK(angle_between(back, normalized<double>(d.x, d.y, d.z)) < 1e-15);
    }
    // Ties: x wins over y and z, y over z.
    CHECK(cube_to_square(1.0, 1.0, 1.0).face == 0);
    CHECK(cube_to_square(0.0, -1.0, 1.0).face == 3);
}

TEST_CASE("cube map: texel solid angles", "[param][cubemap]") {
    const double pi = 3.141592653589793;
    const CubeMap<double> one(1);
    for (int f = 0; f < 6; ++f) CHECK(one.texel_solid_angle(f, 0, 0) == Approx(4 * pi / 6));
    for (int n : {1, 2, 7, 64, 255}) {
        const CubeMap<double> p(n, CubeFilter::dx9_clamped);
        CHECK(total_solid_angle(p) == Approx(4 * pi).epsilon(1e-12));
    }
    for (int n : {2, 5}) check_texel_solid_angles(CubeMap<double>(n), 0, 1, 16, 1e-8);
    CHECK(total_solid_angle(CubeMap<float>(32)) == Approx(4 * pi).epsilon(1e-6));
}

TEST_CASE("cube map: pdf integrates to one and is 1/(6 |Jacobian|)", "[param][cubemap]") {
    const double integral = integrate_sphere(
        [](double x, double y, double z) { return square_to_cube_pdf(x, y, z); }, false, 1000);
    CHECK(integral == Approx(1.0).epsilon(1e-5));
    std::mt19937 rng(6);
    std::uniform_real_distribution<double> U(0.01, 0.99);
    for (int face = 0; face < 6; ++face)
        for (int k = 0; k < 200; ++k) {
            const double u = U(rng), v = U(rng);
            const double jac = jacobian(
                [face](double a, double b) { return square_to_cube(face, a, b); }, u, v, 1e-6);
            const auto d = square_to_cube(face, u, v);
            CHECK(square_to_cube_pdf(d.x, d.y, d.z) * 6 * jac == Approx(1.0).epsilon(1e-6));
        }
}

TEST_CASE("cube map: DX10 seam texels are the nearest texels across the edge", "[param][cubemap]") {
    for (int n : {1, 2, 3, 6}) {
        const CubeMap<double> p(n, CubeFilter::dx10_seamless);
        for (int face = 0; face < 6; ++face)
            for (int k = 0; k < n; ++k)
                for (int edge = 0; edge < 4; ++edge) {
                    // A direction a quarter texel inside the edge, on the centre line of texel k.
                    const double in = 0.25 / n, along = (k + 0.5) / n;
                    double u = edge == 0 ? in : (edge == 1 ? 1 - in : along);
                    double v = edge == 2 ? in : (edge == 3 ? 1 - in : along);
                    const auto d = square_to_cube(face, u, v);
                    const auto fp = p.footprint(d.x, d.y, d.z);
                    // The virtual texel beyond the edge, and the texel of another face nearest it.
                    const int vi = edge == 0 ? -1 : (edge == 1 ? n : k);
                    const int vj = edge == 2 ? -1 : (edge == 3 ? n : k);
                    const auto vp =
                        gl_face_point(face, 2.0 * (vi + 0.5) / n - 1, 2.0 * (vj + 0.5) / n - 1);
                    const auto vd = normalized<double>(vp.x, vp.y, vp.z);
                    std::size_t best = 0;
                    double best_angle = 10;
                    for (int f2 = 0; f2 < 6; ++f2) {
                        if (f2 == face) continue;
                        for (int r = 0; r < n; ++r)
                            for (int c = 0; c < n; ++c) {
                                const double a = angle_between(vd, p.texel_direction(f2, c, r));
                                if (a < best_angle) best_angle = a, best = p.texel_index(f2, c, r);
                            }
                    }
                    // Texels of the footprint on other faces must be that texel (the taps of
                    // the neighbouring row carry a weight of rounding size only).
                    int found = 0;
                    for (int t = 0; t < 4; ++t) {
                        if (fp.weight[t] <= 1e-3) continue;
                        const std::size_t idx = fp.index[t];
                        if (idx / (std::size_t(n) * std::size_t(n)) == std::size_t(face)) continue;
                        CHECK(idx == best);
                        ++found;
                    }
                    CHECK(found >= 1);
                }
    }
}

TEST_CASE("cube map: DX10 corner averages the three corner texels", "[param][cubemap]") {
    for (int n : {1, 4, 9}) {
        const CubeMap<double> p(n);
        for (double sx : {-1.0, 1.0})
            for (double sy : {-1.0, 1.0})
                for (double sz : {-1.0, 1.0}) {
                    const auto fp = p.footprint(sx, sy, sz);
                    std::set<std::size_t> texels;
                    for (int t = 0; t < 4; ++t)
                        if (fp.weight[t] > 0) texels.insert(fp.index[t]);
                    CHECK(texels.size() == 3);
                    for (std::size_t idx : texels) {
                        double w = 0;
                        for (int t = 0; t < 4; ++t)
                            if (fp.index[t] == idx) w += fp.weight[t];
                        CHECK(w == Approx(1.0 / 3));
                        const std::size_t nn = std::size_t(n) * std::size_t(n);
                        const int f = int(idx / nn);
                        const int r = int(idx % nn) / n, c = int(idx % std::size_t(n));
                        const double a = angle_between(p.texel_direction(f, c, r),
                                                       normalized<double>(sx, sy, sz));
                        CHECK(a < 1.6 / n);  // one of the texels touching the corner
                    }
                }
    }
}

TEST_CASE("cube map: DX10 is continuous across edges and corners, DX9 is not", "[param][cubemap]") {
    std::vector<vec3<double>> base, normal;
    cube_edges(base, normal, 37);
    for (int n : {1, 4, 16}) {
        const CubeMap<double> p10(n, CubeFilter::dx10_seamless);
        const double j10 = max_jump(p10, smooth_table<double>(p10), base, normal, 1e-10);
        INFO("n " << n << " DX10 jump " << j10);
        CHECK(j10 < 1e-7);
        const CubeMap<double> p9(n, CubeFilter::dx9_clamped);
        const double j9 = max_jump(p9, smooth_table<double>(p9), base, normal, 1e-10);
        INFO("n " << n << " DX9 jump " << j9);
        CHECK(j9 > 1e-3);  // the seams Iwanicki and Sloan (JGT 2009) warn about
    }
    // Corners: approached along the three edges that meet there.
    const CubeMap<double> p(8);
    const auto table = smooth_table<double>(p);
    double corner[2];
    lookup(p, table.data(), 2, 1.0, 1.0, 1.0, corner);
    for (const auto& d :
         {normalized<double>(1, 1 - 1e-9, 1 - 1e-9), normalized<double>(1 - 1e-9, 1, 1 - 1e-9),
          normalized<double>(1 - 1e-9, 1 - 1e-9, 1)}) {
        double out[2];
        lookup(p, table.data(), 2, d.x, d.y, d.z, out);
        CHECK(out[0] == Approx(corner[0]).margin(1e-7));
        CHECK(out[1] == Approx(corner[1]).margin(1e-7));
    }
}

TEST_CASE("cube map: hardware bilinear within a face", "[param][cubemap]") {
    // A function linear in (u, v) on a face is reproduced exactly inside the ring of centres.
    const int n = 8;
    for (CubeFilter f : {CubeFilter::dx9_clamped, CubeFilter::dx10_seamless}) {
        const CubeMap<double> p(n, f);
        std::vector<double> table(p.texel_count(), 0.0);
        for (int r = 0; r < n; ++r)
            for (int c = 0; c < n; ++c)
                table[p.texel_index(4, c, r)] = 1 + 2 * (c + 0.5) / n - 3 * (r + 0.5) / n;
        std::mt19937 rng(7);
        std::uniform_real_distribution<double> U(0.5 / n, 1 - 0.5 / n);
        for (int k = 0; k < 500; ++k) {
            const double u = U(rng), v = U(rng);
            const auto d = square_to_cube(4, u, v);
            double out;
            lookup(p, table.data(), 1, d.x, d.y, d.z, &out);
            CHECK(out == Approx(1 + 2 * u - 3 * v).margin(1e-12));
        }
    }
    // Quantised weights: multiples of 1/256 per axis with 8 subtexel bits.
    const CubeMap<double> q(8, CubeFilter::dx9_clamped, 8);
    for (const auto& d : random_dirs<double>(2000, 8)) {
        const auto fp = q.footprint(d.x, d.y, d.z);
        for (int t = 0; t < 4; ++t) {
            const double w = fp.weight[t] * 256 * 256;
            CHECK(std::fabs(w - std::round(w)) < 1e-6);
        }
    }
}

TEST_CASE("cube map: convergence", "[param][cubemap]") {
    check_seam_convergence(CubeMap<double>(8), CubeMap<double>(16),
                           CubeMap<double>(8, CubeFilter::dx9_clamped),
                           CubeMap<double>(16, CubeFilter::dx9_clamped), "DX10", "DX9");
}

TEST_CASE("cube map: bad input", "[param][cubemap]") {
    REQUIRE_THROWS_WITH(CubeMap<double>(0),
                        Catch::Contains("sphbasis::param::CubeMap(): expected 1 <= resolution"));
    REQUIRE_THROWS_WITH(CubeMap<float>(4, CubeFilter::dx9_clamped, -1),
                        Catch::Contains("subtexel_bits"));
    const CubeMap<double> p(4);
    const auto t = p.direction_to_uv(0.0, 0.0, 0.0);  // the pole (0, 0, 1): face +Z centre
    CHECK(t.face == 4);
    CHECK(t.u == Approx(0.5));
}
