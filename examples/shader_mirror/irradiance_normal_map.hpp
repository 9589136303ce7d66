// The C++ mirror of irradiance_normal_map.frag, written with GLM types and the sphbasis headers:
// shade_texel() line for line as the shader's, the texture reads as nearest-texel lookups. A CPU
// fallback and the reference of the shader's test (tests/shaders runs the .frag on Mesa's
// llvmpipe and compares with this). Keep the two files side by side and change them together.
//
// Reference: R. Habel and M. Wimmer, "Efficient Irradiance Normal Mapping", I3D 2010 (the
// H-basis light map evaluated at the normal-map normal).
#pragma once

#include <glm/glm.hpp>
#include <sphbasis/basis/hbasis.hpp>
#include <vector>

namespace shader_mirror {

/// The shader's shade_texel(): lr, lg, lb hold the 4 H-basis coefficients of red, green, blue;
/// encoded_normal is the normal-map texel (n/2 + 1/2). sphbasis_hbasis4_eval_sum is
/// sphbasis::basis_eval_sum<HBasis>(4, ...) (same kernel, same constants, same order of the sum).
inline glm::vec3 shade_texel(glm::vec4 lr, glm::vec4 lg, glm::vec4 lb, glm::vec3 encoded_normal) {
    const glm::vec3 n = glm::normalize(encoded_normal * 2.0f - 1.0f);
    const glm::vec3 c[4] = {
        {lr.x, lg.x, lb.x}, {lr.y, lg.y, lb.y}, {lr.z, lg.z, lb.z}, {lr.w, lg.w, lb.w}};
    const glm::vec3 e = sphbasis::basis_eval_sum<sphbasis::HBasis>(4, c, n);
    return glm::max(e, glm::vec3(0.0f));
}

/// The textures of the shader as row-major arrays of w x h texels (row 0 at v = 0).
struct Textures {
    int width = 0, height = 0;
    std::vector<glm::vec4> lightmap_r, lightmap_g, lightmap_b;
    std::vector<glm::vec3> normal_map;
};

/// The shader's main() at pixel (i, j) of a w x h target over the whole texture, nearest
/// filtering: pixel (i, j) reads texel (i, j).
inline glm::vec3 shade_pixel(const Textures& t, int i, int j) {
    const std::size_t k = std::size_t(j) * std::size_t(t.width) + std::size_t(i);
    return shade_texel(t.lightmap_r[k], t.lightmap_g[k], t.lightmap_b[k], t.normal_map[k]);
}

}  // namespace shader_mirror
