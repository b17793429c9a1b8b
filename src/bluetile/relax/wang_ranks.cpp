// Progressive order of a level inside tiles (see wang_ranks.h).
#include "bluetile/relax/wang_ranks.h"

#include <algorithm>
#include <cmath>

namespace bluetile {

std::vector<std::vector<std::uint32_t>> rank_level(const BlockConfigurations& configurations, const TilePoints& tiles,
                                                   std::size_t level_begin) {
  const std::size_t tile_count = tiles.size();
  const std::size_t size = tiles.empty() ? 0 : tiles[0].size();
  const std::size_t level = size - level_begin;
  // neighbours_of[u]: (tile t, shift) pairs: u can sit at the position `shift` away from t (the
  // centre position included, t == u, shift 0).
  struct Placement {
    std::size_t tile;
    Point shift;
  };
  std::vector<std::vector<Placement>> placements(tile_count);
  for (std::size_t t = 0; t < tile_count; ++t) {
    for (int p = 0; p < kBlockPositions; ++p) {
      const Point shift{static_cast<double>(block_dx(p)), static_cast<double>(block_dy(p))};
      for (int u : configurations.candidates(static_cast<int>(t), p)) placements[static_cast<std::size_t>(u)].push_back({t, shift});
    }
  }
  // nearest[t][m]: squared distance from point level_begin + m of tile t to the nearest ranked
  // point that can lie near it (ranked points are skipped).
  std::vector<std::vector<double>> nearest(tile_count, std::vector<double>(level, HUGE_VAL));
  std::vector<std::vector<bool>> ranked(tile_count, std::vector<bool>(level, false));
  auto add_ranked = [&](std::size_t u, Point y) {
    for (const Placement& at : placements[u]) {
      const Point shifted = y + at.shift;
      const std::vector<Point>& tile = tiles[at.tile];
      std::vector<double>& near = nearest[at.tile];
      for (std::size_t m = 0; m < level; ++m) {
        const Point d = tile[level_begin + m] - shifted;
        near[m] = std::min(near[m], d.x * d.x + d.y * d.y);
      }
    }
  };
  for (std::size_t u = 0; u < tile_count; ++u)
    for (std::size_t k = 0; k < level_begin; ++k) add_ranked(u, tiles[u][k]);

  std::vector<std::vector<std::uint32_t>> order(tile_count);
  for (std::size_t s = 0; s < level; ++s) {
    for (std::size_t t = 0; t < tile_count; ++t) {
      std::size_t best = level;
      for (std::size_t m = 0; m < level; ++m)
        if (!ranked[t][m] && (best == level || nearest[t][m] > nearest[t][best])) best = m;
      ranked[t][best] = true;
      order[t].push_back(static_cast<std::uint32_t>(level_begin + best));
      add_ranked(t, tiles[t][level_begin + best]);
    }
  }
  return order;
}

}  // namespace bluetile
