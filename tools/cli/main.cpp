// sphbasis: the command-line tool. `sphbasis <command> [options]`, `sphbasis [<command>] --help`.
//
// Exit status: 0 on success and for --help/-h; 2 for bad input (unknown command or option, a
// malformed or out-of-range value), with one line "sphbasis[ <command>]: <message>" on stderr;
// 1 when the work itself fails (a file that cannot be read or written, standard output closed,
// full or otherwise failing: support/stdout_check.hpp; no command reports success when its
// output was lost); killed by SIGINT, SIGTERM, SIGHUP or SIGPIPE (status 130, 143, 129, 141 in a
// shell) after removing the staged outputs: every output of a command is written all or none
// (support/output_file.hpp).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "../support/output_file.hpp"
#include "../support/stdout_check.hpp"
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
    {"project", "project an environment map onto SH (or any basis): JSON, C++, GLSL, HLSL, engines",
     sphbasis::cli::setup_project},
    {"bake", "bake AO, bent normals, visibility, transfer, irradiance (Embree)",
     sphbasis::cli::setup_bake},
    {"bake-merge", "join the shards of `bake --shard I/N`", sphbasis::cli::setup_bake_merge},
    {"normal-basis", "the SVD normal basis of normal-mapped PRT",
     sphbasis::cli::setup_normal_basis},
    {"render", "path-traced reference vs baked representations: images and report",
     sphbasis::cli::setup_render},
};

/// A message as one line: control characters (a newline in a library's text, a file name's
/// bytes) escaped as \xNN, and at most 1000 characters (the start and the end kept): a guard
/// behind the messages, which abbreviate what they quote from the input themselves.
std::string one_line(const std::string& msg) {
    std::string out;
    for (const char ch : msg) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c < 0x20 || c == 0x7f) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
        } else {
            out += ch;
        }
    }
    if (out.size() > 1000) out = out.substr(0, 800) + " ... " + out.substr(out.size() - 195);
    return out;
}

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
        std::fprintf(stderr, "sphbasis: unknown command '%s' (try sphbasis --help)\n",
                     one_line(argv[1]).c_str());
        return 2;
    }

    // A closed descriptor 1 would be taken by the next file opened (--json PATH) and the table
    // written into it: stop before any work.
    if (!sphbasis::cli::stdout_is_open()) {
        std::fprintf(stderr, "%s: cannot write standard output: it is closed\n", prefix.c_str());
        return 1;
    }
    // The final flush of standard output, checked: exit status 1 if anything written was lost.
    auto finish = [&prefix](int rc) {
        try {
            sphbasis::cli::check_stdout(true);
        } catch (const sphbasis::cli::OutputError& e) {
            std::fprintf(stderr, "%s: %s\n", prefix.c_str(), e.what());
            return 1;
        }
        return rc;
    };

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return finish(app.exit(e));  // the help of the command given, on stdout; 0
    } catch (const CLI::CallForAllHelp& e) {
        return finish(app.exit(e));
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "%s: %s\n", prefix.c_str(), one_line(e.what()).c_str());
        return 2;
    } catch (const sphbasis::cli::UsageError& e) {
        std::fprintf(stderr, "%s: %s\n", prefix.c_str(), one_line(e.what()).c_str());
        return 2;
    }
    // SIGINT, SIGTERM (and SIGHUP, SIGPIPE) remove the staged outputs of the run and end it
    // at once by that signal (support/output_file.hpp).
    sphbasis::cli::install_signal_cleanup(prefix);
    for (auto& [sub, run] : subs) {
        if (!sub->parsed()) continue;
        try {
            return finish(run());
        } catch (const sphbasis::cli::UsageError& e) {
            std::fprintf(stderr, "%s: %s\n", prefix.c_str(), one_line(e.what()).c_str());
            return 2;
        } catch (const std::bad_alloc&) {
            // The estimates of support/memory.hpp refuse what cannot fit before it starts;
            // this is what they missed.
            std::fprintf(stderr,
                         "%s: out of memory (std::bad_alloc): the run needs more memory than "
                         "this machine gave it; reduce its sizes\n",
                         prefix.c_str());
            return 1;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s: %s\n", prefix.c_str(), one_line(e.what()).c_str());
            return 1;
        }
    }
    return 2;  // not reached: require_subcommand(1)
}
