// cone_quad.vert: one bounded distance cone (Hoff et al. 1999) as a screen-aligned square of
// half-side `radius` around the site (or a periodic replica), clamped to its scene's tile so
// that no fragment lands in a neighbouring tile of the atlas. Sample (i, j) of the tile sits at
// framebuffer pixel origin + (i, j), centre + 0.5. cone_quad.frag writes the exact distance as
// depth, so there is no tessellation error.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_common.glsl"

layout(location = 0) flat out uint out_id;
layout(location = 1) flat out ivec4 out_tile;      // tile origin (samples), site pixel of this replica
layout(location = 2) flat out vec4 out_site;       // site fraction (samples), pixel size
layout(location = 3) flat out float out_depth_scale;

void main() {
  ConeInstance cone = instances[gl_InstanceIndex];
  SiteInfo site = sites[cone.id - 1u];
  SceneInfo scene = scenes[site.scene];
  vec2 corner = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1);
  vec2 centre = vec2(cone.pixel) + site.fraction + 0.5;  // framebuffer coordinates within the tile
  vec2 half_side = cone.radius / scene.pixel_size;
  vec2 lo = clamp(centre - half_side, vec2(0.0), vec2(scene.size));
  vec2 hi = clamp(centre + half_side, vec2(0.0), vec2(scene.size));
  gl_Position = to_clip(vec2(scene.origin) + mix(lo, hi, corner), 0.0);
  out_id = cone.id;
  out_tile = ivec4(scene.origin, cone.pixel);
  out_site = vec4(site.fraction, scene.pixel_size);
  out_depth_scale = scene.depth_scale;
}
