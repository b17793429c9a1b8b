// Thinning a tiling by rank, for any density (the paper's "local hierarchical supersampling",
// section 4; the rule of Kopf et al. 2006, "Recursive Wang Tiles for Real-Time Blue Noise",
// section 4: a point is kept when its rank fraction is below the local density).
//
// The full tiling has density D_full = (mean points per tile) / S^2. A thinning asks for a
// fraction f(p) in [0, 1] of it at each plane point p. The point of rank k in a cell of tile t
// (n_t points) is kept when
//   (k + u(i, j)) / n_t  <  f(p)        (p its own position: the density is sampled at the point)
// with u(i, j) in [0, 1) a hashed offset per cell (the rank dither). For a constant f the cell
// keeps ceil(f n_t - u) points, whose mean over cells is exactly f n_t: counts are unbiased at
// every density, also below one point per tile, where a fixed rounding would lose or add up to
// half a point per tile (the error Kopf's tiles show in the sparsest strip of a ramp). Since the
// kept points of a cell are always a prefix of its rank order, they are the tile set's
// progressive subset: blue noise at every density the set's prefixes are.
//
// Dynamic range: one tile holds n_t points, so densities from D_full down to D_full / n_t are a
// prefix of at least one point per tile; below that cells keep 0 or 1 point (unbiased, but no
// longer spread across cells). The default set has 2048 points per tile: 2048:1.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "bluetile/core/torus.h"
#include "bluetile/tiling/tiler.h"

namespace bluetile {

// Throws Error unless `texels` are width x height values, each finite and >= 0, not all zero.
void check_density_map(int width, int height, std::span<const float> texels);

// How a density map of one aspect ratio is placed on a window of another.
enum class MapFit {
  contain,  // the whole map, its aspect kept, centred; nothing beside it
  cover,    // the window filled, the map's aspect kept, centred; what overflows is cut off
  stretch,  // the map stretched over the window
};

// "contain", "cover", "stretch"; and back. parse_map_fit throws Error naming the value and the list.
MapFit parse_map_fit(const std::string& name);
const char* map_fit_name(MapFit fit);

// The rectangle of the plane a `width` x `height` texel map covers when placed on `window` by
// `fit`: the window itself for stretch (and for a map of the window's aspect, to the bit), else the
// centred rectangle of the map's aspect that fits inside it (contain) or holds it (cover). Throws
// Error for a map smaller than 1 x 1 texel or a window that is not finite with x1 > x0 and y1 > y0
// (they came back as the window, or as NaN).
Window fit_map_rectangle(const Window& window, int width, int height, MapFit fit);

class Thinning {
 public:
  // The same fraction everywhere, in (0, 1]. Throws Error otherwise.
  static Thinning uniform(double fraction);

  // A density map: `width` x `height` texels (row by row, row 0 at the BOTTOM, y up; every value
  // finite and >= 0, at least one > 0) stretched over `rectangle` of the plane, texel (c, r)
  // centred at the rectangle's point ((c + 0.5) / width, (r + 0.5) / height) in relative
  // coordinates. The fraction at p is max_fraction * B(p) / (largest texel), B the bilinear
  // interpolation of the texel centres, the edge texels continued beyond the outer centres
  // (inside and outside the rectangle). Throws Error for a bad grid, rectangle or max_fraction
  // (outside (0, 1]).
  static Thinning from_map(int width, int height, std::span<const float> texels, const Window& rectangle,
                           double max_fraction);

  // The map placed on `window` by `fit` (fit_map_rectangle). contain leaves no points beside the
  // map: on the sides with room the fraction is zero from the map's edge on (the rectangle is
  // half-open, [x0, x1) x [y0, y1)), and inside it the map's own, edge texels continued to the
  // edge, so a uniform map fills exactly its rectangle. (It fell to zero over a bilinear step of
  // a texel across the edge, half a texel beside the map: all of a 1 x 1 map's room.)
  static Thinning from_fitted_map(int width, int height, std::span<const float> texels, const Window& window,
                                  MapFit fit, double max_fraction);

  bool constant() const { return grid_.empty(); }
  // f(p), in [0, max_fraction].
  double fraction_at(Point p) const;
  // Bounds of f over the box [box.x0, box.x1] x [box.y0, box.y1] (closed): min <= f(p) <= max
  // for every p there (the smallest and largest texel the bilinear lookup can reach from it).
  struct Bounds {
    double min = 0.0, max = 0.0;
  };
  Bounds fraction_bounds(const Window& box) const;
  double max_fraction_in(const Window& box) const { return fraction_bounds(box).max; }
  // The rank dither u(i, j) in [0, 1) of a cell for a tiling's seed.
  static double dither(std::int64_t i, std::int64_t j, std::uint64_t seed);

  // For the generator's inner loop: texel coordinates tx = p.x * scale_x + offset_x (texel
  // centres at integers), the same in y; values pre-scaled so that the bilinear sample is f.
  struct Map {
    int width = 0, height = 0;
    double scale_x = 0.0, offset_x = 0.0, scale_y = 0.0, offset_y = 0.0;
    const float* values = nullptr;
    Window support;  // f is zero outside (contain's room beside the map); infinite otherwise
  };
  Map map() const;
  double fraction() const { return fraction_; }

 private:
  Thinning() = default;

  double fraction_ = 1.0;        // constant thinnings, and max_fraction of maps
  int width_ = 0, height_ = 0;
  std::vector<float> grid_;      // texels scaled to fractions
  Window rectangle_;
  Window support_{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
};

// f at plane point p of a map thinning, as Thinning::fraction_at computes it (inline for the
// generator's loop).
inline double sample_map(const Thinning::Map& m, Point p) {
  if (!m.support.contains(p)) return 0.0;
  double tx = p.x * m.scale_x + m.offset_x;
  double ty = p.y * m.scale_y + m.offset_y;
  // Clamp to the outer texel centres (edge continued); the last column pairs with itself.
  tx = tx < 0.0 ? 0.0 : (tx > m.width - 1 ? m.width - 1 : tx);
  ty = ty < 0.0 ? 0.0 : (ty > m.height - 1 ? m.height - 1 : ty);
  int cx = static_cast<int>(tx), cy = static_cast<int>(ty);
  double fx = tx - cx, fy = ty - cy;
  int nx = cx + (cx < m.width - 1 ? 1 : 0);
  int ny = cy + (cy < m.height - 1 ? 1 : 0);
  const float* row0 = m.values + static_cast<std::ptrdiff_t>(cy) * m.width;
  const float* row1 = m.values + static_cast<std::ptrdiff_t>(ny) * m.width;
  double bottom = row0[cx] + (static_cast<double>(row0[nx]) - row0[cx]) * fx;
  double top = row1[cx] + (static_cast<double>(row1[nx]) - row1[cx]) * fx;
  return bottom + (top - bottom) * fy;
}

}  // namespace bluetile
