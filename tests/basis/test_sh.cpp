// Tests for basis/sh.hpp: conventions, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <catch2/catch.hpp>
#include <climits>
#include <cmath>
#include <fstream>
#include <glm/vec3.hpp>
#include <limits>
#include <sphbasis/basis/hsh.hpp>
#include <sphbasis/basis/makhotkin.hpp>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "../support/basis_checks.hpp"

using namespace sphbasis;

namespace {

std::vector<double> eval_d(int bands, double x, double y, double z) {
    std::vector<double> v(static_cast<std::size_t>(bands * bands));
    sh::eval(bands, x, y, z, v.data());
    return v;
}

/// Directions over the whole sphere.
std::vector<test::Dir> sphere_dirs(int n, unsigned seed) {
    return test::random_dirs(n, seed, false);
}

double norm_s(int l) { return std::sqrt((2 * l + 1) / (4 * constants::pi)); }

}  // namespace

TEST_CASE("sh: band 0-2 values and signs pin the convention (no Condon-Shortley phase)", "[sh]") {
    const double x = 0.48, y = -0.6, z = 0.64;  // unit
    const auto v = eval_d(3, x, y, z);
    const double c1 = 0.48860251190291992;  // sqrt(3/(4 pi))
    const double c2 = 1.0925484305920792;   // sqrt(15/(4 pi))
    CHECK(v[0] == Approx(0.28209479177387814).epsilon(1e-15));
    CHECK(v[1] == Approx(c1 * y).epsilon(1e-15));  // y_1-1 = +c y
    CHECK(v[2] == Approx(c1 * z).epsilon(1e-15));  // y_10 = +c z
    CHECK(v[3] == Approx(c1 * x).epsilon(1e-15));  // y_11 = +c x
    CHECK(v[4] == Approx(c2 * x * y).epsilon(1e-15));
    CHECK(v[5] == Approx(c2 * y * z).epsilon(1e-15));
    CHECK(v[6] == Approx(0.31539156525252001 * (3 * z * z - 1))
                      .margin(4e-16));  // cancellation in 3z^2-1: absolute
    CHECK(v[7] == Approx(c2 * x * z).epsilon(1e-15));
    CHECK(v[8] == Approx(0.54627421529603959 * (x * x - y * y)).epsilon(1e-15));
    CHECK(sh::index(2, -1) == 5);
    CHECK(sh::count(4) == 16);
}

namespace {
void check_sh_gram(int bands) {
    const auto rule = sphere_rule(2 * (bands - 1));
    const int n = bands * bands;
    std::vector<double> g(static_cast<std::size_t>(n * n), 0.0), y(static_cast<std::size_t>(n));
    for (std::size_t i = 0; i < rule.size(); ++i) {
        sh::eval_unit(bands, rule.x[i], rule.y[i], rule.z[i], y.data());
        for (int a = 0; a < n; ++a)
            for (int b = 0; b <= a; ++b)
                g[static_cast<std::size_t>(a * n + b)] +=
                    rule.w[i] * y[static_cast<std::size_t>(a)] * y[static_cast<std::size_t>(b)];
    }
    double worst = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b <= a; ++b)
            worst = std::max(worst, std::fabs(g[static_cast<std::size_t>(a * n + b)] - (a == b)));
    INFO("bands " << bands);
    CHECK(worst < 1e-12);
}
}  // namespace

TEST_CASE("sh: Gram matrix is the identity by exact quadrature", "[sh]") {
    for (int bands : {1, 3, 8, 9, 20}) check_sh_gram(bands);
}

// 40 bands: 1.3 M products a point on 3160 points (79 s under the -O0 sanitizer build).
TEST_CASE("sh: Gram matrix is the identity by exact quadrature, 40 bands", "[sh][slow]") {
    check_sh_gram(40);
}

