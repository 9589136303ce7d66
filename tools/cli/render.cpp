// sphbasis CLI: `sphbasis render SCENE.json [options]`
//
// Renders a scene (docs/scene-format.md) with the ground truth, render::PathTracer (the
// effects the scene enables and nothing else), and with each requested baked representation
// (render::Representations: irradiance-sh9, ao, bent, prt-*, lightmap-*, volume, specular-*),
// and writes the comparison into --out DIR:
//   reference.exr (linear RGB), reference.png (tone-mapped), reference_stderr.exr (the per-pixel
//   standard error of the reference, RGB); for each representation NAME.exr, NAME.png and
//   NAME_error.png (its relative error against the reference in false colour: render::
//   error_image and false_colour) and NAME_flip.png (its FLIP map: render::flip_error_map of the
//   tone-mapped images, flip_colour); specular_reference.{exr,png} when a specular representation
//   runs (the specular ones are compared with render::render_specular_reference, not with the
//   path tracer); with --aovs the reference's first-hit aov_{normal,albedo,position}.exr;
//   report.json, report.md and report.html (support/report.hpp). All of them are
//   written all or none (support/output_file.hpp): every name is checked before any work, the
//   files are staged in DIR/.sphbasis-staging-<pid>-<n> and moved into place together at the
//   end, so a failed or interrupted run (SIGINT, SIGTERM) leaves the directory as it was.
// Bakes are kept in DIR/cache/<key>.bin (support/bake_cache.hpp) unless --no-cache. With
// --bake BDIR the bakes `sphbasis bake --out BDIR` stored for the same settings (BDIR/cache, in
// the same format and keys) are read first; a BDIR holding none of this render's bakes is one
// line saying why (no bakes, another scene, other settings) before any work.
//
// Sampling: every image comes from render::ImageLoop (render/image_loop.hpp). The
// representations compared with the path tracer are rendered with its seed and its final
// sample count, the specular ones with the specular reference's seed and ss x ss samples, so
// each pair of compared images shares every sample position and the box filter; the
// representations of a group share the camera rays and hit records, whose cost is measured
// once (report: camera_ns_per_sample) apart from each one's shading (shade_ns_per_sample).
//
// Before any work the plan is printed on stderr (and recorded in report.json): the path
// tracer's effects, the bakes each representation reads (with their cache keys), the passes
// skipped and why. The scene's "render" object gives the defaults of --spp/--noise, --exposure
// and --tonemap, and the path tracer's bounce count.
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <set>
#include <sphbasis/render/camera.hpp>
#include <sphbasis/render/image.hpp>
#include <sphbasis/render/image_loop.hpp>
#include <sphbasis/render/image_metrics.hpp>
#include <sphbasis/render/path_tracer.hpp>
#include <sphbasis/render/representation.hpp>
#include <sphbasis/render/specular.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/bake_cache.hpp"
#include "../support/exr.hpp"
#include "../support/json.hpp"
#include "../support/memory.hpp"
#include "../support/output_file.hpp"
#include "../support/png.hpp"
#include "../support/progress.hpp"
#include "../support/report.hpp"
#include "../support/scene_file.hpp"
#include "cli.hpp"

namespace sphbasis::cli {

namespace {

struct RenderOptions {
    std::string scene, representations = "all", out = ".", exposure, tonemap, rotate, noise;
    long long spp = 0, max_spp = 4096, width = 0, height = 0, threads = 0, seed = 0, rays = 256,
              lightmap_size = 128, prt_bands = 3, specular_ss = 4, lxh_lighting_bands = 0,
              lxh_table_size = 32;
    std::string noise_limit_text;
    std::string bake_dir;  // --bake
    bool no_cache = false, aovs = false;
    CLI::Option *spp_opt = nullptr, *noise_opt = nullptr, *width_opt = nullptr,
                *height_opt = nullptr, *exposure_opt = nullptr, *tonemap_opt = nullptr,
                *rotate_opt = nullptr;
};

bool is_specular(const std::string& name) { return name.rfind("specular-", 0) == 0; }
/// The representations that read the distant lighting's SH at render time (and so follow
/// RepresentationSettings::lighting_rotation).
bool follows_rotation(const std::string& name) {
    return name.rfind("irradiance-sh9", 0) == 0 || name == "ao" || name == "bent" ||
           name.rfind("prt-", 0) == 0 || name.rfind("lxh-", 0) == 0;
}

/// "all" or a comma-separated list of render::representation_names(), in the order given.
std::vector<std::string> parse_representations(const std::string& s) {
    const std::vector<std::string>& valid = render::representation_names();
    if (s == "all") return valid;
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ',')) {
        if (!render::Representations::known_name(item)) {
            std::string msg =
                "--representations: unknown representation '" + quote_input(item) + "'";
            const std::string near = item.size() <= 64 ? closest_key(item, valid) : "";
            if (!near.empty()) msg += " (did you mean '" + near + "'?)";
            msg += "; expected 'all' or a list of:";
            for (const std::string& v : valid) msg += " " + v;
            msg += " (and lxh-pcaM, M <= 36; prt-cpca-C-M, C <= 4096, M <= 64)";
            throw UsageError(msg);
        }
        if (std::find(out.begin(), out.end(), item) != out.end())
            throw UsageError("--representations: '" + quote_input(item) + "' given twice");
        out.push_back(item);
    }
    if (out.empty() || s.back() == ',')
        throw UsageError("--representations: expected 'all' or a list such as irradiance-sh9,ao");
    return out;
}

