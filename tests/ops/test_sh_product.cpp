// Tests for ops/sh_product.hpp: real Gaunt coefficients against exact values
// (tests/data/gaunt_reference.txt from tools/gen/gen_gaunt_reference.py), selection rules,
// nonzero counts, SH products against quadrature of pointwise products, unrolled against generic
// kernels, the product matrix, the triple integral, and the `sphbasis gaunt` command.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/ops/sh_product.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "../support/cli_runner.hpp"
#include "../support/sh_checks.hpp"

using namespace sphbasis;

namespace {

struct RefRow {
    int l1, m1, l2, m2, l3, m3;
    double value;
};

struct Reference {
    std::vector<RefRow> all, zero, spot;
    std::map<int, std::pair<std::size_t, std::size_t>> counts;  // bands -> (ordered, pairs)
};

const Reference& reference() {
    static const Reference ref = [] {
        Reference r;
        std::ifstream in(SPHBASIS_TEST_DATA_DIR "/gaunt_reference.txt");
        if (!in) throw std::runtime_error("cannot open gaunt_reference.txt");
        std::string line, section;
        while (std::getline(in, line)) {
            if (line.empty() || line[0] == '#') continue;
            std::istringstream ss(line);
            if (line.rfind("section", 0) == 0) {
                std::string word;
                ss >> word >> section;
                continue;
            }
            if (section == "count") {
                int n;
                std::size_t o, p;
                ss >> n >> o >> p;
                r.counts[n] = {o, p};
                continue;
            }
            RefRow row;
            std::string value;
            ss >> row.l1 >> row.m1 >> row.l2 >> row.m2 >> row.l3 >> row.m3 >> value;
            row.value = std::stod(value);
            if (section == "all")
                r.all.push_back(row);
            else if (section == "zero")
                r.zero.push_back(row);
            else if (section == "spot")
                r.spot.push_back(row);
        }
        return r;
    }();
    return ref;
}

// The six orderings of a triple of (l, m) pairs.
std::vector<std::array<int, 6>> permutations(const RefRow& r) {
    const std::array<std::pair<int, int>, 3> p = {{{r.l1, r.m1}, {r.l2, r.m2}, {r.l3, r.m3}}};
    std::array<int, 3> o = {0, 1, 2};
    std::vector<std::array<int, 6>> out;
    do {
        out.push_back(
            {p[static_cast<std::size_t>(o[0])].first, p[static_cast<std::size_t>(o[0])].second,
             p[static_cast<std::size_t>(o[1])].first, p[static_cast<std::size_t>(o[1])].second,
             p[static_cast<std::size_t>(o[2])].first, p[static_cast<std::size_t>(o[2])].second});
    } while (std::next_permutation(o.begin(), o.end()));
    return out;
}

std::vector<double> random_coeffs(int bands, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> c(static_cast<std::size_t>(bands * bands));
    for (auto& v : c) v = u(rng);
    return c;
}

double eval_expansion(int bands, const std::vector<double>& c, const double* y) {
    double s = 0;
    for (int k = 0; k < bands * bands; ++k) s += c[static_cast<std::size_t>(k)] * y[k];
    return s;
}

// project(a b) onto nc bands by a product rule exact for the integrand's degree.
std::vector<double> quadrature_product(int na, const std::vector<double>& a, int nb,
                                       const std::vector<double>& b, int nc) {
    const int nmax = std::max({na, nb, nc});
    const DirectionalRule rule = sphere_rule((na - 1) + (nb - 1) + (nc - 1));
    std::vector<double> y(static_cast<std::size_t>(nmax * nmax));
    std::vector<double> out(static_cast<std::size_t>(nc * nc), 0.0);
    for (std::size_t q = 0; q < rule.size(); ++q) {
        sh::eval_unit(nmax, rule.x[q], rule.y[q], rule.z[q], y.data());
        const double f = eval_expansion(na, a, y.data()) * eval_expansion(nb, b, y.data());
        for (int k = 0; k < nc * nc; ++k)
            out[static_cast<std::size_t>(k)] += rule.w[q] * f * y[static_cast<std::size_t>(k)];
    }
    return out;
}

using sphbasis::test::max_abs;

// Tolerances of gaunt() against exact values: with the x87 long double working precision the
// results are within an ulp or so; with double (MSVC, ARM) a few ulp of the largest symbol.
constexpr bool extended = std::is_same_v<sphbasis::extended, long double>;
constexpr double gaunt_abs_tol = extended ? 5e-17 : 1e-15;
constexpr double gaunt_rel_tol = extended ? 4e-16 : 3e-14;

struct Rgb {
    double r = 0, g = 0, b = 0;
    friend Rgb operator+(const Rgb& x, const Rgb& y) { return {x.r + y.r, x.g + y.g, x.b + y.b}; }
    friend Rgb operator*(const Rgb& x, double s) { return {x.r * s, x.g * s, x.b * s}; }
};

}  // namespace

