// Property tests of the command line's number grammar (tools/support/args.hpp) on random
// strings: the parser accepts exactly the strings of the grammar, given here independently as
// regular expressions, and its values agree with an independent conversion (strtold, rounded to
// double, and exact 128-bit integer accumulation).
#include <catch2/catch.hpp>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <random>
#include <regex>
#include <string>
#include <vector>

#include "support/args.hpp"

using namespace sphbasis::cli;

namespace {

__extension__ typedef __int128 int128;  // exact accumulation of up to 38 decimal digits

const std::regex integer_grammar("[+-]?[0-9]+");
const std::regex real_grammar("[+-]?([0-9]+\\.?[0-9]*|\\.[0-9]+)([eE][+-]?[0-9]+)?");

/// Random strings over the characters that matter to the grammar (digits most often), plus
/// a few that never belong to a number, lengths 0..max_len.
std::string random_token(std::mt19937_64& rng, std::size_t max_len) {
    static const std::string digits = "0123456789";
    static const std::string other = "+-.eE, xian\t";
    std::uniform_int_distribution<std::size_t> len(0, max_len);
    std::uniform_int_distribution<int> coin(0, 9);
    std::string s;
    const std::size_t n = len(rng);
    for (std::size_t i = 0; i < n; ++i) {
        const std::string& pool = coin(rng) < 6 ? digits : other;
        s += pool[std::uniform_int_distribution<std::size_t>(0, pool.size() - 1)(rng)];
    }
    return s;
}

/// A well-formed real with random parts (so that acceptance is exercised as much as rejection).
std::string random_real(std::mt19937_64& rng) {
    std::uniform_int_distribution<int> coin(0, 3), dig(0, 9), len(0, 5), expo(0, 400);
    std::string s;
    if (coin(rng) == 0) s += coin(rng) < 2 ? "-" : "+";
    const int whole = len(rng), frac = len(rng);
    for (int i = 0; i < whole; ++i) s += char('0' + dig(rng));
    if (coin(rng) != 0 || whole == 0) {
        s += '.';
        for (int i = 0; i < frac; ++i) s += char('0' + dig(rng));
    }
    if (whole == 0 && (s.empty() || s.back() == '.' || s.back() == '-' || s.back() == '+'))
        s += char('0' + dig(rng));
    if (coin(rng) == 0) {
        s += coin(rng) < 2 ? 'e' : 'E';
        if (coin(rng) < 2) s += coin(rng) < 2 ? "-" : "+";
        s += std::to_string(expo(rng));
    }
    return s;
}

/// The grammar's verdict and value for a real, independently of args.cpp: accepted when the
/// regular expression matches and strtold's value rounds to a finite double that is zero or
/// normal. `window` is set where a conforming parser may go either way: results in the
/// subnormal range (strtod's ERANGE on underflow is a libc choice) and values within a rounding
/// of DBL_MAX.
bool reference_real(const std::string& s, double& value, bool& window) {
    window = false;
    if (!std::regex_match(s, real_grammar)) return false;
    const long double v = std::strtold(s.c_str(), nullptr);
    const long double a = std::fabs(v);
    if (a != 0 && a < static_cast<long double>(DBL_MIN)) window = true;
    if (a > static_cast<long double>(DBL_MAX) * 0.999999L &&
        a < static_cast<long double>(DBL_MAX) * 1.000001L)
        window = true;
    value = static_cast<double>(v);
    // A non-zero mantissa whose value underflows even long double is an underflow too.
    const std::string mantissa = s.substr(0, s.find_first_of("eE"));
    const bool nonzero = mantissa.find_first_of("123456789") != std::string::npos;
    if (nonzero && value == 0) return false;
    return std::isfinite(value) && (value == 0 || std::fabs(value) >= DBL_MIN);
}

bool reference_integer(const std::string& s, long long& value) {
    if (!std::regex_match(s, integer_grammar)) return false;
    std::size_t i = (s[0] == '-' || s[0] == '+') ? 1 : 0;
    int128 v = 0;
    for (; i < s.size(); ++i) {
        v = v * 10 + (s[i] - '0');
        if (v > (int128(1) << 64)) return false;  // far outside long long already
    }
    if (s[0] == '-') v = -v;
    if (v > std::numeric_limits<long long>::max() || v < std::numeric_limits<long long>::min())
        return false;
    value = static_cast<long long>(v);
    return true;
}

}  // namespace

