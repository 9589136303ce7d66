// sphbasis against the libraries users would otherwise pick, in one Google Benchmark binary:
// DirectXMath's SHMath (XMSHEvalDirection, XMSHRotate, XMSHRotateZ, XMSHMultiplyN,
// XMSHEval*Light), google/spherical-harmonics (EvalSH, Rotation), sphericart (compute_sample,
// compute_array) and, if installed, GSL (gsl_sf_legendre_array_e at 31 bands). Built only with
// -DSPHBASIS_PEERS_DIR (bench/peers/CMakeLists.txt); only ratios within one run mean anything.
//
// Names are group/param/implementation; every benchmark reports `per_item`, seconds per
// direction / call / rotation / product / light (bench/peers/peer_table.py makes the README's
// table from a JSON run). Each inner loop walks precomputed inputs (1024 directions, 256
// rotations, 1024 coefficient pairs) and DoNotOptimize(out) after each call forces its stores,
// so nothing is hoisted and consecutive calls stay independent. sphbasis is header-only and
// inlines into the loop; the peers are static libraries called as their builds ship them.
//
// Conventions (README, "Coming from DirectXMath"): DirectXMath and google use the
// Condon-Shortley phase (not needed for timing); XMSHRotate takes row-vector matrices, so it is
// given R^T for our R; sphericart takes AoS directions (x y z x y z ...).
#include <DirectXMath.h>
#include <DirectXSH.h>
#include <benchmark/benchmark.h>
#include <sh/spherical_harmonics.h>  // google's namespace is ::sh

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <sphericart.hpp>
#include <string>
#include <vector>
#ifdef SPHBASIS_PEERS_GSL
#include <gsl/gsl_sf_legendre.h>
#endif

#include <sphbasis/basis/sh.hpp>
#include <sphbasis/ops/sh_lights.hpp>
#include <sphbasis/ops/sh_product.hpp>
#include <sphbasis/ops/sh_rotation.hpp>
#include <sphbasis/ops/sh_rotation_fixed.hpp>

// With google's ::sh in the same translation unit, `using namespace sphbasis; sh::...` is
// ambiguous: alias the namespace instead.
namespace sb = sphbasis::sh;

