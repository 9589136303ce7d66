// sphbasis render tier: fitting tangent-space irradiance in any basis of the library, the
// `irradiance` quantity of a bake (the irradiance-normal-mapping lightmap).
//
// Ishmukhametov, "Irradiance Normal Mapping" (thesis): a texel stores the irradiance over the
// hemisphere of tangent-space normals n' (z >= 0, z the interpolated surface normal) in a small
// basis (H-basis, SH, HSH, ...), and the shader evaluates it with the normal-mapped normal.
// Given incoming radiance samples (w_k, L_k, weight_k) over the whole sphere in tangent space,
//   E(n') = sum_k L_k max(n' . w_k, 0) weight_k,          (1)
// a Monte Carlo estimate of the irradiance int L(w) max(n' . w, 0) dw in physical units (a
// constant sky of radiance 1 gives pi; for radiance L = sum c_lm y_lm, E = sum pi a_l c_lm y_lm
// with the normalised clamped-cosine factors a_l of core/clamped_cosine.hpp: Ramamoorthi and
// Hanrahan, "An Efficient Representation for Irradiance Environment Maps", SIGGRAPH 2001;
// ops/imse.hpp's E is this one divided by pi). Directions below the tangent plane count: a
// tilted normal n' sees them. Whether the surface itself blocks them is the caller's choice
// (give them zero radiance).
//
// The fit is the one of the IMSE benchmark (ops/imse.hpp): least squares over the hemisphere,
// discretised by a fixed rule of fit directions d_i with weights v_i,
//   c = argmin sum_i v_i (sum_j c_j B_j(d_i) - E(d_i))^2 = P e,   P = G^-1 Phi^T V,   (2)
// with Phi(i, j) = B_j(d_i) and G = Phi^T V Phi (BasicLeastSquares, ops/projection.hpp). The
// class precomputes P (coeffs x M) once per (basis, coeffs, rule); a fit is then
//   e_i = sum_k L_k weight_k max(d_i . w_k, 0)   (M multiply-adds per sample and channel)
//   c = P e                                       (coeffs x M per channel).
// The fit rule is hemisphere_rule_sqrt(nu, nphi) (core/quadrature.hpp), the IMSE benchmark's
// kind of rule (its bases carry sqrt(z) factors); its default, 12 x 24 = 288 directions, fits
// every basis of the library up to 25 functions to the accuracy of the continuous least squares
// for smooth E (SH products of degree <= 22 integrated exactly), and for a Monte Carlo E, whose
// clamped cosines have kinks, to well below the Monte Carlo noise of any practical ray count
// (tests/render/test_irradiance_fit.cpp measures both).
//
// Cost per point: count * M * ~10 flops plus 3 * coeffs * M for c = P e. Samples are taken in
// blocks of 4, so each pass over the fit directions loads and stores e_i once for 4 samples and
// the loop vectorises; samples of zero radiance (occluded rays without bounces) cost nothing.
// Measured (g++ 12 -O3 -march=native, one core, CPU time): 256 samples, 288 directions:
// 18 us per point for sh 9 and hbasis 6, 31 us for sh 25. No allocation once the caller's
// scratch vector has grown to 3 M doubles. Building the fit: M * coeffs basis evaluations and a
// coeffs^2 Cholesky (well under a millisecond).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "../basis/registry.hpp"
#include "../config.hpp"
#include "../core/error.hpp"
#include "../core/quadrature.hpp"
#include "../core/sampling.hpp"
#include "../ops/projection.hpp"
#include "../ops/sg_fit.hpp"

namespace sphbasis::render {

/// The fit-direction rule of IrradianceFit: hemisphere_rule_sqrt(nu, nphi).
struct IrradianceFitOptions {
    int nu = 12;    // Gauss-Legendre nodes in sqrt(z)
    int nphi = 24;  // uniform azimuths
};

/// Least-squares fit of tangent-space irradiance (1) in a basis of the library (see the header).
/// Built once per (basis, coeffs, rule), shared read-only by all threads; each thread passes its
/// own scratch vector.
class IrradianceFit {
  public:
    /// `basis`: a name of find_basis() ("sh", "hbasis", "hbasis-mod", "hl2", "hsh",
    /// "makhotkin", "zernike"); `coeffs`: a valid count of it. Throws std::invalid_argument for
    /// an unknown basis, a bad count or a bad rule size, std::runtime_error if the basis is
    /// singular on the rule. Cost: M * coeffs basis evaluations and a coeffs^2 Cholesky.
    IrradianceFit(std::string_view basis, int coeffs, const IrradianceFitOptions& options = {})
        : IrradianceFit(basis, coeffs, hemisphere_rule_sqrt(options.nu, options.nphi)) {}

