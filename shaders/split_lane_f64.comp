// split_lane_f64.comp: the exact float64 split of boundary pixels (as split_body.glsl computes
// it, bit for bit) with one pixel per invocation and no memory of its own: nothing in shared
// memory, nothing in a variably indexed array.
//
// On lavapipe a load or store whose address differs between lanes (storage buffers, shared
// memory) is a loop over the lanes, a texel fetch is one gather, and a private array indexed by a
// variable is a ladder of selects (docs/BENCHMARKS.md, "Every stage, host and device pixel work
// side by side"). So positions, grid words, the scene record and the site flags come as texels,
// and the candidates are never stored: one walk over the grid window finds the nearest site and
// counts those within reach, a second walk (the same arithmetic, so the same decisions) keeps
// the ones that survive pruning in BLUETILE_LANE_PIECES register slots (both walks read positions
// by grid-list entry from a copy in list order, not by site index: no grid word before each
// position, the kept entries' site indices fetched once after the walk), and each piece is clipped
// in 3 + BLUETILE_LANE_PIECES register slots (every slot index a constant once the clip steps
// are spelled out, writes included). A pixel with more candidates, or a wider window, or a clip
// that would need more than one new vertex (rounding on nearly coincident bisectors; the host's
// polygon has room), goes to the host, which splits it as the host reference does (same bits);
// its pieces' sums are held in registers until every piece is clipped, so such a pixel adds
// nothing here. Three slots (BLUETILE_MAX_PIECES) on CPU devices; the build compiles this source
// again with BLUETILE_LANE_PIECES=5 as split_lane5_f64.comp, for other devices. Measured against
// split_f64.comp: docs/BENCHMARKS.md, "The split with candidates in registers"; for three
// candidates with constant writes, and five, "The lane kernel for three"; the records as texels
// and the positions in list order, "The lane kernel, texels for the set-up".
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#include "raster_common.glsl"

layout(local_size_x = BLUETILE_SPLIT_GROUP) in;
layout(binding = BLUETILE_BINDING_ID_IMAGE, r32ui) uniform readonly uimage2D id_image;
layout(binding = BLUETILE_BINDING_POSITION_TEXELS) uniform usamplerBuffer position_texels;
layout(binding = BLUETILE_BINDING_GRID_TEXELS) uniform usamplerBuffer grid_texels;
layout(binding = BLUETILE_BINDING_SCENE_TEXELS) uniform usamplerBuffer scene_texels;
layout(binding = BLUETILE_BINDING_SITE_TEXELS) uniform usamplerBuffer site_texels;
layout(binding = BLUETILE_BINDING_LIST_POSITION_TEXELS) uniform usamplerBuffer list_position_texels;

#ifndef BLUETILE_LANE_PIECES
#define BLUETILE_LANE_PIECES BLUETILE_MAX_PIECES
#endif
// Four corners and at most one vertex more per clip by the other BLUETILE_LANE_PIECES - 1.
#define MAX_VERTICES (3 + BLUETILE_LANE_PIECES)
#if (BLUETILE_LANE_PIECES != 3 && BLUETILE_LANE_PIECES != 5) || BLUETILE_MAX_PIECES != 3 || BLUETILE_MAX_PIECES_GPU != 5
#error "clip_by_bisector's CLIP_STEPs and the kept and pending slots are spelled out for three and five"
#endif

dvec2 pixel_size, domain_size;

