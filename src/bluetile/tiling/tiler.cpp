#include "bluetile/tiling/tiler.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"
#include "bluetile/core/text.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tile_set_file.h"

namespace bluetile {
namespace {

// Where a cell stands against a window, from the bounds its computed positions cannot leave:
// fl(i + x) lies in [i, i + 1] for x in [0, 1), and rounding is monotonic, so every X of cell i is
// in [fl(i S), fl((i + 1) S)].
enum class Overlap { outside, partial, inside };

Overlap overlap(double lo_x, double hi_x, double lo_y, double hi_y, const Window& w) {
  if (hi_x < w.x0 || lo_x >= w.x1 || hi_y < w.y0 || lo_y >= w.y1) return Overlap::outside;
  if (lo_x >= w.x0 && hi_x < w.x1 && lo_y >= w.y0 && hi_y < w.y1) return Overlap::inside;
  return Overlap::partial;
}

}  // namespace

Tiler::Tiler(TileSet set, std::uint64_t seed, double tile_size)
    : set_(std::move(set)), rules_(set_.kind), seed_(seed), tile_size_(tile_size) {
  if (!(std::isfinite(tile_size) && tile_size > 0.0))
    throw Error("tile size must be positive and finite, got " + exact_text(tile_size));
  validate_tile_set(set_);
  ranked_.resize(set_.tiles.size());
  std::size_t total = 0;
  for (std::size_t t = 0; t < set_.tiles.size(); ++t) {
    const Tile& tile = set_.tiles[t];
    if (tile.points.empty()) throw Error("tile set: tile " + std::to_string(t) + " has no points");
    RankedTile& r = ranked_[t];
    std::size_t n = tile.points.size();
    r.points.resize(n);
    r.levels.resize(n);
    r.ranks.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
      r.points[tile.ranks[k]] = tile.points[k];
      r.levels[tile.ranks[k]] = tile.levels[k];
    }
    std::iota(r.ranks.begin(), r.ranks.end(), 0u);
    max_points_ = std::max(max_points_, n);
    total += n;
  }
  mean_points_ = static_cast<double>(total) / static_cast<double>(set_.tiles.size());
}

std::span<const Point> Tiler::ranked_points(int tile) const { return ranked_.at(static_cast<std::size_t>(tile)).points; }
std::span<const int> Tiler::ranked_levels(int tile) const { return ranked_.at(static_cast<std::size_t>(tile)).levels; }

CellRange Tiler::cells(const Window& w) const {
  if (!(std::isfinite(w.x0) && std::isfinite(w.y0) && std::isfinite(w.x1) && std::isfinite(w.y1)))
    throw Error("window coordinates must be finite");
  if (!(w.x1 > w.x0)) throw Error("window: x1 must be greater than x0, got x0 " + exact_text(w.x0) + ", x1 " + exact_text(w.x1));
  if (!(w.y1 > w.y0)) throw Error("window: y1 must be greater than y0, got y0 " + exact_text(w.y0) + ", y1 " + exact_text(w.y1));
  double lo_x = std::floor(w.x0 / tile_size_) - 1.0, hi_x = std::floor(w.x1 / tile_size_) + 2.0;
  double lo_y = std::floor(w.y0 / tile_size_) - 1.0, hi_y = std::floor(w.y1 / tile_size_) + 2.0;
  for (double c : {lo_x, hi_x, lo_y, hi_y})
    if (!(std::fabs(c) <= kMaxCellIndex))
      throw Error("window reaches " + number_text(std::fabs(c)) + " tiles from the origin (at most " + number_text(kMaxCellIndex) +
                  " keep tile-local positions exact enough)");
  return {static_cast<std::int64_t>(lo_x), static_cast<std::int64_t>(lo_y), static_cast<std::int64_t>(hi_x),
          static_cast<std::int64_t>(hi_y)};
}

