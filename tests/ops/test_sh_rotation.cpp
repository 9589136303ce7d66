// Tests for ops/sh_rotation.hpp: orthogonality to 200 bands, composition, inverse, agreement
// with evaluation at rotated directions, band energy, and the special cases (z rotation,
// quarter turns, reflections, tangent frames) against the general matrix.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "../support/cli_runner.hpp"
#include "../support/sh_checks.hpp"
#include "sphbasis/ops/sh_rotation.hpp"

namespace sh = sphbasis::sh;
using sphbasis::vec3;
using namespace sphbasis::test;

namespace {

template <class T>
sh::Mat3<T> random_rotation(std::mt19937& rng) {
    std::normal_distribution<double> nd;
    const double w = nd(rng), x = nd(rng), y = nd(rng), z = nd(rng);
    return sh::matrix_from_quaternion(T(w), T(x), T(y), T(z));
}

template <class T>
vec3<double> apply3(const sh::Mat3<T>& r, const vec3<double>& v) {
    return {double(r[0]) * v.x + double(r[1]) * v.y + double(r[2]) * v.z,
            double(r[3]) * v.x + double(r[4]) * v.y + double(r[5]) * v.z,
            double(r[6]) * v.x + double(r[7]) * v.y + double(r[8]) * v.z};
}

/// max |D D^T - I| over all blocks.
template <class T>
double orthogonality_residual(const sh::Rotation<T>& d) {
    double worst = 0;
    for (int l = 0; l < d.bands(); ++l) {
        const int w = 2 * l + 1;
        const T* b = d.block(l);
        for (int i = 0; i < w; ++i)
            for (int j = i; j < w; ++j) {
                double s = 0;
                for (int k = 0; k < w; ++k) s += double(b[i * w + k]) * double(b[j * w + k]);
                worst = std::max(worst, std::fabs(s - (i == j ? 1.0 : 0.0)));
            }
    }
    return worst;
}

double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::fabs(a[i] - b[i]));
    return worst;
}

}  // namespace

TEST_CASE("rotation: band 1 is the permuted matrix and quaternions rotate actively", "[rotation]") {
    // 90 degrees about z: x -> y.
    const double h = std::sqrt(0.5);
    const auto r = sh::matrix_from_quaternion(h, 0.0, 0.0, h);
    const auto v = apply3(r, {1, 0, 0});
    CHECK(v.x == Approx(0).margin(1e-15));
    CHECK(v.y == Approx(1));
    const auto d = sh::rotation_from_matrix(2, r);
    // A function ~ x (coefficient on y_11) becomes ~ y (coefficient on y_1-1).
    std::vector<double> f = {0, 0, 0, 1}, g(4);
    d.apply(f.data(), g.data());
    CHECK(g[1] == Approx(1));
    CHECK(g[3] == Approx(0).margin(1e-15));
    // Non-unit quaternions are normalised.
    const auto r2 = sh::matrix_from_quaternion(3 * h, 0.0, 0.0, 3 * h);
    for (std::size_t i = 0; i < 9; ++i) CHECK(r2[i] == Approx(r[i]).margin(1e-15));
}

TEMPLATE_TEST_CASE("rotation: rotate-then-evaluate equals evaluate at the inverse-rotated point",
                   "[rotation]", float, double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 2e-4 : 1e-11;
    std::mt19937 rng(7);
    for (int bands : {1, 2, 3, 4, 6, 9, 12, 20, 24, 25, 40, 64}) {
        const auto f = random_coeffs<T>(bands, rng);
        const auto r = random_rotation<T>(rng);
        const auto d = sh::rotation_from_matrix(bands, r);
        std::vector<T> g(f.size());
        d.apply(f.data(), g.data());
        double scale = 0;
        for (T c : f) scale += double(c) * double(c);
        scale = std::sqrt(scale) * bands;
        for (int i = 0; i < 20; ++i) {
            const auto w = random_dir(rng);
            const auto rtw = apply3(sh::transpose(r), w);  // R^T w
            const double lhs = sh::eval_sum(bands, g.data(), T(w.x), T(w.y), T(w.z));
            const double rhs = sh::eval_sum(bands, f.data(), T(rtw.x), T(rtw.y), T(rtw.z));
            INFO("bands " << bands);
            CHECK(std::fabs(lhs - rhs) <= tol * scale);
        }
    }
}

