// sphbasis CLI support: DiskBakeCache (see bake_cache.hpp).
#include "bake_cache.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "output_file.hpp"

namespace sphbasis::cli {

std::string hex_key(std::uint64_t key) {
    static const char digits[] = "0123456789abcdef";
    std::string s(16, '0');
    for (int i = 15; i >= 0; --i, key >>= 4) s[std::size_t(i)] = digits[key & 15u];
    return s;
}

std::string DiskBakeCache::path_of(std::uint64_t key) const {
    return (dir_.empty() ? std::string() : dir_ + "/") + hex_key(key) + ".bin";
}

bool DiskBakeCache::load(std::uint64_t key, render::BakeData& out) {
    const std::string path = path_of(key);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
        ++misses_;
        return false;
    }
    std::string why;
    try {
        std::ifstream in(path, std::ios::binary);
        if (!in) throw std::runtime_error("cannot open it");
        std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
        if (in.bad()) throw std::runtime_error("cannot read it");
        const render::BakeFileView v = render::read_bake_file(bytes, render::BakeFileKind::cache);
        if (v.input_hash != key)
            throw std::runtime_error("a bake of another key (" + hex_key(v.input_hash) + ")");
        render::BakeData d = render::deserialize(v.payload, v.payload_size);
        d.from_cache = true;
        out = std::move(d);
        ++hits_;
        return true;
    } catch (const std::exception& e) {
        why = e.what();
    }
    warnings_.push_back(path + ": unreadable cache file (" + why + "); baking again");
    std::fprintf(stderr, "sphbasis render: warning: %s\n", warnings_.back().c_str());
    ++misses_;
    return false;
}

void DiskBakeCache::store(std::uint64_t key, const render::BakeData& data) {
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::create_directories(dir_, ec);
    if (ec)
        throw std::runtime_error("cannot create the bake cache directory '" + dir_ +
                                 "': " + ec.message());
    const std::vector<std::uint8_t> bytes =
        render::write_bake_file(render::BakeFileKind::cache, key, render::serialize(data));
    write_file_atomic(path_of(key), bytes.data(), bytes.size());
    ++stores_;
}

}  // namespace sphbasis::cli
