// sphbasis: windowing of spherical-harmonic expansions against ringing (Gibbs oscillation),
// and the window strength that makes a reconstruction non-negative.
//
// A window scales band l by w_l (w_0 = 1 keeps the mean). Truncating a sharp signal (a small
// light, a bright sun in an environment map) to n bands rings: the reconstruction overshoots and
// goes negative, and irradiance computed from it can be negative too. Windows trade accuracy
// for smoothness:
//   * Hann ("Hanning"):  w_l = (1 + cos(pi l / width)) / 2 for l < width, else 0;
//   * Lanczos sigma:     w_l = sin(pi l / width) / (pi l / width) for l < width, else 0;
//   with `width` usually the band count (P.-P. Sloan, "Stupid Spherical Harmonics (SH)
//   Tricks", GDC 2008, section "Windowing"; the sigma factors of Lanczos, "Applied Analysis",
//   1956);
//   * Sloan's ringing-minimising window: the expansion g that minimises
//     ||g - f||^2 + lambda ||Laplacian g||^2 over the sphere is w_l f_lm with
//     w_l = 1 / (1 + lambda l^2 (l+1)^2)   (the Laplacian's eigenvalue is -l(l+1));
//     ringing_window() chooses the smallest lambda for which the windowed (and optionally
//     convolved, e.g. irradiance) reconstruction is certified >= a target (default 0) by
//     sh::minimum()'s lower bound, by doubling and then bisection in log(lambda).
// The cost in accuracy is reported as the L2 change (Parseval: exact), its ratio to the L2 norm,
// and a bound on the largest pointwise change (sum_l |1 - w_l| ||g_l|| sqrt((2l+1)/(4 pi))).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "sh_convolution.hpp"
#include "sh_minimum.hpp"