namespace {

constexpr std::size_t kDirs = 1024, kRot = 256, kPairs = 1024, kBatch = 4096;

void per_item(benchmark::State& st, std::size_t items) {
    st.counters["per_item"] = benchmark::Counter(
        static_cast<double>(items),
        benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// Unit directions in the layouts the libraries take.
struct Directions {
    std::vector<float> x, y, z, xyz;
    std::vector<DirectX::XMFLOAT4A> dx;
    std::vector<double> xd, yd, zd, xyzd;
    explicit Directions(std::size_t n, unsigned seed = 1) {
        std::mt19937 rng(seed);
        std::normal_distribution<double> g;
        for (std::size_t i = 0; i < n; ++i) {
            double a = g(rng), b = g(rng), c = g(rng);
            const double r = std::sqrt(a * a + b * b + c * c);
            a /= r, b /= r, c /= r;
            x.push_back(float(a)), y.push_back(float(b)), z.push_back(float(c));
            xyz.insert(xyz.end(), {float(a), float(b), float(c)});
            dx.emplace_back(float(a), float(b), float(c), 0.f);
            xd.push_back(a), yd.push_back(b), zd.push_back(c);
            xyzd.insert(xyzd.end(), {a, b, c});
        }
    }
};
const Directions& dirs() {
    static const Directions d(kDirs);
    return d;
}

/// google has no "all coefficients" call: EvalSH(l, m, dir) per coefficient.
template <class T>
void google_eval(int bands, double x, double y, double z, T* out) {
    const Eigen::Vector3d v(x, y, z);
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) out[l * (l + 1) + m] = T(::sh::EvalSH(l, m, v));
}

#ifdef SPHBASIS_PEERS_GSL
/// GSL: the normalised Legendre functions (SPHARM, csphase = +1: no Condon-Shortley phase) times
/// cos/sin(m phi) from (x, y)/rho by complex multiplication. work holds
/// gsl_sf_legendre_array_n(bands - 1).
void gsl_eval(int bands, double x, double y, double z, double* work, double* out) {
    const std::size_t lmax = std::size_t(bands - 1);
    gsl_sf_legendre_array_e(GSL_SF_LEGENDRE_SPHARM, lmax, z, 1.0, work);
    const double rho = std::hypot(x, y);
    const double c1 = rho > 0 ? x / rho : 1.0, s1 = rho > 0 ? y / rho : 0.0;
    for (std::size_t l = 0; l <= lmax; ++l)
        out[l * (l + 1)] = work[gsl_sf_legendre_array_index(l, 0)];
    double cm = 1, sm = 0;
    for (std::size_t m = 1; m <= lmax; ++m) {
        const double c = cm * c1 - sm * s1;
        sm = sm * c1 + cm * s1;
        cm = c;
        for (std::size_t l = m; l <= lmax; ++l) {
            const double p =
                1.4142135623730951 * work[gsl_sf_legendre_array_index(l, m)];  // sqrt(2)
            out[l * (l + 1) + m] = p * cm;
            out[l * (l + 1) - m] = p * sm;
        }
    }
}
#endif

// ---- 1. One call, float, N bands, a normalising eval (sphericart normalises too) and the
// unit-input eval (DirectXMath's XMSHEvalDirection takes unit input).
enum class Eval1 { sb_eval, sb_eval_unit, sb_normalize_then_unit, dx, google, sphericart };

template <int N, Eval1 K>
void eval1(benchmark::State& st) {
    const Directions& d = dirs();
    alignas(64) float out[N * N];
    std::unique_ptr<sphericart::SphericalHarmonics<float>> sc;
    if constexpr (K == Eval1::sphericart)
        sc.reset(new sphericart::SphericalHarmonics<float>(N - 1));
    for (auto _ : st) {
        for (std::size_t i = 0; i < kDirs; ++i) {
            if constexpr (K == Eval1::sb_eval)
                sb::eval<N>(d.x[i], d.y[i], d.z[i], out);
            else if constexpr (K == Eval1::sb_eval_unit)
                sb::eval_unit<N>(d.x[i], d.y[i], d.z[i], out);
            else if constexpr (K == Eval1::sb_normalize_then_unit) {
                // eval<N>'s path before the normalising kernels (reference row)
                float x = d.x[i], y = d.y[i], z = d.z[i];
                sphbasis::normalize_or_pole(x, y, z);
                sb::eval_unit<N>(x, y, z, out);
            } else if constexpr (K == Eval1::dx)
                DirectX::XMSHEvalDirection(out, N, DirectX::XMLoadFloat4A(&d.dx[i]));
            else if constexpr (K == Eval1::google)
                google_eval<float>(N, d.x[i], d.y[i], d.z[i], out);
            else
                sc->compute_sample(d.xyz.data() + 3 * i, 3, out, N * N);
            benchmark::DoNotOptimize(out);
        }
    }
    per_item(st, kDirs);
}

// ---- 2. Batched, float, 4096 directions in cache. sphbasis writes function-major output
// (stride kBatch + 16), sphericart direction-major.
enum class Batch { sb_soa, sb_aos, sphericart };

template <int B, Batch K>
void batch(benchmark::State& st) {
    const Directions d(kBatch, 7);
    const std::size_t stride = kBatch + 16;
    std::vector<float> out(stride * B * B);
    std::unique_ptr<sphericart::SphericalHarmonics<float>> sc;
    if constexpr (K == Batch::sphericart)
        sc.reset(new sphericart::SphericalHarmonics<float>(B - 1));
    for (auto _ : st) {
        if constexpr (K == Batch::sb_soa)
            sb::eval_batch(B, kBatch, d.x.data(), d.y.data(), d.z.data(), out.data(), stride);
        else if constexpr (K == Batch::sb_aos)
            sb::eval_batch_aos(B, kBatch, d.xyz.data(), out.data(), stride);
        else
            sc->compute_array(d.xyz.data(), 3 * kBatch, out.data(), kBatch * B * B);
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    per_item(st, kBatch);
}

// ---- 3. 31 bands, double, one direction per call.
enum class Deg31 { sb, sphericart, gsl, google };

template <Deg31 K>
void deg31(benchmark::State& st) {
    constexpr int B = 31;
    constexpr std::size_t n = 256;
    const Directions& d = dirs();
    std::vector<double> out(B * B);
    std::unique_ptr<sphericart::SphericalHarmonics<double>> sc;
    if constexpr (K == Deg31::sphericart)
        sc.reset(new sphericart::SphericalHarmonics<double>(B - 1));
#ifdef SPHBASIS_PEERS_GSL
    std::vector<double> work(gsl_sf_legendre_array_n(B - 1));
#endif
    for (auto _ : st) {
        for (std::size_t i = 0; i < n; ++i) {
            if constexpr (K == Deg31::sb) {
                sb::eval(B, d.xd[i], d.yd[i], d.zd[i], out.data());
            } else if constexpr (K == Deg31::sphericart) {
                sc->compute_sample(d.xyzd.data() + 3 * i, 3, out.data(), B * B);
            } else if constexpr (K == Deg31::google) {
                google_eval<double>(B, d.xd[i], d.yd[i], d.zd[i], out.data());
            } else {
#ifdef SPHBASIS_PEERS_GSL
                gsl_eval(B, d.xd[i], d.yd[i], d.zd[i], work.data(), out.data());
#endif
            }
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    }
    per_item(st, n);
}

// ---- 4. Rotation from a 3x3 matrix (or quaternion), build + apply to one vector, float.
struct RotData {
    std::vector<std::array<float, 4>> q;   // w, x, y, z
    std::vector<DirectX::XMFLOAT4> qxm;    // x, y, z, w
    std::vector<sphbasis::Mat3<float>> m;  // row-major, column vectors: v' = R v
    std::vector<DirectX::XMMATRIX> xm;     // R^T: DirectXMath's row vectors
    std::vector<Eigen::Quaterniond> qe;
    RotData() {
        std::mt19937 rng(3);
        std::normal_distribution<double> g;
        for (std::size_t i = 0; i < kRot; ++i) {
            double w = g(rng), x = g(rng), y = g(rng), z = g(rng);
            const double r = std::sqrt(w * w + x * x + y * y + z * z);
            w /= r, x /= r, y /= r, z /= r;
            q.push_back({float(w), float(x), float(y), float(z)});
            qxm.emplace_back(float(x), float(y), float(z), float(w));
            qe.emplace_back(w, x, y, z);
            const double R[9] = {
                1 - 2 * (y * y + z * z), 2 * (x * y - w * z),     2 * (x * z + w * y),
                2 * (x * y + w * z),     1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                2 * (x * z - w * y),     2 * (y * z + w * x),     1 - 2 * (x * x + y * y)};
            sphbasis::Mat3<float> f;
            for (std::size_t k = 0; k < 9; ++k) f[k] = float(R[k]);
            m.push_back(f);
            DirectX::XMFLOAT3X3 t(f[0], f[3], f[6], f[1], f[4], f[7], f[2], f[5], f[8]);
            xm.push_back(DirectX::XMLoadFloat3x3(&t));
        }
    }
};

enum class Rot {
    sb_rotate_n,
    sb_fixed_build_apply,
    sb_fixed_quaternion,
    sb_fixed_apply_prebuilt,
    sb_runtime,
    dx_matrix,
    dx_quaternion,
    google_quaternion
};

template <int N, Rot K>
void rotation(benchmark::State& st) {
    const RotData r;
    std::vector<float> in(N * N), out(N * N);
    for (int k = 0; k < N * N; ++k) in[std::size_t(k)] = 0.5f + 0.01f * float(k);
    std::vector<sb::FixedRotation<N, float>> prebuilt;
    if constexpr (K == Rot::sb_fixed_apply_prebuilt)
        for (std::size_t i = 0; i < kRot; ++i) prebuilt.emplace_back(r.m[i]);
    for (auto _ : st) {
        for (std::size_t i = 0; i < kRot; ++i) {
            if constexpr (K == Rot::sb_rotate_n) {
                sb::rotate<N>(r.m[i], in.data(), out.data());
            } else if constexpr (K == Rot::sb_fixed_build_apply) {
                sb::FixedRotation<N, float>(r.m[i]).apply(in.data(), out.data());
            } else if constexpr (K == Rot::sb_fixed_quaternion) {
                sb::FixedRotation<N, float>::from_quaternion(r.q[i][0], r.q[i][1], r.q[i][2],
                                                             r.q[i][3])
                    .apply(in.data(), out.data());
            } else if constexpr (K == Rot::sb_fixed_apply_prebuilt) {
                prebuilt[i].apply(in.data(), out.data());
            } else if constexpr (K == Rot::sb_runtime) {
                sb::Rotation<float>::from_matrix(N, r.m[i]).apply(in.data(), out.data());
            } else if constexpr (K == Rot::dx_matrix) {
                DirectX::XMSHRotate(out.data(), N, r.xm[i], in.data());
            } else if constexpr (K == Rot::dx_quaternion) {
                DirectX::XMSHRotate(
                    out.data(), N,
                    DirectX::XMMatrixRotationQuaternion(DirectX::XMLoadFloat4(&r.qxm[i])),
                    in.data());
            } else {
                ::sh::Rotation::Create(N - 1, r.qe[i])->Apply(in, &out);
            }
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    }
    per_item(st, kRot);
}

enum class RotZ { sb, sb_libm, dx };

/// Reference row: sh::rotate_z as it was with libm's sincos for cos a, sin a (unchecked).
void rotate_z_libm(int bands, float angle, const float* in, float* out) {
    for (int l = 0; l < bands; ++l) out[l * (l + 1)] = in[l * (l + 1)];
    const double c1 = std::cos(double(angle)), s1 = std::sin(double(angle));
    double cm = 1, sm = 0;
    for (int m = 1; m < bands; ++m) {
        const double c = cm * c1 - sm * s1;
        sm = sm * c1 + cm * s1;
        cm = c;
        const float fc = float(cm), fs = float(sm);
        for (int l = m; l < bands; ++l) {
            const float cc = in[l * (l + 1) + m], ss = in[l * (l + 1) - m];
            out[l * (l + 1) + m] = cc * fc + ss * (-fs);
            out[l * (l + 1) - m] = ss * fc + cc * fs;
        }
    }
}

template <int N, RotZ K>
void rotate_z(benchmark::State& st) {
    std::vector<float> in(N * N), out(N * N);
    for (int k = 0; k < N * N; ++k) in[std::size_t(k)] = 0.5f + 0.01f * float(k);
    float a = 0.1f;
    for (auto _ : st) {
        for (std::size_t i = 0; i < kRot; ++i) {
            if constexpr (K == RotZ::sb)
                sb::rotate_z(N, a, in.data(), out.data());
            else if constexpr (K == RotZ::sb_libm)
                rotate_z_libm(N, a, in.data(), out.data());
            else
                DirectX::XMSHRotateZ(out.data(), N, a, in.data());
            a = a > 6.f ? 0.1f : a + 0.01f;
            benchmark::DoNotOptimize(out.data());
            benchmark::ClobberMemory();
        }
    }
    per_item(st, kRot);
}

// ---- 5. Product n x n -> n bands, float.
template <int N, bool Dx>
void product(benchmark::State& st) {
    constexpr std::size_t n2 = N * N;
    std::mt19937 rng(11);
    std::uniform_real_distribution<float> u(-1, 1);
    std::vector<float> a(kPairs * n2), b(kPairs * n2), out(kPairs * n2);
    for (auto& v : a) v = u(rng);
    for (auto& v : b) v = u(rng);
    for (auto _ : st) {
        for (std::size_t p = 0; p < kPairs; ++p) {
            const float* ap = a.data() + p * n2;
            const float* bp = b.data() + p * n2;
            float* op = out.data() + p * n2;
            if constexpr (!Dx)
                sb::product<N>(ap, bp, op);
            else if constexpr (N == 3)
                DirectX::XMSHMultiply3(op, ap, bp);
            else if constexpr (N == 4)
                DirectX::XMSHMultiply4(op, ap, bp);
            else if constexpr (N == 5)
                DirectX::XMSHMultiply5(op, ap, bp);
            else
                DirectX::XMSHMultiply6(op, ap, bp);
        }
        benchmark::DoNotOptimize(out.data());
        benchmark::ClobberMemory();
    }
    per_item(st, kPairs);
}

// ---- 6. Analytic lights, 3 bands, float RGB: sphbasis with an RGB coefficient type (the
// compile-time forms <3>, and the run-time band count for reference), DirectXMath with three
// float arrays.
struct RGB {
    float r = 0, g = 0, b = 0;
};
RGB operator+(const RGB& a, const RGB& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
RGB operator*(const RGB& a, float s) { return {a.r * s, a.g * s, a.b * s}; }

enum class Light { directional, cone, sphere, hemisphere };

template <Light L, bool Fixed>
void light_sb(benchmark::State& st) {
    const Directions& d = dirs();
    RGB out[9];
    const RGB c{1, 2, 3}, g{0.1f, 0.2f, 0.3f};
    for (auto _ : st) {
        for (std::size_t i = 0; i < kRot; ++i) {
            const float x = d.x[i], y = d.y[i], z = d.z[i];
            if constexpr (Fixed) {
                if constexpr (L == Light::directional)
                    sb::directional_light<3>(x, y, z, c, out);
                else if constexpr (L == Light::cone)
                    sb::cone_light<3>(x, y, z, 0.3f, c, out);
                else if constexpr (L == Light::sphere)
                    sb::spherical_light<3>(4 * x, 4 * y, 4 * z, 1.0f, c, out);
                else
                    sb::hemisphere_light<3>(x, y, z, c, g, out);
            } else {
                if constexpr (L == Light::directional)
                    sb::directional_light(3, x, y, z, c, out);
                else if constexpr (L == Light::cone)
                    sb::cone_light(3, x, y, z, 0.3f, c, out);
                else if constexpr (L == Light::sphere)
                    sb::spherical_light(3, 4 * x, 4 * y, 4 * z, 1.0f, c, out);
                else
                    sb::hemisphere_light(3, x, y, z, c, g, out);
            }
            benchmark::DoNotOptimize(out);
        }
    }
    per_item(st, kRot);
}

template <Light L>
void light_dx(benchmark::State& st) {
    const Directions& d = dirs();
    float r[9], gg[9], b[9];
    const DirectX::XMVECTOR c = DirectX::XMVectorSet(1, 2, 3, 0);
    const DirectX::XMVECTOR g = DirectX::XMVectorSet(0.1f, 0.2f, 0.3f, 0);
    for (auto _ : st) {
        for (std::size_t i = 0; i < kRot; ++i) {
            const DirectX::XMVECTOR v = DirectX::XMLoadFloat4A(&d.dx[i]);
            if constexpr (L == Light::directional)
                DirectX::XMSHEvalDirectionalLight(3, v, c, r, gg, b);
            else if constexpr (L == Light::cone)
                DirectX::XMSHEvalConeLight(3, v, 0.3f, c, r, gg, b);
            else if constexpr (L == Light::sphere)
                DirectX::XMSHEvalSphericalLight(3, DirectX::XMVectorScale(v, 4.f), 1.0f, c, r, gg,
                                                b);
            else
                DirectX::XMSHEvalHemisphereLight(3, v, c, g, r, gg, b);
            benchmark::DoNotOptimize(r);
            benchmark::DoNotOptimize(gg);
            benchmark::DoNotOptimize(b);
        }
    }
    per_item(st, kRot);
}

template <class F>
void reg(const std::string& name, F f) {
    benchmark::RegisterBenchmark(name.c_str(), f);
}

template <int N>
void register_eval1() {
    const std::string g = "eval1/" + std::to_string(N) + "/";
    reg(g + "sphbasis_eval_unit", eval1<N, Eval1::sb_eval_unit>);
    reg(g + "sphbasis_eval", eval1<N, Eval1::sb_eval>);
    reg(g + "ref_sphbasis_normalize_then_unit", eval1<N, Eval1::sb_normalize_then_unit>);
    if constexpr (N <= 6) reg(g + "dxmath_unit", eval1<N, Eval1::dx>);
    if constexpr (N <= 4) reg(g + "google_unit", eval1<N, Eval1::google>);
    reg(g + "sphericart", eval1<N, Eval1::sphericart>);
}

template <int N>
void register_rotation() {
    const std::string g = "rotation/" + std::to_string(N) + "/";
    reg(g + "sphbasis_rotate_N", rotation<N, Rot::sb_rotate_n>);
    reg(g + "sphbasis_FixedRotation_build_apply", rotation<N, Rot::sb_fixed_build_apply>);
    reg(g + "sphbasis_FixedRotation_quaternion", rotation<N, Rot::sb_fixed_quaternion>);
    reg(g + "sphbasis_Rotation_runtime", rotation<N, Rot::sb_runtime>);
    reg(g + "ref_sphbasis_apply_prebuilt", rotation<N, Rot::sb_fixed_apply_prebuilt>);
    reg(g + "dxmath_matrix", rotation<N, Rot::dx_matrix>);
    reg(g + "dxmath_quaternion", rotation<N, Rot::dx_quaternion>);
    reg(g + "google_quaternion", rotation<N, Rot::google_quaternion>);
    reg("rotate_z/" + std::to_string(N) + "/sphbasis", rotate_z<N, RotZ::sb>);
    reg("rotate_z/" + std::to_string(N) + "/dxmath", rotate_z<N, RotZ::dx>);
    reg("rotate_z/" + std::to_string(N) + "/ref_sphbasis_libm_sincos", rotate_z<N, RotZ::sb_libm>);
}

template <Light L>
void register_light(const std::string& name) {
    reg("light3/" + name + "/sphbasis_N", light_sb<L, true>);
    reg("light3/" + name + "/sphbasis_runtime", light_sb<L, false>);
    reg("light3/" + name + "/dxmath", light_dx<L>);
}

}  // namespace

int main(int argc, char** argv) {
    register_eval1<3>();
    register_eval1<4>();
    register_eval1<5>();
    register_eval1<6>();
    register_eval1<7>();
    register_eval1<8>();
    for (int b : {3, 8}) {
        const std::string g = "batch4096/" + std::to_string(b) + "/";
        if (b == 3) {
            reg(g + "sphbasis_eval_batch", batch<3, Batch::sb_soa>);
            reg(g + "sphbasis_eval_batch_aos", batch<3, Batch::sb_aos>);
            reg(g + "sphericart_aos", batch<3, Batch::sphericart>);
        } else {
            reg(g + "sphbasis_eval_batch", batch<8, Batch::sb_soa>);
            reg(g + "sphbasis_eval_batch_aos", batch<8, Batch::sb_aos>);
            reg(g + "sphericart_aos", batch<8, Batch::sphericart>);
        }
    }
    reg("deg31_f64/31/sphbasis", deg31<Deg31::sb>);
    reg("deg31_f64/31/sphericart", deg31<Deg31::sphericart>);
#ifdef SPHBASIS_PEERS_GSL
    reg("deg31_f64/31/gsl", deg31<Deg31::gsl>);
#endif
    reg("deg31_f64/31/google", deg31<Deg31::google>);
    register_rotation<3>();
    register_rotation<6>();
    reg("product/3/sphbasis", product<3, false>);
    reg("product/3/dxmath", product<3, true>);
    reg("product/4/sphbasis", product<4, false>);
    reg("product/4/dxmath", product<4, true>);
    reg("product/5/sphbasis", product<5, false>);
    reg("product/5/dxmath", product<5, true>);
    reg("product/6/sphbasis", product<6, false>);
    reg("product/6/dxmath", product<6, true>);
    register_light<Light::directional>("directional");
    register_light<Light::cone>("cone");
    register_light<Light::sphere>("sphere");
    register_light<Light::hemisphere>("hemisphere");
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
