// Struct layouts, bindings and workgroup sizes shared by the raster engine (C++) and its shaders
// (GLSL, std430). Included by both; the C++ side checks sizes and offsets with static_assert.
// No 64-bit float appears in a struct (doubles travel as uvec2 bit patterns), so the float32
// shaders need no Float64 capability.
#ifndef BLUETILE_GPU_RASTER_LAYOUT_H
#define BLUETILE_GPU_RASTER_LAYOUT_H

// The host's classification (raster_reference.cpp) sums segments of this many pixels of one
// row, so runs of equal IDs are summed at once.
#define BLUETILE_CLASSIFY_SEGMENT 32
// classify.comp: a workgroup is a tile of GROUP consecutive columns (one per invocation) by
// ROWS rows, each invocation summing runs down its column. ROWS above 32: the loop over them is
// never unrolled by lavapipe (whose SIMD code runs every unrolled copy); 64 x 64 lists fit in
// 16 KiB of shared memory.
#define BLUETILE_CLASSIFY_GROUP 64
#define BLUETILE_CLASSIFY_ROWS 64
// Boundary pixels per split workgroup: each invocation keeps its candidates and polygons in
// shared memory (about 1.4 KiB each in float64), within the 32 KiB a lavapipe group has.
#define BLUETILE_SPLIT_GROUP 16
// Split workgroups per row of its indirect dispatch (well below the 65535 every device allows).
#define BLUETILE_SPLIT_ROW 4096u
// Sites that may own part of one boundary pixel (after pruning); more go to the host (rare:
// dense clusters at a coarse resolution).
#define BLUETILE_MAX_CANDIDATES 16
// Candidates left after pruning that may share one boundary pixel in split_lane_f64.comp:
// each piece has at most 4 + (this - 1) vertices, the register slots it keeps; more go to the
// host (SceneInfo::max_pieces, which split_body.glsl honours too), which splits them as the
// host reference does, so the bound changes no bit. Three: 89% of the boundary pixels of a
// relaxed set keep two or three, and lavapipe runs every slot and clip step of the kernel for
// every pixel, whether it needs it or not (docs/BENCHMARKS.md, "The lane kernel for three").
#define BLUETILE_MAX_PIECES 3
// The same on other devices (split_lane5_f64.comp): a GPU runs only the steps its pixels need,
// and three leave 11-24% of the boundary pixels to the host, five about 1% (docs/BENCHMARKS.md,
// "The lane kernel for three").
#define BLUETILE_MAX_PIECES_GPU 5
// Grid buckets a split may visit per axis; a wider window (a huge cell in a dense scene) goes
// to the host.
#define BLUETILE_MAX_WINDOW 9
// Segments of the tessellated-fan cone variant (the classic method; see docs/RASTER.md).
#define BLUETILE_FAN_SEGMENTS 32

// Scene flag bits.
#define BLUETILE_SCENE_AREA 1u  // area coverage: classify pixels, split the boundary ones

// Site flag bits.
#define BLUETILE_SITE_SPLIT 1u   // another site is so close that float depths may confuse them: split all its pixels
#define BLUETILE_SITE_WANTED 2u  // its cell is measured (pieces are summed only for wanted sites)

// Descriptor bindings (one set for every pipeline).
#define BLUETILE_BINDING_INSTANCES 0
#define BLUETILE_BINDING_SCENES 1
#define BLUETILE_BINDING_SITES 2
#define BLUETILE_BINDING_POSITIONS 3
#define BLUETILE_BINDING_SUMS 4
#define BLUETILE_BINDING_COUNTERS 5
#define BLUETILE_BINDING_BOUNDARY 6
#define BLUETILE_BINDING_MASKS 7
#define BLUETILE_BINDING_GRID 8
#define BLUETILE_BINDING_OVERFLOW 9
#define BLUETILE_BINDING_ID_IMAGE 10
// The positions and the grid again as uniform texel buffers (read by split_lane_f64.comp):
// lavapipe fetches texels for all lanes without the per-lane loop of a storage-buffer load.
#define BLUETILE_BINDING_POSITION_TEXELS 11
#define BLUETILE_BINDING_GRID_TEXELS 12
// The scene records and the site records as uniform texel buffers (read by split_lane_f64.comp):
// its set-up read each field of the scene record lane by lane, 15% of the kernel's time
// (docs/BENCHMARKS.md, "The lane kernel, texels for the set-up").
#define BLUETILE_BINDING_SCENE_TEXELS 13
#define BLUETILE_BINDING_SITE_TEXELS 14
// The positions again in the order of each scene's grid site list (one 16-byte texel per grid
// word; the bucket starts' texels unused): the lane split's walks read a site's position by its
// list entry, without first fetching its index (split_lane_f64.comp).
#define BLUETILE_BINDING_LIST_POSITION_TEXELS 15
#define BLUETILE_BINDING_COUNT 16
// 16-byte texels per SceneInfo and per SiteInfo.
#define BLUETILE_SCENE_TEXELS 11
#define BLUETILE_SITE_TEXELS 2

