// The exact CPU centroid engine: periodic Voronoi cells as exact polygons in double precision.
//
// Each wanted site's cell starts as the W x H rectangle centred on the site (on a torus no
// point is farther than half a period from the nearest copy of the site along either axis)
// and is clipped by the bisectors of the other sites and their periodic images, visited ring
// by ring through a uniform grid, nearest first. In a bounded domain the cell starts as the
// domain itself and only the sites, no images, clip it. With a density, the finished polygon's
// weighted moments come from density_prefix.h (row prefix tables of the map, built once per map
// and kept by the engine). The search stops once no unvisited site can
// be closer than twice the cell's farthest vertex: such a site's bisector misses the cell.
// All geometry is relative to the site, so precision does not depend on where the site is.
#pragma once

#include <memory>
#include <vector>

#include "bluetile/voronoi/engine.h"

namespace bluetile {

class DensityPrefix;

// Topology kept between calls (kept_topology.h): after a call that measured a scene of at least
// kMinSites sites, each wanted cell keeps a list of the sites near it (within 2.6 times its
// radius) and the positions they had. The next call on a scene with the same place in the batch,
// site count, wanted range, domain and boundary clips each cell against its list only, and
// certifies the result: the list is complete for the new cell when the cell's reach (twice its
// radius) plus how far its site and the farthest-moved site of the scene moved since the list was
// made stays inside the list's radius. Cells whose certificate fails (and coincident ones) are
// computed by the full search, as are all cells of a call whose sites moved too far. Results
// agree with the full search to rounding (the same bisectors clip the cell, in another order),
// and are the same bits whatever the thread count.
// Off by default: kept cells agree with searched ones to rounding (about 1e-16), not bit for bit,
// so with it on a result depends on the calls the engine saw before (same bits for any thread
// count still). ExactEngine() turns it on when the environment sets BLUETILE_EXACT_KEEP_TOPOLOGY=1.
struct ExactEngineOptions {
  bool keep_topology = false;
};
ExactEngineOptions default_exact_engine_options();

// What the kept topology did in the last call (summed over the scenes of the batch).
struct KeptTopologyStats {
  std::size_t kept_cells = 0;      // certified from the kept lists
  std::size_t searched_cells = 0;  // measured by the full search (first calls, fallbacks)
  std::size_t failed_cells = 0;    // of those, cells whose kept list failed its certificate
  std::size_t list_entries = 0;    // entries of the lists now held
  std::size_t bytes = 0;           // memory the kept state holds now
};

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

  // Forgets the kept topology (the next call searches every cell).
  void forget_topology();
  const KeptTopologyStats& last_topology_stats() const { return stats_; }
  struct Topology;  // kept_topology.h

 private:
  const DensityEntry& density_entry(const std::shared_ptr<const DensityGrid>& density);
  std::vector<std::shared_ptr<const DensityEntry>> density_cache_;
  ExactEngineOptions options_;
  std::vector<std::unique_ptr<Topology>> topology_;  // per scene of the batch
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
