// cone_fan.vert: the classic tessellated cone (Hoff et al. 1999): a fan of
// BLUETILE_FAN_SEGMENTS triangles, apex at the site with depth 0, rim circumscribing the circle
// of radius `radius` at the depth of its distance. Depth is interpolated linearly, so the
// diagram is that of the polygonal cones (the tessellation error the quad variant avoids).
// Clip distances cut the fan at its scene's tile.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_common.glsl"

layout(location = 0) flat out uint out_id;
out float gl_ClipDistance[4];

void main() {
  ConeInstance cone = instances[gl_InstanceIndex];
  SiteInfo site = sites[cone.id - 1u];
  SceneInfo scene = scenes[site.scene];
  int triangle = gl_VertexIndex / 3;
  int corner = gl_VertexIndex % 3;
  const float step = 6.28318530718 / float(BLUETILE_FAN_SEGMENTS);
  float rim = cone.radius / cos(0.5 * step);
  vec2 q = vec2(cone.pixel) + site.fraction + 0.5;  // framebuffer coordinates within the tile
  float depth = 0.0;
  if (corner != 0) {
    float angle = step * float(triangle + corner - 1);
    q += rim * vec2(cos(angle), sin(angle)) / scene.pixel_size;
    depth = rim * scene.depth_scale;
  }
  gl_Position = to_clip(vec2(scene.origin) + q, depth);
  gl_ClipDistance[0] = q.x;
  gl_ClipDistance[1] = float(scene.size.x) - q.x;
  gl_ClipDistance[2] = q.y;
  gl_ClipDistance[3] = float(scene.size.y) - q.y;
  out_id = cone.id;
}
