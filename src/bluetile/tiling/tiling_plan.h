// What a tiled window is asked for, and the tiler, thinning and densities that follow from it:
// the one reading of a request that `bluetile tile` and the Python module's tile() share. A
// request gives at most one of a density (uniform tilings) or, with a density map, the density
// where the map is densest or an approximate count over the window; what it leaves out is worked
// out here, with the same tolerances for both front ends.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "bluetile/core/density_grid.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tiler.h"

namespace bluetile {

struct TilingRequest {
  Window window{};           // x1 > x0, y1 > y0, finite
  double tile_size = 0.0;    // plane units per tile; 0: from the density, else 1
  double density = 0.0;      // uniform: points per unit area (0: every point of every tile)
  double max_density = 0.0;  // with a map: points per unit area where it is densest (0: not given)
  double count = 0.0;        // with a map: about this many points over the window (0: not given)
  std::uint64_t seed = 1;
  MapFit fit = MapFit::contain;  // how a map is placed on the window
};

// Stipples a density map gets when nothing sets the density: a drawing a person recognises,
// small enough for an SVG viewer.
inline constexpr double kDefaultTiledStippleCount = 30000.0;

struct TilingPlan {
  std::unique_ptr<Tiler> tiler;
  std::unique_ptr<Thinning> thinning;  // null: every point of every tile
  Window window;
  double max_density = 0.0;   // points per unit area where the density is highest
  double mean_density = 0.0;  // points per unit area over the window, on average
};

// How a front end names a request's fields in its messages, and joins a name to its value: the
// tool's options ("--max-density 500 needs a --density-map"), the Python module's arguments
// ("max_density=500 needs a density_map"). The defaults are the library's own words.
struct TilingNames {
  std::string_view tile_size = "tile size";
  std::string_view density = "density";
  std::string_view max_density = "max density";
  std::string_view count = "count";
  std::string_view density_map = "density map";
  std::string_view assign = " ";  // between a name and its value
};

// The request's own rules, which need no map and no tile set, so a front end can refuse a bad
// request before it reads either: a finite window with x1 > x0 and y1 > y0 ("region: ..."); tile
// size, densities and count finite and >= 0; a density only without a map, a max density or a
// count only with one, and not both. Throws Error in `names`' words. plan_tiling checks them too.
void check_tiling_request(const TilingRequest& request, bool has_map, const TilingNames& names = {});

// The plan for `request` over `set`, thinned by `map` when given (texels as in DensityGrid, the
// map placed on the window by request.fit). Throws Error for a bad or contradictory request
// (check_tiling_request) and for a density the tiles cannot hold, in `names`' words ("use a
// smaller --tile-size").
TilingPlan plan_tiling(TileSet set, const DensityGrid* map, const TilingRequest& request, const TilingNames& names = {});

// The most points, or cells, one window may hold: the other commands' limit on a point set, past
// which a run fills a disk or memory, or runs for hours, instead of being refused.
inline constexpr double kMaxTiledPoints = 1e8;

// Refuses, before any point is made, a window that holds more than kMaxTiledPoints points (area x
// mean density) or cells, or lies off the plane's range (Tiler::cells): Error naming `region`, the
// option or argument that gave the window ("--region 0 0 1e6 1e6 holds about 1e14 points ..."),
// and `tile_size`, the one that sets the tile size, where a larger one would help.
void check_tiling_size(const TilingPlan& plan, const std::string& region, const std::string& tile_size);

}  // namespace bluetile