TEST_CASE("gaunt: pinned values of this library's sign convention", "[gaunt]") {
    // y_11 y_1-1 = (3/(4 pi)) x y = sqrt(3/(4 pi))^2 x y and y_2-2 = sqrt(15/(4 pi)) x y:
    // the integral is +sqrt(15)/(10 sqrt(pi)).
    CHECK(sh::gaunt(1, 1, 1, -1, 2, -2) == Approx(std::sqrt(15.0) / (10 * std::sqrt(M_PI))));
    // y_00 = 1/sqrt(4 pi): Gamma(00, lm, lm) = 1/sqrt(4 pi).
    for (int l = 0; l < 30; ++l)
        for (int m = -l; m <= l; ++m)
            REQUIRE(sh::gaunt(0, 0, l, m, l, m) == Approx(0.28209479177387814).epsilon(1e-14));
    // y_10^2 = (3/(4 pi)) z^2 has a positive y_20 component; y_11^2 a negative one (x^2).
    CHECK(sh::gaunt(1, 0, 1, 0, 2, 0) > 0);
    CHECK(sh::gaunt(1, 1, 1, 1, 2, 0) < 0);
    CHECK(sh::gaunt(1, 1, 1, 1, 2, 2) > 0);  // x^2 - y^2
    // The non-trivial zero (2 3 3; 0 2 -2) = 0.
    CHECK(sh::gaunt(2, 0, 3, -2, 3, -2) == 0.0);
    CHECK(sh::gaunt(2, 0, 3, 2, 3, 2) == 0.0);
}

TEST_CASE("gaunt: exact values for all l <= 8 (all m, every ordering)", "[gaunt]") {
    const Reference& ref = reference();
    REQUIRE(ref.all.size() == 4223);
    double worst = 0, worst_rel = 0;
    int zeros = 0;
    for (const RefRow& r : ref.all) {
        for (const auto& p : permutations(r)) {
            const double g = sh::gaunt(p[0], p[1], p[2], p[3], p[4], p[5]);
            if (r.value == 0) {
                REQUIRE(g == 0.0);  // accidental zeros come out exactly 0
                continue;
            }
            worst = std::max(worst, std::fabs(g - r.value));
            worst_rel = std::max(worst_rel, std::fabs(g - r.value) / std::fabs(r.value));
        }
        zeros += r.value == 0;
    }
    INFO("max abs error " << worst << ", max rel error " << worst_rel);
    CHECK(zeros == 38);
    CHECK(worst < gaunt_abs_tol);
    CHECK(worst_rel < gaunt_rel_tol);
    // The sample of triples that break one rule.
    for (const RefRow& r : ref.zero) REQUIRE(sh::gaunt(r.l1, r.m1, r.l2, r.m2, r.l3, r.m3) == 0.0);
}

TEST_CASE("gaunt: exact spot values up to l = 40", "[gaunt]") {
    const Reference& ref = reference();
    REQUIRE(ref.spot.size() >= 100);
    double worst_rel = 0;
    for (const RefRow& r : ref.spot) {
        for (const auto& p : permutations(r)) {
            const double g = sh::gaunt(p[0], p[1], p[2], p[3], p[4], p[5]);
            if (r.value == 0) {
                REQUIRE(g == 0.0);
                continue;
            }
            worst_rel = std::max(worst_rel, std::fabs(g - r.value) / std::fabs(r.value));
        }
    }
    INFO("max rel error " << worst_rel);
    CHECK(worst_rel < gaunt_rel_tol);
}

