// Shared helpers of the SH operation tests (tests/ops/test_sh_*.cpp): an RGB coefficient type
// (any type with + and * scalar serves as coefficients), fixed-seed random coefficients and random
// unit directions, and pi.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <sphbasis/core/constants.hpp>
#include <sphbasis/core/vec.hpp>
#include <vector>

namespace sphbasis::test {

using constants::pi;

struct RGB {
    double r = 0, g = 0, b = 0;
};
inline RGB operator+(const RGB& a, const RGB& b) { return {a.r + b.r, a.g + b.g, a.b + b.b}; }
inline RGB operator*(const RGB& a, double s) { return {a.r * s, a.g * s, a.b * s}; }
inline RGB operator-(const RGB& a) { return {-a.r, -a.g, -a.b}; }

/// (x, y, z) / |(x, y, z)|.
inline vec3<double> unit(double x, double y, double z) {
    const double r = std::sqrt(x * x + y * y + z * z);
    return {x / r, y / r, z / r};
}

/// Largest |v_i|.
inline double max_abs(const std::vector<double>& v) {
    double m = 0;
    for (double x : v) m = std::max(m, std::fabs(x));
    return m;
}

/// bands^2 coefficients, standard normal, drawn from rng.
template <class T = double>
std::vector<T> random_coeffs(int bands, std::mt19937& rng) {
    std::normal_distribution<double> nd;
    std::vector<T> c(static_cast<std::size_t>(bands * bands));
    for (auto& v : c) v = static_cast<T>(nd(rng));
    return c;
}

/// A uniformly distributed unit direction drawn from rng (a normalised standard normal triple).
inline vec3<double> random_dir(std::mt19937& rng) {
    std::normal_distribution<double> nd;
    const double x = nd(rng), y = nd(rng), z = nd(rng);
    return unit(x, y, z);
}

}  // namespace sphbasis::test
