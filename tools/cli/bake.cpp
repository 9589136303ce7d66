// sphbasis CLI: `sphbasis bake SCENE.json [options]` and `sphbasis bake-merge SHARD... [--out DIR]`
//
// Bakes lighting representations of a scene (docs/scene-format.md) with render::Baker
// (render/bake.hpp): ambient occlusion and its standard error, bent normals, SH visibility,
// diffuse PRT transfer vectors with interreflections, irradiance in any basis of the library,
// and SH radiance at free points. Sources: Hill, "Hardware Accelerating Art Production"
// (Gamasutra 2004), eq. 1-5; Sloan, Lehtinen and Kautz, "Precomputed Radiance Transfer: Theory
// and Practice" (SIGGRAPH 2005 course); Iwanicki and Sloan, "Normal Mapping with Low-Frequency
// Precomputed Visibility" (JGT 2009), section 3.1; Ishmukhametov, "Irradiance Normal Mapping"
// (thesis), section 1.9.
//
// Where (--target): the points, their ids, normals and tangents are render/bake_points.hpp's
// (shared with `sphbasis render`):
//   vertices     every vertex of every mesh; point id = global vertex index in scene order.
//                Writes OUT/<mesh>.ply per mesh (support/ply.hpp lists the property names).
//   texels:RES   a RES x RES lightmap per mesh in its UV set (render::layout_lightmap; point
//                id = mesh index * RES^2 + y * RES + x), gutters dilated by render::lightmap_gutter
//                texels (render::assemble_lightmap). Writes OUT/<mesh>.exr (float channels named as
//                the PLY properties, plus "coverage": 1 where a texel was baked, 0 in gutters and
//                empty space); seams stitched (render::stitch_seams, on the non-crease seams of
//                render::find_seams; bake.json's output entry reports the jumps before/after).
//   probes       the scene's "probes" grid (point id = probe index). Writes OUT/probes.json.
//   --points F   points read from F or standard input ('-'): `x y z nx ny nz` (surface) or
//                `x y z` (free point) per line, '#' comments and blank lines skipped; point
//                id = the point's index. Prints one JSON line per point on stdout:
//                {"p":[x,y,z],"n":[nx,ny,nz],"ao":a,"ao_stderr":s,"bent":[...],
//                 "visibility":[...],"transfer":[...]} with the requested keys only ("n" only
//                for surface points; "transfer" is three lists R, G, B when the channels
//                differ; "irradiance" and "radiance" are three lists). Each quantity is
//                followed by its standard error, as "ao_stderr" follows "ao": "bent_stderr"
//                (one number, radians), "visibility_stderr", "transfer_stderr",
//                "irradiance_stderr", "radiance_stderr" (one list each, the max over R, G, B);
//                "inside" comes with "radiance". Numbers with 17 significant digits.
// High to low: the points of a mesh with a "source" (docs/scene-format.md) are moved to the
// source by render/high_to_low.hpp before the bake (the plan's "project" pass), every such mesh
// is left out of the occlusion scene, `normal_map` adds the source's tangent-space normal
// (normal_x/y/z) and `coverage` marks the points whose ray missed (EXR channel; PLY property).
// Every file bake also writes OUT/bake.json: scene, target, settings, seed, the pass plan (each
// pass's name, reason, rays and seconds), timings and the output files with their channels.
// A complete bake of vertices, texels or probes also stores its results for `sphbasis render`:
// OUT/cache/<key>.bin, the entries render's bake cache reads for the same settings (bit for bit
// what render would bake; docs/bake-format.md, "Reuse by render"); --no-cache skips them.
// The files of a run are written all or none (support/output_file.hpp): every name is checked
// (and OUT created) after the scene and options are valid and before the bake; the files are
// staged in OUT and moved into place together at the end, so a failure or a signal leaves OUT
// as it was.
//
// Sharding: --shard I/N bakes the points with index in [floor(P I / N), floor(P (I + 1) / N))
// of the P points in id order and writes OUT/bake.shard-I-of-N.bin (render/bake_file.hpp's
// format, docs/bake-format.md: the raw results and a JSON header, the input hash of the scene
// file, every file it reads, the target and the settings, and a checksum); `sphbasis
// bake-merge` reads all N shards, refuses a corrupt one, one of another bake and all of them
// when the scene or a file it reads changed since, reloads the scene and writes the same
// files as one run would. Results depend only on (seed, point id, settings) (render/bake.hpp),
// so the merged data files are bit-identical to an unsharded bake's; bake.json differs only in
// its timings and its "shards" entry. With --points, a shard prints its own lines (merging is
// concatenation in shard order).
//
// Adaptive sampling (--target-error X or NAME:X,..., --max-rays N; render::AdaptiveSampling):
// each point traces batches of --rays rays until its standard error of each named quantity is
// at most X or N rays per pass are reached; bake.json's "adaptive" reports the batches, the
// worst errors reached, the rays traced and the rays of a fixed count with the same worst-case
// error (render::AdaptiveSummary, an estimate by the 1/sqrt(N) law). Deterministic per
// (seed, point id) like every bake, so shards merge bit for bit.
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <limits>
#include <memory>
#include <sphbasis/basis/registry.hpp>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/bake_file.hpp>
#include <sphbasis/render/bake_points.hpp>
#include <sphbasis/render/bake_record.hpp>
#include <sphbasis/render/high_to_low.hpp>
#include <sphbasis/render/lightmap.hpp>
#include <sphbasis/render/probe_grid.hpp>
#include <sphbasis/render/seams.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "../support/bake_cache.hpp"
#include "../support/engine_export.hpp"
#include "../support/exr.hpp"
#include "../support/json.hpp"
#include "../support/memory.hpp"
#include "../support/output_file.hpp"
#include "../support/ply.hpp"
#include "../support/progress.hpp"
#include "../support/scene_file.hpp"
#include "bake_gl.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

// The layout of a result record (struct Layout), recorded in each shard's header as
// "record_format", part of its input hash and checked by bake-merge. 2: irr_stderr and
// rad_stderr added. 3: bent_stderr added after bent. 4: the high-to-low normal and hit.
constexpr int kRecordFormat = 4;

// The tangent-space normal map of high-to-low bakes (render/high_to_low.hpp): a quantity of the
// command, not of render::Baker, so a flag of its own beside the library's in
// BakeSettings::quantities (baker_settings() takes it out before the Baker sees it).
constexpr render::Quantity kNormalMap = static_cast<render::Quantity>(1u << 30);
constexpr const char* kNormalMapName = "normal_map";

render::BakeSettings baker_settings(render::BakeSettings s) {
    s.quantities = s.quantities & ~kNormalMap;
    return s;
}

// The quantities the command bakes (names: render::quantity_name()).
constexpr render::Quantity kQuantities[] = {
    render::Quantity::ao,       render::Quantity::bent,       render::Quantity::visibility,
    render::Quantity::transfer, render::Quantity::irradiance, render::Quantity::radiance};

render::Quantity parse_quantities(const std::string& s) {
    render::Quantity q{};
    std::vector<std::string> names;
    for (render::Quantity b : kQuantities) names.push_back(render::quantity_name(b));
    std::stringstream in(s);
    std::string item;
    names.push_back(kNormalMapName);
    while (std::getline(in, item, ',')) {
        render::Quantity bit{};
        if (item == kNormalMapName || item == "normal-map") bit = kNormalMap;
        for (render::Quantity b : kQuantities)
            if (item == render::quantity_name(b)) bit = b;
        if (!any(bit)) {
            const std::string near = item.size() <= 64 ? closest_key(item, names) : "";
            throw UsageError("--quantities: unknown quantity '" + quote_input(item) + "'" +
                             (near.empty() ? std::string(" (expected ao, bent, visibility, "
                                                         "transfer, irradiance, radiance or "
                                                         "normal_map)")
                                           : " (did you mean '" + near + "'?)"));
        }
        q |= bit;
    }
    if (!any(q)) throw UsageError("--quantities: expected a list such as ao,bent");
    return q;
}

// ---------------------------------------------------------------------------------------------
// Targets and points

enum class TargetKind { vertices, texels, probes, points };

struct Target {
    TargetKind kind = TargetKind::vertices;
    int res = 0;  // texels
    std::string text() const {
        switch (kind) {
            case TargetKind::vertices:
                return "vertices";
            case TargetKind::texels:
                return "texels:" + std::to_string(res);
            case TargetKind::probes:
                return "probes";
            case TargetKind::points:
                return "points";
        }
        return "";
    }
};

Target parse_target(const std::string& s) {
    Target t;
    if (s == "vertices") return t;
    if (s == "probes") {
        t.kind = TargetKind::probes;
        return t;
    }
    if (s.rfind("texels:", 0) == 0) {
        long long r = 0;
        if (!parse_integer(s.substr(7), r) || r < 1 || r > 16384)
            throw UsageError("--target: expected texels:RES with 1 <= RES <= 16384, got '" +
                             quote_input(s) + "'");
        t.kind = TargetKind::texels;
        t.res = static_cast<int>(r);
        return t;
    }
    throw UsageError("--target: expected vertices, texels:RES or probes, got '" + quote_input(s) +
                     "'");
}

struct Shard {
    long long index = 0, count = 1;
};

Shard parse_shard(const std::string& s) {
    const std::size_t slash = s.find('/');
    Shard sh;
    if (slash == std::string::npos || !parse_integer(s.substr(0, slash), sh.index) ||
        !parse_integer(s.substr(slash + 1), sh.count) || sh.count < 1 || sh.count > 1000000 ||
        sh.index < 0 || sh.index >= sh.count)
        throw UsageError("--shard: expected I/N with 0 <= I < N <= 1000000, got '" + s + "'");
    return sh;
}

