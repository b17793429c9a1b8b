// cone_quad.frag: the cone's depth at this pixel centre is the exact (float) distance from the
// centre to the site; the depth test LESS keeps the nearest site. Equal depths keep the first
// drawn, and instances are drawn in site order, so ties go to the lower site index every run.
#version 450

layout(location = 0) flat in uint in_id;
layout(location = 1) flat in vec4 in_tile;
layout(location = 2) flat in vec3 in_site;
layout(location = 0) out uint out_id;

void main() {
  vec2 q = (gl_FragCoord.xy - in_tile.xy) * in_tile.zw;
  gl_FragDepth = length(q - in_site.xy) * in_site.z;
  out_id = in_id;
}