TEST_CASE("gaunt: selection rules, exhaustively for l <= 8", "[gaunt]") {
    const Reference& ref = reference();
    std::set<std::array<int, 3>> nonzero;
    for (const RefRow& r : ref.all)
        if (r.value != 0) {
            std::array<int, 3> key = {sh::index(r.l1, r.m1), sh::index(r.l2, r.m2),
                                      sh::index(r.l3, r.m3)};
            std::sort(key.begin(), key.end());
            nonzero.insert(key);
        }
    const int n = 81;
    std::size_t count = 0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            for (int k = 0; k < n; ++k) {
                const int l1 = sh::degree_of(i), l2 = sh::degree_of(j), l3 = sh::degree_of(k);
                const int m1 = i - l1 * (l1 + 1), m2 = j - l2 * (l2 + 1), m3 = k - l3 * (l3 + 1);
                const double g = sh::gaunt(l1, m1, l2, m2, l3, m3);
                std::array<int, 3> key = {i, j, k};
                std::sort(key.begin(), key.end());
                const bool expect = nonzero.count(key) != 0;
                if (!sh::gaunt_allowed(l1, m1, l2, m2, l3, m3)) REQUIRE(g == 0.0);
                // The rules one by one.
                if ((l1 + l2 + l3) % 2 != 0 || l3 > l1 + l2 || l3 < std::abs(l1 - l2) ||
                    ((m1 < 0) + (m2 < 0) + (m3 < 0)) % 2 != 0)
                    REQUIRE(g == 0.0);
                const int a1 = std::abs(m1), a2 = std::abs(m2), a3 = std::abs(m3);
                if (a1 != a2 + a3 && a2 != a1 + a3 && a3 != a1 + a2) REQUIRE(g == 0.0);
                REQUIRE((g != 0.0) == expect);
                count += g != 0.0;
            }
    CHECK(count == ref.counts.at(9).first);
}

TEST_CASE("gaunt: bad input throws", "[gaunt]") {
    CHECK_THROWS_WITH(sh::gaunt(-1, 0, 1, 0, 1, 0),
                      Catch::Contains("sphbasis::sh::gaunt(): expected 0 <= l1"));
    CHECK_THROWS_AS(sh::gaunt(1, 2, 1, 0, 1, 0), std::invalid_argument);
    CHECK_THROWS_AS(sh::gaunt(1, 0, 1, -2, 1, 0), std::invalid_argument);
    CHECK_THROWS_AS(sh::gaunt(1, 0, 1, 0, 3, 4), std::invalid_argument);
    CHECK_THROWS_AS(sh::gaunt(sh::max_bands, 0, 1, 0, 1, 0), std::invalid_argument);
    CHECK_THROWS_AS(sh::TripleTable(0, 3, 3), std::invalid_argument);
    CHECK_THROWS_WITH(sh::TripleTable(3, 3, -1),
                      Catch::Contains("sphbasis::sh::TripleTable(): expected"));
}

TEST_CASE("gaunt: high degrees stay finite and satisfy the completeness sum", "[gaunt][slow]") {
    // sum over l3, m3 of Gamma(i, j, l3 m3)^2 = integral of (y_i y_j)^2, by quadrature.
    const std::array<std::array<int, 4>, 5> cases = {{{60, 7, 45, -3},
                                                      {100, 0, 100, 0},
                                                      {120, 120, 80, -80},
                                                      {150, -2, 3, 1},
                                                      {90, 45, 90, -45}}};
    std::vector<double> w0, wm, tmp;
    for (const auto& c : cases) {
        const int l1 = c[0], m1 = c[1], l2 = c[2], m2 = c[3];
        double sum = 0;
        for (int l3 = std::abs(l1 - l2); l3 <= l1 + l2; ++l3)
            for (int m3 = -l3; m3 <= l3; ++m3) {
                const double g = sh::gaunt(l1, m1, l2, m2, l3, m3);
                REQUIRE(std::isfinite(g));
                sum += g * g;
            }
        const DirectionalRule rule = sphere_rule(2 * (l1 + l2));
        double q = 0;
        for (std::size_t p = 0; p < rule.size(); ++p) {
            const double a = sh::eval_lm(l1, m1, rule.x[p], rule.y[p], rule.z[p]);
            const double b = sh::eval_lm(l2, m2, rule.x[p], rule.y[p], rule.z[p]);
            q += rule.w[p] * a * a * b * b;
        }
        INFO(l1 << " " << m1 << " " << l2 << " " << m2);
        CHECK(sum == Approx(q).epsilon(1e-11));
    }
    // Degree 4000: finite, the unit-sum of the 3j sweep holds implicitly; spot-check symmetry.
    const double g1 = sh::gaunt(4000, 1234, 3000, -1000, 2000, -234);
    const double g2 = sh::gaunt(2000, -234, 4000, 1234, 3000, -1000);
    CHECK(std::isfinite(g1));
    CHECK(g1 == Approx(g2).epsilon(1e-12));
}