/// Everything baked, in id order, and how it maps back to meshes and images.
struct Work {
    Target target;
    std::vector<render::BakePoint> points;
    std::vector<std::size_t> mesh_begin;          // vertices, texels: per mesh, size meshes+1
    std::vector<render::LightmapLayout> layouts;  // texels
    std::vector<bool> surface;                    // points: has a normal
    std::vector<std::array<double, 3>> given_n;   // points: the normal as given
    // High to low (project_sources()): per point the source normal in the tangent frame and
    // whether the ray hit the source (x, y, z, hit); (0, 0, 1, 1) for meshes without a source.
    std::vector<std::array<double, 4>> h2l;
};

// Vertices, texels and probes: the library's bake points (render/bake_points.hpp: the id scheme,
// normals and tangents shared with `sphbasis render`).
Work vertex_work(const SceneFile& scene) {
    Work w;
    const render::SceneDesc desc = scene.scene_desc();
    for (std::size_t k = 0; k < desc.meshes.size(); ++k) {
        w.mesh_begin.push_back(w.points.size());
        const std::vector<render::BakePoint> p = render::vertex_points(desc.meshes, k);
        w.points.insert(w.points.end(), p.begin(), p.end());
    }
    w.mesh_begin.push_back(w.points.size());
    return w;
}

Work texel_work(const SceneFile& scene, int res) {
    Work w;
    const render::SceneDesc desc = scene.lightmap_desc();  // "lightmap_uv": set 0 or 1
    for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
        const SceneMesh& sm = scene.meshes[k];
        if (sm.lightmap_uvs().empty())
            throw std::runtime_error(scene.path + ": meshes[" + std::to_string(k) + "] ('" +
                                     sm.name +
                                     "'): a texel bake needs a UV set, and this mesh has none");
        w.mesh_begin.push_back(w.points.size());
        w.layouts.push_back(render::texel_layout(desc.meshes, k, res));
        for (const render::LightmapSample& s : w.layouts.back().samples)
            w.points.push_back(s.point);
    }
    w.mesh_begin.push_back(w.points.size());
    return w;
}

Work probe_work(const SceneFile& scene) {
    if (!scene.has_probes)
        throw std::runtime_error(scene.path +
                                 ": --target probes needs a \"probes\" grid in the "
                                 "scene (docs/scene-format.md)");
    Work w;
    w.points = render::probe_points(scene.probes);
    return w;
}

Work point_work(std::istream& in, const std::string& source) {
    Work w;
    std::string text;
    long lineno = 0;
    while (std::getline(in, text)) {
        ++lineno;
        const auto first = text.find_first_not_of(" \t\r");
        if (first == std::string::npos || text[first] == '#') continue;
        std::istringstream is(text);
        std::vector<std::string> tok;
        std::string t;
        while (is >> t) tok.push_back(t);
        const std::string where = source + " line " + std::to_string(lineno);
        if (tok.size() != 3 && tok.size() != 6)
            throw UsageError(where + ": expected 'x y z nx ny nz' or 'x y z'");
        std::vector<double> v;
        for (const auto& s : tok) v.push_back(to_real(s, where));
        render::BakePoint p;
        for (std::size_t k = 0; k < 3; ++k)
            if (!(std::fabs(v[k]) <= render::coordinate_limit))
                throw UsageError(where + ": expected coordinates in [-1e15, 1e15], got '" +
                                 quote_input(tok[k]) + "'");
        p.p = {v[0], v[1], v[2]};
        std::array<double, 3> n{0, 0, 0};
        if (tok.size() == 6) {
            n = {v[3], v[4], v[5]};
            // Scaled by its largest component: 1e-320 and 1e300 normals normalise as well.
            const double big = std::max({std::fabs(n[0]), std::fabs(n[1]), std::fabs(n[2])});
            if (!(big > 0)) throw UsageError(where + ": expected a non-zero normal");
            p.n = {n[0] / big, n[1] / big, n[2] / big};
        }
        p.id = w.points.size();
        w.points.push_back(p);
        w.surface.push_back(tok.size() == 6);
        w.given_n.push_back(n);
    }
    if (w.points.empty()) throw UsageError(source + ": no points");
    return w;
}

Work make_work(const SceneFile& scene, const Target& t, const std::string& points_path) {
    Work w;
    switch (t.kind) {
        case TargetKind::vertices:
            w = vertex_work(scene);
            break;
        case TargetKind::texels:
            w = texel_work(scene, t.res);
            break;
        case TargetKind::probes:
            w = probe_work(scene);
            break;
        case TargetKind::points:
            if (points_path == "-") {
                w = point_work(std::cin, "standard input");
            } else {
                std::ifstream f(points_path);
                if (!f) throw std::runtime_error("cannot open points file '" + points_path + "'");
                w = point_work(f, points_path);
            }
            break;
    }
    w.target = t;
    w.h2l.assign(w.points.size(), {0.0, 0.0, 1.0, 1.0});
    return w;
}

// ---------------------------------------------------------------------------------------------
// High to low (render/high_to_low.hpp; the scene's "source", "cage" and "max_ray_distance").

/// The meshes with a "source" (low-poly targets).
std::vector<std::size_t> high_to_low_targets(const SceneFile& scene) {
    std::vector<std::size_t> t;
    for (std::size_t k = 0; k < scene.meshes.size(); ++k)
        if (scene.meshes[k].bake_source >= 0) t.push_back(k);
    return t;
}

/// The projection of target mesh k to its source (its "source", "max_ray_distance" and "cage").
render::HighToLowSettings projection_of(const SceneFile& scene, std::size_t k) {
    const SceneMesh& m = scene.meshes[k];
    render::HighToLowSettings hs;
    hs.target = k;
    hs.source = static_cast<std::size_t>(m.bake_source);
    hs.max_ray_distance = m.max_ray_distance;
    hs.cage_positions = m.cage ? m.cage->data() : nullptr;
    return hs;
}

/// Moves the vertex and texel points of every target to its source (w.points, w.h2l); the
/// "project" pass of the plan (rays 0 and no pass when no mesh has a source).
render::Pass project_sources(const SceneFile& scene, Work& w) {
    render::Pass pass;
    pass.name = "project";
    const std::vector<std::size_t> targets = high_to_low_targets(scene);
    if (targets.empty() ||
        (w.target.kind != TargetKind::vertices && w.target.kind != TargetKind::texels))
        return pass;
    const render::SceneDesc desc = scene.scene_desc();
    std::size_t points = 0, hits = 0;
    for (std::size_t k : targets) {
        const SceneMesh& m = scene.meshes[k];
        const render::HighToLowSettings hs = projection_of(scene, k);
        render::SourceProjector proj(desc.meshes, hs);
        const std::vector<render::ProjectedPoint> pp =
            proj.project(w.target.kind == TargetKind::vertices
                             ? render::low_poly_vertex_points(desc.meshes, hs)
                             : render::low_poly_texel_points(desc.meshes, hs, w.layouts[k]));
        if (pp.size() != w.mesh_begin[k + 1] - w.mesh_begin[k])
            throw std::runtime_error("high to low: the projection of mesh '" + m.name + "' gave " +
                                     std::to_string(pp.size()) + " points for " +
                                     std::to_string(w.mesh_begin[k + 1] - w.mesh_begin[k]));
        for (std::size_t i = 0; i < pp.size(); ++i) {
            const render::ProjectedPoint& p = pp[i];
            w.points[w.mesh_begin[k] + i] = p.point;
            w.h2l[w.mesh_begin[k] + i] = {p.normal.x, p.normal.y, p.normal.z, p.hit ? 1.0 : 0.0};
            hits += p.hit ? 1 : 0;
        }
        points += pp.size();
        pass.rays += proj.rays();
        pass.seconds += proj.seconds();
    }
    pass.reason = "high to low: rays from " + std::to_string(points) + " points of " +
                  std::to_string(targets.size()) + " low-poly meshes to their sources, " +
                  std::to_string(hits) + " hit";
    return pass;
}

// ---------------------------------------------------------------------------------------------
// Results as fixed-size records of doubles: the one form that is printed, written, sharded and
// merged, so that every path gives the same bits.

// The layout of a record and the packing: render/bake_record.hpp (shared with the
// representations' fields).
using Layout = render::RecordLayout;

/// The channels written for the requested quantities: name and offset in the record.
struct Column {
    std::string name;
    std::size_t offset;
};

bool any_rgb_transfer(const Layout& L, const std::vector<double>& rec) {
    for (std::size_t k = L.tr_rgb; k < rec.size(); k += L.stride)
        if (rec[k] != 0) return true;
    return false;
}

std::vector<Column> columns(const render::BakeSettings& s, const Layout& L, bool rgb_transfer) {
    std::vector<Column> c;
    const render::Quantity q = s.quantities;
    auto list = [&](const std::string& prefix, std::size_t off, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) c.push_back({prefix + std::to_string(i), off + i});
    };
    if (has(q, render::Quantity::ao)) c.insert(c.end(), {{"ao", L.ao}, {"ao_stderr", L.ao + 1}});
    if (has(q, render::Quantity::bent))
        c.insert(c.end(), {{"bent_x", L.bent},
                           {"bent_y", L.bent + 1},
                           {"bent_z", L.bent + 2},
                           {"bent_stderr", L.bent_se}});
    if (has(q, render::Quantity::visibility)) {
        list("vis_", L.vis, L.b2);
        list("vis_stderr_", L.vis_se, L.b2);
    }
    if (has(q, render::Quantity::transfer)) {
        if (rgb_transfer) {
            list("transfer_r_", L.tr, L.b2);
            list("transfer_g_", L.tr + L.b2, L.b2);
            list("transfer_b_", L.tr + 2 * L.b2, L.b2);
        } else {
            list("transfer_", L.tr, L.b2);
        }
        list("transfer_stderr_", L.tr_se, L.b2);
    }
    if (has(q, render::Quantity::irradiance)) {
        list("irr_r_", L.irr, L.nc);
        list("irr_g_", L.irr + L.nc, L.nc);
        list("irr_b_", L.irr + 2 * L.nc, L.nc);
        list("irr_stderr_", L.irr_se, L.nc);
    }
    if (has(q, render::Quantity::radiance)) {
        list("rad_r_", L.rad, L.b2);
        list("rad_g_", L.rad + L.b2, L.b2);
        list("rad_b_", L.rad + 2 * L.b2, L.b2);
        list("rad_stderr_", L.rad_se, L.b2);
        c.push_back({"inside", L.inside});
    }
    if (has(q, kNormalMap))
        c.insert(c.end(), {{"normal_x", L.h2l}, {"normal_y", L.h2l + 1}, {"normal_z", L.h2l + 2}});
    return c;
}

