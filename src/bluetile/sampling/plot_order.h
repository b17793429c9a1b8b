// An order in which a pen plotter draws dots: a short open path through every dot, so that the
// pen travels little between them. Greedy nearest neighbour (start at the dot nearest the
// origin, always go to the nearest dot not yet drawn), then 2-opt moves (reverse a stretch of the
// path when that shortens it) tried between each dot and its nearest neighbours until none
// helps. A heuristic, not the shortest path: typically within 10-20 % of it (Johnson and McGeoch
// 1997, "The traveling salesman problem: a case study in local optimization").
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct PlotOrder {
  std::vector<std::size_t> order;  // indices into the dots, the drawing order
  double greedy_travel = 0.0;      // pen-up travel of the greedy path (the dots' units)
  double travel = 0.0;             // pen-up travel of `order`, after 2-opt
};

// The order of `dots` (plane distances, no wrap-around). The same dots give the same order on
// every machine and thread count. Throws Error for a non-finite coordinate.
PlotOrder plot_order(std::span<const Point> dots);

// Length of the open path through dots[order[0]], dots[order[1]], ... Throws Error for an index that names
// no dot (it was read past the end).
double path_length(std::span<const Point> dots, std::span<const std::size_t> order);

}  // namespace bluetile
