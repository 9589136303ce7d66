// sphbasis CLI: `sphbasis normal-basis [--bands 3] [--json PATH]`.
//
// The SVD normal basis of normal-mapped PRT (ops/normal_basis.hpp; Sloan, Lehtinen and Kautz,
// "Precomputed Radiance Transfer: Theory and Practice", SIGGRAPH 2005 course, "Normal Mapping
// for PRT"): the matrix A whose rows are normals over the hemisphere and whose columns are the
// cosine-convolved SH lighting functions of --bands bands, its SVD, and the percent of the
// energy (sum of squared singular values) kept by the first M = 1..bands^2 singular values, for
// the lighting clamped to the geometric hemisphere before the convolution or not, with the
// normals weighted uniformly or by cosine. Prints a table, e.g. for 3 bands
//     M  clamped/uniform  clamped/cosine  unclamped/uniform  unclamped/cosine
//     4            98.35           99.11              93.92             96.29
// and with --json PATH writes
//     {"clamped": {"uniform": [...], "cosine": [...]}, "unclamped": {"uniform": [...],
//      "cosine": [...]}}
// (bands^2 numbers each, percent). Bad options exit with status 2 and one line.
#include "sphbasis/ops/normal_basis.hpp"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "../support/json.hpp"
#include "../support/output_file.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {
struct NormalBasisOptions {
    long long bands = 3;
    std::string json_path;
};
}  // namespace

Run setup_normal_basis(CLI::App& app) {
    auto o = std::make_shared<NormalBasisOptions>();
    app.footer(
        "Print the percent of energy (sum of squared singular values) kept by the first M\n"
        "singular values of the normal matrix of normal-mapped PRT (rows: normals over the\n"
        "hemisphere, columns: cosine-convolved SH lighting functions), for the lighting clamped\n"
        "to the hemisphere or not and normals weighted uniformly or by cosine.");
    add_integer(app, "--bands", o->bands, 1, 8, "SH bands of the lighting (columns: bands^2)", "N");
    add_path(app, "--json", o->json_path,
             "write {\"clamped\": {\"uniform\": [...], \"cosine\": [...]}, \"unclamped\": {...}}");
    return [o] {
        OutputFiles out;  // checked and staged before the work (support/output_file.hpp)
        if (!o->json_path.empty()) out.declare(o->json_path);
        out.prepare();
        const int bands = static_cast<int>(o->bands);
        std::vector<double> e[2][2];  // [clamped][cosine]
        for (int c = 0; c < 2; ++c)
            for (int w = 0; w < 2; ++w) {
                NormalBasisSettings s;
                s.bands = bands;
                s.clamped = c == 0;
                s.weighting = w == 0 ? NormalWeighting::uniform : NormalWeighting::cosine;
                e[c][w] = normal_basis_energy(s);
            }
        std::printf(
            "normal basis: %d bands, %d lighting functions; percent of the energy kept by the "
            "first M singular values\n",
            bands, bands * bands);
        std::printf("%3s  %15s  %14s  %17s  %16s\n", "M", "clamped/uniform", "clamped/cosine",
                    "unclamped/uniform", "unclamped/cosine");
        for (std::size_t m = 0; m < e[0][0].size(); ++m)
            std::printf("%3zu  %15.2f  %14.2f  %17.2f  %16.2f\n", m + 1, e[0][0][m], e[0][1][m],
                        e[1][0][m], e[1][1][m]);
        if (!o->json_path.empty()) {
            Json j;
            const char* names[2] = {"clamped", "unclamped"};
            for (int c = 0; c < 2; ++c) {
                Json v;
                v["uniform"] = e[c][0];
                v["cosine"] = e[c][1];
                j[names[c]] = v;
            }
            out.add(o->json_path, dump_json(j) + "\n");
        }
        out.commit();
        return 0;
    };
}

}  // namespace sphbasis::cli
