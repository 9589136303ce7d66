// Tests for basis/zernike.hpp: convention, orthonormality, references, kernels, bad input.
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sphbasis/basis/zernike.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace sphbasis;

namespace {

using Dir = std::array<double, 3>;
constexpr double pi = constants::pi;
constexpr double eps = std::numeric_limits<double>::epsilon();

/// The scale of band n: sqrt((n+1)/pi), the largest value of the band's functions (m != 0 at the
/// rim, where |R_n^m| = 1).
double scale(int n) { return std::sqrt((n + 1) / pi); }

/// The band of function index k.
int band_of(int k) {
    int n = static_cast<int>(std::sqrt(2.0 * k));
    while (n > 0 && zernike::count(n) > k) --n;
    while (zernike::count(n + 1) <= k) ++n;
    return n;
}

std::vector<double> eval_d(int bands, double x, double y, double z) {
    std::vector<double> v(static_cast<std::size_t>(Zernike::count(bands)));
    basis_eval<Zernike>(Zernike::count(bands), x, y, z, v.data());
    return v;
}

std::vector<Dir> random_dirs(int n, unsigned seed, bool upper = true) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> g;
    std::vector<Dir> d;
    while (static_cast<int>(d.size()) < n) {
        double x = g(rng), y = g(rng), z = g(rng);
        const double r = std::sqrt(x * x + y * y + z * z);
        if (r < 1e-3) continue;
        if (upper) z = std::fabs(z);
        d.push_back({x / r, y / r, z / r});
    }
    return d;
}

/// Calls the kernel k at d and returns its n values.
template <class K>
std::vector<double> run(const K& k, int n, const Dir& d) {
    std::vector<double> v(static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
    k(d[0], d[1], d[2], [&](int i, double x) { v[static_cast<std::size_t>(i)] = x; });
    return v;
}

/// sum_i a[i] b[i], SIMD across i.
double dot(const double* a, const double* b, std::size_t n) {
    using V = batch<double>;
    constexpr std::size_t w = static_cast<std::size_t>(native_width<double>);
    V acc0(0.0), acc1(0.0);
    std::size_t i = 0;
    for (; i + 2 * w <= n; i += 2 * w) {
        acc0 += V::load(a + i) * V::load(b + i);
        acc1 += V::load(a + i + w) * V::load(b + i + w);
    }
    double lanes[native_width<double>];
    (acc0 + acc1).store(lanes);
    double s = 0;
    for (double x : lanes) s += x;
    for (; i < n; ++i) s += a[i] * b[i];
    return s;
}

/// max |G - I| of the Gram matrix of the first n functions on the hemisphere rule of `degree`.
double gram_residual(int n, int degree) {
    const DirectionalRule r = hemisphere_rule(degree);
    const std::size_t np = r.size(), un = static_cast<std::size_t>(n);
    std::vector<double> f(un * np);
    basis_eval_batch<Zernike>(n, np, r.x.data(), r.y.data(), r.z.data(), f.data(), np);
    for (std::size_t k = 0; k < un; ++k)
        for (std::size_t i = 0; i < np; ++i) f[k * np + i] *= std::sqrt(r.w[i]);
    double worst = 0;
    for (std::size_t a = 0; a < un; ++a)
        for (std::size_t b = 0; b <= a; ++b)
            worst =
                std::max(worst, std::fabs(dot(&f[a * np], &f[b * np], np) - (a == b ? 1.0 : 0.0)));
    return worst;
}

struct RefValue {
    int k, l, m;
    double ref;
};
/// The lines of tests/data/hemi_reference.txt, grouped by direction.
std::map<Dir, std::vector<RefValue>> load_reference(const std::string& basis) {
    std::ifstream in(SPHBASIS_TEST_DATA_DIR "/hemi_reference.txt");
    REQUIRE(in.good());
    std::map<Dir, std::vector<RefValue>> out;
    std::string line, b;
    while (std::getline(in, line)) {
        if (line.empty() || line[0] == '#') continue;
        std::istringstream is(line);
        RefValue r;
        Dir d;
        REQUIRE(static_cast<bool>(is >> b));
        if (b != basis) continue;
        REQUIRE(static_cast<bool>(is >> r.k >> r.l >> r.m >> d[0] >> d[1] >> d[2] >> r.ref));
        out[d].push_back(r);
    }
    return out;
}

/// Accuracy bound: 5e-14 S_n plus the input's own conditioning, ~n ulp of rho^m and, within 0.01
/// of the pole, ~n^2 ulp (slope ~n^2 S_n in z there; 1 ulp of z).
double bound(int l, double z) {
    const double dl = l;
    return (5e-14 + eps * dl * (1 + (1 - z < 1e-2 ? dl : 0.0))) * scale(l);
}

void check_reference(int max_l) {
    const auto ref = load_reference("zernike");
    REQUIRE(!ref.empty());
    long count = 0;
    double worst = 0;
    for (const auto& [d, values] : ref) {
        int lmax = 0;
        for (const auto& r : values)
            if (r.l <= max_l) lmax = std::max(lmax, r.l);
        const auto v = eval_d(lmax + 1, d[0], d[1], d[2]);
        for (const auto& r : values) {
            if (r.l > max_l) continue;
            REQUIRE(r.k == zernike::index(r.l, r.m));
            const double got = v[static_cast<std::size_t>(r.k)];
            INFO("l=" << r.l << " m=" << r.m << " dir=" << d[0] << "," << d[1] << "," << d[2]
                      << " got " << got << " ref " << r.ref);
            REQUIRE(std::fabs(got - r.ref) <= bound(r.l, d[2]));
            worst = std::max(worst, std::fabs(got - r.ref) / scale(r.l));
            ++count;
        }
    }
    CHECK(count > 500);
    WARN("zernike reference (l <= " << max_l << "): " << count
                                    << " values, worst |error|/S = " << worst);
}

}  // namespace