TEST_CASE("rotation: both recurrences on special and improper matrices", "[rotation]") {
    // Every branch of the quaternion extraction (w, x, y or z largest), half turns (w = 0),
    // the identity, exact quarter turns, reflections and near-gimbal rotations, at band counts
    // on both sides of the switch from Ivanic-Ruedenberg to Risbo.
    std::vector<sh::Mat3<double>> mats = {{1, 0, 0, 0, 1, 0, 0, 0, 1},
                                          {1, 0, 0, 0, -1, 0, 0, 0, -1},
                                          {-1, 0, 0, 0, 1, 0, 0, 0, -1},
                                          {-1, 0, 0, 0, -1, 0, 0, 0, 1},
                                          {-1, 0, 0, 0, -1, 0, 0, 0, -1},
                                          {1, 0, 0, 0, 1, 0, 0, 0, -1},
                                          sh::matrix_90<double>(0, 1),
                                          sh::matrix_90<double>(1, 3),
                                          sh::matrix_90<double>(2, 2),
                                          sh::matrix_from_euler_zyz(0.3, 1e-9, 0.2),
                                          sh::matrix_from_euler_zyz(0.3, pi - 1e-9, -1.0),
                                          sh::matrix_from_quaternion(0.01, 0.7, -0.7, 0.1)};
    std::mt19937 rng(77);
    for (int bands : {5, 24, 25, 31}) {
        const auto f = random_coeffs<double>(bands, rng);
        std::vector<double> g(f.size()), g2(f.size());
        for (const auto& r : mats) {
            const auto d = sh::rotation_from_matrix(bands, r);
            d.apply(f.data(), g.data());
            sh::rotate(bands, r, f.data(), g2.data());
            CHECK(max_abs_diff(g, g2) <= 1e-13);
            CHECK(orthogonality_residual(d) <= 1e-13);
            for (int i = 0; i < 6; ++i) {
                const auto w = random_dir(rng);
                const auto rtw = apply3(sh::transpose(r), w);
                INFO("bands " << bands << " r00 " << r[0] << " r11 " << r[4] << " r22 " << r[8]);
                CHECK(sh::eval_sum(bands, g.data(), w.x, w.y, w.z) ==
                      Approx(sh::eval_sum(bands, f.data(), rtw.x, rtw.y, rtw.z)).margin(1e-11));
            }
        }
    }
}

TEST_CASE("rotation: D D^T = I to 1e-12 at 40 bands", "[rotation]") {
    std::mt19937 rng(11);
    double worst = 0;
    for (int trial = 0; trial < 3; ++trial) {
        const auto d = sh::rotation_from_matrix(40, random_rotation<double>(rng));
        worst = std::max(worst, orthogonality_residual(d));
    }
    std::printf("[rotation] max |D D^T - I| at 40 bands (3 rotations): %.3g\n", worst);
    CHECK(worst <= 1e-12);
}

TEST_CASE("rotation: D D^T = I at 200 bands, top bands", "[rotation]") {
    // The full check is the [slow] case below; errors grow with l, so the top bands are the
    // worst ones.
    std::mt19937 rng(13);
    const auto d = sh::rotation_from_matrix(200, random_rotation<double>(rng));
    double worst = 0;
    for (int l = 195; l < 200; ++l) {
        const int w = 2 * l + 1;
        const double* b = d.block(l);
        for (int i = 0; i < w; ++i)
            for (int j = i; j < w; ++j) {
                double s = 0;
                for (int k = 0; k < w; ++k) s += b[i * w + k] * b[j * w + k];
                worst = std::max(worst, std::fabs(s - (i == j ? 1.0 : 0.0)));
            }
    }
    std::printf("[rotation] max |D D^T - I| over bands 195..199 of 200: %.3g\n", worst);
    CHECK(worst <= 1e-12);
}

TEST_CASE("rotation: D D^T = I to 1e-9 at 200 bands", "[rotation][slow]") {
    std::mt19937 rng(12);
    const auto t0 = std::chrono::steady_clock::now();
    const auto d = sh::rotation_from_matrix(200, random_rotation<double>(rng));
    const auto t1 = std::chrono::steady_clock::now();
    const double res = orthogonality_residual(d);
    std::printf("[rotation] 200 bands: build %.3f s, max |D D^T - I| = %.3g\n",
                std::chrono::duration<double>(t1 - t0).count(), res);
    CHECK(res <= 1e-9);
    // And the rotated expansion still agrees with evaluation at rotated points.
    const auto r = random_rotation<double>(rng);
    const auto f = random_coeffs<double>(200, rng);
    std::vector<double> g(f.size());
    sh::rotate(200, r, f.data(), g.data());
    for (int i = 0; i < 4; ++i) {
        const auto w = random_dir(rng);
        const auto rtw = apply3(sh::transpose(r), w);
        const double lhs = sh::eval_sum(200, g.data(), w.x, w.y, w.z);
        const double rhs = sh::eval_sum(200, f.data(), rtw.x, rtw.y, rtw.z);
        CHECK(lhs == Approx(rhs).margin(1e-8));
    }
}

