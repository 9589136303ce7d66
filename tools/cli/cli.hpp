// sphbasis CLI: shared declarations. Each subcommand lives in its own file and is listed in
// main.cpp. A subcommand receives the arguments after its name and returns the exit code;
// it reports bad input with a one-line message on stderr and a non-zero exit.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace sphbasis::cli {

using Args = std::vector<std::string>;

int cmd_eval(const Args& args);
int cmd_imse(const Args& args);
int cmd_params(const Args& args);
int cmd_gaunt(const Args& args);
int cmd_rotate(const Args& args);

/// Thrown for bad command-line input; main prints "sphbasis: <message>" and exits with 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace sphbasis::cli
