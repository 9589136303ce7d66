// Tests for render/image_loop.hpp: the sample positions written out independently (the pixel
// centre for one sample, the per-pixel rotated R2 points otherwise; a smaller count's samples
// are the first of a larger one's), the box filter and the film's moments against direct sums,
// several films sharing one set of camera rays, independence from the thread count, and that the
// path tracer, the representations and the specular reference all sample through the loop (the
// same positions: equal coverage images, equal images of a shared shading).
#include <tbb/task_arena.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "render_shapes_for_tests.hpp"
#include "render_test_support.hpp"
#include "sphbasis/core/sampling.hpp"
#include "sphbasis/render/image_loop.hpp"
#include "sphbasis/render/path_tracer.hpp"
#include "sphbasis/render/representation.hpp"
#include "sphbasis/render/shapes.hpp"
#include "sphbasis/render/specular.hpp"

namespace render = sphbasis::render;
using render::Camera;
using render::CameraBatch;
using render::Film;
using render::Image;
using render::ImageLoop;
using render::ImageLoopSettings;
using render::RGB;
using sphbasis::vec3;

namespace {

/// A ball on a plane, seen from above at an angle (hits and misses in one image).
struct LoopWorld {
    std::vector<render::Mesh> meshes;
    render::SceneDesc desc;
    std::unique_ptr<render::Scene> rt;
    LoopWorld() {
        meshes.push_back(render::shapes::sphere({0, 0, 0.6}, 0.6, 12, 24));
        meshes.push_back(sphbasis_test::quad_grid(-2, 2, -2, 2, 0, 1));
        for (const auto& m : meshes) desc.meshes.push_back(m.view());
        desc.environment = sphbasis_test::constant_environment({0.5, 0.6, 0.7});
        desc.lights = {sphbasis_test::directional_light({0.3, -0.4, 0.8}, {2, 2, 2})};
        rt = std::make_unique<render::Scene>(desc.meshes);
    }
};

Camera loop_camera(int w, int h) {
    return sphbasis_test::camera_at({2.5, -2.5, 1.8}, {0, 0, 0.4}, w, h, 60);
}

/// The position of sample s of pixel (x, y), written out: the centre for spp = 1, else R2
/// point s plus the pixel's hashed offset, modulo 1.
std::array<double, 2> expected_position(std::uint64_t seed, int w, int x, int y, int s, int spp) {
    namespace rt = render::detail::rt;
    if (spp == 1) return {x + 0.5, y + 0.5};
    const std::uint64_t key =
        rt::hash(seed, std::uint64_t(y) * std::uint64_t(w) + std::uint64_t(x));
    double u, v;
    sphbasis::r2_sequence(std::uint64_t(s), u, v);
    auto frac = [](double a) { return a - std::floor(a); };
    return {x + frac(u + rt::unit(rt::hash(key, 0x6a09e667u))),
            y + frac(v + rt::unit(rt::hash(key, 0xbb67ae85u)))};
}

}  // namespace

