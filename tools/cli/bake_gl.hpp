// sphbasis CLI: `sphbasis bake --engine gl`, Hill's depth-map bake (tools/gl/gl_bake.hpp) behind
// the bake command's options and files. It bakes ao, transfer (0 bounces) and visibility per
// vertex, per texel and at --points; everything else is refused with one line. The results fill the
// same records as render::Baker's, so every output file and reader is the Embree bake's; bake.json
// gains "engine" (name, directions, resolution, bias, the bounding sphere, the GL renderer).
#pragma once

#include <CLI/CLI.hpp>
#include <sphbasis/render/bake.hpp>
#include <string>
#include <vector>

#include "../support/json.hpp"

namespace sphbasis::cli {

struct GlEngine {
    std::string engine = "embree";
    long long directions = 1024, resolution = 512;
    CLI::Option *directions_opt = nullptr, *resolution_opt = nullptr;
    bool gl() const { return engine == "gl"; }
};

/// Adds --engine, --gl-directions and --gl-resolution to the bake command.
void add_gl_engine_options(CLI::App& app, GlEngine& e);

/// What the bake was asked for, beyond BakeSettings, that the gl engine must refuse.
struct GlRequest {
    bool sharded = false, max_distance = false, high_to_low = false, rays = false;
};

/// Throws UsageError (one line) for an engine name other than embree or gl, --gl-* options
/// without --engine gl, and, with gl, what it does not bake; and when this build has no EGL.
void check_gl_engine(const GlEngine& e, const render::BakeSettings& s, const GlRequest& r);

/// The gl bake of `points` (a progress bar per direction); `record` receives bake.json's
/// "engine" object and `pass` the plan's entry ("gl depth maps", seconds, rays 0).
std::vector<render::PointResult> gl_engine_bake(const GlEngine& e, const render::SceneDesc& scene,
                                                const std::vector<render::BakePoint>& points,
                                                const render::BakeSettings& s, Json& record,
                                                render::Pass& pass);

}  // namespace sphbasis::cli
