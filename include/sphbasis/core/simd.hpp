// sphbasis: a minimal SIMD batch for evaluating kernels across directions.
//
// batch<T> holds native_width<T> lanes of float or double in a GCC/Clang vector extension, so
// the same kernel template that serves float and double also serves batches. The width follows
// the compilation target: 64 bytes with AVX-512F, 32 with AVX, 16 otherwise (SSE2/NEON or the
// compiler's scalarised fallback). Compilers without vector extensions get width 1 and the
// batch paths run the scalar kernels.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "../config.hpp"
#include "scalar.hpp"

#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_HAS_VECTOR_EXT 1
#if defined(__AVX__) || defined(__SSE2__)
#include <immintrin.h>
#endif
#else
#define SPHBASIS_HAS_VECTOR_EXT 0
#endif

namespace sphbasis {

#if SPHBASIS_HAS_VECTOR_EXT
#if defined(__AVX512F__)
inline constexpr std::size_t simd_bytes = 64;
#elif defined(__AVX__)
inline constexpr std::size_t simd_bytes = 32;
#else
inline constexpr std::size_t simd_bytes = 16;
#endif

namespace detail {
template <class T>
struct int_of;
template <>
struct int_of<float> {
    using type = std::int32_t;
};
template <>
struct int_of<double> {
    using type = std::int64_t;
};
template <class T>
struct native_vec;
template <>
struct native_vec<float> {
    typedef float type __attribute__((vector_size(simd_bytes)));
    typedef std::int32_t mask __attribute__((vector_size(simd_bytes)));
};
template <>
struct native_vec<double> {
    typedef double type __attribute__((vector_size(simd_bytes)));
    typedef std::int64_t mask __attribute__((vector_size(simd_bytes)));
};
}  // namespace detail

/// Lanes per batch of T on this compilation target.
template <class T>
inline constexpr int native_width = static_cast<int>(simd_bytes / sizeof(T));

/// A batch of native_width<T> lanes. Arithmetic is lane-wise; comparisons give a mask.
template <class T>
struct batch {
    static_assert(std::is_floating_point_v<T>, "sphbasis::batch holds float or double lanes.");
    using value_type = T;
    using int_type = typename detail::int_of<T>::type;
    using native_type = typename detail::native_vec<T>::type;
    using mask_type = typename detail::native_vec<T>::mask;
    static constexpr int size = native_width<T>;

    native_type v;

    batch() noexcept = default;
    SPHBASIS_FORCEINLINE batch(native_type n) noexcept : v(n) {}
    // Broadcast. `s - 0` keeps -0 (while `0 + s` would turn it into +0) and compiles to one
    // broadcast instruction; a lane loop becomes per-lane masked moves with GCC 12.
    SPHBASIS_FORCEINLINE batch(T s) noexcept : v(s - native_type{}) {}

    static SPHBASIS_FORCEINLINE batch load(const T* p) noexcept {
        batch r;
        std::memcpy(&r.v, p, sizeof(native_type));
        return r;
    }
    SPHBASIS_FORCEINLINE void store(T* p) const noexcept {
        std::memcpy(p, &v, sizeof(native_type));
    }
    SPHBASIS_FORCEINLINE T operator[](int i) const noexcept { return v[i]; }

    friend SPHBASIS_FORCEINLINE batch operator+(batch a, batch b) noexcept { return a.v + b.v; }
    friend SPHBASIS_FORCEINLINE batch operator-(batch a, batch b) noexcept { return a.v - b.v; }
    friend SPHBASIS_FORCEINLINE batch operator*(batch a, batch b) noexcept { return a.v * b.v; }
    friend SPHBASIS_FORCEINLINE batch operator/(batch a, batch b) noexcept { return a.v / b.v; }
    friend SPHBASIS_FORCEINLINE batch operator-(batch a) noexcept { return -a.v; }
    SPHBASIS_FORCEINLINE batch& operator+=(batch b) noexcept { return v += b.v, *this; }
    SPHBASIS_FORCEINLINE batch& operator-=(batch b) noexcept { return v -= b.v, *this; }
    SPHBASIS_FORCEINLINE batch& operator*=(batch b) noexcept { return v *= b.v, *this; }
    friend SPHBASIS_FORCEINLINE mask_type operator<(batch a, batch b) noexcept { return a.v < b.v; }
    friend SPHBASIS_FORCEINLINE mask_type operator>(batch a, batch b) noexcept { return a.v > b.v; }
    friend SPHBASIS_FORCEINLINE mask_type operator<=(batch a, batch b) noexcept {
        return a.v <= b.v;
    }
    friend SPHBASIS_FORCEINLINE mask_type operator>=(batch a, batch b) noexcept {
        return a.v >= b.v;
    }
};

template <class T>
struct scalar_traits<batch<T>, void> {
    using scalar = T;
    using mask = typename batch<T>::mask_type;
    static constexpr int size = batch<T>::size;
};

/// Lane-wise m ? a : b.
template <class T>
SPHBASIS_FORCEINLINE batch<T> select(typename batch<T>::mask_type m, batch<T> a,
                                     batch<T> b) noexcept {
    using M = typename batch<T>::mask_type;
    using N = typename batch<T>::native_type;
    return (N)((m & (M)a.v) | (~m & (M)b.v));
}

template <class T>
SPHBASIS_FORCEINLINE batch<T> vsqrt(batch<T> a) noexcept {
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<T, float>)
        return batch<T>(_mm512_maskz_sqrt_ps(__mmask16(0xFFFF), a.v));
    else
        return batch<T>(_mm512_maskz_sqrt_pd(__mmask8(0xFF), a.v));
#elif defined(__AVX__)
    if constexpr (std::is_same_v<T, float>)
        return batch<T>(_mm256_sqrt_ps(a.v));
    else
        return batch<T>(_mm256_sqrt_pd(a.v));
#elif defined(__SSE2__)
    if constexpr (std::is_same_v<T, float>)
        return batch<T>(_mm_sqrt_ps(a.v));
    else
        return batch<T>(_mm_sqrt_pd(a.v));
#else
    batch<T> r;
    for (int i = 0; i < batch<T>::size; ++i) r.v[i] = std::sqrt(a.v[i]);
    return r;
#endif
}
/// 1/sqrt(a) for a > 0 (normal range), lane-wise: the hardware estimate refined by
/// Newton-Raphson steps to within about 2 ulp of the correctly rounded value; where the target
/// has no estimate instruction, 1/sqrt(a). Several times cheaper than sqrt + division.
/// AVX-512 uses the maskz_ forms with a full mask (as vsqrt does): the unmasked intrinsics
/// trip GCC 12's -Wmaybe-uninitialized inside <immintrin.h> in every user's -Wall build.
template <class T>
SPHBASIS_FORCEINLINE batch<T> vrsqrt(batch<T> a) noexcept {
    using B = batch<T>;
    auto newton = [&](B y) { return y * (B(T(1.5)) - B(T(0.5)) * a * y * y); };
#if defined(__AVX512F__)
    if constexpr (std::is_same_v<T, float>) {
        return newton(B(_mm512_maskz_rsqrt14_ps(__mmask16(0xFFFF), a.v)));  // 2^-14 -> ~2^-27
    } else {
        return newton(newton(B(_mm512_maskz_rsqrt14_pd(__mmask8(0xFF), a.v))));  // 2^-14 -> ~2^-54
    }
#elif defined(__AVX__)
    if constexpr (std::is_same_v<T, float>) {
        return newton(B(_mm256_rsqrt_ps(a.v)));  // 2^-12 -> ~2^-23
    } else {
        return B(T(1)) / vsqrt(a);
    }
#elif defined(__SSE__)
    if constexpr (std::is_same_v<T, float>) {
        return newton(B(_mm_rsqrt_ps(a.v)));
    } else {
        return B(T(1)) / vsqrt(a);
    }
#else
    return B(T(1)) / vsqrt(a);
#endif
}

