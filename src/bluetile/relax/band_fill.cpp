// Band-limited void filling (see band_fill.h).
#include "bluetile/relax/band_fill.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/rng.h"

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
double grid_side(std::size_t total, int cells_per_spacing) {
  return std::ceil(cells_per_spacing / hexagonal_spacing(static_cast<double>(total)));
}

// One tile's grid of candidate places: cell (i, j), at index j * side + i, offers one place, at
// ((i + 1/2, j + 1/2) + jitter) / side with a seeded jitter in [-1/2, 1/2)^2 fixed for the run, so
// that the points fall on no lattice and the floor is checked where a point would go.
struct TileGrid {
  std::vector<Point> place;
  std::vector<double> potential;
  std::vector<float> nearest2;  // squared distance to the nearest point stamped within its reach
};

class Filler {
 public:
  Filler(std::span<const std::vector<Point>> tiles, std::span<const std::vector<FillSource>> sources, std::size_t add,
         const FillOptions& options)
      : options_(options), points_(tiles.begin(), tiles.end()) {
    const std::size_t count = tiles.size();
    existing_ = points_[0].size();
    total_ = existing_ + add;
    side_ = static_cast<std::size_t>(grid_side(total_, options.cells_per_spacing));
    if (side_ > kMaxGrid)
      throw Error("band fill: " + std::to_string(total_) + " points per tile need a grid of " + std::to_string(side_) +
                  " cells a side, more than " + std::to_string(kMaxGrid));
    cell_ = 1.0 / static_cast<double>(side_);
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
  // away, else the cell farthest from every point. The scan starts at a random cell, so that
  // exact ties (an empty grid) go to a random one.
  std::size_t choose(std::size_t t, float threshold2, Rng& rng) const {
    const TileGrid& grid = grids_[t];
    const std::size_t cells = side_ * side_;
    const std::size_t start = static_cast<std::size_t>(rng.below(cells));
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

  // The places of a grid within `radius` of q (tile units, possibly outside the tile).
  template <class Visit>
  void for_places_near(const TileGrid& grid, Point q, double radius, Visit visit) const {
    // A cell's place lies inside the cell: the cells whose square meets the disc.
    const auto range = [&](double centre, long& lo, long& hi) {
      lo = std::max(0L, static_cast<long>(std::floor((centre - radius) / cell_)));
      hi = std::min(static_cast<long>(side_) - 1, static_cast<long>(std::floor((centre + radius) / cell_)));
    };
    long i0, i1, j0, j1;
    range(q.x, i0, i1);
    range(q.y, j0, j1);
    const double r2 = radius * radius;
    for (long j = j0; j <= j1; ++j) {
      for (long i = i0; i <= i1; ++i) {
        const std::size_t c = static_cast<std::size_t>(j) * side_ + static_cast<std::size_t>(i);
        const Point d = grid.place[c] - q;
        const double d2 = d.x * d.x + d.y * d.y;
        if (d2 < r2) visit(c, d2);
      }
    }
  }

  void stamp_potential(std::size_t u, Point p) {
    for (const FillSource& target : targets_[u]) {
      if (!(target.weight > 0.0)) continue;
      TileGrid& grid = grids_[target.tile];
      const double w = target.weight;
      for_places_near(grid, p + target.shift, kernel_.radius(), [&](std::size_t c, double d2) { grid.potential[c] += w * kernel_.at(d2); });
    }
  }

  void stamp_nearest(std::size_t u, Point p, double radius) {
    for (const FillSource& target : targets_[u]) {
      TileGrid& grid = grids_[target.tile];
      for_places_near(grid, p + target.shift, radius, [&](std::size_t c, double d2) {
        grid.nearest2[c] = std::min(grid.nearest2[c], static_cast<float>(d2));
      });
    }
  }

  // A new kernel for prefixes from `prefix` on: every potential restamped with it.
  void rebuild(std::size_t prefix) {
    kernel_prefix_ = prefix;
    kernel_.build(static_cast<double>(prefix), options_.window);
    for (TileGrid& grid : grids_) std::fill(grid.potential.begin(), grid.potential.end(), 0.0);
    for (std::size_t u = 0; u < points_.size(); ++u)
      for (const Point& p : points_[u]) stamp_potential(u, p);
  }

  FillOptions options_;
  std::vector<std::vector<Point>> points_;
  std::vector<std::vector<FillSource>> targets_;
  std::vector<TileGrid> grids_;
  std::size_t existing_ = 0, total_ = 0, side_ = 0;
  double cell_ = 0.0;
  BandKernel kernel_;
  std::size_t kernel_prefix_ = 0;
};

// Checks shared by band_fill and band_rank.
void check_layout(std::span<const std::vector<Point>> tiles, std::span<const std::vector<FillSource>> sources) {
  if (tiles.empty()) throw Error("band fill: no tile");
  if (sources.size() != tiles.size()) throw Error("band fill: one source list per tile is needed");
  for (const std::vector<Point>& tile : tiles)
    if (tile.size() != tiles[0].size()) throw Error("band fill: every tile must hold the same number of points");
  for (std::size_t t = 0; t < sources.size(); ++t) {
    bool self = false;
    for (const FillSource& s : sources[t]) {
      if (s.tile >= tiles.size()) throw Error("band fill: a source names tile " + std::to_string(s.tile));
      if (std::abs(s.shift.x) > 1.0 || std::abs(s.shift.y) > 1.0) throw Error("band fill: a source is shifted past a neighbour");
      self = self || (s.tile == t && s.shift.x == 0.0 && s.shift.y == 0.0);
    }
    if (!self) throw Error("band fill: tile " + std::to_string(t) + " does not count its own points");
  }
}

void validate(const FillOptions& options) {
  check_real_field("fill_floor", options.floor, 0.0, 1.0, " hexagonal spacings");
  check_real_field("fill_window", options.window, 1.0, 8.0, " hexagonal spacings");
  check_whole_field("fill_cells_per_spacing", options.cells_per_spacing, 2, 64);
  if (!(options.regrid > 1.0 && options.regrid <= 2.0))
    throw Error("fill_regrid: expected above 1 to 2, got " + std::to_string(options.regrid));
}

}  // namespace

std::vector<std::vector<Point>> band_fill(std::span<const std::vector<Point>> tiles,
                                          std::span<const std::vector<FillSource>> sources, std::size_t add,
                                          const FillOptions& options) {
  validate(options);
  check_layout(tiles, sources);
  if (add == 0) return std::vector<std::vector<Point>>(tiles.size());
  return Filler(tiles, sources, add, options).run();
}

FillCost band_fill_cost(std::size_t existing, std::size_t add, std::size_t tiles, const FillOptions& options) {
  FillCost cost;
  if (add == 0) return cost;
  const double side = grid_side(existing + add, options.cells_per_spacing);
  const double places = side * side * static_cast<double>(tiles);
  cost.bytes = places * static_cast<double>(sizeof(Point) + sizeof(double) + sizeof(float));
  cost.places_scanned = places * static_cast<double>(add);
  return cost;
}

std::vector<Point> band_fill_torus(std::span<const Point> existing, std::size_t add, const FillOptions& options) {
  const std::vector<std::vector<Point>> tiles{std::vector<Point>(existing.begin(), existing.end())};
  std::vector<std::vector<FillSource>> sources(1);
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) sources[0].push_back({0, Point{static_cast<double>(dx), static_cast<double>(dy)}, 1.0});
  return band_fill(tiles, sources, add, options)[0];
}

}  // namespace bluetile
