// A finished cell to the Cell the engine returns: its moments (area, centroid, second moment
// about the site, polygon.h), its radius, and its weighting by the scene's density (the prefix
// tables of density_prefix.h for a varying density). Shared by the cells the search clips and the
// cells read off the kept Delaunay triangulation.
#pragma once

#include <span>

#include "bluetile/voronoi/engine.h"
#include "bluetile/voronoi/polygon.h"

namespace bluetile {

class DensityPrefix;

// How a scene's density weights its cells: not at all (no density, or a constant one, whose
// weights cancel in the centroid), or texel by texel through its prefix tables.
struct Weighting {
  const DensityPrefix* prefix = nullptr;  // non-null: a varying density
  double constant = 1.0;                  // otherwise: the density everywhere
};

// A measured cell (area, second moment, radius) under the scene's weighting: its mass, weighted
// moments and centroid; `offset` is the plain centroid relative to the site, `polygon` the cell's
// vertices relative to the site (needed only with a density table).
Cell weigh_cell(const Scene& scene, Point origin, const Weighting& weighting, std::span<const Point> polygon, Cell cell,
                Point offset);

// The cell of the site at `origin` from its clipped polygon (relative to the site); a coincident
// site's cell is empty and its centroid the site.
Cell measure_cell(const Scene& scene, Point origin, bool coincident, const ConvexPolygon& cell_polygon,
                  const Weighting& weighting);

// The cell from its shoelace sums, radius squared and vertices (relative to the site, counter-
// clockwise; read only with a density table).
Cell measure_moments(const Scene& scene, Point origin, const PolygonMoments& moments, double radius_squared,
                     std::span<const Point> polygon, const Weighting& weighting);
// The same from the moments themselves: area, centroid relative to the site, second moment
// about the site.
Cell measure_sums(const Scene& scene, Point origin, double area, Point centroid, double second_moment,
                  double radius_squared, std::span<const Point> polygon, const Weighting& weighting);

}  // namespace bluetile
