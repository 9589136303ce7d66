// sphbasis: fully normalised associated Legendre functions Pbar_l^m(cos t) without the
// Condon-Shortley phase, by the standard three-term recurrence in the degree l for fixed order m.
// Standard library only (evaluation tier).
//
// Normalisation: 2 pi int_{-1}^{1} (Pbar_l^m)^2 dz = 1, so y_l0 = Pbar_l^0 and
// y_lm = sqrt(2) Pbar_l^|m| cos(m phi) / sin(|m| phi) are the library's real SH (basis/sh.hpp).
// Recurrence: the standard forward column recursion of the fully normalised functions (Holmes
// and Featherstone, "A unified approach to the Clenshaw summation and the recursive computation
// of very high degree and order normalised associated Legendre functions", Journal of Geodesy
// 2002, eqs. 11-13), with the coefficients factored as below:
//   Pbar_m^m     = sqrt((2m + 1) / (2m)) sin(t) Pbar_{m-1}^{m-1},   Pbar_0^0 = 1 / sqrt(4 pi),
//   Pbar_{m+1}^m = sqrt(2m + 3) z Pbar_m^m,
//   Pbar_l^m     = a_lm (z Pbar_{l-1}^m - b_lm Pbar_{l-2}^m),   l >= m + 2, with
//   a_lm = sqrt((4 l^2 - 1) / ((l - m)(l + m))),
//   b_lm = sqrt(((l - 1 - m)(l - 1 + m)) / (4 (l - 1)^2 - 1)).
// legendre_a() and legendre_b() are the one definition of the coefficients: the SH high-degree
// column recurrence (basis/sh.hpp) computes them on the fly, the Legendre class tabulates them.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "../config.hpp"
#include "constants.hpp"

namespace sphbasis {

/// a_lm of the recurrence (header comment), 0 <= m, l >= m + 2 (m + 1 is also finite).
/// Exact integer arithmetic before the square root for l < 2^25.
SPHBASIS_FORCEINLINE double legendre_a(int l, int m) noexcept {
    const double dl = l, dm = m;
    return std::sqrt((4 * dl * dl - 1) / ((dl - dm) * (dl + dm)));
}

/// b_lm of the recurrence (header comment), 0 <= m, l >= m + 2.
SPHBASIS_FORCEINLINE double legendre_b(int l, int m) noexcept {
    const double dl = l, dm = m;
    return std::sqrt(((dl - 1 - dm) * (dl - 1 + dm)) / (4 * (dl - 1) * (dl - 1) - 1));
}

/// Pbar_l^m for 0 <= m <= l < bands from tabulated a_lm, b_lm (2 bands^2 / 2 doubles): for many
/// evaluations at one band count (projections of maps, hemispherical Gram matrices).
/// Values are order-major: (l, m) at index(l, m), contiguous in l for each m. Sectoral values
/// that underflow (sin^m t below 1e-300 near the poles) end the m loop: the functions they start
/// are negligible there (below ~1e-280 for any l < bands <= 4096).
class Legendre {
  public:
    /// Tables for `bands` >= 0 bands. Cost O(bands^2) square roots.
    explicit Legendre(int bands) : bands_(bands < 0 ? 0 : bands) {
        a_.assign(size(), 0.0);
        b_.assign(size(), 0.0);
        for (int m = 0; m < bands_; ++m)
            for (int l = m + 2; l < bands_; ++l) {
                a_[index(l, m)] = legendre_a(l, m);
                b_[index(l, m)] = legendre_b(l, m);
            }
    }
    int bands() const noexcept { return bands_; }
    /// Number of values, bands (bands + 1) / 2.
    std::size_t size() const noexcept {
        return static_cast<std::size_t>(bands_) * static_cast<std::size_t>(bands_ + 1) / 2;
    }
    /// Position of (l, m), 0 <= m <= l < bands: m bands - m (m - 1) / 2 + l - m.
    std::size_t index(int l, int m) const noexcept {
        const long long mm = m;
        return static_cast<std::size_t>(mm * bands_ - mm * (mm - 1) / 2 + (l - m));
    }

    /// Fills out[0 .. size()) from z = cos t and s = sin t >= 0 (zeros where the sectoral
    /// value underflowed); returns the number of orders m computed.
    int eval(double z, double s, double* out) const noexcept {
        std::fill(out, out + size(), 0.0);
        double pmm = constants::inv_sqrt_four_pi;
        int m = 0;
        for (; m < bands_; ++m) {
            if (m > 0) pmm *= std::sqrt((2.0 * m + 1) / (2.0 * m)) * s;
            if (std::fabs(pmm) < 1e-300) break;
            double* o = out + index(m, m);
            o[0] = pmm;
            if (m + 1 >= bands_) continue;
            const double* a = a_.data() + index(m, m);
            const double* b = b_.data() + index(m, m);
            double p1 = pmm, p2 = std::sqrt(2.0 * m + 3) * z * pmm;
            o[1] = p2;
            for (int k = 2; k < bands_ - m; ++k) {
                const double p = a[k] * (z * p2 - b[k] * p1);
                o[k] = p;
                p1 = p2;
                p2 = p;
            }
        }
        return m;
    }

    /// out[index(l, m)] = sum_g w[g] Pbar_l^m(z[g]) for 1 <= count <= 8 points at once (the
    /// recurrences run interleaved, which hides their latency); s[g] = sin t >= 0. Same
    /// underflow rule as eval().
    void eval_weighted_sum(int count, const double* z, const double* s, const double* w,
                           double* out) const noexcept {
        constexpr int G = 8;
        SPHBASIS_ASSERT(count >= 1 && count <= G);
        std::fill(out, out + size(), 0.0);
        double zz[G], ss[G], ww[G], pmm[G], p1[G], p2[G];
        for (int g = 0; g < G; ++g) {
            const bool on = g < count;
            zz[g] = on ? z[g] : 0.0;
            ss[g] = on ? s[g] : 0.0;
            ww[g] = on ? w[g] : 0.0;
            pmm[g] = on ? constants::inv_sqrt_four_pi : 0.0;
        }
        for (int m = 0; m < bands_; ++m) {
            double big = 0;
            if (m > 0) {
                const double f = std::sqrt((2.0 * m + 1) / (2.0 * m));
                for (int g = 0; g < G; ++g) {
                    pmm[g] *= f * ss[g];
                    if (std::fabs(pmm[g]) < 1e-300) pmm[g] = 0;  // no denormals
                }
            }
            for (int g = 0; g < G; ++g) big = std::max(big, std::fabs(pmm[g]));
            if (big == 0) break;
            double* o = out + index(m, m);
            const double* a = a_.data() + index(m, m);
            const double* b = b_.data() + index(m, m);
            const double c1 = std::sqrt(2.0 * m + 3);
            double s0 = 0, s1 = 0;
            for (int g = 0; g < G; ++g) {
                p1[g] = pmm[g];
                p2[g] = c1 * zz[g] * pmm[g];
                s0 += ww[g] * p1[g];
                s1 += ww[g] * p2[g];
            }
            o[0] = s0;
            if (m + 1 >= bands_) continue;
            o[1] = s1;
            for (int k = 2; k < bands_ - m; ++k) {
                double acc = 0;
                for (int g = 0; g < G; ++g) {
                    const double p = a[k] * (zz[g] * p2[g] - b[k] * p1[g]);
                    p1[g] = p2[g];
                    p2[g] = p;
                    acc += ww[g] * p;
                }
                o[k] = acc;
            }
        }
    }

  private:
    int bands_;
    std::vector<double> a_, b_;
};

}  // namespace sphbasis
