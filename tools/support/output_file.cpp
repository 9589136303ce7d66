// sphbasis CLI support: OutputFiles, write_file_atomic and the signal cleanup (see
// output_file.hpp).
#include "output_file.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>
#if defined(__linux__)
#include <sys/syscall.h>
#endif

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "args.hpp"

namespace sphbasis::cli {

const char* const staging_prefix = ".sphbasis-staging-";

// ---------------------------------------------------------------------------------------------
// The registry the signal handler reads: fixed slots (no allocation in the handler), each a
// staging directory to empty and remove, or an output directory chain to rmdir.

namespace {

constexpr int kSlots = 64;
enum SlotState : int { kFree = 0, kFilling = 1, kStaging = 2, kCreated = 3, kClaimed = 4 };

struct Slot {
    std::atomic<int> state{kFree};
    int levels = 0;  // kCreated: how many directories, from path up, the run created
    char path[PATH_MAX] = {};
};
Slot g_slots[kSlots];
std::atomic<int> g_commit_depth{0};  // > 0 while a commit renames
std::atomic<int> g_pending{0};       // a signal that waits for the renames
std::atomic<int> g_dying{0};
char g_prefix[256] = {};
std::atomic<unsigned long> g_counter{0};

/// A slot for `path`, or -1 when none is free or the path is too long (then a signal leaves
/// the directory behind for the next run to remove).
int register_slot(const std::string& path, int kind, int levels) {
    if (path.size() >= PATH_MAX) return -1;
    for (int i = 0; i < kSlots; ++i) {
        int expected = kFree;
        if (g_slots[i].state.compare_exchange_strong(expected, kFilling)) {
            std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
            g_slots[i].levels = levels;
            g_slots[i].state.store(kind, std::memory_order_release);
            return i;
        }
    }
    return -1;
}

void release_slot(int& i, int kind) noexcept {
    if (i < 0) return;
    int expected = kind;
    g_slots[i].state.compare_exchange_strong(expected, kFree);
    i = -1;
}

/// Empties a flat directory (files only, as a staging is) and removes it, with
/// async-signal-safe calls only: open, getdents64, unlinkat, close, rmdir. Retries when
/// another thread created a file meanwhile.
void remove_flat_dir(const char* path) noexcept {
#if defined(__linux__)
    for (int attempt = 0; attempt < 16; ++attempt) {
        const int dfd = ::open(path, O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
        if (dfd < 0) return;
        alignas(8) char buf[4096];
        for (;;) {
            const long n = ::syscall(SYS_getdents64, dfd, buf, sizeof buf);
            if (n <= 0) break;
            for (long off = 0; off < n;) {
                // struct linux_dirent64: u64 d_ino, s64 d_off, u16 d_reclen, u8 d_type, name.
                unsigned short reclen = 0;
                std::memcpy(&reclen, buf + off + 16, sizeof reclen);
                const char* name = buf + off + 19;
                const bool dots =
                    name[0] == '.' && (name[1] == 0 || (name[1] == '.' && name[2] == 0));
                if (!dots) ::unlinkat(dfd, name, 0);
                if (reclen == 0) break;
                off += reclen;
            }
        }
        ::close(dfd);
        if (::rmdir(path) == 0 || errno == ENOENT || errno == ENOTDIR) return;
    }
#else
    ::rmdir(path);  // elsewhere a staging left by a signal is removed by the next run
#endif
}

/// rmdir of path and of `levels - 1` parents, each only if empty; async-signal-safe.
void remove_created_dirs(const char* path, int levels) noexcept {
    char buf[PATH_MAX];
    std::size_t n = 0;
    while (path[n] != 0 && n + 1 < sizeof buf) {
        buf[n] = path[n];
        ++n;
    }
    buf[n] = 0;
    for (int k = 0; k < levels && n > 0; ++k) {
        if (::rmdir(buf) != 0) return;
        while (n > 0 && buf[n - 1] != '/') --n;  // drop the last component
        while (n > 1 && buf[n - 1] == '/') --n;  // and the slashes before it
        buf[n] = 0;
    }
}

void cleanup_slots() noexcept {
    for (int kind : {int(kStaging), int(kCreated)})
        for (Slot& s : g_slots) {
            int expected = kind;
            if (!s.state.compare_exchange_strong(expected, kClaimed)) continue;
            if (kind == kStaging)
                remove_flat_dir(s.path);
            else
                remove_created_dirs(s.path, s.levels);
        }
}

const char* signal_name(int sig) noexcept {
    switch (sig) {
        case SIGINT:
            return "SIGINT";
        case SIGTERM:
            return "SIGTERM";
        case SIGHUP:
            return "SIGHUP";
        case SIGPIPE:
            return "SIGPIPE";
    }
    return "a signal";
}

void put(const char* s) noexcept {
    std::size_t n = 0;
    while (s[n] != 0) ++n;
    while (n > 0) {
        const ssize_t w = ::write(2, s, n);
        if (w <= 0) return;
        s += w;
        n -= static_cast<std::size_t>(w);
    }
}

/// Removes the staging, says so (not for SIGPIPE: a reader that went away is no news), and
/// ends the process by `sig` so that the parent sees how it ended.
[[noreturn]] void die_of(int sig, bool after_commit) noexcept {
    if (g_dying.exchange(1) != 0)
        for (;;) ::pause();  // another thread is cleaning up and will end the process
    cleanup_slots();
    if (sig != SIGPIPE && g_prefix[0] != 0) {
        put("\n");  // after a progress bar's partial line
        put(g_prefix);
        put(": interrupted by ");
        put(signal_name(sig));
        put(after_commit ? " (after the outputs were written)\n"
                         : "; no output written (the staging was removed)\n");
    }
    struct sigaction sa {};
    sa.sa_handler = SIG_DFL;
    sigemptyset(&sa.sa_mask);
    ::sigaction(sig, &sa, nullptr);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, sig);
    ::pthread_sigmask(SIG_UNBLOCK, &set, nullptr);
    ::raise(sig);
    ::_exit(128 + sig);
}

extern "C" void on_signal(int sig) {
    const int saved = errno;
    g_pending.store(sig);
    if (g_commit_depth.load() == 0) {
        const int s = g_pending.exchange(0);
        if (s != 0) die_of(s, false);
    }
    errno = saved;  // the renames go on; commit() ends the process after them
}

void begin_renames() noexcept { g_commit_depth.fetch_add(1); }
void end_renames() noexcept {
    g_commit_depth.fetch_sub(1);
    const int s = g_pending.exchange(0);
    if (s != 0) die_of(s, true);
}

// ---------------------------------------------------------------------------------------------
// Paths

std::runtime_error write_error(const std::string& path, const std::string& why) {
    return std::runtime_error("cannot write '" + path + "': " + why);
}
std::runtime_error write_error(const std::string& path, int err) {
    return write_error(path, std::strerror(err));
}

std::string base_of(const std::string& p) {
    const std::size_t s = p.find_last_of('/');
    return s == std::string::npos ? p : p.substr(s + 1);
}
/// The directory part of p: "" for a bare name, "/" for "/x".
std::string dir_of(const std::string& p) {
    const std::size_t s = p.find_last_of('/');
    if (s == std::string::npos) return "";
    return s == 0 ? "/" : p.substr(0, s);
}
std::string dir_or_dot(const std::string& p) {
    const std::string d = dir_of(p);
    return d.empty() ? "." : d;
}

bool same_file(const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
}

/// The file a chain of symbolic links ends at (the last path that is not a link, which may
/// not exist: a dangling link).
std::string resolve_links(const std::string& path) {
    std::string cur = path;
    for (int hop = 0; hop < 40; ++hop) {
        struct stat s;
        if (::lstat(cur.c_str(), &s) != 0 || !S_ISLNK(s.st_mode)) return cur;
        std::vector<char> buf(PATH_MAX + 1);
        const ssize_t n = ::readlink(cur.c_str(), buf.data(), buf.size() - 1);
        if (n <= 0) throw write_error(path, n < 0 ? errno : ENOENT);
        const std::string to(buf.data(), static_cast<std::size_t>(n));
        cur = to[0] == '/' ? to : join_path(dir_of(cur), to);
    }
    throw write_error(path, ELOOP);
}

long name_max_of(const std::string& dir) {
    const long n = ::pathconf(dir.c_str(), _PC_NAME_MAX);
    return n > 0 ? n : NAME_MAX;
}

void check_lengths(const std::string& shown, const std::string& target) {
    if (target.size() + 1 > PATH_MAX) throw write_error(shown, ENAMETOOLONG);
    const std::string base = base_of(target);
    const long max = name_max_of(dir_or_dot(target));
    if (static_cast<long>(base.size()) > max)
        throw write_error(shown, "a file name of " + std::to_string(base.size()) +
                                     " bytes, longer than the file system's limit of " +
                                     std::to_string(max));
}

bool process_alive(long pid) {
    if (pid <= 0 || pid > INT_MAX) return false;
    return ::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM;
}

/// Removes the staging directories in `dir` of processes that are gone (a run killed by
/// SIGKILL or a power cut), if they belong to this user. Best effort: errors are ignored.
void remove_stale_stagings(const std::string& dir) {
    DIR* d = ::opendir(dir.c_str());
    if (d == nullptr) return;
    std::vector<std::string> stale;
    const std::size_t plen = std::strlen(staging_prefix);
    while (const dirent* e = ::readdir(d)) {
        const std::string name = e->d_name;
        if (name.compare(0, plen, staging_prefix) != 0) continue;
        std::size_t i = plen;
        long pid = 0;
        while (i < name.size() && name[i] >= '0' && name[i] <= '9' && pid < INT_MAX)
            pid = pid * 10 + (name[i++] - '0');
        if (i == plen || (i < name.size() && name[i] != '-')) continue;
        if (pid == static_cast<long>(::getpid()) || process_alive(pid)) continue;
        stale.push_back(join_path(dir, name));
    }
    ::closedir(d);
    for (const std::string& s : stale) {
        // Only a real directory of this user (in /tmp another user's is none of our business).
        struct stat st;
        if (::lstat(s.c_str(), &st) != 0 || !S_ISDIR(st.st_mode) || st.st_uid != ::geteuid())
            continue;
        std::error_code ec;
        std::filesystem::remove_all(s, ec);
    }
}

void write_all(int fd, const char* p, std::size_t left, int& err) {
    while (left > 0 && err == 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno != EINTR) err = errno;
            continue;
        }
        p += n;
        left -= static_cast<std::size_t>(n);
    }
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// OutputFiles

enum class OutputKind { replace, direct, stdio };

struct OutputFiles::Staging {
    std::string path;  // dir/.sphbasis-staging-<pid>-<n>
    dev_t dev = 0;     // of the directory it is in
    ino_t ino = 0;
    int slot = -1;
};

struct OutputFiles::Output {
    std::string path;    // as declared
    std::string target;  // the file replaced or opened
    OutputKind kind = OutputKind::replace;
    int fd = -1;  // stdio: 1 or 2
    Staging* staging = nullptr;
    std::string stage;  // the staging file of a replaced output
    std::string bytes;  // the contents of a direct output
    bool prepared = false, added = false;
};

OutputFiles::OutputFiles(std::string out_dir) : dir_(std::move(out_dir)) {}

OutputFiles::~OutputFiles() {
    if (!done_) abort();
}

void OutputFiles::classify(Output& out) const {
    const std::string& p = out.path;
    if (p.empty()) throw write_error(p, "expected a path");
    if (p.find('\0') != std::string::npos) throw write_error(p, "a NUL byte in the path");
    if (p.size() + 1 > PATH_MAX) throw write_error(p, ENAMETOOLONG);
    struct stat ls;
    if (::lstat(p.c_str(), &ls) != 0) {
        const int err = errno;
        if (err != ENOENT) throw write_error(p, err);
        if (base_of(p).empty()) throw write_error(p, "expected a file name, got a directory path");
        out.kind = OutputKind::replace;
        out.target = p;
        check_lengths(p, p);
        return;
    }
    struct stat st;
    if (::stat(p.c_str(), &st) != 0) {
        const int err = errno;
        if (!(S_ISLNK(ls.st_mode) && err == ENOENT)) throw write_error(p, err);
        // A dangling link: its target is created.
        out.kind = OutputKind::replace;
        out.target = resolve_links(p);
        struct stat ts;
        if (::lstat(out.target.c_str(), &ts) != 0 && errno != ENOENT) throw write_error(p, errno);
        check_lengths(p, out.target);
        return;
    }
    // Standard output or error by a path (/dev/stdout, /proc/self/fd/1, a tty or pipe): the
    // stream itself, after what the command printed.
    if (S_ISLNK(ls.st_mode) || !S_ISREG(st.st_mode))
        for (int fd : {1, 2}) {
            struct stat fs;
            if (::fstat(fd, &fs) == 0 && same_file(fs, st)) {
                out.kind = OutputKind::stdio;
                out.fd = fd;
                out.target = p;
                return;
            }
        }
    if (S_ISDIR(st.st_mode)) throw write_error(p, EISDIR);
    if (!S_ISREG(st.st_mode)) {
        out.kind = OutputKind::direct;
        out.target = p;
        return;
    }
    out.kind = OutputKind::replace;
    out.target = p;
    if (S_ISLNK(ls.st_mode)) {
        const std::string t = resolve_links(p);
        struct stat ts;
        if (::lstat(t.c_str(), &ts) == 0 && S_ISREG(ts.st_mode) && same_file(ts, st)) {
            out.target = t;
        } else {
            out.kind = OutputKind::direct;  // a magic link (/proc/self/fd/N): no real path
            return;
        }
    }
    check_lengths(p, out.target);
}

void OutputFiles::declare(const std::string& path) {
    if (!dir_.empty() && outputs_.empty()) {
        // An output directory that cannot be one fails here, with the directory's name.
        struct stat s;
        const int err = ::stat(dir_.c_str(), &s) == 0 ? (S_ISDIR(s.st_mode) ? 0 : ENOTDIR)
                        : errno == ENOENT             ? 0
                                                      : errno;
        if (err != 0)
            throw std::runtime_error("cannot create output directory '" + dir_ +
                                     "': " + std::strerror(err));
    }
    auto out = std::make_unique<Output>();
    out->path = path;
    classify(*out);
    // A file replaced twice is a mistake; a device or stream written twice is not (/dev/null).
    if (out->kind == OutputKind::replace)
        for (const auto& o : outputs_)
            if (o->path == path) throw write_error(path, "given as two outputs");
    outputs_.push_back(std::move(out));
    if (prepared_) prepare_one(*outputs_.back());
}

std::string OutputFiles::declare_in(const std::string& dir, const std::string& name) {
    const std::string shown = join_path(dir, quote_input(name));
    if (name.empty() || name == "." || name == "..")
        throw write_error(shown, "expected a file name, got '" + name + "'");
    if (name.find('/') != std::string::npos)
        throw write_error(shown, "a '/' in a file name made from the input");
    if (name.find('\0') != std::string::npos)
        throw write_error(shown, "a NUL byte in a file name made from the input");
    const long max = name_max_of(dir.empty() ? "." : dir);
    if (static_cast<long>(name.size()) > max)
        throw write_error(shown, "a file name of " + std::to_string(name.size()) +
                                     " bytes, longer than the file system's limit of " +
                                     std::to_string(max));
    const std::string path = join_path(dir, name);
    declare(path);
    return path;
}

void OutputFiles::prepare() {
    if (!prepared_ && !dir_.empty()) {
        // How many directories of dir_ are missing: those a failed run removes again.
        std::string d = dir_;
        while (d.size() > 1 && d.back() == '/') d.pop_back();
        int missing = 0;
        for (std::string p = d; !p.empty() && p != "/" && p != ".";) {
            struct stat s;
            if (::lstat(p.c_str(), &s) == 0 || errno != ENOENT) break;
            ++missing;
            p = dir_of(p);
        }
        if (missing > 0) created_slot_ = register_slot(d, kCreated, missing);
        created_dir_ = d;
        created_levels_ = missing;
        std::error_code ec;
        std::filesystem::create_directories(dir_, ec);
        if (ec || !std::filesystem::is_directory(dir_)) {
            abort();
            throw std::runtime_error("cannot create output directory '" + dir_ + "'" +
                                     (ec ? ": " + ec.message() : std::string()));
        }
    }
    prepared_ = true;
    for (auto& o : outputs_)
        if (!o->prepared) prepare_one(*o);
}

void OutputFiles::prepare_one(Output& out) {
    classify(out);  // again: the output directory may exist now
    if (out.kind != OutputKind::replace) {
        if (out.kind == OutputKind::direct && ::access(out.target.c_str(), W_OK) != 0)
            throw write_error(out.path, errno);
        out.prepared = true;
        return;
    }
    const std::string dir = dir_or_dot(out.target);
    struct stat ds;
    if (::stat(dir.c_str(), &ds) != 0) throw write_error(out.path, errno);
    if (!S_ISDIR(ds.st_mode)) throw write_error(out.path, ENOTDIR);
    Staging* staging = nullptr;
    for (const auto& s : stagings_)
        if (s->dev == ds.st_dev && s->ino == ds.st_ino) staging = s.get();
    if (staging == nullptr) {
        remove_stale_stagings(dir);
        auto s = std::make_unique<Staging>();
        s->path = join_path(dir_of(out.target), staging_prefix +
                                                    std::to_string(static_cast<long>(::getpid())) +
                                                    "-" + std::to_string(g_counter.fetch_add(1)));
        s->dev = ds.st_dev;
        s->ino = ds.st_ino;
        s->slot = register_slot(s->path, kStaging, 0);  // before mkdir: a signal may come
        if (::mkdir(s->path.c_str(), 0700) != 0) {
            const int err = errno;
            release_slot(s->slot, kStaging);
            throw write_error(out.path, err);
        }
        stagings_.push_back(std::move(s));
        staging = stagings_.back().get();
    }
    const std::string base = base_of(out.target);
    for (const auto& o : outputs_)
        if (o.get() != &out && o->prepared && o->staging == staging && base_of(o->target) == base)
            throw write_error(out.path, "the same file as the output '" + o->path + "'");
    out.staging = staging;
    out.stage = join_path(staging->path, base);
    if (out.stage.size() + 1 > PATH_MAX) throw write_error(out.path, ENAMETOOLONG);
    out.prepared = true;
}

OutputFiles::Output& OutputFiles::find(const std::string& path) {
    // A path declared twice (a stream: --json /dev/stdout --csv /dev/stdout) takes the
    // contents in the order of the declarations.
    Output* last = nullptr;
    for (auto& o : outputs_)
        if (o->path == path) {
            if (!o->added) return *o;
            last = o.get();
        }
    if (last != nullptr) return *last;
    declare(path);
    if (!prepared_) prepare();
    return *outputs_.back();
}

void OutputFiles::add(const std::string& path, const void* data, std::size_t size) {
    if (done_)
        throw std::logic_error(
            "sphbasis::cli::OutputFiles::add(): expected no add after "
            "commit() or abort()");
    Output& out = find(path);
    if (!out.prepared) prepare();
    const char* p = static_cast<const char*>(data);
    if (out.kind != OutputKind::replace) {
        out.bytes.assign(p, size);
        out.added = true;
        return;
    }
    const int fd = ::open(out.stage.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw write_error(path, errno);
    int err = 0;
    write_all(fd, p, size, err);
    // close() reports delayed write errors (NFS, ENOSPC on some file systems).
    if (::close(fd) != 0 && err == 0) err = errno;
    if (err != 0) {
        ::unlink(out.stage.c_str());
        throw write_error(path, err);
    }
    out.added = true;
}

void OutputFiles::commit() {
    if (done_) throw std::logic_error("sphbasis::cli::OutputFiles::commit(): committed twice");
    // Direct outputs first: they cannot be undone, so a failure among them changes no file.
    bool flushed = false;
    for (auto& o : outputs_) {
        if (!o->added || o->kind == OutputKind::replace) continue;
        if (!flushed) {  // after what the command printed
            std::cout.flush();
            std::fflush(stdout);
            std::fflush(stderr);
            flushed = true;
        }
        int err = 0;
        const int fd = o->kind == OutputKind::stdio
                           ? o->fd
                           : ::open(o->target.c_str(), O_WRONLY | O_TRUNC | O_NOCTTY | O_CLOEXEC);
        if (fd < 0) {
            err = errno;
        } else {
            write_all(fd, o->bytes.data(), o->bytes.size(), err);
            if (o->kind != OutputKind::stdio && ::close(fd) != 0 && err == 0) err = errno;
        }
        if (err != 0) {
            abort();
            throw write_error(o->path, err);
        }
    }
    // Then the renames, each replaced file kept as a hard link in the staging until all are
    // done, so that a failed rename undoes the ones before it.
    struct Renamed {
        Output* out;
        std::string backup;  // "" when the destination was new (or no link could be made)
        bool existed;
    };
    std::vector<Renamed> renamed;
    begin_renames();
    std::size_t n = 0;
    for (auto& o : outputs_) {
        if (!o->added || o->kind != OutputKind::replace) continue;
        Renamed r{o.get(), "", false};
        struct stat st;
        if (::lstat(o->target.c_str(), &st) == 0) {
            r.existed = true;
            if (S_ISREG(st.st_mode)) {
                r.backup = join_path(o->staging->path, ".old-" + std::to_string(n++));
                if (::link(o->target.c_str(), r.backup.c_str()) != 0) r.backup.clear();
                ::chmod(o->stage.c_str(), st.st_mode & 07777);  // keep the file's permissions
            }
        }
        if (::rename(o->stage.c_str(), o->target.c_str()) != 0) {
            const int err = errno;
            for (auto it = renamed.rbegin(); it != renamed.rend(); ++it) {
                if (!it->backup.empty())
                    ::rename(it->backup.c_str(), it->out->target.c_str());
                else if (!it->existed)
                    ::unlink(it->out->target.c_str());
            }
            abort();
            end_renames();
            throw write_error(o->path, err);
        }
        renamed.push_back(r);
    }
    for (auto& s : stagings_) {
        remove_flat_dir(s->path.c_str());
        release_slot(s->slot, kStaging);
    }
    release_slot(created_slot_, kCreated);
    done_ = true;
    end_renames();
}

void OutputFiles::abort() noexcept {
    for (auto& s : stagings_) {
        remove_flat_dir(s->path.c_str());
        release_slot(s->slot, kStaging);
    }
    stagings_.clear();
    if (created_levels_ > 0) remove_created_dirs(created_dir_.c_str(), created_levels_);
    created_levels_ = 0;
    release_slot(created_slot_, kCreated);
    done_ = true;
}

void write_file_atomic(const std::string& path, const void* data, std::size_t size) {
    OutputFiles out;
    out.declare(path);
    out.prepare();
    out.add(path, data, size);
    out.commit();
}

void install_signal_cleanup(const std::string& prefix) {
    const std::size_t n = std::min(prefix.size(), sizeof g_prefix - 1);
    std::memcpy(g_prefix, prefix.data(), n);
    g_prefix[n] = 0;
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) sigaddset(&sa.sa_mask, sig);
    sa.sa_flags = SA_RESTART;
    for (int sig : {SIGINT, SIGTERM, SIGHUP, SIGPIPE}) {
        struct sigaction old {};
        // A signal ignored when the tool started stays ignored (nohup, `&` in a script).
        if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
        ::sigaction(sig, &sa, nullptr);
    }
}

std::string join_path(const std::string& dir, const std::string& name) {
    return dir.empty() || dir == "." ? name : (dir.back() == '/' ? dir + name : dir + "/" + name);
}

void ensure_dir(const std::string& dir) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec || !std::filesystem::is_directory(dir))
        throw std::runtime_error("cannot create output directory '" + dir + "'" +
                                 (ec ? ": " + ec.message() : std::string()));
}

}  // namespace sphbasis::cli