// ---------------------------------------------------------------------------------------------
// Settings, plan and summary as JSON

/// bake.json's "irradiance": what the channels irr_r_k, irr_g_k, irr_b_k hold (value k of the
/// irradiance E(n') = int L max(n' . w, 0) dw over tangent-space normals n', physical units, in
/// the storage of render::irradiance_storage()) and how a shader evaluates them.
Json irradiance_json(const render::BakeSettings& s) {
    const render::IrradianceStorage r = render::irradiance_storage(s.basis, s.coeffs);
    using K = render::IrradianceStorage::Kind;
    Json j = {{"storage", s.basis}, {"values", s.coeffs}};
    if (r.kind == K::fitted) {
        j["channels"] = {"E_00", "E_1-1", "E_10", "E_11"};
        if (s.coeffs == 5) j["channels"].push_back("z");
        j["fit"] = std::string(r.fitted->name) +
                   ": the first SH coefficients of E (ACN, no Condon-Shortley phase)" +
                   (s.coeffs == 5 ? " and z, the zonal coefficient along their L1 axis" : "");
        j["evaluate"] = std::string("basis/registry.hpp find_fitted_basis(\"") + r.fitted->name +
                        "\")->eval_d(values, n')";
        return j;
    }
    j["channels"] = std::string("coefficient k of basis '") + r.basis->name + "' (" +
                    std::to_string(s.coeffs) + " functions), E(n') = sum_k c_k B_k(n')";
    j["fit"] = r.kind == K::sg_nnls ? "non-negative least squares on the fit rule"
               : r.kind == K::sg_running
                   ? "Roughton's running average (render::sg_running_directions)"
                   : "least squares on the fit rule";
    if (std::string(r.basis->name) == "sg") {
        Json axes = Json::array();
        for (const auto& a : sg::bakinglab_axes(s.coeffs)) axes.push_back({a[0], a[1], a[2]});
        j["lobes"] = {{"axes", axes}, {"sharpness", sg::bakinglab_sharpness(s.coeffs)}};
    }
    return j;
}

Json settings_json(const render::BakeSettings& s) {
    Json q = Json::array();
    for (render::Quantity b : kQuantities)
        if (has(s.quantities, b)) q.push_back(render::quantity_name(b));
    if (has(s.quantities, kNormalMap)) q.push_back(kNormalMapName);
    Json j = {{"quantities", q},    {"bands", s.bands},        {"basis", s.basis},
              {"coeffs", s.coeffs}, {"rays", s.rays},          {"bounces", s.bounces},
              {"seed", s.seed},     {"max_distance", nullptr}, {"target_error", s.target_error}};
    if (std::isfinite(s.max_distance)) j["max_distance"] = s.max_distance;
    if (s.adaptive.enabled()) {  // absent otherwise: fixed bakes hash as before
        Json t = Json::object();
        for (render::Quantity b : kQuantities)
            if (s.adaptive[b] > 0) t[render::quantity_name(b)] = s.adaptive[b];
        j["adaptive"] = {{"target_error", t}, {"max_rays", s.adaptive.max_rays}};
    }
    return j;
}

/// --target-error (spec; null when not given): one error for every requested quantity ("0.01")
/// or NAME:ERROR pairs ("ao:0.01,irradiance:0.02"); --max-rays (default 16 --rays).
void parse_adaptive(const std::string* given, long long max_rays, render::BakeSettings& s) {
    if (given == nullptr) {
        if (max_rays > 0) throw UsageError("--max-rays needs --target-error");
        return;
    }
    const std::string& spec = *given;
    if (spec.empty()) throw UsageError("--target-error: expected errors > 0, got ''");
    std::stringstream in(spec);
    std::string item;
    while (std::getline(in, item, ',')) {
        const std::size_t colon = item.find(':');
        const std::string name = colon == std::string::npos ? "" : item.substr(0, colon);
        const double x =
            to_real(item.substr(colon == std::string::npos ? 0 : colon + 1), "--target-error");
        if (!(x > 0) || !std::isfinite(x))
            throw UsageError("--target-error: expected errors > 0, got '" + quote_input(item) +
                             "'");
        const render::Quantity q = render::quantity_of_name(name);
        if (!name.empty() && !has(s.quantities, q))
            throw UsageError("--target-error: '" + quote_input(name) +
                             "' is not one of the --quantities (" +
                             render::quantity_names(s.quantities) + ")");
        for (render::Quantity b : kQuantities)
            if (name.empty() ? has(s.quantities, b) : b == q) s.adaptive[b] = x;
    }
    s.adaptive.max_rays = static_cast<int>(max_rays > 0 ? max_rays : 16LL * s.rays);
    if (s.adaptive.max_rays < s.rays)
        throw UsageError("--max-rays: expected at least --rays (" + std::to_string(s.rays) +
                         "), got " + std::to_string(s.adaptive.max_rays));
}

/// bake.json's "adaptive": the settings, what the points did, and the rays of a fixed count
/// with the same worst-case error (render::AdaptiveSummary; the raw sums let bake-merge join
/// the shards' summaries).
Json adaptive_json(const render::BakeSettings& s, const render::AdaptiveSummary& a) {
    Json worst = Json::object(), ne2 = Json::object();
    for (render::Quantity b : kQuantities)
        if (s.adaptive[b] > 0) {
            worst[render::quantity_name(b)] = a.worst[render::quantity_index(b)];
            ne2[render::quantity_name(b)] = a.worst_ne2[render::quantity_index(b)];
        }
    const double fixed = a.fixed_total(s);
    return {{"points", a.points},
            {"batches", a.batches},
            {"unconverged_points", a.unconverged},
            {"mean_rays_per_pass", a.points ? double(a.batches) * s.rays / double(a.points) : 0.0},
            {"worst_error", worst},
            {"worst_n_error2", ne2},
            {"rays_per_batch_sum", a.rays_per_batch},
            {"rays_traced", a.rays},
            {"fixed_rays_per_pass", a.fixed_rays(s)},
            {"fixed_rays_estimate", fixed},
            {"rays_saved", fixed - double(a.rays)},
            {"saved_fraction", fixed > 0 ? 1 - double(a.rays) / fixed : 0.0}};
}

render::AdaptiveSummary adaptive_summary_of(const Json& j) {
    render::AdaptiveSummary a;
    a.points = j.at("points").get<std::uint64_t>();
    a.batches = j.at("batches").get<std::uint64_t>();
    a.unconverged = j.at("unconverged_points").get<std::uint64_t>();
    a.rays = j.at("rays_traced").get<std::uint64_t>();
    a.rays_per_batch = j.at("rays_per_batch_sum").get<double>();
    for (const auto& [k, v] : j.at("worst_error").items())
        a.worst[render::quantity_index(render::quantity_of_name(k))] = v.get<double>();
    for (const auto& [k, v] : j.at("worst_n_error2").items())
        a.worst_ne2[render::quantity_index(render::quantity_of_name(k))] = v.get<double>();
    return a;
}

Json plan_json(const std::vector<render::Pass>& plan) {
    Json p = Json::array();
    for (const render::Pass& x : plan)
        p.push_back(
            {{"name", x.name}, {"reason", x.reason}, {"rays", x.rays}, {"seconds", x.seconds}});
    return p;
}

std::vector<render::Pass> plan_of(const Json& j) {
    std::vector<render::Pass> plan;
    for (const Json& x : j) {
        render::Pass p;
        p.name = x.at("name").get<std::string>();
        p.reason = x.at("reason").get<std::string>();
        p.rays = x.at("rays").get<std::uint64_t>();
        p.seconds = x.at("seconds").get<double>();
        plan.push_back(p);
    }
    return plan;
}

// ---------------------------------------------------------------------------------------------
// Output files

Json column_names(const std::vector<Column>& cols) {
    Json a = Json::array();
    for (const Column& c : cols) a.push_back(c.name);
    return a;
}

/// The data files a complete bake writes for `target` (before bake.json): one per mesh, or
/// probes.json.
std::vector<std::string> data_files(const SceneFile& scene, const Target& target) {
    std::vector<std::string> files;
    if (target.kind == TargetKind::vertices || target.kind == TargetKind::texels)
        for (const SceneMesh& m : scene.meshes)
            files.push_back(m.name + (target.kind == TargetKind::vertices ? ".ply" : ".exr"));
    else if (target.kind == TargetKind::probes)
        files.push_back("probes.json");
    return files;
}

/// Declares the data files of a complete bake in `out` (before the work: a name too long for
/// the file system or a directory in the way fails here).
void declare_outputs(OutputFiles& out, const std::string& out_dir, const SceneFile& scene,
                     const Target& target, const std::string& summary) {
    for (const std::string& f : data_files(scene, target)) out.declare_in(out_dir, f);
    out.declare_in(out_dir, summary);
}

