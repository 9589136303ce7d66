// Benchmarks of the render tier's bake (render/bake.hpp) against a bare Embree occlusion loop
// over the same rays, in the same run. Items are rays: items_per_second is rays per second.
//   bare/<scene>/<threads>:      rtcOccluded1M over precomputed rays (the bake's own rays for
//                                ao and transfer: same points, R2 + Cranley-Patterson
//                                directions from the same code, origins), 256 rays a stream
//                                copied into a per-thread buffer, tbb::parallel_for over points.
//   ao/<scene>/<threads>:        Baker::bake with Quantity::ao (sampling, tracing, accumulation).
//   transfer6/<scene>/<threads>: Baker::bake with Quantity::transfer, 6 bands (36 SH values per
//                                unoccluded ray through sh::eval_batch), no bounces.
// Scenes: "procedural" (16 UV spheres of 2,016 triangles over a 20,000-triangle grid: 52,256
// triangles) and "engine" (Debian's assimp-testmodels 2CylinderEngine.glb, loaded with Assimp,
// pre-transformed and triangulated; its triangle count is printed in the label). 1024 points
// (mesh vertices with their normals), 256 rays each. The thread count is set with
// tbb::global_control (Embree's BVH traversal runs in the calling threads).
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <atomic>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/image_loop.hpp>
#include <sphbasis/render/path_tracer.hpp>
#include <sphbasis/render/representation.hpp>
#include <sphbasis/render/shapes.hpp>
#include <string>
#include <vector>

namespace {

using namespace sphbasis;
using namespace sphbasis::render;

constexpr int rays_per_point = 256;
constexpr std::size_t point_count = 1024;

struct BenchScene {
    std::vector<Mesh> meshes;
    std::vector<BakePoint> points;
    std::size_t triangles = 0;
    std::string label;
    SceneDesc desc() const {
        SceneDesc d;
        for (const auto& m : meshes) d.meshes.push_back(m.view());
        d.environment.kind = Environment::Kind::constant;
        d.environment.constant = {1, 1, 1};
        return d;
    }
};

Mesh uv_sphere(double cx, double cy, double cz, double r, int rings, int segments) {
    Mesh m;
    const double pi = 3.14159265358979323846;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j <= segments; ++j) {
            const double th = pi * i / rings, ph = 2 * pi * j / segments;
            const double x = std::sin(th) * std::cos(ph), y = std::sin(th) * std::sin(ph),
                         z = std::cos(th);
            m.positions.insert(m.positions.end(),
                               {float(cx + r * x), float(cy + r * y), float(cz + r * z)});
            m.normals.insert(m.normals.end(), {float(x), float(y), float(z)});
        }
    auto at = [&](int i, int j) { return std::uint32_t(i * (segments + 1) + j); };
    for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
            const auto a = at(i, j), b = at(i + 1, j), c = at(i + 1, j + 1), d = at(i, j + 1);
            if (i != 0) m.indices.insert(m.indices.end(), {a, b, d});
            if (i != rings - 1) m.indices.insert(m.indices.end(), {b, c, d});
        }
    return m;
}

Mesh grid(double half, int n) {
    Mesh m;
    for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j) {
            m.positions.insert(m.positions.end(), {float(-half + 2 * half * j / n),
                                                   float(-half + 2 * half * i / n), 0.f});
            m.normals.insert(m.normals.end(), {0.f, 0.f, 1.f});
        }
    auto at = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            m.indices.insert(m.indices.end(), {at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i, j),
                                               at(i + 1, j + 1), at(i + 1, j)});
    return m;
}

/// Points: every k-th vertex of all meshes (with its normal), point_count of them.
void pick_points(BenchScene& s) {
    std::size_t total = 0;
    for (const auto& m : s.meshes) total += m.vertex_count();
    const std::size_t step = std::max<std::size_t>(1, total / point_count);
    std::size_t k = 0;
    for (const auto& m : s.meshes)
        for (std::size_t v = 0; v < m.vertex_count(); ++v, ++k) {
            if (k % step || s.points.size() >= point_count) continue;
            BakePoint p;
            p.p = {m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]};
            p.n = {m.normals[3 * v], m.normals[3 * v + 1], m.normals[3 * v + 2]};
            if (!(std::fabs(p.n.x) + std::fabs(p.n.y) + std::fabs(p.n.z) > 0)) continue;
            p.id = k;
            s.points.push_back(p);
        }
    for (const auto& m : s.meshes) s.triangles += m.triangle_count();
}

