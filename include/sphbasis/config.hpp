// sphbasis: configuration macros.
//
// SPHBASIS_ASSERT(cond) checks preconditions of hot kernels in debug builds only. Define it
// before including any sphbasis header to route failures elsewhere (like eigen_assert).
#pragma once

#include "version.hpp"

#ifndef SPHBASIS_ASSERT
#ifdef NDEBUG
#define SPHBASIS_ASSERT(cond) ((void)0)
#else
#include <cassert>
#define SPHBASIS_ASSERT(cond) assert(cond)
#endif
#endif

// SPHBASIS_FORCEINLINE forces the hot kernels inline (the one-call evaluations depend on it for
// their speed). SPHBASIS_NO_FORCEINLINE makes it plain `inline` (and SPHBASIS_INLINE_LAMBDA
// empty): for unoptimised (-O0) and sanitizer builds, where forced inlining copies every
// band's kernel into every caller and the compiler's back end spends most of its time on the
// copies.
#if defined(SPHBASIS_NO_FORCEINLINE)
#define SPHBASIS_FORCEINLINE inline
#elif defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_FORCEINLINE inline __attribute__((always_inline))
#elif defined(_MSC_VER)
#define SPHBASIS_FORCEINLINE __forceinline
#else
#define SPHBASIS_FORCEINLINE inline
#endif
#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_RESTRICT __restrict__
#elif defined(_MSC_VER)
#define SPHBASIS_RESTRICT __restrict
#else
#define SPHBASIS_RESTRICT
#endif

// SPHBASIS_NOINLINE keeps a function out of line (one-time table builds, cold error paths, the
// large-size paths of the one-call kernels); SPHBASIS_INLINE_LAMBDA always inlines a lambda body
// (placed after the parameter list).
#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_NOINLINE __attribute__((noinline))
#if defined(SPHBASIS_NO_FORCEINLINE)
#define SPHBASIS_INLINE_LAMBDA
#else
#define SPHBASIS_INLINE_LAMBDA __attribute__((always_inline))
#endif
#elif defined(_MSC_VER)
#define SPHBASIS_NOINLINE __declspec(noinline)
#define SPHBASIS_INLINE_LAMBDA
#else
#define SPHBASIS_NOINLINE
#define SPHBASIS_INLINE_LAMBDA
#endif
