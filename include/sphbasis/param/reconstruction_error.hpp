// sphbasis: how well a spherical parameterization's bilinear filtering reconstructs the real
// SH basis functions: the experiment of Iwanicki and Sloan, "Normal Mapping with Low-Frequency
// Precomputed Visibility" (JGT 2009), appendix A.
//
// Tabulate every SH basis function of `Bands` bands at the texel centres (as float, as a GPU
// stores them), reconstruct them by hardware bilinear filtering at many random directions and
// report the mean squared error against the exact values, averaged over the functions and the
// directions. The parameterizations compared are those of param/: dual orthographic and dual
// paraboloid, cube maps filtered as DX9 (clamped per face) and DX10+ (seamless), octahedral with
// clamp-to-edge and with seamless filtering, lat-long; each is sampled at resolutions that give
// total texel counts near 96 * 2^k, k = 0..10, so the curves can be compared at equal storage.
//
// Determinism: errors are summed per block of `reconstruction_block` directions, and the blocks
// in order, so the result is the same whichever parallel-for runs the blocks (the `for_each`
// argument: any callable `for_each(count, body)` that calls body(i) once for every
// i in [0, count), on any threads; the default runs them in order on the calling thread).
// Standard library only; no threads are started here.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "../basis/sh.hpp"
#include "../core/error.hpp"
#include "../core/sampling.hpp"
#include "cubemap.hpp"
#include "dual_orthographic.hpp"
#include "dual_paraboloid.hpp"
#include "latlong.hpp"
#include "octahedral.hpp"
#include "param.hpp"

namespace sphbasis::param {

/// Directions in structure-of-arrays form (unit vectors).
struct DirectionSet {
    std::vector<double> x, y, z;
    std::size_t size() const noexcept { return x.size(); }
};

/// `count` directions uniform on the sphere (square_to_uniform_sphere of (u, v) pairs drawn
/// from std::mt19937_64(seed) by std::uniform_real_distribution<double>(0, 1)), sorted by the
/// Morton code of their octahedral coordinates (16 bits per axis) so that consecutive lookups
/// touch nearby texels. The error means do not depend on the order; the caches do.
/// O(count log count).
inline DirectionSet reconstruction_directions(std::size_t count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    struct Keyed {
        std::uint64_t key;
        vec3<double> d;
    };
    std::vector<Keyed> pts(count);
    auto spread = [](std::uint64_t v) {  // 16 bits -> every other of 32 bits
        v &= 0xffff;
        v = (v | (v << 8)) & 0x00ff00ff;
        v = (v | (v << 4)) & 0x0f0f0f0f;
        v = (v | (v << 2)) & 0x33333333;
        v = (v | (v << 1)) & 0x55555555;
        return v;
    };
    for (auto& p : pts) {
        const double u = uni(rng);
        const double v = uni(rng);
        p.d = square_to_uniform_sphere(u, v);
        const auto s = octahedral_to_square(p.d.x, p.d.y, p.d.z);
        const auto qu = static_cast<std::uint64_t>(std::fmin(s.x * 65536.0, 65535.0));
        const auto qv = static_cast<std::uint64_t>(std::fmin(s.y * 65536.0, 65535.0));
        p.key = spread(qu) | (spread(qv) << 1);
    }
    std::sort(pts.begin(), pts.end(), [](const Keyed& a, const Keyed& b) { return a.key < b.key; });
    DirectionSet out;
    out.x.resize(count);
    out.y.resize(count);
    out.z.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        out.x[i] = pts[i].d.x;
        out.y[i] = pts[i].d.y;
        out.z[i] = pts[i].d.z;
    }
    return out;
}

/// Sums of squared reconstruction errors of the SH basis functions of up to `Bands` bands.
template <int Bands>
struct ShReconstructionError {
    static_assert(Bands >= 1, "ShReconstructionError<Bands> needs at least one band");
    /// sum[b - 1]: over the directions, the squared errors of the first b * b functions.
    std::array<double, Bands> sum{};
    std::size_t points = 0;

    /// Mean squared error over the directions and the first bands * bands functions
    /// (1 <= bands <= Bands); NaN before any direction was added.
    double mse(int bands) const {
        sphbasis::detail::check_range("param::ShReconstructionError::mse", "bands", bands, 1,
                                      Bands);
        return sum[static_cast<std::size_t>(bands - 1)] /
               (double(bands) * double(bands) * double(points));
    }
    ShReconstructionError& operator+=(const ShReconstructionError& o) noexcept {
        for (std::size_t b = 0; b < sum.size(); ++b) sum[b] += o.sum[b];
        points += o.points;
        return *this;
    }
};

