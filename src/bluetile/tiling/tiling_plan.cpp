#include "bluetile/tiling/tiling_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// Midpoints per side of the grid on which the mean of a fitted map over the window is taken: the
// count it sets is "about", like the texel mean of a map that covers the window exactly.
constexpr int kMeanSamplesPerSide = 512;

// The mean over `window` of the map's fraction (1 at its largest texel) when placed by `fit`.
double mean_fraction_over(const DensityGrid& grid, const Window& window, MapFit fit) {
  const Thinning probe = Thinning::from_fitted_map(grid.width, grid.height, grid.texels, window, fit, 1.0);
  double sum = 0.0;
  for (int j = 0; j < kMeanSamplesPerSide; ++j)
    for (int i = 0; i < kMeanSamplesPerSide; ++i)
      sum += probe.fraction_at({window.x0 + (i + 0.5) / kMeanSamplesPerSide * window.width(),
                                window.y0 + (j + 0.5) / kMeanSamplesPerSide * window.height()});
  return sum / (static_cast<double>(kMeanSamplesPerSide) * kMeanSamplesPerSide);
}

void check_amount(std::string_view name, double v) {
  if (!(v >= 0.0) || !std::isfinite(v))
    throw Error(std::string(name) + ": expected a finite number >= 0 (0: not given), got " + number_text(v));
}

// "--count 300", "count=300".
std::string given(std::string_view name, double v, const TilingNames& names) {
  return std::string(name) + std::string(names.assign) + number_text(v);
}

}  // namespace

void check_tiling_request(const TilingRequest& request, bool has_map, const TilingNames& names) {
  const Window& w = request.window;
  for (double v : {w.x0, w.y0, w.x1, w.y1})
    if (!std::isfinite(v)) throw Error("region: coordinates must be finite, got " + number_text(v));
  if (!(w.x1 > w.x0)) throw Error("region: X1 must be greater than X0, got X0 " + number_text(w.x0) + ", X1 " + number_text(w.x1));
  if (!(w.y1 > w.y0)) throw Error("region: Y1 must be greater than Y0, got Y0 " + number_text(w.y0) + ", Y1 " + number_text(w.y1));
  check_amount(names.tile_size, request.tile_size);
  check_amount(names.density, request.density);
  check_amount(names.max_density, request.max_density);
  check_amount(names.count, request.count);
  const std::string map_name(names.density_map);
  if (has_map && request.density > 0.0)
    throw Error(given(names.density, request.density, names) + " is for uniform tilings; with a " + map_name + " give " +
                std::string(names.max_density) + " or " + std::string(names.count));
  if (!has_map && request.max_density > 0.0)
    throw Error(given(names.max_density, request.max_density, names) + " needs a " + map_name + ": give one");
  if (!has_map && request.count > 0.0)
    throw Error(given(names.count, request.count, names) + " needs a " + map_name + ": give one");
  if (request.count > 0.0 && request.max_density > 0.0)
    throw Error(std::string(names.count) + " and " + std::string(names.max_density) + " exclude each other: give one");
}

