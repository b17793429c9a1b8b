// Lloyd relaxation (Lloyd 1982; the paper, section 2): every wanted site moves to the centroid
// of its Voronoi cell, repeatedly. Works on any CentroidEngine. Sites outside the scene's wanted
// range stay fixed, which is how hierarchical levels are relaxed around earlier ones (2.1). With
// a density in the scene the centroids are centres of mass under it, which makes this weighted
// Lloyd (Secord 2002): point density follows the map.
//
// One iteration is a Jacobi step in two parts: measuring (the engine computes every wanted cell
// from the same positions; lloyd_displacement reads a site's move off its cell) and applying
// (move_to_centroids). Loops that combine several measurements of one site before moving it, as
// the Wang-tile loop averages a site's displacements over neighbour configurations (paper,
// section 3), measure through the engine and apply their own mean.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/request_limits.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {

struct LloydIteration {
  int iteration = 0;            // 1-based
  double energy = 0.0;          // sum of cell second moments before the move (CVT energy)
  double max_displacement = 0.0;   // largest distance a site moved (on the torus when periodic)
  double mean_displacement = 0.0;
  std::size_t coincident = 0;   // sites that shared a position and stayed put
  std::size_t fallbacks = 0;    // cells measured by the exact fallback (raster engine)
  std::size_t zero_density = 0;  // sites whose cell has no density and that stayed put
};

struct LloydOptions {
  int iterations = kDefaultIterations;
  // Stop early once the largest displacement of an iteration is below this (domain units);
  // 0 runs all iterations.
  double tolerance = 0.0;
  // Called after every iteration (logging, progress).
  std::function<void(const LloydIteration&)> on_iteration{};
  // Keep every iteration's figures in LloydResult::history (memory grows with the iterations:
  // about 56 bytes each); otherwise only the last is kept.
  bool keep_history = false;
  // Whether to measure the energy. False: the engine is asked for no second moments (each
  // scene's Scene::second_moments is false during the run and restored after) and every
  // LloydIteration::energy is 0; the sites move bit for bit as with it.
  bool energy = true;
};

struct LloydResult {
  std::vector<LloydIteration> history;  // only with LloydOptions::keep_history
  LloydIteration last;                  // the last iteration run (iteration 0: none ran)
  int iterations = 0;                   // iterations run
  bool converged = false;               // stopped by the tolerance
};

// The weight under which Lloyd's sites settle with point density proportional to `target`:
// target^exponent. A centroidal Voronoi diagram's point density goes as the square root of its
// weight in the plane (Gersho 1979; Du, Faber, Gunzburger 1999, section 2.3), so exponent 2 keeps
// a set drawn in proportion to `target` where it is; exponent 1 is Secord 2002's weighting, under
// which the density ratio between regions drifts toward its square root as the set converges.
// Throws Error when the exponent is not in [0, kMaxWeightExponent] (past 8 a map's contrast of 10
// becomes 10^8 between cells, beyond what float texels keep apart); check_weight_exponent names
// it as `name` (a front end's spelling of the argument). weight_for_point_density also throws for a
// target that check_density_grid refuses (an empty one included).
inline constexpr double kDefaultWeightExponent = 2.0;
inline constexpr double kMaxWeightExponent = 8.0;
DensityGrid weight_for_point_density(const DensityGrid& target, double exponent = kDefaultWeightExponent);
void check_weight_exponent(double exponent, const char* name = "weight exponent");

// The memory of a relaxation of `sites` sites (over all sets) on `engine` ("exact" or "raster",
// as EngineChoice names them), the points included: the scene's copy, the cell results and the
// engine's own state (the exact engine's kept triangulation and search grid; the raster engine's
// device, cones, ID buffer and host pixel work), for up-front checks (core/memory_budget.h).
// Peak resident memory of `relax -k 2` from 2e5 to 4e6 sites, one set and sets: exact 312-447
// bytes a site (492 in `progressive`'s levels); raster on lavapipe 80 MiB for the device, then
// 740-935 bytes a site; rounded up with a margin of about a third (docs/BENCHMARKS.md, "Memory").
// (160 bytes a site for both, measured before the exact engine kept its topology, let through
// runs that then ran out of memory.) The test MemoryEstimates.* holds runs under it.
inline constexpr double kExactRelaxBytesPerSite = 640.0, kRasterRelaxBytesPerSite = 1024.0;
inline constexpr double kRasterEngineBytes = 128.0 * 1024 * 1024;
inline double relax_memory_bytes(double sites, std::string_view engine) {
  return engine == "exact" ? sites * kExactRelaxBytesPerSite : kRasterEngineBytes + sites * kRasterRelaxBytesPerSite;
}

// The move of a site to the centroid of its cell, in domain units: the shortest periodic offset
// on a torus, the plain difference in a bounded rectangle.
inline Point lloyd_displacement(const Scene& scene, Point site, const Cell& cell) {
  return scene_offset(scene, site, cell.centroid);
}

// Applies one plain Lloyd step: every wanted site of scenes[k] moves to its centroid in
// cells[k] (the engine's output for those scenes). Returns the step's log, with `iteration` 0.
// Throws Error, before any site moves, unless there is one SceneCells per scene and one cell per
// wanted site of it.
LloydIteration move_to_centroids(std::span<Scene> scenes, std::span<const SceneCells> cells);

// The indices of `sites` (all inside `domain`) in the row order of a grid of about one site per
// bucket, the sites of a bucket in index order: neighbours in the plane near each other in memory.
std::vector<std::uint32_t> grid_row_order(std::span<const Point> sites, const Domain& domain);

// Scenes with at least this many wanted sites are relaxed in grid_row_order. An engine reads each
// site and writes each cell at its index; in the caller's order (random for random sites) those
// are cache and TLB misses once the arrays outgrow the caches, and on two threads each thread
// reads cells the other one wrote (docs/BENCHMARKS.md, "Sites in grid order for the relaxation",
// and "Two threads at 10^4: smaller move chunks and grid order from 8192 sites").
inline constexpr std::size_t kGridOrderSites = std::size_t{1} << 13;

// Relaxes the wanted sites of every scene in place, all scenes in one engine call per
// iteration. The tolerance applies to the largest displacement over all scenes; the history
// sums over scenes. The wanted sites of a scene of kGridOrderSites or more are relaxed in
// grid_row_order and given back in their own order (also when the run throws); while it runs,
// on_iteration sees them in that order. The order is a function of the starting sites alone, so
// the result still is: the same bits for any thread count. It is not bit for bit the result of
// relaxing in the caller's order: a cell's sums start at its neighbour of lowest index
// (periodic_delaunay.h), and coincident sites leave the cell to the lower index.
// No scenes: no iteration runs (result.iterations 0). Throws Error for iterations below 0 or a
// tolerance that is negative or not a number (both were run as 0).
LloydResult relax_lloyd(CentroidEngine& engine, std::vector<Scene>& scenes, const LloydOptions& options);

// One scene, given back however the run ends (an interrupt throws).
inline LloydResult relax_lloyd(CentroidEngine& engine, Scene& scene, const LloydOptions& options) {
  struct Borrowed {
    Scene& scene;
    std::vector<Scene> scenes;
    ~Borrowed() {
      if (!scenes.empty()) scene = std::move(scenes[0]);
    }
  } borrowed{scene, {}};
  borrowed.scenes.push_back(std::move(scene));
  return relax_lloyd(engine, borrowed.scenes, options);
}

}  // namespace bluetile