TEST_CASE("zernike: bands 0-2 closed forms and band-1 signs pin the convention", "[zernike]") {
    auto dirs = random_dirs(50, 1);
    dirs.push_back({0.48, -0.6, 0.64});
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0, -1, 0});
    for (const auto& d : dirs) {
        const double x = d[0], y = d[1], z = d[2], r = std::sqrt(1 + z);
        const double c[6] = {1 / std::sqrt(2 * pi),
                             std::sqrt(2 / pi) * y / r,
                             std::sqrt(2 / pi) * x / r,
                             2 * std::sqrt(3 / pi) * x * y / (1 + z),
                             std::sqrt(3 / (2 * pi)) * (1 - 2 * z),
                             std::sqrt(3 / pi) * (x * x - y * y) / (1 + z)};
        const auto v = eval_d(3, x, y, z);
        for (int k = 0; k < 6; ++k) {
            INFO("k=" << k << " dir=" << x << "," << y << "," << z);
            REQUIRE(std::fabs(v[static_cast<std::size_t>(k)] - c[k]) <= 16 * eps * scale(2));
        }
    }
    // Band 1: Z_1-1 ~ +y, Z_11 ~ +x (the thesis' (1.48) prints -sqrt(2/pi) x/sqrt(1+z), a spurious
    // minus; its (1.47), (1.49) carry a Condon-Shortley-like minus on the sin functions).
    const auto a = eval_d(2, 0.6, 0.0, 0.8);
    CHECK(a[2] > 0);
    CHECK(a[1] == 0);
    const auto b = eval_d(2, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(std::fabs(b[2]) < 1e-16);
    CHECK(a[2] == Approx(std::sqrt(2 / pi) * 0.6 / std::sqrt(1.8)).epsilon(1e-15));
    // (2/sqrt(pi)) cos(phi) sin(t/2), the thesis' left side of (1.48), is the same function.
    CHECK(a[2] == Approx(2 / std::sqrt(pi) * std::sin(0.5 * std::acos(0.8))).epsilon(1e-14));
    CHECK(eval_d(3, 0.0, 0.6, 0.8)[3] == 0);
    CHECK(eval_d(3, 0.6, 0.6, std::sqrt(0.28))[3] > 0);  // Z_2-2 ~ +xy
    CHECK(zernike::index(0, 0) == 0);
    CHECK(zernike::index(1, -1) == 1);
    CHECK(zernike::index(1, 1) == 2);
    CHECK(zernike::index(2, 0) == 4);
    CHECK(zernike::index(3, -1) == 7);
    CHECK(Zernike::count(4) == 10);
    for (int b2 = 1; b2 <= 100; ++b2) {
        CHECK(Zernike::bands_of(Zernike::count(b2)) == b2);
        CHECK(Zernike::bands_of(Zernike::count(b2) + 1) == -1);
    }
    CHECK(std::string(Zernike::name) == "zernike");
    CHECK(Zernike::domain == Domain::hemisphere);
    CHECK(Zernike::orthonormal);
    CHECK(Zernike::max_count() == 2048 * 2049 / 2);
}