    /// As above with any rule of fit directions on the upper hemisphere.
    IrradianceFit(std::string_view basis, int coeffs, DirectionalRule rule)
        : info_(&find_basis(basis)), n_(coeffs), rule_(std::move(rule)) {
        const BasisFunctions f = info_->functions(coeffs);
        if (rule_.size() == 0)
            sphbasis::detail::throw_invalid("render::IrradianceFit",
                                            "a rule with fit directions, got an empty one");
        // The Gram solve for every basis: on the rule, an orthonormal basis has G = I up to the
        // rule's error, and the solve makes the fit the exact discrete least squares anyway.
        const BasicLeastSquares<> ls(f, false, rule_);
        const Eigen::MatrixXd p =
            ls.solve(Eigen::MatrixXd(ls.evaluation().transpose() * ls.weights().asDiagonal()));
        const std::size_t m = rule_.size();
        projector_.resize(static_cast<std::size_t>(n_) * m);
        for (int j = 0; j < n_; ++j)
            for (std::size_t i = 0; i < m; ++i)
                projector_[static_cast<std::size_t>(j) * m + i] =
                    p(j, static_cast<Eigen::Index>(i));
    }

    const BasisInfo& info() const noexcept { return *info_; }
    int coeffs() const noexcept { return n_; }
    /// The fit directions and their weights.
    const DirectionalRule& rule() const noexcept { return rule_; }
    std::size_t directions() const noexcept { return rule_.size(); }
    /// P (coeffs x M, row-major): c = P e for e sampled on the rule's directions.
    const std::vector<double>& projector() const noexcept { return projector_; }

    /// Fits (1) for `count` samples: dirs (3 per sample, tangent space; normalised here, zero
    /// or non-finite directions and zero radiance skipped), radiance (3 per sample, RGB, finite),
    /// weights (one per sample) or, when `weights` is null, the same `weight` for every sample
    /// (4 pi / count for uniform sphere samples). Writes coeffs() coefficients to each of r, g,
    /// b. `scratch` is grown to 3 M doubles once and reused. T: float or double. Throws
    /// std::invalid_argument for null buffers (count > 0) or non-finite radiance or weights.
    template <class T>
    void fit_samples(std::size_t count, const T* dirs, const T* radiance, const T* weights,
                     double weight, double* r, double* g, double* b,
                     std::vector<double>& scratch) const {
        static_assert(std::is_floating_point_v<T>,
                      "sphbasis::render::IrradianceFit: samples are float or double.");
        constexpr const char* fn = "render::IrradianceFit::fit_samples";
        sphbasis::detail::check_buffer(fn, "dirs", dirs, count);
        sphbasis::detail::check_buffer(fn, "radiance", radiance, count);
        check_out(fn, r, g, b);
        const std::size_t m = rule_.size();
        if (scratch.size() < 3 * m) scratch.resize(3 * m);
        double* er = scratch.data();
        double* eg = er + m;
        double* eb = eg + m;
        for (std::size_t i = 0; i < 3 * m; ++i) er[i] = 0;
        // Samples are gathered in blocks of 4 so each pass over the fit directions loads and
        // stores e_i once for 4 samples (the loop is then compute bound and vectorises).
        constexpr int block = 4;
        double bw[block][3], bl[block][3];
        int nb = 0;
        for (std::size_t k = 0; k < count; ++k) {
            const double wk = weights != nullptr ? double(weights[k]) : weight;
            const double lr = double(radiance[3 * k]) * wk;
            const double lg = double(radiance[3 * k + 1]) * wk;
            const double lb = double(radiance[3 * k + 2]) * wk;
            if (!std::isfinite(lr) || !std::isfinite(lg) || !std::isfinite(lb))
                sphbasis::detail::throw_invalid(
                    fn, "finite radiance and weights, got a non-finite one at sample " +
                            std::to_string(k));
            if (lr == 0 && lg == 0 && lb == 0) continue;
            const double wx = double(dirs[3 * k]), wy = double(dirs[3 * k + 1]),
                         wz = double(dirs[3 * k + 2]);
            const double len = std::sqrt(wx * wx + wy * wy + wz * wz);
            if (!(len > 0) || !std::isfinite(len)) continue;
            bw[nb][0] = wx / len, bw[nb][1] = wy / len, bw[nb][2] = wz / len;
            bl[nb][0] = lr, bl[nb][1] = lg, bl[nb][2] = lb;
            if (++nb == block) {
                accumulate_block(bw, bl, er, eg, eb);
                nb = 0;
            }
        }
        for (int j = nb; j < block; ++j)  // pad the last block with zero radiance
            bw[j][0] = bw[j][1] = bw[j][2] = bl[j][0] = bl[j][1] = bl[j][2] = 0;
        if (nb > 0) accumulate_block(bw, bl, er, eg, eb);
        project(er, r);
        project(eg, g);
        project(eb, b);
    }

