// sphbasis render tier: the one persistence format of bake results (the `sphbasis bake --shard`
// shard files and the bake cache of `sphbasis render`), as bytes in and out: the library reads
// and writes no files (the tools do), it frames, checks and parses.
//
// Layout (docs/bake-format.md; all integers little-endian):
//   offset  size  field
//   0       8     magic "SPHBFILE"
//   8       4     u32 format version (bake_file_version)
//   12      4     u32 kind (BakeFileKind: 1 shard, 2 cache entry)
//   16      8     u64 input hash: XXH3-64 of everything the result depends on (InputHash;
//                 the writer says what, the reader recomputes it and compares)
//   24      8     u64 payload size P in bytes (the file is exactly 40 + P bytes)
//   32      8     u64 checksum: XXH3-64 of bytes 0..31 followed by the payload (so a flipped
//                 bit anywhere but in the checksum itself is caught, and there it mismatches)
//   40      P     payload (its layout is the kind's; ByteWriter / ByteReader write and read it)
// XXH3: Collet, "xxHash: Extremely fast non-cryptographic hash algorithm" (xxHash 0.8, 2020),
// through Debian's libxxhash-dev, inlined (XXH_INLINE_ALL: no library to link). A checksum
// finds corruption, not tampering.
//
// read_bake_file() checks magic, version, kind, size and checksum and throws std::runtime_error
// naming the first that fails; ByteReader throws for any read past the payload and for any
// count whose elements could not fit in what is left, so a mutated file gives an error or a
// value, never an out-of-bounds read or a huge allocation. What a parsed value means (a count
// against the scene, an index against a range) is the caller's to validate before use.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#ifndef XXH_INLINE_ALL
#define XXH_INLINE_ALL
#endif
#include <xxhash.h>

#include "../core/error.hpp"

namespace sphbasis::render {

/// The version of the container written by write_bake_file() (read_bake_file() reads only it).
inline constexpr std::uint32_t bake_file_version = 1;
/// Bytes before the payload.
inline constexpr std::size_t bake_file_header_bytes = 40;
inline constexpr char bake_file_magic[8] = {'S', 'P', 'H', 'B', 'F', 'I', 'L', 'E'};

/// What a bake file holds.
enum class BakeFileKind : std::uint32_t { shard = 1, cache = 2 };

/// Streaming XXH3-64 of the inputs of a result: bytes, numbers and strings in a fixed order
/// (strings and byte blocks length-prefixed, so ("ab", "c") and ("a", "bc") differ).
class InputHash {
  public:
    InputHash() { XXH3_64bits_reset(&state_); }
    InputHash& bytes(const void* data, std::size_t size) {
        u64(size);
        if (size > 0) XXH3_64bits_update(&state_, data, size);
        return *this;
    }
    InputHash& str(const std::string& s) { return bytes(s.data(), s.size()); }
    InputHash& u64(std::uint64_t v) {
        unsigned char b[8];
        for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
        XXH3_64bits_update(&state_, b, 8);
        return *this;
    }
    InputHash& f64(double v) {
        std::uint64_t u;
        std::memcpy(&u, &v, 8);
        return u64(u);
    }
    std::uint64_t value() const { return XXH3_64bits_digest(&state_); }

