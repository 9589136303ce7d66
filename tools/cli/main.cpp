// sphbasis: the command-line tool. `sphbasis <subcommand> [options]`.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "cli.hpp"

namespace {

struct Command {
    const char* name;
    int (*run)(const sphbasis::cli::Args&);
    const char* help;
};

const Command commands[] = {
    {"eval", sphbasis::cli::cmd_eval, "evaluate a basis at directions (JSON lines)"},
    {"imse", sphbasis::cli::cmd_imse, "the IMSE basis comparison benchmark"},
    {"params", sphbasis::cli::cmd_params, "the spherical parameterization experiment"},
    {"gaunt", sphbasis::cli::cmd_gaunt, "a real Gaunt (SH tripling) coefficient"},
    {"rotate", sphbasis::cli::cmd_rotate, "rotate SH coefficients"},
};

void usage(std::FILE* f) {
    std::fprintf(f, "usage: sphbasis <command> [options]\n\ncommands:\n");
    for (const auto& c : commands) std::fprintf(f, "  %-8s %s\n", c.name, c.help);
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    if (!std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        usage(stdout);
        return 0;
    }
    for (const auto& c : commands) {
        if (std::strcmp(argv[1], c.name) != 0) continue;
        sphbasis::cli::Args args(argv + 2, argv + argc);
        try {
            return c.run(args);
        } catch (const sphbasis::cli::UsageError& e) {
            std::fprintf(stderr, "sphbasis %s: %s\n", c.name, e.what());
            return 2;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "sphbasis %s: %s\n", c.name, e.what());
            return 1;
        }
    }
    std::fprintf(stderr, "sphbasis: unknown command '%s' (try sphbasis --help)\n", argv[1]);
    return 2;
}