const BenchScene& procedural() {
    static const BenchScene s = [] {
        BenchScene b;
        b.meshes.push_back(grid(10, 100));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                b.meshes.push_back(uv_sphere(-6 + 4 * i, -6 + 4 * j, 1.6, 1.5, 24, 48));
        pick_points(b);
        b.label = "procedural, " + std::to_string(b.triangles) + " triangles";
        return b;
    }();
    return s;
}

const BenchScene& engine() {
    static const BenchScene s = [] {
        BenchScene b;
        const char* path =
            "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";
        Assimp::Importer imp;
        const aiScene* sc =
            imp.ReadFile(path, aiProcess_Triangulate | aiProcess_PreTransformVertices |
                                   aiProcess_GenSmoothNormals | aiProcess_JoinIdenticalVertices);
        if (!sc) return b;
        for (unsigned i = 0; i < sc->mNumMeshes; ++i) {
            const aiMesh* am = sc->mMeshes[i];
            Mesh m;
            for (unsigned v = 0; v < am->mNumVertices; ++v) {
                m.positions.insert(m.positions.end(),
                                   {am->mVertices[v].x, am->mVertices[v].y, am->mVertices[v].z});
                if (am->mNormals)
                    m.normals.insert(m.normals.end(),
                                     {am->mNormals[v].x, am->mNormals[v].y, am->mNormals[v].z});
                else
                    m.normals.insert(m.normals.end(), {0.f, 0.f, 0.f});
            }
            for (unsigned f = 0; f < am->mNumFaces; ++f)
                if (am->mFaces[f].mNumIndices == 3)
                    m.indices.insert(m.indices.end(),
                                     {am->mFaces[f].mIndices[0], am->mFaces[f].mIndices[1],
                                      am->mFaces[f].mIndices[2]});
            b.meshes.push_back(std::move(m));
        }
        pick_points(b);
        b.label = "2CylinderEngine.glb, " + std::to_string(b.triangles) + " triangles";
        return b;
    }();
    return s;
}

