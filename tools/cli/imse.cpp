// sphbasis CLI: `sphbasis imse [--protocol paper|hdri|all] [--signals N] [--seed S]
//                              [--json PATH] [--csv PATH] [--md PATH]`
//
// The IMSE basis comparison (Ishmukhametov, "Irradiance Normal Mapping" (thesis), section 3.1,
// eq. 3.1): for every row (basis and
// size) the integrated mean square error of the least-squares fit of an irradiance signal over
// the upper hemisphere, averaged over N signals, beside what the basis costs to evaluate, to
// project and to store. The library side is sphbasis/ops/imse.hpp; this file runs the two
// protocols, measures the timings and writes the table.
//
// Protocol paper (default): radiance = 9 SH coefficients i.i.d. uniform on [-1, 1]
//   (imse::random_radiance(seed)), irradiance by the factors 1, 2/3, 1/4; each signal sampled on
//   imse::paper_rule(), fitted (projection or Gram solve), its squared residual integrated by
//   the same rule; mean and standard error over the signals; "expected" is the closed form
//   tr(Q)/3; "quad_err" is |tr(Q) - tr(Q_fine)|/3 between paper_rule() and paper_check_rule().
// Protocol hdri: radiance = luminance (Rec. 709: 0.2126 R + 0.7152 G + 0.0722 B, each channel
//   clamped to >= 0 on load) of the eight CC0 maps in data/envmaps, each projected exactly
//   (piecewise-constant texels) to SH of kMapBands bands; irradiance = the clamped-cosine
//   convolution truncated to kSignalBands bands; signals = the maps at uniformly random
//   orientations (Haar: R = Rz(a) Ry(b) Rz(c), cos b uniform), N / 8 per map; the score is the
//   relative IMSE, IMSE / mean over the hemisphere of E^2, computed as
//   (energy - fitted energy) by imse::ShFits and imse::HemisphereShGram. "trunc_bound" is a
//   rigorous bound (mean over the signals) on the change of the relative IMSE from the
//   irradiance left out above kSignalBands bands; "trunc_half" is the measured change from
//   truncating at kSignalBands / 2 instead (the tail falls like L^-3, so the error at
//   kSignalBands is ~8x smaller than that); "quad_err" compares ShFits on two rules.
// SG pipeline rows (paper protocol only; imse::sg_pipeline_imse): sg-ls, sg-nnls, sg-ra, sg-ra-nn
//   with 9 and 12 lobes score BakingLab's SG lightmap pipeline (Pettineo, "SG Series" part 5,
//   2016): radiance sampled at 625 stratified hemisphere directions, the amplitudes of BakingLab's
//   lobe set by one solver, the irradiance by Hill's fitted approximation. The registry's "sg"
//   rows instead fit the irradiance itself in the span of the same lobes.
// Fitted rows (sh-l1-nonlinear, zh3-hallucinate, zh3; imse::fitted_rows()), after the linear
//   ones in both protocols: each signal's representation is fitted from its own low-order SH over
//   the sphere and scored over the hemisphere by imse::fitted_imse() (no closed form; quad_err
//   compares twice the Funk-Hecke nodes; their timings: eval_f / eval_batch_f of the stored
//   values, project_ns = the SH projection its fit reads plus the fit).
// Timings (same run, float, this machine): eval_ns = one registry eval_f call at a time over
//   4096 hemisphere normals; eval_batch_ns = eval_batch_f over 1M normals in chunks of 4096
//   (output kept in cache); project_ns = one least-squares fit from the signal's values at the
//   1024 points of paper_rule(), the basis evaluated there (eval_batch_f) and the weighted
//   sums and Gram solve done per signal, as a baker with per-texel sample directions does.
//   Each is the fastest of several repetitions.
// The long loops run on TBB's threads (support/parallel.hpp); every number but the timings is
// the same whatever the thread count.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/core/sampling.hpp>
#include <sphbasis/ops/imse.hpp>
#include <sphbasis/ops/sg_fit.hpp>
#include <sphbasis/ops/sh_convolution.hpp>
#include <sphbasis/ops/sh_latlong.hpp>
#include <sphbasis/ops/sh_rotation.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/exr.hpp"
#include "../support/json.hpp"
#include "../support/output_file.hpp"
#include "../support/parallel.hpp"
#include "../support/progress.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

constexpr int kMapBands = 256;    // radiance bands projected per map (for the tail bound)
constexpr int kSignalBands = 64;  // irradiance bands of the hdri signals (degree 63)
constexpr int kBatch = 128;       // hdri signals per batch
// The hdri protocol keeps 4 numbers per row and signal (the relative IMSE on two rules, at half
// the bands, and its bound) plus 36 bytes per signal (energy, angles, map): 804 bytes a signal
// for the 24 rows, so its --signals stop at one million (0.8 GB). The paper protocol keeps
// 9 radiance coefficients and one IMSE per signal (80 bytes): up to ten million (0.8 GB).
constexpr long long kMaxSignalsPaper = 10000000;
constexpr long long kMaxSignalsHdri = 1000000;
// The closed-form check of the paper protocol compares the sample mean with the expected value
// in units of the sample's standard error; with fewer signals that standard error is itself too
// uncertain (a t statistic of few degrees of freedom has heavy tails) to call a mismatch a bug.
constexpr long long kMinSignalsJudged = 30;
const char* const kMaps[] = {"city",  "courtyard", "forest",  "interior",
                             "night", "studio",    "sunrise", "sunset"};

double nan() { return std::numeric_limits<double>::quiet_NaN(); }

/// Values at or below this are rounding: the basis spans the paper signal (SH 9, 16, 25).
constexpr double kRoundingFloor = 1e-13;

/// An IMSE (never negative by definition) as reported: rounding-level values, including the
/// tiny negative ones a closed form gives (-1.95e-15 for SH 16), are 0 in every output (the
/// table and Markdown say "0 (<1e-13)", CSV and JSON write 0).
double reported_imse(double v) {
    return std::isfinite(v) && std::fabs(v) <= kRoundingFloor ? 0 : v;
}

struct Timing {
    double eval_ns = 0, eval_batch_ns = 0, project_ns = 0;
};