namespace sphbasis::sh {

namespace detail {
inline void check_width(double width, const char* fn) {
    if (!(width > 0) || !std::isfinite(width))
        sphbasis::detail::throw_invalid(fn,
                                        "a finite window width > 0, got " + std::to_string(width));
}
}  // namespace detail

/// Hann window: w_l = (1 + cos(pi l / width))/2 for l < width, 0 beyond. Throws
/// std::invalid_argument for bad bands or width <= 0.
template <class T = double>
std::vector<T> hanning_window(int bands, double width) {
    check_bands(bands, "sh::hanning_window");
    detail::check_width(width, "sh::hanning_window");
    std::vector<T> w(static_cast<std::size_t>(bands), T(0));
    for (int l = 0; l < bands && l < width; ++l)
        w[static_cast<std::size_t>(l)] =
            static_cast<T>(0.5 * (1 + std::cos(constants::pi * l / width)));
    return w;
}

/// Lanczos sigma window: w_l = sinc(pi l / width) for l < width, 0 beyond.
template <class T = double>
std::vector<T> lanczos_window(int bands, double width) {
    check_bands(bands, "sh::lanczos_window");
    detail::check_width(width, "sh::lanczos_window");
    std::vector<T> w(static_cast<std::size_t>(bands), T(0));
    for (int l = 0; l < bands && l < width; ++l) {
        const double x = constants::pi * l / width;
        w[static_cast<std::size_t>(l)] = static_cast<T>(l == 0 ? 1.0 : std::sin(x) / x);
    }
    return w;
}

/// Sloan's ringing-minimising window w_l = 1/(1 + lambda l^2 (l+1)^2), lambda >= 0 (infinity
/// keeps only the mean). Throws std::invalid_argument for bad bands or lambda < 0 or NaN.
template <class T = double>
std::vector<T> sloan_window(int bands, double lambda) {
    check_bands(bands, "sh::sloan_window");
    if (!(lambda >= 0))
        sphbasis::detail::throw_invalid("sh::sloan_window",
                                        "lambda >= 0, got " + std::to_string(lambda));
    std::vector<T> w(static_cast<std::size_t>(bands));
    for (int l = 0; l < bands; ++l) {
        const double e = double(l) * double(l) * double(l + 1) * double(l + 1);
        w[static_cast<std::size_t>(l)] =
            static_cast<T>(l == 0 ? 1.0 : (std::isinf(lambda) ? 0.0 : 1 / (1 + lambda * e)));
    }
    return w;
}

/// out_lm = window[l] in_lm (in == out allowed): convolve() under this name (the same
/// implementation, sh::detail::scale_bands, and the same coefficient types). Throws
/// std::invalid_argument for bad bands or a null buffer.
template <class T, class C>
void apply_window(int bands, const T* window, const C* in, C* out) {
    detail::scale_bands("sh::apply_window", bands, window, in, out);
}

/// apply_window() with any of window, in, out given as a contiguous range (sizes checked).
template <class W, class In, class Out, detail::not_all_pointers<W, In, Out> = 0>
void apply_window(int bands, W&& window, In&& in, Out&& out) {
    detail::scale_bands_any("sh::apply_window", bands, window, in, out);
}

/// What a window costs: for g (the coefficients, convolved with the kernel if one was given)
/// and g_w = window * g,
struct WindowCost {
    double l2_change;           ///< ||g - g_w||_2 over the sphere (exact, by Parseval)
    double relative_l2_change;  ///< l2_change / ||g||_2 (0 if g = 0)
    double max_change_bound;    ///< >= max over the sphere of |g - g_w|
};

/// The cost of applying `window` to the expansion coeffs (bands^2 values), optionally after a
/// kernel (per-band factors, e.g. clamped_cosine_kernel: the cost in irradiance).
template <class T>
WindowCost window_cost(int bands, const T* coeffs, const T* window, const T* kernel = nullptr) {
    check_bands(bands, "sh::window_cost");
    const std::size_t n = static_cast<std::size_t>(bands);
    sphbasis::detail::check_buffer("sh::window_cost", "coeffs", coeffs, n * n);
    sphbasis::detail::check_buffer("sh::window_cost", "window", window, n);
    double change2 = 0, norm2 = 0, maxb = 0;
    for (int l = 0; l < bands; ++l) {
        const double k = kernel ? static_cast<double>(kernel[l]) : 1.0;
        double band2 = 0;
        for (int i = l * l; i < (l + 1) * (l + 1); ++i) {
            const double g = static_cast<double>(coeffs[i]) * k;
            band2 += g * g;
        }
        const double d = 1 - static_cast<double>(window[l]);
        norm2 += band2;
        change2 += d * d * band2;
        maxb += std::fabs(d) * std::sqrt(band2) * std::sqrt((2 * l + 1) / constants::four_pi);
    }
    WindowCost c;
    c.l2_change = std::sqrt(change2);
    c.relative_l2_change = norm2 > 0 ? std::sqrt(change2 / norm2) : 0.0;
    c.max_change_bound = maxb;
    return c;
}

/// ringing_window()'s answer.
template <class T>
struct RingingWindow {
    double lambda;          ///< the window strength (0: no window needed; inf: impossible)
    std::vector<T> window;  ///< sloan_window(bands, lambda)
    WindowCost cost;        ///< of the window on the (convolved) function, worst channel
    T lower_bound;          ///< certified minimum of the windowed result, all channels
    bool achieved;          ///< lower_bound >= target
};

/// Sloan's ringing-minimising window for a target: the smallest lambda (to 0.1%) such that
/// the reconstruction of kernel * window * coeffs is certified >= target everywhere, for every
/// channel. coeffs holds `channels` expansions of bands^2 values one after another (e.g. R, G,
/// B); kernel (optional, per band) is applied before the test, e.g. clamped_cosine_kernel for
/// "irradiance must be non-negative". If even lambda = inf (the mean alone) is below target,
/// achieved = false and the mean-only window is returned. Assumes, as Sloan does, that the
/// minimum grows with lambda; the returned lambda is certified whatever the shape.
/// Cost: ~40 calls of minimum() per channel. Throws std::invalid_argument for bad input.
template <class T>
RingingWindow<T> ringing_window(int bands, const T* coeffs, int channels = 1,
                                const T* kernel = nullptr, double target = 0) {
    check_bands(bands, "sh::ringing_window");
    if (bands < 1 || channels < 1 || !coeffs || !std::isfinite(target))
        sphbasis::detail::throw_invalid(
            "sh::ringing_window", "bands >= 1, channels >= 1, non-null coeffs and a finite target");
    const std::size_t n2 = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    std::vector<double> work(n2);
    // Lower bound over all channels of the windowed, convolved reconstruction.
    auto lower = [&](double lambda) {
        const std::vector<double> w = sloan_window<double>(bands, lambda);
        double lb = std::numeric_limits<double>::infinity();
        for (int c = 0; c < channels; ++c) {
            const T* src = coeffs + static_cast<std::size_t>(c) * n2;
            for (int l = 0; l < bands; ++l) {
                const double f = w[static_cast<std::size_t>(l)] *
                                 (kernel ? static_cast<double>(kernel[l]) : 1.0);
                for (int i = l * l; i < (l + 1) * (l + 1); ++i)
                    work[static_cast<std::size_t>(i)] = static_cast<double>(src[i]) * f;
            }
            // A loose bound decides most lambdas; tighten only when it cannot.
            MinimumBound<double> m = minimum(bands, work.data(), 1e-3, 400000);
            if (!(m.lower_bound >= target) && !(m.value < target))
                m = minimum(bands, work.data(), 1e-7, 2000000);
            lb = std::min(lb, m.lower_bound);
            if (!(lb >= target)) break;  // one failing channel decides
        }
        return lb;
    };
    auto result = [&](double lambda, double lb, bool ok) {
        RingingWindow<T> r;
        r.lambda = lambda;
        r.window = sloan_window<T>(bands, lambda);
        r.cost = WindowCost{0, 0, 0};
        for (int c = 0; c < channels; ++c) {
            const WindowCost k = window_cost(bands, coeffs + static_cast<std::size_t>(c) * n2,
                                             r.window.data(), kernel);
            r.cost.l2_change = std::max(r.cost.l2_change, k.l2_change);
            r.cost.relative_l2_change = std::max(r.cost.relative_l2_change, k.relative_l2_change);
            r.cost.max_change_bound = std::max(r.cost.max_change_bound, k.max_change_bound);
        }
        T l = static_cast<T>(lb);
        if (static_cast<double>(l) > lb) l = std::nextafter(l, -std::numeric_limits<T>::infinity());
        r.lower_bound = l;
        r.achieved = ok;
        return r;
    };
    double lb0 = lower(0);
    if (lb0 >= target || bands == 1) return result(0, lb0, lb0 >= target);
    const double inf = std::numeric_limits<double>::infinity();
    const double lb_inf = lower(inf);
    if (!(lb_inf >= target)) return result(inf, lb_inf, false);
    // Bracket: lo fails, hi passes.
    const double L = bands - 1;
    double lo = 0, hi = 1e-4 / (L * L * (L + 1) * (L + 1)), lb_hi = lower(hi);
    for (int i = 0; i < 200 && !(lb_hi >= target); ++i) {
        lo = hi;
        hi *= 4;
        lb_hi = lower(hi);
    }
    if (!(lb_hi >= target)) return result(inf, lb_inf, true);
    for (int i = 0; i < 60 && (lo == 0 || hi > lo * 1.001); ++i) {
        const double mid = lo == 0 ? hi / 16 : std::sqrt(lo * hi);
        const double lb = lower(mid);
        if (lb >= target) {
            hi = mid;
            lb_hi = lb;
        } else {
            lo = mid;
        }
        if (lo == 0 && hi < 1e-300) break;
    }
    return result(hi, lb_hi, true);
}

}  // namespace sphbasis::sh
