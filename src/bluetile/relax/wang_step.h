// One Jacobi step of Lloyd relaxation with multiple edge constraints (the paper, section 3): the
// Lloyd displacement of every moving point of every tile, averaged over neighbour configurations
// its tile can be placed in, all measured from the same positions. Nothing moves here; the loop
// (wang_relax.h) applies the means.
//
// Strategies (which configurations, and how the scenes are built):
//  - exact: the mean over every admissible 3x3 block around the tile. Points are grouped by the
//    neighbour positions they see (wang_crop.h), and each group gets one cropped scene per
//    distinct configuration of those positions, weighted by the blocks it stands for
//    (wang_blocks.h). A cell that is not provably complete grows its group's reach and is
//    measured again. This is the oracle the others are compared with.
//  - instances: a fresh seeded random period x period torus tiling as one periodic scene; a
//    point's displacement is the mean over its tile's instances.
//  - rounds: a few whole blocks per tile, chosen so that every tile that fits an edge appears
//    there once (the paper's Figure 5 reading).
// All scenes of a step go to the engine in one call (a second one only for regrown cells).
#pragma once

#include <algorithm>
#include <cmath>

#include <cstdint>
#include <string_view>
#include <vector>

#include "bluetile/relax/wang_blocks.h"
#include "bluetile/relax/wang_crop.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {


// A tile-local coordinate kept in [margin, 1 - margin] and below 1 (tiles cover [0, 1)): where
// every step of a level's relaxation leaves its moving points.
inline Point inside_tile(Point p, double margin) {
  const double top = std::min(1.0 - margin, std::nextafter(1.0, 0.0));
  return {std::clamp(p.x, margin, top), std::clamp(p.y, margin, top)};
}

// The tiles' points while a level is relaxed, tile-local in [0,1)^2, one list per tile id, all of
// the same size: points [moving_begin, size) of each tile move (the level being relaxed), earlier
// ones are fixed and only shape the cells.
struct WangPoints {
  TilePoints tiles;
  std::size_t moving_begin = 0;

  std::size_t moving_count() const { return tiles.empty() ? 0 : tiles[0].size() - moving_begin; }
};

struct WangStepOptions {
  WangStrategy strategy = WangStrategy::exact;
  int period = 16;          // instances: the torus tiling is period x period tiles
  std::uint64_t seed = 1;   // instances and rounds: this step's configurations
};

// What a step measured, per tile and moving point (index k - moving_begin).
struct WangStep {
  std::vector<std::vector<Point>> displacement;  // mean displacement, tile units
  std::vector<std::vector<double>> cell_radius;  // largest cell radius over the configurations (cropping)
  std::vector<std::vector<double>> weight;       // configurations (blocks or instances) the mean is over
  double energy = 0.0;         // sum over points of the mean cell second moment
  std::size_t scenes = 0;      // scenes the engine measured, regrown ones included
  std::size_t cells = 0;       // wanted cells in them
  std::size_t regrown = 0;     // point measurements redone because a cell was not provably complete
  std::size_t coincident = 0;  // cells of sites sharing a position
  std::size_t fallbacks = 0;   // cells the raster engine measured by the exact fallback
};

// Carries each moving point's reach (twice its cell radius, with room for motion) from one step
// to the next, so crops start the right size. Empty before the first step.
struct WangReach {
  std::vector<std::vector<double>> reach;
};

// Measures one step. `configurations` must be made from the points' tile rules. Throws Error when
// a cell cannot be proved complete within the 3x3 block (tiles with too few points).
WangStep measure_wang_step(CentroidEngine& engine, BlockConfigurations& configurations, const WangPoints& points,
                           const WangStepOptions& options, WangReach& reach);

}  // namespace bluetile
