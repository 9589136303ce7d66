// sphbasis: Toksvig's mipmapped normal maps -- specular anti-aliasing from the length of an
// averaged (not renormalised) normal.
//
// Reference: M. Toksvig, "Mipmapping Normal Maps", NVIDIA technical brief, 2004. Equation
// numbers below are the brief's. Notation: L = |Na| is the length of the averaged normal Na,
// s the Blinn-Phong shininess exponent, H the half vector.
//
//   eq. 1   L = 1/(1 + sigma^2)          <=>  sigma^2 = (1 - L)/L
//   eq. 6   f_t = 1/(1 + s sigma^2)       =   L/(L + s(1 - L))
//   eq. 8   spec = (1 + f_t s)/(1 + s) * (Na.H/L)^(f_t s)
//   eq. 9   eq. 8 written with the table axes Na.H and Na.Na (L = sqrt(Na.Na))
//   eq. 10  d/dL [(1 + f_t s)/(1 + s)] = s^2 / ((1 + s)(L + s(1 - L))^2)
//   eq. 11  fade toward the aliased (Na.H/L)^s where quantisation error * eq. 10 > threshold
//   eq. 12  L = s s0/(s s0 + s0 - s) gives the shininess s under a maximum shininess s0
//
// Every function is finite for every input: lengths and cosines are clamped to [0, 1] (NaN to
// 0), and a shininess that is NaN or negative is taken as 0, +inf as the largest finite value.
//
// Corrections to the printed brief (each pinned by tests/shading/test_toksvig.cpp):
//  - eq. 8/9 as printed, (1 + f_t s X^(f_t s))/(1 + s), puts the power inside the numerator.
//    The energy argument of eq. 7 (the widened lobe integrates to 2 pi/(1 + f_t s), so it is
//    scaled by (1 + f_t s)/(1 + s)) and both table properties the brief states (row Na.Na = 1
//    equals the plain power X^s, row Na.Na = 0 is the constant 1/(1 + s)) require
//    (1 + f_t s)/(1 + s) * X^(f_t s); that is what this header implements.
//  - The brief gives the 8-bit length error as sqrt(3)/127.2 ~ 0.0068; sqrt(3)/127.2 is 0.0136.
//    The quoted 0.0068 is half a quantisation step in each of three components,
//    sqrt(3)/(2 * 127); quantization_length_error() returns that, for any bit depth.
//
// Hard cases (all finite): L is clamped to [0, 1], so lengths slightly above 1 from
// quantisation act as L = 1 and L -> 0 gives f_t -> 0, a constant lobe 1/(1 + s). pow(0, 0) is
// taken as 1 (the constant lobe at Na.H = 0). Shininess s > 0 up to 1e6 in float and double.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/vec.hpp"

