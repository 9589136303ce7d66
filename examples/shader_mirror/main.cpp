// Example: the CPU mirror of an irradiance-normal-mapping fragment shader. Renders the
// procedural 16 x 16 light map and normal map through shade_texel() (irradiance_normal_map.hpp,
// the C++ twin of irradiance_normal_map.frag) and prints the image's red channel.
#include <cstdio>

#include "irradiance_normal_map.hpp"
#include "procedural_textures.hpp"

int main() {
    const int n = 16;
    const shader_mirror::Textures t = shader_mirror::procedural_textures(n, n);
    std::printf("exit radiance, red channel, %d x %d (top row is v = 1):\n", n, n);
    for (int j = n - 1; j >= 0; --j) {
        for (int i = 0; i < n; ++i)
            std::printf(" %.2f", double(shader_mirror::shade_pixel(t, i, j).x));
        std::printf("\n");
    }
    return 0;
}
