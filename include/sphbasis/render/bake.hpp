// sphbasis render tier: baking lighting representations at surface points and free points.
//
// Sources: Hill, "Hardware Accelerating Art Production" (Gamasutra 2004), eq. 1-5; Sloan,
// Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory and Practice" (SIGGRAPH 2005
// course); Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed Visibility"
// (JGT 2009), section 3.1; Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 1.9.
//
// Quantities at a surface point x with unit normal n (V(w) = 1 when the ray from x along w
// leaves the scene; y_i real SH without the Condon-Shortley phase, ACN order, world frame):
//   ao         = (1/pi) int V(w) max(n.w, 0) dw (Hill eq. 1-3). Cosine-weighted directions
//                (pdf n.w/pi) make the estimator the mean of V; hits farther than max_distance
//                do not occlude. ao_stderr = sqrt(ao (1 - ao) / (N - 1)), the Monte Carlo
//                standard error (the QMC error is usually smaller).
//   bent       = normalize(int V(w) w max(n.w, 0) dw): the mean unoccluded cosine-sampled
//                direction (same V as ao); n when every sample is occluded.
//                bent_stderr (radians): the angular standard error of bent by the delta method.
//                With the cosine-weighted samples u_j = V(w_j) w_j, m = (1/N) sum u_j (so
//                bent = m/|m|), b = m/|m|, S their sample covariance (N - 1 denominator) and
//                P = I - b b^T: the Jacobian of m -> m/|m| is P/|m| and Cov(m) = S/N, so the
//                covariance of bent is P S P / (N |m|^2), whose trace is the expected squared
//                angle (bent moves in the tangent plane of b): bent_stderr =
//                sqrt(trace(P S P) / N) / |m|. trace(P S P) = (N / (N - 1)) (trace(Q) - b^T Q b)
//                with Q = (1/N) sum u_j u_j^T (the m m^T part of S cancels), so no cancellation
//                against the mean. Unoccluded with V = 1 (cosine pdf): m = (0, 0, 2/3) in the
//                tangent frame, E[x^2] = E[y^2] = 1/4, bent_stderr -> sqrt(1/(2N)) / (2/3).
//                Points nothing can occlude (the analytic pass: bent = n exactly): 0. No
//                unoccluded sample (bent = n by convention, no information on the direction), or
//                fewer than 2 rays: pi, the largest angle between two directions; the delta
//                method's value is capped at pi too (it grows without bound as |m| -> 0, where
//                the linearisation fails).
//   visibility = v_i = int_{n.w > 0} V(w) y_i(w) dw (V = 0 below the tangent plane;
//                Iwanicki and Sloan section 3.1). Directions uniform on the hemisphere of n
//                (the uniform sphere with the lower half known to be 0): v_i = 2pi/N sum V y_i.
//   transfer   = diffuse PRT (Sloan et al.): B(x) = rho(x) sum_i t_i l_i for distant radiance
//                L = sum_i l_i y_i. Without bounces t_i = (1/pi) int V max(n.w, 0) y_i dw,
//                estimated as the mean of V(w_j) y_i(w_j) over cosine-sampled w_j. With bounces
//                (path continuation): at a hit y the path continues along a cosine-sampled
//                direction about y's shading normal, its throughput multiplied by albedo(y) per
//                channel ("multiply by albedo when gathering"); a path escaping along w after k
//                hits adds (prod of the k albedos) y_i(w). rho(x) is factored out. Channels
//                differ only when albedos differ per channel (transfer_rgb).
//                Two-sided: a hit is shaded from the side the ray arrived on (Scene::hit turns
//                the geometric and the shading normal to it together), and a direction of the
//                lobe below the geometric surface (the shading normal differs from it) is
//                reflected in the geometric tangent plane (detail::rt::fold_above) instead of
//                ending the path: every vertex passes on exactly its albedo, so a white furnace
//                (albedo 1, unit sky) gives 1 up to the bounce count. Directional lights at a
//                path vertex use the same folded cosine. All quantities with bounces continue
//                paths this way.
//   irradiance = E(n') = int_{n.w > 0} L_in(w) max(n'.w, 0) dw for normals n' over the tangent
//                hemisphere (Ishmukhametov), L_in the incoming radiance (environment, lights,
//                shadows, bounces; V = 0 below x's tangent plane), fitted in `basis` with `coeffs`
//                functions by least squares over the rule hemisphere_rule_sqrt(32, 32) (the
//                IMSE benchmark's rule). L_in is sampled uniformly over the hemisphere (cosine
//                weights about n would give an unbounded estimator for tilted n') and projected
//                on 8 SH bands in the tangent frame; E = sum pi a_l L_lm y_lm(n') (the clamped
//                cosine; the truncation error is below 0.3% of E). Directional lights (deltas)
//                add V(l) color max(n'.l, 0) exactly, with one shadow ray. At points nothing
//                occludes, L_in is integrated by quadrature (hemisphere_rule(48)) instead of
//                rays: exact for the environment's smooth part, approximate at the edge of a
//                small cone or sphere light.
//                What is stored (BakeSettings::basis, render::irradiance_storage()): a basis's
//                least-squares coefficients as above; "sg-running": BakingLab's SG lobes by
//                Roughton's running average of E at fixed uniform directions (linear: a projector
//                like the least squares'); "sg-nnls": the lobes' least squares with amplitudes
//                >= 0; "zh3", "zh3-hallucinate", "sh-l1-nonlinear": their fit of E's SH (E_lm =
//                pi a_l L_lm, directional lights' exactly). The bake estimates a linear stage
//                (the coefficients; the fitted ones: E's first 9 or 4 SH), pooled by adaptive
//                sampling, and converts it once per point (Baker::finish_point()).
//                irradiance_stderr (coeffs, max over R, G, B): the Monte Carlo standard error of
//                that estimator. The fit is linear in the samples: e = M L_lm + (directional
//                part), M = irr_map (coeffs x 64: least-squares projector times the clamped-cosine
//                convolution), L_lm = (1/N) sum_j 2pi L_in(w_j) y_lm(w_j) (tangent frame), so
//                e = (1/N) sum_j s_j with s_j,kc = 2pi L_in,c(w_j) (M y(w_j))_k, and
//                irradiance_stderr_k = max_c sqrt(var_j(s_j,kc) / N), var with the N - 1
//                denominator (samples with L_in = 0 count as s_j = 0). The directional lights
//                (one deterministic shadow ray each) add no error; at points nothing occludes
//                (quadrature, no rays) it is 0. Like ao_stderr it bounds the QMC error, which is
//                usually smaller.
//   transfer_matrix = the incident-transfer matrix of normal-mapped PRT (Sloan, Lehtinen and
//                Kautz, the normal-mapping slides): the 3-band SH (world frame) of the incident
//                radiance, L_in,i = sum_j M_ij l_j for distant radiance sum_j l_j y_j (bands
//                bands), RGB. Directions below the tangent plane see the distant lighting
//                (they matter only to a normal-mapped normal tilting there: the surface's own
//                occluders are what the bake adds), so an unoccluded point has M = I (the
//                analytic pass): M_ij = delta_ij - int_{n.w > 0} (1 - V) y_i y_j dw + the
//                bounce paths of occluded directions (as transfer's, continued from the hit).
//                Directions uniform on the hemisphere.
//                transfer_matrix_stderr (9 x bands^2, max over R, G, B): M - I is the mean over
//                the N samples of s_j = 2pi y3(w_j) r_j^T, r_j = sum over the escapes of sample
//                j's bounce paths of T y(w_esc) - y(w_j) for an occluded w_j, s_j = 0 for an
//                unoccluded one; the error is sqrt(var_j(s_j,ik) / N) per element, var with the
//                N - 1 denominator. The analytic M = I (nothing occludes) reports 0. Without
//                bounces s_j,00 = -1/2 on occluded samples, so stderr_00 =
//                (1/2) sqrt(p (1 - p) / (N - 1)) with p = 2 (1 - M_00) the occluded fraction.
//   radiance   = r_i = int L_in(w) y_i(w) dw at any point, RGB, directions uniform on the
//                sphere: r_i = 4pi/N sum L_in(w_j) y_i(w_j); directional lights add
//                V(l) color y_i(l). `inside`: more than half the rays hit back faces
//                (the side opposite a triangle's counter-clockwise normal).
//                radiance_stderr (bands^2, max over R, G, B): sqrt(var_j(4pi L_in,c(w_j)
//                y_i(w_j)) / N), var with the N - 1 denominator; directional lights (one shadow
//                ray each) add no error, and with no geometry (quadrature and closed forms, no
//                rays) it is 0.
// Sampling: QMC (the R2 sequence of core/sampling.hpp), shifted per point by a Cranley-Patterson
// rotation hashed from (seed, id) (render/detail/qmc.hpp: the shift in azimuth is applied as a
// rotation of the tangent frame, so no trigonometry per ray); continuation directions of bounces
// hash (seed, id, path, bounce). A result depends only on (seed, id, settings, scene), never on
// threads or order. Rays leave surfaces from x + epsilon n (render::Scene::epsilon(); hits:
// offset_origin()).
// Adaptive sampling (BakeSettings::adaptive, off by default): a point traces batches of `rays`
// rays, batch b shifted by (seed, id, b), pooled, until each targeted quantity's standard error
// (point_error()) meets its target or max_rays is reached; AdaptiveSummary estimates the rays a
// fixed count with the same worst-case error would trace.
//
// The pass plan (plan()): "build" (the Embree scene);
// "analytic" (points that nothing can occlude, render::Scene::can_occlude(): ao = 1, bent = n,
// t_lm = a_l y_lm(n) with a_l the clamped-cosine factors, v_lm = 2pi y_lm(n) int_0^1 P_l,
// irradiance and radiance by quadrature of the sky and closed-form lights: zero rays);
// "cosine" (ao, bent, transfer rays); "hemisphere" (visibility, irradiance); "sphere"
// (radiance); "shadow" (directional lights); "bounce k" for k = 1..K, K the largest k <= bounces
// with rho_max^k > target_error (rho_max the largest albedo channel), and at a point only while
// rho_max^k f_x > target_error, f_x the fraction of the point's own rays that hit geometry
// (its paths; paths end when they escape). target_error is relative to unit radiance.
// force_all_passes runs the ray passes for every point and all `bounces`. Pass::seconds is thread
// time (summed over threads), exclusive: work of one pass nested in another (the shadow rays at
// a bounce's vertices) counts for the inner pass only, so the passes add up to the thread time;
// Pass::rays is exact.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <mutex>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "../basis/registry.hpp"
#include "../basis/sh.hpp"
#include "../core/clamped_cosine.hpp"
#include "../core/constants.hpp"
#include "../core/error.hpp"
#include "../core/frame.hpp"
#include "../core/quadrature.hpp"
#include "../core/sampling.hpp"
#include "../core/simd.hpp"
#include "../core/vec.hpp"
#include "../ops/projection.hpp"
#include "detail/bake_lighting.hpp"
#include "detail/qmc.hpp"
#include "detail/rt_math.hpp"
#include "irradiance_fit.hpp"
#include "lighting.hpp"
#include "mesh.hpp"
#include "scene.hpp"

