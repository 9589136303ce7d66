// Tests for the lazy D of sh::Rotation<T> at 1..8 bands (ops/sh_rotation.hpp): from_matrix /
// from_quaternion store R only, apply() runs the factored rotate<N>, and D is built on first
// access. The lazily built D must equal bit for bit the leading blocks of an eagerly built
// 9-band D (same recurrence; a block does not depend on the band count), apply() must agree
// with the product by D within the accuracy of rotate<N>, copies and two threads reading D at
// once must see the same values, and apply_transposed() must invert apply().
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <stdexcept>
#include <thread>
#include <type_traits>
#include <vector>

#include "../support/rotation_checks.hpp"
#include "sphbasis/ops/sh_rotation.hpp"

namespace sh = sphbasis::sh;

namespace {

template <class T>
sh::Mat3<T> random_matrix(std::mt19937& rng, bool improper) {
    return sphbasis::test::random_rotation_matrix<T>(
        rng, improper ? sphbasis::test::Improper::negate : sphbasis::test::Improper::no);
}

template <class T>
std::vector<T> random_coeffs(std::mt19937& rng, int bands) {
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<T> c(static_cast<std::size_t>(bands * bands));
    for (T& v : c) v = T(u(rng));
    return c;
}

// Bound of |rotate<N> - D product| for coefficients in [-1, 1] (measured max 3.4e-6 float,
// 6.8e-15 double over these cases; the generated code's tests use the same bounds).
template <class T>
double apply_tol() {
    return std::is_same_v<T, float> ? 4.4e-6 : 1.6e-14;
}

// out = D in (Transposed: D^T in) from the stored blocks, accumulated in double.
template <class T>
std::vector<double> d_product(const sh::Rotation<T>& rot, const std::vector<T>& in,
                              bool transposed) {
    const int n = rot.bands();
    std::vector<double> out(in.size(), 0.0);
    for (int l = 0; l < n; ++l) {
        const int w = 2 * l + 1, k0 = l * l;
        const T* b = rot.block(l);
        for (int i = 0; i < w; ++i) {
            double acc = 0;
            for (int j = 0; j < w; ++j)
                acc += double(transposed ? b[j * w + i] : b[i * w + j]) *
                       double(in[static_cast<std::size_t>(k0 + j)]);
            out[static_cast<std::size_t>(k0 + i)] = acc;
        }
    }
    return out;
}

template <class T>
double max_diff(const std::vector<T>& a, const std::vector<double>& b) {
    double worst = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        worst = std::max(worst, std::fabs(double(a[k]) - b[k]));
    return worst;
}

template <class T>
void check_lazy_equals_eager(std::mt19937& rng) {
    for (int trial = 0; trial < 8; ++trial) {
        const bool improper = trial % 2 == 1;
        const sh::Mat3<T> r = random_matrix<T>(rng, improper);
        const auto eager = sh::Rotation<T>::from_matrix(9, r);  // above 8 bands: D at once
        REQUIRE_FALSE(eager.lazy());
        for (int n = 1; n <= 8; ++n) {
            const auto lazy = sh::Rotation<T>::from_matrix(n, r);
            REQUIRE(lazy.lazy());
            REQUIRE(lazy.size() == sh::Rotation<T>::offset(n));
            REQUIRE_FALSE(lazy.lazy());
            bool same = true;
            for (std::size_t k = 0; k < lazy.size(); ++k)
                same = same && lazy.data()[k] == eager.data()[k];
            CHECK(same);
            CHECK(lazy(n - 1, 0, n - 1) == eager(n - 1, 0, n - 1));
        }
    }
}

template <class T>
void check_apply_against_d(std::mt19937& rng) {
    double worst = 0, worst_t = 0, worst_inv = 0;
    for (int trial = 0; trial < 8; ++trial) {
        const sh::Mat3<T> r = random_matrix<T>(rng, trial % 2 == 1);
        for (int n = 1; n <= 8; ++n) {
            const auto rot = sh::Rotation<T>::from_matrix(n, r);
            const std::vector<T> in = random_coeffs<T>(rng, n);
            std::vector<T> out(in.size()), back(in.size()), tout(in.size());
            rot.apply(in.data(), out.data());
            rot.apply_transposed(in.data(), tout.data());
            rot.apply_transposed(out.data(), back.data());
            REQUIRE(rot.lazy());  // apply never formed D
            worst = std::max(worst, max_diff(out, d_product(rot, in, false)));
            worst_t = std::max(worst_t, max_diff(tout, d_product(rot, in, true)));
            std::vector<double> ind(in.begin(), in.end());
            worst_inv = std::max(worst_inv, max_diff(back, ind));
            // the in-place form and the range overload give the same result
            std::vector<T> inplace = in;
            rot.apply(inplace.data(), inplace.data());
            CHECK(inplace == out);
            std::vector<T> ranged(in.size());
            rot.apply(in, ranged);
            CHECK(ranged == out);
        }
    }
    INFO("max |apply - D in| " << worst << ", transposed " << worst_t << ", inverse " << worst_inv);
    CHECK(worst <= apply_tol<T>());
    CHECK(worst_t <= apply_tol<T>());
    CHECK(worst_inv <= 2 * apply_tol<T>());
}

}  // namespace

