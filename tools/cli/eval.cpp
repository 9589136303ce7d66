// sphbasis CLI: `sphbasis eval --basis NAME (--coeffs N | --lm L,M) (--dir X,Y,Z ... | --dirs -)`
//
// Prints one JSON object per direction per line:
//   {"basis":"sh","dir":[x,y,z],"values":[...]}
// with values to 17 significant digits. "dir" echoes the input; the basis is evaluated at the
// normalised direction (zero or non-finite input is rejected here rather than mapped to the
// pole, since a command-line user wants to hear about it). --dirs - reads `x y z` lines from
// standard input (blank lines and lines starting with '#' are skipped).
#include <cmath>
#include <iostream>
#include <sphbasis/basis/registry.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli.hpp"

namespace sphbasis::cli {

namespace {

std::vector<double> check_direction(std::vector<double> d, const std::string& where) {
    if (d.size() != 3) throw UsageError(where + ": expected three components X,Y,Z");
    const double r2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(r2 > 0) || !std::isfinite(r2))
        throw UsageError(where + ": expected a non-zero finite direction");
    return d;
}

}  // namespace

int cmd_eval(const Args& args) {
    Options o(args, {"--basis", "--coeffs", "--lm", "--dir", "--dirs"});
    if (!o.has("--basis")) throw UsageError("--basis NAME is required");
    const BasisInfo* basis = nullptr;
    try {
        basis = &find_basis(o.get("--basis"));
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    if (o.has("--coeffs") == o.has("--lm"))
        throw UsageError("give exactly one of --coeffs N or --lm L,M");

    int size = 0, pick = -1;
    int lm_l = 0, lm_m = 0;
    if (o.has("--coeffs")) {
        const long long n = parse_int(o.get("--coeffs"), "--coeffs");
        if (n < 1 || n > 1000000000 || !basis->valid_count(static_cast<int>(n)))
            throw UsageError(std::string("--coeffs: basis '") + basis->name + "' expects " +
                             basis->count_rule() + " functions, got " + o.get("--coeffs"));
        size = static_cast<int>(n);
    } else {
        const auto v = parse_doubles(o.get("--lm"), "--lm");
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

    std::vector<std::vector<double>> dirs;
    for (const auto& s : o.values("--dir"))
        dirs.push_back(check_direction(parse_doubles(s, "--dir"), "--dir"));
    for (const auto& s : o.positional()) {
        // `--dir X,Y,Z X,Y,Z ...`: further directions follow as plain arguments.
        if (!o.has("--dir")) throw UsageError("unexpected argument '" + s + "'");
        dirs.push_back(check_direction(parse_doubles(s, "--dir"), "--dir"));
    }
    const bool from_stdin = o.has("--dirs");
    if (from_stdin && o.get("--dirs") != "-")
        throw UsageError("--dirs: only '-' (standard input) is supported");
    if (from_stdin == o.has("--dir"))
        throw UsageError("give directions with --dir X,Y,Z or --dirs -");

    const bool sh_single = pick >= 0 && std::string(basis->name) == "sh";
    std::vector<double> values(static_cast<std::size_t>(size));
    std::string out;
    auto emit = [&](const std::vector<double>& d) {
        out = std::string("{\"basis\":\"") + basis->name + "\",\"dir\":[" + json_number(d[0]) +
              "," + json_number(d[1]) + "," + json_number(d[2]) + "],\"values\":[";
        if (sh_single) {
            // One SH function of any degree: O(l) column recurrence, no n^2 table.
            out += json_number(sh::eval_lm(lm_l, lm_m, d[0], d[1], d[2]));
        } else {
            basis->eval_d(size, d[0], d[1], d[2], values.data());
            if (pick >= 0) {
                out += json_number(values[static_cast<std::size_t>(pick)]);
            } else {
                for (int k = 0; k < size; ++k)
                    out += (k ? "," : "") + json_number(values[static_cast<std::size_t>(k)]);
            }
        }
        out += "]}\n";
        std::cout << out;
    };
    if (!from_stdin) {
        for (const auto& d : dirs) emit(d);
    } else {
        std::string line;
        long lineno = 0;
        while (std::getline(std::cin, line)) {
            ++lineno;
            const auto first = line.find_first_not_of(" \t\r");
            if (first == std::string::npos || line[first] == '#') continue;
            std::istringstream is(line);
            std::vector<std::string> tok;
            std::string t;
            while (is >> t) tok.push_back(t);
            const std::string where = "standard input line " + std::to_string(lineno);
            if (tok.size() != 3) throw UsageError(where + ": expected 'x y z'");
            std::vector<double> d;
            for (const auto& s : tok) d.push_back(parse_double(s, where));
            emit(check_direction(d, where));
        }
    }
    return 0;
}

}  // namespace sphbasis::cli
