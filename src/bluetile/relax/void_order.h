// A progressive order of points on the unit torus by voids (Ulichney 1993's void-and-cluster,
// applied to ranking a given set): so that every prefix of the order, not only the whole, is well
// spread. The untiled twin of wang_ranks.h's rank_level_by_voids.
//
// Step by step, the next point is the unranked one of least Gaussian energy
// sum_j exp(-|x - y_j|^2 / (2 sigma^2)) over the ranked points y_j (torus distances), among the
// unranked points at least kVoidSpacingFloor of the largest such distance from every ranked point;
// sigma = sigma_factor hexagonal spacings of the prefix reached, updated each time the prefix grows
// by a quarter. Ties go to the lower index. The energy sees the density over a few spacings, so a
// prefix fills its sparsest regions first; the floor keeps close pairs out of early prefixes.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// Kernel width in hexagonal spacings of the prefix: the value wang_ranks uses (chosen there from
// 0.3 to 1.2, docs/RESULTS.md "Every prefix").
inline constexpr double kVoidSigmaFactor = 0.5;
// The kernel widths the front ends take (--void-sigma, void_sigma) and void_order accepts: below a
// tenth of a spacing the kernel sees no neighbour, beyond four it sees the whole prefix.
inline constexpr double kMinVoidSigma = 0.1, kMaxVoidSigma = 4.0;

// The indices of points[ranked, n) in rank order; points[0, ranked) are ranked already, in their
// order, and count as earlier points. Deterministic; about O(M log M) for M = n - ranked points
// plus O(n) energy updates each time the prefix grows by a quarter. Throws Error for `ranked` above
// the number of points, a sigma_factor outside [kMinVoidSigma, kMaxVoidSigma] ("void_sigma:
// expected 0.1 to 4 ..."; 0, negative and NaN ones ordered without a word) and a point that is not
// finite.
std::vector<std::uint32_t> void_order(std::span<const Point> points, std::size_t ranked,
                                      double sigma_factor = kVoidSigmaFactor);

}  // namespace bluetile
