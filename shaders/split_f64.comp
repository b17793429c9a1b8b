// split_f64.comp: the exact split of boundary pixels in double precision (split_body.glsl).
#version 450
#extension GL_GOOGLE_include_directive : require
#define real double
#define real2 dvec2
#define BLUETILE_SPLIT_FLOAT64 1
#include "split_body.glsl"
