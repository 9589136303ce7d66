// The registry's promise on bad directions, for every basis it lists at every size up to 49:
// basis_eval normalises its input and takes zero or non-finite vectors as the pole (0, 0, 1)
// (basis/basis.hpp), so the values there are finite and equal the pole's, in double, float and
// the float batch; a non-unit vector gives its direction's values.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <sphbasis/basis/registry.hpp>
#include <string>
#include <vector>

using namespace sphbasis;

TEST_CASE("registry: every basis is finite at zero, non-finite and extreme directions",
          "[basis][registry]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    const double tiny = std::numeric_limits<double>::denorm_min();
    // Taken as the pole: zero and non-finite vectors.
    const std::vector<std::array<double, 3>> pole_like{
        {0, 0, 0}, {-0.0, 0, -0.0}, {nan, 0, 1}, {0, inf, 0}, {nan, nan, nan}, {-inf, inf, 1}};
    // Finite, non-unit, at the edges of the range or of the bases' pieces (signed zeros, an
    // icosahedron vertex, a cube face's diagonal).
    const std::vector<std::array<double, 3>> extreme{
        {1e300, 1e300, 0}, {tiny, 0, 0},     {0, 0, -tiny},
        {-0.0, -0.0, 1},   {-0.0, -0.0, -1}, {3, 4, 0},
        {1e-30, 0, 1e-30}, {1, 1, 1},        {0.85065080835203988, 0.52573111211913359, 0}};
    int checked = 0;
    for (const BasisInfo& b : all_bases()) {
        for (int n = 1; n <= 49; ++n) {
            if (!b.valid_count(n)) continue;
            INFO(b.name << " " << n);
            std::vector<double> pole(n), o(n);
            std::vector<float> of(n), ob(std::size_t(n) * 8);
            b.eval_d(n, 0, 0, 1, pole.data());
            auto finite_everywhere = [&](const std::array<double, 3>& d) {
                INFO(d[0] << " " << d[1] << " " << d[2]);
                b.eval_d(n, d[0], d[1], d[2], o.data());
                b.eval_f(n, float(d[0]), float(d[1]), float(d[2]), of.data());
                const std::vector<float> xs(8, float(d[0])), ys(8, float(d[1])), zs(8, float(d[2]));
                b.eval_batch_f(n, 8, xs.data(), ys.data(), zs.data(), ob.data(), 8);
                for (int k = 0; k < n; ++k) {
                    CHECK(std::isfinite(o[k]));
                    CHECK(std::isfinite(of[k]));
                }
                for (float v : ob) CHECK(std::isfinite(v));
                ++checked;
            };
            for (const auto& d : pole_like) {
                finite_everywhere(d);
                for (int k = 0; k < n; ++k) CHECK(o[k] == pole[k]);
            }
            for (const auto& d : extreme) finite_everywhere(d);
            // A non-unit vector is its direction: (3, 4, 0) is (0.6, 0.8, 0).
            std::vector<double> unit(n);
            b.eval_d(n, 3, 4, 0, o.data());
            b.eval_d(n, 0.6, 0.8, 0, unit.data());
            for (int k = 0; k < n; ++k) CHECK(o[k] == Approx(unit[k]).margin(1e-12));
        }
    }
    CHECK(checked >= 700);  // 750 (basis, size, direction) triples today
}
