// cone_square.glsl: what every exact-depth cone vertex shader writes (cone_quad*.vert,
// cone_point.vert): one bounded distance cone (Hoff et al. 1999) as a screen-aligned square of
// half-side `radius` around the site (or a periodic replica), and the flat values that
// cone_quad.frag / cone_point.frag need to compute the exact distance per sample. Sample (i, j)
// of the tile sits at framebuffer pixel origin + (i, j), centre + 0.5.
#include "cone_common.glsl"

layout(location = 0) flat out uint out_id;
layout(location = 1) flat out ivec4 out_tile;      // tile origin (samples), site pixel of this replica
layout(location = 2) flat out vec4 out_site;       // site fraction (samples), pixel size
layout(location = 3) flat out float out_depth_scale;
layout(location = 4) flat out ivec2 out_tile_size;  // tile size (samples): cone_point.frag's clamp

struct ConeSquare {
  vec2 centre;     // framebuffer coordinates within the tile
  vec2 half_side;  // samples
  SceneInfo scene;
};

// The square of cone `index` and the flat outputs of its vertices.
ConeSquare cone_square(uint index) {
  ConeInstance cone = instances[index];
  SiteInfo site = sites[cone.id - 1u];
  ConeSquare square;
  square.scene = scenes[site.scene];
  square.centre = vec2(cone.pixel) + site.fraction + 0.5;
  square.half_side = cone.radius / square.scene.pixel_size;
  out_id = cone.id;
  out_tile = ivec4(square.scene.origin, cone.pixel);
  out_site = vec4(site.fraction, square.scene.pixel_size);
  out_depth_scale = square.scene.depth_scale;
  out_tile_size = square.scene.size;
  return square;
}

// Corner k (bit 0: x, bit 1: y) of the square clamped to its scene's tile, so that no fragment
// lands in a neighbouring tile of the atlas.
void emit_corner(ConeSquare square, int k) {
  vec2 corner = vec2(k & 1, k >> 1);
  vec2 lo = clamp(square.centre - square.half_side, vec2(0.0), vec2(square.scene.size));
  vec2 hi = clamp(square.centre + square.half_side, vec2(0.0), vec2(square.scene.size));
  gl_Position = to_clip(vec2(square.scene.origin) + mix(lo, hi, corner), 0.0);
}
