// Tests for render/image.hpp: tone-mapping operators against their formulas, the sRGB transfer
// function at known values, auto exposure, image comparison (identical images, a known offset,
// judged counts with a stderr image and a mask), error and false-colour images, bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/render/image_metrics.hpp"

namespace render = sphbasis::render;
using render::Image;
using sphbasis_test::constant_image;

namespace {

int srgb8(double linear) {
    const double y =
        linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1 / 2.4) - 0.055;
    return int(std::lround(255 * y));
}

}  // namespace

TEST_CASE("to_srgb8: the sRGB transfer function at known values", "[render][image]") {
    Image im(3, 1, 3);
    const float v[3] = {0.0f, 0.0031308f, 1.0f};
    for (int x = 0; x < 3; ++x)
        for (int c = 0; c < 3; ++c) im.at(x, 0)[c] = v[x];
    const auto out = render::to_srgb8(im, 1.0, "clamp");
    REQUIRE(out.size() == 9);
    CHECK(int(out[0]) == 0);
    CHECK(int(out[3]) == int(std::lround(255 * 12.92 * 0.0031308)));  // 10: the linear segment end
    CHECK(int(out[3]) == 10);
    CHECK(int(out[6]) == 255);
    // 0.5 linear: 1.055 * 0.5^(1/2.4) - 0.055 = 0.73536 -> 188.
    Image half = constant_image(1, 1, 0.5f, 0.5f, 0.5f);
    CHECK(int(render::to_srgb8(half, 1.0, "clamp")[0]) == 188);
}

TEST_CASE("to_srgb8: the operators against their formulas", "[render][image]") {
    const double xs[] = {0.0, 0.05, 0.2, 0.7, 1.0, 2.5, 40.0};
    for (double x : xs) {
        Image im = constant_image(1, 1, float(x), float(x), float(x));
        const double xf = double(float(x));
        const double exposure = 1.5;
        const double e = xf * exposure;
        const double clamp_v = std::min(e, 1.0);
        const double reinhard = e / (1 + e);
        const double aces =
            std::min(1.0, std::max(0.0, (e * (2.51 * e + 0.03)) / (e * (2.43 * e + 0.59) + 0.14)));
        CHECK(int(render::to_srgb8(im, exposure, "clamp")[1]) == srgb8(clamp_v));
        CHECK(int(render::to_srgb8(im, exposure, "reinhard")[1]) == srgb8(reinhard));
        CHECK(int(render::to_srgb8(im, exposure, "aces")[1]) == srgb8(aces));
    }
    CHECK(render::tone_map_names() == std::vector<std::string>{"clamp", "reinhard", "aces"});
}

TEST_CASE("to_srgb8: NaN, negative and infinite values; grey images; bad input throws",
          "[render][image]") {
    Image im(4, 1, 3);
    im.at(0, 0)[0] = std::numeric_limits<float>::quiet_NaN();
    im.at(1, 0)[0] = -3.0f;
    im.at(2, 0)[0] = std::numeric_limits<float>::infinity();
    im.at(3, 0)[0] = 0.5f;
    for (const char* op : {"clamp", "reinhard", "aces"}) {
        const auto out = render::to_srgb8(im, 1.0, op);
        CHECK(int(out[0]) == 0);
        CHECK(int(out[3]) == 0);
        CHECK(int(out[6]) == 255);
    }
    Image grey(2, 1, 1);
    grey.data = {0.5f, 1.0f};
    const auto g = render::to_srgb8(grey, 1.0, "clamp");
    REQUIRE(g.size() == 6);
    CHECK(int(g[0]) == 188);
    CHECK(int(g[1]) == 188);
    CHECK(int(g[2]) == 188);
    CHECK(int(g[5]) == 255);
    CHECK_THROWS_WITH(render::to_srgb8(im, 1.0, "filmic"),
                      Catch::Contains("clamp, reinhard or aces") && Catch::Contains("filmic"));
    CHECK_THROWS_AS(render::to_srgb8(im, -1.0, "clamp"), std::invalid_argument);
    CHECK_THROWS_AS(render::to_srgb8(im, std::nan(""), "clamp"), std::invalid_argument);
    CHECK_THROWS_AS(render::to_srgb8(Image(2, 2, 2), 1.0, "clamp"), std::invalid_argument);
    CHECK_THROWS_AS(Image(0, 2, 3), std::invalid_argument);
    CHECK_THROWS_AS(Image(2, 2, 5), std::invalid_argument);
}

TEST_CASE("auto_exposure: 0.18 over the log-average luminance", "[render][image]") {
    const Image c = constant_image(4, 3, 2.0f, 2.0f, 2.0f);
    CHECK(render::auto_exposure(c) == Approx(0.09).epsilon(1e-6));
    // Two luminances a and b: the geometric mean; black and non-finite pixels left out.
    Image two(4, 1, 3);
    for (int c2 = 0; c2 < 3; ++c2) {
        two.at(0, 0)[c2] = 0.5f;
        two.at(1, 0)[c2] = 8.0f;
        two.at(2, 0)[c2] = 0.0f;
        two.at(3, 0)[c2] = std::numeric_limits<float>::infinity();
    }
    CHECK(render::auto_exposure(two) == Approx(0.18 / 2.0).epsilon(1e-6));
    // Rec. 709 weights: pure green of 1 has luminance 0.7152.
    const Image g = constant_image(2, 2, 0.0f, 1.0f, 0.0f);
    CHECK(render::auto_exposure(g) == Approx(0.18 / 0.7152).epsilon(1e-6));
    CHECK(render::auto_exposure(Image(3, 3, 3)) == 1.0);
}

