// Tests for render/image_metrics.hpp: relative_mse, smape, outside_stderr_fraction and FLIP
// against values computed from their definitions by tools/gen/gen_image_metrics_reference.py
// (numpy/scipy, full 2-D kernels; tests/data/image_metrics_reference.txt); identities
// (identical images give 0, symmetry, scale invariance); finite values for black, dark and huge
// images; tone_mapped(); bad input.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "render_test_support.hpp"
#include "sphbasis/render/image_metrics.hpp"

namespace render = sphbasis::render;
using render::Image;
using sphbasis_test::constant_image;

namespace {

struct Case {
    std::map<std::string, Image> images;  // test, ref, stderr, mask
    // (metric, masked, ppd) -> value
    std::map<std::string, double> values;
    std::map<double, std::vector<double>> flip_maps;
};

std::string value_key(const std::string& metric, int masked, double ppd) {
    std::ostringstream k;
    k << metric << " " << masked << " " << ppd;
    return k.str();
}

const std::map<std::string, Case>& reference_cases() {
    static const std::map<std::string, Case> cases = [] {
        std::map<std::string, Case> out;
        std::ifstream in(SPHBASIS_TEST_DATA_DIR "/image_metrics_reference.txt");
        REQUIRE(in.good());
        std::string line;
        while (std::getline(in, line)) {
            if (line.empty() || line[0] == '#') continue;
            std::istringstream s(line);
            std::string kind, name;
            s >> kind >> name;
            if (kind == "image") {
                std::string role;
                int w = 0, h = 0, c = 0;
                s >> role >> w >> h >> c;
                Image im(w, h, c);
                for (float& v : im.data) s >> v;
                REQUIRE(!s.fail());
                out[name].images[role] = im;
            } else if (kind == "value") {
                std::string metric;
                int masked = 0;
                double ppd = 0, v = 0;
                s >> metric >> masked >> ppd >> v;
                REQUIRE(!s.fail());
                out[name].values[value_key(metric, masked, ppd)] = v;
            } else if (kind == "flipmap") {
                double ppd = 0, v = 0;
                s >> ppd;
                std::vector<double> map;
                while (s >> v) map.push_back(v);
                out[name].flip_maps[ppd] = map;
            }
        }
        return out;
    }();
    return cases;
}

Image scaled(Image im, float s) {
    for (float& v : im.data) v *= s;
    return im;
}

}  // namespace

TEST_CASE("image metrics: values from the definitions (numpy generator)", "[render][metrics]") {
    const auto& cases = reference_cases();
    REQUIRE(cases.size() == 3);
    int checked = 0;
    for (const auto& [name, c] : cases) {
        INFO(name);
        const Image& t = c.images.at("test");
        const Image& r = c.images.at("ref");
        const Image& s = c.images.at("stderr");
        const auto mask_it = c.images.find("mask");
        for (int masked = 0; masked < 2; ++masked) {
            if (masked && mask_it == c.images.end()) continue;
            const Image* mask = masked ? &mask_it->second : nullptr;
            INFO("masked " << masked);
            CHECK(render::relative_mse(t, r, mask) ==
                  Approx(c.values.at(value_key("relative_mse", masked, 0))).epsilon(1e-12));
            CHECK(render::smape(t, r, mask) ==
                  Approx(c.values.at(value_key("smape", masked, 0))).epsilon(1e-12));
            CHECK(render::outside_stderr_fraction(t, r, &s, 3, mask) ==
                  c.values.at(value_key("outside", masked, 0)));
            checked += 3;
        }
        for (const auto& [ppd, map] : c.flip_maps) {
            INFO("ppd " << ppd);
            const Image f = render::flip_error_map(t, r, ppd);
            REQUIRE(f.data.size() == map.size());
            double worst = 0;
            for (std::size_t i = 0; i < map.size(); ++i)
                worst = std::max(worst, std::fabs(double(f.data[i]) - map[i]));
            CHECK(worst < 2e-6);  // float storage of values in [0, 1]
            for (int masked = 0; masked < 2; ++masked) {
                if (masked && mask_it == c.images.end()) continue;
                const Image* mask = masked ? &mask_it->second : nullptr;
                CHECK(render::flip_mean(t, r, ppd, mask) ==
                      Approx(c.values.at(value_key("flip", masked, ppd))).margin(1e-6));
                ++checked;
            }
        }
    }
    CHECK(checked == 10 + 6 + 3);
}

