// classify.comp: reads the ID image once per pass and sums it per site. A workgroup takes a tile
// of BLUETILE_CLASSIFY_GROUP columns by BLUETILE_CLASSIFY_ROWS rows of one scene (z = scene);
// each invocation walks one column of it down, so neighbouring lanes do the same work on
// neighbouring pixels (a CPU device runs the lanes as SIMD vectors), and sums runs of equal IDs
// in registers, flushing each run with one set of 64-bit integer atomics: the sums are exact
// integers, so the same in any order and with any thread count (float atomics are not).
//  - Every sample counts for the site it shows (owned, farthest owned sample) and, in point
//    coverage, is a pixel of that site.
//  - Area coverage: pixel (i, j) spans samples (i, j) to (i + 1, j + 1). Voronoi cells are
//    convex, so when its four corners show one site a, its edges lie in a's cell, and any other
//    cell reaching into it lies strictly inside it, with its site: the pixel is whole unless a
//    site other than a lies in it (the site masks say). Whole pixels are summed here; every other
//    pixel is listed for split_f64/split_f32 (gathered in shared memory, one global atomic per
//    workgroup), which also get their indirect dispatch size here.
//  - Samples no cone reached are counted per scene: such a pass is redone, never accepted.
// Shaped for lavapipe too: no loop has a trip count the compiler could unroll (its SIMD code
// runs every unrolled copy and every branch under a mask) and no private array is indexed by a
// variable (lowered there to a ladder of selects); see docs/RASTER.md.
// The host reference (src/bluetile/voronoi/raster_reference.cpp) does the same sums.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#include "raster_common.glsl"

layout(local_size_x = BLUETILE_CLASSIFY_GROUP) in;
layout(binding = BLUETILE_BINDING_ID_IMAGE, r32ui) uniform readonly uimage2D id_image;

// Boundary pixels listed by each lane (lane l's k-th at l * ROWS + k), then per-lane starts.
shared uint listed[BLUETILE_CLASSIFY_GROUP * BLUETILE_CLASSIFY_ROWS];
shared uint listed_start[BLUETILE_CLASSIFY_GROUP];

SceneInfo scene;

uint id_at(int i, int j) {
  return imageLoad(id_image, scene.origin + ivec2(wrap_index(i, scene.size.x), wrap_index(j, scene.size.y))).x;
}

// The offset d (pixels) of pixel or sample index i from the site's pixel p, wrapped so that
// d + c - f, the offset of its centre from the site, lies in [-size/2, size/2); c = 1/2 for
// pixels (centre between samples), 0 for samples.
int wrapped_offset(int i, int p, float c, float f, int size) {
  int d = i - p;
  float t = float(d) + c - f;
  if (t < -0.5 * float(size)) d += size;
  else if (t >= 0.5 * float(size)) d -= size;
  return d;
}

// Sums of a run of n consecutive offsets d0, d0 + 1, ...: sum d and sum d^2.
int64_t run_sum(int64_t d0, int64_t n) { return n * d0 + n * (n - 1) / 2; }
int64_t run_sum_squares(int64_t d0, int64_t n) { return n * d0 * d0 + d0 * n * (n - 1) + (n - 1) * n * (2 * n - 1) / 6; }

// A run down one column: n pixels at offset dx, offsets dy0, dy0 + 1, ...
void add_column_run(uint site, int dx, int dy0, int n) {
  atomicAdd(sums[site].count, uint(n));
  atomicAdd(sums[site].sum_x, int64_t(n) * dx);
  atomicAdd(sums[site].sum_xx, int64_t(n) * dx * dx);
  atomicAdd(sums[site].sum_y, run_sum(dy0, n));
  atomicAdd(sums[site].sum_yy, run_sum_squares(dy0, n));
}

float distance_squared(SiteInfo s, int dx, int dy) {
  precise vec2 o = (vec2(dx, dy) - s.fraction) * scene.pixel_size;
  precise float d2 = o.x * o.x + o.y * o.y;
  return d2;
}

