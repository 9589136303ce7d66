// Bad input to the tool's support code: the memory limit (tools/support/memory.hpp), the
// number grammar's range messages (args.hpp), and the scene loader (scene_file.hpp) as a
// property on random mutations of the committed scenes: it returns a scene or throws a
// std::exception with a one-line message naming the file, and never crashes or hangs. Also the
// library's coordinate bound behind the loader (render::coordinate_limit: render::Scene and
// render::Baker::bake refuse what Embree would abort on), here because this binary is the one
// that builds with the tool.
#include <unistd.h>

#include <algorithm>
#include <catch2/catch.hpp>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/shapes.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/args.hpp"
#include "support/memory.hpp"
#include "support/scene_file.hpp"

using namespace sphbasis::cli;

namespace {

/// Sets an environment variable for the scope, restoring the previous value.
struct ScopedEnv {
    std::string name, old;
    bool had = false;
    ScopedEnv(const char* n, const char* value) : name(n) {
        const char* o = std::getenv(n);
        had = o != nullptr;
        if (had) old = o;
        if (value)
            setenv(n, value, 1);
        else
            unsetenv(n);
    }
    ~ScopedEnv() {
        if (had)
            setenv(name.c_str(), old.c_str(), 1);
        else
            unsetenv(name.c_str());
    }
};

std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

}  // namespace

TEST_CASE("memory: the limit from SPHBASIS_MAX_MEMORY and the message", "[tool]") {
    {
        ScopedEnv e("SPHBASIS_MAX_MEMORY", "1G");
        CHECK(memory_limit() == (std::uint64_t(1) << 30));
        CHECK_NOTHROW(check_memory("x: ", double(std::uint64_t(1) << 30)));
        REQUIRE_THROWS_WITH(check_memory("scene.json: meshes[0]: ", 2.5 * (1 << 30), "a sphere"),
                            "scene.json: meshes[0]: needs 2.5 GiB (a sphere); at most 1.0 GiB "
                            "allowed (SPHBASIS_MAX_MEMORY)");
    }
    const std::pair<const char*, std::uint64_t> good[] = {
        {"1536", 1536}, {"3k", 3072}, {"3M", 3u << 20}, {"2T", std::uint64_t(2) << 40}};
    for (const auto& [text, bytes] : good) {
        ScopedEnv e("SPHBASIS_MAX_MEMORY", text);
        CHECK(memory_limit() == bytes);
    }
    for (const char* bad :
         {"lots", "0", "1.5G", "1GB", "-1", "G", "99999999999999999999", "9000000000000000000T"}) {
        ScopedEnv e("SPHBASIS_MAX_MEMORY", bad);
        INFO(bad);
        REQUIRE_THROWS_WITH(memory_limit(),
                            Catch::StartsWith("SPHBASIS_MAX_MEMORY: expected a positive number"));
    }
    {
        // Unset: 3/4 of the physical memory (here from /proc/meminfo, in kB, which Linux's
        // sysconf(_SC_PHYS_PAGES) reads as well, rounded to pages).
        ScopedEnv e("SPHBASIS_MAX_MEMORY", nullptr);
        std::ifstream in("/proc/meminfo");
        std::string key;
        double kb = 0;
        if (in >> key >> kb && key == "MemTotal:") {
            const double want = kb * 1024 * 0.75;
            CHECK(std::fabs(double(memory_limit()) - want) <= 0.01 * want);
        }
    }
    CHECK(format_bytes(900) == "900 bytes");
    CHECK(format_bytes(1536) == "1.5 KiB");
    CHECK(format_bytes(12.34 * (1 << 30)) == "12 GiB");
    CHECK(format_bytes(3.25 * (1 << 30)) == "3.2 GiB");
}

