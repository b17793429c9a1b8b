// Cropped scenes of a 3x3 block of tiles, for the Wang-tile loop (the paper, section 3): a scene
// carries only the sites that can reach a wanted cell, and a cell is accepted only when it is
// provably the cell it would be with every site of the block present.
//
// Block coordinates: the centre tile covers [0,1]^2, the block [-1,2]^2, and the tile at position
// p is shifted by (block_dx(p), block_dy(p)). The block is the whole world of a configuration: the
// mean over configurations is the mean over admissible 3x3 blocks around the tile. A group of
// centre-tile points that see the same neighbour positions (mask) shares a crop box: the bounding
// box of the points grown by their reach (twice an upper estimate of their cell radius), within
// the block. A scene holds the group's points (wanted), then every other site of the centre tile
// and of the known positions inside the box, in a periodic domain one reach wider than the box
// on each side, so that periodic copies stay at least two reaches away. A cell of radius R is
// complete when 2 R is at most the clearance of its site: the distance to the nearest site the
// scene could miss (beyond a box side inside the block, in an unknown position, or a periodic
// copy); no site farther than 2 R can touch the cell (the exact engine's own stopping rule).
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/relax/wang_blocks.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {

struct CropGroup {
  int centre = 0;
  PositionMask mask = kCentreOnly;
  std::vector<std::uint32_t> wanted;  // indices into the centre tile's points
  Point low{}, high{};                // the crop box, block coordinates
  double pad = 0.0;                   // the domain's margin around the box
  std::vector<double> clearance;      // per wanted point, see above
};

// The positions of the block whose squares lie closer than `reach` to `point` (block coordinates
// of a centre-tile point), and the centre.
PositionMask visible_positions(Point point, double reach);

// A group of the centre tile's points `wanted` (indices into `centre_points`), with reach[i] the
// reach of wanted[i]; `mask` must hold every position visible_positions gives for them.
CropGroup make_crop_group(int centre, PositionMask mask, std::vector<std::uint32_t> wanted,
                          std::span<const Point> centre_points, std::span<const double> reach);

// Per tile id, the sites it brings to a scene, tile-local: every point of the tile, the wanted
// ones (when it is the centre) among them.
using TilePoints = std::vector<std::vector<Point>>;

// The scenes of one group, configuration by configuration. The scene of `block` (its tiles at
// the group's known positions) holds the wanted points in group order, then the centre's other
// points, then the known positions' points, each in position order, all inside the crop box.
// Each part (the centre's points, the points one tile brings at one position) is cut to the box
// once for all of the group's configurations: a group has about 16 of them, and its scenes
// about 15 sites out of the block's hundreds. `group` and `tiles` must outlive the maker.
class CropSceneMaker {
 public:
  CropSceneMaker(const CropGroup& group, const TilePoints& tiles);
  Scene make(const BlockConfiguration& block);

 private:
  const std::vector<Point>& part(int position, int tile);

  const CropGroup& group_;
  const TilePoints& tiles_;
  Point origin_{};
  std::vector<Point> centre_;             // wanted, then the centre's other points in the box
  std::vector<std::vector<Point>> parts_;  // [position * tiles + tile], relative to the origin
  std::vector<std::uint8_t> made_;
};

// The scene of `group` in the configuration `block`, as CropSceneMaker makes it.
Scene make_crop_scene(const CropGroup& group, const BlockConfiguration& block, const TilePoints& tiles);

// Is the cell of the group's wanted point i, measured in one of its scenes, complete?
inline bool crop_cell_complete(const CropGroup& group, std::size_t i, const Cell& cell) {
  // The slack absorbs the rounding of the cell's vertices (relative 1e-12 is far above it).
  return 2.0 * cell.radius * (1.0 + 1e-12) <= group.clearance[i];
}

}  // namespace bluetile
