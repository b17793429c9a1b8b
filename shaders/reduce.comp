// reduce.comp: per-site sums over the ID buffer, one invocation per pixel of a scene's tile
// (z = scene). Offsets are integer pixel offsets from the site's own pixel, wrapped into
// [-size/2, size/2): 64-bit integer atomics give exact sums, the same in any order and with
// any thread count (float atomics do not; DESIGN section 3). Also records the farthest owned
// pixel centre per site (for the next radii and the coverage check) and counts uncovered
// pixels. In area mode a pixel whose 3x3 neighbourhood shows another ID, or that lies near the
// bisector with its site's own periodic image, is not summed but flagged in a bit mask (one
// bit per pixel, rows padded to whole words) for the host, which splits it exactly.
// raster_engine.cpp has the same reduction on the host (used on CPU devices, where it is
// faster); the two give bit-identical sums.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#include "bluetile/gpu/raster_layout.h"

layout(local_size_x = BLUETILE_REDUCE_GROUP_X, local_size_y = BLUETILE_REDUCE_GROUP_Y) in;

layout(std430, binding = BLUETILE_BINDING_SCENES) readonly buffer Scenes { SceneInfo scenes[]; };
layout(std430, binding = BLUETILE_BINDING_SITES) readonly buffer Sites { SiteInfo sites[]; };
layout(std430, binding = BLUETILE_BINDING_IDS) readonly buffer Ids { uint ids[]; };
layout(std430, binding = BLUETILE_BINDING_SUMS) buffer Sums { SiteSums sums[]; };
layout(std430, binding = BLUETILE_BINDING_COUNTERS) buffer Counters { uint uncovered[]; };
layout(std430, binding = BLUETILE_BINDING_BOUNDARY) buffer Boundary { uint boundary[]; };

layout(push_constant) uniform Push { uint atlas_width; } push;

SceneInfo scene;

// Integer division is scalarized on SIMD CPUs (lavapipe): wrap by comparisons instead.
int wrap_index(int i, int size) { return i < 0 ? i + size : (i >= size ? i - size : i); }

uint id_at(ivec2 p) {
  p = ivec2(wrap_index(p.x, scene.size.x), wrap_index(p.y, scene.size.y));
  return ids[uint(scene.origin.y + p.y) * push.atlas_width + uint(scene.origin.x + p.x)];
}

// d in (-size, size) wrapped into [-(size/2), size - size/2).
int wrap_offset(int d, int size, int halfsize) {
  d = d < -halfsize ? d + size : d;
  return d >= size - halfsize ? d - size : d;
}

void main() {
  uint scene_index = gl_WorkGroupID.z;
  scene = scenes[scene_index];
  int i = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y);
  if (i >= scene.size.x || j >= scene.size.y) return;
  uint id = id_at(ivec2(i, j));
  if (id == 0u) {
    atomicAdd(uncovered[scene_index], 1u);
    return;
  }
  ivec2 halfsize = scene.size >> 1;
  uint s = id - 1u;
  SiteInfo site = sites[s];
  ivec2 d = ivec2(wrap_offset(i - site.pixel.x, scene.size.x, halfsize.x), wrap_offset(j - site.pixel.y, scene.size.y, halfsize.y));
  vec2 offset = vec2(d) * scene.pixel_size + site.fraction;
  atomicMax(sums[s].farthest, floatBitsToUint(dot(offset, offset)));
  atomicAdd(sums[s].owned, 1u);
  if ((scene.flags & BLUETILE_SCENE_AREA) != 0u) {
    bool whole = abs(d.x) < halfsize.x - 1 && abs(d.y) < halfsize.y - 1 && (site.flags & BLUETILE_SITE_SPLIT) == 0u;
    for (int dy = -1; dy <= 1 && whole; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (id_at(ivec2(i + dx, j + dy)) != id) whole = false;
    if (!whole) {
      uint words_per_row = uint(scene.size.x + 31) >> 5;
      atomicOr(boundary[scene.boundary_offset + uint(j) * words_per_row + uint(i >> 5)], 1u << uint(i & 31));
      return;
    }
  }
  atomicAdd(sums[s].count, 1u);
  atomicAdd(sums[s].sum_x, int64_t(d.x));
  atomicAdd(sums[s].sum_y, int64_t(d.y));
  atomicAdd(sums[s].sum_xx, int64_t(d.x) * int64_t(d.x));
  atomicAdd(sums[s].sum_yy, int64_t(d.y) * int64_t(d.y));
}