TEST_CASE("image metrics: identities", "[render][metrics]") {
    const auto& c = reference_cases().at("random16");
    const Image& t = c.images.at("test");
    const Image& r = c.images.at("ref");
    // Identical images: 0 for every metric.
    CHECK(render::relative_mse(r, r) == 0);
    CHECK(render::smape(r, r) == 0);
    CHECK(render::outside_stderr_fraction(r, r, nullptr) == 0);
    CHECK(render::flip_mean(r, r) == 0);
    // FLIP is symmetric; relative MSE is not.
    const Image a = render::flip_error_map(t, r), b = render::flip_error_map(r, t);
    CHECK(a.data == b.data);
    CHECK(render::relative_mse(t, r) != Approx(render::relative_mse(r, t)));
    // relative MSE, sMAPE and the stderr fraction are invariant under a common scale (their
    // floors scale with the reference's mean): 2^-20 and 2^40 are exact in float.
    for (float k : {std::ldexp(1.0f, -20), std::ldexp(1.0f, 40)}) {
        CHECK(render::relative_mse(scaled(t, k), scaled(r, k)) ==
              Approx(render::relative_mse(t, r)).epsilon(1e-12));
        CHECK(render::smape(scaled(t, k), scaled(r, k)) ==
              Approx(render::smape(t, r)).epsilon(1e-12));
        const Image s = c.images.at("stderr");
        CHECK(render::outside_stderr_fraction(scaled(t, k), scaled(r, k), &s) >= 0);
    }
    // Closed forms on constant images: t = 0.6, r = 0.5 in every channel, m = 0.5.
    const Image t1 = constant_image(4, 3, 0.625f, 0.625f, 0.625f);
    const Image r1 = constant_image(4, 3, 0.5f, 0.5f, 0.5f);
    CHECK(render::relative_mse(t1, r1) == Approx(0.015625 / (0.25 + 1e-2 * 0.25)).epsilon(1e-14));
    CHECK(render::smape(t1, r1) == Approx(0.25 / (1.125 + 5e-3)).epsilon(1e-14));
    // Standard errors: a difference of 0.125 is outside 3 x 0.04 and inside 3 x 0.05.
    Image s1 = constant_image(4, 3, 0.04f, 0.05f, 0.05f);
    CHECK(render::outside_stderr_fraction(t1, r1, &s1) == 1);
    s1 = constant_image(4, 3, 0.05f, 0.05f, 0.05f);
    CHECK(render::outside_stderr_fraction(t1, r1, &s1) == 0);
    CHECK(render::outside_stderr_fraction(t1, r1, &s1, 2) == 1);
    // Zero stderr: floored at 1e-4 m = 5e-5, so beyond 3 x 5e-5 a difference of 2e-4 is
    // outside, 1e-5 is not.
    const Image t2 = constant_image(4, 3, 0.5002f, 0.5f, 0.5f);
    const Image t3 = constant_image(4, 3, 0.50001f, 0.5f, 0.5f);
    CHECK(render::outside_stderr_fraction(t2, r1, nullptr) == 1);
    CHECK(render::outside_stderr_fraction(t3, r1, nullptr) == 0);
    // FLIP: the largest colour difference, green against blue on flat images, is 1 (no
    // features); black against white is below it; a flat image differs from itself by 0.
    CHECK(render::flip_mean(constant_image(8, 8, 0, 1, 0), constant_image(8, 8, 0, 0, 1)) ==
          Approx(1).margin(1e-6));
    const double bw =
        render::flip_mean(constant_image(8, 8, 0, 0, 0), constant_image(8, 8, 1, 1, 1));
    CHECK(bw > 0.5);
    CHECK(bw < 1);
}

