// The progressive order (ranks) of a level's points inside tiles, so that a tiler can thin every
// tile to its first m points and still get a well-spread plane (the paper's hierarchical sets
// that tile, section 3). Greedy farthest point, all tiles together: at step s every tile in turn
// takes, among its level's points not yet ranked, the one farthest from every point already
// ranked that can lie near it in a tiling, namely its own (earlier levels included) and those of
// each tile that fits each neighbour position, shifted there. Ties go to the lower index.
#pragma once

#include <cstdint>
#include <vector>

#include "bluetile/relax/wang_blocks.h"
#include "bluetile/relax/wang_crop.h"

namespace bluetile {

// For every tile, the indices of its points [level_begin, size) in rank order. Points before
// level_begin are the earlier levels, ranked already. All tiles must have the same size.
std::vector<std::vector<std::uint32_t>> rank_level(const BlockConfigurations& configurations, const TilePoints& tiles,
                                                   std::size_t level_begin);

}  // namespace bluetile
