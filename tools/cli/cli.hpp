// sphbasis CLI: the subcommands. Each lives in its own file and is listed in main.cpp. A
// subcommand registers its options on its CLI11 App (CLI11 parses the command line and prints
// the help) and returns the function that runs it after parsing; that function returns the
// exit code and reports bad input by throwing UsageError (support/args.hpp), which main prints
// as one line "sphbasis <command>: <message>" with exit status 2.
#pragma once

#include <functional>

#include "../support/args.hpp"

namespace CLI {
class App;
}

namespace sphbasis::cli {

using Run = std::function<int()>;

Run setup_eval(CLI::App& app);
Run setup_imse(CLI::App& app);
Run setup_params(CLI::App& app);
Run setup_gaunt(CLI::App& app);
Run setup_rotate(CLI::App& app);
Run setup_bake(CLI::App& app);
Run setup_bake_merge(CLI::App& app);
Run setup_normal_basis(CLI::App& app);
Run setup_render(CLI::App& app);
Run setup_project(CLI::App& app);

}  // namespace sphbasis::cli
