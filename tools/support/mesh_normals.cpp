// sphbasis CLI support: generate_normals (see mesh_normals.hpp).
#include "mesh_normals.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <unordered_map>

namespace sphbasis::cli {

namespace {

using D3 = std::array<double, 3>;

D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 cross(const D3& a, const D3& b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

std::uint32_t bits(float f) {
    f += 0.0f;  // -0 -> +0: equal positions weld
    std::uint32_t u;
    std::memcpy(&u, &f, sizeof u);
    return u;
}

struct Key {
    std::uint32_t a, b, c, d;
    bool operator==(const Key& o) const { return a == o.a && b == o.b && c == o.c && d == o.d; }
};
struct KeyHash {
    std::size_t operator()(const Key& k) const {
        std::uint64_t h = 0x9e3779b97f4a7c15ull;
        for (std::uint32_t v : {k.a, k.b, k.c, k.d}) {
            h ^= v;
            h *= 0xff51afd7ed558ccdull;
            h ^= h >> 33;
        }
        return static_cast<std::size_t>(h);
    }
};

}  // namespace

void generate_normals(render::Mesh& m, const std::vector<char>& generate,
                      double smoothing_angle_deg) {
    const std::size_t T = m.triangle_count(), V = m.vertex_count();
    if (generate.size() != T || m.normals.size() != 3 * V)
        throw std::invalid_argument(
            "sphbasis::cli::generate_normals(): expected one flag per triangle and 3 normal "
            "components per vertex");
    for (std::uint32_t i : m.indices)
        if (i >= V)
            throw std::invalid_argument(
                "sphbasis::cli::generate_normals(): expected indices below the vertex count, "
                "got " +
                std::to_string(i));
    const double pi = 3.14159265358979324;
    const bool flat = !(smoothing_angle_deg > 0);
    // The faces within the angle: dot(n_s, n_t) >= cos(angle), rounding aside (a box's 90-degree
    // neighbours must stay out at 90).
    const double cos_max =
        smoothing_angle_deg >= 180 ? -2.0 : std::cos(smoothing_angle_deg * pi / 180) - 1e-12;
    auto pos = [&m](std::uint32_t i) {
        const float* p = &m.positions[3 * std::size_t(i)];
        return D3{p[0], p[1], p[2]};
    };
    // Unit face normals (0 for a degenerate triangle) and corner angles of generated triangles.
    std::vector<D3> fn(T, D3{0, 0, 0}), angle(T, D3{0, 0, 0});
    for (std::size_t t = 0; t < T; ++t) {
        if (!generate[t]) continue;
        const std::uint32_t* tri = &m.indices[3 * t];
        const D3 p[3] = {pos(tri[0]), pos(tri[1]), pos(tri[2])};
        const D3 c = cross(sub(p[1], p[0]), sub(p[2], p[0]));
        const double l = std::sqrt(dot(c, c));
        if (l > 0 && std::isfinite(l)) fn[t] = {c[0] / l, c[1] / l, c[2] / l};
        for (int k = 0; k < 3; ++k) {
            const D3 e1 = sub(p[(k + 1) % 3], p[k]), e2 = sub(p[(k + 2) % 3], p[k]);
            const D3 x = cross(e1, e2);
            const double a = std::atan2(std::sqrt(dot(x, x)), dot(e1, e2));
            angle[t][std::size_t(k)] = std::isfinite(a) ? a : 0.0;
        }
    }
    // Weld positions, then list the generated corners around each welded position (CSR).
    std::vector<std::uint32_t> weld(V, 0);
    {
        std::unordered_map<Key, std::uint32_t, KeyHash> ids;
        ids.reserve(V);
        for (std::size_t i = 0; i < V; ++i) {
            const float* p = &m.positions[3 * i];
            const Key k{bits(p[0]), bits(p[1]), bits(p[2]), 0};
            weld[i] = ids.emplace(k, static_cast<std::uint32_t>(ids.size())).first->second;
        }
    }
    std::vector<std::size_t> first(V + 1, 0);
    for (std::size_t t = 0; t < T; ++t)
        if (generate[t])
            for (int k = 0; k < 3; ++k) ++first[weld[m.indices[3 * t + std::size_t(k)]] + 1];
    for (std::size_t i = 0; i < V; ++i) first[i + 1] += first[i];
    std::vector<std::size_t> corners(first[V]), fill(first.begin(), first.end() - 1);
    for (std::size_t t = 0; t < T; ++t)
        if (generate[t])
            for (std::size_t k = 0; k < 3; ++k)
                corners[fill[weld[m.indices[3 * t + k]]]++] = 3 * t + k;

    // New vertices: one per (old vertex, normal).
    render::Mesh out;
    out.albedo = m.albedo;
    out.albedo_texels = m.albedo_texels;
    out.albedo_map = m.albedo_map;
    out.normal_texels = m.normal_texels;
    out.normal_map = m.normal_map;
    out.shininess = m.shininess;
    out.specular = m.specular;
    const bool uvs = m.uvs.size() == 2 * V, tangents = m.tangents.size() == 4 * V;
    std::unordered_map<Key, std::uint32_t, KeyHash> split;
    std::vector<std::uint32_t> kept(V, std::numeric_limits<std::uint32_t>::max());
    auto add_vertex = [&](std::uint32_t i, const float* n) {
        const auto id = static_cast<std::uint32_t>(out.vertex_count());
        out.positions.insert(out.positions.end(), m.positions.begin() + std::ptrdiff_t(3 * i),
                             m.positions.begin() + std::ptrdiff_t(3 * i + 3));
        out.normals.insert(out.normals.end(), n, n + 3);
        if (uvs)
            out.uvs.insert(out.uvs.end(), m.uvs.begin() + std::ptrdiff_t(2 * i),
                           m.uvs.begin() + std::ptrdiff_t(2 * i + 2));
        if (tangents)
            out.tangents.insert(out.tangents.end(), m.tangents.begin() + std::ptrdiff_t(4 * i),
                                m.tangents.begin() + std::ptrdiff_t(4 * i + 4));
        return id;
    };
    out.indices.resize(m.indices.size());
    for (std::size_t t = 0; t < T; ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            const std::uint32_t i = m.indices[3 * t + k];
            if (!generate[t]) {
                if (kept[i] == std::numeric_limits<std::uint32_t>::max())
                    kept[i] = add_vertex(i, &m.normals[3 * std::size_t(i)]);
                out.indices[3 * t + k] = kept[i];
                continue;
            }
            D3 s{0, 0, 0};
            if (flat) {
                s = fn[t];
            } else {
                const std::size_t w = weld[i];
                for (std::size_t c = first[w]; c < first[w + 1]; ++c) {
                    const std::size_t u = corners[c] / 3;
                    if (!(dot(fn[u], fn[t]) >= cos_max)) continue;
                    const double a = angle[u][corners[c] % 3];
                    for (std::size_t j = 0; j < 3; ++j) s[j] += a * fn[u][j];
                }
            }
            const double l = std::sqrt(dot(s, s));
            // A degenerate triangle (no normal of its own, dropped later by the loader) keeps
            // (0, 0, 1).
            const float n[3] = {l > 0 ? float(s[0] / l) : 0.0f, l > 0 ? float(s[1] / l) : 0.0f,
                                l > 0 ? float(s[2] / l) : 1.0f};
            const Key key{i, bits(n[0]), bits(n[1]), bits(n[2])};
            const auto it = split.find(key);
            if (it != split.end()) {
                out.indices[3 * t + k] = it->second;
            } else {
                const std::uint32_t id = add_vertex(i, n);
                split.emplace(key, id);
                out.indices[3 * t + k] = id;
            }
        }
    m = std::move(out);
}

}  // namespace sphbasis::cli