TEST_CASE("args: subnormal reals are numbers; range errors name the range", "[tool]") {
    double v = 0;
    REQUIRE(parse_real("1e-320", v));
    CHECK(v == std::strtod("1e-320", nullptr));
    CHECK(v > 0);
    CHECK(v < DBL_MIN);
    REQUIRE(parse_real("-4.9406564584124654e-324", v));
    CHECK(v == -std::numeric_limits<double>::denorm_min());
    REQUIRE(parse_real("0e-999", v));  // zero itself never underflows
    CHECK(v == 0);
    CHECK_FALSE(parse_real("1e-400", v));
    CHECK_FALSE(parse_real("1e400", v));
    REQUIRE_THROWS_WITH(to_real("1e-400", "--dir"),
                        Catch::StartsWith("--dir: expected a number that does not round to zero"));
    REQUIRE_THROWS_WITH(to_real("-1e400", "--dir"),
                        Catch::StartsWith("--dir: expected a finite number (magnitude at most "
                                          "1.7976931348623157e308)"));
    REQUIRE_THROWS_WITH(to_real("1e", "--dir"), "--dir: expected a finite number, got '1e'");
    REQUIRE_THROWS_WITH(to_integer("18446744073709551617", "--n"),
                        "--n: expected an integer in [-9223372036854775808, "
                        "9223372036854775807], got '18446744073709551617'");
    REQUIRE_THROWS_WITH(to_integer("1.5", "--n"), "--n: expected an integer, got '1.5'");
}