TEST_CASE("rotation: composition, inverse and band energy", "[rotation]") {
    std::mt19937 rng(3);
    const int bands = 12;
    const auto r1 = random_rotation<double>(rng);
    const auto r2 = random_rotation<double>(rng);
    const auto d1 = sh::rotation_from_matrix(bands, r1);
    const auto d2 = sh::rotation_from_matrix(bands, r2);
    const auto d12 = sh::rotation_from_matrix(bands, sh::multiply(r1, r2));
    const auto f = random_coeffs<double>(bands, rng);
    std::vector<double> a(f.size()), b(f.size()), c(f.size());
    d2.apply(f.data(), a.data());
    d1.apply(a.data(), b.data());
    d12.apply(f.data(), c.data());
    CHECK(max_abs_diff(b, c) <= 1e-12);

    // Inverse: D(R^T) = D(R)^T, apply_transposed undoes apply, transposed() agrees.
    const auto dt = sh::rotation_from_matrix(bands, sh::transpose(r1));
    const auto d1t = d1.transposed();
    for (std::size_t i = 0; i < d1.size(); ++i)
        CHECK(dt.data()[i] == Approx(d1t.data()[i]).margin(1e-13));
    d1.apply(f.data(), a.data());
    d1.apply_transposed(a.data(), b.data());
    CHECK(max_abs_diff(b, f) <= 1e-13);

    // Energy per band is invariant.
    for (int l = 0; l < bands; ++l) {
        double e0 = 0, e1 = 0;
        for (int m = -l; m <= l; ++m) {
            e0 += f[std::size_t(sh::index(l, m))] * f[std::size_t(sh::index(l, m))];
            e1 += a[std::size_t(sh::index(l, m))] * a[std::size_t(sh::index(l, m))];
        }
        CHECK(e1 == Approx(e0).epsilon(1e-13));
    }
}

TEST_CASE("rotation: streaming rotate() equals the stored matrix, RGB and in place", "[rotation]") {
    std::mt19937 rng(5);
    for (int bands : {1, 2, 3, 6, 17}) {
        const auto r = random_rotation<double>(rng);
        const auto d = sh::rotation_from_matrix(bands, r);
        std::vector<RGB> f(std::size_t(bands * bands)), g1(f.size()), g2(f.size());
        std::normal_distribution<double> nd;
        for (auto& c : f) c = {nd(rng), nd(rng), nd(rng)};
        d.apply(f.data(), g1.data());
        sh::rotate(bands, r, f.data(), g2.data());
        auto inplace = f;
        sh::rotate(bands, r, inplace.data(), inplace.data());
        for (std::size_t k = 0; k < f.size(); ++k) {
            CHECK(g2[k].r == Approx(g1[k].r).margin(1e-13));
            CHECK(g2[k].g == Approx(g1[k].g).margin(1e-13));
            CHECK(g2[k].b == Approx(g1[k].b).margin(1e-13));
            CHECK(inplace[k].b == Approx(g1[k].b).margin(1e-13));
        }
        // Reflections on RGB (unary minus).
        std::vector<RGB> refl(f.size());
        sh::reflect_z(bands, f.data(), refl.data());
        CHECK(refl.back().r == ((bands - 1 + bands - 1) % 2 == 0 ? f.back().r : -f.back().r));
        // Vector overload.
        std::vector<double> fd(f.size());
        for (std::size_t k = 0; k < f.size(); ++k) fd[k] = f[k].g;
        const auto gd = d.apply(fd);
        for (std::size_t k = 0; k < f.size(); ++k) CHECK(gd[k] == Approx(g1[k].g).margin(1e-13));
    }
}

