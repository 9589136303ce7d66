// sphbasis render tier: lightmap layout in a mesh's UV set, and gutter dilation.
//
// A texel bake (Hill, "Hardware Accelerating Art Production", Gamasutra 2004: per-texel
// ambient occlusion and its artifacts; Iwanicki and Sloan, "Normal Mapping with Low-Frequency
// Precomputed Visibility", JGT 2009, section 3.1: SH visibility stored per texel like a
// lightmap; Ishmukhametov, "Irradiance Normal Mapping" (thesis): tangent-space irradiance per
// texel) needs one surface point per texel the mesh's UV chart touches:
//
//   * Texels. Texel (x, y) of a W x H lightmap (x right, y down from the top row, which is
//     v = 1) is the square [x/W, (x+1)/W] x [1-(y+1)/H, 1-y/H] in UV space; its centre is
//     ((x + 0.5)/W, 1 - (y + 0.5)/H).
//   * Conservative coverage. A texel is covered by a triangle when the triangle overlaps the
//     texel's square with a positive area (not only when it contains the centre), so a sliver
//     thinner than a texel still covers every texel it crosses, and texels a chart's edge cuts
//     are baked (bilinear filtering reads them). The overlap area is computed exactly by
//     clipping the triangle to the square (Sutherland-Hodgman). A texel several triangles
//     cover takes the one with the largest overlap; ties go to the lowest triangle index.
//   * Sample. The texel centre's closest point on the chosen triangle in UV space (Ericson,
//     "Real-Time Collision Detection", 2005, section 5.1.5) gives barycentrics b; position,
//     normal (the interpolated shading normal, the geometric normal without normals) and
//     tangent (interpolated mesh tangents, Gram-Schmidt against n; zero without tangents) are
//     interpolated with b. Clamping into the triangle keeps the sample on the surface when the
//     centre lies outside the chart: a centre outside the triangle extrapolated linearly
//     would land off the mesh, often inside or behind a neighbouring wall, and bake its
//     darkness (or light from behind the wall) into a visible texel (Hill's per-texel
//     artifacts).
//   * Offset. The sample is then pulled along its normal by LightmapOptions::normal_offset
//     times the texel's world-space size s = sqrt(triangle area / triangle UV area in texels)
//     (default 1/16 texel). A texel stands for the whole square footprint, while the sample is
//     one point of a flat facet: on curved or faceted surfaces the rays of a point at the
//     bottom of the footprint graze the neighbouring facets and self-shadow (the "shadow
//     terminator"), and a point exactly in a crease sees both walls. The offset is a small
//     fraction of a texel so that it stays well inside any wall thicker than a texel: it never
//     carries a sample through geometry (the usual cause of light leaking through walls), and
//     the bias it adds to ao is of the order of the offset over the occluder distance. The
//     ray-origin epsilon against floating-point self-intersection is the Baker's, not this.
//   * Cost. O(sum over triangles of the texels in their UV bounding boxes): edge functions
//     classify the texels fully inside or outside a triangle, only texels on its edges are
//     clipped. Memory: 12 bytes per texel while rasterising, then one LightmapSample (176
//     bytes) per covered texel. Measured (g++ 12 -O3, one core, CPU time): 32768 triangles
//     into a fully covered 1024 x 1024 map, 1.0 s, most of it writing the 1M samples.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/vec.hpp"
#include "bake.hpp"
#include "mesh.hpp"

