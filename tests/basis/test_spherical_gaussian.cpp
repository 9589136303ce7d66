// Tests for basis/spherical_gaussian.hpp and ops/sg_fit.hpp: spherical Gaussian lobes, BakingLab's
// lobe sets, Hill's fitted irradiance against the exact integral, and the three solvers.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/basis/spherical_gaussian.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/core/sampling.hpp>
#include <sphbasis/ops/imse.hpp>
#include <sphbasis/ops/sg_fit.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;
using sphbasis::test::Dir;
using sphbasis::test::random_dirs;

namespace {

constexpr double pi = constants::pi;

/// The reference file of tools/gen/gen_sg_reference.py.
struct Reference {
    std::map<int, double> set_sharpness;
    struct H {
        int p;
        double lambda, c, value;
    };
    std::vector<H> h;
};
const Reference& reference() {
    static const Reference r = [] {
        Reference out;
        std::ifstream in(SPHBASIS_TEST_DATA_DIR "/sg_reference.txt");
        std::string line;
        while (std::getline(in, line)) {
            std::istringstream s(line);
            std::string tag;
            s >> tag;
            if (tag == "SET") {
                int count;
                double l;
                s >> count >> l;
                out.set_sharpness[count] = l;
            } else if (tag == "H") {
                Reference::H h;
                s >> h.p >> h.lambda >> h.c >> h.value;
                out.h.push_back(h);
            }
        }
        return out;
    }();
    return r;
}

sg::Lobe<double> lobe(Dir d, double lambda, double a) {
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return {d[0] / n, d[1] / n, d[2] / n, lambda, a};
}

/// Uniform random directions on the hemisphere z >= 0 (3 x n), fixed seed.
Eigen::Matrix3Xd uniform_hemisphere(int n, unsigned seed) {
    std::mt19937_64 gen(seed);
    std::uniform_real_distribution<double> u(0, 1);
    Eigen::Matrix3Xd d(3, n);
    for (int i = 0; i < n; ++i) {
        const auto v = square_to_uniform_hemisphere(u(gen), u(gen));
        d.col(i) << v.x, v.y, v.z;
    }
    return d;
}

/// Values of sum_k amp(k, c) G_k at the directions (S x C).
Eigen::MatrixXd values_of(const std::vector<sg::Lobe<double>>& lobes, const Eigen::MatrixXd& amp,
                          const Eigen::Matrix3Xd& dirs) {
    return sg::design_matrix(lobes, dirs) * amp;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// One lobe: closed forms

TEST_CASE("sg: integral over the sphere is 2 pi a (1 - exp(-2 lambda)) / lambda", "[sg]") {
    const DirectionalRule rule = sphere_rule(160);
    for (double l : {0.0, 0.25, 1.0, 3.6, 6.7, 20.0}) {
        const auto g = lobe({0.3, -0.5, 0.8}, l, 1.75);
        double q = 0;
        for (std::size_t i = 0; i < rule.size(); ++i)
            q += rule.w[i] * sg::eval(g, rule.x[i], rule.y[i], rule.z[i]);
        const double closed = l == 0 ? 4 * pi * 1.75 : 2 * pi * 1.75 * (1 - std::exp(-2 * l)) / l;
        INFO("lambda " << l);
        CHECK(sg::integral(g) == Approx(closed).epsilon(1e-14));
        CHECK(q == Approx(closed).epsilon(1e-12));
        if (l > 0) CHECK(sg::integral_approx(g) == Approx(2 * pi * 1.75 / l).epsilon(1e-15));
    }
    // Small lambda: no cancellation (the series 4 pi a (1 - lambda + ...)).
    CHECK(sg::integral(lobe({0, 0, 1}, 1e-12, 1.0)) == Approx(4 * pi * (1 - 1e-12)).epsilon(1e-15));
}

TEST_CASE("sg: the product of two lobes is a lobe; inner product by quadrature", "[sg]") {
    const DirectionalRule rule = sphere_rule(200);
    const auto dirs = random_dirs(40, 3, false);
    const std::vector<std::pair<sg::Lobe<double>, sg::Lobe<double>>> pairs = {
        {lobe({0, 0, 1}, 2.0, 1.0), lobe({1, 0, 0}, 3.0, 0.5)},
        {lobe({0.2, 0.3, 0.9}, 5.5, 2.0), lobe({0.25, 0.3, 0.85}, 6.7, -1.5)},
        {lobe({0, 0, 1}, 4.0, 1.0), lobe({0, 0, -1}, 4.0, 3.0)},  // u = 0: a constant
    };
    for (const auto& [a, b] : pairs) {
        const sg::Lobe<double> p = sg::product(a, b);
        for (const Dir& d : dirs) {
            const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double x = d[0] / n, y = d[1] / n, z = d[2] / n;
            const double want = sg::eval(a, x, y, z) * sg::eval(b, x, y, z);
            CHECK(sg::eval(p, x, y, z) == Approx(want).epsilon(1e-13).margin(1e-300));
        }
        double q = 0;
        for (std::size_t i = 0; i < rule.size(); ++i)
            q += rule.w[i] * sg::eval(a, rule.x[i], rule.y[i], rule.z[i]) *
                 sg::eval(b, rule.x[i], rule.y[i], rule.z[i]);
        CHECK(sg::inner_product(a, b) == Approx(q).epsilon(1e-12));
    }
    const auto c = sg::product(pairs[2].first, pairs[2].second);
    CHECK(c.sharpness == 0);
    CHECK(c.amplitude == Approx(3 * std::exp(-8.0)).epsilon(1e-15));
}

TEST_CASE("sg: hemisphere_integral against the generator and the closed forms at the poles",
          "[sg]") {
    const auto& ref = reference();
    REQUIRE(ref.h.size() == 2 * (12 + 4) * 21);  // 12 sharpnesses and the 4 sets
    double worst = 0;
    for (const auto& h : ref.h) {
        const double v = sg::hemisphere_integral(h.lambda, h.c, h.p);
        worst = std::max(worst, std::fabs(v - h.value) / h.value);
    }
    INFO("worst relative error " << worst);
    CHECK(worst <= 1e-12);
    for (double l : {0.5, 3.0, 40.0}) {
        const double e = std::exp(-l);
        CHECK(sg::hemisphere_integral(l, 1.0) ==
              Approx(2 * pi * (l - 1 + e) / (l * l)).epsilon(1e-13));
        CHECK(sg::hemisphere_integral(l, -1.0) ==
              Approx(2 * pi * e * (1 - (1 + l) * e) / (l * l)).epsilon(1e-12));
        CHECK(sg::hemisphere_integral(l, 1.0, 0) == Approx(2 * pi * (1 - e) / l).epsilon(1e-13));
    }
    // lambda = 0: the clamped cosine integrates to pi, the hemisphere to 2 pi.
    CHECK(sg::hemisphere_integral(0, 0.3) == Approx(pi).epsilon(1e-14));
    CHECK(sg::hemisphere_integral(0, 0.3, 0) == Approx(2 * pi).epsilon(1e-14));
    // Halves of the sphere add up to the whole integral.
    for (double c : {-0.7, 0.0, 0.4}) {
        const double whole = sg::integral(lobe({0, 0, 1}, 4.0, 1.0));
        CHECK(sg::hemisphere_integral(4, c, 0) + sg::hemisphere_integral(4, -c, 0) ==
              Approx(whole).epsilon(1e-13));
    }
    REQUIRE_THROWS_WITH(sg::hemisphere_integral(1, 1.5),
                        "sphbasis::sg::hemisphere_integral(): expected -1 <= mu . n <= 1, got "
                        "1.500000");
    REQUIRE_THROWS_AS(sg::hemisphere_integral(-1, 0.5), std::invalid_argument);
    REQUIRE_THROWS_AS(sg::hemisphere_integral(1, 0.5, 2), std::invalid_argument);
}

TEST_CASE("sg: Hill's fitted irradiance against the exact integral", "[sg]") {
    // Per sharpness: the worst error over mu . n = -1, -0.9, ..., 1, normalised by the
    // approximate integral 2 pi a / lambda (the fit's own unit), and relative to the exact value
    // where that is above 1% of the unit. The table is printed; docs/techniques.md quotes it.
    const auto& ref = reference();
    std::map<double, std::pair<double, double>> worst;  // lambda -> (abs, rel)
    for (const auto& h : ref.h) {
        if (h.p != 1) continue;
        const sg::Lobe<double> g{0, 0, 1, h.lambda, 1.0};
        const double fit = sg::irradiance_fitted(g, h.c);
        const double unit = 2 * pi / h.lambda;
        auto& w = worst[h.lambda];
        w.first = std::max(w.first, std::fabs(fit - h.value) / unit);
        if (h.value > 0.01 * unit)
            w.second = std::max(w.second, std::fabs(fit - h.value) / h.value);
    }
    std::printf(
        "sg: Hill's fit against the exact irradiance (lambda: max |err| / (2 pi a / "
        "lambda), max relative err where E > 1%%):\n");
    double worst_from_1 = 0, worst_sets = 0;
    for (const auto& [l, w] : worst) {
        std::printf("  %-8.4g %.4f %.4f\n", l, w.first, w.second);
        if (l >= 1) worst_from_1 = std::max(worst_from_1, w.first);
        if (l > 3.5 && l < 7) worst_sets = std::max(worst_sets, w.first);
    }
    CHECK(worst_from_1 <= 0.02);
    CHECK(worst_sets <= 0.014);
    // Below lambda = 1 the fit is not usable: its scale 1 + 2 exp(-2 lambda) - 1/lambda turns
    // negative, and at lambda = 0.5 it gives a negative irradiance facing the lobe.
    CHECK(worst.at(0.5).first >= 0.3);
    CHECK(sg::irradiance_fitted(sg::Lobe<double>{0, 0, 1, 0.5, 1.0}, 1.0) < 0);
    // At mu . n = 1 the fit is exact up to exp(-2 lambda) (1 - 1/lambda) of the unit.
    for (double l : {5.0, 8.0, 24.0}) {  // where |0.36 mu . n| > x1: the saturate branch
        const sg::Lobe<double> g{0, 0, 1, l, 1.0};
        CHECK(sg::irradiance_fitted(g, 1.0) / (2 * pi / l) -
                  sg::hemisphere_integral(l, 1.0) / (2 * pi / l) ==
              Approx(std::exp(-2 * l) * (1 - 1 / l)).margin(1e-13));
    }
    // float and double agree; the batch path equals the scalar path.
    const sg::Lobe<float> gf{0, 0, 1, 5.5f, 2.0f};
    const sg::Lobe<double> gd{0, 0, 1, 5.5, 2.0};
    std::array<float, 16> c{}, out{};
    for (std::size_t i = 0; i < c.size(); ++i) c[i] = -1 + 2 * float(i) / 15;
    for (std::size_t i = 0; i < c.size(); i += batch<float>::size) {
        const auto b = sg::irradiance_fitted(gf, batch<float>::load(c.data() + i));
        b.store(out.data() + i);
    }
    for (std::size_t i = 0; i < c.size(); ++i) {
        CHECK(out[i] == Approx(sg::irradiance_fitted(gf, c[i])).epsilon(1e-6).margin(1e-6));
        CHECK(double(sg::irradiance_fitted(gf, c[i])) ==
              Approx(sg::irradiance_fitted(gd, double(c[i]))).epsilon(1e-5).margin(1e-6));
    }
    // At a normal: through mu . n.
    CHECK(sg::irradiance_fitted(gd, 0.6, 0.0, 0.8) == sg::irradiance_fitted(gd, 0.8));
    CHECK(sg::irradiance_exact(gd, 0.8) == Approx(2 * sg::hemisphere_integral(5.5, 0.8)));
}

// ---------------------------------------------------------------------------------------------
// The SIMD exp

TEMPLATE_TEST_CASE("sg: batch exp within 2 ulp of std::exp", "[sg]", float, double) {
    using T = TestType;
    using B = batch<T>;
    const T lo = std::is_same_v<T, float> ? T(-87) : T(-708);
    std::vector<T> x;
    for (int i = 0; i <= 20000; ++i) x.push_back(lo + (T(20) - lo) * T(i) / T(20000));
    for (T v : {T(0), T(-0.0), T(1e-30), T(-1e-30), T(-0.3465), T(0.3466)}) x.push_back(v);
    while (x.size() % B::size) x.push_back(T(0));
    double worst = 0;
    std::vector<T> y(x.size());
    for (std::size_t i = 0; i < x.size(); i += B::size)
        sg::detail::vexp(B::load(x.data() + i)).store(y.data() + i);
    for (std::size_t i = 0; i < x.size(); ++i) {
        const T want = std::exp(x[i]);
        worst = std::max(worst, double(std::fabs(y[i] - want)) /
                                    (double(want) * double(std::numeric_limits<T>::epsilon())));
    }
    INFO("worst ulp " << worst);
    CHECK(worst <= 2);
    // Below the range: 0; above: finite; NaN-free.
    std::array<T, 64> big{};
    for (std::size_t i = 0; i < big.size(); ++i) big[i] = (i % 2 ? T(-1) : T(1)) * T(1e30);
    for (std::size_t i = 0; i + B::size <= big.size(); i += B::size) {
        std::array<T, 64> r{};
        sg::detail::vexp(B::load(big.data() + i)).store(r.data());
        for (int j = 0; j < B::size; ++j) {
            CHECK(std::isfinite(r[std::size_t(j)]));
            if (big[i + std::size_t(j)] < 0) CHECK(r[std::size_t(j)] == 0);
        }
    }
}

// ---------------------------------------------------------------------------------------------
// BakingLab's lobe sets and the basis

TEST_CASE("sg: BakingLab's lobe sets", "[sg]") {
    const auto& ref = reference();
    for (int count : {5, 6, 9, 12}) {
        INFO("count " << count);
        const auto axes = sg::bakinglab_axes(count);
        REQUIRE(axes.size() == std::size_t(count));
        for (std::size_t k = 0; k < axes.size(); ++k) {
            const auto& a = axes[k];
            CHECK(a[0] * a[0] + a[1] * a[1] + a[2] * a[2] == Approx(1).epsilon(1e-15));
            // Heights (2j + 1) / (2 count), j = 0 .. count - 1: equal-area bands.
            CHECK(a[2] == Approx((2.0 * double(k) + 1) / (2 * count)).margin(1e-15));
        }
        CHECK(sg::bakinglab_sharpness(count) == Approx(ref.set_sharpness.at(count)).epsilon(1e-13));
        // The sphere set: count points, both hemispheres.
        const auto s = sg::bakinglab_axes(count, sg::Distribution::sphere);
        CHECK(s.size() == std::size_t(count));
        CHECK(s.front()[2] < 0);
        CHECK(s.back()[2] > 0);
    }
    CHECK(sg::bakinglab_sharpness(9) == Approx(5.5134907309).epsilon(1e-9));
    REQUIRE_THROWS_WITH(sg::bakinglab_axes(0),
                        "sphbasis::sg::bakinglab_axes(): expected 1 <= "
                        "count <= 64, got 0");
}

TEMPLATE_TEST_CASE("sg: the basis evaluates the unit lobes of the sets; batch equals scalar",
                   "[sg]", float, double) {
    using T = TestType;
    const BasisInfo& info = find_basis("sg");
    CHECK(info.domain == Domain::hemisphere);
    CHECK_FALSE(info.orthonormal);
    CHECK(info.valid_count(9));
    CHECK_FALSE(info.valid_count(7));
    for (int count : {5, 6, 9, 12}) {
        const auto lobes = sg::bakinglab_lobes(count);
        for (const Dir& d : random_dirs(10, 7, false)) {
            std::vector<double> v(std::size_t(count), 0.0);
            basis_eval<SphericalGaussian>(count, d[0], d[1], d[2], v.data());
            const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            for (int k = 0; k < count; ++k)
                CHECK(v[std::size_t(k)] ==
                      Approx(sg::eval(lobes[std::size_t(k)], d[0] / n, d[1] / n, d[2] / n))
                          .epsilon(1e-14));
        }
        const auto in = test::scaled_inputs<T>(random_dirs(37, 5, false), 3);
        std::vector<T> coeffs(static_cast<std::size_t>(count));
        for (std::size_t k = 0; k < coeffs.size(); ++k) coeffs[k] = T(std::sin(double(k) + 1));
        const T et = std::numeric_limits<T>::epsilon();
        // exp of an argument up to 2 lambda ~ 13.4 in magnitude: the argument's rounding
        // (~13.4 ulp) dominates float against double.
        test::check_batch_equals_scalar<SphericalGaussian, T>(count, coeffs, in, 8 * et,
                                                              40 * double(et), 40 * et);
    }
    double v[12];
    REQUIRE_THROWS_WITH(basis_eval<SphericalGaussian>(7, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected 5, 6, 9 or 12 functions for basis "
                        "'sg', got 7");
}

// ---------------------------------------------------------------------------------------------
// The solvers

TEST_CASE("sg: least squares fits a function made of the lobes back exactly", "[sg]") {
    for (int count : {5, 9, 12}) {
        INFO("count " << count);
        const auto lobes = sg::bakinglab_lobes(count);
        Eigen::MatrixXd amp(count, 3);
        for (int k = 0; k < count; ++k) amp.row(k) << std::sin(k + 1.0), std::cos(2.0 * k), 0.5 + k;
        // From samples.
        const Eigen::Matrix3Xd dirs = uniform_hemisphere(500, 11);
        const Eigen::MatrixXd fit = sg::fit_least_squares(lobes, dirs, values_of(lobes, amp, dirs));
        CHECK((fit - amp).cwiseAbs().maxCoeff() <= 1e-9);
        // From a function over the hemisphere (quadrature weights).
        const DirectionalRule rule = hemisphere_rule(40);
        Eigen::Matrix3Xd rd(3, Eigen::Index(rule.size()));
        for (std::size_t i = 0; i < rule.size(); ++i)
            rd.col(Eigen::Index(i)) << rule.x[i], rule.y[i], rule.z[i];
        const Eigen::MatrixXd f = values_of(lobes, amp, rd);
        CHECK((sg::fit_function(lobes, rule, f, sg::Solver::least_squares) - amp)
                  .cwiseAbs()
                  .maxCoeff() <= 1e-9);
    }
}

TEST_CASE("sg: NNLS gives non-negative amplitudes, equals LS when LS is non-negative", "[sg]") {
    const auto lobes = sg::bakinglab_lobes(9);
    const Eigen::Matrix3Xd dirs = uniform_hemisphere(400, 5);
    const Eigen::MatrixXd a = sg::design_matrix(lobes, dirs);
    // A non-negative combination: NNLS = LS = the amplitudes.
    Eigen::MatrixXd amp(9, 1);
    for (int k = 0; k < 9; ++k) amp(k, 0) = 0.25 + 0.1 * k;
    const Eigen::MatrixXd f = a * amp;
    const Eigen::MatrixXd ls = sg::fit_least_squares(lobes, dirs, f);
    const Eigen::MatrixXd nn = sg::fit_nnls(lobes, dirs, f);
    CHECK((ls - amp).cwiseAbs().maxCoeff() <= 1e-9);
    CHECK((nn - ls).cwiseAbs().maxCoeff() <= 1e-9);
    // A signal whose LS fit has negative amplitudes: a sharp light near the horizon plus a
    // negative-leaning mix. NNLS is >= 0 and satisfies the Kuhn-Tucker conditions.
    const sg::Lobe<double> sun = lobe({1, 0.2, 0.15}, 40.0, 10.0);
    Eigen::MatrixXd g(dirs.cols(), 1);
    for (Eigen::Index i = 0; i < dirs.cols(); ++i)
        g(i, 0) = sg::eval(sun, dirs(0, i), dirs(1, i), dirs(2, i)) + 0.1;
    const Eigen::MatrixXd ls2 = sg::fit_least_squares(lobes, dirs, g);
    REQUIRE(ls2.minCoeff() < 0);
    const Eigen::MatrixXd nn2 = sg::fit_nnls(lobes, dirs, g);
    CHECK(nn2.minCoeff() >= 0);
    const Eigen::VectorXd grad = a.transpose() * (g.col(0) - a * nn2.col(0));
    const double scale = (a.transpose() * g.col(0)).cwiseAbs().maxCoeff();
    for (int k = 0; k < 9; ++k) {
        if (nn2(k, 0) > 0)
            CHECK(std::fabs(grad(k)) <= 1e-10 * scale);  // stationary on the free set
        else
            CHECK(grad(k) <= 1e-10 * scale);  // no descent into the bound
    }
    // Its residual is no smaller than LS's, and no larger than any other feasible point's.
    const double r_ls = (a * ls2 - g).squaredNorm(), r_nn = (a * nn2 - g).squaredNorm();
    CHECK(r_nn >= r_ls);
    CHECK(r_nn <= (a * ls2.cwiseMax(0.0) - g).squaredNorm());
    REQUIRE_THROWS_WITH(sg::fit_nnls(lobes, dirs, Eigen::MatrixXd(3, 1)),
                        "sphbasis::sg::fit_nnls(): expected one row of values per direction "
                        "(400), got 3");
}

TEST_CASE("sg: the running average converges to the least-squares fit", "[sg]") {
    const auto lobes = sg::bakinglab_lobes(9);
    Eigen::MatrixXd amp(9, 1);
    for (int k = 0; k < 9; ++k) amp(k, 0) = 1.0 + 0.5 * std::sin(3.0 * k);
    const int total = 1 << 18;
    const Eigen::Matrix3Xd dirs = uniform_hemisphere(total, 21);
    const Eigen::MatrixXd f = values_of(lobes, amp, dirs);
    sg::RunningAverage ra(lobes, 1, sg::Distribution::hemisphere);
    sg::RunningAverage ra_nn(lobes, 1, sg::Distribution::hemisphere, true);
    // The error of the reconstruction over the hemisphere, relative to the signal.
    const DirectionalRule rule = hemisphere_rule(30);
    Eigen::Matrix3Xd rd(3, Eigen::Index(rule.size()));
    Eigen::VectorXd w(Eigen::Index(rule.size()));
    for (std::size_t i = 0; i < rule.size(); ++i) {
        rd.col(Eigen::Index(i)) << rule.x[i], rule.y[i], rule.z[i];
        w(Eigen::Index(i)) = rule.w[i];
    }
    const Eigen::MatrixXd a = sg::design_matrix(lobes, rd);
    const double energy = w.dot((a * amp).cwiseAbs2().col(0));
    auto rel_error = [&](const Eigen::MatrixXd& x) {
        return std::sqrt(w.dot((a * (x - amp)).cwiseAbs2().col(0)) / energy);
    };
    std::vector<double> errors;
    for (int i = 0; i < total; ++i) {
        const double v = f(i, 0);
        ra.add(dirs(0, i), dirs(1, i), dirs(2, i), &v);
        ra_nn.add(dirs(0, i), dirs(1, i), dirs(2, i), &v);
        if (((i + 1) & i) == 0 && i + 1 >= 1024) errors.push_back(rel_error(ra.amplitudes()));
    }
    std::printf("sg: running average, relative L2 error after 2^10 .. 2^18 samples:");
    for (double e : errors) std::printf(" %.4f", e);
    std::printf("\n");
    CHECK(ra.samples() == total);
    // Decreasing, and small at the end.
    CHECK(errors.back() < 0.5 * errors.front());
    CHECK(errors.back() <= 0.05);
    CHECK(ra_nn.amplitudes().minCoeff() >= 0);
    CHECK(rel_error(ra_nn.amplitudes()) <= 0.05);
}

// ---------------------------------------------------------------------------------------------
// BakingLab's pipeline in the IMSE benchmark (ops/imse.hpp)

TEST_CASE("sg: the IMSE of BakingLab's SG pipeline", "[sg][imse]") {
    const Eigen::Matrix3Xd dirs = imse::sg_sample_directions();
    REQUIRE(dirs.cols() == 625);
    CHECK(dirs.row(2).minCoeff() >= 0);
    CHECK((dirs.colwise().norm().array() - 1).abs().maxCoeff() <= 1e-15);
    // Stratified in z: 25 directions per band of height 1/25.
    for (int band = 0; band < 25; ++band) {
        int in = 0;
        for (Eigen::Index i = 0; i < dirs.cols(); ++i)
            in += dirs(2, i) >= band / 25.0 && dirs(2, i) < (band + 1) / 25.0;
        CHECK(in == 25);
    }
    const Eigen::MatrixXd c = imse::random_radiance(3, 40);
    const DirectionalRule rule = imse::paper_rule();
    for (auto solver : {sg::Solver::least_squares, sg::Solver::nnls, sg::Solver::running_average,
                        sg::Solver::running_average_nn}) {
        INFO("solver " << int(solver));
        const Eigen::VectorXd v = imse::sg_pipeline_imse(9, solver, c, dirs, rule);
        REQUIRE(v.size() == 40);
        CHECK(v.minCoeff() > 0);
        // Every solver is positively homogeneous, so the IMSE is of degree 2.
        const Eigen::VectorXd v2 = imse::sg_pipeline_imse(9, solver, 2.5 * c, dirs, rule);
        CHECK((v2 - 6.25 * v).cwiseAbs().maxCoeff() <= 1e-10 * v.maxCoeff());
        // The rule integrates the pipeline's residual: the finer rule agrees. Hill's fit switches
        // branches with a continuous first derivative only, so the rule converges algebraically
        // (measured 1e-5 of the value).
        const Eigen::VectorXd vf =
            imse::sg_pipeline_imse(9, solver, c.leftCols(4), dirs, imse::paper_check_rule());
        CHECK((vf - v.head(4)).cwiseAbs().maxCoeff() <= 1e-4 * v.head(4).maxCoeff());
    }
    // The linear solvers: the closed form c^T Q c equals the direct computation.
    for (auto solver : {sg::Solver::least_squares, sg::Solver::running_average}) {
        const Eigen::MatrixXd q = imse::sg_pipeline_residual_form(9, solver, dirs, rule);
        const Eigen::VectorXd v = imse::sg_pipeline_imse(9, solver, c.leftCols(5), dirs, rule);
        for (int s = 0; s < 5; ++s) CHECK(imse::imse_of(q, c.col(s)) == Approx(v(s)).epsilon(1e-9));
    }
    CHECK_THROWS_AS(imse::sg_pipeline_residual_form(9, sg::Solver::nnls, dirs, rule),
                    std::invalid_argument);
    // The irradiance's scale: a constant radiance (c_0 only) ends up within a few percent (the
    // radiance below the horizon, which the pipeline never samples, is replaced by the lobes'
    // tails; measured 0.040).
    Eigen::MatrixXd one = Eigen::MatrixXd::Zero(9, 1);
    one(0, 0) = 1;
    const double e2 = 0.28209479177387814 * 0.28209479177387814 * 2 * pi;  // int E^2, E = y_00
    const double rel = imse::sg_pipeline_imse(12, sg::Solver::least_squares, one, dirs)(0) / e2;
    std::printf("sg: pipeline, constant radiance, SG12 least squares: relative IMSE %.5f\n", rel);
    CHECK(rel <= 0.05);
}
