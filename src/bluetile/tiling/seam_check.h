// How well the tiles of a set fit together (the paper, section 3: tiles relaxed together must sit
// side by side without a seam). The seam check measures, for every prefix of levels, the minimum
// distance between points of different tiles over every admissible 2x2 block of tiles (edge and
// diagonal neighbours, so the corner problem of edge tiles counts): no tiling of the plane by the
// set can have two points of different tiles closer. Beside it, the minimum within tiles and
// their ratio; distances also in hexagonal spacings of the tiled density (seamX, X/W of the
// docs/RESULTS.md, "Wang tiles"). And the points of a seeded torus tiling, for analysing a tiled plane.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "bluetile/tiling/tile_set.h"

namespace bluetile {

// How the second tile of a pair sits relative to the first.
enum class TileRelation : std::uint8_t { east, north, north_east, north_west };

struct ClosestPair {
  int first_tile = -1, second_tile = -1;  // tile ids; second_tile sits `relation` of first_tile
  TileRelation relation = TileRelation::east;
  std::size_t first_point = 0, second_point = 0;  // indices into the tiles' points
};

struct SeamLevel {
  int level = 0;                     // prefix: points of levels 0 .. level
  std::size_t points_per_tile = 0;   // the smallest tile's count in the prefix
  double spacing = 0.0;              // hexagonal spacing of points_per_tile points in a unit tile
  double cross_min = std::numeric_limits<double>::infinity();   // tile units, across seams
  double within_min = std::numeric_limits<double>::infinity();  // tile units, inside one tile
  ClosestPair closest;               // a pair at cross_min

  double cross_relative() const { return cross_min / spacing; }    // seamX
  double within_relative() const { return within_min / spacing; }
  double ratio() const { return cross_min / within_min; }          // X/W
};

struct SeamCheck {
  std::size_t blocks = 0;       // admissible 2x2 blocks (256 for wang8)
  std::size_t tile_pairs = 0;   // distinct (tile, tile, relation) pairs they hold
  std::vector<SeamLevel> levels;  // one per level present, ascending
};

// Throws Error when the set has no points or its tiles are not those of its kind.
SeamCheck check_seams(const TileSet& set);

// The points of the period x period torus tiling `seed` of `set` (TileRules::tile_at_periodic),
// scaled to the unit torus: cell (i, j) covers [i, i+1] x [j, j+1] / period. Only points whose
// rank is below `max_rank` (all by default) are taken. `levels` and `ranks` receive each point's.
struct TiledPlane {
  int period = 0;
  std::vector<int> cell_tiles;  // tile id of cell (i, j) at j * period + i
  std::vector<Point> points;
  std::vector<int> levels;
  std::vector<std::uint32_t> ranks;
};
TiledPlane torus_tiling(const TileSet& set, int period, std::uint64_t seed,
                        std::uint32_t max_rank = std::numeric_limits<std::uint32_t>::max());

}  // namespace bluetile
