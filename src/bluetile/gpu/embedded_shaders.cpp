#include "bluetile/gpu/embedded_shaders.h"

#include <string>

#include "bluetile/core/error.h"

namespace bluetile {

std::span<const std::uint32_t> embedded_shader(std::string_view name) {
  for (const EmbeddedShader& shader : embedded_shaders())
    if (shader.name == name) return shader.code;
  throw Error("no embedded shader named '" + std::string(name) + "' (build problem)");
}

}  // namespace bluetile