Mat3<double> rotation_xyz_deg(const std::vector<double>& deg) {
    // R = Rz(z) Ry(y) Rx(x), as the scene file's "rotate_deg" (docs/scene-format.md).
    const double k = 3.14159265358979323846 / 180;
    const double cx = std::cos(deg[0] * k), sx = std::sin(deg[0] * k);
    const double cy = std::cos(deg[1] * k), sy = std::sin(deg[1] * k);
    const double cz = std::cos(deg[2] * k), sz = std::sin(deg[2] * k);
    const Mat3<double> rx{1, 0, 0, 0, cx, -sx, 0, sx, cx}, ry{cy, 0, sy, 0, 1, 0, -sy, 0, cy},
        rz{cz, -sz, 0, sz, cz, 0, 0, 0, 1};
    auto mul = [](const Mat3<double>& a, const Mat3<double>& b) {
        Mat3<double> c{};
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j)
                for (std::size_t l = 0; l < 3; ++l) c[3 * i + j] += a[3 * i + l] * b[3 * l + j];
        return c;
    };
    return mul(rz, mul(ry, rx));
}

vec3<double> rotated(const Mat3<double>& r, const vec3<double>& v) {
    return {r[0] * v.x + r[1] * v.y + r[2] * v.z, r[3] * v.x + r[4] * v.y + r[5] * v.z,
            r[6] * v.x + r[7] * v.y + r[8] * v.z};
}

std::string where_text(render::BakeRequest::Where w) {
    switch (w) {
        case render::BakeRequest::Where::vertex:
            return "vertex";
        case render::BakeRequest::Where::texel:
            return "texel";
        case render::BakeRequest::Where::probes:
            return "probes";
    }
    return "?";
}

std::string request_details(const render::BakeRequest& r) {
    const render::BakeSettings& s = r.settings;
    std::string d;
    if (has(s.quantities, render::Quantity::visibility | render::Quantity::transfer |
                              render::Quantity::radiance | render::Quantity::transfer_matrix))
        d += "bands " + std::to_string(s.bands) + ", ";
    if (has(s.quantities, render::Quantity::irradiance))
        d += "basis " + s.basis + " (" + std::to_string(s.coeffs) + "), ";
    d += "rays " + std::to_string(s.rays) + ", bounces " + std::to_string(s.bounces) + ", seed " +
         std::to_string(s.seed);
    if (r.where == render::BakeRequest::Where::texel)
        d +=
            ", lightmap " + std::to_string(r.lightmap_size) + "x" + std::to_string(r.lightmap_size);
    if (s.adaptive.enabled()) d += ", adaptive to " + std::to_string(s.adaptive.max_rays) + " rays";
    if (r.high_to_low != 0) d += ", high to low";
    return d;
}

/// The bakes `sphbasis render` reads: first those of `sphbasis bake --out DIR` (--bake DIR: its
/// DIR/cache, read only), then its own cache (--out DIR/cache, null with --no-cache), where fresh
/// bakes are stored.
class ReuseCache : public render::BakeCache {
  public:
    ReuseCache(DiskBakeCache* from_bake, DiskBakeCache* own) : from_bake_(from_bake), own_(own) {}
    bool load(std::uint64_t key, render::BakeData& out) override {
        if (from_bake_ && from_bake_->load(key, out)) {
            from_bake_keys_.insert(key);
            return true;
        }
        return own_ && own_->load(key, out);
    }
    void store(std::uint64_t key, const render::BakeData& data) override {
        if (own_) own_->store(key, data);
    }
    /// Whether the bake of `key` was loaded from --bake DIR.
    bool from_bake(std::uint64_t key) const { return from_bake_keys_.count(key) > 0; }

  private:
    DiskBakeCache *from_bake_, *own_;
    std::set<std::uint64_t> from_bake_keys_;
};

/// The one line saying why none of a render's bakes is in `sphbasis bake`'s DIR/cache: no
/// entries, entries of another scene (their key, recomputed from this scene, differs), or of
/// other settings (the first one held and the first one needed are named).
std::string bake_mismatch(const std::string& dir, const render::SceneDesc& desc,
                          const std::vector<std::string>& needed) {
    const std::string cache_dir = join_path(dir, "cache");
    std::size_t entries = 0, other_scene = 0;
    std::string held;
    std::error_code ec;
    for (std::filesystem::directory_iterator it(cache_dir, ec), end; !ec && it != end;
         it.increment(ec)) {
        if (entries >= 256) break;
        const std::filesystem::path& p = it->path();
        if (p.extension() != ".bin" || !it->is_regular_file(ec)) continue;
        try {
            std::ifstream in(p, std::ios::binary);
            const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                                  std::istreambuf_iterator<char>());
            const render::BakeFileView v =
                render::read_bake_file(bytes, render::BakeFileKind::cache);
            const render::BakeData d = render::deserialize(v.payload, v.payload_size);
            ++entries;
            if (render::bake_key(desc, d.request) != v.input_hash) {
                ++other_scene;
            } else if (held.empty()) {
                held = where_text(d.request.where) + " " +
                       render::quantity_names(d.request.settings.quantities) + ": " +
                       request_details(d.request);
            }
        } catch (const std::exception&) {
            // An unreadable entry fits nothing; the reasons are render's cache warnings.
        }
    }
    const std::string pre = "--bake " + dir + ": ";
    if (entries == 0)
        return pre + "no bakes there (expected " + cache_dir +
               "/<key>.bin, written by `sphbasis bake --out " + dir + "`)";
    if (held.empty())
        return pre + "its bakes are of another scene (other geometry, albedos or lighting); " +
               "bake this scene or drop --bake";
    return pre + "none of its bakes has this render's settings (it holds " + held +
           "; this render needs " + needed.front() + "); bake with these or drop --bake";
}