namespace sphbasis::render {

/// One covered texel: its pixel (x right, y down from the top row, which is v = 1) and the
/// surface point baked for it (point.id = id_base + y * width + x).
struct LightmapSample {
    int x = 0, y = 0;
    BakePoint point;
    /// The triangle the sample lies on and the barycentrics (of its vertices 0, 1, 2) of the
    /// sample's surface point; `surface` is that point before the normal offset
    /// (point.p = surface + offset * point.n).
    std::uint32_t triangle = 0;
    std::array<double, 3> barycentric{1, 0, 0};
    vec3<double> surface{0, 0, 0};
    /// The UV coordinates of the surface point (the texel centre clamped into the triangle).
    double u = 0, v = 0;
    /// Handedness of the tangent frame: bitangent = bitangent_sign * cross(n, tangent), the
    /// sign of the interpolated tangents' w (glTF); +1 without tangents.
    double bitangent_sign = 1;
    /// The offset applied along point.n, in world units.
    double offset = 0;
};

struct LightmapLayout {
    int width = 0, height = 0;
    std::vector<LightmapSample> samples;  // one per covered texel, in row-major order
    std::vector<std::uint8_t> covered;    // width * height: 1 where a sample is
    std::size_t skipped_triangles = 0;    // zero-area in UV space (not rasterised)
    /// Triangles with UV area but zero area in space and no usable shading normal: no normal
    /// can be given to their samples, so they are not rasterised either (counted apart).
    std::size_t degenerate_triangles = 0;
};

/// Options of layout_lightmap().
struct LightmapOptions {
    /// Offset of each sample along its normal, in texels of world-space size (see the header).
    /// Must be finite and >= 0; 0 keeps samples exactly on the surface.
    double normal_offset = 1.0 / 16.0;
};

namespace lightmap_detail {

/// Area of the part of triangle (a, b, c) (pixel coordinates) inside the square
/// [x0, x0 + 1] x [y0, y0 + 1]: the triangle clipped by the square's four edges
/// (Sutherland-Hodgman), then the shoelace formula relative to the first vertex, so a polygon
/// degenerate to a segment on an edge gives exactly 0.
inline double clipped_area(const std::array<double, 2>* tri, double x0, double y0) noexcept {
    std::array<std::array<double, 2>, 9> buf_a{}, buf_b{};
    int n = 3;
    for (int i = 0; i < 3; ++i) buf_a[static_cast<std::size_t>(i)] = tri[i];
    auto* in = &buf_a;
    auto* out = &buf_b;
    // Clip against: x >= x0, x <= x0 + 1, y >= y0, y <= y0 + 1.
    for (int e = 0; e < 4 && n > 0; ++e) {
        const int axis = e / 2;
        const bool lower = (e % 2) == 0;
        const double c = (axis == 0 ? x0 : y0) + (lower ? 0.0 : 1.0);
        int m = 0;
        for (int i = 0; i < n; ++i) {
            const auto& p = (*in)[static_cast<std::size_t>(i)];
            const auto& q = (*in)[static_cast<std::size_t>((i + 1) % n)];
            const double dp = lower ? p[static_cast<std::size_t>(axis)] - c
                                    : c - p[static_cast<std::size_t>(axis)];
            const double dq = lower ? q[static_cast<std::size_t>(axis)] - c
                                    : c - q[static_cast<std::size_t>(axis)];
            if (dp >= 0) (*out)[static_cast<std::size_t>(m++)] = p;
            if ((dp >= 0) != (dq >= 0)) {
                const double t = dp / (dp - dq);
                std::array<double, 2> r;
                r[static_cast<std::size_t>(axis)] = c;  // exactly on the edge
                const std::size_t o = static_cast<std::size_t>(1 - axis);
                r[o] = p[o] + t * (q[o] - p[o]);
                (*out)[static_cast<std::size_t>(m++)] = r;
            }
        }
        n = m;
        std::swap(in, out);
    }
    if (n < 3) return 0;
    const auto& o = (*in)[0];
    double twice = 0;
    for (int i = 1; i + 1 < n; ++i) {
        const auto& p = (*in)[static_cast<std::size_t>(i)];
        const auto& q = (*in)[static_cast<std::size_t>(i + 1)];
        twice += (p[0] - o[0]) * (q[1] - o[1]) - (q[0] - o[0]) * (p[1] - o[1]);
    }
    return 0.5 * std::abs(twice);
}

/// Barycentrics of the point of triangle (a, b, c) closest to p, in 2D (Ericson, "Real-Time
/// Collision Detection", 2005, section 5.1.5, by Voronoi regions).
inline std::array<double, 3> closest_barycentric(const std::array<double, 2>& p,
                                                 const std::array<double, 2>& a,
                                                 const std::array<double, 2>& b,
                                                 const std::array<double, 2>& c) noexcept {
    auto sub = [](const std::array<double, 2>& s, const std::array<double, 2>& t) {
        return std::array<double, 2>{s[0] - t[0], s[1] - t[1]};
    };
    auto dot2 = [](const std::array<double, 2>& s, const std::array<double, 2>& t) {
        return s[0] * t[0] + s[1] * t[1];
    };
    const auto ab = sub(b, a), ac = sub(c, a), ap = sub(p, a);
    const double d1 = dot2(ab, ap), d2 = dot2(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    const auto bp = sub(p, b);
    const double d3 = dot2(ab, bp), d4 = dot2(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double t = d1 / (d1 - d3);
        return {1 - t, t, 0};
    }
    const auto cp = sub(p, c);
    const double d5 = dot2(ab, cp), d6 = dot2(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double t = d2 / (d2 - d6);
        return {1 - t, 0, t};
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - t, t};
    }
    const double denom = 1 / (va + vb + vc);
    const double bv = vb * denom, bw = vc * denom;
    return {1 - bv - bw, bv, bw};
}

inline vec3<double> load3(const float* p, std::size_t i) noexcept {
    return {double(p[3 * i]), double(p[3 * i + 1]), double(p[3 * i + 2])};
}
inline vec3<double> add(const vec3<double>& a, const vec3<double>& b) noexcept {
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline vec3<double> scale(const vec3<double>& a, double s) noexcept {
    return {a.x * s, a.y * s, a.z * s};
}
inline double norm(const vec3<double>& a) noexcept { return std::sqrt(dot(a, a)); }
/// a / |a|, or zero when |a| is zero or not finite.
inline vec3<double> unit_or_zero(const vec3<double>& a) noexcept {
    const double l = norm(a);
    if (!(l > 0) || !std::isfinite(l)) return {0, 0, 0};
    return scale(a, 1 / l);
}

inline void check_lightmap_size(const char* fn, int width, int height) {
    sphbasis::detail::check_range(fn, "width", width, 1, 16384);
    sphbasis::detail::check_range(fn, "height", height, 1, 16384);
}

}  // namespace lightmap_detail

/// Rasterises the mesh's triangles in UV space with conservative coverage and places each
/// covered texel's sample on the surface (the header explains coverage, sample placement and
/// the offset). Throws std::invalid_argument if the mesh has no UVs, the resolution is not in
/// [1, 16384], an array the mesh needs is null, an index is out of range, a UV or position is
/// not finite, or options.normal_offset is negative or not finite. Triangles of zero UV area
/// are skipped and counted (skipped_triangles). Deterministic; single-threaded.
inline LightmapLayout layout_lightmap(const MeshView& mesh, int width, int height,
                                      std::uint64_t id_base, const LightmapOptions& options) {
    constexpr const char* fn = "render::layout_lightmap";
    lightmap_detail::check_lightmap_size(fn, width, height);
    if (mesh.uvs == nullptr)
        sphbasis::detail::throw_invalid(fn,
                                        "a mesh with UVs (MeshView::uvs), got a mesh without UVs");
    sphbasis::detail::check_buffer(fn, "positions", mesh.positions, mesh.vertex_count);
    sphbasis::detail::check_buffer(fn, "indices", mesh.indices, mesh.triangle_count);
    if (mesh.triangle_count > 0 && mesh.vertex_count == 0)
        sphbasis::detail::throw_invalid(
            fn, "vertices for " + std::to_string(mesh.triangle_count) + " triangles, got none");
    if (!(options.normal_offset >= 0) || !std::isfinite(options.normal_offset))
        sphbasis::detail::throw_invalid(
            fn, "a finite normal_offset >= 0, got " + std::to_string(options.normal_offset));
    for (std::size_t i = 0; i < 2 * mesh.vertex_count; ++i)
        if (!std::isfinite(mesh.uvs[i]))
            sphbasis::detail::throw_invalid(fn, "finite UVs, got " + std::to_string(mesh.uvs[i]) +
                                                    " at vertex " + std::to_string(i / 2));
    for (std::size_t i = 0; i < 3 * mesh.vertex_count; ++i)
        if (!std::isfinite(mesh.positions[i]))
            sphbasis::detail::throw_invalid(fn, "finite positions, got " +
                                                    std::to_string(mesh.positions[i]) +
                                                    " at vertex " + std::to_string(i / 3));
    for (std::size_t i = 0; i < 3 * mesh.triangle_count; ++i)
        if (mesh.indices[i] >= mesh.vertex_count)
            sphbasis::detail::throw_invalid(
                fn, "vertex indices < " + std::to_string(mesh.vertex_count) + ", got " +
                        std::to_string(mesh.indices[i]) + " in triangle " + std::to_string(i / 3));

    LightmapLayout out;
    out.width = width;
    out.height = height;
    const std::size_t texels = std::size_t(width) * std::size_t(height);
    out.covered.assign(texels, 0);
    // Per texel: the best overlap so far and its triangle (ties keep the lower index, which
    // was rasterised first).
    std::vector<double> best_area(texels, 0.0);
    std::vector<std::uint32_t> best_tri(texels, std::numeric_limits<std::uint32_t>::max());
    const double W = width, H = height;

    for (std::size_t t = 0; t < mesh.triangle_count; ++t) {
        const std::uint32_t* idx = mesh.indices + 3 * t;
        std::array<std::array<double, 2>, 3> px;  // pixel coordinates: X = u W, Y = (1 - v) H
        for (int k = 0; k < 3; ++k) {
            const std::size_t v = idx[k];
            px[static_cast<std::size_t>(k)] = {double(mesh.uvs[2 * v]) * W,
                                               (1 - double(mesh.uvs[2 * v + 1])) * H};
        }
        const double twice = (px[1][0] - px[0][0]) * (px[2][1] - px[0][1]) -
                             (px[2][0] - px[0][0]) * (px[1][1] - px[0][1]);
        if (!(std::abs(twice) > 0)) {
            ++out.skipped_triangles;
            continue;
        }
        // Samples need a normal: a triangle degenerate in space needs shading normals.
        const vec3<double> p0 = lightmap_detail::load3(mesh.positions, idx[0]);
        const vec3<double> p1 = lightmap_detail::load3(mesh.positions, idx[1]);
        const vec3<double> p2 = lightmap_detail::load3(mesh.positions, idx[2]);
        const vec3<double> gn = cross(vec3<double>{p1.x - p0.x, p1.y - p0.y, p1.z - p0.z},
                                      vec3<double>{p2.x - p0.x, p2.y - p0.y, p2.z - p0.z});
        if (!(lightmap_detail::norm(gn) > 0) && mesh.normals == nullptr) {
            ++out.degenerate_triangles;
            continue;
        }
        double xmin = px[0][0], xmax = px[0][0], ymin = px[0][1], ymax = px[0][1];
        for (int k = 1; k < 3; ++k) {
            xmin = std::min(xmin, px[static_cast<std::size_t>(k)][0]);
            xmax = std::max(xmax, px[static_cast<std::size_t>(k)][0]);
            ymin = std::min(ymin, px[static_cast<std::size_t>(k)][1]);
            ymax = std::max(ymax, px[static_cast<std::size_t>(k)][1]);
        }
        // Texels whose square can overlap: floor(min) .. ceil(max) - 1, clipped to the image.
        const auto lo_i = [](double v, int n) {
            return int(std::clamp(std::floor(v), 0.0, double(n)));
        };
        const auto hi_i = [](double v, int n) {
            return int(std::clamp(std::ceil(v), 0.0, double(n)));
        };
        const int x0 = lo_i(xmin, width), x1 = hi_i(xmax, width);
        const int y0 = lo_i(ymin, height), y1 = hi_i(ymax, height);
        // Edge functions (positive inside) classify most texels without clipping: a texel with
        // all four corners inside every edge is covered fully, one with all four corners
        // outside one edge is not covered (a separating axis); only the others are clipped.
        const double orient = twice > 0 ? 1.0 : -1.0;
        double ea[3], eb[3], ec[3];  // edge k: ea x + eb y + ec >= 0 inside
        for (std::size_t k = 0; k < 3; ++k) {
            const auto& a = px[k];
            const auto& b = px[(k + 1) % 3];
            ea[k] = -orient * (b[1] - a[1]);
            eb[k] = orient * (b[0] - a[0]);
            ec[k] = -(ea[k] * a[0] + eb[k] * a[1]);
        }
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x) {
                bool inside = true, outside = false;
                for (std::size_t k = 0; k < 3; ++k) {
                    const double e00 = ea[k] * x + eb[k] * y + ec[k];
                    const double e10 = e00 + ea[k], e01 = e00 + eb[k], e11 = e10 + eb[k];
                    const double lo = std::min(std::min(e00, e10), std::min(e01, e11));
                    const double hi = std::max(std::max(e00, e10), std::max(e01, e11));
                    // Margins of rounding size leave borderline texels to the exact clip.
                    const double tol = 1e-9 * (std::abs(ea[k]) + std::abs(eb[k]) + 1) *
                                       (std::abs(x) + std::abs(y) + 1);
                    if (hi < -tol) outside = true;
                    if (lo <= tol) inside = false;
                }
                if (outside) continue;
                const double a =
                    inside ? 1.0 : lightmap_detail::clipped_area(px.data(), double(x), double(y));
                if (!(a > 0)) continue;
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                if (a > best_area[i]) {
                    best_area[i] = a;
                    best_tri[i] = static_cast<std::uint32_t>(t);
                }
            }
    }