namespace sphbasis::render {

/// The quantities a bake can produce: flags, combined with | into a set (BakeSettings::
/// quantities); has(set, q) asks whether a set holds any of q.
enum class Quantity : unsigned {
    ao = 1u << 0,
    bent = 1u << 1,
    visibility = 1u << 2,
    transfer = 1u << 3,
    irradiance = 1u << 4,
    radiance = 1u << 5,
    transfer_matrix = 1u << 6,
};

constexpr Quantity operator|(Quantity a, Quantity b) noexcept {
    return static_cast<Quantity>(static_cast<unsigned>(a) | static_cast<unsigned>(b));
}
constexpr Quantity operator&(Quantity a, Quantity b) noexcept {
    return static_cast<Quantity>(static_cast<unsigned>(a) & static_cast<unsigned>(b));
}
constexpr Quantity operator~(Quantity a) noexcept {
    return static_cast<Quantity>(~static_cast<unsigned>(a));
}
constexpr Quantity& operator|=(Quantity& a, Quantity b) noexcept { return a = a | b; }
/// True when the set holds a flag.
constexpr bool any(Quantity set) noexcept { return static_cast<unsigned>(set) != 0; }
/// True when `set` holds any of the flags of `q`.
constexpr bool has(Quantity set, Quantity q) noexcept { return any(set & q); }

/// Every quantity, in bit order.
inline constexpr Quantity all_quantities[] = {
    Quantity::ao,         Quantity::bent,     Quantity::visibility,     Quantity::transfer,
    Quantity::irradiance, Quantity::radiance, Quantity::transfer_matrix};

/// The position of a one-flag quantity in all_quantities (its bit), 0..6.
constexpr std::size_t quantity_index(Quantity q) noexcept {
    std::size_t i = 0;
    for (unsigned b = static_cast<unsigned>(q); b > 1u; b >>= 1) ++i;
    return i;
}

/// The name of a quantity, as the enumerator is spelled ("ao", "transfer_matrix"): the names
/// of the CLI's --quantities and of the files' settings. "" for a value that is not one flag.
inline const char* quantity_name(Quantity q) noexcept {
    switch (q) {
        case Quantity::ao:
            return "ao";
        case Quantity::bent:
            return "bent";
        case Quantity::visibility:
            return "visibility";
        case Quantity::transfer:
            return "transfer";
        case Quantity::irradiance:
            return "irradiance";
        case Quantity::radiance:
            return "radiance";
        case Quantity::transfer_matrix:
            return "transfer_matrix";
    }
    return "";
}

/// The quantity of a name (quantity_name()'s inverse), or the empty set for an unknown name.
inline Quantity quantity_of_name(const std::string& name) noexcept {
    for (Quantity q : all_quantities)
        if (name == quantity_name(q)) return q;
    return Quantity{};
}

/// The names of the flags of a set, comma-separated in bit order ("ao,transfer").
inline std::string quantity_names(Quantity set) {
    std::string s;
    for (Quantity q : all_quantities)
        if (has(set, q)) s += (s.empty() ? "" : ",") + std::string(quantity_name(q));
    return s;
}

/// Adaptive sampling: each point traces batches of BakeSettings::rays rays (every pass), each
/// batch with its own Cranley-Patterson shift hashed from (seed, id, batch), until the standard
/// error of every quantity with a target is at most that target (point_error()) or
/// max_rays rays per pass are reached. Batch 0 is the fixed bake's sample set, so one batch
/// reproduces it bit for bit. The batches are pooled as one sample of batches x rays: means
/// averaged, the standard error from the pooled sum of squares (within-batch variances plus
/// the spread of the batch means); bent from the pooled mean vector.
struct AdaptiveSampling {
    std::array<double, 7> target{};  // by quantity_index(); 0: no target for that quantity
    int max_rays = 0;                // rays per point and pass at most; 0: adaptive sampling off
    bool enabled() const noexcept { return max_rays > 0; }
    double& operator[](Quantity q) noexcept { return target[quantity_index(q)]; }
    double operator[](Quantity q) const noexcept { return target[quantity_index(q)]; }
};

struct BakeSettings {
    Quantity quantities = Quantity::ao;  // a set (|)
    int bands = 3;  // SH bands of visibility, transfer, radiance; transfer_matrix: of the lighting
    /// What `irradiance` stores (render::irradiance_storage()): a basis of find_basis() ("sh",
    /// "hbasis", ..., "sg", "ambient-cube", "ambient-dice"), BakingLab's SG lobes fitted by
    /// non-negative least squares ("sg-nnls") or the running average ("sg-running"), or a
    /// fitted representation ("zh3", "zh3-hallucinate", "sh-l1-nonlinear").
    std::string basis = "sh";
    int coeffs = 9;   // its coefficient count (values per channel)
    int rays = 256;   // rays per point and pass
    int bounces = 0;  // at most this many interreflection bounces
    std::uint64_t seed = 0;
    double max_distance =
        std::numeric_limits<double>::infinity();  // ao: farther hits don't occlude
    double target_error = 1e-3;     // a bounce runs only while its bound is above this
    bool force_all_passes = false;  // run every pass the plan would skip (for tests)
    AdaptiveSampling adaptive;      // off by default: every point traces `rays`
};

/// A point to bake. A surface point has a normal (need not be unit; it is normalised), a free
/// point (radiance, probes) has normal {0, 0, 0}. `tangent` (unit, orthogonal to n, or zero
/// for tangent_frame(n)) orients the tangent space of `irradiance`. `id` seeds the point's
/// sample sequence: results depend only on (seed, id, settings), never on the thread count
/// or the order of points, which is what makes sharded bakes bit-identical to one run.
struct BakePoint {
    vec3<double> p{0, 0, 0}, n{0, 0, 0}, tangent{0, 0, 0};
    /// The tangent frame of `irradiance` is (tangent, bitangent_sign * n x tangent, n): -1 where
    /// the UVs are mirrored (glTF's tangent w), so the frame follows the normal map's.
    double bitangent_sign = 1;
    std::uint64_t id = 0;
};

/// What a bake gives per point; only the requested quantities are filled.
struct PointResult {
    double ao = 0, ao_stderr = 0;
    vec3<double> bent{0, 0, 0};
    double bent_stderr = 0;                             // radians (header comment)
    std::vector<double> visibility, visibility_stderr;  // bands^2
    std::array<std::vector<double>, 3> transfer;        // R, G, B (bands^2 each)
    std::vector<double> transfer_stderr;                // bands^2 (max over channels)
    bool transfer_rgb = false;  // false: the three channels are equal (print one list)
    std::array<std::vector<double>, 3> irradiance;  // R, G, B (coeffs each)
    std::vector<double> irradiance_stderr;          // coeffs (max over channels)
    std::array<std::vector<double>, 3> radiance;    // R, G, B (bands^2 each)
    std::vector<double> radiance_stderr;            // bands^2 (max over channels)
    /// R, G, B: 9 x bands^2, row-major (row i: incident coefficient i, column j: lighting j).
    std::array<std::vector<double>, 3> transfer_matrix;
    std::vector<double> transfer_matrix_stderr;  // 9 x bands^2 (max over channels)
    bool inside = false;     // the point is inside closed geometry (probes leak)
    int batches = 1;         // batches of BakeSettings::rays traced (adaptive sampling)
    std::uint64_t rays = 0;  // rays the point traced, all passes and batches
};

/// The standard error of quantity q (one flag) at a point: ao_stderr, bent_stderr (radians),
/// or the largest coefficient's standard error of the other quantities (0 when not baked).
inline double point_error(const PointResult& r, Quantity q) noexcept {
    auto mx = [](const std::vector<double>& v) {
        double m = 0;
        for (double x : v) m = std::max(m, x);
        return m;
    };
    switch (q) {
        case Quantity::ao:
            return r.ao_stderr;
        case Quantity::bent:
            return r.bent_stderr;
        case Quantity::visibility:
            return mx(r.visibility_stderr);
        case Quantity::transfer:
            return mx(r.transfer_stderr);
        case Quantity::irradiance:
            return mx(r.irradiance_stderr);
        case Quantity::radiance:
            return mx(r.radiance_stderr);
        case Quantity::transfer_matrix:
            return mx(r.transfer_matrix_stderr);
    }
    return 0;
}

/// True when every quantity with an adaptive target has point_error() <= its target.
inline bool meets_targets(const BakeSettings& s, const PointResult& r) noexcept {
    for (Quantity q : all_quantities)
        if (s.adaptive[q] > 0 && !(point_error(r, q) <= s.adaptive[q])) return false;
    return true;
}

/// What adaptive sampling did over a set of points, and what a fixed ray count reaching the
/// same worst-case error would cost. Sums and maxima, so the summaries of shards merge().
/// The fixed count per pass is estimated by the 1/sqrt(N) law of the standard error: a point
/// with error e at n rays has e sqrt(n / R) at R rays, so R = max over the targeted
/// quantities and the points of n e^2 / E^2 reaches the worst-case error E of the adaptive
/// bake at every point; its cost is R / rays times the rays of one batch of every point.
struct AdaptiveSummary {
    std::uint64_t points = 0, batches = 0, unconverged = 0;  // unconverged: stopped at max_rays
    std::uint64_t rays = 0;             // rays traced (sum of PointResult::rays)
    double rays_per_batch = 0;          // sum over the points of rays / batches
    std::array<double, 7> worst{};      // by quantity_index(): max over points of the error
    std::array<double, 7> worst_ne2{};  // max over points of (batches rays) error^2

    void add(const BakeSettings& s, const PointResult& r) {
        ++points;
        batches += std::uint64_t(r.batches);
        rays += r.rays;
        rays_per_batch += double(r.rays) / double(std::max(r.batches, 1));
        if (!meets_targets(s, r)) ++unconverged;
        const double n = double(r.batches) * double(s.rays);
        for (Quantity q : all_quantities) {
            if (!(s.adaptive[q] > 0)) continue;
            const double e = point_error(r, q);
            const std::size_t i = quantity_index(q);
            worst[i] = std::max(worst[i], e);
            worst_ne2[i] = std::max(worst_ne2[i], n * e * e);
        }
    }
    void merge(const AdaptiveSummary& o) {
        points += o.points;
        batches += o.batches;
        unconverged += o.unconverged;
        rays += o.rays;
        rays_per_batch += o.rays_per_batch;
        for (std::size_t i = 0; i < worst.size(); ++i) {
            worst[i] = std::max(worst[i], o.worst[i]);
            worst_ne2[i] = std::max(worst_ne2[i], o.worst_ne2[i]);
        }
    }
    /// R: rays per point and pass of a fixed bake with the same worst-case error (at least
    /// `rays`, the batch).
    double fixed_rays(const BakeSettings& s) const noexcept {
        double r = double(s.rays);
        for (std::size_t i = 0; i < worst.size(); ++i)
            if (worst[i] > 0) r = std::max(r, worst_ne2[i] / (worst[i] * worst[i]));
        return r;
    }
    /// The rays of that fixed bake (estimate).
    double fixed_total(const BakeSettings& s) const noexcept {
        return fixed_rays(s) / double(s.rays) * rays_per_batch;
    }
};

}  // namespace sphbasis::render

namespace sphbasis::render::detail {

/// Pools the batches of one point (AdaptiveSampling): sums of the batch means and of their
/// squares, and of the squared batch standard errors, per quantity, coefficient and channel.
class AdaptivePool {
  public:
    AdaptivePool(Quantity q, std::size_t rays) : q_(q), n_(double(rays)) {}

    void add(const PointResult& r, const rt::V3& bent_m) {
        using namespace rt;
        ++b_;
        add1(0, std::vector<double>{r.ao}, std::vector<double>{r.ao_stderr});
        add1(1, r.visibility, r.visibility_stderr);
        add1(2, r.transfer, r.transfer_stderr);
        add1(3, r.irradiance, r.irradiance_stderr);
        add1(4, r.radiance, r.radiance_stderr);
        add1(5, r.transfer_matrix, r.transfer_matrix_stderr);
        m_ = m_ + bent_m;
        bent_var_ += r.bent_stderr * r.bent_stderr * dot(bent_m, bent_m);
        rgb_ = rgb_ || r.transfer_rgb;
        inside_ += r.inside ? 1 : 0;
    }

    /// The pooled result of the batches so far (n: the point's unit normal, bent's fallback).
    void result(PointResult& out, const rt::V3& n) const {
        std::vector<double> se;
        std::array<std::vector<double>, 3> mean;
        if (has(q_, Quantity::ao)) {
            finish(0, mean, se);
            out.ao = mean[0][0];
            out.ao_stderr = se[0];
        }
        if (has(q_, Quantity::bent)) {
            const double lm = rt::length(m_) / double(b_);
            out.bent = rt::normalized(m_, n);
            out.bent_stderr =
                lm > 0 ? std::min(constants::pi, std::sqrt(bent_var_) / (double(b_) * lm))
                       : constants::pi;
        }
        if (has(q_, Quantity::visibility)) {
            finish(1, mean, out.visibility_stderr);
            out.visibility = mean[0];
        }
        if (has(q_, Quantity::transfer)) {
            finish(2, out.transfer, out.transfer_stderr);
            out.transfer_rgb = rgb_;
        }
        if (has(q_, Quantity::irradiance)) finish(3, out.irradiance, out.irradiance_stderr);
        if (has(q_, Quantity::radiance)) finish(4, out.radiance, out.radiance_stderr);
        if (has(q_, Quantity::transfer_matrix))
            finish(5, out.transfer_matrix, out.transfer_matrix_stderr);
        out.inside = 2 * inside_ > b_;
    }

  private:
    struct Sums {
        std::size_t channels = 0;
        std::array<std::vector<double>, 3> mean, mean2;
        std::vector<double> se2;
    };

    void add1(std::size_t k, const std::array<std::vector<double>, 3>& mean,
              const std::vector<double>& se) {
        Sums& s = sums_[k];
        if (b_ == 1) {
            s.channels = 0;
            for (std::size_t c = 0; c < 3 && !mean[c].empty(); ++c) {
                s.mean[c].assign(mean[c].size(), 0.0);
                s.mean2[c].assign(mean[c].size(), 0.0);
                s.channels = c + 1;
            }
            s.se2.assign(se.size(), 0.0);
        }
        for (std::size_t c = 0; c < s.channels; ++c)
            for (std::size_t i = 0; i < mean[c].size() && i < s.mean[c].size(); ++i) {
                s.mean[c][i] += mean[c][i];
                s.mean2[c][i] += mean[c][i] * mean[c][i];
            }
        for (std::size_t i = 0; i < se.size() && i < s.se2.size(); ++i) s.se2[i] += se[i] * se[i];
    }
    void add1(std::size_t k, const std::vector<double>& mean, const std::vector<double>& se) {
        add1(k, std::array<std::vector<double>, 3>{mean, {}, {}}, se);
    }

