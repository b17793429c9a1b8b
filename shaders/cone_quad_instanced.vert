// cone_quad_instanced.vert: a cone's square (cone_square.glsl) as one instance of a four-vertex
// triangle strip, one instanced draw per pass (ConeDraw::instanced).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_square.glsl"

void main() { emit_corner(cone_square(uint(gl_InstanceIndex)), gl_VertexIndex); }
