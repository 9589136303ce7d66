// sphbasis: convolution of spherical-harmonic expansions with zonal kernels, band energies, and
// the Ramamoorthi-Hanrahan irradiance formula. (The certified minimum over the sphere is in
// ops/sh_minimum.hpp, the windows against ringing in ops/sh_windowing.hpp.)
//
// Funk-Hecke: for a kernel h(cos theta) about the pole, the convolution
//   (h * f)(n) = integral over the sphere of h(n . w) f(w) dw
// multiplies the coefficients of band l by
//   Lambda_l = 2 pi integral_{-1}^{1} h(t) P_l(t) dt                      (P_l Legendre)
// (= sqrt(4 pi/(2l+1)) times the kernel's own zonal coefficient on y_l0). Functions here
// return the per-band factors Lambda_l ("unnormalized") or Lambda_l / Lambda_0 ("normalized",
// a_0 = 1), and convolve() applies them.
//
// Clamped cosine max(cos theta, 0) (Ramamoorthi and Hanrahan, "An efficient representation for
// irradiance environment maps", SIGGRAPH 2001, eq. 8; Ishmukhametov, "Irradiance Normal
// Mapping" (thesis), eq. 2.3; the closed form lives in core/clamped_cosine.hpp):
//   Lambda_0 = pi, Lambda_1 = 2 pi/3, Lambda_l = 0 for odd l > 1, and for even l
//   Lambda_l = 2 pi (-1)^(l/2 + 1) / ((l + 2)(l - 1)) * binom(l, l/2) / 2^l,
// so normalized a_0 = 1, a_1 = 2/3, a_2 = 1/4, a_4 = -1/24, a_6 = 1/64, ...
// binom(l, l/2)/2^l is carried as a running product (it is < 1), so nothing overflows at any l.
// The irradiance of radiance L is E = (Lambda * L); the exit radiance of a white Lambertian
// surface is E/pi, i.e. the normalized factors (Ishmukhametov, eq. 2.3, builds the 1/pi in).
//
// Phong lobes max(cos theta, 0)^s, any real s > -1: with I_l = integral_0^1 t^s P_l(t) dt,
//   I_0 = 1/(s+1),  I_1 = 1/(s+2),  I_{l+2} = I_l (s - l)/(s + l + 3),   Lambda_l = 2 pi I_l,
// which follows from integral_0^1 x^s P_l = sqrt(pi) 2^(-s-1) Gamma(1+s) /
// (Gamma(1 + (s-l)/2) Gamma((s+l+3)/2)) (Gradshteyn-Ryzhik 7.126.2). s = 1 is the clamped
// cosine; for integer s the factor vanishes for l = s+2, s+4, ...
//
// Any kernel h(t): Funk-Hecke by Gauss-Legendre quadrature on [-1, 0] and [0, 1] separately, so
// kernels with a kink or jump at the horizon (clamped lobes, hemispherical windows) are
// integrated to full accuracy; a kernel polynomial of degree d on each half is exact with
// nodes >= (d + bands)/2.
//
// Irradiance fast path (3 bands): E(n) = n^T M n, n = (x, y, z, 1), Ramamoorthi-Hanrahan
// eqs. 11-13 with c1 = sqrt(15 pi)/16, c2 = sqrt(3 pi)/6, c3 = 3 sqrt(5 pi)/16,
// c4 = sqrt(pi)/2, c5 = sqrt(5 pi)/16 (their 0.429043, 0.511664, 0.743125, 0.886227,
// 0.247708 rounded). The quadratic form equals clamped-cosine convolution + evaluation
// exactly.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/contiguous.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"
#include "../core/scalar.hpp"
#include "../core/vec.hpp"

