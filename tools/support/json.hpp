// sphbasis CLI support: JSON output with the tool's number format.
//
// Documents are built as nlohmann::ordered_json (keys keep their insertion order) and written by
// dump_json, which differs from nlohmann's dump only in numbers and line breaks: every
// floating-point number is written as format_real (17 significant digits, which round-trips
// a double; e.g. -0.59999999999999998 where nlohmann writes the shortest -0.6), and arrays named
// in a layout put one element per line. Integers are written as integers.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>

namespace sphbasis::cli {

using Json = nlohmann::ordered_json;

/// %.17g (round-trips); "0" for +0 and -0 (a sign on zero means nothing to a JSON reader);
/// "null" for NaN and infinities. Also the number format of the CSV files.
std::string format_real(double v);

/// Arrays under these keys (at any depth) put each element on its own line, indented by the
/// given number of spaces, the closing ']' on a line of its own; all else is compact.
using JsonLayout = std::map<std::string, int>;

/// j as JSON text (no trailing newline).
std::string dump_json(const Json& j, const JsonLayout& layout = {});

}  // namespace sphbasis::cli
