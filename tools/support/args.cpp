// sphbasis CLI support: the number grammar (see args.hpp) and its CLI11 options.
#include "args.hpp"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace sphbasis::cli {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }

// Length of the run of digits of s starting at i.
std::size_t digits(const std::string& s, std::size_t i) {
    std::size_t n = 0;
    while (i + n < s.size() && is_digit(s[i + n])) ++n;
    return n;
}

}  // namespace

bool parse_integer(const std::string& s, long long& out) {
    std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
    if (digits(s, i) == 0 || i + digits(s, i) != s.size()) return false;
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (errno == ERANGE) return false;
    out = v;
    return true;
}

namespace {

enum class Real { ok, malformed, overflow, underflow };

/// The grammar's verdict on s: ok (and the value), malformed, or a number whose magnitude is
/// beyond double (overflow) or so small that it rounds to zero (underflow). Subnormal results
/// are numbers like any other (strtod's ERANGE on them is a libc choice, not an error).
Real classify_real(const std::string& s, double& out) {
    std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
    const std::size_t whole = digits(s, i);
    i += whole;
    std::size_t frac = 0;
    if (i < s.size() && s[i] == '.') {
        frac = digits(s, i + 1);
        i += 1 + frac;
    }
    if (whole + frac == 0) return Real::malformed;
    const std::size_t mantissa_end = i;
    if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
        ++i;
        if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
        const std::size_t exp = digits(s, i);
        if (exp == 0) return Real::malformed;
        i += exp;
    }
    if (i != s.size()) return Real::malformed;
    errno = 0;
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    if (!std::isfinite(v)) return Real::overflow;
    if (errno == ERANGE && v == 0 &&
        s.find_first_of("123456789") < mantissa_end)  // a non-zero mantissa rounded to 0
        return Real::underflow;
    out = v;
    return Real::ok;
}

/// s has the integer grammar's form (whether or not it fits in long long).
bool is_integer_text(const std::string& s) {
    const std::size_t i = (!s.empty() && (s[0] == '-' || s[0] == '+')) ? 1 : 0;
    return digits(s, i) > 0 && i + digits(s, i) == s.size();
}

}  // namespace

bool parse_real(const std::string& s, double& out) { return classify_real(s, out) == Real::ok; }

std::string quote_input(const std::string& s) {
    const std::size_t shown = 40;
    std::string out;
    for (std::size_t i = 0; i < s.size() && i < shown; ++i) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 0x20 && c < 0x7f) {
            out += static_cast<char>(c);
        } else {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\x%02X", c);
            out += buf;
        }
    }
    if (s.size() > shown) out += "... (" + std::to_string(s.size()) + " bytes)";
    return out;
}

bool read_line(std::FILE* in, std::string& line, long& lineno, std::size_t max_bytes,
               const std::string& where) {
    line.clear();
    bool any = false;
    for (;;) {
#if defined(__unix__) || defined(__APPLE__)
        const int c = getc_unlocked(in);  // one thread reads; the locking getc is 3x slower
#else
        const int c = std::getc(in);
#endif
        if (c == EOF) {
            if (std::ferror(in)) {
                const int err = errno;
                throw std::runtime_error("cannot read " + where +
                                         (err ? std::string(": ") + std::strerror(err) : ""));
            }
            if (any) ++lineno;
            return any;
        }
        any = true;
        if (c == '\n') {
            ++lineno;
            return true;
        }
        if (line.size() >= max_bytes)
            throw UsageError(where + " line " + std::to_string(lineno + 1) + ": longer than " +
                             std::to_string(max_bytes) + " bytes (the longest line accepted)");
        line += static_cast<char>(c);
    }
}

long long to_integer(const std::string& s, const std::string& what) {
    long long v = 0;
    if (parse_integer(s, v)) return v;
    if (is_integer_text(s))
        throw UsageError(what + ": expected an integer in [" +
                         std::to_string(std::numeric_limits<long long>::min()) + ", " +
                         std::to_string(std::numeric_limits<long long>::max()) + "], got '" +
                         quote_input(s) + "'");
    throw UsageError(what + ": expected an integer, got '" + quote_input(s) + "'");
}

double to_real(const std::string& s, const std::string& what) {
    double v = 0;
    switch (classify_real(s, v)) {
        case Real::ok:
            return v;
        case Real::overflow:
            throw UsageError(
                what +
                ": expected a finite number (magnitude at most 1.7976931348623157e308), got '" +
                quote_input(s) + "'");
        case Real::underflow:
            throw UsageError(what +
                             ": expected a number that does not round to zero (magnitude at least "
                             "4.9406564584124654e-324, or 0), got '" +
                             quote_input(s) + "'");
        case Real::malformed:
            break;
    }
    throw UsageError(what + ": expected a finite number, got '" + quote_input(s) + "'");
}

std::vector<double> to_reals(const std::string& s, const std::string& what) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const auto comma = s.find(',', start);
        out.push_back(to_real(s.substr(start, comma - start), what));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

CLI::Option* add_integer(CLI::App& app, const std::string& name, long long& out, long long lo,
                         long long hi, const std::string& help, const std::string& var,
                         const std::string& why) {
    auto check = [lo, hi, var, why](const std::string& s) -> std::string {
        long long v = 0;
        if (!parse_integer(s, v)) {
            if (!is_integer_text(s)) return "expected an integer, got '" + quote_input(s) + "'";
            // Digits beyond long long: outside every option's range.
            const std::string shown = quote_input(s);
            if (lo == 0 && hi == std::numeric_limits<long long>::max())
                return "expected a non-negative integer at most " + std::to_string(hi) + ", got " +
                       shown;
            return "expected " + std::to_string(lo) + " <= " + var + " <= " + std::to_string(hi) +
                   (why.empty() ? "" : " (" + why + ")") + ", got " + shown;
        }
        if (v >= lo && v <= hi) return {};
        if (lo == 0 && hi == std::numeric_limits<long long>::max())
            return "expected a non-negative integer, got " + quote_input(s);
        return "expected " + std::to_string(lo) + " <= " + var + " <= " + std::to_string(hi) +
               (why.empty() ? "" : " (" + why + ")") + ", got " + quote_input(s);
    };
    CLI::Option* o = app.add_option(
        name,
        [&out](const CLI::results_t& r) {
            long long v = 0;
            const bool ok = parse_integer(r.at(0), v);  // checked above
            out = v;
            return ok;
        },
        help);
    o->check(CLI::Validator(check, "", ""))
        ->type_name(var)
        ->default_str(std::to_string(out))
        ->expected(1);
    return o;
}

CLI::Option* add_path(CLI::App& app, const std::string& name, std::string& out,
                      const std::string& help) {
    return app.add_option(name, out, help)
        ->type_name("PATH")
        ->check(CLI::Validator(
            [](const std::string& s) { return s.empty() ? std::string("expected a path") : ""; },
            "", ""));
}

CLI::Option* add_scene(CLI::App& app, std::string& out) {
    return app.add_option("scene", out, "the scene file (JSON)")
        ->type_name("SCENE.json")
        ->required();
}

}  // namespace sphbasis::cli
