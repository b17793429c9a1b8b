// Bond-orientational order psi_6 (Halperin and Nelson, PRL 41, 1978) from exact periodic
// Voronoi cells.
#include "bluetile/analysis/bond_order.h"

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {

BondOrder bond_orientational_order(std::span<const Point> points) {
  if (points.size() < 2) throw Error("bond-orientational order needs at least 2 points, got " + std::to_string(points.size()));
  const std::vector<std::vector<Point>> cells = exact_cell_polygons(make_scene({points.begin(), points.end()}));
  // An edge shorter than this (relative to the spacing) is a tie left by co-circular sites.
  const double tiny = 1e-9 * hexagonal_spacing(static_cast<double>(points.size()));
  BondOrder order;
  std::complex<double> sum_global = 0.0;
  std::size_t sites = 0;
  for (const std::vector<Point>& cell : cells) {
    std::complex<double> psi = 0.0;
    int bonds = 0;
    for (std::size_t i = 0; i < cell.size(); ++i) {
      const Point v = cell[i], w = cell[(i + 1) % cell.size()], d = w - v;
      const double length2 = d.x * d.x + d.y * d.y;
      if (length2 <= tiny * tiny) continue;
      // The neighbour (or its periodic image) is the site reflected in the edge's line.
      const Point foot = v - (v.x * d.x + v.y * d.y) / length2 * d;
      const std::complex<double> direction(foot.x, foot.y);
      psi += std::pow(direction / std::abs(direction), 6);
      ++bonds;
    }
    if (bonds == 0) continue;
    psi /= static_cast<double>(bonds);
    order.local += std::abs(psi);
    sum_global += psi;
    ++sites;
  }
  if (sites > 0) {
    order.local /= static_cast<double>(sites);
    order.global = std::abs(sum_global / static_cast<double>(sites));
  }
  return order;
}

}  // namespace bluetile
