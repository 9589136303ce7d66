// Tests for basis/ambient_dice_bezier.hpp: Ambient Dice over the icosahedron's faces (Iwanicki
// and Sloan 2017), the Bezier variant (values and derivatives at the vertices, hybrid cubic Bezier
// triangles) and the linear one.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/basis/ambient_dice_bezier.hpp>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/ops/projection.hpp>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"
#include "../support/engine_reference.hpp"

using namespace sphbasis;
namespace tb = sphbasis::ambient_dice::tables;

namespace {

using Vec = std::array<double, 3>;

double dot3(const Vec& a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

Vec unit3(Vec v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / n, v[1] / n, v[2] / n};
}

/// Lines `tag x y z v...` of tests/data/ambient_dice_bezier_reference.txt.
std::vector<std::vector<double>> reference(const std::string& tag) {
    return sphbasis::test::engine_reference(tag, "ambient_dice_bezier_reference.txt");
}

/// A smooth test function of the direction (a cubic in x, y, z) and its gradient in R^3.
double test_f(const Vec& d) {
    const double x = d[0], y = d[1], z = d[2];
    return 1 + x - 2 * y + x * z + 3 * y * y * z - x * x * x / 2;
}
Vec test_grad(const Vec& d) {
    const double x = d[0], y = d[1], z = d[2];
    return {1 + z - 1.5 * x * x, -2 + 6 * y * z, x + 3 * y * y};
}

/// The Bezier coefficients of test_f: its values and tangential derivatives at the vertices.
std::vector<double> test_coefficients() {
    std::vector<double> c(36);
    for (int k = 0; k < 12; ++k) {
        const Vec v = {tb::vertex[k][0], tb::vertex[k][1], tb::vertex[k][2]};
        const Vec g = test_grad(v);
        c[std::size_t(3 * k)] = test_f(v);
        c[std::size_t(3 * k + 1)] = dot3(g, tb::tangent_u[k]);
        c[std::size_t(3 * k + 2)] = dot3(g, tb::tangent_w[k]);
    }
    return c;
}

double bezier(const std::vector<double>& c, const Vec& d) {
    return basis_eval_sum<AmbientDiceBezier>(36, c, d[0], d[1], d[2]);
}

/// The point at angle t from v towards the unit tangent t (cos t v + sin t u).
Vec along(const double* v, const double* u, double t) {
    return {std::cos(t) * v[0] + std::sin(t) * u[0], std::cos(t) * v[1] + std::sin(t) * u[1],
            std::cos(t) * v[2] + std::sin(t) * u[2]};
}

/// The 30 edges: pairs of neighbouring vertices (cos = 1/sqrt(5)).
std::vector<std::pair<int, int>> edges() {
    std::vector<std::pair<int, int>> e;
    for (int i = 0; i < 12; ++i)
        for (int j = i + 1; j < 12; ++j) {
            const Vec vi = {tb::vertex[i][0], tb::vertex[i][1], tb::vertex[i][2]};
            if (std::fabs(dot3(vi, tb::vertex[j]) - 1 / std::sqrt(5.0)) < 1e-12)
                e.emplace_back(i, j);
        }
    return e;
}

}  // namespace

TEST_CASE("ambient-dice-bezier: values against the reference generator",
          "[ambient-dice][ambient-dice-bezier]") {
    const auto rows = reference("ambient-dice-bezier");
    REQUIRE(rows.size() >= 40);
    for (const auto& r : rows) {
        REQUIRE(r.size() == 39);
        std::array<double, 36> d;
        std::array<float, 36> f;
        basis_eval<AmbientDiceBezier>(36, r[0], r[1], r[2], d.data());
        basis_eval<AmbientDiceBezier>(36, float(r[0]), float(r[1]), float(r[2]), f.data());
        for (std::size_t k = 0; k < 36; ++k) {
            CHECK(d[k] == Approx(r[3 + k]).margin(1e-15));
            CHECK(f[k] == Approx(r[3 + k]).margin(1e-6));
        }
    }
    const auto lin = reference("ambient-dice-linear");
    REQUIRE(lin.size() >= 40);
    for (const auto& r : lin) {
        REQUIRE(r.size() == 15);
        std::array<double, 12> d;
        basis_eval<AmbientDiceLinear>(12, r[0], r[1], r[2], d.data());
        for (std::size_t k = 0; k < 12; ++k) CHECK(d[k] == Approx(r[3 + k]).margin(1e-15));
    }
}

