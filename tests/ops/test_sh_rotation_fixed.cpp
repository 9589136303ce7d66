// Tests for ops/sh_rotation_fixed.hpp (generated): FixedRotation<N, T> and rotate<N> equal the
// run-time sh::Rotation / sh::rotate for every N in 1..8 (random proper and improper rotations,
// float and double), preserve band energy, compose, invert by apply_transposed, rotate RGB
// coefficients in one pass, and the checked entry point refuses non-orthonormal matrices.
#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <glm/glm.hpp>
#include <random>
#include <vector>

#include "../support/rotation_checks.hpp"
#include "sphbasis/ops/sh_rotation.hpp"
#include "sphbasis/ops/sh_rotation_fixed.hpp"

namespace sh = sphbasis::sh;

namespace {

template <class T>
sh::Mat3<T> random_rotation(std::mt19937& rng, bool improper) {
    return sphbasis::test::random_rotation_matrix<T>(
        rng, improper ? sphbasis::test::Improper::reflect_z : sphbasis::test::Improper::no);
}

template <class T>
double tol() {
    return std::is_same_v<T, float> ? 2e-5 : 1e-13;
}

struct RGB {
    double r = 0, g = 0, b = 0;
};
RGB operator+(const RGB& a, const RGB& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
RGB operator*(const RGB& a, double s) { return {a.r * s, a.g * s, a.b * s}; }

template <int N, class T>
void check_against_runtime(std::mt19937& rng) {
    for (int trial = 0; trial < 20; ++trial) {
        const bool improper = trial % 4 == 3;
        const sh::Mat3<T> r = random_rotation<T>(rng, improper);
        const sh::FixedRotation<N, T> f(r);
        const auto d = sh::Rotation<T>::from_matrix(N, r);
        REQUIRE(d.size() == f.size());
        double worst = 0;
        for (int l = 0; l < N; ++l)
            for (int m = -l; m <= l; ++m)
                for (int n = -l; n <= l; ++n) {
                    const std::size_t w = static_cast<std::size_t>(2 * l + 1);
                    const T v = d.data()[f.offset(l) + static_cast<std::size_t>(m + l) * w +
                                         static_cast<std::size_t>(n + l)];
                    // f's blocks are column-major, the run-time ones row-major
                    CHECK(f.block(l)[static_cast<std::size_t>(n + l) * w +
                                     static_cast<std::size_t>(m + l)] == f(l, m, n));
                    worst = std::max(worst, std::fabs(double(f(l, m, n)) - double(v)));
                }
        CHECK(worst <= tol<T>());
        // rotate<N> and apply equal sh::rotate; band energy is invariant.
        std::uniform_real_distribution<T> u(T(-1), T(1));
        std::array<T, N * N> in{}, a{}, b{}, c{};
        for (auto& v : in) v = u(rng);
        f.apply(in.data(), a.data());
        sh::rotate<N>(r, in.data(), b.data());
        sh::rotate(N, r, in.data(), c.data());
        for (std::size_t k = 0; k < std::size_t(N * N); ++k) {
            CHECK(std::fabs(double(a[k]) - double(c[k])) <= 4 * tol<T>());
            CHECK(std::fabs(double(b[k]) - double(c[k])) <= 4 * tol<T>());
        }
        for (int l = 0; l < N; ++l) {
            double e0 = 0, e1 = 0;
            for (std::size_t k = std::size_t(l * l); k < std::size_t((l + 1) * (l + 1)); ++k) {
                e0 += double(in[k]) * double(in[k]);
                e1 += double(a[k]) * double(a[k]);
            }
            CHECK(std::fabs(e1 - e0) <= 8 * tol<T>() * (1 + e0));
        }
        // in place; the inverse.
        std::array<T, N* N> ip = in;
        f.apply(ip.data(), ip.data());
        for (std::size_t k = 0; k < std::size_t(N * N); ++k) CHECK(ip[k] == a[k]);
        f.apply_transposed(a.data(), b.data());
        for (std::size_t k = 0; k < std::size_t(N * N); ++k)
            CHECK(std::fabs(double(b[k]) - double(in[k])) <= 8 * tol<T>());
    }
}

template <int... Ns, class T>
void all_bands(std::mt19937& rng, T) {
    (check_against_runtime<Ns, T>(rng), ...);
}

}  // namespace

TEMPLATE_TEST_CASE("FixedRotation<N> equals the run-time Rotation for N = 1..8", "[ops][rotation]",
                   float, double) {
    std::mt19937 rng(14);
    all_bands<1, 2, 3, 4, 5, 6, 7, 8>(rng, TestType(0));
}

TEST_CASE("FixedRotation: identity, quaternion, composition, matrix types", "[ops][rotation]") {
    std::mt19937 rng(3);
    const sh::FixedRotation<5, double> id;
    const sh::FixedRotation<5, double> fid(sh::Mat3<double>{1, 0, 0, 0, 1, 0, 0, 0, 1});
    for (std::size_t k = 0; k < id.size(); ++k)
        CHECK(id.data()[k] == Approx(fid.data()[k]).margin(1e-15));
    // quaternion == matrix of the quaternion
    const auto q = sh::FixedRotation<6, double>::from_quaternion(0.3, -0.2, 0.9, 0.4);
    const auto qm = sh::FixedRotation<6, double>(sh::matrix_from_quaternion(0.3, -0.2, 0.9, 0.4));
    for (std::size_t k = 0; k < q.size(); ++k) CHECK(q.data()[k] == qm.data()[k]);
    // D(R1 R2) = D(R1) D(R2)
    const auto r1 = random_rotation<double>(rng, false), r2 = random_rotation<double>(rng, true);
    const sh::FixedRotation<7, double> d1(r1), d2(r2), d12(sh::multiply(r1, r2));
    std::array<double, 49> in{}, a{}, b{};
    for (int k = 0; k < 49; ++k) in[static_cast<std::size_t>(k)] = std::sin(k + 1.0);
    d2.apply(in.data(), a.data());
    d1.apply(a.data(), a.data());
    d12.apply(in.data(), b.data());
    for (std::size_t k = 0; k < 49; ++k) CHECK(a[k] == Approx(b[k]).margin(1e-13));
    // glm (column-major) and Eigen (m(row, col)) read as the same rotation
    glm::dmat3 g;
    Eigen::Matrix3d e;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            g[j][i] = r1[static_cast<std::size_t>(3 * i + j)];
            e(i, j) = r1[static_cast<std::size_t>(3 * i + j)];
        }
    const auto dg = sh::FixedRotation<7, double>::from_matrix(g);
    const auto de = sh::FixedRotation<7, double>::from_matrix(e);
    for (std::size_t k = 0; k < d1.size(); ++k) {
        CHECK(dg.data()[k] == d1.data()[k]);
        CHECK(de.data()[k] == d1.data()[k]);
    }
    // the checked entry point refuses a scaled matrix
    sh::Mat3<double> bad = r1;
    bad[0] *= 1.01;
    using F3 = sh::FixedRotation<3, double>;
    CHECK_THROWS_WITH(F3::from_matrix(bad), Catch::Contains("sh::FixedRotation::from_matrix"));
}

