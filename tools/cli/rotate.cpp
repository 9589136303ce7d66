// sphbasis CLI: `sphbasis rotate --bands N --quat W,X,Y,Z --coeffs C0,C1,...`
//
// Rotates a real SH coefficient vector (this library's convention: no Condon-Shortley phase,
// ACN order, N bands = N^2 coefficients) by the rotation of the quaternion (w, x, y, z): the
// rotated function is g(v) = f(R^T v), so a lobe at direction d moves to R d
// (ops/sh_rotation.hpp). A non-unit quaternion is normalised; a zero one is an error. Prints one
// JSON line, numbers with 17 significant digits, "quat" echoing the input:
//   $ sphbasis rotate --bands 2 --quat 0.70710678118654752,0,0,0.70710678118654752 --coeffs 1,0,0,1
//   {"bands":2,"quat":[0.70710678118654757,0,0,0.70710678118654757],"coeffs":[1,1,0,0]}
// Both `--bands 3` and `--bands=3` work, and lists may hold negative numbers (`--coeffs -1,2`).
//
// `--coeffs -` reads the coefficients from standard input (a command line holds only about 81
// bands of them), in either form:
//   - numbers of the CLI's grammar separated by spaces, tabs, commas or newlines, over any
//     number of lines ('#' lines and blank lines skipped), or
//   - one JSON line: an array of numbers, or an object with a "coeffs" array, such as rotate's
//     own output (its "bands", if present, must equal --bands), so rotations chain in a pipe:
//       sphbasis rotate --bands 100 --quat ... --coeffs - < c.txt |
//           sphbasis rotate --bands 100 --quat ... --coeffs -
// A line may be at most 1 MiB + 32 bytes per expected coefficient long (a number as this tool
// writes it takes at most 25 bytes with its comma); more numbers than N^2 stop the reading.
// Bad input (missing or repeated options, a wrong number of coefficients, non-numbers, a zero
// quaternion, bands outside 1..8192) exits with status 2 and a one-line message.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "../support/json.hpp"
#include "../support/stdout_check.hpp"
#include "cli.hpp"
#include "sphbasis/ops/sh_rotation.hpp"

namespace sphbasis::cli {

namespace {

struct RotateOptions {
    long long bands = 0;
    std::string quat, coeffs;
};

/// The coefficients on standard input (see the file comment); at most `want` of them.
std::vector<double> read_coeffs(long long bands, std::size_t want) {
    const std::size_t max_line = max_line_bytes + 32 * want;
    std::vector<double> c;
    std::string text;
    long lineno = 0;
    bool json = false;
    while (read_line(stdin, text, lineno, max_line)) {
        const auto first = text.find_first_not_of(" \t\r");
        if (first == std::string::npos || text[first] == '#') continue;
        const std::string where = "standard input line " + std::to_string(lineno);
        if (json) throw UsageError(where + ": expected nothing after the JSON line");
        if (text[first] == '[' || text[first] == '{') {
            if (!c.empty()) throw UsageError(where + ": expected numbers, not JSON, after numbers");
            json = true;
            Json j = Json::parse(text, nullptr, false);
            if (j.is_discarded()) throw UsageError(where + ": malformed JSON");
            if (j.is_object()) {
                if (!j.contains("coeffs") || !j["coeffs"].is_array())
                    throw UsageError(where + ": expected a JSON object with a \"coeffs\" array");
                if (j.contains("bands") && j["bands"] != Json(bands))
                    throw UsageError(where + ": the JSON line has \"bands\":" + j["bands"].dump() +
                                     ", expected " + std::to_string(bands) + " (--bands)");
                j = j["coeffs"];
            }
            if (!j.is_array())
                throw UsageError(where + ": expected a JSON array of numbers or an object");
            for (const auto& v : j) {
                if (!v.is_number() || !std::isfinite(v.get<double>()))
                    throw UsageError(where + ": expected finite numbers in the JSON array, got " +
                                     v.dump().substr(0, 40));
                c.push_back(v.get<double>());
            }
            continue;
        }
        std::size_t i = 0;
        while (i < text.size()) {
            const auto a = text.find_first_not_of(" \t\r,", i);
            if (a == std::string::npos) break;
            const auto b = std::min(text.size(), text.find_first_of(" \t\r,", a));
            if (c.size() == want)
                throw UsageError("--coeffs -: expected N^2 = " + std::to_string(want) +
                                 " coefficients for --bands " + std::to_string(bands) +
                                 ", got more (" + where + ")");
            c.push_back(to_real(text.substr(a, b - a), where));
            i = b;
        }
    }
    return c;
}

int run_rotate(const RotateOptions& o) {
    const long long bands = o.bands;
    const std::vector<double> q = to_reals(o.quat, "--quat");
    if (q.size() != 4)
        throw UsageError("--quat: expected four numbers W,X,Y,Z, got " + std::to_string(q.size()));
    const double big = std::max(std::max(std::fabs(q[0]), std::fabs(q[1])),
                                std::max(std::fabs(q[2]), std::fabs(q[3])));
    if (!(big > 0)) throw UsageError("--quat: expected a non-zero quaternion");
    const std::size_t want = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
    std::vector<double> c =
        o.coeffs == "-" ? read_coeffs(bands, want) : to_reals(o.coeffs, "--coeffs");
    if (c.size() != want)
        throw UsageError("--coeffs: expected N^2 = " + std::to_string(want) +
                         " coefficients for --bands " + std::to_string(bands) + ", got " +
                         std::to_string(c.size()));

    // Scale by the largest component first so that tiny or huge quaternions normalise cleanly.
    const int n = static_cast<int>(bands);
    try {
        sh::rotate_quaternion(n, q[0] / big, q[1] / big, q[2] / big, q[3] / big, c.data(),
                              c.data());
    } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
    }
    const Json out = {{"bands", n}, {"quat", q}, {"coeffs", c}};
    std::cout << dump_json(out) << '\n';
    return 0;
}

}  // namespace

Run setup_rotate(CLI::App& app) {
    auto o = std::make_shared<RotateOptions>();
    app.footer(
        "Rotate N^2 real SH coefficients (no Condon-Shortley phase, ACN order) by a quaternion\n"
        "(normalised if not unit); prints {\"bands\":N,\"quat\":[...],\"coeffs\":[...]}.\n"
        "--coeffs - reads them from standard input: numbers separated by spaces, commas or\n"
        "newlines, or one JSON line (an array, or an object with \"coeffs\": rotate's output).");
    add_integer(app, "--bands", o->bands, 1, sh::max_bands, "number of bands N")
        ->required()
        ->default_str("");
    app.add_option("--quat", o->quat, "the rotation as a quaternion")
        ->type_name("W,X,Y,Z")
        ->required();
    app.add_option("--coeffs", o->coeffs, "the N^2 coefficients, or '-' for standard input")
        ->type_name("C0,C1,...")
        ->required();
    return [o] { return run_rotate(*o); };
}

}  // namespace sphbasis::cli