void main() {
  const uint scene_index = gl_WorkGroupID.z;
  scene = scenes[scene_index];
  const uint lane = gl_LocalInvocationID.x;
  const int i = int(gl_GlobalInvocationID.x);
  const int j0 = int(gl_WorkGroupID.y) * BLUETILE_CLASSIFY_ROWS;
  // The same for the whole workgroup: no barrier below is skipped by some lanes only.
  if (j0 >= scene.size.y || int(gl_WorkGroupID.x) * BLUETILE_CLASSIFY_GROUP >= scene.size.x) return;
  const bool in_tile = i < scene.size.x;
  const int j1 = in_tile ? min(j0 + BLUETILE_CLASSIFY_ROWS, scene.size.y) : j0;
  const bool area = (scene.flags & BLUETILE_SCENE_AREA) != 0u;
  const uint words_per_row = uint(scene.size.x + 15) >> 4;
  const uint mask_shift = 2u * uint(i & 15);

  if (!area) {  // uniform: the scene's flag
    // Point coverage: every sample is a pixel of the site it shows. One outer iteration per run
    // of equal IDs down the column, its sums kept in registers, then one set of atomics: on a
    // SIMD device the atomics run once per run rather than once per row under a mask. The
    // integer totals (and the largest distance) are the same however the samples are grouped.
    uint uncovered = 0u;
    uint a = in_tile ? id_at(i, j0) : 0u;
    int j = j0;
    while (j < j1) {
      const uint run_site = a;
      const SiteInfo site = sites[max(a, 1u) - 1u];
      const int dx = wrapped_offset(i, site.pixel.x, 0.0, site.fraction.x, scene.size.x);
      int n = 0;
      int64_t sum_dy = 0, sum_dyy = 0;
      float far = 0.0;
      do {
        const int dy = wrapped_offset(j, site.pixel.y, 0.0, site.fraction.y, scene.size.y);
        sum_dy += dy;
        sum_dyy += int64_t(dy) * dy;
        far = max(far, distance_squared(site, dx, dy));
        ++n;
        ++j;
        a = id_at(i, j);
      } while (j < j1 && a == run_site);
      if (run_site == 0u) {
        uncovered += uint(n);
      } else {
        const uint g = run_site - 1u;
        atomicAdd(sums[g].owned, uint(n));
        atomicMax(sums[g].farthest, floatBitsToUint(far));
        atomicAdd(sums[g].count, uint(n));
        atomicAdd(sums[g].sum_x, int64_t(n) * dx);
        atomicAdd(sums[g].sum_xx, int64_t(n) * dx * dx);
        atomicAdd(sums[g].sum_y, sum_dy);
        atomicAdd(sums[g].sum_yy, sum_dyy);
      }
    }
    if (uncovered != 0u) atomicAdd(counters[BLUETILE_COUNTER_UNCOVERED + scene_index], uncovered);
    return;
  }

  // Area coverage. Sample run: samples (i, j) showing sample_site with offsets sample_dy, sample_dy + 1, ...
  uint sample_site = 0u;
  int sample_dx = 0, sample_dy = 0, sample_length = 0;
  float sample_far = 0.0;
  // Pixel run (area coverage), the same down the column.
  uint pixel_site = 0u;
  int pixel_dx = 0, pixel_dy = 0, pixel_length = 0;
  uint uncovered = 0u;
  uint listed_count = 0u;

  // The samples at the top of the current pixel: (i, j) and (i + 1, j).
  uint a = in_tile ? id_at(i, j0) : 0u, b = in_tile ? id_at(i + 1, j0) : 0u;
  for (int j = j0; j < j1; ++j) {
    // The samples below: (i, j + 1) is the next row's sample, (i + 1, j + 1) a corner.
    const uint c = id_at(i, j + 1), e = id_at(i + 1, j + 1);
    const SiteInfo site = sites[max(a, 1u) - 1u];
    // Sample (i, j).
    const int dx = wrapped_offset(i, site.pixel.x, 0.0, site.fraction.x, scene.size.x);
    const int dy = wrapped_offset(j, site.pixel.y, 0.0, site.fraction.y, scene.size.y);
    const bool sample_continues = a == sample_site && dx == sample_dx && dy == sample_dy + sample_length;
    if (a == 0u) ++uncovered;
    if (!sample_continues && sample_length > 0) {
      uint g = sample_site - 1u;
      atomicAdd(sums[g].owned, uint(sample_length));
      atomicMax(sums[g].farthest, floatBitsToUint(sample_far));
      sample_length = 0;
    }
    if (a != 0u) {
      if (sample_length == 0) {
        sample_site = a;
        sample_dx = dx;
        sample_dy = dy;
        sample_far = 0.0;
      }
      ++sample_length;
      sample_far = max(sample_far, distance_squared(site, dx, dy));
    }
    // Pixel (i, j).
    {
      bool whole = a != 0u && a == b && a == c && a == e && (site.flags & BLUETILE_SITE_SPLIT) == 0u;
      uint word = masks[scene.mask_offset + uint(j) * words_per_row + uint(i >> 4)] >> mask_shift;
      bool holds_site = (word & 1u) != 0u, holds_several = (word & 2u) != 0u;
      whole = whole && (!holds_site || (!holds_several && site.pixel == ivec2(i, j)));
      const int pdx = wrapped_offset(i, site.pixel.x, 0.5, site.fraction.x, scene.size.x);
      const int pdy = wrapped_offset(j, site.pixel.y, 0.5, site.fraction.y, scene.size.y);
      // Pixels near half a period from the site are split, where the torus wrap is exact.
      float tx = float(pdx) + 0.5 - site.fraction.x, ty = float(pdy) + 0.5 - site.fraction.y;
      whole = whole && abs(tx) < 0.5 * float(scene.size.x) - 1.0 && abs(ty) < 0.5 * float(scene.size.y) - 1.0;
      const bool pixel_continues = whole && a == pixel_site && pdx == pixel_dx && pdy == pixel_dy + pixel_length;
      if (!pixel_continues && pixel_length > 0) {
        add_column_run(pixel_site - 1u, pixel_dx, pixel_dy, pixel_length);
        pixel_length = 0;
      }
      if (whole) {
        if (pixel_length == 0) {
          pixel_site = a;
          pixel_dx = pdx;
          pixel_dy = pdy;
        }
        ++pixel_length;
      } else {
        listed[lane * uint(BLUETILE_CLASSIFY_ROWS) + listed_count] = uint(j * scene.size.x + i);
        ++listed_count;
      }
    }
    a = c;
    b = e;
  }
  if (sample_length > 0) {
    uint g = sample_site - 1u;
    atomicAdd(sums[g].owned, uint(sample_length));
    atomicMax(sums[g].farthest, floatBitsToUint(sample_far));
  }
  if (pixel_length > 0) add_column_run(pixel_site - 1u, pixel_dx, pixel_dy, pixel_length);
  if (uncovered != 0u) atomicAdd(counters[BLUETILE_COUNTER_UNCOVERED + scene_index], uncovered);

  // The group's boundary pixels: lane starts by a prefix sum, one global atomic for the group.
  listed_start[lane] = listed_count;
  barrier();
  if (lane == 0u) {
    uint total = 0u;
    for (uint l = 0u; l < uint(BLUETILE_CLASSIFY_GROUP); ++l) {
      uint n = listed_start[l];
      listed_start[l] = total;
      total += n;
    }
    uint first = total != 0u ? atomicAdd(counters[BLUETILE_COUNTER_BOUNDARY], total) : 0u;
    for (uint l = 0u; l < uint(BLUETILE_CLASSIFY_GROUP); ++l) listed_start[l] += first;
    if (total != 0u) {
      // Groups of the split: x at most BLUETILE_SPLIT_ROW, then rows of them.
      uint groups = (first + total + BLUETILE_SPLIT_GROUP - 1u) / BLUETILE_SPLIT_GROUP;
      atomicMax(counters[BLUETILE_COUNTER_DISPATCH], min(groups, BLUETILE_SPLIT_ROW));
      atomicMax(counters[BLUETILE_COUNTER_DISPATCH + 1], (groups + BLUETILE_SPLIT_ROW - 1u) / BLUETILE_SPLIT_ROW);
    }
  }
  barrier();
  const uint first = listed_start[lane];
  for (uint k = 0u; k < listed_count; ++k) boundary[first + k] = uvec2(scene_index, listed[lane * uint(BLUETILE_CLASSIFY_ROWS) + k]);
}
