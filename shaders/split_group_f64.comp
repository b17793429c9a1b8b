// split_group_f64.comp: the exact float64 split of boundary pixels (as split_body.glsl computes
// it, bit for bit) shaped for SIMD CPU devices: one pixel at a time per group of
// BLUETILE_SPLIT_LANES invocations (one subgroup), never one pixel per invocation.
//
// On lavapipe every load or store whose address differs between lanes is a loop over the lanes,
// and a private array indexed by a variable becomes a ladder of selects; a kernel with one pixel
// per lane is made of both (docs/BENCHMARKS.md, "Every stage, host and device pixel work side by
// side"). Here the pixel, its scene, its corners and its grid window are the same in every lane;
// the lanes share the window's sites (lane l takes every BLUETILE_SPLIT_LANES-th one), so every
// per-lane load does useful work; candidates stay in registers, candidate c in lane c % LANES
// (two slots), ordered as the window lists them, and move between lanes by subgroup shuffles;
// then lane a clips candidate a's piece by the bisectors with every other candidate (the loop
// over the others is the same in every lane), its polygon in registers: a fixed number of
// vertex slots, every index a constant once the compiler unrolls the loops over them. A pixel
// with more than BLUETILE_MAX_PIECES candidates left after pruning (a polygon that could outgrow
// the slots) goes to the host, as one with more than BLUETILE_MAX_CANDIDATES does.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#extension GL_KHR_shader_subgroup_basic : require
#extension GL_KHR_shader_subgroup_ballot : require
#extension GL_KHR_shader_subgroup_shuffle : require
#extension GL_KHR_shader_subgroup_arithmetic : require
#include "raster_common.glsl"

layout(local_size_x = BLUETILE_SPLIT_LANES) in;
layout(binding = BLUETILE_BINDING_ID_IMAGE, r32ui) uniform readonly uimage2D id_image;
layout(binding = BLUETILE_BINDING_POSITION_TEXELS) uniform usamplerBuffer position_texels;
layout(binding = BLUETILE_BINDING_GRID_TEXELS) uniform usamplerBuffer grid_texels;

#define LANES BLUETILE_SPLIT_LANES
// Four corners and at most one vertex more per clip by the other BLUETILE_MAX_PIECES - 1.
#define MAX_VERTICES (3 + BLUETILE_MAX_PIECES)
#if MAX_VERTICES != 8
#error "clip_by_bisector spells out eight CLIP_STEPs"
#endif

SceneInfo scene;
dvec2 pixel_size, domain_size;

double unpack_real(uvec2 bits) { return packDouble2x32(bits); }
dvec2 unpack_real2(uvec2 bits[2]) { return dvec2(unpack_real(bits[0]), unpack_real(bits[1])); }
dvec2 position(uint g) {
  uvec4 p = texelFetch(position_texels, int(g));
  return dvec2(unpack_real(p.xy), unpack_real(p.zw));
}
uint grid_word(uint k) { return texelFetch(grid_texels, int(k)).x; }
// Site g relative to sample (i, j), domain units (as split_body.glsl).
dvec2 site_from_sample(uint g, ivec2 ij) {
  precise dvec2 lattice = dvec2(ij) * pixel_size;
  precise dvec2 o = position(g) - lattice;
  return o;
}

uint id_at(int i, int j) {
  return imageLoad(id_image, scene.origin + ivec2(wrap_index(i, scene.size.x), wrap_index(j, scene.size.y))).x;
}

// floor(a / n) for n > 0 (SiteGrid::wrap_count), without integer division, which lavapipe runs
// lane by lane: the floor of the double quotient, off by at most one, corrected.
int floor_division(int a, int n) {
  int q = int(floor(double(a) / double(n)));
  q -= a - q * n < 0 ? 1 : 0;
  q += a - q * n >= n ? 1 : 0;
  return q;
}

double wrap_axis(double d, double period) { return d < -0.5 * period ? d + period : (d >= 0.5 * period ? d - period : d); }

