// sphbasis CLI support: memory_limit and check_memory (see memory.hpp).
#include "memory.hpp"

#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>
#endif

namespace sphbasis::cli {

namespace {

std::uint64_t physical_memory() {
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) return std::uint64_t(pages) * std::uint64_t(page);
#endif
    return std::uint64_t(8) << 30;  // unknown: assume 8 GiB
}

}  // namespace

std::uint64_t memory_limit() {
    const char* env = std::getenv("SPHBASIS_MAX_MEMORY");
    if (env == nullptr || *env == '\0') return physical_memory() / 4 * 3;
    const std::string s = env;
    std::size_t i = 0;
    std::uint64_t v = 0;
    bool overflow = false;
    for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) {
        overflow = overflow || v > (UINT64_MAX - 9) / 10;
        v = 10 * v + std::uint64_t(s[i] - '0');
    }
    int shift = 0;
    if (i + 1 == s.size()) {
        const char u = s[i];
        shift = (u == 'K' || u == 'k')   ? 10
                : (u == 'M' || u == 'm') ? 20
                : (u == 'G' || u == 'g') ? 30
                : (u == 'T' || u == 't') ? 40
                                         : -1;
        ++i;
    }
    if (i == 0 || i != s.size() || shift < 0 || overflow || v == 0 || (v >> (63 - shift)) != 0)
        throw std::runtime_error(
            "SPHBASIS_MAX_MEMORY: expected a positive number of bytes with an optional K, M, G "
            "or T suffix (below 2^63 bytes), got '" +
            s.substr(0, 40) + (s.size() > 40 ? "...'" : "'"));
    return v << shift;
}

std::string format_bytes(double bytes) {
    char buf[64];
    if (bytes < 1024) {
        std::snprintf(buf, sizeof buf, "%.0f bytes", bytes);
    } else {
        const char* unit[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
        int u = 0;
        double v = bytes / 1024;
        while (v >= 1024 && u < 5) {
            v /= 1024;
            ++u;
        }
        std::snprintf(buf, sizeof buf, v < 10 ? "%.1f %s" : "%.0f %s", v, unit[u]);
    }
    return buf;
}

void check_memory(const std::string& what, double bytes, const std::string& detail) {
    const std::uint64_t limit = memory_limit();
    if (!(bytes > double(limit))) return;
    const bool from_env = std::getenv("SPHBASIS_MAX_MEMORY") != nullptr &&
                          *std::getenv("SPHBASIS_MAX_MEMORY") != '\0';
    throw std::runtime_error(
        what + "needs " + format_bytes(bytes) + (detail.empty() ? "" : " (" + detail + ")") +
        "; at most " + format_bytes(double(limit)) + " allowed (" +
        (from_env ? "SPHBASIS_MAX_MEMORY" : "3/4 of physical memory; SPHBASIS_MAX_MEMORY sets it") +
        ")");
}

}  // namespace sphbasis::cli
