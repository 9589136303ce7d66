// sphbasis render tier: a regular grid of irradiance-volume probes with trilinear interpolation.
//
// CONTRACT (written by the lead; the lightmap helper implements it and may add members and
// functions, but keeps these names and meanings: the tool is written against them).
#pragma once

#include <array>
#include <cstddef>
#include <stdexcept>
#include <vector>

#include "../core/vec.hpp"

namespace sphbasis::render {

/// counts[0] x counts[1] x counts[2] probes spanning the box [lo, hi] (corners included),
/// probe (i, j, k) at index i + counts[0] * (j + counts[1] * k).
struct ProbeGrid {
    vec3<double> lo{0, 0, 0}, hi{1, 1, 1};
    std::array<int, 3> counts{2, 2, 2};

    std::size_t size() const noexcept {
        return std::size_t(counts[0]) * std::size_t(counts[1]) * std::size_t(counts[2]);
    }
    std::size_t index(int i, int j, int k) const noexcept {
        return std::size_t(i) + std::size_t(counts[0]) * (std::size_t(j) + std::size_t(counts[1]) * std::size_t(k));
    }
    vec3<double> position(int i, int j, int k) const noexcept {
        auto at = [](double lo, double hi, int i, int n) { return n > 1 ? lo + (hi - lo) * i / (n - 1) : 0.5 * (lo + hi); };
        return {at(lo.x, hi.x, i, counts[0]), at(lo.y, hi.y, j, counts[1]), at(lo.z, hi.z, k, counts[2])};
    }
};

}  // namespace sphbasis::render
