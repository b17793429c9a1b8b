// Cropped scenes of a 3x3 block of tiles (see wang_crop.h for the method and its guarantee).
#include "bluetile/relax/wang_crop.h"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>

namespace bluetile {
namespace {

// Distance from p to the square [x0, x0+1] x [y0, y0+1].
double distance_to_square(Point p, double x0, double y0) {
  double gx = std::max({x0 - p.x, 0.0, p.x - (x0 + 1.0)});
  double gy = std::max({y0 - p.y, 0.0, p.y - (y0 + 1.0)});
  return std::sqrt(gx * gx + gy * gy);
}

bool inside(Point p, Point low, Point high) { return p.x >= low.x && p.x <= high.x && p.y >= low.y && p.y <= high.y; }

}  // namespace

PositionMask visible_positions(Point point, double reach) {
  PositionMask mask = kCentreOnly;
  for (int p = 0; p < kBlockPositions; ++p) {
    if (p == kBlockCentre) continue;
    if (distance_to_square(point, block_dx(p), block_dy(p)) < reach) mask |= PositionMask{1} << p;
  }
  return mask;
}

CropGroup make_crop_group(int centre, PositionMask mask, std::vector<std::uint32_t> wanted,
                          std::span<const Point> centre_points, std::span<const double> reach) {
  assert(!wanted.empty() && wanted.size() == reach.size());
  CropGroup group;
  group.centre = centre;
  group.mask = mask | kCentreOnly;
  group.wanted = std::move(wanted);
  double max_reach = 0.0;
  Point low{HUGE_VAL, HUGE_VAL}, high{-HUGE_VAL, -HUGE_VAL};
  for (std::size_t i = 0; i < group.wanted.size(); ++i) {
    Point p = centre_points[group.wanted[i]];
    low = {std::min(low.x, p.x - reach[i]), std::min(low.y, p.y - reach[i])};
    high = {std::max(high.x, p.x + reach[i]), std::max(high.y, p.y + reach[i])};
    max_reach = std::max(max_reach, reach[i]);
  }
  // Nothing lies outside the block: a box reaching past it stops there.
  group.low = {std::max(low.x, -1.0), std::max(low.y, -1.0)};
  group.high = {std::min(high.x, 2.0), std::min(high.y, 2.0)};
  group.pad = max_reach;

  group.clearance.resize(group.wanted.size());
  for (std::size_t i = 0; i < group.wanted.size(); ++i) {
    Point p = centre_points[group.wanted[i]];
    // Periodic copies of the scene's sites lie at least two pads away.
    double c = 2.0 * group.pad;
    // Sites beyond a side of the box that lies inside the block are left out.
    if (group.low.x > -1.0) c = std::min(c, p.x - group.low.x);
    if (group.low.y > -1.0) c = std::min(c, p.y - group.low.y);
    if (group.high.x < 2.0) c = std::min(c, group.high.x - p.x);
    if (group.high.y < 2.0) c = std::min(c, group.high.y - p.y);
    // So are the sites of positions whose tile the configuration does not fix.
    for (int q = 0; q < kBlockPositions; ++q)
      if (!(group.mask & (PositionMask{1} << q))) c = std::min(c, distance_to_square(p, block_dx(q), block_dy(q)));
    group.clearance[i] = c;
  }
  return group;
}

CropSceneMaker::CropSceneMaker(const CropGroup& group, const TilePoints& tiles)
    : group_(group), tiles_(tiles), origin_(group.low - Point{group.pad, group.pad}) {
  const std::vector<Point>& centre = tiles[static_cast<std::size_t>(group.centre)];
  centre_.reserve(centre.size());
  for (std::uint32_t k : group.wanted) centre_.push_back(centre[k] - origin_);
  // The centre's other points, in index order (the wanted indices are sorted).
  assert(std::is_sorted(group.wanted.begin(), group.wanted.end()));
  std::size_t next_wanted = 0;
  for (std::uint32_t k = 0; k < centre.size(); ++k) {
    if (next_wanted < group.wanted.size() && group.wanted[next_wanted] == k) {
      ++next_wanted;
      continue;
    }
    if (inside(centre[k], group.low, group.high)) centre_.push_back(centre[k] - origin_);
  }
  parts_.resize(static_cast<std::size_t>(kBlockPositions) * tiles.size());
  made_.assign(parts_.size(), 0);
}

const std::vector<Point>& CropSceneMaker::part(int position, int tile) {
  const std::size_t slot = static_cast<std::size_t>(position) * tiles_.size() + static_cast<std::size_t>(tile);
  std::vector<Point>& points = parts_[slot];
  if (made_[slot]) return points;
  made_[slot] = 1;
  const Point shift{static_cast<double>(block_dx(position)), static_cast<double>(block_dy(position))};
  for (Point q : tiles_[static_cast<std::size_t>(tile)]) {
    const Point b = q + shift;
    if (inside(b, group_.low, group_.high)) points.push_back(b - origin_);
  }
  return points;
}

Scene CropSceneMaker::make(const BlockConfiguration& block) {
  assert(block.tiles[kBlockCentre] == group_.centre);
  std::array<const std::vector<Point>*, kBlockPositions> known{};
  std::size_t count = centre_.size();
  for (int p = 0; p < kBlockPositions; ++p) {
    if (p == kBlockCentre || !(group_.mask & (PositionMask{1} << p))) continue;
    const int tile = block.tiles[static_cast<std::size_t>(p)];
    assert(tile >= 0 && static_cast<std::size_t>(tile) < tiles_.size());
    known[static_cast<std::size_t>(p)] = &part(p, tile);
    count += known[static_cast<std::size_t>(p)]->size();
  }
  Scene scene;
  scene.domain.size = group_.high - group_.low + Point{2.0 * group_.pad, 2.0 * group_.pad};
  scene.sites.reserve(count);
  scene.sites.assign(centre_.begin(), centre_.end());
  for (const std::vector<Point>* points : known)
    if (points) scene.sites.insert(scene.sites.end(), points->begin(), points->end());
  scene.wanted_begin = 0;
  scene.wanted_end = group_.wanted.size();
  return scene;
}

Scene make_crop_scene(const CropGroup& group, const BlockConfiguration& block, const TilePoints& tiles) {
  return CropSceneMaker(group, tiles).make(block);
}

}  // namespace bluetile