    /// fit_samples() with one weight for every sample and a scratch vector of its own (one
    /// allocation per call).
    template <class T>
    void fit_samples(std::size_t count, const T* dirs, const T* radiance, double weight, double* r,
                     double* g, double* b) const {
        std::vector<double> scratch;
        fit_samples(count, dirs, radiance, static_cast<const T*>(nullptr), weight, r, g, b,
                    scratch);
    }

    /// Fits an irradiance known as a function of the normal (analytic unoccluded lights):
    /// e(x, y, z) for a unit tangent-space normal with z >= 0 returns either one value (grey:
    /// r = g = b) or three (std::array<double, 3>: R, G, B). Cost: M calls of e and
    /// 3 * coeffs * M multiply-adds.
    template <class F>
    void fit_function(F&& e, double* r, double* g, double* b) const {
        constexpr const char* fn = "render::IrradianceFit::fit_function";
        check_out(fn, r, g, b);
        const std::size_t m = rule_.size();
        std::vector<double> s(3 * m);
        for (std::size_t i = 0; i < m; ++i) {
            const auto v = e(rule_.x[i], rule_.y[i], rule_.z[i]);
            if constexpr (std::is_arithmetic_v<std::decay_t<decltype(v)>>) {
                s[i] = s[m + i] = s[2 * m + i] = double(v);
            } else {
                s[i] = double(v[0]);
                s[m + i] = double(v[1]);
                s[2 * m + i] = double(v[2]);
            }
        }
        project(s.data(), r);
        project(s.data() + m, g);
        project(s.data() + 2 * m, b);
    }

    /// The fitted irradiance sum_j c_j B_j(n) at a tangent-space normal n (normalised by the
    /// basis; c: coeffs() values).
    double evaluate(const double* c, double x, double y, double z) const {
        sphbasis::detail::check_buffer("render::IrradianceFit::evaluate", "coefficients", c,
                                       std::size_t(n_));
        std::array<double, 64> vals{};
        std::vector<double> big;
        double* out = vals.data();
        if (n_ > 64) {
            big.resize(static_cast<std::size_t>(n_));
            out = big.data();
        }
        info_->eval_d(n_, x, y, z, out);
        double s = 0;
        for (int j = 0; j < n_; ++j) s += c[j] * out[j];
        return s;
    }

