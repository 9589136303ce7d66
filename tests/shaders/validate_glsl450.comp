#version 450
#extension GL_GOOGLE_include_directive : require
#include "sphbasis.glsl"
#include "validate_body.glsl"