/// CPU seconds of the whole process (all threads): on a shared machine the wall clock of the
/// 2-thread runs depends on other load; CPU time per ray constant from 1 to 2 threads means the
/// bake itself scales (no serialisation, no contention).
double process_cpu_seconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * double(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

const BenchScene& scene_of(int which) { return which == 0 ? procedural() : engine(); }

/// The bake's ao rays for each point (same sampling as Baker: render/bake.hpp).
std::vector<RTCRay> bake_rays(const BenchScene& s, const Scene& rt, std::uint64_t seed) {
    using namespace sphbasis::render::detail::rt;
    std::vector<RTCRay> rays(s.points.size() * rays_per_point);
    const QmcTable qmc(rays_per_point);
    std::vector<V3> dirs(rays_per_point);
    for (std::size_t i = 0; i < s.points.size(); ++i) {
        const auto& bp = s.points[i];
        const V3 n = normalized(bp.n);
        const std::uint64_t key = hash(seed, bp.id);
        const double cu = unit(hash(key, 1)), cv = unit(hash(key, 2));
        const Frame<double> f(n);
        const V3 o = bp.p + n * rt.epsilon();
        qmc.directions(Warp::cosine, f, cu, cv, dirs.data());
        for (std::size_t j = 0; j < std::size_t(rays_per_point); ++j)
            Scene::set_ray(rays[i * rays_per_point + j], o, dirs[j]);
    }
    return rays;
}

/// A run of bare, ao or transfer6: the scene of argument 0 (ok() false, with the benchmark
/// skipped, when it is not available) and the thread count of argument 1 while it lives.
struct Run {
    const BenchScene& s;
    tbb::global_control gc;
    explicit Run(const benchmark::State& state)
        : s(scene_of(int(state.range(0)))),
          gc(tbb::global_control::max_allowed_parallelism, std::size_t(state.range(1))) {}
    bool ok(benchmark::State& state) const {
        if (s.points.empty()) state.SkipWithError("scene not available");
        return !s.points.empty();
    }
};

void bare(benchmark::State& state) {
    const Run run(state);
    if (!run.ok(state)) return;
    const BenchScene& s = run.s;
    const Scene rt(s.desc().meshes);
    const std::vector<RTCRay> pristine = bake_rays(s, rt, 0);
    // Each point's rays are copied into a per-thread buffer (as the bake reuses its per-thread
    // ray buffer) and traced as one stream; the occlusion counts keep the work observable.
    tbb::enumerable_thread_specific<std::vector<RTCRay>> buffers(
        [] { return std::vector<RTCRay>(rays_per_point); });
    std::atomic<std::uint64_t> occluded{0};
    const double cpu0 = process_cpu_seconds();
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, s.points.size(), 4),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              RTCRay* p = buffers.local().data();
                              std::uint64_t hits = 0;
                              for (std::size_t i = r.begin(); i != r.end(); ++i) {
                                  std::memcpy(p, &pristine[i * rays_per_point],
                                              rays_per_point * sizeof(RTCRay));
                                  rt.occluded(p, rays_per_point);
                                  hits += std::uint64_t(Scene::is_occluded(p[0]));
                              }
                              occluded += hits;
                          });
    }
    std::uint64_t total = occluded.load();
    benchmark::DoNotOptimize(total);
    state.counters["cpu_ns_per_ray"] = 1e9 * (process_cpu_seconds() - cpu0) /
                                       (double(state.iterations()) * double(pristine.size()));
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(pristine.size()));
    state.SetLabel(s.label);
}

void bake(benchmark::State& state, Quantity quantities, int bands) {
    const Run run(state);
    if (!run.ok(state)) return;
    const BenchScene& s = run.s;
    BakeSettings st;
    st.quantities = quantities;
    st.bands = bands;
    st.rays = rays_per_point;
    Baker b(s.desc(), st);
    const std::uint64_t before = b.rays_traced();
    const double cpu0 = process_cpu_seconds();
    for (auto _ : state) {
        auto r = b.bake(s.points);
        benchmark::DoNotOptimize(r.data());
    }
    state.counters["cpu_ns_per_ray"] =
        1e9 * (process_cpu_seconds() - cpu0) / double(b.rays_traced() - before);
    state.SetItemsProcessed(std::int64_t(b.rays_traced() - before));
    state.SetLabel(s.label);
}

void ao(benchmark::State& state) { bake(state, Quantity::ao, 3); }
void transfer6(benchmark::State& state) { bake(state, Quantity::transfer, 6); }

void args(benchmark::internal::Benchmark* b) {
    b->ArgNames({"scene", "threads"});
    for (int scene : {0, 1})
        for (int threads : {1, 2}) b->Args({scene, threads});
    b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(bare)->Apply(args);
BENCHMARK(ao)->Apply(args);
BENCHMARK(transfer6)->Apply(args);

}  // namespace

// ---------------------------------------------------------------------------------------------
// The path tracer (render/path_tracer.hpp) against a bare Embree loop of the same rays.
//   trace/<threads>/<tile>: PathTracer::render of the procedural scene (constant sky and a sun,
//                        2 bounces, 96 x 96 pixels, 8 samples per pixel, fixed; tiles of
//                        8 x 8 or 16 x 16 pixels, the default), items = every
//                        ray it traced (camera, bounce and shadow rays: TraceCounters::rays()).
//   trace_bare/<threads>: the rays of one such render, recorded by PathTracer::record_rays and
//                        replayed the way the tracer traces them: the same streams in the same
//                        order (a tile's camera rays as one coherent stream, then per path depth
//                        its shadow rays as one rtcOccluded1M stream and its BRDF rays as one
//                        rtcIntersect1M stream, or rtcOccluded1M at the last depth when no light
//                        needs a hit distance), tbb::parallel_for over the streams; each
//                        stream is copied from the log into a per-thread buffer first.
//   trace_copies/<threads>: trace_bare without the tracing (the copies from the log alone:
//                        what the replay costs beyond Embree; the tracer builds its rays).
// The ratio of trace's and trace_bare's items_per_second is the tracer's efficiency (the goal
// is >= 70%); both report rays_per_path, equal when they trace the same rays.