// Fixed slots of the counters buffer; per-scene uncovered-sample counts follow.
#define BLUETILE_COUNTER_DISPATCH 0   // 3 words: the split's indirect dispatch (x, y, z)
#define BLUETILE_COUNTER_BOUNDARY 3   // boundary pixels listed
#define BLUETILE_COUNTER_OVERFLOW 4   // boundary pixels left to the host
#define BLUETILE_COUNTER_GUARD 5      // of those, the ones the lane split's clip guard left
#define BLUETILE_COUNTER_UNCOVERED 8  // first per-scene uncovered-sample count

#ifdef __cplusplus
#include <cstddef>
#include <cstdint>
namespace bluetile::gpu {
using uint = std::uint32_t;
using int64_t = std::int64_t;
struct vec2 { float x, y; };
struct ivec2 { std::int32_t x, y; };
struct uvec2 { std::uint32_t x, y; };
#endif

// One cone: a site or one of its periodic replicas, drawn as a square of half-side `radius`
// (domain units) clamped to its scene's tile.
struct ConeInstance {
  ivec2 pixel;   // the site's pixel shifted by whole periods for a replica (may lie outside the tile)
  float radius;  // domain units
  uint id;       // global site index + 1 (0 = no site)
};

// Sample (i, j) of a scene lies at (i hx, j hy): the corners of the pixels in area coverage,
// the pixel centres in point coverage. Pixel (i, j) of area coverage spans samples (i, j) to
// (i + 1, j + 1), wrapped.
struct SceneInfo {
  ivec2 origin;       // tile corner in the atlas, samples
  ivec2 size;         // tile size: the scene's resolution rx x ry
  vec2 pixel_size;    // hx, hy (domain units)
  vec2 domain_size;
  float depth_scale;  // 1 / (largest depth distance): depths stay in [0, 1]
  uint site_begin;    // global index of the scene's first site
  uint flags;
  uint mask_offset;   // first word of the scene's site masks (two bits per pixel, rows of words)
  ivec2 grid_size;    // site grid columns, rows
  uint grid_offset;   // first word of the scene's grid in the grid buffer: bucket starts, then sites
  uint max_pieces;    // candidates after pruning a pixel may keep; more go to the host
  vec2 bucket_size;   // site grid bucket sides, domain units
  float reach_limit;  // farthest a piece may lie from its site for the fixed-point bounds (domain)
  uint guard_test;    // tests only (RasterOptions::split_guard_test): nonzero trips the lane
                      // split's clip guard on pixels whose index i + j rx has all its bits
  // The same in double precision (bit patterns), for the float64 split.
  uvec2 pixel_size64[2];
  uvec2 domain_size64[2];
  uvec2 bucket_size64[2];
  uvec2 reach_limit64;
  // Fixed-point scales of piece sums (powers of two): area, first moment, second moment.
  uvec2 scale64[3];
  vec2 scale32;      // area and first-moment scales as floats (the float32 split)
  float scale32_second;
  float pad2;
};

// Per site: what the shaders need to form offsets relative to the site.
struct SiteInfo {
  ivec2 pixel;    // floor(site / pixel size): the sample below-left of the site
  vec2 fraction;  // site / pixel size - pixel, in [0, 1)
  uint scene;
  uint flags;     // BLUETILE_SITE_*
  uint pad0;
  uint pad1;
};

// Per site sums. Whole pixels (area) or samples (point): integer offsets d in pixels from the
// site's pixel, wrapped into [-size/2, size/2); exact, so independent of order. Boundary pieces
// (area): fixed-point moments relative to the site, scaled by the scene's scales.
struct SiteSums {
  int64_t sum_x;
  int64_t sum_y;
  int64_t sum_xx;
  int64_t sum_yy;
  int64_t piece_area;
  int64_t piece_x;
  int64_t piece_y;
  int64_t piece_second;
  uint count;     // whole pixels (area) or samples (point) summed
  uint owned;     // samples showing this site's ID
  uint farthest;  // float bits of the largest squared distance (domain units) to an owned sample
  uint pad;
};

#ifdef __cplusplus
static_assert(sizeof(ConeInstance) == 16);
static_assert(sizeof(SceneInfo) == 176);
static_assert(offsetof(SceneInfo, pixel_size64) == 80);
static_assert(offsetof(SceneInfo, scale64) == 136);
// split_lane_f64.comp reads the records as 16-byte texels at these offsets.
static_assert(sizeof(SceneInfo) == 16 * BLUETILE_SCENE_TEXELS && sizeof(SiteInfo) == 16 * BLUETILE_SITE_TEXELS);
static_assert(offsetof(SceneInfo, origin) == 0 && offsetof(SceneInfo, size) == 8 && offsetof(SceneInfo, site_begin) == 36);
static_assert(offsetof(SceneInfo, grid_size) == 48 && offsetof(SceneInfo, grid_offset) == 56 && offsetof(SceneInfo, max_pieces) == 60);
static_assert(offsetof(SceneInfo, guard_test) == 76 && offsetof(SceneInfo, domain_size64) == 96);
static_assert(offsetof(SceneInfo, bucket_size64) == 112 && offsetof(SceneInfo, reach_limit64) == 128);
static_assert(offsetof(SiteInfo, flags) == 20);
static_assert(sizeof(SiteInfo) == 32);
static_assert(sizeof(SiteSums) == 80);
}  // namespace bluetile::gpu
#endif

#endif
