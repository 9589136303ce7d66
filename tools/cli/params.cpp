// sphbasis CLI: `sphbasis params [--points N] [--json PATH] [--csv PATH] [--threads T]
//                                [--seed S] [--subtexel-bits B]`
//
// The experiment of Iwanicki and Sloan, "Normal Mapping with Low-Frequency Precomputed
// Visibility" (JGT 2009), appendix A: for each spherical parameterization and a range of
// resolutions, tabulate every real SH basis function of 6 bands (36 functions; the first 9 are
// the 3-band set) at the texel centres, reconstruct them by hardware bilinear filtering at N
// random directions (uniform on the sphere, default one million), and report the mean squared
// error against the exact values, averaged over the functions and the directions, as a
// function of the total number of texels. The experiment is the library's
// (param/reconstruction_error.hpp); this file runs it on TBB's threads and writes the table.
// The numbers do not depend on --threads.
//
// --points is at most 100 million: the directions take 56 bytes each at their peak (5.6 GB).
//
// Output: a table on standard output, --json PATH (read by tools/plot/plot_params.py) and
// --csv PATH with one row per (parameterization, resolution).
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <sphbasis/param/reconstruction_error.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../support/json.hpp"
#include "../support/output_file.hpp"
#include "../support/parallel.hpp"
#include "../support/progress.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

struct ParamsOptions {
    long long points = 1000000, threads = 1, seed = 1, bits = 0;
    std::string json_path, csv_path;
};

int run_params(const ParamsOptions& o) {
    // Check and stage the outputs first so a bad path fails before a minute of work, changing
    // nothing; they are written together at the end, all or none (support/output_file.hpp).
    OutputFiles outputs;
    for (const std::string* f : {&o.json_path, &o.csv_path})
        if (!f->empty()) outputs.declare(*f);
    outputs.prepare();
    const ThreadLimit limit(static_cast<std::size_t>(o.threads));
    const int bits = static_cast<int>(o.bits);

    const auto t0 = std::chrono::steady_clock::now();
    const param::DirectionSet dirs = param::reconstruction_directions(
        static_cast<std::size_t>(o.points), static_cast<std::uint64_t>(o.seed));
    const auto& cases = param::reconstruction_cases();
    std::vector<param::ReconstructionResult> results;
    std::printf("%-20s %6s %8s %14s %14s\n", "parameterization", "n", "texels", "MSE 3 bands",
                "MSE 6 bands");
    {
        Progress bar("params",
                     static_cast<long long>(cases.size()) * param::reconstruction_budgets);
        for (const auto& c : cases) {
            for (int k = 0; k < param::reconstruction_budgets; ++k) {
                const int n = param::reconstruction_resolution(c, k);
                results.push_back(param::run_reconstruction_case(c, n, bits, dirs, ParallelFor{}));
                const auto& r = results.back();
                std::printf("%-20s %6d %8zu %14.6e %14.6e\n", r.param.c_str(), r.resolution,
                            r.texels, r.mse3, r.mse6);
                std::fflush(stdout);
                bar.update();
            }
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Summary: the best parameterization at each texel budget, by interpolating every curve
    // log-log at the budget (the resolutions give only approximately equal texel counts).
    std::printf("\nbest at equal texel count (log-log interpolation):\n");
    for (double budget : {384.0, 1536.0, 6144.0, 24576.0}) {
        for (int bands : {3, 6}) {
            std::string best;
            double best_mse = INFINITY;
            for (const auto& c : cases) {
                const double m = param::reconstruction_mse_at(results, c.name, budget, bands);
                if (m < best_mse) best_mse = m, best = c.name;
            }
            const double dx10 = param::reconstruction_mse_at(results, "cube_dx10", budget, bands);
            const double octa =
                param::reconstruction_mse_at(results, "octahedral_seamless", budget, bands);
            std::printf(
                "  %6.0f texels, %d bands: %-20s MSE %.3e (cube_dx10 %.3e, "
                "octahedral_seamless %.3e)\n",
                budget, bands, best.c_str(), best_mse, dx10, octa);
        }
    }
    std::printf("\n%lld points, %lld threads, %.1f s\n", o.points, o.threads, seconds);

    if (!o.json_path.empty()) {
        Json j = {{"experiment", "params"},  {"points", o.points},    {"seed", o.seed},
                  {"subtexel_bits", o.bits}, {"table_type", "float"}, {"seconds", seconds}};
        Json& ps = j["parameterizations"] = Json::array();
        for (const auto& c : cases) ps.push_back({{"name", c.name}, {"label", c.label}});
        Json& rs = j["results"] = Json::array();
        for (const auto& r : results)
            rs.push_back({{"param", r.param},
                          {"resolution", r.resolution},
                          {"texels", r.texels},
                          {"mse_3bands", r.mse3},
                          {"mse_6bands", r.mse6}});
        outputs.add(o.json_path, dump_json(j, {{"results", 0}}) + "\n");
    }
    if (!o.csv_path.empty()) {
        std::ostringstream csv;
        csv << "param,resolution,texels,mse_3bands,mse_6bands\n";
        for (const auto& r : results)
            csv << r.param << "," << r.resolution << "," << r.texels << "," << format_real(r.mse3)
                << "," << format_real(r.mse6) << "\n";
        outputs.add(o.csv_path, csv.str());
    }
    outputs.commit();
    return 0;
}

}  // namespace

Run setup_params(CLI::App& app) {
    auto o = std::make_shared<ParamsOptions>();
    o->threads = std::max(1u, std::thread::hardware_concurrency());
    app.footer(
        "The parameterization experiment of Iwanicki and Sloan (JGT 2009, appendix A): MSE of\n"
        "bilinearly reconstructed SH basis functions (3 and 6 bands) per spherical\n"
        "parameterization against the total texel count. The results do not depend on\n"
        "--threads.");
    // param::reconstruction_directions holds 56 bytes per point at its peak (a 32-byte sort key
    // and direction, then 24 bytes of output), so the limit is set where that is 5.6 GB.
    add_integer(app, "--points", o->points, 1, 100000000, "random directions", "N",
                "56 bytes of memory per point, 5.6 GB at the limit");
    add_path(app, "--json", o->json_path, "write the results as JSON (tools/plot/plot_params.py)");
    add_path(app, "--csv", o->csv_path, "write the results as CSV");
    add_integer(app, "--threads", o->threads, 1, 256,
                "worker threads (default: hardware concurrency)", "T");
    add_integer(app, "--seed", o->seed, 0, std::numeric_limits<long long>::max(), "random seed",
                "S");
    add_integer(app, "--subtexel-bits", o->bits, 0, 24,
                "quantise filter weights to B bits as GPUs do (8 on current GPUs; 0: exact)", "B");
    return [o] { return run_params(*o); };
}

}  // namespace sphbasis::cli