  private:
    static void check_out(const char* fn, double* r, double* g, double* b) {
        sphbasis::detail::check_buffer(fn, "r", r, 1);
        sphbasis::detail::check_buffer(fn, "g", g, 1);
        sphbasis::detail::check_buffer(fn, "b", b, 1);
    }
    void accumulate_block(const double (&w)[4][3], const double (&l)[4][3],
                          double* SPHBASIS_RESTRICT er, double* SPHBASIS_RESTRICT eg,
                          double* SPHBASIS_RESTRICT eb) const noexcept {
        const double* SPHBASIS_RESTRICT dx = rule_.x.data();
        const double* SPHBASIS_RESTRICT dy = rule_.y.data();
        const double* SPHBASIS_RESTRICT dz = rule_.z.data();
        const std::size_t m = rule_.size();
        const double w0x = w[0][0], w0y = w[0][1], w0z = w[0][2];
        const double w1x = w[1][0], w1y = w[1][1], w1z = w[1][2];
        const double w2x = w[2][0], w2y = w[2][1], w2z = w[2][2];
        const double w3x = w[3][0], w3y = w[3][1], w3z = w[3][2];
        for (std::size_t i = 0; i < m; ++i) {
            const double x = dx[i], y = dy[i], z = dz[i];
            double c0 = x * w0x + y * w0y + z * w0z;
            double c1 = x * w1x + y * w1y + z * w1z;
            double c2 = x * w2x + y * w2y + z * w2z;
            double c3 = x * w3x + y * w3y + z * w3z;
            c0 = c0 > 0 ? c0 : 0;
            c1 = c1 > 0 ? c1 : 0;
            c2 = c2 > 0 ? c2 : 0;
            c3 = c3 > 0 ? c3 : 0;
            er[i] += c0 * l[0][0] + c1 * l[1][0] + c2 * l[2][0] + c3 * l[3][0];
            eg[i] += c0 * l[0][1] + c1 * l[1][1] + c2 * l[2][1] + c3 * l[3][1];
            eb[i] += c0 * l[0][2] + c1 * l[1][2] + c2 * l[2][2] + c3 * l[3][2];
        }
    }
    void project(const double* e, double* out) const {
        const std::size_t m = rule_.size();
        for (int j = 0; j < n_; ++j) {
            const double* pj = projector_.data() + static_cast<std::size_t>(j) * m;
            double s = 0;
            for (std::size_t i = 0; i < m; ++i) s += pj[i] * e[i];
            out[j] = s;
        }
    }

