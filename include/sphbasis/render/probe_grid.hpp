// sphbasis render tier: a regular grid of irradiance-volume probes with trilinear interpolation.
//
// An irradiance volume (Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 1.9)
// stores lighting (here: SH radiance coefficients, or any per-probe vector) at the nodes of a
// regular grid and reconstructs it at any point p by trilinear interpolation of the 8 probes of
// p's cell. Points outside the box are clamped to it. Probes that fall inside closed geometry
// see only the inside of a wall (dark, or light from the other side) and leak it into the
// rooms on both sides of the wall; the Baker flags them (PointResult::inside) and
// interpolate_valid() leaves them out: the weights of the valid corners are renormalised to
// sum to one, and a point whose 8 corners are all invalid takes the nearest valid probe.
//
// Trilinear interpolation reproduces affine functions of p exactly inside the box (the
// weights are the products of the 1D hat functions, whose first moments are the coordinates),
// and gives each probe's value at its position.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/error.hpp"
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
        return std::size_t(i) +
               std::size_t(counts[0]) * (std::size_t(j) + std::size_t(counts[1]) * std::size_t(k));
    }
    vec3<double> position(int i, int j, int k) const noexcept {
        auto at = [](double lo, double hi, int i, int n) {
            return n > 1 ? lo + (hi - lo) * i / (n - 1) : 0.5 * (lo + hi);
        };
        return {at(lo.x, hi.x, i, counts[0]), at(lo.y, hi.y, j, counts[1]),
                at(lo.z, hi.z, k, counts[2])};
    }
    /// The position of probe `index` (i + counts[0] * (j + counts[1] * k)).
    vec3<double> position(std::size_t index) const noexcept {
        const std::size_t nx = std::size_t(counts[0]), ny = std::size_t(counts[1]);
        return position(int(index % nx), int((index / nx) % ny), int(index / (nx * ny)));
    }

    /// Throws std::invalid_argument unless 1 <= counts[a] <= 2^20 on every axis, the grid holds
    /// at most 2^32 probes, lo and hi are finite and lo <= hi componentwise.
    void validate() const {
        constexpr const char* fn = "render::ProbeGrid";
        for (int a = 0; a < 3; ++a)
            sphbasis::detail::check_range(fn, "counts[a]", counts[static_cast<std::size_t>(a)], 1,
                                          1 << 20);
        if (size() > (std::size_t(1) << 32))
            sphbasis::detail::throw_invalid(fn,
                                            "at most 2^32 probes, got " + std::to_string(size()));
        const double l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
        for (int a = 0; a < 3; ++a)
            if (!std::isfinite(l[a]) || !std::isfinite(h[a]) || !(l[a] <= h[a]))
                sphbasis::detail::throw_invalid(
                    fn, "finite lo <= hi on every axis, got lo = " + std::to_string(l[a]) +
                            ", hi = " + std::to_string(h[a]) + " on axis " + std::to_string(a));
    }

    /// The cell of p (clamped into the box): the lower corner (i, j, k) and the fractional
    /// position t in [0, 1] on each axis; on an axis with one probe, or lo == hi, i = 0 and
    /// t = 0. For a valid grid; p must be finite (std::invalid_argument otherwise).
    struct Cell {
        std::array<int, 3> base{0, 0, 0};
        std::array<double, 3> t{0, 0, 0};
    };
    Cell cell_of(const vec3<double>& p) const {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
            sphbasis::detail::throw_invalid("render::ProbeGrid::cell_of",
                                            "a finite point, got (" + std::to_string(p.x) + ", " +
                                                std::to_string(p.y) + ", " + std::to_string(p.z) +
                                                ")");
        Cell c;
        const double pp[3] = {p.x, p.y, p.z}, l[3] = {lo.x, lo.y, lo.z}, h[3] = {hi.x, hi.y, hi.z};
        for (std::size_t a = 0; a < 3; ++a) {
            const int n = counts[a];
            if (n < 2 || !(h[a] > l[a])) continue;
            const double s = (std::clamp(pp[a], l[a], h[a]) - l[a]) / (h[a] - l[a]) * (n - 1);
            const int i = std::min(int(std::floor(s)), n - 2);
            c.base[a] = i;
            c.t[a] = std::clamp(s - i, 0.0, 1.0);
        }
        return c;
    }

    /// The 8 probes of p's cell and their trilinear weights (non-negative, summing to one up
    /// to rounding). Validates the grid (validate()) and p (cell_of()). Corner c = dx + 2 dy + 4
    /// dz; on an axis with one probe both corners are that probe (the second with weight 0).
    struct Weights {
        std::array<std::size_t, 8> index{};
        std::array<double, 8> w{};
    };
    Weights weights(const vec3<double>& p) const {
        validate();  // a few compares; an invalid grid would index out of range
        const Cell c = cell_of(p);
        Weights r;
        for (int corner = 0; corner < 8; ++corner) {
            int ijk[3];
            double w = 1;
            for (std::size_t a = 0; a < 3; ++a) {
                const int d = (corner >> a) & 1;
                ijk[a] = std::min(c.base[a] + d, counts[a] - 1);
                w *= d != 0 ? c.t[a] : 1 - c.t[a];
            }
            r.index[static_cast<std::size_t>(corner)] = index(ijk[0], ijk[1], ijk[2]);
            r.w[static_cast<std::size_t>(corner)] = w;
        }
        return r;
    }

    /// The trilinear interpolation at p (clamped into the box) of one value per probe
    /// (values[index(i, j, k)]; size() of them). C: any type with C * double and C + C
    /// (double, an RGB struct, ...). Cost: 8 multiply-adds of C.
    template <class C>
    C interpolate(const C* values, const vec3<double>& p) const {
        sphbasis::detail::check_buffer("render::ProbeGrid::interpolate", "values", values, size());
        const Weights wt = weights(p);
        C r = values[wt.index[0]] * wt.w[0];
        for (std::size_t k = 1; k < 8; ++k) r = r + values[wt.index[k]] * wt.w[k];
        return r;
    }

    /// The trilinear interpolation at p (clamped into the box) of n coefficients per probe
    /// (values[probe * n + c], size() * n of them) into out[0 .. n).
    void interpolate(const double* values, std::size_t n, const vec3<double>& p,
                     double* out) const {
        constexpr const char* fn = "render::ProbeGrid::interpolate";
        sphbasis::detail::check_buffer(fn, "values", values, size() * n);
        sphbasis::detail::check_buffer(fn, "out", out, n);
        combine(values, n, weights(p), out);
    }

    /// As interpolate(values, n, p, out), leaving out the probes flagged in `inside`
    /// (size() flags, nonzero = inside geometry, e.g. PointResult::inside): the weights of the
    /// valid corners of p's cell are renormalised; when they sum to zero (every corner with a
    /// positive weight is inside) p takes the values of the nearest valid probe (Euclidean
    /// distance to p clamped into the box, ties to the lowest index; O(size()) search). Throws
    /// std::runtime_error when every probe is flagged.
    void interpolate_valid(const double* values, std::size_t n, const std::uint8_t* inside,
                           const vec3<double>& p, double* out) const {
        constexpr const char* fn = "render::ProbeGrid::interpolate_valid";
        sphbasis::detail::check_buffer(fn, "values", values, size() * n);
        sphbasis::detail::check_buffer(fn, "inside", inside, size());
        sphbasis::detail::check_buffer(fn, "out", out, n);
        Weights wt = weights(p);
        double total = 0;
        for (std::size_t k = 0; k < 8; ++k) {
            if (inside[wt.index[k]] != 0) wt.w[k] = 0;
            total += wt.w[k];
        }
        if (total > 0) {
            for (auto& w : wt.w) w /= total;
            combine(values, n, wt, out);
            return;
        }
        const std::size_t best = nearest_valid(inside, p);
        for (std::size_t c = 0; c < n; ++c) out[c] = values[best * n + c];
    }

    /// The valid probe (inside[i] == 0) nearest to p clamped into the box, ties to the lowest
    /// index. Throws std::runtime_error if every probe is flagged.
    std::size_t nearest_valid(const std::uint8_t* inside, const vec3<double>& p) const {
        constexpr const char* fn = "render::ProbeGrid::nearest_valid";
        sphbasis::detail::check_buffer(fn, "inside", inside, size());
        const vec3<double> q{std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y),
                             std::clamp(p.z, lo.z, hi.z)};
        std::size_t best = size();
        double best_d = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < size(); ++i) {
            if (inside[i] != 0) continue;
            const vec3<double> x = position(i);
            const vec3<double> d{x.x - q.x, x.y - q.y, x.z - q.z};
            const double dd = dot(d, d);
            if (dd < best_d) {
                best_d = dd;
                best = i;
            }
        }
        if (best == size())
            sphbasis::detail::throw_runtime(fn,
                                            "at least one probe outside geometry, got every probe "
                                            "flagged as inside");
        return best;
    }

  private:
    static void combine(const double* values, std::size_t n, const Weights& wt, double* out) {
        for (std::size_t c = 0; c < n; ++c) out[c] = 0;
        for (std::size_t k = 0; k < 8; ++k) {
            if (wt.w[k] == 0) continue;
            const double* v = values + wt.index[k] * n;
            for (std::size_t c = 0; c < n; ++c) out[c] += wt.w[k] * v[c];
        }
    }
};

}  // namespace sphbasis::render
