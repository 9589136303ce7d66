// sphbasis render tier: seamless lightmap charts by least squares on the texels of UV seams.
//
// A seam is a mesh edge whose two triangles map its ends to different UVs (a UV sphere's
// u = 0 / u = 1 column, the edges between the faces of a box with a chart per face). A point
// of the edge then reads the lightmap at two places, one per side, and bilinear filtering mixes
// different texels there: each side's texels are baked at their own centres, half a texel
// inside the chart, so the two sides disagree by about the gradient times a texel, plus the
// bake's noise. Stitching (Liu, Ferguson, Jacobson and Gingold, "Seamless: Seam Erasure and
// Seam-Aware Decoupling of Shape from Mesh Resolution", ACM TOG 36(6) 2017, the seam-erasure
// energy) changes only the texels that bilinear filtering reads along the seams, minimising
//     sum_i (x_i - x0_i)^2 + weight * sum_s (B0(s) x - B1(s) x)^2
// where x0 are the baked (and dilated) values, s runs over points along each seam edge
// (samples_per_texel per texel of the longer side, at (k + 1/2) / n of the edge) and B0, B1 are
// the bilinear weights of the two sides' UVs of s. The normal equations
// (I + weight sum_s d_s d_s^T) x = x0, d_s = B0(s) - B1(s), are sparse, symmetric positive
// definite, shared by every channel: one sparse Cholesky factorisation (Eigen's
// SimplicialLDLT), one solve per channel. A larger weight leaves less of a jump and moves the
// texels farther along chains of seams (the fans at a UV sphere's poles tie a whole row): at the
// default 1000 the largest jump of a smooth field baked into 64^2 texels drops to 2.3% (a
// 16 x 32 UV sphere, at a pole fan) and 0.8% (a box's chart edges) of what it was; 100 leaves
// 3.5% and 5.5%, 10000 0.9% and 0.08% (tests/render/test_seams.cpp's fields).
//
// Bilinear filtering: texel (x, y) (x right, y down from the top row, v = 1) has its centre at
// ((x + 1/2) / W, 1 - (y + 1/2) / H) (render/lightmap.hpp); a UV reads the four nearest
// centres, indices clamped to the image (clamp-to-edge addressing, which is what a UV on the
// image border such as the sphere's u = 0 and u = 1 needs).
//
// Cost: O(E log E) to find the seams of E triangle edges; the solve is over the texels within
// one texel of a seam (a thin band: O(seam length in texels)), with at most 8 x 8 non-zeros per
// seam point.
#pragma once

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "mesh.hpp"