/// A progress bar fed with (done, total) pairs from any thread (the library's callbacks), in
/// thousandths of the total so that a total that grows (progressive passes) still ends at 100%.
class FractionBar {
  public:
    explicit FractionBar(const std::string& label) : bar_(label, 1000) {}
    void operator()(std::uint64_t done, std::uint64_t total) {
        if (total == 0) return;
        const long long now =
            static_cast<long long>(std::min<double>(1000, 1000.0 * double(done) / double(total)));
        long long prev = shown_.load();
        while (now > prev && !shown_.compare_exchange_weak(prev, now)) {
        }
        if (now > prev) bar_.update(now - prev);
    }
    void done() { bar_.done(); }

  private:
    Progress bar_;
    std::atomic<long long> shown_{0};
};

/// Renders representations `which` (indices into reps' names) together with one
/// render::ImageLoop of `spp` samples per pixel and `seed` (the compared reference's), so that
/// they share the camera rays and hit records: images[i] receives representation i's image
/// (Representations::render(i, camera, spp)'s: the same samples, hits, shading and sums),
/// shade_ns[i] its shading thread-seconds per pixel sample in nanoseconds; camera_seconds and
/// camera_rays grow by the shared part. Films of at most 256 MiB at a time (a group per film
/// budget).
void render_together(const render::Representations& reps, const render::Scene& rt,
                     const render::Camera& camera, const std::vector<std::size_t>& which, int spp,
                     std::uint64_t seed, const char* label, std::vector<render::Image>& images,
                     std::vector<double>& shade_ns, double& camera_seconds,
                     std::uint64_t& camera_rays) {
    if (which.empty()) return;
    const std::size_t N = std::size_t(camera.width) * std::size_t(camera.height);
    const std::size_t per_group = std::max<std::size_t>(1, (std::size_t(256) << 20) / (32 * N));
    FractionBar bar(label);
    std::atomic<std::uint64_t> done{0};
    const std::uint64_t total = std::uint64_t(N) * std::uint64_t(spp) * which.size();
    for (std::size_t g0 = 0; g0 < which.size(); g0 += per_group) {
        const std::size_t g1 = std::min(which.size(), g0 + per_group);
        render::ImageLoopSettings ls;
        ls.seed = seed;
        ls.spp = spp;
        ls.hits = true;
        render::ImageLoop loop(rt, camera, ls);
        const double angle = loop.pinhole().pixel_angle();
        std::vector<render::Film> films(g1 - g0, render::Film(camera.width, camera.height, false));
        std::vector<render::Film*> fp;
        for (render::Film& f : films) fp.push_back(&f);
        loop.run(
            0, spp, fp,
            [&](const render::CameraBatch& b, std::size_t f, render::RGB* out) {
                const std::size_t i = which[g0 + f];
                for (std::size_t k = 0; k < b.n; ++k) {
                    const render::Hit& h = b.hits[k];
                    const vec3<double>& d = b.directions[k];
                    out[k] = h.valid ? reps.shade(i, h, {-d.x, -d.y, -d.z}, h.t * angle)
                                     : reps.background(d);
                }
            },
            [&](std::uint64_t d) { bar(done.fetch_add(d * (g1 - g0)) + d * (g1 - g0), total); });
        const render::ImageLoopStats& st = loop.stats();
        for (std::size_t f = 0; f < films.size(); ++f) {
            images[which[g0 + f]] = films[f].mean();
            shade_ns[which[g0 + f]] = 1e9 * st.shade_seconds[f] / (double(N) * spp);
        }
        camera_seconds += st.camera_seconds;
        camera_rays += st.camera_rays;
    }
    bar.done();
}

/// The bytes of an OpenEXR file of `img` (float RGB, or Y for one channel), encoded in memory
/// so that the EXR joins the other outputs in one all-or-none commit.
std::string exr_bytes(const render::Image& img) {
    std::vector<std::string> channels;
    std::vector<float> values;
    if (img.channels == 1) {
        channels = {"Y"};
        values = img.data;
    } else {
        channels = {"R", "G", "B"};
        values.reserve(std::size_t(img.width) * std::size_t(img.height) * 3);
        for (int y = 0; y < img.height; ++y)
            for (int x = 0; x < img.width; ++x) {
                const float* p = img.at(x, y);
                values.insert(values.end(), {p[0], p[1], p[2]});
            }
    }
    return encode_exr(img.width, img.height, channels, values);
}

std::string png_bytes(const std::vector<std::uint8_t>& rgb, int w, int h) {
    return encode_png(rgb, w, h, 3);
}

std::string scene_summary(const SceneFile& s) {
    std::size_t tris = 0, normal_maps = 0, shiny = 0;
    for (const SceneMesh& m : s.meshes) {
        tris += m.mesh.triangle_count();
        if (m.mesh.normal_map.texels != nullptr) ++normal_maps;
        if (m.mesh.shininess > 0) ++shiny;
    }
    std::string env = "none";
    if (s.environment.kind == render::Environment::Kind::constant) env = "constant";
    if (s.environment.kind == render::Environment::Kind::latlong)
        env = std::to_string(s.environment.width) + "x" + std::to_string(s.environment.height) +
              " lat-long";
    return std::to_string(s.meshes.size()) + " meshes, " + std::to_string(tris) +
           " triangles, normal maps on " + std::to_string(normal_maps) + ", shiny materials on " +
           std::to_string(shiny) + ", environment " + env + ", " + std::to_string(s.lights.size()) +
           " analytic lights";
}

