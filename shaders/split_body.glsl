// split_body.glsl: the exact split of boundary pixels, included by split_f64.comp (double
// precision, the default where the device has shaderFloat64) and split_f32.comp (single
// precision, for devices without it; its error is measured in docs/RASTER.md).
//
// One invocation per pixel listed by classify.comp. The sites that can own part of the pixel are
// found without trusting the ID image: a site t owns a point q of the pixel only if
// |t - centre| <= |t - q| + diag/2 <= |s - q| + diag/2 <= |s - centre| + diag for any site s,
// so every site within (distance of the nearest corner owner to the centre + pixel diagonal)
// is gathered from the scene's site grid, then those beyond (nearest + diagonal) are dropped.
// For each wanted candidate the pixel square, relative to that site, is clipped by its bisectors
// with the others (the pieces partition the pixel), and the piece's area, first and second
// moments go to its site as fixed-point integers (64-bit atomics: order-independent sums).
// Pixels with more candidates or a wider grid window than the bounds below, or a piece too far
// from its site for the fixed-point range, are left to the host (overflow list), which splits
// them with the same arithmetic (src/bluetile/voronoi/raster_reference.cpp).
// Where a density map weights the cells, the weight of a piece is the integral of the density
// over it: multiply its moments here (per-texel density: clip by texel edges first).
#extension GL_EXT_shader_atomic_int64 : require
#include "raster_common.glsl"

layout(local_size_x = BLUETILE_SPLIT_GROUP) in;
layout(binding = BLUETILE_BINDING_ID_IMAGE, r32ui) uniform readonly uimage2D id_image;

SceneInfo scene;
real2 pixel_size, domain_size;

#if BLUETILE_SPLIT_FLOAT64
real unpack_real(uvec2 bits) { return packDouble2x32(bits); }
real2 unpack_real2(uvec2 bits[2]) { return real2(unpack_real(bits[0]), unpack_real(bits[1])); }
real2 position(uint g) { uvec4 p = positions[g]; return real2(unpack_real(p.xy), unpack_real(p.zw)); }
// Site g relative to sample (i, j) (both inside the domain), domain units.
real2 site_from_sample(uint g, ivec2 ij) {
  precise real2 lattice = real2(ij) * pixel_size;
  precise real2 o = position(g) - lattice;
  return o;
}
// Site b relative to site a (same periodic image), domain units: exact for close sites.
real2 site_from_site(uint a, uint b) {
  precise real2 o = position(b) - position(a);
  return o;
}
#else
// Positions as (pixel, fraction): a 24-bit fixed-point fraction of a pixel, so differences of
// close sites keep their digits (plain float coordinates lose them near 1).
real2 site_from_sample(uint g, ivec2 ij) {
  SiteInfo s = sites[g];
  return (real2(s.pixel - ij) + s.fraction) * pixel_size;
}
real2 site_from_site(uint a, uint b) {
  SiteInfo sa = sites[a], sb = sites[b];
  return (real2(sb.pixel - sa.pixel) + (sb.fraction - sa.fraction)) * pixel_size;
}
#endif

uint id_at(int i, int j) {
  return imageLoad(id_image, scene.origin + ivec2(wrap_index(i, scene.size.x), wrap_index(j, scene.size.y))).x;
}

// floor(a / n) for the periodic image of bucket index a (as SiteGrid::wrap_count).
int wrap_count(int a, int n) { return a >= 0 ? (a < n ? 0 : a / n) : (a >= -n ? -1 : -((-a + n - 1) / n)); }

real wrap_axis(real d, real period) { return d < -0.5 * period ? d + period : (d >= 0.5 * period ? d - period : d); }

