// Hill's depth-map bake: ambient occlusion, diffuse SH transfer (no bounces) and SH visibility of
// bake points,
// from orthographic depth maps of the scene rendered from N directions over the sphere, in
// OpenGL 4.3 (a vertex/fragment depth pass and a compute pass per direction) through headless
// EGL (tools/gl/egl_context.hpp): `sphbasis bake --engine gl`.
//
// Source: Hill, "Hardware Accelerating Art Production" (Gamasutra 2004), "Mapping AO onto the
// GPU" (eq. 3a/3b: a sphere of directions, one depth map each, visibility by a depth comparison,
// samples weighted by the hemispherical function and averaged by the weight sum) and the PRT
// extension (eq. 5: the same samples times the basis functions, which are evaluated on the CPU
// per direction and uploaded as constants). Orthographic maps fitted to the scene's bounding
// sphere, as the article recommends.
//
// Per point x (unit normal n) and direction d_j, j = 0 .. N-1, of the spherical Fibonacci set
// (z_j = 1 - (2j + 1)/N, azimuth 2 pi j / golden ratio; each of solid angle 4 pi / N):
//   w_j   = (4 pi / N) max(n.d_j, 0)
//   V_j   = 1 when depth(x) <= map_j(x) + bias_j (nothing between x and the sky along d_j)
//   ao    = sum_j w_j V_j / sum_j w_j
//   t_i   = sum_j w_j V_j y_i(d_j) / sum_j w_j           (render/bake.hpp's `transfer`, 0 bounces)
//   v_i   = (4 pi / N) sum_{j: n.d_j > 0} V_j y_i(d_j)  (render/bake.hpp's `visibility`)
// Dividing by sum_j w_j (Hill's weight sum) rather than pi makes a point nothing occludes get
// ao = 1 and t_i = a_l y_i(n) up to the direction set's quadrature error of y_i cos.
// The depth map of d_j: the scene (every triangle, both sides) rendered orthographically along
// -d_j into a res x res depth texture (32-bit float) covering the bounding sphere of the scene
// and the points (centre c, radius R; texel size w = 2R/res). depth(x) and map_j(x) are distances
// along -d_j; map_j(x) is the nearest-texel value at x's texel (no filtering).
// Bias: bias_j = k w (1 + tan theta_j), theta_j the angle between n and d_j, k =
// GlBakeOptions::bias_texels (1): the point's own surface, sampled at a texel centre up to
// w/sqrt(2) away, lies at most (w/sqrt(2)) tan theta nearer the sky, plus one texel of rasterizer
// and float slack. Consequences: an occluder closer to x than bias_j along d_j is missed, and
// within about a texel of an occluder's silhouette in map_j the test is decided by the texel's
// centre, so ao errs there by the weight of those directions.
// Standard errors (ao_stderr, transfer_stderr): those of N_eff = (sum w)^2 / sum w^2 independent
// samples with the same weighted variance; visibility_stderr: that of the n_h directions above
// the tangent plane as uniform hemisphere samples 2 pi V y_i. A scale for the sampling error of
// the direction set, not a bound on the depth-map error.
//
// Cost: N depth renders of all triangles at res^2 and N compute dispatches over the points
// (O(N (T + res^2 + P bands^2)) work), one readback; memory: the triangles, one res^2 depth
// texture, 4 + 2 bands^2 floats per point and quantity with SH.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "sphbasis/core/vec.hpp"
#include "sphbasis/render/bake.hpp"
#include "sphbasis/render/scene.hpp"

namespace sphbasis::gl {

/// The quantities gl_bake() bakes.
inline constexpr render::Quantity gl_quantities =
    render::Quantity::ao | render::Quantity::transfer | render::Quantity::visibility;

struct GlBakeOptions {
    int directions = 1024;     // N, over the sphere
    int resolution = 512;      // res: the depth maps are res x res
    double bias_texels = 1.0;  // k of the bias (header comment), in texels
    bool software = false;     // force Mesa's llvmpipe (LIBGL_ALWAYS_SOFTWARE)
};

/// What a GL bake did: the driver, the bounding sphere, the work and its time.
struct GlBakeInfo {
    std::string renderer, version;                        // GL_RENDERER, GL_VERSION
    double center[3] = {0, 0, 0}, radius = 0, texel = 0;  // c, R, w (world units)
    std::size_t triangles = 0, tests = 0;                 // tests: points x directions
    double seconds = 0;                                   // context excluded
};

/// The spherical Fibonacci directions (header comment), unit, in order.
std::vector<vec3<double>> fibonacci_directions(int n);

/// "" when a headless OpenGL 4.3 context can be (or was) created on this thread, else why not.
std::string gl_unavailable_reason(bool software = false);

/// Bakes `quantities` (of gl_quantities; SH ones with `bands` bands) at the
/// points (surface points: non-zero normal) of the scene's triangles. Results fill the same
/// PointResult fields as render::Baker (transfer's three channels equal, transfer_rgb false).
/// `progress(j)` is called after direction j. Throws std::invalid_argument for other
/// quantities, bands outside 1..16, a free or non-finite point, options out of range, and
/// std::runtime_error when no OpenGL 4.3 context can be created or GL reports an error.
std::vector<render::PointResult> gl_bake(const render::SceneDesc& scene,
                                         const std::vector<render::BakePoint>& points,
                                         render::Quantity quantities, int bands,
                                         const GlBakeOptions& options, GlBakeInfo* info = nullptr,
                                         const std::function<void(std::size_t)>& progress = {});

}  // namespace sphbasis::gl
