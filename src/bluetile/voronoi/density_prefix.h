// Weighted polygon moments from per-row prefix tables of a texel-constant density (the weighted
// centroid of a Voronoi cell, Secord 2002 "Weighted Voronoi Stippling"), built once per density
// map and kept across Lloyd iterations. Same integrals as density_moments (density_moments.h),
// which stays the reference: the polygon is cut at texel row lines only, and what lies between
// an edge piece and the polygon's left side is summed once per cell row (a cell up to 64 texels
// wide) or comes from the table (a wider one) instead of texel by texel for every piece.
#pragma once

#include <span>
#include <vector>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/torus.h"
#include "bluetile/voronoi/density_moments.h"

namespace bluetile {

class DensityPrefix {
 public:
  // Block moments of every row of `density`, which must outlive this object and not change
  // (24 bytes per block of kBlock texels). `density` must not be empty.
  explicit DensityPrefix(const DensityGrid& density);

  // As density_moments(polygon, origin, density, domain_size, periodic) (density_moments.h):
  // the integrals of rho, rho x, rho |x|^2 over the counter-clockwise polygon (relative to
  // `origin`), agreeing with it to about 1e-13 relative. Thread-safe. With `second` false the
  // second moment is not integrated and is left 0 (Scene::second_moments; about a tenth of the
  // integration); mass and first moments are the same bits either way.
  WeightedMoments moments(std::span<const Point> polygon, Point origin, Point domain_size, bool periodic,
                          bool second = true) const;

  // Texels per block: the moments of a row are kept per block, about the block's first column,
  // and summed from there to the cell, so that nothing grows far beyond the moments it is
  // subtracted from (a prefix over a whole row of 1024 texels lost about 1e-3 relative on a
  // cell's second moment by cancellation); 8 keeps the table at 3 bytes per texel. Read only for
  // cells wider than 64 texels (few sites on a large map); narrower ones sum their texels.
  static constexpr int kBlock = 8;

  // Moments of a block's texels about its first column, in texel units: integrals of rho,
  // rho t and rho t^2.
  struct Entry {
    double q0, q1, q2;
  };

 private:
  template <bool kSecond>
  WeightedMoments integrate(std::span<const Point> polygon, Point origin, Point domain_size, bool periodic) const;

  const DensityGrid* density_;
  std::size_t blocks_per_row_ = 0;
  std::vector<Entry> table_;  // row by row as the grid, a row's blocks left to right
};

}  // namespace bluetile
