// Nearest-neighbour distances on the periodic domain, or in the plain domain rectangle for a
// bounded set (the paper's table, section 2: the minimum, maximum and range of
// nearest-neighbour distances detect small irregularities). Normalised by the hexagonal
// spacing, the minimum is Lagae and Dutre's relative radius rho (2008; psa's "global minimum
// distance") and the mean psa's "average minimum distance".
#pragma once

#include <cstddef>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// For each point, the distance to its nearest other point: on the torus (periodic images
// included, so a lone point's nearest neighbour is its own copy one period away; needs >= 1
// point), or Euclidean inside the domain rectangle for Boundary::bounded (needs >= 2 points).
// A periodic point outside the domain counts as its copy inside. Throws Error for too few points,
// a point that is not finite or (bounded) outside the domain, and a domain check_domain refuses.
std::vector<double> nearest_neighbour_distances(const std::vector<Point>& points, const Domain& domain = {},
                                                Boundary boundary = Boundary::periodic);

struct NearestNeighbourStats {
  std::size_t count = 0;
  double min = 0.0, max = 0.0, mean = 0.0;
  // Distances divided by the hexagonal lattice spacing for this count and area: 1 is the
  // largest possible minimum distance.
  double hexagonal_spacing = 0.0;

  double rho() const { return min / hexagonal_spacing; }           // relative radius
  double rho_mean() const { return mean / hexagonal_spacing; }     // average minimum distance
};

NearestNeighbourStats nearest_neighbour_stats(const std::vector<Point>& points, const Domain& domain = {},
                                              Boundary boundary = Boundary::periodic);

}  // namespace bluetile
