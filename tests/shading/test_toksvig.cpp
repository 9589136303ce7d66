// Tests of shading/toksvig.hpp (Toksvig, "Mipmapping Normal Maps", 2004). Values are compared
// with closed forms retyped here from the definitions (eq. 1, 5, 6, 7), with numerical
// integration over the hemisphere and with finite differences, not with the header's own
// helpers.
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <random>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/shading/toksvig.hpp>
#include <type_traits>
#include <vector>

namespace tk = sphbasis::toksvig;

namespace {

const double pi = 3.141592653589793;

// int over the hemisphere around Na of lobe(c) d omega with c = cos theta, as 2 pi int_0^1
// lobe(c) dc: composite Gauss-Legendre on panels refined geometrically toward c = 1 (the peak,
// of width ~1/(exponent + 1)) and toward c = 0 (c^exponent is not smooth there for a small
// non-integer exponent).
template <class Lobe>
double hemisphere_integral(Lobe&& lobe, double exponent) {
    std::vector<double> t, w;
    sphbasis::gauss_legendre(32, t, w);
    std::vector<double> edges{0.0};
    for (double e = 1e-15; e < 0.5; e *= 4) edges.push_back(e);
    std::vector<double> top;
    for (double e = 1.0 / (16 * (exponent + 1)); e < 0.5; e *= 2) top.push_back(1 - e);
    edges.push_back(0.5);
    for (auto it = top.rbegin(); it != top.rend(); ++it) edges.push_back(*it);
    edges.push_back(1.0);
    double sum = 0;
    for (std::size_t p = 0; p + 1 < edges.size(); ++p) {
        const double a = edges[p], b = edges[p + 1];
        for (std::size_t i = 0; i < t.size(); ++i)
            sum += 0.5 * (b - a) * w[i] * lobe(0.5 * (a + b) + 0.5 * (b - a) * t[i]);
    }
    return 2 * pi * sum;
}

// eq. 6 retyped through the variance of eq. 1: f_t = 1/(1 + s sigma^2), sigma^2 = (1 - L)/L.
double ref_factor(double L, double s) { return 1.0 / (1.0 + s * (1.0 - L) / L); }

}  // namespace

TEMPLATE_TEST_CASE("toksvig: eq. 1 variance and length", "[toksvig]", float, double) {
    using T = TestType;
    for (double L : {0.01, 0.2, 0.5, 0.75, 0.9, 0.999}) {
        const T s2 = tk::variance_from_length(T(L));
        const double Lt = double(T(L));
        CHECK(double(s2) == Approx((1 - Lt) / Lt).epsilon(1e-6));
        CHECK(double(tk::length_from_variance(s2)) == Approx(L).epsilon(1e-6));
    }
    // Hard cases: L = 1 and above (quantisation) give 0; L -> 0 gives a large finite value.
    CHECK(tk::variance_from_length(T(1)) == T(0));
    CHECK(tk::variance_from_length(T(1.003)) == T(0));
    CHECK(std::isfinite(tk::variance_from_length(T(0))));
    CHECK(tk::variance_from_length(T(0)) > T(1e30));
    CHECK(std::isfinite(tk::variance_from_length(std::numeric_limits<T>::denorm_min())));
    CHECK(tk::length_from_variance(T(-1)) == T(1));
}

