// The operations' entry points with the types users hold: GLM and Eigen directions, glm::vec3
// RGB coefficients, float coefficients, and output buffers as contiguous ranges (std::vector,
// std::array) beside raw pointers.
#include <Eigen/Dense>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <glm/vec3.hpp>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/ops/projection.hpp>
#include <sphbasis/ops/sh_convolution.hpp>
#include <sphbasis/ops/sh_latlong.hpp>
#include <sphbasis/ops/sh_lights.hpp>
#include <sphbasis/ops/sh_windowing.hpp>
#include <vector>

using namespace sphbasis;

TEST_CASE("user types: lights take GLM and Eigen directions and ranges", "[user_types]") {
    const int bands = 4;
    std::vector<double> ref(16), a(16);
    sh::directional_light(bands, 0.3, -0.2, 0.9, 2.0, ref.data());
    sh::directional_light(bands, glm::dvec3(0.3, -0.2, 0.9), 2.0, a);  // range out
    for (std::size_t k = 0; k < 16; ++k) CHECK(a[k] == Approx(ref[k]).epsilon(1e-14).margin(1e-16));
    std::array<double, 16> b{};
    sh::directional_light(bands, Eigen::Vector3d(0.3, -0.2, 0.9), 2.0, b);
    for (std::size_t k = 0; k < 16; ++k) CHECK(b[k] == Approx(ref[k]).epsilon(1e-14).margin(1e-16));
    sh::directional_light(bands, vec3<double>{0.3, -0.2, 0.9}, 2.0, a.data());  // pointer out
    for (std::size_t k = 0; k < 16; ++k) CHECK(a[k] == Approx(ref[k]).epsilon(1e-14).margin(1e-16));
    // float directions and glm::vec3 RGB radiance.
    std::vector<glm::vec3> rgb(16);
    sh::cone_light(bands, glm::vec3(0.f, 0.f, 1.f), 0.5f, glm::vec3(1.f, 2.f, 3.f), rgb);
    std::vector<float> mono(16);
    sh::cone_light(bands, Eigen::Vector3f(0.f, 0.f, 1.f), 0.5f, 1.0f, mono);
    for (std::size_t k = 0; k < 16; ++k) {
        CHECK(rgb[k].x == Approx(mono[k]).margin(1e-6));
        CHECK(rgb[k].z == Approx(3 * mono[k]).margin(1e-6));
    }
    sh::spherical_light(bands, glm::dvec3(0, 0, 4), 1.0, 1.0, a);
    sh::spherical_light_solid_angle(bands, Eigen::Vector3d(0, 0, 1), 0.3, 1.0, a);
    sh::hemisphere_light(bands, glm::dvec3(0, 0, 1), 1.0, 0.25, a);
    std::vector<double> hemi(16);
    sh::hemisphere_light(bands, 0.0, 0.0, 1.0, 1.0, 0.25, hemi.data());
    for (std::size_t k = 0; k < 16; ++k)
        CHECK(a[k] == Approx(hemi[k]).epsilon(1e-14).margin(1e-16));
    const std::vector<double> kern = sh::phong_kernel(bands, 4.0);
    sh::zonal_light(bands, glm::dvec3(1, 0, 0), kern.data(), 1.0, a);
    // A range that is too small is an error, not an overrun.
    std::vector<double> small(15);
    CHECK_THROWS_WITH(sh::directional_light(bands, glm::dvec3(0, 0, 1), 1.0, small),
                      Catch::Contains("sphbasis::sh::directional_light(): expected out buffer of "
                                      "at least 16 elements, got 15"));
}