// The rank-th set bit of the low `bits` bits of mask (rank below their count), 0 if none: a
// loop of constant length, unrolled by the compiler (a loop of variable length is a masked loop
// on lavapipe, costly per iteration).
uint nth_bit(uint mask, uint rank, const uint bits) {
  uint seen = 0u, at = 0u;
  for (uint p = 0u; p < bits; ++p) {
    const uint bit = (mask >> p) & 1u;
    at = bit != 0u && seen == rank ? p : at;
    seen += bit;
  }
  return at;
}

// This lane's piece: vertices [0, vertex_count) relative to its owner.
dvec2 polygon[MAX_VERTICES];
int vertex_count;
double max_radius_squared;

// Vertex k of the clip, as ConvexPolygon::clip's edge (k - 1) -> k: before it at most k + 1
// vertices are out (a convex polygon's sides change sign at most twice, and only the entering
// crossing adds two), so slot m is sought among the first k + 2 only: a constant bound once k is
// a literal, so every slot index is a constant after unrolling.
#define CLIP_STEP(k)                                                              \
  if ((k) < vertex_count) {                                                       \
    const dvec2 pk = polygon[k];                                                  \
    const double sk = side[k];                                                    \
    if ((sl < 0.0 && sk > 0.0) || (sl > 0.0 && sk < 0.0)) {                       \
      precise double t = sl / (sl - sk);                                          \
      precise dvec2 x = pl + t * (pk - pl);                                       \
      for (int j = 0; j <= min((k) + 1, MAX_VERTICES - 1); ++j)                   \
        if (j == m) clipped[j] = x;                                               \
      ++m;                                                                        \
      precise double r2 = x.x * x.x + x.y * x.y;                                  \
      radius_squared = max(radius_squared, r2);                                   \
    }                                                                             \
    if (sk <= 0.0) {                                                              \
      for (int j = 0; j <= min((k) + 1, MAX_VERTICES - 1); ++j)                   \
        if (j == m) clipped[j] = pk;                                              \
      ++m;                                                                        \
      precise double r2 = pk.x * pk.x + pk.y * pk.y;                              \
      radius_squared = max(radius_squared, r2);                                   \
    }                                                                             \
    pl = pk;                                                                      \
    sl = sk;                                                                      \
  }

// ConvexPolygon::clip_by_bisector on the registers of this lane (same arithmetic, same order).
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
  dvec2 pl = polygon[0];
  double sl = side[0];
  for (int k = 1; k < MAX_VERTICES; ++k) {
    if (k == vertex_count - 1) {
      pl = polygon[k];
      sl = side[k];
    }
  }
  dvec2 clipped[MAX_VERTICES];
  for (int k = 0; k < MAX_VERTICES; ++k) clipped[k] = dvec2(0.0);
  int m = 0;
  precise double radius_squared = 0.0;
  CLIP_STEP(0) CLIP_STEP(1) CLIP_STEP(2) CLIP_STEP(3) CLIP_STEP(4) CLIP_STEP(5) CLIP_STEP(6) CLIP_STEP(7)
  for (int k = 0; k < MAX_VERTICES; ++k) polygon[k] = clipped[k];
  vertex_count = m;
  max_radius_squared = radius_squared;
}

int64_t fixed_point(double v, double scale) {
  precise double scaled = floor(v * scale + 0.5);
  return int64_t(scaled);
}

void push_overflow(uvec2 entry) {
  if (gl_SubgroupInvocationID == 0u) {
    uint k = atomicAdd(counters[BLUETILE_COUNTER_OVERFLOW], 1u);
    overflow[k] = entry;
  }
}

