// Tile-set files: the text format that stores a TileSet (tile_set.h), and the checks reading
// makes, for sets built in memory too.
#pragma once

#include <string>

#include "bluetile/tiling/tile_set.h"

namespace bluetile {

// Tile-set files, version 1 (docs/DESIGN.md, tile-set file):
//   # bluetile tiles 1
//   # <header comment lines>
//   # set KIND colours C
//   # tile ID N E S W                 (corner sets: # tile ID corners NW NE SE SW)
//   x y level rank                    (one line per point, 17 significant digits)
// Other comment lines are ignored. Reading checks everything (the version, the kind, that C
// fits it, every tile present once with the colours its id has, coordinates finite in [0,1),
// levels non-negative, ranks a permutation that levels follow) and throws Error naming the
// file (or `name`) and line.
TileSet parse_tile_set(const std::string& text, const std::string& name);
TileSet read_tile_set(const std::string& path);
// write(read(file)) reproduces a file this wrote, bit for bit.
std::string format_tile_set(const TileSet& set);
void write_tile_set(const std::string& path, const TileSet& set);

// Checks a set built in memory the way reading checks a file; throws Error naming the tile.
void validate_tile_set(const TileSet& set);

}  // namespace bluetile
