// sphbasis CLI: `sphbasis params [--points N] [--json PATH] [--csv PATH] [--threads T]
//                                [--seed S] [--subtexel-bits B]`
//
// The experiment of seed 000's appendix A (Iwanicki and Sloan): for each spherical
// parameterization and a range of resolutions, tabulate every real SH basis function of 6
// bands (36 functions; the first 9 are the 3-band set) at the texel centres, reconstruct them
// by hardware bilinear filtering at N random directions (uniform on the sphere, default one
// million), and report the mean squared error against the exact values, averaged over the
// functions and the directions, as a function of the total number of texels.
//
// Parameterizations (include/sphbasis/param/): dual orthographic and dual paraboloid through
// the concentric map, shrunk so the equator lies on the outer ring of texel centres; cube maps
// filtered as DX9 (clamped per face) and DX10+ (seamless across faces); octahedral with
// clamp-to-edge and with seamless (mirrored-border) filtering; lat-long. Resolutions are chosen
// so that every parameterization is sampled near the same total texel counts, 96 * 2^k for
// k = 0..10 (96 to 98304 texels). Tables are float, as a GPU stores them; filtering weights
// are exact unless --subtexel-bits gives the hardware's fixed-point precision (8 on current
// GPUs). Directions are sorted along a space-filling curve before the lookups (the MSE does
// not depend on the order; the caches do).
//
// Output: a table on standard output, --json PATH (read by tools/plot/plot_params.py) and
// --csv PATH with one row per (parameterization, resolution).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <functional>
#include <numeric>
#include <random>
#include <sphbasis/basis/sh.hpp>
#include <sphbasis/param/cubemap.hpp>
#include <sphbasis/param/dual_orthographic.hpp>
#include <sphbasis/param/dual_paraboloid.hpp>
#include <sphbasis/param/latlong.hpp>
#include <sphbasis/param/octahedral.hpp>
#include <string>
#include <thread>
#include <vector>

#include "cli.hpp"