TEST_CASE("rotation: z rotation, quarter turns and reflections against the general matrix",
          "[rotation]") {
    std::mt19937 rng(9);
    const int bands = 10;
    const auto f = random_coeffs<double>(bands, rng);
    std::vector<double> a(f.size()), b(f.size());
    for (double angle : {0.3, -1.7, 2.5, 100.0}) {
        sh::rotate_z(bands, angle, f.data(), a.data());
        sh::rotation_from_matrix(bands, sh::matrix_rotation_z(angle)).apply(f.data(), b.data());
        CHECK(max_abs_diff(a, b) <= 1e-12);
    }
    // rotate_z at high order: 120 bands against the general streaming rotate() (Risbo).
    {
        const auto f120 = random_coeffs<double>(120, rng);
        std::vector<double> z1(f120.size()), z2(f120.size());
        sh::rotate_z(120, 0.77, f120.data(), z1.data());
        sh::rotate(120, sh::matrix_rotation_z(0.77), f120.data(), z2.data());
        CHECK(max_abs_diff(z1, z2) <= 1e-11);
    }
    for (int k = -5; k <= 5; ++k) {
        sh::rotate_z90(bands, k, f.data(), a.data());
        sh::rotation_90<double>(bands, 2, k).apply(f.data(), b.data());
        CHECK(max_abs_diff(a, b) <= 1e-13);
        sh::rotate_z(bands, k * pi / 2, f.data(), b.data());
        CHECK(max_abs_diff(a, b) <= 1e-12);
    }
    // Quarter turns about x and y: exact matrices agree with the Euler construction.
    for (int axis = 0; axis < 2; ++axis)
        for (int k = 1; k <= 3; ++k) {
            const auto exact = sh::rotation_90<double>(bands, axis, k);
            const double ang = k * pi / 2;
            // Rz(-90) Ry(a) Rz(90) is the rotation by a about Rz(-90) y = +x.
            const auto m = axis == 0 ? sh::matrix_from_euler_zyz(-pi / 2, ang, pi / 2)
                                     : sh::matrix_from_euler_zyz(0.0, ang, 0.0);
            const auto approx = sh::rotation_from_matrix(bands, m);
            for (std::size_t i = 0; i < exact.size(); ++i)
                CHECK(exact.data()[i] == Approx(approx.data()[i]).margin(1e-13));
        }
    // Reflections: against the improper diagonal matrices and against evaluation.
    for (int axis = 0; axis < 3; ++axis) {
        sh::Mat3<double> m = {1, 0, 0, 0, 1, 0, 0, 0, 1};
        m[std::size_t(4 * axis)] = -1;
        sh::reflect(bands, axis, f.data(), a.data());
        sh::rotation_from_matrix(bands, m).apply(f.data(), b.data());
        CHECK(max_abs_diff(a, b) <= 1e-14);
        for (int i = 0; i < 5; ++i) {
            auto w = random_dir(rng);
            auto wr = w;
            (axis == 0 ? wr.x : axis == 1 ? wr.y : wr.z) *= -1;
            CHECK(sh::eval_sum(bands, a.data(), w.x, w.y, w.z) ==
                  Approx(sh::eval_sum(bands, f.data(), wr.x, wr.y, wr.z)).margin(1e-12));
        }
    }
    sh::reflect_z(bands, f.data(), a.data());
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const std::size_t k = std::size_t(sh::index(l, m));
            CHECK(a[k] == ((l + m) % 2 == 0 ? f[k] : -f[k]));
        }
    // The point reflection -I gives (-1)^l.
    sh::rotation_from_matrix(bands, sh::Mat3<double>{-1, 0, 0, 0, -1, 0, 0, 0, -1})
        .apply(f.data(), a.data());
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const std::size_t k = std::size_t(sh::index(l, m));
            CHECK(a[k] == Approx(l % 2 ? -f[k] : f[k]).margin(1e-14));
        }
}

TEST_CASE("rotation: Euler ZYZ is Rz Ry Rz and matches z rotations", "[rotation]") {
    const double al = 0.4, be = 1.1, ga = -2.2;
    const auto r = sh::matrix_from_euler_zyz(al, be, ga);
    const auto expect = sh::multiply(
        sh::matrix_rotation_z(al),
        sh::multiply(sh::matrix_from_euler_zyz(0.0, be, 0.0), sh::matrix_rotation_z(ga)));
    for (std::size_t i = 0; i < 9; ++i) CHECK(r[i] == Approx(expect[i]).margin(1e-15));
    // Ry(beta) rotates z towards +x.
    CHECK(sh::matrix_from_euler_zyz(0.0, be, 0.0)[2] == Approx(std::sin(be)));
    std::mt19937 rng(1);
    const int bands = 8;
    const auto f = random_coeffs<double>(bands, rng);
    std::vector<double> a(f.size()), b(f.size());
    sh::rotation_from_euler_zyz(bands, al, be, ga).apply(f.data(), a.data());
    sh::rotate_z(bands, ga, f.data(), b.data());
    sh::rotation_from_euler_zyz(bands, 0.0, be, 0.0).apply(b.data(), b.data());
    sh::rotate_z(bands, al, b.data(), b.data());
    CHECK(max_abs_diff(a, b) <= 1e-13);
}