struct RowResult {
    std::string basis;
    int coeffs = 0;
    double imse = 0, stderr_imse = 0;
    double expected = nan(), expected_stderr = nan();
    double quad_err = nan();
    double trunc_bound = nan(), trunc_half = nan();
    std::vector<double> per_map;  // hdri: mean relative IMSE per map
    Timing t;
};

struct ProtocolResult {
    std::string protocol;
    long long signals = 0;
    std::uint64_t seed = 0;
    std::vector<RowResult> rows;
    std::vector<std::string> notes;
    std::vector<std::string> maps;
    std::vector<long long> map_signals;
    std::vector<double> map_tail;  // hdri: truncation bound / mean hemisphere energy per map
    double seconds = 0;
};

/// An empty result of `protocol` on `signals` signals drawn with `seed`.
ProtocolResult new_result(const char* protocol, long long signals, std::uint64_t seed) {
    ProtocolResult res;
    res.protocol = protocol;
    res.signals = signals;
    res.seed = seed;
    return res;
}

// ---------------------------------------------------------------------------------------------
// The benchmark's rows (imse::paper_rows(), the same for both protocols), resolved in the registry.

/// One row of the table: a basis of the registry and its size, or (info null) a fitted
/// representation (imse::fitted_rows(), the fit protocol) and the values it stores.
struct Row {
    const BasisInfo* info;
    int n;
    const FittedBasisInfo* fitted = nullptr;
    const char* name() const { return info != nullptr ? info->name : fitted->name; }
};

/// The linear rows (imse::paper_rows()), then the fitted ones.
std::vector<Row> benchmark_rows() {
    std::vector<Row> rows;
    for (const imse::Row& r : imse::paper_rows()) rows.push_back({&find_basis(r.basis), r.n});
    for (const std::string& name : imse::fitted_rows()) {
        const FittedBasisInfo* f = find_fitted_basis(name);
        rows.push_back({nullptr, f->stored, f});
    }
    return rows;
}

// ---------------------------------------------------------------------------------------------
// Timings

struct Normals {
    std::vector<float> x, y, z;
};
/// Normals uniform on the upper hemisphere (for the timings only).
Normals random_normals(std::size_t count, std::uint64_t seed) {
    std::mt19937_64 gen(seed);
    auto u01 = [&] { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
    Normals n;
    n.x.resize(count);
    n.y.resize(count);
    n.z.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        const double u = u01();
        const double v = u01();
        const vec3<double> d = square_to_uniform_hemisphere(u, v);
        n.x[i] = static_cast<float>(d.x);
        n.y[i] = static_cast<float>(d.y);
        n.z[i] = static_cast<float>(d.z);
    }
    return n;
}

volatile float g_sink = 0;  // keeps timed results alive

/// The projection a baker computes, timed by measure() and measure_fitted(): the rule's points
/// in float and its weights times one fixed signal (the irradiance of random_radiance(7, 1));
/// project() writes r_k = sum_i w_i E_i f_k(x_i) for n functions of `info`.
struct ProjectionProbe {
    std::size_t m;
    std::vector<float> xs, ys, zs, vals;
    std::vector<double> we;
    explicit ProjectionProbe(const DirectionalRule& rule)
        : m(rule.size()), xs(m), ys(m), zs(m), we(m) {
        const Eigen::MatrixXd e = imse::irradiance_samples(imse::random_radiance(7, 1), rule);
        for (std::size_t i = 0; i < m; ++i) {
            xs[i] = static_cast<float>(rule.x[i]);
            ys[i] = static_cast<float>(rule.y[i]);
            zs[i] = static_cast<float>(rule.z[i]);
            we[i] = rule.w[i] * e(static_cast<Eigen::Index>(i), 0);
        }
    }
    void project(const BasisInfo& info, int n, double* r) {
        vals.resize(m * static_cast<std::size_t>(n));
        info.eval_batch_f(n, m, xs.data(), ys.data(), zs.data(), vals.data(), m);
        for (int k = 0; k < n; ++k) {
            const float* v = vals.data() + static_cast<std::size_t>(k) * m;
            double sum = 0;
            for (std::size_t i = 0; i < m; ++i) sum += we[i] * static_cast<double>(v[i]);
            r[k] = sum;
        }
    }
};

Timing measure(const BasisInfo& info, int n, const Normals& small, const Normals& big,
               const DirectionalRule& rule) {
    Timing t;
    std::vector<float> out(static_cast<std::size_t>(n));
    const std::size_t ns = small.x.size();
    // One call at a time.
    {
        double best = 1e300;
        for (int rep = 0; rep < 5; ++rep) {
            float acc = 0;
            const auto t0 = Clock::now();
            const int calls = 1 << 16;
            for (int i = 0; i < calls; ++i) {
                const std::size_t k = static_cast<std::size_t>(i) & (ns - 1);
                info.eval_f(n, small.x[k], small.y[k], small.z[k], out.data());
                acc += out[static_cast<std::size_t>(n - 1)];
            }
            best = std::min(best, seconds_since(t0) * 1e9 / calls);
            g_sink = g_sink + acc;
        }
        t.eval_ns = best;
    }
    // Batched over 1M normals, in chunks of 4096.
    {
        // Stride padded past a multiple of 4 KiB so that the n output rows do not alias in cache.
        const std::size_t chunk = 4096, stride = chunk + 16, total = big.x.size();
        std::vector<float> buf(stride * static_cast<std::size_t>(n));
        double best = 1e300;
        for (int rep = 0; rep < 3; ++rep) {
            float acc = 0;
            const auto t0 = Clock::now();
            for (std::size_t i = 0; i < total; i += chunk) {
                const std::size_t len = std::min(chunk, total - i);
                info.eval_batch_f(n, len, big.x.data() + i, big.y.data() + i, big.z.data() + i,
                                  buf.data(), stride);
                acc += buf[len - 1];
            }
            best = std::min(best, seconds_since(t0) * 1e9 / static_cast<double>(total));
            g_sink = g_sink + acc;
        }
        t.eval_batch_ns = best;
    }
    // Projection: fit one signal from its values at the rule's points.
    {
        ProjectionProbe probe(rule);
        const imse::Fit fit(info.functions(n), imse::orthonormal_on_hemisphere(info), rule);
        Eigen::VectorXd r(n);
        const int signals = 64;
        double best = 1e300;
        for (int rep = 0; rep < 3; ++rep) {
            double acc = 0;
            const auto t0 = Clock::now();
            for (int s = 0; s < signals; ++s) {
                probe.project(info, n, r.data());
                acc += fit.solve(r)(0);
            }
            best = std::min(best, seconds_since(t0) * 1e9 / signals);
            g_sink = g_sink + static_cast<float>(acc);
        }
        t.project_ns = best;
    }
    return t;
}

