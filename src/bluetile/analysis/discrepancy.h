// L2 discrepancies of a point set in the unit square, the uniformity measures of quasi-Monte
// Carlo: centred (CD), wrap-around (WD), mixture (MD) and L2-star, by their closed forms
// (Hickernell 1998, "A generalized discrepancy and quadrature error bound"; Zhou, Fang and Ning
// 2013 for the mixture discrepancy), with the conventions of scipy.stats.qmc.discrepancy: CD,
// WD and MD are the squared discrepancies, L2-star its square root. Each is O(N^2): every pair.
#pragma once

#include <cstddef>
#include <span>

#include "bluetile/core/torus.h"

namespace bluetile {

struct Discrepancies {
  double centred = 0.0;      // CD^2
  double wrap_around = 0.0;  // WD^2: invariant under shifts on the torus
  double mixture = 0.0;      // MD^2
  double l2_star = 0.0;      // L2-star (not squared)
};

// All four of a set of points in [0, 1]^2, in one pass over the pairs on thread_count()
// threads; the same bits whatever the thread count. Throws Error for an empty set and for a point
// that is not finite or lies outside [0, 1]^2.
Discrepancies discrepancies(std::span<const Point> points);

// Pairs the computation visits: its cost (analysis budgets).
double discrepancy_pairs(std::size_t count);

}  // namespace bluetile
