// sphbasis CLI: option parsing shared by the subcommands.
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "cli.hpp"

namespace sphbasis::cli {

namespace {
bool looks_like_option(const std::string& a) { return a.size() > 2 && a[0] == '-' && a[1] == '-'; }
}  // namespace

Options::Options(const Args& args, const std::vector<std::string>& known,
                 const std::vector<std::string>& flags) {
    auto is_known = [&](const std::string& n) {
        for (const auto& k : known)
            if (k == n) return true;
        for (const auto& f : flags)
            if (f == n) return true;
        return false;
    };
    auto is_flag = [&](const std::string& n) {
        for (const auto& f : flags)
            if (f == n) return true;
        return false;
    };
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& a = args[i];
        if (!looks_like_option(a)) {
            positional_.push_back(a);
            continue;
        }
        const auto eq = a.find('=');
        const std::string name = a.substr(0, eq);
        if (!is_known(name)) throw UsageError("unknown option '" + name + "'");
        std::vector<std::string>* vals = nullptr;
        for (auto& o : opts_)
            if (o.first == name) vals = &o.second;
        if (!vals) {
            opts_.push_back({name, {}});
            vals = &opts_.back().second;
        }
        if (is_flag(name)) {
            if (eq != std::string::npos) throw UsageError("option '" + name + "' takes no value");
            continue;
        }
        if (eq != std::string::npos) {
            vals->push_back(a.substr(eq + 1));
            continue;
        }
        if (i + 1 >= args.size() || looks_like_option(args[i + 1]))
            throw UsageError("option '" + name + "' expects a value");
        vals->push_back(args[++i]);
    }
}

bool Options::has(const std::string& name) const {
    for (const auto& o : opts_)
        if (o.first == name) return true;
    return false;
}

const std::vector<std::string>& Options::values(const std::string& name) const {
    static const std::vector<std::string> none;
    for (const auto& o : opts_)
        if (o.first == name) return o.second;
    return none;
}

std::string Options::get(const std::string& name, const std::string& fallback) const {
    const auto& v = values(name);
    if (v.empty()) return fallback;
    if (v.size() > 1) throw UsageError("option '" + name + "' given more than once");
    return v[0];
}

long long parse_int(const std::string& s, const std::string& what) {
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(s.c_str(), &end, 10);
    if (s.empty() || *end != '\0' || errno == ERANGE)
        throw UsageError(what + ": expected an integer, got '" + s + "'");
    return v;
}

double parse_double(const std::string& s, const std::string& what) {
    char* end = nullptr;
    errno = 0;
    const double v = std::strtod(s.c_str(), &end);
    if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        throw UsageError(what + ": expected a finite number, got '" + s + "'");
    return v;
}

std::vector<double> parse_doubles(const std::string& s, const std::string& what) {
    std::vector<double> out;
    std::size_t start = 0;
    while (true) {
        const auto comma = s.find(',', start);
        out.push_back(parse_double(s.substr(start, comma - start), what));
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    return out;
}

std::string json_number(double v) {
    if (!std::isfinite(v)) return "null";
    if (v == 0) return "0";  // also -0: a sign on zero means nothing to a JSON reader
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

}  // namespace sphbasis::cli