/// measure() for a fitted representation: eval_ns and eval_batch_ns as for a basis (the stored
/// values of one random signal); project_ns = the SH projection of the values its fit reads from
/// the signal at the rule's points (as a baker would) plus the fit.
Timing measure_fitted(const FittedBasisInfo& f, const Normals& small, const Normals& big,
                      const DirectionalRule& rule) {
    Timing t;
    const std::size_t ns = small.x.size();
    std::vector<double> sh(9);
    {
        const Eigen::VectorXd a = imse::irradiance_factors();
        const Eigen::MatrixXd c = imse::random_radiance(7, 1);
        for (int k = 0; k < 9; ++k) sh[static_cast<std::size_t>(k)] = a(k) * c(k, 0);
    }
    std::vector<double> stored_d(static_cast<std::size_t>(f.stored));
    f.fit(sh.data(), stored_d.data());
    const std::vector<float> stored(stored_d.begin(), stored_d.end());
    {
        double best = 1e300;
        for (int rep = 0; rep < 5; ++rep) {
            float acc = 0;
            const auto t0 = Clock::now();
            const int calls = 1 << 16;
            for (int i = 0; i < calls; ++i) {
                const std::size_t k = static_cast<std::size_t>(i) & (ns - 1);
                acc += f.eval_f(stored.data(), small.x[k], small.y[k], small.z[k]);
            }
            best = std::min(best, seconds_since(t0) * 1e9 / calls);
            g_sink = g_sink + acc;
        }
        t.eval_ns = best;
    }
    {
        const std::size_t chunk = 4096, total = big.x.size();
        std::vector<float> buf(chunk);
        double best = 1e300;
        for (int rep = 0; rep < 3; ++rep) {
            float acc = 0;
            const auto t0 = Clock::now();
            for (std::size_t i = 0; i < total; i += chunk) {
                const std::size_t len = std::min(chunk, total - i);
                f.eval_batch_f(stored.data(), len, big.x.data() + i, big.y.data() + i,
                               big.z.data() + i, buf.data());
                acc += buf[len - 1];
            }
            best = std::min(best, seconds_since(t0) * 1e9 / static_cast<double>(total));
            g_sink = g_sink + acc;
        }
        t.eval_batch_ns = best;
    }
    {
        const int n = f.sh_coeffs;
        ProjectionProbe probe(rule);
        std::vector<double> proj(static_cast<std::size_t>(n)), out(16);
        const BasisInfo& shb = find_basis("sh");
        const int signals = 64;
        double best = 1e300;
        for (int rep = 0; rep < 3; ++rep) {
            double acc = 0;
            const auto t0 = Clock::now();
            for (int s = 0; s < signals; ++s) {
                probe.project(shb, n, proj.data());
                f.fit(proj.data(), out.data());
                acc += out[0];
            }
            best = std::min(best, seconds_since(t0) * 1e9 / signals);
            g_sink = g_sink + static_cast<float>(acc);
        }
        t.project_ns = best;
    }
    return t;
}

std::vector<Timing> measure_all(const std::vector<Row>& rows) {
    const Normals small = random_normals(4096, 11), big = random_normals(1 << 20, 12);
    const DirectionalRule rule = imse::paper_rule();
    std::vector<Timing> out;
    Progress bar("timing", static_cast<long long>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r) {
        out.push_back(rows[r].fitted != nullptr
                          ? measure_fitted(*rows[r].fitted, small, big, rule)
                          : measure(*rows[r].info, rows[r].n, small, big, rule));
        bar.update();
    }
    bar.done();
    return out;
}

// ---------------------------------------------------------------------------------------------
// BakingLab's SG pipeline (imse::sg_pipeline_imse): rows after the registry's, paper protocol only

struct SgPipelineRow {
    const char* name;
    sg::Solver solver;
};
const SgPipelineRow kSgPipeline[] = {{"sg-ls", sg::Solver::least_squares},
                                     {"sg-nnls", sg::Solver::nnls},
                                     {"sg-ra", sg::Solver::running_average},
                                     {"sg-ra-nn", sg::Solver::running_average_nn}};
constexpr int kSgPipelineCounts[] = {9, 12};