    const BasisInfo* info_;
    int n_;
    DirectionalRule rule_;
    std::vector<double> projector_;
};

/// What the bake's `irradiance` stores per channel (render::BakeSettings::basis and coeffs):
///   linear       the coefficients of a basis of find_basis() ("sh", "hbasis", ..., "sg",
///                "ambient-cube", "ambient-dice"), the least squares of IrradianceFit;
///   sg_nnls      "sg-nnls": BakingLab's lobes (basis "sg", 5, 6, 9 or 12), the same least
///                squares with non-negative amplitudes (sg::nnls_gram on the fit rule's Gram
///                matrix G = Phi^T V Phi and h = G c, c the least-squares amplitudes);
///   sg_running   "sg-running": BakingLab's lobes, Roughton's running average (sg::RunningAverage)
///                over the irradiance at sg_running_directions() in their order. With the
///                directions fixed it is linear in the values, so the bake applies it as a
///                projector like the least squares (sg_running_projector());
///   fitted       a fitted representation of find_fitted_basis() ("zh3" 5 values, "zh3-hallucinate"
///                4, "sh-l1-nonlinear" 4), its `fit` of the irradiance's first SH coefficients
///                over the sphere of normals (E_lm = pi a_l L_lm, exact for a radiance known to
///                8 bands, and for directional lights).
/// Every kind evaluates to the irradiance at a tangent-space normal (eval()).
struct IrradianceStorage {
    enum class Kind { linear, sg_nnls, sg_running, fitted };
    Kind kind = Kind::linear;
    std::string name;                         // as given ("sg-nnls", "zh3", ...)
    const BasisInfo* basis = nullptr;         // linear, sg_nnls, sg_running: the basis
    const FittedBasisInfo* fitted = nullptr;  // fitted
    int coeffs = 0;                           // values stored per channel
    /// Values per channel the bake's linear stage estimates before finish() (and pools over
    /// adaptive batches): coeffs, or the fitted representation's SH coefficients.
    int stage() const noexcept { return kind == Kind::fitted ? fitted->sh_coeffs : coeffs; }
    /// The stored irradiance at a normal (x, y, z) (normalised by the basis), c: coeffs values.
    double eval(const double* c, double x, double y, double z) const {
        if (fitted) return fitted->eval_d(c, x, y, z);
        std::array<double, 64> small;
        std::vector<double> big;
        double* v = small.data();
        if (coeffs > 64) {
            big.resize(std::size_t(coeffs));
            v = big.data();
        }
        basis->eval_d(coeffs, x, y, z, v);
        double s = 0;
        for (int j = 0; j < coeffs; ++j) s += c[j] * v[j];
        return s;
    }
};

/// The storage called `name` with `coeffs` values (IrradianceStorage). Throws
/// std::invalid_argument naming `fn` for an unknown name or a count the storage does not take.
inline IrradianceStorage irradiance_storage(std::string_view name, int coeffs,
                                            const char* fn = "render::irradiance_storage") {
    IrradianceStorage r;
    r.name = std::string(name);
    r.coeffs = coeffs;
    if (const FittedBasisInfo* f = find_fitted_basis(name)) {
        r.kind = IrradianceStorage::Kind::fitted;
        r.fitted = f;
        if (coeffs != f->stored)
            sphbasis::detail::throw_invalid(fn, std::string("coeffs: ") +
                                                    std::to_string(f->stored) + " values for '" +
                                                    f->name + "', got " + std::to_string(coeffs));
        return r;
    }
    std::string_view b = name;
    if (name == "sg-nnls" || name == "sg-running") {
        r.kind = name == "sg-nnls" ? IrradianceStorage::Kind::sg_nnls
                                   : IrradianceStorage::Kind::sg_running;
        b = "sg";
    }
    try {
        r.basis = &find_basis(b);
    } catch (const std::invalid_argument& e) {
        sphbasis::detail::throw_invalid(
            fn, std::string("a basis of find_basis(), sg-nnls, sg-running or a fitted "
                            "representation (zh3, zh3-hallucinate, sh-l1-nonlinear); ") +
                    e.what());
    }
    if (!r.basis->valid_count(coeffs))
        sphbasis::detail::throw_invalid(fn, std::string("coeffs: ") + r.basis->count_rule() +
                                                " functions for basis '" + r.basis->name +
                                                "', got " + std::to_string(coeffs));
    return r;
}

/// The sample directions of the "sg-running" irradiance: `count` points of the R2 sequence
/// (core/sampling.hpp) mapped uniformly onto the tangent hemisphere z >= 0, in sequence order
/// (low discrepancy at every prefix, so the running average sees the whole hemisphere early),
/// each with the weight 2 pi / count.
inline DirectionalRule sg_running_directions(int count = 1024) {
    sphbasis::detail::check_range("render::sg_running_directions", "count", count, 1, 1 << 20);
    DirectionalRule r;
    for (int i = 0; i < count; ++i) {
        double u, v;
        r2_sequence(std::uint64_t(i), u, v);
        const vec3<double> d = square_to_uniform_hemisphere(u, v);
        r.x.push_back(d.x);
        r.y.push_back(d.y);
        r.z.push_back(d.z);
        r.w.push_back(constants::two_pi / count);
    }
    return r;
}

/// R (lobes x directions, row-major): the amplitudes of sg::RunningAverage (hemisphere lobe set
/// of `lobes` lobes, not clamped) fed the values f_i at rule's directions in order are R f. The
/// running average is linear in the values once the directions are fixed (its normalisation
/// mean(G_k^2) depends on the directions only), so column i is its result for the one-hot
/// values e_i; computed 64 columns per pass. Cost: directions^2 lobes / 64 * ~10 flops plus
/// directions^2 / 64 lobes exp (1024 directions, 9 lobes: ~10 ms).
inline std::vector<double> sg_running_projector(int lobes, const DirectionalRule& rule) {
    const std::size_t m = rule.size(), k = std::size_t(lobes);
    const std::vector<sg::Lobe<double>> set = sg::bakinglab_lobes(lobes);
    std::vector<double> p(k * m, 0.0);
    constexpr std::size_t chunk = 64;
    std::vector<double> v(chunk);
    for (std::size_t c0 = 0; c0 < m; c0 += chunk) {
        const std::size_t nc = std::min(chunk, m - c0);
        sg::RunningAverage ra(set, int(nc), sg::Distribution::hemisphere);
        for (std::size_t i = 0; i < m; ++i) {
            std::fill(v.begin(), v.end(), 0.0);
            if (i >= c0 && i < c0 + nc) v[i - c0] = 1;
            ra.add(rule.x[i], rule.y[i], rule.z[i], v.data());
        }
        const Eigen::MatrixXd& a = ra.amplitudes();
        for (std::size_t j = 0; j < k; ++j)
            for (std::size_t c = 0; c < nc; ++c)
                p[j * m + c0 + c] = a(Eigen::Index(j), Eigen::Index(c));
    }
    return p;
}

}  // namespace sphbasis::render
