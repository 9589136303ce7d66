// Shared checks for the basis tests (tests/basis/test_*.cpp): fixed-seed random directions,
// kernel runs, Gram residuals by exact quadrature, the mpmath reference of the hemispherical
// bases, the prefix property, batch path against scalar path and float against double, and
// SPHBASIS_HEMI_BASIS_TESTS, the test cases every hemispherical basis shares.
//
// A test file says `using namespace sphbasis; using namespace sphbasis::test;` and has Dir,
// random_dirs, pi and eps at hand.
//
// The checks of the hemispherical bases take a traits type Tr (HemiTraits below makes one) with
//   using Basis = ...;                      the basis (basis/basis.hpp interface)
//   static double scale(int l);             the largest value of band l's functions
//   static int degree_of(int k);            the band of function k
//   static int index(int l, int m);         the function index of (l, m)
//   using RowKernel, ColumnKernel;          the basis' recurrence kernels ({bands})
//   static void with_kernel(int bands, F);  the basis' kernel dispatch
#pragma once

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sphbasis/basis/basis.hpp>
#include <sphbasis/core/constants.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/core/simd.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace sphbasis::test {

using Dir = std::array<double, 3>;
using constants::pi;
constexpr double eps = std::numeric_limits<double>::epsilon();

/// The traits of a hemispherical basis B (see the top of this file): its recurrence kernels RowK
/// and ColK, and the functions giving the scale of band l, the band of function k and the index of
/// (l, m).
template <class B, class RowK, class ColK, double (*Scale)(int), int (*DegreeOf)(int),
          int (*Index)(int, int)>
struct HemiTraits {
    using Basis = B;
    using RowKernel = RowK;
    using ColumnKernel = ColK;
    static double scale(int l) { return Scale(l); }
    static int degree_of(int k) { return DegreeOf(k); }
    static int index(int l, int m) { return Index(l, m); }
    template <class F>
    static void with_kernel(int bands, F&& f) {
        B::with_bands_kernel(bands, std::forward<F>(f));
    }
};