namespace sphbasis::render {

/// A seam edge: its two ends in the UV sets of its two triangles, uv[side][end] = {u, v}, the
/// ends matched by position. `crease`: the vertex normals differ across it at an end.
struct SeamEdge {
    std::array<std::array<std::array<double, 2>, 2>, 2> uv{};
    std::array<std::uint32_t, 2> triangle{};
    bool crease = false;
};

/// The seam edges of a mesh: pairs of triangle edges with the same two end positions (bit for
/// bit, as a UV split duplicates a vertex) whose UVs differ at either end. Edges shared by one
/// or more than two triangles are not seams (borders, non-manifold). A crease (the mesh's
/// vertex normals differ across the edge, like a box's flat faces) is left out unless
/// `creases`: the quantities of a surface point depend on its normal, so the two sides of a
/// crease differ in truth and stitching would blur a real edge; a position-only quantity
/// (radiance at points) may stitch them. Without normals no edge is a crease. Throws
/// std::invalid_argument for a mesh without UVs or with an index out of range. Deterministic
/// (sorted by position). Cost O(E log E), E = 3 triangles.
inline std::vector<SeamEdge> find_seams(const MeshView& mesh, bool creases = false) {
    constexpr const char* fn = "render::find_seams";
    if (mesh.uvs == nullptr) sphbasis::detail::throw_invalid(fn, "a mesh with UVs, got none");
    sphbasis::detail::check_buffer(fn, "positions", mesh.positions, mesh.vertex_count);
    sphbasis::detail::check_buffer(fn, "indices", mesh.indices, mesh.triangle_count);
    for (std::size_t i = 0; i < 3 * mesh.triangle_count; ++i)
        if (mesh.indices[i] >= mesh.vertex_count)
            sphbasis::detail::throw_invalid(
                fn, "vertex indices < " + std::to_string(mesh.vertex_count) + ", got " +
                        std::to_string(mesh.indices[i]) + " in triangle " + std::to_string(i / 3));
    struct Half {
        std::array<float, 6> key;        // the two end positions, lower first
        std::array<std::uint32_t, 2> v;  // the vertices at those ends
        std::uint32_t triangle;
    };
    std::vector<Half> h;
    h.reserve(3 * mesh.triangle_count);
    for (std::size_t t = 0; t < mesh.triangle_count; ++t)
        for (std::size_t k = 0; k < 3; ++k) {
            std::uint32_t a = mesh.indices[3 * t + k], b = mesh.indices[3 * t + (k + 1) % 3];
            std::array<float, 3> pa, pb;
            for (std::size_t c = 0; c < 3; ++c) {
                pa[c] = mesh.positions[3 * std::size_t(a) + c];
                pb[c] = mesh.positions[3 * std::size_t(b) + c];
            }
            if (pa == pb) continue;
            if (pb < pa) {
                std::swap(pa, pb);
                std::swap(a, b);
            }
            h.push_back({{pa[0], pa[1], pa[2], pb[0], pb[1], pb[2]}, {a, b}, std::uint32_t(t)});
        }
    std::sort(h.begin(), h.end(), [](const Half& x, const Half& y) {
        return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
    });
    auto uv = [&](std::uint32_t v) {
        return std::array<double, 2>{double(mesh.uvs[2 * std::size_t(v)]),
                                     double(mesh.uvs[2 * std::size_t(v) + 1])};
    };
    std::vector<SeamEdge> out;
    for (std::size_t i = 0; i < h.size();) {
        std::size_t j = i + 1;
        while (j < h.size() && h[j].key == h[i].key) ++j;
        if (j - i == 2) {
            SeamEdge e;
            for (std::size_t s = 0; s < 2; ++s) {
                e.uv[s] = {uv(h[i + s].v[0]), uv(h[i + s].v[1])};
                e.triangle[s] = h[i + s].triangle;
            }
            if (mesh.normals != nullptr)
                for (std::size_t end = 0; end < 2; ++end)
                    for (std::size_t c = 0; c < 3; ++c)
                        e.crease =
                            e.crease || mesh.normals[3 * std::size_t(h[i].v[end]) + c] !=
                                            mesh.normals[3 * std::size_t(h[i + 1].v[end]) + c];
            if (e.uv[0] != e.uv[1] && (creases || !e.crease)) out.push_back(e);
        }
        i = j;
    }
    return out;
}

/// The bilinear taps of a UV: four texel indices (y * width + x) and weights summing to 1
/// (header: texel centres, clamp-to-edge).
struct BilinearTaps {
    std::array<std::size_t, 4> texel{};
    std::array<double, 4> weight{};
};

inline BilinearTaps bilinear_taps(int width, int height, double u, double v) noexcept {
    const double X = u * width - 0.5, Y = (1 - v) * height - 0.5;
    const double fx0 = std::floor(X), fy0 = std::floor(Y);
    const double fx = X - fx0, fy = Y - fy0;
    auto clampi = [](double i, int n) { return std::size_t(std::clamp(i, 0.0, double(n - 1))); };
    const std::size_t x0 = clampi(fx0, width), x1 = clampi(fx0 + 1, width);
    const std::size_t y0 = clampi(fy0, height), y1 = clampi(fy0 + 1, height);
    const std::size_t W = std::size_t(width);
    return {{y0 * W + x0, y0 * W + x1, y1 * W + x0, y1 * W + x1},
            {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy}};
}

/// Channel c of an image (`channels` floats per texel, row-major from the top row) filtered
/// bilinearly at (u, v).
inline double sample_bilinear(const float* image, int width, int height, int channels, int c,
                              double u, double v) noexcept {
    const BilinearTaps t = bilinear_taps(width, height, u, v);
    double s = 0;
    for (std::size_t k = 0; k < 4; ++k)
        s += t.weight[k] * double(image[t.texel[k] * std::size_t(channels) + std::size_t(c)]);
    return s;
}

/// Options of stitch_seams().
struct SeamOptions {
    double weight = 1000;          // of the seam term against the baked values (header)
    double samples_per_texel = 2;  // seam points per texel of edge length (longer side)
};

/// What stitch_seams() did: the seam points, the texels it solved for, and the largest jump
/// |B0(s) x - B1(s) x| over the seam points and stitched channels before and after.
struct SeamStats {
    std::size_t edges = 0, points = 0, texels = 0;
    double max_jump_before = 0, max_jump_after = 0;
};

namespace seams_detail {

/// The points along the seams at which the two sides are compared: their two sides' taps.
inline std::vector<std::array<BilinearTaps, 2>> seam_points(int width, int height,
                                                            const std::vector<SeamEdge>& seams,
                                                            double samples_per_texel) {
    std::vector<std::array<BilinearTaps, 2>> pts;
    for (const SeamEdge& e : seams) {
        double len = 0;
        for (std::size_t s = 0; s < 2; ++s)
            len = std::max(len, std::hypot((e.uv[s][1][0] - e.uv[s][0][0]) * width,
                                           (e.uv[s][1][1] - e.uv[s][0][1]) * height));
        const int n = std::max(1, int(std::ceil(samples_per_texel * len)));
        for (int k = 0; k < n; ++k) {
            const double t = (k + 0.5) / n;
            std::array<BilinearTaps, 2> p;
            for (std::size_t s = 0; s < 2; ++s)
                p[s] = bilinear_taps(width, height,
                                     e.uv[s][0][0] + t * (e.uv[s][1][0] - e.uv[s][0][0]),
                                     e.uv[s][0][1] + t * (e.uv[s][1][1] - e.uv[s][0][1]));
            pts.push_back(p);
        }
    }
    return pts;
}

inline double max_jump(const float* image, int channels, int stitched,
                       const std::vector<std::array<BilinearTaps, 2>>& pts) {
    double m = 0;
    for (const auto& p : pts)
        for (int c = 0; c < stitched; ++c) {
            double d = 0;
            for (std::size_t s = 0; s < 2; ++s)
                for (std::size_t k = 0; k < 4; ++k)
                    d += (s == 0 ? 1 : -1) * p[s].weight[k] *
                         double(image[p[s].texel[k] * std::size_t(channels) + std::size_t(c)]);
            m = std::max(m, std::fabs(d));
        }
    return m;
}

}  // namespace seams_detail

/// The largest jump across the seams of channels [0, stitched) of an image: the measure
/// stitch_seams() reports, at the same seam points.
inline double seam_jump(const float* image, int width, int height, int channels, int stitched,
                        const std::vector<SeamEdge>& seams, const SeamOptions& options = {}) {
    return seams_detail::max_jump(
        image, channels, stitched,
        seams_detail::seam_points(width, height, seams, options.samples_per_texel));
}

/// Stitches channels [0, stitched) of a lightmap (`channels` floats per texel, row-major from
/// the top row; other channels, e.g. a coverage mask, are left alone) across the seams of its
/// mesh (find_seams()), in place: the least-squares problem of the header over the texels
/// bilinear filtering reads along the seams. Call it on the assembled image (after the gutter
/// dilation, whose texels the seam points also read). Throws std::invalid_argument for a size
/// outside [1, 16384], stitched not in [0, channels], weight or samples_per_texel not finite
/// and > 0, or a null image; std::runtime_error if the factorisation fails (it cannot for
/// finite input: the matrix is I plus a positive semi-definite sum).
inline SeamStats stitch_seams(float* image, int width, int height, int channels, int stitched,
                              const std::vector<SeamEdge>& seams, const SeamOptions& options = {}) {
    constexpr const char* fn = "render::stitch_seams";
    sphbasis::detail::check_range(fn, "width", width, 1, 16384);
    sphbasis::detail::check_range(fn, "height", height, 1, 16384);
    sphbasis::detail::check_range(fn, "channels", channels, 1, 1 << 20);
    sphbasis::detail::check_range(fn, "stitched", stitched, 0, channels);
    if (!(options.weight > 0) || !std::isfinite(options.weight) ||
        !(options.samples_per_texel > 0) || !std::isfinite(options.samples_per_texel))
        sphbasis::detail::throw_invalid(fn, "a finite weight > 0 and samples_per_texel > 0");
    sphbasis::detail::check_buffer(fn, "image", image, std::size_t(width) * std::size_t(height));
    SeamStats st;
    st.edges = seams.size();
    const auto pts = seams_detail::seam_points(width, height, seams, options.samples_per_texel);
    st.points = pts.size();
    st.max_jump_before = seams_detail::max_jump(image, channels, stitched, pts);
    if (pts.empty() || stitched == 0) {
        st.max_jump_after = st.max_jump_before;
        return st;
    }
    // The unknowns: every texel a seam point reads, numbered in texel order.
    std::vector<std::size_t> texels;
    for (const auto& p : pts)
        for (const auto& side : p)
            texels.insert(texels.end(), side.texel.begin(), side.texel.end());
    std::sort(texels.begin(), texels.end());
    texels.erase(std::unique(texels.begin(), texels.end()), texels.end());
    st.texels = texels.size();
    auto var = [&](std::size_t texel) {
        return Eigen::Index(std::lower_bound(texels.begin(), texels.end(), texel) - texels.begin());
    };
    const Eigen::Index n = Eigen::Index(texels.size());
    std::vector<Eigen::Triplet<double>> trip;
    trip.reserve(std::size_t(n) + pts.size() * 64);
    for (Eigen::Index i = 0; i < n; ++i) trip.emplace_back(i, i, 1.0);
    for (const auto& p : pts) {
        std::array<std::pair<Eigen::Index, double>, 8> d;
        for (std::size_t s = 0; s < 2; ++s)
            for (std::size_t k = 0; k < 4; ++k)
                d[4 * s + k] = {var(p[s].texel[k]), (s == 0 ? 1 : -1) * p[s].weight[k]};
        for (const auto& a : d)
            for (const auto& b : d)
                if (a.second != 0 && b.second != 0)
                    trip.emplace_back(a.first, b.first, options.weight * a.second * b.second);
    }
    Eigen::SparseMatrix<double> A(n, n);
    A.setFromTriplets(trip.begin(), trip.end());  // duplicates are summed
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(A);
    if (ldlt.info() != Eigen::Success)
        throw std::runtime_error(std::string("sphbasis::") + fn +
                                 "(): the seam system could not be factorised");
    const std::size_t ch = std::size_t(channels);
    Eigen::VectorXd x0(n);
    for (int c = 0; c < stitched; ++c) {
        for (Eigen::Index i = 0; i < n; ++i)
            x0(i) = double(image[texels[std::size_t(i)] * ch + std::size_t(c)]);
        const Eigen::VectorXd x = ldlt.solve(x0);
        for (Eigen::Index i = 0; i < n; ++i)
            image[texels[std::size_t(i)] * ch + std::size_t(c)] = static_cast<float>(x(i));
    }
    st.max_jump_after = seams_detail::max_jump(image, channels, stitched, pts);
    return st;
}

}  // namespace sphbasis::render
