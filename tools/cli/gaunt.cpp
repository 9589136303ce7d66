// sphbasis CLI: `sphbasis gaunt L1 M1 L2 M2 L3 M3`.
//
// Prints the real Gaunt (SH tripling) coefficient Gamma = integral of y_L1M1 y_L2M2 y_L3M3 over
// the sphere (this library's real SH: no Condon-Shortley phase, y_1-1 = +0.4886 y) with 17
// significant digits on one line, e.g.
//     $ sphbasis gaunt 1 1 1 -1 2 -2
//     0.21850968611841584
// Negative orders are plain arguments (`sphbasis gaunt 2 -1 3 2 3 -3`); a coefficient that a
// selection rule forbids prints 0. Exactly six integers are expected; non-integers, l < 0,
// l >= 8192, |m| > l or a wrong count exit with status 2 and a one-line message.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cli.hpp"
#include "sphbasis/ops/sh_product.hpp"

namespace sphbasis::cli {

namespace {

int parse_int(const std::string& s, const char* name) {
    const char* p = s.c_str();
    // Plain decimal integers only: no leading space, "+", hex, or trailing characters.
    std::size_t at = 0;
    if (p[at] == '-') ++at;
    bool digits = p[at] != '\0';
    for (std::size_t q = at; p[q] != '\0'; ++q) digits = digits && p[q] >= '0' && p[q] <= '9';
    if (!digits)
        throw UsageError(std::string("expected an integer for ") + name + ", got '" + s + "'");
    errno = 0;
    char* end = nullptr;
    const long v = std::strtol(p, &end, 10);
    if (errno == ERANGE || v < -1000000000L || v > 1000000000L)
        throw UsageError(std::string(name) + " out of range: '" + s + "'");
    return static_cast<int>(v);
}

}  // namespace

int cmd_gaunt(const Args& args) {
    if (args.size() == 1 && (args[0] == "--help" || args[0] == "-h")) {
        std::printf(
            "usage: sphbasis gaunt L1 M1 L2 M2 L3 M3\n"
            "prints the real Gaunt coefficient (integral of y_L1M1 y_L2M2 y_L3M3 over the "
            "sphere;\nreal SH without the Condon-Shortley phase) with 17 significant digits\n");
        return 0;
    }
    if (args.size() != 6)
        throw UsageError("expected 6 integers L1 M1 L2 M2 L3 M3, got " +
                         std::to_string(args.size()) + " argument" + (args.size() == 1 ? "" : "s"));
    static const char* names[6] = {"L1", "M1", "L2", "M2", "L3", "M3"};
    int v[6];
    for (int i = 0; i < 6; ++i) v[i] = parse_int(args[static_cast<std::size_t>(i)], names[i]);
    for (int i = 0; i < 6; i += 2) {
        const int l = v[i], m = v[i + 1];
        if (l < 0 || l >= sh::max_bands)
            throw UsageError(std::string("expected 0 <= ") + names[i] + " < " +
                             std::to_string(sh::max_bands) + ", got " + std::to_string(l));
        if (m < -l || m > l)
            throw UsageError(std::string("expected |") + names[i + 1] + "| <= " + names[i] +
                             ", got " + names[i] + " = " + std::to_string(l) + ", " + names[i + 1] +
                             " = " + std::to_string(m));
    }
    const double g = sh::gaunt(v[0], v[1], v[2], v[3], v[4], v[5]);
    std::printf("%.17g\n", g == 0 ? 0.0 : g);  // no "-0"
    return 0;
}

}  // namespace sphbasis::cli
