// sphbasis: the kernels and the basis interface (basis/basis.hpp) shared by the hemispherical
// bases evaluated by the normalised Jacobi recurrence (basis/detail/jacobi.hpp): HSH (hsh.hpp),
// Makhotkin (makhotkin.hpp) and Zernike (zernike.hpp). Internal: users include those headers.
//
// A family type Fam supplies, beside `static constexpr hemi::Family family`:
//   prep(x, y, z, zc, X, Y, E)            the recurrence inputs of a direction, any value type
//                                         (float, double, batch, sphbasis::extended);
//   rows<Cap>(bands, zc, X, Y, E, store)  the row recurrence in the basis' order, bands <= Cap;
//   index(band, m)                        the function index of the label (band, m).
// Kernels: a compile-time band count (<= 8) gets the row recurrence unrolled, <= 64 bands the
// row recurrence, more the column recurrence (lane by lane for batches).
#pragma once

#include <string>
#include <type_traits>
#include <utility>

#include "../../config.hpp"
#include "../../core/scalar.hpp"
#include "../basis.hpp"
#include "../sh.hpp"
#include "jacobi.hpp"

namespace sphbasis::detail::hemi {

/// ACN order (index l(l+1) + m) and its row recurrence, for families with step 1: derive Fam
/// from Acn<Fam>.
template <class Fam>
struct Acn {
    static constexpr int index(int l, int m) noexcept { return l * (l + 1) + m; }
    template <int Cap, class V, class Store>
    static SPHBASIS_FORCEINLINE void rows(int bands, const V& zc, const V& X, const V& Y,
                                          const V& E, Store&& store) noexcept {
        rows_acn<Fam, Cap>(bands, zc, X, Y, E, store);
    }
};

/// The row recurrence: N > 0, exactly N bands (the compiler unrolls it and keeps it in
/// registers); N = 0, `bands` <= max_row_bands bands.
template <class Fam, int N>
struct RowKernelOf {
    int bands = N;
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z,
                                         Store&& store) const noexcept {
        V zc, X, Y, E;
        Fam::prep(x, y, z, zc, X, Y, E);
        if constexpr (N > 0)
            Fam::template rows<N>(N, zc, X, Y, E, store);
        else
            Fam::template rows<max_row_bands>(bands, zc, X, Y, E, store);
    }
};
template <class Fam, int N>
using FixedRowKernel = RowKernelOf<Fam, N>;
template <class Fam>
using RowKernel = RowKernelOf<Fam, 0>;

/// Any band count: the column recurrence in sphbasis::extended.
template <class Fam>
struct ColumnKernel {
    int bands;
    template <class V, class Store>
    void operator()(const V& x, const V& y, const V& z, Store&& store) const {
        columns_any(
            Fam::family, bands, x, y, z, store,
            [](extended dx, extended dy, extended dz, extended& zc, extended& X, extended& Y,
               extended& E) { Fam::prep(dx, dy, dz, zc, X, Y, E); },
            [](int b, int m) { return Fam::index(b, m); });
    }
};

/// bands > 8: RowKernel<Fam> (<= max_row_bands bands) or ColumnKernel<Fam>. For float and
/// double it passes the direction by value to one out-of-line function: the caller's kernel
/// lambda, which holds the direction by reference, then stays small enough to be inlined, and
/// the direction of the unrolled kernels stays in registers instead of being stored for this
/// path and loaded back (~1/3 of a 4-function call). Batches run the recurrences inline.
template <class Fam>
struct LargeKernel {
    int bands;
    template <class V, class Store>
    SPHBASIS_FORCEINLINE void operator()(const V& x, const V& y, const V& z, Store&& store) const {
        if constexpr (std::is_floating_point_v<V>) {
            large<V, std::decay_t<Store>>(bands, x, y, z, store);
        } else if (bands <= max_row_bands) {
            RowKernel<Fam>{bands}(x, y, z, store);
        } else {
            ColumnKernel<Fam>{bands}(x, y, z, store);
        }
    }
    template <class V, class Store>
    SPHBASIS_NOINLINE static void large(int bands, V x, V y, V z, Store store) {
        if (bands <= max_row_bands)
            RowKernel<Fam>{bands}(x, y, z, store);
        else
            ColumnKernel<Fam>{bands}(x, y, z, store);
    }
};

