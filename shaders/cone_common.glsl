// cone_common.glsl: bindings and helpers shared by the cone shaders.
#include "raster_common.glsl"

layout(push_constant) uniform Push { vec2 atlas_size; } push;

// Atlas framebuffer coordinates to clip space.
vec4 to_clip(vec2 framebuffer, float depth) { return vec4(framebuffer / push.atlas_size * 2.0 - 1.0, depth, 1.0); }
