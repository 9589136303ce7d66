// Bakes an ambient-occlusion lightmap of a floor under a floating square, from plain arrays,
// with the library alone (render/: Embree and oneTBB), and writes it as an 8-bit PGM image.
//   example_bake_lightmap [out.pgm]
// The steps a game's baker takes: the texel points of a mesh's UV chart (texel_layout: one
// point per covered texel, with the id scheme and tangents the renderer uses), a Baker over the
// scene, and the lightmap image with dilated gutters (assemble_lightmap).
#include <cstdio>
#include <sphbasis/render/bake.hpp>
#include <sphbasis/render/bake_points.hpp>
#include <sphbasis/render/lightmap.hpp>
#include <vector>

int main(int argc, char** argv) {
    using namespace sphbasis::render;
    // The floor: [-1, 1]^2 at z = 0, UVs over the whole map, normals up.
    const std::vector<float> floor_p = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
    const std::vector<float> floor_n = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    const std::vector<float> floor_uv = {0, 0, 1, 0, 1, 1, 0, 1};
    // A square of side 0.8 floating at z = 0.4, facing down (it casts the occlusion).
    const std::vector<float> roof_p = {-0.4f, -0.4f, 0.4f, 0.4f,  -0.4f, 0.4f,
                                       0.4f,  0.4f,  0.4f, -0.4f, 0.4f,  0.4f};
    const std::vector<std::uint32_t> tris = {0, 1, 2, 0, 2, 3};
    const std::vector<std::uint32_t> roof_tris = {0, 2, 1, 0, 3, 2};

    MeshView floor;
    floor.positions = floor_p.data();
    floor.normals = floor_n.data();
    floor.uvs = floor_uv.data();
    floor.vertex_count = 4;
    floor.indices = tris.data();
    floor.triangle_count = 2;
    MeshView roof;
    roof.positions = roof_p.data();
    roof.vertex_count = 4;
    roof.indices = roof_tris.data();
    roof.triangle_count = 2;

    SceneDesc scene;  // no lighting: ao needs none
    scene.meshes = {floor, roof};
    BakeSettings settings;
    settings.quantities = Quantity::ao;
    settings.rays = 256;

    const int res = 64;
    const LightmapLayout layout = texel_layout(scene.meshes, 0, res);
    Baker baker(scene, settings);
    const std::vector<PointResult> ao = baker.bake(texel_points(layout));
    const std::vector<float> image = assemble_lightmap(
        layout, 1, [&](std::size_t i, float* out) { out[0] = static_cast<float>(ao[i].ao); });

    double sum = 0;
    for (const PointResult& r : ao) sum += r.ao;
    std::printf("%zu texels baked, %llu rays, mean ao %.4f\n", ao.size(),
                static_cast<unsigned long long>(baker.rays_traced()), sum / double(ao.size()));

    const char* path = argc > 1 ? argv[1] : "bake_lightmap.pgm";
    std::FILE* f = std::fopen(path, "wb");
    if (f == nullptr) {
        std::fprintf(stderr, "cannot write %s\n", path);
        return 1;
    }
    std::fprintf(f, "P5\n%d %d\n255\n", res, res);
    for (float v : image) std::fputc(static_cast<int>(v * 255.0f + 0.5f), f);
    std::fclose(f);
    std::printf("wrote %s\n", path);
    return 0;
}
