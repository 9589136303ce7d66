// sphbasis CLI: `sphbasis eval --basis NAME (--coeffs N | --lm L,M) (--dir X,Y,Z ... | --dirs -)`
//
// Prints one JSON object per direction per line:
//   {"basis":"sh","dir":[x,y,z],"values":[...]}
// with values to 17 significant digits (format_real: the output format is a contract). "dir"
// echoes the input; the basis is evaluated at the normalised direction (scaled by its largest
// component first, so 1e200,0,0 and 1e-300,0,0 are +x; zero or non-finite input is rejected
// here rather than mapped to the pole, since a command-line user wants to hear about it).
//
// --lm L,M: one function. L runs over the degrees of the basis's largest size (sh: 0..8191,
// hsh and makhotkin: 0..2047, zernike: n = 0..2047), said in the message when L is outside.
// For sh the one value comes from sh::eval_lm (O(L) time and memory); for the other bases
// the prefix of (L+1)^2 functions is evaluated (at most 4M values, 32 MB).
//
// --dirs - reads directions from standard input, one per line, each either `x y z` (numbers of
// the CLI's grammar, support/args.hpp, separated by spaces, tabs or commas) or a JSON line: an
// array [x,y,z] or an object with a "dir" array (so eval's own output can be fed back). Blank
// lines and lines starting with '#' are skipped. A line may be at most 1 MiB long (a longer
// one, e.g. `< /dev/zero`, is an error at once, not after reading it all); the last line needs
// no '\n'. A bad line stops the run with "standard input line N: ..." and status 2; standard
// output is checked after every line written, so a full disk or a closed pipe stops the run
// within one buffer (exit status 1).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <sphbasis/basis/registry.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/json.hpp"
#include "../support/stdout_check.hpp"
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
    const double big = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    if (!(big > 0) || !std::isfinite(big))
        throw UsageError(where + ": expected a non-zero finite direction");
    return d;
}

/// d scaled by its largest component (the evaluators normalise; this keeps d*d finite).
std::vector<double> scaled(const std::vector<double>& d) {
    const double big = std::max({std::fabs(d[0]), std::fabs(d[1]), std::fabs(d[2])});
    return {d[0] / big, d[1] / big, d[2] / big};
}

/// One direction line of standard input (see the file comment).
std::vector<double> parse_direction_line(const std::string& text, std::size_t first,
                                         const std::string& where) {
    std::vector<double> d;
    if (text[first] == '[' || text[first] == '{') {
        Json j = Json::parse(text, nullptr, false);
        if (j.is_discarded())
            throw UsageError(where + ": expected 'x y z' or a JSON line, got malformed JSON");
        if (j.is_object()) {
            if (!j.contains("dir"))
                throw UsageError(where + ": expected a JSON object with a \"dir\" array");
            j = j["dir"];
        }
        if (!j.is_array() || j.size() != 3)
            throw UsageError(where + ": expected a JSON array of three numbers [x,y,z]");
        for (const auto& v : j) {
            if (!v.is_number() || !std::isfinite(v.get<double>()))
                throw UsageError(where + ": expected a JSON array of three finite numbers");
            d.push_back(v.get<double>());
        }
        return d;
    }
    std::size_t i = 0;
    while (i < text.size()) {
        const auto a = text.find_first_not_of(" \t\r,", i);
        if (a == std::string::npos) break;
        const auto b = std::min(text.size(), text.find_first_of(" \t\r,", a));
        if (d.size() == 3) throw UsageError(where + ": expected 'x y z', got more numbers");
        d.push_back(to_real(text.substr(a, b - a), where));
        i = b;
    }
    if (d.size() != 3) throw UsageError(where + ": expected 'x y z'");
    return d;
}

