// Tests for core/frame.hpp: orthonormal frames (Duff et al. 2017) near the poles and at random
// normals, to_local / to_world round trips, quaternion <-> matrix round trips, frame_to_normal
// taking +z to n, and the GLM / Eigen adapters (conventions of each type).
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <catch2/catch.hpp>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <random>
#include <vector>

#include "sphbasis/core/frame.hpp"

using sphbasis::Frame;
using sphbasis::Mat3;
using sphbasis::vec3;

namespace {

template <class T>
vec3<T> random_unit(std::mt19937& rng) {
    std::normal_distribution<double> nd;
    const double x = nd(rng), y = nd(rng), z = nd(rng);
    const double r = std::sqrt(x * x + y * y + z * z);
    return {T(x / r), T(y / r), T(z / r)};
}

template <class T>
vec3<T> unit(double x, double y, double z) {
    const double r = std::sqrt(x * x + y * y + z * z);
    return {T(x / r), T(y / r), T(z / r)};
}

template <class T>
std::vector<vec3<T>> test_normals() {
    std::vector<vec3<T>> ns = {
        unit<T>(0, 0, 1),        unit<T>(0, 0, -1),        unit<T>(1e-8, 0, 1),
        unit<T>(1e-8, 0, -1),    unit<T>(0, -1e-12, -1),   unit<T>(3e-4, -2e-4, -1),
        unit<T>(3e-4, 2e-4, 1),  unit<T>(1, 0, 0),         unit<T>(0, 1, 0),
        unit<T>(0.6, 0.8, 1e-9), unit<T>(0.6, 0.8, -1e-9), unit<T>(-0.3, 0.2, -0.9)};
    std::mt19937 rng(5);
    for (int i = 0; i < 200; ++i) ns.push_back(random_unit<T>(rng));
    return ns;
}

template <class T>
double max_abs(const Mat3<T>& a, const Mat3<T>& b) {
    double w = 0;
    for (std::size_t i = 0; i < 9; ++i) w = std::max(w, std::fabs(double(a[i]) - double(b[i])));
    return w;
}

}  // namespace

TEMPLATE_TEST_CASE("frame: Duff et al. frames are orthonormal and right-handed", "[frame]", float,
                   double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 4e-7 : 1e-15;
    for (const auto& n : test_normals<T>()) {
        const Frame<T> f(n);
        INFO("n = " << n.x << ", " << n.y << ", " << n.z);
        CHECK(std::fabs(double(dot(f.s, f.s)) - 1) <= tol);
        CHECK(std::fabs(double(dot(f.t, f.t)) - 1) <= tol);
        CHECK(std::fabs(double(dot(f.s, f.t))) <= tol);
        CHECK(std::fabs(double(dot(f.s, f.n))) <= tol);
        CHECK(std::fabs(double(dot(f.t, f.n))) <= tol);
        const auto c = cross(f.s, f.t);  // right-handed: s x t = n
        CHECK(std::fabs(double(c.x - n.x)) <= 2 * tol);
        CHECK(std::fabs(double(c.y - n.y)) <= 2 * tol);
        CHECK(std::fabs(double(c.z - n.z)) <= 2 * tol);
        // The local pole is the normal.
        const auto l = f.to_local(n);
        CHECK(double(l.z) == Approx(1).margin(tol));
        CHECK(Frame<T>::cos_theta(l) == Approx(T(1)).margin(tol));
    }
    // Exact at the poles.
    const Frame<T> up(vec3<T>{0, 0, 1}), down(vec3<T>{0, 0, -1});
    CHECK((up.s.x == 1 && up.s.y == 0 && up.s.z == 0 && up.t.y == 1));
    CHECK((down.s.x == 1 && down.t.y == -1 && down.t.x == 0));
}