TEST_CASE("product: nonzero counts of the n x n -> n tensor", "[gaunt][product]") {
    // Ordered triples (i, j, k < n^2) and symmetric pairs (i <= j, k), n = 1..9; the same numbers
    // are in the header comment of ops/sh_product.hpp and in the reference file.
    const std::array<std::size_t, 9> ordered = {1, 10, 83, 353, 1158, 2907, 6460, 12868, 23621};
    const std::array<std::size_t, 9> pairs = {1, 7, 52, 194, 623, 1517, 3348, 6588, 12057};
    const Reference& ref = reference();
    for (int n = 1; n <= 9; ++n) {
        const sh::TripleTable t(n, n, n);
        std::size_t p = 0;
        for (int k = 0; k < n * n; ++k)
            for (std::size_t e = t.row_begin(k); e < t.row_begin(k + 1); ++e) p += t.i(e) <= t.j(e);
        INFO("n = " << n);
        CHECK(t.size() == ordered[static_cast<std::size_t>(n - 1)]);
        CHECK(p == pairs[static_cast<std::size_t>(n - 1)]);
        CHECK(t.size() == ref.counts.at(n).first);
        CHECK(p == ref.counts.at(n).second);
    }
}

TEST_CASE("product: table entries equal gaunt() and the exact values", "[gaunt][product]") {
    const sh::TripleTable t(9, 7, 8);  // different band counts
    for (int k = 0; k < 64; ++k)
        for (std::size_t e = t.row_begin(k); e < t.row_begin(k + 1); ++e) {
            const int i = static_cast<int>(t.i(e)), j = static_cast<int>(t.j(e));
            const int l1 = sh::degree_of(i), l2 = sh::degree_of(j), l3 = sh::degree_of(k);
            REQUIRE(t.value(e) == Approx(sh::gaunt(l1, i - l1 * (l1 + 1), l2, j - l2 * (l2 + 1), l3,
                                                   k - l3 * (l3 + 1)))
                                      .epsilon(4e-16));
            REQUIRE(t.value(e) != 0.0);
            REQUIRE(t(i, j, k) == t.value(e));
        }
    const Reference& ref = reference();
    for (const RefRow& r : ref.all)
        for (const auto& p : permutations(r)) {
            const int i = sh::index(p[0], p[1]), j = sh::index(p[2], p[3]),
                      k = sh::index(p[4], p[5]);
            if (i >= 81 || j >= 49 || k >= 64) continue;
            REQUIRE(t(i, j, k) == Approx(r.value).margin(1e-15));
        }
}

TEST_CASE("product: generic kernel equals quadrature of the pointwise product", "[product]") {
    std::mt19937 rng(11);
    // (na, nb, nc): exact full products (nc = na + nb - 1), truncated ones and mixed counts.
    const std::array<std::array<int, 3>, 8> cases = {
        {{3, 3, 5}, {2, 4, 5}, {3, 3, 3}, {6, 6, 6}, {5, 2, 3}, {4, 7, 9}, {8, 8, 15}, {1, 5, 4}}};
    for (const auto& c : cases) {
        const int na = c[0], nb = c[1], nc = c[2];
        const auto a = random_coeffs(na, rng), b = random_coeffs(nb, rng);
        std::vector<double> out(static_cast<std::size_t>(nc * nc));
        sh::product(na, a.data(), nb, b.data(), nc, out.data());
        const auto q = quadrature_product(na, a, nb, b, nc);
        double err = 0;
        for (std::size_t k = 0; k < out.size(); ++k) err = std::max(err, std::fabs(out[k] - q[k]));
        INFO(na << " x " << nb << " -> " << nc << ": max error " << err);
        CHECK(err < 1e-14 * std::max(1.0, max_abs(q)) * nc);
    }
}

