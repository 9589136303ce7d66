// Tests of basis/basis.hpp's argument handling, through every entry point that takes a direction
// or a buffer: directions as glm::vec3/dvec3 and Eigen::Vector3f/3d, the scalar deduced from the
// arguments, buffers as pointers, std::vector and std::array (sizes checked), and the size rule
// (bands in the namespaces, function counts in the generic API).
#include <Eigen/Core>
#include <array>
#include <catch2/catch.hpp>
#include <glm/glm.hpp>
#include <sphbasis/basis/hbasis.hpp>
#include <sphbasis/basis/hsh.hpp>
#include <sphbasis/basis/makhotkin.hpp>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/basis/zernike.hpp>
#include <string>
#include <vector>

using namespace sphbasis;

namespace {

constexpr double dx = 0.36, dy = -0.48, dz = 0.8;  // a unit direction in the upper hemisphere

/// The reference: the component form with pointers, in double.
template <class Eval>
std::vector<double> reference(int size, Eval&& eval) {
    std::vector<double> out(static_cast<std::size_t>(size));
    eval(dx, dy, dz, out.data());
    return out;
}

template <class A, class B>
void check_close(const A& got, const B& want, std::size_t n, double tol) {
    for (std::size_t k = 0; k < n; ++k) {
        INFO("k = " << k);
        CHECK(static_cast<double>(got[k]) == Approx(static_cast<double>(want[k])).margin(tol));
    }
}

}  // namespace

TEST_CASE("basis: sh entry points take glm and Eigen directions and ranges", "[basis][sh]") {
    const auto want =
        reference(9, [](double x, double y, double z, double* o) { sh::eval(3, x, y, z, o); });
    const glm::vec3 gf{float(dx), float(dy), float(dz)};
    const glm::dvec3 gd{dx, dy, dz};
    const Eigen::Vector3f ef{float(dx), float(dy), float(dz)};
    const Eigen::Vector3d ed{dx, dy, dz};

    std::vector<float> vf(9);
    sh::eval(3, gf, vf);  // float values: the output's scalar
    check_close(vf, want, 9, 1e-6);
    std::array<double, 9> ad{};
    sh::eval(3, gd, ad);
    check_close(ad, want, 9, 1e-15);
    float pf[9];
    sh::eval(3, ef, pf);
    check_close(pf, want, 9, 1e-6);
    std::vector<double> vd(9);
    sh::eval(3, ed, vd);
    check_close(vd, want, 9, 1e-15);
    // Mixed component types: converted to the output's scalar.
    sh::eval(3, dx, float(dy), dz, vf);
    check_close(vf, want, 9, 1e-6);
    // Non-unit input is normalised.
    sh::eval(3, 2.0 * gd, vd);
    check_close(vd, want, 9, 1e-15);

    // Unit-length entry points and the compile-time band counts.
    sh::eval_unit(3, gd, vd);
    check_close(vd, want, 9, 1e-15);
    std::array<float, 9> af{};
    sh::eval<3>(gf, af);
    check_close(af, want, 9, 1e-6);
    sh::eval_unit<3>(ed, ad);
    check_close(ad, want, 9, 1e-15);
    sh::eval<3>(ef, pf);
    check_close(pf, want, 9, 1e-6);

    // One function.
    CHECK(sh::eval_lm(2, -1, gd) == Approx(want[5]).margin(1e-15));
    const auto lf = sh::eval_lm(1, 1, ef);
    static_assert(std::is_same_v<decltype(lf), const float>, "the direction's scalar");
    CHECK(lf == Approx(want[3]).margin(1e-6));

    // The expansion: coefficients as vector/array/pointer, RGB-like coefficient types.
    std::vector<double> c(9);
    for (int k = 0; k < 9; ++k) c[std::size_t(k)] = 0.1 * (k + 1);
    double expect = 0;
    for (int k = 0; k < 9; ++k) expect += c[std::size_t(k)] * want[std::size_t(k)];
    CHECK(sh::eval_sum(3, c, gd) == Approx(expect).margin(1e-14));
    CHECK(sh::eval_sum(3, c.data(), ed) == Approx(expect).margin(1e-14));
    CHECK(sh::eval_sum(3, c, dx, dy, dz) == Approx(expect).margin(1e-14));
    std::vector<glm::vec3> rgb(9);
    for (int k = 0; k < 9; ++k) rgb[std::size_t(k)] = glm::vec3(float(c[std::size_t(k)]), 0.f, 1.f);
    const glm::vec3 s = sh::eval_sum(3, rgb, ed);  // glm::vec3 * double: via its float scalar
    CHECK(s.x == Approx(expect).margin(1e-5));
    const glm::vec3 s2 = sh::eval_sum(3, rgb, gf);
    CHECK(s2.x == Approx(expect).margin(1e-5));
    CHECK(sh::eval_sum(0, c, gd) == 0.0);

    // Batches with ranges.
    const std::vector<double> xs{dx, 0.0}, ys{dy, 0.0}, zs{dz, 1.0};
    std::vector<double> out(18);
    sh::eval_batch(3, 2, xs, ys, zs, out, 2);
    for (int k = 0; k < 9; ++k) CHECK(out[std::size_t(2 * k)] == Approx(want[std::size_t(k)]));
    std::vector<double> sums(2);
    sh::eval_sum_batch(3, c, 2, xs, ys, zs, sums);
    CHECK(sums[0] == Approx(expect).margin(1e-14));

    // Condon-Shortley with ranges.
    std::vector<double> cs = c;
    sh::to_condon_shortley(3, cs);
    CHECK(cs[3] == -c[3]);
    sh::from_condon_shortley(3, cs);
    CHECK(cs == c);
}