TEST_CASE("scene_file: random mutations of the committed scenes load or fail in one line",
          "[tool]") {
    namespace fs = std::filesystem;
    // Nothing large is built while mutating (a mutated count or size is refused instead).
    ScopedEnv mem("SPHBASIS_MAX_MEMORY", "64M");
    const fs::path data = fs::path(SPHBASIS_TEST_DATA_DIR) / "scenes";
    std::vector<fs::path> scenes;
    for (const fs::path& dir : {data, data / "render"})
        for (const auto& e : fs::directory_iterator(dir))
            if (e.path().extension() == ".json") scenes.push_back(e.path());
    std::sort(scenes.begin(), scenes.end());
    REQUIRE(scenes.size() >= 5);
    const fs::path tmp =
        fs::temp_directory_path() / ("sphbasis_scene_mutations_" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    const std::string file = (tmp / "m.json").string();

    // Values a mutation puts somewhere: extremes of every kind the loader reads.
    const std::vector<nlohmann::json> values = {nullptr,
                                                true,
                                                0,
                                                -1,
                                                1,
                                                2,
                                                4096,
                                                8193,
                                                1e300,
                                                -1e300,
                                                1e-320,
                                                2e18,
                                                1e15,
                                                0.5,
                                                "",
                                                "x",
                                                "sphere",
                                                "quad",
                                                "box",
                                                "torus",
                                                "../quad_uv.obj",
                                                std::string(300, 'k'),
                                                nlohmann::json::array(),
                                                nlohmann::json::array({1, 2, 3}),
                                                nlohmann::json::array({1e300, 0, 0}),
                                                nlohmann::json::array({0, 0, 0}),
                                                nlohmann::json::object(),
                                                nlohmann::json::parse(R"({"shape": "quad"})")};

    std::mt19937_64 rng(20261204);
    std::size_t loaded = 0, refused = 0;
    const auto t0 = std::chrono::steady_clock::now();
    const std::clock_t c0 = std::clock();
    const int iterations = 1500;
    for (int it = 0; it < iterations; ++it) {
        const fs::path& src = scenes[std::size_t(it) % scenes.size()];
        std::string text = slurp(src.string());
        // Files named by the scene resolve against its own directory.
        nlohmann::json j = nlohmann::json::parse(text);
        std::function<void(nlohmann::json&)> absolutise = [&](nlohmann::json& n) {
            if (n.is_object()) {
                for (auto e = n.begin(); e != n.end(); ++e) {
                    const std::string& k = e.key();
                    if ((k == "file" || k == "albedo_map" || k == "normal_map") &&
                        e.value().is_string())
                        e.value() = (src.parent_path() / e.value().get<std::string>()).string();
                    else
                        absolutise(e.value());
                }
            } else if (n.is_array()) {
                for (auto& v : n) absolutise(v);
            }
        };
        absolutise(j);
        const int kind = int(rng() % 3);
        if (kind == 2) {
            // Numbers: scale one number by 2^k, k in [-4, 4] (mostly still a valid scene), or
            // by a power of ten up to 1e30 either way.
            std::vector<nlohmann::json*> nums;
            std::function<void(nlohmann::json&)> collect = [&](nlohmann::json& n) {
                if (n.is_number()) nums.push_back(&n);
                if (n.is_structured())  // (a primitive iterates over itself)
                    for (auto& v : n) collect(v);
            };
            collect(j);
            if (!nums.empty()) {
                nlohmann::json& n = *nums[rng() % nums.size()];
                const double f = rng() % 4 ? std::ldexp(1.0, int(rng() % 9) - 4)
                                           : std::pow(10.0, double(int(rng() % 61) - 30));
                n = n.get<double>() * f;
            }
            text = j.dump();
        } else if (kind == 0) {
            // Structure: replace a random node (object member or array element) by a value,
            // once or twice.
            for (int m = 0, n = 1 + int(rng() % 2); m < n; ++m) {
                nlohmann::json* node = &j;
                for (int depth = 0; depth < 6 && (node->is_object() || node->is_array()) &&
                                    !node->empty() && rng() % 4 != 0;
                     ++depth) {
                    auto child = node->begin();
                    std::advance(child, std::ptrdiff_t(rng() % node->size()));
                    node = &*child;
                }
                *node = values[rng() % values.size()];
            }
            text = j.dump();
        } else {
            // Bytes: replace, delete or insert up to four bytes of the (indented) text.
            text = j.dump(1);
            for (int m = 0, n = 1 + int(rng() % 4); m < n && !text.empty(); ++m) {
                const std::size_t at = rng() % text.size();
                const char pick[] = "{}[],:\"0123456789.eE-+ \n\\aZ\x01\x7f\xff";
                const char ch = pick[rng() % (sizeof pick - 1)];
                switch (rng() % 3) {
                    case 0:
                        text[at] = ch;
                        break;
                    case 1:
                        text.erase(at, 1);
                        break;
                    default:
                        text.insert(text.begin() + std::ptrdiff_t(at), ch);
                }
            }
        }
        {
            std::ofstream out(file, std::ios::binary);
            out << text;
        }
        INFO("mutation " << it << " of " << src.filename().string() << ": " << text.substr(0, 300));
        try {
            const SceneFile s = load_scene(file);
            REQUIRE(!s.meshes.empty());
            ++loaded;
        } catch (const std::exception& e) {
            const std::string msg = e.what();
            INFO("message: " << msg);
            CHECK(msg.rfind(file + ": ", 0) == 0);
            CHECK(msg.find('\n') == std::string::npos);
            CHECK(msg.size() <= 400 + file.size());
            ++refused;
        }
    }
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double cpu = double(std::clock() - c0) / CLOCKS_PER_SEC;
    WARN("scene mutations: " << iterations << " in " << secs << " s wall, " << cpu << " s CPU ("
                             << loaded << " loaded, " << refused << " refused)");
    fs::remove_all(tmp);
    CHECK(loaded > 150);
    CHECK(refused > 500);
}

TEST_CASE("render: coordinates beyond coordinate_limit are refused, not passed to Embree",
          "[tool]") {
    using namespace sphbasis;
    render::Mesh m = render::shapes::quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 1);
    {
        render::Mesh far = m;
        far.positions[0] = 2e18f;  // Embree aborted on an assertion here
        REQUIRE_THROWS_WITH(render::Scene({far.view()}),
                            Catch::Contains("render::Scene(): expected vertex coordinates within "
                                            "[-1e15, 1e15] (render::coordinate_limit), got "
                                            "1999999968613498880") &&
                                Catch::Contains("(mesh 0)"));
        far.positions[0] = -1e15f;  // the bound itself (as float: 999999986991104) is accepted
        CHECK_NOTHROW(render::Scene({far.view()}));
    }
    render::SceneDesc desc;
    desc.meshes.push_back(m.view());
    render::BakeSettings s;
    s.quantities = render::Quantity::ao;
    s.rays = 4;
    render::Baker baker(desc, s);
    render::BakePoint p;
    p.n = {0, 0, 1};
    p.p = {0, 0, 1e15};
    CHECK(baker.bake({p}).size() == 1);
    p.p = {0, -2e18, 0};
    REQUIRE_THROWS_WITH(
        baker.bake({p}),
        Catch::Contains("positions within [-1e15, 1e15] (render::coordinate_limit), "
                        "got -2000000000000000000.000000 at point 0"));
}