// Why the product rule is exact: Z_n^m = N R_n^|m|(rho) trig(m phi) with rho^2 = 1 - z, and
// R_n^m(rho) = rho^m times a polynomial in rho^2 of degree (n - m)/2. For two functions of orders
// m, m' the product is rho^(|m|+|m'|) times a polynomial in rho^2 times trig(m phi) trig(m' phi).
// If |m| + |m'| is even, it is a polynomial in z = 1 - rho^2 of degree (n + n')/2 <= bands - 1,
// integrated exactly by the (bands)-point Gauss-Legendre rule in z; the phi factor is a
// trigonometric polynomial of degree <= 2(bands-1) < the 2 bands - 1 uniform points in phi. If
// |m| + |m'| is odd then m != m' and the uniform phi rule sums cos/sin((m -+ m') phi),
// 0 < |m -+ m'| < 2 bands - 1, to exactly 0 at every z node. Hence hemisphere_rule(2(bands-1))
// (even hemisphere_rule(bands - 1) for the z part) gives the exact Gram matrix.
TEST_CASE("zernike: Gram matrix is the identity by exact quadrature", "[zernike]") {
    for (int bands = 1; bands <= 10; ++bands) {
        const double r = gram_residual(Zernike::count(bands), 2 * (bands - 1));
        INFO("bands " << bands << " residual " << r);
        CHECK(r < 1e-13);
    }
}

TEST_CASE("zernike: Gram matrix is the identity by exact quadrature, 16 to 48 bands",
          "[zernike][slow]") {
    for (int bands : {16, 32, 48}) {
        const double r = gram_residual(Zernike::count(bands), 2 * (bands - 1));
        INFO("bands " << bands << " residual " << r);
        CHECK(r < 1e-12);
        WARN("zernike Gram residual, " << bands << " bands: " << r);
    }
}

TEST_CASE("zernike: column recurrence is orthonormal per order to 512 bands", "[zernike][slow]") {
    // At phi = 0 the m >= 0 functions are g_nm(z) cos(0) = g_nm(z), and the hemisphere integral of
    // Z_nm Z_n'm is pi (1 + delta_m0) int_0^1 g_nm g_n'm dz: a polynomial of degree <= bands - 1 in
    // z (as in the Gram test), exact with `bands` Gauss-Legendre nodes.
    const int bands = 512;
    std::vector<double> t, w;
    gauss_legendre(bands, t, w);
    const std::vector<int> orders = {0, 1, 2, 100, 301, 509, 510, 511};
    std::vector<std::vector<double>> g(orders.size());
    std::vector<double> v(static_cast<std::size_t>(Zernike::count(bands)));
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double z = 0.5 * (t[i] + 1);
        const double s = std::sqrt((1 - z) * (1 + z));
        zernike::detail::ColumnKernel{bands}(
            s, 0.0, z, [&](int k, double x) { v[static_cast<std::size_t>(k)] = x; });
        for (std::size_t j = 0; j < orders.size(); ++j)
            for (int n = orders[j]; n < bands; n += 2)
                g[j].push_back(v[static_cast<std::size_t>(zernike::index(n, orders[j]))]);
    }
    double worst = 0;
    for (std::size_t j = 0; j < orders.size(); ++j) {
        const int m = orders[j], nn = (bands - 1 - m) / 2 + 1;
        const std::size_t un = static_cast<std::size_t>(nn);
        const double c = pi * (m == 0 ? 2 : 1);
        for (std::size_t a = 0; a < un; ++a)
            for (std::size_t b = 0; b <= a; ++b) {
                double s = 0;
                for (std::size_t i = 0; i < t.size(); ++i)
                    s += 0.5 * w[i] * g[j][i * un + a] * g[j][i * un + b];
                worst = std::max(worst, std::fabs(c * s - (a == b ? 1.0 : 0.0)));
            }
    }
    WARN("zernike per-order Gram residual at 512 bands: " << worst);
    CHECK(worst < 1e-12);
}