TEST_CASE("args: parse_real accepts exactly the grammar, with strtold's value", "[tool]") {
    std::mt19937_64 rng(20261130);
    std::size_t accepted = 0, rejected = 0;
    for (int k = 0; k < 40000; ++k) {
        const std::string s = (k % 2) ? random_token(rng, 14) : random_real(rng);
        double ref = 0, got = 0;
        bool window = false;
        const bool want = reference_real(s, ref, window);
        const bool ok = parse_real(s, got);
        INFO("input '" << s << "'");
        if (!window) REQUIRE(ok == want);
        if (ok && want) {
            // strtod rounds once; strtold then a rounding to double may differ by one ulp.
            REQUIRE(std::fabs(got - ref) <= std::fabs(ref) * DBL_EPSILON);
            REQUIRE(std::isfinite(got));
        }
        (ok ? accepted : rejected)++;
    }
    // Both outcomes were exercised many times.
    CHECK(accepted > 15000);
    CHECK(rejected > 15000);
}

TEST_CASE("args: parse_integer accepts exactly the grammar within long long", "[tool]") {
    std::mt19937_64 rng(7);
    std::size_t accepted = 0;
    for (int k = 0; k < 40000; ++k) {
        std::string s = random_token(rng, 22);
        if (k % 3 == 0) {  // digits only, lengths around the 19-digit limit
            s = (k % 2 ? "-" : "");
            const int n = std::uniform_int_distribution<int>(1, 21)(rng);
            for (int i = 0; i < n; ++i)
                s += char('0' + std::uniform_int_distribution<int>(0, 9)(rng));
        }
        long long ref = 0, got = 0;
        const bool want = reference_integer(s, ref);
        INFO("input '" << s << "'");
        REQUIRE(parse_integer(s, got) == want);
        if (want) {
            REQUIRE(got == ref);
            ++accepted;
        }
    }
    CHECK(accepted > 5000);
    long long v = 0;
    CHECK(parse_integer("9223372036854775807", v));
    CHECK(v == std::numeric_limits<long long>::max());
    CHECK(parse_integer("-9223372036854775808", v));
    CHECK(v == std::numeric_limits<long long>::min());
    CHECK_FALSE(parse_integer("9223372036854775808", v));
    CHECK_FALSE(parse_integer("-9223372036854775809", v));
}

TEST_CASE("args: to_reals splits on commas and names the bad element", "[tool]") {
    std::mt19937_64 rng(11);
    for (int k = 0; k < 2000; ++k) {
        const int n = std::uniform_int_distribution<int>(1, 5)(rng);
        std::vector<std::string> parts;
        std::string joined;
        for (int i = 0; i < n; ++i) {
            parts.push_back(random_real(rng));
            joined += (i ? "," : "") + parts.back();
        }
        std::vector<double> want;
        bool all = true, window = false;
        for (const auto& p : parts) {
            double v = 0;
            bool w = false;
            all = reference_real(p, v, w) && all;
            window = window || w;
            want.push_back(v);
        }
        if (window) continue;
        INFO("input '" << joined << "'");
        if (all) {
            const auto got = to_reals(joined, "--dir");
            REQUIRE(got.size() == want.size());
            for (std::size_t i = 0; i < got.size(); ++i)
                REQUIRE(std::fabs(got[i] - want[i]) <= std::fabs(want[i]) * DBL_EPSILON);
        } else {
            REQUIRE_THROWS_AS(to_reals(joined, "--dir"), UsageError);
        }
    }
    CHECK_THROWS_WITH(to_reals("1,,2", "--dir"), Catch::Contains("--dir") && Catch::Contains("''"));
    CHECK_THROWS_WITH(to_reals("1,2,", "--dir"), Catch::Contains("--dir"));
    CHECK_THROWS_AS(to_reals("", "--dir"), UsageError);
}
