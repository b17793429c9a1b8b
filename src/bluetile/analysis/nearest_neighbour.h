// Nearest-neighbour distances on the periodic domain (the paper's table, section 2: the
// minimum, maximum and range of nearest-neighbour distances detect small irregularities).
#pragma once

#include <cstddef>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// For each point, the torus distance to its nearest other point (periodic images included,
// so a lone point's nearest neighbour is its own copy one period away). Needs >= 1 point.
std::vector<double> nearest_neighbour_distances(const std::vector<Point>& points, const Domain& domain = {});

struct NearestNeighbourStats {
  std::size_t count = 0;
  double min = 0.0, max = 0.0, mean = 0.0;
  // Distances divided by the hexagonal lattice spacing for this count and area: 1 is the
  // largest possible minimum distance.
  double hexagonal_spacing = 0.0;
};

NearestNeighbourStats nearest_neighbour_stats(const std::vector<Point>& points, const Domain& domain = {});

}  // namespace bluetile