TEMPLATE_TEST_CASE("toksvig: eq. 6 factor, limits and both forms", "[toksvig]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-5 : 1e-13;
    for (double s : {1.0, 4.0, 32.0, 1000.0, 1e6}) {
        for (double L : {0.001, 0.1, 0.5, 0.9, 0.99, 0.9999}) {
            const double Lt = double(T(L));  // the length as stored in T
            const double f = double(tk::factor(T(L), T(s)));
            CHECK(f == Approx(ref_factor(Lt, s)).epsilon(tol));
            CHECK(double(tk::factor_from_variance(T((1 - Lt) / Lt), T(s))) ==
                  Approx(ref_factor(Lt, s)).epsilon(tol * 10));
        }
        // f_t -> 1 as L -> 1: 1 - f_t ~ s (1 - L) for small 1 - L.
        CHECK(tk::factor(T(1), T(s)) == T(1));
        CHECK(tk::factor(T(1.01), T(s)) == T(1));  // quantised lengths above 1
        double prev = 0;
        for (int k = 1; k <= 12; ++k) {
            const double eps = std::pow(10.0, -k);
            if (sizeof(T) == 4 && eps < 1e-6) break;
            const double f = double(tk::factor(T(1 - eps), T(s)));
            CHECK(f >= prev);
            prev = f;
        }
        const double one_minus = 1 - double(T(1 - 1e-6));
        CHECK(1 - double(tk::factor(T(1 - 1e-6), T(s))) <= s * one_minus * 1.01 + 1e-7);
        // f_t -> 0 as L -> 0: f_t ~ L/s.
        CHECK(tk::factor(T(0), T(s)) == T(0));
        CHECK(double(tk::factor(T(1e-6), T(s))) == Approx(1e-6 / s).epsilon(1e-5));
        CHECK(double(tk::widened_exponent(T(0.5), T(s))) == Approx(s / (1 + s)).epsilon(tol));
    }
    CHECK(tk::factor(T(0), T(0)) == T(1));  // s = 0 and L = 0: documented as 1
}

TEST_CASE("toksvig: eq. 5, convolving the two Gaussians", "[toksvig]") {
    // 1/s' = sigma^2 + 1/s (the variances of eq. 4's Gaussians add).
    for (double s : {1.0, 10.0, 300.0})
        for (double L : {0.3, 0.8, 0.97}) {
            const double sigma2 = (1 - L) / L;
            CHECK(1.0 / tk::widened_exponent(L, s) == Approx(sigma2 + 1.0 / s).epsilon(1e-13));
        }
}

// Energy. The brief's eq. 7 gives the unwidened lobe's integral over the hemisphere,
// int cos^s d omega = 2 pi/(s + 1); we measure it and the eq. 8 lobe numerically. Measured
// (double, s in 1..1e6, L in 0..1): eq. 7 holds to 1.5e-11 relative and the eq. 8 lobe
// integrates to 2 pi/(1 + s) to 1.5e-11 relative for every L (both at s = 1e6; below s = 1e4
// both are within 1e-13). The residual is the quadrature's: cos theta near 1 carries a
// rounding of 1e-16, which c^s amplifies by s. So eq. 7 is exact in solid angle and the
// widening with the (1 + f_t s)/(1 + s) scale preserves energy exactly, not approximately. The
// approximation lives in eq. 4 instead: the Gaussian exp(-s a^2/2) on the plane integrates to
// 2 pi/s, a relative error of exactly 1/s against eq. 7 (100% at s = 1, 3% at s = 32,
// 1e-6 at s = 1e6). The brief's eq. 8 as printed, (1 + f_t s X^(f_t s))/(1 + s), integrates to
// 2 pi (1 + s'/(s' + 1))/(1 + s): up to twice the energy (x 1.97 at s = 32, L = 1).
TEST_CASE("toksvig: energy of the widened lobe (eq. 7, eq. 8)", "[toksvig]") {
    double worst7 = 0, worst8 = 0;
    for (double s : {1.0, 2.0, 8.0, 32.0, 128.0, 1024.0, 1e4, 1e5, 1e6}) {
        const double target = 2 * pi / (1 + s);  // eq. 7
        const double unwidened = hemisphere_integral([s](double c) { return std::pow(c, s); }, s);
        worst7 = std::fmax(worst7, std::fabs(unwidened / target - 1));
        for (double L : {0.0, 1e-3, 0.05, 0.3, 0.5, 0.8, 0.95, 0.99, 0.999, 0.99999, 1.0}) {
            const double sp = s * (L > 0 ? ref_factor(L, s) : 0.0);
            const double e8 =
                hemisphere_integral([L, s](double c) { return tk::specular(L * c, L, s); }, sp);
            worst8 = std::fmax(worst8, std::fabs(e8 / target - 1));
            // The printed grouping is not energy-preserving (it is the same at L = 0 only).
            const double printed = hemisphere_integral(
                [sp, s](double c) { return (1 + sp * std::pow(c, sp)) / (1 + s); }, sp);
            if (L > 0.05) CHECK(printed / target - 1 > 0.2);
        }
        // eq. 4's Gaussian: 2 pi/s, relative error 1/s.
        CHECK((2 * pi / s) / target - 1 == Approx(1 / s).epsilon(1e-9));
    }
    INFO("eq. 7 worst relative error " << worst7 << ", eq. 8 worst " << worst8);
    CHECK(worst7 < 1e-10);
    CHECK(worst8 < 1e-10);
}