TEST_CASE("ambient-dice-bezier: interpolates values and derivatives at the vertices",
          "[ambient-dice][ambient-dice-bezier]") {
    const auto c = test_coefficients();
    const double h = 1e-6;
    for (int k = 0; k < 12; ++k) {
        const double* v = tb::vertex[k];
        INFO("vertex " << k);
        CHECK(bezier(c, {v[0], v[1], v[2]}) == Approx(c[std::size_t(3 * k)]).epsilon(1e-14));
        for (int t = 0; t < 2; ++t) {
            const double* u = t == 0 ? tb::tangent_u[k] : tb::tangent_w[k];
            // Central differences across the vertex: each side lies in another face; the
            // patch is C1 at the vertex, so the error is O(h).
            const double g = (bezier(c, along(v, u, h)) - bezier(c, along(v, u, -h))) / (2 * h);
            CHECK(g == Approx(c[std::size_t(3 * k + 1 + t)]).margin(2e-5));
        }
        // Any tangent direction: the derivative is the gradient's component (both edges' data
        // determine the whole tangential gradient).
        const double a = 0.3 + k;
        double u[3];
        for (int i = 0; i < 3; ++i)
            u[i] = std::cos(a) * tb::tangent_u[k][i] + std::sin(a) * tb::tangent_w[k][i];
        const double g = (bezier(c, along(v, u, h)) - bezier(c, along(v, u, -h))) / (2 * h);
        CHECK(g == Approx(std::cos(a) * c[std::size_t(3 * k + 1)] +
                          std::sin(a) * c[std::size_t(3 * k + 2)])
                       .margin(2e-5));
    }
}

TEST_CASE("ambient-dice-bezier: continuous across every edge, C1 at edge midpoints",
          "[ambient-dice][ambient-dice-bezier]") {
    const auto e = edges();
    REQUIRE(e.size() == 30);
    // Arbitrary coefficients (not from a smooth function): continuity is the construction's.
    std::vector<double> c(36);
    for (std::size_t k = 0; k < 36; ++k) c[k] = std::sin(3.7 * double(k) + 1);
    double worst_c0 = 0, worst_c1 = 0;
    for (const auto& [i, j] : e) {
        const double *vi = tb::vertex[i], *vj = tb::vertex[j];
        const Vec n = unit3({vi[1] * vj[2] - vi[2] * vj[1], vi[2] * vj[0] - vi[0] * vj[2],
                             vi[0] * vj[1] - vi[1] * vj[0]});
        for (double s : {0.1, 0.37, 0.5, 0.81}) {
            const Vec d = unit3({(1 - s) * vi[0] + s * vj[0], (1 - s) * vi[1] + s * vj[1],
                                 (1 - s) * vi[2] + s * vj[2]});
            const double eps = 1e-10;
            const double left = bezier(
                             c, unit3({d[0] - eps * n[0], d[1] - eps * n[1], d[2] - eps * n[2]})),
                         right = bezier(
                             c, unit3({d[0] + eps * n[0], d[1] + eps * n[1], d[2] + eps * n[2]}));
            worst_c0 = std::max(worst_c0, std::fabs(left - right));
            if (s == 0.5) {
                const double h = 1e-6, mid = bezier(c, d);
                const double dl = (mid - bezier(c, unit3({d[0] - h * n[0], d[1] - h * n[1],
                                                          d[2] - h * n[2]}))) /
                                  h,
                             dr = (bezier(c, unit3({d[0] + h * n[0], d[1] + h * n[1],
                                                    d[2] + h * n[2]})) -
                                   mid) /
                                  h;
                worst_c1 = std::max(worst_c1, std::fabs(dl - dr));
            }
        }
    }
    CHECK(worst_c0 < 1e-8);
    CHECK(worst_c1 < 1e-4);
    // Away from the midpoints the cross derivative may jump (C0 only): the check above would
    // fail there, which shows it tests something. Measured at s = 0.25 on the first edge.
    const auto [i, j] = e[0];
    const double *vi = tb::vertex[i], *vj = tb::vertex[j];
    const Vec n = unit3({vi[1] * vj[2] - vi[2] * vj[1], vi[2] * vj[0] - vi[0] * vj[2],
                         vi[0] * vj[1] - vi[1] * vj[0]});
    const Vec d = unit3(
        {0.75 * vi[0] + 0.25 * vj[0], 0.75 * vi[1] + 0.25 * vj[1], 0.75 * vi[2] + 0.25 * vj[2]});
    const double h = 1e-6, mid = bezier(c, d);
    const double dl =
        (mid - bezier(c, unit3({d[0] - h * n[0], d[1] - h * n[1], d[2] - h * n[2]}))) / h;
    const double dr =
        (bezier(c, unit3({d[0] + h * n[0], d[1] + h * n[1], d[2] + h * n[2]})) - mid) / h;
    CHECK(std::fabs(dl - dr) > 1e-3);
}

