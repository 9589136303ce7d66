// sphbasis CLI: `sphbasis gaunt L1 M1 L2 M2 L3 M3`.
//
// Prints the real Gaunt (SH tripling) coefficient Gamma = integral of y_L1M1 y_L2M2 y_L3M3 over
// the sphere (this library's real SH: no Condon-Shortley phase, y_1-1 = +0.4886 y) with 17
// significant digits on one line, e.g.
//     $ sphbasis gaunt 1 1 1 -1 2 -2
//     0.21850968611841581
// Negative orders are plain arguments (`sphbasis gaunt 2 -1 3 2 3 -3`); a coefficient that a
// selection rule forbids prints 0. Exactly six integers (the CLI's integer grammar,
// support/args.hpp) are expected; l outside 0..8191, |m| > l or a wrong count exit with status 2
// and a one-line message.
#include <CLI/CLI.hpp>
#include <array>
#include <cstdio>
#include <memory>
#include <string>

#include "cli.hpp"
#include "sphbasis/ops/sh_product.hpp"

namespace sphbasis::cli {

Run setup_gaunt(CLI::App& app) {
    static const char* names[6] = {"L1", "M1", "L2", "M2", "L3", "M3"};
    static const char* help[6] = {"degree of the first function",  "its order",
                                  "degree of the second function", "its order",
                                  "degree of the third function",  "its order"};
    auto v = std::make_shared<std::array<long long, 6>>();
    app.footer(
        "Print the real Gaunt coefficient: the integral of y_L1M1 y_L2M2 y_L3M3 over the sphere\n"
        "(real SH without the Condon-Shortley phase), with 17 significant digits.");
    const long long lmax = sh::max_bands - 1;
    for (std::size_t i = 0; i < 6; ++i)
        add_integer(app, names[i], (*v)[i], i % 2 ? -lmax : 0, lmax, help[i], names[i])
            ->required()
            ->type_name("INT")
            ->default_str("");
    return [v] {
        const auto& a = *v;
        for (std::size_t i = 0; i < 6; i += 2) {
            const long long l = a[i], m = a[i + 1];
            if (m < -l || m > l)
                throw UsageError(std::string("expected |") + names[i + 1] + "| <= " + names[i] +
                                 ", got " + names[i] + " = " + std::to_string(l) + ", " +
                                 names[i + 1] + " = " + std::to_string(m));
        }
        const double g =
            sh::gaunt(static_cast<int>(a[0]), static_cast<int>(a[1]), static_cast<int>(a[2]),
                      static_cast<int>(a[3]), static_cast<int>(a[4]), static_cast<int>(a[5]));
        std::printf("%.17g\n", g == 0 ? 0.0 : g);  // no "-0"
        return 0;
    };
}

}  // namespace sphbasis::cli
