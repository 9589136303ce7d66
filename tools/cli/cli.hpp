// sphbasis CLI: shared declarations. Each subcommand lives in its own file and is listed in
// main.cpp. A subcommand receives the arguments after its name and returns the exit code;
// it reports bad input with a one-line message on stderr and a non-zero exit.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>
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

/// Command-line options in the forms `--name value` and `--name=value`. A value may start with
/// '-' (negative numbers: `--dir -0.6,0,0.8`); anything else starting with "--" is an option.
class Options {
  public:
    /// Parses args; `flags` are the option names that take no value (e.g. "--help").
    Options(const Args& args, const std::vector<std::string>& known,
            const std::vector<std::string>& flags = {});
    bool has(const std::string& name) const;
    /// All values given to an option (repeatable options, and `--dir A B C`).
    const std::vector<std::string>& values(const std::string& name) const;
    /// The single value of an option, or `fallback` if absent; UsageError if given twice.
    std::string get(const std::string& name, const std::string& fallback = "") const;
    /// Arguments that belong to no option.
    const std::vector<std::string>& positional() const { return positional_; }

  private:
    std::vector<std::pair<std::string, std::vector<std::string>>> opts_;
    std::vector<std::string> positional_;
};

/// Parsers that throw UsageError with the option's name on malformed input.
long long parse_int(const std::string& s, const std::string& what);
double parse_double(const std::string& s, const std::string& what);
std::vector<double> parse_doubles(const std::string& s, const std::string& what);
/// Prints a double with 17 significant digits (round-trips), as JSON.
std::string json_number(double v);

}  // namespace sphbasis::cli
