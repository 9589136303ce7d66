// Tests for ops/lxh_table.hpp: the row-scaling construction against an exact quadrature of the
// product L * H_n projected onto K bands (the independent reference), the truncation bound of
// fewer cosine bands, the symmetric construction against the plain one on every
// parameterization of param/, the sparse direct product, blending linearity, shading, bad input.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/frame.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/ops/lxh_table.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/param/dual_orthographic.hpp>
#include <sphbasis/param/dual_paraboloid.hpp>
#include <sphbasis/param/latlong.hpp>
#include <sphbasis/param/octahedral.hpp>
#include <vector>

#include "../support/sh_checks.hpp"

using namespace sphbasis;

namespace {

std::vector<double> random_lighting(int bands, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> l(3 * static_cast<std::size_t>(bands * bands));
    for (double& v : l) v = u(rng);
    for (int c = 0; c < 3; ++c) l[static_cast<std::size_t>(c)] += 3.0;  // mostly positive
    return l;
}

/// proj_K(L * max(n . w, 0)) by a quadrature exact for it: Gauss-Legendre in cos(theta) about
/// n on [0, 1] times uniform azimuths (the integrand is a polynomial of degree N + K - 1 in w on
/// the hemisphere about n; odd powers of sin(theta) integrate to zero in phi).
std::vector<double> quadrature_lxh(int nb, const std::vector<double>& rgb, int kb, double nx,
                                   double ny, double nz) {
    const int deg = nb + kb - 1;
    const int nt = deg + 2, np = 2 * deg + 4;
    std::vector<double> t, wt;
    gauss_legendre(nt, t, wt);
    vec3<double> n{nx, ny, nz}, s, tt;
    coordinate_system(n, s, tt);
    std::vector<double> out(3 * static_cast<std::size_t>(kb * kb), 0.0);
    std::vector<double> yl(static_cast<std::size_t>(nb * nb)),
        yk(static_cast<std::size_t>(kb * kb));
    for (int i = 0; i < nt; ++i) {
        const double ct = 0.5 * (t[static_cast<std::size_t>(i)] + 1);
        const double st = std::sqrt(1 - ct * ct);
        for (int j = 0; j < np; ++j) {
            const double phi = (j + 0.5) * 2 * constants::pi / np;
            const double lx = st * std::cos(phi), ly = st * std::sin(phi);
            const double wx = lx * s.x + ly * tt.x + ct * n.x;
            const double wy = lx * s.y + ly * tt.y + ct * n.y;
            const double wz = lx * s.z + ly * tt.z + ct * n.z;
            const double w = 0.5 * wt[static_cast<std::size_t>(i)] * 2 * constants::pi / np * ct;
            sh::eval(nb, wx, wy, wz, yl.data());
            sh::eval(kb, wx, wy, wz, yk.data());
            for (int c = 0; c < 3; ++c) {
                double lv = 0;
                for (int a = 0; a < nb * nb; ++a)
                    lv +=
                        rgb[static_cast<std::size_t>(3 * a + c)] * yl[static_cast<std::size_t>(a)];
                for (int k = 0; k < kb * kb; ++k)
                    out[static_cast<std::size_t>(3 * k + c)] +=
                        w * lv * yk[static_cast<std::size_t>(k)];
            }
        }
    }
    return out;
}

using sphbasis::test::max_abs;

std::array<double, 3> random_unit(std::mt19937& rng) {
    std::normal_distribution<double> g;
    double x = g(rng), y = g(rng), z = g(rng);
    const double l = std::sqrt(x * x + y * y + z * z);
    return {x / l, y / l, z / l};
}

template <class P>
void check_symmetric_equals_plain(const P& p, int nb, int kb, double tol) {
    const auto light = random_lighting(nb, 11);
    const LxhMatrix m = lxh_matrix(nb, light.data(), kb);
    const auto plain = build_lxh_table(p, m, LxhConstruction::plain);
    const auto sym = build_lxh_table(p, m, LxhConstruction::symmetric);
    REQUIRE(plain.data.size() == sym.data.size());
    double scale = 0, diff = 0;
    for (std::size_t i = 0; i < plain.data.size(); ++i) {
        scale = std::max(scale, std::fabs(double(plain.data[i])));
        diff = std::max(diff, std::fabs(double(plain.data[i]) - double(sym.data[i])));
    }
    INFO("texels " << sym.stats.texels << ", orbits " << sym.stats.orbits);
    CHECK(diff <= tol * scale);
    CHECK(sym.stats.texels == p.texel_count());
    // The symmetries are used: at most a quarter of the SH evaluations.
    CHECK(sym.stats.orbits * 4 <= sym.stats.texels);
    CHECK(plain.stats.orbits == plain.stats.texels);
}

}  // namespace