  private:
    XXH3_state_t state_;
};

/// Little-endian writer of a payload.
class ByteWriter {
  public:
    void u8(std::uint8_t v) { out_.push_back(v); }
    void u32(std::uint32_t v) {
        for (int i = 0; i < 4; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void u64(std::uint64_t v) {
        for (int i = 0; i < 8; ++i) out_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    }
    void f64(double v) {
        std::uint64_t u;
        std::memcpy(&u, &v, 8);
        u64(u);
    }
    /// u64 length, then the bytes.
    void str(const std::string& s) {
        u64(s.size());
        out_.insert(out_.end(), s.begin(), s.end());
    }
    /// u64 count, then the doubles.
    void f64s(const std::vector<double>& v) {
        u64(v.size());
        for (double d : v) f64(d);
    }
    /// u64 count, then the bytes.
    void u8s(const std::vector<std::uint8_t>& v) {
        u64(v.size());
        out_.insert(out_.end(), v.begin(), v.end());
    }
    const std::vector<std::uint8_t>& bytes() const noexcept { return out_; }
    std::vector<std::uint8_t> take() noexcept { return std::move(out_); }

  private:
    std::vector<std::uint8_t> out_;
};

/// Little-endian reader of a payload; every read is bounds-checked (std::runtime_error
/// "sphbasis::<fn>(): expected ...", fn as given).
class ByteReader {
  public:
    ByteReader(const std::uint8_t* data, std::size_t size, const char* fn)
        : p_(data), n_(size), fn_(fn) {}
    std::uint8_t u8() {
        need(1);
        return p_[pos_++];
    }
    std::uint32_t u32() {
        need(4);
        std::uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= std::uint32_t(p_[pos_ + std::size_t(i)]) << (8 * i);
        pos_ += 4;
        return v;
    }
    std::uint64_t u64() {
        need(8);
        std::uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= std::uint64_t(p_[pos_ + std::size_t(i)]) << (8 * i);
        pos_ += 8;
        return v;
    }
    double f64() {
        const std::uint64_t u = u64();
        double d;
        std::memcpy(&d, &u, 8);
        return d;
    }
    /// A count of elements of `element_bytes` each that must fit in what is left.
    std::size_t count(std::size_t element_bytes) {
        const std::uint64_t c = u64();
        if (element_bytes > 0 && c > remaining() / element_bytes)
            sphbasis::detail::throw_runtime(
                fn_, "a count that fits the " + std::to_string(remaining()) + " bytes left, got " +
                         std::to_string(c) + " of " + std::to_string(element_bytes) + " bytes");
        return static_cast<std::size_t>(c);
    }
    std::string str() {
        const std::size_t c = count(1);
        std::string s(reinterpret_cast<const char*>(p_ + pos_), c);
        pos_ += c;
        return s;
    }
    std::vector<double> f64s() {
        std::vector<double> v(count(8));
        for (double& d : v) d = f64();
        return v;
    }
    std::vector<std::uint8_t> u8s() {
        const std::size_t c = count(1);
        std::vector<std::uint8_t> v(p_ + pos_, p_ + pos_ + c);
        pos_ += c;
        return v;
    }
    std::size_t remaining() const noexcept { return n_ - pos_; }
    /// Throws unless every byte was read.
    void finish() const {
        if (pos_ != n_)
            sphbasis::detail::throw_runtime(fn_, "the payload to end after " +
                                                     std::to_string(pos_) + " bytes, got " +
                                                     std::to_string(n_ - pos_) + " trailing bytes");
    }

  private:
    void need(std::size_t k) const {
        if (k > n_ - pos_)
            sphbasis::detail::throw_runtime(fn_, std::to_string(k) + " more bytes at offset " +
                                                     std::to_string(pos_) +
                                                     ", got a truncated payload");
    }
    const std::uint8_t* p_;
    std::size_t n_, pos_ = 0;
    const char* fn_;
};

namespace bake_file_detail {
inline std::uint64_t checksum(const std::uint8_t* header32, const std::uint8_t* payload,
                              std::size_t size) {
    XXH3_state_t s;
    XXH3_64bits_reset(&s);
    XXH3_64bits_update(&s, header32, 32);
    if (size > 0) XXH3_64bits_update(&s, payload, size);
    return XXH3_64bits_digest(&s);
}
inline std::uint64_t le64(const std::uint8_t* p) noexcept {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v |= std::uint64_t(p[i]) << (8 * i);
    return v;
}
inline std::uint32_t le32(const std::uint8_t* p) noexcept {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= std::uint32_t(p[i]) << (8 * i);
    return v;
}
}  // namespace bake_file_detail

/// The bytes of a bake file: header (kind, input hash, size, checksum) and payload.
inline std::vector<std::uint8_t> write_bake_file(BakeFileKind kind, std::uint64_t input_hash,
                                                 const std::vector<std::uint8_t>& payload) {
    std::vector<std::uint8_t> out(bake_file_header_bytes + payload.size());
    std::memcpy(out.data(), bake_file_magic, 8);
    auto put = [&out](std::size_t at, std::uint64_t v, int bytes) {
        for (int i = 0; i < bytes; ++i) out[at + std::size_t(i)] = std::uint8_t(v >> (8 * i));
    };
    put(8, bake_file_version, 4);
    put(12, static_cast<std::uint32_t>(kind), 4);
    put(16, input_hash, 8);
    put(24, payload.size(), 8);
    if (!payload.empty())
        std::memcpy(out.data() + bake_file_header_bytes, payload.data(), payload.size());
    put(32, bake_file_detail::checksum(out.data(), payload.data(), payload.size()), 8);
    return out;
}

/// A bake file's header fields and its payload's place in the bytes.
struct BakeFileView {
    std::uint32_t version = 0;
    BakeFileKind kind = BakeFileKind::shard;
    std::uint64_t input_hash = 0;
    const std::uint8_t* payload = nullptr;
    std::size_t payload_size = 0;
};

/// Checks `size` bytes as a bake file of `kind` (magic, version, kind, size, checksum: header
/// comment) and returns its header and payload (pointing into `data`). Throws
/// std::runtime_error naming what is wrong. The input hash is returned, not checked: the caller
/// compares it with the hash of its own inputs.
inline BakeFileView read_bake_file(const std::uint8_t* data, std::size_t size, BakeFileKind kind) {
    constexpr const char* fn = "render::read_bake_file";
    using namespace bake_file_detail;
    if (size < bake_file_header_bytes || std::memcmp(data, bake_file_magic, 8) != 0)
        sphbasis::detail::throw_runtime(fn, "a bake file (magic SPHBFILE), got other bytes");
    BakeFileView v;
    v.version = le32(data + 8);
    if (v.version != bake_file_version)
        sphbasis::detail::throw_runtime(fn, "format version " + std::to_string(bake_file_version) +
                                                ", got " + std::to_string(v.version));
    const std::uint32_t k = le32(data + 12);
    if (k != static_cast<std::uint32_t>(kind))
        sphbasis::detail::throw_runtime(
            fn, std::string("a ") + (kind == BakeFileKind::shard ? "shard" : "cache entry") +
                    " (kind " + std::to_string(static_cast<std::uint32_t>(kind)) + "), got kind " +
                    std::to_string(k));
    v.kind = kind;
    v.input_hash = le64(data + 16);
    const std::uint64_t p = le64(data + 24);
    if (p != size - bake_file_header_bytes)
        sphbasis::detail::throw_runtime(
            fn, std::to_string(p) + " payload bytes (the header's), got " +
                    std::to_string(size - bake_file_header_bytes) + " (truncated or extended)");
    v.payload = data + bake_file_header_bytes;
    v.payload_size = static_cast<std::size_t>(p);
    if (checksum(data, v.payload, v.payload_size) != le64(data + 32))
        sphbasis::detail::throw_runtime(fn, "the checksum to match, got a corrupt file");
    return v;
}

inline BakeFileView read_bake_file(const std::vector<std::uint8_t>& bytes, BakeFileKind kind) {
    return read_bake_file(bytes.data(), bytes.size(), kind);
}

}  // namespace sphbasis::render
