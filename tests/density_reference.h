// Independent references for weighted (density) cells, written apart from the engines: a cell
// polygon clipped by every other site's bisector with no grid and no early stop, and a polygon's
// weighted moments by clipping it against every texel in turn.
#pragma once

#include <vector>

#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile::test {

// The cell of `site` relative to it, counter-clockwise: the domain rectangle (bounded) or the
// W x H rectangle centred on the site (periodic) clipped by the bisector of every other site and,
// on a torus, of every copy of every site within two periods.
std::vector<Point> brute_force_cell(const Scene& scene, std::size_t site);

// Weighted moments of `polygon` (relative to `origin`) under the scene's density (1 when it has
// none): the polygon clipped by each texel rectangle (and each periodic copy of it), piece by piece.
WeightedMoments brute_force_moments(const std::vector<Point>& polygon, Point origin, const Scene& scene);

// The weighted centroid of `site` by both of the above, in domain coordinates (not wrapped).
Point brute_force_centroid(const Scene& scene, std::size_t site);

}  // namespace bluetile::test
