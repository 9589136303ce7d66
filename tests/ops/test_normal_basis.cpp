// Tests for ops/normal_basis.hpp: closed forms of the clamped and unclamped columns, the SVD
// energies (monotone, 100% at M = bands^2, the cosine weighting above the uniform one) and the
// values printed in Sloan, Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and
// Practice" (SIGGRAPH 2005 course), "Normal Mapping for PRT": M = 4: 93.9 (uniform) / 96.4
// (cosine), M = 6: 98.7 / 99.3, reproduced by the unclamped variant and not by the clamped one.
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/ops/normal_basis.hpp>
#include <vector>

using namespace sphbasis;

namespace {
std::vector<double> energies(int bands, bool clamped, NormalWeighting w, int rings = 0) {
    NormalBasisSettings s;
    s.bands = bands;
    s.clamped = clamped;
    s.weighting = w;
    s.rings = rings;
    return normal_basis_energy(s);
}
}  // namespace

TEST_CASE("normal basis: columns against closed forms", "[ops][normal_basis]") {
    const double y00 = 0.28209479177387814,
                 y10 = 0.48860251190291992;  // 1/(2 sqrt(pi)), sqrt(3/(4 pi))
    std::vector<double> c(9), u(9);
    for (double theta : {0.0, 0.3, 1.0, 1.4, 1.5707963267948966}) {
        const double nx = std::sin(theta) * 0.6, ny = std::sin(theta) * 0.8, nz = std::cos(theta);
        convolved_lighting_columns(3, true, nx, ny, nz, c.data());
        convolved_lighting_columns(3, false, nx, ny, nz, u.data());
        INFO("theta " << theta);
        // The sky view factor: integral over w_z > 0 of max(n . w, 0) = pi (1 + cos theta) / 2.
        CHECK(c[0] == Approx(y00 * constants::pi * (1 + nz) / 2).epsilon(1e-13));
        CHECK(u[0] == Approx(y00 * constants::pi).epsilon(1e-15));
        // Unclamped: pi a_1 y_10(n) = (2 pi / 3) y10 n_z.
        CHECK(u[2] == Approx(2 * constants::pi / 3 * y10 * nz).margin(1e-15));
    }
    // n = x: integral over x > 0, z > 0 of x z = 2/3, times y10.
    convolved_lighting_columns(3, true, 1, 0, 0, c.data());
    CHECK(c[2] == Approx(2.0 / 3.0 * y10).epsilon(1e-13));
    // n = z: the lune is the whole upper hemisphere, clamped = unclamped.
    convolved_lighting_columns(3, true, 0, 0, 1, c.data());
    convolved_lighting_columns(3, false, 0, 0, 1, u.data());
    for (int j = 0; j < 9; ++j)
        CHECK(c[static_cast<std::size_t>(j)] ==
              Approx(u[static_cast<std::size_t>(j)]).margin(1e-14));
}

TEST_CASE("normal basis: energies monotone, 100% at full rank, cosine above uniform",
          "[ops][normal_basis]") {
    for (int bands = 1; bands <= 4; ++bands)
        for (bool clamped : {true, false}) {
            if (clamped && bands == 4) continue;  // cost; bands 4 unclamped covers 16 columns
            const auto eu = energies(bands, clamped, NormalWeighting::uniform, 12);
            const auto ec = energies(bands, clamped, NormalWeighting::cosine, 12);
            REQUIRE(eu.size() == static_cast<std::size_t>(bands * bands));
            REQUIRE(ec.size() == eu.size());
            CHECK(eu.back() == 100.0);
            CHECK(ec.back() == 100.0);
            for (std::size_t m = 1; m < eu.size(); ++m) {
                CHECK(eu[m] >= eu[m - 1]);
                CHECK(ec[m] >= ec[m - 1]);
            }
            // Weighting the normals near the geometric normal, where the convolved lighting
            // functions vary least, puts more of the energy into the first terms.
            for (std::size_t m = 0; m + 1 < eu.size(); ++m) {
                if (eu[m] < 99.99) CHECK(ec[m] > eu[m]);
                if (eu[m] < 99) CHECK(ec[m] > eu[m] + 0.3);
            }
        }
    // Converged: 12 and the automatic 24 rings agree to 1e-5 percent (the clamped columns
    // converge algebraically in the rings: 24 vs 48 agree to 2e-6).
    const auto a = energies(3, true, NormalWeighting::uniform, 12);
    const auto b = energies(3, true, NormalWeighting::uniform);
    for (std::size_t m = 0; m < a.size(); ++m) CHECK(a[m] == Approx(b[m]).margin(1e-5));
}