TEST_CASE("rotation: rotate_zyz equals rotate() of the Euler matrix", "[rotation]") {
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int bands : {1, 2, 3, 5, 8, 16, 24, 25, 32}) {
        for (int trial = 0; trial < 4; ++trial) {
            const double al = 2 * pi * u(rng), be = pi * u(rng), ga = 2 * pi * u(rng);
            const auto f = random_coeffs<double>(bands, rng);
            std::vector<double> a(f.size()), b(f.size());
            sh::rotate(bands, sh::matrix_from_euler_zyz(al, be, ga), f.data(), a.data());
            sh::rotate_zyz(bands, al, be, ga, f.data(), b.data());
            INFO("bands " << bands);
            CHECK(max_abs_diff(a, b) <= 1e-12);
            // In place, and with ranges.
            std::vector<double> c = f;
            sh::rotate_zyz(bands, al, be, ga, c, c);
            CHECK(max_abs_diff(b, c) == 0);
        }
    }
    // beta = 0 and pi (where Euler angles are singular) are exact cases, not special ones.
    for (double be : {0.0, pi}) {
        const int bands = 6;
        const auto f = random_coeffs<double>(bands, rng);
        std::vector<double> a(f.size()), b(f.size());
        sh::rotate(bands, sh::matrix_from_euler_zyz(0.3, be, -1.2), f.data(), a.data());
        sh::rotate_zyz(bands, 0.3, be, -1.2, f.data(), b.data());
        CHECK(max_abs_diff(a, b) <= 1e-13);
    }
    // RGB coefficients and float.
    {
        const int bands = 5;
        const auto f = random_coeffs<double>(bands, rng);
        std::vector<RGB> rgb(f.size()), out(f.size());
        for (std::size_t i = 0; i < f.size(); ++i) rgb[i] = {f[i], -f[i], 2 * f[i]};
        std::vector<double> a(f.size());
        sh::rotate_zyz(bands, 0.4, 1.1, -2.2, f.data(), a.data());
        sh::rotate_zyz(bands, 0.4, 1.1, -2.2, rgb.data(), out.data());
        for (std::size_t i = 0; i < f.size(); ++i) {
            CHECK(out[i].r == Approx(a[i]).margin(1e-15));
            CHECK(out[i].b == Approx(2 * a[i]).margin(1e-15));
        }
        std::vector<float> ff(f.begin(), f.end()), fo(f.size());
        sh::rotate_zyz(bands, 0.4f, 1.1f, -2.2f, ff, fo);
        for (std::size_t i = 0; i < f.size(); ++i) CHECK(fo[i] == Approx(a[i]).margin(2e-6));
    }
    std::vector<double> c(9), o(4);
    CHECK_THROWS_WITH(
        sh::rotate_zyz(3, 0.1, 0.2, 0.3, c, o),
        Catch::Contains("sphbasis::sh::rotate_zyz(): expected output buffer of at least 9 "
                        "elements, got 4"));
    CHECK_THROWS_WITH(sh::rotate_zyz(-1, 0.1, 0.2, 0.3, c, o),
                      Catch::Contains("sphbasis::sh::rotate_zyz(): expected 0 <= bands"));
}

TEST_CASE("rotation: glm, Eigen and row-major matrices and quaternions give one rotation",
          "[rotation]") {
    const double w = 0.9, x = -0.3, y = 0.2, z = -0.1;
    const sh::Mat3<double> r = sh::matrix_from_quaternion(w, x, y, z);  // row-major
    const glm::dquat gq(w, x, y, z);
    const glm::dmat3 gm = glm::mat3_cast(glm::normalize(gq));  // column-major
    const Eigen::Quaterniond eq(w, x, y, z);
    const Eigen::Matrix3d em = eq.normalized().toRotationMatrix();
    const sphbasis::Quatd sq{w, x, y, z};
    std::mt19937 rng(41);
    for (int bands : {3, 7, 26}) {
        INFO("bands " << bands);
        const auto f = random_coeffs<double>(bands, rng);
        std::vector<double> ref(f.size()), g(f.size());
        sh::rotate(bands, r, f.data(), ref.data());
        sh::rotate(bands, gm, f.data(), g.data());
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotate(bands, em, f, g);  // ranges
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotate(bands, gq, f, g);  // a quaternion through rotate()
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotate_quaternion(bands, eq, f, g);
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotate_quaternion(bands, sq, f.data(), g.data());
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotation_from_matrix(bands, gm).apply(f, g);
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotation_from_matrix(bands, em).apply(f, g);
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::rotation_from_quaternion(bands, gq).apply(f, g);
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        sh::Rotation<double>::from_quaternion(bands, eq).apply(f, g);
        CHECK(max_abs_diff(ref, g) <= 1e-13);
        // Copying glm's memory into a row-major array would give the inverse rotation.
        sh::Mat3<double> wrong;
        std::copy(&gm[0][0], &gm[0][0] + 9, wrong.begin());
        sh::rotate(bands, wrong, f.data(), g.data());
        if (bands > 1) CHECK(max_abs_diff(ref, g) > 1e-3);
    }
    // float types: glm::mat3, glm::quat, Eigen::Matrix3f, Eigen::Quaternionf.
    {
        const int bands = 4;
        const auto fd = random_coeffs<double>(bands, rng);
        std::vector<double> ref(fd.size());
        sh::rotate(bands, r, fd.data(), ref.data());
        std::vector<float> f(fd.begin(), fd.end());
        std::array<float, 16> g{};
        const auto wf = static_cast<float>(w), xf = static_cast<float>(x),
                   yf = static_cast<float>(y), zf = static_cast<float>(z);
        const glm::quat gqf(wf, xf, yf, zf);
        const Eigen::Quaternionf eqf(wf, xf, yf, zf);
        auto check = [&] {
            for (std::size_t i = 0; i < ref.size(); ++i) CHECK(g[i] == Approx(ref[i]).margin(2e-6));
        };
        sh::rotate(bands, glm::mat3_cast(glm::normalize(gqf)), f, g);
        check();
        sh::rotate(bands, eqf.normalized().toRotationMatrix(), f, g);
        check();
        sh::rotate_quaternion(bands, gqf, f, g);
        check();
        sh::rotate_quaternion(bands, eqf, f, g);
        check();
    }
    // Directions as any 3-vector type.
    const glm::dvec3 n(0.3, -0.4, 0.866);
    const auto d1 = sh::rotation_to_normal(5, n), d2 = sh::rotation_to_normal(5, n.x, n.y, n.z);
    const auto d3 = sh::rotation_to_normal(5, Eigen::Vector3d(n.x, n.y, n.z));
    const auto d4 = sh::rotation_to_normal(5, glm::vec3(n));
    for (std::size_t i = 0; i < d1.size(); ++i) {
        CHECK(d1.data()[i] == d2.data()[i]);
        CHECK(d3.data()[i] == d2.data()[i]);
        CHECK(d4.data()[i] == Approx(d2.data()[i]).margin(1e-6));
    }
    const auto fr = sh::frame_to_normal(Eigen::Vector3f(0.f, 0.f, 1.f));
    CHECK(fr[8] == 1.0f);
    // Sizes of ranges are checked; a dynamic Eigen matrix must be 3x3.
    std::vector<double> c(9), shortv(8);
    CHECK_THROWS_WITH(sh::rotate(3, gm, shortv, c),
                      Catch::Contains("sphbasis::sh::rotate(): expected input buffer of at least 9 "
                                      "elements, got 8"));
    CHECK_THROWS_WITH(
        sh::rotation_from_matrix(3, gm).apply(c, shortv),
        Catch::Contains("sphbasis::sh::Rotation::apply(): expected output buffer of at least 9"));
    CHECK_THROWS_WITH(sh::rotate(3, Eigen::MatrixXd::Identity(4, 4).eval(), c, c),
                      Catch::Contains("sphbasis::sh::rotate(): expected a 3x3 matrix, got 4x4"));
    CHECK_THROWS_WITH(sh::rotate(3, glm::dmat3(2.0), c, c),
                      Catch::Contains("sphbasis::sh::rotate(): expected an orthonormal"));
    CHECK_THROWS_WITH(sh::rotate_z(3, 0.1, c.data(), static_cast<double*>(nullptr)),
                      Catch::Contains("sphbasis::sh::rotate_z(): expected a non-null output"));
}

