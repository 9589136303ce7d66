// Tests for render/probe_grid.hpp: validation, cells, trilinear interpolation (exact for affine
// functions, exact at probes, clamped outside) and the inside-geometry fallback.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <random>
#include <sphbasis/render/probe_grid.hpp>
#include <vector>

using namespace sphbasis;
using namespace sphbasis::render;

namespace {
ProbeGrid make_grid() {
    ProbeGrid g;
    g.lo = {-1.0, 0.5, 2.0};
    g.hi = {3.0, 1.5, 5.0};
    g.counts = {5, 3, 4};
    return g;
}
double affine(const vec3<double>& p, int c) {
    return 0.3 + (c + 1) * 1.7 * p.x - 0.4 * p.y + (2.5 - c) * p.z;
}
}  // namespace

TEST_CASE("probe grid: validation", "[render][probes]") {
    CHECK_NOTHROW(make_grid().validate());
    ProbeGrid g = make_grid();
    g.counts[1] = 0;
    CHECK_THROWS_WITH(g.validate(), Catch::Contains("sphbasis::render::ProbeGrid(): expected"));
    g = make_grid();
    g.lo.x = 4;  // lo > hi
    CHECK_THROWS_AS(g.validate(), std::invalid_argument);
    g = make_grid();
    g.hi.z = std::numeric_limits<double>::quiet_NaN();
    CHECK_THROWS_AS(g.validate(), std::invalid_argument);
    g = make_grid();
    g.lo.y = -std::numeric_limits<double>::infinity();
    CHECK_THROWS_AS(g.validate(), std::invalid_argument);
    g = make_grid();
    g.lo = g.hi;  // a flat box is allowed
    g.counts = {1, 1, 1};
    CHECK_NOTHROW(g.validate());
    CHECK_THROWS_AS(make_grid().cell_of({0, std::nan(""), 3}), std::invalid_argument);
}

TEST_CASE("probe grid: cells and weights", "[render][probes]") {
    const ProbeGrid g = make_grid();
    // Spacing 1 in x, 0.5 in y, 1 in z.
    const auto c = g.cell_of({0.25, 1.2, 4.5});
    CHECK(c.base == std::array<int, 3>{1, 1, 2});
    CHECK(c.t[0] == Approx(0.25));
    CHECK(c.t[1] == Approx(0.4));
    CHECK(c.t[2] == Approx(0.5));
    // The upper boundary belongs to the last cell with t = 1.
    const auto top = g.cell_of(g.hi);
    CHECK(top.base == std::array<int, 3>{3, 1, 2});
    CHECK(top.t == std::array<double, 3>{1, 1, 1});
    // Outside: clamped.
    const auto out = g.cell_of({-10, 10, 3.5});
    CHECK(out.base == std::array<int, 3>{0, 1, 1});
    CHECK(out.t[0] == 0.0);
    CHECK(out.t[1] == 1.0);
    const auto w = g.weights({0.25, 1.2, 4.5});
    double sum = 0;
    for (double x : w.w) {
        CHECK(x >= 0);
        sum += x;
    }
    CHECK(sum == Approx(1).epsilon(1e-15));
    CHECK(w.index[0] == g.index(1, 1, 2));
    CHECK(w.index[7] == g.index(2, 2, 3));
    CHECK(w.w[0] == Approx(0.75 * 0.6 * 0.5));
}