TEST_CASE("product: with enough bands the product is exact pointwise", "[product]") {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    const int na = 4, nb = 3, nc = na + nb - 1;
    const auto a = random_coeffs(na, rng), b = random_coeffs(nb, rng);
    std::vector<double> c(static_cast<std::size_t>(nc * nc));
    sh::product(na, a.data(), nb, b.data(), nc, c.data());
    std::vector<double> y(static_cast<std::size_t>(nc * nc));
    for (int s = 0; s < 100; ++s) {
        sh::eval(nc, u(rng), u(rng), u(rng), y.data());
        const double f = eval_expansion(na, a, y.data()) * eval_expansion(nb, b, y.data());
        REQUIRE(eval_expansion(nc, c, y.data()) == Approx(f).margin(1e-13));
    }
}

TEMPLATE_TEST_CASE("product: unrolled kernels agree with the generic sparse kernel", "[product]",
                   float, double) {
    using T = TestType;
    const T tol = std::is_same_v<T, float> ? T(2e-6) : T(1e-15);
    std::mt19937 rng(7);
    std::uniform_real_distribution<T> u(-1, 1);
    auto check = [&](auto n_const) {
        constexpr int N = decltype(n_const)::value;
        const sh::TripleTable t(N, N, N);
        for (int rep = 0; rep < 20; ++rep) {
            std::array<T, N * N> a{}, b{}, fixed{}, generic{}, runtime{};
            for (int k = 0; k < N * N; ++k) {
                a[static_cast<std::size_t>(k)] = u(rng);
                b[static_cast<std::size_t>(k)] = u(rng);
            }
            sh::product<N>(a.data(), b.data(), fixed.data());
            sh::product(t, a.data(), b.data(), generic.data());
            sh::product(N, a.data(), b.data(), runtime.data());
            for (int k = 0; k < N * N; ++k) {
                const auto uk = static_cast<std::size_t>(k);
                INFO("N = " << N << ", k = " << k);
                REQUIRE(std::fabs(fixed[uk] - generic[uk]) <= tol * N);
                REQUIRE(runtime[uk] == fixed[uk]);
            }
        }
    };
    check(std::integral_constant<int, 1>{});
    check(std::integral_constant<int, 2>{});
    check(std::integral_constant<int, 3>{});
    check(std::integral_constant<int, 4>{});
    check(std::integral_constant<int, 5>{});
    check(std::integral_constant<int, 6>{});
    check(std::integral_constant<int, 7>{});  // product<7> uses the generic kernel
}

TEST_CASE("product: float kernels are within a few ulp of double", "[product]") {
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(-1, 1);
    std::array<double, 36> a{}, b{}, cd{};
    std::array<float, 36> af{}, bf{}, cf{};
    for (std::size_t k = 0; k < 36; ++k) {
        af[k] = static_cast<float>(u(rng));
        bf[k] = static_cast<float>(u(rng));
        a[k] = af[k];
        b[k] = bf[k];
    }
    sh::product<6>(a.data(), b.data(), cd.data());
    sh::product<6>(af.data(), bf.data(), cf.data());
    double scale = 0;
    for (std::size_t i = 0; i < 36; ++i) scale += std::fabs(a[i]) * std::fabs(b[i]);
    for (std::size_t k = 0; k < 36; ++k)
        CHECK(std::fabs(double(cf[k]) - cd[k]) <= 64 * 6e-8 * std::max(1.0, scale));
}

TEST_CASE("product: RGB coefficients times scalar visibility", "[product]") {
    std::mt19937 rng(13);
    const int n = 4;
    const auto r = random_coeffs(n, rng), g = random_coeffs(n, rng), bl = random_coeffs(n, rng);
    const auto v = random_coeffs(n, rng);
    std::vector<Rgb> light(16);
    for (std::size_t k = 0; k < 16; ++k) light[k] = {r[k], g[k], bl[k]};
    std::vector<Rgb> out_fixed(16), out_generic(16), out_mixed(9);
    std::vector<double> rr(16), gg(16), bb(16), r3(9);
    sh::product<4>(light.data(), v.data(), out_fixed.data());
    sh::product(sh::triple_table(4, 4, 4), light.data(), v.data(), out_generic.data());
    sh::product(4, light.data(), 4, v.data(), 3, out_mixed.data());
    sh::product(4, r.data(), v.data(), rr.data());
    sh::product(4, g.data(), v.data(), gg.data());
    sh::product(4, bl.data(), v.data(), bb.data());
    sh::product(4, r.data(), 4, v.data(), 3, r3.data());
    for (std::size_t k = 0; k < 16; ++k) {
        CHECK(out_fixed[k].r == Approx(rr[k]).margin(1e-15));
        CHECK(out_fixed[k].g == Approx(gg[k]).margin(1e-15));
        CHECK(out_fixed[k].b == Approx(bb[k]).margin(1e-15));
        CHECK(out_generic[k].b == Approx(bb[k]).margin(1e-15));
    }
    for (std::size_t k = 0; k < 9; ++k) CHECK(out_mixed[k].r == Approx(r3[k]).margin(1e-15));
    // Product matrix and triple integral with RGB coefficients, channel by channel.
    const auto mrgb = sh::product_matrix(4, light.data(), 3, 2);
    const auto mg = sh::product_matrix(4, g.data(), 3, 2);
    REQUIRE(mrgb.size() == 36);
    for (std::size_t e = 0; e < 36; ++e) CHECK(mrgb[e].g == Approx(mg[e]).margin(1e-15));
    const Rgb ti = sh::triple_integral(4, light.data(), 4, v.data(), 3, v.data());
    CHECK(ti.b ==
          Approx(sh::triple_integral(4, bl.data(), 4, v.data(), 3, v.data())).margin(1e-15));
}

