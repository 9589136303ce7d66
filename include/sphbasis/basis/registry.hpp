// sphbasis: every basis by name, for tools and benchmarks that choose a basis at run time
// (the CLI's --basis NAME, the IMSE benchmark). Compile-time code should use the basis types.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "../core/error.hpp"
#include "ambient_cube.hpp"
#include "ambient_dice.hpp"
#include "ambient_dice_bezier.hpp"
#include "basis.hpp"
#include "hbasis.hpp"
#include "hl2.hpp"
#include "hsh.hpp"
#include "makhotkin.hpp"
#include "sh.hpp"
#include "sh_l1_nonlinear.hpp"
#include "spherical_gaussian.hpp"
#include "zernike.hpp"
#include "zh3.hpp"

namespace sphbasis {

/// Type-erased access to one basis.
struct BasisInfo {
    const char* name;
    Domain domain;
    bool orthonormal;
    bool (*valid_count)(int count);
    const char* (*count_rule)();
    /// basis_eval<B>(count, ...) and basis_eval_batch<B>(count, directions, ...).
    void (*eval_d)(int count, double x, double y, double z, double* out);
    void (*eval_f)(int count, float x, float y, float z, float* out);
    void (*eval_batch_f)(int count, std::size_t directions, const float* xs, const float* ys,
                         const float* zs, float* out, std::size_t stride);
    /// Index of the function labelled (l, m) and the smallest size containing it; throws
    /// std::invalid_argument if the basis has no such label.
    std::pair<int, int> (*lm_index)(int l, int m);