TEST_CASE("probe grid: trilinear interpolation is exact for affine functions and at probes",
          "[render][probes]") {
    const ProbeGrid g = make_grid();
    const std::size_t n = 3;
    std::vector<double> values(g.size() * n), scalar(g.size());
    for (int k = 0; k < g.counts[2]; ++k)
        for (int j = 0; j < g.counts[1]; ++j)
            for (int i = 0; i < g.counts[0]; ++i) {
                const auto p = g.position(i, j, k);
                for (std::size_t c = 0; c < n; ++c)
                    values[g.index(i, j, k) * n + c] = affine(p, int(c));
                scalar[g.index(i, j, k)] = affine(p, 0);
                const auto q = g.position(g.index(i, j, k));
                CHECK(q.x == p.x);
                CHECK(q.y == p.y);
                CHECK(q.z == p.z);
            }
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> ux(-1, 3), uy(0.5, 1.5), uz(2, 5);
    double out[3];
    for (int s = 0; s < 200; ++s) {
        const vec3<double> p{ux(rng), uy(rng), uz(rng)};
        g.interpolate(values.data(), n, p, out);
        for (std::size_t c = 0; c < n; ++c)
            CHECK(out[c] == Approx(affine(p, int(c))).margin(1e-12));
        CHECK(g.interpolate(scalar.data(), p) == Approx(affine(p, 0)).margin(1e-12));
    }
    // At each probe: its own value, exactly up to rounding.
    for (std::size_t i = 0; i < g.size(); ++i) {
        g.interpolate(values.data(), n, g.position(i), out);
        for (std::size_t c = 0; c < n; ++c)
            CHECK(out[c] == Approx(values[i * n + c]).margin(1e-12));
    }
    // Outside the box: the value at the clamped point.
    g.interpolate(values.data(), n, {10, -3, 4}, out);
    CHECK(out[1] == Approx(affine({3, 0.5, 4}, 1)).margin(1e-12));
    // A non-affine function is not reproduced between probes (the test can fail).
    std::vector<double> sq(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) sq[i] = g.position(i).x * g.position(i).x;
    CHECK(std::abs(g.interpolate(sq.data(), vec3<double>{0.5, 1, 3}) - 0.25) > 0.1);
    // An axis with one probe: constant along it.
    ProbeGrid flat = g;
    flat.counts = {5, 1, 4};
    std::vector<double> fv(flat.size());
    for (std::size_t i = 0; i < flat.size(); ++i) fv[i] = affine(flat.position(i), 0);
    CHECK(flat.interpolate(fv.data(), vec3<double>{0.3, 0.7, 3.3}) ==
          Approx(affine({0.3, 1.0, 3.3}, 0)).margin(1e-12));
    CHECK_THROWS_AS(g.interpolate(static_cast<const double*>(nullptr), n, {0, 1, 3}, out),
                    std::invalid_argument);
}

TEST_CASE("probe grid: probes inside geometry are left out", "[render][probes]") {
    const ProbeGrid g = make_grid();
    const std::size_t n = 2;
    std::vector<double> values(g.size() * n);
    std::vector<std::uint8_t> inside(g.size(), 0);
    for (std::size_t i = 0; i < g.size(); ++i) {
        values[i * n] = affine(g.position(i), 0);
        values[i * n + 1] = affine(g.position(i), 1);
    }
    double out[2], ref[2];
    // Nothing flagged: the same as interpolate().
    const vec3<double> p{0.25, 1.2, 4.5};
    g.interpolate_valid(values.data(), n, inside.data(), p, out);
    g.interpolate(values.data(), n, p, ref);
    CHECK(out[0] == Approx(ref[0]).margin(1e-12));
    CHECK(out[1] == Approx(ref[1]).margin(1e-12));
    // Flag one corner and poison its values: renormalised weights over the other seven.
    const auto w = g.weights(p);
    inside[w.index[3]] = 1;
    values[w.index[3] * n] = values[w.index[3] * n + 1] = std::numeric_limits<double>::quiet_NaN();
    g.interpolate_valid(values.data(), n, inside.data(), p, out);
    double e0 = 0, e1 = 0, tw = 0;
    for (std::size_t k = 0; k < 8; ++k) {
        if (k == 3) continue;
        e0 += w.w[k] * values[w.index[k] * n];
        e1 += w.w[k] * values[w.index[k] * n + 1];
        tw += w.w[k];
    }
    CHECK(tw < 0.99);
    CHECK(out[0] == Approx(e0 / tw).margin(1e-12));
    CHECK(out[1] == Approx(e1 / tw).margin(1e-12));
    // All eight corners flagged: the nearest valid probe's values.
    for (auto idx : w.index) inside[idx] = 1;
    g.interpolate_valid(values.data(), n, inside.data(), p, out);
    const std::size_t nearest = g.nearest_valid(inside.data(), p);
    CHECK(inside[nearest] == 0);
    // Brute-force nearest, independently.
    double best = 1e300;
    std::size_t bi = 0;
    for (std::size_t i = 0; i < g.size(); ++i) {
        if (inside[i] != 0) continue;
        const auto q = g.position(i);
        const double d =
            (q.x - p.x) * (q.x - p.x) + (q.y - p.y) * (q.y - p.y) + (q.z - p.z) * (q.z - p.z);
        if (d < best) best = d, bi = i;
    }
    CHECK(nearest == bi);
    CHECK(out[0] == values[bi * n]);
    CHECK(out[1] == values[bi * n + 1]);
    // Every probe flagged: a runtime error, never NaN.
    std::fill(inside.begin(), inside.end(), std::uint8_t(1));
    CHECK_THROWS_AS(g.interpolate_valid(values.data(), n, inside.data(), p, out),
                    std::runtime_error);
}
