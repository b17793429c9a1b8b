// raster_common.glsl: the buffers every raster shader sees (layouts in
// src/bluetile/gpu/raster_layout.h) and small helpers.
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "bluetile/gpu/raster_layout.h"

layout(std430, binding = BLUETILE_BINDING_INSTANCES) readonly buffer Instances { ConeInstance instances[]; };
layout(std430, binding = BLUETILE_BINDING_SCENES) readonly buffer Scenes { SceneInfo scenes[]; };
layout(std430, binding = BLUETILE_BINDING_SITES) readonly buffer Sites { SiteInfo sites[]; };
// Site positions in domain units as double bit patterns (x, y): read by the float64 split only.
layout(std430, binding = BLUETILE_BINDING_POSITIONS) readonly buffer Positions { uvec4 positions[]; };
layout(std430, binding = BLUETILE_BINDING_SUMS) buffer Sums { SiteSums sums[]; };
layout(std430, binding = BLUETILE_BINDING_COUNTERS) buffer Counters { uint counters[]; };
layout(std430, binding = BLUETILE_BINDING_BOUNDARY) buffer Boundary { uvec2 boundary[]; };
// Two bits per pixel: the pixel holds a site; it holds more than one.
layout(std430, binding = BLUETILE_BINDING_MASKS) readonly buffer Masks { uint masks[]; };
// Per scene: bucket starts (columns x rows + 1), then the scene-local indices of its sites.
layout(std430, binding = BLUETILE_BINDING_GRID) readonly buffer Grid { uint grid[]; };
layout(std430, binding = BLUETILE_BINDING_OVERFLOW) buffer Overflow { uvec2 overflow[]; };

// i in (-size, 2 size) wrapped into [0, size); integer division is scalarized on SIMD CPUs
// (lavapipe), comparisons are not.
int wrap_index(int i, int size) { return i < 0 ? i + size : (i >= size ? i - size : i); }
