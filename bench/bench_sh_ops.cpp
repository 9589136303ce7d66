// Benchmarks of the SH operators (ops/sh_rotation, sh_convolution, sh_lights), float.
// Items are what the name says: rotations (one coefficient vector rotated), lights (one light
// turned into coefficients), texels (of a projected environment map) or normals (irradiance
// evaluations); ns per item = 1e9 / items_per_second.
//   rotation_build_apply<N>: Rotation::from_matrix(quaternion) + apply, N bands
//   rotation_from_matrix_apply<N>: Rotation::from_matrix(N, R) + apply (checked; <= 8 bands:
//                            rotate<N>, D never formed)
//   rotate_matrix<N>:        sh::rotate(N, R, in, out), checked (vs fixed_rotate: the checks)
//   orthonormal_check<Fast>: max |R R^T - I| check alone, straight-line vs generic loop
//   rotate_streaming<N>:     sh::rotate_quaternion (<= 8 bands: rotate<N>; above: band by band)
//   rotation_apply<N>:       apply of a prebuilt rotation (one channel, and RGB)
//   rotation_prepared_apply<N>: the same after Rotation::prepare() (apply multiplies by D)
//   fixed_rotation_build_apply<N>: FixedRotation<N, float>::from_quaternion + apply (generated)
//   fixed_rotate<N>:         sh::rotate<N>(Mat3, in, out), the matrices precomputed (D never
//                            formed: R, R Q R^T, Euler factorisation; one channel, and RGB)
//   fixed_rotation_apply<N>: apply of a prebuilt FixedRotation (one channel, and RGB)
//   *_light_fixed:           the analytic lights with a compile-time band count (3), float RGB
//   rotate_z<N>:             rotation about z (cos/sin of m phi), for comparison
//   *_light<3>:              the analytic lights at 3 bands, float RGB
//   cubemap_project:         6 x 64 x 64 cube map (float RGB) to 3 bands
//   latlong_project:         128 x 64 lat-long map (float RGB) to 3 bands
//   irradiance_rh / irradiance_convolve: E(n) from 9 coefficients, RH quadratic form vs
//                            clamped-cosine convolution + eval_sum
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <sphbasis/ops/sh_convolution.hpp>
#include <sphbasis/ops/sh_lights.hpp>
#include <sphbasis/ops/sh_rotation.hpp>
#include <sphbasis/ops/sh_rotation_fixed.hpp>
#include <vector>

namespace sh = sphbasis::sh;