/// Calls f(kernel) with the fastest kernel for 1 <= bands: Fixed<bands> up to 8 bands, else
/// LargeKernel<Fam>. Inlined into the caller, so that the one-call path has no call, no frame
/// and no reload of the direction between the band-count check and the unrolled kernel.
template <template <int> class Fixed, class Fam, class F>
SPHBASIS_FORCEINLINE decltype(auto) with_bands_kernel(int bands, F&& f) {
#define SPHBASIS_HEMI_FIXED_CASE(N) \
    case N:                         \
        return f(Fixed<N>{});
    switch (bands) {
        SPHBASIS_HEMI_FIXED_CASE(1)
        SPHBASIS_HEMI_FIXED_CASE(2)
        SPHBASIS_HEMI_FIXED_CASE(3)
        SPHBASIS_HEMI_FIXED_CASE(4)
        SPHBASIS_HEMI_FIXED_CASE(5)
        SPHBASIS_HEMI_FIXED_CASE(6)
        SPHBASIS_HEMI_FIXED_CASE(7)
        SPHBASIS_HEMI_FIXED_CASE(8)
        default:
            return f(LargeKernel<Fam>{bands});
    }
#undef SPHBASIS_HEMI_FIXED_CASE
}

/// Square function counts: n bands = n^2 functions.
struct SquareCount {
    static constexpr int count(int bands) noexcept { return bands * bands; }
    /// The band count of n functions, or -1 if n is not a positive square.
    static int bands_of(int n) noexcept { return sh::bands_of_count(n); }
    static constexpr const char* rule = "a square number (bands^2";
};

/// The basis interface of a hemispherical basis orthonormal on the upper hemisphere: Count's
/// band-count rule (count, bands_of, rule), 1 <= bands <= MaxBands, the kernels of
/// with_bands_kernel<Fixed, Fam>. The basis type derives from it and adds its `name`.
template <class Count, int MaxBands, class Fam, template <int> class Fixed>
struct HemiBasis {
    static constexpr Domain domain = Domain::hemisphere;
    static constexpr bool orthonormal = true;
    static constexpr int max_bands = MaxBands;
    /// Number of functions in `bands` bands.
    static constexpr int count(int bands) noexcept { return Count::count(bands); }
    /// The band count of `count` functions, or -1 if it is no size of this basis.
    static int bands_of(int count) noexcept { return Count::bands_of(count); }
    static bool valid_count(int count) noexcept {
        const int b = bands_of(count);
        return b >= 1 && b <= MaxBands;
    }
    /// "a square number (bands^2, bands <= 2048) of", from Count's rule and MaxBands.
    static const char* count_rule() {
        static const std::string rule =
            std::string(Count::rule) + ", bands <= " + std::to_string(MaxBands) + ") of";
        return rule.c_str();
    }
    static int max_count() noexcept { return count(MaxBands); }
    /// Precondition: valid_count(count). Batch stores need lane(k, i, v) above 64 bands.
    template <class F>
    static SPHBASIS_FORCEINLINE decltype(auto) with_kernel(int count, F&& f) {
        return hemi::with_bands_kernel<Fixed, Fam>(bands_of(count), std::forward<F>(f));
    }
    /// Precondition: 1 <= bands <= max_bands.
    template <class F>
    static SPHBASIS_FORCEINLINE decltype(auto) with_bands_kernel(int bands, F&& f) {
        return hemi::with_bands_kernel<Fixed, Fam>(bands, std::forward<F>(f));
    }
    /// The kernel of exactly N bands: unrolled for N <= 8, the row recurrence above (N <= 64).
    template <int N>
    static constexpr auto fixed_kernel() noexcept {
        static_assert(N >= 1 && N <= max_row_bands,
                      "sphbasis: compile-time band counts are 1..64.");
        if constexpr (N <= 8)
            return Fixed<N>{};
        else
            return RowKernel<Fam>{N};
    }
};

}  // namespace sphbasis::detail::hemi

/// Expanded in a hemispherical basis' namespace detail after its family Fam and its
/// FixedKernel<N>: the kernel names RowKernel and ColumnKernel (<= 64 bands, any band count) and
/// with_bands_kernel(bands, f), which calls f(kernel) with the fastest kernel for
/// 1 <= bands <= max_bands.
// clang-format off
#define SPHBASIS_HEMI_KERNELS(Fam)                                                                 \
    using RowKernel = ::sphbasis::detail::hemi::RowKernel<Fam>;                                    \
    using ColumnKernel = ::sphbasis::detail::hemi::ColumnKernel<Fam>;                              \
    template <class F>                                                                             \
    inline decltype(auto) with_bands_kernel(int bands, F&& f) {                                    \
        return ::sphbasis::detail::hemi::with_bands_kernel<FixedKernel, Fam>(                      \
            bands, std::forward<F>(f));                                                            \
    }                                                                                              \
    static_assert(true, "SPHBASIS_HEMI_KERNELS ends with a semicolon")
// clang-format on
