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

// The same order by voids (Ulichney 1993's void-and-cluster, tiled): every tile in turn takes the
// unranked point of least Gaussian energy sum_j w_j exp(-|x - y_j|^2 / (2 sigma^2)) over the
// ranked points y_j that can lie near it (w_j: 1 in its own tile, 1 / the number of tiles that
// fit at a neighbour position), among those not much nearer to a ranked point than the farthest
// one is; sigma = sigma_factor hexagonal spacings of the prefix reached, updated each time the
// prefix grows by a quarter. A smooth energy sees the density over several spacings, where
// farthest point sees only the nearest point, and the neighbour weights spread a level's first
// points over different parts of different tiles (prefix C_LF 0.07-0.18 against 0.5-1.5).
std::vector<std::vector<std::uint32_t>> rank_level_by_voids(const BlockConfigurations& configurations,
                                                            const TilePoints& tiles, std::size_t level_begin,
                                                            double sigma_factor);

}  // namespace bluetile