TEST_CASE("basis: sizes and buffers are checked", "[basis][sh]") {
    std::vector<double> small(4);
    const glm::dvec3 d(0, 0, 1);
    REQUIRE_THROWS_WITH(sh::eval(3, d, small),
                        "sphbasis::sh::eval(): expected output buffer of at least 9 elements, "
                        "got 4");
    REQUIRE_THROWS_WITH(sh::eval(3, 0.0, 0.0, 1.0, static_cast<double*>(nullptr)),
                        "sphbasis::sh::eval(): expected a non-null output buffer");
    sh::eval(0, 0.0, 0.0, 1.0, static_cast<double*>(nullptr));  // nothing written: fine
    REQUIRE_THROWS_WITH(sh::eval_sum(3, small, d), Catch::Contains("coefficient buffer"));
    REQUIRE_THROWS_WITH(sh::to_condon_shortley(3, static_cast<double*>(nullptr)),
                        "sphbasis::sh::to_condon_shortley(): expected a non-null coefficient "
                        "buffer");
    REQUIRE_THROWS_WITH(
        sh::from_condon_shortley(-1, small),
        "sphbasis::sh::from_condon_shortley(): expected 0 <= bands <= 8192, got -1");
    REQUIRE_THROWS_WITH(sh::to_condon_shortley(3, small), Catch::Contains("at least 9"));
    std::array<double, 4> a4{};
    REQUIRE_THROWS_WITH(sh::eval<3>(d, a4), Catch::Contains("at least 9"));
    double p4[4];
    REQUIRE_THROWS_WITH(sh::eval(3, d, p4), Catch::Contains("at least 9 elements, got 4"));
    const std::vector<double> xs(2, 0.0);
    std::vector<double> out(17);
    REQUIRE_THROWS_WITH(sh::eval_batch(3, 2, xs, xs, xs, out, 2),
                        Catch::Contains("output buffer of at least 18"));
    REQUIRE_THROWS_WITH(sh::eval_batch(3, 3, xs, xs, xs, out, 3),
                        Catch::Contains("x buffer of at least 3"));
    REQUIRE_THROWS_WITH(basis_eval<HBasis>(6, d, small), Catch::Contains("at least 6"));

    // The size rule: messages say the unit, derived from the limits.
    REQUIRE_THROWS_WITH(hsh::eval(hsh::max_bands + 1, d, small),
                        "sphbasis::hsh::eval(): expected 0 <= bands <= 2048, got 2049");
    CHECK(std::string(SH::count_rule()) == "a square number (bands^2, bands <= 8192) of");
    CHECK(std::string(HSH::count_rule()) == "a square number (bands^2, bands <= 2048) of");
    CHECK(std::string(Zernike::count_rule()) ==
          "a triangular number (bands(bands+1)/2, bands <= 2048) of");
    REQUIRE_THROWS_WITH(basis_eval<Zernike>(5, d, small),
                        "sphbasis::basis_eval(): expected a triangular number (bands(bands+1)/2, "
                        "bands <= 2048) of functions for basis 'zernike', got 5");
}

