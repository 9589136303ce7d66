// Outputs written whole or not at all, by the kind of their path (tools/support/
// output_file.hpp): symbolic links written through, devices and FIFOs written directly and
// never replaced, a directory in the way or a name too long refused before anything is
// written, a failed commit undone, stale staging directories removed, and a signal that
// removes the staging. Each case checks the file system itself (lstat, the bytes read back).
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <sys/wait.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "support/output_file.hpp"

using namespace sphbasis::cli;
namespace fs = std::filesystem;

namespace {

/// A fresh empty directory under the temporary directory, removed at the end of the case.
struct TempDir {
    std::string path;
    TempDir() {
        char tmpl[] = "/tmp/sphbasis-output-test-XXXXXX";
        const char* p = ::mkdtemp(tmpl);
        REQUIRE(p != nullptr);
        path = p;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
    std::string operator/(const std::string& name) const { return path + "/" + name; }
};

std::string read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void write_plain(const std::string& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

/// The names in dir that start with the staging prefix.
int stagings_in(const std::string& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.path().filename().string().rfind(staging_prefix, 0) == 0) ++n;
    return n;
}

int entries_in(const std::string& dir) {
    int n = 0;
    for (const auto& e : fs::directory_iterator(dir)) {
        (void)e;
        ++n;
    }
    return n;
}

bool is_kind(const std::string& path, mode_t kind) {
    struct stat s;
    return ::lstat(path.c_str(), &s) == 0 && (s.st_mode & S_IFMT) == kind;
}

}  // namespace

TEST_CASE("output: a symlink is written through and stays a link", "[tools][output]") {
    TempDir d;
    write_plain(d / "target.json", "old");
    REQUIRE(::symlink("target.json", (d / "link.json").c_str()) == 0);
    write_file_atomic(d / "link.json", std::string("new contents"));
    CHECK(is_kind(d / "link.json", S_IFLNK));
    CHECK(is_kind(d / "target.json", S_IFREG));
    CHECK(read_all(d / "target.json") == "new contents");
    CHECK(stagings_in(d.path) == 0);
    CHECK(entries_in(d.path) == 2);

    // A chain of links into another directory: the staging is beside the final target.
    fs::create_directory(d / "sub");
    write_plain(d / "sub/t", "old");
    REQUIRE(::symlink("sub/t", (d / "l1").c_str()) == 0);
    REQUIRE(::symlink(fs::absolute(d / "l1").c_str(), (d / "l2").c_str()) == 0);
    write_file_atomic(d / "l2", std::string("through two links"));
    CHECK(is_kind(d / "l1", S_IFLNK));
    CHECK(is_kind(d / "l2", S_IFLNK));
    CHECK(read_all(d / "sub/t") == "through two links");
    CHECK(stagings_in(d / "sub") == 0);

    // A dangling link: its target is created.
    REQUIRE(::symlink("made.json", (d / "dangling").c_str()) == 0);
    write_file_atomic(d / "dangling", std::string("made"));
    CHECK(is_kind(d / "dangling", S_IFLNK));
    CHECK(read_all(d / "made.json") == "made");
}

TEST_CASE("output: /dev/null and a FIFO are written directly", "[tools][output]") {
    write_file_atomic("/dev/null", std::string("discarded"));
    CHECK(is_kind("/dev/null", S_IFCHR));

    TempDir d;
    const std::string fifo = d / "fifo";
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    std::string got;
    std::thread reader([&] { got = read_all(fifo); });
    const std::string bytes(200000, 'x');  // more than a pipe buffer
    write_file_atomic(fifo, bytes);
    reader.join();
    CHECK(got == bytes);
    CHECK(is_kind(fifo, S_IFIFO));
    CHECK(entries_in(d.path) == 1);  // no staging beside it
}

TEST_CASE("output: a character device is never replaced; ENOSPC is an error", "[tools][output]") {
    TempDir d;
    std::string full = "/dev/full", null = "/dev/null";
    if (::geteuid() == 0) {
        // Private copies: a wrong rename would replace these, not the system's nodes.
        full = d / "full";
        null = d / "null";
        REQUIRE(::mknod(full.c_str(), S_IFCHR | 0666, ::makedev(1, 7)) == 0);
        REQUIRE(::mknod(null.c_str(), S_IFCHR | 0666, ::makedev(1, 3)) == 0);
    } else {
        WARN("not root: /dev/full itself is used (no private device node)");
    }
    REQUIRE_THROWS_WITH(write_file_atomic(full, std::string("x")),
                        "cannot write '" + full + "': No space left on device");
    CHECK(is_kind(full, S_IFCHR));
    write_file_atomic(null, std::string("x"));
    CHECK(is_kind(null, S_IFCHR));

    // A failed direct write changes no other output of the command.
    write_plain(d / "a.json", "old");
    {
        OutputFiles out;
        out.declare(d / "a.json");
        out.declare(full);
        out.prepare();
        out.add(d / "a.json", std::string("new"));
        out.add(full, std::string("x"));
        CHECK_THROWS_WITH(out.commit(), Catch::Contains("No space left on device"));
    }
    CHECK(read_all(d / "a.json") == "old");
    CHECK(stagings_in(d.path) == 0);
}

TEST_CASE("output: a directory in the way, a bad or too long name fail before writing",
          "[tools][output]") {
    TempDir d;
    fs::create_directory(d / "taken.json");
    OutputFiles out(d.path);
    CHECK_THROWS_WITH(out.declare(d / "taken.json"),
                      "cannot write '" + (d / "taken.json") + "': Is a directory");
    CHECK_THROWS_WITH(out.declare_in(d.path, std::string(300, 'a') + ".ply"),
                      Catch::Contains("a file name of 304 bytes, longer than the file system's "
                                      "limit of 255"));
    CHECK_THROWS_WITH(out.declare_in(d.path, "a/b.ply"), Catch::Contains("a '/' in a file name"));
    CHECK_THROWS_WITH(out.declare_in(d.path, std::string("a\0b", 3)),
                      Catch::Contains("a NUL byte"));
    CHECK_THROWS_WITH(out.declare_in(d.path, ".."), Catch::Contains("expected a file name"));
    CHECK_THROWS_WITH(out.declare(d.path + "/x/"),
                      Catch::Contains("expected a file name, got a directory path"));
    {
        OutputFiles missing;  // a missing directory is found by prepare(), before the work
        missing.declare(d / "no/x.json");
        CHECK_THROWS_WITH(missing.prepare(),
                          "cannot write '" + (d / "no/x.json") + "': No such file or directory");
    }
    out.declare(d / "one.json");
    CHECK_THROWS_WITH(out.declare(d / "one.json"), Catch::Contains("given as two outputs"));
    out.declare(d.path + "/./one.json");
    CHECK_THROWS_WITH(out.prepare(), Catch::Contains("the same file as the output"));
    out.abort();
    CHECK(entries_in(d.path) == 1);  // the directory in the way, nothing else
    // A name of exactly NAME_MAX bytes is fine.
    write_file_atomic(d / std::string(255, 'b'), std::string("ok"));
    CHECK(read_all(d / std::string(255, 'b')) == "ok");
}

TEST_CASE("output: all or none, and a failed commit undoes its renames", "[tools][output]") {
    TempDir d;
    write_plain(d / "a", "old a");
    write_plain(d / "c", "old c");
    ::chmod((d / "c").c_str(), 0600);
    SECTION("a failure before commit changes nothing") {
        {
            OutputFiles out(d.path);
            for (const char* n : {"a", "b", "c"}) out.declare_in(d.path, n);
            out.prepare();
            CHECK(stagings_in(d.path) == 1);
            out.add(d / "a", std::string("new a"));
            out.add(d / "b", std::string("new b"));
        }  // no commit: an exception left the scope
        CHECK(read_all(d / "a") == "old a");
        CHECK(!fs::exists(d / "b"));
        CHECK(stagings_in(d.path) == 0);
    }
    SECTION("a destination that became a directory fails the commit; the others are restored") {
        OutputFiles out(d.path);
        for (const char* n : {"a", "b", "c", "d"}) out.declare_in(d.path, n);
        out.prepare();
        for (const char* n : {"a", "b", "c", "d"}) out.add(d / n, std::string("new ") + n);
        fs::create_directory(d / "d");  // after prepare(): only the rename can fail
        fs::create_directory(d / "d/inside");
        CHECK_THROWS_WITH(out.commit(), Catch::Contains("cannot write '" + (d / "d") + "'"));
        CHECK(read_all(d / "a") == "old a");
        CHECK(!fs::exists(d / "b"));
        CHECK(read_all(d / "c") == "old c");
        CHECK(fs::is_directory(d / "d/inside"));
        CHECK(stagings_in(d.path) == 0);
    }
    SECTION("a commit replaces all, keeping the permissions of a replaced file") {
        OutputFiles out(d.path);
        for (const char* n : {"a", "b", "c"}) out.declare_in(d.path, n);
        out.prepare();
        for (const char* n : {"a", "b", "c"}) out.add(d / n, std::string("new ") + n);
        out.commit();
        CHECK(read_all(d / "a") == "new a");
        CHECK(read_all(d / "b") == "new b");
        CHECK(read_all(d / "c") == "new c");
        struct stat s;
        REQUIRE(::stat((d / "c").c_str(), &s) == 0);
        CHECK((s.st_mode & 0777) == 0600);
        CHECK(entries_in(d.path) == 3);
    }
}

TEST_CASE("output: the output directory is created by prepare() and removed by a failure",
          "[tools][output]") {
    TempDir d;
    const std::string dir = d / "new/sub";
    {
        OutputFiles out(dir);
        out.declare_in(dir, "x.json");
        CHECK(!fs::exists(d / "new"));  // declaring creates nothing
        out.prepare();
        CHECK(fs::is_directory(dir));
        out.add(join_path(dir, "x.json"), std::string("x"));
    }
    CHECK(!fs::exists(d / "new"));
    write_plain(d / "file", "");
    OutputFiles bad(d / "file");
    CHECK_THROWS_WITH(bad.declare_in(d / "file", "x.json"),
                      "cannot create output directory '" + (d / "file") + "': Not a directory");
}

TEST_CASE("output: stale staging directories of dead processes are removed", "[tools][output]") {
    TempDir d;
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) ::_exit(0);
    REQUIRE(::waitpid(child, nullptr, 0) == child);  // a pid that is gone
    const std::string dead = d / (std::string(staging_prefix) + std::to_string(child) + "-3");
    const std::string alive =
        d / (std::string(staging_prefix) + std::to_string(::getppid()) + "-0");
    const std::string other = d / (std::string(staging_prefix) + "notapid");
    for (const std::string& s : {dead, alive, other}) {
        fs::create_directory(s);
        write_plain(s + "/half.ply", "half a file");
    }
    write_file_atomic(d / "x.json", std::string("x"));
    CHECK(!fs::exists(dead));
    CHECK(fs::exists(alive + "/half.ply"));  // its process runs: may be staging right now
    CHECK(fs::exists(other + "/half.ply"));  // not a name this tool makes
}