/// eval: the irradiance sum_k a_k irradiance_fitted(G_k, n) at one normal (float); batch: the
/// same over SIMD batches of normals; project: one texel's amplitudes from its 625 samples.
Timing measure_sg_pipeline(int count, sg::Solver solver, const Normals& small, const Normals& big,
                           const Eigen::Matrix3Xd& dirs) {
    Timing t;
    const auto lobes = sg::bakinglab_lobes<float>(count);
    std::vector<float> amp(lobes.size());
    for (std::size_t k = 0; k < amp.size(); ++k) amp[k] = 0.5f + 0.1f * static_cast<float>(k);
    {
        double best = 1e300;
        const std::size_t ns = small.x.size();
        for (int rep = 0; rep < 5; ++rep) {
            float acc = 0;
            const auto t0 = Clock::now();
            const int calls = 1 << 16;
            for (int i = 0; i < calls; ++i) {
                const std::size_t j = static_cast<std::size_t>(i) & (ns - 1);
                for (std::size_t k = 0; k < lobes.size(); ++k)
                    acc += amp[k] *
                           sg::irradiance_fitted(lobes[k], small.x[j], small.y[j], small.z[j]);
            }
            best = std::min(best, seconds_since(t0) * 1e9 / calls);
            g_sink = g_sink + acc;
        }
        t.eval_ns = best;
    }
    {
        using B = batch<float>;
        double best = 1e300;
        const std::size_t total = big.x.size() / B::size * B::size;
        for (int rep = 0; rep < 3; ++rep) {
            B acc(0.0f);
            const auto t0 = Clock::now();
            for (std::size_t i = 0; i < total; i += B::size) {
                const B x = B::load(big.x.data() + i), y = B::load(big.y.data() + i),
                        z = B::load(big.z.data() + i);
                B e(0.0f);
                for (std::size_t k = 0; k < lobes.size(); ++k)
                    e += B(amp[k]) * sg::irradiance_fitted(lobes[k], x, y, z);
                acc += e;
            }
            best = std::min(best, seconds_since(t0) * 1e9 / static_cast<double>(total));
            g_sink = g_sink + acc[0];
        }
        t.eval_batch_ns = best;
    }
    {
        const auto dl = sg::bakinglab_lobes(count);
        const Eigen::MatrixXd c = imse::random_radiance(7, 1);
        Eigen::MatrixXd ys(dirs.cols(), imse::signal_coeffs);
        for (Eigen::Index i = 0; i < dirs.cols(); ++i) {
            double y[imse::signal_coeffs];
            sh::eval_unit(3, dirs(0, i), dirs(1, i), dirs(2, i), y);
            for (int k = 0; k < imse::signal_coeffs; ++k) ys(i, k) = y[k];
        }
        const Eigen::MatrixXd v = ys * c;
        // The running average's per-lobe integrals are computed once per lobe set, as a bake
        // would; each texel starts from a copy.
        const sg::RunningAverage fresh(dl, 1, sg::Distribution::hemisphere,
                                       solver == sg::Solver::running_average_nn);
        double best = 1e300;
        const int signals = 16;
        for (int rep = 0; rep < 3; ++rep) {
            double acc = 0;
            const auto t0 = Clock::now();
            for (int s = 0; s < signals; ++s) {
                if (solver == sg::Solver::least_squares) {
                    acc += sg::fit_least_squares(dl, dirs, v)(0, 0);
                } else if (solver == sg::Solver::nnls) {
                    acc += sg::fit_nnls(dl, dirs, v)(0, 0);
                } else {
                    sg::RunningAverage ra = fresh;
                    for (Eigen::Index i = 0; i < dirs.cols(); ++i)
                        ra.add(dirs(0, i), dirs(1, i), dirs(2, i), &v(i, 0));
                    acc += ra.amplitudes()(0, 0);
                }
            }
            best = std::min(best, seconds_since(t0) * 1e9 / signals);
            g_sink = g_sink + static_cast<float>(acc);
        }
        t.project_ns = best;
    }
    return t;
}

/// The pipeline rows of the paper protocol for `radiance` (9 x S).
void add_sg_pipeline_rows(ProtocolResult& res, const Eigen::MatrixXd& radiance,
                          const DirectionalRule& rule, const DirectionalRule& fine) {
    const Eigen::Matrix3Xd dirs = imse::sg_sample_directions();
    const Normals small = random_normals(4096, 11), big = random_normals(1 << 20, 12);
    const Eigen::Index signals = radiance.cols();
    Progress bar("sg pipeline",
                 static_cast<long long>(sizeof kSgPipeline / sizeof kSgPipeline[0] * 2));
    for (int count : kSgPipelineCounts) {
        for (const SgPipelineRow& p : kSgPipeline) {
            Eigen::VectorXd values(signals);
            const Eigen::Index chunk = 1000;
            for (Eigen::Index s0 = 0; s0 < signals; s0 += chunk) {
                const Eigen::Index len = std::min<Eigen::Index>(chunk, signals - s0);
                values.segment(s0, len) = imse::sg_pipeline_imse(
                    count, p.solver, radiance.middleCols(s0, len), dirs, rule);
            }
            const imse::Summary sum = imse::summarize(values);
            RowResult row;
            row.basis = p.name;
            row.coeffs = count;
            row.imse = reported_imse(sum.mean);
            row.stderr_imse = sum.standard_error;
            // quad_err: the first 100 signals on the finer rule.
            const Eigen::Index nq = std::min<Eigen::Index>(100, signals);
            row.quad_err = std::fabs(
                imse::sg_pipeline_imse(count, p.solver, radiance.leftCols(nq), dirs, fine).mean() -
                values.head(nq).mean());
            if (p.solver == sg::Solver::least_squares || p.solver == sg::Solver::running_average) {
                const Eigen::MatrixXd q =
                    imse::sg_pipeline_residual_form(count, p.solver, dirs, rule);
                row.expected = reported_imse(imse::expected(q));
                row.expected_stderr =
                    imse::stddev_uniform(q) / std::sqrt(static_cast<double>(signals));
            }
            row.t = measure_sg_pipeline(count, p.solver, small, big, dirs);
            res.rows.push_back(row);
            bar.update();
        }
    }
    bar.done();
    res.notes.push_back(
        "sg-ls, sg-nnls, sg-ra, sg-ra-nn: BakingLab's SG pipeline (radiance sampled at 625 "
        "stratified hemisphere directions, lobe amplitudes by least squares, non-negative least "
        "squares, running average, non-negative running average; irradiance by Hill's fitted "
        "approximation); eval ns = that irradiance at one normal, proj ns = one texel's solve; "
        "quad_err on the first 100 signals");
}

// ---------------------------------------------------------------------------------------------
// Protocol paper