TEST_CASE("FixedRotation rotates RGB coefficients in one pass like each channel",
          "[ops][rotation]") {
    std::mt19937 rng(5);
    const auto r = random_rotation<double>(rng, false);
    const sh::FixedRotation<4, double> d(r);
    std::array<RGB, 16> in{}, out{};
    std::array<double, 16> ch{}, cho{};
    for (int k = 0; k < 16; ++k)
        in[static_cast<std::size_t>(k)] = {k * 0.1, std::cos(k), -k * 0.03};
    d.apply(in.data(), out.data());
    for (int c = 0; c < 3; ++c) {
        for (int k = 0; k < 16; ++k) {
            const RGB& v = in[static_cast<std::size_t>(k)];
            ch[static_cast<std::size_t>(k)] = c == 0 ? v.r : c == 1 ? v.g : v.b;
        }
        d.apply(ch.data(), cho.data());
        for (std::size_t k = 0; k < 16; ++k) {
            const RGB& v = out[k];
            CHECK((c == 0 ? v.r : c == 1 ? v.g : v.b) == Approx(cho[k]).margin(1e-15));
        }
    }
    std::array<RGB, 16> out2{};
    sh::rotate<4>(r, in.data(), out2.data());
    for (std::size_t k = 0; k < 16; ++k) CHECK(out2[k].g == Approx(out[k].g).margin(1e-15));
}

namespace {

sh::Mat3<double> zyz_matrix(double a, double b, double c) {
    const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b),
                 cc = std::cos(c), sc = std::sin(c);
    const sh::Mat3<double> rza{ca, -sa, 0, sa, ca, 0, 0, 0, 1}, ry{cb, 0, sb, 0, 1, 0, -sb, 0, cb},
        rzc{cc, -sc, 0, sc, cc, 0, 0, 0, 1};
    return sh::multiply(rza, sh::multiply(ry, rzc));
}

