// Tests for core/sampling.hpp: uniformly distributed rotations (Shoemake's quaternions and ZYZ
// Euler angles) and the uniform sphere warp.
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <vector>

#include "sphbasis/core/constants.hpp"
#include "sphbasis/core/frame.hpp"
#include "sphbasis/core/sampling.hpp"

namespace {

/// Moments of R over N uniformly random rotations: the mean of R e_z (0 for uniform: the image
/// of a fixed vector is uniform on the sphere) and of R_ij^2 (1/3: R_ij is a coordinate of a
/// uniform point on the sphere, so R_ij^2 ~ Beta(1/2, 1), variance 4/45).
template <class Draw>
void check_uniform_rotations(Draw draw, int count) {
    double mean_z[3] = {0, 0, 0}, mean_sq[9] = {};
    double mean_cross = 0;  // E[R_00 R_11] = 0 for the Haar measure
    for (int i = 0; i < count; ++i) {
        const sphbasis::Mat3<double> r = draw();
        for (int k = 0; k < 3; ++k) mean_z[k] += r[static_cast<std::size_t>(3 * k + 2)];
        for (std::size_t k = 0; k < 9; ++k) mean_sq[k] += r[k] * r[k];
        mean_cross += r[0] * r[4];
    }
    const double n = count;
    const double se_z = std::sqrt(1.0 / 3.0 / n), se_sq = std::sqrt(4.0 / 45.0 / n);
    for (double& v : mean_z) {
        v /= n;
        CHECK(std::fabs(v) < 5 * se_z);
    }
    for (double& v : mean_sq) {
        v /= n;
        CHECK(std::fabs(v - 1.0 / 3.0) < 5 * se_sq);
    }
    // E[R_ij R_kl] = delta_ik delta_jl / 3; Var(R_00 R_11) <= E[R_00^2] = 1/3 bounds the error.
    CHECK(std::fabs(mean_cross / n) < 5 * std::sqrt(1.0 / 3.0 / n));
}

}  // namespace

TEST_CASE("sampling: cube_to_rotation gives unit quaternions, uniform on SO(3)", "[sampling]") {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int i = 0; i < 1000; ++i) {
        const auto q = sphbasis::cube_to_rotation(u(rng), u(rng), u(rng));
        CHECK(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z == Approx(1).epsilon(1e-15));
    }
    for (double c : {0.0, 1.0}) {  // the corners of the cube stay unit
        const auto q = sphbasis::cube_to_rotation(c, c, c);
        CHECK(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z == Approx(1).epsilon(1e-15));
    }
    const auto qf = sphbasis::cube_to_rotation(0.3f, 0.6f, 0.9f);
    CHECK(qf.w * qf.w + qf.x * qf.x + qf.y * qf.y + qf.z * qf.z == Approx(1.0f).epsilon(1e-6));
    check_uniform_rotations(
        [&] {
            const auto q = sphbasis::cube_to_rotation(u(rng), u(rng), u(rng));
            return sphbasis::matrix_from_quaternion(q.w, q.x, q.y, q.z);
        },
        200000);
}

TEST_CASE("sampling: cube_to_euler_zyz gives uniform rotations", "[sampling]") {
    std::mt19937_64 rng(4);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    check_uniform_rotations(
        [&] {
            const auto a = sphbasis::cube_to_euler_zyz(u(rng), u(rng), u(rng));
            return sphbasis::matrix_from_euler_zyz(a[0], a[1], a[2]);
        },
        200000);
    // alpha = 2 pi u1, beta = acos(2 u2 - 1), gamma = 2 pi u3, exactly.
    const auto a = sphbasis::cube_to_euler_zyz(0.25, 0.75, 0.5);
    CHECK(a[0] == sphbasis::constants::two_pi * 0.25);
    CHECK(a[1] == std::acos(0.5));
    CHECK(a[2] == sphbasis::constants::two_pi * 0.5);
    CHECK(sphbasis::cube_to_euler_zyz(0.0, 0.0, 0.0)[1] == Approx(sphbasis::constants::pi));
    CHECK(sphbasis::cube_to_euler_zyz(0.0, 1.0, 0.0)[1] == 0.0);
}

TEST_CASE("sampling: uniform sphere directions have zero mean and unit length", "[sampling]") {
    std::mt19937_64 rng(6);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int n = 100000;
    double m[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const auto d = sphbasis::square_to_uniform_sphere(u(rng), u(rng));
        CHECK(d.x * d.x + d.y * d.y + d.z * d.z == Approx(1).epsilon(1e-15));
        m[0] += d.x;
        m[1] += d.y;
        m[2] += d.z;
    }
    for (double v : m) CHECK(std::fabs(v / n) < 5 * std::sqrt(1.0 / 3.0 / n));
    std::vector<double> su, sv;
    CHECK_THROWS_WITH(
        sphbasis::stratified(0, 1, su, sv),
        Catch::Contains("sphbasis::stratified(): expected k >= 1 strata per axis, got 0"));
}