TEMPLATE_TEST_CASE("toksvig: eq. 8/9 values and hard cases", "[toksvig]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 2e-5 : 1e-12;
    for (double s : {1.0, 16.0, 200.0}) {
        for (double L : {0.2, 0.6, 0.95}) {
            const double f = ref_factor(L, s);
            for (double c : {0.0, 0.3, 0.9, 1.0}) {
                const double expect = (1 + f * s) / (1 + s) * std::pow(c, f * s);
                CHECK(double(tk::specular(T(L * c), T(L), T(s))) ==
                      Approx(expect).epsilon(tol).margin(1e-30));
                CHECK(double(tk::specular_from_dots(T(L * c), T(L * L), T(s))) ==
                      Approx(expect).epsilon(tol * 4).margin(1e-30));
            }
        }
        // L = 1: the plain Blinn-Phong power; L = 0: the constant 1/(1 + s).
        CHECK(double(tk::specular(T(0.8), T(1), T(s))) == Approx(std::pow(0.8, s)).epsilon(tol));
        CHECK(double(tk::specular(T(0), T(0), T(s))) == Approx(1 / (1 + s)).epsilon(tol));
        CHECK(double(tk::aliased_specular(T(0.4), T(0.25), T(s))) ==
              Approx(std::pow(0.8, s)).epsilon(tol));
        CHECK(double(tk::relative_intensity(T(0.5), T(s))) ==
              Approx((1 + s / (1 + s)) / (1 + s)).epsilon(tol));
    }
    // Every finite input gives a finite value in [0, 1], s from 1 to 1e6.
    const T lengths[] = {T(0),
                         std::numeric_limits<T>::denorm_min(),
                         T(1e-30),
                         T(0.5),
                         T(1) - std::numeric_limits<T>::epsilon(),
                         T(1),
                         T(1.0001),
                         T(1.02)};
    const T dots[] = {T(-1), T(-0.1), T(0), T(0.3), T(1), T(1.05)};
    for (double s : {1.0, 10.0, 1e3, 1e6})
        for (T L : lengths)
            for (T nh : dots) {
                const T a = tk::specular(nh, L, T(s));
                const T b = tk::specular_from_dots(nh, L * L, T(s));
                const T c = tk::faded_specular(nh, L * L, T(s), tk::quantization_length_error<T>(8),
                                               T(0.05));
                const T d = tk::aliased_specular(nh, L * L, T(s));
                for (T v : {a, b, c, d}) {
                    REQUIRE(std::isfinite(v));
                    REQUIRE(v >= T(0));
                    REQUIRE(v <= T(1));
                }
                REQUIRE(std::isfinite(tk::sensitivity(L, T(s))));
                REQUIRE(std::isfinite(tk::log2_sigma(L)));
                REQUIRE(std::isfinite(tk::env_lod(L, T(20), T(10))));
            }
}

TEMPLATE_TEST_CASE("toksvig: eq. 10 sensitivity is the derivative of the intensity", "[toksvig]",
                   float, double) {
    using T = TestType;
    for (double s : {1.0, 40.0, 1000.0}) {
        for (double L : {0.1, 0.5, 0.9, 0.99}) {
            const double h = 1e-6 * L;
            const double fd = (double(tk::relative_intensity(L + h, s)) -
                               double(tk::relative_intensity(L - h, s))) /
                              (2 * h);
            CHECK(double(tk::sensitivity(T(L), T(s))) == Approx(fd).epsilon(1e-5));
        }
        CHECK(double(tk::sensitivity(T(1), T(s))) == Approx(s * s / (1 + s)).epsilon(1e-6));
    }
}

