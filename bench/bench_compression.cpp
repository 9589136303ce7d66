// PCA and CPCA compression time against the number of points (ops/compression.hpp).
// Data: P points of 27 columns (3 bands of SH, RGB: a transfer-vector-like signal that varies
// smoothly with a direction, plus a little noise), C = 16 clusters, M = 4 vectors.
// Items processed = points, so the items/s column reads as points per second: constant
// items/s across sizes means linear growth. The iterative CPCA runs a fixed number of
// iterations (10, no early stop) so sizes compare per iteration.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/core/sampling.hpp>
#include <sphbasis/ops/compression.hpp>

using namespace sphbasis;

namespace {

Eigen::MatrixXd transfer_like(Eigen::Index p) {
    std::mt19937_64 rng(42);
    auto uni = [&] { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
    Eigen::MatrixXd x(p, 27);
    for (Eigen::Index i = 0; i < p; ++i) {
        const auto d = square_to_uniform_sphere(uni(), uni());
        double y[9];
        sh::eval(3, d.x, d.y, d.z, y);
        const double albedo[3] = {0.8, 0.6 + 0.2 * d.x, 0.4 + 0.3 * d.z};
        for (int ch = 0; ch < 3; ++ch)
            for (int k = 0; k < 9; ++k)
                x(i, ch * 9 + k) = albedo[ch] * y[k] *
                                       (k == 0  ? 1.0
                                        : k < 4 ? 0.667
                                                : 0.25) +
                                   1e-3 * (uni() - 0.5);
    }
    return x;
}

void pca_svd(benchmark::State& state) {
    const Eigen::MatrixXd x = transfer_like(state.range(0));
    for (auto _ : state) benchmark::DoNotOptimize(compress::pca(x, 4, compress::PcaMethod::svd));
    state.SetItemsProcessed(state.iterations() * state.range(0));
}

void pca_covariance(benchmark::State& state) {
    const Eigen::MatrixXd x = transfer_like(state.range(0));
    for (auto _ : state)
        benchmark::DoNotOptimize(compress::pca(x, 4, compress::PcaMethod::covariance));
    state.SetItemsProcessed(state.iterations() * state.range(0));
}

void cpca_static(benchmark::State& state) {
    const Eigen::MatrixXd x = transfer_like(state.range(0));
    compress::CpcaSettings s;
    s.clusters = 16;
    s.vectors = 4;
    int lloyd = 0;
    double err = 0, seconds = 0;
    for (auto _ : state) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto m = compress::cpca_static(x, s);
        seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        lloyd = m.lloyd_iterations;
        err = m.error_history.back();
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
    state.counters["lloyd"] = lloyd;
    // Lloyd iterations grow with P (up to the cap of 100): the cost per iteration is the
    // linear part.
    state.counters["ms_per_lloyd"] =
        1e3 * seconds / static_cast<double>(state.iterations()) / std::max(1, lloyd);
    state.counters["err_per_point"] = err / static_cast<double>(state.range(0));
}

void cpca_iterative(benchmark::State& state) {
    const Eigen::MatrixXd x = transfer_like(state.range(0));
    compress::CpcaSettings s;
    s.clusters = 16;
    s.vectors = 4;
    s.max_iterations = 10;
    s.min_relative_decrease = 0;
    int iterations = 0;
    double err = 0, err0 = 0, extra = 0;
    for (auto _ : state) {
        // The static stage timed apart (paused), so the reclassification loop's cost per
        // iteration is the difference.
        state.PauseTiming();
        auto t0 = std::chrono::steady_clock::now();
        benchmark::DoNotOptimize(compress::cpca_static(x, s));
        const double st =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        state.ResumeTiming();
        t0 = std::chrono::steady_clock::now();
        const auto m = compress::cpca_iterative(x, s);
        extra += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() - st;
        iterations = m.iterations;
        err = m.error_history.back();
        err0 = m.error_history.front();
    }
    state.SetItemsProcessed(state.iterations() * state.range(0));
    state.counters["iterations"] = iterations;
    state.counters["err_ratio_vs_static"] = err / err0;
    state.counters["ms_per_iteration"] =
        1e3 * extra / static_cast<double>(state.iterations()) / std::max(1, iterations);
}

}  // namespace

BENCHMARK(pca_svd)->RangeMultiplier(4)->Range(1 << 10, 1 << 16)->Unit(benchmark::kMillisecond);
BENCHMARK(pca_covariance)
    ->RangeMultiplier(4)
    ->Range(1 << 10, 1 << 16)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(cpca_static)->RangeMultiplier(4)->Range(1 << 10, 1 << 16)->Unit(benchmark::kMillisecond);
BENCHMARK(cpca_iterative)
    ->RangeMultiplier(4)
    ->Range(1 << 10, 1 << 16)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
