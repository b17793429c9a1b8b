// split_f32.comp: the split of boundary pixels in single precision, for devices without
// shaderFloat64 (split_body.glsl; measured error in docs/RASTER.md).
#version 450
#extension GL_GOOGLE_include_directive : require
#define real float
#define real2 vec2
#define BLUETILE_SPLIT_FLOAT64 0
#include "split_body.glsl"