TEST_CASE("rotation lazy: D built on first access equals the eager D bit for bit",
          "[rotation][lazy]") {
    std::mt19937 rng(1401);
    check_lazy_equals_eager<float>(rng);
    check_lazy_equals_eager<double>(rng);
}

TEST_CASE("rotation lazy: apply and apply_transposed through rotate<N> match D",
          "[rotation][lazy]") {
    std::mt19937 rng(1402);
    check_apply_against_d<float>(rng);
    check_apply_against_d<double>(rng);
}

TEST_CASE("rotation lazy: sh::rotate and rotate_quaternion at 1..8 bands match D",
          "[rotation][lazy]") {
    std::mt19937 rng(1403);
    std::normal_distribution<double> nd;
    for (int trial = 0; trial < 6; ++trial) {
        const double w = nd(rng), x = nd(rng), y = nd(rng), z = nd(rng);
        const sh::Mat3<double> r = sh::matrix_from_quaternion(w, x, y, z);
        const auto eager = sh::Rotation<double>::from_matrix(9, r);
        for (int n = 1; n <= 8; ++n) {
            const std::vector<double> in = random_coeffs<double>(rng, n);
            std::vector<double> a(in.size()), b(in.size()), c(in.size()), d(in.size());
            sh::rotate(n, r, in.data(), a.data());
            sh::rotate_quaternion(n, w, x, y, z, in.data(), b.data());
            const auto q = sh::Rotation<double>::from_quaternion(n, w, x, y, z);
            REQUIRE(q.lazy());
            q.apply(in.data(), c.data());
            sh::rotation_from_quaternion(n, w, x, y, z).apply(in, d);
            // the reference: the leading blocks of the eager 9-band D
            std::vector<double> ref(in.size(), 0.0);
            for (int l = 0; l < n; ++l)
                for (int m = -l; m <= l; ++m) {
                    double acc = 0;
                    for (int k = -l; k <= l; ++k)
                        acc += eager(l, m, k) * in[static_cast<std::size_t>(sh::index(l, k))];
                    ref[static_cast<std::size_t>(sh::index(l, m))] = acc;
                }
            CHECK(max_diff(a, ref) <= apply_tol<double>());
            CHECK(max_diff(b, ref) <= apply_tol<double>());
            CHECK(max_diff(c, ref) <= apply_tol<double>());
            CHECK(max_diff(d, ref) <= apply_tol<double>());
        }
    }
}