TEST_CASE("toksvig: quantisation error of 8-bit normals and the eq. 11 fade", "[toksvig]") {
    // The brief's 0.0068 for 8 bits (its printed sqrt(3)/127.2 is twice that).
    CHECK(tk::quantization_length_error(8) == Approx(0.0068).margin(5e-5));
    CHECK(tk::quantization_length_error(8) == Approx(std::sqrt(3.0) / 254).epsilon(1e-15));
    CHECK(tk::quantization_length_error(16) == Approx(std::sqrt(3.0) / (2 * 32767.0)));
    REQUIRE_THROWS_WITH(
        tk::quantization_length_error(1),
        Catch::Contains("sphbasis::toksvig::quantization_length_error(): expected"));
    REQUIRE_THROWS_WITH(tk::quantization_length_error(33), Catch::Contains("2 <= bits <= 32"));

    // The bound holds for SNORM8-quantised unit normals.
    std::mt19937 rng(12);
    std::normal_distribution<double> g;
    const double bound = tk::quantization_length_error(8);
    double worst = 0;
    for (int k = 0; k < 100000; ++k) {
        double v[3] = {g(rng), g(rng), g(rng)};
        const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        double q2 = 0;
        for (double& c : v) {
            const auto q = static_cast<std::int8_t>(std::lround(c / l * 127));
            const double dq = tk::decode_snorm8(q);
            q2 += dq * dq;
        }
        worst = std::fmax(worst, std::fabs(std::sqrt(q2) - 1));
        const float L = static_cast<float>(std::sqrt(q2));  // may exceed 1
        REQUIRE(tk::factor(L, 64.0f) <= 1.0f);
        REQUIRE(tk::factor(L, 64.0f) > 0.5f);
    }
    INFO("worst 8-bit length error " << worst);
    CHECK(worst <= bound);
    CHECK(worst > 0.5 * bound);
    CHECK(tk::decode_snorm8(-128) == -1.0f);
    CHECK(tk::decode_snorm8(127) == 1.0f);
    CHECK(tk::decode_unorm8(255) == 1.0f);
    CHECK(tk::decode_unorm8(0) == -1.0f);

    // eq. 11: w = threshold/error where error = length_error * eq. 10 exceeds the threshold.
    const double s = 64, err = bound, thr = 0.05;
    for (double L : {0.3, 0.7, 0.9, 0.97, 0.99, 0.999, 1.0}) {
        const double nn = L * L;
        for (double c : {0.5, 0.95, 1.0}) {
            const double nh = L * c;
            const double sens = s * s / ((1 + s) * std::pow(L + s * (1 - L), 2));
            const double e = err * sens;
            const double f = ref_factor(L, s);
            const double anti = (1 + f * s) / (1 + s) * std::pow(c, f * s);
            const double alias = std::pow(c, s);
            const double expect = e > thr ? thr / e * anti + (1 - thr / e) * alias : anti;
            CHECK(tk::faded_specular(nh, nn, s, err, thr) == Approx(expect).epsilon(1e-12));
        }
    }
    // At L = 1 antialiased and aliased coincide, so the fade is continuous there.
    CHECK(tk::faded_specular(0.9, 1.0, s, err, thr) == Approx(std::pow(0.9, s)));
}

TEMPLATE_TEST_CASE("toksvig: eq. 12 inverts eq. 6 (free gloss maps)", "[toksvig]", float, double) {
    using T = TestType;
    const double tol = sizeof(T) == 4 ? 1e-5 : 1e-12;
    for (double s0 : {1.0, 8.0, 100.0, 1e4, 1e6})
        for (double frac : {1e-4, 0.01, 0.1, 0.5, 0.9, 1.0}) {
            const double s = s0 * frac;
            const T L = tk::gloss_normal_scale(T(s), T(s0));
            CHECK(double(L) == Approx(s * s0 / (s * s0 + s0 - s)).epsilon(tol));
            // Independent: eq. 6 retyped. Storing L in T costs relative error eps in L, which
            // eq. 6 amplifies by up to s0 (the brief's eq. 10 point: high exponents need
            // precise lengths), so float is good to ~6e-8 s0: 6% at s0 = 1e6.
            const double rel = 4 * s0 * std::numeric_limits<T>::epsilon() + 1e-12;
            CHECK(ref_factor(double(L), s0) * s0 == Approx(s).epsilon(rel));
            CHECK(double(tk::widened_exponent(L, T(s0))) == Approx(s).epsilon(rel));
        }
    CHECK(tk::gloss_normal_scale(T(50), T(10)) == T(1));  // s >= s0: unscaled
    CHECK(tk::gloss_normal_scale(T(-1), T(10)) == T(0));
}

