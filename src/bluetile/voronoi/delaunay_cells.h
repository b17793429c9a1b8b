// Voronoi cells read off a periodic Delaunay triangulation (periodic_delaunay.h): a cell's
// vertices are the circumcentres of the triangles around its site, counter-clockwise, and its
// moments the shoelace sums over them (polygon.h).
//
// Every number is a function of the sites alone, never of how the triangulation was reached (a
// fresh build or flips, in any order, on any number of threads), so that a cell's bits do not
// depend on the calls before:
// - an offset between two sites is the correctly rounded difference of the exact copies
//   (predicates.h), the same bits from either end up to sign;
// - a circumcentre is computed relative to the corner opposite the triangle's longest edge (ties:
//   the lower site index), from the offsets to the next two corners counter-clockwise; that
//   corner's angle is the largest, which keeps the digits of nearly coincident sites (docs/
//   DESIGN.md, section 4); a cell's vertex is that centre plus the offset from its site to the
//   corner (kept per corner between the sweep and the cells);
// - a cell's shoelace sums start after the edge shared with its neighbour of lowest site index
//   (the vertex's canonical corner, periodic_delaunay.h).
// A Delaunay triangulation is unique away from cocircular ties, so equal sites give equal
// triangles and equal cells; cells on a tie (an edge whose in-circle test is exactly 0) are left
// to the search.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/voronoi/cell_measure.h"
#include "bluetile/voronoi/periodic_delaunay.h"

namespace bluetile {

class DelaunayCells {
 public:
  // What a sweep over the triangles found, in triangle order: triangles that are not valid
  // (clockwise, or an edge of a quarter period or more), edges whose in-circle test fails or ties
  // (as PeriodicDelaunay::link), and triangles whose circumcircle reaches the radius limit.
  struct Sweep {
    std::vector<std::uint32_t> invalid, suspects, ties, oversized;
    double area = 0.0;  // of all triangles, for the check that they cover the domain once
  };

  // One pass over every triangle at the vertices' current positions (on all threads): checks it,
  // tests its edges (each edge once, from the lower-numbered triangle) and computes its
  // circumcentre, all from the same offsets. The test results stand only when no triangle is
  // invalid; the circumcentres only for triangles the flips after leave alone. `lanes`: four
  // triangles at a time where the processor has AVX2 (delaunay_sweep.h; the same bits either way).
  Sweep sweep(const PeriodicDelaunay& triangulation, bool lanes = true);

  // Circumcentres of the triangles in `triangles` again (after flips); adds those whose
  // circumcircle reaches the radius limit to `oversized`, in list order. On all threads when the
  // list is long, so no triangle may appear twice.
  void recompute(const PeriodicDelaunay& triangulation, std::span<const std::uint32_t> triangles,
                 std::vector<std::uint32_t>& oversized);

  // Whether the triangle's circumcircle stays below the radius limit: a tenth of the shorter
  // period, so that cells and their neighbours stay well inside the quarter period the
  // predicates need (scenes with a larger empty circle are searched).
  bool fits(const PeriodicDelaunay& triangulation, std::uint32_t triangle) const;

  // The cell of `vertex`, whose site is at `origin` in `scene`. Returns false, leaving `cell`
  // alone, when the cell lies on a cocircular tie (left to the search). Without a density map and
  // with scene.second_moments false, the second moment is not summed and is left 0.
  bool measure(const PeriodicDelaunay& triangulation, std::uint32_t vertex, const Scene& scene, Point origin,
               const Weighting& weighting, Cell& cell) const;

  // measure for four vertices, `cells[j]` for `vertices[j]` at `origins[j]`: with `lanes`, and
  // where the processor has AVX2, without a density or a tie, the four walks at once in SIMD lanes
  // (the same bits, delaunay_sweep.h). Bit j of the result: cell j measured.
  int measure_four(const PeriodicDelaunay& triangulation, const std::uint32_t* vertices, const Scene& scene,
                   const Point* origins, const Weighting& weighting, Cell* const* cells, bool lanes) const;

  std::size_t bytes() const { return centres_.capacity() * sizeof(Point); }

 private:
  // measure, with or without the second moment's sum and the polygon a density map weighs (a
  // separate loop each, no branch in it).
  template <bool kSecond, bool kPolygon>
  bool walk(const PeriodicDelaunay& triangulation, std::uint32_t vertex, const Scene& scene, Point origin,
            const Weighting& weighting, Cell& cell) const;

  // Per triangle t, its circumcentre relative to each corner k: centres_[3 t + k].
  std::vector<Point> centres_;
};

}  // namespace bluetile
