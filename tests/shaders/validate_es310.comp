#version 310 es
#extension GL_GOOGLE_include_directive : require
#include "sphbasis.glsl"
#include "sphbasis_render.glsl"
#include "validate_body.glsl"