namespace {

struct RGB {
    float r = 0, g = 0, b = 0;
};
inline RGB operator+(const RGB& a, const RGB& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline RGB operator*(const RGB& a, float s) { return {a.r * s, a.g * s, a.b * s}; }

constexpr std::size_t kCount = 256;

// name<N> (one float channel, all 0.5) and name_rgb<N> (RGB) from name_of<N>(state, fill).
#define SPHBASIS_BENCH_ONE_AND_RGB(name)          \
    template <int N>                              \
    void name(benchmark::State& st) {             \
        name##_of<N>(st, 0.5f);                   \
    }                                             \
    template <int N>                              \
    void name##_rgb(benchmark::State& st) {       \
        name##_of<N>(st, RGB{0.5f, 0.25f, 1.0f}); \
    }

std::vector<std::array<float, 4>> quaternions() {
    std::mt19937 rng(1);
    std::normal_distribution<float> g;
    std::vector<std::array<float, 4>> q(kCount);
    for (auto& v : q) v = {g(rng), g(rng), g(rng), g(rng)};
    return q;
}

/// The rotation matrices of quaternions().
std::vector<sh::Mat3<float>> matrices() {
    std::vector<sh::Mat3<float>> m;
    for (const auto& v : quaternions())
        m.push_back(sh::matrix_from_quaternion(v[0], v[1], v[2], v[3]));
    return m;
}

std::vector<sphbasis::vec3<float>> directions() {
    std::mt19937 rng(2);
    std::normal_distribution<float> g;
    std::vector<sphbasis::vec3<float>> d(kCount);
    for (auto& v : d) {
        float x = g(rng), y = g(rng), z = g(rng);
        const float r = std::sqrt(x * x + y * y + z * z);
        v = {x / r, y / r, z / r};
    }
    return d;
}

/// Calls f(q) for each of the kCount quaternions per iteration; items are quaternions.
template <class F>
void per_quaternion(benchmark::State& st, F&& f) {
    const auto q = quaternions();
    for (auto _ : st)
        for (const auto& v : q) f(v);
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

template <int N>
void rotation_build_apply(benchmark::State& st) {
    std::vector<float> in(N * N, 0.5f), out(N * N);
    per_quaternion(st, [&](const std::array<float, 4>& v) {
        const auto d = sh::rotation_from_quaternion(N, v[0], v[1], v[2], v[3]);
        d.apply(in.data(), out.data());
        benchmark::DoNotOptimize(out.data());
    });
}

/// The checked matrix path users of DirectXMath take: Rotation::from_matrix(N, R) + apply,
/// kCount precomputed matrices (at N <= 8: the checks, then rotate<N>; D never formed).
template <int N>
void rotation_from_matrix_apply(benchmark::State& st) {
    const std::vector<sh::Mat3<float>> m = matrices();
    std::vector<float> in(N * N, 0.5f), out(N * N);
    for (auto _ : st) {
        for (const auto& r : m) {
            const auto d = sh::Rotation<float>::from_matrix(N, r);
            d.apply(in.data(), out.data());
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

/// sh::rotate(N, R, in, out) (checked: bands range, orthonormality, null buffers) by kCount
/// precomputed matrices; compare with fixed_rotate<N> (no checks) for the cost of the checks.
template <int N>
void rotate_matrix(benchmark::State& st) {
    const std::vector<sh::Mat3<float>> m = matrices();
    std::vector<float> in(N * N, 0.5f), out(N * N);
    for (auto _ : st) {
        for (const auto& r : m) {
            sh::rotate(N, r, in.data(), out.data());
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

/// The orthonormality check alone per matrix: the straight-line test of the checked entry
/// points (Fast) against the generic loop of core/frame.hpp.
template <bool Fast>
void orthonormal_check(benchmark::State& st) {
    const std::vector<sh::Mat3<float>> m = matrices();
    const float tol = sphbasis::detail::default_orthonormal_tolerance<float>();
    for (auto _ : st) {
        for (const auto& r : m) {
            if constexpr (Fast)
                sh::detail::check_orthonormal_fast(r, tol, "bench");
            else
                sphbasis::detail::check_orthonormal(r, tol, "bench");
            benchmark::ClobberMemory();
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

/// sh::rotate_quaternion of N^2 coefficients of type C, all `fill`.
template <int N, class C>
void rotate_streaming_of(benchmark::State& st, const C& fill) {
    std::vector<C> in(N * N, fill), out(N * N);
    per_quaternion(st, [&](const std::array<float, 4>& v) {
        sh::rotate_quaternion(N, v[0], v[1], v[2], v[3], in.data(), out.data());
        benchmark::DoNotOptimize(out.data());
    });
}
SPHBASIS_BENCH_ONE_AND_RGB(rotate_streaming)

/// The prebuilt rotation d applied to kCount vectors of N^2 coefficients of type C, all `fill`.
template <int N, class D, class C>
void apply_prebuilt(benchmark::State& st, const D& d, const C& fill) {
    std::vector<C> in(N * N * kCount, fill), out(N * N * kCount);
    for (auto _ : st) {
        for (std::size_t i = 0; i < kCount; ++i)
            d.apply(in.data() + i * N * N, out.data() + i * N * N);
        benchmark::DoNotOptimize(out.data());
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

/// A prebuilt Rotation applied to kCount vectors of N^2 coefficients of type C, all `fill`.
template <int N, class C>
void rotation_apply_of(benchmark::State& st, const C& fill) {
    const auto q = quaternions();
    apply_prebuilt<N>(st, sh::rotation_from_quaternion(N, q[0][0], q[0][1], q[0][2], q[0][3]),
                      fill);
}
SPHBASIS_BENCH_ONE_AND_RGB(rotation_apply)

/// The same rotation after prepare(): apply multiplies by D (compare with rotation_apply, the
/// factored rotate<N>, and with rotation_from_matrix_apply, build + apply).
template <int N, class C>
void rotation_prepared_apply_of(benchmark::State& st, const C& fill) {
    const auto q = quaternions();
    auto d = sh::rotation_from_quaternion(N, q[0][0], q[0][1], q[0][2], q[0][3]);
    d.prepare();
    apply_prebuilt<N>(st, d, fill);
}
SPHBASIS_BENCH_ONE_AND_RGB(rotation_prepared_apply)

template <int N>
void fixed_rotation_build_apply(benchmark::State& st) {
    std::vector<float> in(N * N, 0.5f), out(N * N);
    per_quaternion(st, [&](const std::array<float, 4>& v) {
        const auto d = sh::FixedRotation<N, float>::from_quaternion(v[0], v[1], v[2], v[3]);
        d.apply(in.data(), out.data());
        benchmark::DoNotOptimize(out.data());
    });
}

/// sh::rotate<N> of N^2 coefficients of type C (all `fill`) by kCount precomputed matrices.
template <int N, class C>
void fixed_rotate_of(benchmark::State& st, const C& fill) {
    const std::vector<sh::Mat3<float>> m = matrices();
    std::vector<C> in(N * N, fill), out(N * N);
    for (auto _ : st) {
        for (const auto& r : m) {
            sh::rotate<N>(r, in.data(), out.data());
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}
SPHBASIS_BENCH_ONE_AND_RGB(fixed_rotate)

/// A prebuilt FixedRotation applied to kCount vectors of N^2 coefficients of type C.
template <int N, class C>
void fixed_rotation_apply_of(benchmark::State& st, const C& fill) {
    const auto q = quaternions();
    apply_prebuilt<N>(
        st, sh::FixedRotation<N, float>::from_quaternion(q[0][0], q[0][1], q[0][2], q[0][3]), fill);
}
SPHBASIS_BENCH_ONE_AND_RGB(fixed_rotation_apply)

template <int N>
void rotate_z(benchmark::State& st) {
    std::vector<float> in(N * N, 0.5f), out(N * N);
    float a = 0.1f;
    for (auto _ : st) {
        for (std::size_t i = 0; i < kCount; ++i) {
            sh::rotate_z(N, a, in.data(), out.data());
            a += 0.01f;
            benchmark::DoNotOptimize(out.data());
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

template <class Light>
void light_bench(benchmark::State& st, Light&& light) {
    const auto d = directions();
    RGB out[9];
    for (auto _ : st) {
        for (const auto& v : d) {
            light(v, out);
            benchmark::DoNotOptimize(out);
        }
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

void directional_light(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::directional_light(3, v.x, v.y, v.z, RGB{1, 2, 3}, out);
    });
}
void cone_light(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::cone_light(3, v.x, v.y, v.z, 0.3f, RGB{1, 2, 3}, out);
    });
}
void spherical_light(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::spherical_light(3, 4 * v.x, 4 * v.y, 4 * v.z, 1.0f, RGB{1, 2, 3}, out);
    });
}
void directional_light_fixed(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::directional_light<3>(v.x, v.y, v.z, RGB{1, 2, 3}, out);
    });
}
void cone_light_fixed(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::cone_light<3>(v.x, v.y, v.z, 0.3f, RGB{1, 2, 3}, out);
    });
}
void spherical_light_fixed(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::spherical_light<3>(4 * v.x, 4 * v.y, 4 * v.z, 1.0f, RGB{1, 2, 3}, out);
    });
}
void hemisphere_light_fixed(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::hemisphere_light<3>(v.x, v.y, v.z, RGB{1, 2, 3}, RGB{0.1f, 0.2f, 0.3f}, out);
    });
}
void hemisphere_light(benchmark::State& st) {
    light_bench(st, [](const sphbasis::vec3<float>& v, RGB* out) {
        sh::hemisphere_light(3, v.x, v.y, v.z, RGB{1, 2, 3}, RGB{0.1f, 0.2f, 0.3f}, out);
    });
}

void cubemap_project(benchmark::State& st) {
    const int n = 64;
    std::vector<RGB> tex(6 * n * n);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0, 1);
    for (auto& t : tex) t = {u(rng), u(rng), u(rng)};
    RGB out[9];
    for (auto _ : st) {
        sh::project_cubemap(3, n, tex.data(), out);
        benchmark::DoNotOptimize(out);
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) * 6 * n * n);
}

void latlong_project(benchmark::State& st) {
    const int w = 128, h = 64;
    std::vector<RGB> tex(static_cast<std::size_t>(w * h));
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0, 1);
    for (auto& t : tex) t = {u(rng), u(rng), u(rng)};
    RGB out[9];
    for (auto _ : st) {
        sh::project_latlong(3, w, h, tex.data(), out);
        benchmark::DoNotOptimize(out);
    }
    st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()) * w * h);
}

void irradiance_rh(benchmark::State& st) {
    const auto d = directions();
    float L[9] = {1, 0.2f, 0.3f, -0.1f, 0.05f, 0.1f, -0.2f, 0.02f, 0.03f};
    const auto M = sh::irradiance_matrix<float>(L);
    float acc = 0;
    for (auto _ : st) {
        for (const auto& v : d) acc += sh::eval_irradiance_matrix(M, v.x, v.y, v.z);
        benchmark::DoNotOptimize(acc);
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

void irradiance_convolve(benchmark::State& st) {
    const auto d = directions();
    float L[9] = {1, 0.2f, 0.3f, -0.1f, 0.05f, 0.1f, -0.2f, 0.02f, 0.03f}, E[9];
    const auto a = sh::clamped_cosine_kernel<float>(3);
    sh::convolve(3, a.data(), L, E);
    float acc = 0;
    for (auto _ : st) {
        for (const auto& v : d) acc += sh::eval_sum(3, E, v.x, v.y, v.z);
        benchmark::DoNotOptimize(acc);
    }
    st.SetItemsProcessed(st.iterations() * static_cast<std::int64_t>(kCount));
}

}  // namespace

BENCHMARK_TEMPLATE(rotation_build_apply, 3);
BENCHMARK_TEMPLATE(rotation_build_apply, 6);
BENCHMARK_TEMPLATE(rotation_from_matrix_apply, 3);
BENCHMARK_TEMPLATE(rotation_from_matrix_apply, 6);
BENCHMARK_TEMPLATE(rotate_matrix, 3);
BENCHMARK_TEMPLATE(rotate_matrix, 6);
BENCHMARK_TEMPLATE(orthonormal_check, true);
BENCHMARK_TEMPLATE(orthonormal_check, false);
BENCHMARK_TEMPLATE(rotate_streaming, 3);
BENCHMARK_TEMPLATE(rotate_streaming, 6);
BENCHMARK_TEMPLATE(rotate_streaming_rgb, 3);
BENCHMARK_TEMPLATE(rotate_streaming_rgb, 6);
BENCHMARK_TEMPLATE(rotation_apply, 3);
BENCHMARK_TEMPLATE(rotation_apply, 6);
BENCHMARK_TEMPLATE(rotation_apply_rgb, 3);
BENCHMARK_TEMPLATE(rotation_apply_rgb, 6);
BENCHMARK_TEMPLATE(rotation_prepared_apply, 3);
BENCHMARK_TEMPLATE(rotation_prepared_apply, 6);
BENCHMARK_TEMPLATE(rotation_prepared_apply_rgb, 3);
BENCHMARK_TEMPLATE(rotation_prepared_apply_rgb, 6);
BENCHMARK_TEMPLATE(fixed_rotation_build_apply, 3);
BENCHMARK_TEMPLATE(fixed_rotation_build_apply, 6);
BENCHMARK_TEMPLATE(fixed_rotate, 3);
BENCHMARK_TEMPLATE(fixed_rotate, 6);
BENCHMARK_TEMPLATE(fixed_rotate_rgb, 3);
BENCHMARK_TEMPLATE(fixed_rotate_rgb, 6);
BENCHMARK_TEMPLATE(fixed_rotation_apply, 3);
BENCHMARK_TEMPLATE(fixed_rotation_apply, 6);
BENCHMARK_TEMPLATE(fixed_rotation_apply_rgb, 3);
BENCHMARK_TEMPLATE(fixed_rotation_apply_rgb, 6);
BENCHMARK(directional_light_fixed);
BENCHMARK(cone_light_fixed);
BENCHMARK(spherical_light_fixed);
BENCHMARK(hemisphere_light_fixed);
BENCHMARK_TEMPLATE(rotate_z, 3);
BENCHMARK_TEMPLATE(rotate_z, 6);
BENCHMARK(directional_light);
BENCHMARK(cone_light);
BENCHMARK(spherical_light);
BENCHMARK(hemisphere_light);
BENCHMARK(cubemap_project);
BENCHMARK(latlong_project);
BENCHMARK(irradiance_rh);
BENCHMARK(irradiance_convolve);

BENCHMARK_MAIN();