namespace {

// The kept points of one cell into out_positions/out_ranks (room for the tile's count); returns
// how many. `Ranks` false skips writing ranks (callers that want positions only).
template <bool Ranks>
std::size_t generate_cell(std::span<const Point> points, double fi, double fj, double size, Overlap where,
                          const Window& w, const Thinning* thinning, double dither, Thinning::Bounds cell_bounds,
                          Point* out_positions, std::uint32_t* out_ranks) {
  const std::size_t n = points.size();
  // Ranks below `limit` may be kept (k + dither < f n for some p in the cell); ranks below `sure`
  // are kept wherever they are (k + dither < f n for every p), with a relative margin far above
  // the bilinear lookup's rounding (a few ulps), so the map test is needed only in between.
  auto ranks_below = [&](double fraction) {
    double bound = std::ceil(fraction * static_cast<double>(n) - dither);
    return bound <= 0.0 ? std::size_t{0} : std::min(n, static_cast<std::size_t>(bound));
  };
  std::size_t limit = n, sure = n;
  if (thinning != nullptr) {
    limit = ranks_below(cell_bounds.max);
    sure = thinning->constant() ? limit : std::min(limit, ranks_below(cell_bounds.min * (1.0 - 1e-12)));
  }
  std::size_t count = 0;
  if (where == Overlap::inside) {
    for (std::size_t k = 0; k < sure; ++k) {
      out_positions[k] = Point{(fi + points[k].x) * size, (fj + points[k].y) * size};
      if constexpr (Ranks) out_ranks[k] = static_cast<std::uint32_t>(k);
    }
    count = sure;
  } else {
    for (std::size_t k = 0; k < sure; ++k) {
      Point p{(fi + points[k].x) * size, (fj + points[k].y) * size};
      out_positions[count] = p;
      if constexpr (Ranks) out_ranks[count] = static_cast<std::uint32_t>(k);
      count += w.contains(p) ? 1 : 0;
    }
  }
  if (sure == limit) return count;
  const Thinning::Map map = thinning->map();
  const double scale = static_cast<double>(n);
  for (std::size_t k = sure; k < limit; ++k) {
    Point p{(fi + points[k].x) * size, (fj + points[k].y) * size};
    bool keep = static_cast<double>(k) + dither < sample_map(map, p) * scale;
    if (where != Overlap::inside) keep = keep && w.contains(p);
    out_positions[count] = p;
    if constexpr (Ranks) out_ranks[count] = static_cast<std::uint32_t>(k);
    count += keep ? 1 : 0;
  }
  return count;
}

}  // namespace

void Tiler::for_each_cell(const Window& window, const Thinning* thinning,
                          const std::function<void(const CellPoints&)>& visit) const {
  for_each_cell(window, cells(window), thinning, visit);
}

void Tiler::for_each_cell(const Window& window, const CellRange& range, const Thinning* thinning,
                          const std::function<void(const CellPoints&)>& visit) const {
  std::vector<Point> positions(max_points_);
  std::vector<std::uint32_t> ranks(max_points_);
  for (std::int64_t j = range.j0; j < range.j1; ++j) {
    cancellation_point();  // a row: 10^4 cells of a window of 10^8 (the limit) take about 1 ms
    for (std::int64_t i = range.i0; i < range.i1; ++i) {
      CellPoints cell = cell_points(i, j, window, thinning, positions.data(), ranks.data());
      if (!cell.positions.empty()) visit(cell);
    }
  }
}

CellPoints Tiler::cell_points(std::int64_t i, std::int64_t j, const Window& window, const Thinning* thinning,
                              Point* positions, std::uint32_t* ranks) const {
  const double fi = static_cast<double>(i), fj = static_cast<double>(j);
  const double lo_x = fi * tile_size_, hi_x = (fi + 1.0) * tile_size_;
  const double lo_y = fj * tile_size_, hi_y = (fj + 1.0) * tile_size_;
  CellPoints cell{i, j, 0, {}, {}};
  Overlap where = overlap(lo_x, hi_x, lo_y, hi_y, window);
  if (where == Overlap::outside) return cell;
  double dither = 0.0;
  Thinning::Bounds bounds{1.0, 1.0};
  if (thinning != nullptr) {
    dither = Thinning::dither(i, j, seed_);
    bounds = thinning->fraction_bounds({lo_x, lo_y, hi_x, hi_y});
  }
  cell.tile = tile_at(i, j);
  const RankedTile& ranked = ranked_[static_cast<std::size_t>(cell.tile)];
  std::size_t count;
  if (ranks == nullptr || (thinning == nullptr && where == Overlap::inside)) {
    count = generate_cell<false>(ranked.points, fi, fj, tile_size_, where, window, thinning, dither, bounds,
                                 positions, nullptr);
    if (ranks != nullptr) cell.ranks = std::span<const std::uint32_t>(ranked.ranks.data(), count);
  } else {
    count = generate_cell<true>(ranked.points, fi, fj, tile_size_, where, window, thinning, dither, bounds,
                                positions, ranks);
    cell.ranks = std::span<const std::uint32_t>(ranks, count);
  }
  cell.positions = std::span<const Point>(positions, count);
  return cell;
}