TEST_CASE("rotation: tangent frame taking +z to a normal", "[rotation]") {
    std::mt19937 rng(21);
    std::vector<vec3<double>> normals = {{0, 0, 1},          {0, 0, -1},    {1, 0, 0},
                                         {0, -1, 0},         {1e-9, 0, -1}, {0, 1e-12, -1},
                                         {0.3, 0.4, -0.866}, {2, 0, 0}};
    for (int i = 0; i < 50; ++i) normals.push_back(random_dir(rng));
    for (const auto& n0 : normals) {
        const auto r = sh::frame_to_normal(n0.x, n0.y, n0.z);
        const double len = std::sqrt(n0.x * n0.x + n0.y * n0.y + n0.z * n0.z);
        const auto n = apply3(r, {0, 0, 1});
        CHECK(n.x == Approx(n0.x / len).margin(1e-15));
        CHECK(n.y == Approx(n0.y / len).margin(1e-15));
        CHECK(n.z == Approx(n0.z / len).margin(1e-15));
        REQUIRE_NOTHROW(sh::rotation_from_matrix(3, r, 1e-14));
        const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) +
                           r[2] * (r[3] * r[7] - r[4] * r[6]);
        CHECK(det == Approx(1).epsilon(1e-14));
    }
    // Continuity across the equator (the Duff et al. branch switch would jump there).
    const auto ra = sh::frame_to_normal(0.6, 0.8, 1e-9), rb = sh::frame_to_normal(0.6, 0.8, -1e-9);
    for (std::size_t i = 0; i < 9; ++i) CHECK(ra[i] == Approx(rb[i]).margin(1e-8));
    // A zonal function (coefficients z_l on m = 0) moves to the normal: coefficients become
    // z_l sqrt(4 pi / (2l+1)) y_lm(n).
    const int bands = 7;
    const auto n = random_dir(rng);
    std::vector<double> f(std::size_t(bands * bands), 0.0), g(f.size()), y(f.size());
    for (int l = 0; l < bands; ++l) f[std::size_t(sh::index(l, 0))] = 1.0 + l;
    sh::rotation_to_normal(bands, n.x, n.y, n.z).apply(f.data(), g.data());
    sh::eval(bands, n.x, n.y, n.z, y.data());
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const std::size_t k = std::size_t(sh::index(l, m));
            CHECK(g[k] == Approx((1.0 + l) * std::sqrt(4 * pi / (2 * l + 1)) * y[k]).margin(1e-13));
        }
    // From an explicit frame.
    const auto t = sh::matrix_from_frame<double>({0, 1, 0}, {-1, 0, 0}, {0, 0, 1});
    CHECK(t[1] == -1.0);
    CHECK_THROWS_WITH((sh::matrix_from_frame<double>({0, 1, 0}, {0, 1, 0}, {0, 0, 1})),
                      Catch::Contains("sphbasis::matrix_from_frame(): expected an orthonormal"));
}