namespace {

struct TraceBench {
    std::unique_ptr<Scene> scene;
    Camera camera;
    TraceSettings settings;
    Environment env;
    std::vector<Light> lights;
};

const TraceBench& trace_bench() {
    static const TraceBench t = [] {
        TraceBench b;
        std::vector<MeshView> views;
        for (const auto& m : procedural().meshes) views.push_back(m.view());
        b.scene = std::make_unique<Scene>(views);
        b.camera.position = {0, -14, 8};
        b.camera.look_at = {0, 0, 0};
        b.camera.fov_deg = 50;
        b.camera.width = b.camera.height = 96;
        b.settings.bounces = 2;
        b.settings.spp_min = b.settings.spp_max = 8;
        b.settings.target_noise = 0;
        b.env.kind = Environment::Kind::constant;
        b.env.constant = {0.6, 0.7, 1.0};
        Light sun;
        sun.direction = {0.4, -0.3, 1};
        sun.color = {3, 3, 3};
        b.lights.push_back(sun);
        return b;
    }();
    return t;
}

/// The bench's settings with the tile size of argument 1.
TraceSettings trace_settings(const benchmark::State& state) {
    TraceSettings s = trace_bench().settings;
    s.tile = int(state.range(1));
    return s;
}

void trace(benchmark::State& state) {
    const TraceBench& b = trace_bench();
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism,
                           std::size_t(state.range(0)));
    const PathTracer t(*b.scene, b.env, b.lights, trace_settings(state));
    std::uint64_t rays = 0;
    for (auto _ : state) {
        const TraceResult r = t.render(b.camera);
        rays += r.counters.rays();
        benchmark::DoNotOptimize(r.color.data.data());
    }
    state.SetItemsProcessed(std::int64_t(rays));
    state.counters["rays_per_path"] =
        double(rays) / (double(state.iterations()) * 96 * 96 * b.settings.spp_max);
}

/// The rays of one trace render, as trace_bare replays them (recorded once).
struct TraceLog {
    std::vector<PathTracer::RayRecord> log;
    std::vector<std::pair<std::size_t, std::size_t>> streams;  // [begin, end) of the log
    std::size_t longest = 0;
};

const TraceLog& trace_log(const TraceSettings& settings) {
    static std::map<int, TraceLog> logs;  // by tile size (benchmarks run one at a time)
    const auto found = logs.find(settings.tile);
    if (found != logs.end()) return found->second;
    TraceLog& t = logs[settings.tile];
    t = [&] {
        const TraceBench& b = trace_bench();
        TraceLog l;
        PathTracer tracer(*b.scene, b.env, b.lights, settings);
        tracer.record_rays(&l.log);
        tracer.render(b.camera);
        for (std::size_t i = 0; i < l.log.size();) {
            const std::size_t n = std::max<std::uint32_t>(1, l.log[i].stream);
            l.streams.emplace_back(i, i + n);
            l.longest = std::max(l.longest, n);
            i += n;
        }
        return l;
    }();
    return t;
}

