// Benchmarks of real SH evaluation (basis/sh.hpp). Items are directions: items_per_second is
// directions per second, so ns per direction = 1e9 / items_per_second.
//   one_call:   sh::eval<N> (normalising) called once per direction, results consumed
//   runtime:    sh::eval(bands, ...) with the band count known only at run time
//   columns:    the column recurrence (above 256 bands) at 31 and 100 bands, for the ratio
//   batch:      sh::eval_batch over 512 (in cache) or 1M directions (SoA in and out, SIMD)
//   batch_aos:  sh::eval_batch_aos, the same directions interleaved (x y z x y z ...), the same
//               output: its ratio to batch in one run is the cost of the interleaved input
//   memory_floor: the loads and stores of batch, in its order, with no arithmetic
//   sum_batch:  sh::eval_sum_batch over 4096 (in cache) or 1M directions (sum c_i y_i, the y_i
//               not stored)
#include <benchmark/benchmark.h>

#include <new>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <vector>

namespace {

// Every array starts on a 64-byte boundary, so that an AVX-512 batch is one cache line and the
// results do not depend on where the heap (16-byte aligned) puts the arrays.
template <class T>
struct Aligned64 {
    using value_type = T;
    Aligned64() = default;
    template <class U>
    Aligned64(const Aligned64<U>&) noexcept {}
    T* allocate(std::size_t n) {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t(64)));
    }
    void deallocate(T* p, std::size_t) noexcept { ::operator delete(p, std::align_val_t(64)); }
    template <class U>
    bool operator==(const Aligned64<U>&) const noexcept {
        return true;
    }
    template <class U>
    bool operator!=(const Aligned64<U>&) const noexcept {
        return false;
    }
};
template <class T>
using vec = std::vector<T, Aligned64<T>>;

template <class T>
struct Dirs {
    vec<T> x, y, z;
    explicit Dirs(std::size_t n) {
        std::mt19937 rng(1);
        std::normal_distribution<double> g;
        for (std::size_t i = 0; i < n; ++i) {
            double a = g(rng), b = g(rng), c = g(rng);
            const double r = std::sqrt(a * a + b * b + c * c);
            x.push_back(T(a / r));
            y.push_back(T(b / r));
            z.push_back(T(c / r));
        }
    }
};

// Unit = true: sh::eval_unit<N> (no normalisation); false: sh::eval<N> (normalising).
template <int N, class T, bool Unit>
void one_call_impl(benchmark::State& st) {
    const Dirs<T> d(4096);
    T out[N * N];
    for (auto _ : st) {
        for (std::size_t i = 0; i < 4096; ++i) {
            if constexpr (Unit)
                sphbasis::sh::eval_unit<N>(d.x[i], d.y[i], d.z[i], out);
            else
                sphbasis::sh::eval<N>(d.x[i], d.y[i], d.z[i], out);
            // Forces the stores of this call (a compiler barrier), with no dependency between
            // calls: independent calls overlap in the CPU as they do in a user's loop.
            benchmark::DoNotOptimize(out);
        }
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) * 4096);
}
template <int N, class T>
void one_call(benchmark::State& st) {
    one_call_impl<N, T, false>(st);
}
template <int N, class T>
void one_call_unit(benchmark::State& st) {
    one_call_impl<N, T, true>(st);
}