TEST_CASE("render::ImageLoop: sample positions, the box filter and the film's moments",
          "[render][image_loop]") {
    LoopWorld w;
    const Camera cam = loop_camera(11, 7);
    const render::PinholeCamera pc(cam);
    for (int spp : {1, 5}) {
        ImageLoopSettings ls;
        ls.seed = 77;
        ls.spp = spp;
        ls.tile = 4;
        ImageLoop loop(*w.rt, cam, ls);
        Film film(cam.width, cam.height, true);
        std::mutex m;
        std::map<std::pair<std::uint64_t, std::uint64_t>, vec3<double>> dirs;
        // li returns a function of (pixel, sample) and records the direction it was given.
        loop.run(0, spp, {&film}, [&](const CameraBatch& b, std::size_t f, RGB* out) {
            CHECK(f == 0);
            CHECK(b.hits == nullptr);
            std::lock_guard<std::mutex> lock(m);
            for (std::size_t k = 0; k < b.n; ++k) {
                dirs[{b.pixels[k], b.sample}] = b.directions[k];
                const double v = double(b.pixels[k] % 13) + 0.25 * double(b.sample * b.sample);
                out[k] = {v, 2 * v, -v};
            }
        });
        REQUIRE(dirs.size() == std::size_t(cam.width * cam.height * spp));
        CHECK(film.spp == spp);
        CHECK(loop.stats().camera_rays == std::uint64_t(cam.width * cam.height * spp));
        const Image mean = film.mean(), se = film.standard_error();
        double worst = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const std::uint64_t p = std::uint64_t(y * cam.width + x);
                double s = 0, q = 0;
                for (int i = 0; i < spp; ++i) {
                    const auto e = expected_position(77, cam.width, x, y, i, spp);
                    const vec3<double> d = pc.ray(e[0], e[1]).direction;
                    const vec3<double> g = dirs[{p, std::uint64_t(i)}];
                    worst = std::max(
                        {worst, std::fabs(d.x - g.x), std::fabs(d.y - g.y), std::fabs(d.z - g.z)});
                    const double v = double(p % 13) + 0.25 * double(i * i);
                    s += v;
                    q += v * v;
                }
                // The box filter: the plain mean of the pixel's samples.
                CHECK(mean.at(x, y)[0] == Approx(s / spp).epsilon(1e-6));
                CHECK(mean.at(x, y)[1] == Approx(2 * s / spp).epsilon(1e-6));
                CHECK(mean.at(x, y)[2] == Approx(-s / spp).epsilon(1e-6));
                if (spp == 1) {
                    CHECK(std::isinf(se.at(x, y)[0]));
                } else {
                    const double var = (q - s * s / spp) / (spp - 1);
                    CHECK(se.at(x, y)[0] == Approx(std::sqrt(var / spp)).margin(1e-6));
                }
            }
        CHECK(worst < 1e-15);
    }
}

TEST_CASE("render::ImageLoop: passes continue one sequence; films share camera rays; threads",
          "[render][image_loop]") {
    LoopWorld w;
    const Camera cam = loop_camera(19, 13);
    ImageLoopSettings ls;
    ls.seed = 5;
    ls.spp = 8;
    ls.hits = true;
    // The hit distance (0 on a miss) of each camera ray: depends on the position only.
    auto depth = [](const CameraBatch& b, std::size_t f, RGB* out) {
        for (std::size_t k = 0; k < b.n; ++k) {
            const double t = b.hits[k].valid ? b.hits[k].t : 0.0;
            out[k] = {t, f == 0 ? t : t * t, 1};
        }
    };
    ImageLoop whole(*w.rt, cam, ls);
    Film a(cam.width, cam.height, true), a2(cam.width, cam.height, false);
    whole.run(0, 8, {&a, &a2}, depth);
    CHECK(whole.stats().camera_rays == std::uint64_t(8 * cam.width * cam.height));
    REQUIRE(whole.stats().shade_seconds.size() == 2);
    CHECK(whole.stats().camera_seconds > 0);
    // In passes of 1, 1, 2 and 4 samples (a progressive renderer), on one thread.
    ImageLoop passes(*w.rt, cam, ls);
    Film b(cam.width, cam.height, true);
    tbb::task_arena one(1);
    one.execute([&] {
        for (auto [s0, s1] : {std::pair<int, int>{0, 1}, {1, 2}, {2, 4}, {4, 8}})
            passes.run(s0, s1, {&b}, depth);
    });
    CHECK(b.spp == 8);
    CHECK(a.sum == b.sum);
    CHECK(a.sq == b.sq);
    CHECK(a.hits == b.hits);
    const Image cov = a.coverage();
    double covered = 0;
    for (float c : cov.data) covered += c;
    CHECK(covered > 0.2 * double(cov.data.size()));
    CHECK(covered < 0.9 * double(cov.data.size()));
    // Film 1 squared the hit distances: its sums are film 0's sums of squares.
    for (std::size_t i = 0; i < a.sum.size(); i += 3) CHECK(a2.sum[i + 1] == a.sq[i]);
    // Bad input.
    Film small(3, 3, false);
    CHECK_THROWS_AS(whole.run(0, 9, {&a}, depth), std::invalid_argument);
    CHECK_THROWS_AS(whole.run(2, 1, {&a}, depth), std::invalid_argument);
    CHECK_THROWS_WITH(whole.run(0, 1, {&small}, depth),
                      Catch::Contains("sphbasis::render::ImageLoop::run()"));
    ls.spp = 0;
    CHECK_THROWS_AS(ImageLoop(*w.rt, cam, ls), std::invalid_argument);
}

