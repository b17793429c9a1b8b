// The tile set built into the library: data/tiles/default.tiles (made by `bluetile wang`; the
// command is in data/tiles/README.md and in the file's header), embedded at build time so that
// the tool needs no file beside it.
#pragma once

#include <string_view>

#include "bluetile/tiling/tile_set.h"

namespace bluetile {

// The file's name, for messages and output headers.
inline constexpr const char* kDefaultTileSetName = "default.tiles";

// The embedded file's text.
std::string_view default_tile_set_text();

// The embedded set, parsed (and validated) on each call.
TileSet default_tile_set();

}  // namespace bluetile
