#include "tiler_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "bluetile/core/rng.h"

namespace bluetile::test {

TileSet make_test_tile_set(TileSetKind kind, int side, std::uint64_t seed, bool same_points) {
  TileRules rules(kind);
  TileSet set;
  set.kind = kind;
  set.header.push_back("test set: jittered grid, greedy farthest-point ranks");
  Rng rng(seed);
  const int n = side * side;
  for (int t = 0; t < rules.tile_count(); ++t) {
    if (same_points && t > 0) {
      Tile copy = set.tiles[0];
      copy.colours = rules.colours(t);
      set.tiles.push_back(std::move(copy));
      continue;
    }
    Tile tile;
    tile.colours = rules.colours(t);
    for (int r = 0; r < side; ++r)
      for (int c = 0; c < side; ++c) {
        // Jitter within 60 % of each grid cell: the points stay in [0, 1) and apart.
        double x = (c + 0.2 + 0.6 * rng.uniform()) / side, y = (r + 0.2 + 0.6 * rng.uniform()) / side;
        tile.points.push_back({x, y});
      }
    // Greedy farthest point on the tile's torus: each next rank is the point farthest from the
    // ranked ones.
    std::vector<double> gap(n, std::numeric_limits<double>::infinity());
    std::vector<bool> taken(n, false);
    tile.ranks.assign(n, 0);
    tile.levels.assign(n, 0);
    int next = static_cast<int>(rng.below(static_cast<std::uint64_t>(n)));
    for (int rank = 0; rank < n; ++rank) {
      taken[next] = true;
      tile.ranks[next] = static_cast<std::uint32_t>(rank);
      tile.levels[next] = rank < n / 4 ? 0 : 1;
      int best = -1;
      for (int k = 0; k < n; ++k) {
        if (taken[k]) continue;
        gap[k] = std::min(gap[k], torus_distance_squared(tile.points[k], tile.points[next], Domain{}));
        if (best < 0 || gap[k] > gap[best]) best = k;
      }
      next = best;
    }
    set.tiles.push_back(std::move(tile));
  }
  return set;
}

double min_distance(const std::vector<Point>& points) {
  const std::size_t n = points.size();
  if (n < 2) return std::numeric_limits<double>::infinity();
  double x0 = points[0].x, y0 = points[0].y, x1 = x0, y1 = y0;
  for (Point p : points) x0 = std::min(x0, p.x), y0 = std::min(y0, p.y), x1 = std::max(x1, p.x), y1 = std::max(y1, p.y);
  // Buckets of about 2 points each; a pair closer than `reach` buckets is found in the
  // (2 reach + 1)^2 block around either point, so the search widens until the best pair is.
  double cell = std::sqrt(std::max((x1 - x0) * (y1 - y0), 1e-300) / static_cast<double>(n) * 2.0);
  using Key = std::pair<long long, long long>;
  auto key = [&](Point p) {
    return Key(static_cast<long long>(std::floor((p.x - x0) / cell)), static_cast<long long>(std::floor((p.y - y0) / cell)));
  };
  struct Hash {
    std::size_t operator()(const Key& k) const { return std::hash<long long>()(k.first * 1000003LL + k.second); }
  };
  std::unordered_map<Key, std::vector<std::size_t>, Hash> grid;
  for (std::size_t k = 0; k < n; ++k) grid[key(points[k])].push_back(k);
  double best = std::numeric_limits<double>::infinity();
  for (long long reach = 1;; ++reach) {
    for (std::size_t a = 0; a < n; ++a) {
      Key k = key(points[a]);
      for (long long dy = -reach; dy <= reach; ++dy)
        for (long long dx = -reach; dx <= reach; ++dx) {
          auto it = grid.find({k.first + dx, k.second + dy});
          if (it == grid.end()) continue;
          for (std::size_t b : it->second)
            if (b != a) best = std::min(best, std::hypot(points[a].x - points[b].x, points[a].y - points[b].y));
        }
    }
    if (best <= static_cast<double>(reach) * cell) return best;
  }
}

}  // namespace bluetile::test
