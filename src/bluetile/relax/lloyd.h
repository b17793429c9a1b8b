// Lloyd relaxation (Lloyd 1982; the paper, section 2): every wanted site moves to the centroid
// of its Voronoi cell, repeatedly. Works on any CentroidEngine. Sites outside the scene's wanted
// range stay fixed, which is how hierarchical levels are relaxed around earlier ones (2.1).
//
// One iteration is a Jacobi step in two parts: measuring (the engine computes every wanted cell
// from the same positions; lloyd_displacement reads a site's move off its cell) and applying
// (move_to_centroids). Loops that combine several measurements of one site before moving it, as
// the Wang-tile loop averages a site's displacements over neighbour configurations (paper,
// section 3), measure through the engine and apply their own mean.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "bluetile/voronoi/engine.h"

namespace bluetile {

struct LloydIteration {
  int iteration = 0;            // 1-based
  double energy = 0.0;          // sum of cell second moments before the move (CVT energy)
  double max_displacement = 0.0;   // largest torus distance a site moved
  double mean_displacement = 0.0;
  std::size_t coincident = 0;   // sites that shared a position and stayed put
  std::size_t fallbacks = 0;    // cells measured by the exact fallback (raster engine)
};

struct LloydOptions {
  int iterations = 80;
  // Stop early once the largest displacement of an iteration is below this (domain units);
  // 0 runs all iterations.
  double tolerance = 0.0;
  // Called after every iteration (logging, progress).
  std::function<void(const LloydIteration&)> on_iteration;
};

struct LloydResult {
  std::vector<LloydIteration> history;
  bool converged = false;  // stopped by the tolerance
};

// The move of a site to the centroid of its cell: the torus offset from `site` to
// `cell.centroid` in `domain`, in domain units.
inline Point lloyd_displacement(Point site, const Cell& cell, const Domain& domain) {
  return torus_offset(site, cell.centroid, domain);
}

// Applies one plain Lloyd step: every wanted site of scenes[k] moves to its centroid in
// cells[k] (the engine's output for those scenes). Returns the step's log, with `iteration` 0.
LloydIteration move_to_centroids(std::span<Scene> scenes, std::span<const SceneCells> cells);

// Relaxes the wanted sites of every scene in place, all scenes in one engine call per
// iteration. The tolerance applies to the largest displacement over all scenes; the history
// sums over scenes.
LloydResult relax_lloyd(CentroidEngine& engine, std::vector<Scene>& scenes, const LloydOptions& options);

inline LloydResult relax_lloyd(CentroidEngine& engine, Scene& scene, const LloydOptions& options) {
  std::vector<Scene> scenes{std::move(scene)};
  LloydResult result = relax_lloyd(engine, scenes, options);
  scene = std::move(scenes[0]);
  return result;
}

}  // namespace bluetile
