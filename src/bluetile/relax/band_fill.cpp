// Band-limited void filling (see band_fill.h).
#include "bluetile/relax/band_fill.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstdio>
#include <cmath>
#include <limits>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Samples of the kernel's radial profile, uniform in r^2 (the stamps compute r^2, not r): the
// linear interpolation between them is below 1e-4 of the peak, far under what moves an argmin.
constexpr std::size_t kKernelSamples = 4096;
// A grid finer than this per tile side is a mistyped count (8192^2 cells hold 1.3 GB per tile).
constexpr std::size_t kMaxGrid = 8192;

// The windowed band kernel at one prefix: jinc(2 pi R r) (the plane's ideal low pass, band radius
// R = sqrt(k) / 2 cycles per tile) times a Hann window of radius rc, tabulated against r^2.
class BandKernel {
 public:
  void build(double prefix, double window) {
    const double band = 0.5 * std::sqrt(prefix);
    radius_ = std::min(window * hexagonal_spacing(prefix), 1.0);  // shifts reach one tile, no further
    radius2_ = radius_ * radius_;
    table_.resize(kKernelSamples + 1);
    for (std::size_t s = 0; s <= kKernelSamples; ++s) {
      const double r = std::sqrt(radius2_ * static_cast<double>(s) / kKernelSamples);
      const double z = 2.0 * kPi * band * r;
      const double jinc = z < 1e-9 ? 1.0 : 2.0 * std::cyl_bessel_j(1.0, z) / z;
      table_[s] = jinc * (0.5 + 0.5 * std::cos(kPi * r / radius_));
    }
  }
  double radius() const { return radius_; }
  double radius2() const { return radius2_; }
  double at(double r2) const {
    const double t = r2 / radius2_ * kKernelSamples;
    const std::size_t s = std::min(static_cast<std::size_t>(t), kKernelSamples - 1);
    const double f = t - static_cast<double>(s);
    return table_[s] + f * (table_[s + 1] - table_[s]);
  }

 private:
  double radius_ = 0.0, radius2_ = 0.0;
  std::vector<double> table_;
};

// Places a side of each tile's grid: cells_per_spacing per hexagonal spacing of the final count.
// Throws Error past kMaxGrid, naming the largest count the grid allows.
std::size_t grid_side(std::size_t total, int cells_per_spacing) {
  const double side = std::ceil(cells_per_spacing / hexagonal_spacing(static_cast<double>(total)));
  if (side > static_cast<double>(kMaxGrid)) {
    // hexagonal_spacing(N) = sqrt(2 / (sqrt(3) N)) = cells_per_spacing / kMaxGrid at the limit.
    const double limit = 2.0 / std::sqrt(3.0) * std::pow(static_cast<double>(kMaxGrid) / cells_per_spacing, 2.0);
    char most[32];
    const ClassicNumbers classic;
    std::snprintf(most, sizeof most, "%.3g", limit);
    throw Error("band fill: " + std::to_string(total) + " points per tile or set need a grid of " +
                std::to_string(static_cast<long long>(side)) + " places a side, more than " + std::to_string(kMaxGrid) +
                " (at most about " + most + " points at " + std::to_string(cells_per_spacing) + " places per spacing)");
  }
  return static_cast<std::size_t>(side);
}

// A point changes the grid only within its kernel's reach, so the choice of the next place keeps a
// summary per block of kBlockSide^2 cells (its least potential among the places far enough from
// every point) in a tournament tree, and re-reads only the blocks a stamp touched or whose places
// a falling floor let in. A round then costs about the cells its stamps cover, not a scan of every
// place: the fill grows as N log N instead of N^2. The choice is the same as a scan's, ties and all.
constexpr std::size_t kBlockSide = 16;
// Rows of a grid per task of a parallel restamp.
constexpr std::size_t kRebuildBandRows = 32;
constexpr float kNoneIneligible = -1.0f;  // below every squared distance

// A block's summary, and a node's of the blocks below it: the least potential of an eligible
// place (at least the floor from every point) and where it is, whether another eligible place
// has the same potential, and the largest squared distance below the floor (a falling floor
// lets that place in).
struct BlockSummary {
  double least = 0.0;
  std::size_t place = kNoPlace;  // kNoPlace: no eligible place
  bool tied = false;
  float ineligible2 = kNoneIneligible;

