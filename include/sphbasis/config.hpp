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

#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_FORCEINLINE inline __attribute__((always_inline))
#define SPHBASIS_RESTRICT __restrict__
#elif defined(_MSC_VER)
#define SPHBASIS_FORCEINLINE __forceinline
#define SPHBASIS_RESTRICT __restrict
#else
#define SPHBASIS_FORCEINLINE inline
#define SPHBASIS_RESTRICT
#endif

// SPHBASIS_NOINLINE keeps a function out of line (one-time table builds, cold error paths, the
// large-size paths of the one-call kernels); SPHBASIS_INLINE_LAMBDA always inlines a lambda body
// (placed after the parameter list).
#if defined(__GNUC__) || defined(__clang__)
#define SPHBASIS_NOINLINE __attribute__((noinline))
#define SPHBASIS_INLINE_LAMBDA __attribute__((always_inline))
#elif defined(_MSC_VER)
#define SPHBASIS_NOINLINE __declspec(noinline)
#define SPHBASIS_INLINE_LAMBDA
#else
#define SPHBASIS_NOINLINE
#define SPHBASIS_INLINE_LAMBDA
#endif