TEST_CASE("product: the product matrix reproduces the product", "[product]") {
    std::mt19937 rng(17);
    // Iwanicki and Sloan (JGT 2009, Sec. 3): lighting L (5 bands) times visibility V (4 bands)
    // projected onto the 3 bands of the clamped cosine: 9 rows, 16 columns.
    const std::array<std::array<int, 3>, 4> cases = {{{5, 4, 3}, {3, 6, 3}, {4, 4, 7}, {2, 3, 5}}};
    for (const auto& c : cases) {
        const int na = c[0], nb = c[1], nc = c[2];
        const auto a = random_coeffs(na, rng), b = random_coeffs(nb, rng);
        const std::vector<double> m = sh::product_matrix(na, a.data(), nb, nc);
        REQUIRE(m.size() == static_cast<std::size_t>(nc * nc * nb * nb));
        std::vector<double> direct(static_cast<std::size_t>(nc * nc));
        sh::product(na, a.data(), nb, b.data(), nc, direct.data());
        for (int k = 0; k < nc * nc; ++k) {
            double s = 0;
            for (int j = 0; j < nb * nb; ++j)
                s += m[static_cast<std::size_t>(k * nb * nb + j)] * b[static_cast<std::size_t>(j)];
            REQUIRE(s == Approx(direct[static_cast<std::size_t>(k)]).margin(1e-14));
        }
        // M(a) depends linearly on a, and M(y_00 / Y00) is the identity on the first bands.
        if (nc <= nb) {
            std::vector<double> unit(static_cast<std::size_t>(na * na), 0.0);
            unit[0] = 1 / 0.28209479177387814;  // a = 1 everywhere
            const auto id = sh::product_matrix(na, unit.data(), nb, nc);
            for (int k = 0; k < nc * nc; ++k)
                for (int j = 0; j < nb * nb; ++j)
                    REQUIRE(id[static_cast<std::size_t>(k * nb * nb + j)] ==
                            Approx(k == j ? 1.0 : 0.0).margin(1e-15));
        }
    }
    // The reflectance integral of the source document: h . (M(L) V) = integral of L V H.
    const auto L = random_coeffs(5, rng), V = random_coeffs(4, rng), H = random_coeffs(3, rng);
    const auto M = sh::product_matrix(5, L.data(), 4, 3);
    double via_matrix = 0;
    for (int k = 0; k < 9; ++k) {
        double row = 0;
        for (int j = 0; j < 16; ++j)
            row += M[static_cast<std::size_t>(k * 16 + j)] * V[static_cast<std::size_t>(j)];
        via_matrix += H[static_cast<std::size_t>(k)] * row;
    }
    CHECK(via_matrix ==
          Approx(sh::triple_integral(5, L.data(), 4, V.data(), 3, H.data())).margin(1e-14));
}

