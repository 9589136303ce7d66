// Benchmarks of the L x H tables (ops/lxh_table.hpp). Items are texels: items_per_second is
// texels per second of a table build over a 16 x 16 x 6 DX10 cube map, RGB lighting of N bands,
// visibility of K bands, the exact N + K - 1 cosine bands, float output.
//   direct:    per texel, the clamped-cosine SH vector c(n) and the sparse SH product
//              proj_K(L c(n)) per channel (sh::product over the Gaunt table (N, C, K)), buffers
//              preallocated: the "direct per-texel product"
//   rowscale:  build_lxh_table(plain): the product matrix P_L once (timed), then P_L c(n) per
//              texel
//   symmetric: build_lxh_table with the orbits under z negation and 90 degree z rotations
//              (make_lxh_orbits once per parameterization, outside the timing: it does not
//              depend on the lighting)
// Every variant writes into a table allocated once (a rebuild per lighting change).
// lxh_ratio times the three alternately in one run, in thread CPU time (the machine may be
// shared), and reports ns per texel and the ratios as counters (direct_ns, rowscale_ns,
// symmetric_ns, direct_over_rowscale, rowscale_over_symmetric): the claims "row scaling is
// faster than the direct product" and "the symmetries make it faster" are those ratios.
#include <benchmark/benchmark.h>

#include <ctime>
#include <random>
#include <sphbasis/ops/lxh_table.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <vector>

namespace {

using namespace sphbasis;

std::vector<double> lighting(int bands) {
    std::mt19937 rng(1);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<double> l(3 * static_cast<std::size_t>(bands * bands));
    for (double& v : l) v = u(rng);
    return l;
}

/// The direct per-texel product into a float table of the same layout.
void direct_table(const param::CubeMap<double>& p, int nb, const std::vector<double>& rgb, int kb,
                  std::vector<float>& table) {
    const int cb = nb + kb - 1;
    const sh::TripleTable& t = sh::triple_table(nb, cb, kb);
    std::vector<double> a(static_cast<std::size_t>(cb));
    clamped_cosine_factors(cb, a.data());
    const int nn = nb * nb, kk = kb * kb;
    std::vector<double> c(static_cast<std::size_t>(cb * cb)), ch(3 * static_cast<std::size_t>(nn)),
        r(static_cast<std::size_t>(kk));
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < nn; ++i)
            ch[static_cast<std::size_t>(k * nn + i)] = rgb[static_cast<std::size_t>(3 * i + k)];
    table.resize(p.texel_count() * 3 * static_cast<std::size_t>(kk));
    for (int face = 0; face < 6; ++face)
        for (int row = 0; row < p.height(); ++row)
            for (int col = 0; col < p.width(); ++col) {
                const auto d = p.texel_direction(face, col, row);
                sh::eval(cb, d.x, d.y, d.z, c.data());
                for (int l = 0; l < cb; ++l)
                    for (int m = -l; m <= l; ++m)
                        c[static_cast<std::size_t>(sh::index(l, m))] *=
                            constants::pi * a[static_cast<std::size_t>(l)];
                float* out =
                    table.data() + p.texel_index(face, col, row) * 3 * static_cast<std::size_t>(kk);
                for (int k = 0; k < 3; ++k) {
                    sh::product(t, ch.data() + k * nn, c.data(), r.data());
                    for (int q = 0; q < kk; ++q)
                        out[3 * q + k] = static_cast<float>(r[static_cast<std::size_t>(q)]);
                }
            }
}

enum class Kind { direct, rowscale, symmetric };

double cpu_ns() {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) * 1e9 + static_cast<double>(t.tv_nsec);
}

template <Kind K>
void lxh_build(benchmark::State& st) {
    const int nb = static_cast<int>(st.range(0)), kb = static_cast<int>(st.range(1));
    const param::CubeMap<double> cube(16);
    const auto rgb = lighting(nb);
    std::vector<float> table;
    const LxhOrbits orbits = make_lxh_orbits(cube);
    auto tab = build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb));
    for (auto _ : st) {
        if constexpr (K == Kind::direct) {
            direct_table(cube, nb, rgb, kb, table);
            benchmark::DoNotOptimize(table.data());
        } else if constexpr (K == Kind::rowscale) {
            // The product matrix is part of the build (once per lighting).
            build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb), LxhConstruction::plain, tab);
            benchmark::DoNotOptimize(tab.data.data());
        } else {
            build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb), orbits, tab);
            benchmark::DoNotOptimize(tab.data.data());
        }
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) *
                         static_cast<std::int64_t>(cube.texel_count()));
}

void lxh_ratio(benchmark::State& st) {
    const int nb = static_cast<int>(st.range(0)), kb = static_cast<int>(st.range(1));
    const param::CubeMap<double> cube(16);
    const auto rgb = lighting(nb);
    const double texels = static_cast<double>(cube.texel_count());
    std::vector<float> table;
    const LxhOrbits orbits = make_lxh_orbits(cube);
    auto a = build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb));
    auto b = a;
    direct_table(cube, nb, rgb, kb, table);
    double td = 0, tr = 0, ts = 0;
    for (auto _ : st) {
        const double t0 = cpu_ns();
        direct_table(cube, nb, rgb, kb, table);
        benchmark::DoNotOptimize(table.data());
        const double t1 = cpu_ns();
        build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb), LxhConstruction::plain, a);
        benchmark::DoNotOptimize(a.data.data());
        const double t2 = cpu_ns();
        build_lxh_table(cube, lxh_matrix(nb, rgb.data(), kb), orbits, b);
        benchmark::DoNotOptimize(b.data.data());
        const double t3 = cpu_ns();
        td += t1 - t0;
        tr += t2 - t1;
        ts += t3 - t2;
    }
    const double n = static_cast<double>(st.iterations()) * texels;
    st.counters["direct_ns"] = td / n;
    st.counters["rowscale_ns"] = tr / n;
    st.counters["symmetric_ns"] = ts / n;
    st.counters["direct_over_rowscale"] = td / tr;
    st.counters["rowscale_over_symmetric"] = tr / ts;
}

void bands(benchmark::internal::Benchmark* b) {
    b->Args({3, 3})->Args({3, 4})->Args({4, 4})->Args({3, 6})->Args({6, 6});
}

}  // namespace

BENCHMARK_TEMPLATE(lxh_build, Kind::direct)->Apply(bands)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(lxh_build, Kind::rowscale)->Apply(bands)->Unit(benchmark::kMicrosecond);
BENCHMARK_TEMPLATE(lxh_build, Kind::symmetric)->Apply(bands)->Unit(benchmark::kMicrosecond);
BENCHMARK(lxh_ratio)->Apply(bands)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