TEST_CASE("lxh: row scaling equals the projection of L * H by quadrature", "[ops][lxh]") {
    std::mt19937 rng(5);
    for (auto [nb, kb] :
         {std::pair{3, 3}, std::pair{4, 4}, std::pair{2, 6}, std::pair{6, 2}, std::pair{1, 1}}) {
        const auto light = random_lighting(nb, static_cast<unsigned>(nb * 10 + kb));
        const LxhMatrix m = lxh_matrix(nb, light.data(), kb);
        CHECK(m.cosine_bands == nb + kb - 1);
        std::vector<double> out(m.column_size()), direct(m.column_size());
        for (int trial = 0; trial < 12; ++trial) {
            auto n = random_unit(rng);
            if (trial == 0) n = {0, 0, 1};
            if (trial == 1) n = {0, 0, -1};
            const auto ref = quadrature_lxh(nb, light, kb, n[0], n[1], n[2]);
            lxh_at(m, n[0], n[1], n[2], out.data());
            lxh_direct(nb, light.data(), kb, 0, n[0], n[1], n[2], direct.data());
            const double scale = max_abs(ref);
            INFO("N " << nb << " K " << kb << " n " << n[0] << " " << n[1] << " " << n[2]);
            for (std::size_t q = 0; q < out.size(); ++q) {
                CHECK(std::fabs(out[q] - ref[q]) <= 1e-12 * scale);
                CHECK(std::fabs(direct[q] - ref[q]) <= 1e-12 * scale);
            }
        }
    }
}

TEST_CASE("lxh: float table at texel centres within 1e-6 of the quadrature", "[ops][lxh]") {
    const int nb = 3, kb = 4;
    const auto light = random_lighting(nb, 3);
    const param::CubeMap<double> cube(4);
    const auto tab = build_lxh_table(cube, nb, light.data(), kb);
    REQUIRE(tab.channels() == 48);
    REQUIRE(tab.data.size() == cube.texel_count() * 48);
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < 4; ++row)
            for (int col = 0; col < 4; ++col) {
                const auto d = cube.texel_direction(face, col, row);
                const auto ref = quadrature_lxh(nb, light, kb, d.x, d.y, d.z);
                const double scale = max_abs(ref);
                const float* t = tab.data.data() + cube.texel_index(face, col, row) * 48;
                for (std::size_t q = 0; q < 48; ++q)
                    REQUIRE(std::fabs(double(t[q]) - ref[q]) <= 1e-6 * scale);
            }
}

TEST_CASE("lxh: fewer cosine bands stay within the truncation bound", "[ops][lxh]") {
    std::mt19937 rng(9);
    // N = 3, K = 2: N + K - 2 = 3 and a_3 = 0, so 3 cosine bands are exact.
    {
        const auto light = random_lighting(3, 1);
        CHECK(lxh_truncation_bound(3, light.data(), 2, 3) == 0);  // the dropped band 3 has a_3 = 0
        const LxhMatrix m3 = lxh_matrix(3, light.data(), 2, 3);
        std::vector<double> out(m3.column_size());
        const auto n = random_unit(rng);
        lxh_at(m3, n[0], n[1], n[2], out.data());
        const auto ref = quadrature_lxh(3, light, 2, n[0], n[1], n[2]);
        for (std::size_t q = 0; q < out.size(); ++q)
            CHECK(std::fabs(out[q] - ref[q]) <= 1e-12 * max_abs(ref));
    }
    // N = K = 3 with the reference's 9 rows (C = 3): the dropped band l = 4 gives an error that
    // is nonzero and below the bound.
    for (auto [nb, kb, cb] : {std::tuple{3, 3, 3}, std::tuple{4, 4, 3}, std::tuple{4, 4, 5}}) {
        const auto light = random_lighting(nb, 2);
        const double bound = lxh_truncation_bound(nb, light.data(), kb, cb);
        REQUIRE(bound > 0);
        const LxhMatrix m = lxh_matrix(nb, light.data(), kb, cb);
        std::vector<double> out(m.column_size());
        double worst = 0;
        for (int trial = 0; trial < 20; ++trial) {
            const auto n = random_unit(rng);
            lxh_at(m, n[0], n[1], n[2], out.data());
            const auto ref = quadrature_lxh(nb, light, kb, n[0], n[1], n[2]);
            for (int c = 0; c < 3; ++c) {
                double e2 = 0;
                for (std::size_t q = static_cast<std::size_t>(c); q < out.size(); q += 3)
                    e2 += (out[q] - ref[q]) * (out[q] - ref[q]);
                worst = std::max(worst, std::sqrt(e2));
            }
        }
        INFO("N " << nb << " K " << kb << " C " << cb << ": error " << worst << ", bound "
                  << bound);
        CHECK(worst <= bound);
        CHECK(worst > 1e-3 * bound);  // the bound is not vacuous
    }
    const auto light = random_lighting(3, 1);
    CHECK(lxh_truncation_bound(3, light.data(), 3, 0) == 0);
    CHECK(lxh_truncation_bound(3, light.data(), 3, 5) == 0);
}

