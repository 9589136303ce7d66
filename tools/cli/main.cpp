// sphbasis: the command-line tool. `sphbasis <command> [options]`, `sphbasis [<command>] --help`.
//
// Exit status: 0 on success and for --help/-h; 2 for bad input (unknown command or option, a
// malformed or out-of-range value), with one line "sphbasis[ <command>]: <message>" on stderr;
// 1 when the work itself fails (a file that cannot be read or written).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"

namespace {

struct Command {
    const char* name;
    const char* help;
    sphbasis::cli::Run (*setup)(CLI::App&);
};

const Command commands[] = {
    {"eval", "evaluate a basis at directions (JSON lines)", sphbasis::cli::setup_eval},
    {"imse", "the IMSE basis comparison benchmark", sphbasis::cli::setup_imse},
    {"params", "the spherical parameterization experiment", sphbasis::cli::setup_params},
    {"gaunt", "a real Gaunt (SH tripling) coefficient", sphbasis::cli::setup_gaunt},
    {"rotate", "rotate SH coefficients", sphbasis::cli::setup_rotate},
    {"bake", "bake AO, bent normals, visibility, transfer, irradiance (Embree)",
     sphbasis::cli::setup_bake},
    {"bake-merge", "join the shards of `bake --shard I/N`", sphbasis::cli::setup_bake_merge},
};

}  // namespace

int main(int argc, char** argv) {
    CLI::App app("sphbasis: spherical and hemispherical basis functions", "sphbasis");
    app.require_subcommand(1);
    std::vector<std::pair<CLI::App*, sphbasis::cli::Run>> subs;
    for (const auto& c : commands) {
        CLI::App* sub = app.add_subcommand(c.name, c.help);
        subs.emplace_back(sub, c.setup(*sub));
    }

    if (argc < 2) {
        std::cerr << app.help();
        return 2;
    }
    const std::string first = argv[1];
    std::string prefix = "sphbasis";
    bool known = first.size() > 0 && first[0] == '-';
    for (const auto& c : commands)
        if (first == c.name) {
            prefix += std::string(" ") + c.name;
            known = true;
        }
    if (!known) {
        std::fprintf(stderr, "sphbasis: unknown command '%s' (try sphbasis --help)\n", argv[1]);
        return 2;
    }

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);  // the help of the command given, on stdout; 0
    } catch (const CLI::CallForAllHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s\n", prefix.c_str(), e.what());
        return 2;
    } catch (const sphbasis::cli::UsageError& e) {
        std::fprintf(stderr, "%s: %s\n", prefix.c_str(), e.what());
        return 2;
    }
    for (auto& [sub, run] : subs) {
        if (!sub->parsed()) continue;
        try {
            return run();
        } catch (const sphbasis::cli::UsageError& e) {
            std::fprintf(stderr, "%s: %s\n", prefix.c_str(), e.what());
            return 2;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", prefix.c_str(), e.what());
            return 1;
        }
    }
    return 2;  // not reached: require_subcommand(1)
}