double unpack_real(uvec2 bits) { return packDouble2x32(bits); }
dvec2 position(uint g) {
  uvec4 p = texelFetch(position_texels, int(g));
  return dvec2(unpack_real(p.xy), unpack_real(p.zw));
}
uint grid_word(uint k) { return texelFetch(grid_texels, int(k)).x; }
// The position of the site at grid word w of a site list (the same bits as position()).
dvec2 list_position(uint w) {
  uvec4 p = texelFetch(list_position_texels, int(w));
  return dvec2(unpack_real(p.xy), unpack_real(p.zw));
}
// The fields of SceneInfo this kernel reads, from its 16-byte texels (offsets asserted in
// raster_layout.h): a storage-buffer load of the record is a loop over the lanes per field.
struct SceneFields {
  ivec2 origin, size, grid_size;
  uint site_begin, grid_offset, max_pieces, guard_test;
  dvec2 pixel_size, domain_size, bucket_size;
  double reach_limit, scale_area, scale_first, scale_second;
};
SceneFields scene_fields(uint k) {
  const int at = int(k) * BLUETILE_SCENE_TEXELS;
  const uvec4 t0 = texelFetch(scene_texels, at), t2 = texelFetch(scene_texels, at + 2), t3 = texelFetch(scene_texels, at + 3),
              t4 = texelFetch(scene_texels, at + 4), t5 = texelFetch(scene_texels, at + 5), t6 = texelFetch(scene_texels, at + 6),
              t7 = texelFetch(scene_texels, at + 7), t8 = texelFetch(scene_texels, at + 8), t9 = texelFetch(scene_texels, at + 9);
  SceneFields f;
  f.origin = ivec2(t0.xy);
  f.size = ivec2(t0.zw);
  f.site_begin = t2.y;
  f.grid_size = ivec2(t3.xy);
  f.grid_offset = t3.z;
  f.max_pieces = t3.w;
  f.guard_test = t4.w;
  f.pixel_size = dvec2(unpack_real(t5.xy), unpack_real(t5.zw));
  f.domain_size = dvec2(unpack_real(t6.xy), unpack_real(t6.zw));
  f.bucket_size = dvec2(unpack_real(t7.xy), unpack_real(t7.zw));
  f.reach_limit = unpack_real(t8.xy);
  f.scale_area = unpack_real(t8.zw);
  f.scale_first = unpack_real(t9.xy);
  f.scale_second = unpack_real(t9.zw);
  return f;
}
uint site_flags(uint g) { return texelFetch(site_texels, int(g) * BLUETILE_SITE_TEXELS + 1).y; }
// Site g relative to sample (i, j), domain units (as split_body.glsl).
dvec2 site_from_sample(uint g, ivec2 ij) {
  precise dvec2 lattice = dvec2(ij) * pixel_size;
  precise dvec2 o = position(g) - lattice;
  return o;
}

// floor(a / n) for n > 0 without integer division (lane by lane on lavapipe): the floor of the
// double quotient, off by at most one, corrected.
int floor_division(int a, int n) {
  int q = int(floor(double(a) / double(n)));
  q -= a - q * n < 0 ? 1 : 0;
  q += a - q * n >= n ? 1 : 0;
  return q;
}

double wrap_axis(double d, double period) { return d < -0.5 * period ? d + period : (d >= 0.5 * period ? d - period : d); }

// The piece being clipped: vertices [0, vertex_count) relative to its owner.
dvec2 polygon[MAX_VERTICES];
int vertex_count;
double max_radius_squared;
// Set by a clip that needed more than one new vertex, or a slot the kernel lacks: the pixel goes
// to the host. force_guard: SceneInfo::guard_test trips it on the next clip (tests only).
bool clip_lost, force_guard;

// Prepends v to the output: slots 0 .. bound - 1 move up by one. Every slot index is a constant, so
// each slot is one select under the step's condition; writing at the end (slot m) would compare
// every slot with m and select under a mask of its own, which on lavapipe cost several times the
// clip's arithmetic (docs/BENCHMARKS.md, "The lane kernel under perf").
#define PREPEND(v, bound)                                                       \
  clip_lost = clip_lost || m > (bound);                                        \
  for (int j = (bound); j > 0; --j) clipped[j] = clipped[j - 1];               \
  clipped[0] = v;                                                              \
  ++m;