  static constexpr std::size_t kNoPlace = static_cast<std::size_t>(-1);
};

class BlockTree {
 public:
  void reset(std::size_t blocks) {
    leaves_ = std::bit_ceil(std::max<std::size_t>(blocks, 1));
    node_.assign(2 * leaves_, BlockSummary{});
  }
  void set(std::size_t b, const BlockSummary& s) {
    std::size_t n = leaves_ + b;
    node_[n] = s;
    for (n /= 2; n >= 1; n /= 2) node_[n] = merge(node_[2 * n], node_[2 * n + 1]);
  }
  const BlockSummary& root() const { return node_[1]; }
  // Appends the blocks holding an ineligible place at squared distance >= threshold2.
  void crossed(float threshold2, std::vector<std::size_t>& out) const { crossed(1, threshold2, out); }

 private:
  static BlockSummary merge(const BlockSummary& a, const BlockSummary& b) {
    const bool a_has = a.place != BlockSummary::kNoPlace, b_has = b.place != BlockSummary::kNoPlace;
    BlockSummary m = !b_has || (a_has && a.least < b.least) ? a : !a_has || b.least < a.least ? b : a;
    if (a_has && b_has && a.least == b.least) m.tied = true;
    m.ineligible2 = std::max(a.ineligible2, b.ineligible2);
    return m;
  }
  void crossed(std::size_t n, float threshold2, std::vector<std::size_t>& out) const {
    if (!(node_[n].ineligible2 >= threshold2)) return;
    if (n >= leaves_) {
      out.push_back(n - leaves_);
      return;
    }
    crossed(2 * n, threshold2, out);
    crossed(2 * n + 1, threshold2, out);
  }

  std::size_t leaves_ = 0;
  std::vector<BlockSummary> node_;  // node n's children are 2n and 2n + 1; the blocks are the leaves
};

// The cells of a grid whose squares meet a disc: columns i0..i1, rows j0..j1.
struct Window {
  long i0, i1, j0, j1;
};

// One tile's grid of candidate places: cell (i, j), at index j * side + i, offers one place, at
// ((i + 1/2, j + 1/2) + jitter) / side with a seeded jitter in [-1/2, 1/2)^2 fixed for the run, so
// that the points fall on no lattice and the floor is checked where a point would go.
struct TileGrid {
  std::vector<Point> place;
  std::vector<double> potential;
  std::vector<float> nearest2;  // squared distance to the nearest point stamped within its reach
  BlockTree tree;
  std::vector<std::uint8_t> is_dirty;  // per block: to be read again before the next choice
  std::vector<std::size_t> dirty;      // those blocks, in the order they were marked
  float threshold2 = std::numeric_limits<float>::infinity();  // the squared floor of the last choice
};

class Filler {
 public:
  Filler(std::span<const std::vector<Point>> tiles, std::span<const std::vector<FillSource>> sources, std::size_t add,
         const FillOptions& options)
      : options_(options), points_(tiles.begin(), tiles.end()) {
    const std::size_t count = tiles.size();
    existing_ = points_[0].size();
    total_ = existing_ + add;
    side_ = grid_side(total_, options.cells_per_spacing);
    cell_ = 1.0 / static_cast<double>(side_);
    block_side_ = (side_ + kBlockSide - 1) / kBlockSide;
    grids_.resize(count);
    for (std::size_t t = 0; t < count; ++t) {
      TileGrid& grid = grids_[t];
      Rng jitter(derive_seed(options.seed, t));
      grid.place.resize(side_ * side_);
      // (i + u) / side rounds to 1 for u just below 1 in the last cell: kept inside the tile.
      const double below_one = std::nextafter(1.0, 0.0);
      for (std::size_t c = 0; c < side_ * side_; ++c) {
        const Point p = Point{static_cast<double>(c % side_) + jitter.uniform(), static_cast<double>(c / side_) + jitter.uniform()} * cell_;
        grid.place[c] = Point{std::min(p.x, below_one), std::min(p.y, below_one)};
      }
      grid.potential.assign(side_ * side_, 0.0);
      grid.nearest2.assign(side_ * side_, std::numeric_limits<float>::infinity());
      grid.tree.reset(block_side_ * block_side_);
      grid.is_dirty.assign(block_side_ * block_side_, 0);
      for (std::size_t b = 0; b < grid.is_dirty.size(); ++b) mark_dirty(grid, b);
    }
    // Where each tile's points count: the reverse of `sources`.
    targets_.resize(count);
    for (std::size_t t = 0; t < count; ++t)
      for (const FillSource& s : sources[t]) targets_[s.tile].push_back({t, s.shift, s.weight});
    // The existing points block the floor of the first new point: their own stamps are larger.
    for (std::size_t u = 0; u < count; ++u)
      for (std::size_t m = 0; m < existing_; ++m)
        stamp_nearest(u, points_[u][m], options.floor * hexagonal_spacing(static_cast<double>(existing_ + 1)));
  }