/// Writes the data files of a complete bake (all points) into `out` (committed by the
/// caller); returns the "outputs" entry.
Json write_outputs(const SceneFile& scene, const Work& w, const render::BakeSettings& s,
                   const std::vector<double>& rec, const std::string& out_dir, OutputFiles& out) {
    const Layout L(s);
    const std::vector<Column> cols = columns(s, L, any_rgb_transfer(L, rec));
    Json outputs = Json::array();
    const std::size_t nc = cols.size();
    if (w.target.kind == TargetKind::vertices) {
        // High to low: whether each vertex's ray hit its source (1 on meshes without one).
        std::vector<Column> vcols = cols;
        if (!high_to_low_targets(scene).empty()) vcols.push_back({"coverage", L.h2l + 3});
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const render::Mesh& m = scene.meshes[k].mesh;
            const std::vector<double> nd = render::vertex_normals(m.view());
            const std::vector<float> n(nd.begin(), nd.end());
            std::vector<std::string> names = {"x", "y", "z", "nx", "ny", "nz"};
            for (const Column& c : vcols) names.push_back(c.name);
            std::vector<float> vals;
            vals.reserve(m.vertex_count() * names.size());
            for (std::size_t v = 0; v < m.vertex_count(); ++v) {
                vals.insert(vals.end(), m.positions.begin() + std::ptrdiff_t(3 * v),
                            m.positions.begin() + std::ptrdiff_t(3 * v + 3));
                vals.insert(vals.end(), n.begin() + std::ptrdiff_t(3 * v),
                            n.begin() + std::ptrdiff_t(3 * v + 3));
                const double* r = rec.data() + (w.mesh_begin[k] + v) * L.stride;
                for (const Column& c : vcols) vals.push_back(static_cast<float>(r[c.offset]));
            }
            const std::string file = scene.meshes[k].name + ".ply";
            out.add(join_path(out_dir, file),
                    ply_binary(names, vals, m.vertex_count(), m.indices,
                               {"sphbasis bake: " + scene.meshes[k].name}));
            outputs.push_back({{"file", file},
                               {"mesh", scene.meshes[k].name},
                               {"kind", "ply"},
                               {"vertices", m.vertex_count()},
                               {"channels", column_names(vcols)}});
        }
    } else if (w.target.kind == TargetKind::texels) {
        for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
            const render::LightmapLayout& lay = w.layouts[k];
            const std::size_t nch = nc + 1;  // + coverage, set after the dilation
            const std::size_t npx = std::size_t(lay.width) * std::size_t(lay.height);
            std::vector<float> img = render::assemble_lightmap(
                lay, static_cast<int>(nch), [&](std::size_t i, float* px) {
                    const double* r = rec.data() + (w.mesh_begin[k] + i) * L.stride;
                    for (std::size_t c = 0; c < nc; ++c)
                        px[c] = static_cast<float>(r[cols[c].offset]);
                });
            // Seamless charts (render/seams.hpp): the baked channels, not the coverage.
            const render::SeamStats seams = render::stitch_seams(
                img.data(), lay.width, lay.height, static_cast<int>(nch), static_cast<int>(nc),
                render::find_seams(scene.meshes[k].mesh.view()));
            for (std::size_t p = 0; p < npx; ++p) img[p * nch + nc] = lay.covered[p] ? 1.0f : 0.0f;
            // High to low: texels whose ray missed the source are not covered.
            for (std::size_t i = 0; i < lay.samples.size(); ++i)
                if (rec[(w.mesh_begin[k] + i) * L.stride + L.h2l + 3] == 0)
                    img[(std::size_t(lay.samples[i].y) * std::size_t(lay.width) +
                         std::size_t(lay.samples[i].x)) *
                            nch +
                        nc] = 0.0f;
            std::vector<std::string> names;
            for (const Column& c : cols) names.push_back(c.name);
            names.push_back("coverage");
            const std::string file = scene.meshes[k].name + ".exr";
            out.add(join_path(out_dir, file), encode_exr(lay.width, lay.height, names, img));
            Json cn = column_names(cols);
            cn.push_back("coverage");
            outputs.push_back({{"file", file},
                               {"mesh", scene.meshes[k].name},
                               {"kind", "exr"},
                               {"width", lay.width},
                               {"height", lay.height},
                               {"texels_baked", lay.samples.size()},
                               {"skipped_triangles", lay.skipped_triangles},
                               {"gutter", render::lightmap_gutter},
                               {"seams",
                                {{"edges", seams.edges},
                                 {"texels", seams.texels},
                                 {"max_jump_before", seams.max_jump_before},
                                 {"max_jump_after", seams.max_jump_after}}},
                               {"channels", cn}});
        }
    } else if (w.target.kind == TargetKind::probes) {
        const render::ProbeGrid& g = scene.probes;
        Json probes = Json::array();
        std::size_t inside = 0;
        for (std::size_t i = 0; i < w.points.size(); ++i) {
            const double* r = rec.data() + i * L.stride;
            Json vals = Json::array();
            for (const Column& c : cols)
                if (c.name != "inside") vals.push_back(r[c.offset]);
            const bool in = r[L.inside] != 0;
            inside += in ? 1 : 0;
            const vec3<double>& p = w.points[i].p;
            probes.push_back({{"index", w.points[i].id},
                              {"p", {p.x, p.y, p.z}},
                              {"inside", in},
                              {"values", vals}});
        }
        Json names = Json::array();
        for (const Column& c : cols)
            if (c.name != "inside") names.push_back(c.name);
        Json doc = {{"grid",
                     {{"min", {g.lo.x, g.lo.y, g.lo.z}},
                      {"max", {g.hi.x, g.hi.y, g.hi.z}},
                      {"counts", {g.counts[0], g.counts[1], g.counts[2]}}}},
                    {"channels", names},
                    {"inside", inside},
                    {"probes", probes}};
        out.add(join_path(out_dir, "probes.json"), dump_json(doc, {{"probes", 0}}) + "\n");
        outputs.push_back({{"file", "probes.json"},
                           {"kind", "json"},
                           {"probes", w.points.size()},
                           {"inside", inside},
                           {"channels", names}});
    }
    return outputs;
}

/// What support/engine_export.hpp reads of a complete bake (`--format gltf`); rec may be null
/// before the bake (the file names only).
EngineInput engine_input(const SceneFile& scene, const Work& w, const render::BakeSettings& s,
                         const std::vector<double>* rec, ImageEncoding encoding,
                         const CompressionExport& compression) {
    const Layout L(s);
    EngineInput in;
    in.target = w.target.kind == TargetKind::texels   ? EngineTarget::texels
                : w.target.kind == TargetKind::probes ? EngineTarget::probes
                                                      : EngineTarget::vertices;
    in.meshes = &scene.meshes;
    in.probes = &scene.probes;
    in.mesh_begin = &w.mesh_begin;
    in.layouts = &w.layouts;
    for (const Column& c : columns(s, L, rec != nullptr && any_rgb_transfer(L, *rec)))
        in.columns.emplace_back(c.name, c.offset);
    in.records = rec;
    in.stride = L.stride;
    in.basis = s.basis;
    in.encoding = encoding;
    in.compression = compression;
    in.seed = s.seed + 1;  // k-means++ seeding: any fixed stream of the bake's seed
    if (compression.lxh_visibility_bands > 0 && rec != nullptr)
        in.lighting = distant_lighting_sh(scene, compression.lxh_lighting_bands);
    return in;
}

/// The engine files of `in` (and bake.json) declared in `out` before the bake.
void declare_engine_files(OutputFiles& out, const std::string& dir, const EngineInput& in) {
    for (const std::string& f : engine_file_names(in)) out.declare_in(dir, f);
    out.declare_in(dir, "bake.json");
}

/// The engine files of a complete bake added to `out`, listed in summary["outputs"].
void add_engine_files(OutputFiles& out, const std::string& dir, const EngineInput& in,
                      Json& summary) {
    summary["outputs"] = Json::array();
    for (EngineFile& f : export_engine(in, summary["outputs"]))
        out.add(join_path(dir, f.name), f.bytes);
}

void print_points(const Work& w, const render::BakeSettings& s, const std::vector<double>& rec,
                  std::size_t begin) {
    const Layout L(s);
    const render::Quantity q = s.quantities;
    auto list = [&](const double* p, std::size_t n) {
        Json a = Json::array();
        for (std::size_t i = 0; i < n; ++i) a.push_back(p[i]);
        return a;
    };
    auto rgb = [&](const double* p, std::size_t n) {
        return Json::array({list(p, n), list(p + n, n), list(p + 2 * n, n)});
    };
    for (std::size_t k = 0; k * L.stride < rec.size(); ++k) {
        const std::size_t i = begin + k;
        const double* r = rec.data() + k * L.stride;
        const vec3<double>& p = w.points[i].p;
        Json line = {{"p", {p.x, p.y, p.z}}};
        if (w.surface[i]) line["n"] = {w.given_n[i][0], w.given_n[i][1], w.given_n[i][2]};
        if (has(q, render::Quantity::ao)) {
            line["ao"] = r[L.ao];
            line["ao_stderr"] = r[L.ao + 1];
        }
        if (has(q, render::Quantity::bent)) {
            line["bent"] = list(r + L.bent, 3);
            line["bent_stderr"] = r[L.bent_se];
        }
        if (has(q, render::Quantity::visibility)) {
            line["visibility"] = list(r + L.vis, L.b2);
            line["visibility_stderr"] = list(r + L.vis_se, L.b2);
        }
        if (has(q, render::Quantity::transfer)) {
            line["transfer"] = r[L.tr_rgb] != 0 ? rgb(r + L.tr, L.b2) : list(r + L.tr, L.b2);
            line["transfer_stderr"] = list(r + L.tr_se, L.b2);
        }
        if (has(q, render::Quantity::irradiance)) {
            line["irradiance"] = rgb(r + L.irr, L.nc);
            line["irradiance_stderr"] = list(r + L.irr_se, L.nc);
        }
        if (has(q, render::Quantity::radiance)) {
            line["radiance"] = rgb(r + L.rad, L.b2);
            line["radiance_stderr"] = list(r + L.rad_se, L.b2);
            line["inside"] = r[L.inside] != 0;
        }
        std::cout << dump_json(line) << '\n';
    }
    std::cout.flush();
}

