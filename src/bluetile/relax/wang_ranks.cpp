// Progressive order of a level inside tiles (see wang_ranks.h).
#include "bluetile/relax/wang_ranks.h"

#include <algorithm>
#include <cmath>

namespace bluetile {
namespace {

// The voids order takes its point among those at least this fraction of the farthest one's
// distance from every ranked point: the smooth energy alone let close pairs into early prefixes
// (rho 0.40 at the first quarter of level 0 against 0.48 with this floor and 0.54 for farthest
// point; wang8, 32 to 128 points per tile, seed 1, docs/RESULTS.md).
constexpr double kVoidSpacingFloor = 0.7;

// Where a point of tile u can lie near another tile's points: placements[u] lists (t, shift,
// weight) for each tile t and block position with u among the tiles that fit there (the centre
// included: t == u, shift 0, weight 1), weight 1 / the number of tiles that fit.
struct Placement {
  std::size_t tile;
  Point shift;
  double weight;
};

std::vector<std::vector<Placement>> placements_of(const BlockConfigurations& configurations, std::size_t tile_count) {
  std::vector<std::vector<Placement>> placements(tile_count);
  for (std::size_t t = 0; t < tile_count; ++t)
    for (int p = 0; p < kBlockPositions; ++p) {
      const Point shift{static_cast<double>(block_dx(p)), static_cast<double>(block_dy(p))};
      const std::vector<int>& fits = configurations.candidates(static_cast<int>(t), p);
      for (int u : fits)
        placements[static_cast<std::size_t>(u)].push_back({t, shift, 1.0 / static_cast<double>(fits.size())});
    }
  return placements;
}

}  // namespace

std::vector<std::vector<std::uint32_t>> rank_level(const BlockConfigurations& configurations, const TilePoints& tiles,
                                                   std::size_t level_begin) {
  const std::size_t tile_count = tiles.size();
  const std::size_t size = tiles.empty() ? 0 : tiles[0].size();
  const std::size_t level = size - level_begin;
  const std::vector<std::vector<Placement>> placements = placements_of(configurations, tile_count);  // weights unused
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

std::vector<std::vector<std::uint32_t>> rank_level_by_voids(const BlockConfigurations& configurations,
                                                            const TilePoints& tiles, std::size_t level_begin,
                                                            double sigma_factor) {
  const std::size_t tile_count = tiles.size();
  const std::size_t size = tiles.empty() ? 0 : tiles[0].size();
  const std::size_t level = size - level_begin;
  const std::vector<std::vector<Placement>> placements = placements_of(configurations, tile_count);
  std::vector<std::vector<double>> energy(tile_count, std::vector<double>(level, 0.0));
  std::vector<std::vector<double>> nearest(tile_count, std::vector<double>(level, HUGE_VAL));
  std::vector<std::vector<bool>> ranked(tile_count, std::vector<bool>(level, false));
  double inv2s2 = 0.0, reach2 = 0.0;
  auto set_sigma = [&](std::size_t prefix) {
    const double sigma = sigma_factor * std::sqrt(2.0 / (std::sqrt(3.0) * static_cast<double>(prefix)));
    inv2s2 = 1.0 / (2.0 * sigma * sigma);
    reach2 = 16.0 * sigma * sigma;
  };
  bool refresh = false;  // energies rebuilt for a new sigma: the nearest distances stand
  auto add_ranked = [&](std::size_t u, Point y) {
    for (const Placement& at : placements[u]) {
      const Point shifted = y + at.shift;
      const std::vector<Point>& tile = tiles[at.tile];
      std::vector<double>& e = energy[at.tile];
      std::vector<double>& near = nearest[at.tile];
      for (std::size_t m = 0; m < level; ++m) {
        const Point d = tile[level_begin + m] - shifted;
        const double d2 = d.x * d.x + d.y * d.y;
        if (d2 < reach2) e[m] += at.weight * std::exp(-d2 * inv2s2);
        if (!refresh) near[m] = std::min(near[m], d2);
      }
    }
  };
  std::vector<std::vector<std::uint32_t>> order(tile_count);
  std::size_t sigma_prefix = 0;
  for (std::size_t s = 0; s < level; ++s) {
    const std::size_t prefix = level_begin + s + 1;  // the prefix each tile reaches this round
    if (sigma_prefix == 0 || static_cast<double>(prefix) > 1.25 * static_cast<double>(sigma_prefix)) {
      sigma_prefix = prefix;
      set_sigma(prefix);
      for (auto& e : energy) std::fill(e.begin(), e.end(), 0.0);
      refresh = s > 0;
      for (std::size_t u = 0; u < tile_count; ++u) {
        for (std::size_t k = 0; k < level_begin; ++k) add_ranked(u, tiles[u][k]);
        for (std::uint32_t k : order[u]) add_ranked(u, tiles[u][k]);
      }
      refresh = false;
    }
    for (std::size_t t = 0; t < tile_count; ++t) {
      // Among the points not much closer to a ranked one than the farthest is, the deepest void.
      double farthest = 0.0;
      for (std::size_t m = 0; m < level; ++m)
        if (!ranked[t][m]) farthest = std::max(farthest, nearest[t][m]);
      const double floor = kVoidSpacingFloor * kVoidSpacingFloor * farthest;  // squared distances
      std::size_t best = level;
      for (std::size_t m = 0; m < level; ++m)
        if (!ranked[t][m] && !(nearest[t][m] < floor) && (best == level || energy[t][m] < energy[t][best])) best = m;
      ranked[t][best] = true;
      order[t].push_back(static_cast<std::uint32_t>(level_begin + best));
      add_ranked(t, tiles[t][level_begin + best]);
    }
  }
  return order;
}

}  // namespace bluetile
