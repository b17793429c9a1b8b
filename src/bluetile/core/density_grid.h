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
  DensityGrid(int w, int h, float value = 0.0f)
      : width(w), height(h), texels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), value) {}

  bool empty() const { return texels.empty(); }
  float at(int column, int row) const {
    return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column)];
  }
  float& at(int column, int row) {
    return texels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width) + static_cast<std::size_t>(column)];
  }
  // Mean texel value (the density's integral over a unit-area rectangle), in double.
  double mean() const;
};

// What a lookup outside the texel centres sees: the edge texels continued (a bounded picture),
// or the grid repeated (a periodic domain).
enum class GridEdge { clamp, wrap };

// The bilinear interpolation of the texel values at `uv`, in coordinates normalised to the grid
// ([0,1]^2 covers it, u to the right, v up; texel (i, j)'s centre is at ((i + 0.5) / width,
// (j + 0.5) / height)). Outside [0,1]^2 `edge` decides. The grid must not be empty.
double sample_bilinear(const DensityGrid& grid, Point uv, GridEdge edge = GridEdge::clamp);

}  // namespace bluetile
