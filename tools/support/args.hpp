// sphbasis CLI support: bad-input errors, the one number grammar of the command line, and
// CLI11 options that use it.
//
// The number grammar (options, positional arguments and standard input alike):
//   integer  an optional sign ('+' or '-') and decimal digits: -12, +7, 010 (= 10; leading
//            zeros are decimal, there is no hex or octal), within the range of long long. No
//            spaces, no fraction, no exponent. Each option then checks its own range.
//   real     an optional sign, decimal digits with an optional '.' and fraction (at least one
//            digit before or after the point), an optional exponent 'e' or 'E' with an optional
//            sign and digits: 1, -0.6, .5, 2., 1e-3. The value must be finite (at most
//            1.7976931348623157e308 in magnitude); subnormal values (1e-320) are numbers like any
//            other, but a non-zero number that rounds to zero (1e-400) is refused. No spaces, hex
//            floats, "inf" or "nan".
//   list     reals separated by ',' and no spaces: -0.6,0,0.8.
// CLI11 splits the command line into options and values (a value may start with '-' when it is
// a number: `--dir -0.6,0,0.8`); these functions turn the values into numbers.
//
// Standard input (`eval --dirs -`, `rotate --coeffs -`) is read line by line by read_line:
// a line ends at '\n' (a '\r' before it is whitespace); a last line without '\n' is a line
// like any other; a line longer than its bound (1 MiB unless the command says otherwise) is an
// error, raised before more than the bound is held in memory, so `< /dev/zero` fails at once.
#pragma once

#include <cstddef>
#include <cstdio>
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

/// s for a message: at most 40 characters (then "..." and the length), bytes outside printable
/// ASCII as \xNN, so that a bad token of a megabyte or of NUL bytes stays one short line.
std::string quote_input(const std::string& s);

/// The grammar as converters: UsageError "<what>: expected an integer, got 's'" (or "a finite
/// number") on malformed input (s shown by quote_input); digits beyond long long, an overflowing
/// or a zero-rounding real name the range instead.
long long to_integer(const std::string& s, const std::string& what);
double to_real(const std::string& s, const std::string& what);
std::vector<double> to_reals(const std::string& s, const std::string& what);

/// The default bound of a line of standard input: 1 MiB (a direction line needs under 100 bytes).
inline constexpr std::size_t max_line_bytes = std::size_t(1) << 20;

/// Reads the next line of `in` into `line` (without the '\n'); false at the end of the input.
/// lineno counts the lines read. Throws UsageError "<where> line N: longer than B bytes (...)"
/// when a line exceeds max_bytes, and std::runtime_error "cannot read <where>: <reason>" when
/// reading fails.
bool read_line(std::FILE* in, std::string& line, long& lineno, std::size_t max_bytes,
               const std::string& where = "standard input");

/// Adds `--name VAR` to app: an integer of the grammar with lo <= value <= hi, stored in `out`
/// when given (out keeps its default otherwise, which the help shows). Bad input is a CLI11
/// ValidationError "--name: expected lo <= VAR <= hi, got s" ("expected a non-negative
/// integer, got s" when the only bound is 0); a non-empty `why` follows the bounds in
/// parentheses ("expected 1 <= N <= 100000000 (56 bytes of memory per point), got ...").
CLI::Option* add_integer(CLI::App& app, const std::string& name, long long& out, long long lo,
                         long long hi, const std::string& help, const std::string& var = "N",
                         const std::string& why = "");

/// Adds `--name VAR` to app: a path, checked non-empty ("--name: expected a path").
CLI::Option* add_path(CLI::App& app, const std::string& name, std::string& out,
                      const std::string& help);

/// Adds the required positional argument SCENE.json: the scene file (docs/scene-format.md).
CLI::Option* add_scene(CLI::App& app, std::string& out);

}  // namespace sphbasis::cli
