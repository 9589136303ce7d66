// sphbasis CLI support: the disk cache of `sphbasis render`'s bakes (render::BakeCache).
//
// One file per bake, DIR/<key>.bin with the key as 16 lower-case hex digits
// (render::bake_key(): a hash of everything the bake depends on), in the format of the bake
// shards (render/bake_file.hpp, docs/bake-format.md): kind "cache", the key as input hash, a
// checksum, and render::serialize(BakeData) as payload. Files are written to a temporary name
// and renamed (support/output_file.hpp), so a killed run leaves whole files or none. A file that
// cannot be read back (truncated, bit-flipped, foreign, of another key or version) is reported
// as a warning and treated as missing: the bake runs again and the file is replaced.
#pragma once

#include <cstddef>
#include <cstdint>
#include <sphbasis/render/bake_file.hpp>
#include <sphbasis/render/representation.hpp>
#include <string>
#include <vector>

namespace sphbasis::cli {

class DiskBakeCache : public render::BakeCache {
  public:
    /// `dir` is created on the first store(), not before (a run that bakes nothing new
    /// leaves no directory behind).
    explicit DiskBakeCache(std::string dir) : dir_(std::move(dir)) {}

    /// The file of a key: DIR/<16 hex digits>.bin.
    std::string path_of(std::uint64_t key) const;

    bool load(std::uint64_t key, render::BakeData& out) override;
    void store(std::uint64_t key, const render::BakeData& data) override;

    std::size_t hits() const noexcept { return hits_; }
    std::size_t misses() const noexcept { return misses_; }
    std::size_t stores() const noexcept { return stores_; }
    /// One line per corrupt file met ("<path>: <reason>; baking again").
    const std::vector<std::string>& warnings() const noexcept { return warnings_; }

  private:
    std::string dir_;
    std::size_t hits_ = 0, misses_ = 0, stores_ = 0;
    std::vector<std::string> warnings_;
};

/// 16 lower-case hex digits.
std::string hex_key(std::uint64_t key);

}  // namespace sphbasis::cli
