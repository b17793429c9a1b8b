// cone_point.frag: cone_quad.frag for point cones: samples outside the cone's tile are dropped
// (a point is not clamped to the tile as the quads are).
#version 450

layout(location = 0) flat in uint in_id;
layout(location = 1) flat in ivec4 in_tile;
layout(location = 2) flat in vec4 in_site;
layout(location = 3) flat in float in_depth_scale;
layout(location = 4) flat in ivec2 in_tile_size;
layout(location = 0) out uint out_id;

void main() {
  ivec2 sample_index = ivec2(gl_FragCoord.xy) - in_tile.xy;
  if (any(lessThan(sample_index, ivec2(0))) || any(greaterThanEqual(sample_index, in_tile_size))) discard;
  vec2 offset = (vec2(sample_index - in_tile.zw) - in_site.xy) * in_site.zw;
  gl_FragDepth = length(offset) * in_depth_scale;
  out_id = in_id;
}
