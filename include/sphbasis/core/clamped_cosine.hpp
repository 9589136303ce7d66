// sphbasis: the Funk-Hecke factors of the clamped cosine max(cos theta, 0), the kernel that turns
// radiance into irradiance, in closed form. Standard library only (evaluation tier), so the
// operations (ops/sh_convolution.hpp, ops/sh_lights.hpp, ops/imse.hpp) and the shading tables
// share one definition.
//
// References: Ramamoorthi and Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps" (SIGGRAPH 2001), eq. 8; Ishmukhametov, "Irradiance Normal Mapping" (thesis), eq. 2.3.
//   Lambda_l = 2 pi int_0^1 t P_l(t) dt = pi a_l, with the normalised factors
//   a_0 = 1, a_1 = 2/3, a_l = 0 for odd l > 1, and for even l >= 2
//   a_l = 2 (-1)^(l/2 - 1) / ((l + 2)(l - 1)) * binom(l, l/2) / 2^l,
// so a_2 = 1/4, a_4 = -1/24, a_6 = 1/64, and |a_l| ~ 1.6 l^(-5/2) decreases for even l >= 2.
// binom(l, l/2) / 2^l < 1 is carried as the running product r_l = r_{l-2} (l - 1) / l, so nothing
// overflows at any l. The irradiance of radiance L = sum c_lm y_lm is E = sum Lambda_l c_lm y_lm;
// a white Lambertian surface reflects E / pi = sum a_l c_lm y_lm.
#pragma once

#include <cstddef>
#include <string>

#include "error.hpp"

namespace sphbasis {

namespace detail {
/// a_l from r_l = binom(l, l/2) / 2^l for even l >= 2.
inline double clamped_cosine_even(int l, double r) noexcept {
    const double sign = (l / 2) % 2 ? 1.0 : -1.0;  // (-1)^(l/2 - 1)
    return sign * 2 * r / (static_cast<double>(l + 2) * (l - 1));
}
}  // namespace detail

/// The normalised clamped-cosine factor a_l = Lambda_l / pi of degree l >= 0 (header comment):
/// 1, 2/3, 1/4, 0, -1/24, 0, 1/64, ... Cost O(l). Throws std::invalid_argument for l < 0.
inline double clamped_cosine(int l) {
    if (l < 0) detail::throw_invalid("clamped_cosine", "l >= 0, got " + std::to_string(l));
    if (l == 0) return 1;
    if (l == 1) return 2.0 / 3.0;
    if (l % 2) return 0;
    double r = 1;  // binom(l, l/2) / 2^l
    for (int k = 2; k <= l; k += 2) r *= static_cast<double>(k - 1) / k;
    return detail::clamped_cosine_even(l, r);
}

/// out[l] = a_l for 0 <= l < bands, the same values as clamped_cosine(l) in O(bands) total.
/// Nothing is written for bands <= 0.
inline void clamped_cosine_factors(int bands, double* out) noexcept {
    double r = 1;
    for (int l = 0; l < bands; ++l) {
        const std::size_t i = static_cast<std::size_t>(l);
        if (l == 0)
            out[i] = 1;
        else if (l == 1)
            out[i] = 2.0 / 3.0;
        else if (l % 2)
            out[i] = 0;
        else {
            r *= static_cast<double>(l - 1) / l;
            out[i] = detail::clamped_cosine_even(l, r);
        }
    }
}

}  // namespace sphbasis