TEST_CASE("normal basis: the course notes' values come from the unclamped variant",
          "[ops][normal_basis]") {
    const auto uu = energies(3, false, NormalWeighting::uniform);
    const auto uc = energies(3, false, NormalWeighting::cosine);
    const auto cu = energies(3, true, NormalWeighting::uniform, 12);  // 1e-4 percent of 24 rings
    const auto cc = energies(3, true, NormalWeighting::cosine, 12);
    // Printed: M = 4: 93.9 / 96.4, M = 6: 98.7 / 99.3 (uniform / cosine).
    CHECK(std::fabs(uu[3] - 93.9) < 0.15);
    CHECK(std::fabs(uc[3] - 96.4) < 0.15);
    CHECK(std::fabs(uu[5] - 98.7) < 0.15);
    CHECK(std::fabs(uc[5] - 99.3) < 0.15);
    // The clamped variant is far from them at M = 4.
    CHECK(cu[3] - 93.9 > 4);
    CHECK(cc[3] - 96.4 > 2.5);
    // Our values (the table of docs/techniques.md).
    CHECK(uu[3] == Approx(93.92).margin(0.005));
    CHECK(uc[3] == Approx(96.29).margin(0.005));
    CHECK(cu[3] == Approx(98.35).margin(0.005));
    CHECK(cc[3] == Approx(99.11).margin(0.005));
}

TEST_CASE("normal basis: the SVD reconstructs A", "[ops][normal_basis]") {
    NormalBasisSettings s;
    s.rings = 8;
    const Eigen::MatrixXd a = normal_basis_matrix(s);
    const NormalBasis nb = normal_basis(s);
    REQUIRE(nb.u.rows() == a.rows());
    REQUIRE(nb.u.cols() == 9);
    const Eigen::MatrixXd r = nb.u * nb.singular_values.asDiagonal() * nb.v.transpose();
    CHECK((r - a).norm() <= 1e-12 * a.norm());
    CHECK(nb.normals.size() == static_cast<std::size_t>(a.rows()));
    // Uniform weights sum to the hemisphere's solid angle.
    double sum = 0;
    for (double w : nb.normals.w) sum += w;
    CHECK(sum == Approx(constants::two_pi).epsilon(1e-12));
}

TEST_CASE("normal basis: bad input throws", "[ops][normal_basis]") {
    NormalBasisSettings s;
    s.bands = 0;
    CHECK_THROWS_WITH(normal_basis(s), Catch::Contains("1 <= bands <= 8, got 0"));
    s.bands = 9;
    CHECK_THROWS_WITH(normal_basis_matrix(s), Catch::Contains("1 <= bands <= 8, got 9"));
    s.bands = 3;
    s.rings = -1;
    CHECK_THROWS_WITH(normal_basis(s), Catch::Contains("0 <= rings <= 4096"));
    s.rings = 0;
    s.weighting = static_cast<NormalWeighting>(7);
    CHECK_THROWS_WITH(normal_basis(s), Catch::Contains("weighting uniform or cosine"));
    std::vector<double> out(81);
    CHECK_THROWS_WITH(convolved_lighting_columns(10, true, 0, 0, 1, out.data()),
                      Catch::Contains("bands"));
}