// One pixel, the same in every lane; false where it goes to the host.
bool split_pixel(uvec2 entry, uint lane) {
  scene = scenes[entry.x];
  pixel_size = unpack_real2(scene.pixel_size64);
  domain_size = unpack_real2(scene.domain_size64);
  const dvec2 bucket_size = unpack_real2(scene.bucket_size64);
  const double reach_limit = unpack_real(scene.reach_limit64);
  const int j = floor_division(int(entry.y), scene.size.x), i = int(entry.y) - j * scene.size.x;
  const ivec2 ij = ivec2(i, j);
  const dvec2 half_pixel = 0.5 * pixel_size;
  precise const double diagonal = sqrt(pixel_size.x * pixel_size.x + pixel_size.y * pixel_size.y) * (1.0 + 1.0 / 65536.0);

  // Reach from the corner owners, one corner per lane.
  double nearest = 1e30;
  if (lane < 4u) {
    uint id = id_at(i + int(lane & 1u), j + int(lane >> 1));
    if (id != 0u) {
      precise dvec2 o = site_from_sample(id - 1u, ij) - half_pixel;
      o = dvec2(wrap_axis(o.x, domain_size.x), wrap_axis(o.y, domain_size.y));
      precise double d = sqrt(o.x * o.x + o.y * o.y);
      nearest = d;
    }
  }
  nearest = subgroupMin(nearest);
  if (nearest >= 1e30) return true;  // uncovered: this pass is redone
  precise double reach = nearest + diagonal;

  const dvec2 centre = (dvec2(ij) + 0.5) * pixel_size;
  const ivec2 lo = ivec2(floor((centre - reach) / bucket_size)), hi = ivec2(floor((centre + reach) / bucket_size));
  if (hi.x - lo.x >= BLUETILE_MAX_WINDOW || hi.y - lo.y >= BLUETILE_MAX_WINDOW) return false;

  // Candidates c and LANES + c of the window's order in this lane's two slots, as their place
  // in the scene's site list and their periodic image: 32-bit values, which lavapipe shuffles
  // in one instruction (64-bit ones take a loop over the lanes).
  uint slot0 = 0u, slot1 = 0u, image_bits0 = 0u, image_bits1 = 0u;
  uint count = 0u;
  const int columns = scene.grid_size.x, rows = scene.grid_size.y;
  const uint site_list = scene.grid_offset + uint(columns * rows) + 1u;
  for (int by = lo.y; by <= hi.y; ++by) {
    const int wy = floor_division(by, rows);
    const uint row = scene.grid_offset + uint((by - wy * rows) * columns);
    // A run of buckets in one periodic image is one stretch of the site list.
    for (int bx = lo.x; bx <= hi.x;) {
      const int wx = floor_division(bx, columns);
      const int run_end = min(hi.x, (wx + 1) * columns - 1);
      const uint first = grid_word(row + uint(bx - wx * columns)), last = grid_word(row + uint(run_end - wx * columns) + 1u);
      const dvec2 image_shift = dvec2(wx, wy) * domain_size;
      const uint image_bits = uint(wx + 32768) | (uint(wy + 32768) << 16);
      for (uint base = first; base < last; base += LANES) {
        const uint s = base + lane;
        bool passes = false;
        if (s < last) {
          const uint g = scene.site_begin + grid_word(site_list + s);
          precise dvec2 o = (site_from_sample(g, ij) - half_pixel) + image_shift;
          precise double d2 = o.x * o.x + o.y * o.y;
          passes = d2 <= reach * reach;
        }
        const uint mask = subgroupBallot(passes).x;
        const uint added = uint(bitCount(mask));
        if (count + added > uint(BLUETILE_MAX_CANDIDATES)) return false;
        // Slot k of this lane takes candidate k LANES + lane: the rank-th new one.
        const int rank0 = int(lane) - int(count), rank1 = int(lane + LANES) - int(count);
        const uint from0 = nth_bit(mask, uint(clamp(rank0, 0, LANES - 1)), LANES), from1 = nth_bit(mask, uint(clamp(rank1, 0, LANES - 1)), LANES);
        const uint s0 = subgroupShuffle(s, from0), s1 = subgroupShuffle(s, from1);
        if (rank0 >= 0 && rank0 < int(added)) {
          slot0 = s0;
          image_bits0 = image_bits;
        }
        if (rank1 >= 0 && rank1 < int(added)) {
          slot1 = s1;
          image_bits1 = image_bits;
        }
        count += added;
      }
      bx = run_end + 1;
    }
  }
  if (count == 0u) return true;
  // Each lane's candidates again from their places (the same arithmetic, the same bits).
  uint site0 = 0u, site1 = 0u;
  ivec2 image0 = ivec2(0), image1 = ivec2(0);
  dvec2 position0 = dvec2(0.0), position1 = dvec2(0.0), offset0 = dvec2(0.0), offset1 = dvec2(0.0);
  double distance0 = 1e30, distance1 = 1e30;
  if (lane < count) {
    site0 = scene.site_begin + grid_word(site_list + slot0);
    image0 = ivec2(int(image_bits0 & 0xffffu) - 32768, int(image_bits0 >> 16) - 32768);
    position0 = position(site0);
    precise dvec2 lattice = dvec2(ij) * pixel_size;
    precise dvec2 o = ((position0 - lattice) - half_pixel) + dvec2(image0) * domain_size;
    precise double d2 = o.x * o.x + o.y * o.y;
    offset0 = o;
    distance0 = d2;
  }
  if (lane + LANES < count) {
    site1 = scene.site_begin + grid_word(site_list + slot1);
    image1 = ivec2(int(image_bits1 & 0xffffu) - 32768, int(image_bits1 >> 16) - 32768);
    position1 = position(site1);
    precise dvec2 lattice = dvec2(ij) * pixel_size;
    precise dvec2 o = ((position1 - lattice) - half_pixel) + dvec2(image1) * domain_size;
    precise double d2 = o.x * o.x + o.y * o.y;
    offset1 = o;
    distance1 = d2;
  }
  // The nearest candidate, the first of equals.
  const double nearest2 = subgroupMin(min(distance0, distance1));
  const uint nearest_index = subgroupMin(min(distance0 == nearest2 ? lane : 64u, distance1 == nearest2 ? lane + LANES : 64u));
  reach = sqrt(nearest2) + diagonal;
  const uint nearest_lane = nearest_index % LANES;
  const uint n0 = subgroupShuffle(site0, nearest_lane), n1 = subgroupShuffle(site1, nearest_lane);
  const ivec2 m0 = subgroupShuffle(image0, nearest_lane), m1 = subgroupShuffle(image1, nearest_lane);
  const uint s0 = nearest_index < LANES ? n0 : n1;
  const ivec2 s0_image = nearest_index < LANES ? m0 : m1;
  const dvec2 s0_position = position(s0);
  precise const dvec2 corner0 = -(site_from_sample(s0, ij) + dvec2(s0_image) * domain_size);

  // Pruning, both slots of every lane at once: a candidate owns or cuts a piece only if it is
  // nearer than s0 at some corner (the distance difference is affine over the pixel).
  bool keep[2];
  for (int slot = 0; slot < 2; ++slot) {
    const uint c = lane + uint(slot) * LANES;
    const dvec2 site_position = slot == 0 ? position0 : position1;
    const ivec2 image = slot == 0 ? image0 : image1;
    const double distance = slot == 0 ? distance0 : distance1;
    bool kept = c < count && distance <= reach * reach;
    if (kept && c != nearest_index) {
      precise dvec2 between = site_position - s0_position;
      precise dvec2 d = between + dvec2(image - s0_image) * domain_size;
      precise double offset = 0.5 * (d.x * d.x + d.y * d.y);
      bool nearer_somewhere = false;
      for (int corner = 0; corner < 4; ++corner) {
        precise dvec2 p = corner0 + dvec2(corner & 1, corner >> 1) * pixel_size;
        precise double side = p.x * d.x + p.y * d.y - offset;
        nearer_somewhere = nearer_somewhere || side > 0.0;
      }
      kept = nearer_somewhere;
    }
    keep[slot] = kept;
  }
  // Any kept candidate beyond the fixed-point reach sends the pixel to the host.
  bool beyond = false;
  if (keep[0]) {
    precise double d = sqrt(offset0.x * offset0.x + offset0.y * offset0.y);
    beyond = beyond || d + diagonal > reach_limit;
  }
  if (keep[1]) {
    precise double d = sqrt(offset1.x * offset1.x + offset1.y * offset1.y);
    beyond = beyond || d + diagonal > reach_limit;
  }
  if (subgroupBallot(beyond).x != 0u) return false;
  const uint kept_mask = subgroupBallot(keep[0]).x | (subgroupBallot(keep[1]).x << LANES);
  const uint kept = uint(bitCount(kept_mask));
  if (kept > uint(BLUETILE_MAX_PIECES)) return false;
  // Kept candidate a (in the window's order) to lane a.
  const uint from = nth_bit(kept_mask, min(lane, kept - 1u), 2 * LANES);
  const uint k0 = subgroupShuffle(site0, from % LANES), k1 = subgroupShuffle(site1, from % LANES);
  const ivec2 i0 = subgroupShuffle(image0, from % LANES), i1 = subgroupShuffle(image1, from % LANES);
  const uint owner = from < LANES ? k0 : k1;
  const ivec2 owner_image = from < LANES ? i0 : i1;

  // Lane a: the piece of candidate a, clipped by the bisectors with the others in order.
  const bool owns = lane < kept && (sites[owner].flags & BLUETILE_SITE_WANTED) != 0u;
  const dvec2 owner_position = position(owner);
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
  for (uint b = 0u; b < kept; ++b) {
    const uint other = subgroupShuffle(owner, b);
    const ivec2 other_image = subgroupShuffle(owner_image, b);
    const dvec2 other_position = position(other);
    precise dvec2 between = other_position - owner_position;
    precise dvec2 d = between + dvec2(other_image - owner_image) * domain_size;
    if (owns && b != lane && vertex_count >= 3 && !(d.x == 0.0 && d.y == 0.0)) clip_by_bisector(d);
  }
  if (!owns || vertex_count < 3) return true;
  precise double cross_sum = 0.0, x_sum = 0.0, y_sum = 0.0, xx_sum = 0.0, yy_sum = 0.0;
  dvec2 p = polygon[0];
  for (int k = 1; k < MAX_VERTICES; ++k)
    if (k == vertex_count - 1) p = polygon[k];
  for (int k = 0; k < MAX_VERTICES; ++k) {
    if (k >= vertex_count) continue;
    const dvec2 q = polygon[k];
    precise double c = p.x * q.y - q.x * p.y;
    cross_sum += c;
    x_sum += (p.x + q.x) * c;
    y_sum += (p.y + q.y) * c;
    xx_sum += (p.x * p.x + p.x * q.x + q.x * q.x) * c;
    yy_sum += (p.y * p.y + p.y * q.y + q.y * q.y) * c;
    p = q;
  }
  precise double piece_area = 0.5 * cross_sum;
  if (!(piece_area > 0.0)) return true;
  const double scale_area = unpack_real(scene.scale64[0]), scale_first = unpack_real(scene.scale64[1]),
               scale_second = unpack_real(scene.scale64[2]);
  atomicAdd(sums[owner].piece_area, fixed_point(piece_area, scale_area));
  precise double first_x = x_sum / 6.0, first_y = y_sum / 6.0, second = (xx_sum + yy_sum) / 12.0;
  atomicAdd(sums[owner].piece_x, fixed_point(first_x, scale_first));
  atomicAdd(sums[owner].piece_y, fixed_point(first_y, scale_first));
  atomicAdd(sums[owner].piece_second, fixed_point(second, scale_second));
  return true;
}

void main() {
  // A workgroup takes the BLUETILE_SPLIT_GROUP pixels split_body.glsl's would, one after another
  // (the same indirect dispatch); the bound is read, so no compiler unrolls the loop.
  const uint group = gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x;
  const uint begin = group * BLUETILE_SPLIT_GROUP;
  const uint end = min(begin + BLUETILE_SPLIT_GROUP, counters[BLUETILE_COUNTER_BOUNDARY]);
  const uint lane = gl_SubgroupInvocationID;
  for (uint k = begin; k < end; ++k) {
    const uvec2 entry = boundary[k];
    if (!split_pixel(entry, lane)) push_overflow(entry);
  }
}