TEST_CASE("toksvig: environment-map lod from log2 sigma", "[toksvig]") {
    CHECK(tk::log2_sigma(0.5) == Approx(0.0).margin(1e-15));  // sigma^2 = 1
    CHECK(tk::log2_sigma(0.2) == Approx(0.5 * std::log2(4.0)));
    CHECK(tk::log2_sigma(1.0) == Approx(-511.0));
    CHECK(tk::log2_sigma(1.0f) == Approx(-63.0f));
    // sigma = 1/8 rad on a level with 64 texels per radian: level log2(8) = 3.
    const double L = 1 / (1 + 1.0 / 64);
    CHECK(tk::env_lod(L, 64.0, 10.0) == Approx(3.0).epsilon(1e-12));
    CHECK(tk::env_lod(1.0, 64.0, 10.0) == 0.0);
    CHECK(tk::env_lod(1e-6, 64.0, 7.5) == 7.5);
}

TEST_CASE("toksvig: the 2D table of eq. 9", "[toksvig]") {
    for (double s : {1.0, 40.0, 1e4}) {
        for (auto wh : {std::pair<int, int>{2, 2}, {37, 23}, {256, 256}, {64, 1000}}) {
            tk::SpecularTableOptions o;
            o.width = wh.first;
            o.height = wh.second;
            o.shininess = s;
            const tk::SpecularTable t = tk::make_specular_table(o);
            REQUIRE(t.value.size() == std::size_t(o.width) * std::size_t(o.height));
            // Row Na.Na = 1 is the 1D table; row Na.Na = 0 is the constant 1/(1 + s).
            const std::vector<float> one_d = tk::make_power_table(o.width, s);
            for (int c = 0; c < o.width; ++c) {
                CHECK(t.at(c, o.height - 1) ==
                      Approx(one_d[std::size_t(c)]).epsilon(1e-6).margin(1e-37));
                CHECK(t.at(c, 0) == Approx(1 / (1 + s)).epsilon(1e-6));
            }
            // Each cell against eq. 8 retyped; the unused region marked, where Na.H > |Na|.
            for (int r = 0; r < o.height; ++r)
                for (int c = 0; c < o.width; ++c) {
                    const double nh = double(c) / (o.width - 1), nn = double(r) / (o.height - 1);
                    const double L = std::sqrt(nn);
                    REQUIRE(t.is_used(c, r) == (nh <= L));
                    const double x = std::fmin(nh, L);
                    const double f = L > 0 ? ref_factor(L, s) : 0.0;
                    const double cosv = L > 0 ? x / L : 0.0;
                    const double expect = (1 + f * s) / (1 + s) * std::pow(cosv, f * s);
                    REQUIRE(t.at(c, r) == Approx(expect).epsilon(2e-6).margin(1e-37));
                }
        }
    }
    // The unused region is a third of the table in the limit (int_0^1 (1 - sqrt(y)) dy).
    tk::SpecularTableOptions big;
    big.width = big.height = 1024;
    const tk::SpecularTable t = tk::make_specular_table(big);
    std::size_t unused = 0;
    for (auto u : t.used) unused += u == 0;
    CHECK(double(unused) / double(t.used.size()) == Approx(1.0 / 3).margin(2e-3));
    // Texel-centre sampling: axes at (k + 0.5)/size.
    tk::SpecularTableOptions tc;
    tc.width = 8;
    tc.height = 4;
    tc.sampling = tk::TableSampling::texel_centres;
    const tk::SpecularTable tt = tk::make_specular_table(tc);
    CHECK(tt.na_dot_h(0) == Approx(1.0 / 16));
    CHECK(tt.na_dot_na(3) == Approx(7.0 / 8));
    CHECK(tt.at(2, 1) == Approx(tk::specular_from_dots(5.0 / 16, 3.0 / 8, 32.0)).epsilon(1e-6));
    // With the eq. 11 fade: rows near Na.Na = 1 move toward the aliased power.
    tk::SpecularTableOptions fo;
    fo.width = fo.height = 64;
    fo.shininess = 256;
    fo.normal_bits = 8;
    const tk::SpecularTable ft = tk::make_specular_table(fo);
    const double nn = 62.0 / 63, nh = 0.98 * std::sqrt(nn);
    const int col = int(std::lround(nh * 63));
    const double nhc = col / 63.0;
    CHECK(ft.at(col, 62) ==
          Approx(tk::faded_specular(nhc, nn, 256.0, tk::quantization_length_error(8), 0.05))
              .epsilon(1e-6));
    CHECK(ft.at(col, 62) != Approx(tk::specular_from_dots(nhc, nn, 256.0)).epsilon(1e-3));
    // Bad options.
    tk::SpecularTableOptions bad;
    bad.width = 1;
    REQUIRE_THROWS_WITH(tk::make_specular_table(bad),
                        Catch::Contains("sphbasis::toksvig::make_specular_table(): expected"));
    bad.width = 4;
    bad.shininess = 0;
    REQUIRE_THROWS_WITH(tk::make_specular_table(bad), Catch::Contains("shininess"));
    bad.shininess = 8;
    bad.normal_bits = 1;
    REQUIRE_THROWS_WITH(tk::make_specular_table(bad), Catch::Contains("normal_bits"));
}