namespace sphbasis::sh {

/// Unnormalized: the Funk-Hecke factors Lambda_l themselves (pi, 2pi/3, pi/4 for the clamped
/// cosine: irradiance from radiance). Normalized: divided by Lambda_0 (1, 2/3, 1/4: a kernel
/// that integrates to one, e.g. Lambertian exit radiance for albedo 1).
enum class KernelScale { unnormalized, normalized };

namespace detail {

inline void normalize_kernel(std::vector<double>& k, KernelScale scale, const char* fn) {
    if (scale == KernelScale::unnormalized || k.empty()) return;
    if (!(k[0] != 0) || !std::isfinite(k[0]))
        sphbasis::detail::throw_invalid(
            fn, "a kernel with a finite non-zero integral (Lambda_0) for KernelScale::normalized");
    const double inv = 1 / k[0];
    for (double& v : k) v *= inv;
}

template <class T>
std::vector<T> cast_vector(const std::vector<double>& v) {
    std::vector<T> out(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) out[i] = static_cast<T>(v[i]);
    return out;
}

}  // namespace detail

/// Funk-Hecke factors Lambda_l, l < bands, of the clamped cosine max(cos theta, 0) by the
/// closed form (header comment). Throws std::invalid_argument for bad bands.
template <class T = double>
std::vector<T> clamped_cosine_kernel(int bands, KernelScale scale = KernelScale::unnormalized) {
    check_bands(bands, "sh::clamped_cosine_kernel");
    std::vector<double> k(static_cast<std::size_t>(bands));
    clamped_cosine_factors(bands, k.data());  // a_l = Lambda_l / pi (core/clamped_cosine.hpp)
    if (scale == KernelScale::unnormalized)
        for (double& v : k) v *= constants::pi;
    detail::normalize_kernel(k, scale, "sh::clamped_cosine_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors of the Phong lobe max(cos theta, 0)^s for real s > -1 (s = 0 is the
/// hemisphere indicator, s = 1 the clamped cosine). Normalized divides by Lambda_0 =
/// 2 pi/(s + 1), i.e. the lobe (s + 1)/(2 pi) cos^s. Throws std::invalid_argument for bad
/// bands or s <= -1.
template <class T = double>
std::vector<T> phong_kernel(int bands, double s, KernelScale scale = KernelScale::unnormalized) {
    check_bands(bands, "sh::phong_kernel");
    if (!(s > -1) || !std::isfinite(s))
        sphbasis::detail::throw_invalid("sh::phong_kernel",
                                        "an exponent s > -1, got " + std::to_string(s));
    std::vector<double> k(static_cast<std::size_t>(bands), 0.0);
    double ie = 1 / (s + 1), io = 1 / (s + 2);  // I_l for the current even and odd l
    for (int l = 0; l < bands; ++l) {
        const std::size_t i = static_cast<std::size_t>(l);
        if (l % 2 == 0) {
            k[i] = constants::two_pi * ie;
            ie *= (s - l) / (s + l + 3);
        } else {
            k[i] = constants::two_pi * io;
            io *= (s - l) / (s + l + 3);
        }
    }
    detail::normalize_kernel(k, scale, "sh::phong_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors of any zonal kernel h(t), t = cos theta, by Gauss-Legendre quadrature
/// with `nodes` points on each of [-1, 0] and [0, 1] (0: bands + 32). h is called with double
/// and returns something convertible to double. Exact for h polynomial of degree d on each
/// half when nodes >= (d + bands)/2. Cost O(nodes * bands) plus O(nodes^2) for the rule.
/// Throws std::invalid_argument for bad bands or nodes < 0.
template <class T = double, class F>
std::vector<T> zonal_kernel(int bands, F&& h, KernelScale scale = KernelScale::unnormalized,
                            int nodes = 0) {
    check_bands(bands, "sh::zonal_kernel");
    if (nodes < 0 || nodes > 100000)
        sphbasis::detail::throw_invalid(
            "sh::zonal_kernel",
            "0 <= nodes <= 100000 (0: automatic), got " + std::to_string(nodes));
    const int nq = nodes > 0 ? nodes : bands + 32;
    std::vector<double> t, w;
    gauss_legendre(nq, t, w);
    std::vector<double> k(static_cast<std::size_t>(bands), 0.0);
    for (int half = 0; half < 2; ++half)
        for (std::size_t i = 0; i < t.size(); ++i) {
            // Map [-1, 1] to [-1, 0] or [0, 1].
            const double x = half == 0 ? 0.5 * (t[i] - 1) : 0.5 * (t[i] + 1);
            const double hw = static_cast<double>(h(x)) * 0.5 * w[i];
            double p0 = 1, p1 = x;
            for (int l = 0; l < bands; ++l) {
                double pl;
                if (l == 0)
                    pl = p0;
                else if (l == 1)
                    pl = p1;
                else {
                    pl = ((2 * l - 1) * x * p1 - (l - 1) * p0) / l;
                    p0 = p1;
                    p1 = pl;
                }
                k[static_cast<std::size_t>(l)] += hw * pl;
            }
        }
    for (double& v : k) v *= constants::two_pi;
    detail::normalize_kernel(k, scale, "sh::zonal_kernel");
    return detail::cast_vector<T>(k);
}

/// Funk-Hecke factors from a zonal function's own coefficients z_l (on y_l0):
/// Lambda_l = sqrt(4 pi/(2l+1)) z_l. out may equal z.
template <class T>
void zonal_to_kernel(int bands, const T* z, T* out) {
    check_bands(bands, "sh::zonal_to_kernel");
    sphbasis::detail::check_buffer("sh::zonal_to_kernel", "z", z, static_cast<std::size_t>(bands));
    sphbasis::detail::check_buffer("sh::zonal_to_kernel", "out", out,
                                   static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l)
        out[l] = z[l] * static_cast<T>(std::sqrt(constants::four_pi / (2 * l + 1)));
}
/// The inverse of zonal_to_kernel: z_l = sqrt((2l+1)/(4 pi)) Lambda_l.
template <class T>
void kernel_to_zonal(int bands, const T* kernel, T* out) {
    check_bands(bands, "sh::kernel_to_zonal");
    sphbasis::detail::check_buffer("sh::kernel_to_zonal", "kernel", kernel,
                                   static_cast<std::size_t>(bands));
    sphbasis::detail::check_buffer("sh::kernel_to_zonal", "out", out,
                                   static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l)
        out[l] = kernel[l] * static_cast<T>(std::sqrt((2 * l + 1) / constants::four_pi));
}

namespace detail {

/// out_lm = kernel[l] in_lm, the one loop of convolve() and apply_window(); scale_bands() adds
/// the checks of their pointer API boundary under the caller's name, scale_bands_any() those of
/// the range one (each buffer checked once). The kernel is rounded once to the
/// coefficients' scalar (coefficient_scalar_t<C>: float for float and glm::vec3, double for
/// double), so float coefficients stay float and RGB types need only C * their own scalar.
template <class T, class C>
void scale_bands_unchecked(int bands, const T* kernel, const C* in, C* out) {
    using S = coefficient_scalar_t<C>;
    static_assert(sphbasis::detail::is_scalable<C, S>::value,
                  "sphbasis::sh::convolve: the coefficient type C needs C * "
                  "coefficient_scalar_t<C> (specialise sphbasis::coefficient_scalar).");
    static_assert(std::is_arithmetic_v<T>,
                  "sphbasis::sh::convolve: the kernel is float or double.");
    for (int l = 0; l < bands; ++l) {
        const S f = static_cast<S>(kernel[l]);
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) out[k] = in[k] * f;
    }
}

template <class T, class C>
void scale_bands(const char* fn, int bands, const T* kernel, const C* in, C* out) {
    check_bands(bands, fn);
    const std::size_t n = static_cast<std::size_t>(bands);
    sphbasis::detail::check_buffer(fn, "kernel", kernel, n);
    sphbasis::detail::check_buffer(fn, "in", in, n * n);
    sphbasis::detail::check_buffer(fn, "out", out, n * n);
    scale_bands_unchecked(bands, kernel, in, out);
}

/// scale_bands() for buffers given as pointers or contiguous ranges (sizes checked).
template <class K, class In, class Out>
void scale_bands_any(const char* fn, int bands, K&& kernel, In&& in, Out&& out) {
    check_bands(bands, fn);
    const std::size_t n = static_cast<std::size_t>(bands);
    auto pk = sphbasis::detail::buffer_data(fn, "kernel", kernel, n);
    auto pi = sphbasis::detail::buffer_data(fn, "in", in, n * n);
    auto po = sphbasis::detail::buffer_data(fn, "out", out, n * n);
    using C = std::remove_cv_t<std::remove_pointer_t<decltype(po)>>;
    scale_bands_unchecked(
        bands, static_cast<const std::remove_cv_t<std::remove_pointer_t<decltype(pk)>>*>(pk),
        static_cast<const C*>(pi), po);
}

/// Selects the range overloads of convolve() and apply_window(): not all three buffers pointers.
template <class K, class In, class Out>
using not_all_pointers =
    std::enable_if_t<!(std::is_pointer_v<std::decay_t<K>> && std::is_pointer_v<std::decay_t<In>> &&
                       std::is_pointer_v<std::decay_t<Out>>),
                     int>;

}  // namespace detail

/// out_lm = kernel[l] in_lm for `bands` bands (in == out allowed). C is any coefficient type
/// with C * coefficient_scalar_t<C> (float, double, glm::vec3, an RGB struct); the kernel (float
/// or double, e.g. clamped_cosine_kernel()) is rounded to that scalar. Throws
/// std::invalid_argument for bad bands or a null buffer.
template <class T, class C>
void convolve(int bands, const T* kernel, const C* in, C* out) {
    detail::scale_bands("sh::convolve", bands, kernel, in, out);
}

/// convolve() with any of kernel, in, out given as a contiguous range (std::vector, std::array,
/// std::span): kernel of at least bands values, in and out of at least bands^2 (checked).
template <class K, class In, class Out, detail::not_all_pointers<K, In, Out> = 0>
void convolve(int bands, K&& kernel, In&& in, Out&& out) {
    detail::scale_bands_any("sh::convolve", bands, kernel, in, out);
}

/// Energy per band, e_l = sum_m c_lm^2 for l < bands, of SH coefficients (bands^2 values, ACN):
/// by Parseval the squared L2 norm over the sphere of band l, invariant under rotation. T is
/// float or double. Throws std::invalid_argument for bad bands or a null coeffs.
template <class T>
std::vector<T> band_energies(int bands, const T* coeffs) {
    static_assert(std::is_floating_point_v<T>,
                  "sphbasis::sh::band_energies: the coefficients are float or double.");
    check_bands(bands, "sh::band_energies");
    sphbasis::detail::check_buffer("sh::band_energies", "coeffs", coeffs,
                                   static_cast<std::size_t>(bands));
    std::vector<T> e(static_cast<std::size_t>(bands), T(0));
    for (int l = 0; l < bands; ++l)
        for (int m = -l; m <= l; ++m) {
            const T c = coeffs[index(l, m)];
            e[static_cast<std::size_t>(l)] += c * c;
        }
    return e;
}

/// band_energies() of a contiguous range of at least bands^2 coefficients (checked).
template <class R, std::enable_if_t<sphbasis::detail::is_contiguous_range_v<R>, int> = 0>
auto band_energies(int bands, const R& coeffs) {
    check_bands(bands, "sh::band_energies");
    return band_energies(bands, sphbasis::detail::buffer_data("sh::band_energies", "coeffs", coeffs,
                                                              static_cast<std::size_t>(bands) *
                                                                  static_cast<std::size_t>(bands)));
}

// ---------------------------------------------------------------------------------------------
// Ramamoorthi-Hanrahan irradiance (3 bands)

namespace irradiance_constants {
inline constexpr double c1 = 0.42904276540489172;  // sqrt(15 pi)/16
inline constexpr double c2 = 0.51166335397324424;  // sqrt(3 pi)/6
inline constexpr double c3 = 0.74312386830112707;  // 3 sqrt(5 pi)/16
inline constexpr double c4 = 0.88622692545275801;  // sqrt(pi)/2
inline constexpr double c5 = 0.24770795610037569;  // sqrt(5 pi)/16
}  // namespace irradiance_constants

/// The symmetric 4x4 matrix M (row-major) with irradiance E(n) = n^T M n, n = (x, y, z, 1), from
/// the 9 radiance coefficients L (3 bands, this library's convention), Ramamoorthi-Hanrahan
/// eq. 12. C is any coefficient type with C + C and C * S, S = coefficient_scalar_t<C> (float,
/// double, glm::vec3, an RGB struct); the constants are rounded to T, then to S.
template <class T = double, class C>
std::array<C, 16> irradiance_matrix(const C* L) {
    using S = coefficient_scalar_t<C>;
    static_assert(sphbasis::detail::is_scalable<C, S>::value,
                  "sphbasis::sh::irradiance_matrix: the coefficient type C needs C + C and C * "
                  "coefficient_scalar_t<C> (specialise sphbasis::coefficient_scalar).");
    sphbasis::detail::check_buffer("sh::irradiance_matrix", "L", L, 9);
    namespace k = irradiance_constants;
    const S c1 = S(T(k::c1)), c2 = S(T(k::c2)), c3 = S(T(k::c3)), c4 = S(T(k::c4)),
            c5 = S(T(k::c5));
    // ACN: 0 L00, 1 L1-1, 2 L10, 3 L11, 4 L2-2, 5 L2-1, 6 L20, 7 L21, 8 L22.
    const C m01 = L[4] * c1, m02 = L[7] * c1, m03 = L[3] * c2, m12 = L[5] * c1, m13 = L[1] * c2,
            m23 = L[2] * c2;
    return {L[8] * c1, m01,          m02,       m03,  //
            m01,       L[8] * (-c1), m12,       m13,  //
            m02,       m12,          L[6] * c3, m23,  //
            m03,       m13,          m23,       L[0] * c4 + L[6] * (-c5)};
}

/// irradiance_matrix() of a contiguous range of at least 9 coefficients (checked).
template <class T = double, class R,
          std::enable_if_t<sphbasis::detail::is_contiguous_range_v<R>, int> = 0>
auto irradiance_matrix(const R& L) {
    return irradiance_matrix<T>(sphbasis::detail::buffer_data("sh::irradiance_matrix", "L", L, 9));
}

/// n^T M n with n = (x, y, z, 1), (x, y, z) normalised as by sh::eval. 10 multiply-adds; the
/// direction terms are computed in T and rounded to coefficient_scalar_t<C>.
template <class C, class T>
C eval_irradiance_matrix(const std::array<C, 16>& M, T x, T y, T z) {
    using S = coefficient_scalar_t<C>;
    normalize_or_pole(x, y, z);
    // Symmetric: diagonal once, off-diagonal twice.
    C e = M[15] + M[0] * S(x * x) + M[5] * S(y * y) + M[10] * S(z * z);
    e = e + M[1] * S(T(2) * x * y) + M[2] * S(T(2) * x * z) + M[6] * S(T(2) * y * z);
    e = e + M[3] * S(T(2) * x) + M[7] * S(T(2) * y) + M[11] * S(T(2) * z);
    return e;
}

/// eval_irradiance_matrix() at a normal of any 3-vector type (glm::vec3, Eigen::Vector3d).
template <class C, class D, std::enable_if_t<sphbasis::detail::is_direction_v<D>, int> = 0>
C eval_irradiance_matrix(const std::array<C, 16>& M, const D& n) {
    using T = direction_scalar_t<D>;
    return eval_irradiance_matrix(M, T(component<0>(n)), T(component<1>(n)), T(component<2>(n)));
}

/// Irradiance at normal (x, y, z) from 9 radiance coefficients, Ramamoorthi-Hanrahan eq. 13:
/// c1 L22 (x^2 - y^2) + c3 L20 z^2 + c4 L00 - c5 L20 + 2 c1 (L2-2 xy + L21 xz + L2-1 yz)
/// + 2 c2 (L11 x + L1-1 y + L10 z). Equal to convolve(clamped_cosine_kernel) + eval_sum.
/// C is any coefficient type with C + C and C * coefficient_scalar_t<C>; the direction terms
/// are computed in T and rounded to that scalar. Hot path: no checks beyond SPHBASIS_ASSERT.
template <class C, class T>
C irradiance(const C* L, T x, T y, T z) {
    using S = coefficient_scalar_t<C>;
    static_assert(sphbasis::detail::is_scalable<C, S>::value,
                  "sphbasis::sh::irradiance: the coefficient type C needs C + C and C * "
                  "coefficient_scalar_t<C> (specialise sphbasis::coefficient_scalar).");
    SPHBASIS_ASSERT(L != nullptr);
    namespace k = irradiance_constants;
    normalize_or_pole(x, y, z);
    const T c1 = T(k::c1), c2 = T(k::c2), c3 = T(k::c3), c4 = T(k::c4), c5 = T(k::c5);
    C e = L[8] * S(c1 * (x * x - y * y)) + L[6] * S(c3 * z * z - c5) + L[0] * S(c4);
    e = e + L[4] * S(T(2) * c1 * x * y) + L[7] * S(T(2) * c1 * x * z) + L[5] * S(T(2) * c1 * y * z);
    e = e + L[3] * S(T(2) * c2 * x) + L[1] * S(T(2) * c2 * y) + L[2] * S(T(2) * c2 * z);
    return e;
}

/// irradiance() at a normal of any 3-vector type (glm::vec3, Eigen::Vector3f, sphbasis::vec3),
/// with the 9 coefficients as C* or as a contiguous range of at least 9 (checked).
template <class LC, class D, std::enable_if_t<sphbasis::detail::is_direction_v<D>, int> = 0>
auto irradiance(const LC& L, const D& n) {
    using T = direction_scalar_t<D>;
    const auto* p = sphbasis::detail::buffer_data("sh::irradiance", "L", L, 9);
    return irradiance(p, T(component<0>(n)), T(component<1>(n)), T(component<2>(n)));
}

}  // namespace sphbasis::sh
