// Tests of param/reconstruction_error.hpp: the SH reconstruction experiment of Iwanicki and
// Sloan (JGT 2009, appendix A) against exact cases and a direct computation.
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/param/reconstruction_error.hpp>
#include <thread>
#include <vector>

using namespace sphbasis;
using namespace sphbasis::param;

namespace {

// Runs the blocks in reverse order, two threads: the blocked sums must not notice.
struct TwoThreadsReversed {
    template <class F>
    void operator()(std::size_t count, F&& body) const {
        std::thread t([&] {
            for (std::size_t i = count; i-- > 0;)
                if (i % 2 == 0) body(i);
        });
        for (std::size_t i = count; i-- > 0;)
            if (i % 2 == 1) body(i);
        t.join();
    }
};

}  // namespace

TEST_CASE("reconstruction: directions are unit, uniform, deterministic",
          "[param][reconstruction]") {
    const std::size_t n = 40000;
    const DirectionSet d = reconstruction_directions(n, 5);
    REQUIRE(d.size() == n);
    double mz = 0, mzz = 0, mx = 0;
    for (std::size_t i = 0; i < n; ++i) {
        CHECK(std::fabs(d.x[i] * d.x[i] + d.y[i] * d.y[i] + d.z[i] * d.z[i] - 1) < 1e-14);
        mx += d.x[i];
        mz += d.z[i];
        mzz += d.z[i] * d.z[i];
    }
    // Uniform on the sphere: E[x] = E[z] = 0 (sd 1/sqrt(3n)), E[z^2] = 1/3 (sd 0.298/sqrt(n)).
    CHECK(std::fabs(mx / n) < 5 / std::sqrt(3.0 * n));
    CHECK(std::fabs(mz / n) < 5 / std::sqrt(3.0 * n));
    CHECK(std::fabs(mzz / n - 1.0 / 3) < 5 * 0.298 / std::sqrt(double(n)));
    const DirectionSet again = reconstruction_directions(n, 5);
    CHECK(again.x == d.x);
    CHECK(again.z == d.z);
    CHECK(reconstruction_directions(100, 6).x != reconstruction_directions(100, 5).x);
}

TEST_CASE("reconstruction: bilinear filtering reproduces a constant exactly",
          "[param][reconstruction]") {
    // One band (y00 constant): the footprint weights sum to 1, so a double table reconstructs
    // y00 to rounding at every direction, with every filter and subtexel precision.
    const DirectionSet d = reconstruction_directions(5000, 2);
    for (const auto& c : reconstruction_cases())
        for (int bits : {0, 8})
            with_parameterization(c.id, 5, bits, [&](const auto& p) {
                const std::vector<double> table = tabulate_sh<1, double>(p);
                const ShReconstructionError<1> e = sh_reconstruction_error<1>(p, table, d);
                INFO(c.name << " bits " << bits);
                CHECK(e.points == d.size());
                CHECK(e.mse(1) < 1e-30);
                return 0;
            });
}

TEST_CASE("reconstruction: the blocked sums equal a direct computation",
          "[param][reconstruction]") {
    // A direct, independent computation: lookup() and the run-time SH recurrence sh::eval(6,...),
    // means over points and functions in one loop.
    const DirectionSet d = reconstruction_directions(3 * reconstruction_block + 17, 9);
    const Octahedral<double> p(12, OctahedralFilter::seamless);
    const std::vector<float> table = tabulate_sh<6, float>(p);
    double s3 = 0, s6 = 0;
    for (std::size_t i = 0; i < d.size(); ++i) {
        float rec[36];
        double exact[36];
        lookup(p, table.data(), 36, d.x[i], d.y[i], d.z[i], rec);
        sh::eval(6, d.x[i], d.y[i], d.z[i], exact);
        for (int k = 0; k < 36; ++k) {
            const double e2 = (double(rec[k]) - exact[k]) * (double(rec[k]) - exact[k]);
            if (k < 9) s3 += e2;
            s6 += e2;
        }
    }
    const double n = double(d.size());
    const ShReconstructionError<6> e = sh_reconstruction_error<6>(p, table, d);
    CHECK(e.mse(3) == Approx(s3 / (9 * n)).epsilon(1e-12));
    CHECK(e.mse(6) == Approx(s6 / (36 * n)).epsilon(1e-12));
    // The same numbers to the last bit whatever runs the blocks.
    const ShReconstructionError<6> f =
        sh_reconstruction_error<6>(p, table, d, TwoThreadsReversed{});
    CHECK(f.sum == e.sum);
    CHECK(f.points == e.points);
}