TEST_CASE("compare: identical images, a known offset, judged counts", "[render][image]") {
    const Image ref = constant_image(8, 4, 0.5f, 0.25f, 1.0f);
    const auto same = render::compare(ref, ref, nullptr);
    CHECK(same.rmse == 0);
    CHECK(same.rel_mse == 0);
    CHECK(same.smape == 0);
    CHECK(same.judged == 32);
    CHECK(same.total == 32);

    const double d = 0.125;
    const Image off = constant_image(8, 4, float(0.5 + d), float(0.25 + d), float(1.0 + d));
    const auto e = render::compare(off, ref, nullptr);
    CHECK(e.rmse == Approx(d).epsilon(1e-6));
    const double floor = 1e-3 * render::luminance(0.5, 0.25, 1.0);
    const double r2 = 0.25 + 0.0625 + 1.0;
    CHECK(e.rel_mse == Approx(3 * d * d / (r2 + floor * floor)).epsilon(1e-6));
    const double ts = (0.5 + d) + (0.25 + d) + (1 + d);
    CHECK(e.smape == Approx(3 * d / (ts + 1.75 + floor)).epsilon(1e-6));

    // A stderr image: the left half too noisy (0.1 > 0.05 * luminance), the right half fine.
    const double lum = render::luminance(0.5, 0.25, 1.0);
    Image se(8, 4, 3);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 8; ++x)
            for (int c = 0; c < 3; ++c) se.at(x, y)[c] = float(x < 4 ? 0.1 * lum : 0.01 * lum);
    const auto j = render::compare(off, ref, &se, 0.05);
    CHECK(j.judged == 16);
    CHECK(j.total == 32);
    CHECK(j.rmse == Approx(d).epsilon(1e-6));
    // A mask: the top row left out of everything.
    Image mask(8, 4, 1);
    for (int y = 1; y < 4; ++y)
        for (int x = 0; x < 8; ++x) mask.at(x, y)[0] = 1;
    const auto m = render::compare(off, ref, &se, 0.05, &mask);
    CHECK(m.total == 24);
    CHECK(m.judged == 12);

    // The error image: |t - r| / (|r| + floor), -1 where not judged.
    const Image err = render::error_image(off, ref, &se, 0.05, &mask);
    REQUIRE(err.channels == 1);
    CHECK(err.at(0, 0)[0] == -1.0f);  // masked
    CHECK(err.at(1, 2)[0] == -1.0f);  // too noisy
    CHECK(err.at(6, 2)[0] == Approx(std::sqrt(3 * d * d) / (std::sqrt(r2) + floor)).epsilon(1e-6));
    const auto fc = render::false_colour(err);
    REQUIRE(fc.size() == 3 * 32);
    CHECK(int(fc[0]) == 128);
    CHECK(int(fc[1]) == 128);
    CHECK(int(fc[2]) == 128);
}

TEST_CASE("false_colour: the ends of the logarithmic scale", "[render][image]") {
    Image e(4, 1, 1);
    e.data = {0.0f, 1e-3f, 1.0f, 50.0f};
    const auto c = render::false_colour(e);
    CHECK(int(c[0]) == 68);  // viridis start
    CHECK(int(c[3]) == 68);
    CHECK(int(c[6]) == 253);  // viridis end
    CHECK(int(c[9]) == 253);
    CHECK(int(c[11]) == 37);
}

TEST_CASE("compare: bad input throws", "[render][image]") {
    const Image a = constant_image(4, 4, 1, 1, 1), b = constant_image(4, 3, 1, 1, 1);
    CHECK_THROWS_WITH(render::compare(a, b, nullptr), Catch::Contains("4x3"));
    CHECK_THROWS_AS(render::compare(a, a, nullptr, 0.0), std::invalid_argument);
    CHECK_THROWS_AS(render::compare(a, a, nullptr, -1.0), std::invalid_argument);
    CHECK_THROWS_AS(render::compare(a, a, &b), std::invalid_argument);
    Image mask(4, 3, 1);
    CHECK_THROWS_AS(render::compare(a, a, nullptr, 0.05, &mask), std::invalid_argument);
    Image broken = a;
    broken.data.pop_back();
    CHECK_THROWS_AS(render::compare(broken, a, nullptr), std::invalid_argument);
    CHECK_THROWS_AS(render::error_image(a, b, nullptr), std::invalid_argument);
    // A black reference stays NaN-free.
    const Image black(4, 4, 3);
    const auto z = render::compare(a, black, nullptr);
    CHECK(std::isfinite(z.rel_mse));
    CHECK(std::isfinite(z.smape));
}
