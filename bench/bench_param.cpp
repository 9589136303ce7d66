// Benchmarks of the spherical parameterizations (param/) and the Toksvig factors
// (shading/toksvig.hpp). Items are directions (direction -> uv, bilinear lookup) or texels
// (Toksvig factor per texel), so the reports read as items per second.
//
//   build/bin/bench_param [--benchmark_format=json]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstddef>
#include <random>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/param/dual_orthographic.hpp>
#include <sphbasis/param/dual_paraboloid.hpp>
#include <sphbasis/param/latlong.hpp>
#include <sphbasis/param/octahedral.hpp>
#include <sphbasis/shading/toksvig.hpp>
#include <vector>

namespace {

using namespace sphbasis;
using namespace sphbasis::param;

constexpr std::size_t kDirs = 4096;
constexpr std::size_t kChannels = 9;  // a 3-band SH vector per texel

struct Dirs {
    std::vector<float> x, y, z;
};

const Dirs& directions() {
    static const Dirs d = [] {
        Dirs out;
        std::mt19937 rng(1);
        std::normal_distribution<float> g;
        for (std::size_t i = 0; i < kDirs; ++i) {
            float a = g(rng), b = g(rng), c = g(rng);
            const float l = std::sqrt(a * a + b * b + c * c);
            out.x.push_back(a / l);
            out.y.push_back(b / l);
            out.z.push_back(c / l);
        }
        return out;
    }();
    return d;
}

template <class P>
void bm_direction_to_uv(benchmark::State& state, const P& p) {
    const Dirs& d = directions();
    for (auto _ : state) {
        for (std::size_t i = 0; i < kDirs; ++i) {
            auto t = p.direction_to_uv(d.x[i], d.y[i], d.z[i]);
            benchmark::DoNotOptimize(t);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kDirs));
}

template <class P>
void bm_lookup(benchmark::State& state, const P& p) {
    const Dirs& d = directions();
    std::vector<float> table(p.texel_count() * kChannels);
    for (std::size_t k = 0; k < table.size(); ++k) table[k] = static_cast<float>(k % 7) * 0.25f;
    float out[kChannels];
    for (auto _ : state) {
        for (std::size_t i = 0; i < kDirs; ++i) {
            lookup(p, table.data(), kChannels, d.x[i], d.y[i], d.z[i], out);
            benchmark::DoNotOptimize(out);
        }
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(kDirs));
}

// 32 texels a side for the dual maps, 16 per cube face, 32 octahedral, 16 x 32 lat-long: the
// small tables Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009), find adequate.
void BM_uv_dual_paraboloid(benchmark::State& s) {
    bm_direction_to_uv(s, DualParaboloid<float>(32));
}
void BM_uv_dual_orthographic(benchmark::State& s) {
    bm_direction_to_uv(s, DualOrthographic<float>(32));
}
void BM_uv_cubemap(benchmark::State& s) { bm_direction_to_uv(s, CubeMap<float>(16)); }
void BM_uv_octahedral(benchmark::State& s) { bm_direction_to_uv(s, Octahedral<float>(32)); }
void BM_uv_latlong(benchmark::State& s) { bm_direction_to_uv(s, LatLong<float>(16)); }

void BM_lookup9_dual_paraboloid(benchmark::State& s) { bm_lookup(s, DualParaboloid<float>(32)); }
void BM_lookup9_dual_orthographic(benchmark::State& s) {
    bm_lookup(s, DualOrthographic<float>(32));
}
void BM_lookup9_cubemap_dx9(benchmark::State& s) {
    bm_lookup(s, CubeMap<float>(16, CubeFilter::dx9_clamped));
}
void BM_lookup9_cubemap_dx10(benchmark::State& s) {
    bm_lookup(s, CubeMap<float>(16, CubeFilter::dx10_seamless));
}
void BM_lookup9_octahedral_clamp(benchmark::State& s) {
    bm_lookup(s, Octahedral<float>(32, OctahedralFilter::clamp));
}
void BM_lookup9_octahedral_seamless(benchmark::State& s) {
    bm_lookup(s, Octahedral<float>(32, OctahedralFilter::seamless));
}
void BM_lookup9_latlong(benchmark::State& s) { bm_lookup(s, LatLong<float>(16)); }

BENCHMARK(BM_uv_dual_paraboloid);
BENCHMARK(BM_uv_dual_orthographic);
BENCHMARK(BM_uv_cubemap);
BENCHMARK(BM_uv_octahedral);
BENCHMARK(BM_uv_latlong);
BENCHMARK(BM_lookup9_dual_paraboloid);
BENCHMARK(BM_lookup9_dual_orthographic);
BENCHMARK(BM_lookup9_cubemap_dx9);
BENCHMARK(BM_lookup9_cubemap_dx10);
BENCHMARK(BM_lookup9_octahedral_clamp);
BENCHMARK(BM_lookup9_octahedral_seamless);
BENCHMARK(BM_lookup9_latlong);

// Toksvig factor per texel of a 256 x 256 mip level (lengths from a box-filtered noise map).
void BM_toksvig_factor_per_texel(benchmark::State& state) {
    const int n = 512;
    std::vector<vec3<float>> map(static_cast<std::size_t>(n * n));
    std::mt19937 rng(2);
    std::normal_distribution<float> g(0.0f, 0.3f);
    for (auto& v : map) {
        const float a = g(rng), b = g(rng), l = std::sqrt(a * a + b * b + 1.0f);
        v = {a / l, b / l, 1.0f / l};
    }
    const auto chain = toksvig::build_normal_mips(map.data(), n, n);
    const auto& level = chain[1];
    std::vector<float> out(level.length.size());
    for (auto _ : state) {
        for (std::size_t k = 0; k < out.size(); ++k)
            out[k] = toksvig::factor(level.length[k], 64.0f);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(out.size()));
}
BENCHMARK(BM_toksvig_factor_per_texel);

// The eq. 9 shading term per pixel from (Na.H, Na.Na), the ALU alternative to the 2D table.
void BM_toksvig_specular_from_dots(benchmark::State& state) {
    std::vector<float> nh(4096), nn(4096);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    for (std::size_t k = 0; k < nh.size(); ++k) {
        nn[k] = u(rng);
        nh[k] = u(rng) * std::sqrt(nn[k]);
    }
    for (auto _ : state) {
        for (std::size_t k = 0; k < nh.size(); ++k)
            benchmark::DoNotOptimize(toksvig::specular_from_dots(nh[k], nn[k], 64.0f));
    }
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                            static_cast<std::int64_t>(nh.size()));
}
BENCHMARK(BM_toksvig_specular_from_dots);

// Building the 2D table of eq. 9 (256 x 256 texels).
void BM_toksvig_table_256(benchmark::State& state) {
    toksvig::SpecularTableOptions o;
    o.shininess = 64;
    for (auto _ : state) benchmark::DoNotOptimize(toksvig::make_specular_table(o));
    state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * 256 * 256);
}
BENCHMARK(BM_toksvig_table_256);

}  // namespace

BENCHMARK_MAIN();