  std::vector<std::vector<Point>> run() {
    Rng rng(derive_seed(options_.seed, points_.size()));
    const std::size_t count = points_.size();
    const std::size_t add = total_ - existing_;
    for (std::size_t r = 0; r < add; ++r) {
      const std::size_t prefix = existing_ + r + 1;
      if (kernel_prefix_ == 0 || static_cast<double>(prefix) > options_.regrid * static_cast<double>(kernel_prefix_))
        rebuild(prefix);
      const double floor = options_.floor * hexagonal_spacing(static_cast<double>(prefix));
      for (std::size_t t = 0; t < count; ++t) {
        const Point p = grids_[t].place[choose(t, static_cast<float>(floor * floor), rng)];
        points_[t].push_back(p);
        stamp_potential(t, p);
        stamp_nearest(t, p, floor);
      }
      if (options_.on_round) options_.on_round(r + 1, add);
    }
    std::vector<std::vector<Point>> added(count);
    for (std::size_t t = 0; t < count; ++t) added[t].assign(points_[t].begin() + static_cast<std::ptrdiff_t>(existing_), points_[t].end());
    return added;
  }

 private:
  // The cell of least potential among those whose nearest point is at least sqrt(threshold2)
  // away, else the cell farthest from every point; exact ties go to the first in the order of a
  // scan from a random cell (so that an empty grid gives a random one), which only a scan knows.
  std::size_t choose(std::size_t t, float threshold2, Rng& rng) {
    TileGrid& grid = grids_[t];
    const std::size_t start = static_cast<std::size_t>(rng.below(side_ * side_));
    refresh(grid, threshold2);
    const BlockSummary& best = grid.tree.root();
    if (best.place == BlockSummary::kNoPlace || best.tied) return scan(grid, threshold2, start);
    return best.place;
  }

  // Every place, from `start` on: the first of least potential among the eligible ones, else the
  // first farthest from every point.
  std::size_t scan(const TileGrid& grid, float threshold2, std::size_t start) const {
    const std::size_t cells = side_ * side_;
    std::size_t best = cells, farthest = start;
    double best_value = 0.0;
    for (std::size_t n = 0, c = start; n < cells; ++n, c = c + 1 == cells ? 0 : c + 1) {
      const float d2 = grid.nearest2[c];
      if (d2 >= threshold2) {
        if (best == cells || grid.potential[c] < best_value) best = c, best_value = grid.potential[c];
      } else if (best == cells && d2 > grid.nearest2[farthest]) {
        farthest = c;
      }
    }
    return best != cells ? best : farthest;
  }

  // Reads again the blocks stamped since the last choice and those a lower floor lets places into.
  void refresh(TileGrid& grid, float threshold2) {
    if (threshold2 > grid.threshold2) {  // a higher floor shuts places out anywhere (not in a fill's rounds)
      for (std::size_t b = 0; b < grid.is_dirty.size(); ++b) mark_dirty(grid, b);
    } else {
      crossed_.clear();
      grid.tree.crossed(threshold2, crossed_);
      for (std::size_t b : crossed_) mark_dirty(grid, b);
    }
    grid.threshold2 = threshold2;
    for (std::size_t b : grid.dirty) {
      grid.tree.set(b, summarize(grid, b, threshold2));
      grid.is_dirty[b] = 0;
    }
    grid.dirty.clear();
  }