// Candidates of the current pixel: global site index, periodic image (whole periods), offset
// from the pixel centre and its squared length; then the clipped polygon, relative to its owner
// (two buffers, clipped from one into the other). In shared memory, each invocation its own
// slice: lavapipe turns a private array indexed by a variable into a ladder of selects and
// unrolls every loop over one, running all copies under a mask (about 11 us per pixel).
#define MAX_VERTICES (4 + BLUETILE_MAX_CANDIDATES)
shared uint candidate_site_s[BLUETILE_SPLIT_GROUP * BLUETILE_MAX_CANDIDATES];
shared ivec2 candidate_image_s[BLUETILE_SPLIT_GROUP * BLUETILE_MAX_CANDIDATES];
shared real2 candidate_offset_s[BLUETILE_SPLIT_GROUP * BLUETILE_MAX_CANDIDATES];
shared real candidate_distance_s[BLUETILE_SPLIT_GROUP * BLUETILE_MAX_CANDIDATES];
shared real2 polygon_s[BLUETILE_SPLIT_GROUP * 2 * MAX_VERTICES];
uint candidate_base, polygon_base, clipped_base;
#define candidate_site(c) candidate_site_s[candidate_base + uint(c)]
#define candidate_image(c) candidate_image_s[candidate_base + uint(c)]
#define candidate_offset(c) candidate_offset_s[candidate_base + uint(c)]
#define candidate_distance(c) candidate_distance_s[candidate_base + uint(c)]
#define polygon(k) polygon_s[polygon_base + uint(k)]
#define clipped(k) polygon_s[clipped_base + uint(k)]
int vertex_count;
real max_radius_squared;

// Keeps the part of the polygon closer to the origin than to d (ConvexPolygon::clip_by_bisector).
void clip_by_bisector(real2 d) {
  precise real dd = d.x * d.x + d.y * d.y;
  if (dd >= 4.0 * max_radius_squared) return;
  precise real offset = 0.5 * dd;
  bool any_outside = false;
  for (int k = 0; k < vertex_count; ++k) {
    const real2 p = polygon(k);
    precise real s = p.x * d.x + p.y * d.y - offset;
    any_outside = any_outside || s > 0.0;
  }
  if (!any_outside) return;
  // Second pass: the side of each vertex recomputed (the same arithmetic, so the same bits)
  // and the previous vertex carried along, so each vertex is read once per pass.
  int m = 0;
  precise real radius_squared = 0.0;
  real2 pl = polygon(vertex_count - 1);
  precise real sl = pl.x * d.x + pl.y * d.y - offset;
  for (int k = 0; k < vertex_count; ++k) {
    const real2 pk = polygon(k);
    precise real sk = pk.x * d.x + pk.y * d.y - offset;
    if ((sl < 0.0 && sk > 0.0) || (sl > 0.0 && sk < 0.0)) {
      precise real t = sl / (sl - sk);
      precise real2 x = pl + t * (pk - pl);
      clipped(m++) = x;
      radius_squared = max(radius_squared, x.x * x.x + x.y * x.y);
    }
    if (sk <= 0.0) {
      clipped(m++) = pk;
      radius_squared = max(radius_squared, pk.x * pk.x + pk.y * pk.y);
    }
    pl = pk;
    sl = sk;
  }
  // The clipped polygon is the polygon now: swap the buffers.
  uint t = polygon_base;
  polygon_base = clipped_base;
  clipped_base = t;
  vertex_count = m;
  max_radius_squared = radius_squared;
}

int64_t fixed_point(real v, real scale) {
  precise real scaled = floor(v * scale + 0.5);
  return int64_t(scaled);
}

void push_overflow(uvec2 entry) {
  uint k = atomicAdd(counters[BLUETILE_COUNTER_OVERFLOW], 1u);
  overflow[k] = entry;
}