    std::size_t count = 0;
    for (std::size_t i = 0; i < texels; ++i)
        count += best_tri[i] != std::numeric_limits<std::uint32_t>::max() ? 1 : 0;
    out.samples.reserve(count);
    const double offset_texels = options.normal_offset;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            if (best_tri[i] == std::numeric_limits<std::uint32_t>::max()) continue;
            const std::uint32_t t = best_tri[i];
            const std::uint32_t* idx = mesh.indices + 3 * std::size_t(t);
            std::array<std::array<double, 2>, 3> uv;
            std::array<vec3<double>, 3> p;
            for (int k = 0; k < 3; ++k) {
                const std::size_t v = idx[k];
                uv[static_cast<std::size_t>(k)] = {double(mesh.uvs[2 * v]),
                                                   double(mesh.uvs[2 * v + 1])};
                p[static_cast<std::size_t>(k)] = lightmap_detail::load3(mesh.positions, v);
            }
            const std::array<double, 2> centre{(x + 0.5) / W, 1 - (y + 0.5) / H};
            const std::array<double, 3> b =
                lightmap_detail::closest_barycentric(centre, uv[0], uv[1], uv[2]);
            LightmapSample s;
            s.x = x;
            s.y = y;
            s.triangle = t;
            s.barycentric = b;
            s.u = b[0] * uv[0][0] + b[1] * uv[1][0] + b[2] * uv[2][0];
            s.v = b[0] * uv[0][1] + b[1] * uv[1][1] + b[2] * uv[2][1];
            s.surface =
                lightmap_detail::add(lightmap_detail::add(lightmap_detail::scale(p[0], b[0]),
                                                          lightmap_detail::scale(p[1], b[1])),
                                     lightmap_detail::scale(p[2], b[2]));
            const vec3<double> e1{p[1].x - p[0].x, p[1].y - p[0].y, p[1].z - p[0].z};
            const vec3<double> e2{p[2].x - p[0].x, p[2].y - p[0].y, p[2].z - p[0].z};
            const vec3<double> gcross = cross(e1, e2);
            vec3<double> n{0, 0, 0};
            if (mesh.normals != nullptr) {
                vec3<double> acc{0, 0, 0};
                for (int k = 0; k < 3; ++k)
                    acc = lightmap_detail::add(
                        acc, lightmap_detail::scale(lightmap_detail::load3(mesh.normals, idx[k]),
                                                    b[static_cast<std::size_t>(k)]));
                n = lightmap_detail::unit_or_zero(acc);
            }
            if (dot(n, n) == 0) n = lightmap_detail::unit_or_zero(gcross);
            if (dot(n, n) == 0) n = {0, 0, 1};  // unreachable: degenerate triangles skipped
            vec3<double> tangent{0, 0, 0};
            if (mesh.tangents != nullptr) {
                vec3<double> acc{0, 0, 0};
                double w = 0;
                for (int k = 0; k < 3; ++k) {
                    const float* tk = mesh.tangents + 4 * std::size_t(idx[k]);
                    const double bk = b[static_cast<std::size_t>(k)];
                    acc =
                        lightmap_detail::add(acc, vec3<double>{bk * tk[0], bk * tk[1], bk * tk[2]});
                    w += bk * tk[3];
                }
                tangent = lightmap_detail::unit_or_zero(lightmap_detail::add(
                    acc, lightmap_detail::scale(n, -dot(acc, n))));  // Gram-Schmidt
                s.bitangent_sign = w < 0 ? -1.0 : 1.0;
                s.point.bitangent_sign = s.bitangent_sign;
            }
            // World-space size of a texel on this triangle: sqrt(area / UV area in texels).
            const double area3 = 0.5 * lightmap_detail::norm(gcross);
            const double area_uv = 0.5 *
                                   std::abs((uv[1][0] - uv[0][0]) * (uv[2][1] - uv[0][1]) -
                                            (uv[2][0] - uv[0][0]) * (uv[1][1] - uv[0][1])) *
                                   W * H;
            const double texel_size = area_uv > 0 ? std::sqrt(area3 / area_uv) : 0.0;
            s.offset = offset_texels * texel_size;
            s.point.p = lightmap_detail::add(s.surface, lightmap_detail::scale(n, s.offset));
            s.point.n = n;
            s.point.tangent = tangent;
            s.point.id = id_base + std::uint64_t(i);
            out.covered[i] = 1;
            out.samples.push_back(s);
        }
    return out;
}

