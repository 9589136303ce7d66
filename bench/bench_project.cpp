// Benchmark of `sphbasis project` on its own parts: reading a 2048 x 1024 float RGB OpenEXR
// (ZIP, as tools write them; generated here, a smooth sky with a sun and noise, so that the
// compression has real work) and projecting it onto 3 bands (sh::project_latlong_fn, RGB, the
// code path of the command). Items are texels. The claim of docs/project.md, "projection takes
// at most 2x the time of the read", is the ratio project / read of one run:
//   build/bin/bench_project --benchmark_format=json
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <sphbasis/ops/sh_latlong.hpp>
#include <string>
#include <vector>

#include "support/envmap.hpp"
#include "support/exr.hpp"

namespace {

constexpr int width = 2048, height = 1024;

struct Rgb {
    double r = 0, g = 0, b = 0;
    Rgb operator+(const Rgb& o) const { return {r + o.r, g + o.g, b + o.b}; }
    Rgb operator*(double s) const { return {r * s, g * s, b * s}; }
};

const std::string& map_path() {
    static const std::string path = [] {
        std::vector<float> px(static_cast<std::size_t>(width) * height * 3);
        std::mt19937 rng(7);
        std::normal_distribution<float> noise(0.0f, 0.02f);
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const double th = 3.141592653589793 * (y + 0.5) / height;
                const double ph = 6.283185307179586 * (x + 0.5) / width;
                const double sun = std::exp(200 * (std::sin(th) * std::cos(ph - 1) - 1));
                const double sky = 0.5 + 0.4 * std::cos(th);
                float* p = &px[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
                p[0] = static_cast<float>(sky * 0.6 + 50 * sun) + noise(rng);
                p[1] = static_cast<float>(sky * 0.8 + 45 * sun) + noise(rng);
                p[2] = static_cast<float>(sky * 1.0 + 40 * sun) + noise(rng);
            }
        const std::string p = "/tmp/sphbasis_bench_project_2048x1024.exr";
        sphbasis::cli::write_exr_channels(p, width, height, {"R", "G", "B"}, px);
        return p;
    }();
    return path;
}

void read_exr(benchmark::State& state) {
    const std::string& path = map_path();
    for (auto _ : state) {
        sphbasis::cli::LinearRgbImage img = sphbasis::cli::load_linear_rgb(path);
        benchmark::DoNotOptimize(img.rgb.data());
    }
    state.SetItemsProcessed(state.iterations() * width * height);
}
BENCHMARK(read_exr)->Unit(benchmark::kMillisecond);

void project_sh3(benchmark::State& state) {
    const sphbasis::cli::LinearRgbImage img = sphbasis::cli::load_linear_rgb(map_path());
    Rgb out[9];
    for (auto _ : state) {
        sphbasis::sh::project_latlong_fn(
            3, width, height,
            [&](int c, int r) {
                const float* p =
                    &img.rgb[(std::size_t(r) * std::size_t(width) + std::size_t(c)) * 3];
                return Rgb{p[0], p[1], p[2]};
            },
            out);
        benchmark::DoNotOptimize(out);
    }
    state.SetItemsProcessed(state.iterations() * width * height);
}
BENCHMARK(project_sh3)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