TEMPLATE_TEST_CASE("frame: to_local and to_world are inverse", "[frame]", float, double) {
    using T = TestType;
    const double tol = std::is_same_v<T, float> ? 1e-6 : 1e-15;
    std::mt19937 rng(9);
    for (const auto& n : test_normals<T>()) {
        const Frame<T> f(n);
        const auto v = random_unit<T>(rng);
        const auto back = f.to_world(f.to_local(v));
        CHECK(std::fabs(double(back.x - v.x)) <= 2 * tol);
        CHECK(std::fabs(double(back.y - v.y)) <= 2 * tol);
        CHECK(std::fabs(double(back.z - v.z)) <= 2 * tol);
        const auto m = f.matrix();  // columns s, t, n: to_world
        const auto w = sphbasis::multiply(m, v), w2 = f.to_world(v);
        CHECK(std::fabs(double(w.x - w2.x)) <= tol);
        CHECK(std::fabs(double(w.z - w2.z)) <= tol);
    }
    // Spherical coordinates in the local frame.
    const vec3<T> v{T(0.6), T(0), T(0.8)};
    CHECK(Frame<T>::sin_theta(v) == Approx(T(0.6)));
    CHECK(Frame<T>::cos_phi(v) == Approx(T(1)));
    CHECK(Frame<T>::sin_phi(vec3<T>{0, 0, 1}) == T(0));
    // Any 3-vector type.
    const Frame<float> g(glm::vec3(0, 1, 0));
    CHECK(g.n.y == 1.0f);
    const auto lg = g.to_local(Eigen::Vector3f(0, 1, 0));
    CHECK(lg.z == Approx(1.0f));
}

TEST_CASE("frame: frame_to_normal maps +z to n and equals Frame(n) for n_z >= 0", "[frame]") {
    for (const auto& n : test_normals<double>()) {
        const auto r = sphbasis::frame_to_normal(n.x, n.y, n.z);
        const auto z = sphbasis::multiply(r, vec3<double>{0, 0, 1});
        CHECK(z.x == Approx(n.x).margin(1e-15));
        CHECK(z.y == Approx(n.y).margin(1e-15));
        CHECK(z.z == Approx(n.z).margin(1e-15));
        const auto rt = sphbasis::multiply(r, sphbasis::transpose(r));
        CHECK(max_abs(rt, Mat3<double>{1, 0, 0, 0, 1, 0, 0, 0, 1}) <= 1e-15);
        if (n.z >= 0) CHECK(max_abs(r, Frame<double>(n).matrix()) <= 1e-15);
        // Any 3-vector type.
        CHECK(max_abs(r, sphbasis::frame_to_normal(glm::dvec3(n.x, n.y, n.z))) == 0);
        CHECK(max_abs(r, sphbasis::frame_to_normal(Eigen::Vector3d(n.x, n.y, n.z))) == 0);
    }
}

TEST_CASE("frame: quaternion <-> matrix round trips", "[frame]") {
    std::mt19937 rng(11);
    std::normal_distribution<double> nd;
    for (int i = 0; i < 500; ++i) {
        double w = nd(rng), x = nd(rng), y = nd(rng), z = nd(rng);
        if (i == 0) w = 1, x = y = z = 0;           // identity
        if (i == 1) w = 0, x = 1, y = z = 0;        // half turn about x (trace -1)
        if (i == 2) w = 1e-9, x = 0, y = 0, z = 1;  // near half turn about z
        const double n = std::sqrt(w * w + x * x + y * y + z * z);
        const auto r = sphbasis::matrix_from_quaternion(w, x, y, z);
        const auto q = sphbasis::quaternion_from_matrix(r);
        // q and -q are one rotation.
        const double s = (q.w * w + q.x * x + q.y * y + q.z * z) >= 0 ? 1 : -1;
        CHECK(s * q.w == Approx(w / n).margin(1e-14));
        CHECK(s * q.x == Approx(x / n).margin(1e-14));
        CHECK(s * q.y == Approx(y / n).margin(1e-14));
        CHECK(s * q.z == Approx(z / n).margin(1e-14));
        CHECK(max_abs(sphbasis::matrix_from_quaternion(q.w, q.x, q.y, q.z), r) <= 1e-14);
        // An improper matrix gives the quaternion of -R.
        Mat3<double> neg;
        for (std::size_t k = 0; k < 9; ++k) neg[k] = -r[k];
        bool improper = false;
        const auto qn = sphbasis::quaternion_of(neg, improper);
        CHECK(improper);
        CHECK(std::fabs(qn.w * q.w + qn.x * q.x + qn.y * q.y + qn.z * q.z) ==
              Approx(1).epsilon(1e-14));
    }
    CHECK_THROWS_WITH(sphbasis::matrix_from_quaternion(0.0, 0.0, 0.0, 0.0),
                      Catch::Contains("sphbasis::matrix_from_quaternion(): expected a finite"));
}

