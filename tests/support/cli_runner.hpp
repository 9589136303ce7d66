// Test support: runs the built `sphbasis` tool and captures what it prints (POSIX only).
#pragma once

#if defined(__unix__) || defined(__APPLE__)
#define SPHBASIS_TEST_HAVE_POPEN 1

#include <algorithm>
#include <catch2/catch.hpp>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <string>

namespace sphbasis::test {

/// Path of the tool built beside the tests (empty if it was not built).
inline std::string tool_path() {
    const std::string exe = std::string(SPHBASIS_BINARY_DIR) + "/bin/sphbasis";
    return std::ifstream(exe) ? exe : std::string();
}

/// Runs `sphbasis <args>` with stderr merged into stdout; returns the output, sets the wait
/// status (0 on success). Returns "" with status -1 if the process cannot be started.
inline std::string run_tool(const std::string& args, int& status) {
    std::string out;
    FILE* p = popen((tool_path() + " " + args + " 2>&1").c_str(), "r");
    if (!p) {
        status = -1;
        return out;
    }
    char buf[4096];
    while (std::fgets(buf, sizeof buf, p)) out += buf;
    status = pclose(p);
    return out;
}

/// Each of `bad` (the arguments after `command`) makes the tool exit non-zero with exactly one
/// line of output (the error).
inline void check_rejects(const std::string& command, std::initializer_list<const char*> bad) {
    for (const char* args : bad) {
        int st = 0;
        const std::string out = run_tool(command + " " + args, st);
        INFO(command << " " << args << " -> " << out);
        CHECK(st != 0);
        CHECK(std::count(out.begin(), out.end(), '\n') == 1);
    }
}

}  // namespace sphbasis::test
#endif