TEST_CASE("ambient-dice-bezier: constants exact, locality, linear variant",
          "[ambient-dice][ambient-dice-bezier]") {
    std::vector<double> one(36, 0.0);
    for (int k = 0; k < 12; ++k) one[std::size_t(3 * k)] = 1;
    for (const auto& d : test::random_dirs(200, 11, false)) {
        std::array<double, 36> v;
        std::array<double, 12> l;
        basis_eval<AmbientDiceBezier>(36, d[0], d[1], d[2], v.data());
        basis_eval<AmbientDiceLinear>(12, d[0], d[1], d[2], l.data());
        double s = 0, sl = 0;
        int nz = 0, nzl = 0;
        for (int k = 0; k < 12; ++k) s += v[std::size_t(3 * k)];
        for (double x : v) nz += x != 0;
        for (double x : l) {
            CHECK(x >= 0);
            sl += x;
            nzl += x != 0;
        }
        CHECK(s == Approx(1).epsilon(1e-15));
        CHECK(sl == Approx(1).epsilon(1e-15));
        CHECK(bezier(one, {d[0], d[1], d[2]}) == Approx(1).epsilon(1e-15));
        CHECK(nz <= 9);
        CHECK(nzl <= 3);
    }
    // At a vertex: its value function 1, its derivative functions 0, every other function 0.
    for (int k = 0; k < 12; ++k) {
        std::array<double, 36> v;
        std::array<double, 12> l;
        basis_eval<AmbientDiceBezier>(36, tb::vertex[k][0], tb::vertex[k][1], tb::vertex[k][2],
                                      v.data());
        basis_eval<AmbientDiceLinear>(12, tb::vertex[k][0], tb::vertex[k][1], tb::vertex[k][2],
                                      l.data());
        for (int q = 0; q < 36; ++q)
            CHECK(v[std::size_t(q)] == Approx(q == 3 * k ? 1.0 : 0.0).margin(1e-15));
        for (int q = 0; q < 12; ++q)
            CHECK(l[std::size_t(q)] == Approx(q == k ? 1.0 : 0.0).margin(1e-15));
    }
}