ProtocolResult run_paper(const std::vector<Row>& rows, long long signals, std::uint64_t seed) {
    const auto t0 = Clock::now();
    ProtocolResult res = new_result("paper", signals, seed);
    const DirectionalRule rule = imse::paper_rule(), fine = imse::paper_check_rule();
    const Eigen::MatrixXd radiance = imse::random_radiance(seed, static_cast<int>(signals));
    Progress bar("paper", static_cast<long long>(rows.size()));
    for (std::size_t r = 0; r < rows.size(); ++r) {
        if (rows[r].fitted != nullptr) {
            // The fit protocol: no closed form (non-linear); quad_err against twice the
            // Funk-Hecke nodes and 24 bands.
            const FittedBasisInfo& f = *rows[r].fitted;
            const Eigen::VectorXd values = imse::fitted_imse_paper(f, radiance);
            const Eigen::VectorXd fine_values =
                imse::fitted_imse_paper(f, radiance, 24, imse::fitted_check_nodes);
            const imse::Summary sum = imse::summarize(values);
            RowResult row;
            row.basis = f.name;
            row.coeffs = f.stored;
            row.imse = reported_imse(sum.mean);
            row.stderr_imse = sum.standard_error;
            row.quad_err = std::fabs(fine_values.mean() - sum.mean);
            res.rows.push_back(row);
            bar.update();
            continue;
        }
        const BasisInfo& info = *rows[r].info;
        const int n = rows[r].n;
        const BasisFunctions b = info.functions(n);
        const bool ortho = imse::orthonormal_on_hemisphere(info);
        const Eigen::MatrixXd q = imse::residual_form(b, ortho, rule);
        const Eigen::MatrixXd qf = imse::residual_form(b, ortho, fine);
        const imse::Fit fit(b, ortho, rule);
        Eigen::VectorXd values(signals);
        const Eigen::Index chunk = 1000;
        for (Eigen::Index s0 = 0; s0 < signals; s0 += chunk) {
            const Eigen::Index len = std::min<Eigen::Index>(chunk, signals - s0);
            values.segment(s0, len) =
                fit.imse(imse::irradiance_samples(radiance.middleCols(s0, len), rule));
        }
        const imse::Summary sum = imse::summarize(values);
        RowResult row;
        row.basis = info.name;
        row.coeffs = n;
        row.imse = reported_imse(sum.mean);
        row.stderr_imse = sum.standard_error;
        row.expected = reported_imse(imse::expected(q));
        row.expected_stderr = imse::stddev_uniform(q) / std::sqrt(static_cast<double>(signals));
        row.quad_err = std::fabs(imse::expected(qf) - imse::expected(q));
        res.rows.push_back(row);
        bar.update();
    }
    bar.done();
    res.notes.push_back(
        "IMSE and expected values at or below 1e-13 are rounding (the basis spans "
        "the signal) and are reported as 0");
    res.notes.push_back("radiance: 9 SH coefficients i.i.d. uniform on [-1,1] (mt19937_64, seed " +
                        std::to_string(seed) + "); irradiance factors 1, 2/3, 1/4");
    res.notes.push_back(
        "fit and IMSE by quadrature in u = sqrt(z): " + std::to_string(rule.size()) +
        " points (32 x 32); quad_err against " + std::to_string(fine.size()) + " points (64 x 48)");
    add_sg_pipeline_rows(res, radiance, rule, fine);
    res.notes.push_back(
        "fitted rows (sh-l1-nonlinear, zh3-hallucinate, zh3): fit from the irradiance's own SH "
        "over the sphere, error over the hemisphere through the SH Gram of 16 bands; quad_err "
        "against 24 bands and twice the Funk-Hecke nodes; no closed form");
    res.seconds = seconds_since(t0);
    return res;
}

// ---------------------------------------------------------------------------------------------
// Protocol hdri

std::string envmap_dir() {
    if (const char* e = std::getenv("SPHBASIS_ENVMAPS")) return e;
#if defined(SPHBASIS_SOURCE_DIR)
    return std::string(SPHBASIS_SOURCE_DIR) + "/data/envmaps";
#else
    return "data/envmaps";
#endif
}

/// The luminance of an EXR lat-long map (support/exr.hpp) as the library's map type.
LatLongMap load_map(const std::string& path) {
    LuminanceImage img = load_exr_luminance(path);
    LatLongMap m;
    m.width = img.width;
    m.height = img.height;
    m.values = std::move(img.values);
    return m;
}

