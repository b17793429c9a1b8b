// Progressive point sets by band-limited void filling: every prefix even, not only the level
// boundaries. Points are added one rank at a time, each where the low-frequency density of the
// points ranked before it is lowest: the potential is the points' density seen through the
// band the LF measure reads (frequencies below half sqrt(k) for a prefix of k points, a jinc
// kernel in the plane, windowed to a few spacings), and the new point takes its minimum among the
// places at least a floor of hexagonal spacings from every earlier point. Adding the point there
// lowers the prefix's low-frequency power the most (its cross term with the existing sum is most
// negative), so every prefix stays about equally even, where relaxing a level around fixed earlier
// points leaves its in-between prefixes far less even than its boundary (docs/RESULTS.md, "Every
// prefix"). It is Ulichney's void-and-cluster (1993) with placement anywhere instead of a choice
// among given points, and the ideal low-pass kernel instead of a Gaussian: a Gaussian only says
// "far", the jinc's negative ring also says "at a spacing from the neighbours".
//
// The tiled form (Hiller, Deussen and Keller 2001's sets that tile, section 3): a tile's potential
// and floor count the points of every tile that can lie next to it, shifted there, weighted by how
// often it lies there; the tiles take one point each per round.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string_view>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// Where the points of tile `tile` can lie near a given tile: shifted by `shift` (tile units, each
// coordinate -1, 0 or 1), counting with `weight` in its potential (the probability of that tile at
// that place; 1 for the tile itself at shift 0). Every source blocks the floor in full.
struct FillSource {
  std::size_t tile = 0;
  Point shift{0.0, 0.0};
  double weight = 1.0;
};

// Measured on 1024 points, every prefix from 1/16 on (docs/RESULTS.md, "Every prefix"): the floor
// 0.66 keeps rho at 0.66 with LF unchanged from 0.60; a window of 4 spacings gives the unwindowed
// band's LF (3: +15 %, 2: +40 %); 8 grid cells per spacing and a kernel rebuilt every 25 % of
// growth cost no measurable LF against exact evaluation.
inline constexpr double kFillFloor = 0.66;
inline constexpr double kFillWindow = 4.0;
inline constexpr int kFillCellsPerSpacing = 8;
inline constexpr double kFillRegrid = 1.25;

struct FillOptions {
  // Smallest distance from a new point to every earlier one, in hexagonal spacings of the prefix
  // it completes; where no place is that far, the farthest place is taken.
  double floor = kFillFloor;
  double window = kFillWindow;                  // kernel radius, hexagonal spacings of the prefix
  int cells_per_spacing = kFillCellsPerSpacing;  // potential grid, per spacing of the final count
  double regrid = kFillRegrid;                  // kernel rebuilt when the prefix grew this much
  std::uint64_t seed = 1;
  // Called after each round (one new point in every tile) with the rounds done and the total.
  std::function<void(std::size_t done, std::size_t total)> on_round{};
};

// Adds `add` points to every tile. tiles[t] holds tile t's existing points, in [0,1)^2, ranked
// before the new ones; every tile must hold the same number. sources[t] lists where points count
// near tile t; it must hold {t, (0, 0), 1}. Returns each tile's new points in rank order: round r
// gives every tile its point r, tile by tile in index order. The same bits for any thread count.
// Throws Error for inconsistent input, a point outside [0, 1)^2 or not finite, or options outside
// their ranges.
std::vector<std::vector<Point>> band_fill(std::span<const std::vector<Point>> tiles,
                                          std::span<const std::vector<FillSource>> sources, std::size_t add,
                                          const FillOptions& options);

// Throws Error("<what>: ...") unless `tiles` is not empty, its tiles hold the same number of points,
// each in [0, 1)^2, and `sources` holds one list per tile that names known tiles, shifted by at
// most a tile, and the tile itself unshifted: band_fill's input, and the lattice steps'
// (wang_lattice.h).
void check_fill_layout(std::span<const std::vector<Point>> tiles, std::span<const std::vector<FillSource>> sources,
                       std::string_view what);

// What filling `add` points per tile onto `existing` costs, for checks before the work: the grids'
// memory, and about how many grid places the stamps and the choices visit (they grow as
// N log N: each new kernel restamps every point so far; about 6 ns a place on this project's
// machines, one thread, docs/RESULTS.md).
struct FillCost {
  double bytes = 0.0;
  double places_visited = 0.0;
};
// Throws Error, as band_fill would, where the grid of existing + add points exceeds its limit.
FillCost band_fill_cost(std::size_t existing, std::size_t add, std::size_t tiles, const FillOptions& options);
inline constexpr double kFillSecondsPerPlace = 6e-9;

// The untiled form on the unit torus: the `add` points filled in rank order after `existing`.
// An existing point outside [0, 1)^2 counts as its copy inside (the result is the same); one that
// is not finite is an Error.
std::vector<Point> band_fill_torus(std::span<const Point> existing, std::size_t add, const FillOptions& options);

}  // namespace bluetile