// ---------------------------------------------------------------------------------------------
// Shard files: render/bake_file.hpp's format (docs/bake-format.md), kind shard. Payload: the
// JSON header (string), u64 stride, the records (u64 count of doubles, then the doubles). Input
// hash: shard_input_hash().

/// What a shard's records depend on: the scene's files (input_hash(SceneFile)), the target,
/// the settings and the record layout.
std::uint64_t shard_input_hash(std::uint64_t scene_hash, const std::string& target,
                               const Json& settings) {
    return render::InputHash()
        .u64(scene_hash)
        .str(target)
        .str(settings.dump())
        .u64(kRecordFormat)
        .value();
}

std::vector<std::uint8_t> shard_bytes(std::uint64_t input_hash, const Json& header,
                                      const std::vector<double>& rec, std::size_t stride) {
    render::ByteWriter w;
    w.str(header.dump());
    w.u64(stride);
    w.f64s(rec);
    return render::write_bake_file(render::BakeFileKind::shard, input_hash, w.bytes());
}

struct ShardData {
    Json header;
    std::uint64_t input_hash = 0;
    std::vector<double> rec;
    std::uint64_t stride = 0;  // doubles per record
};

/// Reads every field of a shard header that bake-merge uses, with its type, so that a header
/// edited or cut short is one message naming the file (not nlohmann's exception text later).
void check_shard_header(const Json& h, const std::string& file) {
    try {
        const Json& sh = h.at("shard");
        (void)sh.at("count").get<long long>();
        (void)sh.at("index").get<std::size_t>();
        (void)sh.at("begin").get<std::size_t>();
        (void)sh.at("end").get<std::size_t>();
        if (sh.at("end").get<std::size_t>() < sh.at("begin").get<std::size_t>())
            throw std::runtime_error(file + ": corrupt shard header (end before begin)");
        (void)h.at("scene").get<std::string>();
        (void)h.at("scene_file").get<std::string>();
        (void)h.at("target").get<std::string>();
        (void)h.at("points").get<std::size_t>();
        (void)h.at("rays").get<std::uint64_t>();
        (void)h.at("seconds").at("bake").get<double>();
        (void)plan_of(h.at("plan"));
        const Json& js = h.at("settings");
        for (const Json& q : js.at("quantities")) (void)q.get<std::string>();
        for (const char* k : {"bands", "coeffs", "rays", "bounces"}) (void)js.at(k).get<int>();
        (void)js.at("basis").get<std::string>();
        (void)js.at("seed").get<std::uint64_t>();
        if (!js.at("max_distance").is_null()) (void)js.at("max_distance").get<double>();
        (void)js.at("target_error").get<double>();
    } catch (const nlohmann::json::exception& e) {
        std::string why = e.what();  // "[json.exception.type_error.302] type must be ..."
        const std::size_t p = why.find("] ");
        if (p != std::string::npos) why = why.substr(p + 2);
        if (why.size() > 100) why = why.substr(0, 100) + "...";
        throw std::runtime_error(file + ": corrupt shard header (" + why + ")");
    }
}

ShardData read_shard(const std::string& file) {
    struct stat st {};
    if (::stat(file.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
        throw std::runtime_error(file + ": not a regular file; expected a shard file");
    std::ifstream f(file, std::ios::binary);
    if (!f) throw std::runtime_error("cannot open shard file '" + file + "'");
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(f)),
                                          std::istreambuf_iterator<char>());
    if (f.bad()) throw std::runtime_error("cannot read shard file '" + file + "'");
    ShardData d;
    std::string text;
    try {
        const render::BakeFileView v = render::read_bake_file(bytes, render::BakeFileKind::shard);
        d.input_hash = v.input_hash;
        render::ByteReader r(v.payload, v.payload_size, "bake-merge");
        text = r.str();
        d.stride = r.u64();
        d.rec = r.f64s();
        r.finish();
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(file + ": not a shard file of this sphbasis bake (" + e.what() +
                                 ")");
    }
    try {
        d.header = Json::parse(text);
    } catch (const std::exception&) {
        throw std::runtime_error(file + ": corrupt shard header");
    }
    if (!d.header.is_object()) throw std::runtime_error(file + ": corrupt shard header");
    const int format =
        d.header.contains("record_format") && d.header["record_format"].is_number_integer()
            ? d.header["record_format"].get<int>()
            : 1;
    if (format != kRecordFormat)
        throw std::runtime_error(file + ": a shard of record format " + std::to_string(format) +
                                 ", this sphbasis reads format " + std::to_string(kRecordFormat) +
                                 ": bake the shards again with this version");
    check_shard_header(d.header, file);
    if (d.stride == 0 || d.rec.size() % d.stride != 0)
        throw std::runtime_error(file + ": corrupt shard (" + std::to_string(d.rec.size()) +
                                 " numbers in records of " + std::to_string(d.stride) + ")");
    return d;
}

// ---------------------------------------------------------------------------------------------
// Reuse by `sphbasis render` (docs/bake-format.md): a complete bake of vertices, texels or probes
// also stores its results as the bake-cache entries render reads, OUT/cache/<key>.bin (one per
// mesh with triangles; probes: one), each under render::bake_key() of the request render makes
// for the same settings, so `sphbasis render --out OUT` or `--bake OUT` loads them instead of
// baking. The key covers adaptive sampling and high-to-low projections (render bakes neither), so
// such a bake's entries are never taken for render's. The entries are whole files
// (support/bake_cache.hpp), written before the outputs are committed; like render's cache they are
// kept whatever happens after.

/// Stores the parts of a complete bake (results of every point, in id order) in OUT/cache and
/// returns bake.json's "render_cache" entry. Times and rays are shared out by point count.
Json store_for_render(const SceneFile& scene, const Work& w, const render::BakeSettings& s,
                      const std::vector<render::PointResult>& results,
                      const std::vector<render::Pass>& plan, double seconds, std::uint64_t rays,
                      const std::string& out_dir) {
    DiskBakeCache cache(join_path(out_dir, "cache"));
    // Keyed on the whole scene, as render keys its bakes (a high-to-low bake traced without its
    // targets: high_to_low says so).
    const render::SceneDesc desc = scene.scene_desc();
    std::vector<render::HighToLowSettings> projections;
    for (std::size_t k : high_to_low_targets(scene)) projections.push_back(projection_of(scene, k));
    const std::uint64_t high_to_low = render::high_to_low_key(desc, projections);
    Json entries = Json::array();
    const bool probes = w.target.kind == TargetKind::probes;
    const std::size_t parts = probes ? 1 : desc.meshes.size();
    for (std::size_t k = 0; k < parts; ++k) {
        if (!probes && desc.meshes[k].triangle_count == 0) continue;  // render bakes none
        render::BakeData d;
        d.request.mesh = probes ? 0 : k;
        d.request.settings = s;
        d.request.lighting_dependent = render::depends_on_lighting(s.quantities);
        d.request.high_to_low = high_to_low;
        if (probes) {
            d.request.where = render::BakeRequest::Where::probes;
            d.request.probes = scene.probes;
        } else if (w.target.kind == TargetKind::texels) {
            d.request.where = render::BakeRequest::Where::texel;
            d.request.lightmap_size = w.target.res;
            d.layout = w.layouts[k];
        }
        const std::size_t b = probes ? 0 : w.mesh_begin[k];
        const std::size_t e = probes ? results.size() : w.mesh_begin[k + 1];
        d.results.assign(results.begin() + std::ptrdiff_t(b), results.begin() + std::ptrdiff_t(e));
        const double share = results.empty() ? 0.0 : double(e - b) / double(results.size());
        d.plan = plan;
        d.seconds = seconds * share;
        d.rays = static_cast<std::uint64_t>(double(rays) * share);
        const std::uint64_t key = render::bake_key(desc, d.request);
        cache.store(key, d);
        Json entry = {{"file", "cache/" + hex_key(key) + ".bin"}, {"key", hex_key(key)}};
        if (!probes) entry["mesh"] = scene.meshes[k].name;
        entries.push_back(entry);
    }
    return entries;
}

// ---------------------------------------------------------------------------------------------

/// --encoding and --export (bake and bake-merge) shape only --format gltf's files: given (even
/// as the default) without it, they are refused.
void check_gltf_options(bool gltf, const CLI::Option* encoding, const CLI::Option* exports) {
    if (gltf) return;
    if (encoding->count() > 0) throw UsageError("--encoding: needs --format gltf");
    if (exports->count() > 0) throw UsageError("--export: needs --format gltf");
}

struct BakeOptions {
    std::string scene, quantities = "ao", basis = "sh", target = "vertices", points, out = ".",
                       shard, max_distance, format = "native", encoding = "png8", exports,
                       target_error, sg_solver = "ls";
    bool no_cache = false;
    long long bands = 3, coeffs = 9, rays = 256, bounces = 0, seed = 0, max_rays = 0;
    // Whether an option was given is its count, never its value against the default (an
    // explicit default is a request too, refused where it would be ignored).
    CLI::Option *target_opt = nullptr, *points_opt = nullptr, *out_opt = nullptr,
                *maxd_opt = nullptr, *coeffs_opt = nullptr, *rays_opt = nullptr,
                *sg_solver_opt = nullptr, *encoding_opt = nullptr, *export_opt = nullptr,
                *shard_opt = nullptr, *target_error_opt = nullptr;
    GlEngine gl;  // --engine gl (bake_gl.hpp)
};

