// sphbasis CLI: `sphbasis eval --basis NAME (--coeffs N | --lm L,M) (--dir X,Y,Z ... | --dirs -)`
//
// Prints one JSON object per direction per line:
//   {"basis":"sh","dir":[x,y,z],"values":[...]}
// with values to 17 significant digits (format_real: the output format is a contract). "dir"
// echoes the input; the basis is evaluated at the normalised direction (zero or non-finite input
// is rejected here rather than mapped to the pole, since a command-line user wants to hear
// about it). --dirs - reads `x y z` lines from standard input (blank lines and lines starting
// with '#' are skipped).
#include <CLI/CLI.hpp>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <sphbasis/basis/registry.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/json.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

struct EvalOptions {
    std::string basis, lm, dirs_in;
    long long coeffs = 0;
    std::vector<std::string> dirs;
    CLI::Option *coeffs_opt = nullptr, *lm_opt = nullptr, *dir_opt = nullptr, *dirs_opt = nullptr;
};

std::vector<double> check_direction(std::vector<double> d, const std::string& where) {
    if (d.size() != 3) throw UsageError(where + ": expected three components X,Y,Z");
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(r2 > 0) || !std::isfinite(r2))
        throw UsageError(where + ": expected a non-zero finite direction");
    return d;
}

int run_eval(const EvalOptions& o) {
    const BasisInfo* basis = nullptr;
    try {
        basis = &find_basis(o.basis);
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    const bool has_coeffs = o.coeffs_opt->count() > 0, has_lm = o.lm_opt->count() > 0;
    if (has_coeffs == has_lm) throw UsageError("give exactly one of --coeffs N or --lm L,M");

    int size = 0, pick = -1;
    int lm_l = 0, lm_m = 0;
    if (has_coeffs) {
        const long long n = o.coeffs;
        if (n < 1 || n > 1000000000 || !basis->valid_count(static_cast<int>(n)))
            throw UsageError(std::string("--coeffs: basis '") + basis->name + "' expects " +
                             basis->count_rule() + " functions, got " + std::to_string(n));
        size = static_cast<int>(n);
    } else {
        const auto v = to_reals(o.lm, "--lm");
        if (v.size() != 2 || v[0] != std::floor(v[0]) || v[1] != std::floor(v[1]) ||
            std::fabs(v[0]) > 1e6 || std::fabs(v[1]) > 1e6)
            throw UsageError("--lm: expected two integers L,M");
        lm_l = static_cast<int>(v[0]);
        lm_m = static_cast<int>(v[1]);
        try {
            const auto [index, needed] = basis->lm_index(lm_l, lm_m);
            pick = index;
            size = needed;
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--lm: ") + e.what());
        }
        if (!basis->valid_count(size))
            throw UsageError(std::string("--lm: basis '") + basis->name + "' has no function (" +
                             std::to_string(lm_l) + "," + std::to_string(lm_m) + ")");
    }

    // `--dir X,Y,Z X,Y,Z ...`: CLI11 collects every direction after --dir.
    std::vector<std::vector<double>> dirs;
    for (const auto& s : o.dirs) dirs.push_back(check_direction(to_reals(s, "--dir"), "--dir"));
    const bool from_stdin = o.dirs_opt->count() > 0;
    if (from_stdin && o.dirs_in != "-")
        throw UsageError("--dirs: only '-' (standard input) is supported");
    if (from_stdin == (o.dir_opt->count() > 0))
        throw UsageError("give directions with --dir X,Y,Z or --dirs -");

    const bool sh_single = pick >= 0 && std::string(basis->name) == "sh";
    std::vector<double> values(static_cast<std::size_t>(size));
    Json line = {{"basis", basis->name}, {"dir", Json::array()}, {"values", Json::array()}};
    auto emit = [&](const std::vector<double>& d) {
        line["dir"] = {d[0], d[1], d[2]};
        Json& out = line["values"];
        out = Json::array();
        if (sh_single) {
            // One SH function of any degree: O(l) column recurrence, no n^2 table.
            out.push_back(sh::eval_lm(lm_l, lm_m, d[0], d[1], d[2]));
        } else {
            basis->eval_d(size, d[0], d[1], d[2], values.data());
            if (pick >= 0)
                out.push_back(values[static_cast<std::size_t>(pick)]);
            else
                for (int k = 0; k < size; ++k) out.push_back(values[static_cast<std::size_t>(k)]);
        }
        std::cout << dump_json(line) << '\n';
    };
    if (!from_stdin) {
        for (const auto& d : dirs) emit(d);
    } else {
        std::string text;
        long lineno = 0;
        while (std::getline(std::cin, text)) {
            ++lineno;
            const auto first = text.find_first_not_of(" \t\r");
            if (first == std::string::npos || text[first] == '#') continue;
            std::istringstream is(text);
            std::vector<std::string> tok;
            std::string t;
            while (is >> t) tok.push_back(t);
            const std::string where = "standard input line " + std::to_string(lineno);
            if (tok.size() != 3) throw UsageError(where + ": expected 'x y z'");
            std::vector<double> d;
            for (const auto& s : tok) d.push_back(to_real(s, where));
            emit(check_direction(d, where));
        }
    }
    return 0;
}

}  // namespace

Run setup_eval(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
    app.footer(
        "Evaluate a basis at directions; prints one JSON line per direction,\n"
        "{\"basis\":NAME,\"dir\":[x,y,z],\"values\":[...]}, numbers with 17 significant digits.");
    app.add_option("--basis", o->basis, "the basis: sh, hsh, makhotkin, zernike, hbasis, ...")
        ->type_name("NAME")
        ->required();
    o->coeffs_opt = add_integer(app, "--coeffs", o->coeffs, std::numeric_limits<long long>::min(),
                                std::numeric_limits<long long>::max(),
                                "evaluate the first N functions (a size the basis has)");
    o->coeffs_opt->default_str("");
    o->lm_opt = app.add_option("--lm", o->lm, "evaluate the one function of degree L, order M")
                    ->type_name("L,M");
    o->dir_opt = app.add_option("--dir", o->dirs, "one or more directions (any non-zero length)")
                     ->type_name("X,Y,Z");
    o->dirs_opt =
        app.add_option("--dirs", o->dirs_in, "'-': read 'x y z' lines from standard input")
            ->type_name("-");
    return [o] { return run_eval(*o); };
}

}  // namespace sphbasis::cli