TEST_CASE("product: triple integral equals quadrature", "[product]") {
    std::mt19937 rng(19);
    const std::array<std::array<int, 3>, 4> cases = {{{3, 3, 3}, {5, 4, 3}, {2, 6, 7}, {8, 8, 8}}};
    for (const auto& c : cases) {
        const int na = c[0], nb = c[1], nc = c[2];
        const auto a = random_coeffs(na, rng), b = random_coeffs(nb, rng),
                   cc = random_coeffs(nc, rng);
        const int nmax = std::max({na, nb, nc});
        const DirectionalRule rule = sphere_rule(na + nb + nc - 3);
        std::vector<double> y(static_cast<std::size_t>(nmax * nmax));
        double q = 0;
        for (std::size_t p = 0; p < rule.size(); ++p) {
            sh::eval_unit(nmax, rule.x[p], rule.y[p], rule.z[p], y.data());
            q += rule.w[p] * eval_expansion(na, a, y.data()) * eval_expansion(nb, b, y.data()) *
                 eval_expansion(nc, cc, y.data());
        }
        const double t = sh::triple_integral(na, a.data(), nb, b.data(), nc, cc.data());
        INFO(na << " " << nb << " " << nc);
        CHECK(t == Approx(q).margin(1e-13));
        // Symmetric in its arguments.
        CHECK(sh::triple_integral(nc, cc.data(), na, a.data(), nb, b.data()) ==
              Approx(q).margin(1e-13));
    }
}

TEST_CASE("product: larger band counts against quadrature", "[product][slow]") {
    std::mt19937 rng(23);
    const auto a = random_coeffs(16, rng), b = random_coeffs(12, rng);
    std::vector<double> out(400);
    sh::product(16, a.data(), 12, b.data(), 20, out.data());
    const auto q = quadrature_product(16, a, 12, b, 20);
    double err = 0;
    for (std::size_t k = 0; k < out.size(); ++k) err = std::max(err, std::fabs(out[k] - q[k]));
    CHECK(err < 1e-12);
}

#ifdef SPHBASIS_TEST_HAVE_POPEN
TEST_CASE("gaunt: the sphbasis gaunt command", "[gaunt][cli]") {
    // Documented behaviour: one line with 17 significant digits; negative m are plain arguments;
    // bad input exits non-zero. Runs only when the tool was built beside the tests.
    if (test::tool_path().empty()) {
        WARN("sphbasis tool not built; skipping");
        return;
    }
    auto run = [](const std::string& args, int& status) {
        return test::run_tool("gaunt " + args, status);
    };
    int st = 0;
    std::string out = run("2 -1 3 2 3 -3", st);
    CHECK(st == 0);
    char expect[64];
    std::snprintf(expect, sizeof expect, "%.17g\n", sh::gaunt(2, -1, 3, 2, 3, -3));
    CHECK(out == expect);
    out = run("1 1 1 -1 2 -2", st);
    CHECK(st == 0);
    CHECK(std::stod(out) == Approx(std::sqrt(15.0) / (10 * std::sqrt(M_PI))).epsilon(1e-15));
    CHECK(run("1 0 1 0 1 0", st) == "0\n");
    CHECK(st == 0);
    test::check_rejects("gaunt", {"1 0 1 0", "1 0 1 0 1 0 1", "1.5 0 1 0 1 0", "-1 0 1 0 1 0",
                                  "1 2 1 0 1 0", "a 0 1 0 1 0", "1 0 1 0 1 0x"});
}
#endif

TEST_CASE("product: ranges and pointers, checked at the boundary", "[product]") {
    std::mt19937 rng(17);
    std::normal_distribution<double> nd;
    std::vector<double> a(16), b(16), p1(16), p2(16), p3(16);
    for (auto& v : a) v = nd(rng);
    for (auto& v : b) v = nd(rng);
    sh::product(4, a.data(), b.data(), p1.data());
    sh::product(4, a, b, p2);  // std::vector ranges
    CHECK(p1 == p2);
    std::array<double, 16> p4{};
    sh::product<4>(a, b, p4);
    sh::product(sh::triple_table(4, 4, 4), a, b, p3);
    for (std::size_t i = 0; i < 16; ++i) {
        CHECK(p4[i] == Approx(p1[i]).margin(1e-14));
        CHECK(p3[i] == Approx(p1[i]).margin(1e-14));
    }
    std::vector<double> small(9);
    CHECK_THROWS_WITH(sh::product(4, a, b, small),
                      Catch::Contains("sphbasis::sh::product(): expected out buffer of at least 16 "
                                      "elements, got 9"));
    CHECK_THROWS_WITH(sh::product(4, a.data(), static_cast<const double*>(nullptr), p1.data()),
                      Catch::Contains("sphbasis::sh::product(): expected a non-null b buffer"));
    CHECK_THROWS_WITH(sh::product(3, a.data(), 3, b.data(), 3, static_cast<double*>(nullptr)),
                      Catch::Contains("sphbasis::sh::product(): expected a non-null out buffer"));
    CHECK_THROWS_WITH(sh::product(0, a.data(), b.data(), p1.data()),
                      Catch::Contains("sphbasis::sh::product(): expected 1 <= bands"));
}