TEST_CASE("image metrics: finite for black, dark and huge images", "[render][metrics]") {
    const Image black(6, 5, 3);
    const Image dark = constant_image(6, 5, 1e-30f, 0, 1e-38f);
    const float big = std::numeric_limits<float>::max();
    const Image huge = constant_image(6, 5, big, big, 0);
    Image mixed(6, 5, 3);
    for (std::size_t i = 0; i < mixed.data.size(); ++i) mixed.data[i] = i % 2 ? big : 0.0f;
    const Image* images[] = {&black, &dark, &huge, &mixed};
    for (const Image* t : images)
        for (const Image* r : images) {
            const double v[] = {render::relative_mse(*t, *r),
                                render::smape(*t, *r),
                                render::outside_stderr_fraction(*t, *r, nullptr),
                                render::outside_stderr_fraction(*t, *r, r),
                                render::flip_mean(*t, *r),
                                render::compare(*t, *r, nullptr).rel_mse_floored,
                                render::compare(*t, *r, nullptr).smape_floored};
            for (double x : v) CHECK(std::isfinite(x));
        }
    // A black reference: m = 1 (the published eps = 1e-2).
    CHECK(render::relative_mse(dark, black) == Approx(1e-60 / 3 / 1e-2).epsilon(1e-6));
    CHECK(render::relative_mse(black, black) == 0);
    // No selected pixel: 0.
    const Image none(6, 5, 1);
    CHECK(render::relative_mse(huge, black, &none) == 0);
    CHECK(render::flip_mean(huge, black, render::flip_default_ppd, &none) == 0);
}

TEST_CASE("image metrics: tone_mapped", "[render][metrics]") {
    Image im(4, 1, 3);
    im.data = {0.5f,  1.0f,          4.0f, -1.0f, std::numeric_limits<float>::infinity(),
               0.0f,  std::nanf(""), 2.0f, 1e30f, 0.25f,
               0.25f, 0.25f};
    const Image c = render::tone_mapped(im, 1, "clamp");
    CHECK(c.data == std::vector<float>{0.5f, 1, 1, 0, 1, 0, 0, 1, 1, 0.25f, 0.25f, 0.25f});
    const Image r = render::tone_mapped(im, 2, "reinhard");
    CHECK(r.data[0] == Approx(0.5));
    CHECK(r.data[9] == Approx(1.0 / 3.0));
    CHECK_THROWS_WITH(render::tone_mapped(im, 1, "filmic"), Catch::Contains("clamp"));
    CHECK_THROWS_AS(render::tone_mapped(im, -1, "clamp"), std::invalid_argument);
}

TEST_CASE("image metrics: bad input throws", "[render][metrics]") {
    const Image a = constant_image(4, 4, 1, 1, 1), b = constant_image(4, 3, 1, 1, 1);
    CHECK_THROWS_WITH(render::relative_mse(a, b), Catch::Contains("4x3"));
    CHECK_THROWS_AS(render::smape(a, b), std::invalid_argument);
    CHECK_THROWS_AS(render::flip_error_map(a, b), std::invalid_argument);
    CHECK_THROWS_AS(render::outside_stderr_fraction(a, a, &b), std::invalid_argument);
    CHECK_THROWS_AS(render::outside_stderr_fraction(a, a, nullptr, 0), std::invalid_argument);
    CHECK_THROWS_WITH(render::flip_error_map(a, a, 0.5), Catch::Contains("pixels per degree"));
    Image nan = a;
    nan.data[5] = std::nanf("");
    CHECK_THROWS_WITH(
        render::relative_mse(nan, a),
        Catch::Contains("finite values in the test image") && Catch::Contains("(1, 0)"));
    CHECK_THROWS_AS(render::flip_mean(a, nan), std::invalid_argument);
    const Image negative = constant_image(4, 4, -1, 0, 0);
    CHECK_THROWS_WITH(render::outside_stderr_fraction(a, a, &negative),
                      Catch::Contains("standard errors >= 0"));
    const Image mask(4, 3, 1);
    CHECK_THROWS_AS(render::flip_mean(a, a, render::flip_default_ppd, &mask),
                    std::invalid_argument);
}

TEST_CASE("image metrics: flip_colour and flip_mean_of", "[render][metrics]") {
    Image m(3, 1, 1);
    m.data = {0.0f, 1.0f, std::nanf("")};
    const auto c = render::flip_colour(m);
    CHECK(std::vector<int>(c.begin(), c.end()) ==
          std::vector<int>{68, 1, 84, 253, 231, 37, 128, 128, 128});
    m.data = {0.25f, 0.75f, 0.5f};
    Image mask(3, 1, 1);
    mask.data = {1, 0, 1};
    CHECK(render::flip_mean_of(m, &mask) == Approx(0.375));
    const auto cm = render::flip_colour(m, &mask);
    CHECK(int(cm[3]) == 128);
    CHECK(int(cm[4]) == 128);
    CHECK(int(cm[0]) != 128);
    const Image wrong(2, 1, 1);
    CHECK_THROWS_AS(render::flip_colour(m, &wrong), std::invalid_argument);
    CHECK(render::flip_mean_of(m) == Approx(0.5));
}
