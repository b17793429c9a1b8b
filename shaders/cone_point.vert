// cone_point.vert: a cone's square (cone_square.glsl) as one point primitive whose size is the
// square's side (ConeDraw::points): one vertex per cone. A point is not clamped to its tile:
// cone_point.frag drops the samples outside it. Non-square pixels get the larger side (a square
// that covers more samples only adds exact depths).
#version 450
#extension GL_GOOGLE_include_directive : require
#include "cone_square.glsl"

void main() {
  ConeSquare square = cone_square(uint(gl_VertexIndex));
  gl_Position = to_clip(vec2(square.scene.origin) + square.centre, 0.0);
  gl_PointSize = 2.0 * max(square.half_side.x, square.half_side.y);
}
