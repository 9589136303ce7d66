// sphbasis render tier: baked values laid out for lookups at a camera hit, shared by the
// representation families (representations/family.hpp).
//
// A Field holds one bake's values (or values derived from them) at float precision: per vertex
// (interpolated with the hit's barycentrics), per lightmap texel (read bilinearly at Hit::uv
// with clamp-to-edge, texel (0, 0) at uv (0, 1); render::assemble_lightmap(), gutters of
// render::lightmap_gutter texels), or per probe (double, interpolated trilinearly by the caller).
// Lightmaps are baked on the front side of each surface (the side of its normal); a back-face hit
// reads the front's data.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "../bake.hpp"
#include "../bake_cache.hpp"
#include "../bake_record.hpp"
#include "../lightmap.hpp"
#include "../probe_grid.hpp"
#include "../scene.hpp"

namespace sphbasis::render::representations {

/// Baked values laid out for lookups at float precision (probes: double).
struct Field {
    BakeRequest::Where where = BakeRequest::Where::vertex;
    int channels = 0, width = 0, height = 0;
    std::vector<float> data;  // vertex: vertex_count x channels; texel: width x height x ch
    std::vector<double> probe_values;  // probes x 27 (R, G, B x 9)
    std::vector<std::uint8_t> inside;
    ProbeGrid grid;
};

/// The quantity a field of a bake holds: the first of transfer_matrix, transfer, irradiance and
/// visibility the bake has; else ao and bent (ao | bent).
inline Quantity field_quantity(const BakeSettings& s) noexcept {
    for (Quantity q : {Quantity::transfer_matrix, Quantity::transfer, Quantity::irradiance,
                       Quantity::visibility})
        if (has(s.quantities, q)) return q;
    return Quantity::ao | Quantity::bent;
}
/// Channels of a result: the values of field_quantity()'s block (render/bake_record.hpp)
/// without its standard errors and flags: transfer_matrix 27 bands^2, transfer 3 bands^2,
/// irradiance 3 coeffs, visibility bands^2; ao + bent 4 (ao, bent x, y, z).
inline int channels_of(const BakeSettings& s) noexcept {
    const int b2 = s.bands * s.bands;
    switch (field_quantity(s)) {
        case Quantity::transfer_matrix:
            return 27 * b2;
        case Quantity::transfer:
            return 3 * b2;
        case Quantity::irradiance:
            return 3 * s.coeffs;
        case Quantity::visibility:
            return b2;
        default:
            return 4;
    }
}
/// Point r's channels_of(s) values at float precision: the leading values of its
/// render::pack_quantity() block (ao + bent: ao, then bent x, y, z).
inline void pack(const BakeSettings& s, const PointResult& r, float* out) {
    const Quantity q = field_quantity(s);
    if (q == (Quantity::ao | Quantity::bent)) {
        float ao[2], bent[4];
        pack_quantity(Quantity::ao, s, r, ao);
        pack_quantity(Quantity::bent, s, r, bent);
        out[0] = ao[0];
        std::copy(bent, bent + 3, out + 1);
        return;
    }
    const std::size_t b2 = std::size_t(s.bands) * std::size_t(s.bands);
    std::vector<float> block(quantity_block_size(q, b2, std::size_t(s.coeffs)));
    pack_quantity(q, b2, std::size_t(s.coeffs), r, block.data());
    std::copy(block.begin(), block.begin() + channels_of(s), out);
}

/// A vertex or texel field of `channels` values per point of bake d, point i's written by
/// pack_point(i, out) (texels: render::assemble_lightmap, the lightmap `sphbasis bake` writes,
/// gutters of lightmap_gutter texels).
template <class PackPoint>
Field make_field(const BakeData& d, int channels, PackPoint&& pack_point) {
    Field f;
    f.where = d.request.where;
    f.channels = channels;
    const std::size_t ch = std::size_t(f.channels);
    if (f.where == BakeRequest::Where::vertex) {
        f.data.assign(d.results.size() * ch, 0.f);
        for (std::size_t v = 0; v < d.results.size(); ++v) pack_point(v, f.data.data() + v * ch);
        return f;
    }
    f.width = d.layout.width;
    f.height = d.layout.height;
    f.data = assemble_lightmap(d.layout, channels, pack_point);
    return f;
}

/// The field of a bake as it was baked: every quantity the request asked for (pack()); probes
/// keep their 3-band radiance at double precision.
inline Field make_field(const BakeData& d) {
    Field f;
    const BakeRequest& q = d.request;
    f.where = q.where;
    if (q.where == BakeRequest::Where::probes) {
        f.grid = q.probes;
        f.probe_values.assign(27 * d.results.size(), 0.0);
        f.inside.assign(d.results.size(), 0);
        for (std::size_t i = 0; i < d.results.size(); ++i) {
            const PointResult& r = d.results[i];
            f.inside[i] = r.inside ? 1 : 0;
            for (std::size_t c = 0; c < 3; ++c)
                for (std::size_t k = 0; k < 9 && k < r.radiance[c].size(); ++k)
                    f.probe_values[27 * i + 9 * c + k] = r.radiance[c][k];
        }
        // Every probe inside geometry: keep them all rather than fail at render time.
        if (std::find(f.inside.begin(), f.inside.end(), 0) == f.inside.end())
            std::fill(f.inside.begin(), f.inside.end(), 0);
        return f;
    }
    return make_field(d, channels_of(q.settings),
                      [&](std::size_t i, float* out) { pack(q.settings, d.results[i], out); });
}

/// Interpolated channels of a field at a hit (vertex: barycentric; texel: bilinear at uv,
/// clamp to edge; texel (0, 0) at uv (0, 1)).
inline void lookup(const Field& f, const Hit& h, double* out) noexcept {
    const std::size_t ch = std::size_t(f.channels);
    if (f.where == BakeRequest::Where::vertex) {
        const double w[3] = {1 - h.u - h.v, h.u, h.v};
        for (std::size_t c = 0; c < ch; ++c) out[c] = 0;
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = h.vertices[std::size_t(k)];
            if ((v + 1) * ch > f.data.size()) continue;
            const float* p = f.data.data() + v * ch;
            for (std::size_t c = 0; c < ch; ++c) out[c] += w[k] * double(p[c]);
        }
        return;
    }
    double x = h.uv[0] * f.width - 0.5, y = (1 - h.uv[1]) * f.height - 0.5;
    if (!std::isfinite(x)) x = 0;
    if (!std::isfinite(y)) y = 0;
    x = std::clamp(x, 0.0, double(f.width - 1));
    y = std::clamp(y, 0.0, double(f.height - 1));
    const int x0 = std::min(int(x), f.width - 1), y0 = std::min(int(y), f.height - 1);
    const int x1 = std::min(x0 + 1, f.width - 1), y1 = std::min(y0 + 1, f.height - 1);
    const double ax = x - x0, ay = y - y0;
    auto at = [&](int xx, int yy) {
        return f.data.data() + (std::size_t(yy) * std::size_t(f.width) + std::size_t(xx)) * ch;
    };
    const float *p00 = at(x0, y0), *p10 = at(x1, y0), *p01 = at(x0, y1), *p11 = at(x1, y1);
    const double w00 = (1 - ax) * (1 - ay), w10 = ax * (1 - ay), w01 = (1 - ax) * ay, w11 = ax * ay;
    for (std::size_t c = 0; c < ch; ++c)
        out[c] = w00 * p00[c] + w10 * p10[c] + w01 * p01[c] + w11 * p11[c];
}