TEST_CASE("lxh: the symmetric construction equals the plain one on every parameterization",
          "[ops][lxh]") {
    SECTION("cube map, DX10 seamless") {
        check_symmetric_equals_plain(param::CubeMap<double>(8), 3, 3, 1e-6);
    }
    SECTION("cube map, DX9 clamped") {
        check_symmetric_equals_plain(param::CubeMap<double>(6, param::CubeFilter::dx9_clamped), 4,
                                     2, 1e-6);
    }
    SECTION("dual paraboloid") {
        check_symmetric_equals_plain(param::DualParaboloid<double>(8), 3, 4, 1e-6);
    }
    SECTION("dual orthographic") {
        check_symmetric_equals_plain(param::DualOrthographic<double>(8), 3, 3, 1e-6);
    }
    SECTION("octahedral") {
        check_symmetric_equals_plain(param::Octahedral<double>(8), 3, 3, 1e-6);
    }
    SECTION("lat-long") { check_symmetric_equals_plain(param::LatLong<double>(8), 2, 5, 1e-6); }
    SECTION("float texel directions") {
        check_symmetric_equals_plain(param::CubeMap<float>(8), 3, 3, 1e-5);
    }
}

TEST_CASE("lxh: odd resolutions and the pole keep the symmetric construction exact", "[ops][lxh]") {
    // An odd cube face has texels on the axes (x = y = 0 at the face centres).
    const param::CubeMap<double> cube(5);
    const auto light = random_lighting(3, 4);
    const LxhMatrix m = lxh_matrix(3, light.data(), 3);
    const auto plain = build_lxh_table(cube, m, LxhConstruction::plain);
    const auto sym = build_lxh_table(cube, m, LxhConstruction::symmetric);
    double diff = 0, scale = 0;
    for (std::size_t i = 0; i < plain.data.size(); ++i) {
        diff = std::max(diff, std::fabs(double(plain.data[i]) - double(sym.data[i])));
        scale = std::max(scale, std::fabs(double(plain.data[i])));
    }
    CHECK(diff <= 1e-6 * scale);
}

TEST_CASE("lxh: blending tables equals the table of the blended lighting", "[ops][lxh]") {
    const param::DualParaboloid<double> p(6);
    const int nb = 3, kb = 3;
    const auto la = random_lighting(nb, 21), lb = random_lighting(nb, 22);
    const auto ta = build_lxh_table(p, nb, la.data(), kb);
    const auto tb = build_lxh_table(p, nb, lb.data(), kb);
    for (double t : {0.0, 0.25, 0.5, 1.0, 1.5}) {
        std::vector<double> mix(la.size());
        for (std::size_t i = 0; i < la.size(); ++i) mix[i] = (1 - t) * la[i] + t * lb[i];
        const auto tm = build_lxh_table(p, nb, mix.data(), kb, 0, LxhConstruction::symmetric);
        const auto bl = blend_lxh_tables(ta, tb, t);
        double diff = 0, scale = 0;
        for (std::size_t i = 0; i < tm.data.size(); ++i) {
            diff = std::max(diff, std::fabs(double(tm.data[i]) - double(bl.data[i])));
            scale = std::max(scale, std::fabs(double(tm.data[i])));
        }
        INFO("t = " << t);
        CHECK(diff <= 1e-6 * scale);
    }
    // Linear in L: the table of 2 L is twice the table of L.
    std::vector<double> twice(la);
    for (double& v : twice) v *= 2;
    const auto t2 = build_lxh_table(p, nb, twice.data(), kb);
    for (std::size_t i = 0; i < t2.data.size(); ++i) CHECK(t2.data[i] == 2 * ta.data[i]);
    CHECK_THROWS_WITH(blend_lxh_tables(ta, build_lxh_table(p, nb, la.data(), 2), 0.5),
                      Catch::Contains("same bands"));
    CHECK_THROWS_WITH(blend_lxh_tables(ta, tb, std::nan("")), Catch::Contains("finite weight"));
}

