// cone_common.glsl: bindings shared by the cone shaders (see src/bluetile/gpu/raster_layout.h).
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#include "bluetile/gpu/raster_layout.h"

layout(std430, binding = BLUETILE_BINDING_INSTANCES) readonly buffer Instances { ConeInstance instances[]; };
layout(std430, binding = BLUETILE_BINDING_SCENES) readonly buffer Scenes { SceneInfo scenes[]; };
layout(std430, binding = BLUETILE_BINDING_SITES) readonly buffer Sites { SiteInfo sites[]; };

layout(push_constant) uniform Push { vec2 atlas_size; } push;

// Atlas pixel coordinates of scene point q to clip space.
vec4 to_clip(SceneInfo scene, vec2 q, float depth) {
  vec2 pixel = vec2(scene.origin) + q / scene.pixel_size;
  return vec4(pixel / push.atlas_size * 2.0 - 1.0, depth, 1.0);
}