int run_render(const RenderOptions& o) {
    const auto t_start = Clock::now();
    // --- Options that need no scene (bad input fails before anything is read or written).
    std::vector<std::string> names = parse_representations(o.representations);
    if (o.spp_opt->count() > 0 && o.noise_opt->count() > 0)
        throw UsageError("give either --spp or --noise, not both");
    double noise = 0;
    if (o.noise_opt->count() > 0) {
        noise = to_real(o.noise, "--noise");
        if (!(noise > 0 && noise < 1))
            throw UsageError("--noise: expected a relative noise in (0, 1), got " +
                             quote_input(o.noise));
    }
    bool have_exposure = false, auto_exp = true;
    double exposure = 1;
    if (o.exposure_opt->count() > 0) {
        have_exposure = true;
        if (o.exposure != "auto") {
            exposure = to_real(o.exposure, "--exposure");
            if (!(exposure > 0)) throw UsageError("--exposure: expected a positive number or auto");
            auto_exp = false;
        }
    }
    const std::vector<std::string> ops = render::tone_map_names();
    if (o.tonemap_opt->count() > 0 && std::find(ops.begin(), ops.end(), o.tonemap) == ops.end())
        throw UsageError("--tonemap: unknown operator '" + quote_input(o.tonemap) + "' (expected " +
                         render::tone_map_list() + ")");
    double noise_limit = 0.05;
    if (!o.noise_limit_text.empty()) {
        noise_limit = to_real(o.noise_limit_text, "--noise-limit");
        if (!(noise_limit > 0))
            throw UsageError("--noise-limit: expected a positive fraction, got " +
                             quote_input(o.noise_limit_text));
    }
    std::vector<double> rot_deg;
    if (o.rotate_opt->count() > 0) {
        rot_deg = to_reals(o.rotate, "--rotate-lighting-deg");
        if (rot_deg.size() != 3)
            throw UsageError("--rotate-lighting-deg: expected x,y,z (three angles in degrees)");
    }

    // --- The scene.
    const SceneFile scene = load_scene(o.scene);
    if (!scene.camera.present)
        throw std::runtime_error(o.scene +
                                 ": no \"camera\": the renderer needs one (docs/scene-format.md)");
    render::Camera camera;
    camera.position = scene.camera.position;
    camera.look_at = scene.camera.look_at;
    camera.up = scene.camera.up;
    camera.fov_deg = scene.camera.fov_deg;
    camera.width = o.width_opt->count() > 0 ? int(o.width) : scene.camera.width;
    camera.height = o.height_opt->count() > 0 ? int(o.height) : scene.camera.height;
    try {
        render::validate(camera);
    } catch (const std::invalid_argument& e) {
        throw std::runtime_error(o.scene + ": camera: " + e.what());
    }
    {
        // The run's big arrays, estimated before any is allocated (support/memory.hpp): the
        // geometry, the images (the reference's sums and squares, its stderr, each
        // representation's film, image, error image and PNGs), the lightmaps (a bake point, its
        // result and the stored coefficients per texel, growing with the PRT bands) and the probes.
        const double pixels = double(camera.width) * double(camera.height);
        double texels = 0, geometry = 0;
        for (const SceneMesh& m : scene.meshes) {
            if (!m.mesh.uvs.empty()) texels += double(o.lightmap_size) * double(o.lightmap_size);
            geometry += double(m.mesh.vertex_count()) * mesh_bytes_per_vertex +
                        double(m.mesh.triangle_count()) * mesh_bytes_per_triangle;
        }
        const double nb2 = double(o.prt_bands) * double(o.prt_bands);
        const double probes = scene.has_probes ? double(scene.probes.size()) : 0;
        // The representations' images are all kept (12 bytes a pixel each) and made in groups
        // of films of 32 bytes a pixel, 256 MiB at most a group (one film at least).
        const double reps = double(names.size());
        const double films = std::max(32 * pixels, std::min(268435456.0, 32 * pixels * reps));
        const double bytes = geometry + pixels * (128 + 28 * reps) + films +
                             texels * (256 + 64 * nb2) + probes * 512;
        check_memory(o.scene + ": ", bytes,
                     std::to_string(camera.width) + " x " + std::to_string(camera.height) +
                         " pixels, " + std::to_string(static_cast<long long>(texels)) +
                         " lightmap texels, " + std::to_string(static_cast<long long>(probes)) +
                         " probes");
    }
    for (std::size_t k = 0; k < scene.meshes.size(); ++k)
        if (scene.meshes[k].dropped_triangles > 0)
            std::fprintf(stderr,
                         "sphbasis render: %s: meshes[%zu] ('%s'): %zu degenerate triangles "
                         "dropped\n",
                         scene.path.c_str(), k, scene.meshes[k].name.c_str(),
                         scene.meshes[k].dropped_triangles);

    Report rep;
    rep.scene = scene.path;
    rep.width = camera.width;
    rep.height = camera.height;
    rep.noise_limit = noise_limit;
    rep.lighting_rotation_deg = rot_deg;
    rep.bounces = scene.render.bounces;
    rep.tonemap = o.tonemap_opt->count() > 0 ? o.tonemap : scene.render.tonemap;
    if (!have_exposure) {
        auto_exp = scene.render.auto_exposure;
        exposure = scene.render.exposure;
    }
    rep.auto_exposure = auto_exp;

    // Only the effects the scene calls for: the specular comparison needs a shiny material
    // and a directional light (specular.hpp shades only those).
    bool any_shiny = false, any_directional = false;
    for (const SceneMesh& m : scene.meshes) any_shiny = any_shiny || m.mesh.shininess > 0;
    for (const render::Light& l : scene.lights)
        any_directional = any_directional || l.type == render::Light::Type::directional;
    rep.plan.push_back({"scene", scene_summary(scene)});
    if (!any_shiny || !any_directional) {
        const std::string why = !any_shiny ? "no material declares a \"shininess\""
                                           : "there is no directional light (the specular "
                                             "comparison shades directional lights only)";
        std::vector<std::string> dropped;
        for (const std::string& n : names)
            if (is_specular(n)) dropped.push_back(n);
        if (!dropped.empty()) {
            if (o.representations != "all")
                throw UsageError("--representations: " + dropped.front() +
                                 " needs a shiny material and a directional light, but in " +
                                 "this scene " + why);
            names.erase(std::remove_if(names.begin(), names.end(), is_specular), names.end());
            rep.plan.push_back({"specular pass", "skipped: " + why});
        }
    }
    if (names.empty()) throw UsageError("--representations: nothing to render");

    // --- The outputs, checked before any work: every name, a directory in the way. The
    // output directory is created only once the scene and the settings are valid (files.prepare()
    // below, before the bakes), with a staging directory in it, where the files wait until all
    // of them are written (all or none).
    OutputFiles files(o.out);
    {
        std::vector<std::string> outs = {"reference.exr", "reference.png", "reference_stderr.exr"};
        if (o.aovs)
            for (const char* a : {"aov_normal.exr", "aov_albedo.exr", "aov_position.exr"})
                outs.push_back(a);
        if (std::any_of(names.begin(), names.end(), is_specular))
            for (const char* a : {"specular_reference.exr", "specular_reference.png"})
                outs.push_back(a);
        for (const std::string& n : names)
            for (const char* a : {".exr", ".png", "_error.png"}) outs.push_back(n + a);
        for (const char* a : {"report.json", "report.md", "report.html"}) outs.push_back(a);
        for (const std::string& f : outs) files.declare_in(o.out, f);
    }

    // --- Settings.
    render::TraceSettings ts;
    ts.bounces = scene.render.bounces;
    ts.seed = static_cast<std::uint64_t>(o.seed);
    ts.aovs = o.aovs;
    if (o.spp_opt->count() > 0 || (noise == 0 && scene.render.spp > 0)) {
        const int spp = o.spp_opt->count() > 0 ? int(o.spp) : scene.render.spp;
        ts.spp_min = ts.spp_max = spp;
        ts.target_noise = 0;
    } else {
        ts.target_noise = noise > 0 ? noise : (scene.render.noise > 0 ? scene.render.noise : 0.02);
        ts.spp_max = int(o.max_spp);
        ts.spp_min = std::min(16, ts.spp_max);
    }
    render::RepresentationSettings rs;
    rs.rays = int(o.rays);
    rs.bounces = scene.render.bounces < 0 ? 64 : scene.render.bounces;
    rs.prt_bands = int(o.prt_bands);
    rs.lxh_lighting_bands = int(o.lxh_lighting_bands);
    rs.lxh_table_size = int(o.lxh_table_size);
    rs.lightmap_size = int(o.lightmap_size);
    rs.seed = static_cast<std::uint64_t>(o.seed);
    rs.has_probes = scene.has_probes;
    rs.probes = scene.probes;
    Mat3<double> R{1, 0, 0, 0, 1, 0, 0, 0, 1};
    if (!rot_deg.empty()) R = rotation_xyz_deg(rot_deg);
    rs.lighting_rotation = R;

    std::unique_ptr<tbb::global_control> limit;
    if (o.threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<std::size_t>(o.threads));
    rep.threads = tbb::this_task_arena::max_concurrency();
    if (o.threads > 0) rep.threads = std::min(rep.threads, int(o.threads));

    // --- The plan.
    const render::SceneDesc desc = scene.scene_desc();
    const render::Scene rt(desc.meshes);
    // The ground truth sees the rotated lighting; the bakes keep the scene's (the SH-lit
    // representations rotate their SH at render time, the others cannot follow).
    render::Environment env = desc.environment;
    std::vector<render::Light> lights = desc.lights;
    if (!rot_deg.empty()) {
        Mat3<double> er{};
        for (std::size_t i = 0; i < 3; ++i)
            for (std::size_t j = 0; j < 3; ++j)
                for (std::size_t l = 0; l < 3; ++l)
                    er[3 * i + j] += R[3 * i + l] * env.rotation[3 * l + j];
        env.rotation = er;
        for (render::Light& l : lights) {
            l.direction = rotated(R, l.direction);
            l.position = rotated(R, l.position);
        }
        rep.plan.push_back(
            {"lighting rotation",
             "the reference's lighting rotated; irradiance-sh9*, ao, bent, prt-* and lxh-* rotate "
             "their "
             "SH at render time (no bake); lightmaps, volume and specular keep the baked "
             "lighting"});
    }
    render::PathTracer tracer(rt, env, lights, ts);
    rep.effects = tracer.effects();
    render::Representations reps(desc, rt, rs, names);
    const std::vector<render::BakeRequest> requests = reps.bakes();
    std::vector<std::uint64_t> keys;
    for (const render::BakeRequest& r : requests) {
        PlannedBake b;
        b.where = where_text(r.where);
        if (r.where != render::BakeRequest::Where::probes && r.mesh < scene.meshes.size())
            b.mesh = scene.meshes[r.mesh].name;
        b.quantities = render::quantity_names(r.settings.quantities);
        b.details = request_details(r);
        keys.push_back(render::bake_key(desc, r));
        b.key = hex_key(keys.back());
        b.lighting_dependent = r.lighting_dependent;
        rep.bakes.push_back(b);
    }
    // --bake DIR: the bakes `sphbasis bake --out DIR` stored for the same settings are read
    // instead of baked; a DIR with none of them is refused before any work.
    if (!o.bake_dir.empty() && !keys.empty()) {
        const DiskBakeCache probe(join_path(o.bake_dir, "cache"));
        std::size_t found = 0;
        for (std::uint64_t k : keys) {
            std::error_code ec;
            found += std::filesystem::is_regular_file(probe.path_of(k), ec) ? 1 : 0;
        }
        if (found == 0) {
            std::vector<std::string> needed;
            for (const PlannedBake& b : rep.bakes)
                needed.push_back(b.where + " " + b.quantities + ": " + b.details);
            throw std::runtime_error(bake_mismatch(o.bake_dir, desc, needed));
        }
        rep.plan.push_back({"reuse", std::to_string(found) + " of " + std::to_string(keys.size()) +
                                         " bakes from " + o.bake_dir +
                                         " (sphbasis bake), the others baked"});
    }
    // Which representation reads which bake.
    for (std::size_t n = 0; n < names.size(); ++n)
        for (std::size_t i : reps.reads(n)) rep.bakes[i].read_by.push_back(names[n]);
    const bool want_specular = std::any_of(names.begin(), names.end(),
                                           [](const std::string& n) { return is_specular(n); });
    rep.specular_reference = want_specular;
    rep.specular_ss = int(o.specular_ss);
    {
        std::string list;
        for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
        rep.plan.push_back({"representations", list});
    }
    std::fputs(plan_text(rep).c_str(), stderr);

    // --- Bakes.
    files.prepare();
    std::unique_ptr<DiskBakeCache> cache, from_bake;
    if (!o.no_cache) cache = std::make_unique<DiskBakeCache>(join_path(o.out, "cache"));
    if (!o.bake_dir.empty())
        from_bake = std::make_unique<DiskBakeCache>(join_path(o.bake_dir, "cache"));
    ReuseCache reuse(from_bake.get(), cache.get());
    std::vector<bool> cached_before(keys.size(), false);
    for (std::size_t i = 0; i < keys.size() && cache; ++i) {
        std::error_code ec;
        cached_before[i] = std::filesystem::is_regular_file(cache->path_of(keys[i]), ec);
    }
    {
        FractionBar bar("bake");
        reps.prepare(cache || from_bake ? &reuse : nullptr,
                     [&bar](std::uint64_t d, std::uint64_t t) { bar(d, t); });
        bar.done();
    }
    rep.bakes_run = reps.bakes_run();
    rep.bakes_loaded = reps.bakes_loaded();
    if (from_bake) rep.warnings = from_bake->warnings();
    if (cache)
        rep.warnings.insert(rep.warnings.end(), cache->warnings().begin(), cache->warnings().end());
    std::size_t reused = 0;
    for (std::size_t i = 0; i < rep.bakes.size(); ++i) {
        bool corrupt = false;
        for (const std::string& w : rep.warnings)
            corrupt = corrupt || (cache && w.rfind(cache->path_of(keys[i]), 0) == 0);
        if (reuse.from_bake(keys[i]) && reps.bake_data(i).from_cache) {
            rep.bakes[i].status = "from bake " + o.bake_dir;
            ++reused;
        } else {
            rep.bakes[i].status = cached_before[i] && !corrupt ? "from cache" : "baked";
        }
    }

    // --- The reference.
    render::TraceResult ref;
    {
        FractionBar bar("reference");
        ref = tracer.render(camera, [&bar](std::uint64_t d, std::uint64_t t) { bar(d, t); });
        bar.done();
    }
    rep.spp = ref.spp;
    rep.relative_noise = ref.relative_noise;
    rep.reference_seconds = ref.seconds;
    const render::TraceCounters& c = ref.counters;
    rep.camera_rays = c.camera_rays;
    rep.shadow_rays = c.shadow_rays;
    rep.bounce_rays = c.bounce_rays;
    rep.normal_map_lookups = c.normal_map_lookups;
    rep.specular_evaluations = c.specular_evaluations;
    rep.environment_samples = c.environment_samples;
    rep.light_samples = c.light_samples;
    rep.rays_per_second =
        ref.seconds > 0 ? double(c.camera_rays + c.shadow_rays + c.bounce_rays) / ref.seconds : 0;
    if (auto_exp) exposure = render::auto_exposure(ref.color);
    rep.exposure = exposure;
    const render::Image* mask = ref.coverage.data.empty() ? nullptr : &ref.coverage;

    auto add_exr = [&](const std::string& base, const render::Image& img) {
        files.add(join_path(o.out, base + ".exr"), exr_bytes(img));
    };
    auto add_image = [&](const std::string& base, const render::Image& img) {
        add_exr(base, img);
        files.add(join_path(o.out, base + ".png"),
                  png_bytes(render::to_srgb8(img, exposure, rep.tonemap), img.width, img.height));
    };
    add_image("reference", ref.color);
    add_exr("reference_stderr", ref.stderr_);
    if (o.aovs)
        for (const auto& [name, img] :
             {std::pair<const char*, const render::Image*>{"normal", &ref.normal},
              {"albedo", &ref.albedo},
              {"position", &ref.position}})
            if (!img->data.empty()) add_exr(std::string("aov_") + name, *img);
    rep.reference_image = "reference.png";
    rep.reference_exr = "reference.exr";
    rep.reference_stderr_exr = "reference_stderr.exr";

    render::Image spec_ref;
    if (want_specular) {
        const auto t0 = Clock::now();
        spec_ref = render::render_specular_reference(desc, rt, camera, int(o.specular_ss),
                                                     static_cast<std::uint64_t>(o.seed));
        rep.specular_reference_seconds = seconds_since(t0);
        add_image("specular_reference", spec_ref);
        rep.specular_reference_image = "specular_reference.png";
    }

    // --- The representations' images: one render::ImageLoop per comparison, with the
    // compared reference's seed and sample count (the sampling rule, report.hpp), the camera
    // rays and hit records shared by the representations of a group.
    rep.representation_spp = ref.spp;
    rep.specular_spp = want_specular ? int(o.specular_ss * o.specular_ss) : 0;
    std::vector<render::Image> images(names.size());
    std::vector<double> shade_ns(names.size(), 0.0);
    {
        std::vector<std::size_t> plain, specs;
        for (std::size_t i = 0; i < names.size(); ++i)
            (is_specular(names[i]) ? specs : plain).push_back(i);
        double camera_seconds = 0;
        std::uint64_t camera_rays = 0;
        render_together(reps, rt, camera, plain, rep.representation_spp, std::uint64_t(o.seed),
                        "representations", images, shade_ns, camera_seconds, camera_rays);
        render_together(reps, rt, camera, specs, rep.specular_spp, std::uint64_t(o.seed),
                        "specular representations", images, shade_ns, camera_seconds, camera_rays);
        rep.camera_ns_per_sample = camera_rays > 0 ? 1e9 * camera_seconds / double(camera_rays) : 0;
    }

    // --- Each representation: its errors, and the time of a frame at one sample per pixel
    // (the pixel centre) with one thread and with all threads.
    // FLIP compares what the PNGs show: both images tone-mapped as they are.
    rep.flip_ppd = render::flip_default_ppd;
    const render::Image ref_shown = render::tone_mapped(ref.color, exposure, rep.tonemap);
    const render::Image spec_ref_shown =
        want_specular ? render::tone_mapped(spec_ref, exposure, rep.tonemap) : render::Image();
    tbb::task_arena one_thread(1);
    for (std::size_t i = 0; i < names.size(); ++i) {
        const std::string& n = names[i];
        std::fprintf(stderr, "sphbasis render: %s\n", n.c_str());
        ReportRow row;
        row.name = n;
        const render::Image& img = images[i];
        row.spp = is_specular(n) ? rep.specular_spp : rep.representation_spp;
        row.shade_ns = shade_ns[i];
        one_thread.execute([&] {
            const auto t1 = Clock::now();
            (void)reps.render(i, camera);
            row.render_ms_1 = 1e3 * seconds_since(t1);
        });
        const auto t0 = Clock::now();
        (void)reps.render(i, camera);
        row.render_ms_all = 1e3 * seconds_since(t0);
        const bool spec = is_specular(n);
        const render::Image& against = spec ? spec_ref : ref.color;
        const render::Image* se = spec ? nullptr : &ref.stderr_;
        row.against = spec ? "specular reference" : "path tracer";
        const render::ImageError e = render::compare(img, against, se, noise_limit, mask);
        row.rmse = e.rmse;
        row.rel_mse = e.rel_mse;
        row.smape = e.smape;
        row.judged = e.judged;
        row.total = e.total;
        row.rel_mse_floored = e.rel_mse_floored;
        row.smape_floored = e.smape_floored;
        row.outside_3_stderr = render::outside_stderr_fraction(img, against, se, 3, mask);
        const render::Image flip_map =
            render::flip_error_map(render::tone_mapped(img, exposure, rep.tonemap),
                                   spec ? spec_ref_shown : ref_shown, rep.flip_ppd);
        row.flip = render::flip_mean_of(flip_map, mask);
        const render::RepresentationStats st = reps.stats(i);
        // Bake + compress: the bakes read and what is built from them after (L x H tables, PCA).
        row.bake_seconds = st.bake_seconds + st.build_seconds;
        row.bake_rays = st.bake_rays;
        row.cached = st.cached;
        row.element = st.element;
        row.bytes_per_element = st.bytes_per_element;
        row.elements = st.elements;
        row.cannot_show = st.cannot_show;
        if (!rot_deg.empty() && !follows_rotation(n) && !spec)
            row.cannot_show += std::string(row.cannot_show.empty() ? "" : "; ") +
                               "a rotated light (baked lighting)";
        add_image(n, img);
        const render::Image err = render::error_image(img, against, se, noise_limit, mask);
        files.add(join_path(o.out, n + "_error.png"),
                  png_bytes(render::false_colour(err), err.width, err.height));
        row.image = n + ".png";
        row.error_image = n + "_error.png";
        files.add(join_path(o.out, n + "_flip.png"),
                  png_bytes(render::flip_colour(flip_map, mask), flip_map.width, flip_map.height));
        row.flip_image = n + "_flip.png";
        row.exr = n + ".exr";
        rep.rows.push_back(row);
    }
    // --- The reports, then every file at once.
    {
        std::ostringstream cmd;
        cmd << "sphbasis render " << o.scene << " --representations " << o.representations;
        if (ts.target_noise > 0)
            cmd << " --noise " << ts.target_noise << " --max-spp " << ts.spp_max;
        else
            cmd << " --spp " << ts.spp_max;
        cmd << " --width " << camera.width << " --height " << camera.height << " --seed " << o.seed
            << " --rays " << o.rays;
        if (!rot_deg.empty())
            cmd << " --rotate-lighting-deg " << rot_deg[0] << "," << rot_deg[1] << ","
                << rot_deg[2];
        rep.command = cmd.str();
    }
    rank_rows(rep);
    rep.total_seconds = seconds_since(t_start);
    files.add(
        join_path(o.out, "report.json"),
        dump_json(report_json(rep), {{"plan", 2}, {"bakes", 2}, {"representations", 2}}) + "\n");
    files.add(join_path(o.out, "report.md"), report_markdown(rep));
    files.add(join_path(o.out, "report.html"), report_html(rep));
    files.commit();
    std::fprintf(stderr,
                 "sphbasis render: %zu representations, reference %d spp (noise %.3g) in %.3g s, "
                 "%zu bakes run, %zu from the cache%s; wrote %s\n",
                 names.size(), rep.spp, rep.relative_noise, rep.reference_seconds, rep.bakes_run,
                 rep.bakes_loaded,
                 o.bake_dir.empty()
                     ? ""
                     : (" (" + std::to_string(reused) + " from --bake " + o.bake_dir + ")").c_str(),
                 join_path(o.out, "report.html").c_str());
    return 0;
}

}  // namespace

