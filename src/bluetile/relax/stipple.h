// Stipple drawings by weighted Lloyd relaxation (Secord 2002, "Weighted Voronoi Stippling"):
// what `bluetile stipple` and the Python module's `stipple` both start from, defined once.
// The drawing spans the map's aspect ratio with its longer side 1; dots start where the map is
// dense, drawn in proportion to it, and their cells are weighted by map^exponent, under which a
// relaxed set keeps that density (weight_for_point_density, lloyd.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/torus.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/engine.h"

namespace bluetile {

struct StippleStart {
  std::size_t count = 0;        // dots, >= 1
  std::uint64_t seed = 1;       // of the density-proportional start (set 0 of the seed)
  bool periodic = false;        // cells wrap around the picture's edges; else they end at its border
  double weight_exponent = kDefaultWeightExponent;  // cells weighted by map^exponent
};

// [0, W) x [0, H) with the map's aspect ratio and max(W, H) = 1. Throws Error for an empty map or
// one check_density_grid refuses.
Domain stipple_domain(const DensityGrid& map);

// The scene weighted Lloyd relaxes: `start.count` sites drawn in proportion to `map` over its
// stipple_domain, the weighted map as the scene's density. Throws Error for an empty map, a map
// that is zero everywhere, no dots or more than kMaxSetPoints, or a weight exponent out of range
// (check_weight_exponent).
Scene stipple_scene(const DensityGrid& map, const StippleStart& start);

// Dots that just touch where the map is densest: half the hexagonal spacing of the count that
// would fill the domain at that density. Throws Error for a map that is empty, that
// check_density_grid refuses or that is zero everywhere, a domain check_domain refuses and no dots.
double stipple_dot_radius(const DensityGrid& map, const Domain& domain, std::size_t count);

}  // namespace bluetile