TEST_CASE("zernike: values against the mpmath reference (l <= 255)", "[zernike][reference]") {
    check_reference(255);
}

TEST_CASE("zernike: values against the mpmath reference (l <= 2047)",
          "[zernike][reference][slow]") {
    check_reference(2047);
}

TEST_CASE("zernike: unrolled kernels, row recurrence and column recurrence agree", "[zernike]") {
    auto dirs = random_dirs(100, 2);
    for (Dir d : {Dir{0, 0, 1}, Dir{1, 0, 0}, Dir{0, -1, 0}, Dir{0.6, 0.8, 1e-9}, Dir{1e-9, 0, 1},
                  Dir{0, 0, -1}, Dir{0.6, 0, -0.8}})
        dirs.push_back(d);
    for (auto& d : dirs) normalize_or_pole(d[0], d[1], d[2]);  // the kernels take unit input
    for (int bands = 1; bands <= 8; ++bands) {
        const int n = Zernike::count(bands);
        double worst = 0;
        for (const auto& d : dirs) {
            std::vector<double> fixed;
            zernike::detail::with_kernel(bands, [&](auto k) { fixed = run(k, n, d); });
            const auto rows = run(zernike::detail::RowKernel{bands}, n, d);
            const auto cols = run(zernike::detail::ColumnKernel{bands}, n, d);
            for (int k = 0; k < n; ++k) {
                const std::size_t uk = static_cast<std::size_t>(k);
                const double s = scale(band_of(k));
                worst = std::max(worst, std::fabs(fixed[uk] - rows[uk]) / s);
                worst = std::max(worst, std::fabs(fixed[uk] - cols[uk]) / s);
            }
        }
        INFO("bands " << bands);
        CHECK(worst <= 16 * eps);
    }
    // Row (<= 64 bands) against column recurrence at the switch-over.
    double worst = 0;
    for (const auto& d : dirs) {
        const auto rows = run(zernike::detail::RowKernel{64}, Zernike::count(64), d);
        const auto cols = run(zernike::detail::ColumnKernel{64}, Zernike::count(64), d);
        for (int k = 0; k < Zernike::count(64); ++k)
            worst = std::max(worst, std::fabs(rows[static_cast<std::size_t>(k)] -
                                              cols[static_cast<std::size_t>(k)]) /
                                        scale(band_of(k)));
    }
    CHECK(worst <= 1e-13);
}

TEST_CASE("zernike: prefix property", "[zernike]") {
    for (const auto& d : random_dirs(5, 3)) {
        const auto big = eval_d(100, d[0], d[1], d[2]);
        for (int b : {1, 2, 3, 7, 8, 9, 31, 64, 65, 99}) {
            const auto small = eval_d(b, d[0], d[1], d[2]);
            double worst = 0;
            for (int i = 0; i < Zernike::count(b); ++i)
                worst = std::max(worst, std::fabs(small[static_cast<std::size_t>(i)] -
                                                  big[static_cast<std::size_t>(i)]) /
                                            scale(band_of(i)));
            INFO("bands " << b);
            CHECK(worst <= 1e-13);
        }
        // Within one evaluation path the prefix is bitwise.
        const auto a = eval_d(40, d[0], d[1], d[2]);
        const auto c = eval_d(20, d[0], d[1], d[2]);
        CHECK(std::equal(c.begin(), c.end(), a.begin()));
    }
}

