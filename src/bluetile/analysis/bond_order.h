// Bond-orientational order psi_6 (Halperin and Nelson 1978; psa's "similarity to the hexagonal
// lattice"): for site j with Voronoi neighbours k at angles theta_jk,
//   psi_6(j) = (1 / n_j) * sum over k of exp(6 i theta_jk),
// 1 in magnitude on a hexagonal lattice, 0 on a square one. Neighbours are those whose periodic
// cells share an edge of positive length with j's (the exact engine's cells; a square lattice's
// corner-touching diagonal neighbours are not neighbours).
#pragma once

#include <span>

#include "bluetile/core/torus.h"

namespace bluetile {

struct BondOrder {
  double local = 0.0;   // mean over sites of |psi_6(j)|: local hexagonal order, whatever the orientation
  double global = 0.0;  // |mean over sites of psi_6(j)|: one common orientation (a lattice)
};

// On the unit torus. Coincident sites (no cell) are left out. Throws Error for fewer than 2
// points.
BondOrder bond_orientational_order(std::span<const Point> points);

}  // namespace bluetile
