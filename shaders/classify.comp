// classify.comp: reads the ID image once per pass and sums it per site. One invocation walks a
// segment of BLUETILE_CLASSIFY_SEGMENT pixels of one row (z = scene) and sums runs of equal IDs
// in registers, flushing each run with one set of 64-bit integer atomics: the sums are exact
// integers, so the same in any order and with any thread count (float atomics are not).
//  - Every sample counts for the site it shows (owned, farthest owned sample) and, in point
//    coverage, is a pixel of that site.
//  - Area coverage: pixel (i, j) spans samples (i, j) to (i + 1, j + 1). Voronoi cells are
//    convex, so when its four corners show one site a, its edges lie in a's cell, and any other
//    cell reaching into it lies strictly inside it, with its site: the pixel is whole unless a
//    site other than a lies in it (the site masks say). Whole pixels are summed here; every other
//    pixel is listed for split_f64/split_f32, which also get their indirect dispatch size here.
//  - Samples no cone reached are counted per scene: such a pass is redone, never accepted.
// The host reference (src/bluetile/voronoi/raster_reference.cpp) does the same sums.
#version 450
#extension GL_GOOGLE_include_directive : require
#extension GL_EXT_shader_atomic_int64 : require
#include "raster_common.glsl"

layout(local_size_x = 1, local_size_y = BLUETILE_CLASSIFY_GROUP) in;
layout(binding = BLUETILE_BINDING_ID_IMAGE, r32ui) uniform readonly uimage2D id_image;

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

void add_run(uint site, int dx0, int dy, int n) {
  atomicAdd(sums[site].count, uint(n));
  atomicAdd(sums[site].sum_x, run_sum(dx0, n));
  atomicAdd(sums[site].sum_xx, run_sum_squares(dx0, n));
  atomicAdd(sums[site].sum_y, int64_t(n) * dy);
  atomicAdd(sums[site].sum_yy, int64_t(n) * dy * dy);
}

float distance_squared(SiteInfo s, int dx, int dy) {
  precise vec2 o = (vec2(dx, dy) - s.fraction) * scene.pixel_size;
  precise float d2 = o.x * o.x + o.y * o.y;
  return d2;
}