// Vertex k of the clip, as ConvexPolygon::clip's edge (k - 1) -> k, taken from the last vertex
// to the first: its output, the crossing then the vertex, is prepended vertex first, so the
// output ends in the host's order. A convex piece of n < MAX_VERTICES vertices gives at most
// n - k + 1 vertices from steps k and later, so the slots that move are constant too. A piece
// being clipped has at most MAX_VERTICES - 1 vertices (four corners, one more per earlier clip),
// so there is no step MAX_VERTICES - 1: lavapipe would run it for every pixel. Rounding could
// break the bound (vertices alternating sides along a line nearly on an edge); PREPEND and the
// clip's end check it (clip_lost) instead of losing a vertex the host keeps.
#define CLIP_STEP(k)                                                              \
  if ((k) < vertex_count) {                                                       \
    const dvec2 pk = polygon[k];                                                  \
    const double sk = side[k];                                                    \
    const dvec2 pl = (k) == 0 ? last : polygon[max((k) - 1, 0)];                  \
    const double sl = (k) == 0 ? last_side : side[max((k) - 1, 0)];               \
    if (sk <= 0.0) {                                                              \
      PREPEND(pk, MAX_VERTICES - 1 - (k))                                         \
      precise double r2 = pk.x * pk.x + pk.y * pk.y;                              \
      radius_squared = max(radius_squared, r2);                                   \
    }                                                                             \
    if ((sl < 0.0 && sk > 0.0) || (sl > 0.0 && sk < 0.0)) {                       \
      precise double t = sl / (sl - sk);                                          \
      precise dvec2 x = pl + t * (pk - pl);                                       \
      PREPEND(x, MAX_VERTICES - 1 - (k))                                          \
      precise double r2 = x.x * x.x + x.y * x.y;                                  \
      radius_squared = max(radius_squared, r2);                                   \
    }                                                                             \
  }

// ConvexPolygon::clip_by_bisector on registers (same arithmetic, same order).
void clip_by_bisector(dvec2 d) {
  precise double dd = d.x * d.x + d.y * d.y;
  if (dd >= 4.0 * max_radius_squared) return;
  precise double offset = 0.5 * dd;
  double side[MAX_VERTICES];
  bool any_outside = false;
  for (int k = 0; k < MAX_VERTICES; ++k) {
    precise double s = polygon[k].x * d.x + polygon[k].y * d.y - offset;
    side[k] = s;
    any_outside = any_outside || (k < vertex_count && s > 0.0);
  }
  if (!any_outside) return;
  dvec2 last = polygon[0];
  double last_side = side[0];
  for (int k = 1; k < MAX_VERTICES; ++k) {
    if (k == vertex_count - 1) {
      last = polygon[k];
      last_side = side[k];
    }
  }
  dvec2 clipped[MAX_VERTICES];
  for (int k = 0; k < MAX_VERTICES; ++k) clipped[k] = dvec2(0.0);
  int m = 0;
  precise double radius_squared = 0.0;
#if BLUETILE_LANE_PIECES == 5
  CLIP_STEP(6) CLIP_STEP(5)
#endif
  CLIP_STEP(4) CLIP_STEP(3) CLIP_STEP(2) CLIP_STEP(1) CLIP_STEP(0)
  clip_lost = clip_lost || m > vertex_count + 1 || force_guard;
  for (int k = 0; k < MAX_VERTICES; ++k) polygon[k] = clipped[k];
  vertex_count = m;
  max_radius_squared = radius_squared;
}

int64_t fixed_point(double v, double scale) {
  precise double scaled = floor(v * scale + 0.5);
  return int64_t(scaled);
}

// The kept candidates: global site index and periodic image (16 bits per axis, offset by 32768),
// named slots so that no array is indexed by a variable.
uint kept_site0, kept_site1, kept_site2, kept_site3, kept_site4;
uint kept_image0, kept_image1, kept_image2, kept_image3, kept_image4;
void keep_candidate(uint at, uint g, uint image_bits) {
  if (at == 0u) { kept_site0 = g; kept_image0 = image_bits; }
  if (at == 1u) { kept_site1 = g; kept_image1 = image_bits; }
  if (at == 2u) { kept_site2 = g; kept_image2 = image_bits; }
#if BLUETILE_LANE_PIECES == 5
  if (at == 3u) { kept_site3 = g; kept_image3 = image_bits; }
  if (at == 4u) { kept_site4 = g; kept_image4 = image_bits; }
#endif
}
#if BLUETILE_LANE_PIECES == 5
uint kept_site(uint a) { return a == 0u ? kept_site0 : a == 1u ? kept_site1 : a == 2u ? kept_site2 : a == 3u ? kept_site3 : kept_site4; }
uint kept_image_bits(uint a) { return a == 0u ? kept_image0 : a == 1u ? kept_image1 : a == 2u ? kept_image2 : a == 3u ? kept_image3 : kept_image4; }
#else
uint kept_site(uint a) { return a == 0u ? kept_site0 : a == 1u ? kept_site1 : kept_site2; }
uint kept_image_bits(uint a) { return a == 0u ? kept_image0 : a == 1u ? kept_image1 : kept_image2; }
#endif
ivec2 kept_image(uint a) {
  const uint bits = kept_image_bits(a);
  return ivec2(int(bits & 0xffffu) - 32768, int(bits >> 16) - 32768);
}