/// The largest degree L of a basis with (l, m) labels: the largest L whose (L+1)-band prefix is
/// a valid size (valid sizes are a prefix of the label order). -1 if it has no labels. Only L
/// up to 46339 are tried, where lm_index's int arithmetic holds.
long long max_degree(const BasisInfo& b) {
    auto fits = [&b](int l) {
        try {
            return b.valid_count(b.lm_index(l, l).second);
        } catch (const std::invalid_argument&) {
            return false;
        }
    };
    if (!fits(0)) return -1;
    int lo = 0, hi = 46339;  // fits(lo); find the last L that fits
    if (fits(hi)) return hi;
    while (hi - lo > 1) {
        const int mid = lo + (hi - lo) / 2;
        (fits(mid) ? lo : hi) = mid;
    }
    return lo;
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
        const auto comma = o.lm.find(',');
        if (comma == std::string::npos || o.lm.find(',', comma + 1) != std::string::npos)
            throw UsageError("--lm: expected two integers L,M, got '" + quote_input(o.lm) + "'");
        const long long l = to_integer(o.lm.substr(0, comma), "--lm");
        const long long m = to_integer(o.lm.substr(comma + 1), "--lm");
        // The range first, stated in the message, before any size is computed from L.
        const long long lmax = max_degree(*basis);
        if (lmax >= 0 && (l < 0 || l > lmax))
            throw UsageError("--lm: expected 0 <= L <= " + std::to_string(lmax) + " for basis '" +
                             basis->name + "' (its sizes are " + basis->count_rule() +
                             " functions), got L = " + std::to_string(l));
        if (lmax >= 0 && (m < -l || m > l))
            throw UsageError("--lm: expected -L <= M <= L, got L = " + std::to_string(l) +
                             ", M = " + std::to_string(m));
        lm_l = static_cast<int>(l);
        lm_m = static_cast<int>(m);
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

    // One SH function of any degree: sh::eval_lm, O(l) time and memory, no table of (l+1)^2.
    const bool sh_single = pick >= 0 && std::string(basis->name) == "sh";
    std::vector<double> values(sh_single ? 0 : static_cast<std::size_t>(size));
    Json line = {{"basis", basis->name}, {"dir", Json::array()}, {"values", Json::array()}};
    auto emit = [&](const std::vector<double>& d) {
        line["dir"] = {d[0], d[1], d[2]};
        Json& out = line["values"];
        out = Json::array();
        const std::vector<double> u = scaled(d);
        if (sh_single) {
            out.push_back(sh::eval_lm(lm_l, lm_m, u[0], u[1], u[2]));
        } else {
            basis->eval_d(size, u[0], u[1], u[2], values.data());
            if (pick >= 0)
                out.push_back(values[static_cast<std::size_t>(pick)]);
            else
                for (int k = 0; k < size; ++k) out.push_back(values[static_cast<std::size_t>(k)]);
        }
        std::cout << dump_json(line) << '\n';
        check_stdout();  // a failed flush stops the run here, not after all the input
    };
    if (!from_stdin) {
        for (const auto& d : dirs) emit(d);
    } else {
        std::string text;
        long lineno = 0;
        while (read_line(stdin, text, lineno, max_line_bytes)) {
            const auto first = text.find_first_not_of(" \t\r");
            if (first == std::string::npos || text[first] == '#') continue;
            const std::string where = "standard input line " + std::to_string(lineno);
            emit(check_direction(parse_direction_line(text, first, where), where));
        }
    }
    return 0;
}

}  // namespace

Run setup_eval(CLI::App& app) {
    auto o = std::make_shared<EvalOptions>();
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
    app.footer(
        "Evaluate a basis at directions; prints one JSON line per direction,\n"
        "{\"basis\":NAME,\"dir\":[x,y,z],\"values\":[...]}, numbers with 17 significant digits.\n"
        "--dirs - reads one direction a line: 'x y z' (or x,y,z), [x,y,z] or a JSON object with\n"
        "\"dir\" (eval's own output); '#' lines and blank lines are skipped; at most 1 MiB a "
        "line.\n"
        "--lm L,M: L within the degrees of the basis's largest size (sh: 0..8191).");
    return [o] { return run_eval(*o); };
}

}  // namespace sphbasis::cli