void main() {
  const uint k = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * BLUETILE_SPLIT_GROUP + gl_LocalInvocationID.x;
  candidate_base = gl_LocalInvocationID.x * uint(BLUETILE_MAX_CANDIDATES);
  polygon_base = gl_LocalInvocationID.x * uint(2 * MAX_VERTICES);
  clipped_base = polygon_base + uint(MAX_VERTICES);
  if (k >= counters[BLUETILE_COUNTER_BOUNDARY]) return;
  const uvec2 entry = boundary[k];
  scene = scenes[entry.x];
#if BLUETILE_SPLIT_FLOAT64
  pixel_size = unpack_real2(scene.pixel_size64);
  domain_size = unpack_real2(scene.domain_size64);
  const real2 bucket_size = unpack_real2(scene.bucket_size64);
  const real reach_limit = unpack_real(scene.reach_limit64);
  const real scale_area = unpack_real(scene.scale64[0]), scale_first = unpack_real(scene.scale64[1]),
             scale_second = unpack_real(scene.scale64[2]);
#else
  pixel_size = scene.pixel_size;
  domain_size = scene.domain_size;
  const real2 bucket_size = scene.bucket_size;
  const real reach_limit = scene.reach_limit;
  const real scale_area = scene.scale32.x, scale_first = scene.scale32.y, scale_second = scene.scale32_second;
#endif
  const int i = int(entry.y % uint(scene.size.x)), j = int(entry.y / uint(scene.size.x));
  const ivec2 ij = ivec2(i, j);
  const real2 half_pixel = 0.5 * pixel_size;
  precise const real diagonal = sqrt(pixel_size.x * pixel_size.x + pixel_size.y * pixel_size.y) * (1.0 + 1.0 / 65536.0);  // slack for rounding

  // Reach from the corner owners (any site's distance bounds the nearest one's).
  real nearest = 1e30;
  for (int corner = 0; corner < 4; ++corner) {
    uint id = id_at(i + (corner & 1), j + (corner >> 1));
    if (id == 0u) continue;
    precise real2 o = site_from_sample(id - 1u, ij) - half_pixel;
    o = real2(wrap_axis(o.x, domain_size.x), wrap_axis(o.y, domain_size.y));
    precise real d = sqrt(o.x * o.x + o.y * o.y);
    nearest = min(nearest, d);
  }
  if (nearest >= 1e30) return;  // uncovered: this pass is redone
  precise real reach = nearest + diagonal;

  // The grid window that holds every site within reach of the centre, periodic images included.
  const real2 centre = (real2(ij) + 0.5) * pixel_size;
  const ivec2 lo = ivec2(floor((centre - reach) / bucket_size)), hi = ivec2(floor((centre + reach) / bucket_size));
  if (hi.x - lo.x >= BLUETILE_MAX_WINDOW || hi.y - lo.y >= BLUETILE_MAX_WINDOW) {
    push_overflow(entry);
    return;
  }
  const uint columns = uint(scene.grid_size.x), rows = uint(scene.grid_size.y);
  int count = 0, nearest_index = 0;
  real nearest2 = 1e30;
  for (int by = lo.y; by <= hi.y; ++by) {
    int wy = wrap_count(by, int(rows));
    for (int bx = lo.x; bx <= hi.x; ++bx) {
      int wx = wrap_count(bx, int(columns));
      uint bucket = uint(by - wy * int(rows)) * columns + uint(bx - wx * int(columns));
      uint first = grid[scene.grid_offset + bucket], last = grid[scene.grid_offset + bucket + 1u];
      for (uint s = first; s < last; ++s) {
        uint g = scene.site_begin + grid[scene.grid_offset + columns * rows + 1u + s];
        precise real2 o = (site_from_sample(g, ij) - half_pixel) + real2(wx, wy) * domain_size;
        precise real d2 = o.x * o.x + o.y * o.y;
        if (d2 > reach * reach) continue;
        if (count == BLUETILE_MAX_CANDIDATES) {
          push_overflow(entry);
          return;
        }
        candidate_site(count) = g;
        candidate_image(count) = ivec2(wx, wy);
        candidate_offset(count) = o;
        candidate_distance(count) = d2;
        // The nearest so far (the first of equals), kept in registers.
        if (count == 0 || d2 < nearest2) {
          nearest2 = d2;
          nearest_index = count;
        }
        ++count;
      }
    }
  }
  // Only sites within (nearest + diagonal) of the centre can be nearest somewhere in the pixel.
  reach = sqrt(nearest2) + diagonal;
  // The nearest one, s0, owns part of the pixel; another site owns part of it only if it is
  // nearer than s0 at some corner (the distance difference is affine over the pixel), and one
  // that is not is never the nearest anywhere in it, so it cuts no piece either.
  const uint s0 = candidate_site(nearest_index);
  const ivec2 image0 = candidate_image(nearest_index);
  precise const real2 corner0 = -(site_from_sample(s0, ij) + real2(image0) * domain_size);
  int kept = 0;
  for (int c = 0; c < count; ++c) {
    if (candidate_distance(c) > reach * reach) continue;
    if (c != nearest_index) {
      precise real2 d = site_from_site(s0, candidate_site(c)) + real2(candidate_image(c) - image0) * domain_size;
      precise real offset = 0.5 * (d.x * d.x + d.y * d.y);
      bool nearer_somewhere = false;
      for (int corner = 0; corner < 4; ++corner) {
        precise real2 p = corner0 + real2(corner & 1, corner >> 1) * pixel_size;
        precise real side = p.x * d.x + p.y * d.y - offset;
        nearer_somewhere = nearer_somewhere || side > 0.0;
      }
      if (!nearer_somewhere) continue;
    }
    candidate_site(kept) = candidate_site(c);
    candidate_image(kept) = candidate_image(c);
    candidate_offset(kept) = candidate_offset(c);
    ++kept;
  }
  if (kept > int(scene.max_pieces)) {  // the bound the host reference applies too
    push_overflow(entry);
    return;
  }
  for (int c = 0; c < kept; ++c) {
    precise real2 o = candidate_offset(c);
    precise real d = sqrt(o.x * o.x + o.y * o.y);
    if (d + diagonal > reach_limit) {
      push_overflow(entry);
      return;
    }
  }

  for (int a = 0; a < kept; ++a) {
    const uint owner = candidate_site(a);
    if ((sites[owner].flags & BLUETILE_SITE_WANTED) == 0u) continue;
    // The pixel square relative to this image of the owner.
    precise const real2 corner = -(site_from_sample(owner, ij) + real2(candidate_image(a)) * domain_size);
    polygon(0) = corner;
    polygon(1) = corner + real2(pixel_size.x, 0.0);
    polygon(2) = corner + pixel_size;
    polygon(3) = corner + real2(0.0, pixel_size.y);
    vertex_count = 4;
    max_radius_squared = 0.0;
    for (int v = 0; v < 4; ++v) {
      precise real r2 = polygon(v).x * polygon(v).x + polygon(v).y * polygon(v).y;
      max_radius_squared = max(max_radius_squared, r2);
    }
    for (int b = 0; b < kept && vertex_count >= 3; ++b) {
      if (b == a) continue;
      precise real2 d = site_from_site(owner, candidate_site(b)) + real2(candidate_image(b) - candidate_image(a)) * domain_size;
      if (d.x == 0.0 && d.y == 0.0) continue;
      clip_by_bisector(d);
    }
    if (vertex_count < 3) continue;
    precise real cross_sum = 0.0, x_sum = 0.0, y_sum = 0.0, xx_sum = 0.0, yy_sum = 0.0;
    for (int v = 0, u = vertex_count - 1; v < vertex_count; u = v++) {
      precise real2 p = polygon(u), q = polygon(v);
      precise real c = p.x * q.y - q.x * p.y;
      cross_sum += c;
      x_sum += (p.x + q.x) * c;
      y_sum += (p.y + q.y) * c;
      xx_sum += (p.x * p.x + p.x * q.x + q.x * q.x) * c;
      yy_sum += (p.y * p.y + p.y * q.y + q.y * q.y) * c;
    }
    precise real piece_area = 0.5 * cross_sum;
    if (!(piece_area > 0.0)) continue;
    atomicAdd(sums[owner].piece_area, fixed_point(piece_area, scale_area));
    precise real first_x = x_sum / 6.0, first_y = y_sum / 6.0, second = (xx_sum + yy_sum) / 12.0;
    atomicAdd(sums[owner].piece_x, fixed_point(first_x, scale_first));
    atomicAdd(sums[owner].piece_y, fixed_point(first_y, scale_first));
    atomicAdd(sums[owner].piece_second, fixed_point(second, scale_second));
  }
}