/// Replays the log: each stream is copied from the log into a per-thread buffer (as the tracer
/// builds each stream in its per-tile buffers) and, when `trace` (false: the copies alone, to
/// measure what they cost the bare loop), traced the way the tracer traced it.
void replay(benchmark::State& state, bool trace) {
    const TraceBench& b = trace_bench();
    const TraceLog& tl = trace_log(trace_settings(state));
    const auto& log = tl.log;
    const auto& streams = tl.streams;
    tbb::global_control gc(tbb::global_control::max_allowed_parallelism,
                           std::size_t(state.range(0)));
    const Scene& rt = *b.scene;
    struct Buffers {
        std::vector<RTCRayHit> work;
        std::vector<RTCRay> occl;
    };
    tbb::enumerable_thread_specific<Buffers> buffers([&] {
        return Buffers{std::vector<RTCRayHit>(tl.longest), std::vector<RTCRay>(tl.longest)};
    });
    std::atomic<std::uint64_t> hits{0};
    for (auto _ : state) {
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, streams.size(), 1),
                          [&](const tbb::blocked_range<std::size_t>& r) {
                              Buffers& buf = buffers.local();
                              std::uint64_t h = 0;
                              for (std::size_t s = r.begin(); s != r.end(); ++s) {
                                  const auto [i0, i1] = streams[s];
                                  const std::size_t n = i1 - i0;
                                  const PathTracer::RayRecord& head = log[i0];
                                  if (head.kind == 2) {
                                      RTCRay* occl = buf.occl.data();
                                      for (std::size_t i = 0; i < n; ++i)
                                          occl[i] = log[i0 + i].ray.ray;
                                      if (trace) rt.occluded(occl, n);
                                      h += std::uint64_t(Scene::is_occluded(occl[0]));
                                      continue;
                                  }
                                  RTCRayHit* work = buf.work.data();
                                  for (std::size_t i = 0; i < n; ++i) work[i] = log[i0 + i].ray;
                                  if (!trace) {
                                  } else if (!head.coherent) {
                                      rt.intersect(work, n);
                                  } else {
                                      RTCIntersectContext ctx;
                                      rtcInitIntersectContext(&ctx);
                                      ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
                                      for (std::size_t i = 0; i < n; i += 1024)
                                          rtcIntersect1M(
                                              rt.handle(), &ctx, work + i,
                                              unsigned(std::min<std::size_t>(1024, n - i)),
                                              sizeof(RTCRayHit));
                                  }
                                  h += std::uint64_t(work[0].hit.geomID != RTC_INVALID_GEOMETRY_ID);
                              }
                              hits += h;
                          });
    }
    std::uint64_t total = hits.load();
    benchmark::DoNotOptimize(total);
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(log.size()));
    // The same rays as trace: its rays_per_path counter must equal this one.
    state.counters["rays_per_path"] = double(log.size()) / (96.0 * 96.0 * b.settings.spp_max);
}

void trace_bare(benchmark::State& state) { replay(state, true); }
void trace_copies(benchmark::State& state) { replay(state, false); }

void trace_args(benchmark::internal::Benchmark* b) {
    b->ArgNames({"threads", "tile"});
    for (int threads : {1, 2})
        for (int tile : {8, 16}) b->Args({threads, tile});
    b->Unit(benchmark::kMillisecond)->UseRealTime();
}

BENCHMARK(trace_bare)->Apply(trace_args);
BENCHMARK(trace)->Apply(trace_args);
BENCHMARK(trace_copies)->Apply(trace_args);

}  // namespace

// ---------------------------------------------------------------------------------------------
// Representation shading (render/representation.hpp): the cost per pixel of each
// representation's shade() at precomputed camera hits, one thread ("what accuracy costs in
// time"; camera rays and bakes are not timed: camera_rays times the rays and hit records the
// representations share, as render::ImageLoop makes them). Items are pixels: ns per pixel = 1e9 /
// items_per_second. Scene: a UV sphere (16 x 32) over a 4 x 4 plane under a lat-long sky and a
// sun, 64 x 64 camera, bakes of 32 rays, 64 x 64 lightmaps, 1 bounce.

namespace {

struct ShadeFixture {
    std::vector<Mesh> meshes;
    std::vector<float> sky;
    SceneDesc desc;
    std::unique_ptr<Scene> rt;
    std::unique_ptr<Representations> reps;
    std::vector<Hit> hits;
    std::vector<vec3<double>> views;
    std::vector<double> footprints;
    std::vector<std::string> names;
    std::string error;
    Camera camera;

