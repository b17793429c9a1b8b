// The seam check of a tile set and torus tilings of it (see seam_check.h).
#include "bluetile/tiling/seam_check.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "bluetile/core/error.h"
#include "bluetile/tiling/tile_set_file.h"

namespace bluetile {
namespace {

Point relation_shift(TileRelation relation) {
  switch (relation) {
    case TileRelation::east: return {1.0, 0.0};
    case TileRelation::north: return {0.0, 1.0};
    case TileRelation::north_east: return {1.0, 1.0};
    case TileRelation::north_west: return {-1.0, 1.0};
  }
  return {0.0, 0.0};
}

double distance_to_square(Point p, Point corner) {
  double gx = std::max({corner.x - p.x, 0.0, p.x - (corner.x + 1.0)});
  double gy = std::max({corner.y - p.y, 0.0, p.y - (corner.y + 1.0)});
  return std::sqrt(gx * gx + gy * gy);
}

struct Indexed {
  Point p;
  std::size_t index;
};

// Smallest distance between two points of one tile, by a sweep along x.
double within_minimum(std::vector<Indexed> points) {
  std::sort(points.begin(), points.end(), [](const Indexed& a, const Indexed& b) {
    return a.p.x < b.p.x || (a.p.x == b.p.x && a.index < b.index);
  });
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size() && points[j].p.x - points[i].p.x < best; ++j) {
      Point d = points[j].p - points[i].p;
      best = std::min(best, std::sqrt(d.x * d.x + d.y * d.y));
    }
  }
  return best;
}

// Smallest distance between a point of `first` (tile at the origin) and one of `second` shifted
// by `shift`. A pair closer than `cut` has each point within `cut` of the other tile's square,
// so only those take part; the cut doubles until the minimum lies below it.
double cross_minimum(const std::vector<Indexed>& first, const std::vector<Indexed>& second, Point shift, double cut,
                     std::size_t& first_point, std::size_t& second_point) {
  for (;; cut *= 2.0) {
    std::vector<Indexed> a, b;
    for (const Indexed& p : first)
      if (distance_to_square(p.p, shift) < cut) a.push_back(p);
    for (const Indexed& q : second) {
      Indexed s{q.p + shift, q.index};
      if (distance_to_square(s.p, {0.0, 0.0}) < cut) b.push_back(s);
    }
    double best = std::numeric_limits<double>::infinity();
    for (const Indexed& p : a) {
      for (const Indexed& q : b) {
        Point d = q.p - p.p;
        double distance = std::sqrt(d.x * d.x + d.y * d.y);
        if (distance < best) {
          best = distance;
          first_point = p.index;
          second_point = q.index;
        }
      }
    }
    // Beyond 3 tile units every pair of the two squares has been seen.
    if (best < cut || cut > 3.0) return best;
  }
}

}  // namespace

SeamCheck check_seams(const TileSet& set) {
  validate_tile_set(set);
  const TileRules rules(set.kind);
  SeamCheck check;
  std::set<std::tuple<int, int, TileRelation>> pairs;
  rules.for_each_block(2, 2, [&](std::span<const int> block) {
    ++check.blocks;
    pairs.insert({block[0], block[1], TileRelation::east});
    pairs.insert({block[2], block[3], TileRelation::east});
    pairs.insert({block[0], block[2], TileRelation::north});
    pairs.insert({block[1], block[3], TileRelation::north});
    pairs.insert({block[0], block[3], TileRelation::north_east});
    pairs.insert({block[1], block[2], TileRelation::north_west});
  });
  check.tile_pairs = pairs.size();

  std::set<int> levels;
  for (const Tile& tile : set.tiles) levels.insert(tile.levels.begin(), tile.levels.end());
  if (levels.empty()) throw Error("the tile set holds no points");
  for (int level : levels) {
    SeamLevel result;
    result.level = level;
    std::vector<std::vector<Indexed>> prefix(set.tiles.size());
    result.points_per_tile = std::numeric_limits<std::size_t>::max();
    for (std::size_t t = 0; t < set.tiles.size(); ++t) {
      const Tile& tile = set.tiles[t];
      for (std::size_t k = 0; k < tile.points.size(); ++k)
        if (tile.levels[k] <= level) prefix[t].push_back({tile.points[k], k});
      result.points_per_tile = std::min(result.points_per_tile, prefix[t].size());
      result.within_min = std::min(result.within_min, within_minimum(prefix[t]));
    }
    result.spacing = hexagonal_spacing(static_cast<double>(std::max<std::size_t>(result.points_per_tile, 1)));
    const double cut = 2.0 * result.spacing;
    for (const auto& [a, b, relation] : pairs) {
      std::size_t pa = 0, pb = 0;
      double d = cross_minimum(prefix[static_cast<std::size_t>(a)], prefix[static_cast<std::size_t>(b)],
                               relation_shift(relation), cut, pa, pb);
      if (d < result.cross_min) {
        result.cross_min = d;
        result.closest = {a, b, relation, pa, pb};
      }
    }
    check.levels.push_back(result);
  }
  return check;
}

TiledPlane torus_tiling(const TileSet& set, int period, std::uint64_t seed, std::uint32_t max_rank) {
  if (period < 1) throw Error("a torus tiling needs a period of at least 1, got " + std::to_string(period));
  const TileRules rules(set.kind);
  TiledPlane plane;
  plane.period = period;
  const double scale = 1.0 / static_cast<double>(period);
  for (int j = 0; j < period; ++j) {
    for (int i = 0; i < period; ++i) {
      const int id = rules.tile_at_periodic(i, j, seed, period);
      plane.cell_tiles.push_back(id);
      const Tile& tile = set.tiles[static_cast<std::size_t>(id)];
      for (std::size_t k = 0; k < tile.points.size(); ++k) {
        if (tile.ranks[k] >= max_rank) continue;
        // wrap_point: (period - 1 + x) / period can round up to 1.
        plane.points.push_back(wrap_point({(static_cast<double>(i) + tile.points[k].x) * scale,
                                           (static_cast<double>(j) + tile.points[k].y) * scale},
                                          Domain{}));
        plane.levels.push_back(tile.levels[k]);
        plane.ranks.push_back(tile.ranks[k]);
      }
    }
  }
  return plane;
}

}  // namespace bluetile
