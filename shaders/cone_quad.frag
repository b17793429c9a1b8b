// cone_quad.frag: the cone's depth at this sample is the distance from the sample to the site,
// formed from the integer sample offset minus the site's fraction so that its float error is
// relative to the distance (about 1e-7 of it), not to the domain. The depth test LESS keeps the
// nearest site. Equal depths keep the first drawn, and instances are drawn in site order, so
// ties go to the lower site index every run.
#version 450

layout(location = 0) flat in uint in_id;
layout(location = 1) flat in ivec4 in_tile;
layout(location = 2) flat in vec4 in_site;
layout(location = 3) flat in float in_depth_scale;
layout(location = 0) out uint out_id;

void main() {
  ivec2 sample_index = ivec2(gl_FragCoord.xy) - in_tile.xy;
  vec2 offset = (vec2(sample_index - in_tile.zw) - in_site.xy) * in_site.zw;
  gl_FragDepth = length(offset) * in_depth_scale;
  out_id = in_id;
}
