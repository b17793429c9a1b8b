// SPIR-V compiled from shaders/ at build time (cmake/EmbedShaders.cmake) and linked into the
// library, so the binary needs no shader files at run time.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace bluetile {

struct EmbeddedShader {
  std::string_view name;  // the GLSL file name, e.g. "cone.frag"
  std::span<const std::uint32_t> code;
};

std::span<const EmbeddedShader> embedded_shaders();

// The SPIR-V of shader `name`; throws Error when there is none (a build problem).
std::span<const std::uint32_t> embedded_shader(std::string_view name);

}  // namespace bluetile