  BlockSummary summarize(const TileGrid& grid, std::size_t b, float threshold2) const {
    BlockSummary s;
    const std::size_t i0 = b % block_side_ * kBlockSide, j0 = b / block_side_ * kBlockSide;
    const std::size_t i1 = std::min(side_, i0 + kBlockSide), j1 = std::min(side_, j0 + kBlockSide);
    for (std::size_t j = j0; j < j1; ++j) {
      for (std::size_t c = j * side_ + i0, end = j * side_ + i1; c < end; ++c) {
        const float d2 = grid.nearest2[c];
        if (d2 >= threshold2) {
          const double p = grid.potential[c];
          if (s.place == BlockSummary::kNoPlace || p < s.least) {
            s.least = p, s.place = c, s.tied = false;
          } else if (p == s.least) {
            s.tied = true;
          }
        } else {
          s.ineligible2 = std::max(s.ineligible2, d2);
        }
      }
    }
    return s;
  }

  static void mark_dirty(TileGrid& grid, std::size_t b) {
    if (grid.is_dirty[b]) return;
    grid.is_dirty[b] = 1;
    grid.dirty.push_back(b);
  }

  // The cells of the grid whose square meets the disc of `radius` about q (tile units, possibly
  // outside the tile): false when none.
  bool window(Point q, double radius, Window& w) const {
    const auto range = [&](double centre, long& lo, long& hi) {
      lo = std::max(0L, static_cast<long>(std::floor((centre - radius) / cell_)));
      hi = std::min(static_cast<long>(side_) - 1, static_cast<long>(std::floor((centre + radius) / cell_)));
    };
    range(q.x, w.i0, w.i1);
    range(q.y, w.j0, w.j1);
    return w.i0 <= w.i1 && w.j0 <= w.j1;
  }

  // The places within `radius` of q (its window w) in rows row_lo to row_hi - 1 (a cell's place
  // lies inside the cell: only the cells whose square meets the disc are looked at).
  template <class Visit>
  void for_places_near(const TileGrid& grid, Point q, double radius, const Window& w, long row_lo, long row_hi,
                       Visit visit) const {
    const double r2 = radius * radius;
    for (long j = std::max(w.j0, row_lo), j_end = std::min(w.j1 + 1, row_hi); j < j_end; ++j) {
      // Only the cells of the row whose square meets the disc (a hair wider, for rounding).
      const double bottom = static_cast<double>(j) * cell_, dy = std::max({0.0, bottom - q.y, q.y - (bottom + cell_)});
      if (dy >= radius) continue;
      const double half = std::sqrt(r2 - dy * dy) * (1.0 + 1e-9) + 1e-12;
      const long row_i0 = std::max(w.i0, static_cast<long>(std::floor((q.x - half) / cell_)));
      const long row_i1 = std::min(w.i1, static_cast<long>(std::floor((q.x + half) / cell_)));
      for (long i = row_i0; i <= row_i1; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * side_ + static_cast<std::size_t>(i);
        const Point d = grid.place[c] - q;
        const double d2 = d.x * d.x + d.y * d.y;
        if (d2 < r2) visit(c, d2);
      }
    }
  }

  // for_places_near over every row, the blocks it may change marked to be read again.
  template <class Visit>
  void change_places_near(TileGrid& grid, Point q, double radius, Visit visit) {
    Window w;
    if (!window(q, radius, w)) return;
    const std::size_t bi1 = static_cast<std::size_t>(w.i1) / kBlockSide, bj1 = static_cast<std::size_t>(w.j1) / kBlockSide;
    for (std::size_t bj = static_cast<std::size_t>(w.j0) / kBlockSide; bj <= bj1; ++bj)
      for (std::size_t bi = static_cast<std::size_t>(w.i0) / kBlockSide; bi <= bi1; ++bi) mark_dirty(grid, bj * block_side_ + bi);
    for_places_near(grid, q, radius, w, 0, static_cast<long>(side_), visit);
  }