/// The SH basis functions of `Bands` bands (ACN order, interleaved) at every texel centre of
/// p, rounded to V (float as a GPU stores them, or double).
template <int Bands, class V = float, class P>
std::vector<V> tabulate_sh(const P& p) {
    constexpr int k = Bands * Bands;
    return tabulate<V>(p, std::size_t(k), [](double x, double y, double z, V* out) {
        double v[k];
        sh::eval<Bands>(x, y, z, v);
        for (int i = 0; i < k; ++i) out[i] = static_cast<V>(v[i]);
    });
}

/// Squared errors of the bilinear reconstruction from `table` (tabulate_sh<Bands, V>(p)) at the
/// directions [begin, end) of d, against sh::eval<Bands> in double. For each direction the
/// squared errors are summed in ACN order and the running sum is added to sum[b - 1] after
/// each band b. Cost: one footprint and one Bands-band SH evaluation per direction.
/// Throws std::invalid_argument if the table is too small for p or the range lies outside d.
template <int Bands, class V, class P>
ShReconstructionError<Bands> sh_reconstruction_error(const P& p, const std::vector<V>& table,
                                                     const DirectionSet& d, std::size_t begin,
                                                     std::size_t end) {
    constexpr int k = Bands * Bands;
    const char* fn = "param::sh_reconstruction_error";
    if (table.size() < p.texel_count() * std::size_t(k))
        sphbasis::detail::throw_invalid(fn, "a table of " + std::to_string(p.texel_count() * k) +
                                                " values, got " + std::to_string(table.size()));
    if (d.y.size() != d.size() || d.z.size() != d.size())
        sphbasis::detail::throw_invalid(fn, "x, y and z of equal length");
    if (begin > end || end > d.size())
        sphbasis::detail::throw_invalid(fn, "begin <= end <= " + std::to_string(d.size()) +
                                                ", got [" + std::to_string(begin) + ", " +
                                                std::to_string(end) + ")");
    ShReconstructionError<Bands> e;
    e.points = end - begin;
    V rec[k];
    double exact[k];
    for (std::size_t i = begin; i < end; ++i) {
        const double x = d.x[i], y = d.y[i], z = d.z[i];
        reconstruct(table.data(), std::size_t(k), p.footprint(x, y, z), rec);
        sh::eval<Bands>(x, y, z, exact);
        double s = 0;
        for (int b = 0; b < Bands; ++b) {
            for (int q = b * b; q < (b + 1) * (b + 1); ++q) {
                const double diff = double(rec[q]) - exact[q];
                s += diff * diff;
            }
            e.sum[static_cast<std::size_t>(b)] += s;
        }
    }
    return e;
}

/// Directions per block of the blocked sums below.
inline constexpr std::size_t reconstruction_block = 8192;

/// Runs body(i) for i = 0, ..., count - 1 in order (the default `for_each`).
struct SerialFor {
    template <class F>
    void operator()(std::size_t count, F&& body) const {
        for (std::size_t i = 0; i < count; ++i) body(i);
    }
};

/// Squared errors over all directions of d, summed per block of reconstruction_block
/// directions and then over the blocks in order: the same result for any `for_each`.
template <int Bands, class V, class P, class ForEach = SerialFor>
ShReconstructionError<Bands> sh_reconstruction_error(const P& p, const std::vector<V>& table,
                                                     const DirectionSet& d,
                                                     ForEach&& for_each = {}) {
    const std::size_t n = d.size();
    const std::size_t blocks = (n + reconstruction_block - 1) / reconstruction_block;
    std::vector<ShReconstructionError<Bands>> part(blocks);
    for_each(blocks, [&](std::size_t b) {
        const std::size_t lo = b * reconstruction_block;
        part[b] =
            sh_reconstruction_error<Bands>(p, table, d, lo, std::min(n, lo + reconstruction_block));
    });
    ShReconstructionError<Bands> total;
    for (const auto& e : part) total += e;
    return total;
}

// ---------------------------------------------------------------------------------------------
// The experiment: parameterizations, resolutions, results.

/// The parameterizations of the experiment.
enum class ReconstructionParam {
    dual_orthographic,
    dual_paraboloid,
    cube_dx9,
    cube_dx10,
    octahedral_clamp,
    octahedral_seamless,
    latlong,
};

/// One parameterization of the experiment: its name (for files), a label (for plots), total
/// texels = texels_per_n2 * n^2 at resolution n, and the smallest resolution it allows.
struct ReconstructionCase {
    ReconstructionParam id;
    const char* name;
    const char* label;
    int texels_per_n2;
    int min_n;
};