TEST_CASE("rotation: float agrees with double", "[rotation]") {
    std::mt19937 rng(33);
    for (int bands : {3, 6, 16}) {
        const auto rd = random_rotation<double>(rng);
        sh::Mat3<float> rf;
        for (std::size_t i = 0; i < 9; ++i) rf[i] = float(rd[i]);
        const auto dd = sh::rotation_from_matrix(bands, rd);
        const auto df = sh::rotation_from_matrix(bands, rf);
        double worst = 0;
        for (std::size_t i = 0; i < dd.size(); ++i)
            worst = std::max(worst, std::fabs(double(df.data()[i]) - dd.data()[i]));
        INFO("bands " << bands);
        CHECK(worst <= 2e-7 * bands);
    }
}

TEST_CASE("rotation: bad input throws with the function name", "[rotation]") {
    std::vector<double> c(9, 1.0), o(9);
    const sh::Mat3<double> id = {1, 0, 0, 0, 1, 0, 0, 0, 1};
    CHECK_THROWS_WITH(
        sh::rotation_from_matrix(-1, id),
        Catch::Contains("sphbasis::sh::Rotation::from_matrix(): expected 0 <= bands"));
    CHECK_THROWS_WITH(
        sh::rotation_from_matrix(2000, id),
        Catch::Contains("sphbasis::sh::Rotation::from_matrix(): expected 0 <= bands"));
    CHECK_THROWS_WITH(sh::rotate(-3, id, c.data(), o.data()),
                      Catch::Contains("sphbasis::sh::rotate(): expected 0 <= bands"));
    CHECK_THROWS_WITH(
        sh::rotation_from_matrix(3, sh::Mat3<double>{2, 0, 0, 0, 1, 0, 0, 0, 1}),
        Catch::Contains("sphbasis::sh::Rotation::from_matrix(): expected an orthonormal"));
    CHECK_THROWS_WITH(
        sh::rotate(3, sh::Mat3<double>{1, 0.1, 0, 0, 1, 0, 0, 0, 1}, c.data(), o.data()),
        Catch::Contains("sphbasis::sh::rotate(): expected an orthonormal"));
    CHECK_THROWS_WITH(
        sh::rotate(3, sh::Mat3<double>{std::nan(""), 0, 0, 0, 1, 0, 0, 0, 1}, c.data(), o.data()),
        Catch::Contains("non-finite"));
    CHECK_THROWS_WITH(
        sh::rotation_from_quaternion(3, 0.0, 0.0, 0.0, 0.0),
        Catch::Contains("sphbasis::matrix_from_quaternion(): expected a finite non-zero"));
    CHECK_THROWS_WITH(
        sh::rotation_from_quaternion(3, 1.0, std::numeric_limits<double>::infinity(), 0.0, 0.0),
        Catch::Contains("expected a finite non-zero"));
    CHECK_THROWS_WITH(sh::rotate_z(-1, 0.5, c.data(), o.data()),
                      Catch::Contains("sphbasis::sh::rotate_z(): expected"));
    CHECK_THROWS_WITH(sh::reflect(3, 3, c.data(), o.data()),
                      Catch::Contains("sphbasis::sh::reflect(): expected axis"));
    CHECK_THROWS_WITH(sh::matrix_90<double>(5, 1),
                      Catch::Contains("sphbasis::matrix_90(): expected axis"));
    CHECK_THROWS_WITH(sh::rotate(3, id, static_cast<const double*>(nullptr), o.data()),
                      Catch::Contains("sphbasis::sh::rotate(): expected a non-null input buffer"));
    const auto d = sh::rotation_from_matrix(3, id);
    CHECK_THROWS_WITH(d.apply(std::vector<double>(4)),
                      Catch::Contains("sphbasis::sh::Rotation::apply(): expected 9 coefficients"));
    // Zero bands is valid and does nothing.
    CHECK_NOTHROW(sh::rotate(0, id, c.data(), o.data()));
    CHECK(sh::rotation_from_matrix(0, id).size() == 0);
}