template <class T>
void runtime(benchmark::State& st) {
    const int bands = static_cast<int>(st.range(0));
    const std::size_t n = bands > 20 ? 256 : 4096;
    const Dirs<T> d(n);
    vec<T> out(static_cast<std::size_t>(bands * bands));
    for (auto _ : st) {
        for (std::size_t i = 0; i < n; ++i) {
            sphbasis::sh::eval(bands, d.x[i], d.y[i], d.z[i], out.data());
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

// The column recurrence (the path above 256 bands) at a band count the row recurrence also
// serves: the ratio runtime<double>/N : columns/N is what the row path saves.
void columns(benchmark::State& st) {
    const int bands = static_cast<int>(st.range(0));
    const std::size_t n = 256;
    const Dirs<double> d(n);
    vec<double> out(static_cast<std::size_t>(bands * bands));
    for (auto _ : st) {
        for (std::size_t i = 0; i < n; ++i) {
            sphbasis::sh::detail::eval_columns(bands, d.x[i], d.y[i], d.z[i], [&](int k, double v) {
                out[static_cast<std::size_t>(k)] = v;
            });
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

// range(0) bands, range(1) directions: 1M (output in DRAM) or 512 (output stays in cache: the
// compute cost without the memory traffic of writing n^2 floats per direction).
template <class T>
void batch(benchmark::State& st) {
    const int bands = static_cast<int>(st.range(0));
    const std::size_t n = static_cast<std::size_t>(st.range(1));
    // A stride of n + 16: with a power-of-two stride every function's output row maps to the
    // same cache sets and 64 rows thrash them (measured 2.5x slower at 8 bands).
    const std::size_t stride = n + 16;
    const Dirs<T> d(n);
    vec<T> out(stride * static_cast<std::size_t>(bands * bands));
    for (auto _ : st) {
        sphbasis::sh::eval_batch(bands, n, d.x.data(), d.y.data(), d.z.data(), out.data(), stride);
        benchmark::DoNotOptimize(out.data());
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

// batch() with the directions interleaved (AoS), deinterleaved by sh::eval_batch_aos.
template <class T>
void batch_aos(benchmark::State& st) {
    const int bands = static_cast<int>(st.range(0));
    const std::size_t n = static_cast<std::size_t>(st.range(1));
    const std::size_t stride = n + 16;
    const Dirs<T> d(n);
    vec<T> xyz(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        xyz[3 * i] = d.x[i];
        xyz[3 * i + 1] = d.y[i];
        xyz[3 * i + 2] = d.z[i];
    }
    vec<T> out(stride * static_cast<std::size_t>(bands * bands));
    for (auto _ : st) {
        sphbasis::sh::eval_batch_aos(bands, n, xyz.data(), out.data(), stride);
        benchmark::DoNotOptimize(out.data());
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

// The memory reference for batch(): the same loads and stores in the same order (one SIMD batch
// of directions read, then one vector store per function row), with no arithmetic. Over 1M
// directions batch() runs at about this speed; it is a reference, not a strict bound (at 8
// bands the kernel measured faster).
template <int Bands, class T>
void memory_floor(benchmark::State& st) {
    using V = sphbasis::batch<T>;
    constexpr std::size_t W = static_cast<std::size_t>(V::size);
    constexpr int bands = Bands;  // compile-time: the row stores unroll as batch()'s do
    const std::size_t n = 1 << 20, stride = n + 16;
    const Dirs<T> d(n);
    vec<T> out(stride * static_cast<std::size_t>(bands * bands));
    for (auto _ : st) {
        for (std::size_t i = 0; i < n; i += W) {
            const V v = V::load(d.x.data() + i) + V::load(d.y.data() + i) + V::load(d.z.data() + i);
            for (int k = 0; k < bands * bands; ++k)
                v.store(out.data() + static_cast<std::size_t>(k) * stride + i);
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

// The expansion: range(0) bands, range(1) directions (4096 stay in L1/L2: compute cost only).
template <class T>
void sum_batch(benchmark::State& st) {
    const int bands = static_cast<int>(st.range(0));
    const std::size_t n = static_cast<std::size_t>(st.range(1));
    const Dirs<T> d(n);
    vec<T> c(static_cast<std::size_t>(bands * bands), T(0.5)), out(n);
    for (auto _ : st) {
        sphbasis::sh::eval_sum_batch(bands, c.data(), n, d.x.data(), d.y.data(), d.z.data(),
                                     out.data());
        benchmark::DoNotOptimize(out.data());
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations() * n));
}

}  // namespace

BENCHMARK_TEMPLATE(one_call, 3, float);
BENCHMARK_TEMPLATE(one_call, 8, float);
BENCHMARK_TEMPLATE(one_call, 3, double);
BENCHMARK_TEMPLATE(one_call_unit, 3, float);
BENCHMARK_TEMPLATE(one_call_unit, 8, float);
BENCHMARK_TEMPLATE(runtime, float)->Arg(3)->Arg(8);
BENCHMARK_TEMPLATE(runtime, double)->Arg(31)->Arg(100);
BENCHMARK(columns)->Arg(31)->Arg(100);
BENCHMARK_TEMPLATE(batch, float)->ArgsProduct({{3, 8, 16}, {512, 1 << 20}});
BENCHMARK_TEMPLATE(batch_aos, float)->ArgsProduct({{3, 8, 16}, {512, 1 << 20}});
BENCHMARK_TEMPLATE(memory_floor, 3, float);
BENCHMARK_TEMPLATE(memory_floor, 8, float);
BENCHMARK_TEMPLATE(memory_floor, 16, float);
BENCHMARK_TEMPLATE(sum_batch, float)->ArgsProduct({{3, 8}, {4096, 1 << 20}});

BENCHMARK_MAIN();