/// --basis, --coeffs and --sg-solver as render::BakeSettings::basis and coeffs: "sgN" is "sg"
/// with N lobes; a basis or representation of one size (ambient-dice, zh3, zh3-hallucinate,
/// sh-l1-nonlinear) and the hemispherical sizes of the ambient cube (5) and of Ambient Dice over
/// the faces (ambient-dice-bezier 30, ambient-dice-linear 10: the irradiance is fitted over the
/// tangent hemisphere) take their size without --coeffs; --sg-solver nnls|running stores
/// "sg-nnls" / "sg-running". ambient-dice-ycocg (30 luma values, 10 for each chroma channel)
/// is refused: a bake stores one count for every channel.
std::pair<std::string, int> irradiance_basis_of(const BakeOptions& o) {
    std::string name = o.basis;
    int coeffs = static_cast<int>(o.coeffs);
    const bool given = o.coeffs_opt != nullptr && o.coeffs_opt->count() > 0;
    auto fixed = [&](int n) {
        if (given && coeffs != n)
            throw UsageError("--coeffs: '" + quote_input(o.basis) + "' stores " +
                             std::to_string(n) + " values, got " + std::to_string(coeffs));
        coeffs = n;
    };
    for (int n : {5, 6, 9, 12})
        if (name == "sg" + std::to_string(n)) {
            name = "sg";
            fixed(n);
        }
    if (name == "ambient-dice-ycocg")
        throw UsageError(
            "--basis: ambient-dice-ycocg stores 30 luma and 10 + 10 chroma values, but a bake "
            "stores the same count for R, G and B; bake ambient-dice-bezier and "
            "ambient-dice-linear (render's lightmap-ambient-dice-ycocg reads both)");
    if (!given) {
        if (name == "ambient-cube") coeffs = 5;
        if (name == "ambient-dice") coeffs = 12;
        if (name == "ambient-dice-bezier") coeffs = 30;
        if (name == "ambient-dice-linear") coeffs = 10;
    }
    // Irradiance is fitted over the tangent hemisphere, where 2 of the 12 vertices of the
    // full-sphere sizes have no support (a singular fit).
    const int full = name == "ambient-dice-bezier" ? 36 : (name == "ambient-dice-linear" ? 12 : 0);
    if (full > 0 && coeffs == full)
        throw UsageError("--coeffs: '" + name + "' stores " + std::to_string(full / 6 * 5) +
                         " values on the tangent hemisphere (" + std::to_string(full) +
                         " is the whole sphere's), got " + std::to_string(full));
    if (const FittedBasisInfo* f = find_fitted_basis(name)) fixed(f->stored);
    if (o.sg_solver_opt->count() > 0) {
        if (o.sg_solver != "ls" && o.sg_solver != "nnls" && o.sg_solver != "running")
            throw UsageError("--sg-solver: expected ls, nnls or running, got '" +
                             quote_input(o.sg_solver) + "'");
        if (name != "sg")
            throw UsageError("--sg-solver: only for --basis sg5|sg6|sg9|sg12 (or sg), got '" +
                             quote_input(o.basis) + "'");
        if (o.sg_solver != "ls") name = "sg-" + o.sg_solver;
    }
    return {name, coeffs};
}

/// Estimated bytes per baked point: its layout (BakePoint), its result (Baker::result_bytes),
/// the packed record (doubles) and the output's copy of it (floats in PLY/EXR, text in JSON).
double bytes_per_point(const render::BakeSettings& s) {
    const double result = double(render::Baker::result_bytes(s));
    return double(sizeof(render::BakePoint)) + 2 * result + 64;
}

render::BakeSettings settings_of(const BakeOptions& o) {
    render::BakeSettings s;
    s.quantities = parse_quantities(o.quantities);
    s.bands = static_cast<int>(o.bands);
    std::tie(s.basis, s.coeffs) = irradiance_basis_of(o);
    if (find_fitted_basis(s.basis) == nullptr) {  // a fitted one's count is checked above
        const BasisInfo* b = nullptr;
        try {
            b = &find_basis(s.basis == "sg-nnls" || s.basis == "sg-running" ? "sg" : s.basis);
        } catch (const std::invalid_argument& e) {
            throw UsageError(std::string("--basis: ") + e.what());
        }
        if (!b->valid_count(s.coeffs))
            throw UsageError(std::string("--coeffs: basis '") + b->name + "' expects " +
                             b->count_rule() + " functions, got " + std::to_string(s.coeffs));
    }
    s.rays = static_cast<int>(o.rays);
    s.bounces = static_cast<int>(o.bounces);
    s.seed = static_cast<std::uint64_t>(o.seed);
    if (o.maxd_opt->count() > 0) {
        s.max_distance = to_real(o.max_distance, "--max-distance");
        if (!(s.max_distance > 0)) throw UsageError("--max-distance: expected a positive distance");
    }
    parse_adaptive(o.target_error_opt->count() > 0 ? &o.target_error : nullptr, o.max_rays, s);
    return s;
}

void report_rate(std::size_t points, std::uint64_t rays, double secs) {
    std::fprintf(stderr, "sphbasis bake: %zu points, %llu rays in %.3f s: %.3g rays/s\n", points,
                 static_cast<unsigned long long>(rays), secs,
                 secs > 0 ? static_cast<double>(rays) / secs : 0.0);
}