TEMPLATE_TEST_CASE("toksvig: normal-map mip chain without renormalisation", "[toksvig]", float,
                   double) {
    using T = TestType;
    using V = sphbasis::vec3<T>;
    const T tol = std::numeric_limits<T>::epsilon() * 16;
    // A constant map stays constant at every level, any size.
    for (auto wh : {std::pair<int, int>{16, 16}, {13, 7}, {1, 9}, {1, 1}, {64, 2}}) {
        const V n{T(0.36), T(0.48), T(0.8)};
        std::vector<V> map(std::size_t(wh.first * wh.second), n);
        const auto chain = tk::build_normal_mips(map.data(), wh.first, wh.second);
        REQUIRE(chain.back().width == 1);
        REQUIRE(chain.back().height == 1);
        for (const auto& lv : chain)
            for (std::size_t k = 0; k < lv.normal.size(); ++k) {
                CHECK(std::fabs(lv.normal[k].x - n.x) <= tol);
                CHECK(std::fabs(lv.normal[k].y - n.y) <= tol);
                CHECK(std::fabs(lv.normal[k].z - n.z) <= tol);
                CHECK(std::fabs(lv.length[k] - T(1)) <= tol);
            }
        const auto f = tk::factor_map(chain.back(), T(100));
        CHECK(std::fabs(f[0] - T(1)) <= T(100) * tol);
    }
    // The brief's example: two groups 30 degrees either side average to length sqrt(3/4).
    const T c30 = T(0.86602540378443865), s30 = T(0.5);
    std::vector<V> checker(64);
    for (int r = 0; r < 8; ++r)
        for (int c = 0; c < 8; ++c)
            checker[std::size_t(r * 8 + c)] = ((r + c) % 2) ? V{s30, 0, c30} : V{-s30, 0, c30};
    const auto chain = tk::build_normal_mips(checker.data(), 8, 8);
    REQUIRE(chain.size() == 4);
    for (std::size_t lv = 1; lv < chain.size(); ++lv)
        for (T L : chain[lv].length) CHECK(std::fabs(L - c30) <= tol);
    const auto f = tk::factor_map(chain[1], T(32));
    CHECK(double(f[0]) == Approx(ref_factor(double(c30), 32)).epsilon(1e-6));
    // For power-of-two sizes the top level is the mean of the base (box filter, no renormalise).
    std::mt19937 rng(13);
    std::normal_distribution<double> g;
    std::vector<V> rnd(32 * 16);
    double mean[3] = {0, 0, 0};
    for (auto& v : rnd) {
        double x = g(rng), y = g(rng), z = std::fabs(g(rng)) + 0.5;
        const double l = std::sqrt(x * x + y * y + z * z);
        v = {T(x / l), T(y / l), T(z / l)};
        mean[0] += double(v.x) / double(rnd.size());
        mean[1] += double(v.y) / double(rnd.size());
        mean[2] += double(v.z) / double(rnd.size());
    }
    const auto rc = tk::build_normal_mips(rnd.data(), 32, 16);
    REQUIRE(rc.size() == 6);
    CHECK(double(rc.back().normal[0].x) == Approx(mean[0]).margin(1e-5));
    CHECK(double(rc.back().normal[0].z) == Approx(mean[2]).margin(1e-5));
    CHECK(
        double(rc.back().length[0]) ==
        Approx(std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2])).margin(1e-5));
    CHECK(rc.back().length[0] < T(1));
    REQUIRE_THROWS_WITH(tk::build_normal_mips<T>(nullptr, 4, 4),
                        Catch::Contains("sphbasis::toksvig::build_normal_mips(): expected"));
}

