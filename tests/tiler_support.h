// A tile set made in the tests, independent of `bluetile wang`: each tile a jittered grid of
// points whose ranks follow a greedy farthest-point order on the tile's own torus (so every rank
// prefix is spread within the tile; across seams it is not relaxed). Enough to check the tiler's
// bookkeeping and the scaling of its thinning; not a set to judge spectra by.
#pragma once

#include <cstdint>

#include "bluetile/tiling/tile_set.h"

namespace bluetile::test {

// `side` x `side` jittered points per tile (levels: rank < side^2 / 4 is level 0, the rest 1).
// `same_points`: every tile gets the first tile's points and ranks (a periodic plane).
TileSet make_test_tile_set(TileSetKind kind, int side, std::uint64_t seed, bool same_points = false);

// The smallest distance between any two of `points` (plain plane distance, brute force on a grid).
double min_distance(const std::vector<Point>& points);

}  // namespace bluetile::test
