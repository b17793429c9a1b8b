// cone_quad.vert: one bounded distance cone (Hoff et al. 1999) as a screen-aligned square of
// half-side `radius` around the site (or a periodic replica), clamped to its scene's tile so
// that no fragment lands in a neighbouring tile of the atlas. cone_quad.frag writes the exact
// distance as depth, so there is no tessellation error.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_common.glsl"

layout(location = 0) flat out uint out_id;
layout(location = 1) flat out vec4 out_tile;   // tile origin (pixels), pixel size
layout(location = 2) flat out vec3 out_site;   // site position, depth scale

void main() {
  ConeInstance cone = instances[gl_InstanceIndex];
  SceneInfo scene = scenes[sites[cone.id - 1u].scene];
  vec2 corner = vec2(gl_VertexIndex & 1, gl_VertexIndex >> 1);
  vec2 lo = clamp(cone.position - cone.radius, vec2(0.0), scene.domain_size);
  vec2 hi = clamp(cone.position + cone.radius, vec2(0.0), scene.domain_size);
  gl_Position = to_clip(scene, mix(lo, hi, corner), 0.0);
  out_id = cone.id;
  out_tile = vec4(vec2(scene.origin), scene.pixel_size);
  out_site = vec3(cone.position, scene.depth_scale);
}