    /// Means over the B batches and the pooled standard error of B N samples: the sum of
    /// squares about the pooled mean is N (N - 1) sum_b se_b^2 + N sum_b (mean_b - mean)^2
    /// (within the batches plus between them), the error sqrt(SS / (BN - 1) / (BN)), the largest
    /// over the channels (se_b is already the largest channel's, so this is an upper bound).
    void finish(std::size_t k, std::array<std::vector<double>, 3>& mean,
                std::vector<double>& se) const {
        const Sums& s = sums_[k];
        const double B = double(b_), N = n_, total = B * N;
        for (std::size_t c = 0; c < 3; ++c) {
            mean[c].assign(s.mean[c].size(), 0.0);
            for (std::size_t i = 0; i < s.mean[c].size(); ++i) mean[c][i] = s.mean[c][i] / B;
        }
        se.assign(s.se2.size(), 0.0);
        if (total < 2) return;
        for (std::size_t i = 0; i < se.size(); ++i) {
            double worst = 0;
            for (std::size_t c = 0; c < s.channels; ++c) {
                if (i >= mean[c].size()) continue;
                const double between = std::max(0.0, s.mean2[c][i] - B * mean[c][i] * mean[c][i]);
                worst = std::max(worst, N * (N - 1) * s.se2[i] + N * between);
            }
            se[i] = std::sqrt(worst / (total - 1) / total);
        }
    }

    Quantity q_;
    double n_;
    int b_ = 0, inside_ = 0;
    std::array<Sums, 6> sums_;
    rt::V3 m_{0, 0, 0};
    double bent_var_ = 0;
    bool rgb_ = false;
};

}  // namespace sphbasis::render::detail

namespace sphbasis::render {

/// One pass of the plan: what runs, why, and what it cost.
struct Pass {
    std::string name, reason;
    std::uint64_t rays = 0;
    double seconds = 0;
};

}  // namespace sphbasis::render

namespace sphbasis::render {

/// Bakes the requested quantities of a scene. The constructor validates the scene and the
/// settings (std::invalid_argument with a message), builds the Embree scene (or borrows one)
/// and derives the pass plan; bake() runs exactly the planned passes, in parallel on oneTBB.
class Baker {
  public:
    /// Builds the ray-tracing scene of scene.meshes (the "build" pass).
    Baker(const SceneDesc& scene, const BakeSettings& settings)
        : settings_(validated(settings)),
          owned_(timed_scene(scene.meshes, build_seconds_)),
          scene_(*owned_),
          env_(scene.environment),
          lights_(scene.lights) {
        init();
    }
    /// Borrows `built`, a Scene of the same meshes (render::Scene(scene.meshes)), which must
    /// outlive the Baker: one BVH for a renderer and its bakes. The lighting is scene's; the
    /// "build" pass costs 0 s here. Results equal those of the building constructor.
    Baker(const Scene& built, const SceneDesc& scene, const BakeSettings& settings)
        : settings_(validated(settings)),
          scene_(built),
          env_(scene.environment),
          lights_(scene.lights) {
        if (built.mesh_count() != scene.meshes.size())
            sphbasis::detail::throw_invalid(
                "render::Baker", "a Scene of the " + std::to_string(scene.meshes.size()) +
                                     " meshes of the SceneDesc, got one of " +
                                     std::to_string(built.mesh_count()));
        init();
    }
    Baker(const Baker&) = delete;
    Baker& operator=(const Baker&) = delete;

  private:
    void init() {
        validate_lighting();
        qmc_ = detail::rt::QmcTable(static_cast<std::size_t>(settings_.rays));
        stats_ = std::make_unique<Stat[]>(stat_count());
        stats_[build].seconds = build_seconds_;
        derive_plan();
        if (has(settings_.quantities, Quantity::irradiance)) prepare_irradiance();
        if (has(settings_.quantities, Quantity::irradiance | Quantity::radiance))
            prepare_quadrature();
        publish_plan();
    }