/// The seven parameterizations, in table order.
inline const std::array<ReconstructionCase, 7>& reconstruction_cases() noexcept {
    using R = ReconstructionParam;
    static const std::array<ReconstructionCase, 7> cases = {{
        {R::dual_orthographic, "dual_orthographic", "dual orthographic", 2, 2},
        {R::dual_paraboloid, "dual_paraboloid", "dual paraboloid", 2, 2},
        {R::cube_dx9, "cube_dx9", "cube map, DX9 (clamped per face)", 6, 1},
        {R::cube_dx10, "cube_dx10", "cube map, DX10 (seamless)", 6, 1},
        {R::octahedral_clamp, "octahedral_clamp", "octahedral, clamp-to-edge", 1, 1},
        {R::octahedral_seamless, "octahedral_seamless", "octahedral, seamless border", 1, 1},
        {R::latlong, "latlong", "lat-long (2n x n)", 2, 1},
    }};
    return cases;
}

/// Number of texel budgets of the experiment: 96 * 2^k total texels, k = 0..10.
inline constexpr int reconstruction_budgets = 11;

/// The resolution n whose total texel count is nearest 96 * 2^k (at least c.min_n).
inline int reconstruction_resolution(const ReconstructionCase& c, int k) {
    sphbasis::detail::check_range("param::reconstruction_resolution", "k", k, 0, 40);
    const double target = 96.0 * std::ldexp(1.0, k);
    const int n = static_cast<int>(std::lround(std::sqrt(target / c.texels_per_n2)));
    return std::max(n, c.min_n);
}

/// Calls f(p) with the parameterization `id` built at resolution n (double coordinates) with
/// subtexel_bits bits of filter-weight precision (0: exact), and returns what f returns.
template <class F>
decltype(auto) with_parameterization(ReconstructionParam id, int n, int subtexel_bits, F&& f) {
    switch (id) {
        case ReconstructionParam::dual_orthographic:
            return f(DualOrthographic<double>(n, subtexel_bits));
        case ReconstructionParam::dual_paraboloid:
            return f(DualParaboloid<double>(n, subtexel_bits));
        case ReconstructionParam::cube_dx9:
            return f(CubeMap<double>(n, CubeFilter::dx9_clamped, subtexel_bits));
        case ReconstructionParam::cube_dx10:
            return f(CubeMap<double>(n, CubeFilter::dx10_seamless, subtexel_bits));
        case ReconstructionParam::octahedral_clamp:
            return f(Octahedral<double>(n, OctahedralFilter::clamp, subtexel_bits));
        case ReconstructionParam::octahedral_seamless:
            return f(Octahedral<double>(n, OctahedralFilter::seamless, subtexel_bits));
        case ReconstructionParam::latlong:
            break;
    }
    return f(LatLong<double>(n, subtexel_bits));
}

/// One row of the experiment's results: the MSE of the 3-band (9) and 6-band (36) functions.
struct ReconstructionResult {
    std::string param;
    int resolution = 0;
    std::size_t texels = 0;
    double mse3 = 0, mse6 = 0;
};

/// Runs one (parameterization, resolution) of the experiment: SH of 6 bands tabulated as float
/// and reconstructed at the directions d. Throws std::invalid_argument for a resolution or
/// subtexel_bits the parameterization rejects. Cost: O(texels + d.size()) 6-band evaluations.
template <class ForEach = SerialFor>
ReconstructionResult run_reconstruction_case(const ReconstructionCase& c, int n, int subtexel_bits,
                                             const DirectionSet& d, ForEach&& for_each = {}) {
    return with_parameterization(c.id, n, subtexel_bits, [&](const auto& p) {
        const std::vector<float> table = tabulate_sh<6, float>(p);
        const ShReconstructionError<6> e = sh_reconstruction_error<6>(p, table, d, for_each);
        ReconstructionResult r;
        r.param = c.name;
        r.resolution = p.resolution();
        r.texels = p.texel_count();
        r.mse3 = e.mse(3);
        r.mse6 = e.mse(6);
        return r;
    });
}

/// The MSE of parameterization `name` at `texels` total texels, interpolated log-log between
/// the results bracketing it (the resolutions give only approximately equal texel counts);
/// `bands` is 3 or 6. NaN when no two results of that name bracket the budget.
inline double reconstruction_mse_at(const std::vector<ReconstructionResult>& results,
                                    const std::string& name, double texels, int bands) {
    if (bands != 3 && bands != 6)
        sphbasis::detail::throw_invalid("param::reconstruction_mse_at",
                                        "bands 3 or 6, got " + std::to_string(bands));
    const bool six = bands == 6;
    double lx0 = 0, ly0 = 0;
    bool have = false;
    for (const auto& r : results) {
        if (r.param != name) continue;
        const double lx = std::log(double(r.texels)), ly = std::log(six ? r.mse6 : r.mse3);
        if (have && lx >= std::log(texels) && lx > lx0)
            return std::exp(ly0 + (ly - ly0) * (std::log(texels) - lx0) / (lx - lx0));
        lx0 = lx;
        ly0 = ly;
        have = true;
    }
    return std::nan("");
}

}  // namespace sphbasis::param