TEST_CASE("render::ImageLoop: the path tracer, representations and specular images sample alike",
          "[render][image_loop]") {
    LoopWorld w;
    const Camera cam = loop_camera(16, 12);
    const int spp = 6;
    const std::uint64_t seed = 31;
    // The path tracer's coverage is the loop's coverage for the same seed and count.
    render::TraceSettings ts;
    ts.spp_min = ts.spp_max = spp;
    ts.target_noise = 0;
    ts.seed = seed;
    ts.bounces = 0;
    const render::PathTracer tracer(*w.rt, w.desc.environment, w.desc.lights, ts);
    const render::TraceResult ref = tracer.render(cam);
    ImageLoopSettings ls;
    ls.seed = seed;
    ls.spp = spp;
    ImageLoop loop(*w.rt, cam, ls);
    Film film(cam.width, cam.height, false);
    loop.run(0, spp, {&film}, [](const CameraBatch& b, std::size_t, RGB* out) {
        for (std::size_t k = 0; k < b.n; ++k) out[k] = {0, 0, 0};
    });
    CHECK(sphbasis_test::max_abs_diff(ref.coverage, film.coverage()) == 0);
    int partial = 0;
    for (float c : ref.coverage.data) partial += c > 0 && c < 1;
    CHECK(partial > 3);  // edge pixels: the positions are not the centre
    // A representation rendered with the same seed and count shows the sky exactly where the
    // reference's camera rays missed: its background fraction is 1 - coverage.
    render::RepresentationSettings rs;
    rs.seed = seed;
    render::Representations reps(w.desc, *w.rt, rs, {"irradiance-sh9"});
    reps.prepare(nullptr);
    const Image img = reps.render(0, cam, spp);
    const Image img1 = reps.render(0, cam, 1);
    // A pixel's value is c L_sky + (1 - c) (mean of its hits): fully covered pixels of the
    // ball's top are lit, the background pixels are exactly the sky.
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x)
            if (ref.coverage.at(x, y)[0] == 0) {
                CHECK(img.at(x, y)[0] == Approx(0.5).epsilon(1e-6));
                CHECK(img.at(x, y)[2] == Approx(0.7).epsilon(1e-6));
            }
    CHECK(sphbasis_test::max_abs_diff(img, img1) > 0);  // one sample: the centre
    // Two representations through one loop (the CLI shares the camera rays so) give the images
    // Representations::render gives each alone, to the bit.
    render::Representations two(w.desc, *w.rt, rs, {"irradiance-sh9", "ao"});
    two.prepare(nullptr);
    ImageLoopSettings hs = ls;
    hs.hits = true;
    ImageLoop shared(*w.rt, cam, hs);
    const double angle = shared.pinhole().pixel_angle();
    Film f0(cam.width, cam.height, false), f1(cam.width, cam.height, false);
    shared.run(0, spp, {&f0, &f1}, [&](const CameraBatch& b, std::size_t f, RGB* out) {
        for (std::size_t k = 0; k < b.n; ++k) {
            const render::Hit& h = b.hits[k];
            const vec3<double>& d = b.directions[k];
            out[k] = h.valid ? two.shade(f, h, {-d.x, -d.y, -d.z}, h.t * angle) : two.background(d);
        }
    });
    CHECK(f0.mean().data == two.render(0, cam, spp).data);
    CHECK(f1.mean().data == two.render(1, cam, spp).data);
    CHECK(shared.stats().camera_rays == std::uint64_t(spp * cam.width * cam.height));
    // The specular images: one sample per pixel is the centre, ss x ss the loop's positions;
    // a scene without shiny materials is black in every mode.
    const Image spec = render::render_specular_reference(w.desc, *w.rt, cam, 2, seed);
    CHECK(sphbasis_test::max_abs(spec) == 0);
}
