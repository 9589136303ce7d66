// Tests of sphbasis/ops/sh_latlong.hpp: exact projection of piecewise-constant lat-long maps.
#include <catch2/catch.hpp>
#include <cmath>
#include <sphbasis/core/quadrature.hpp>
#include <sphbasis/ops/sh_latlong.hpp>
#include <stdexcept>
#include <vector>

using namespace sphbasis;

TEST_CASE(
    "sh::project_latlong integrates piecewise-constant texels exactly (ported from the "
    "FFT projector of the IMSE benchmark)",
    "[latlong]") {
    // Constant map: only y_00, with coefficient sqrt(4 pi).
    LatLongMap one{32, 16, std::vector<double>(32 * 16, 1.0)};
    const std::vector<double> c1 = sh::project_latlong(one, 6);
    CHECK(c1[0] == Approx(std::sqrt(constants::four_pi)).epsilon(1e-14));
    for (std::size_t k = 1; k < c1.size(); ++k) CHECK(c1[k] == Approx(0).margin(1e-14));
    CHECK(squared_norm(one) == Approx(constants::four_pi).epsilon(1e-14));
    // A rough map against brute-force 2D Gauss-Legendre inside every texel; a width that is not
    // a power of two takes the direct DFT.
    for (int width : {24, 20}) {
        const int height = 12, bands = 8;
        LatLongMap m{width, height, {}};
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i)
                m.values.push_back(std::sin(0.37 * i + 0.1 * j * j) + 0.5);
        const std::vector<double> c = sh::project_latlong(m, bands);
        std::vector<double> ref(static_cast<std::size_t>(bands * bands), 0.0);
        std::vector<double> yv(ref.size()), gt, gw;
        gauss_legendre(16, gt, gw);
        for (int j = 0; j < height; ++j)
            for (int i = 0; i < width; ++i) {
                const double t0 = constants::pi * j / height, t1 = constants::pi * (j + 1) / height;
                const double p0 = constants::two_pi * i / width,
                             p1 = constants::two_pi * (i + 1) / width;
                for (std::size_t a = 0; a < gt.size(); ++a)
                    for (std::size_t b = 0; b < gt.size(); ++b) {
                        const double t = 0.5 * (t0 + t1) + 0.5 * (t1 - t0) * gt[a];
                        const double ph = 0.5 * (p0 + p1) + 0.5 * (p1 - p0) * gt[b];
                        const double wt =
                            0.25 * (t1 - t0) * (p1 - p0) * gw[a] * gw[b] * std::sin(t);
                        sh::eval(bands, std::sin(t) * std::cos(ph), std::sin(t) * std::sin(ph),
                                 std::cos(t), yv.data());
                        const double v = m.values[static_cast<std::size_t>(j * width + i)];
                        for (std::size_t k = 0; k < ref.size(); ++k) ref[k] += wt * v * yv[k];
                    }
            }
        for (std::size_t k = 0; k < ref.size(); ++k) CHECK(c[k] == Approx(ref[k]).margin(1e-12));
    }
    CHECK_THROWS_AS(sh::project_latlong(LatLongMap{4, 2, {1.0}}, 4), std::invalid_argument);
}