template <class T>
SPHBASIS_FORCEINLINE batch<T> vabs(batch<T> a) noexcept {
    using M = typename batch<T>::mask_type;
    using N = typename batch<T>::native_type;
    return (N)((M)a.v & ~(M)(batch<T>(T(-0.0)).v));
}
template <class T>
SPHBASIS_FORCEINLINE batch<T> vfma(batch<T> a, batch<T> b, batch<T> c) noexcept {
    return a.v * b.v + c.v;
}
template <class T>
SPHBASIS_FORCEINLINE batch<T> vmax(batch<T> a, batch<T> b) noexcept {
    return select(a > b, a, b);
}
template <class T>
SPHBASIS_FORCEINLINE batch<T> vmin(batch<T> a, batch<T> b) noexcept {
    return select(a < b, a, b);
}
namespace detail {
/// Bit i set where lane i of the comparison mask m is true (one instruction on x86).
template <class M>
SPHBASIS_FORCEINLINE unsigned lane_bits(M m) noexcept {
    constexpr std::size_t lanes = sizeof(M) / sizeof(m[0]);
#if defined(__AVX512F__)
    if constexpr (sizeof(M) == 64) {
        if constexpr (lanes == 16)
            return _mm512_test_epi32_mask(reinterpret_cast<__m512i>(m),
                                          reinterpret_cast<__m512i>(m));
        else
            return _mm512_test_epi64_mask(reinterpret_cast<__m512i>(m),
                                          reinterpret_cast<__m512i>(m));
    }
#endif
#if defined(__AVX__)
    if constexpr (sizeof(M) == 32) {
        if constexpr (lanes == 8)
            return static_cast<unsigned>(_mm256_movemask_ps(reinterpret_cast<__m256>(m)));
        else
            return static_cast<unsigned>(_mm256_movemask_pd(reinterpret_cast<__m256d>(m)));
    }
#endif
#if defined(__SSE2__)
    if constexpr (sizeof(M) == 16) {
        if constexpr (lanes == 4)
            return static_cast<unsigned>(_mm_movemask_ps(reinterpret_cast<__m128>(m)));
        else
            return static_cast<unsigned>(_mm_movemask_pd(reinterpret_cast<__m128d>(m)));
    }
#endif
    unsigned bits = 0;
    for (std::size_t i = 0; i < lanes; ++i)
        if (m[i]) bits |= 1u << i;
    return bits;
}
}  // namespace detail

/// True if every lane of the comparison mask m is true. A lane loop would compile to one
/// extract and branch per lane (measured: 16 of each per AVX-512 float batch).
template <class M, std::enable_if_t<!std::is_arithmetic_v<M>, int> = 0>
SPHBASIS_FORCEINLINE bool all(M m) noexcept {
    constexpr std::size_t lanes = sizeof(M) / sizeof(m[0]);
    return detail::lane_bits(m) == (lanes == 32 ? ~0u : (1u << lanes) - 1u);
}
/// True if any lane of the comparison mask m is true.
template <class M, std::enable_if_t<!std::is_arithmetic_v<M>, int> = 0>
SPHBASIS_FORCEINLINE bool any(M m) noexcept {
    return detail::lane_bits(m) != 0;
}

#else
template <class T>
inline constexpr int native_width = 1;
template <class T>
using batch = T;
#endif

}  // namespace sphbasis