TEST_CASE("output: SIGTERM removes the staging and the created directory, and kills",
          "[tools][output]") {
    TempDir d;
    write_plain(d / "old.json", "old");
    const std::string dir = d / "out";
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        install_signal_cleanup("test");
        ::close(2);  // no message in the test's output
        OutputFiles out(dir);
        OutputFiles beside;
        try {
            out.declare_in(dir, "a.ply");
            out.prepare();
            out.add(join_path(dir, "a.ply"), std::string(1000, 'a'));
            beside.declare(d / "old.json");
            beside.prepare();
            beside.add(d / "old.json", std::string("new"));
            ::raise(SIGTERM);
        } catch (...) {
        }
        ::_exit(3);  // not reached when the signal kills
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == SIGTERM);
    CHECK(!fs::exists(dir));
    CHECK(read_all(d / "old.json") == "old");
    CHECK(entries_in(d.path) == 1);
}

TEST_CASE("output: a signal at any moment of a commit leaves all files old or all new",
          "[tools][output]") {
    // The signal lands before the renames (the staging is removed, every file stays old) or
    // during them (it waits until all are done): never some old and some new.
    constexpr int n = 60, trials = 12;
    int all_old = 0, all_new = 0;
    for (int trial = 0; trial < trials; ++trial) {
        TempDir d;
        for (int i = 0; i < n; ++i) write_plain(d / std::to_string(i), "old");
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            install_signal_cleanup("test");
            ::close(2);
            OutputFiles out(d.path);
            for (int i = 0; i < n; ++i) out.declare_in(d.path, std::to_string(i));
            out.prepare();
            // Delays that span the writing of the staging and the commit.
            std::thread killer([trial] {
                std::this_thread::sleep_for(std::chrono::microseconds(3000 * trial));
                ::kill(::getpid(), SIGTERM);
            });
            for (int i = 0; i < n; ++i) out.add(d / std::to_string(i), std::string("new"));
            out.commit();
            killer.join();  // the signal ends the process here at the latest
            ::_exit(3);
        }
        int status = 0;
        REQUIRE(::waitpid(child, &status, 0) == child);
        CHECK(WIFSIGNALED(status));
        int fresh = 0;
        for (int i = 0; i < n; ++i) fresh += read_all(d / std::to_string(i)) == "new" ? 1 : 0;
        CHECK((fresh == 0 || fresh == n));
        CHECK(stagings_in(d.path) == 0);
        all_old += fresh == 0 ? 1 : 0;
        all_new += fresh == n ? 1 : 0;
    }
    INFO("all old " << all_old << ", all new " << all_new);
    CHECK(all_old + all_new == trials);
}
