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

/// A unique temporary name beside `path` (same directory, so rename() is atomic), for writers
/// that must produce the file themselves (OpenEXR): write it, then commit_temporary().
std::string temporary_name_for(const std::string& path);
/// Renames `temp` to `path`; on failure removes `temp` and throws std::runtime_error.
void commit_temporary(const std::string& temp, const std::string& path);
/// Removes `temp` if it exists (after a failed write); never throws.
void discard_temporary(const std::string& temp) noexcept;

}  // namespace sphbasis::cli