namespace sphbasis::cli {

namespace {

constexpr int kBands = 6;
constexpr int kFuncs = kBands * kBands;  // 36; the first 9 are the 3-band functions
constexpr int kFuncs3 = 9;

struct Points {
    std::vector<double> x, y, z;
    std::size_t size() const { return x.size(); }
};

// Uniform directions (z = 1 - 2u, phi = 2 pi v), sorted by the Morton code of their
// octahedral coordinates so that consecutive lookups touch nearby texels.
Points make_points(std::size_t count, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    struct P {
        std::uint64_t key;
        double x, y, z;
    };
    std::vector<P> pts(count);
    auto spread = [](std::uint64_t v) {  // 16 bits -> every other of 32 bits
        v &= 0xffff;
        v = (v | (v << 8)) & 0x00ff00ff;
        v = (v | (v << 4)) & 0x0f0f0f0f;
        v = (v | (v << 2)) & 0x33333333;
        v = (v | (v << 1)) & 0x55555555;
        return v;
    };
    for (auto& p : pts) {
        const double z = 1.0 - 2.0 * uni(rng);
        const double phi = 6.2831853071795865 * uni(rng);  // 2 pi
        const double r = std::sqrt(std::fmax(0.0, 1.0 - z * z));
        p.x = r * std::cos(phi);
        p.y = r * std::sin(phi);
        p.z = z;
        const auto s = param::octahedral_to_square(p.x, p.y, p.z);
        const auto qu = static_cast<std::uint64_t>(std::fmin(s.x * 65536.0, 65535.0));
        const auto qv = static_cast<std::uint64_t>(std::fmin(s.y * 65536.0, 65535.0));
        p.key = spread(qu) | (spread(qv) << 1);
    }
    std::sort(pts.begin(), pts.end(), [](const P& a, const P& b) { return a.key < b.key; });
    Points out;
    out.x.resize(count);
    out.y.resize(count);
    out.z.resize(count);
    for (std::size_t i = 0; i < count; ++i) {
        out.x[i] = pts[i].x;
        out.y[i] = pts[i].y;
        out.z[i] = pts[i].z;
    }
    return out;
}

struct Errors {
    double sum3 = 0, sum6 = 0;  // sums of squared errors over the 9 and the 36 functions
};

// Squared reconstruction errors over points [begin, end) for one parameterization and table.
template <class P>
Errors accumulate(const P& p, const std::vector<float>& table, const Points& pts, std::size_t begin,
                  std::size_t end) {
    Errors e;
    float rec[kFuncs];
    double exact[kFuncs];
    for (std::size_t i = begin; i < end; ++i) {
        const double x = pts.x[i], y = pts.y[i], z = pts.z[i];
        param::reconstruct(table.data(), kFuncs, p.footprint(x, y, z), rec);
        sh::eval<kBands>(x, y, z, exact);
        double s3 = 0, s6 = 0;
        for (int k = 0; k < kFuncs3; ++k) {
            const double d = double(rec[k]) - exact[k];
            s3 += d * d;
        }
        s6 = s3;
        for (int k = kFuncs3; k < kFuncs; ++k) {
            const double d = double(rec[k]) - exact[k];
            s6 += d * d;
        }
        e.sum3 += s3;
        e.sum6 += s6;
    }
    return e;
}

struct Result {
    std::string param;
    int resolution = 0;
    std::size_t texels = 0;
    double mse3 = 0, mse6 = 0;
};

template <class P>
Result run(const std::string& name, const P& p, const Points& pts, int threads) {
    const std::vector<float> table =
        param::tabulate<float>(p, kFuncs, [](double x, double y, double z, float* out) {
            double v[kFuncs];
            sh::eval<kBands>(x, y, z, v);
            for (int k = 0; k < kFuncs; ++k) out[k] = static_cast<float>(v[k]);
        });
    const std::size_t n = pts.size();
    std::vector<Errors> part(static_cast<std::size_t>(threads));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t) {
        const std::size_t b = n * static_cast<std::size_t>(t) / static_cast<std::size_t>(threads);
        const std::size_t e =
            n * static_cast<std::size_t>(t + 1) / static_cast<std::size_t>(threads);
        pool.emplace_back(
            [&, t, b, e] { part[static_cast<std::size_t>(t)] = accumulate(p, table, pts, b, e); });
    }
    for (auto& th : pool) th.join();
    Errors sum;
    for (const auto& e : part) {
        sum.sum3 += e.sum3;
        sum.sum6 += e.sum6;
    }
    Result r;
    r.param = name;
    r.resolution = p.resolution();
    r.texels = p.texel_count();
    r.mse3 = sum.sum3 / (double(kFuncs3) * double(n));
    r.mse6 = sum.sum6 / (double(kFuncs) * double(n));
    return r;
}

struct Param {
    const char* name;
    const char* label;
    int texels_per_n2;  // total texels = texels_per_n2 * n^2
    int min_n;
    std::function<Result(int n, int bits, const Points&, int threads)> run;
};

std::vector<Param> parameterizations() {
    using namespace param;
    return {
        {"dual_orthographic", "dual orthographic", 2, 2,
         [](int n, int b, const Points& p, int t) {
             return run("dual_orthographic", DualOrthographic<double>(n, b), p, t);
         }},
        {"dual_paraboloid", "dual paraboloid", 2, 2,
         [](int n, int b, const Points& p, int t) {
             return run("dual_paraboloid", DualParaboloid<double>(n, b), p, t);
         }},
        {"cube_dx9", "cube map, DX9 (clamped per face)", 6, 1,
         [](int n, int b, const Points& p, int t) {
             return run("cube_dx9", CubeMap<double>(n, CubeFilter::dx9_clamped, b), p, t);
         }},
        {"cube_dx10", "cube map, DX10 (seamless)", 6, 1,
         [](int n, int b, const Points& p, int t) {
             return run("cube_dx10", CubeMap<double>(n, CubeFilter::dx10_seamless, b), p, t);
         }},
        {"octahedral_clamp", "octahedral, clamp-to-edge", 1, 1,
         [](int n, int b, const Points& p, int t) {
             return run("octahedral_clamp", Octahedral<double>(n, OctahedralFilter::clamp, b), p,
                        t);
         }},
        {"octahedral_seamless", "octahedral, seamless border", 1, 1,
         [](int n, int b, const Points& p, int t) {
             return run("octahedral_seamless", Octahedral<double>(n, OctahedralFilter::seamless, b),
                        p, t);
         }},
        {"latlong", "lat-long (2n x n)", 2, 1,
         [](int n, int b, const Points& p, int t) {
             return run("latlong", LatLong<double>(n, b), p, t);
         }},
    };
}

constexpr int kTargets = 11;  // total texel targets 96 * 2^k, k = 0..10

int resolution_for(const Param& p, int k) {
    const double target = 96.0 * std::ldexp(1.0, k);
    const int n = static_cast<int>(std::lround(std::sqrt(target / p.texels_per_n2)));
    return std::max(n, p.min_n);
}

void usage_text() {
    std::printf(
        "usage: sphbasis params [--points N] [--json PATH] [--csv PATH] [--threads T]\n"
        "                       [--seed S] [--subtexel-bits B]\n"
        "Seed 000's appendix experiment: MSE of bilinearly reconstructed SH basis functions\n"
        "(3 and 6 bands) per spherical parameterization against the total texel count.\n"
        "  --points N         random directions (default 1000000)\n"
        "  --json PATH        write the results as JSON (for tools/plot/plot_params.py)\n"
        "  --csv PATH         write the results as CSV\n"
        "  --threads T        worker threads (default: hardware concurrency)\n"
        "  --seed S           random seed (default 1)\n"
        "  --subtexel-bits B  quantise filter weights to B bits as GPUs do (default 0: exact)\n");
}

}  // namespace

