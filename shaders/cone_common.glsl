// cone_common.glsl: bindings and helpers shared by the cone shaders.
#include "raster_common.glsl"

// The viewport's size and where the atlas lies in it (0, 0 but for point cones, whose viewport
// reaches past the atlas so that a replica's centre outside it stays inside the clip volume).
layout(push_constant) uniform Push { vec2 viewport_size; vec2 atlas_offset; } push;

// Atlas framebuffer coordinates to clip space.
vec4 to_clip(vec2 framebuffer, float depth) {
  return vec4((framebuffer + push.atlas_offset) / push.viewport_size * 2.0 - 1.0, depth, 1.0);
}