TEMPLATE_TEST_CASE("zernike: batch path equals scalar path", "[zernike]", float, double) {
    using T = TestType;
    auto dirs = random_dirs(37, 5, false);  // not a multiple of any SIMD width; both hemispheres
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    std::vector<T> xs, ys, zs;
    for (const auto& d : dirs) {
        xs.push_back(T(d[0] * 3));  // non-unit on purpose: both paths normalise
        ys.push_back(T(d[1] * 3));
        zs.push_back(T(d[2] * 3));
    }
    const std::size_t n = dirs.size();
    for (int bands : {1, 2, 3, 4, 8, 9, 17, 64, 66}) {
        const int nf = Zernike::count(bands);
        const std::size_t unf = static_cast<std::size_t>(nf);
        std::vector<T> out(unf * n), one(unf), coeffs(unf), sums(n);
        for (std::size_t k = 0; k < unf; ++k) coeffs[k] = T(std::sin(double(k) + 1));
        basis_eval_batch<Zernike>(nf, n, xs.data(), ys.data(), zs.data(), out.data(), n);
        basis_eval_sum_batch<Zernike>(nf, coeffs.data(), n, xs.data(), ys.data(), zs.data(),
                                      sums.data());
        double worst = 0, worst_sum = 0;
        for (std::size_t i = 0; i < n; ++i) {
            basis_eval<Zernike>(nf, xs[i], ys[i], zs[i], one.data());
            double dot = 0, mag = 0;
            for (std::size_t k = 0; k < unf; ++k) {
                const int l = band_of(int(k));
                worst = std::max(worst, std::fabs(double(out[k * n + i]) - double(one[k])) /
                                            ((l + 1) * scale(l)));
                dot += double(coeffs[k]) * double(one[k]);
                mag += std::fabs(double(coeffs[k]) * double(one[k]));
            }
            const T s1 = basis_eval_sum<Zernike>(nf, coeffs.data(), xs[i], ys[i], zs[i]);
            worst_sum = std::max(worst_sum, std::fabs(double(s1) - dot) / (mag + 1));
            worst_sum = std::max(worst_sum, std::fabs(double(sums[i]) - dot) / (mag + 1));
        }
        INFO("bands " << bands);
        CHECK(worst <= 4 * double(std::numeric_limits<T>::epsilon()));
        CHECK(worst_sum <= 8 * double(std::numeric_limits<T>::epsilon()));
    }
}

TEST_CASE("zernike: float is within a stated bound of double", "[zernike]") {
    // Bound: |float - double| <= 6 (n + 1)^1.5 ulp(float) * S_n (measured worst 0.8 (n + 1)^1.5):
    // the float path normalises the direction in float (near the pole band-n functions have slope
    // ~n^2 in z) and rounds each recurrence step (~n^1.5 ulp near the ends).
    const double ef = std::numeric_limits<float>::epsilon();
    double worst = 0;
    auto dirs = random_dirs(200, 9);
    dirs.push_back({0, 0, 1});
    dirs.push_back({0.6, 0.8, 0});
    for (const auto& d : dirs) {
        for (int bands : {3, 8, 31, 64, 70}) {
            std::vector<float> f(static_cast<std::size_t>(Zernike::count(bands)));
            basis_eval<Zernike>(Zernike::count(bands), float(d[0]), float(d[1]), float(d[2]),
                                f.data());
            const auto dd =
                eval_d(bands, double(float(d[0])), double(float(d[1])), double(float(d[2])));
            for (std::size_t k = 0; k < f.size(); ++k) {
                const int l = band_of(int(k));
                worst = std::max(worst, std::fabs(double(f[k]) - dd[k]) /
                                            (std::pow(l + 1, 1.5) * ef * scale(l)));
            }
        }
    }
    WARN("zernike float vs double: worst |f - d| / ((l + 1)^1.5 ulp S_l) = " << worst);
    CHECK(worst <= 6);
}

TEST_CASE("zernike: below the horizon every function is 0", "[zernike]") {
    auto dirs = random_dirs(50, 4, false);
    for (Dir d : {Dir{0, 0, -1}, Dir{1, 0, -1e-300}, Dir{0.6, 0.8, -1e-12}, Dir{0, 1, -0.5}})
        dirs.push_back(d);
    for (const auto& d : dirs) {
        if (d[2] >= 0) continue;
        for (int bands : {1, 3, 8, 20, 65}) {
            const auto v = eval_d(bands, d[0], d[1], d[2]);
            for (double x : v) REQUIRE(x == 0);
        }
    }
}

