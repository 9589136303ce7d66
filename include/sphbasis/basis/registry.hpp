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
#include "basis.hpp"
#include "hbasis.hpp"
#include "hl2.hpp"
#include "hsh.hpp"
#include "makhotkin.hpp"
#include "sh.hpp"
#include "spherical_gaussian.hpp"
#include "zernike.hpp"

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
    };
    return v;
}

/// The basis called `name` ("sh", "hsh", "makhotkin", "zernike", "hbasis", "hbasis-mod",
/// "hl2", "sg"). Throws std::invalid_argument naming the known bases otherwise.
template <class = void>
const BasisInfo& find_basis(std::string_view name) {
    for (const auto& b : all_bases())
        if (name == b.name) return b;
    std::string known;
    for (const auto& b : all_bases()) known += std::string(known.empty() ? "" : ", ") + b.name;
    detail::throw_invalid("find_basis",
                          "one of: " + known + "; got unknown basis '" + std::string(name) + "'");
}

}  // namespace sphbasis