TEST_CASE("lxh: shading V . (L x H)(n) equals the triple integral", "[ops][lxh]") {
    const int nb = 3, kb = 3;
    const auto light = random_lighting(nb, 8);
    const param::CubeMap<double> cube(4);
    const auto tab = build_lxh_table(cube, nb, light.data(), kb);
    std::vector<double> v(static_cast<std::size_t>(kb * kb));
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (double& x : v) x = u(rng);
    v[0] = 1.5;
    // At a texel centre the bilinear lookup returns the texel (interior texel of face +Z).
    const auto d = cube.texel_direction(4, 1, 2);
    const auto got = tab.shade(v.data(), d.x, d.y, d.z);
    const auto ref = quadrature_lxh(nb, light, kb, d.x, d.y, d.z);
    for (int c = 0; c < 3; ++c) {
        double e = 0, s = 0;
        for (int k = 0; k < kb * kb; ++k) {
            e += v[static_cast<std::size_t>(k)] * ref[static_cast<std::size_t>(3 * k + c)];
            s += std::fabs(v[static_cast<std::size_t>(k)] *
                           ref[static_cast<std::size_t>(3 * k + c)]);
        }
        CHECK(std::fabs(got[static_cast<std::size_t>(c)] - e) <= 1e-6 * s);
    }
}

TEST_CASE("lxh: bad input throws", "[ops][lxh]") {
    const auto light = random_lighting(3, 1);
    CHECK_THROWS_WITH(lxh_matrix(0, light.data(), 3), Catch::Contains("1 <= lighting bands <= 16"));
    CHECK_THROWS_WITH(lxh_matrix(3, light.data(), 17),
                      Catch::Contains("1 <= visibility bands <= 16"));
    CHECK_THROWS_WITH(lxh_matrix(3, light.data(), 3, 6), Catch::Contains("0 <= cosine bands <= 5"));
    CHECK_THROWS_WITH(lxh_matrix(3, light.data(), 3, -1), Catch::Contains("cosine bands"));
    CHECK_THROWS_WITH(lxh_matrix(3, nullptr, 3), Catch::Contains("null pointer"));
    auto bad = light;
    bad[7] = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_WITH(lxh_matrix(3, bad.data(), 3),
                      Catch::Contains("finite lighting coefficients"));
    bad[7] = std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(build_lxh_table(param::CubeMap<double>(2), 3, bad.data(), 3),
                    std::invalid_argument);
    CHECK_THROWS_WITH(lxh_truncation_bound(3, light.data(), 0, 3),
                      Catch::Contains("visibility bands"));
    LxhMatrix broken = lxh_matrix(3, light.data(), 3);
    broken.columns.pop_back();
    CHECK_THROWS_WITH(build_lxh_table(param::CubeMap<double>(2), broken),
                      Catch::Contains("inconsistent"));
    std::vector<double> out(27);
    CHECK_THROWS_WITH(lxh_direct(3, light.data(), 3, 7, 0, 0, 1, out.data()),
                      Catch::Contains("cosine bands"));
}

TEST_CASE("lxh: orbits reused across lightings, storage reused across builds", "[ops][lxh]") {
    const param::CubeMap<double> cube(6);
    const LxhOrbits orbits = make_lxh_orbits(cube);
    CHECK(orbits.texels == cube.texel_count());
    // 6 x 36 texels: orbits of 8 (z negation pairs +Z/-Z and the side halves, 4 rotations).
    CHECK(orbits.orbits() == cube.texel_count() / 8);
    LxhTable<param::CubeMap<double>> tab{cube, 0, 0, 0, {}, {}};
    for (unsigned seed : {1u, 2u}) {
        const auto light = random_lighting(4, seed);
        const LxhMatrix m = lxh_matrix(4, light.data(), 3);
        build_lxh_table(cube, m, orbits, tab);
        const auto plain = build_lxh_table(cube, m);
        double diff = 0, scale = 0;
        for (std::size_t i = 0; i < plain.data.size(); ++i) {
            diff = std::max(diff, std::fabs(double(plain.data[i]) - double(tab.data[i])));
            scale = std::max(scale, std::fabs(double(plain.data[i])));
        }
        CHECK(diff <= 1e-6 * scale);
        CHECK(tab.stats.orbits == orbits.orbits());
    }
    CHECK_THROWS_WITH(build_lxh_table(param::CubeMap<double>(4),
                                      lxh_matrix(4, random_lighting(4, 1).data(), 3), orbits, tab),
                      Catch::Contains("the orbits of this parameterization"));
}
