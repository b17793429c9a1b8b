// The exact engine's cell search: a site's periodic Voronoi cell as an exact polygon in double
// precision, the W x H rectangle centred on the site (on a torus no point is farther than half
// a period from the nearest copy of the site along either axis; in a bounded domain the domain
// itself) clipped by the bisectors of the other sites and their periodic images, visited ring by
// ring through a uniform grid, nearest first, until no unvisited site can be closer than twice
// the cell's farthest vertex (its bisector then misses the cell). Far-from-uniform sites (on a
// line, in a cluster) are searched through a k-d tree instead (site_tree.h). All geometry is
// relative to the site, so precision does not depend on where the site is.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "bluetile/voronoi/cell_measure.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/site_grid.h"
#include "bluetile/voronoi/site_tree.h"

namespace bluetile {

// The label of the cell edges that come from the initial rectangle (the site's own copies).
inline constexpr std::uint32_t kOwnCopy = kUnlabelled;

// The neighbour search of one scene: the uniform grid, and the tree for far-from-uniform sites.
struct CellSearch {
  SiteGrid grid;
  std::optional<SiteTree> tree;

  explicit CellSearch(const Scene& scene);
};

// Per-thread buffers of the searches, reused from cell to cell.
struct SearchScratch {
  struct Candidate {
    double distance_squared;
    Point offset;
    std::uint32_t site;
  };
  std::vector<Candidate> candidates;
  SiteTree::Search tree;
};

// Computes the cell of `site`, at `origin` (its position), into `cell_polygon`, relative to the
// site; each edge is labelled with the site whose bisector carries it (kOwnCopy: the starting
// rectangle). Returns false when the site coincides with a site of lower index (which owns the
// cell).
bool build_cell(const Scene& scene, const CellSearch& search, std::uint32_t site, Point origin,
                ConvexPolygon& cell_polygon, SearchScratch& scratch);

// Measures every wanted cell of `scene` by the search into cells[site - wanted_begin], buckets in
// chunks (on all threads when `parallel`; the same bits for any thread count).
void search_cells(const Scene& scene, const CellSearch& search, const Weighting& weighting, std::span<Cell> cells,
                  bool parallel);

// Measures the cells of `sites` (wanted ones) by the search, likewise.
void search_listed_cells(const Scene& scene, const CellSearch& search, const Weighting& weighting,
                         std::span<const std::uint32_t> sites, std::span<Cell> cells, bool parallel);

}  // namespace bluetile
