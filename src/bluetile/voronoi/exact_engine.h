// The exact CPU centroid engine: periodic Voronoi cells as exact polygons in double precision.
//
// A cell can be measured two ways, which agree to rounding (about 1e-16; tests hold them within
// 1e-12):
// - the search (cell_search.h): the W x H rectangle centred on the site (on a torus no point is
//   farther than half a period from the nearest copy of the site along either axis; in a bounded
//   domain the domain itself), clipped by the bisectors of the other sites and their periodic
//   images, visited ring by ring through a uniform grid, nearest first, until no unvisited site
//   can be closer than twice the cell's farthest vertex;
// - the Delaunay triangulation of the sites kept between calls (kept_delaunay.h): a Lloyd step
//   moves sites so little that the triangulation of the step before, moved and repaired by a
//   few edge flips with exact predicates, is the new one; a cell's vertices are the circumcentres
//   of the triangles around its site.
// With a density, the finished polygon's weighted moments come from density_prefix.h (row prefix
// tables of the map, built once per map and kept by the engine). All geometry is relative to the
// site, so precision does not depend on where the site is.
#pragma once

#include <memory>
#include <vector>

#include "bluetile/voronoi/engine.h"

namespace bluetile {

class DensityPrefix;

// Topology kept between calls (kept_delaunay.h): periodic scenes of at least 256 sites are
// measured through a Delaunay triangulation kept per place in the batch, built from the search at
// the first call and repaired by flips at the next calls on a scene of the same shape (site
// count, wanted range, domain). A result is a function of the scene alone, never of the calls
// before it nor of the thread count: the triangulation of a set of sites is unique (cocircular
// ties broken by a symbolic perturbation), a cell's arithmetic is canonical, and a scene or cell
// goes to the search only for properties of its sites (bounded domains, fewer sites, coincident
// sites, an empty circle of a tenth of a period or more, cells on an exact cocircular tie). Off:
// every cell is searched (the reference the tests compare with); ExactEngine() turns it off when
// the environment sets BLUETILE_EXACT_KEEP_TOPOLOGY=0.
//
// simd: the triangulation's sweep four triangles at a time, and its cells four at a time, where
// the processor has AVX2 and the environment does not set BLUETILE_SIMD=0; the same bits as one
// at a time (delaunay_sweep.h).
struct ExactEngineOptions {
  bool keep_topology = true;
  bool simd = true;
};
ExactEngineOptions default_exact_engine_options();

// What the kept triangulations did in the last call (summed over the scenes of the batch).
struct KeptTopologyStats {
  std::size_t kept_cells = 0;      // measured from a kept triangulation
  std::size_t searched_cells = 0;  // measured by the search (scenes it does not suit, ties)
  std::size_t tie_cells = 0;       // of those, cells on an exact cocircular tie
  std::size_t flips = 0;           // edge flips that repaired kept triangulations
  std::size_t rebuilds = 0;        // triangulations built from the search (first calls, large moves)
  std::size_t exact_stars = 0;     // of their vertices, stars computed with exact predicates (ties)
  std::size_t repaired_vertices = 0;  // vertices removed and inserted again after large moves
  std::size_t bytes = 0;           // memory the kept state holds now
};

class KeptDelaunay;

class ExactEngine final : public CentroidEngine {
 public:
  ExactEngine();
  explicit ExactEngine(ExactEngineOptions options);
  ~ExactEngine() override;
  std::string_view name() const override { return "exact"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;

  // How a density weights cells: whether it is uniform, and its prefix tables when it is not
  // (density_prefix.h). Kept per map across calls (a relaxation measures the same map every
  // iteration); the tables of the few maps seen last are kept. The cache makes compute unsafe
  // to call from two threads at once on one engine (one engine per thread instead).
  struct DensityEntry;

  // Forgets the kept triangulations (the next call builds them again).
  void forget_topology();
  const KeptTopologyStats& last_topology_stats() const { return stats_; }

 private:
  const DensityEntry& density_entry(const std::shared_ptr<const DensityGrid>& density);
  std::vector<std::shared_ptr<const DensityEntry>> density_cache_;
  ExactEngineOptions options_;
  std::vector<std::unique_ptr<KeptDelaunay>> kept_;  // per scene of the batch
  KeptTopologyStats stats_;
};

// The cell polygon of one site, vertices counter-clockwise relative to the site (for drawing
// and tests). Empty for a coincident site.
std::vector<Point> exact_cell_polygon(const Scene& scene, std::size_t site);

// Every site's cell polygon (as exact_cell_polygon), the search grid built once for all: for
// drawing all cells or measuring their shapes. On all threads; same result whatever their count.
std::vector<std::vector<Point>> exact_cell_polygons(const Scene& scene);

// Indices of the sites whose cells share an edge with `site`'s cell (periodic images folded
// onto their site index; `site` itself when the cell touches its own copy; a bounded domain's
// border is no neighbour).
std::vector<std::size_t> exact_cell_neighbours(const Scene& scene, std::size_t site);

}  // namespace bluetile