TEST_CASE("sh: addition theorem sum_m y_lm^2 = (2l+1)/(4 pi) to 100 bands", "[sh]") {
    for (const auto& d : sphere_dirs(20, 7)) {
        const auto v = eval_d(100, d[0], d[1], d[2]);
        for (int l = 0; l < 100; ++l) {
            double s = 0;
            for (int m = -l; m <= l; ++m)
                s += v[static_cast<std::size_t>(sh::index(l, m))] *
                     v[static_cast<std::size_t>(sh::index(l, m))];
            REQUIRE(std::fabs(s - norm_s(l) * norm_s(l)) <=
                    1e-13 * norm_s(l) * norm_s(l) * (l + 1));
        }
    }
}

TEST_CASE("sh: unrolled kernels, row recurrence and column recurrence agree", "[sh]") {
    auto dirs = sphere_dirs(200, 11);
    dirs.push_back({0, 0, 1});
    dirs.push_back({0, 0, -1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({std::sqrt(0.5), -std::sqrt(0.5), 0});
    for (int bands = 1; bands <= 8; ++bands) {
        const int n = bands * bands;
        for (const auto& d : dirs) {
            std::vector<double> fixed(static_cast<std::size_t>(n)), rows(fixed), cols(fixed);
            auto put = [](std::vector<double>& v) {
                return [&v](int k, double x) { v[static_cast<std::size_t>(k)] = x; };
            };
            sh::detail::with_bands_kernel(bands, [&](auto k) { k(d[0], d[1], d[2], put(fixed)); });
            sh::detail::eval_rows(bands, d[0], d[1], d[2], put(rows));
            sh::detail::eval_columns(bands, d[0], d[1], d[2], put(cols));
            for (int k = 0; k < n; ++k) {
                const int l = sh::degree_of(k);
                // Worst measured over these directions, in eps * S_l: rows 3.5, columns 4.1 with
                // FMA (x86-64-v3, native AVX-512); rows 5.0, columns 8.5 without (x86-64, SSE2:
                // every multiply-add rounded twice). Bound 16 on every target.
                const double tol = 16 * std::numeric_limits<double>::epsilon() * norm_s(l);
                REQUIRE(std::fabs(fixed[static_cast<std::size_t>(k)] -
                                  rows[static_cast<std::size_t>(k)]) <= tol);
                REQUIRE(std::fabs(fixed[static_cast<std::size_t>(k)] -
                                  cols[static_cast<std::size_t>(k)]) <= tol);
            }
        }
    }
    // Row (<= 64 bands) against column recurrence at the switch-over.
    for (const auto& d : sphere_dirs(20, 12)) {
        std::vector<double> rows(64 * 64), cols(64 * 64);
        sh::detail::eval_rows(64, d[0], d[1], d[2],
                              [&](int k, double x) { rows[static_cast<std::size_t>(k)] = x; });
        sh::detail::eval_columns(64, d[0], d[1], d[2],
                                 [&](int k, double x) { cols[static_cast<std::size_t>(k)] = x; });
        for (int k = 0; k < 64 * 64; ++k)
            REQUIRE(
                std::fabs(rows[static_cast<std::size_t>(k)] - cols[static_cast<std::size_t>(k)]) <=
                1e-13 * norm_s(sh::degree_of(k)));
    }
}

TEST_CASE("sh: prefix property and eval_lm", "[sh]") {
    const auto d = sphere_dirs(1, 3)[0];
    const auto big = eval_d(70, d[0], d[1], d[2]);
    for (int k : {1, 2, 3, 8, 9, 31, 64, 65}) {
        const auto small = eval_d(k, d[0], d[1], d[2]);
        for (int i = 0; i < k * k; ++i)
            REQUIRE(
                std::fabs(small[static_cast<std::size_t>(i)] - big[static_cast<std::size_t>(i)]) <=
                1e-13 * norm_s(sh::degree_of(i)));
    }
    for (int l : {0, 1, 5, 33, 69})
        for (int m : {-l, -l / 2, 0, l / 3, l})
            REQUIRE(std::fabs(sh::eval_lm(l, m, d[0], d[1], d[2]) -
                              big[static_cast<std::size_t>(sh::index(l, m))]) <= 1e-13 * norm_s(l));
}

TEST_CASE("sh: compile-time band count and vector adapters", "[sh]") {
    float a[16], b[16];
    sh::eval<4>(0.3f, -0.2f, 0.9f, a);
    sh::eval(4, glm::vec3(0.3f, -0.2f, 0.9f), b);
    // Same kernels, but inlining may contract different products into FMAs: a few ulp.
    for (int k = 0; k < 16; ++k) CHECK(std::fabs(a[k] - b[k]) <= 4e-7f);
    double c[100], e[100];
    sh::eval<10>(0.3, -0.2, 0.9, c);
    sh::eval(10, vec3<double>{0.3, -0.2, 0.9}, e);
    for (int k = 0; k < 100; ++k) CHECK(std::fabs(c[k] - e[k]) <= 1e-14);
}

TEMPLATE_TEST_CASE("sh: batch path equals scalar path", "[sh]", float, double) {
    using T = TestType;
    // 37: not a multiple of any SIMD width; * 3: non-unit on purpose, both paths normalise.
    const auto in = test::scaled_inputs<T>(sphere_dirs(37, 5), 3);
    const auto &xs = in.xs, &ys = in.ys, &zs = in.zs;
    const std::size_t n = in.size();
    for (int bands : {1, 2, 3, 5, 8, 9, 17, 64, 66}) {
        const std::size_t nf = static_cast<std::size_t>(bands * bands);
        std::vector<T> out(nf * n), one(nf), coeffs(nf), sums(n);
        for (std::size_t k = 0; k < nf; ++k) coeffs[k] = T(std::sin(double(k) + 1));
        sh::eval_batch(bands, n, xs.data(), ys.data(), zs.data(), out.data(), n);
        sh::eval_sum_batch(bands, coeffs.data(), n, xs.data(), ys.data(), zs.data(), sums.data());
        for (std::size_t i = 0; i < n; ++i) {
            sh::eval(bands, xs[i], ys[i], zs[i], one.data());
            T dot = 0;
            for (std::size_t k = 0; k < nf; ++k) {
                const int l = sh::degree_of(int(k));
                const T tol = T(2 * (l + 1)) * std::numeric_limits<T>::epsilon() * T(norm_s(l));
                REQUIRE(std::fabs(out[k * n + i] - one[k]) <= tol);
                dot += coeffs[k] * one[k];
            }
            const T s1 = sh::eval_sum(bands, coeffs.data(), xs[i], ys[i], zs[i]);
            const T tol = T(64) * std::numeric_limits<T>::epsilon() * T(bands * bands);
            REQUIRE(std::fabs(s1 - dot) <= tol);
            REQUIRE(std::fabs(sums[i] - dot) <= tol);
        }
    }
}

TEST_CASE("sh: float is within a stated bound of double", "[sh]") {
    // Bound: |float - double| <= 8 (l + 1) ulp(float) * S_l, measured worst ~2(l+1) ulp.
    for (const auto& d : sphere_dirs(100, 9)) {
        for (int bands : {3, 8, 31}) {
            std::vector<float> f(static_cast<std::size_t>(bands * bands));
            std::vector<double> dd(f.size());
            sh::eval(bands, float(d[0]), float(d[1]), float(d[2]), f.data());
            sh::eval(bands, double(float(d[0])), double(float(d[1])), double(float(d[2])),
                     dd.data());
            for (std::size_t k = 0; k < f.size(); ++k) {
                const int l = sh::degree_of(int(k));
                REQUIRE(std::fabs(double(f[k]) - dd[k]) <=
                        8.0 * (l + 1) * std::numeric_limits<float>::epsilon() * norm_s(l));
            }
        }
    }
}

TEST_CASE("sh: Condon-Shortley conversion", "[sh]") {
    // f = sum c_k y_k must equal sum c'_k y'_k with y' the Condon-Shortley functions
    // (y'_lm = (-1)^m y_lm for the real basis), e.g. google's y'_11 = -sqrt(3/4pi) x.
    std::vector<double> c(16), cs(16);
    for (int k = 0; k < 16; ++k)
        c[static_cast<std::size_t>(k)] = cs[static_cast<std::size_t>(k)] = 0.1 * (k + 1);
    sh::to_condon_shortley(4, cs.data());
    const auto v = eval_d(4, 0.2, 0.3, 0.9327379053088815);
    double f = 0, fcs = 0;
    for (int l = 0; l < 4; ++l)
        for (int m = -l; m <= l; ++m) {
            const std::size_t k = static_cast<std::size_t>(sh::index(l, m));
            f += c[k] * v[k];
            fcs += cs[k] * ((m & 1) ? -v[k] : v[k]);
        }
    CHECK(fcs == Approx(f).epsilon(1e-14));
    CHECK(cs[3] == -c[3]);
    CHECK(cs[2] == c[2]);
    sh::from_condon_shortley(4, cs.data());
    CHECK(cs == c);
}

TEST_CASE("sh: hard directions stay finite and accurate", "[sh]") {
    // Poles, x = y = 0, equator, within 1e-12 of the poles, non-unit and denormal input.
    const double e = 1e-12;
    const std::vector<std::array<double, 3>> hard = {{0, 0, 1},
                                                     {0, 0, -1},
                                                     {1, 0, 0},
                                                     {0, 1, 0},
                                                     {e, 0, 1},
                                                     {0, -e, -1},
                                                     {e, e, 1},
                                                     {1e-300, 0, 1},
                                                     {0.5, 0.5, 0},
                                                     {3e-310, 2e-310, 1e-310},
                                                     {1e300, 1e300, 1e300}};
    for (int bands : {3, 31, 200, 2001}) {
        std::vector<double> v(static_cast<std::size_t>(bands * bands));
        for (const auto& d : hard) {
            sh::eval(bands, d[0], d[1], d[2], v.data());
            for (double x : v) REQUIRE(std::isfinite(x));
        }
    }
    // At the north pole only m = 0 survives: y_l0 = S_l, within the bound.
    const auto v = eval_d(300, 0, 0, 1);
    for (int l = 0; l < 300; ++l)
        for (int m = -l; m <= l; ++m)
            REQUIRE(std::fabs(v[static_cast<std::size_t>(sh::index(l, m))] -
                              (m == 0 ? norm_s(l) : 0.0)) <=
                    (1e-12 + l * double(l) * 1.1e-16) * norm_s(l));
}

TEST_CASE("sh: bad input has its documented outcome", "[sh]") {
    double v[9], pole[9];
    sh::eval(3, 0.0, 0.0, 1.0, pole);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    for (auto d :
         std::vector<std::array<double, 3>>{{0, 0, 0}, {nan, 0, 1}, {0, inf, 0}, {nan, nan, nan}}) {
        sh::eval(3, d[0], d[1], d[2], v);
        for (int k = 0; k < 9; ++k) REQUIRE(v[k] == pole[k]);
    }
    REQUIRE_THROWS_WITH(sh::eval(-1, 0.0, 0.0, 1.0, v), Catch::Contains("expected 0 <= bands"));
    REQUIRE_THROWS_WITH(sh::eval(sh::max_bands + 1, 0.0, 0.0, 1.0, v), Catch::Contains("bands"));
    REQUIRE_THROWS_AS(sh::eval_lm(2, 3, 0.0, 0.0, 1.0), std::invalid_argument);
    REQUIRE_THROWS_AS(sh::eval_lm(-1, 0, 0.0, 0.0, 1.0), std::invalid_argument);
    float xs[2] = {0, 1}, out[2];
    REQUIRE_THROWS_WITH(sh::eval_batch(1, 2, xs, xs, xs, out, 1), Catch::Contains("stride"));
    sh::eval(0, 0.0, 0.0, 1.0, v);  // zero bands: nothing to do, no throw
}

TEMPLATE_TEST_CASE("sh: bad input in the batch paths gives the pole", "[sh]", float, double) {
    // Mixed batches (good and bad lanes together, at several offsets) go through the slow
    // normalisation path; every bad lane must come out as the pole (0, 0, 1), every good lane
    // as the scalar path gives it. 3 bands use the quadratic sum kernel, 4 the generic one.
    using T = TestType;
    const T nan = std::numeric_limits<T>::quiet_NaN(), inf = std::numeric_limits<T>::infinity();
    const std::size_t n = 67;
    std::vector<T> xs(n), ys(n), zs(n);
    for (std::size_t i = 0; i < n; ++i) {
        xs[i] = T(std::sin(1.0 + double(i)));
        ys[i] = T(std::cos(2.0 * double(i)));
        zs[i] = T(0.3 - 0.01 * double(i));
        if (i % 7 == 3) xs[i] = nan;
        if (i % 11 == 5) xs[i] = ys[i] = zs[i] = 0;
        if (i % 13 == 8) zs[i] = -inf;
    }
    for (int bands : {3, 4}) {
        const std::size_t nf = static_cast<std::size_t>(bands * bands);
        std::vector<T> coeffs(nf), pole(nf), one(nf), out(nf * n), sums(n);
        for (std::size_t k = 0; k < nf; ++k) coeffs[k] = T(0.5 + std::cos(double(k)));
        // The pole evaluated at run time, as the bad lanes are: with sh::eval inlined, constant
        // (0, 0, 1) would be folded at compile time, without the FMA contraction of the run-time
        // code (1 ulp apart at y_30).
        volatile T pole_z = T(1);
        sh::eval(bands, T(0), T(0), T(pole_z), pole.data());
        sh::eval_batch(bands, n, xs.data(), ys.data(), zs.data(), out.data(), n);
        sh::eval_sum_batch(bands, coeffs.data(), n, xs.data(), ys.data(), zs.data(), sums.data());
        for (std::size_t i = 0; i < n; ++i) {
            const bool bad = i % 7 == 3 || i % 11 == 5 || i % 13 == 8;
            sh::eval(bands, xs[i], ys[i], zs[i], one.data());
            double dot = 0;
            for (std::size_t k = 0; k < nf; ++k) {
                INFO("bands " << bands << " direction " << i << " function " << k);
                REQUIRE(std::isfinite(out[k * n + i]));
                if (bad) REQUIRE(one[k] == pole[k]);
                REQUIRE(std::fabs(out[k * n + i] - one[k]) <=
                        8 * std::numeric_limits<T>::epsilon());
                dot += double(coeffs[k]) * double(one[k]);
            }
            INFO("bands " << bands << " direction " << i);
            REQUIRE(std::isfinite(sums[i]));
            REQUIRE(std::fabs(double(sums[i]) - dot) <= 32 * std::numeric_limits<T>::epsilon());
        }
    }
}

TEST_CASE("sh: band count of a function count", "[sh]") {
    // Against a plain integer search, across the no-sqrt range (<= 8 bands) and beyond it.
    for (int n = -3; n <= 20000; ++n) {
        int expect = -1;
        for (int b = 1; b * b <= n; ++b)
            if (b * b == n) expect = b;
        INFO("n = " << n);
        REQUIRE(sh::bands_of_count(n) == expect);
        REQUIRE(SH::bands_of(n) == expect);
    }
    REQUIRE(sh::bands_of_count(8192 * 8192) == 8192);
    REQUIRE(sh::bands_of_count(8192 * 8192 - 1) == -1);
    REQUIRE(sh::bands_of_count(46340 * 46340) == 46340);
}

// The one-direction row path keeps every row's Q on the stack: the size documented in sh.hpp.
static_assert(sh::detail::RowTable<double>::size_for(sh::detail::max_row_bands) == 2296);

TEST_CASE("sh: the double row path (65..256 bands) agrees with the column path", "[sh]") {
    // Two different recurrences (rows on Q = Pbar / sin^m in z, columns on Pbar in l with
    // exponent-carried sectoral starts) must agree within the accuracy bound, near the poles
    // too, where the rows multiply a large Q by an underflowing sin^m.
    auto dirs = sphere_dirs(20, 17);
    for (double e : {1e-12, 1e-9, 1e-6, 1e-3}) {
        dirs.push_back({e, 0, std::sqrt(1 - e * e)});
        dirs.push_back({0.6 * e, -0.8 * e, -std::sqrt(1 - e * e)});
    }
    dirs.push_back({0, 0, 1});
    dirs.push_back({0, 0, -1});
    dirs.push_back({1, 0, 0});
    for (int bands : {65, 100, 256}) {
        const std::size_t nf = static_cast<std::size_t>(bands * bands);
        std::vector<double> rows(nf), cols(nf);
        for (const auto& d : dirs) {
            sh::eval(bands, d[0], d[1], d[2], rows.data());
            sh::detail::eval_columns(bands, d[0], d[1], d[2], [&](int k, double v) {
                cols[static_cast<std::size_t>(k)] = v;
            });
            for (int l = 0; l < bands; ++l)
                for (int m = -l; m <= l; ++m) {
                    const std::size_t k = static_cast<std::size_t>(sh::index(l, m));
                    INFO("bands " << bands << " l " << l << " m " << m << " dir " << d[0] << ","
                                  << d[1] << "," << d[2]);
                    REQUIRE(std::isfinite(rows[k]));
                    REQUIRE(std::fabs(rows[k] - cols[k]) <=
                            (1e-12 + l * double(l) * 1.1e-16) * norm_s(l));
                }
        }
    }
}

TEST_CASE("sh: values against the mpmath reference (l <= 2000)", "[sh][reference]") {
    std::ifstream in(SPHBASIS_TEST_DATA_DIR "/sh_reference.txt");
    REQUIRE(in.good());
    std::string line;
    long count = 0;
    double worst = 0;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream is(line);
        int l, m;
        double x, y, z, ref;
        REQUIRE(static_cast<bool>(is >> l >> m >> x >> y >> z >> ref));
        const double s = norm_s(l);
        const double bound = l <= 100 ? 1e-12 * s : (1e-12 + l * double(l) * 1.1e-16) * s;
        const double got = sh::eval_lm(l, m, x, y, z);
        // The full evaluation path too: unrolled (l < 8), rows in T (l < 64) and rows in double
        // (l < 256). Above, eval() and eval_lm share the column recurrence.
        if (l < 256) {
            const auto v = eval_d(l + 1, x, y, z);
            REQUIRE(std::fabs(v[static_cast<std::size_t>(sh::index(l, m))] - ref) <= bound);
        }
        INFO("l=" << l << " m=" << m << " dir=" << x << "," << y << "," << z);
        REQUIRE(std::fabs(got - ref) <= bound);
        worst = std::max(worst, std::fabs(got - ref) / s);
        ++count;
    }
    CHECK(count > 1000);
    WARN("sh reference: " << count << " values, worst |error|/S = " << worst);
}

TEST_CASE("sh: counts near the int range are refused, never wrapped or looped on", "[sh]") {
    using namespace sphbasis;
    CHECK(sh::count(46340) == 2147395600);
    CHECK_THROWS_WITH(sh::count(46341),
                      Catch::Contains("sh::count(): expected 0 <= bands <= 46340"));
    CHECK_THROWS_AS(sh::count(100000), std::invalid_argument);
    CHECK_THROWS_AS(sh::count(-1), std::invalid_argument);
    CHECK(sh::degree_of(2147395599) == 46339);
    CHECK(sh::degree_of(2147395600) == 46340);
    CHECK(sh::degree_of(INT_MAX) == 46340);
    CHECK(sh::bands_of_count(2147395600) == 46340);
    for (int n : {2147395601, INT_MAX - 1, INT_MAX}) {
        CHECK(sh::bands_of_count(n) == -1);
        std::vector<double> y(4);
        CHECK_THROWS_AS(basis_eval<SH>(n, 0.0, 0.0, 1.0, y.data()), std::invalid_argument);
        CHECK_THROWS_AS(evaluator<SH>(n), std::invalid_argument);
        CHECK_THROWS_AS(basis_eval<HSH>(n, 0.0, 0.0, 1.0, y.data()), std::invalid_argument);
        CHECK_THROWS_AS(basis_eval<Makhotkin>(n, 0.0, 0.0, 1.0, y.data()), std::invalid_argument);
    }
}

TEMPLATE_TEST_CASE("sh: eval_batch_aos (interleaved x y z) equals eval_batch (SoA)", "[sh]", float,
                   double) {
    using T = TestType;
    const int W = sphbasis::native_width<T>;
    // Counts around the SIMD width (tails of every length), a few whole batches plus a tail, and
    // more than two blocks of the deinterleaving (sh::detail::aos_block);
    // inputs * 3: not unit length, both paths normalise.
    for (const int n : {0, 1, W - 1, W, W + 1, 3 * W + 5, 2 * 256 + 7}) {
        const auto in = test::scaled_inputs<T>(sphere_dirs(std::max(n, 1), 11), 3);
        const std::size_t nd = static_cast<std::size_t>(n);
        std::vector<T> xyz(3 * nd);
        for (std::size_t i = 0; i < nd; ++i) {
            xyz[3 * i] = in.xs[i];
            xyz[3 * i + 1] = in.ys[i];
            xyz[3 * i + 2] = in.zs[i];
        }
        for (int bands : {1, 3, 6, 8, 9, 17}) {
            const std::size_t nf = static_cast<std::size_t>(bands * bands);
            const std::size_t stride = nd + 3;
            std::vector<T> soa(nf * stride, T(-7)), aos(nf * stride, T(-7));
            sh::eval_batch(bands, nd, in.xs.data(), in.ys.data(), in.zs.data(), soa.data(), stride);
            sh::eval_batch_aos(bands, nd, xyz, aos, stride);  // ranges: sizes checked
            for (std::size_t k = 0; k < nf; ++k)
                for (std::size_t i = 0; i < stride; ++i) {
                    const T tol = T(4) * std::numeric_limits<T>::epsilon() *
                                  T(norm_s(sh::degree_of(static_cast<int>(k))));
                    REQUIRE(std::fabs(aos[k * stride + i] - soa[k * stride + i]) <= tol);
                }
        }
    }
    // The pole for zero and non-finite directions, as eval_batch.
    const T inf = std::numeric_limits<T>::infinity();
    std::vector<T> bad = {0, 0, 0, inf, 1, 2, 0, 0, 5}, out(9 * 3);
    sh::eval_batch_aos(3, 3, bad.data(), out.data(), 3);
    T pole[9];
    sh::eval<3>(T(0), T(0), T(1), pole);
    for (std::size_t k = 0; k < 9; ++k)
        for (std::size_t i = 0; i < 3; ++i) CHECK(out[k * 3 + i] == Approx(pole[k]).margin(1e-6));
}

TEST_CASE("sh: eval_batch_aos checks its buffers and stride", "[sh]") {
    std::vector<float> xyz(3 * 5), out(9 * 5);
    REQUIRE_THROWS_WITH(sh::eval_batch_aos(3, 5, xyz, out, 4),
                        Catch::Contains("sphbasis::sh::eval_batch_aos(): expected stride >= "
                                        "directions"));
    REQUIRE_THROWS_WITH(sh::eval_batch_aos(3, 6, xyz, out, 6),
                        Catch::Contains("sphbasis::sh::eval_batch_aos(): expected direction "
                                        "buffer of at least 18 elements, got 15"));
    REQUIRE_THROWS_WITH(sh::eval_batch_aos(4, 5, xyz, out, 5),
                        Catch::Contains("expected output buffer of at least 80 elements, got 45"));
    REQUIRE_THROWS_WITH(sh::eval_batch_aos(-1, 5, xyz, out, 5),
                        Catch::Contains("sphbasis::sh::eval_batch_aos()"));
    const float* null = nullptr;
    REQUIRE_THROWS_WITH(sh::eval_batch_aos(3, 5, null, out, 5),
                        Catch::Contains("non-null direction buffer"));
    REQUIRE_NOTHROW(sh::eval_batch_aos(3, 0, null, out, 0));
}

TEST_CASE("sh: value-returning Condon-Shortley conversions", "[sh]") {
    std::vector<double> c(16);
    for (std::size_t k = 0; k < 16; ++k) c[k] = 0.1 * double(k + 1);
    std::vector<double> in_place = c;
    sh::to_condon_shortley(4, in_place);
    const std::vector<double> cs = sh::to_condon_shortley(c);  // c is left as it was
    CHECK(cs == in_place);
    CHECK(c[3] == Approx(0.4));
    CHECK(cs[3] == -c[3]);  // (l, m) = (1, 1): odd m flips
    CHECK(cs[4] == c[4]);   // (2, -2): even m stays
    CHECK(sh::from_condon_shortley(cs) == c);
    CHECK(sh::from_condon_shortley(sh::to_condon_shortley(std::vector<double>(c))) == c);
    // std::array: the band count from the size.
    const std::array<float, 9> a{1, 2, 3, 4, 5, 6, 7, 8, 9};
    const std::array<float, 9> b = sh::to_condon_shortley(a);
    const std::array<float, 9> want{1, -2, 3, -4, 5, -6, 7, -8, 9};
    CHECK(b == want);
    REQUIRE_THROWS_WITH(sh::to_condon_shortley(std::vector<double>(10)),
                        "sphbasis::sh::to_condon_shortley(): expected a coefficient range of "
                        "bands^2 elements, got 10");
    REQUIRE_THROWS_WITH(sh::from_condon_shortley(std::vector<double>(3)),
                        Catch::Contains("sphbasis::sh::from_condon_shortley()"));
    CHECK(sh::to_condon_shortley(std::vector<double>{}).empty());
}

#if SPHBASIS_SH_VEC8_EVAL
TEST_CASE("sh: the 8-lane one-call kernels equal the scalar unrolled ones", "[sh]") {
    // eval_fixed_vec8_N runs eval_fixed_N's operations lane by lane (sh::eval<N>, eval_unit<N>
    // and eval at 4..8 bands, float into an array): the same values up to how the compiler
    // contracts a*b+c in the two forms (measured bit-identical); bound 1 ulp of the band scale.
    // Directions include the poles, the equator and x = y = 0.
    auto dirs = sphere_dirs(200, 21);
    dirs.push_back({0, 0, 1});
    dirs.push_back({0, 0, -1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0.6, -0.8, 0});
    double worst = 0;
    auto check = [&](auto n) {
        constexpr int N = decltype(n)::value;
        for (const auto& d : dirs) {
            const float x = float(d[0]), y = float(d[1]), z = float(d[2]);
            float v[N * N], s[N * N];
            sh::detail::eval_fixed_vec8<N>(x, y, z, v);
            sh::detail::eval_fixed<N>(x, y, z, [&](int k, float f) { s[k] = f; });
            for (int k = 0; k < N * N; ++k) {
                const double scale = norm_s(sh::degree_of(k));
                worst = std::max(worst, std::fabs(double(v[k]) - double(s[k])) / scale);
            }
        }
    };
    check(std::integral_constant<int, 4>{});
    check(std::integral_constant<int, 5>{});
    check(std::integral_constant<int, 6>{});
    check(std::integral_constant<int, 7>{});
    check(std::integral_constant<int, 8>{});
    INFO("max |vec8 - scalar| / band scale " << worst);
    CHECK(worst <= std::numeric_limits<float>::epsilon());
}
#endif
