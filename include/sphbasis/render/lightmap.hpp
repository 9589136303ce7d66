// sphbasis render tier: lightmap layout in a mesh's UV set, and gutter dilation.
//
// CONTRACT (written by the lead; the lightmap helper implements it and may add members and
// functions, but keeps these names and meanings: the tool is written against them).
#pragma once

#include <cstdint>
#include <stdexcept>
#include <vector>

#include "bake.hpp"
#include "mesh.hpp"

namespace sphbasis::render {

/// One covered texel: its pixel (x right, y down from the top row, which is v = 1) and the
/// surface point baked for it (point.id = id_base + y * width + x).
struct LightmapSample {
    int x = 0, y = 0;
    BakePoint point;
};

struct LightmapLayout {
    int width = 0, height = 0;
    std::vector<LightmapSample> samples;   // one per covered texel, in row-major order
    std::vector<std::uint8_t> covered;     // width * height: 1 where a sample is
    std::size_t skipped_triangles = 0;     // zero-area in UV space (not rasterised)
};

/// Rasterises the mesh's triangles in UV space with conservative coverage and places each
/// covered texel's sample on the surface. Throws std::invalid_argument if the mesh has no UVs
/// or the resolution is not in [1, 16384].
inline LightmapLayout layout_lightmap(const MeshView& mesh, int width, int height,
                                      std::uint64_t id_base = 0) {
    (void)mesh, (void)width, (void)height, (void)id_base;
    throw std::logic_error("sphbasis::render::layout_lightmap: not implemented yet");
}

/// Fills up to `gutter` texels around the covered region (covered[i] != 0) with the average of
/// covered neighbours, `channels` floats per texel, so bilinear filtering does not fetch
/// unbaked texels.
inline void dilate(float* image, int width, int height, int channels,
                   const std::vector<std::uint8_t>& covered, int gutter) {
    (void)image, (void)width, (void)height, (void)channels, (void)covered, (void)gutter;
    throw std::logic_error("sphbasis::render::dilate: not implemented yet");
}

}  // namespace sphbasis::render