void main() {
  const uint scene_index = gl_WorkGroupID.z;
  scene = scenes[scene_index];
  const int j = int(gl_GlobalInvocationID.y);
  const int i0 = int(gl_WorkGroupID.x) * BLUETILE_CLASSIFY_SEGMENT;
  if (j >= scene.size.y || i0 >= scene.size.x) return;
  const int i1 = min(i0 + BLUETILE_CLASSIFY_SEGMENT, scene.size.x);
  const bool area = (scene.flags & BLUETILE_SCENE_AREA) != 0u;
  const uint words_per_row = uint(scene.size.x + 15) >> 4;

  // The site of the current runs and its info.
  uint site_id = 0u;
  SiteInfo site;
  int site_dy_sample = 0, site_dy_pixel = 0;
  // Sample run: [sample_start, sample_start + sample_length), offsets from sample_dx.
  uint sample_site = 0u;
  int sample_dx = 0, sample_dy = 0, sample_length = 0;
  float sample_far = 0.0;
  // Pixel run (area coverage).
  uint pixel_site = 0u;
  int pixel_dx = 0, pixel_length = 0, pixel_dy = 0;
  uint uncovered = 0u;
  uint listed[BLUETILE_CLASSIFY_SEGMENT];
  uint listed_count = 0u;

  uint a = id_at(i0, j), c = area ? id_at(i0, j + 1) : 0u;
  for (int i = i0; i < i1; ++i) {
    const uint b = id_at(i + 1, j), e = area ? id_at(i + 1, j + 1) : 0u;
    if (a == 0u) {
      ++uncovered;
    } else if (a != site_id) {
      site_id = a;
      site = sites[a - 1u];
      site_dy_sample = wrapped_offset(j, site.pixel.y, 0.0, site.fraction.y, scene.size.y);
      site_dy_pixel = wrapped_offset(j, site.pixel.y, 0.5, site.fraction.y, scene.size.y);
    }
    // Sample (i, j).
    if (a != 0u) {
      int dx = wrapped_offset(i, site.pixel.x, 0.0, site.fraction.x, scene.size.x);
      if (a == sample_site && dx == sample_dx + sample_length) {
        ++sample_length;
      } else {
        if (sample_length > 0) {
          uint g = sample_site - 1u;
          atomicAdd(sums[g].owned, uint(sample_length));
          atomicMax(sums[g].farthest, floatBitsToUint(sample_far));
          if (!area) add_run(g, sample_dx, sample_dy, sample_length);
        }
        sample_site = a;
        sample_dx = dx;
        sample_dy = site_dy_sample;
        sample_length = 1;
        sample_far = distance_squared(site, dx, site_dy_sample);
      }
      // A run of samples on one row is farthest from the site at one of its ends.
      sample_far = max(sample_far, distance_squared(site, dx, site_dy_sample));
    }
    // Pixel (i, j).
    if (area) {
      bool whole = a != 0u && a == b && a == c && a == e && (site.flags & BLUETILE_SITE_SPLIT) == 0u;
      int dx = 0;
      if (whole) {
        uint word = masks[scene.mask_offset + uint(j) * words_per_row + uint(i >> 4)] >> (2u * uint(i & 15));
        bool holds_site = (word & 1u) != 0u, holds_several = (word & 2u) != 0u;
        whole = !holds_site || (!holds_several && site.pixel == ivec2(i, j));
        dx = wrapped_offset(i, site.pixel.x, 0.5, site.fraction.x, scene.size.x);
        // Pixels near half a period from the site are split, where the torus wrap is exact.
        float tx = float(dx) + 0.5 - site.fraction.x, ty = float(site_dy_pixel) + 0.5 - site.fraction.y;
        whole = whole && abs(tx) < 0.5 * float(scene.size.x) - 1.0 && abs(ty) < 0.5 * float(scene.size.y) - 1.0;
      }
      if (whole && a == pixel_site && dx == pixel_dx + pixel_length) {
        ++pixel_length;
      } else {
        if (pixel_length > 0) add_run(pixel_site - 1u, pixel_dx, pixel_dy, pixel_length);
        pixel_length = 0;
        if (whole) {
          pixel_site = a;
          pixel_dx = dx;
          pixel_dy = site_dy_pixel;
          pixel_length = 1;
        } else {
          listed[listed_count++] = uint(j * scene.size.x + i);
        }
      }
    }
    a = b;
    c = e;
  }
  if (sample_length > 0) {
    uint g = sample_site - 1u;
    atomicAdd(sums[g].owned, uint(sample_length));
    atomicMax(sums[g].farthest, floatBitsToUint(sample_far));
    if (!area) add_run(g, sample_dx, sample_dy, sample_length);
  }
  if (pixel_length > 0) add_run(pixel_site - 1u, pixel_dx, pixel_dy, pixel_length);
  if (uncovered != 0u) atomicAdd(counters[BLUETILE_COUNTER_UNCOVERED + scene_index], uncovered);
  if (listed_count != 0u) {
    uint first = atomicAdd(counters[BLUETILE_COUNTER_BOUNDARY], listed_count);
    for (uint k = 0u; k < listed_count; ++k) boundary[first + k] = uvec2(scene_index, listed[k]);
    // Groups of the split: x at most BLUETILE_SPLIT_ROW, then rows of them.
    uint groups = (first + listed_count + BLUETILE_SPLIT_GROUP - 1u) / BLUETILE_SPLIT_GROUP;
    atomicMax(counters[BLUETILE_COUNTER_DISPATCH], min(groups, BLUETILE_SPLIT_ROW));
    atomicMax(counters[BLUETILE_COUNTER_DISPATCH + 1], (groups + BLUETILE_SPLIT_ROW - 1u) / BLUETILE_SPLIT_ROW);
  }
}
