// sphbasis CLI support: bad-input errors, the one number grammar of the command line, and
// CLI11 options that use it.
//
// The number grammar (options, positional arguments and standard input alike):
//   integer  an optional sign ('+' or '-') and decimal digits: -12, +7, 010 (= 10; leading
//            zeros are decimal, there is no hex or octal), within the range of long long. No
//            spaces, no fraction, no exponent. Each option then checks its own range.
//   real     an optional sign, decimal digits with an optional '.' and fraction (at least one
//            digit before or after the point), an optional exponent 'e' or 'E' with an optional
//            sign and digits: 1, -0.6, .5, 2., 1e-3. The value must be finite and not underflow
//            (strtod's ERANGE). No spaces, hex floats, "inf" or "nan".
//   list     reals separated by ',' and no spaces: -0.6,0,0.8.
// CLI11 splits the command line into options and values (a value may start with '-' when it is
// a number: `--dir -0.6,0,0.8`); these functions turn the values into numbers.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace sphbasis::cli {

/// Bad command-line input: main prints "sphbasis <command>: <message>" and exits with 2.
struct UsageError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

/// The grammar as predicates: true and the value if s is an integer / a real.
bool parse_integer(const std::string& s, long long& out);
bool parse_real(const std::string& s, double& out);

/// The grammar as converters: UsageError "<what>: expected an integer, got 's'" (or "a finite
/// number") on malformed input.
long long to_integer(const std::string& s, const std::string& what);
double to_real(const std::string& s, const std::string& what);
std::vector<double> to_reals(const std::string& s, const std::string& what);

/// Adds `--name VAR` to app: an integer of the grammar with lo <= value <= hi, stored in `out`
/// when given (out keeps its default otherwise, which the help shows). Bad input is a CLI11
/// ValidationError "--name: expected lo <= VAR <= hi, got s" ("expected a non-negative
/// integer, got s" when the only bound is 0).
CLI::Option* add_integer(CLI::App& app, const std::string& name, long long& out, long long lo,
                         long long hi, const std::string& help, const std::string& var = "N");

/// Adds `--name VAR` to app: a path, checked non-empty ("--name: expected a path").
CLI::Option* add_path(CLI::App& app, const std::string& name, std::string& out,
                      const std::string& help);

}  // namespace sphbasis::cli
