// Reader of tests/data/engine_bases_reference.txt (tools/gen/gen_engine_bases_reference.py) and
// the other tagged reference files (ambient_dice_bezier_reference.txt): the lines starting with
// a given tag, as numbers after the tag.
#pragma once

#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace sphbasis::test {

inline std::vector<std::vector<double>> engine_reference(
    const std::string& tag, const std::string& file = "engine_bases_reference.txt") {
    std::ifstream f(std::string(SPHBASIS_TEST_DATA_DIR) + "/" + file);
    std::vector<std::vector<double>> rows;
    std::string line;
    while (std::getline(f, line)) {
        std::istringstream s(line);
        std::string t;
        if (!(s >> t) || t != tag) continue;
        std::vector<double> v;
        double x;
        while (s >> x) v.push_back(x);
        rows.push_back(v);
    }
    return rows;
}

/// The value of `const NAME VALUE`, NaN if absent.
inline double engine_constant(const std::string& name) {
    std::ifstream f(std::string(SPHBASIS_TEST_DATA_DIR) + "/engine_bases_reference.txt");
    std::string line;
    while (std::getline(f, line)) {
        std::istringstream s(line);
        std::string t, n;
        double v;
        if ((s >> t >> n >> v) && t == "const" && n == name) return v;
    }
    return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace sphbasis::test
