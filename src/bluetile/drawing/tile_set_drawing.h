// A picture of a tile set, for a person to check it by eye (wang-check's tiles.png). Part of the
// images component; internal: only the tool draws it.
#pragma once

#include <cstdint>

#include "bluetile/io/image.h"
#include "bluetile/tiling/tile_set.h"

namespace bluetile {

// The picture of a tile set: every tile with its points and its edge (or corner) colours, then a
// small torus tiling with the Voronoi cells of its points and the colours on the seams, so a
// reader sees that colours match across every edge and points run on across them.
Canvas draw_tile_set(const TileSet& set, std::uint64_t seed);

}  // namespace bluetile