int run_bake(const BakeOptions& o) {
    const auto t_start = Clock::now();
    const render::BakeSettings s = settings_of(o);
    Target target = parse_target(o.target);
    const bool points_mode = o.points_opt->count() > 0;
    if (points_mode && o.target_opt->count() > 0)
        throw UsageError("give either --target or --points, not both");
    if (points_mode) target.kind = TargetKind::points;
    // Probes are free points (no surface, no normal): only radiance is defined there.
    if (target.kind == TargetKind::probes && any(s.quantities & ~render::Quantity::radiance))
        throw UsageError(
            "--target probes: probes bake only radiance (they have no surface "
            "normal for ao, bent, visibility, transfer or irradiance); give "
            "--quantities radiance");
    if (has(s.quantities, kNormalMap) && target.kind != TargetKind::vertices &&
        target.kind != TargetKind::texels)
        throw UsageError(
            "--quantities normal_map: the tangent-space normal map is baked per vertex or texel "
            "(--target vertices or texels:RES) of meshes with a \"source\"");
    const Shard shard = o.shard_opt->count() > 0 ? parse_shard(o.shard) : Shard{};
    const bool write_files = !points_mode || o.out_opt->count() > 0;
    const bool gltf = o.format == "gltf";
    const ImageEncoding encoding = parse_image_encoding(o.encoding);
    const CompressionExport compression = parse_compression_export(o.exports);
    if (o.format != "native" && !gltf)
        throw UsageError("--format: expected native or gltf, got '" + quote_input(o.format) + "'");
    check_gltf_options(gltf, o.encoding_opt, o.export_opt);
    if (gltf && (points_mode || shard.count > 1))
        throw UsageError(
            "--format gltf: not with --points or --shard (give --format gltf to bake-merge)");

    const SceneFile scene = load_scene(o.scene);
    check_gl_engine(o.gl, s,
                    {shard.count > 1, o.maxd_opt->count() > 0, !high_to_low_targets(scene).empty(),
                     o.rays_opt->count() > 0});
    for (std::size_t k = 0; k < scene.meshes.size(); ++k)
        if (scene.meshes[k].dropped_triangles > 0)
            std::fprintf(
                stderr, "sphbasis bake: %s: meshes[%zu] ('%s'): %zu degenerate triangles dropped\n",
                scene.path.c_str(), k, scene.meshes[k].name.c_str(),
                scene.meshes[k].dropped_triangles);
    // What a shard's records depend on, hashed from the files as loaded (bake-merge recomputes it).
    const bool sharded = shard.count > 1 && !points_mode && write_files;
    const std::uint64_t scene_hash = sharded ? input_hash(scene) : 0;
    const double t_load = seconds_since(t_start);

    // The points' memory, estimated before the layout allocates it.
    double points = 0, geometry = 0;
    for (const SceneMesh& m : scene.meshes) {
        points += target.kind == TargetKind::texels ? double(target.res) * double(target.res)
                                                    : double(m.mesh.vertex_count());
        geometry += double(m.mesh.vertex_count()) * mesh_bytes_per_vertex +
                    double(m.mesh.triangle_count()) * mesh_bytes_per_triangle;
    }
    if (target.kind == TargetKind::probes) points = double(scene.probes.size());
    if (target.kind != TargetKind::points)
        check_memory(o.scene + ": ", geometry + points * bytes_per_point(s),
                     "baking " + std::to_string(static_cast<long long>(points)) + " " +
                         (target.kind == TargetKind::texels   ? "texels"
                          : target.kind == TargetKind::probes ? "probes"
                                                              : "vertices") +
                         " at " + format_bytes(bytes_per_point(s)) + " each");

    const auto t_layout0 = Clock::now();
    Work w = make_work(scene, target, o.points);
    const render::Pass projection = project_sources(scene, w);
    const double t_layout = seconds_since(t_layout0);
    if (points_mode && any(s.quantities & ~render::Quantity::radiance))
        for (std::size_t i = 0; i < w.points.size(); ++i)
            if (!w.surface[i])
                throw UsageError((o.points == "-" ? std::string("standard input") : o.points) +
                                 ": point " + std::to_string(i + 1) +
                                 " is 'x y z' (no normal): ao, bent, visibility, transfer and "
                                 "irradiance need 'x y z nx ny nz'; free points bake radiance");
    // The outputs, checked before the bake; OUT and the staging are created once the baker
    // accepted the settings (out.prepare() below).
    OutputFiles out(write_files ? o.out : std::string());
    const std::string shard_file =
        "bake.shard-" + std::to_string(shard.index) + "-of-" + std::to_string(shard.count) + ".bin";
    if (write_files) {
        if (sharded) {
            out.declare_in(o.out, shard_file);
        } else if (gltf) {
            declare_engine_files(out, o.out,
                                 engine_input(scene, w, s, nullptr, encoding, compression));
        } else {
            declare_outputs(out, o.out, scene, w.target,
                            points_mode ? "bake-points.json" : "bake.json");
        }
    }
    const std::size_t total = w.points.size();
    // total < 2^43 points and count <= 10^6 keep the products below 2^63.
    const std::size_t begin = static_cast<std::size_t>(
        std::uint64_t(total) * std::uint64_t(shard.index) / std::uint64_t(shard.count));
    const std::size_t end = static_cast<std::size_t>(
        std::uint64_t(total) * std::uint64_t(shard.index + 1) / std::uint64_t(shard.count));
    const std::vector<render::BakePoint> mine(w.points.begin() + std::ptrdiff_t(begin),
                                              w.points.begin() + std::ptrdiff_t(end));

    // Low-poly meshes with a source never occlude (render/high_to_low.hpp).
    const render::SceneDesc desc =
        render::high_to_low_occluders(scene.scene_desc(), high_to_low_targets(scene));
    const auto t_bake0 = Clock::now();
    // Without a quantity of the Baker (normal_map alone) nothing is traced beyond projection.
    std::unique_ptr<render::Baker> baker;
    if (any(baker_settings(s).quantities) && !o.gl.gl())
        baker = std::make_unique<render::Baker>(desc, baker_settings(s));
    if (write_files) out.prepare();
    std::vector<render::PointResult> results(baker ? 0 : mine.size());
    if (baker) {
        Progress bar("bake", static_cast<long long>(mine.size()));
        results =
            baker->bake(mine, [&bar](std::size_t k) { bar.update(static_cast<long long>(k)); });
        bar.done();
    }
    Json gl_record;
    render::Pass gl_pass;
    if (o.gl.gl()) results = gl_engine_bake(o.gl, desc, mine, s, gl_record, gl_pass);
    const double t_bake = seconds_since(t_bake0);
    if (results.size() != mine.size())
        throw std::runtime_error("the baker returned " + std::to_string(results.size()) +
                                 " results for " + std::to_string(mine.size()) + " points");
    const Layout L(s);
    std::vector<double> rec = render::pack_records(L, results);
    for (std::size_t k = 0; k < mine.size(); ++k)
        std::copy(w.h2l[begin + k].begin(), w.h2l[begin + k].end(),
                  rec.begin() + std::ptrdiff_t(k * L.stride + L.h2l));
    // The scene's limits (docs/scene-format.md) keep every result finite; should one not be,
    // no file is written with it (a PLY or EXR of inf or NaN at exit 0 would pass for a bake).
    for (std::size_t i = 0; i < rec.size(); ++i)
        if (!std::isfinite(rec[i]))
            throw std::runtime_error(o.scene + ": the bake gave a non-finite value at point " +
                                     std::to_string(begin + i / L.stride) + " (value " +
                                     std::to_string(i % L.stride) +
                                     " of its record); nothing was written");
    std::vector<render::Pass> plan = baker ? baker->plan() : std::vector<render::Pass>{};
    if (projection.rays > 0) plan.insert(plan.begin(), projection);
    if (o.gl.gl()) plan.push_back(gl_pass);
    const std::uint64_t rays = (baker ? baker->rays_traced() : 0) + projection.rays;

    Json summary = {{"tool", "sphbasis bake"},
                    {"scene", scene.path},
                    {"target", w.target.text()},
                    {"points", total},
                    {"seed", s.seed},
                    {"settings", settings_json(s)},
                    {"plan", plan_json(plan)},
                    {"rays", rays},
                    {"rays_per_second", t_bake > 0 ? static_cast<double>(rays) / t_bake : 0.0}};
    if (o.gl.gl()) summary["engine"] = gl_record;
    if (has(s.quantities, render::Quantity::irradiance)) summary["irradiance"] = irradiance_json(s);
    if (shard.count > 1)
        summary["shard"] = {
            {"index", shard.index}, {"count", shard.count}, {"begin", begin}, {"end", end}};
    if (s.adaptive.enabled()) {
        render::AdaptiveSummary a;
        for (const render::PointResult& r : results) a.add(s, r);
        summary["adaptive"] = adaptive_json(s, a);
    }

    if (points_mode) print_points(w, s, rec, begin);
    const auto t_write0 = Clock::now();
    if (write_files) {
        if (sharded) {
            std::error_code ec;
            Json header = summary;
            header["scene_file"] = std::filesystem::absolute(scene.path, ec).string();
            header["record_format"] = kRecordFormat;
            header["seconds"] = {{"load", t_load}, {"layout", t_layout}, {"bake", t_bake}};
            const std::vector<std::uint8_t> bytes =
                shard_bytes(shard_input_hash(scene_hash, w.target.text(), settings_json(s)), header,
                            rec, L.stride);
            out.add(join_path(o.out, shard_file), std::string(bytes.begin(), bytes.end()));
        } else {
            if (gltf) {
                add_engine_files(out, o.out, engine_input(scene, w, s, &rec, encoding, compression),
                                 summary);
            } else if (!points_mode) {
                summary["outputs"] = write_outputs(scene, w, s, rec, o.out, out);
            }
            // Texels on a second UV set are not the render's (it bakes texels on set 0) and the
            // key does not say which set: nothing to reuse. Adaptive and high-to-low bakes are
            // stored under keys of their own (store_for_render()).
            const bool uv1 = w.target.kind == TargetKind::texels &&
                             std::any_of(scene.meshes.begin(), scene.meshes.end(),
                                         [](const SceneMesh& m) { return m.lightmap_uv == 1; });
            if (!points_mode && !o.no_cache && baker && !uv1)
                summary["render_cache"] = store_for_render(scene, w, baker_settings(s), results,
                                                           plan, t_bake, rays, o.out);
            summary["seconds"] = {{"load", t_load},
                                  {"layout", t_layout},
                                  {"bake", t_bake},
                                  {"write", seconds_since(t_write0)},
                                  {"total", seconds_since(t_start)}};
            out.add(join_path(o.out, points_mode ? "bake-points.json" : "bake.json"),
                    dump_json(summary, {{"plan", 2}, {"outputs", 2}, {"render_cache", 2}}) + "\n");
        }
        out.commit();
    }
    report_rate(mine.size(), rays, t_bake);
    return 0;
}

struct MergeOptions {
    std::vector<std::string> shards;
    std::string out = ".", format = "native", encoding = "png8", exports;
    CLI::Option *encoding_opt = nullptr, *export_opt = nullptr;
};

