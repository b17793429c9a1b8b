// Points of an aperiodic tiling of the infinite plane, window by window: the use the paper's
// abstract names for its tiles ("efficiently tiled over the sampling plane in an aperiodic way ...
// while still allowing for local hierarchical supersampling", Hiller, Deussen, Keller 2001,
// sections 3 and 4), with thinning by rank for any density (density_thinning.h).
//
// The plane: cell (i, j) is the square [i S, (i+1) S] x [j S, (j+1) S] of side S (the tile size, in
// plane units), y up; it holds tile TileRules::tile_at(i, j, seed), a pure O(1) function of the
// cell and the seed. A tile point at tile-local (x, y) in [0,1)^2 sits at the plane position
//   X = fl(fl(i + x) * S),  Y = fl(fl(j + y) * S)
// (fl: rounding to double), a pure function of (i, j, x, y, S): two windows agree bit for bit on
// their overlap, and a window is exactly the union of its parts. Error against the exact
// (i + x) S: at most 2^-53 (|i| + 1) S + ulp(X) / 2, i.e. below 2.3e-10 S at 10^6 tiles from the
// origin. Users who need more keep the exact form (cell, tile-local point) every point carries.
//
// Windows are half-open, [x0, x1) x [y0, y1), so that windows sharing an edge never share a point.
// Cells are visited row by row from the bottom (j ascending), each row left to right, and a
// cell's points in rank order: the order of a window's points is fixed too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"
#include "bluetile/tiling/tile_set.h"

namespace bluetile {

class Thinning;

// A window of the plane, [x0, x1) x [y0, y1), plane units.
struct Window {
  double x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0;

  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  double area() const { return width() * height(); }
  bool contains(Point p) const { return p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1; }
};

// Cells i0..i1-1 by j0..j1-1 (half-open), the cells a window may draw points from.
struct CellRange {
  std::int64_t i0 = 0, j0 = 0, i1 = 0, j1 = 0;

  std::int64_t columns() const { return i1 - i0; }
  std::int64_t rows() const { return j1 - j0; }
};

// One point of a tiled window, with where it comes from.
struct TiledPoint {
  Point position{0.0, 0.0}; // plane coordinates
  std::int64_t i = 0, j = 0;  // its cell
  int tile = 0;            // the tile id in that cell
  int level = 0;           // its level in the tile
  std::uint32_t rank = 0;  // its rank in the tile (0 = first in the progressive order)
  Point local{0.0, 0.0};    // tile-local coordinates in [0,1)^2, exact as in the tile set
};

// The kept points of one cell, as the fast path hands them out: positions[k] has rank ranks[k].
struct CellPoints {
  std::int64_t i = 0, j = 0;
  int tile = 0;
  std::span<const Point> positions;
  std::span<const std::uint32_t> ranks;
};

// Cells farther than this from the origin (in tiles, along either axis) are refused: at 2^31 a
// tile-local offset is still resolved to 2^-21 of a tile (ulp of 2^31 in double).
inline constexpr double kMaxCellIndex = 2147483648.0;

class Tiler {
 public:
  // Throws Error for an invalid set (validate_tile_set), an empty tile, or a tile size that is
  // not positive and finite.
  Tiler(TileSet set, std::uint64_t seed, double tile_size);

  const TileSet& tile_set() const { return set_; }
  const TileRules& rules() const { return rules_; }
  std::uint64_t seed() const { return seed_; }
  double tile_size() const { return tile_size_; }
  // Points of the largest tile, and the mean over tiles: the density of the full tiling is
  // mean_points_per_tile() / tile_size()^2 points per unit area.
  std::size_t max_points_per_tile() const { return max_points_; }
  double mean_points_per_tile() const { return mean_points_; }
  double full_density() const { return mean_points_ / (tile_size_ * tile_size_); }

