// A density over a rectangle: a grid of non-negative texels, constant within each texel.
//
// Laid over a rectangle [0,W) x [0,H), texel (i, j) covers [i W/width, (i+1) W/width) x
// [j H/height, (j+1) H/height): column i counts from the left, row j from the BOTTOM, the
// plane's y being up. (An image's row 0 is the top of the picture: io/density_map.h flips it.)
// Because the density is constant per texel, the weighted area and moments of a polygon are
// exact sums over the polygon's pieces in each texel; engines use that, and bilinear lookup is
// only for tools that want a smooth density (tiling, thinning).
#pragma once

#include <cstddef>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct DensityGrid {
  int width = 0, height = 0;
  std::vector<float> texels;  // row by row, row 0 at the bottom; every value finite and >= 0

  DensityGrid() = default;
  // Throws Error for a negative width or height (it made a vector of about 2^64 texels).
  DensityGrid(int w, int h, float value = 0.0f)
      : width(w), height(h), texels(texel_count(w, h), value) {}

  bool empty() const { return texels.empty(); }
  float at(int column, int row) const {
    return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column)];
  }
  float& at(int column, int row) {
    return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column)];
  }
  // Mean texel value (the density's integral over a unit-area rectangle), in double.
  double mean() const;

 private:
  static std::size_t texel_count(int w, int h);
};

// Throws Error unless `grid` is one the functions that take a density can read: a width and a
// height of at least 1 and width x height texels ("density grid of 0 x 4 texels holds 4 values"),
// every texel finite and >= 0 (the message names the first other one and its value). Returns
// whether any texel is positive: what a density zero everywhere means is the caller's to say.
bool check_density_grid(const DensityGrid& grid);

// What a lookup outside the texel centres sees: the edge texels continued (a bounded picture),
// or the grid repeated (a periodic domain).
enum class GridEdge { clamp, wrap };

// The bilinear interpolation of the texel values at `uv`, in coordinates normalised to the grid
// ([0,1]^2 covers it, u to the right, v up; texel (i, j)'s centre is at ((i + 0.5) / width,
// (j + 0.5) / height)). Outside [0,1]^2 `edge` decides. Throws Error for a grid whose size does
// not match its texels (an empty one included) or a `uv` that is not finite; the texels' values
// are not checked (a lookup is cheap; check_density_grid checks them once).
double sample_bilinear(const DensityGrid& grid, Point uv, GridEdge edge = GridEdge::clamp);

}  // namespace bluetile