TEST_CASE("product: a triple table beyond the table ceiling is refused before building",
          "[product]") {
    CHECK_THROWS_WITH(
        sphbasis::sh::TripleTable(64, 64, 64),
        Catch::Contains("SPHBASIS_MAX_TABLE_BYTES") && Catch::Contains("bands 64 x 64 -> 64"));
    std::vector<double> a(64 * 64, 0.0), b(64 * 64, 0.0), c(64 * 64, 0.0);
    CHECK_THROWS_AS(sphbasis::sh::product(64, a, b, c), std::invalid_argument);
}

namespace {

// Largest |float - double| of the n x n -> n product over `reps` random pairs in [-1, 1], in
// float ulps (2^-23) of S_k = sum_ij |Gamma_ijk a_i b_j|, the scale of the sum's rounding.
template <int N, class Kernel>
double product_error_ulps(Kernel kernel, int reps) {
    const sh::TripleTable& t = sh::triple_table(N, N, N);
    REQUIRE(t.has_pairs());
    const double* v = t.pair_values<double>();
    const std::uint32_t* ij = t.pair_ij_data();
    const std::size_t* row = t.pair_row_data();
    std::mt19937 rng(13 + N);
    std::uniform_real_distribution<float> u(-1, 1);
    double worst = 0;
    for (int rep = 0; rep < reps; ++rep) {
        std::array<float, N * N> af{}, bf{}, cf{};
        std::array<double, N * N> a{}, b{}, c{};
        for (std::size_t k = 0; k < af.size(); ++k) {
            af[k] = u(rng);
            bf[k] = u(rng);
            a[k] = af[k];
            b[k] = bf[k];
        }
        sh::product<N>(a.data(), b.data(), c.data());
        kernel(af.data(), bf.data(), cf.data());
        for (std::size_t k = 0; k < af.size(); ++k) {
            double s = 0;
            for (std::size_t e = row[k]; e < row[k + 1]; ++e) {
                const std::uint32_t i = ij[e] & 0xffffu, j = ij[e] >> 16;
                s += std::fabs(v[e]) * (std::fabs(a[i] * b[j]) + std::fabs(a[j] * b[i]));
            }
            REQUIRE(std::isfinite(cf[k]));
            worst = std::max(worst, std::fabs(double(cf[k]) - c[k]) / (std::ldexp(1.0, -23) * s));
        }
    }
    return worst;
}

template <int N>
void check_float_product(int reps, double ulps) {
    INFO("N = " << N);
    const double e = product_error_ulps<N>(
        [](const float* a, const float* b, float* out) { sh::product<N>(a, b, out); }, reps);
    CHECK(e <= ulps);
#if defined(SPHBASIS_SH_PRODUCT_RINGS)
    // The ring kernel from 3 bands on, also where product<N> keeps the Gaunt sums. (At 1 and 2
    // bands an output has one or two terms and the rings' error, which scales with every
    // coefficient, is not bounded by them: 2171 ulps at 2 bands; product<N> never takes it there.)
    if constexpr (N >= 3) {
        const double er =
            product_error_ulps<N>([](const float* a, const float* b,
                                     float* out) { sh::detail::product_rings<N>(a, b, out); },
                                  reps);
        CHECK(er <= ulps);
    }
#endif
}

}  // namespace

// The ring kernel (AVX2 + FMA, ops/sh_product_rings.hpp) and the unrolled Gaunt sums against
// the double Gaunt kernel, in float ulps of sum_ij |Gamma_ijk a_i b_j|. Measured worst over
// 20000 pairs a band count (x86-64-v3): Gaunt sums 1.32, 1.80, 1.87, 1.85, 2.25, 1.82 ulps at
// 1..6 bands; rings 2.39, 1.99, 1.75, 1.28 ulps at 3..6 bands.
TEST_CASE("product: float kernels against the double Gaunt kernel, ulps of sum |terms|",
          "[product]") {
    check_float_product<1>(2000, 4);
    check_float_product<2>(2000, 4);
    check_float_product<3>(2000, 4);
    check_float_product<4>(2000, 4);
    check_float_product<5>(2000, 4);
    check_float_product<6>(2000, 4);
}
