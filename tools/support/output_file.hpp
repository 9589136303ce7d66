// sphbasis CLI support: the outputs of a command written all or none, each by the rules of
// its kind of path (the semantics of coreutils' cp and install, and of atomic editors).
//
// Path kinds (classified when the output is declared, before the work):
//   missing          a new regular file; its directory must exist (or be the command's --out,
//                    which OutputFiles creates).
//   regular file     replaced whole: written to a staging file in the same directory, then
//                    renamed over it (rename() within one directory is atomic on POSIX file
//                    systems); the replaced file's permission bits are kept. A hard link to
//                    the old file keeps the old contents.
//   symbolic link    written through to its target: the link stays a link, and the target is
//                    replaced as a regular file by a staging file beside the target (a dangling
//                    link's target is created). /dev/stdout and /proc/self/fd/N are no real
//                    links: they are written directly (below).
//   character device, FIFO, socket, block device, standard output or error (by path)
//                    written directly: opened and written at commit, never renamed over,
//                    removed or truncated by a rename, so `--json /dev/null` and
//                    `--json /dev/stdout` work and a write error (ENOSPC from /dev/full) fails
//                    the command. A FIFO's open waits for a reader.
//   directory        an error before any work: "cannot write 'PATH': Is a directory".
// Names derived from input (a mesh's name) are checked too: not empty, no '/' or NUL, at most
// NAME_MAX bytes, the whole path (and its staging name) under PATH_MAX. Two outputs that
// replace the same file are an error; a device or stream given twice (--json /dev/stdout
// --csv /dev/stdout) is written twice, in the order of the declarations.
//
// All or none: OutputFiles stages every replaced file of a command in a directory
// ".sphbasis-staging-<pid>-<n>" inside the destination's directory (the --out directory, or
// beside a single output), and moves them into place only at commit(), after every file was
// written and every direct output was written without error. A failure before commit() (a
// full disk, an exception, a signal) removes the staging and changes no destination. If a
// rename within commit() fails, the renames before it are undone (the replaced files are kept
// as hard links in the staging until the end). Direct outputs cannot be undone, so they are
// written first: a failed direct write leaves every replaced file as it was.
//
// Signals: install_signal_cleanup() makes SIGINT, SIGTERM, SIGHUP and SIGPIPE (those not
// ignored when the tool started) remove every staging directory and the output directories
// the run created (when still empty) with async-signal-safe calls, then end the process by
// that signal (exit status 130, 143, 129, 141 in a shell) at once, whatever the worker threads
// are doing. A signal that arrives during the renames of a commit waits until they are done.
// A run killed by SIGKILL leaves its staging directory; the next run that stages in the same
// directory removes every staging directory whose process is gone.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace sphbasis::cli {

/// The outputs of one command, written all or none (see the file comment). Typical use:
///   OutputFiles out(dir);             // dir: the --out directory (created by prepare()), or ""
///   out.declare(path); ...            // every output, checked now (throws std::runtime_error)
///   out.prepare();                    // creates dir and the staging; before the work
///   ... the work ...; out.add(path, bytes); ...
///   out.commit();                     // all at once; the destructor of an uncommitted set
///                                     // removes the staging (and dir, if it created it)
/// Errors are std::runtime_error "cannot write 'PATH': <reason>" (or "cannot create output
/// directory 'DIR': <reason>"). Not thread-safe: one thread declares, adds and commits.
class OutputFiles {
  public:
    explicit OutputFiles(std::string out_dir = {});
    ~OutputFiles();
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;

    /// Declares `path` as an output and checks what can be checked without writing: its
    /// length, its kind (a directory is an error), a symlink's target. Creates nothing.
    void declare(const std::string& path);
    /// Declares the output join_path(dir, name) for a name derived from input (a mesh's name
    /// plus an extension) and returns it: name must be non-empty, other than "." and "..",
    /// free of '/' and NUL and at most NAME_MAX bytes.
    std::string declare_in(const std::string& dir, const std::string& name);
    /// Creates the output directory (if given and missing) and the staging directories of the
    /// outputs declared so far, removing stale staging directories of dead processes beside
    /// them: after this, every declared output is known to be writable (a direct output by
    /// access(W_OK)). Call once the input is validated and before the work. Idempotent.
    void prepare();
    /// Writes the contents of output `path` into its staging (a direct output keeps them in
    /// memory). An output not declared before is declared and prepared now.
    void add(const std::string& path, const void* data, std::size_t size);
    void add(const std::string& path, const std::string& bytes) {
        add(path, bytes.data(), bytes.size());
    }
    /// Moves every added output into place (declared outputs never added are left alone) and
    /// removes the staging. On failure nothing changed (see the file comment) and it throws.
    void commit();
    /// Removes the staging and an output directory this set created, if empty. Never throws.
    void abort() noexcept;

  private:
    struct Output;
    struct Staging;
    Output& find(const std::string& path);
    void classify(Output& out) const;
    void prepare_one(Output& out);

    std::string dir_;
    std::vector<std::unique_ptr<Output>> outputs_;
    std::vector<std::unique_ptr<Staging>> stagings_;
    std::string created_dir_;  // the top-most directory prepare() created, for abort()
    int created_slot_ = -1;
    int created_levels_ = 0;
    bool prepared_ = false;
    bool done_ = false;
};

/// Writes one file by the rules above (a one-output OutputFiles). Throws std::runtime_error
/// "cannot write 'path': <strerror>" (e.g. "No space left on device" for ENOSPC).
void write_file_atomic(const std::string& path, const void* data, std::size_t size);
inline void write_file_atomic(const std::string& path, const std::string& bytes) {
    write_file_atomic(path, bytes.data(), bytes.size());
}

/// Installs the signal handlers described in the file comment; `prefix` ("sphbasis render")
/// starts the one line printed on stderr for SIGINT, SIGTERM and SIGHUP. Call once, early.
void install_signal_cleanup(const std::string& prefix);

/// The prefix of staging directory names, ".sphbasis-staging-".
extern const char* const staging_prefix;

/// dir/name ("." or "" as dir: name alone; no doubled '/' when dir ends with one).
std::string join_path(const std::string& dir, const std::string& name);
/// Creates directory `dir` and its parents if missing. Throws std::runtime_error "cannot create
/// output directory 'dir'[: reason]" when it cannot, or when `dir` is not a directory.
void ensure_dir(const std::string& dir);

}  // namespace sphbasis::cli