    /// The evaluator of `count` functions (throws std::invalid_argument for a bad count).
    BasisFunctions functions(int count) const {
        if (!valid_count(count))
            detail::throw_invalid("BasisInfo::functions", std::string(count_rule()) +
                                                              " functions for basis '" + name +
                                                              "', got " + std::to_string(count));
        auto f = eval_d;
        return {count,
                [f, count](double x, double y, double z, double* out) { f(count, x, y, z, out); }};
    }
};

namespace detail {
/// (l, m) labels of bases with the SH band structure: index l(l+1)+m, size (l+1)^2.
inline std::pair<int, int> banded_lm(int l, int m) {
    if (l < 0 || m < -l || m > l)
        throw_invalid("lm_index", "l >= 0 and |m| <= l, got l = " + std::to_string(l) +
                                      ", m = " + std::to_string(m));
    return {l * (l + 1) + m, (l + 1) * (l + 1)};
}
inline std::pair<int, int> no_lm(int, int) {
    throw_invalid("lm_index",
                  "a basis with (l, m) labels; this basis has a fixed size (select "
                  "its functions with --coeffs)");
}

template <class B>
BasisInfo make_info(std::pair<int, int> (*lm)(int, int)) {
    return BasisInfo{B::name,
                     B::domain,
                     B::orthonormal,
                     [](int count) { return B::valid_count(count); },
                     []() { return B::count_rule(); },
                     [](int count, double x, double y, double z, double* out) {
                         basis_eval<B>(count, x, y, z, out);
                     },
                     [](int count, float x, float y, float z, float* out) {
                         basis_eval<B>(count, x, y, z, out);
                     },
                     [](int count, std::size_t directions, const float* xs, const float* ys,
                        const float* zs, float* out, std::size_t stride) {
                         basis_eval_batch<B>(count, directions, xs, ys, zs, out, stride);
                     },
                     lm};
}
}  // namespace detail

// all_bases() and find_basis() are templates with a defaulted parameter only so that their
// bodies, which instantiate every basis's kernels for float, double and SIMD batches, are
// compiled where they are called, not in every file that includes this header.

/// All bases, in the order of the CLI's help text.
template <class = void>
const std::vector<BasisInfo>& all_bases() {
    static const std::vector<BasisInfo> v = {
        detail::make_info<SH>(detail::banded_lm),
        detail::make_info<HSH>(detail::banded_lm),
        detail::make_info<Makhotkin>(detail::banded_lm),
        // Zernike: band n holds m = -n, -n+2, ..., n; n + 1 bands = (n+1)(n+2)/2 functions.
        detail::make_info<Zernike>([](int n, int m) -> std::pair<int, int> {
            if (n < 0 || m < -n || m > n || (n - m) % 2 != 0)
                detail::throw_invalid("lm_index",
                                      "n >= 0, |m| <= n and n - m even for zernike, got n = " +
                                          std::to_string(n) + ", m = " + std::to_string(m));
            return {zernike::index(n, m), (n + 1) * (n + 2) / 2};
        }),
        detail::make_info<HBasis>(detail::no_lm),
        detail::make_info<HBasisMod>(detail::no_lm),
        detail::make_info<HL2>(detail::no_lm),
        detail::make_info<SphericalGaussian>(detail::no_lm),
        detail::make_info<AmbientCube>(detail::no_lm),
        detail::make_info<AmbientDice>(detail::no_lm),
        detail::make_info<AmbientDiceBezier>(detail::no_lm),
        detail::make_info<AmbientDiceLinear>(detail::no_lm),
        detail::make_info<AmbientDiceBezierNormalized>(detail::no_lm),
        detail::make_info<AmbientDiceLinearNormalized>(detail::no_lm),
    };
    return v;
}

/// The basis called `name` ("sh", "hsh", "makhotkin", "zernike", "hbasis", "hbasis-mod",
/// "hl2", "sg", "ambient-cube", "ambient-dice", "ambient-dice-bezier", "ambient-dice-linear",
/// "ambient-dice-bezier-normalized", "ambient-dice-linear-normalized").
/// Throws std::invalid_argument naming the known bases otherwise.
template <class = void>
const BasisInfo& find_basis(std::string_view name) {
    for (const auto& b : all_bases())
        if (name == b.name) return b;
    std::string known;
    for (const auto& b : all_bases()) known += std::string(known.empty() ? "" : ", ") + b.name;
    detail::throw_invalid("find_basis",
                          "one of: " + known + "; got unknown basis '" + std::string(name) + "'");
}

// ---- Fitted (non-linear) representations ------------------------------------------------------
// ZH3 and L1 SH with the Geomerics reconstruction are no linear span: their coefficients come
// from a fit of the signal's low-order SH coefficients (over the whole sphere, as engines project
// probes) and their evaluation is non-linear in them. They share this "fit protocol" instead of
// BasisInfo: the IMSE benchmark (ops/imse.hpp) fits each signal with `fit` and integrates the
// squared error of `eval` by quadrature.

/// Type-erased access to one fitted representation of a scalar signal on the sphere.
struct FittedBasisInfo {
    const char* name;
    int stored;     // values stored per channel (the storage of a texel or probe)
    int sh_coeffs;  // SH coefficients of the signal (ACN, first ones) that the fit reads
    /// The stored values from the signal's first sh_coeffs SH coefficients.
    void (*fit)(const double* sh, double* stored_out);
    /// The representation at a unit direction (normalised as by basis_eval), float and double,
    /// and over `directions` SoA directions (SIMD across directions).
    double (*eval_d)(const double* stored, double x, double y, double z);
    float (*eval_f)(const float* stored, float x, float y, float z);
    void (*eval_batch_f)(const float* stored, std::size_t directions, const float* xs,
                         const float* ys, const float* zs, float* out);
    /// The representation's SH coefficients to `bands` bands (bands^2 values to out; `nodes`: the
    /// quadrature of a non-polynomial one); returns the squared sphere norm of the part above.
    double (*sh_expansion)(const double* stored, int bands, int nodes, double* out);
};

/// All fitted representations: "sh-l1-nonlinear" (4 values), "zh3" (5), "zh3-hallucinate" (4).
template <class = void>
const std::vector<FittedBasisInfo>& all_fitted_bases() {
    static const std::vector<FittedBasisInfo> v = {
        {"sh-l1-nonlinear", sh_l1_nonlinear::stored, 4,
         [](const double* sh, double* out) { sh_l1_nonlinear::fit(sh, out); },
         [](const double* c, double x, double y, double z) {
             return sh_l1_nonlinear::eval(c, x, y, z);
         },
         [](const float* c, float x, float y, float z) {
             return sh_l1_nonlinear::eval(c, x, y, z);
         },
         [](const float* c, std::size_t n, const float* xs, const float* ys, const float* zs,
            float* out) { sh_l1_nonlinear::eval_batch(c, n, xs, ys, zs, out); },
         [](const double* c, int bands, int nodes, double* out) {
             return sh_l1_nonlinear::sh_expansion(c, bands, out, nodes);
         }},
        {"zh3", zh3::stored, 9, [](const double* sh, double* out) { zh3::fit(sh, out); },
         [](const double* c, double x, double y, double z) { return zh3::eval(c, x, y, z); },
         [](const float* c, float x, float y, float z) { return zh3::eval(c, x, y, z); },
         [](const float* c, std::size_t n, const float* xs, const float* ys, const float* zs,
            float* out) { zh3::eval_batch(c, n, xs, ys, zs, out); },
         [](const double* c, int bands, int, double* out) {
             return zh3::sh_expansion(c, bands, out);
         }},
        {"zh3-hallucinate", zh3::stored_hallucinated, 4,
         [](const double* sh, double* out) {
             for (int k = 0; k < 4; ++k) out[k] = sh[k];
         },
         [](const double* c, double x, double y, double z) {
             double full[zh3::stored];
             zh3::hallucinate(c, full);
             return zh3::eval(full, x, y, z);
         },
         [](const float* c, float x, float y, float z) {
             float full[zh3::stored];
             zh3::hallucinate(c, full);
             return zh3::eval(full, x, y, z);
         },
         [](const float* c, std::size_t n, const float* xs, const float* ys, const float* zs,
            float* out) {
             float full[zh3::stored];
             zh3::hallucinate(c, full);
             zh3::eval_batch(full, n, xs, ys, zs, out);
         },
         [](const double* c, int bands, int, double* out) {
             double full[zh3::stored];
             zh3::hallucinate(c, full);
             return zh3::sh_expansion(full, bands, out);
         }},
    };
    return v;
}

/// The fitted representation called `name`, or nullptr.
template <class = void>
const FittedBasisInfo* find_fitted_basis(std::string_view name) noexcept {
    for (const auto& b : all_fitted_bases())
        if (name == b.name) return &b;
    return nullptr;
}

}  // namespace sphbasis
