#version 450
#extension GL_GOOGLE_include_directive : require
// Irradiance normal mapping with an H-basis light map: each light-map texel stores, per colour
// channel, the 4 H-basis coefficients of the exit radiance of a white Lambertian surface over the
// hemisphere around the surface normal (tangent space, z = the geometric normal); the fragment
// evaluates that expansion at the normal-map normal (Habel and Wimmer, "Efficient Irradiance
// Normal Mapping", I3D 2010).
//
// The C++ mirror of this shader is irradiance_normal_map.hpp, side by side with it: the shading
// sits in one function, shade_texel(), that both sides write line for line; main() only reads
// the textures. tests/shaders runs this file on Mesa's llvmpipe against the mirror.
//
// Include: glslangValidator -I<sphbasis>/shaders (GL_GOOGLE_include_directive), or paste
// shaders/sphbasis.glsl in place of the #include with your engine's includer (the test does).
#include "sphbasis.glsl"

layout(binding = 0) uniform sampler2D lightmap_r;  // H-basis coefficients h1..h4 of red in .xyzw
layout(binding = 1) uniform sampler2D lightmap_g;  // ... of green
layout(binding = 2) uniform sampler2D lightmap_b;  // ... of blue
layout(binding = 3) uniform sampler2D normal_map;  // tangent-space normal, stored as n/2 + 1/2

layout(location = 0) in vec2 uv;
layout(location = 0) out vec4 color;

// The shading of one texel: decode the normal, gather the RGB coefficients, evaluate the
// expansion (sphbasis_hbasis4_eval_sum), clamp the ringing below zero.
vec3 shade_texel(vec4 lr, vec4 lg, vec4 lb, vec3 encoded_normal)
{
    vec3 n = normalize(encoded_normal * 2.0 - 1.0);
    vec3 c[4];
    c[0] = vec3(lr.x, lg.x, lb.x);
    c[1] = vec3(lr.y, lg.y, lb.y);
    c[2] = vec3(lr.z, lg.z, lb.z);
    c[3] = vec3(lr.w, lg.w, lb.w);
    vec3 e = sphbasis_hbasis4_eval_sum(c, n);
    return max(e, vec3(0.0));
}

void main()
{
    color = vec4(shade_texel(texture(lightmap_r, uv), texture(lightmap_g, uv),
                             texture(lightmap_b, uv), texture(normal_map, uv).xyz),
                 1.0);
}
