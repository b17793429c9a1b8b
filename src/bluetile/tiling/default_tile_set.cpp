#include "bluetile/tiling/default_tile_set.h"

#include <string>

#include "bluetile/tiling/tile_set_file.h"

// The assembler copies the file in at build time (CMake passes its path and makes this source
// depend on it): no generated source of hex bytes to compile.
asm(".section .rodata\n"
    ".balign 16\n"
    "bluetile_default_tiles_begin:\n"
    ".incbin \"" BLUETILE_DEFAULT_TILES "\"\n"
    "bluetile_default_tiles_end:\n"
    ".byte 0\n"
    ".previous\n");

extern "C" const char bluetile_default_tiles_begin[];
extern "C" const char bluetile_default_tiles_end[];

namespace bluetile {

std::string_view default_tile_set_text() {
  return {bluetile_default_tiles_begin, static_cast<std::size_t>(bluetile_default_tiles_end - bluetile_default_tiles_begin)};
}

TileSet default_tile_set() { return parse_tile_set(std::string(default_tile_set_text()), kDefaultTileSetName); }

}  // namespace bluetile