    ShadeFixture() {
        meshes.push_back(shapes::sphere({0, 0, 0.6}, 0.5, 16, 32));
        meshes.push_back(shapes::quad({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 4));
        sky.resize(32 * 16 * 3);
        for (int y = 0; y < 16; ++y)
            for (int x = 0; x < 32; ++x)
                for (int c = 0; c < 3; ++c)
                    sky[std::size_t((y * 32 + x) * 3 + c)] =
                        0.2f + 0.8f * float(16 - y) / 16.0f + (x == 5 && y == 3 ? 20.0f : 0.0f);
        for (const Mesh& m : meshes) desc.meshes.push_back(m.view());
        desc.environment.kind = Environment::Kind::latlong;
        desc.environment.texels = sky.data();
        desc.environment.width = 32;
        desc.environment.height = 16;
        Light sun;
        sun.direction = {0.3, -0.4, 0.8};
        sun.color = {2, 2, 1.8};
        desc.lights = {sun};
        rt = std::make_unique<Scene>(desc.meshes);
        RepresentationSettings s;
        s.rays = 32;
        s.bounces = 1;
        s.lightmap_size = 64;
        names = representation_names();
        try {
            reps = std::make_unique<Representations>(desc, *rt, s, names);
        } catch (const std::exception& e) {  // the specular shading may not exist yet
            error = e.what();
            names.erase(
                std::remove_if(names.begin(), names.end(),
                               [](const std::string& n) { return n.rfind("specular", 0) == 0; }),
                names.end());
            reps = std::make_unique<Representations>(desc, *rt, s, names);
        }
        reps->prepare(nullptr);
        Camera& cam = camera;
        cam.position = {0, -3, 1.5};
        cam.look_at = {0, 0, 0.3};
        cam.width = cam.height = 64;
        const PinholeCamera pc(cam);
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const CameraRay r = pc.ray(x + 0.5, y + 0.5);
                const Hit h = rt->intersect(r.origin, r.direction);
                if (!h.valid) continue;
                hits.push_back(h);
                views.push_back({-r.direction.x, -r.direction.y, -r.direction.z});
                footprints.push_back(h.t * pc.pixel_angle());
            }
    }
};

ShadeFixture& shade_fixture() {
    static ShadeFixture f;
    return f;
}

void shade_representation(benchmark::State& state, const std::string& name) {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    ShadeFixture& f = shade_fixture();
    const auto it = std::find(f.names.begin(), f.names.end(), name);
    if (it == f.names.end()) {
        state.SkipWithError(("not available: " + f.error).c_str());
        return;
    }
    const std::size_t index = std::size_t(it - f.names.begin());
    double sink = 0;
    for (auto _ : state) {
        for (std::size_t i = 0; i < f.hits.size(); ++i)
            sink += f.reps->shade(index, f.hits[i], f.views[i], f.footprints[i])[0];
        benchmark::DoNotOptimize(sink);
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(f.hits.size()));
    state.counters["bytes_per_element"] = double(f.reps->stats(index).bytes_per_element);
}

/// The camera rays and hit records every representation's image shares (render::ImageLoop with
/// hits, an li that shades nothing), one thread: the part of a frame the shade/<name> rows
/// leave out. Items are pixels (one sample each, the pixel centre).
void camera_rays(benchmark::State& state) {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    ShadeFixture& f = shade_fixture();
    ImageLoopSettings ls;
    ls.hits = true;
    ImageLoop loop(*f.rt, f.camera, ls);
    for (auto _ : state) {
        Film film(f.camera.width, f.camera.height, false);
        loop.run(0, 1, {&film}, [](const CameraBatch& b, std::size_t, RGB* out) {
            for (std::size_t k = 0; k < b.n; ++k) out[k] = {b.hits[k].t, 0, 0};
        });
        benchmark::DoNotOptimize(film.sum.data());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * f.camera.width * f.camera.height);
}
BENCHMARK(camera_rays)->Unit(benchmark::kMicrosecond);

[[maybe_unused]] const bool shade_registered = [] {
    for (const std::string& n : representation_names())
        benchmark::RegisterBenchmark(("shade/" + n).c_str(), [n](benchmark::State& s) {
            shade_representation(s, n);
        })->Unit(benchmark::kMicrosecond);
    return true;
}();

}  // namespace

BENCHMARK_MAIN();