ProtocolResult run_hdri(const std::vector<Row>& rows, long long signals, std::uint64_t seed) {
    const auto t0 = Clock::now();
    ProtocolResult res = new_result("hdri", signals, seed);
    const int nmaps = static_cast<int>(sizeof kMaps / sizeof kMaps[0]);
    const std::string dir = envmap_dir();
    const int nb = kSignalBands, k = nb * nb;

    // Maps: radiance SH to kMapBands bands, irradiance to kSignalBands, truncation bounds.
    std::vector<std::vector<double>> irr(static_cast<std::size_t>(nmaps));
    std::vector<double> tail(static_cast<std::size_t>(nmaps));
    {
        Progress bar("hdri: projecting maps", nmaps);
        parallel_for(static_cast<std::size_t>(nmaps), [&](std::size_t i) {
            const LatLongMap map = load_map(dir + "/" + kMaps[i] + ".exr");
            const std::vector<double> rad = sh::project_latlong(map, kMapBands);
            const std::vector<double> energies = sh::band_energies(kMapBands, rad.data());
            tail[static_cast<std::size_t>(i)] =
                imse::truncation_bound(energies, squared_norm(map), nb);
            std::vector<double> e(static_cast<std::size_t>(k));
            for (int c = 0; c < k; ++c)
                e[static_cast<std::size_t>(c)] =
                    clamped_cosine(sh::degree_of(c)) * rad[static_cast<std::size_t>(c)];
            irr[static_cast<std::size_t>(i)] = std::move(e);
            bar.update();
        });
    }

    // Fits of all rows against SH of nb bands, on two rules (the second checks the first).
    std::vector<BasisFunctions> fns;
    std::vector<bool> ortho;
    std::vector<const FittedBasisInfo*> fitted_bases;  // the fitted rows, after the linear ones
    for (const auto& r : rows) {
        if (r.fitted != nullptr) {
            fitted_bases.push_back(r.fitted);
            continue;
        }
        fns.push_back(r.info->functions(r.n));
        ortho.push_back(imse::orthonormal_on_hemisphere(*r.info));
    }
    const auto [nu, nphi] = imse::hdri_rule_size(nb);
    const imse::ShFits fits(fns, ortho, nb, nu, nphi);
    const imse::ShFits fits_fine(fns, ortho, nb, nu + 16, nphi + 8);
    const imse::HemisphereShGram gram(nb);
    const int half = nb / 2;
    const imse::HemisphereShGram gram_half(half);

    // Signals: map-major, N / 8 per map (the first N % 8 maps get one more); orientation
    // angles drawn in signal order from mt19937_64(seed ^ 0x9e3779b97f4a7c15).
    std::vector<int> map_of(static_cast<std::size_t>(signals));
    res.map_signals.assign(static_cast<std::size_t>(nmaps), 0);
    for (long long s = 0, i = 0; i < nmaps; ++i) {
        const long long cnt = signals / nmaps + (i < signals % nmaps ? 1 : 0);
        res.map_signals[static_cast<std::size_t>(i)] = cnt;
        for (long long c = 0; c < cnt; ++c)
            map_of[static_cast<std::size_t>(s++)] = static_cast<int>(i);
    }
    std::vector<double> angles(static_cast<std::size_t>(3 * signals));
    {
        std::mt19937_64 gen(seed ^ 0x9e3779b97f4a7c15ULL);
        auto u01 = [&] { return static_cast<double>(gen() >> 11) * 0x1.0p-53; };
        for (long long s = 0; s < signals; ++s) {
            const double u1 = u01(), u2 = u01(), u3 = u01();
            const std::array<double, 3> e = cube_to_euler_zyz(u1, u2, u3);
            std::copy(e.begin(), e.end(), angles.begin() + 3 * s);
        }
    }

    const int nlin = fits.rows();
    const int nrows = nlin + static_cast<int>(fitted_bases.size());
    Eigen::MatrixXd rel(nrows, signals), bound(nrows, signals), rel_half(nrows, signals),
        rel_fine(nrows, signals);
    Eigen::VectorXd energy(signals);
    const int nbatches = static_cast<int>((signals + kBatch - 1) / kBatch);
    Progress bar("hdri: signals", signals);
    parallel_for(static_cast<std::size_t>(nbatches), [&](std::size_t bi) {
        const long long s0 = static_cast<long long>(bi) * kBatch;
        const int len = static_cast<int>(std::min<long long>(kBatch, signals - s0));
        Eigen::MatrixXd e(k, len), eh = Eigen::MatrixXd::Zero(k, len);
        std::vector<double> a(static_cast<std::size_t>(k));
        for (int c = 0; c < len; ++c) {
            const long long s = s0 + c;
            const std::vector<double>& src =
                irr[static_cast<std::size_t>(map_of[static_cast<std::size_t>(s)])];
            const double* ang = angles.data() + 3 * s;
            sh::rotate_zyz(nb, ang[0], ang[1], ang[2], src.data(), a.data());
            for (int q = 0; q < k; ++q) e(q, c) = a[static_cast<std::size_t>(q)];
            for (int q = 0; q < half * half; ++q) eh(q, c) = a[static_cast<std::size_t>(q)];
        }
        const Eigen::MatrixXd fitted = fits.fitted_energy(e);
        const Eigen::MatrixXd fitted_fine = fits_fine.fitted_energy(e);
        const Eigen::MatrixXd fitted_half = fits.fitted_energy(eh);
        for (int c = 0; c < len; ++c) {
            const long long s = s0 + c;
            const double en = gram.energy(e.col(c).data());
            Eigen::VectorXd hv = eh.col(c).head(half * half);
            const double en_half = gram_half.energy(hv.data());
            const double t = tail[static_cast<std::size_t>(map_of[static_cast<std::size_t>(s)])];
            energy(s) = en;
            for (int r = 0; r < nlin; ++r) {
                const double im = en - fitted(r, c);
                rel(r, s) = imse::relative(im, en);
                rel_fine(r, s) = imse::relative(en - fitted_fine(r, c), en);
                rel_half(r, s) = imse::relative(en_half - fitted_half(r, c), en_half);
                bound(r, s) = imse::relative_error_bound(im, en, t);
            }
            // Fitted rows: the fit protocol through the same Gram matrices; the bound adds the
            // representation's own part above nb bands to the signal's.
            for (std::size_t f = 0; f < fitted_bases.size(); ++f) {
                const int r = nlin + static_cast<int>(f);
                double tr = 0;
                const double im = imse::fitted_imse(*fitted_bases[f], gram, e.col(c).data(),
                                                    imse::fitted_nodes, &tr);
                rel(r, s) = imse::relative(im, en);
                rel_fine(r, s) =
                    imse::relative(imse::fitted_imse(*fitted_bases[f], gram, e.col(c).data(),
                                                     imse::fitted_check_nodes),
                                   en);
                rel_half(r, s) = imse::relative(
                    imse::fitted_imse(*fitted_bases[f], gram_half, hv.data()), en_half);
                const double st = std::sqrt(t) + std::sqrt(tr);
                bound(r, s) = imse::relative_error_bound(im, en, st * st);
            }
        }
        bar.update(len);
    });
    bar.done();

    for (int i = 0; i < nmaps; ++i) res.maps.push_back(kMaps[i]);
    // Tail bound relative to the mean hemisphere energy of the map's signals (for the report).
    res.map_tail.assign(static_cast<std::size_t>(nmaps), 0.0);
    {
        std::vector<double> esum(static_cast<std::size_t>(nmaps), 0.0);
        for (long long s = 0; s < signals; ++s)
            esum[static_cast<std::size_t>(map_of[static_cast<std::size_t>(s)])] += energy(s);
        for (int i = 0; i < nmaps; ++i) {
            const double cnt = static_cast<double>(res.map_signals[static_cast<std::size_t>(i)]);
            res.map_tail[static_cast<std::size_t>(i)] =
                cnt > 0
                    ? tail[static_cast<std::size_t>(i)] / (esum[static_cast<std::size_t>(i)] / cnt)
                    : nan();
        }
    }
    for (int r = 0; r < nrows; ++r) {
        RowResult row;
        row.basis = rows[static_cast<std::size_t>(r)].name();
        row.coeffs = rows[static_cast<std::size_t>(r)].n;
        const imse::Summary sum = imse::summarize(rel.row(r).transpose());
        row.imse = reported_imse(sum.mean);
        row.stderr_imse = sum.standard_error;
        row.trunc_bound = bound.row(r).mean();
        row.trunc_half = std::fabs(rel_half.row(r).mean() - sum.mean);
        row.quad_err = std::fabs(rel_fine.row(r).mean() - sum.mean);
        for (int i = 0; i < nmaps; ++i) {
            double acc = 0;
            long long cnt = 0;
            for (long long s = 0; s < signals; ++s)
                if (map_of[static_cast<std::size_t>(s)] == i) {
                    acc += rel(r, s);
                    ++cnt;
                }
            row.per_map.push_back(cnt ? acc / static_cast<double>(cnt) : nan());
        }
        res.rows.push_back(row);
    }
    res.notes.push_back(
        "relative IMSE = IMSE / mean over the hemisphere of E^2; radiance = luminance "
        "0.2126 R + 0.7152 G + 0.0722 B, channels clamped >= 0");
    res.notes.push_back("maps projected exactly (piecewise-constant texels) to " +
                        std::to_string(kMapBands) + " SH bands; irradiance truncated to " +
                        std::to_string(nb) + " bands; " + std::to_string(signals) +
                        " random orientations (seed " + std::to_string(seed) + ")");
    res.notes.push_back("fits by quadrature in u = sqrt(z): " + std::to_string(nu) + " x " +
                        std::to_string(nphi) + " points; quad_err against " +
                        std::to_string(nu + 16) + " x " + std::to_string(nphi + 8));
    res.seconds = seconds_since(t0);
    return res;
}