/// The banded entry points of a hemispherical basis B (namespace functions passed as F) against
/// the generic API with the same function count.
template <class B, class Ns>
void check_hemi_entry_points() {
    constexpr int bands = 4;
    const int n = B::count(bands);
    std::vector<double> want(static_cast<std::size_t>(n));
    basis_eval<B>(n, dx, dy, dz, want.data());
    const glm::vec3 gf{float(dx), float(dy), float(dz)};
    const glm::dvec3 gd{dx, dy, dz};
    const Eigen::Vector3f ef{float(dx), float(dy), float(dz)};
    const Eigen::Vector3d ed{dx, dy, dz};

    std::vector<float> vf(static_cast<std::size_t>(n));
    std::vector<double> vd(static_cast<std::size_t>(n));
    Ns::eval(bands, gf, vf);
    check_close(vf, want, std::size_t(n), 1e-5);
    Ns::eval(bands, ed, vd);
    check_close(vd, want, std::size_t(n), 1e-14);
    Ns::eval(bands, dx, dy, dz, vd.data());
    check_close(vd, want, std::size_t(n), 1e-14);
    Ns::eval_unit(bands, gd, vd);
    check_close(vd, want, std::size_t(n), 1e-14);
    Ns::template eval_fixed<bands>(ef, vf);
    check_close(vf, want, std::size_t(n), 1e-5);
    Ns::template eval_fixed<bands>(gd, vd);
    check_close(vd, want, std::size_t(n), 1e-14);
    // Generic API with glm/Eigen and ranges.
    basis_eval<B>(n, ef, vf);
    check_close(vf, want, std::size_t(n), 1e-5);

    std::vector<double> c(static_cast<std::size_t>(n));
    double expect = 0;
    for (int k = 0; k < n; ++k) {
        c[std::size_t(k)] = 1.0 / (k + 1);
        expect += c[std::size_t(k)] * want[std::size_t(k)];
    }
    CHECK(Ns::eval_sum(bands, c, gd) == Approx(expect).margin(1e-14));
    CHECK(Ns::eval_sum(bands, c, ed) == Approx(expect).margin(1e-14));
    CHECK(basis_eval_sum<B>(n, c, gf) == Approx(expect).margin(1e-5));
    CHECK(basis_eval_sum<B>(n, c, dx, dy, dz) == Approx(expect).margin(1e-14));

    const std::vector<float> xs{float(dx)}, ys{float(dy)}, zs{float(dz)};
    std::vector<float> out(static_cast<std::size_t>(n));
    Ns::eval_batch(bands, std::size_t(1), xs, ys, zs, out, std::size_t(1));
    check_close(out, want, std::size_t(n), 1e-5);
    basis_eval_batch<B>(n, 1, xs, ys, zs, out, 1);
    check_close(out, want, std::size_t(n), 1e-5);
    std::vector<float> cf(c.begin(), c.end()), sum(1);
    Ns::eval_sum_batch(bands, cf, std::size_t(1), xs, ys, zs, sum);
    CHECK(sum[0] == Approx(expect).margin(1e-5));
    basis_eval_sum_batch<B>(n, cf, 1, xs.data(), ys.data(), zs.data(), sum.data());
    CHECK(sum[0] == Approx(expect).margin(1e-5));
}

// The namespaces as types, so one template checks all three.
#define SPHBASIS_NS_TYPE(NS)                               \
    struct NS##_ns {                                       \
        template <class... A>                              \
        static void eval(int b, A&&... a) {                \
            NS::eval(b, std::forward<A>(a)...);            \
        }                                                  \
        template <class... A>                              \
        static void eval_unit(int b, A&&... a) {           \
            NS::eval_unit(b, std::forward<A>(a)...);       \
        }                                                  \
        template <int N, class... A>                       \
        static void eval_fixed(A&&... a) {                 \
            NS::eval<N>(std::forward<A>(a)...);            \
        }                                                  \
        template <class... A>                              \
        static auto eval_sum(int b, A&&... a) {            \
            return NS::eval_sum(b, std::forward<A>(a)...); \
        }                                                  \
        template <class... A>                              \
        static void eval_batch(int b, A&&... a) {          \
            NS::eval_batch(b, std::forward<A>(a)...);      \
        }                                                  \
        template <class... A>                              \
        static void eval_sum_batch(int b, A&&... a) {      \
            NS::eval_sum_batch(b, std::forward<A>(a)...);  \
        }                                                  \
    };
SPHBASIS_NS_TYPE(hsh)
SPHBASIS_NS_TYPE(makhotkin)
SPHBASIS_NS_TYPE(zernike)
#undef SPHBASIS_NS_TYPE

TEST_CASE("basis: hsh, makhotkin and zernike have sh's banded entry points", "[basis]") {
    SECTION("hsh") { check_hemi_entry_points<HSH, hsh_ns>(); }
    SECTION("makhotkin") { check_hemi_entry_points<Makhotkin, makhotkin_ns>(); }
    SECTION("zernike") { check_hemi_entry_points<Zernike, zernike_ns>(); }
    CHECK(hsh::count(3) == 9);
    CHECK(makhotkin::count(3) == 9);
    CHECK(zernike::count(3) == 6);
    CHECK(HSH::bands_of(16) == 4);
    CHECK(Zernike::bands_of(10) == 4);
}