std::size_t Tiler::point_bound(const Window& window) const {
  const CellRange range = cells(window);
  return static_cast<std::size_t>(range.columns()) * static_cast<std::size_t>(range.rows()) * max_points_;
}

std::size_t Tiler::write_points(const Window& window, const Thinning* thinning, Point* out) const {
  const CellRange range = cells(window);
  std::size_t used = 0;
  for (std::int64_t j = range.j0; j < range.j1; ++j)
    for (std::int64_t i = range.i0; i < range.i1; ++i)
      used += cell_points(i, j, window, thinning, out + used, nullptr).positions.size();
  return used;
}

std::size_t Tiler::append_points(const Window& window, const Thinning* thinning, std::vector<Point>& out) const {
  const CellRange range = cells(window);
  const std::size_t start = out.size();
  std::size_t used = start;
  for (std::int64_t j = range.j0; j < range.j1; ++j)
    for (std::int64_t i = range.i0; i < range.i1; ++i) {
      // Room for a whole tile, grown geometrically; the cell writes straight into it.
      if (out.size() < used + max_points_) out.resize(std::max(used + max_points_, 2 * out.size()));
      used += cell_points(i, j, window, thinning, out.data() + used, nullptr).positions.size();
    }
  out.resize(used);
  return used - start;
}

std::vector<TiledPoint> Tiler::tiled_points(const Window& window, const Thinning* thinning) const {
  std::vector<TiledPoint> result;
  for_each_cell(window, thinning, [&](const CellPoints& cell) {
    const RankedTile& ranked = ranked_[static_cast<std::size_t>(cell.tile)];
    for (std::size_t k = 0; k < cell.positions.size(); ++k) {
      std::uint32_t rank = cell.ranks[k];
      result.push_back({cell.positions[k], cell.i, cell.j, cell.tile, ranked.levels[rank], rank, ranked.points[rank]});
    }
  });
  return result;
}

WindowPoints::WindowPoints(const Tiler& tiler, const Window& window, const Thinning* thinning)
    : tiler_(tiler), window_(window), thinning_(thinning), range_(tiler.cells(window)), next_i_(range_.i0),
      next_j_(range_.j0), positions_(tiler.max_points_per_tile()), ranks_(tiler.max_points_per_tile()) {}

bool WindowPoints::load_next_cell() {
  cell_ = {};
  index_ = 0;
  while (cell_.positions.empty() && next_j_ < range_.j1) {
    cell_ = tiler_.cell_points(next_i_, next_j_, window_, thinning_, positions_.data(), ranks_.data());
    if (++next_i_ == range_.i1) next_i_ = range_.i0, ++next_j_;
  }
  return !cell_.positions.empty();
}

bool WindowPoints::next(TiledPoint& point) {
  if (index_ == cell_.positions.size() && !load_next_cell()) return false;
  std::uint32_t rank = cell_.ranks[index_];
  point.position = cell_.positions[index_];
  point.i = cell_.i;
  point.j = cell_.j;
  point.tile = cell_.tile;
  point.rank = rank;
  point.level = tiler_.ranked_levels(cell_.tile)[rank];
  point.local = tiler_.ranked_points(cell_.tile)[rank];
  ++index_;
  return true;
}

}  // namespace bluetile