/// rotate<N>(r), its scalar and its vector implementations (the latter in place; the AVX2
/// kernels against the scalar code where they are compiled) against the run-time sh::rotate: max
/// |difference| over the coefficients (rotate<N> in place included).
template <int N, class T>
double rotate_direct_error(const sh::Mat3<double>& rd, bool improper, std::mt19937& rng) {
    sh::Mat3<T> r;
    for (std::size_t k = 0; k < 9; ++k) r[k] = T(improper ? -rd[k] : rd[k]);
    std::uniform_real_distribution<double> u(-1, 1);
    std::array<T, N * N> in{}, a{}, b{};
    for (auto& v : in) v = T(u(rng));
    sh::rotate<N>(r, in.data(), a.data());
    sh::rotate(N, r, in.data(), b.data());
    std::array<T, N* N> ip = in;
    sh::rotate<N>(r, ip.data(), ip.data());
    // both implementations, whichever rotate<N> picks on this target
    std::array<T, N * N> s{}, v = in;
    sh::detail::rotate_direct_scalar<N>(r.data(), in.data(), s.data());
#if SPHBASIS_SH_ROTATION_VECTOR
    if constexpr (N >= 4) sh::detail::rotate_direct_vec<N>(r.data(), v.data(), v.data());
#endif
    if constexpr (N < 4) v = s;
#if SPHBASIS_SH_ROTATION_AVX2
    // the AVX2 kernels by name (in place), float
    std::array<T, N* N> w = in;
    if constexpr (std::is_same_v<T, float> && N == 3)
        sh::detail::rotate_three_bands_avx2(r.data(), w.data(), w.data());
#if SPHBASIS_SH_ROTATION_VECTOR
    if constexpr (std::is_same_v<T, float> && N >= 4)
        sh::detail::rotate_direct_avx2<N>(r.data(), w.data(), w.data());
#endif
    if constexpr (!std::is_same_v<T, float> || N < 3) w = s;
#else
    const std::array<T, N* N>& w = s;
#endif
    double worst = 0;
    for (std::size_t k = 0; k < std::size_t(N * N); ++k) {
        // In place agrees with out of place to rounding (not bit for bit: the compiler may
        // contract a*b+c into an FMA differently in the two inlined copies).
        worst = std::max(
            {worst, std::fabs(double(a[k]) - double(b[k])), std::fabs(double(s[k]) - double(b[k])),
             std::fabs(double(v[k]) - double(b[k])), std::fabs(double(ip[k]) - double(a[k])),
             std::fabs(double(w[k]) - double(s[k]))});
    }
    return worst;
}

template <class T, int... Ns>
void rotate_direct_cases(std::mt19937& rng) {
    const double eps = std::is_same_v<T, float> ? 1e-5 : 3e-14;
    const double pi = 3.14159265358979323846;
    const double betas[] = {0.0,       1e-8,      -1e-8,      1e-12,    3e-5, pi,
                            pi - 1e-8, pi + 1e-8, pi - 1e-12, 0.5 * pi, 1.3};
    std::uniform_real_distribution<double> ang(-pi, pi);
    double worst = 0;
    for (double beta : betas)
        for (int trial = 0; trial < 6; ++trial) {
            const auto rd =
                zyz_matrix(trial == 0 ? 0.0 : ang(rng), beta, trial == 1 ? 0.0 : ang(rng));
            for (bool improper : {false, true})
                worst = std::max({worst, rotate_direct_error<Ns, T>(rd, improper, rng)...});
        }
    for (int trial = 0; trial < 40; ++trial) {
        const auto rd = random_rotation<double>(rng, trial % 2 == 1);
        worst = std::max({worst, rotate_direct_error<Ns, T>(rd, false, rng)...});
    }
    INFO("worst " << worst);
    CHECK(worst <= eps);
}

}  // namespace

TEMPLATE_TEST_CASE(
    "rotate<N> (factored, D never formed) equals the run-time sh::rotate for N = 1..8, near "
    "the Euler singularity and for improper matrices",
    "[ops][rotation]", float, double) {
    std::mt19937 rng(141);
    rotate_direct_cases<TestType, 1, 2, 3, 4, 5, 6, 7, 8>(rng);
}
