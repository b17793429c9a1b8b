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

class ExactEngine final : public CentroidEngine {
 public:
  ExactEngine();
  ~ExactEngine() override;
  std::string_view name() const override { return "exact"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;

  // How a density weights cells: whether it is uniform, and its prefix tables when it is not
  // (density_prefix.h). Kept per map across calls (a relaxation measures the same map every
  // iteration); the tables of the few maps seen last are kept. The cache makes compute unsafe
  // to call from two threads at once on one engine (one engine per thread instead).
  struct DensityEntry;

 private:
  const DensityEntry& density_entry(const std::shared_ptr<const DensityGrid>& density);
  std::vector<std::shared_ptr<const DensityEntry>> density_cache_;
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