int cmd_params(const Args& args) {
    Options o(args, {"--points", "--json", "--csv", "--threads", "--seed", "--subtexel-bits"},
              {"--help"});
    if (o.has("--help")) {
        usage_text();
        return 0;
    }
    if (!o.positional().empty())
        throw UsageError("unexpected argument '" + o.positional()[0] + "'");
    const long long points = parse_int(o.get("--points", "1000000"), "--points");
    if (points < 1 || points > 1000000000LL)
        throw UsageError("--points: expected 1 <= N <= 1000000000, got " + o.get("--points"));
    const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
    const long long threads = parse_int(o.get("--threads", std::to_string(hw)), "--threads");
    if (threads < 1 || threads > 256)
        throw UsageError("--threads: expected 1 <= T <= 256, got " + o.get("--threads"));
    const long long seed = parse_int(o.get("--seed", "1"), "--seed");
    if (seed < 0) throw UsageError("--seed: expected a non-negative integer");
    const long long bits = parse_int(o.get("--subtexel-bits", "0"), "--subtexel-bits");
    if (bits < 0 || bits > 24)
        throw UsageError("--subtexel-bits: expected 0 <= B <= 24, got " + o.get("--subtexel-bits"));
    const std::string json_path = o.get("--json"), csv_path = o.get("--csv");
    // Open the outputs first so a bad path fails before a minute of work.
    std::ofstream json, csv;
    if (o.has("--json")) {
        json.open(json_path);
        if (!json) throw std::runtime_error("cannot write '" + json_path + "'");
    }
    if (o.has("--csv")) {
        csv.open(csv_path);
        if (!csv) throw std::runtime_error("cannot write '" + csv_path + "'");
    }

    const auto t0 = std::chrono::steady_clock::now();
    const Points pts =
        make_points(static_cast<std::size_t>(points), static_cast<std::uint64_t>(seed));
    const auto params = parameterizations();
    std::vector<Result> results;
    std::printf("%-20s %6s %8s %14s %14s\n", "parameterization", "n", "texels", "MSE 3 bands",
                "MSE 6 bands");
    for (const auto& p : params) {
        for (int k = 0; k < kTargets; ++k) {
            const int n = resolution_for(p, k);
            results.push_back(p.run(n, static_cast<int>(bits), pts, static_cast<int>(threads)));
            const Result& r = results.back();
            std::printf("%-20s %6d %8zu %14.6e %14.6e\n", r.param.c_str(), r.resolution, r.texels,
                        r.mse3, r.mse6);
            std::fflush(stdout);
        }
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Summary: the best parameterization at each texel budget, by interpolating every curve
    // log-log at the budget (the resolutions give only approximately equal texel counts).
    auto mse_at = [&](const std::string& name, double texels, bool six) {
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
    };
    std::printf("\nbest at equal texel count (log-log interpolation):\n");
    for (double budget : {384.0, 1536.0, 6144.0, 24576.0}) {
        for (bool six : {false, true}) {
            std::string best;
            double best_mse = INFINITY;
            for (const auto& p : params) {
                const double m = mse_at(p.name, budget, six);
                if (m < best_mse) best_mse = m, best = p.name;
            }
            const double dx10 = mse_at("cube_dx10", budget, six);
            const double octa = mse_at("octahedral_seamless", budget, six);
            std::printf(
                "  %6.0f texels, %d bands: %-20s MSE %.3e (cube_dx10 %.3e, "
                "octahedral_seamless %.3e)\n",
                budget, six ? 6 : 3, best.c_str(), best_mse, dx10, octa);
        }
    }
    std::printf("\n%lld points, %lld threads, %.1f s\n", points, threads, seconds);

    if (json.is_open()) {
        json << "{\"experiment\":\"params\",\"points\":" << points << ",\"seed\":" << seed
             << ",\"subtexel_bits\":" << bits << ",\"table_type\":\"float\""
             << ",\"seconds\":" << json_number(seconds) << ",\"parameterizations\":[";
        for (std::size_t i = 0; i < params.size(); ++i)
            json << (i ? "," : "") << "{\"name\":\"" << params[i].name << "\",\"label\":\""
                 << params[i].label << "\"}";
        json << "],\"results\":[\n";
        for (std::size_t i = 0; i < results.size(); ++i) {
            const Result& r = results[i];
            json << (i ? ",\n" : "") << "{\"param\":\"" << r.param
                 << "\",\"resolution\":" << r.resolution << ",\"texels\":" << r.texels
                 << ",\"mse_3bands\":" << json_number(r.mse3)
                 << ",\"mse_6bands\":" << json_number(r.mse6) << "}";
        }
        json << "\n]}\n";
        if (!json) throw std::runtime_error("error writing '" + json_path + "'");
    }
    if (csv.is_open()) {
        csv << "param,resolution,texels,mse_3bands,mse_6bands\n";
        for (const auto& r : results)
            csv << r.param << "," << r.resolution << "," << r.texels << "," << json_number(r.mse3)
                << "," << json_number(r.mse6) << "\n";
        if (!csv) throw std::runtime_error("error writing '" + csv_path + "'");
    }
    return 0;
}

}  // namespace sphbasis::cli