TEST_CASE("zernike: pole and horizon are finite and exact", "[zernike]") {
    // Pole (rho = 0): only m = 0 survives, R_n^0(0) = (-1)^(n/2). Horizon (rho = 1): R_n^m(1) = 1,
    // so Z_nm = sqrt((n+1)(2 - delta_m0)/(2 pi)) trig(m phi).
    const double phi = std::atan2(-0.8, 0.6);
    for (int bands : {1, 3, 8, 20, 64, 65, 300}) {
        const auto p = eval_d(bands, 0, 0, 1);
        const auto h = eval_d(bands, 0.6, -0.8, 0);
        const auto hz = eval_d(bands, 0.6, -0.8, -0.0);  // -0 is on the horizon, not below
        double worst = 0;
        for (int n = 0; n < bands; ++n)
            for (int m = -n; m <= n; m += 2) {
                const std::size_t k = static_cast<std::size_t>(zernike::index(n, m));
                const double s = scale(n);
                REQUIRE(std::isfinite(p[k]));
                REQUIRE(std::isfinite(h[k]));
                const double c = std::sqrt((n + 1) * (m == 0 ? 1.0 : 2.0) / (2 * pi));
                const double pole = m == 0 ? ((n / 2) % 2 ? -c : c) : 0.0;
                const double rim = c * (m > 0   ? std::cos(m * phi)
                                        : m < 0 ? std::sin(-m * phi)
                                                : 1.0);
                worst = std::max(worst, std::fabs(p[k] - pole) / s);
                worst = std::max(worst, std::fabs(h[k] - rim) / s);
                REQUIRE(hz[k] == h[k]);
            }
        INFO("bands " << bands);
        CHECK(worst <= 1e-14 + 20 * eps * bands);
    }
}

TEST_CASE("zernike: hard directions stay finite", "[zernike]") {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Dir> hard = {
        {0, 0, 1}, {1e-300, 0, 1}, {3e-310, 2e-310, 1e-310}, {1e300, 1e300, 1e300}, {1, 1e-300, 0},
        {0, 0, 0}, {nan, 0, 1},    {1e-20, -1e-20, 1}};
    double pole[15];
    basis_eval<Zernike>(15, 0.0, 0.0, 1.0, pole);
    for (int bands : {4, 9, 64, 200}) {
        std::vector<double> v(static_cast<std::size_t>(Zernike::count(bands)));
        std::vector<float> f(v.size());
        for (const auto& d : hard) {
            basis_eval<Zernike>(Zernike::count(bands), d[0], d[1], d[2], v.data());
            basis_eval<Zernike>(Zernike::count(bands), float(d[0]), float(d[1]), float(d[2]),
                                f.data());
            for (double x : v) REQUIRE(std::isfinite(x));
            for (float x : f) REQUIRE(std::isfinite(x));
        }
    }
    double v[15];
    basis_eval<Zernike>(15, nan, 0.0, 0.0, v);  // no direction: the pole
    for (int k = 0; k < 15; ++k) CHECK(v[k] == pole[k]);
}

TEST_CASE("zernike: bad sizes throw", "[zernike]") {
    double v[16];
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(5, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected a triangular number (bands(bands+1)/2, "
                        "bands <= 2048) of functions for basis 'zernike', got 5");
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(-3, 0.0, 0.0, 1.0, v), Catch::Contains("got -3"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(9, 0.0, 0.0, 1.0, v), Catch::Contains("got 9"));
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(2049 * 2050 / 2, 0.0, 0.0, 1.0, v),
                        Catch::Contains("bands <= 2048"));
    REQUIRE_THROWS_WITH(basis_eval_batch<Zernike>(3, 2, f, f, f, f, 1), Catch::Contains("stride"));
    REQUIRE_THROWS_WITH(
        basis_eval_sum<Zernike>(4, f, 0.f, 0.f, 1.f),
        Catch::Contains("sphbasis::basis_eval_sum(): expected a triangular number"));
    CHECK(Zernike::valid_count(2048 * 2049 / 2));
    CHECK_FALSE(Zernike::valid_count(2049 * 2050 / 2));
    CHECK_FALSE(Zernike::valid_count(2147483647));
}
