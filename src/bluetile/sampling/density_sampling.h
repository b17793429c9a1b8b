// Random points whose density follows a density grid: each point picks a texel with probability
// proportional to its density (inversion of the cumulative sum, texels in row order), then a
// uniform place inside it. The start of weighted Lloyd (stippling, Secord 2002 section 3.1 starts
// from such a rejection-sampled set), and a white-noise baseline for thinned tilings.
#pragma once

#include <cstddef>
#include <vector>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/torus.h"

namespace bluetile {

// `count` points in [0,W) x [0,H) of `domain`, the grid laid over it (density_grid.h).
// Deterministic for a given rng state. Throws Error when the grid is empty or zero everywhere,
// for a grid check_density_grid refuses, for a domain check_domain refuses and above kMaxSetPoints
// (check_set_points).
std::vector<Point> sample_density(const DensityGrid& density, const Domain& domain, std::size_t count, Rng& rng);

// Set `set` of seed `seed`, drawn in proportion to `density` over the unit square: the start of
// `bluetile relax --density-map`, as uniform_random_points (core/rng.h) is the uniform one.
std::vector<Point> density_random_points(const DensityGrid& density, std::size_t count, std::uint64_t seed,
                                         std::uint64_t set = 0);

}  // namespace bluetile
