// sphbasis: values carried with a separate binary exponent, value = m * 2^e. The high-degree
// (column) recurrences of SH and of the hemispherical bases start from sectoral values that
// underflow long before the functions do; carrying the exponent lets the recurrence grow them
// back into range.
#pragma once

#include <algorithm>
#include <cmath>

namespace sphbasis::detail {

/// Mantissas are kept within 2^+-rescale_bits (~3e144): far inside the double range.
inline constexpr int rescale_bits = 480;

/// m * 2^e in precision R (double, or long double for the hemispherical columns).
template <class R>
struct Scaled {
    R m;
    int e;

    /// Multiplies by f * 2^fe and renormalises the mantissa once it falls below
    /// 2^-rescale_bits, so that it never underflows.
    void scale(R f, int fe) noexcept {
        m *= f;
        e += fe;
        if (m != 0 && std::fabs(m) < std::ldexp(R(1), -rescale_bits)) {
            int k;
            m = std::frexp(m, &k);
            e += k;
        }
    }
};

/// One rescaling step of a three-term recurrence whose last two values p0, p1 carry the common
/// exponent e < 0: once |p0| exceeds 2^rescale_bits, moves magnitude from the mantissas into the
/// exponent, but never above 2^0.
template <class R>
inline void shed_magnitude(R& p0, R& p1, int& e) noexcept {
    if (e < 0 && std::fabs(p0) > std::ldexp(R(1), rescale_bits)) {
        const int k = std::min(rescale_bits, -e);
        p0 = std::ldexp(p0, -k);
        p1 = std::ldexp(p1, -k);
        e += k;
    }
}

}  // namespace sphbasis::detail
