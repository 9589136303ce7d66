// sphbasis CLI support: dump_json (see json.hpp).
#include "json.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace sphbasis::cli {

std::string format_real(double v) {
    if (!std::isfinite(v)) return "null";
    if (v == 0) return "0";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

namespace {

void write(std::string& out, const Json& j, const JsonLayout& layout, int indent) {
    switch (j.type()) {
        case Json::value_t::number_float:
            out += format_real(j.get<double>());
            return;
        case Json::value_t::object: {
            out += '{';
            bool first = true;
            for (auto it = j.begin(); it != j.end(); ++it) {
                if (!first) out += ',';
                first = false;
                out += Json(it.key()).dump();
                out += ':';
                const auto lay = layout.find(it.key());
                write(out, it.value(), layout,
                      it.value().is_array() && lay != layout.end() ? lay->second : -1);
            }
            out += '}';
            return;
        }
        case Json::value_t::array: {
            out += '[';
            bool first = true;
            for (const auto& e : j) {
                if (indent >= 0) {
                    out += first ? "\n" : ",\n";
                    out.append(static_cast<std::size_t>(indent), ' ');
                } else if (!first) {
                    out += ',';
                }
                first = false;
                write(out, e, layout, -1);
            }
            if (indent >= 0) out += '\n';
            out += ']';
            return;
        }
        default:  // null, boolean, integers, strings: nlohmann's own text
            out += j.dump();
            return;
    }
}

}  // namespace

std::string dump_json(const Json& j, const JsonLayout& layout) {
    std::string out;
    write(out, j, layout, -1);
    return out;
}

}  // namespace sphbasis::cli
