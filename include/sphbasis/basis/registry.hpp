// sphbasis: every basis by name, for tools and benchmarks that choose a basis at run time
// (the CLI's --basis NAME, the IMSE benchmark). Compile-time code should use the basis types.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "basis.hpp"
#include "hbasis.hpp"
#include "hl2.hpp"
#include "hsh.hpp"
#include "makhotkin.hpp"
#include "sh.hpp"
#include "zernike.hpp"

namespace sphbasis {

/// Type-erased access to one basis.
struct BasisInfo {
    const char* name;
    Domain domain;
    bool orthonormal;
    bool (*valid_count)(int);
    const char* (*count_rule)();
    void (*eval_d)(int n, double x, double y, double z, double* out);
    void (*eval_f)(int n, float x, float y, float z, float* out);
    void (*eval_batch_f)(int n, std::size_t count, const float* xs, const float* ys,
                         const float* zs, float* out, std::size_t stride);
    void (*eval_sum_batch_f)(int n, const float* coeffs, std::size_t count, const float* xs,
                             const float* ys, const float* zs, float* out);
    /// Index of the function labelled (l, m) and the smallest size containing it; throws
    /// std::invalid_argument if the basis has no such label.
    std::pair<int, int> (*lm_index)(int l, int m);

    BasisFunctions functions(int n) const {
        if (!valid_count(n))
            throw std::invalid_argument(std::string("sphbasis::BasisInfo::functions(): expected ") +
                                        count_rule() + " functions for basis '" + name + "', got " +
                                        std::to_string(n));
        auto f = eval_d;
        return {n, [f, n](double x, double y, double z, double* out) { f(n, x, y, z, out); }};
    }
};

namespace detail {
/// (l, m) labels of bases with the SH band structure: index l(l+1)+m, size (l+1)^2.
inline std::pair<int, int> banded_lm(int l, int m) {
    if (l < 0 || m < -l || m > l)
        throw std::invalid_argument("sphbasis::lm_index(): expected l >= 0 and |m| <= l, got l = " +
                                    std::to_string(l) + ", m = " + std::to_string(m));
    return {l * (l + 1) + m, (l + 1) * (l + 1)};
}
inline std::pair<int, int> no_lm(int, int) {
    throw std::invalid_argument(
        "sphbasis::lm_index(): this basis has a fixed size; select its functions with --coeffs");
}

template <class B>
BasisInfo make_info(std::pair<int, int> (*lm)(int, int)) {
    return BasisInfo{
        B::name,
        B::domain,
        B::orthonormal,
        [](int n) { return B::valid_count(n); },
        []() { return B::count_rule(); },
        [](int n, double x, double y, double z, double* out) { basis_eval<B>(n, x, y, z, out); },
        [](int n, float x, float y, float z, float* out) { basis_eval<B>(n, x, y, z, out); },
        [](int n, std::size_t c, const float* xs, const float* ys, const float* zs, float* out,
           std::size_t stride) { basis_eval_batch<B>(n, c, xs, ys, zs, out, stride); },
        [](int n, const float* co, std::size_t c, const float* xs, const float* ys, const float* zs,
           float* out) { basis_eval_sum_batch<B>(n, co, c, xs, ys, zs, out); },
        lm};
}
}  // namespace detail

/// All bases, in the order of the CLI's help text.
inline const std::vector<BasisInfo>& all_bases() {
    static const std::vector<BasisInfo> v = {
        detail::make_info<SH>(detail::banded_lm),
        detail::make_info<HSH>(detail::banded_lm),
        detail::make_info<Makhotkin>(detail::banded_lm),
        // Zernike: band n holds m = -n, -n+2, ..., n; n + 1 bands = (n+1)(n+2)/2 functions.
        detail::make_info<Zernike>([](int n, int m) -> std::pair<int, int> {
            if (n < 0 || m < -n || m > n || (n - m) % 2 != 0)
                throw std::invalid_argument(
                    "sphbasis::lm_index(): expected n >= 0, |m| <= n and n - m even for "
                    "zernike, got n = " +
                    std::to_string(n) + ", m = " + std::to_string(m));
            return {zernike::index(n, m), (n + 1) * (n + 2) / 2};
        }),
        detail::make_info<HBasis>(detail::no_lm),
        detail::make_info<HBasisMod>(detail::no_lm),
        detail::make_info<HL2>(detail::no_lm),
    };
    return v;
}

/// The basis called `name` ("sh", "hsh", "makhotkin", "zernike", "hbasis", "hbasis-mod",
/// "hl2"). Throws std::invalid_argument naming the known bases otherwise.
inline const BasisInfo& find_basis(std::string_view name) {
    for (const auto& b : all_bases())
        if (name == b.name) return b;
    std::string known;
    for (const auto& b : all_bases()) known += std::string(known.empty() ? "" : ", ") + b.name;
    throw std::invalid_argument("sphbasis::find_basis(): unknown basis '" + std::string(name) +
                                "' (expected one of: " + known + ")");
}

}  // namespace sphbasis