TilingPlan plan_tiling(TileSet set, const DensityGrid* map, const TilingRequest& request, const TilingNames& names) {
  check_tiling_request(request, map != nullptr, names);
  TilingPlan plan;
  plan.window = request.window;
  const Window& w = plan.window;

  double points_per_tile = 0.0;
  for (const Tile& t : set.tiles) points_per_tile += static_cast<double>(t.points.size());
  points_per_tile /= static_cast<double>(std::max<std::size_t>(1, set.tiles.size()));

  // The map's mean and largest texel: the window's mean density over its highest. Bilinear
  // interpolation keeps the mean of the texels up to the half-texel border: close enough to set
  // a density by and to size a run by. A map that covers the window exactly (stretched, or of its
  // aspect) keeps the texel mean; otherwise the fitted map's mean over the window is sampled.
  double largest = 1.0, mean = 1.0;
  if (map) {
    // Before its mean over its largest texel is taken: a zero map gave "density -nan is too low".
    check_density_map(map->width, map->height, map->texels);
    largest = 0.0, mean = 0.0;
    for (float v : map->texels) largest = std::max(largest, static_cast<double>(v)), mean += v;
    mean /= static_cast<double>(map->texels.size());
    const Window placed = fit_map_rectangle(w, map->width, map->height, request.fit);
    const bool exact = placed.x0 == w.x0 && placed.x1 == w.x1 && placed.y0 == w.y0 && placed.y1 == w.y1;
    if (!exact) mean = largest * mean_fraction_over(*map, w, request.fit);
  }

  // The density where it is highest: given, from the count, or the full tiling's.
  double tile_size = request.tile_size;
  double target = map ? request.max_density : request.density;
  if (map && (request.count > 0.0 || (target == 0.0 && tile_size == 0.0))) {
    const double count = request.count > 0.0 ? request.count : kDefaultTiledStippleCount;
    target = count / (w.area() * mean / largest);
  }
  if (tile_size == 0.0) tile_size = target > 0.0 ? std::sqrt(points_per_tile / target) : 1.0;
  if (!std::isfinite(tile_size))
    throw Error("density " + number_text(target) + " is too low to set a tile size from (" + number_text(points_per_tile) +
                " points per tile would need tiles of size " + number_text(tile_size) + "): give a higher density");
  plan.tiler = std::make_unique<Tiler>(std::move(set), request.seed, tile_size);
  const double full = plan.tiler->full_density();
  // Tiles so small that their density overflows: every density would read as "too low" beside inf.
  if (!std::isfinite(full))
    throw Error("tile size " + number_text(tile_size) + " is too small: " + number_text(points_per_tile) +
                " points per tile would be more points per unit area than a double holds; use a larger " +
                std::string(names.tile_size));
  if (target == 0.0) target = full;
  // A hair of rounding (sqrt then square) must not refuse the density it came from.
  if (target > full * (1.0 + 1e-12))
    throw Error("density " + number_text(target) + " is more than tiles of size " + number_text(tile_size) + " hold (" +
                number_text(full) + " points per unit area): use a smaller " + std::string(names.tile_size) +
                " or leave it out");
  // Within rounding of the full density: every point, no thinning.
  const double fraction = target >= full * (1.0 - 1e-12) ? 1.0 : target / full;
  if (!(fraction > 0.0))
    throw Error("density " + number_text(target) + " is too low for tiles of size " + number_text(tile_size) + " (" +
                number_text(full) + " points per unit area): no point would be kept; use a larger " +
                std::string(names.tile_size));
  plan.max_density = target;
  plan.mean_density = target * mean / largest;
  if (map) {
    plan.thinning = std::make_unique<Thinning>(
        Thinning::from_fitted_map(map->width, map->height, map->texels, w, request.fit, fraction));
  } else if (fraction < 1.0) {
    plan.thinning = std::make_unique<Thinning>(Thinning::uniform(fraction));
  }
  return plan;
}

void check_tiling_size(const TilingPlan& plan, const std::string& region, const std::string& tile_size) {
  const Window& w = plan.window;
  const std::string name = region + " " + number_text(w.x0) + " " + number_text(w.y0) + " " + number_text(w.x1) + " " +
                           number_text(w.y1);
  const CellRange range = plan.tiler->cells(w);  // first: refuses windows off the plane's range
  const double points = w.area() * plan.mean_density;
  if (!(points <= kMaxTiledPoints))
    throw Error(name + " holds about " + count_text(points) + " points (" + number_text(plan.mean_density) +
                " per unit area), more than the limit of " + count_text(kMaxTiledPoints) +
                " points: use a smaller region or a lower density");
  const double cells = static_cast<double>(range.columns()) * static_cast<double>(range.rows());
  if (!(cells <= kMaxTiledPoints))
    throw Error(name + " spans about " + count_text(cells) + " tiles of size " + number_text(plan.tiler->tile_size()) +
                ", more than the limit of " + count_text(kMaxTiledPoints) +
                " tiles: use a larger " + tile_size + " or a smaller region");
}

}  // namespace bluetile
