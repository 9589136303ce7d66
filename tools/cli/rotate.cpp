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
#include "cli.hpp"
#include "sphbasis/ops/sh_rotation.hpp"

namespace sphbasis::cli {

namespace {

struct RotateOptions {
    long long bands = 0;
    std::string quat, coeffs;
};

int run_rotate(const RotateOptions& o) {
    const long long bands = o.bands;
    const std::vector<double> q = to_reals(o.quat, "--quat");
    if (q.size() != 4)
        throw UsageError("--quat: expected four numbers W,X,Y,Z, got " + std::to_string(q.size()));
    const double big = std::max(std::max(std::fabs(q[0]), std::fabs(q[1])),
                                std::max(std::fabs(q[2]), std::fabs(q[3])));
    if (!(big > 0)) throw UsageError("--quat: expected a non-zero quaternion");
    std::vector<double> c = to_reals(o.coeffs, "--coeffs");
    const std::size_t want = static_cast<std::size_t>(bands) * static_cast<std::size_t>(bands);
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
        "(normalised if not unit); prints {\"bands\":N,\"quat\":[...],\"coeffs\":[...]}.");
    add_integer(app, "--bands", o->bands, 1, sh::max_bands, "number of bands N")
        ->required()
        ->default_str("");
    app.add_option("--quat", o->quat, "the rotation as a quaternion")
        ->type_name("W,X,Y,Z")
        ->required();
    app.add_option("--coeffs", o->coeffs, "the N^2 coefficients")
        ->type_name("C0,C1,...")
        ->required();
    return [o] { return run_rotate(*o); };
}

}  // namespace sphbasis::cli