TEST_CASE("toksvig: normal maps as glm and Eigen vectors", "[toksvig]") {
    std::vector<glm::vec3> g(4 * 2);
    std::vector<Eigen::Vector3d> e(4 * 2);
    std::vector<sphbasis::vec3<float>> v(4 * 2);
    for (std::size_t k = 0; k < g.size(); ++k) {
        const float a = 0.1f * float(k);
        g[k] = glm::vec3(std::sin(a), 0.0f, std::cos(a));
        e[k] = Eigen::Vector3d(std::sin(a), 0.0, std::cos(a));
        v[k] = {std::sin(a), 0.0f, std::cos(a)};
    }
    const auto cg = tk::build_normal_mips(g, 4, 2);  // a range of glm::vec3: float chain
    const auto cv = tk::build_normal_mips(v.data(), 4, 2);
    const auto ce = tk::build_normal_mips(e.data(), 4, 2);  // Eigen::Vector3d: double chain
    static_assert(std::is_same_v<decltype(cg), decltype(cv)>, "float chain");
    static_assert(std::is_same_v<std::decay_t<decltype(ce[0].length[0])>, double>, "double chain");
    REQUIRE(cg.size() == cv.size());
    for (std::size_t l = 0; l < cg.size(); ++l)
        for (std::size_t k = 0; k < cg[l].length.size(); ++k) {
            CHECK(cg[l].length[k] == cv[l].length[k]);
            CHECK(ce[l].length[k] == Approx(double(cv[l].length[k])).epsilon(1e-6));
        }
    REQUIRE_THROWS_WITH(tk::build_normal_mips(g, 4, 4),
                        Catch::Contains("sphbasis::toksvig::build_normal_mips(): expected a normal "
                                        "array of width * height = 16 elements, got 8"));
}

TEMPLATE_TEST_CASE("toksvig: infinite, NaN and negative shininess give finite values", "[toksvig]",
                   float, double) {
    using T = TestType;
    namespace tk = sphbasis::toksvig;
    const T inf = std::numeric_limits<T>::infinity(), nan = std::numeric_limits<T>::quiet_NaN();
    for (T s : {inf, nan, T(-1)})
        for (T l : {T(0), T(0.5), T(1)})
            for (T c : {T(0), T(0.5), T(1)}) {
                CHECK(std::isfinite(tk::specular(c, l, s)));
                CHECK(std::isfinite(tk::factor(l, s)));
                CHECK(std::isfinite(tk::relative_intensity(l, s)));
                CHECK(std::isfinite(tk::aliased_specular(c, l, s)));
                CHECK(std::isfinite(tk::sensitivity(l, s)));
                CHECK(std::isfinite(tk::faded_specular(c, l, s, T(0.01), T(0.1))));
            }
    // An infinite exponent is the limit of large ones: a mirror lobe (1 at c = 1, 0 below).
    CHECK(tk::specular(T(1), T(1), inf) == T(1));
    CHECK(tk::specular(T(0.5), T(1), inf) == T(0));
}
