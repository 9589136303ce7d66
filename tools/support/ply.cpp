// sphbasis CLI support: ply_binary (see ply.hpp).
#include "ply.hpp"

#include <cstring>
#include <stdexcept>

namespace sphbasis::cli {

namespace {

bool host_is_little_endian() {
    const std::uint32_t one = 1;
    unsigned char b = 0;
    std::memcpy(&b, &one, 1);
    return b == 1;
}

template <class T>
void put(std::string& out, T v) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (!host_is_little_endian())
        for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    out.append(reinterpret_cast<const char*>(b), sizeof(T));
}

}  // namespace

std::string ply_binary(const std::vector<std::string>& names, const std::vector<float>& values,
                       std::size_t vertex_count, const std::vector<std::uint32_t>& indices,
                       const std::vector<std::string>& comments) {
    if (values.size() != vertex_count * names.size())
        throw std::invalid_argument("sphbasis::cli::ply_binary(): expected " +
                                    std::to_string(vertex_count * names.size()) + " values, got " +
                                    std::to_string(values.size()));
    if (indices.size() % 3 != 0)
        throw std::invalid_argument("sphbasis::cli::ply_binary(): expected 3 indices per face");
    for (std::uint32_t i : indices)
        if (i >= vertex_count)
            throw std::invalid_argument("sphbasis::cli::ply_binary(): index out of range");
    std::string out = "ply\nformat binary_little_endian 1.0\n";
    for (const std::string& c : comments) out += "comment " + c + "\n";
    out += "element vertex " + std::to_string(vertex_count) + "\n";
    for (const std::string& n : names) out += "property float " + n + "\n";
    out += "element face " + std::to_string(indices.size() / 3) + "\n";
    out += "property list uchar uint vertex_indices\nend_header\n";
    out.reserve(out.size() + values.size() * 4 + indices.size() / 3 * 13);
    for (float v : values) put(out, v);
    for (std::size_t t = 0; t < indices.size(); t += 3) {
        put(out, static_cast<unsigned char>(3));
        put(out, indices[t]);
        put(out, indices[t + 1]);
        put(out, indices[t + 2]);
    }
    return out;
}

}  // namespace sphbasis::cli
