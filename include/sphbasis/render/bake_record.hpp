// sphbasis render tier: a bake's results (render::PointResult) as flat blocks of numbers, the one
// packing that `sphbasis bake` writes (its records: PLY, EXR and JSON channels, shards) and that
// the representations' fields read (render/representations/field.hpp).
//
// pack_quantity(q, settings, result, out) writes quantity q's block (B = settings.bands,
// C = settings.coeffs):
//   ao               ao, ao_stderr                                                 2
//   bent             bent x, y, z, bent_stderr (radians)                           4
//   visibility       visibility (B^2), visibility_stderr (B^2)                     2 B^2
//   transfer         R, G, B (B^2 each), transfer_stderr (B^2), transfer_rgb       4 B^2 + 1
//   irradiance       R, G, B (C each), irradiance_stderr (C)                       4 C
//   radiance         R, G, B (B^2 each), radiance_stderr (B^2), inside             4 B^2 + 1
//   transfer_matrix  R, G, B (9 B^2 each), transfer_matrix_stderr (9 B^2)          36 B^2
// Flags are 1 or 0. A list shorter than its place is padded with 0 (a quantity not baked gives a
// block of zeros); transfer channels left empty take R's list (equal channels).
//
// RecordLayout: the record of one point, the blocks of ao, bent, visibility, transfer,
// irradiance and radiance in this order (transfer_matrix is not in it), then 4 numbers of a
// high-to-low bake (render/high_to_low.hpp: the source's normal x, y, z and 1 where the ray hit
// it, else 0), which pack_records() leaves 0 and `sphbasis bake` fills; pack_records() packs a
// bake into consecutive records. This is record_format 4 of `sphbasis bake`'s shards
// (docs/bake-format.md).
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

#include "bake.hpp"

namespace sphbasis::render {

namespace bake_record_detail {
template <class T>
void copy_padded(const std::vector<double>& v, std::size_t n, T* out) noexcept {
    for (std::size_t i = 0; i < n; ++i) out[i] = T(i < v.size() ? v[i] : 0.0);
}
}  // namespace bake_record_detail

/// The numbers in quantity q's block for `b2` = bands^2 and `nc` = coeffs (header comment); 0 for
/// a set of several flags.
constexpr std::size_t quantity_block_size(Quantity q, std::size_t b2, std::size_t nc) noexcept {
    switch (q) {
        case Quantity::ao:
            return 2;
        case Quantity::bent:
            return 4;
        case Quantity::visibility:
            return 2 * b2;
        case Quantity::transfer:
        case Quantity::radiance:
            return 4 * b2 + 1;
        case Quantity::irradiance:
            return 4 * nc;
        case Quantity::transfer_matrix:
            return 36 * b2;
    }
    return 0;
}

/// Writes quantity q's block of r (header comment) into out[0 .. quantity_block_size(q)),
/// `b2` = bands^2, `nc` = coeffs. T: double or float. Nothing for a set of several flags.
template <class T>
void pack_quantity(Quantity q, std::size_t b2, std::size_t nc, const PointResult& r,
                   T* out) noexcept {
    using bake_record_detail::copy_padded;
    switch (q) {
        case Quantity::ao:
            out[0] = T(r.ao);
            out[1] = T(r.ao_stderr);
            return;
        case Quantity::bent:
            out[0] = T(r.bent.x);
            out[1] = T(r.bent.y);
            out[2] = T(r.bent.z);
            out[3] = T(r.bent_stderr);
            return;
        case Quantity::visibility:
            copy_padded(r.visibility, b2, out);
            copy_padded(r.visibility_stderr, b2, out + b2);
            return;
        case Quantity::transfer:
            for (std::size_t c = 0; c < 3; ++c)
                copy_padded(r.transfer[c].empty() ? r.transfer[0] : r.transfer[c], b2,
                            out + c * b2);
            copy_padded(r.transfer_stderr, b2, out + 3 * b2);
            out[4 * b2] = T(r.transfer_rgb ? 1 : 0);
            return;
        case Quantity::irradiance:
            for (std::size_t c = 0; c < 3; ++c) copy_padded(r.irradiance[c], nc, out + c * nc);
            copy_padded(r.irradiance_stderr, nc, out + 3 * nc);
            return;
        case Quantity::radiance:
            for (std::size_t c = 0; c < 3; ++c) copy_padded(r.radiance[c], b2, out + c * b2);
            copy_padded(r.radiance_stderr, b2, out + 3 * b2);
            out[4 * b2] = T(r.inside ? 1 : 0);
            return;
        case Quantity::transfer_matrix:
            for (std::size_t c = 0; c < 3; ++c)
                copy_padded(r.transfer_matrix[c], 9 * b2, out + c * 9 * b2);
            copy_padded(r.transfer_matrix_stderr, 9 * b2, out + 27 * b2);
            return;
    }
}
/// pack_quantity() for the bands and coeffs of settings s.
template <class T>
void pack_quantity(Quantity q, const BakeSettings& s, const PointResult& r, T* out) noexcept {
    pack_quantity(q, std::size_t(s.bands) * std::size_t(s.bands), std::size_t(s.coeffs), r, out);
}

/// The offsets of the blocks in a point's record (header comment) for settings s: ao, ao + 1
/// (ao_stderr), bent (x, y, z), bent_se, vis, vis_se, tr (R, G, B), tr_se, tr_rgb, irr (R, G, B),
/// irr_se, rad (R, G, B), rad_se, inside, h2l (normal x, y, z, hit); stride = the record's length.
struct RecordLayout {
    std::size_t b2 = 0, nc = 0;  // bands^2, irradiance coefficients
    std::size_t ao = 0, bent = 2, bent_se = 5, vis = 6, vis_se = 0, tr = 0, tr_se = 0, tr_rgb = 0,
                irr = 0, irr_se = 0, rad = 0, rad_se = 0, inside = 0, h2l = 0, stride = 0;
    explicit RecordLayout(const BakeSettings& s)
        : b2(std::size_t(s.bands) * std::size_t(s.bands)), nc(std::size_t(s.coeffs)) {
        vis_se = vis + b2;
        tr = vis_se + b2;
        tr_se = tr + 3 * b2;
        tr_rgb = tr_se + b2;
        irr = tr_rgb + 1;
        irr_se = irr + 3 * nc;
        rad = irr_se + nc;
        rad_se = rad + 3 * b2;
        inside = rad_se + b2;
        h2l = inside + 1;
        stride = h2l + 4;
    }
};

/// Writes the record of r (L.stride numbers) into out.
inline void pack_record(const RecordLayout& L, const PointResult& r, double* out) noexcept {
    const std::pair<Quantity, std::size_t> blocks[] = {
        {Quantity::ao, L.ao},       {Quantity::bent, L.bent},      {Quantity::visibility, L.vis},
        {Quantity::transfer, L.tr}, {Quantity::irradiance, L.irr}, {Quantity::radiance, L.rad}};
    for (const auto& [q, at] : blocks) pack_quantity(q, L.b2, L.nc, r, out + at);
}

/// The records of a bake's results, consecutive (results.size() x L.stride numbers).
inline std::vector<double> pack_records(const RecordLayout& L,
                                        const std::vector<PointResult>& results) {
    std::vector<double> out(L.stride * results.size(), 0.0);
    for (std::size_t k = 0; k < results.size(); ++k)
        pack_record(L, results[k], out.data() + k * L.stride);
    return out;
}

}  // namespace sphbasis::render