int run_merge(const MergeOptions& o) {
    const auto t0 = Clock::now();
    const bool gltf = o.format == "gltf";
    if (o.format != "native" && !gltf)
        throw UsageError("--format: expected native or gltf, got '" + quote_input(o.format) + "'");
    const ImageEncoding encoding = parse_image_encoding(o.encoding);
    const CompressionExport compression = parse_compression_export(o.exports);
    check_gltf_options(gltf, o.encoding_opt, o.export_opt);
    std::vector<ShardData> parts;
    for (const std::string& f : o.shards) parts.push_back(read_shard(f));
    const Json& h0 = parts.front().header;
    const long long count = h0.at("shard").at("count").get<long long>();
    if (static_cast<long long>(parts.size()) != count)
        throw UsageError("expected " + std::to_string(count) + " shard files (the shards of " +
                         std::to_string(count) + "), got " + std::to_string(parts.size()));
    std::vector<const ShardData*> by_index(static_cast<std::size_t>(count), nullptr);
    for (std::size_t k = 0; k < parts.size(); ++k) {
        const Json& h = parts[k].header;
        for (const char* key : {"scene_file", "target", "points", "settings"})
            if (h.at(key) != h0.at(key))
                throw UsageError(o.shards[k] + ": not from the same bake as " + o.shards[0] +
                                 " (\"" + key + "\" differs)");
        if (parts[k].input_hash != parts[0].input_hash)
            throw UsageError(o.shards[k] + ": not from the same bake as " + o.shards[0] +
                             " (the input hash differs: another scene file or version of it)");
        if (h.at("shard").at("count").get<long long>() != count)
            throw UsageError(o.shards[k] + ": a shard of " +
                             std::to_string(h.at("shard").at("count").get<long long>()) +
                             ", expected of " + std::to_string(count));
        const auto i = h.at("shard").at("index").get<std::size_t>();
        if (i >= by_index.size()) throw UsageError(o.shards[k] + ": corrupt shard index");
        if (by_index[i] != nullptr)
            throw UsageError(o.shards[k] + ": shard " + std::to_string(i) + " given twice");
        by_index[i] = &parts[k];
    }
    const std::string scene_file = h0.at("scene_file").get<std::string>();
    const SceneFile scene = load_scene(scene_file);

    render::BakeSettings s;
    const Json& js = h0.at("settings");
    s.quantities = render::Quantity{};
    for (const Json& q : js.at("quantities"))
        s.quantities |= q.get<std::string>() == kNormalMapName
                            ? kNormalMap
                            : render::quantity_of_name(q.get<std::string>());
    s.bands = js.at("bands").get<int>();
    s.basis = js.at("basis").get<std::string>();
    s.coeffs = js.at("coeffs").get<int>();
    s.rays = js.at("rays").get<int>();
    s.bounces = js.at("bounces").get<int>();
    s.seed = js.at("seed").get<std::uint64_t>();
    if (!js.at("max_distance").is_null()) s.max_distance = js.at("max_distance").get<double>();
    s.target_error = js.at("target_error").get<double>();
    if (js.contains("adaptive")) {
        for (const auto& [k, v] : js.at("adaptive").at("target_error").items())
            s.adaptive[render::quantity_of_name(k)] = v.get<double>();
        s.adaptive.max_rays = js.at("adaptive").at("max_rays").get<int>();
    }

    // Everything the records depend on, recomputed from the files as they are now: a scene, mesh
    // or image edited since the bake (or settings edited in a header) is refused here.
    if (shard_input_hash(input_hash(scene), h0.at("target").get<std::string>(), settings_json(s)) !=
        parts[0].input_hash)
        throw std::runtime_error(scene_file +
                                 ": the scene or a file it reads changed since the shards were "
                                 "baked (their input hash differs); bake the shards again");
    const Work w = make_work(scene, parse_target(h0.at("target").get<std::string>()), "");
    if (h0.at("points").get<std::size_t>() != w.points.size())
        throw std::runtime_error(o.shards[0] + ": a bake of " +
                                 std::to_string(h0.at("points").get<std::size_t>()) +
                                 " points, the scene has " + std::to_string(w.points.size()));
    const Layout L(s);
    std::vector<double> rec;
    rec.reserve(w.points.size() * L.stride);
    std::vector<render::Pass> plan;
    std::uint64_t rays = 0;
    double bake_seconds = 0;
    render::AdaptiveSummary adaptive;
    for (std::size_t i = 0; i < by_index.size(); ++i) {
        const ShardData& d = *by_index[i];
        if (s.adaptive.enabled()) adaptive.merge(adaptive_summary_of(d.header.at("adaptive")));
        const Json& sh = d.header.at("shard");
        if (d.stride != L.stride)
            throw std::runtime_error("shard " + std::to_string(i) + ": records of " +
                                     std::to_string(d.stride) + " numbers, the settings give " +
                                     std::to_string(L.stride));
        if (sh.at("begin").get<std::size_t>() * L.stride != rec.size() ||
            (sh.at("end").get<std::size_t>() - sh.at("begin").get<std::size_t>()) * L.stride !=
                d.rec.size())
            throw std::runtime_error("shard " + std::to_string(i) +
                                     ": its point range does not fit");
        rec.insert(rec.end(), d.rec.begin(), d.rec.end());
        rays += d.header.at("rays").get<std::uint64_t>();
        bake_seconds += d.header.at("seconds").at("bake").get<double>();
        const std::vector<render::Pass> p = plan_of(d.header.at("plan"));
        for (const render::Pass& x : p) {
            auto it = std::find_if(plan.begin(), plan.end(),
                                   [&](const render::Pass& y) { return y.name == x.name; });
            if (it == plan.end()) {
                plan.push_back(x);
            } else {
                it->rays += x.rays;
                it->seconds += x.seconds;
            }
        }
    }
    if (rec.size() != w.points.size() * L.stride)
        throw std::runtime_error("the shards hold " + std::to_string(rec.size() / L.stride) +
                                 " points, the scene has " + std::to_string(w.points.size()));
    OutputFiles out(o.out);
    if (gltf)
        declare_engine_files(out, o.out, engine_input(scene, w, s, nullptr, encoding, compression));
    else
        declare_outputs(out, o.out, scene, w.target, "bake.json");
    out.prepare();
    Json summary = {
        {"tool", "sphbasis bake"},
        {"scene", h0.at("scene")},
        {"target", w.target.text()},
        {"points", w.points.size()},
        {"seed", s.seed},
        {"settings", settings_json(s)},
        {"plan", plan_json(plan)},
        {"rays", rays},
        {"rays_per_second", bake_seconds > 0 ? static_cast<double>(rays) / bake_seconds : 0.0},
        {"shards", count}};
    if (s.adaptive.enabled()) summary["adaptive"] = adaptive_json(s, adaptive);
    if (has(s.quantities, render::Quantity::irradiance)) summary["irradiance"] = irradiance_json(s);
    if (gltf)
        add_engine_files(out, o.out, engine_input(scene, w, s, &rec, encoding, compression),
                         summary);
    else
        summary["outputs"] = write_outputs(scene, w, s, rec, o.out, out);
    summary["seconds"] = {{"bake_sum_over_shards", bake_seconds}, {"merge", seconds_since(t0)}};
    out.add(join_path(o.out, "bake.json"),
            dump_json(summary, {{"plan", 2}, {"outputs", 2}}) + "\n");
    out.commit();
    std::fprintf(stderr, "sphbasis bake-merge: %lld shards, %zu points\n", count, w.points.size());
    return 0;
}

}  // namespace

Run setup_bake(CLI::App& app) {
    auto o = std::make_shared<BakeOptions>();
    app.footer(
        "Bake ambient occlusion, bent normals, SH visibility, PRT transfer, irradiance and\n"
        "radiance of a scene (docs/scene-format.md) per vertex (PLY), per texel (EXR), on the\n"
        "scene's probe grid (JSON) or at points (JSON lines on stdout). Writes OUT/bake.json\n"
        "with the pass plan, timings and settings. --shard I/N bakes 1/N of the points for\n"
        "`sphbasis bake-merge`. A mesh with a \"source\" is baked from its high-poly source\n"
        "(docs/baking.md, \"High to low\").");
    add_scene(app, o->scene);
    app.add_option("--quantities", o->quantities,
                   "comma-separated: ao, bent, visibility, transfer, irradiance, radiance, "
                   "normal_map (meshes with a \"source\")")
        ->type_name("LIST")
        ->capture_default_str();
    // render::Baker's range (BakeSettings::bands).
    add_integer(app, "--bands", o->bands, 1, 16, "SH bands of visibility, transfer and radiance");
    app.add_option("--basis", o->basis,
                   "basis of irradiance: sh, hbasis, hbasis-mod, hl2, hsh, makhotkin, zernike, "
                   "sg5|sg6|sg9|sg12 (BakingLab's lobes; or sg --coeffs N), ambient-cube (5 "
                   "values), ambient-dice (12), ambient-dice-bezier (30), ambient-dice-linear "
                   "(10); non-linear: zh3 (5 values), zh3-hallucinate (4), sh-l1-nonlinear (4)")
        ->type_name("NAME")
        ->capture_default_str();
    o->coeffs_opt = add_integer(app, "--coeffs", o->coeffs, 1, 1024,
                                "irradiance coefficients (default 9, or the basis's one size)");
    o->sg_solver_opt =
        app.add_option("--sg-solver", o->sg_solver,
                       "--basis sgN: least squares (ls), non-negative least squares (nnls) or "
                       "Roughton's running average (running)")
            ->type_name("ls|nnls|running")
            ->capture_default_str();
    o->rays_opt = add_integer(app, "--rays", o->rays, 1, 1 << 24, "rays per point and pass");
    add_integer(app, "--bounces", o->bounces, 0, 64, "interreflection bounces at most", "B");
    add_integer(app, "--seed", o->seed, 0, std::numeric_limits<long long>::max(), "random seed",
                "S");
    o->maxd_opt = app.add_option("--max-distance", o->max_distance,
                                 "ao: hits farther than D do not occlude (default: none)")
                      ->type_name("D");
    o->target_opt = app.add_option("--target", o->target, "vertices, texels:RES or probes")
                        ->type_name("vertices|texels:RES|probes")
                        ->capture_default_str();
    o->points_opt =
        app.add_option(
               "--points", o->points,
               "bake at points from FILE or '-' (stdin): 'x y z nx ny nz' or 'x y z' per line")
            ->type_name("FILE|-");
    o->out_opt = add_path(app, "--out", o->out, "output directory (created if missing)");
    o->out_opt->type_name("DIR")->capture_default_str();
    o->shard_opt =
        app.add_option("--shard", o->shard, "bake shard I of N (0 <= I < N)")->type_name("I/N");
    app.add_option("--format", o->format,
                   "native (PLY, EXR, JSON) or gltf (engine files: docs/export-format.md)")
        ->type_name("native|gltf")
        ->capture_default_str();
    o->encoding_opt =
        app.add_option("--encoding", o->encoding, "--format gltf: lightmap and probe images")
            ->type_name("png8|png16|half|float")
            ->capture_default_str();
    o->export_opt =
        app.add_option("--export", o->exports,
                       "--format gltf: transfer by PCA or CPCA (pca:M, cpca:C:M), Toksvig's table "
                       "(toksvig:S), the L x H table (lxh:K[:N[:RES]]), the SVD normal basis "
                       "(svd:M[:RES])")
            ->type_name("LIST");
    app.add_flag("--no-cache", o->no_cache,
                 "do not also store the results in OUT/cache for `sphbasis render` to reuse");
    o->target_error_opt =
        app.add_option("--target-error", o->target_error,
                       "adaptive sampling: batches of --rays rays per point until each standard "
                       "error is at most X (one X for all, or ao:X,irradiance:Y,...)")
            ->type_name("X|NAME:X,...");
    add_integer(app, "--max-rays", o->max_rays, 1, 1 << 30,
                "adaptive sampling: rays per point and pass at most (default 16 --rays)");
    add_gl_engine_options(app, o->gl);
    return [o] { return run_bake(*o); };
}

Run setup_bake_merge(CLI::App& app) {
    auto o = std::make_shared<MergeOptions>();
    app.footer(
        "Join the shard files of `sphbasis bake --shard I/N` (bake.shard-I-of-N.bin, all N of\n"
        "them) into the files one unsharded bake writes, bit for bit. The scene file must be\n"
        "unchanged and at the path recorded in the shards.");
    app.add_option("shards", o->shards, "the N shard files")->type_name("SHARD.bin")->required();
    add_path(app, "--out", o->out, "output directory (created if missing)")
        ->type_name("DIR")
        ->capture_default_str();
    app.add_option("--format", o->format, "as for bake: native or gltf (docs/export-format.md)")
        ->type_name("native|gltf")
        ->capture_default_str();
    o->encoding_opt =
        app.add_option("--encoding", o->encoding, "as for bake: --format gltf's images")
            ->type_name("png8|png16|half|float")
            ->capture_default_str();
    o->export_opt =
        app.add_option("--export", o->exports, "as for bake: --format gltf's extra files")
            ->type_name("LIST");
    return [o] { return run_merge(*o); };
}

}  // namespace sphbasis::cli
