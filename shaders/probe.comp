// probe.comp: writes 1 + its invocation index into a buffer. Used by the tests to check that
// SPIR-V is compiled at build time and embedded; the raster engine's shaders sit beside it.
#version 450
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Output { uint values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < values.length()) values[i] = i + 1u;
}
