// sphbasis CLI support: files written whole or not at all.
//
// Every bake output goes through write_file_atomic: the bytes go to a unique temporary file in
// the destination's directory (".<name>.tmp-<pid>-<n>"), which is flushed (and fsync'ed when
// asked) and then renamed over the destination. rename() within one directory is atomic on
// POSIX file systems, so an interrupted or failed bake leaves either the old file or the new
// one, never half a file; on failure the temporary is removed.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace sphbasis::cli {

/// Writes `size` bytes to `path` through a temporary file and a rename. Throws
/// std::runtime_error "cannot write 'path': <strerror>" (e.g. "No space left on device" for
/// ENOSPC, "Input/output error" for EIO) after removing the temporary.
void write_file_atomic(const std::string& path, const void* data, std::size_t size,
                       bool sync = false);
inline void write_file_atomic(const std::string& path, const std::string& bytes,
                              bool sync = false) {
    write_file_atomic(path, bytes.data(), bytes.size(), sync);
}

/// Throws std::runtime_error "cannot write 'path': <strerror>" unless a file can be created in
/// path's directory (a temporary is created and removed): checks an output before a long run
/// without creating or truncating `path` itself.
void check_writable(const std::string& path);

/// Several outputs written all or none: commit() writes every file to its temporary first and
/// renames them only when all were written, so a failure (a bad path, a full disk) leaves every
/// destination as it was. (The renames themselves can fail only on a file system that
/// changed meanwhile; then the files renamed before stay.)
class OutputFiles {
  public:
    void add(std::string path, std::string bytes) {
        files_.emplace_back(std::move(path), std::move(bytes));
    }
    void commit(bool sync = false);

  private:
    std::vector<std::pair<std::string, std::string>> files_;
};

/// Writes `data` to a new temporary beside `path` and returns its name (commit_temporary() or
/// discard_temporary() it); throws as write_file_atomic() after removing it.
std::string write_temporary(const std::string& path, const void* data, std::size_t size,
                            bool sync = false);

/// A unique temporary name beside `path` (same directory, so rename() is atomic), for writers
/// that must produce the file themselves (OpenEXR): write it, then commit_temporary().
std::string temporary_name_for(const std::string& path);
/// Renames `temp` to `path`; on failure removes `temp` and throws std::runtime_error.
void commit_temporary(const std::string& temp, const std::string& path);
/// Removes `temp` if it exists (after a failed write); never throws.
void discard_temporary(const std::string& temp) noexcept;

/// dir/name ("." or "" as dir: name alone; no doubled '/' when dir ends with one).
std::string join_path(const std::string& dir, const std::string& name);
/// Creates directory `dir` and its parents if missing. Throws std::runtime_error "cannot create
/// output directory 'dir'[: reason]" when it cannot, or when `dir` is not a directory.
void ensure_dir(const std::string& dir);

}  // namespace sphbasis::cli
