// sphbasis CLI: the gl engine of `sphbasis bake` (bake_gl.hpp).
#include "bake_gl.hpp"

#include <cstdio>

#include "../support/args.hpp"
#include "../support/progress.hpp"
#include "cli.hpp"
#ifdef SPHBASIS_HAVE_GL_BAKE
#include "gl_bake.hpp"
#endif

namespace sphbasis::cli {

void add_gl_engine_options(CLI::App& app, GlEngine& e) {
    app.add_option("--engine", e.engine,
                   "embree (ray tracing, every quantity) or gl (Hill's depth maps in OpenGL 4.3 "
                   "through headless EGL: ao, transfer with 0 bounces, visibility)")
        ->type_name("embree|gl")
        ->capture_default_str();
    e.directions_opt = add_integer(app, "--gl-directions", e.directions, 1, 1 << 20,
                                   "--engine gl: depth-map directions over the sphere (default "
                                   "1024)");
    e.resolution_opt = add_integer(app, "--gl-resolution", e.resolution, 1, 16384,
                                   "--engine gl: depth maps are R x R texels (default 512)", "R");
}

void check_gl_engine(const GlEngine& e, const render::BakeSettings& s, const GlRequest& r) {
    if (e.engine != "embree" && !e.gl())
        throw UsageError("--engine: expected embree or gl, got '" + quote_input(e.engine) + "'");
    if (!e.gl()) {
        if (e.directions_opt->count() > 0 || e.resolution_opt->count() > 0)
            throw UsageError("--gl-directions, --gl-resolution: only with --engine gl");
        return;
    }
    const std::string pre = "--engine gl: ";
    using render::Quantity;
    const Quantity supported = Quantity::ao | Quantity::transfer | Quantity::visibility;
    if (any(s.quantities & ~supported))
        throw UsageError(pre + "bakes the quantities ao, transfer and visibility only, got '" +
                         render::quantity_names(s.quantities & ~supported) +
                         "' (use --engine embree)");
    if (s.bounces > 0)
        throw UsageError(pre + "bakes transfer without bounces (--bounces 0), got --bounces " +
                         std::to_string(s.bounces));
    if (s.adaptive.enabled())
        throw UsageError(pre + "samples a fixed direction set: no --target-error or --max-rays");
    if (r.rays) throw UsageError(pre + "samples --gl-directions directions, not --rays");
    if (r.max_distance)
        throw UsageError(pre +
                         "a depth map holds the nearest surface to the sky only: no "
                         "--max-distance");
    if (r.sharded) throw UsageError(pre + "bakes in one run: no --shard");
    if (r.high_to_low)
        throw UsageError(pre + "does not bake high to low (a mesh of the scene has a \"source\")");
#ifndef SPHBASIS_HAVE_GL_BAKE
    throw UsageError(pre +
                     "this sphbasis was built without EGL and GL/glcorearb.h (install "
                     "libegl-dev libgl-dev and rebuild)");
#endif
}

std::vector<render::PointResult> gl_engine_bake(const GlEngine& e, const render::SceneDesc& scene,
                                                const std::vector<render::BakePoint>& points,
                                                const render::BakeSettings& s, Json& record,
                                                render::Pass& pass) {
#ifdef SPHBASIS_HAVE_GL_BAKE
    gl::GlBakeOptions o;
    o.directions = static_cast<int>(e.directions);
    o.resolution = static_cast<int>(e.resolution);
    gl::GlBakeInfo info;
    std::vector<render::PointResult> r;
    {
        Progress bar("gl bake", e.directions);
        r = gl::gl_bake(scene, points, s.quantities, s.bands, o, &info,
                        [&bar](std::size_t) { bar.update(); });
        bar.done();
    }
    record = {
        {"name", "gl"},
        {"directions", o.directions},
        {"resolution", o.resolution},
        {"bias",
         {{"texels", o.bias_texels},
          {"world", o.bias_texels * info.texel},
          {"rule", "depth <= map + k w (1 + tan theta)"}}},
        {"texel", info.texel},
        {"sphere",
         {{"center", {info.center[0], info.center[1], info.center[2]}}, {"radius", info.radius}}},
        {"triangles", info.triangles},
        {"tests", info.tests},
        {"renderer", info.renderer},
        {"version", info.version}};
    pass.name = "gl depth maps";
    pass.reason = "--engine gl: " + std::to_string(o.directions) + " orthographic " +
                  std::to_string(o.resolution) + "^2 depth maps, one test per point and map";
    pass.rays = 0;
    pass.seconds = info.seconds;
    std::fprintf(stderr,
                 "sphbasis bake: gl: %zu points x %d directions (%d^2 maps) on %s in %.3f s\n",
                 points.size(), o.directions, o.resolution, info.renderer.c_str(), info.seconds);
    return r;
#else
    (void)e, (void)scene, (void)points, (void)s, (void)record, (void)pass;
    throw UsageError("--engine gl: this sphbasis was built without EGL");
#endif
}

}  // namespace sphbasis::cli
