// Seam spacing: a short repulsion after the constrained Lloyd iterations of a level. Averaging
// Lloyd displacements over neighbour configurations leaves a point near an edge where it suits
// the mean neighbour, so some tile that may sit there can still bring a point close to it (the
// seam check's minimum, seamX, stays below the spacing inside tiles). Here every pair of points
// that can meet in a tiling (the same tile, or two tiles of an admissible 2x2 block at their
// offset in it) closer than `spacing` is pushed apart along the line joining them, Jacobi, a
// moving point taking half of the gap when its partner moves too and all of it when the partner
// is a fixed point of an earlier level. Pushes from one tile at one position, and from different
// positions, add up (those points coexist in a tiling); tiles that are alternatives at one
// position (a tiling holds one of them there) push by the strongest. Only the level's moving
// points move, inside their tile.
#pragma once

#include <cstddef>

#include "bluetile/relax/wang_step.h"
#include "bluetile/tiling/tile_set.h"

namespace bluetile {

struct SeamSpacingOptions {
  int iterations = 0;        // repulsion steps (0: none)
  double spacing = 0.0;      // tile units: pairs closer than this are pushed apart
  double edge_margin = 0.0;  // points stay in [margin, 1 - margin] of their tile
};

// What the steps left: the moving points still closer than the spacing to a point they can
// meet, and the steps run (the loop stops early once there is none).
struct SeamSpacingResult {
  std::size_t close_points = 0;
  int iterations = 0;
};

SeamSpacingResult space_seams(const TileRules& rules, WangPoints& points, const SeamSpacingOptions& options);

}  // namespace bluetile