TEST_CASE("rotation lazy: float from_quaternion / from_matrix at 1..8 bands match D",
          "[rotation][lazy]") {
    // The float paths with their own code (AVX-512 or AVX2 where enabled): the quaternion-to-matrix
    // in registers (non-unit quaternions are normalised), the orthonormality check, the 3-band
    // kernel. Reference: the leading blocks of an eager 9-band D in double.
    std::mt19937 rng(1404);
    std::normal_distribution<double> nd;
    double worst_q = 0, worst_m = 0, worst_r = 0;
    for (int trial = 0; trial < 8; ++trial) {
        const double s = trial % 3 == 0 ? 1e-3 : trial % 3 == 1 ? 1.0 : 1e3;  // |q| scales
        const double w = s * nd(rng), x = s * nd(rng), y = s * nd(rng), z = s * nd(rng);
        const sh::Mat3<double> rd = sh::matrix_from_quaternion(w, x, y, z);
        sh::Mat3<float> rf;
        for (std::size_t k = 0; k < 9; ++k) rf[k] = float(rd[k]);
        const auto eager = sh::Rotation<double>::from_matrix(9, rd);
        for (int n = 1; n <= 8; ++n) {
            const std::vector<float> in = random_coeffs<float>(rng, n);
            std::vector<float> a(in.size()), b(in.size()), c(in.size());
            sh::Rotation<float>::from_quaternion(n, float(w), float(x), float(y), float(z))
                .apply(in.data(), a.data());
            sh::Rotation<float>::from_matrix(n, rf).apply(in.data(), b.data());
            sh::rotate(n, rf, in.data(), c.data());
            std::vector<double> ref(in.size(), 0.0);
            for (int l = 0; l < n; ++l)
                for (int m = -l; m <= l; ++m) {
                    double acc = 0;
                    for (int k = -l; k <= l; ++k)
                        acc += eager(l, m, k) * in[static_cast<std::size_t>(sh::index(l, k))];
                    ref[static_cast<std::size_t>(sh::index(l, m))] = acc;
                }
            worst_q = std::max(worst_q, max_diff(a, ref));
            worst_m = std::max(worst_m, max_diff(b, ref));
            worst_r = std::max(worst_r, max_diff(c, ref));
        }
    }
    INFO("max error: quaternion " << worst_q << ", matrix " << worst_m << ", rotate " << worst_r);
    CHECK(worst_q <= apply_tol<float>());
    CHECK(worst_m <= apply_tol<float>());
    CHECK(worst_r <= apply_tol<float>());
    // the checks still run: a zero quaternion, a scaled or a NaN matrix throw
    CHECK_THROWS_AS(sh::Rotation<float>::from_quaternion(3, 0.f, 0.f, 0.f, 0.f),
                    std::invalid_argument);
    sh::Mat3<float> bad = random_matrix<float>(rng, false);
    for (float& v : bad) v *= 1.01f;
    CHECK_THROWS_AS(sh::Rotation<float>::from_matrix(3, bad), std::invalid_argument);
    // a NaN in any entry (each reaches its own lanes of the vector check)
    for (std::size_t k = 0; k < 9; ++k) {
        bad = random_matrix<float>(rng, false);
        bad[k] = std::nanf("");
        CHECK_THROWS_AS(sh::Rotation<float>::from_matrix(3, bad), std::invalid_argument);
    }
    // I + 2e-4 E_k: one entry of R R^T off by 2e-4 or 4e-4 (a diagonal), above the float
    // tolerance 3e-5, the rest exact; every entry k, so every lane of the check is exercised
    for (std::size_t k = 0; k < 9; ++k) {
        sh::Mat3<float> skew{1, 0, 0, 0, 1, 0, 0, 0, 1};
        skew[k] += 2e-4f;
        CHECK_THROWS_AS(sh::Rotation<float>::from_matrix(3, skew), std::invalid_argument);
        CHECK_NOTHROW(sh::Rotation<float>::from_matrix(3, skew, 1e-3f));
    }
}

template <class T>
void check_prepared(std::mt19937& rng) {
    double worst = 0, worst_t = 0;
    for (int trial = 0; trial < 4; ++trial) {
        const sh::Mat3<T> r = random_matrix<T>(rng, trial % 2 == 1);
        for (int n = 1; n <= 8; ++n) {
            auto rot = sh::Rotation<T>::from_matrix(n, r);
            REQUIRE_FALSE(rot.prepared());
            rot.prepare();
            REQUIRE(rot.prepared() == (n >= 4));  // 1..3 bands: the factored form stays
            REQUIRE(rot.lazy() == (n < 4));       // D formed at 4..8 bands
            const std::vector<T> in = random_coeffs<T>(rng, n);
            std::vector<T> out(in.size()), tout(in.size());
            rot.apply(in.data(), out.data());
            rot.apply_transposed(in.data(), tout.data());
            worst = std::max(worst, max_diff(out, d_product(rot, in, false)));
            worst_t = std::max(worst_t, max_diff(tout, d_product(rot, in, true)));
            std::vector<T> inplace = in;
            rot.apply(inplace.data(), inplace.data());
            CHECK(inplace == out);
            const sh::Rotation<T> copy = rot;  // copies stay prepared
            CHECK(copy.prepared() == rot.prepared());
            std::vector<T> out2(in.size());
            copy.apply(in.data(), out2.data());
            CHECK(out2 == out);
        }
    }
    INFO("max |prepared apply - D in| " << worst << ", transposed " << worst_t);
    // the same products as d_product up to the order of the float sums
    CHECK(worst <= apply_tol<T>());
    CHECK(worst_t <= apply_tol<T>());
}