/// layout_lightmap() with the default LightmapOptions.
inline LightmapLayout layout_lightmap(const MeshView& mesh, int width, int height,
                                      std::uint64_t id_base = 0) {
    return layout_lightmap(mesh, width, height, id_base, LightmapOptions{});
}

/// Fills up to `gutter` texels around the covered region (covered[i] != 0) with the average of
/// covered neighbours, `channels` floats per texel, so bilinear filtering does not fetch
/// unbaked texels. Pass k (1 <= k <= gutter) gives every texel not yet filled that has a
/// covered or already-filled texel among its 8 neighbours the average of those neighbours (as
/// they were before the pass, so the result does not depend on the scan order): after `gutter`
/// passes exactly the texels within Chebyshev distance `gutter` of the covered region are
/// filled. Covered texels are never written; texels farther away are left as they are. Throws
/// std::invalid_argument for a size outside [1, 16384], channels < 1, gutter < 0, a null
/// image or covered.size() != width * height. Cost O(gutter * width * height * channels),
/// width * height bytes of scratch.
inline void dilate(float* image, int width, int height, int channels,
                   const std::vector<std::uint8_t>& covered, int gutter) {
    constexpr const char* fn = "render::dilate";
    lightmap_detail::check_lightmap_size(fn, width, height);
    if (channels < 1)
        sphbasis::detail::throw_invalid(fn, "channels >= 1, got " + std::to_string(channels));
    if (gutter < 0)
        sphbasis::detail::throw_invalid(fn, "gutter >= 0, got " + std::to_string(gutter));
    const std::size_t texels = std::size_t(width) * std::size_t(height);
    if (covered.size() != texels)
        sphbasis::detail::throw_invalid(
            fn, "covered.size() == width * height = " + std::to_string(texels) + ", got " +
                    std::to_string(covered.size()));
    sphbasis::detail::check_buffer(fn, "image", image, texels);
    std::vector<std::uint8_t> known(texels);
    for (std::size_t i = 0; i < texels; ++i) known[i] = covered[i] != 0 ? 1 : 0;
    std::vector<double> sum(static_cast<std::size_t>(channels));
    const std::size_t ch = static_cast<std::size_t>(channels);
    for (int pass = 0; pass < gutter; ++pass) {
        bool any = false;
        // 2 marks texels filled in this pass: they are not read until the next one.
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                if (known[i] != 0) continue;
                int count = 0;
                std::fill(sum.begin(), sum.end(), 0.0);
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int nx = x + dx, ny = y + dy;
                        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= width || ny >= height)
                            continue;
                        const std::size_t j =
                            std::size_t(ny) * std::size_t(width) + std::size_t(nx);
                        if (known[j] != 1) continue;
                        ++count;
                        for (std::size_t c = 0; c < ch; ++c) sum[c] += double(image[j * ch + c]);
                    }
                if (count == 0) continue;
                for (std::size_t c = 0; c < ch; ++c)
                    image[i * ch + c] = static_cast<float>(sum[c] / count);
                known[i] = 2;
                any = true;
            }
        if (!any) break;
        for (auto& k : known)
            if (k == 2) k = 1;
    }
}