namespace sphbasis::toksvig {

namespace detail {
template <class T>
SPHBASIS_FORCEINLINE T clamp01(T x) noexcept {
    // NaN maps to 0 so every later formula sees a value in [0, 1].
    return x > T(1) ? T(1) : (x > T(0) ? x : T(0));
}
/// A shininess in [0, largest finite]: NaN and negative values give 0, +inf the largest finite
/// value, so no formula below meets inf/inf or 0 * inf.
template <class T>
SPHBASIS_FORCEINLINE T finite_shininess(T s) noexcept {
    return s > T(0) ? (s < std::numeric_limits<T>::max() ? s : std::numeric_limits<T>::max())
                    : T(0);
}
}  // namespace detail

/// eq. 1: the variance sigma^2 of the normals in a footprint from the length L of their
/// average, sigma^2 = (1 - L)/L. L is clamped to [min normal, 1]: L >= 1 (including lengths
/// slightly above 1 from quantisation) gives 0, L -> 0 gives a large finite value.
template <class T>
SPHBASIS_FORCEINLINE T variance_from_length(T length) noexcept {
    const T l = std::fmax(detail::clamp01(length), std::numeric_limits<T>::min());
    return (T(1) - l) / l;
}

/// eq. 1 forward: the length of the averaged normal for a variance, L = 1/(1 + sigma^2).
/// sigma^2 < 0 is taken as 0.
template <class T>
SPHBASIS_FORCEINLINE T length_from_variance(T sigma2) noexcept {
    return T(1) / (T(1) + (sigma2 > T(0) ? sigma2 : T(0)));
}

/// eq. 6: the Toksvig factor f_t = L/(L + s(1 - L)) in [0, 1], the factor by which the
/// shininess s is scaled down. f_t -> 1 as L -> 1 and -> 0 as L -> 0. L is clamped to [0, 1];
/// s >= 0 (s = 0 and L = 0 together give 1). Cost: one division.
template <class T>
SPHBASIS_FORCEINLINE T factor(T length, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    const T l = detail::clamp01(length);
    const T den = l + shininess * (T(1) - l);
    return den > T(0) ? l / den : T(1);
}

/// eq. 6 from the variance: f_t = 1/(1 + s sigma^2).
template <class T>
SPHBASIS_FORCEINLINE T factor_from_variance(T sigma2, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    return T(1) / (T(1) + shininess * (sigma2 > T(0) ? sigma2 : T(0)));
}

/// The widened exponent s' = f_t s of eq. 5.
template <class T>
SPHBASIS_FORCEINLINE T widened_exponent(T length, T shininess) noexcept {
    return factor(length, shininess) * shininess;
}

/// The energy-preserving scale of the widened lobe, (1 + f_t s)/(1 + s): the peak of eq. 8
/// and the "relative intensity of the highlight" of the brief's figure 4. 1 at L = 1,
/// 1/(1 + s) at L = 0.
template <class T>
SPHBASIS_FORCEINLINE T relative_intensity(T length, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    return (T(1) + widened_exponent(length, shininess)) / (T(1) + shininess);
}

/// eq. 8: the energy-preserving Blinn-Phong term (1 + f_t s)/(1 + s) * (Na.H/L)^(f_t s), with
/// na_dot_h = Na.H and length = L = |Na|. The cosine Na.H/L is clamped to [0, 1] (back-facing
/// half vectors give 0, or the constant 1/(1 + s) when f_t s = 0); L is clamped to [0, 1].
template <class T>
SPHBASIS_FORCEINLINE T specular(T na_dot_h, T length, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    const T l = detail::clamp01(length);
    const T sp = widened_exponent(l, shininess);
    const T c = l > T(0) ? detail::clamp01(na_dot_h / l) : T(0);
    return (T(1) + sp) / (T(1) + shininess) * std::pow(c, sp);
}

/// eq. 9: eq. 8 in terms of the 2D table axes na_dot_h = Na.H and na_dot_na = Na.Na (the
/// square root is taken here, not by the caller). Na.Na is clamped to [0, 1].
template <class T>
SPHBASIS_FORCEINLINE T specular_from_dots(T na_dot_h, T na_dot_na, T shininess) noexcept {
    return specular(na_dot_h, std::sqrt(detail::clamp01(na_dot_na)), shininess);
}

/// eq. 2: the traditional (aliased) Blinn-Phong term (Na.H/|Na|)^s of the renormalised normal,
/// from the table axes. Cosine clamped to [0, 1]; Na.Na = 0 gives 0 (pow(0, s), s > 0).
template <class T>
SPHBASIS_FORCEINLINE T aliased_specular(T na_dot_h, T na_dot_na, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    const T l = std::sqrt(detail::clamp01(na_dot_na));
    const T c = l > T(0) ? detail::clamp01(na_dot_h / l) : T(0);
    return std::pow(c, shininess);
}

/// eq. 10: the sensitivity of the relative intensity to error in L,
/// s^2/((1 + s)(L + s(1 - L))^2); s^2/(1 + s) at L = 1, and 1 at L = 0, s = 0 (the limit along
/// L = 0). L clamped to [0, 1], s > 0.
template <class T>
SPHBASIS_FORCEINLINE T sensitivity(T length, T shininess) noexcept {
    shininess = detail::finite_shininess(shininess);
    const T l = detail::clamp01(length);
    const T den = l + shininess * (T(1) - l);
    // L = 0 and s = 0 together: the limit along L = 0, 1/(1 + s) -> 1. Factored so that no
    // intermediate overflows for the largest finite s.
    if (!(den > T(0))) return T(1);
    return shininess / (T(1) + shininess) * (shininess / den) / den;
}

/// The worst-case error in L of a normal stored with `bits`-bit signed normalised (SNORM)
/// components: half a step 1/(2^(bits-1) - 1) in each of three components,
/// sqrt(3)/(2 (2^(bits-1) - 1)); 0.0068190 for 8 bits (the brief's 0.0068). Throws
/// std::invalid_argument unless 2 <= bits <= 32.
template <class T = double>
T quantization_length_error(int bits) {
    if (bits < 2 || bits > 32)
        sphbasis::detail::check_range("toksvig::quantization_length_error", "bits", bits, 2, 32);
    const double steps = std::ldexp(1.0, bits - 1) - 1.0;
    return static_cast<T>(0.86602540378443865 / steps);  // sqrt(3)/2 / steps
}

/// eq. 11: the 2D-table value faded toward the aliased formula where the intensity error
/// length_error * sensitivity(L, s) exceeds `threshold`: with w = threshold/error (w = 1 where
/// error <= threshold), w * eq. 9 + (1 - w) * eq. 2. length_error <= 0 or threshold <= 0 with
/// a zero error gives eq. 9; threshold <= 0 with a positive error gives eq. 2.
template <class T>
SPHBASIS_FORCEINLINE T faded_specular(T na_dot_h, T na_dot_na, T shininess, T length_error,
                                      T threshold) noexcept {
    const T anti = specular_from_dots(na_dot_h, na_dot_na, shininess);
    const T error = length_error * sensitivity(std::sqrt(detail::clamp01(na_dot_na)), shininess);
    if (!(error > threshold)) return anti;
    const T w = threshold > T(0) ? threshold / error : T(0);
    return w * anti + (T(1) - w) * aliased_specular(na_dot_h, na_dot_na, shininess);
}

/// eq. 12 (free gloss maps): the length to scale a base normal to so that a surface with
/// maximum shininess s0 shows shininess s, L = s s0/(s s0 + s0 - s); the inverse of eq. 6 in
/// the sense factor(L, s0) * s0 == s. s is clamped to [0, s0] (s >= s0 gives 1, s <= 0 gives
/// 0); s0 > 0.
template <class T>
SPHBASIS_FORCEINLINE T gloss_normal_scale(T shininess, T max_shininess) noexcept {
    const T s0 = max_shininess;
    const T s = shininess > s0 ? s0 : (shininess > T(0) ? shininess : T(0));
    const T den = s * s0 + s0 - s;
    return den > T(0) ? s * s0 / den : T(1);
}

/// log2 of sigma = sqrt(eq. 1), the quantity the brief's environment-map section sets the
/// level of detail from. Finite: sigma^2 is floored at the smallest normal number, so L >= 1
/// gives 0.5 log2(min normal) (-511 for double, -63 for float).
template <class T>
SPHBASIS_FORCEINLINE T log2_sigma(T length) noexcept {
    return T(0.5) *
           std::log2(std::fmax(variance_from_length(length), std::numeric_limits<T>::min()));
}

/// Environment-map level of detail that blurs a reflection by the normal spread sigma:
/// lod = log2(sigma) + log2(level0_texels_per_radian), the mip level whose texels span sigma
/// radians, clamped to [0, max_lod]. For a cube map of face size N use 2N/pi texels per radian
/// (the face average) or N/2 (the face centre). Add it to the lod of the reflection lookup.
template <class T>
SPHBASIS_FORCEINLINE T env_lod(T length, T level0_texels_per_radian, T max_lod) noexcept {
    const T lod = log2_sigma(length) +
                  std::log2(std::fmax(level0_texels_per_radian, std::numeric_limits<T>::min()));
    return lod > max_lod ? max_lod : (lod > T(0) ? lod : T(0));
}

// ---------------------------------------------------------------------------------------------
// The 2D lookup table of eq. 9.

/// Where the table samples its axes. `endpoints`: axis value k/(size - 1), so the rows
/// Na.Na = 0 and Na.Na = 1 and the column Na.H = 1 are stored exactly (sample a texture made of
/// it at ((k/(size-1)) (size-1) + 0.5)/size). `texel_centres`: axis value (k + 0.5)/size, the
/// value a GPU reads at the texel centre when addressed directly with Na.H and Na.Na.
enum class TableSampling { endpoints, texel_centres };

/// Options of make_specular_table().
struct SpecularTableOptions {
    int width = 256;          ///< samples along Na.H in [0, 1] (columns)
    int height = 256;         ///< samples along Na.Na in [0, 1] (rows)
    double shininess = 32;    ///< s, > 0
    int normal_bits = 0;      ///< > 0: fade with eq. 11 for a normal map of this bit depth
    double threshold = 0.05;  ///< eq. 11 threshold on the intensity error
    TableSampling sampling = TableSampling::endpoints;
};

/// The eq. 9 table: value[row * width + col] at Na.H = axis(col), Na.Na = axis(row).
/// used[k] is 0 where Na.H > sqrt(Na.Na), the region no normal can reach (a third of the
/// table in the limit); those cells hold the value at Na.H = sqrt(Na.Na), a continuous
/// extension so bilinear filtering at the boundary stays correct.
struct SpecularTable {
    int width = 0, height = 0;
    TableSampling sampling = TableSampling::endpoints;
    std::vector<float> value;
    std::vector<std::uint8_t> used;

