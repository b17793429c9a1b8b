// cone_quad.vert: a cone's square (cone_square.glsl) as two triangles of a non-indexed list,
// six vertices per cone in one draw (ConeDraw::triangles). lavapipe shades vertices in batches of
// eight, and per-instance draws leave most of each batch empty.
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_square.glsl"

const int kCorner[6] = int[6](0, 1, 2, 2, 1, 3);

void main() { emit_corner(cone_square(uint(gl_VertexIndex) / 6u), kCorner[gl_VertexIndex % 6]); }
