// A user program of the render tier: bakes ambient occlusion at the centre of a unit quad
// under nothing (ao = 1) through find_package(sphbasis COMPONENTS render), proving that the
// render headers, Embree, oneTBB and xxHash (the bake file format) are found and linked.
#include <cmath>
#include <cstdio>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/bake_file.hpp>

int main() {
    const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::uint32_t indices[] = {0, 1, 2, 0, 2, 3};
    sphbasis::render::MeshView quad;
    quad.positions = positions;
    quad.vertex_count = 4;
    quad.indices = indices;
    quad.triangle_count = 2;
    sphbasis::render::SceneDesc scene;
    scene.meshes.push_back(quad);
    sphbasis::render::BakeSettings settings;
    settings.quantities = sphbasis::render::Quantity::ao;
    settings.rays = 64;
    sphbasis::render::Baker baker(scene, settings);
    sphbasis::render::BakePoint point;
    point.p = {0, 0, 0};
    point.n = {0, 0, 1};
    const auto results = baker.bake({point});
    std::printf("ao=%.17g\n", results.at(0).ao);
    sphbasis::render::ByteWriter w;
    w.f64(results.at(0).ao);
    const auto file =
        sphbasis::render::write_bake_file(sphbasis::render::BakeFileKind::cache, 1, w.bytes());
    const auto view = sphbasis::render::read_bake_file(file, sphbasis::render::BakeFileKind::cache);
    sphbasis::render::ByteReader r(view.payload, view.payload_size, "consumer");
    return std::fabs(results.at(0).ao - 1.0) < 1e-12 && r.f64() == results.at(0).ao ? 0 : 1;
}