TEST_CASE("user types: convolve and irradiance deduce the coefficient scalar", "[user_types]") {
    const int bands = 3;
    const std::vector<double> k = sh::clamped_cosine_kernel(bands);  // double kernel
    std::vector<glm::vec3> L(9), E(9);
    std::vector<float> Lf(9), Ef(9);
    for (std::size_t i = 0; i < 9; ++i) {
        Lf[i] = 0.1f * float(i + 1);
        L[i] = glm::vec3(Lf[i], 2 * Lf[i], -Lf[i]);
    }
    sh::convolve(bands, k.data(), L.data(), E.data());  // glm::vec3 * float
    sh::convolve(bands, k, Lf, Ef);                     // ranges, float coefficients
    for (std::size_t i = 0; i < 9; ++i) {
        CHECK(E[i].x == Ef[i]);
        CHECK(E[i].y == 2 * Ef[i]);
    }
    sh::apply_window(bands, k, Lf, Ef);
    for (std::size_t i = 0; i < 9; ++i) CHECK(E[i].x == Ef[i]);
    // Irradiance at a GLM / Eigen normal equals convolution + evaluation.
    const glm::vec3 n(0.2f, 0.3f, 0.9f);
    const glm::vec3 e = sh::irradiance(L.data(), n);
    const float ef = sh::irradiance(Lf, Eigen::Vector3f(0.2f, 0.3f, 0.9f));
    const float ref = sh::eval_sum(bands, Ef.data(), 0.2f, 0.3f, 0.9f);
    CHECK(ef == Approx(ref).epsilon(1e-5));
    CHECK(e.x == Approx(ref).epsilon(1e-5));
    CHECK(e.z == Approx(-ref).epsilon(1e-5));
    const auto M = sh::irradiance_matrix(L);
    CHECK(sh::eval_irradiance_matrix(M, n).y == Approx(2 * ref).epsilon(1e-5));
    const std::vector<float> en = sh::band_energies(bands, Lf);
    CHECK(en[0] == Approx(0.01f));
}

TEST_CASE("user types: project takes f(direction), project_mc any 3-vector container",
          "[user_types]") {
    const BasisFunctions b = evaluator<SH>(9);
    const DirectionalRule rule = sphere_rule(8);
    const Eigen::VectorXd ref = project(
        b, [](double x, double, double z) { return 1 + x * z; }, rule);
    const Eigen::VectorXd g = project(
        b, [](const glm::dvec3& d) { return 1 + d.x * d.z; }, rule);
    const Eigen::VectorXd e = project(
        b, [](const Eigen::Vector3d& d) { return 1 + d.x() * d.z(); }, rule);
    const Eigen::VectorXd v = project(
        b, [](const vec3<double>& d) { return 1 + d.x * d.z; }, rule);
    CHECK((g - ref).cwiseAbs().maxCoeff() == 0);
    CHECK((e - ref).cwiseAbs().maxCoeff() == 0);
    CHECK((v - ref).cwiseAbs().maxCoeff() == 0);
    const Eigen::VectorXd fg = fit(
        b, [](const glm::dvec3& d) { return 1 + d.x * d.z; }, rule);
    CHECK((fg - ref).cwiseAbs().maxCoeff() <= 1e-12);
    // project_mc from containers of GLM and Eigen vectors.
    const std::vector<vec3<double>> dv = {{0, 0, 1}, {1, 0, 0}, {0, 1, 1}};
    const std::vector<glm::vec3> dg = {{0, 0, 1}, {1, 0, 0}, {0, 1, 1}};
    const std::array<Eigen::Vector3f, 3> de = {Eigen::Vector3f(0, 0, 1), Eigen::Vector3f(1, 0, 0),
                                               Eigen::Vector3f(0, 1, 1)};
    const std::vector<double> vals = {1, 2, 3}, w = {0.5, 0.25, 0.25};
    const std::array<float, 3> wf = {0.5f, 0.25f, 0.25f};
    const Eigen::VectorXd mv = project_mc(b, dv, vals, w);
    const Eigen::VectorXd mg = project_mc(b, dg, vals, w);
    const Eigen::VectorXd me = project_mc(b, de, vals, wf);
    CHECK((mg - mv).cwiseAbs().maxCoeff() <= 1e-7);
    CHECK((me - mv).cwiseAbs().maxCoeff() <= 1e-7);
    CHECK_THROWS_WITH(project_mc(b, dg, vals, std::vector<double>{1.0}),
                      Catch::Contains("sphbasis::project_mc(): expected as many values"));
}

TEST_CASE("user types: lat-long projection into ranges", "[user_types]") {
    const std::vector<glm::vec3> tex(8 * 4, glm::vec3(1.f, 2.f, 3.f));
    std::vector<glm::vec3> out(9);
    sh::project_latlong(3, 8, 4, tex, out);
    CHECK(out[0].y == Approx(2 * std::sqrt(4 * constants::pi)).epsilon(1e-6));
    std::vector<glm::vec3> small(8);
    CHECK_THROWS_WITH(
        sh::project_latlong(3, 8, 4, tex, small),
        Catch::Contains("sphbasis::sh::project_latlong(): expected out buffer of at least 9"));
}