// A pixel's piece sums (area, first moments, second moment; fixed point) per kept slot, added
// to its owner's only after every piece was clipped within the slots.
i64vec4 pending0, pending1, pending2, pending3, pending4;
bool has0, has1, has2, has3, has4;
void hold_piece(uint at, i64vec4 v) {
  if (at == 0u) { pending0 = v; has0 = true; }
  if (at == 1u) { pending1 = v; has1 = true; }
  if (at == 2u) { pending2 = v; has2 = true; }
#if BLUETILE_LANE_PIECES == 5
  if (at == 3u) { pending3 = v; has3 = true; }
  if (at == 4u) { pending4 = v; has4 = true; }
#endif
}
#define COMMIT(s)                                          \
  if (has##s) {                                            \
    atomicAdd(sums[kept_site##s].piece_area, pending##s.x);   \
    atomicAdd(sums[kept_site##s].piece_x, pending##s.y);      \
    atomicAdd(sums[kept_site##s].piece_y, pending##s.z);      \
    atomicAdd(sums[kept_site##s].piece_second, pending##s.w); \
  }

// Splits pixel `entry`; false where it goes to the host.
bool split_pixel(uvec2 entry) {
  const SceneFields scene = scene_fields(entry.x);
  pixel_size = scene.pixel_size;
  domain_size = scene.domain_size;
  const dvec2 bucket_size = scene.bucket_size;
  const double reach_limit = scene.reach_limit;
  const int j = floor_division(int(entry.y), scene.size.x), i = int(entry.y) - j * scene.size.x;
  const ivec2 ij = ivec2(i, j);
  // The sample's lattice point: the walks measure every site from it (as site_from_sample).
  precise const dvec2 lattice = dvec2(ij) * pixel_size;
  const dvec2 half_pixel = 0.5 * pixel_size;
  precise const double diagonal = sqrt(pixel_size.x * pixel_size.x + pixel_size.y * pixel_size.y) * (1.0 + 1.0 / 65536.0);

  // Reach from the corner owners (any site's distance bounds the nearest one's).
  double nearest = 1e30;
  for (int corner = 0; corner < 4; ++corner) {
    const ivec2 at = ivec2(wrap_index(i + (corner & 1), scene.size.x), wrap_index(j + (corner >> 1), scene.size.y));
    const uint id = imageLoad(id_image, scene.origin + at).x;
    if (id == 0u) continue;
    precise dvec2 o = site_from_sample(id - 1u, ij) - half_pixel;
    o = dvec2(wrap_axis(o.x, domain_size.x), wrap_axis(o.y, domain_size.y));
    precise double d = sqrt(o.x * o.x + o.y * o.y);
    nearest = min(nearest, d);
  }
  if (nearest >= 1e30) return true;  // uncovered: this pass is redone
  precise const double reach = nearest + diagonal;

  // The grid window that holds every site within reach of the centre, periodic images included.
  const dvec2 centre = (dvec2(ij) + 0.5) * pixel_size;
  const ivec2 lo = ivec2(floor((centre - reach) / bucket_size)), hi = ivec2(floor((centre + reach) / bucket_size));
  if (hi.x - lo.x >= BLUETILE_MAX_WINDOW || hi.y - lo.y >= BLUETILE_MAX_WINDOW) return false;
  const int columns = scene.grid_size.x, rows = scene.grid_size.y;
  const uint site_list = scene.grid_offset + uint(columns * rows) + 1u;
  // The window's first bucket (column cx0, row cy0) and its periodic image (wx0, wy0); the walks
  // step both along, without a division per bucket.
  const int wx0 = floor_division(lo.x, columns), wy0 = floor_division(lo.y, rows);
  const int cx0 = lo.x - wx0 * columns, cy0 = lo.y - wy0 * rows;

  // First walk: the candidates within reach are counted, the nearest (the first of equals) kept.
  uint count = 0u, nearest_index = 0u, nearest_entry = site_list;
  ivec2 nearest_image = ivec2(0);
  double nearest2 = 1e30;
  for (int by = lo.y, wy = wy0, cy = cy0; by <= hi.y; ++by, cy = cy + 1 == rows ? 0 : cy + 1, wy += cy == 0 ? 1 : 0) {
    const uint row = scene.grid_offset + uint(cy * columns);
    for (int bx = lo.x, wx = wx0, cx = cx0; bx <= hi.x; ++bx, cx = cx + 1 == columns ? 0 : cx + 1, wx += cx == 0 ? 1 : 0) {
      const uint bucket = row + uint(cx);
      const uint last = grid_word(bucket + 1u);
      for (uint s = grid_word(bucket); s < last; ++s) {
        precise dvec2 o = ((list_position(site_list + s) - lattice) - half_pixel) + dvec2(wx, wy) * domain_size;
        precise double d2 = o.x * o.x + o.y * o.y;
        if (d2 > reach * reach) continue;
        if (count == 0u || d2 < nearest2) {
          nearest2 = d2;
          nearest_index = count;
          nearest_entry = site_list + s;
          nearest_image = ivec2(wx, wy);
        }
        ++count;
      }
    }
  }
  if (count > uint(BLUETILE_MAX_CANDIDATES)) return false;
  if (count == 0u) return true;

  // Second walk: only sites within (nearest + diagonal) of the centre can be nearest somewhere in
  // the pixel, and of those only the ones nearer than the nearest, s0, at some corner.
  precise const double reach0 = sqrt(nearest2) + diagonal;
  const uint nearest_site = scene.site_begin + grid_word(nearest_entry);
  const dvec2 s0_position = position(nearest_site);
  precise const dvec2 corner0 = -(site_from_sample(nearest_site, ij) + dvec2(nearest_image) * domain_size);
  uint c = 0u, kept = 0u;
  bool beyond = false;
  // The walk keeps grid words (list entries); their site indices are fetched once after it.
  kept_site0 = kept_site1 = kept_site2 = kept_site3 = kept_site4 = site_list;
  for (int by = lo.y, wy = wy0, cy = cy0; by <= hi.y; ++by, cy = cy + 1 == rows ? 0 : cy + 1, wy += cy == 0 ? 1 : 0) {
    const uint row = scene.grid_offset + uint(cy * columns);
    for (int bx = lo.x, wx = wx0, cx = cx0; bx <= hi.x; ++bx, cx = cx + 1 == columns ? 0 : cx + 1, wx += cx == 0 ? 1 : 0) {
      const uint bucket = row + uint(cx);
      const uint last = grid_word(bucket + 1u);
      for (uint s = grid_word(bucket); s < last; ++s) {
        const dvec2 p = list_position(site_list + s);
        precise dvec2 o = ((p - lattice) - half_pixel) + dvec2(wx, wy) * domain_size;
        precise double d2 = o.x * o.x + o.y * o.y;
        if (d2 > reach * reach) continue;
        const uint here = c++;
        if (d2 > reach0 * reach0) continue;
        if (here != nearest_index) {
          precise dvec2 between = p - s0_position;
          precise dvec2 d = between + dvec2(ivec2(wx, wy) - nearest_image) * domain_size;
          precise double offset = 0.5 * (d.x * d.x + d.y * d.y);
          bool nearer_somewhere = false;
          for (int corner = 0; corner < 4; ++corner) {
            precise dvec2 q = corner0 + dvec2(corner & 1, corner >> 1) * pixel_size;
            precise double side = q.x * d.x + q.y * d.y - offset;
            nearer_somewhere = nearer_somewhere || side > 0.0;
          }
          if (!nearer_somewhere) continue;
        }
        precise double distance = sqrt(o.x * o.x + o.y * o.y);
        beyond = beyond || distance + diagonal > reach_limit;
        keep_candidate(kept, site_list + s, uint(wx + 32768) | (uint(wy + 32768) << 16));
        ++kept;
      }
    }
  }
  // The bounds the host reference applies too (scene.max_pieces is this kernel's slot count).
  if (kept > scene.max_pieces || kept > uint(BLUETILE_LANE_PIECES) || beyond) return false;
  kept_site0 = scene.site_begin + grid_word(kept_site0);
  kept_site1 = scene.site_begin + grid_word(kept_site1);
  kept_site2 = scene.site_begin + grid_word(kept_site2);
#if BLUETILE_LANE_PIECES == 5
  kept_site3 = scene.site_begin + grid_word(kept_site3);
  kept_site4 = scene.site_begin + grid_word(kept_site4);
#endif

  const double scale_area = scene.scale_area, scale_first = scene.scale_first, scale_second = scene.scale_second;
  has0 = has1 = has2 = has3 = has4 = false;
  clip_lost = false;
  const bool force_here = scene.guard_test != 0u && (entry.y & scene.guard_test) == scene.guard_test;
  for (uint a = 0u; a < kept; ++a) {
    const uint owner = kept_site(a);
    if ((site_flags(owner) & BLUETILE_SITE_WANTED) == 0u) continue;
    const ivec2 owner_image = kept_image(a);
    const dvec2 owner_position = position(owner);
    // The pixel square relative to this image of the owner.
    precise const dvec2 corner = -(site_from_sample(owner, ij) + dvec2(owner_image) * domain_size);
    polygon[0] = corner;
    polygon[1] = corner + dvec2(pixel_size.x, 0.0);
    polygon[2] = corner + pixel_size;
    polygon[3] = corner + dvec2(0.0, pixel_size.y);
    for (int k = 4; k < MAX_VERTICES; ++k) polygon[k] = dvec2(0.0);
    vertex_count = 4;
    max_radius_squared = 0.0;
    for (int v = 0; v < 4; ++v) {
      precise double r2 = polygon[v].x * polygon[v].x + polygon[v].y * polygon[v].y;
      max_radius_squared = max(max_radius_squared, r2);
    }
    // The others in the host's order, a skipped without a pass of its own (lavapipe would run
    // the pass's whole body under a mask).
    force_guard = force_here && a + 1u == kept;  // the last piece: the others' sums are held
    for (uint other = 1u; other < kept && vertex_count >= 3; ++other) {
      const uint b = other <= a ? other - 1u : other;
      precise dvec2 between = position(kept_site(b)) - owner_position;
      precise dvec2 d = between + dvec2(kept_image(b) - owner_image) * domain_size;
      if (d.x == 0.0 && d.y == 0.0) continue;
      clip_by_bisector(d);
    }
    if (clip_lost) {
      atomicAdd(counters[BLUETILE_COUNTER_GUARD], 1u);
      return false;
    }
    if (vertex_count < 3) continue;
    precise double cross_sum = 0.0, x_sum = 0.0, y_sum = 0.0, xx_sum = 0.0, yy_sum = 0.0;
    dvec2 p = polygon[0];
    for (int k = 1; k < MAX_VERTICES; ++k)
      if (k == vertex_count - 1) p = polygon[k];
    for (int k = 0; k < MAX_VERTICES; ++k) {
      if (k >= vertex_count) continue;
      const dvec2 q = polygon[k];
      precise double cross = p.x * q.y - q.x * p.y;
      cross_sum += cross;
      x_sum += (p.x + q.x) * cross;
      y_sum += (p.y + q.y) * cross;
      xx_sum += (p.x * p.x + p.x * q.x + q.x * q.x) * cross;
      yy_sum += (p.y * p.y + p.y * q.y + q.y * q.y) * cross;
      p = q;
    }
    precise double piece_area = 0.5 * cross_sum;
    if (!(piece_area > 0.0)) continue;
    precise double first_x = x_sum / 6.0, first_y = y_sum / 6.0, second = (xx_sum + yy_sum) / 12.0;
    hold_piece(a, i64vec4(fixed_point(piece_area, scale_area), fixed_point(first_x, scale_first),
                          fixed_point(first_y, scale_first), fixed_point(second, scale_second)));
  }
  COMMIT(0) COMMIT(1) COMMIT(2)
#if BLUETILE_LANE_PIECES == 5
  COMMIT(3) COMMIT(4)
#endif
  return true;
}

void main() {
  const uint k = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * BLUETILE_SPLIT_GROUP + gl_LocalInvocationID.x;
  if (k >= counters[BLUETILE_COUNTER_BOUNDARY]) return;
  const uvec2 entry = boundary[k];
  if (!split_pixel(entry)) {
    const uint at = atomicAdd(counters[BLUETILE_COUNTER_OVERFLOW], 1u);
    overflow[at] = entry;
  }
}