  // The tile of cell (i, j): O(1), the same for the same seed anywhere on the plane.
  int tile_at(std::int64_t i, std::int64_t j) const { return rules_.tile_at(i, j, seed_); }
  // The plane position of tile-local point `local` of cell (i, j) (the formula above).
  Point position(std::int64_t i, std::int64_t j, Point local) const {
    return {(static_cast<double>(i) + local.x) * tile_size_, (static_cast<double>(j) + local.y) * tile_size_};
  }
  // Tile `tile`'s points in rank order (local coordinates) and their levels.
  std::span<const Point> ranked_points(int tile) const;
  std::span<const int> ranked_levels(int tile) const;

  // The cells whose points can fall into `window` (one cell of margin on each side, since a point
  // just inside a cell's edge may round onto it). Throws Error for a window that is not finite,
  // whose x1 <= x0 or y1 <= y0, or that reaches beyond kMaxCellIndex tiles.
  CellRange cells(const Window& window) const;

  // Calls visit(points) for every cell of cells(window) that keeps at least one point inside
  // `window`, in the fixed order, with that cell's kept points. `thinning` (nullptr: keep all)
  // decides which ranks a cell keeps. The spans are valid during the call only.
  void for_each_cell(const Window& window, const Thinning* thinning,
                     const std::function<void(const CellPoints&)>& visit) const;
  // The same for the cells j0..j1-1 of one range only (for callers that split a window's rows
  // among threads): cells(window) must contain them.
  void for_each_cell(const Window& window, const CellRange& range, const Thinning* thinning,
                     const std::function<void(const CellPoints&)>& visit) const;

  // Appends the positions of every kept point of `window` to `out`, in the fixed order; returns
  // how many were appended.
  std::size_t append_points(const Window& window, const Thinning* thinning, std::vector<Point>& out) const;

  // Cell (i, j)'s kept points inside `window`, written to `positions` and `ranks` (room for
  // max_points_per_tile() each; ranks nullptr: positions only, and the result's ranks empty).
  // The result's spans point into those buffers (or into the tiler); empty when none is kept.
  CellPoints cell_points(std::int64_t i, std::int64_t j, const Window& window, const Thinning* thinning,
                         Point* positions, std::uint32_t* ranks) const;

  // The fastest form: the positions of every kept point of `window`, in the fixed order, written
  // to `out`, which must have room for point_bound(window) points (an upper bound: every point of
  // every cell the window touches); returns how many were written.
  std::size_t point_bound(const Window& window) const;
  std::size_t write_points(const Window& window, const Thinning* thinning, Point* out) const;

  // Every kept point of `window` with its cell, tile, level and rank, in the fixed order.
  std::vector<TiledPoint> tiled_points(const Window& window, const Thinning* thinning = nullptr) const;

 private:
  struct RankedTile {
    std::vector<Point> points;  // in rank order
    std::vector<int> levels;
    std::vector<std::uint32_t> ranks;  // 0, 1, 2, ...: handed out as spans
  };

  TileSet set_;
  TileRules rules_;
  std::uint64_t seed_;
  double tile_size_;
  std::vector<RankedTile> ranked_;
  std::size_t max_points_ = 0;
  double mean_points_ = 0.0;
};

// A points-in-window iterator for code that embeds the library: yields every kept point of a
// window in the fixed order, one at a time, holding one cell's points at a time.
//   WindowPoints points(tiler, window);
//   for (TiledPoint p; points.next(p);) use(p);
class WindowPoints {
 public:
  // `tiler` and `thinning` must outlive the iterator. Throws as Tiler::cells does.
  WindowPoints(const Tiler& tiler, const Window& window, const Thinning* thinning = nullptr);

  // The next point into `point`; false (and `point` untouched) once the window is exhausted.
  bool next(TiledPoint& point);

 private:
  bool load_next_cell();

  const Tiler& tiler_;
  Window window_;
  const Thinning* thinning_;
  CellRange range_;
  std::int64_t next_i_, next_j_;
  std::vector<Point> positions_;
  std::vector<std::uint32_t> ranks_;
  CellPoints cell_;  // the current cell's kept points (spans into the buffers above)
  std::size_t index_ = 0;
};

}  // namespace bluetile