  public:
    /// The passes that will run (name, reason); after bake(), with rays and seconds.
    const std::vector<Pass>& plan() const noexcept { return plan_; }
    /// Results for each point (same order). `progress(k)` (optional) is called with the number
    /// of points finished since its last call, from any thread. Throws std::invalid_argument
    /// for a non-finite point, normal or tangent, or a free point (normal 0) when ao, bent,
    /// visibility, transfer or irradiance is requested.
    template <class Progress = void (*)(std::size_t)>
    std::vector<PointResult> bake(const std::vector<BakePoint>& points,
                                  Progress&& progress = nullptr) {
        check_points(points);
        std::vector<PointResult> out(points.size());
        const std::size_t grain = 4;
        // Scratch and counters per thread, not per range: the ray and SH buffers are allocated
        // once per thread and stay warm in its cache (results never depend on them).
        tbb::enumerable_thread_specific<Local> locals([this] { return Local(stat_count()); });
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, points.size(), grain),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              Local& local = locals.local();
                              for (std::size_t i = r.begin(); i != r.end(); ++i)
                                  bake_point(points[i], out[i], local);
                              using P = std::decay_t<Progress>;
                              if constexpr (std::is_same_v<P, std::nullptr_t>) {
                              } else if constexpr (std::is_pointer_v<P>) {
                                  if (progress) progress(r.size());
                              } else {
                                  progress(r.size());
                              }
                          });
        for (const Local& local : locals) merge(local);
        publish_plan();
        return out;
    }
    /// Rays traced so far, all passes.
    std::uint64_t rays_traced() const noexcept {
        std::uint64_t s = 0;
        for (std::size_t k = 0; k < stat_count(); ++k) s += stats_[k].rays.load();
        return s;
    }

    /// Bytes of one PointResult holding the requested quantities (the struct and its vectors'
    /// payload; allocator overhead not counted): the memory per vertex, texel or probe.
    static std::size_t result_bytes(const BakeSettings& s) noexcept {
        const std::size_t n = std::size_t(s.bands) * std::size_t(s.bands), d = sizeof(double);
        std::size_t b = sizeof(PointResult);
        if (has(s.quantities, Quantity::visibility)) b += 2 * n * d;
        if (has(s.quantities, Quantity::transfer)) b += 4 * n * d;
        if (has(s.quantities, Quantity::irradiance))
            b += 4 * std::size_t(std::max(s.coeffs, 0)) * d;
        if (has(s.quantities, Quantity::radiance)) b += 4 * n * d;
        if (has(s.quantities, Quantity::transfer_matrix)) b += 36 * n * d;
        return b;
    }
    /// The ray-tracing scene.
    const Scene& scene() const noexcept { return scene_; }
    /// The bounces that run (K of the header comment).
    int planned_bounces() const noexcept { return bounces_; }
    /// Drops a planned pass by name ("cosine", "hemisphere", "sphere", "shadow", "bounce k",
    /// "analytic"): for tests that show each pass matters. A dropped ray pass leaves its
    /// contribution out (V = 1 for a dropped "cosine" or "hemisphere", no bounce light for a
    /// dropped bounce); a dropped "analytic" pass sends its points to the ray passes.
    void drop_pass(const std::string& name) {
        dropped_.insert(name);
        publish_plan();
    }

  private:
    // Pass indices: fixed ones, then bounce k at bounce0 + k - 1.
    enum : std::size_t { build, analytic, cosine, hemisphere, sphere, shadow, bounce0 };
    static constexpr int irr_bands = 8;  // SH bands of L_in for irradiance
    struct Stat {
        std::atomic<std::uint64_t> rays{0};
        std::atomic<std::uint64_t> points{0};
        double seconds = 0;
        bool planned = false;
        std::string reason;
    };
    using Clock = std::chrono::steady_clock;
    static constexpr std::size_t no_pass = std::size_t(-1);
    struct Local {
        explicit Local(std::size_t n) : rays(n, 0), points(n, 0), seconds(n, 0) {}
        std::vector<std::uint64_t> rays, points;
        std::vector<double> seconds;
        std::size_t timing = no_pass;  // the pass whose Timer is innermost
        Clock::time_point since{};     // when that pass last started or resumed
        // scratch
        std::vector<RTCRay> ray;
        std::vector<RTCRayHit> rayhit;
        std::vector<double> xs, ys, zs, ysh, w, lanes;
        std::vector<double> dx, dy, dz;  // the cosine pass's directions
        std::array<std::vector<double>, 3> wc;
        std::vector<std::array<double, 3>> entry_w;
        std::vector<std::uint32_t> entry_sample;
        std::vector<detail::rt::V3> dirs, local;
        std::vector<char> va, vt;
        // irradiance error: y(local_j), g_j = M y(local_j) (coefficient k's plane of stride
        // rays) and L_in of the lit samples (R, G, B planes of stride rays)
        std::vector<double> irr_y, irr_g, irr_l;
        // transfer_matrix: y3(w_j) and r_j of the occluded samples, the sums of squares of
        // s_j, the occluded samples' slots
        std::vector<double> mat_y, mat_r, mat_ss;
        std::vector<std::uint32_t> mat_slot, mat_samples;
        detail::rt::V3 bent_m{0, 0, 0};  // the last cosine pass's mean V w (adaptive pooling)
    };
    /// Exclusive pass timing: a Timer started inside another pauses the outer one, so nested
    /// work (the shadow rays of a bounce) counts for the inner pass only and the passes'
    /// seconds add up to the thread time.
    struct Timer {
        Local& l;
        std::size_t outer;
        Timer(Local& local, std::size_t pass) : l(local), outer(local.timing) {
            const Clock::time_point now = Clock::now();
            if (outer != no_pass)
                l.seconds[outer] += std::chrono::duration<double>(now - l.since).count();
            l.timing = pass;
            l.since = now;
        }
        Timer(const Timer&) = delete;
        Timer& operator=(const Timer&) = delete;
        ~Timer() {
            const Clock::time_point now = Clock::now();
            l.seconds[l.timing] += std::chrono::duration<double>(now - l.since).count();
            l.timing = outer;
            l.since = now;
        }
    };

    std::size_t stat_count() const noexcept {
        return bounce0 + static_cast<std::size_t>(std::max(settings_.bounces, 0));
    }
    static std::string pass_name(std::size_t k) {
        static const char* names[] = {"build",      "analytic", "cosine",
                                      "hemisphere", "sphere",   "shadow"};
        if (k < bounce0) return names[k];
        return "bounce " + std::to_string(k - bounce0 + 1);
    }
    bool enabled(std::size_t k) const {
        return (stats_[k].planned || stats_[k].rays.load() || stats_[k].points.load()) &&
               !dropped_.count(pass_name(k));
    }

    static BakeSettings validated(const BakeSettings& s) {
        const char* fn = "render::Baker";
        Quantity all{};
        for (Quantity q : all_quantities) all |= q;
        if (!any(s.quantities) || any(s.quantities & ~all))
            sphbasis::detail::throw_invalid(
                fn,
                "quantities: a non-empty set of ao, bent, visibility, transfer, irradiance, "
                "radiance, transfer_matrix, got the bit set " +
                    std::to_string(static_cast<unsigned>(s.quantities)));
        sphbasis::detail::check_range(fn, "bands", s.bands, 1, 16);
        sphbasis::detail::check_range(fn, "rays", s.rays, 1, 1 << 24);
        sphbasis::detail::check_range(fn, "bounces", s.bounces, 0, 64);
        if (!(s.max_distance > 0))
            sphbasis::detail::throw_invalid(
                fn, "max_distance > 0, got " + std::to_string(s.max_distance));
        if (!(s.target_error >= 0) || !std::isfinite(s.target_error))
            sphbasis::detail::throw_invalid(
                fn, "a finite target_error >= 0, got " + std::to_string(s.target_error));
        if (s.adaptive.enabled() || s.adaptive.target != decltype(s.adaptive.target){}) {
            sphbasis::detail::check_range(fn, "adaptive.max_rays", s.adaptive.max_rays, s.rays,
                                          1 << 30);
            bool some = false;
            for (Quantity q : all_quantities) {
                const double t = s.adaptive[q];
                if (!(t >= 0) || !std::isfinite(t) || (t > 0 && !has(s.quantities, q)))
                    sphbasis::detail::throw_invalid(
                        fn, std::string("adaptive targets: finite, >= 0 and only for requested "
                                        "quantities, got ") +
                                std::to_string(t) + " for " + quantity_name(q));
                some = some || t > 0;
            }
            if (!some)
                sphbasis::detail::throw_invalid(
                    fn, "adaptive sampling: a target > 0 for at least one requested quantity");
        }
        if (has(s.quantities, Quantity::irradiance))
            (void)irradiance_storage(s.basis, s.coeffs, fn);
        return s;
    }
    static std::unique_ptr<Scene> timed_scene(const std::vector<MeshView>& m, double& seconds) {
        const auto t0 = Clock::now();
        auto s = std::make_unique<Scene>(m);
        seconds = std::chrono::duration<double>(Clock::now() - t0).count();
        return s;
    }

    void validate_lighting() {
        // render::validate (lighting.hpp) is the one check of environments and lights (finite
        // texels, an orthonormal rotation, sizes, angles); the Baker adds its own below.
        const char* fn = "render::Baker";
        using namespace detail::rt;
        validate(env_);
        for (std::size_t i = 0; i < lights_.size(); ++i) {
            Light& l = lights_[i];
            validate(l);
            const std::string at = " (light " + std::to_string(i) + ")";
            if (l.type != Light::Type::sphere) {
                const double len = length(l.direction);
                if (!(len > 0) || !std::isfinite(len))
                    sphbasis::detail::throw_invalid(fn, "a finite non-zero light direction" + at);
                l.direction = l.direction * (1 / len);
            }
            bool ok = true;
            for (std::size_t k = 0; k < 3; ++k)
                ok = ok && std::isfinite(l.color[k]) && l.color[k] >= 0 &&
                     std::isfinite(l.ground[k]) && l.ground[k] >= 0;
            if (!ok) sphbasis::detail::throw_invalid(fn, "finite light colours >= 0" + at);
            if (l.type == Light::Type::cone && !(l.angle_deg >= 0 && l.angle_deg <= 180))
                sphbasis::detail::throw_invalid(
                    fn, "0 <= angle_deg <= 180, got " + std::to_string(l.angle_deg) + at);
            if (l.type == Light::Type::sphere &&
                (!(l.radius > 0) || !std::isfinite(l.radius) || !finite(l.position)))
                sphbasis::detail::throw_invalid(
                    fn, "a sphere light with a finite position and radius > 0" + at);
        }
    }

    bool wants(Quantity q) const noexcept { return has(settings_.quantities, q); }
    bool has_directional() const noexcept {
        for (const auto& l : lights_)
            if (l.type == Light::Type::directional) return true;
        return false;
    }

    void derive_plan() {
        const bool force = settings_.force_all_passes;
        const bool occl = scene_.can_occlude();
        stats_[build].planned = true;
        stats_[build].reason = std::string(owned_ ? "" : "borrowed ") + "Embree scene of " +
                               std::to_string(scene_.triangle_count()) + " triangles (" +
                               std::to_string(scene_.degenerate_triangles()) +
                               " degenerate skipped)";
        if (!occl && !force) {
            stats_[analytic].planned = true;
            stats_[analytic].reason = scene_.occlusion_reason() +
                                      ": nothing occludes points on it, closed forms, no rays";
        }
        const std::string why_rays =
            force ? "force_all_passes"
                  : (occl ? "the scene can occlude: " + scene_.occlusion_reason()
                          : "points not cleared by the convex test");
        if (wants(Quantity::ao | Quantity::bent | Quantity::transfer) && (occl || force)) {
            stats_[cosine].planned = true;
            stats_[cosine].reason = "ao/bent/transfer, cosine-weighted: " + why_rays;
        }
        if (wants(Quantity::visibility | Quantity::irradiance | Quantity::transfer_matrix) &&
            (occl || force)) {
            stats_[hemisphere].planned = true;
            stats_[hemisphere].reason =
                "visibility/irradiance/transfer_matrix, uniform hemisphere: " + why_rays;
        }
        if (wants(Quantity::radiance) && (scene_.triangle_count() > 0 || force)) {
            stats_[sphere].planned = true;
            stats_[sphere].reason = "radiance at points, uniform sphere";
        }
        if (wants(Quantity::irradiance | Quantity::radiance) && has_directional() &&
            (occl || force || wants(Quantity::radiance))) {
            stats_[shadow].planned = true;
            stats_[shadow].reason = "directional lights: one shadow ray per point and light";
        }
        // Bounces.
        const bool bounce_q = wants(Quantity::transfer | Quantity::irradiance | Quantity::radiance |
                                    Quantity::transfer_matrix);
        const double rho = scene_.max_albedo();
        bounces_ = 0;
        if (!bounce_q || settings_.bounces == 0) return;
        if (force) {
            bounces_ = settings_.bounces;
        } else if (rho > 0 && scene_.triangle_count() > 0) {
            // A point's fraction f_x of rays that hit geometry is at most 1, so rho_max^k bounds
            // bounce k everywhere; each point then stops at the first k with rho_max^k f_x <=
            // target_error (continue_paths). (A scene-wide estimate of f is no bound: a point in
            // a small enclosure of a large open scene has f_x near 1.)
            for (int k = 1; k <= settings_.bounces; ++k) {
                if (std::pow(rho, k) > settings_.target_error)
                    bounces_ = k;
                else
                    break;
            }
        }
        rho_max_ = rho;
        for (int k = 1; k <= bounces_; ++k) {
            Stat& s = stats_[bounce0 + std::size_t(k - 1)];
            // On a lone convex mesh only points the convex test does not clear trace rays: the
            // bounce passes then appear in the plan only if such points traced them.
            s.planned = occl || force || wants(Quantity::radiance);
            char buf[200];
            if (force)
                std::snprintf(buf, sizeof buf, "forced (force_all_passes), every point");
            else
                std::snprintf(buf, sizeof buf,
                              "bound rho_max^%d = %.3g > target_error %.3g; at the points with "
                              "rho_max^%d f_x > target_error (f_x: the point's rays that hit)",
                              k, std::pow(rho, k), settings_.target_error, k);
            s.reason = buf;
        }
    }

    void publish_plan() {
        plan_.clear();
        for (std::size_t k = 0; k < stat_count(); ++k) {
            if (!enabled(k)) continue;
            Pass p;
            p.name = pass_name(k);
            p.reason = stats_[k].reason.empty() ? "points not cleared by the convex test"
                                                : stats_[k].reason;
            p.rays = stats_[k].rays.load();
            p.seconds = stats_[k].seconds;
            plan_.push_back(p);
        }
    }

    void merge(const Local& l) {
        std::lock_guard<std::mutex> g(mutex_);
        for (std::size_t k = 0; k < stat_count(); ++k) {
            stats_[k].rays += l.rays[k];
            stats_[k].points += l.points[k];
            stats_[k].seconds += l.seconds[k];
        }
    }

    void check_points(const std::vector<BakePoint>& pts) const {
        const char* fn = "render::Baker::bake";
        using namespace detail::rt;
        const bool surface_q =
            wants(Quantity::ao | Quantity::bent | Quantity::transfer | Quantity::visibility |
                  Quantity::irradiance | Quantity::transfer_matrix);
        for (std::size_t i = 0; i < pts.size(); ++i) {
            const BakePoint& p = pts[i];
            if (!finite(p.p) || !finite(p.n) || !finite(p.tangent))
                sphbasis::detail::throw_invalid(fn,
                                                "finite positions, normals and tangents, got "
                                                "a NaN or an infinity at point " +
                                                    std::to_string(i));
            for (const double x : {p.p.x, p.p.y, p.p.z})
                if (!(std::fabs(x) <= coordinate_limit))
                    sphbasis::detail::throw_invalid(
                        fn, "positions within [-1e15, 1e15] (render::coordinate_limit), got " +
                                std::to_string(x) + " at point " + std::to_string(i));
            if (surface_q && !(length(p.n) > 0))
                sphbasis::detail::throw_invalid(
                    fn,
                    "a surface point (non-zero normal) for ao, bent, visibility, transfer and "
                    "irradiance, got normal 0 at point " +
                        std::to_string(i));
        }
    }

    // ---- sky ----------------------------------------------------------------------------
    /// Radiance along a ray from o in direction d whose first hit is at tmax (inf: escaped).
    RGB sky(const detail::rt::V3& o, const detail::rt::V3& d, double tmax) const noexcept {
        const bool escaped = !(tmax < std::numeric_limits<double>::infinity());
        RGB L = escaped ? env_.radiance({d.x, d.y, d.z}) : RGB{0, 0, 0};
        detail::rt::add_light_radiance(lights_, o, d, tmax, escaped, L);
        return L;
    }

    // ---- precomputation -------------------------------------------------------------------
    void prepare_irradiance() {
        // The linear stage (header comment): irr_map_ (stage x 64) takes L_lm (local, 8 bands) to
        // the stage's values, irr_projector_ (stage x M) the irradiance on irr_rule_'s M
        // directions (directional lights) to them.
        irr_ = irradiance_storage(settings_.basis, settings_.coeffs);
        const int n = irr_bands * irr_bands;
        double a[irr_bands];
        clamped_cosine_factors(irr_bands, a);
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        if (irr_.kind == IrradianceStorage::Kind::fitted) {
            // The irradiance's SH: E_lm = pi a_l L_lm (directional lights: finish_irradiance()).
            irr_map_ = Eigen::MatrixXd::Zero(irr_.stage(), n);
            for (int l = 0; l < irr_bands; ++l)
                for (int k = l * l; k < (l + 1) * (l + 1) && k < irr_.stage(); ++k)
                    irr_map_(k, k) = constants::pi * a[l];
        } else {
            if (irr_.kind == IrradianceStorage::Kind::sg_running) {
                irr_rule_ = sg_running_directions();
                irr_projector_ = Eigen::Map<const RowMajor>(
                    sg_running_projector(settings_.coeffs, irr_rule_).data(), settings_.coeffs,
                    static_cast<Eigen::Index>(irr_rule_.size()));
            } else {
                // One fit for every irradiance in the library (render/irradiance_fit.hpp): least
                // squares over hemisphere_rule_sqrt(32, 32) in the tangent frame, as a projector
                // P (coeffs x M).
                const IrradianceFit fit(irr_.basis->name, settings_.coeffs,
                                        hemisphere_rule_sqrt(32, 32));
                irr_rule_ = fit.rule();
                irr_projector_ =
                    Eigen::Map<const RowMajor>(fit.projector().data(), fit.coeffs(),
                                               static_cast<Eigen::Index>(fit.directions()));
                if (irr_.kind == IrradianceStorage::Kind::sg_nnls) {
                    // G = Phi^T V Phi on the rule (NNLS in the Gram form: finish_point()).
                    const BasicLeastSquares<> ls(irr_.basis->functions(settings_.coeffs), false,
                                                 irr_rule_);
                    irr_gram_ =
                        ls.evaluation().transpose() * ls.weights().asDiagonal() * ls.evaluation();
                }
            }
            Eigen::MatrixXd m(static_cast<Eigen::Index>(irr_rule_.size()), n);
            std::vector<double> y(static_cast<std::size_t>(n));
            for (std::size_t i = 0; i < irr_rule_.size(); ++i) {
                sh::eval_unit(irr_bands, irr_rule_.x[i], irr_rule_.y[i], irr_rule_.z[i], y.data());
                for (int l = 0; l < irr_bands; ++l)
                    for (int k = l * l; k < (l + 1) * (l + 1); ++k)
                        m(Eigen::Index(i), k) = constants::pi * a[l] * y[std::size_t(k)];
            }
            irr_map_ = irr_projector_ * m;  // coeffs x n: L_lm (local) -> fitted E
        }
        irr_map_rows_.resize(std::size_t(irr_map_.size()));
        for (Eigen::Index k = 0; k < irr_map_.rows(); ++k)
            for (Eigen::Index i = 0; i < n; ++i)
                irr_map_rows_[std::size_t(k * n + i)] = irr_map_(k, i);
    }
    void prepare_quadrature() {
        // Hemisphere rule in the tangent frame (irradiance of unoccluded points) and sphere
        // rule (radiance with no geometry): the sky is sampled, not ray traced.
        hemi_rule_ = hemisphere_rule(48);
        sphere_rule_ = sphere_rule(48);
    }

    // ---- per point ------------------------------------------------------------------------
    std::uint64_t local_rays(const Local& L) const noexcept {
        return std::accumulate(L.rays.begin(), L.rays.end(), std::uint64_t(0));
    }

    /// One point: one batch, or adaptive batches (AdaptiveSampling) pooled until the targets
    /// are met or max_rays is reached.
    void bake_point(const BakePoint& bp, PointResult& res, Local& L) const {
        using namespace detail::rt;
        const std::uint64_t key = hash(settings_.seed, bp.id), r0 = local_rays(L);
        if (!settings_.adaptive.enabled()) {
            bake_batch(bp, key, res, L);
        } else {
            const V3 n = normalized(bp.n, {0, 0, 0});
            detail::AdaptivePool pool(settings_.quantities, std::size_t(settings_.rays));
            const int max_batches = std::max(1, settings_.adaptive.max_rays / settings_.rays);
            for (int b = 0; b < max_batches; ++b) {
                PointResult rb;
                L.bent_m = n * (2.0 / 3.0);  // points nothing occludes skip the cosine pass
                bake_batch(bp, b == 0 ? key : hash(key, 0x6261746368ull, std::uint64_t(b)), rb, L);
                pool.add(rb, L.bent_m);
                if (b == 0)
                    res = std::move(rb);  // one batch: the fixed bake's result, bit for bit
                else
                    pool.result(res, n);
                res.batches = b + 1;
                if (meets_targets(settings_, res)) break;
            }
        }
        res.rays = local_rays(L) - r0;
        if (wants(Quantity::irradiance)) finish_point(res);
    }

    /// The stored irradiance from the linear stage (header comment), after adaptive pooling:
    /// sg-nnls solves the NNLS of the least-squares amplitudes c (h = G c); a fitted
    /// representation fits the stage's SH of E, its standard errors those of the SH it copies,
    /// and ZH3's zonal value z = sqrt(4 pi / 5) sum_m e_2m y_2m(axis) the bound
    /// sqrt(sum_m stderr_2m^2) (Cauchy-Schwarz: sum_m (sqrt(4 pi / 5) y_2m)^2 = 1; the axis's own
    /// error left out). The linear kinds are stored as estimated.
    void finish_point(PointResult& res) const {
        if (irr_.kind == IrradianceStorage::Kind::sg_nnls) {
            for (auto& ch : res.irradiance) {
                Eigen::Map<Eigen::VectorXd> c(ch.data(), Eigen::Index(ch.size()));
                c = sg::nnls_gram(irr_gram_, irr_gram_ * c).eval();
            }
        } else if (irr_.kind == IrradianceStorage::Kind::fitted) {
            const std::size_t nk = std::size_t(irr_.coeffs);
            std::vector<double> out(nk);
            for (auto& ch : res.irradiance) {
                irr_.fitted->fit(ch.data(), out.data());
                ch = out;
            }
            std::vector<double>& se = res.irradiance_stderr;
            double z2 = 0;
            for (std::size_t k = 4; k < se.size(); ++k) z2 += se[k] * se[k];
            se.resize(nk);
            if (nk > 4) se[4] = std::sqrt(z2);
        }
    }

    void bake_batch(const BakePoint& bp, std::uint64_t key, PointResult& res, Local& L) const {
        using namespace detail::rt;
        const V3 n = normalized(bp.n, {0, 0, 0});
        const bool surface = length(n) > 0;
        const double cu = unit(hash(key, 1)), cv = unit(hash(key, 2));
        Frame<double> f;
        if (surface) f = frame_of(n, bp.tangent, bp.bitangent_sign);
        const bool free_of_occluders = surface && !settings_.force_all_passes &&
                                       !dropped_.count("analytic") && scene_.unoccluded(bp.p, n);
        if (free_of_occluders && enabled(analytic)) {
            Timer t{L, analytic};
            ++L.points[analytic];
            analytic_point(bp.p, n, f, res);
        } else {
            if (wants(Quantity::ao | Quantity::bent | Quantity::transfer))
                cosine_pass(bp, n, f, key, cu, cv, res, L);
            if (wants(Quantity::visibility | Quantity::irradiance))
                hemisphere_pass(bp, n, f, key, cu, cv, res, L);
            if (wants(Quantity::transfer_matrix)) matrix_pass(bp, n, f, key, cu, cv, res, L);
        }
        if (wants(Quantity::radiance)) {
            if (scene_.triangle_count() == 0 && !settings_.force_all_passes) {
                Timer t{L, analytic};
                ++L.points[analytic];
                radiance_closed_form(bp.p, res);
            } else {
                sphere_pass(bp, n, key, cu, cv, res, L);
            }
        }
    }

    static Frame<double> frame_of(const detail::rt::V3& n, const detail::rt::V3& tangent,
                                  double bitangent_sign = 1) {
        using namespace detail::rt;
        V3 t = tangent - n * dot(n, tangent);
        const double lt = length(t);
        if (lt > 1e-6) {
            t = t * (1 / lt);
            return Frame<double>(t, cross(n, t) * (bitangent_sign < 0 ? -1.0 : 1.0), n);
        }
        return Frame<double>(n);
    }

    std::size_t nsh() const noexcept { return std::size_t(settings_.bands * settings_.bands); }

    void analytic_point(const detail::rt::V3& p, const detail::rt::V3& n, const Frame<double>& f,
                        PointResult& res) const {
        using namespace detail::rt;
        const int B = settings_.bands;
        std::vector<double> y(nsh()), a(static_cast<std::size_t>(B));
        sh::eval_unit(B, n.x, n.y, n.z, y.data());
        clamped_cosine_factors(B, a.data());
        if (wants(Quantity::ao)) {
            res.ao = 1;
            res.ao_stderr = 0;
        }
        if (wants(Quantity::bent)) {
            res.bent = n;
            res.bent_stderr = 0;
        }
        if (wants(Quantity::transfer)) {
            std::vector<double> t(nsh());
            for (int l = 0; l < B; ++l)
                for (int k = l * l; k < (l + 1) * (l + 1); ++k)
                    t[std::size_t(k)] = a[std::size_t(l)] * y[std::size_t(k)];
            res.transfer = {t, t, t};
            res.transfer_stderr.assign(nsh(), 0.0);
            res.transfer_rgb = false;
        }
        if (wants(Quantity::transfer_matrix)) {
            std::vector<double> m(9 * nsh(), 0.0);
            for (std::size_t i = 0; i < 9 && i < nsh(); ++i) m[i * nsh() + i] = 1;
            res.transfer_matrix = {m, m, m};
            res.transfer_matrix_stderr.assign(9 * nsh(), 0.0);
        }
        if (wants(Quantity::visibility)) {
            res.visibility.assign(nsh(), 0.0);
            std::vector<double> lam(static_cast<std::size_t>(B));
            sh::detail::cap_factors(B, 1.0, lam.data());  // the upper hemisphere: 1 - cos = 1
            for (int l = 0; l < B; ++l)
                for (int k = l * l; k < (l + 1) * (l + 1); ++k)
                    res.visibility[std::size_t(k)] = lam[std::size_t(l)] * y[std::size_t(k)];
            res.visibility_stderr.assign(nsh(), 0.0);
        }
        if (wants(Quantity::irradiance)) {
            // L_lm in the tangent frame by quadrature of the sky over the upper hemisphere.
            const int n8 = irr_bands * irr_bands;
            std::array<std::vector<double>, 3> Llm;
            for (auto& v : Llm) v.assign(std::size_t(n8), 0.0);
            std::vector<double> yy(static_cast<std::size_t>(n8));
            const double inf = std::numeric_limits<double>::infinity();
            for (std::size_t q = 0; q < hemi_rule_.size(); ++q) {
                const V3 dl{hemi_rule_.x[q], hemi_rule_.y[q], hemi_rule_.z[q]};
                const RGB s = sky(p, f.to_world(dl), inf);
                sh::eval_unit(irr_bands, dl.x, dl.y, dl.z, yy.data());
                for (std::size_t c = 0; c < 3; ++c)
                    if (s[c] != 0)
                        for (std::size_t k = 0; k < std::size_t(n8); ++k)
                            Llm[c][k] += hemi_rule_.w[q] * s[c] * yy[k];
            }
            std::vector<std::pair<V3, RGB>> dir;  // unoccluded directional lights (local)
            for (const auto& l : lights_)
                if (l.type == Light::Type::directional && dot(l.direction, n) > 0)
                    dir.push_back({f.to_local(l.direction), l.color});
            finish_irradiance(Llm, dir, res);
            res.irradiance_stderr.assign(std::size_t(irr_map_.rows()), 0.0);
        }
    }

    /// irradiance coefficients from L_lm (local, 8 bands) and visible directional lights.
    void finish_irradiance(const std::array<std::vector<double>, 3>& Llm,
                           const std::vector<std::pair<detail::rt::V3, RGB>>& dir,
                           PointResult& res) const {
        const Eigen::Index n8 = irr_bands * irr_bands;
        Eigen::MatrixXd lm(n8, 3);
        for (Eigen::Index k = 0; k < n8; ++k)
            for (Eigen::Index c = 0; c < 3; ++c) lm(k, c) = Llm[std::size_t(c)][std::size_t(k)];
        Eigen::MatrixXd e = irr_map_ * lm;  // stage x 3
        if (irr_.kind == IrradianceStorage::Kind::fitted) {
            // A delta of colour col along d: E_lm = pi a_l col y_lm(d), exact per coefficient.
            const int nb = irr_.stage() <= 4 ? 2 : 3;
            double a[3], y[9];
            clamped_cosine_factors(nb, a);
            for (const auto& [d, col] : dir) {
                sh::eval_unit(nb, d.x, d.y, d.z, y);
                for (Eigen::Index k = 0; k < e.rows(); ++k)
                    for (Eigen::Index c = 0; c < 3; ++c)
                        e(k, c) += constants::pi * a[k == 0 ? 0 : (k < 4 ? 1 : 2)] *
                                   y[std::size_t(k)] * col[std::size_t(c)];
            }
        } else if (!dir.empty()) {
            const Eigen::Index R = static_cast<Eigen::Index>(irr_rule_.size());
            Eigen::MatrixXd s = Eigen::MatrixXd::Zero(R, 3);
            for (const auto& [d, col] : dir)
                for (Eigen::Index i = 0; i < R; ++i) {
                    const std::size_t ii = std::size_t(i);
                    const double c =
                        irr_rule_.x[ii] * d.x + irr_rule_.y[ii] * d.y + irr_rule_.z[ii] * d.z;
                    if (c > 0)
                        for (Eigen::Index k = 0; k < 3; ++k) s(i, k) += c * col[std::size_t(k)];
                }
            e += irr_projector_ * s;
        }
        for (std::size_t c = 0; c < 3; ++c) {
            res.irradiance[c].resize(std::size_t(e.rows()));
            for (Eigen::Index k = 0; k < e.rows(); ++k)
                res.irradiance[c][std::size_t(k)] = e(k, Eigen::Index(c));
        }
    }

    /// Zonal SH of a cap of half-angle alpha about d with radiance col, added to out.
    void add_cap(const detail::rt::V3& d, double cos_alpha, const RGB& col,
                 std::array<std::vector<double>, 3>& out) const {
        const int B = settings_.bands;
        std::vector<double> y(nsh());
        sh::eval_unit(B, d.x, d.y, d.z, y.data());
        std::vector<double> lam(static_cast<std::size_t>(B));
        sh::detail::cap_factors(B, 1 - cos_alpha, lam.data());  // Funk-Hecke factors of the cap
        for (int l = 0; l < B; ++l) {
            for (int k = l * l; k < (l + 1) * (l + 1); ++k)
                for (std::size_t c = 0; c < 3; ++c)
                    out[c][std::size_t(k)] += col[c] * lam[std::size_t(l)] * y[std::size_t(k)];
        }
    }

    /// radiance with no geometry: the environment by quadrature, lights in closed form.
    void radiance_closed_form(const detail::rt::V3& p, PointResult& res) const {
        using namespace detail::rt;
        for (auto& v : res.radiance) v.assign(nsh(), 0.0);
        res.radiance_stderr.assign(nsh(), 0.0);
        std::vector<double> y(nsh());
        if (env_.kind != Environment::Kind::none)
            for (std::size_t q = 0; q < sphere_rule_.size(); ++q) {
                const V3 d{sphere_rule_.x[q], sphere_rule_.y[q], sphere_rule_.z[q]};
                const RGB s = env_.radiance({d.x, d.y, d.z});
                sh::eval_unit(settings_.bands, d.x, d.y, d.z, y.data());
                for (std::size_t c = 0; c < 3; ++c)
                    for (std::size_t k = 0; k < nsh(); ++k)
                        res.radiance[c][k] += sphere_rule_.w[q] * s[c] * y[k];
            }
        for (const Light& l : lights_) {
            switch (l.type) {
                case Light::Type::directional: {
                    sh::eval_unit(settings_.bands, l.direction.x, l.direction.y, l.direction.z,
                                  y.data());
                    for (std::size_t c = 0; c < 3; ++c)
                        for (std::size_t k = 0; k < nsh(); ++k)
                            res.radiance[c][k] += l.color[c] * y[k];
                    break;
                }
                case Light::Type::cone:
                    add_cap(l.direction, std::cos(l.angle_deg * constants::pi / 180), l.color,
                            res.radiance);
                    break;
                case Light::Type::hemisphere: {
                    add_cap(l.direction, -1.0, l.ground, res.radiance);
                    const RGB diff{l.color[0] - l.ground[0], l.color[1] - l.ground[1],
                                   l.color[2] - l.ground[2]};
                    add_cap(l.direction, 0.0, diff, res.radiance);
                    break;
                }
                case Light::Type::sphere: {
                    const V3 dc = l.position - p;
                    const double dist = length(dc);
                    if (dist <= l.radius)
                        add_cap({0, 0, 1}, -1.0, l.color, res.radiance);
                    else
                        add_cap(dc * (1 / dist),
                                std::sqrt(std::max(0.0, 1 - (l.radius / dist) * (l.radius / dist))),
                                l.color, res.radiance);
                    break;
                }
            }
        }
    }

    // ---- ray passes -----------------------------------------------------------------------
    /// A bounce path: which primary sample, its throughput and its current hit.
    struct PathState {
        std::uint32_t sample;
        RGB throughput;
        Hit hit;
    };

    /// Continues paths from their hits for the planned bounces. For each escape (and, with
    /// `lit`, each light seen or each directional light reached from a vertex), calls
    /// emit(sample, direction, weight RGB, escaped) ... simplified: escape(sample, dir, T) and
    /// light(sample, radiance RGB).
    template <class Escape, class Gather>
    void continue_paths(std::vector<PathState>& paths, std::size_t primary_rays, std::uint64_t key,
                        bool lit, Local& L, Escape&& escape, Gather&& gather) const {
        using namespace detail::rt;
        // f_x: the fraction of this point's primary rays that hit geometry (every hit starts a
        // path), the point's own factor of the bound rho_max^k f_x.
        const double fx = primary_rays > 0 ? double(paths.size()) / double(primary_rays) : 0.0;
        for (int k = 1; k <= bounces_ && !paths.empty(); ++k) {
            const std::size_t pass = bounce0 + std::size_t(k - 1);
            if (dropped_.count(pass_name(pass))) break;
            if (!settings_.force_all_passes &&
                !(std::pow(rho_max_, k) * fx > settings_.target_error))
                break;
            Timer t{L, pass};
            std::vector<PathState> next;
            std::vector<V3> dirs;
            L.rayhit.clear();
            std::vector<PathState> live, lit_paths;
            for (PathState& ps : paths) {
                for (std::size_t c = 0; c < 3; ++c) ps.throughput[c] *= ps.hit.albedo[c];
                if (!(std::max({ps.throughput[0], ps.throughput[1], ps.throughput[2]}) > 0))
                    continue;
                if (lit) lit_paths.push_back(ps);
                const std::uint64_t h = hash(key, ps.sample, std::uint64_t(k));
                const Frame<double> f(ps.hit.shading_normal);
                // The cosine lobe about the shading normal, folded above the geometric surface
                // (fold_above: the weight stays the albedo, nothing is lost where the two
                // normals differ). Only a direction exactly in the tangent plane (probability
                // 0) ends the path.
                const V3 d = fold_above(
                    ps.hit.geometric_normal,
                    f.to_world(square_to_cosine_hemisphere(unit(hash(h, 1)), unit(hash(h, 2)))));
                if (!(dot(d, ps.hit.geometric_normal) > 0)) continue;
                RTCRayHit r;
                Scene::set_ray(r, scene_.offset_origin(ps.hit.position, ps.hit.geometric_normal, d),
                               d);
                L.rayhit.push_back(r);
                dirs.push_back(d);
                live.push_back(ps);
            }
            if (lit) direct_lights_at_vertices(lit_paths, L, gather);
            scene_.intersect(L.rayhit.data(), L.rayhit.size());
            L.rays[pass] += L.rayhit.size();
            for (std::size_t i = 0; i < live.size(); ++i) {
                const RTCRayHit& r = L.rayhit[i];
                const bool esc = r.hit.geomID == RTC_INVALID_GEOMETRY_ID;
                const V3 o{r.ray.org_x, r.ray.org_y, r.ray.org_z};
                escape(live[i].sample, dirs[i], live[i].throughput, o,
                       esc ? std::numeric_limits<double>::infinity() : double(r.ray.tfar));
                if (!esc && k < bounces_) {
                    PathState ps = live[i];
                    ps.hit = scene_.hit(r);
                    next.push_back(ps);
                }
            }
            paths.swap(next);
        }
    }

    /// Next-event estimation of directional lights at path vertices (throughput already
    /// includes the vertex albedo): T color c / pi when unshadowed, c the folded cosine of the
    /// path's continuation (detail::rt::folded_cosine; max(ns.l, 0) where ns = ng).
    template <class Gather>
    void direct_lights_at_vertices(const std::vector<PathState>& live, Local& L,
                                   Gather&& gather) const {
        using namespace detail::rt;
        if (!has_directional()) return;
        Timer t{L, shadow};
        std::vector<RTCRay> rays;
        std::vector<std::pair<std::uint32_t, RGB>> contrib;
        for (const PathState& ps : live)
            for (const Light& l : lights_) {
                if (l.type != Light::Type::directional) continue;
                const double c =
                    folded_cosine(ps.hit.shading_normal, ps.hit.geometric_normal, l.direction);
                if (!(c > 0)) continue;
                RTCRay r;
                Scene::set_ray(
                    r, scene_.offset_origin(ps.hit.position, ps.hit.geometric_normal, l.direction),
                    l.direction);
                rays.push_back(r);
                RGB w;
                for (std::size_t k = 0; k < 3; ++k)
                    w[k] = ps.throughput[k] * l.color[k] * c * constants::inv_pi;
                contrib.push_back({ps.sample, w});
            }
        if (!dropped_.count("shadow")) {
            scene_.occluded(rays.data(), rays.size());
            L.rays[shadow] += rays.size();
        }
        for (std::size_t i = 0; i < rays.size(); ++i)
            if (!Scene::is_occluded(rays[i])) gather(contrib[i].first, contrib[i].second);
    }

    /// acc[q] += sum of v_e and acc[lanes + q] += sum of v_e^2 over e = q mod lanes, e < n (n a
    /// multiple of lanes), v_e = y[e] (w null) or w[e] y[e]: one SIMD register per `lanes`
    /// partial sums where batches are that wide, the same sums in the same order otherwise.
    template <std::size_t lanes>
    static void accumulate_lanes(const double* y, const double* w, std::size_t n,
                                 double* acc) noexcept {
#if SPHBASIS_HAS_VECTOR_EXT
        using B = batch<double>;
        constexpr std::size_t W = static_cast<std::size_t>(B::size);
        if constexpr (lanes % W == 0) {
            constexpr std::size_t nb = lanes / W;
            B a[nb], b[nb];
            for (std::size_t i = 0; i < nb; ++i) {
                a[i] = B::load(acc + i * W);
                b[i] = B::load(acc + lanes + i * W);
            }
            for (std::size_t e = 0; e < n; e += lanes)
                for (std::size_t i = 0; i < nb; ++i) {
                    B v = B::load(y + e + i * W);
                    if (w) v = v * B::load(w + e + i * W);
                    a[i] += v;
                    b[i] += v * v;
                }
            for (std::size_t i = 0; i < nb; ++i) {
                a[i].store(acc + i * W);
                b[i].store(acc + lanes + i * W);
            }
            return;
        }
#endif
        for (std::size_t e = 0; e < n; e += lanes)
            for (std::size_t q = 0; q < lanes; ++q) {
                const double v = w ? w[e + q] * y[e + q] : y[e + q];
                acc[q] += v;
                acc[lanes + q] += v * v;
            }
    }

    /// SH accumulation of weighted directions: out_c[k] = scale * sum_e w_c[e] y_k(d_e) and the
    /// standard error of the mean of per-sample values (samples without an entry are 0). The
    /// directions are L.xs, L.ys, L.zs[0..m); `unit`: every weight is 1 (w is not read).
    /// The basis values come from sh::eval_batch a block of `block` directions at a time (the
    /// block's values stay in L1 between evaluation and accumulation), summed in `lanes`
    /// independent partial sums per coefficient and channel: a fixed order (entry e goes to lane
    /// e mod lanes), so the result does not depend on threads, and the loop runs at SIMD width.
    void accumulate_sh(Local& L, std::size_t m, const std::vector<std::array<double, 3>>& w,
                       bool unit, const std::vector<std::uint32_t>& sample, std::size_t nsamples,
                       double scale, bool rgb, std::array<std::vector<double>, 3>& out,
                       std::vector<double>* stderr_out) const {
        const std::size_t K = nsh();
        for (auto& v : out) v.assign(K, 0.0);
        if (stderr_out) stderr_out->assign(K, 0.0);
        if (m == 0) return;
        const std::size_t nc = rgb ? 3 : 1;
        // Per-sample totals are needed for the error when a sample has several entries.
        bool unique = true;
        for (std::size_t e = 1; e < m && unique; ++e) unique = sample[e] != sample[e - 1];
        std::array<std::vector<double>, 3>& wc = L.wc;
        if (!unit)
            for (std::size_t c = 0; c < nc; ++c) {
                wc[c].resize(m);
                for (std::size_t e = 0; e < m; ++e) wc[c][e] = w[e][c];
            }
        const double N = double(nsamples);
        auto finish = [&](std::size_t k, std::size_t c, double s, double s2) {
            const double mean = s / N;
            out[c][k] = scale * mean;
            if (stderr_out && nsamples > 1) {
                const double var = std::max(0.0, (s2 / N - mean * mean)) * N / (N - 1);
                (*stderr_out)[k] = std::max((*stderr_out)[k], scale * std::sqrt(var / N));
            }
        };
        if (!unique && stderr_out) {
            // Entries of one sample summed first (bounce paths): all values at once.
            L.ysh.resize(K * m);
            sh::eval_batch(settings_.bands, m, L.xs.data(), L.ys.data(), L.zs.data(), L.ysh.data(),
                           m);
            std::vector<double> acc;
            for (std::size_t k = 0; k < K; ++k) {
                const double* yk = &L.ysh[k * m];
                for (std::size_t c = 0; c < nc; ++c) {
                    acc.assign(nsamples, 0.0);
                    const double* wp = unit ? nullptr : wc[c].data();
                    for (std::size_t e = 0; e < m; ++e)
                        acc[sample[e]] += (unit ? 1.0 : wp[e]) * yk[e];
                    double s = 0, s2 = 0;
                    for (double v : acc) {
                        s += v;
                        s2 += v * v;
                    }
                    finish(k, c, s, s2);
                }
                if (!rgb) out[1][k] = out[2][k] = out[0][k];
            }
            return;
        }
        constexpr std::size_t block = 64, lanes = 8;
        const std::size_t padded = (m + lanes - 1) / lanes * lanes;
        if (!unit)  // zero weights past m: the last block's padding adds exact zeros
            for (std::size_t c = 0; c < nc; ++c) wc[c].resize(padded, 0.0);
        L.lanes.assign(K * nc * 2 * lanes, 0.0);
        L.ysh.resize(K * block);
        for (std::size_t e0 = 0; e0 < m; e0 += block) {
            const std::size_t mb = std::min(block, m - e0);
            const std::size_t mp = std::min(block, padded - e0);  // mb rounded up to lanes
            sh::eval_batch(settings_.bands, mb, L.xs.data() + e0, L.ys.data() + e0,
                           L.zs.data() + e0, L.ysh.data(), block);
            for (std::size_t k = 0; k < K; ++k)
                for (std::size_t e = mb; e < mp; ++e) L.ysh[k * block + e] = 0;
            for (std::size_t k = 0; k < K; ++k) {
                const double* yk = &L.ysh[k * block];
                for (std::size_t c = 0; c < nc; ++c)
                    accumulate_lanes<lanes>(yk, unit ? nullptr : wc[c].data() + e0, mp,
                                            &L.lanes[(k * nc + c) * 2 * lanes]);
            }
        }
        for (std::size_t k = 0; k < K; ++k) {
            for (std::size_t c = 0; c < nc; ++c) {
                const double* a = &L.lanes[(k * nc + c) * 2 * lanes];
                const double* b = a + lanes;
                const double s = ((a[0] + a[1]) + (a[2] + a[3])) + ((a[4] + a[5]) + (a[6] + a[7]));
                const double s2 = ((b[0] + b[1]) + (b[2] + b[3])) + ((b[4] + b[5]) + (b[6] + b[7]));
                finish(k, c, s, s2);
            }
            if (!rgb) out[1][k] = out[2][k] = out[0][k];
        }
    }

    void push_dir(Local& L, const detail::rt::V3& d) const {
        L.xs.push_back(d.x);
        L.ys.push_back(d.y);
        L.zs.push_back(d.z);
    }
    void clear_dirs(Local& L) const {
        L.xs.clear();
        L.ys.clear();
        L.zs.clear();
    }

    /// ao, bent and transfer from cosine-weighted rays. The directions are generated as three
    /// arrays (L.dx, L.dy, L.dz); without bounces (and without a finite max_distance beside
    /// transfer) the rays are occlusion queries and every per-ray step after tracing is
    /// branch-free: visibility is a 0/1 value, the unoccluded directions are compacted for the
    /// SH accumulation.
    void cosine_pass(const BakePoint& bp, const detail::rt::V3& n, const Frame<double>& f,
                     std::uint64_t key, double cu, double cv, PointResult& res, Local& L) const {
        using namespace detail::rt;
        const std::size_t N = std::size_t(settings_.rays);
        const bool tr = wants(Quantity::transfer);
        const double maxd = settings_.max_distance;
        const bool finite_max = maxd < std::numeric_limits<double>::infinity();
        const bool use_hits =
            tr && (bounces_ > 0 || (finite_max && wants(Quantity::ao | Quantity::bent)));
        const bool run = !dropped_.count("cosine");
        const V3 o = bp.p + n * scene_.epsilon();
        std::vector<char>& vis_ao = L.va;
        std::vector<char>& vis_tr = L.vt;
        L.dx.resize(N);
        L.dy.resize(N);
        L.dz.resize(N);
        const double *dx = L.dx.data(), *dy = L.dy.data(), *dz = L.dz.data();
        vis_ao.assign(N, 1);
        std::vector<PathState> paths;
        {
            Timer t{L, cosine};
            qmc_.directions(Warp::cosine, f, cu, cv, L.dx.data(), L.dy.data(), L.dz.data());
            if (run && use_hits) {
                vis_tr.assign(N, 1);
                L.rayhit.resize(N);
                for (std::size_t j = 0; j < N; ++j)
                    Scene::set_ray(L.rayhit[j], o, V3{dx[j], dy[j], dz[j]});
                scene_.intersect(L.rayhit.data(), N);
                for (std::size_t j = 0; j < N; ++j) {
                    const RTCRayHit& r = L.rayhit[j];
                    if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                    vis_tr[j] = 0;
                    vis_ao[j] = r.ray.tfar > maxd;
                    if (bounces_ > 0)
                        paths.push_back({std::uint32_t(j), RGB{1, 1, 1}, scene_.hit(r)});
                }
            } else if (run) {
                // One visibility serves both: tfar is max_distance for ao/bent alone and
                // infinite with transfer (whose finite max_distance case traces hits above).
                L.ray.resize(N);
                const double tfar = tr ? std::numeric_limits<double>::infinity() : maxd;
                RTCRay proto;
                Scene::set_ray(proto, o, V3{0, 0, 1}, 0, tfar);
                RTCRay* rays = L.ray.data();
                for (std::size_t j = 0; j < N; ++j) {
                    RTCRay r = proto;
                    r.dir_x = static_cast<float>(dx[j]);
                    r.dir_y = static_cast<float>(dy[j]);
                    r.dir_z = static_cast<float>(dz[j]);
                    rays[j] = r;
                }
                scene_.occluded(rays, N);
                char* va = vis_ao.data();
                for (std::size_t j = 0; j < N; ++j) va[j] = !Scene::is_occluded(rays[j]);
            }
            if (run) L.rays[cosine] += N;
            if (wants(Quantity::ao | Quantity::bent)) ao_bent(N, L, vis_ao, n, res);
        }
        if (!tr) return;
        transfer_part(N, L, use_hits && run ? vis_tr : vis_ao, paths, key, res);
    }

    void ao_bent(std::size_t N, Local& L, const std::vector<char>& vis_ao, const detail::rt::V3& n,
                 PointResult& res) const {
        using namespace detail::rt;
        const double *dx = L.dx.data(), *dy = L.dy.data(), *dz = L.dz.data();
        const char* va = vis_ao.data();
        double s = 0, bx = 0, by = 0, bz = 0;
        if (!wants(Quantity::bent)) {
            for (std::size_t j = 0; j < N; ++j) s += va[j];
        } else {
            // The second moments of V_j w_j (V in {0, 1}: V w w^T = V (w w^T)) beside the sums,
            // for bent_stderr; still one branch-free loop.
            double sxx = 0, syy = 0, szz = 0, sxy = 0, sxz = 0, syz = 0;
            for (std::size_t j = 0; j < N; ++j) {
                const double v = va[j];
                const double x = v * dx[j], y = v * dy[j], z = v * dz[j];
                s += v;
                bx += x;
                by += y;
                bz += z;
                sxx += x * dx[j];
                syy += y * dy[j];
                szz += z * dz[j];
                sxy += x * dy[j];
                sxz += x * dz[j];
                syz += y * dz[j];
            }
            res.bent = normalized(V3{bx, by, bz}, n);
            L.bent_m = V3{bx, by, bz} * (1 / double(N));
            res.bent_stderr = bent_error(N, s, V3{bx, by, bz}, {sxx, syy, szz, sxy, sxz, syz});
        }
        if (wants(Quantity::ao)) {
            res.ao = s / double(N);
            res.ao_stderr = N > 1 ? std::sqrt(res.ao * (1 - res.ao) / double(N - 1)) : 0;
        }
    }

    /// bent_stderr (header comment) from the sums over N cosine-weighted samples of V_j w_j
    /// (sum) and of V_j w_j w_j^T (second: xx, yy, zz, xy, xz, yz); `hits` = sum of V_j.
    static double bent_error(std::size_t N, double hits, const detail::rt::V3& sum,
                             const std::array<double, 6>& second) noexcept {
        using namespace detail::rt;
        const double pi = constants::pi;
        if (N < 2 || !(hits > 0)) return pi;  // no variance estimate / no unoccluded sample
        const double dn = double(N);
        const V3 m = sum * (1 / dn);
        const double lm = length(m);
        if (!(lm > 0)) return pi;
        const V3 b = m * (1 / lm);
        // S = (second / N - m m^T) N / (N - 1); trace(P S P) = trace(S) - b^T S b (P = I - b b^T
        // is a symmetric projector), with the m m^T part 0 in both: trace(m m^T) = |m|^2 =
        // b^T m m^T b. So trace(P S P) = (trace(Q) - b^T Q b) N / (N - 1), Q = second / N.
        const double qxx = second[0] / dn, qyy = second[1] / dn, qzz = second[2] / dn;
        const double qxy = second[3] / dn, qxz = second[4] / dn, qyz = second[5] / dn;
        const double bqb = b.x * b.x * qxx + b.y * b.y * qyy + b.z * b.z * qzz +
                           2 * (b.x * b.y * qxy + b.x * b.z * qxz + b.y * b.z * qyz);
        const double tr = std::max(0.0, (qxx + qyy + qzz - bqb) * dn / (dn - 1));
        return std::min(pi, std::sqrt(tr / dn) / lm);
    }

    void transfer_part(std::size_t N, Local& L, const std::vector<char>& vis_tr,
                       std::vector<PathState>& paths, std::uint64_t key, PointResult& res) const {
        using namespace detail::rt;
        // Transfer: entries (sample, direction, weight) for direct escapes, then bounces. The
        // escapes are compacted without branches (every direction is written, the end moves
        // by its visibility).
        std::vector<std::array<double, 3>>& w = L.entry_w;
        std::vector<std::uint32_t>& smp = L.entry_sample;
        L.xs.resize(N);
        L.ys.resize(N);
        L.zs.resize(N);
        smp.resize(N);
        {
            const double *dx = L.dx.data(), *dy = L.dy.data(), *dz = L.dz.data();
            double *xs = L.xs.data(), *ys = L.ys.data(), *zs = L.zs.data();
            std::uint32_t* sp = smp.data();
            const char* vis = vis_tr.data();
            std::size_t m = 0;
            for (std::size_t j = 0; j < N; ++j) {
                xs[m] = dx[j];
                ys[m] = dy[j];
                zs[m] = dz[j];
                sp[m] = std::uint32_t(j);
                m += std::size_t(vis[j] != 0);
            }
            L.xs.resize(m);
            L.ys.resize(m);
            L.zs.resize(m);
            smp.resize(m);
        }
        if (paths.empty()) {
            // Direct escapes only: every weight is 1, one entry per sample, in sample order.
            accumulate_sh(L, smp.size(), w, true, smp, N, 1.0, false, res.transfer,
                          &res.transfer_stderr);
            res.transfer_rgb = false;
            return;
        }
        w.assign(smp.size(), {1, 1, 1});
        continue_paths(
            paths, N, hash(key, 0x7472ull), false, L,
            [&](std::uint32_t sample, const V3& d, const RGB& T, const V3&, double tmax) {
                if (tmax < std::numeric_limits<double>::infinity()) return;
                push_dir(L, d);
                w.push_back({T[0], T[1], T[2]});
                smp.push_back(sample);
            },
            [](std::uint32_t, const RGB&) {});
        // Entries must be grouped by sample for the error: sort by sample (stable).
        sort_entries(L, w, smp);
        bool rgb = false;
        for (const auto& x : w) rgb = rgb || x[0] != x[1] || x[1] != x[2];
        accumulate_sh(L, smp.size(), w, false, smp, N, 1.0, rgb, res.transfer,
                      &res.transfer_stderr);
        res.transfer_rgb = rgb;
    }

    void sort_entries(Local& L, std::vector<std::array<double, 3>>& w,
                      std::vector<std::uint32_t>& smp) const {
        if (std::is_sorted(smp.begin(), smp.end())) return;
        std::vector<std::size_t> idx(smp.size());
        std::iota(idx.begin(), idx.end(), std::size_t(0));
        std::stable_sort(idx.begin(), idx.end(),
                         [&](std::size_t a, std::size_t b) { return smp[a] < smp[b]; });
        auto perm = [&](auto& v) {
            auto c = v;
            for (std::size_t i = 0; i < idx.size(); ++i) v[i] = c[idx[i]];
        };
        perm(w);
        perm(smp);
        perm(L.xs);
        perm(L.ys);
        perm(L.zs);
    }

    /// Shadow rays toward directional lights from o; returns (light, visible) pairs.
    std::vector<std::pair<const Light*, bool>> directional_visibility(const detail::rt::V3& o,
                                                                      const detail::rt::V3* n,
                                                                      Local& L) const {
        using namespace detail::rt;
        std::vector<std::pair<const Light*, bool>> out;
        std::vector<RTCRay> rays;
        for (const Light& l : lights_) {
            if (l.type != Light::Type::directional) continue;
            if (n && !(dot(*n, l.direction) > 0)) continue;
            RTCRay r;
            Scene::set_ray(r, o, l.direction);
            rays.push_back(r);
            out.push_back({&l, true});
        }
        if (rays.empty()) return out;
        if (!dropped_.count("shadow")) {
            Timer t{L, shadow};
            scene_.occluded(rays.data(), rays.size());
            L.rays[shadow] += rays.size();
        }
        for (std::size_t i = 0; i < rays.size(); ++i) out[i].second = !Scene::is_occluded(rays[i]);
        return out;
    }

    /// Incoming radiance samples L_j along traced rays (sky, lights, bounces with NEE).
    void radiance_samples(const detail::rt::V3& o, const std::vector<detail::rt::V3>& dirs,
                          std::uint64_t key, std::size_t pass, bool run, std::vector<RGB>& Ls,
                          std::size_t* back, std::vector<char>* vis, Local& L) const {
        using namespace detail::rt;
        const std::size_t N = dirs.size();
        Ls.assign(N, RGB{0, 0, 0});
        std::vector<PathState> paths;
        {
            Timer t{L, pass};
            L.rayhit.resize(N);
            for (std::size_t j = 0; j < N; ++j) Scene::set_ray(L.rayhit[j], o, dirs[j]);
            if (run) {
                scene_.intersect(L.rayhit.data(), N);
                L.rays[pass] += N;
            }
            for (std::size_t j = 0; j < N; ++j) {
                const RTCRayHit& r = L.rayhit[j];
                const bool esc = r.hit.geomID == RTC_INVALID_GEOMETRY_ID;
                if (vis) (*vis)[j] = esc;
                Ls[j] = sky(o, dirs[j],
                            esc ? std::numeric_limits<double>::infinity() : double(r.ray.tfar));
                if (esc) continue;
                const Hit h = scene_.hit(r);
                if (back && h.back_face) ++*back;
                if (bounces_ > 0) paths.push_back({std::uint32_t(j), RGB{1, 1, 1}, h});
            }
        }
        auto gather = [&](std::uint32_t s, const RGB& c) {
            for (std::size_t k = 0; k < 3; ++k) Ls[s][k] += c[k];
        };
        continue_paths(
            paths, N, hash(key, 0x6972ull), true, L,
            [&](std::uint32_t s, const V3& d, const RGB& T, const V3& org, double tmax) {
                const RGB c = sky(org, d, tmax);
                for (std::size_t k = 0; k < 3; ++k) Ls[s][k] += T[k] * c[k];
            },
            gather);
    }

    void hemisphere_pass(const BakePoint& bp, const detail::rt::V3& n, const Frame<double>& f,
                         std::uint64_t key, double cu, double cv, PointResult& res,
                         Local& L) const {
        using namespace detail::rt;
        const std::size_t N = std::size_t(settings_.rays);
        const bool run = !dropped_.count("hemisphere");
        const V3 o = bp.p + n * scene_.epsilon();
        std::vector<V3> dirs(N), local(N);
        qmc_.directions(Warp::uniform_hemisphere, f, cu, cv, dirs.data());
        for (std::size_t j = 0; j < N; ++j) local[j] = f.to_local(dirs[j]);
        std::vector<char> vis(N, 1);
        std::vector<RGB> Ls;
        if (wants(Quantity::irradiance)) {
            radiance_samples(o, dirs, hash(key, 3), hemisphere, run, Ls, nullptr, &vis, L);
        } else if (run) {
            Timer t{L, hemisphere};
            L.ray.resize(N);
            for (std::size_t j = 0; j < N; ++j) Scene::set_ray(L.ray[j], o, dirs[j]);
            scene_.occluded(L.ray.data(), N);
            L.rays[hemisphere] += N;
            for (std::size_t j = 0; j < N; ++j) vis[j] = !Scene::is_occluded(L.ray[j]);
        }
        Timer t{L, hemisphere};
        if (wants(Quantity::visibility)) {
            clear_dirs(L);
            std::vector<std::array<double, 3>> w;
            std::vector<std::uint32_t> smp;
            for (std::size_t j = 0; j < N; ++j)
                if (vis[j]) {
                    push_dir(L, dirs[j]);
                    smp.push_back(std::uint32_t(j));
                }
            std::array<std::vector<double>, 3> v3;
            accumulate_sh(L, smp.size(), w, true, smp, N, constants::two_pi, false, v3,
                          &res.visibility_stderr);
            res.visibility = v3[0];
        }
        if (wants(Quantity::irradiance)) {
            const std::size_t n8 = std::size_t(irr_bands * irr_bands);
            std::array<std::vector<double>, 3> Llm;
            for (auto& v : Llm) v.assign(n8, 0.0);
            // The basis values of the lit samples are kept (columns of L.irr_y) for the error.
            const std::size_t nk = std::size_t(irr_map_.rows());
            L.irr_y.resize(n8);
            L.irr_l.resize(3 * N);
            L.irr_g.resize(nk * N);
            double* yy = L.irr_y.data();
            std::size_t m = 0;
            for (std::size_t j = 0; j < N; ++j) {
                if (Ls[j][0] == 0 && Ls[j][1] == 0 && Ls[j][2] == 0) continue;
                sh::eval_unit(irr_bands, local[j].x, local[j].y, local[j].z, yy);
                for (std::size_t c = 0; c < 3; ++c) {
                    L.irr_l[c * N + m] = Ls[j][c];
                    for (std::size_t k = 0; k < n8; ++k) Llm[c][k] += Ls[j][c] * yy[k];
                }
                for (std::size_t k = 0; k < nk; ++k)
                    L.irr_g[k * N + m] = dot_lanes(&irr_map_rows_[k * n8], yy);
                ++m;
            }
            for (auto& v : Llm)
                for (double& x : v) x *= constants::two_pi / double(N);
            std::vector<std::pair<V3, RGB>> dl;
            for (const auto& [light, visible] : directional_visibility(o, &n, L))
                if (visible) dl.push_back({f.to_local(light->direction), light->color});
            finish_irradiance(Llm, dl, res);
            irradiance_error(N, m, Llm, L, res.irradiance_stderr);
        }
    }

    /// sum_i a[i] b[i] over the 64 coefficients of irr_bands, in 8 lanes (vectorises).
    static double dot_lanes(const double* a, const double* b) noexcept {
        constexpr std::size_t lanes = 8, n = std::size_t(irr_bands * irr_bands);
        double acc[lanes] = {};
        for (std::size_t i = 0; i < n; i += lanes)
            for (std::size_t q = 0; q < lanes; ++q) acc[q] += a[i + q] * b[i + q];
        return ((acc[0] + acc[1]) + (acc[2] + acc[3])) + ((acc[4] + acc[5]) + (acc[6] + acc[7]));
    }

    /// irradiance_stderr (header comment) from the m lit samples of N: g_jk = (M y(w_j))_k
    /// (L.irr_g), s_j,kc = 2pi L_jc g_jk (L.irr_l), about the mean M L_lm (two-pass variance
    /// over all N samples, the unlit ones s = 0), in 8 independent lanes so that the sums
    /// vectorise. Cost with the g_j: 64 coeffs + 3 coeffs multiply-adds per lit sample.
    void irradiance_error(std::size_t N, std::size_t m,
                          const std::array<std::vector<double>, 3>& Llm, Local& L,
                          std::vector<double>& out) const {
        const Eigen::Index K = irr_map_.rows();
        out.assign(std::size_t(K), 0.0);
        if (N < 2 || m == 0) return;
        const double a = constants::two_pi, dn = double(N);
        constexpr std::size_t lanes = 8;
        for (std::size_t c = 0; c < 3; ++c) {
            const Eigen::VectorXd mean = irr_map_ * Eigen::Map<const Eigen::VectorXd>(
                                                        Llm[c].data(), Eigen::Index(Llm[c].size()));
            const double* l = L.irr_l.data() + c * N;
            for (Eigen::Index k = 0; k < K; ++k) {
                const double* g = L.irr_g.data() + std::size_t(k) * N;
                const double mu = mean(k);
                double acc[lanes] = {};
                std::size_t j = 0;
                for (; j + lanes <= m; j += lanes)
                    for (std::size_t q = 0; q < lanes; ++q) {
                        const double d = a * l[j + q] * g[j + q] - mu;
                        acc[q] += d * d;
                    }
                for (; j < m; ++j) {
                    const double d = a * l[j] * g[j] - mu;
                    acc[j % lanes] += d * d;
                }
                double ss = double(N - m) * mu * mu;
                for (double x : acc) ss += x;
                double& o = out[std::size_t(k)];
                o = std::max(o, std::sqrt(ss / (dn - 1) / dn));
            }
        }
    }

    /// transfer_matrix (header comment): M = I + 2pi/N sum over occluded hemisphere samples j
    /// of y3(w_j) (T y(w_esc) - y(w_j))^T, the sum over each escape of its bounce path.
    void matrix_pass(const BakePoint& bp, const detail::rt::V3& n, const Frame<double>& f,
                     std::uint64_t key, double cu, double cv, PointResult& res, Local& L) const {
        using namespace detail::rt;
        const std::size_t N = std::size_t(settings_.rays), nl = nsh();
        const bool run = !dropped_.count("hemisphere");
        const V3 o = bp.p + n * scene_.epsilon();
        std::vector<V3> dirs(N);
        qmc_.directions(Warp::uniform_hemisphere, f, cu, cv, dirs.data());
        std::vector<PathState> paths;
        std::vector<char> occluded(N, 0);
        if (run) {
            Timer t{L, hemisphere};
            L.rayhit.resize(N);
            for (std::size_t j = 0; j < N; ++j) Scene::set_ray(L.rayhit[j], o, dirs[j]);
            scene_.intersect(L.rayhit.data(), N);
            L.rays[hemisphere] += N;
            for (std::size_t j = 0; j < N; ++j) {
                const RTCRayHit& r = L.rayhit[j];
                if (r.hit.geomID == RTC_INVALID_GEOMETRY_ID) continue;
                occluded[j] = 1;
                if (bounces_ > 0) paths.push_back({std::uint32_t(j), RGB{1, 1, 1}, scene_.hit(r)});
            }
        }
        std::array<std::vector<double>, 3>& M = res.transfer_matrix;
        for (auto& m : M) m.assign(9 * nl, 0.0);
        // r_j per occluded sample and channel (slot[j]: its row in R, 3 nl doubles) for the
        // error; M itself is summed in the same order as ever.
        std::vector<std::uint32_t>& slot = L.mat_slot;
        std::vector<std::uint32_t>& slot_sample = L.mat_samples;
        slot.assign(N, std::uint32_t(-1));
        slot_sample.clear();
        for (std::size_t j = 0; j < N; ++j)
            if (occluded[j]) {
                slot[j] = std::uint32_t(slot_sample.size());
                slot_sample.push_back(std::uint32_t(j));
            }
        std::vector<double>& R = L.mat_r;
        R.assign(slot_sample.size() * 3 * nl, 0.0);
        // y3(w_j) once per occluded sample (every escape of its paths and the error use it).
        std::vector<double>& Y = L.mat_y;
        Y.resize(slot_sample.size() * 9);
        for (std::size_t q = 0; q < slot_sample.size(); ++q) {
            const V3& ws = dirs[slot_sample[q]];
            sh::eval_unit(3, ws.x, ws.y, ws.z, Y.data() + 9 * q);
        }
        std::vector<double> yj(nl);
        const double scale = constants::two_pi / double(N);
        auto add = [&](std::size_t sample, const V3& d, const RGB& w) {
            const double* yi = Y.data() + std::size_t(slot[sample]) * 9;
            sh::eval_unit(settings_.bands, d.x, d.y, d.z, yj.data());
            double* r = R.data() + std::size_t(slot[sample]) * 3 * nl;
            for (std::size_t c = 0; c < 3; ++c) {
                if (w[c] == 0) continue;
                for (std::size_t i = 0; i < 9; ++i) {
                    const double a = scale * w[c] * yi[i];
                    double* row = M[c].data() + i * nl;
                    for (std::size_t k = 0; k < nl; ++k) row[k] += a * yj[k];
                }
                for (std::size_t k = 0; k < nl; ++k) r[c * nl + k] += w[c] * yj[k];
            }
        };
        {
            Timer t{L, hemisphere};
            for (std::size_t j = 0; j < N; ++j)
                if (occluded[j]) add(j, dirs[j], RGB{-1, -1, -1});
        }
        continue_paths(
            paths, N, hash(key, 0x6d74ull), false, L,
            [&](std::uint32_t sample, const V3& d, const RGB& T, const V3&, double tmax) {
                if (tmax < std::numeric_limits<double>::infinity()) return;
                add(sample, d, T);
            },
            [](std::uint32_t, const RGB&) {});
        Timer t{L, hemisphere};
        matrix_error(N, nl, slot_sample.size(), Y, R, M, L.mat_ss, res.transfer_matrix_stderr);
        for (auto& m : M)
            for (std::size_t i = 0; i < 9 && i < nl; ++i) m[i * nl + i] += 1;
    }

    /// transfer_matrix_stderr (header comment) from the y3(w_j) and r_j of the `occ` occluded
    /// samples (Y: 9 per sample; R: 3 nl per sample, channel-major) and M - I (the mean of s_j,
    /// before the identity is added).
    static void matrix_error(std::size_t N, std::size_t nl, std::size_t occ,
                             const std::vector<double>& Y, const std::vector<double>& R,
                             const std::array<std::vector<double>, 3>& M, std::vector<double>& ss,
                             std::vector<double>& out) {
        out.assign(9 * nl, 0.0);
        if (N < 2 || occ == 0) return;
        // Equal channels (no bounces, or grey albedos): one channel's sums serve all three.
        bool same = true;
        for (std::size_t q = 0; q < occ && same; ++q) {
            const double* r = R.data() + q * 3 * nl;
            for (std::size_t k = 0; k < nl && same; ++k)
                same = r[k] == r[nl + k] && r[k] == r[2 * nl + k];
        }
        const std::size_t nc = same ? 1 : 3;
        const double dn = double(N), a = constants::two_pi;
        ss.assign(27 * nl, 0.0);  // channel c, element (i, k): sum_j s_j,ik^2
        for (std::size_t q = 0; q < occ; ++q) {
            const double* yi = Y.data() + 9 * q;
            const double* r = R.data() + q * 3 * nl;
            for (std::size_t c = 0; c < nc; ++c)
                for (std::size_t i = 0; i < 9; ++i) {
                    double* o = ss.data() + (c * 9 + i) * nl;
                    const double ay = a * yi[i];
                    for (std::size_t k = 0; k < nl; ++k) {
                        const double v = ay * r[c * nl + k];
                        o[k] += v * v;
                    }
                }
        }
        for (std::size_t c = 0; c < nc; ++c)
            for (std::size_t e = 0; e < 9 * nl; ++e) {
                const double mean = M[c][e];
                const double var =
                    std::max(0.0, ss[c * 9 * nl + e] / dn - mean * mean) * dn / (dn - 1);
                out[e] = std::max(out[e], std::sqrt(var / dn));
            }
    }

    void sphere_pass(const BakePoint& bp, const detail::rt::V3& n, std::uint64_t key, double cu,
                     double cv, PointResult& res, Local& L) const {
        using namespace detail::rt;
        const std::size_t N = std::size_t(settings_.rays);
        const bool run = !dropped_.count("sphere");
        const V3 o = bp.p + n * scene_.epsilon();
        std::vector<V3> dirs(N);
        qmc_.directions(Warp::uniform_sphere, Frame<double>(), cu, cv, dirs.data());
        std::vector<RGB> Ls;
        std::size_t back = 0;
        radiance_samples(o, dirs, hash(key, 5), sphere, run, Ls, &back, nullptr, L);
        Timer t{L, sphere};
        res.inside = 2 * back > N;
        clear_dirs(L);
        std::vector<std::array<double, 3>> w;
        std::vector<std::uint32_t> smp;
        for (std::size_t j = 0; j < N; ++j)
            if (Ls[j][0] != 0 || Ls[j][1] != 0 || Ls[j][2] != 0) {
                push_dir(L, dirs[j]);
                w.push_back(Ls[j]);
                smp.push_back(std::uint32_t(j));
            }
        accumulate_sh(L, smp.size(), w, false, smp, N, constants::four_pi, true, res.radiance,
                      &res.radiance_stderr);
        std::vector<double> y(nsh());
        for (const auto& [light, visible] : directional_visibility(o, nullptr, L)) {
            if (!visible) continue;
            sh::eval_unit(settings_.bands, light->direction.x, light->direction.y,
                          light->direction.z, y.data());
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < nsh(); ++k)
                    res.radiance[c][k] += light->color[c] * y[k];
        }
    }

    BakeSettings settings_;
    double build_seconds_ = 0;
    std::unique_ptr<Scene> owned_;  // null when the Scene is borrowed
    const Scene& scene_;
    Environment env_;
    std::vector<Light> lights_;
    std::vector<Pass> plan_;
    std::unique_ptr<Stat[]> stats_;
    std::mutex mutex_;
    std::set<std::string> dropped_;
    double rho_max_ = 0;
    int bounces_ = 0;
    DirectionalRule irr_rule_, hemi_rule_, sphere_rule_;
    IrradianceStorage irr_;
    Eigen::MatrixXd irr_projector_, irr_map_, irr_gram_;
    std::vector<double> irr_map_rows_;  // irr_map_, row-major
    detail::rt::QmcTable qmc_;
};

}  // namespace sphbasis::render
