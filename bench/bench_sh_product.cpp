// Benchmarks of the SH product (ops/sh_product.hpp), float. Items are products: items_per_second
// is products per second (n x n -> n bands, DirectXMath's XMSHMultiplyN), over 1024 pairs of
// coefficient vectors that stay in cache.
//   unrolled: sh::product<N> (generated code, ops/sh_product_fixed.hpp; for float with AVX2 + FMA
//             at 3..6 bands the Gauss-Legendre ring kernel, ops/sh_product_rings.hpp)
//   generic:  sh::product(table, ...), the sparse kernel over a TripleTable(N, N, N)
//   runtime:  sh::product(N, ...), band count known at run time (dispatches to the unrolled code)
//   rgb:      unrolled, RGB lighting times scalar visibility (3 floats a coefficient)
// The ratio unrolled/generic at each N is the claim "the unrolled product beats the generic one":
// read both from the same run.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <random>
#include <sphbasis/ops/sh_product.hpp>
#include <vector>

namespace {

constexpr std::size_t pairs = 1024;

struct Rgb {
    float r = 0, g = 0, b = 0;
    friend Rgb operator+(const Rgb& x, const Rgb& y) { return {x.r + y.r, x.g + y.g, x.b + y.b}; }
    friend Rgb operator*(const Rgb& x, float s) { return {x.r * s, x.g * s, x.b * s}; }
};

template <class C>
std::vector<C> random_vectors(std::size_t count, std::uint32_t seed);

template <>
std::vector<float> random_vectors<float>(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> v(count);
    for (auto& x : v) x = u(rng);
    return v;
}

template <>
std::vector<Rgb> random_vectors<Rgb>(std::size_t count, std::uint32_t seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<Rgb> v(count);
    for (auto& x : v) x = {u(rng), u(rng), u(rng)};
    return v;
}

enum class Kind { unrolled, generic, runtime };

template <int N, Kind K, class C = float>
void product(benchmark::State& st) {
    constexpr std::size_t n2 = N * N;
    const auto a = random_vectors<C>(pairs * n2, 1);
    const auto b = random_vectors<float>(pairs * n2, 2);
    std::vector<C> out(pairs * n2);
    const sphbasis::sh::TripleTable& table = sphbasis::sh::triple_table(N, N, N);
    for (auto _ : st) {
        for (std::size_t p = 0; p < pairs; ++p) {
            const C* ap = a.data() + p * n2;
            const float* bp = b.data() + p * n2;
            C* op = out.data() + p * n2;
            if constexpr (K == Kind::unrolled)
                sphbasis::sh::product<N>(ap, bp, op);
            else if constexpr (K == Kind::generic)
                sphbasis::sh::product(table, ap, bp, op);
            else
                sphbasis::sh::product(N, ap, bp, op);
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) *
                         static_cast<std::int64_t>(pairs));
    st.counters["nonzeros"] = static_cast<double>(table.size());
}

}  // namespace

#define SPHBASIS_BENCH_PRODUCT(N)                                                 \
    BENCHMARK_TEMPLATE(product, N, Kind::unrolled)->Name("product/unrolled/" #N); \
    BENCHMARK_TEMPLATE(product, N, Kind::generic)->Name("product/generic/" #N);   \
    BENCHMARK_TEMPLATE(product, N, Kind::runtime)->Name("product/runtime/" #N);   \
    BENCHMARK_TEMPLATE(product, N, Kind::unrolled, Rgb)->Name("product/rgb_unrolled/" #N);

SPHBASIS_BENCH_PRODUCT(3)
SPHBASIS_BENCH_PRODUCT(4)
SPHBASIS_BENCH_PRODUCT(5)
SPHBASIS_BENCH_PRODUCT(6)

BENCHMARK_MAIN();