// ---------------------------------------------------------------------------------------------
// Output

std::string fmt(const char* f, double v) {
    if (!std::isfinite(v)) return "-";
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

std::string quad_rel(const RowResult& r) {
    if (!(std::fabs(r.imse) > kRoundingFloor)) return "exact";
    return fmt("%.0e", r.quad_err / std::fabs(r.imse));
}

std::string value_or_floor(double v, const char* f) {
    if (std::isfinite(v) && std::fabs(v) <= kRoundingFloor) return "0 (<1e-13)";
    return fmt(f, v);
}

void print_table(std::ostream& os, const ProtocolResult& p) {
    const bool hdri = p.protocol == "hdri";
    os << "protocol " << p.protocol << ": " << p.signals << " signals, seed " << p.seed << ", "
       << fmt("%.1f", p.seconds) << " s\n";
    for (const auto& n : p.notes) os << "  " << n << "\n";
    char line[512];
    std::snprintf(line, sizeof line, "%-15s %6s  %-23s %-21s %-9s %8s %8s %8s %12s\n", "basis",
                  "coeffs", hdri ? "rel. IMSE +- stderr" : "IMSE +- stderr",
                  hdri ? "trunc.bound  d(32->64)" : "expected +- stderr", "quad.rel", "eval ns",
                  "batch ns", "proj ns", "B/texel 8/16/32");
    os << line;
    double worst_z = 0;
    for (const auto& r : p.rows) {
        const std::string val =
            value_or_floor(r.imse, "%.4e") +
            (std::fabs(r.imse) > kRoundingFloor ? " +- " + fmt("%.1e", r.stderr_imse) : "");
        std::string second;
        if (hdri) {
            second = fmt("%.1e", r.trunc_bound) + "      " + fmt("%.1e", r.trunc_half);
        } else {
            second =
                value_or_floor(r.expected, "%.4e") + (std::fabs(r.expected) > kRoundingFloor
                                                          ? " +- " + fmt("%.1e", r.expected_stderr)
                                                          : "");
            if (std::fabs(r.expected) > kRoundingFloor && r.stderr_imse > 0)
                worst_z = std::max(worst_z, std::fabs(r.imse - r.expected) / r.stderr_imse);
        }
        const std::string bytes = std::to_string(3 * r.coeffs) + "/" +
                                  std::to_string(6 * r.coeffs) + "/" +
                                  std::to_string(12 * r.coeffs);
        std::snprintf(line, sizeof line, "%-15s %6d  %-23s %-21s %-9s %8.2f %8.2f %8.0f %12s\n",
                      r.basis.c_str(), r.coeffs, val.c_str(), second.c_str(), quad_rel(r).c_str(),
                      r.t.eval_ns, r.t.eval_batch_ns, r.t.project_ns, bytes.c_str());
        os << line;
    }
    if (!hdri && !p.rows.empty()) {
        if (p.signals < kMinSignalsJudged) {
            os << "  closed form vs sample mean: not judged with " << p.signals
               << " signals (the standard error of fewer than " << kMinSignalsJudged
               << " is too uncertain to tell a mismatch from chance)\n";
        } else {
            os << "  closed form vs sample mean: largest |mean - expected| = "
               << fmt("%.2f", worst_z) << " standard errors";
            os << (worst_z > 5 ? "  WARNING: mismatch, this is a bug\n" : "\n");
        }
    }
}

Json protocol_json(const ProtocolResult& p) {
    const bool hdri = p.protocol == "hdri";
    Json o = {{"protocol", p.protocol}, {"signals", p.signals}, {"seed", p.seed},
              {"relative", hdri},       {"seconds", p.seconds}, {"notes", p.notes}};
    if (!p.maps.empty()) {
        Json& maps = o["maps"] = Json::array();
        for (std::size_t i = 0; i < p.maps.size(); ++i)
            maps.push_back({{"name", p.maps[i]},
                            {"signals", p.map_signals[i]},
                            {"tail_bound_rel", p.map_tail[i]}});
    }
    Json& rows = o["rows"] = Json::array();
    for (const RowResult& r : p.rows) {
        Json row = {{"basis", r.basis},       {"coeffs", r.coeffs},
                    {"imse", r.imse},         {"stderr", r.stderr_imse},
                    {"expected", r.expected}, {"expected_stderr", r.expected_stderr},
                    {"quad_err", r.quad_err}};
        if (hdri) {
            row["trunc_bound"] = r.trunc_bound;
            row["trunc_half"] = r.trunc_half;
            row["per_map"] = r.per_map;
        }
        row["eval_ns"] = r.t.eval_ns;
        row["eval_batch_ns"] = r.t.eval_batch_ns;
        row["project_ns"] = r.t.project_ns;
        row["bytes_per_texel_rgb8"] = 3 * r.coeffs;
        row["bytes_per_texel_rgb16f"] = 6 * r.coeffs;
        row["bytes_per_texel_rgb32f"] = 12 * r.coeffs;
        rows.push_back(std::move(row));
    }
    return o;
}

std::string csv_of(const std::vector<ProtocolResult>& ps) {
    std::ostringstream o;
    o << "protocol,basis,coeffs,imse,stderr,expected,quad_err,trunc_bound,eval_ns,eval_batch_ns,"
         "project_ns,bytes_per_texel_rgb8,bytes_per_texel_rgb16f,bytes_per_texel_rgb32f\n";
    for (const auto& p : ps)
        for (const auto& r : p.rows)
            o << p.protocol << "," << r.basis << "," << r.coeffs << "," << format_real(r.imse)
              << "," << format_real(r.stderr_imse) << ","
              << (std::isfinite(r.expected) ? format_real(r.expected) : "") << ","
              << format_real(r.quad_err) << ","
              << (std::isfinite(r.trunc_bound) ? format_real(r.trunc_bound) : "") << ","
              << format_real(r.t.eval_ns) << "," << format_real(r.t.eval_batch_ns) << ","
              << format_real(r.t.project_ns) << "," << 3 * r.coeffs << "," << 6 * r.coeffs << ","
              << 12 * r.coeffs << "\n";
    return o.str();
}

std::string md_of(const std::vector<ProtocolResult>& ps) {
    std::ostringstream o;
    for (const auto& p : ps) {
        const bool hdri = p.protocol == "hdri";
        o << "### Protocol `" << p.protocol << "` (" << p.signals << " signals, seed " << p.seed
          << ")\n\n";
        for (const auto& n : p.notes) o << "- " << n << "\n";
        o << "\n| basis | coeffs | " << (hdri ? "relative IMSE ± stderr" : "IMSE ± stderr") << " | "
          << (hdri ? "truncation bound | change 32→64 bands" : "expected (closed form)")
          << " | quadrature rel. error | eval ns | batch eval ns | project ns | bytes/texel RGB "
             "8-bit / half / float |\n"
          << "|---|---:|---:|---:|" << (hdri ? "---:|" : "") << "---:|---:|---:|---:|---:|\n";
        for (const auto& r : p.rows) {
            o << "| " << r.basis << " | " << r.coeffs << " | " << value_or_floor(r.imse, "%.4e");
            if (std::fabs(r.imse) > kRoundingFloor) o << " ± " << fmt("%.1e", r.stderr_imse);
            o << " | ";
            if (hdri)
                o << fmt("%.1e", r.trunc_bound) << " | " << fmt("%.1e", r.trunc_half);
            else
                o << value_or_floor(r.expected, "%.4e");
            o << " | " << quad_rel(r) << " | " << fmt("%.2f", r.t.eval_ns) << " | "
              << fmt("%.2f", r.t.eval_batch_ns) << " | " << fmt("%.0f", r.t.project_ns) << " | "
              << 3 * r.coeffs << " / " << 6 * r.coeffs << " / " << 12 * r.coeffs << " |\n";
        }
        o << "\n";
    }
    return o.str();
}

struct ImseOptions {
    std::string protocol = "paper";
    long long signals = 10000, seed = 1;
    std::string json_path, csv_path, md_path;
};

int run_imse(const ImseOptions& o) {
    const long long signals = o.signals;
    const std::uint64_t seed = static_cast<std::uint64_t>(o.seed);
    // Memory before work: the limits and their reasons are at kMaxSignalsHdri.
    if (o.protocol != "paper" && signals > kMaxSignalsHdri)
        throw UsageError("--signals: expected N <= " + std::to_string(kMaxSignalsHdri) +
                         " for --protocol " + o.protocol +
                         " (the hdri protocol keeps 804 bytes per signal, 0.8 GB at the "
                         "limit), got " +
                         std::to_string(signals));
    // Fail before the long run, not after it, changing nothing; the outputs are staged and
    // written together at the end, all or none (support/output_file.hpp).
    OutputFiles outputs;
    for (const std::string* f : {&o.json_path, &o.csv_path, &o.md_path})
        if (!f->empty()) outputs.declare(*f);
    outputs.prepare();

    const auto t0 = Clock::now();
    const std::vector<Row> rows = benchmark_rows();
    const std::vector<Timing> timing = measure_all(rows);

    std::vector<ProtocolResult> results;
    if (o.protocol == "paper" || o.protocol == "all")
        results.push_back(run_paper(rows, signals, seed));
    if (o.protocol == "hdri" || o.protocol == "all")
        results.push_back(run_hdri(rows, signals, seed));
    for (auto& p : results)
        for (std::size_t r = 0; r < p.rows.size() && r < timing.size(); ++r)
            p.rows[r].t = timing[r];  // the SG pipeline rows carry their own
    for (const auto& p : results) {
        print_table(std::cout, p);
        std::cout << "\n";
    }
    std::cout << "total " << fmt("%.1f", seconds_since(t0)) << " s\n";

    if (!o.json_path.empty()) {
        const JsonLayout layout = {{"rows", 2}, {"protocols", 0}};
        Json j;
        if (results.size() == 1) {
            j = protocol_json(results[0]);
        } else {
            j = {{"protocol", "all"}, {"signals", signals}, {"seed", seed}};
            Json& ps = j["protocols"] = Json::array();
            for (const auto& p : results) ps.push_back(protocol_json(p));
        }
        outputs.add(o.json_path, dump_json(j, layout) + "\n");
    }
    if (!o.csv_path.empty()) outputs.add(o.csv_path, csv_of(results));
    if (!o.md_path.empty()) outputs.add(o.md_path, md_of(results));
    outputs.commit();
    return 0;
}

}  // namespace

