// Ranked sample tables from published samplers, the anchors of the untiled prefix sweep
// (docs/RESULTS.md, "Every prefix of an untiled set"): a renderer takes the first k points of
// such a table, so every prefix counts. Written here from the papers' descriptions.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile::bench {

// The first n points of the two-dimensional Sobol' sequence (dimension 0 the van der Corput
// radical inverse, dimension 1 Sobol's second, with the direction numbers of the Pascal matrix
// mod 2), each coordinate under its own nested uniform (Owen) scramble: every bit flipped by a
// random bit drawn from the seed and the bits above it. Points stay in their index order, so
// every power-of-two prefix is a (0, m, 2)-net.
std::vector<Point> owen_sobol_points(std::size_t n, std::uint64_t seed);

// Mitchell's best-candidate order (1991): the k-th point is the one of `candidates_per_point`
// * k uniform candidates farthest from the k before it on the torus.
std::vector<Point> best_candidate_points(std::size_t n, std::uint64_t seed, std::size_t candidates_per_point);

}  // namespace bluetile::bench