  void stamp_potential(std::size_t u, Point p) {
    for (const FillSource& target : targets_[u]) {
      if (!(target.weight > 0.0)) continue;
      TileGrid& grid = grids_[target.tile];
      const double w = target.weight;
      change_places_near(grid, p + target.shift, kernel_.radius(), [&](std::size_t c, double d2) { grid.potential[c] += w * kernel_.at(d2); });
    }
  }

  void stamp_nearest(std::size_t u, Point p, double radius) {
    for (const FillSource& target : targets_[u]) {
      TileGrid& grid = grids_[target.tile];
      change_places_near(grid, p + target.shift, radius, [&](std::size_t c, double d2) {
        grid.nearest2[c] = std::min(grid.nearest2[c], static_cast<float>(d2));
      });
    }
  }

  // A new kernel for prefixes from `prefix` on: every potential restamped with it, in bands of
  // rows on every thread. A place adds the points' terms in the order of a serial restamp (tile,
  // then rank, then source), so the bits do not depend on the thread count.
  void rebuild(std::size_t prefix) {
    kernel_prefix_ = prefix;
    kernel_.build(static_cast<double>(prefix), options_.window);
    // Every stamp, in that order, listed under the grid it lands in with its rows, so that a band
    // finds its stamps by two comparisons each.
    for (std::vector<Restamp>& list : restamps_) list.clear();
    restamps_.resize(grids_.size());
    for (std::size_t u = 0; u < points_.size(); ++u) {
      for (const Point& p : points_[u]) {
        for (const FillSource& target : targets_[u]) {
          Window w;
          if (!(target.weight > 0.0) || !window(p + target.shift, kernel_.radius(), w)) continue;
          restamps_[target.tile].push_back({p + target.shift, target.weight, w});
        }
      }
    }
    const std::size_t bands = (side_ + kRebuildBandRows - 1) / kRebuildBandRows;
    parallel_for(grids_.size() * bands, 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t chunk = begin; chunk < end; ++chunk) {
        TileGrid& grid = grids_[chunk / bands];
        const long row_lo = static_cast<long>(chunk % bands * kRebuildBandRows);
        const long row_hi = std::min(static_cast<long>(side_), row_lo + static_cast<long>(kRebuildBandRows));
        std::fill(grid.potential.begin() + row_lo * static_cast<long>(side_), grid.potential.begin() + row_hi * static_cast<long>(side_), 0.0);
        for (const Restamp& r : restamps_[chunk / bands]) {
          if (r.window.j1 < row_lo || r.window.j0 >= row_hi) continue;
          for_places_near(grid, r.centre, kernel_.radius(), r.window, row_lo, row_hi,
                          [&](std::size_t c, double d2) { grid.potential[c] += r.weight * kernel_.at(d2); });
        }
      }
    });
    for (TileGrid& grid : grids_)
      for (std::size_t b = 0; b < grid.is_dirty.size(); ++b) mark_dirty(grid, b);
  }

  FillOptions options_;
  std::vector<std::vector<Point>> points_;
  std::vector<std::vector<FillSource>> targets_;
  std::vector<TileGrid> grids_;
  std::size_t existing_ = 0, total_ = 0, side_ = 0, block_side_ = 0;
  std::vector<std::size_t> crossed_;  // scratch of refresh
  struct Restamp {
    Point centre;
    double weight;
    Window window;
  };
  std::vector<std::vector<Restamp>> restamps_;  // scratch of rebuild, per grid
  double cell_ = 0.0;
  BandKernel kernel_;
  std::size_t kernel_prefix_ = 0;
};

// Checks shared by band_fill and band_rank.
void validate(const FillOptions& options) {
  check_real_field("fill_floor", options.floor, 0.0, 1.0, " hexagonal spacings");
  check_real_field("fill_window", options.window, 1.0, 8.0, " hexagonal spacings");
  check_whole_field("fill_cells_per_spacing", options.cells_per_spacing, 2, 64);
  if (!(options.regrid > 1.0 && options.regrid <= 2.0))
    throw Error("fill_regrid: expected above 1 to 2, got " + shortest_text(options.regrid));
}

}  // namespace