TEST_CASE("ambient-dice-bezier: hemisphere sizes, batch equals scalar, registry, bad sizes",
          "[ambient-dice][ambient-dice-bezier]") {
    // 30 / 10 functions: the 36 / 12 without vertices 9 and 10, which vanish on z >= 0 (equal
    // within rounding: the two sizes' code may contract products into FMAs differently).
    for (const auto& d : test::random_dirs(60, 12, true)) {
        std::array<double, 36> v;
        std::array<double, 30> h;
        std::array<double, 12> l;
        std::array<double, 10> hl;
        basis_eval<AmbientDiceBezier>(36, d[0], d[1], d[2], v.data());
        basis_eval<AmbientDiceBezier>(30, d[0], d[1], d[2], h.data());
        basis_eval<AmbientDiceLinear>(12, d[0], d[1], d[2], l.data());
        basis_eval<AmbientDiceLinear>(10, d[0], d[1], d[2], hl.data());
        for (std::size_t k = 27; k < 33; ++k) CHECK(v[k] == 0);
        for (std::size_t k = 0; k < 30; ++k) CHECK(std::abs(h[k] - v[k < 27 ? k : k + 6]) <= 1e-15);
        CHECK(l[9] == 0);
        CHECK(l[10] == 0);
        for (std::size_t k = 0; k < 10; ++k) CHECK(std::abs(hl[k] - l[k < 9 ? k : k + 2]) <= 1e-15);
    }
    const auto dirs = test::random_dirs(37, 10, false);
    const auto inf = test::scaled_inputs<float>(dirs, 0.5);
    const auto ind = test::scaled_inputs<double>(dirs, 0.5);
    for (int n : {30, 36}) {
        std::vector<float> cf(static_cast<std::size_t>(n));
        for (std::size_t k = 0; k < cf.size(); ++k) cf[k] = float(std::sin(double(k) + 1));
        std::vector<double> cd(cf.begin(), cf.end());
        test::check_batch_equals_scalar<AmbientDiceBezier, float>(n, cf, inf, 1e-6f, 1e-6, 2e-5f);
        test::check_batch_equals_scalar<AmbientDiceBezier, double>(n, cd, ind, 1e-15, 1e-15, 1e-14);
    }
    for (int n : {10, 12}) {
        std::vector<float> cf(static_cast<std::size_t>(n));
        for (std::size_t k = 0; k < cf.size(); ++k) cf[k] = float(std::sin(double(k) + 1));
        std::vector<double> cd(cf.begin(), cf.end());
        test::check_batch_equals_scalar<AmbientDiceLinear, float>(n, cf, inf, 3e-7f, 3e-7, 4e-6f);
        test::check_batch_equals_scalar<AmbientDiceLinear, double>(n, cd, ind, 1e-15, 1e-15, 1e-14);
    }
    const BasisInfo& b = find_basis("ambient-dice-bezier");
    CHECK(b.domain == Domain::sphere);
    CHECK(b.valid_count(36));
    CHECK(b.valid_count(30));
    CHECK(find_basis("ambient-dice-linear").valid_count(12));
    std::array<double, 36> v;
    CHECK_THROWS_WITH(basis_eval<AmbientDiceBezier>(12, 0.0, 0.0, 1.0, v.data()),
                      Catch::Contains("30 (upper hemisphere) or 36 functions for basis "
                                      "'ambient-dice-bezier'"));
    CHECK_THROWS_WITH(basis_eval<AmbientDiceLinear>(36, 0.0, 0.0, 1.0, v.data()),
                      Catch::Contains("10 (upper hemisphere) or 12 functions for basis "
                                      "'ambient-dice-linear'"));
}

TEST_CASE("ambient-dice-bezier: least-squares fits on the sphere and the upper hemisphere",
          "[ambient-dice][ambient-dice-bezier]") {
    // Samples of an expansion in the span: the fit recovers its coefficients (the Gram matrix is
    // regular on the domain: 36 on the sphere, 30 on z >= 0).
    const std::vector<std::pair<int, DirectionalRule>> cases = {{36, sphere_rule(40)},
                                                                {30, hemisphere_rule(40)}};
    for (const auto& p : cases) {
        const int n = p.first;
        const DirectionalRule& rule = p.second;
        const BasisFunctions f = find_basis("ambient-dice-bezier").functions(n);
        Eigen::VectorXd c(n);
        for (int k = 0; k < n; ++k) c(k) = std::cos(1.3 * k);
        const Eigen::VectorXd got = fit(
            f,
            [&](double x, double y, double z) {
                std::vector<double> v(std::size_t(n), 0.0);
                f.eval(x, y, z, v.data());
                double s = 0;
                for (int k = 0; k < n; ++k) s += c(k) * v[std::size_t(k)];
                return s;
            },
            rule);
        INFO("n = " << n);
        CHECK((got - c).cwiseAbs().maxCoeff() < 1e-9);
    }
    // A smooth function's fit beats the interpolation of its vertex data in the L2 norm.
    const DirectionalRule rule = sphere_rule(40);
    const BasisFunctions f = find_basis("ambient-dice-bezier").functions(36);
    const auto fn = [](double x, double y, double z) { return test_f({x, y, z}); };
    const Eigen::VectorXd c = fit(f, fn, rule);
    const auto ci = test_coefficients();
    const double e_fit = squared_error(f, c, fn, rule),
                 e_interp =
                     squared_error(f, Eigen::Map<const Eigen::VectorXd>(ci.data(), 36), fn, rule);
    const double norm2 = squared_error(f, Eigen::VectorXd::Zero(36), fn, rule);
    INFO("fit " << e_fit << ", interpolation " << e_interp << ", |f|^2 " << norm2);
    CHECK(e_fit <= e_interp);
    CHECK(e_interp < 1e-2 * norm2);  // measured: fit 0.027, interpolation 0.069, |f|^2 35.5
}