/// n unit directions from a normal distribution with a fixed seed; `upper` folds them onto z >= 0.
inline std::vector<Dir> random_dirs(int n, unsigned seed, bool upper = true) {
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

/// The components of `dirs` times `scale`, rounded to T: x, y and z arrays for the batch paths.
template <class T>
struct Inputs {
    std::vector<T> xs, ys, zs;
    std::size_t size() const noexcept { return xs.size(); }
};
template <class T>
Inputs<T> scaled_inputs(const std::vector<Dir>& dirs, double scale) {
    Inputs<T> in;
    for (const auto& d : dirs) {
        in.xs.push_back(T(d[0] * scale));
        in.ys.push_back(T(d[1] * scale));
        in.zs.push_back(T(d[2] * scale));
    }
    return in;
}

/// The B::count(bands) values of B at (x, y, z), in double.
template <class B>
std::vector<double> eval_bands(int bands, double x, double y, double z) {
    std::vector<double> v(static_cast<std::size_t>(B::count(bands)));
    basis_eval<B>(B::count(bands), x, y, z, v.data());
    return v;
}

/// Calls the kernel k at d and returns its n values.
template <class K>
std::vector<double> run_kernel(const K& k, int n, const Dir& d) {
    std::vector<double> v(static_cast<std::size_t>(n), std::numeric_limits<double>::quiet_NaN());
    k(d[0], d[1], d[2], [&](int i, double x) { v[static_cast<std::size_t>(i)] = x; });
    return v;
}

/// sum_i a[i] b[i], SIMD across i.
inline double simd_dot(const double* a, const double* b, std::size_t n) {
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

/// max |G - I| of the Gram matrix of B's first n functions on the hemisphere rule of `degree`
/// (batch evaluation).
template <class B>
double gram_residual(int n, int degree) {
    const DirectionalRule r = hemisphere_rule(degree);
    const std::size_t np = r.size(), un = static_cast<std::size_t>(n);
    std::vector<double> f(un * np);
    basis_eval_batch<B>(n, np, r.x.data(), r.y.data(), r.z.data(), f.data(), np);
    for (std::size_t k = 0; k < un; ++k)
        for (std::size_t i = 0; i < np; ++i) f[k * np + i] *= std::sqrt(r.w[i]);
    double worst = 0;
    for (std::size_t a = 0; a < un; ++a)
        for (std::size_t b = 0; b <= a; ++b)
            worst = std::max(
                worst, std::fabs(simd_dot(&f[a * np], &f[b * np], np) - (a == b ? 1.0 : 0.0)));
    return worst;
}

/// Checks gram_residual<B>(B::count(bands), degree(bands)) < tol for each band count; `report`
/// also prints the residuals.
template <class B, class Degree>
void check_gram_identity(const std::vector<int>& band_counts, Degree degree, double tol,
                         bool report) {
    for (int bands : band_counts) {
        const double r = gram_residual<B>(B::count(bands), degree(bands));
        INFO("bands " << bands << " residual " << r);
        CHECK(r < tol);
        if (report) WARN(B::name << " Gram residual, " << bands << " bands: " << r);
    }
}

/// The 1..n band counts 1, 2, ..., n.
inline std::vector<int> band_range(int n) {
    std::vector<int> b;
    for (int i = 1; i <= n; ++i) b.push_back(i);
    return b;
}

/// Gram matrix of B's n functions by the rule r, scalar evaluation, full n x n.
template <class B>
std::vector<std::vector<double>> gram_matrix(int n, const DirectionalRule& r) {
    const std::size_t un = static_cast<std::size_t>(n);
    std::vector<std::vector<double>> g(un, std::vector<double>(un, 0.0));
    std::vector<double> v(un);
    for (std::size_t i = 0; i < r.size(); ++i) {
        basis_eval<B>(n, r.x[i], r.y[i], r.z[i], v.data());
        for (std::size_t a = 0; a < un; ++a)
            for (std::size_t b = 0; b < un; ++b) g[a][b] += r.w[i] * v[a] * v[b];
    }
    return g;
}

/// Per-order orthonormality of Tr's column recurrence at `bands` bands: at phi = 0 the m >= 0
/// functions are g_lm(z), and pi (1 + delta_m0) int_0^1 g_lm g_l'm dz, by `bands` Gauss-Legendre
/// nodes in z, is delta_ll'. Bands of order m are m, m + step, ... Returns max |G - I|.
template <class Tr>
double column_gram_residual(int bands, const std::vector<int>& orders, int step) {
    constexpr double pi = constants::pi;
    std::vector<double> t, w;
    gauss_legendre(bands, t, w);
    std::vector<std::vector<double>> g(orders.size());
    std::vector<double> v(static_cast<std::size_t>(Tr::Basis::count(bands)));
    for (std::size_t i = 0; i < t.size(); ++i) {
        const double z = 0.5 * (t[i] + 1);
        const double s = std::sqrt((1 - z) * (1 + z));
        typename Tr::ColumnKernel{bands}(
            s, 0.0, z, [&](int k, double x) { v[static_cast<std::size_t>(k)] = x; });
        for (std::size_t j = 0; j < orders.size(); ++j)
            for (int l = orders[j]; l < bands; l += step)
                g[j].push_back(v[static_cast<std::size_t>(Tr::index(l, orders[j]))]);
    }
    double worst = 0;
    for (std::size_t j = 0; j < orders.size(); ++j) {
        const int m = orders[j];
        const std::size_t un = static_cast<std::size_t>((bands - 1 - m) / step + 1);
        const double c = pi * (m == 0 ? 2 : 1);
        for (std::size_t a = 0; a < un; ++a)
            for (std::size_t b = 0; b <= a; ++b) {
                double s = 0;
                for (std::size_t i = 0; i < t.size(); ++i)
                    s += 0.5 * w[i] * g[j][i * un + a] * g[j][i * un + b];
                worst = std::max(worst, std::fabs(c * s - (a == b ? 1.0 : 0.0)));
            }
    }
    return worst;
}

/// column_gram_residual<Tr>(512, orders, step) < 1e-12, and reports it.
template <class Tr>
void check_column_orthonormal(const std::vector<int>& orders, int step) {
    const double worst = column_gram_residual<Tr>(512, orders, step);
    WARN(Tr::Basis::name << " per-order Gram residual at 512 bands: " << worst);
    CHECK(worst < 1e-12);
}

struct RefValue {
    int k, l, m;
    double ref;
};
/// The lines of tests/data/hemi_reference.txt for `basis`, grouped by direction.
inline std::map<Dir, std::vector<RefValue>> load_hemi_reference(const std::string& basis) {
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

/// B's first n functions against the mpmath reference lines of `name`, each within `tol`. Returns
/// the number of values checked and the worst |error|.
template <class B>
std::pair<long, double> check_reference_values(const std::string& name, int n, double tol) {
    long count = 0;
    double worst = 0;
    std::vector<double> v(static_cast<std::size_t>(n));
    for (const auto& [d, values] : load_hemi_reference(name)) {
        basis_eval<B>(n, d[0], d[1], d[2], v.data());
        for (const auto& r : values) {
            const double got = v[static_cast<std::size_t>(r.k)];
            INFO(name << " k=" << r.k << " dir=" << d[0] << "," << d[1] << "," << d[2]);
            REQUIRE(std::fabs(got - r.ref) <= tol);
            worst = std::max(worst, std::fabs(got - r.ref));
            ++count;
        }
    }
    return {count, worst};
}

/// Accuracy bound: 5e-14 S_l plus the input's own conditioning, ~l ulp of the sectoral factor and,
/// within 0.01 of the pole, ~l^2 ulp (slope ~l^2 S_l in z there; 1 ulp of z).
template <class Tr>
double reference_bound(int l, double z) {
    constexpr double eps = std::numeric_limits<double>::epsilon();
    const double dl = l;
    return (5e-14 + eps * dl * (1 + (1 - z < 1e-2 ? dl : 0.0))) * Tr::scale(l);
}

/// Tr's values against its mpmath reference lines up to degree max_l.
template <class Tr>
void check_hemi_reference(int max_l) {
    using B = typename Tr::Basis;
    const auto ref = load_hemi_reference(B::name);
    REQUIRE(!ref.empty());
    long count = 0;
    double worst = 0;
    for (const auto& [d, values] : ref) {
        int lmax = 0;
        for (const auto& r : values)
            if (r.l <= max_l) lmax = std::max(lmax, r.l);
        const auto v = eval_bands<B>(lmax + 1, d[0], d[1], d[2]);
        for (const auto& r : values) {
            if (r.l > max_l) continue;
            REQUIRE(r.k == Tr::index(r.l, r.m));
            const double got = v[static_cast<std::size_t>(r.k)];
            INFO("l=" << r.l << " m=" << r.m << " dir=" << d[0] << "," << d[1] << "," << d[2]
                      << " got " << got << " ref " << r.ref);
            REQUIRE(std::fabs(got - r.ref) <= reference_bound<Tr>(r.l, d[2]));
            worst = std::max(worst, std::fabs(got - r.ref) / Tr::scale(r.l));
            ++count;
        }
    }
    CHECK(count > 500);
    WARN(B::name << " reference (l <= " << max_l << "): " << count
                 << " values, worst |error|/S = " << worst);
}

/// Unrolled kernels (bands <= 8), row recurrence and column recurrence agree within 16 ulp of the
/// scale; row and column recurrence at 64 bands within 1e-13.
template <class Tr>
void check_kernels_agree() {
    using B = typename Tr::Basis;
    using RowK = typename Tr::RowKernel;
    using ColK = typename Tr::ColumnKernel;
    constexpr double eps = std::numeric_limits<double>::epsilon();
    auto dirs = random_dirs(100, 2);
    for (Dir d : {Dir{0, 0, 1}, Dir{1, 0, 0}, Dir{0, -1, 0}, Dir{0.6, 0.8, 1e-9}, Dir{1e-9, 0, 1},
                  Dir{0, 0, -1}, Dir{0.6, 0, -0.8}})
        dirs.push_back(d);
    for (auto& d : dirs) normalize_or_pole(d[0], d[1], d[2]);  // the kernels take unit input
    for (int bands = 1; bands <= 8; ++bands) {
        const int n = B::count(bands);
        double worst = 0;
        for (const auto& d : dirs) {
            std::vector<double> fixed;
            Tr::with_kernel(bands, [&](auto k) { fixed = run_kernel(k, n, d); });
            const auto rows = run_kernel(RowK{bands}, n, d);
            const auto cols = run_kernel(ColK{bands}, n, d);
            for (int k = 0; k < n; ++k) {
                const std::size_t uk = static_cast<std::size_t>(k);
                const double s = Tr::scale(Tr::degree_of(k));
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
        const auto rows = run_kernel(RowK{64}, B::count(64), d);
        const auto cols = run_kernel(ColK{64}, B::count(64), d);
        for (int k = 0; k < B::count(64); ++k)
            worst = std::max(worst, std::fabs(rows[static_cast<std::size_t>(k)] -
                                              cols[static_cast<std::size_t>(k)]) /
                                        Tr::scale(Tr::degree_of(k)));
    }
    CHECK(worst <= 1e-13);
}

/// The first count(b) values of 100 bands equal those of b bands within 1e-13 of the scale, and
/// bitwise within one evaluation path (20 and 40 bands).
template <class Tr>
void check_prefix_property() {
    using B = typename Tr::Basis;
    for (const auto& d : random_dirs(5, 3)) {
        const auto big = eval_bands<B>(100, d[0], d[1], d[2]);
        for (int b : {1, 2, 3, 7, 8, 9, 31, 64, 65, 99}) {
            const auto small = eval_bands<B>(b, d[0], d[1], d[2]);
            double worst = 0;
            for (int i = 0; i < B::count(b); ++i)
                worst = std::max(worst, std::fabs(small[static_cast<std::size_t>(i)] -
                                                  big[static_cast<std::size_t>(i)]) /
                                            Tr::scale(Tr::degree_of(i)));
            INFO("bands " << b);
            CHECK(worst <= 1e-13);
        }
        // Within one evaluation path the prefix is bitwise.
        const auto a = eval_bands<B>(40, d[0], d[1], d[2]);
        const auto c = eval_bands<B>(20, d[0], d[1], d[2]);
        CHECK(std::equal(c.begin(), c.end(), a.begin()));
    }
}

/// Batch evaluation equals scalar evaluation within 4 ulp of (l + 1) S_l, sums within 8 ulp of
/// the magnitude, for band counts across every kernel.
template <class Tr, class T>
void check_batch_equals_scalar() {
    using B = typename Tr::Basis;
    auto dirs = random_dirs(37, 5, false);  // not a multiple of any SIMD width; both hemispheres
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    const auto in = scaled_inputs<T>(dirs, 3);  // non-unit on purpose: both paths normalise
    const T *xs = in.xs.data(), *ys = in.ys.data(), *zs = in.zs.data();
    const std::size_t n = dirs.size();
    for (int bands : {1, 2, 3, 4, 8, 9, 17, 64, 66}) {
        const int nf = B::count(bands);
        const std::size_t unf = static_cast<std::size_t>(nf);
        std::vector<T> out(unf * n), one(unf), coeffs(unf), sums(n);
        for (std::size_t k = 0; k < unf; ++k) coeffs[k] = T(std::sin(double(k) + 1));
        basis_eval_batch<B>(nf, n, xs, ys, zs, out.data(), n);
        basis_eval_sum_batch<B>(nf, coeffs.data(), n, xs, ys, zs, sums.data());
        double worst = 0, worst_sum = 0;
        for (std::size_t i = 0; i < n; ++i) {
            basis_eval<B>(nf, xs[i], ys[i], zs[i], one.data());
            double dot = 0, mag = 0;
            for (std::size_t k = 0; k < unf; ++k) {
                const int l = Tr::degree_of(int(k));
                worst = std::max(worst, std::fabs(double(out[k * n + i]) - double(one[k])) /
                                            ((l + 1) * Tr::scale(l)));
                dot += double(coeffs[k]) * double(one[k]);
                mag += std::fabs(double(coeffs[k]) * double(one[k]));
            }
            const T s1 = basis_eval_sum<B>(nf, coeffs.data(), xs[i], ys[i], zs[i]);
            worst_sum = std::max(worst_sum, std::fabs(double(s1) - dot) / (mag + 1));
            worst_sum = std::max(worst_sum, std::fabs(double(sums[i]) - dot) / (mag + 1));
        }
        INFO("bands " << bands);
        CHECK(worst <= 4 * double(std::numeric_limits<T>::epsilon()));
        CHECK(worst_sum <= 8 * double(std::numeric_limits<T>::epsilon()));
    }
}

/// Batch equals scalar for B's nf functions at `in` with explicit bounds: |batch - scalar| <=
/// tol_batch, |float - double| <= tol_double, |sum - dot| <= tol_sum (dot accumulated in T).
template <class B, class T>
void check_batch_equals_scalar(int nf, const std::vector<T>& coeffs, const Inputs<T>& in,
                               T tol_batch, double tol_double, T tol_sum) {
    const std::size_t n = in.size(), unf = static_cast<std::size_t>(nf);
    const T *xs = in.xs.data(), *ys = in.ys.data(), *zs = in.zs.data();
    std::vector<T> out(unf * n), one(unf), sums(n);
    std::vector<double> dd(unf);
    basis_eval_batch<B>(nf, n, xs, ys, zs, out.data(), n);
    basis_eval_sum_batch<B>(nf, coeffs.data(), n, xs, ys, zs, sums.data());
    for (std::size_t i = 0; i < n; ++i) {
        basis_eval<B>(nf, xs[i], ys[i], zs[i], one.data());
        basis_eval<B>(nf, double(xs[i]), double(ys[i]), double(zs[i]), dd.data());
        T dot = 0;
        for (std::size_t k = 0; k < unf; ++k) {
            REQUIRE(std::fabs(out[k * n + i] - one[k]) <= tol_batch);
            REQUIRE(std::fabs(double(one[k]) - dd[k]) <= tol_double);
            dot += coeffs[k] * one[k];
        }
        REQUIRE(std::fabs(basis_eval_sum<B>(nf, coeffs.data(), xs[i], ys[i], zs[i]) - dot) <=
                tol_sum);
        REQUIRE(std::fabs(sums[i] - dot) <= tol_sum);
    }
}

/// |float - double| <= 6 (l + 1)^1.5 ulp(float) S_l at the float-rounded directions.
template <class Tr>
void check_float_vs_double() {
    using B = typename Tr::Basis;
    const double ef = std::numeric_limits<float>::epsilon();
    double worst = 0;
    auto dirs = random_dirs(200, 9);
    dirs.push_back({0, 0, 1});
    dirs.push_back({0.6, 0.8, 0});
    for (const auto& d : dirs) {
        for (int bands : {3, 8, 31, 64, 70}) {
            std::vector<float> f(static_cast<std::size_t>(B::count(bands)));
            basis_eval<B>(B::count(bands), float(d[0]), float(d[1]), float(d[2]), f.data());
            const auto dd =
                eval_bands<B>(bands, double(float(d[0])), double(float(d[1])), double(float(d[2])));
            for (std::size_t k = 0; k < f.size(); ++k) {
                const int l = Tr::degree_of(int(k));
                worst = std::max(worst, std::fabs(double(f[k]) - dd[k]) /
                                            (std::pow(l + 1, 1.5) * ef * Tr::scale(l)));
            }
        }
    }
    WARN(B::name << " float vs double: worst |f - d| / ((l + 1)^1.5 ulp S_l) = " << worst);
    CHECK(worst <= 6);
}

/// Below the horizon every function of B is exactly 0.
template <class B>
void check_zero_below_horizon() {
    auto dirs = random_dirs(50, 4, false);
    for (Dir d : {Dir{0, 0, -1}, Dir{1, 0, -1e-300}, Dir{0.6, 0.8, -1e-12}, Dir{0, 1, -0.5}})
        dirs.push_back(d);
    for (const auto& d : dirs) {
        if (d[2] >= 0) continue;
        for (int bands : {1, 3, 8, 20, 65}) {
            const auto v = eval_bands<B>(bands, d[0], d[1], d[2]);
            for (double x : v) REQUIRE(x == 0);
        }
    }
}

/// Poles, denormal, huge, zero and NaN input give finite values in float and double; a direction
/// that is none (NaN) gives the pole's first n_pole values.
template <class B>
void check_hard_directions_finite(int n_pole) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const std::vector<Dir> hard = {
        {0, 0, 1}, {1e-300, 0, 1}, {3e-310, 2e-310, 1e-310}, {1e300, 1e300, 1e300}, {1, 1e-300, 0},
        {0, 0, 0}, {nan, 0, 1},    {1e-20, -1e-20, 1}};
    const std::size_t np = static_cast<std::size_t>(n_pole);
    std::vector<double> pole(np);
    basis_eval<B>(n_pole, 0.0, 0.0, 1.0, pole.data());
    for (int bands : {4, 9, 64, 200}) {
        std::vector<double> v(static_cast<std::size_t>(B::count(bands)));
        std::vector<float> f(v.size());
        for (const auto& d : hard) {
            basis_eval<B>(B::count(bands), d[0], d[1], d[2], v.data());
            basis_eval<B>(B::count(bands), float(d[0]), float(d[1]), float(d[2]), f.data());
            for (double x : v) REQUIRE(std::isfinite(x));
            for (float x : f) REQUIRE(std::isfinite(x));
        }
    }
    std::vector<double> v(np);
    basis_eval<B>(n_pole, nan, 0.0, 0.0, v.data());  // no direction: the pole
    for (std::size_t k = 0; k < np; ++k) CHECK(v[k] == pole[k]);
}

/// The directions of the closed-form checks: 50 random ones on the upper hemisphere (seed 1), one
/// general direction, the pole and two horizon points.
inline std::vector<Dir> closed_form_dirs() {
    auto dirs = random_dirs(50, 1);
    dirs.push_back({0.48, -0.6, 0.64});
    dirs.push_back({0, 0, 1});
    dirs.push_back({1, 0, 0});
    dirs.push_back({0, -1, 0});
    return dirs;
}

/// B's first N functions (3 bands) equal the closed forms f(x, y, z) (a std::array<double, N>)
/// within `tol` at closed_form_dirs().
template <class B, class F>
void check_closed_forms(F&& f, double tol) {
    for (const auto& d : closed_form_dirs()) {
        const double x = d[0], y = d[1], z = d[2];
        const auto c = f(x, y, z);
        const auto v = eval_bands<B>(3, x, y, z);
        for (std::size_t k = 0; k < c.size(); ++k) {
            INFO("k=" << k << " dir=" << x << "," << y << "," << z);
            REQUIRE(std::fabs(v[k] - c[k]) <= tol);
        }
    }
}

/// Band-1 signs (no Condon-Shortley phase): at (0.6, 0, 0.8) the x-like function kx is positive
/// and equals `x_value` within 1e-15 (relative), the y-like function 1 is 0; at (0, 0.6, 0.8) the
/// y-like one is positive and the x-like one below 1e-16. Returns the values at (0.6, 0, 0.8).
template <class B>
std::vector<double> check_band1_signs(std::size_t kx, double x_value) {
    const auto a = eval_bands<B>(2, 0.6, 0.0, 0.8);
    CHECK(a[kx] > 0);
    CHECK(a[1] == 0);
    const auto b = eval_bands<B>(2, 0.0, 0.6, 0.8);
    CHECK(b[1] > 0);
    CHECK(std::fabs(b[kx]) < 1e-16);
    CHECK(a[kx] == Approx(x_value).epsilon(1e-15));
    return a;
}

/// The square-count bases' sizes: n bands are n^2 functions, index(l, m) = l (l + 1) + m.
template <class Tr>
void check_square_counts() {
    using B = typename Tr::Basis;
    CHECK(Tr::index(2, -1) == 5);
    CHECK(B::count(4) == 16);
    CHECK(B::bands_of(16) == 4);
    CHECK(B::bands_of(15) == -1);
}

/// B's declared traits: its name, the hemisphere domain, orthonormality and its largest count.
template <class B>
void check_declared(const std::string& name, int max_count) {
    CHECK(std::string(B::name) == name);
    CHECK(B::domain == Domain::hemisphere);
    CHECK(B::orthonormal);
    CHECK(B::max_count() == max_count);
}

/// Pole (0, 0, 1) and horizon (0.6, -0.8, +-0) at band counts up to 300, orders m = -l, -l + step,
/// ..., l: finite, pole(l, m) and rim(l, m) within 1e-14 + 20 eps bands of the scale (`exact_rim`:
/// the horizon values equal rim(l, m) exactly), and -0 gives the values of +0 (on the horizon, not
/// below).
template <class Tr, class Pole, class Rim>
void check_pole_and_horizon(int step, Pole&& pole, Rim&& rim, bool exact_rim) {
    using B = typename Tr::Basis;
    for (int bands : {1, 3, 8, 20, 64, 65, 300}) {
        const auto p = eval_bands<B>(bands, 0, 0, 1);
        const auto h = eval_bands<B>(bands, 0.6, -0.8, 0);
        const auto hz = eval_bands<B>(bands, 0.6, -0.8, -0.0);
        double worst = 0;
        for (int l = 0; l < bands; ++l)
            for (int m = -l; m <= l; m += step) {
                const std::size_t k = static_cast<std::size_t>(Tr::index(l, m));
                const double s = Tr::scale(l);
                REQUIRE(std::isfinite(p[k]));
                REQUIRE(std::isfinite(h[k]));
                worst = std::max(worst, std::fabs(p[k] - pole(l, m)) / s);
                if (exact_rim)
                    REQUIRE(h[k] == rim(l, m));
                else
                    worst = std::max(worst, std::fabs(h[k] - rim(l, m)) / s);
                REQUIRE(hz[k] == h[k]);
            }
        INFO("bands " << bands);
        CHECK(worst <= 1e-14 + 20 * eps * bands);
    }
}

/// Bad function counts throw: 5 with the full message ("sphbasis::basis_eval(): expected <shape>
/// <detail> of functions for basis '<name>', got 5"), 0 and `negative` naming the count,
/// `too_many` naming the 2048-band limit, a batch of `batch_count` with a short stride naming the
/// stride, and basis_eval_sum of `sum_count` functions naming the shape; max_count() is a valid
/// count, `too_many` is not.
template <class B>
void check_bad_counts(const std::string& shape, const std::string& detail, int negative,
                      int too_many, int batch_count, int sum_count) {
    double v[16];
    float f[4];
    REQUIRE_THROWS_WITH(basis_eval<B>(5, 0.0, 0.0, 1.0, v),
                        "sphbasis::basis_eval(): expected " + shape + " " + detail +
                            " of functions for basis '" + B::name + "', got 5");
    REQUIRE_THROWS_WITH(basis_eval<B>(0, 0.0, 0.0, 1.0, v), Catch::Contains("got 0"));
    REQUIRE_THROWS_WITH(basis_eval<B>(negative, 0.0, 0.0, 1.0, v),
                        Catch::Contains("got " + std::to_string(negative)));
    REQUIRE_THROWS_WITH(basis_eval<B>(too_many, 0.0, 0.0, 1.0, v),
                        Catch::Contains("bands <= 2048"));
    REQUIRE_THROWS_WITH(basis_eval_batch<B>(batch_count, 2, f, f, f, f, 1),
                        Catch::Contains("stride"));
    REQUIRE_THROWS_WITH(basis_eval_sum<B>(sum_count, f, 0.f, 0.f, 1.f),
                        Catch::Contains("sphbasis::basis_eval_sum(): expected " + shape));
    CHECK(B::valid_count(B::max_count()));
    CHECK_FALSE(B::valid_count(too_many));
}

}  // namespace sphbasis::test

/// Registers the test cases every hemispherical basis shares, named "<NAME>: ..." and tagged
/// [<NAME>] (NAME a string literal, TR the traits type above, N_POLE the function count of the
/// hard-direction check): mpmath reference (l <= 255; l <= 2047 [slow]), the kernels agree, the
/// prefix property, batch equals scalar (float, double), float within 6 (l + 1)^1.5 ulp(float) S_l
/// of double (the float path normalises the direction in float, where near the pole degree-l
/// functions have slope ~l^2 in z, and rounds each recurrence step, ~l^1.5 ulp near the ends),
/// 0 below the horizon and finite values at hard directions.
#define SPHBASIS_HEMI_BASIS_TESTS(NAME, TR, N_POLE)                                               \
    TEST_CASE(NAME ": values against the mpmath reference (l <= 255)", "[" NAME "][reference]") { \
        sphbasis::test::check_hemi_reference<TR>(255);                                            \
    }                                                                                             \
    TEST_CASE(NAME ": values against the mpmath reference (l <= 2047)",                           \
              "[" NAME "][reference][slow]") {                                                    \
        sphbasis::test::check_hemi_reference<TR>(2047);                                           \
    }                                                                                             \
    TEST_CASE(NAME ": unrolled kernels, row recurrence and column recurrence agree",              \
              "[" NAME "]") {                                                                     \
        sphbasis::test::check_kernels_agree<TR>();                                                \
    }                                                                                             \
    TEST_CASE(NAME ": prefix property", "[" NAME "]") {                                           \
        sphbasis::test::check_prefix_property<TR>();                                              \
    }                                                                                             \
    TEMPLATE_TEST_CASE(NAME ": batch path equals scalar path", "[" NAME "]", float, double) {     \
        sphbasis::test::check_batch_equals_scalar<TR, TestType>();                                \
    }                                                                                             \
    TEST_CASE(NAME ": float is within a stated bound of double", "[" NAME "]") {                  \
        sphbasis::test::check_float_vs_double<TR>();                                              \
    }                                                                                             \
    TEST_CASE(NAME ": below the horizon every function is 0", "[" NAME "]") {                     \
        sphbasis::test::check_zero_below_horizon<typename TR::Basis>();                           \
    }                                                                                             \
    TEST_CASE(NAME ": hard directions stay finite", "[" NAME "]") {                               \
        sphbasis::test::check_hard_directions_finite<typename TR::Basis>(N_POLE);                 \
    }