    /// Axis value of column/row k.
    double axis(int k, int size) const noexcept {
        return sampling == TableSampling::endpoints ? (size > 1 ? double(k) / (size - 1) : 1.0)
                                                    : (k + 0.5) / size;
    }
    double na_dot_h(int col) const noexcept { return axis(col, width); }
    double na_dot_na(int row) const noexcept { return axis(row, height); }
    float at(int col, int row) const noexcept {
        return value[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                     static_cast<std::size_t>(col)];
    }
    bool is_used(int col, int row) const noexcept {
        return used[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(col)] != 0;
    }
};

/// Builds the eq. 9 table (eq. 11 faded if options.normal_bits > 0), any size, in double
/// rounded to float. Throws std::invalid_argument for width or height < 1 (< 2 with
/// endpoint sampling), shininess <= 0 or not finite, normal_bits outside [0, 32] or 1,
/// threshold < 0. Cost: width * height pow calls.
inline SpecularTable make_specular_table(const SpecularTableOptions& o) {
    const int min_size = o.sampling == TableSampling::endpoints ? 2 : 1;
    if (o.width < min_size || o.height < min_size)
        sphbasis::detail::throw_invalid("toksvig::make_specular_table",
                                        "width and height >= " + std::to_string(min_size) +
                                            ", got " + std::to_string(o.width) + " x " +
                                            std::to_string(o.height));
    if (!(o.shininess > 0) || !std::isfinite(o.shininess))
        sphbasis::detail::throw_invalid(
            "toksvig::make_specular_table",
            "a finite shininess > 0, got " + std::to_string(o.shininess));
    if (o.normal_bits < 0 || o.normal_bits == 1 || o.normal_bits > 32)
        sphbasis::detail::throw_invalid(
            "toksvig::make_specular_table",
            "normal_bits 0 (no fade) or 2..32, got " + std::to_string(o.normal_bits));
    if (!(o.threshold >= 0))
        sphbasis::detail::throw_invalid("toksvig::make_specular_table",
                                        "threshold >= 0, got " + std::to_string(o.threshold));
    SpecularTable t;
    t.width = o.width;
    t.height = o.height;
    t.sampling = o.sampling;
    const std::size_t n = static_cast<std::size_t>(o.width) * static_cast<std::size_t>(o.height);
    t.value.resize(n);
    t.used.resize(n);
    const double err = o.normal_bits > 0 ? quantization_length_error<double>(o.normal_bits) : 0.0;
    for (int row = 0; row < o.height; ++row) {
        const double nn = t.na_dot_na(row);
        const double len = std::sqrt(nn);
        for (int col = 0; col < o.width; ++col) {
            const double nh = t.na_dot_h(col);
            const bool used = !(nh > len);
            const double x = used ? nh : len;
            const double v = o.normal_bits > 0
                                 ? faded_specular(x, nn, o.shininess, err, o.threshold)
                                 : specular_from_dots(x, nn, o.shininess);
            const std::size_t k =
                static_cast<std::size_t>(row) * static_cast<std::size_t>(o.width) +
                static_cast<std::size_t>(col);
            t.value[k] = static_cast<float>(v);
            t.used[k] = used ? 1 : 0;
        }
    }
    return t;
}

/// The 1D table of the traditional renormalised lookup, (k/(size - 1))^s (endpoints) or
/// ((k + 0.5)/size)^s (texel centres): the row Na.Na = 1 of make_specular_table().
inline std::vector<float> make_power_table(int size, double shininess,
                                           TableSampling sampling = TableSampling::endpoints) {
    const int min_size = sampling == TableSampling::endpoints ? 2 : 1;
    if (size < min_size)
        sphbasis::detail::throw_invalid(
            "toksvig::make_power_table",
            "size >= " + std::to_string(min_size) + ", got " + std::to_string(size));
    if (!(shininess > 0) || !std::isfinite(shininess))
        sphbasis::detail::throw_invalid("toksvig::make_power_table",
                                        "a finite shininess > 0, got " + std::to_string(shininess));
    std::vector<float> out(static_cast<std::size_t>(size));
    for (int k = 0; k < size; ++k) {
        const double x =
            sampling == TableSampling::endpoints ? double(k) / (size - 1) : (k + 0.5) / size;
        out[static_cast<std::size_t>(k)] = static_cast<float>(std::pow(x, shininess));
    }
    return out;
}

// ---------------------------------------------------------------------------------------------
// Normal-map mip chains without renormalisation.

/// Decodes an 8-bit SNORM component (-127..127 -> -1..1; -128 -> -1, as D3D10+ and GL do).
inline float decode_snorm8(std::int8_t c) noexcept {
    const float v = static_cast<float>(c) * (1.0f / 127.0f);
    return v < -1.0f ? -1.0f : v;
}
/// Decodes an 8-bit UNORM component with the usual 2c/255 - 1 bias (0..255 -> -1..1).
inline float decode_unorm8(std::uint8_t c) noexcept {
    // (c - 127.5) / 127.5 is exact at both ends (0 -> -1, 255 -> +1) under any contraction;
    // c * (2/255) - 1 becomes 0.99999994 at 255 when the compiler fuses it into an FMA.
    return (static_cast<float>(c) - 127.5f) / 127.5f;
}

/// One level of a normal-map mip chain: the averaged, not renormalised, normals and their
/// lengths L = |Na| (row-major, index row * width + col).
template <class T>
struct NormalMipLevel {
    int width = 0, height = 0;
    std::vector<vec3<T>> normal;
    std::vector<T> length;
};

/// Builds the mip chain of a width x height normal map (row-major) by box filtering without
/// renormalisation, down to 1 x 1; level 0 is the input as given (lengths of quantised normals
/// may be slightly above or below 1). Each level halves each dimension (floor, at least 1); a
/// texel of the next level averages the contiguous block of 1, 2 or 3 texels per axis that
/// partitions the level above (exactly the 2 x 2 box for even sizes), so a constant map stays
/// constant and the chain is exact for powers of two. Other 3-vector types (glm::vec3,
/// Eigen::Vector3f, ...) and contiguous ranges of them: the overloads below. Throws
/// std::invalid_argument for a non-positive size or a null pointer.
template <class T>
std::vector<NormalMipLevel<T>> build_normal_mips(const vec3<T>* normals, int width, int height) {
    if (width < 1 || height < 1 || normals == nullptr)
        sphbasis::detail::throw_invalid("toksvig::build_normal_mips",
                                        "width, height >= 1 and a non-null normal array, got " +
                                            std::to_string(width) + " x " + std::to_string(height) +
                                            (normals == nullptr ? " and null" : ""));
    auto idx = [](int col, int row, int w) {
        return static_cast<std::size_t>(row) * static_cast<std::size_t>(w) +
               static_cast<std::size_t>(col);
    };
    auto finish = [](NormalMipLevel<T>& lv) {
        lv.length.resize(lv.normal.size());
        for (std::size_t k = 0; k < lv.normal.size(); ++k)
            lv.length[k] = std::sqrt(dot(lv.normal[k], lv.normal[k]));
    };
    std::vector<NormalMipLevel<T>> chain;
    NormalMipLevel<T> base;
    base.width = width;
    base.height = height;
    base.normal.assign(normals, normals + idx(0, height, width));
    finish(base);
    chain.push_back(std::move(base));
    while (chain.back().width > 1 || chain.back().height > 1) {
        const NormalMipLevel<T>& up = chain.back();
        NormalMipLevel<T> lv;
        lv.width = up.width > 1 ? up.width / 2 : 1;
        lv.height = up.height > 1 ? up.height / 2 : 1;
        lv.normal.resize(idx(0, lv.height, lv.width));
        for (int r = 0; r < lv.height; ++r) {
            const int r0 = static_cast<int>(static_cast<long long>(r) * up.height / lv.height);
            const int r1 = static_cast<int>(static_cast<long long>(r + 1) * up.height / lv.height);
            for (int c = 0; c < lv.width; ++c) {
                const int c0 = static_cast<int>(static_cast<long long>(c) * up.width / lv.width);
                const int c1 =
                    static_cast<int>(static_cast<long long>(c + 1) * up.width / lv.width);
                vec3<T> sum{T(0), T(0), T(0)};
                for (int rr = r0; rr < r1; ++rr)
                    for (int cc = c0; cc < c1; ++cc) {
                        const vec3<T>& n = up.normal[idx(cc, rr, up.width)];
                        sum.x += n.x;
                        sum.y += n.y;
                        sum.z += n.z;
                    }
                const T inv = T(1) / static_cast<T>((r1 - r0) * (c1 - c0));
                lv.normal[idx(c, r, lv.width)] = {sum.x * inv, sum.y * inv, sum.z * inv};
            }
        }
        finish(lv);
        chain.push_back(std::move(lv));
    }
    return chain;
}

namespace detail {
template <class N>
struct is_vec3 : std::false_type {};
template <class T>
struct is_vec3<vec3<T>> : std::true_type {};
}  // namespace detail

/// build_normal_mips() for normals of any other 3-vector type (glm::vec3, Eigen::Vector3f, ...),
/// in its scalar type (float or double). Costs one copy of level 0 more.
template <class N, std::enable_if_t<sphbasis::detail::is_direction_v<N> &&
                                        !detail::is_vec3<std::remove_cv_t<N>>::value,
                                    int> = 0>
auto build_normal_mips(const N* normals, int width, int height) {
    using T = direction_scalar_t<N>;
    static_assert(std::is_floating_point_v<T>,
                  "sphbasis::toksvig::build_normal_mips: normals have float or double components.");
    std::vector<vec3<T>> v;
    if (normals != nullptr && width >= 1 && height >= 1) {
        v.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
        for (std::size_t k = 0; k < v.size(); ++k)
            v[k] = {static_cast<T>(component<0>(normals[k])),
                    static_cast<T>(component<1>(normals[k])),
                    static_cast<T>(component<2>(normals[k]))};
    }
    return build_normal_mips(normals != nullptr ? v.data() : nullptr, width, height);
}

/// build_normal_mips() for a contiguous range of normals (std::vector<glm::vec3>, ...), size
/// checked: at least width * height elements.
template <class Normals, class = decltype(std::declval<const Normals&>().data()),
          class = decltype(std::declval<const Normals&>().size())>
auto build_normal_mips(const Normals& normals, int width, int height) {
    if (width >= 1 && height >= 1 &&
        static_cast<std::size_t>(normals.size()) <
            static_cast<std::size_t>(width) * static_cast<std::size_t>(height))
        sphbasis::detail::throw_invalid(
            "toksvig::build_normal_mips",
            "a normal array of width * height = " +
                std::to_string(static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) +
                " elements, got " + std::to_string(normals.size()));
    return build_normal_mips(normals.data(), width, height);
}

/// The Toksvig factor (eq. 6) of every texel of a mip level, for shininess s.
template <class T>
std::vector<T> factor_map(const NormalMipLevel<T>& level, T shininess) {
    std::vector<T> out(level.length.size());
    for (std::size_t k = 0; k < out.size(); ++k) out[k] = factor(level.length[k], shininess);
    return out;
}

}  // namespace sphbasis::toksvig
