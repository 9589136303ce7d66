// sphbasis: the batch evaluation shared by the fitted (non-linear) representations whose
// Expansion<T> is built once from the stored values and evaluated per unit direction
// (basis/sh_l1_nonlinear.hpp, basis/zh3.hpp). Internal: users include those headers.
#pragma once

#include <cstddef>

#include "../../core/error.hpp"
#include "../../core/simd.hpp"
#include "../basis.hpp"

namespace sphbasis::detail {

/// The eval_batch of a fitted representation (`fn` names it in errors): checks the direction
/// and output buffers, builds Expansion<T> from the stored values c once, and evaluates it at
/// `directions` SoA directions (normalised as by basis_eval), SIMD across directions.
template <template <class> class Expansion, class T>
void eval_expansion_batch(const char* fn, const T* c, std::size_t directions, const T* xs,
                          const T* ys, const T* zs, T* out) {
    for (const T* p : {xs, ys, zs}) check_buffer(fn, "direction", p, directions);
    check_buffer(fn, "out", out, directions);
    const Expansion<T> e(c);
    for_each_direction(
        directions, xs, ys, zs,
        [&](const batch<T>& x, const batch<T>& y, const batch<T>& z, std::size_t i) {
            e(x, y, z).store(out + i);
        },
        [&](T x, T y, T z, std::size_t i) { out[i] = e(x, y, z); });
}

}  // namespace sphbasis::detail
