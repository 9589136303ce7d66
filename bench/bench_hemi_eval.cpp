// Benchmarks of the hemispherical bases (basis/hsh.hpp, makhotkin.hpp, zernike.hpp, hbasis.hpp,
// hl2.hpp) and of Ambient Dice's face variants (basis/ambient_dice_bezier.hpp) in float. Items are
// directions: items_per_second is directions per second, so ns per direction = 1e9 /
// items_per_second. The argument is the number of functions n.
//   one_call:   basis_eval<B>(n, x, y, z, out) once per direction (normalising, run-time n)
//   batch:      basis_eval_batch<B> over 1M directions (SoA in and out, SIMD across directions)
//   sum_batch:  basis_eval_sum_batch<B> over 1M directions (sum c_i B_i, the B_i not stored)
// Sizes: the usual ones (HSH/Makhotkin 2-5 bands = 4..25 functions, Zernike 2-5 bands = 3..15,
// H-basis 4 and 6, HL2 3), and one high count per recurrence path (64 bands: the row recurrence,
// 65 bands: the column recurrence) for one_call; Ambient Dice Bezier 30 and 36, linear 10 and 12.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <sphbasis/basis/ambient_dice_bezier.hpp>
#include <sphbasis/basis/hbasis.hpp>
#include <sphbasis/basis/hl2.hpp>
#include <sphbasis/basis/hsh.hpp>
#include <sphbasis/basis/makhotkin.hpp>
#include <sphbasis/basis/zernike.hpp>
#include <vector>

namespace {

using sphbasis::AmbientDiceBezier;
using sphbasis::AmbientDiceBezierNormalized;
using sphbasis::AmbientDiceLinear;
using sphbasis::HBasis;
using sphbasis::HBasisMod;
using sphbasis::HL2;
using sphbasis::HSH;
using sphbasis::Makhotkin;
using sphbasis::Zernike;

/// Unit directions on the upper hemisphere (where the bases live), fixed seed.
struct Dirs {
    std::vector<float> x, y, z;
    explicit Dirs(std::size_t n) {
        std::mt19937 rng(1);
        std::normal_distribution<double> g;
        x.reserve(n);
        y.reserve(n);
        z.reserve(n);
        for (std::size_t i = 0; i < n; ++i) {
            const double a = g(rng), b = g(rng), c = std::fabs(g(rng));
            const double r = std::sqrt(a * a + b * b + c * c);
            x.push_back(float(a / r));
            y.push_back(float(b / r));
            z.push_back(float(c / r));
        }
    }
};

const Dirs& million() {
    static const Dirs d(std::size_t(1) << 20);
    return d;
}

template <class B>
void one_call(benchmark::State& st) {
    const int n = static_cast<int>(st.range(0));
    const std::size_t count = n > 1000 ? 64 : 4096;
    const Dirs d(count);
    std::vector<float> out(static_cast<std::size_t>(n));
    float acc = 0;
    for (auto _ : st) {
        for (std::size_t i = 0; i < count; ++i) {
            sphbasis::basis_eval<B>(n, d.x[i], d.y[i], d.z[i], out.data());
            benchmark::DoNotOptimize(out.data());
            acc += out[static_cast<std::size_t>(n - 1)];
        }
    }
    benchmark::DoNotOptimize(acc);
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) *
                         static_cast<std::int64_t>(count));
}

/// Calls f(d) on the million directions once per iteration; items are directions.
template <class F>
void over_million(benchmark::State& st, F&& f) {
    const Dirs& d = million();
    for (auto _ : st) {
        f(d);
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) *
                         static_cast<std::int64_t>(d.x.size()));
}

template <class B>
void batch(benchmark::State& st) {
    const int n = static_cast<int>(st.range(0));
    const std::size_t count = million().x.size();
    std::vector<float> out(static_cast<std::size_t>(n) * count);
    over_million(st, [&](const Dirs& d) {
        sphbasis::basis_eval_batch<B>(n, count, d.x.data(), d.y.data(), d.z.data(), out.data(),
                                      count);
        benchmark::DoNotOptimize(out.data());
    });
}

template <class B>
void sum_batch(benchmark::State& st) {
    const int n = static_cast<int>(st.range(0));
    const std::size_t count = million().x.size();
    std::vector<float> coeffs(static_cast<std::size_t>(n)), out(count);
    for (std::size_t k = 0; k < coeffs.size(); ++k) coeffs[k] = float(std::sin(double(k) + 1));
    over_million(st, [&](const Dirs& d) {
        sphbasis::basis_eval_sum_batch<B>(n, coeffs.data(), count, d.x.data(), d.y.data(),
                                          d.z.data(), out.data());
        benchmark::DoNotOptimize(out.data());
    });
}

}  // namespace

// HSH and Makhotkin: 2..5 bands (4, 9, 16, 25 functions); 64 and 65 bands one call at a time.
BENCHMARK_TEMPLATE(one_call, HSH)->Arg(4)->Arg(9)->Arg(16)->Arg(25)->Arg(64 * 64)->Arg(65 * 65);
BENCHMARK_TEMPLATE(batch, HSH)->Arg(4)->Arg(9)->Arg(16)->Arg(25)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, HSH)->Arg(4)->Arg(9)->Arg(16)->Arg(25)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(one_call, Makhotkin)
    ->Arg(4)
    ->Arg(9)
    ->Arg(16)
    ->Arg(25)
    ->Arg(64 * 64)
    ->Arg(65 * 65);
BENCHMARK_TEMPLATE(batch, Makhotkin)
    ->Arg(4)
    ->Arg(9)
    ->Arg(16)
    ->Arg(25)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, Makhotkin)
    ->Arg(4)
    ->Arg(9)
    ->Arg(16)
    ->Arg(25)
    ->Unit(benchmark::kMillisecond);
// Zernike: 2..5 bands (3, 6, 10, 15 functions); 64 and 65 bands (2080, 2145) one call at a time.
BENCHMARK_TEMPLATE(one_call, Zernike)->Arg(3)->Arg(6)->Arg(10)->Arg(15)->Arg(2080)->Arg(2145);
BENCHMARK_TEMPLATE(batch, Zernike)->Arg(3)->Arg(6)->Arg(10)->Arg(15)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, Zernike)
    ->Arg(3)
    ->Arg(6)
    ->Arg(10)
    ->Arg(15)
    ->Unit(benchmark::kMillisecond);
// H-basis, modified H-basis: 4 and 6 functions; HL2: 3.
BENCHMARK_TEMPLATE(one_call, HBasis)->Arg(4)->Arg(6);
BENCHMARK_TEMPLATE(batch, HBasis)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, HBasis)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(one_call, HBasisMod)->Arg(4)->Arg(6);
BENCHMARK_TEMPLATE(batch, HBasisMod)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, HBasisMod)->Arg(4)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(one_call, HL2)->Arg(3);
BENCHMARK_TEMPLATE(batch, HL2)->Arg(3)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, HL2)->Arg(3)->Unit(benchmark::kMillisecond);

BENCHMARK_TEMPLATE(one_call, AmbientDiceBezier)->Arg(30)->Arg(36);
BENCHMARK_TEMPLATE(batch, AmbientDiceBezier)->Arg(30)->Arg(36)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, AmbientDiceBezier)->Arg(30)->Arg(36)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(batch, AmbientDiceBezierNormalized)->Arg(36)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(one_call, AmbientDiceLinear)->Arg(10)->Arg(12);
BENCHMARK_TEMPLATE(batch, AmbientDiceLinear)->Arg(10)->Arg(12)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(sum_batch, AmbientDiceLinear)->Arg(10)->Arg(12)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