Run setup_imse(CLI::App& app) {
    auto o = std::make_shared<ImseOptions>();
    app.footer(
        "The IMSE basis comparison (Ishmukhametov, section 3.1): the least-squares fit error of\n"
        "irradiance over the upper hemisphere per basis and size, beside evaluation, projection\n"
        "and storage costs.");
    app.add_option("--protocol", o->protocol,
                   "paper: random 9-coefficient radiance; hdri: the maps in data/envmaps; all")
        ->type_name("paper|hdri|all")
        ->capture_default_str()
        ->check(CLI::Validator(
            [](const std::string& s) {
                return s == "paper" || s == "hdri" || s == "all"
                           ? std::string()
                           : "expected paper, hdri or all, got '" + s + "'";
            },
            "", ""));
    add_integer(app, "--signals", o->signals, 2, kMaxSignalsPaper,
                "signals averaged per row (hdri: at most 1000000)", "N",
                "80 bytes of memory per signal, 0.8 GB at the limit; hdri: 804 bytes, at most "
                "1000000");
    add_integer(app, "--seed", o->seed, 0, std::numeric_limits<long long>::max(), "random seed",
                "S");
    add_path(app, "--json", o->json_path, "write the results as JSON (tools/plot/plot_imse.py)");
    add_path(app, "--csv", o->csv_path, "write the results as CSV");
    add_path(app, "--md", o->md_path, "write the results as Markdown tables");
    return [o] { return run_imse(*o); };
}

}  // namespace sphbasis::cli