TEST_CASE("rotation lazy: prepare() makes apply multiply by D at 4..8 bands", "[rotation][lazy]") {
    std::mt19937 rng(1405);
    check_prepared<float>(rng);
    check_prepared<double>(rng);
}

TEST_CASE("rotation lazy: copies, moves and two threads reading D see the same D",
          "[rotation][lazy]") {
    std::mt19937 rng(1404);
    for (int n : {3, 6, 8}) {
        const sh::Mat3<float> r = random_matrix<float>(rng, n == 6);
        const auto ref = sh::Rotation<float>::from_matrix(9, r);  // eager
        for (int round = 0; round < 20; ++round) {
            const auto rot = sh::Rotation<float>::from_matrix(n, r);
            const sh::Rotation<float> before = rot;  // copied while lazy
            const float* p1 = nullptr;
            const float* p2 = nullptr;
            std::thread t1([&] { p1 = rot.data(); });
            std::thread t2([&] { p2 = rot.block(n - 1); });
            t1.join();
            t2.join();
            REQUIRE(p1 != nullptr);
            CHECK(p2 == p1 + sh::Rotation<float>::offset(n - 1));  // one published D
            const sh::Rotation<float> after = rot;                 // copied once D exists
            CHECK_FALSE(after.lazy());
            CHECK(after.data() != rot.data());  // a value copy
            bool same = true;
            for (std::size_t k = 0; k < rot.size(); ++k)
                same = same && p1[k] == ref.data()[k] && after.data()[k] == p1[k] &&
                       before.data()[k] == p1[k];
            CHECK(same);
        }
    }
    // moves and assignment
    auto a = sh::Rotation<double>::from_matrix(4, random_matrix<double>(rng, false));
    const double d13 = a(1, 1, -1);
    sh::Rotation<double> b = std::move(a);
    CHECK(b(1, 1, -1) == d13);
    CHECK(a.bands() == 0);  // NOLINT(bugprone-use-after-move): the moved-from state is empty
    sh::Rotation<double> c;
    c = b;
    CHECK(c(1, 1, -1) == d13);
    c = sh::Rotation<double>::from_matrix(2, random_matrix<double>(rng, true));
    CHECK(c.bands() == 2);
    CHECK(c.lazy());
}

TEST_CASE("rotation lazy: the mutable data() makes apply use the edited D", "[rotation][lazy]") {
    auto rot = sh::Rotation<double>::from_matrix(3, sh::matrix_rotation_z(0.5));
    double* d = rot.data();
    CHECK_FALSE(rot.lazy());
    d[0] = 2;  // scale band 0
    const std::vector<double> in(9, 1.0);
    std::vector<double> out(9);
    rot.apply(in.data(), out.data());
    CHECK(out[0] == 2.0);
    // transposed() of a lazy rotation stays lazy and inverts it
    const auto r =
        sh::Rotation<float>::from_matrix(5, sh::matrix_from_euler_zyz(0.3f, 1.1f, -0.4f));
    const auto t = r.transposed();
    CHECK(t.lazy());
    std::mt19937 rng(1405);
    const std::vector<float> x = random_coeffs<float>(rng, 5);
    std::vector<float> y(x.size()), z(x.size());
    r.apply(x.data(), y.data());
    t.apply(y.data(), z.data());
    CHECK(max_diff(z, std::vector<double>(x.begin(), x.end())) <= 2 * apply_tol<float>());
}