Run setup_render(CLI::App& app) {
    auto o = std::make_shared<RenderOptions>();
    app.footer(
        "Render a scene (docs/scene-format.md; it needs a \"camera\") with the ground-truth path\n"
        "tracer and with each baked representation, and write into DIR: reference.{exr,png},\n"
        "reference_stderr.exr, NAME.{exr,png}, NAME_error.png and NAME_flip.png per\n"
        "representation, and report.{json,md,html} (FLIP and other errors, ranked by FLIP; bake\n"
        "time, render time, memory, what it cannot show).\n"
        "Bakes are cached in DIR/cache. The plan is printed on stderr before any work.");
    add_scene(app, o->scene);
    app.add_option("--representations", o->representations,
                   "'all' or a comma-separated list (irradiance-sh9, ao, prt-vertex, ...)")
        ->type_name("LIST|all")
        ->capture_default_str();
    o->spp_opt =
        add_integer(app, "--spp", o->spp, 2, 1 << 20,
                    "reference samples per pixel (fixed; default: the scene's, or --noise)");
    o->noise_opt =
        app.add_option("--noise", o->noise,
                       "reference: sample until this relative standard error (default 0.02)")
            ->type_name("X");
    // At least 2 samples: the reference's standard error needs two.
    add_integer(app, "--max-spp", o->max_spp, 2, 1 << 20,
                "with --noise: at most N samples per pixel");
    o->width_opt =
        add_integer(app, "--width", o->width, 1, 16384, "image width (default: the scene's)", "W");
    o->height_opt = add_integer(app, "--height", o->height, 1, 16384,
                                "image height (default: the scene's)", "H");
    add_integer(app, "--threads", o->threads, 0, 4096, "threads (0: all)");
    add_integer(app, "--seed", o->seed, 0, std::numeric_limits<long long>::max(), "random seed",
                "S");
    o->exposure_opt =
        app.add_option("--exposure", o->exposure, "exposure of the PNGs: a factor or auto")
            ->type_name("X|auto");
    o->tonemap_opt = app.add_option("--tonemap", o->tonemap,
                                    "tone mapping of the PNGs: " + render::tone_map_list())
                         ->type_name("NAME");
    add_integer(app, "--rays", o->rays, 1, 1 << 24, "bake rays per point and pass");
    add_integer(app, "--lightmap-size", o->lightmap_size, 1, 8192, "lightmap texels per side");
    // The library's ranges (render::Representations' settings check).
    add_integer(app, "--prt-bands", o->prt_bands, 1, 8, "PRT transfer bands", "B");
    add_integer(app, "--lxh-lighting-bands", o->lxh_lighting_bands, 0, 16,
                "lxh-*: SH bands of the lighting in the L x H tables (0: the visibility's)", "B");
    add_integer(app, "--lxh-table-size", o->lxh_table_size, 1, 1024,
                "lxh-*: texels per cube-map face edge of the L x H tables", "N");
    add_integer(app, "--specular-ss", o->specular_ss, 1, 64,
                "specular reference: S x S camera rays per pixel", "S");
    o->rotate_opt = app.add_option("--rotate-lighting-deg", o->rotate,
                                   "rotate the lighting at render time (x,y,z degrees; no re-bake "
                                   "for the SH-lit representations)")
                        ->type_name("X,Y,Z");
    app.add_option("--noise-limit", o->noise_limit_text,
                   "judge a pixel where the reference's stderr is at most X of its luminance "
                   "(default 0.05)")
        ->type_name("X");
    app.add_flag("--no-cache", o->no_cache, "bake everything again; keep no bake cache");
    add_path(app, "--bake", o->bake_dir,
             "read the bakes `sphbasis bake --out DIR` stored for the same settings (DIR/cache) "
             "instead of baking them")
        ->type_name("DIR");
    app.add_flag("--aovs", o->aovs,
                 "also write the reference's first-hit normal, albedo and position "
                 "(aov_normal.exr, aov_albedo.exr, aov_position.exr)");
    add_path(app, "--out", o->out, "output directory (created if missing)")
        ->type_name("DIR")
        ->capture_default_str();
    // A run that fails leaves no trace: OutputFiles removes its staging and the output
    // directory it created (when nothing else was put there).
    return [o] { return run_render(*o); };
}

}  // namespace sphbasis::cli