#ifdef SPHBASIS_TEST_HAVE_POPEN
TEST_CASE("rotation: the sphbasis rotate command", "[rotation][cli]") {
    // One JSON line {"bands":N,"quat":[...],"coeffs":[...]} with 17 significant digits (so the
    // numbers round-trip to what sh::rotate_quaternion computes); both option spellings and
    // negative numbers; bad input exits non-zero with one line. Runs only when the tool was
    // built beside the tests.
    if (sphbasis::test::tool_path().empty()) {
        WARN("sphbasis tool not built; skipping");
        return;
    }
    auto run = [](const std::string& args, int& status) {
        return sphbasis::test::run_tool("rotate " + args, status);
    };
    auto coeffs_of = [](const std::string& out) {
        std::vector<double> v;
        const auto at = out.find("\"coeffs\":[");
        REQUIRE(at != std::string::npos);
        std::stringstream ss(out.substr(at + 10));
        double x;
        char sep;
        while (ss >> x) {
            v.push_back(x);
            if (!(ss >> sep) || sep != ',') break;
        }
        return v;
    };
    int st = 0;
    std::string out = run("--bands 3 --quat 0.9,-0.3,0.2,-0.1 --coeffs 1,-2,3,-4,5,-6,7,-8,9", st);
    CHECK(st == 0);
    CHECK(out.rfind("{\"bands\":3,\"quat\":[0.90000000000000002,-0.29999999999999999,", 0) == 0);
    CHECK(std::count(out.begin(), out.end(), '\n') == 1);
    std::vector<double> expect = {1, -2, 3, -4, 5, -6, 7, -8, 9};
    sh::rotate_quaternion(3, 0.9, -0.3, 0.2, -0.1, expect.data(), expect.data());
    const auto got = coeffs_of(out);
    REQUIRE(got.size() == 9);
    for (std::size_t k = 0; k < 9; ++k) CHECK(got[k] == Approx(expect[k]).margin(1e-15));
    const std::string out2 =
        run("--bands=3 --quat=0.9,-0.3,0.2,-0.1 --coeffs=1,-2,3,-4,5,-6,7,-8,9", st);
    CHECK(st == 0);
    CHECK(out2 == out);
    sphbasis::test::check_rejects(
        "rotate",
        {"--bands 2 --quat 0,0,0,0 --coeffs 1,0,0,1", "--bands 2 --quat 1,0,0 --coeffs 1,0,0,1",
         "--bands 2 --quat 1,0,0,0 --coeffs 1,0,0", "--bands x --quat 1,0,0,0 --coeffs 1",
         "--quat 1,0,0,0 --coeffs 1", "--bands 0 --quat 1,0,0,0 --coeffs 1",
         "--bands 1 --quat 1,0,0,0 --coeffs 1 extra", "--bands 1 --quat 1,nan,0,0 --coeffs 1",
         "--bands 1 --bands 1 --quat 1,0,0,0 --coeffs 1", "--bands 1 --quat 1,0,0,0 --coeffs 1,"});
}
#endif

TEST_CASE("rotation: rotate_z refuses a non-finite angle", "[rotation]") {
    std::vector<double> in(16, 1.0), out(16, 0.0);
    CHECK_THROWS_WITH(sphbasis::sh::rotate_z(4, std::nan(""), in, out),
                      Catch::Contains("sh::rotate_z(): expected a finite angle"));
    CHECK_THROWS_AS(sphbasis::sh::rotate_z(4, HUGE_VAL, in, out), std::invalid_argument);
    CHECK_THROWS_AS(sphbasis::sh::rotate_z(4, -HUGE_VALF, in.data(), out.data()),
                    std::invalid_argument);
}

TEST_CASE("rotation: a rotation table beyond the table ceiling is refused before allocating",
          "[rotation]") {
    CHECK_THROWS_WITH(sphbasis::sh::rotation_from_quaternion(1024, 1.0, 0.0, 0.0, 0.0),
                      Catch::Contains("SPHBASIS_MAX_TABLE_BYTES") && Catch::Contains("1024 bands"));
    CHECK(sphbasis::sh::rotation_from_quaternion(8, 1.0, 0.0, 0.0, 0.0).bands() == 8);
}

TEST_CASE("rotation: the inline cos/sin of rotate_z agree with libm", "[rotation]") {
    // Angles across the reduced range: near 0, near multiples of pi/2 (where the Cody-Waite
    // reduction matters), large ones up to the 1e5 switch, and beyond it (libm itself).
    std::vector<double> angles{0.0, -0.0, 1e-300, 1e-8,  0.5,  0.7853981633974483,
                               1.0, 1e5,  -1e5,   1.5e5, 1e300};
    for (int k = -64; k <= 64; ++k)
        for (double d : {-1e-9, 0.0, 1e-9}) angles.push_back(k * 1.5707963267948966 + d);
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> wide(-1e5, 1e5), narrow(-10, 10);
    for (int i = 0; i < 2000; ++i) angles.push_back(i % 2 ? wide(rng) : narrow(rng));
    double full = 0, reduced = 0;
    for (double a : angles) {
        double c, s;
        sphbasis::sh::detail::cos_sin<true>(a, c, s);
        full = std::max({full, std::fabs(c - std::cos(a)), std::fabs(s - std::sin(a))});
        sphbasis::sh::detail::cos_sin<false>(a, c, s);
        reduced = std::max({reduced, std::fabs(c - std::cos(a)), std::fabs(s - std::sin(a))});
    }
    // Absolute errors: a few ulps of 1 in double (the reduction of |a| <= 1e5 carries about
    // 1e5 * 2^-53 of the argument's own rounding, which libm sees identically), 1e-11 for float.
    CHECK(full <= 4.5e-16);
    CHECK(reduced <= 1e-11);
}
