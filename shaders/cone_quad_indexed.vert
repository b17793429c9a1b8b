// cone_quad_indexed.vert: a cone's square (cone_square.glsl) as four vertices, two triangles by an
// index buffer (0 1 2, 2 1 3 per cone), in one indexed draw (ConeDraw::indexed).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_square.glsl"

void main() { emit_corner(cone_square(uint(gl_VertexIndex) / 4u), gl_VertexIndex % 4); }