TEST_CASE("frame: glm and Eigen matrices and quaternions are read in their own conventions",
          "[frame]") {
    const double w = 0.9, x = -0.3, y = 0.2, z = -0.1;
    const auto r = sphbasis::matrix_from_quaternion(w, x, y, z);
    // glm::mat3_cast and Eigen's toRotationMatrix describe the same rotation.
    const glm::dquat gq(w, x, y, z);  // glm constructs from (w, x, y, z)
    const glm::dmat3 gm = glm::mat3_cast(glm::normalize(gq));
    const Eigen::Quaterniond eq(w, x, y, z);  // Eigen too
    const Eigen::Matrix3d em = eq.normalized().toRotationMatrix();
    CHECK(max_abs(sphbasis::to_mat3(gm), r) <= 1e-15);
    CHECK(max_abs(sphbasis::to_mat3(em), r) <= 1e-15);
    CHECK(max_abs(sphbasis::to_rotation_matrix(gq), r) <= 1e-15);
    CHECK(max_abs(sphbasis::to_rotation_matrix(eq), r) <= 1e-15);
    CHECK(max_abs(sphbasis::to_rotation_matrix(r), r) == 0);
    // glm is column-major: its memory read row by row is the transpose.
    const double* raw = &gm[0][0];
    CHECK(raw[1] == Approx(r[3]));
    // Quaternions by name, whatever the storage order.
    const auto pg = sphbasis::to_quat(gq), pe = sphbasis::to_quat(eq);
    CHECK((pg.w == w && pg.x == x && pg.y == y && pg.z == z));
    CHECK((pe.w == w && pe.x == x && pe.y == y && pe.z == z));
    // Scalar types follow the argument.
    static_assert(std::is_same_v<sphbasis::rotation_scalar_t<glm::mat3>, float>);
    static_assert(std::is_same_v<sphbasis::rotation_scalar_t<Eigen::Quaternionf>, float>);
    static_assert(std::is_same_v<sphbasis::rotation_scalar_t<Eigen::Matrix3d>, double>);
    static_assert(sphbasis::is_quaternion_v<glm::quat> &&
                  sphbasis::is_quaternion_v<Eigen::Quaterniond>);
    static_assert(!sphbasis::is_quaternion_v<Eigen::Matrix3d> && sphbasis::is_matrix3_v<glm::mat3>);
    // A dynamic Eigen matrix must be 3x3 at run time.
    CHECK_THROWS_WITH(sphbasis::to_mat3(Eigen::MatrixXd::Identity(2, 2).eval(), "sh::rotate"),
                      Catch::Contains("sphbasis::sh::rotate(): expected a 3x3 matrix, got 2x2"));
}

TEST_CASE("frame: quaternions of any finite magnitude give their rotation", "[frame]") {
    using namespace sphbasis;
    const Mat3<double> ref = matrix_from_quaternion(0.5, 0.5, 0.5, 0.5);
    for (double scale : {1e-310, 1e-300, 1e-150, 1.0, 1e150, 1e300}) {
        const Mat3<double> r =
            matrix_from_quaternion(0.5 * scale, 0.5 * scale, 0.5 * scale, 0.5 * scale);
        for (std::size_t i = 0; i < 9; ++i) CHECK(r[i] == Approx(ref[i]).margin(1e-15));
    }
    // (1e300, 1e300, 0, 0) is (1, 1, 0, 0) scaled: 90 degrees about x.
    const Mat3<double> rx = matrix_from_quaternion(1e300, 1e300, 0.0, 0.0);
    const Mat3<double> rx_ref{1, 0, 0, 0, 0, -1, 0, 1, 0};
    for (std::size_t i = 0; i < 9; ++i) CHECK(rx[i] == Approx(rx_ref[i]).margin(1e-15));
    CHECK_THROWS_AS(matrix_from_quaternion(0.0, 0.0, 0.0, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(matrix_from_quaternion(std::nan(""), 0.0, 0.0, 1.0), std::invalid_argument);
    CHECK_THROWS_AS(matrix_from_quaternion(HUGE_VAL, 0.0, 0.0, 1.0), std::invalid_argument);
}
