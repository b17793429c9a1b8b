// The sweep and the cell walks of DelaunayCells (delaunay_cells.h) in two forms that give the same
// bits: one triangle (cell) at a time in plain doubles, and four at a time in AVX2 lanes
// (delaunay_sweep_avx2.cpp), chosen at run time. A lane does exactly the scalar form's IEEE
// operations in the same order (no fused multiply-add: the files are compiled with
// -ffp-contract=off); a triangle that needs a branch the lanes do not take (a corner's shifted
// copy, an orientation the filter cannot decide) goes through the scalar form whole, and the found
// lists keep triangle order.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bluetile/voronoi/delaunay_cells.h"

namespace bluetile::detail {

// What every triangle of one sweep shares.
struct SweepFrame {
  const PeriodicDelaunay& triangulation;
  Point* centres;  // per triangle t, its circumcentre relative to corner k at centres[3 t + k]
  Point quarter;   // a quarter period
  double limit;    // the squared circumradius limit
};

// One triangle, in triangle order within `found`.
void sweep_triangle(const SweepFrame& frame, std::uint32_t triangle, DelaunayCells::Sweep& found);
// Edge `edge` of an unshifted valid triangle, which owns it (its neighbour's index is not lower).
void sweep_edge(const SweepFrame& frame, std::uint32_t triangle, int edge, DelaunayCells::Sweep& found);
// An edge whose in-circle filter could not decide: the exact test.
void settle_edge(const PeriodicDelaunay& triangulation, std::uint32_t triangle, int edge, DelaunayCells::Sweep& found);

// Whether this processor runs the four-lane form (AVX2), and the environment does not ask for
// the scalar one (BLUETILE_SIMD=0); read once.
bool sweep_lanes_available();
// Triangles [begin, end), four at a time where the processor has AVX2 (the rest one at a time);
// the same bits and lists as sweep_triangle over them in order.
void sweep_lanes(const SweepFrame& frame, std::size_t begin, std::size_t end, DelaunayCells::Sweep& found);

// A cell walk's sums (DelaunayCells::walk) for four vertices at once, lane j for vertex j: the
// shoelace sums over each cell's edges from its canonical corner, in walk's order and arithmetic
// (the second moment's only with `second`, else 0), and the largest squared vertex distance.
// Precondition: sweep_lanes_available(), no tie in the triangulation.
struct WalkSums {
  double cross[4], sx[4], sy[4], second[4], radius_squared[4];
};
void walk_lanes(const PeriodicDelaunay& triangulation, const Point* centres, const std::uint32_t* vertices, bool second,
                WalkSums& sums);

}  // namespace bluetile::detail