/// The field value at the nearest texel, or the vertex of the largest barycentric weight.
inline void lookup_nearest(const Field& f, const Hit& h, double* out) noexcept {
    const std::size_t ch = std::size_t(f.channels);
    const float* p = nullptr;
    if (f.where == BakeRequest::Where::vertex) {
        const double w[3] = {1 - h.u - h.v, h.u, h.v};
        const int k = w[0] >= w[1] && w[0] >= w[2] ? 0 : (w[1] >= w[2] ? 1 : 2);
        const std::size_t v = h.vertices[std::size_t(k)];
        if ((v + 1) * ch <= f.data.size()) p = f.data.data() + v * ch;
    } else {
        double x = h.uv[0] * f.width, y = (1 - h.uv[1]) * f.height;
        if (!std::isfinite(x)) x = 0;
        if (!std::isfinite(y)) y = 0;
        const int xi = std::clamp(int(std::floor(x)), 0, f.width - 1);
        const int yi = std::clamp(int(std::floor(y)), 0, f.height - 1);
        p = f.data.data() + (std::size_t(yi) * std::size_t(f.width) + std::size_t(xi)) * ch;
    }
    for (std::size_t c = 0; c < ch; ++c) out[c] = p ? double(p[c]) : 0.0;
}

}  // namespace sphbasis::render::representations