/// Texels dilated around each chart by assemble_lightmap(): enough for bilinear filtering and
/// the first mip levels (each halving needs one more texel of gutter).
inline constexpr int lightmap_gutter = 4;

/// The lightmap image of a layout: `channels` floats per texel, row-major from the top row,
/// sample i's values written by pack(i, float* out) (channels floats) at its texel, gutters
/// dilated by lightmap_gutter texels (dilate()), zero farther away. Throws
/// std::invalid_argument for channels < 1 or a layout whose sizes disagree.
/// Cost O(samples * channels + lightmap_gutter * width * height * channels).
template <class Pack>
std::vector<float> assemble_lightmap(const LightmapLayout& layout, int channels, Pack&& pack) {
    constexpr const char* fn = "render::assemble_lightmap";
    lightmap_detail::check_lightmap_size(fn, layout.width, layout.height);
    if (channels < 1)
        sphbasis::detail::throw_invalid(fn, "channels >= 1, got " + std::to_string(channels));
    const std::size_t ch = std::size_t(channels);
    const std::size_t w = std::size_t(layout.width), texels = w * std::size_t(layout.height);
    std::vector<float> image(texels * ch, 0.0f);
    for (std::size_t i = 0; i < layout.samples.size(); ++i) {
        const LightmapSample& s = layout.samples[i];
        if (s.x < 0 || s.y < 0 || s.x >= layout.width || s.y >= layout.height)
            sphbasis::detail::throw_invalid(
                fn, "samples inside the layout, got sample " + std::to_string(i) + " at (" +
                        std::to_string(s.x) + ", " + std::to_string(s.y) + ")");
        pack(i, image.data() + (std::size_t(s.y) * w + std::size_t(s.x)) * ch);
    }
    dilate(image.data(), layout.width, layout.height, channels, layout.covered, lightmap_gutter);
    return image;
}

}  // namespace sphbasis::render
