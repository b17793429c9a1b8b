// Struct layouts and workgroup sizes shared by the raster engine (C++) and its shaders (GLSL,
// std430). Included by both; the C++ side checks sizes and offsets with static_assert.
#ifndef BLUETILE_GPU_RASTER_LAYOUT_H
#define BLUETILE_GPU_RASTER_LAYOUT_H

#define BLUETILE_REDUCE_GROUP_X 16
#define BLUETILE_REDUCE_GROUP_Y 16
// Segments of the tessellated-fan cone variant (the classic method; see DESIGN section 3).
#define BLUETILE_FAN_SEGMENTS 32

// Scene flag bits.
#define BLUETILE_SCENE_AREA 1u  // split boundary pixels on the host: reduce interior pixels only

// Site flag bits.
#define BLUETILE_SITE_SPLIT 1u  // another site is so close that float depths may confuse them

// Descriptor bindings (one set).
#define BLUETILE_BINDING_INSTANCES 0
#define BLUETILE_BINDING_SCENES 1
#define BLUETILE_BINDING_SITES 2
#define BLUETILE_BINDING_IDS 3
#define BLUETILE_BINDING_SUMS 4
#define BLUETILE_BINDING_COUNTERS 5
#define BLUETILE_BINDING_BOUNDARY 6

#ifdef __cplusplus
#include <cstdint>
namespace bluetile::gpu {
using uint = std::uint32_t;
using int64_t = std::int64_t;
struct vec2 { float x, y; };
struct ivec2 { std::int32_t x, y; };
#define BLUETILE_STRUCT(name) struct name
#else
#define BLUETILE_STRUCT(name) struct name
#endif

// One cone: a site or one of its periodic replicas, drawn as a square of half-side `radius`
// (domain units) clamped to its scene's rectangle.
BLUETILE_STRUCT(ConeInstance) {
  vec2 position;  // replica position in scene coordinates (may lie outside the domain)
  float radius;
  uint id;        // global site index + 1 (0 = no site)
};

BLUETILE_STRUCT(SceneInfo) {
  ivec2 origin;       // tile corner in the atlas, pixels
  ivec2 size;         // tile size, pixels (the scene's resolution)
  vec2 pixel_size;    // domain units per pixel along x and y
  vec2 domain_size;
  float depth_scale;  // 1 / (largest possible depth distance): depths stay in [0, 1]
  uint site_begin;    // global index of the scene's first site
  uint boundary_offset;  // first word of the scene's boundary bit mask (rows padded to words)
  uint flags;
};

// Per site: what the reduction needs to form offsets relative to the site exactly.
BLUETILE_STRUCT(SiteInfo) {
  ivec2 pixel;     // the pixel that holds the site
  vec2 fraction;   // site offset of that pixel's centre, (pixel + 0.5) * pixel_size - site
  uint scene;
  uint flags;  // BLUETILE_SITE_SPLIT: split all its pixels on the host (area mode)
  uint pad1;
  uint pad2;
};

// Per site sums over its whole pixels, offsets in pixels relative to the site's pixel,
// wrapped into [-size/2, size/2). Integer sums are exact and independent of order.
BLUETILE_STRUCT(SiteSums) {
  int64_t sum_x;
  int64_t sum_y;
  int64_t sum_xx;
  int64_t sum_yy;
  uint count;       // whole pixels summed (all owned pixels in point mode, interior ones in area mode)
  uint owned;       // pixel centres showing this site's ID
  uint farthest;    // float bits of the largest squared distance (domain units) to an owned centre
  uint pad;
};

#ifdef __cplusplus
static_assert(sizeof(ConeInstance) == 16);
static_assert(sizeof(SceneInfo) == 48);
static_assert(sizeof(SiteInfo) == 32);
static_assert(sizeof(SiteSums) == 48);
}  // namespace bluetile::gpu
#endif

#endif