void check_fill_layout(std::span<const std::vector<Point>> tiles, std::span<const std::vector<FillSource>> sources,
                       std::string_view what) {
  const std::string prefix = std::string(what) + ": ";
  if (tiles.empty()) throw Error(prefix + "no tile");
  if (sources.size() != tiles.size()) throw Error(prefix + "one source list per tile is needed");
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    if (tiles[t].size() != tiles[0].size()) throw Error(prefix + "every tile must hold the same number of points");
    // A NaN or a point outside its tile fell out of the grid's buckets without a word.
    for (std::size_t i = 0; i < tiles[t].size(); ++i) {
      const Point p = tiles[t][i];
      if (!(p.x >= 0.0 && p.x < 1.0 && p.y >= 0.0 && p.y < 1.0))
        throw Error(prefix + "tile " + std::to_string(t) + ", point " + std::to_string(i) + " (" + shortest_text(p.x) +
                    ", " + shortest_text(p.y) + ") lies outside [0, 1)^2");
    }
  }
  for (std::size_t t = 0; t < sources.size(); ++t) {
    bool self = false;
    for (const FillSource& s : sources[t]) {
      if (s.tile >= tiles.size()) throw Error(prefix + "a source names tile " + std::to_string(s.tile));
      if (!(std::abs(s.shift.x) <= 1.0 && std::abs(s.shift.y) <= 1.0)) throw Error(prefix + "a source is shifted past a neighbour");
      self = self || (s.tile == t && s.shift.x == 0.0 && s.shift.y == 0.0);
    }
    if (!self) throw Error(prefix + "tile " + std::to_string(t) + " does not count its own points");
  }
}

std::vector<std::vector<Point>> band_fill(std::span<const std::vector<Point>> tiles,
                                          std::span<const std::vector<FillSource>> sources, std::size_t add,
                                          const FillOptions& options) {
  validate(options);
  check_fill_layout(tiles, sources, "band fill");
  if (add == 0) return std::vector<std::vector<Point>>(tiles.size());
  return Filler(tiles, sources, add, options).run();
}

FillCost band_fill_cost(std::size_t existing, std::size_t add, std::size_t tiles, const FillOptions& options) {
  FillCost cost;
  if (add == 0) return cost;
  const std::size_t total = existing + add;
  const double side = static_cast<double>(grid_side(total, options.cells_per_spacing));
  const double places = side * side;
  const double blocks = std::ceil(side / kBlockSide) * std::ceil(side / kBlockSide);
  cost.bytes = static_cast<double>(tiles) * (places * static_cast<double>(sizeof(Point) + sizeof(double) + sizeof(float)) +
                                             blocks * static_cast<double>(1 + 2 * sizeof(BlockSummary)));
  // The places one stamp of the kernel for a prefix covers, its shifted copies together.
  const auto disc = [&](double prefix) {
    const double radius = std::min(options.window * hexagonal_spacing(prefix), 1.0) * side;
    return std::min(kPi * radius * radius, 9.0 * places);
  };
  // The fill's own schedule: a restamp of every point so far at each new kernel, then per round
  // the new point's stamp and the blocks it touched read again.
  double visits = 0.0, kernel_prefix = 0.0, round = 0.0;
  for (std::size_t p = existing + 1; p <= total; ++p) {
    if (kernel_prefix == 0.0 || static_cast<double>(p) > options.regrid * kernel_prefix) {
      kernel_prefix = static_cast<double>(p);
      round = 2.0 * disc(kernel_prefix);
      visits += static_cast<double>(p - 1) * disc(kernel_prefix);
    }
    visits += round;
  }
  cost.places_visited = visits * static_cast<double>(tiles);
  return cost;
}

std::vector<Point> band_fill_torus(std::span<const Point> existing, std::size_t add, const FillOptions& options) {
  check_finite_points(existing, "band fill");
  std::vector<std::vector<Point>> tiles{std::vector<Point>(existing.begin(), existing.end())};
  for (Point& p : tiles[0]) p = wrap_point(p, Domain{});  // on the torus, 1.25 is 0.25
  std::vector<std::vector<FillSource>> sources(1);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) sources[0].push_back({0, Point{static_cast<double>(dx), static_cast<double>(dy)}, 1.0});
  return band_fill(tiles, sources, add, options)[0];
}

}  // namespace bluetile