TEST_CASE("reconstruction: bilinear error falls as h^4 (MSE) with resolution",
          "[param][reconstruction]") {
    // Bilinear interpolation of a smooth function errs by O(h^2), so the MSE of the 3-band
    // functions falls by ~16 when the texel size halves (well above the float floor here); the
    // octahedral map's folds (where the mapped function has kinks) cost a little: 11.7 at 16->32.
    const DirectionSet d = reconstruction_directions(20000, 3);
    const auto& cases = reconstruction_cases();
    const auto& octa = *std::find_if(cases.begin(), cases.end(), [](const auto& c) {
        return c.id == ReconstructionParam::octahedral_seamless;
    });
    const ReconstructionResult a = run_reconstruction_case(octa, 16, 0, d);
    const ReconstructionResult b = run_reconstruction_case(octa, 32, 0, d);
    CHECK(a.texels == 256);
    CHECK(b.texels == 1024);
    const double ratio = a.mse3 / b.mse3;
    CHECK(ratio > 10);
    CHECK(ratio < 20);
    CHECK(b.mse6 > b.mse3);  // higher bands vary faster
}

TEST_CASE("reconstruction: resolutions and texel budgets", "[param][reconstruction]") {
    for (const auto& c : reconstruction_cases())
        for (int k = 0; k < reconstruction_budgets; ++k) {
            const int n = reconstruction_resolution(c, k);
            const double budget = 96.0 * std::ldexp(1.0, k);
            const double texels = double(c.texels_per_n2) * n * n;
            INFO(c.name << " k " << k);
            CHECK(n >= c.min_n);
            CHECK(texels / budget < 1.6);
            CHECK(texels / budget > 0.6);
            with_parameterization(c.id, n, 0, [&](const auto& p) {
                CHECK(double(p.texel_count()) == texels);
                return 0;
            });
        }
}

TEST_CASE("reconstruction: log-log interpolation is exact on a power law",
          "[param][reconstruction]") {
    std::vector<ReconstructionResult> rs;
    for (std::size_t t : {std::size_t(100), std::size_t(400), std::size_t(1600)}) {
        ReconstructionResult r;
        r.param = "p";
        r.texels = t;
        r.mse3 = 5.0 / (double(t) * double(t));
        r.mse6 = 2.0 / double(t);
        rs.push_back(r);
    }
    CHECK(reconstruction_mse_at(rs, "p", 250, 3) == Approx(5.0 / (250.0 * 250.0)).epsilon(1e-12));
    CHECK(reconstruction_mse_at(rs, "p", 1000, 6) == Approx(2.0 / 1000).epsilon(1e-12));
    CHECK(std::isnan(reconstruction_mse_at(rs, "p", 5000, 3)));
    CHECK(std::isnan(reconstruction_mse_at(rs, "q", 250, 3)));
}

TEST_CASE("reconstruction: bad input", "[param][reconstruction]") {
    const DirectionSet d = reconstruction_directions(10, 1);
    const LatLong<double> p(4);
    const std::vector<float> small(10);
    REQUIRE_THROWS_WITH(sh_reconstruction_error<2>(p, small, d, 0, 10),
                        "sphbasis::param::sh_reconstruction_error(): expected a table of 128 "
                        "values, got 10");
    const std::vector<float> table = tabulate_sh<2>(p);
    CHECK_THROWS_AS(sh_reconstruction_error<2>(p, table, d, 0, 11), std::invalid_argument);
    CHECK_THROWS_AS(sh_reconstruction_error<2>(p, table, d, 5, 4), std::invalid_argument);
    const auto e = sh_reconstruction_error<2>(p, table, d, 0, 10);
    REQUIRE_THROWS_WITH(e.mse(3),
                        "sphbasis::param::ShReconstructionError::mse(): expected 1 <= "
                        "bands <= 2, got 3");
    CHECK_THROWS_AS(reconstruction_mse_at({}, "p", 10, 4), std::invalid_argument);
}
