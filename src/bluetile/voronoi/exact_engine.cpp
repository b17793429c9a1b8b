// Exact periodic Voronoi cells by half-plane clipping (see exact_engine.h for the method).
#include "bluetile/voronoi/exact_engine.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/scene.h"

namespace bluetile {
namespace {

// Sites bucketed on a uniform grid over the domain, stored contiguously in bucket order.
class PeriodicGrid {
 public:
  explicit PeriodicGrid(const Scene& scene) : domain_(scene.domain) {
    const std::size_t n = scene.sites.size();
    double bucket_side =
        std::sqrt(kSitesPerBucket * domain_.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
    columns_ = std::clamp<long>(std::lround(domain_.size.x / bucket_side), 1, 1 << 14);
    rows_ = std::clamp<long>(std::lround(domain_.size.y / bucket_side), 1, 1 << 14);
    cell_size_ = {domain_.size.x / static_cast<double>(columns_), domain_.size.y / static_cast<double>(rows_)};

    std::vector<std::uint32_t> bucket_of(n);
    start_.assign(static_cast<std::size_t>(columns_ * rows_) + 1, 0);
    for (std::size_t i = 0; i < n; ++i) {
      auto [cx, cy] = bucket_coordinates(scene.sites[i]);
      bucket_of[i] = static_cast<std::uint32_t>(cy * columns_ + cx);
      ++start_[bucket_of[i] + 1];
    }
    for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
    points_.resize(n);
    index_.resize(n);
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {  // stable: within a bucket, sites keep index order
      std::uint32_t slot = fill[bucket_of[i]]++;
      points_[slot] = scene.sites[i];
      index_[slot] = static_cast<std::uint32_t>(i);
    }
    build_search_order();
  }

  // A bucket offset and the least distance from any point of bucket (0,0) to bucket (dx,dy).
  struct SearchStep {
    long dx, dy;
    double lower_bound_squared;
  };
  // Every offset within kSearchRadius buckets whose lower bound is below kSearchRadius buckets,
  // nearest first: a cell is complete once the next step's bound reaches twice its radius.
  const std::vector<SearchStep>& search_order() const { return search_order_; }

  std::pair<long, long> bucket_coordinates(Point p) const {
    long cx = std::clamp<long>(static_cast<long>(p.x / cell_size_.x), 0, columns_ - 1);
    long cy = std::clamp<long>(static_cast<long>(p.y / cell_size_.y), 0, rows_ - 1);
    return {cx, cy};
  }

  long columns() const { return columns_; }
  long rows() const { return rows_; }
  Point cell_size() const { return cell_size_; }
  const Domain& domain() const { return domain_; }

  // Calls visit(site index, offset from `origin` to that copy of the site) for every site in
  // bucket (cx, cy), where cx, cy may lie outside the grid: they then name a periodic copy.
  template <typename Visit>
  void for_each_in_bucket(long cx, long cy, Point origin, Visit visit) const {
    long wx = wrap_count(cx, columns_), wy = wrap_count(cy, rows_);
    std::size_t b = static_cast<std::size_t>((cy - wy * rows_) * columns_ + (cx - wx * columns_));
    Point shift{static_cast<double>(wx) * domain_.size.x - origin.x,
                static_cast<double>(wy) * domain_.size.y - origin.y};
    for (std::uint32_t s = start_[b]; s < start_[b + 1]; ++s) visit(index_[s], points_[s] + shift);
  }

  // Buckets in storage order, for cache-friendly traversal.
  std::size_t bucket_count() const { return start_.size() - 1; }
  std::span<const std::uint32_t> sites_in_bucket(std::size_t b) const {
    return {index_.data() + start_[b], index_.data() + start_[b + 1]};
  }

 private:
  // How many periods bucket index a lies away from [0, n): floor(a / n), without a division in
  // the common case of a neighbour at most one period away (divisions dominated the search).
  static long wrap_count(long a, long n) {
    if (a >= 0) return a < n ? 0 : a < 2 * n ? 1 : a / n;
    return a >= -n ? -1 : -((-a + n - 1) / n);
  }

  void build_search_order() {
    // Offsets beyond the radius have a bound of at least this; keeping only steps below it makes
    // the list complete up to it, whatever the bucket shape.
    const double limit = static_cast<double>(kSearchRadius) * std::min(cell_size_.x, cell_size_.y);
    for (long dy = -kSearchRadius; dy <= kSearchRadius; ++dy) {
      for (long dx = -kSearchRadius; dx <= kSearchRadius; ++dx) {
        double gx = static_cast<double>(std::max(0L, std::labs(dx) - 1)) * cell_size_.x;
        double gy = static_cast<double>(std::max(0L, std::labs(dy) - 1)) * cell_size_.y;
        double bound = gx * gx + gy * gy;
        if (bound < limit * limit) search_order_.push_back({dx, dy, bound});
      }
    }
    // Nearest first; among equal bounds the nearer bucket centre first, then a fixed order.
    std::stable_sort(search_order_.begin(), search_order_.end(), [](const SearchStep& a, const SearchStep& b) {
      if (a.lower_bound_squared != b.lower_bound_squared) return a.lower_bound_squared < b.lower_bound_squared;
      return a.dx * a.dx + a.dy * a.dy < b.dx * b.dx + b.dy * b.dy;
    });
  }

  // About one site per bucket: the buckets a relaxed cell needs are then the 21 of a 5x5 block
  // without its corners, and each holds few sites the cell does not need.
  static constexpr double kSitesPerBucket = 1.0;
  // Steps precomputed per grid (13 x 13 buckets); larger cells (rare: big empty regions, tiny N)
  // fall back to the ring search.
  static constexpr long kSearchRadius = 6;

  Domain domain_;
  long columns_ = 1, rows_ = 1;
  Point cell_size_;
  std::vector<std::uint32_t> start_;
  std::vector<Point> points_;
  std::vector<std::uint32_t> index_;
  std::vector<SearchStep> search_order_;
};

constexpr std::uint32_t kOwnCopy = std::numeric_limits<std::uint32_t>::max();

struct Vertex {
  Point p;
  std::uint32_t edge_site;  // site whose bisector carries the edge from this vertex to the next
};

// Builds one cell: clips a convex polygon (relative to the site) by bisectors.
class CellBuilder {
 public:
  CellBuilder() : polygon_(kInitialCapacity), scratch_(kInitialCapacity), side_(kInitialCapacity) {}

  void reset(Point half_size) {
    polygon_[0] = {{-half_size.x, -half_size.y}, kOwnCopy};
    polygon_[1] = {{half_size.x, -half_size.y}, kOwnCopy};
    polygon_[2] = {{half_size.x, half_size.y}, kOwnCopy};
    polygon_[3] = {{-half_size.x, half_size.y}, kOwnCopy};
    size_ = 4;
    max_radius_squared_ = half_size.x * half_size.x + half_size.y * half_size.y;
  }

  // Keeps the part of the cell closer to the site (origin) than to d: x.d <= |d|^2 / 2.
  void clip(Point d, std::uint32_t site) {
    const double dd = d.x * d.x + d.y * d.y;
    // Every vertex v has v.d <= |v||d| <= |d|^2/2 when |d|^2 >= 4 max|v|^2: nothing to cut.
    if (dd >= 4.0 * max_radius_squared_) return;
    const double c = 0.5 * dd;
    const std::size_t n = size_;
    const Vertex* in = polygon_.data();
    double* side = side_.data();
    bool any_outside = false;
    for (std::size_t i = 0; i < n; ++i) {
      side[i] = in[i].p.x * d.x + in[i].p.y * d.y - c;
      any_outside |= side[i] > 0.0;
    }
    if (!any_outside) return;
    // A convex polygon cut by a line gains at most one vertex.
    if (scratch_.size() < n + 1) grow(2 * (n + 1));
    in = polygon_.data();
    Vertex* out = scratch_.data();
    std::size_t m = 0;
    double radius_squared = 0.0;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      // Edge j -> i. A crossing strictly from one side to the other adds a vertex; a vertex
      // exactly on the line is kept as it is, so co-circular ties (lattices) add no duplicates.
      const double sj = side[j], si = side[i];
      if ((sj < 0.0 && si > 0.0) || (sj > 0.0 && si < 0.0)) {
        const double t = sj / (sj - si);
        const Point x = in[j].p + t * (in[i].p - in[j].p);
        out[m++] = {x, sj < 0.0 ? site : in[j].edge_site};
        radius_squared = std::max(radius_squared, x.x * x.x + x.y * x.y);
      }
      if (si <= 0.0) {
        out[m++] = in[i];
        radius_squared = std::max(radius_squared, in[i].p.x * in[i].p.x + in[i].p.y * in[i].p.y);
      }
    }
    polygon_.swap(scratch_);
    size_ = m;
    max_radius_squared_ = radius_squared;
  }

  double max_radius_squared() const { return max_radius_squared_; }
  std::span<const Vertex> polygon() const { return {polygon_.data(), size_}; }

  // Area, centroid offset and second moment about the origin (the site).
  void measure(double& area, Point& centroid, double& second_moment) const {
    double a2 = 0.0, cx = 0.0, cy = 0.0, ixx = 0.0, iyy = 0.0;
    for (std::size_t i = 0, j = size_ - 1; i < size_; j = i++) {
      Point p = polygon_[j].p, q = polygon_[i].p;
      double cross = p.x * q.y - q.x * p.y;
      a2 += cross;
      cx += (p.x + q.x) * cross;
      cy += (p.y + q.y) * cross;
      ixx += (p.x * p.x + p.x * q.x + q.x * q.x) * cross;
      iyy += (p.y * p.y + p.y * q.y + q.y * q.y) * cross;
    }
    area = 0.5 * a2;
    centroid = a2 > 0.0 ? Point{cx / (3.0 * a2), cy / (3.0 * a2)} : Point{0.0, 0.0};
    second_moment = (ixx + iyy) / 12.0;
  }

 private:
  // Cells rarely have more than a dozen vertices; the buffers grow for pathological ties.
  static constexpr std::size_t kInitialCapacity = 64;

  void grow(std::size_t capacity) {
    polygon_.resize(capacity);
    scratch_.resize(capacity);
    side_.resize(capacity);
  }

  // Vertices [0, size_) of polygon_ are the cell; scratch_ receives the next one.
  std::vector<Vertex> polygon_, scratch_;
  std::vector<double> side_;  // signed distance of each vertex to the clipping line
  std::size_t size_ = 0;
  double max_radius_squared_ = 0.0;
};

struct Candidate {
  double distance_squared;
  Point offset;
  std::uint32_t site;
};

// The fallback search: square rings of buckets around the site's bucket until the ring's inner
// distance reaches twice the cell radius. Returns false for a coincident site.
bool build_cell_by_rings(const Scene& scene, const PeriodicGrid& grid, std::uint32_t site, CellBuilder& builder,
                std::vector<Candidate>& candidates) {
  const Point origin = scene.sites[site];
  const Point cell = grid.cell_size();
  builder.reset(0.5 * scene.domain.size);
  auto [cx, cy] = grid.bucket_coordinates(origin);
  bool coincident = false;

  auto gather = [&](long bx, long by) {
    grid.for_each_in_bucket(bx, by, origin, [&](std::uint32_t other, Point d) {
      if (d.x == 0.0 && d.y == 0.0) {
        if (other < site) coincident = true;
        return;  // the site itself, or a copy of it at the same place
      }
      candidates.push_back({d.x * d.x + d.y * d.y, d, other});
    });
  };
  auto clip_nearest_first = [&] {
    // Insertion sort: a ring holds a few dozen candidates, and being stable it breaks distance
    // ties by gathering order, which is fixed, so the clipping order is the same every run.
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      Candidate c = candidates[i];
      std::size_t j = i;
      for (; j > 0 && candidates[j - 1].distance_squared > c.distance_squared; --j) candidates[j] = candidates[j - 1];
      candidates[j] = c;
    }
    for (const Candidate& c : candidates) builder.clip(c.offset, c.site);
    candidates.clear();
  };

  // Ring 0 and 1 together (the 3x3 block), then one ring at a time.
  candidates.clear();
  for (long dy = -1; dy <= 1; ++dy)
    for (long dx = -1; dx <= 1; ++dx) gather(cx + dx, cy + dy);
  if (coincident) return false;
  clip_nearest_first();

  for (long ring = 1;; ++ring) {
    // Every site not yet visited lies outside buckets [c - ring, c + ring] on both axes.
    double reach = std::min({origin.x - static_cast<double>(cx - ring) * cell.x,
                             static_cast<double>(cx + ring + 1) * cell.x - origin.x,
                             origin.y - static_cast<double>(cy - ring) * cell.y,
                             static_cast<double>(cy + ring + 1) * cell.y - origin.y});
    if (reach > 0.0 && reach * reach >= 4.0 * builder.max_radius_squared()) break;
    long next = ring + 1;
    for (long dx = -next; dx <= next; ++dx) {
      gather(cx + dx, cy - next);
      gather(cx + dx, cy + next);
    }
    for (long dy = -next + 1; dy <= next - 1; ++dy) {
      gather(cx - next, cy + dy);
      gather(cx + next, cy + dy);
    }
    if (coincident) return false;
    clip_nearest_first();
    // The initial rectangle bounds every cell, so the search ends by ring ~ 2 periods at most.
    assert(next <= 4 * (grid.columns() + grid.rows()) + 8);
  }
  return true;
}

// Computes the cell of `site` into `builder`. Returns false when the site coincides with a
// site of lower index (which owns the cell).
bool build_cell(const Scene& scene, const PeriodicGrid& grid, std::uint32_t site, CellBuilder& builder,
                std::vector<Candidate>& candidates) {
  const Point origin = scene.sites[site];
  const Point cell = grid.cell_size();
  builder.reset(0.5 * scene.domain.size);
  auto [cx, cy] = grid.bucket_coordinates(origin);
  // The site's place inside its bucket, for the exact distance to each bucket visited.
  const Point local{origin.x - static_cast<double>(cx) * cell.x, origin.y - static_cast<double>(cy) * cell.y};
  bool coincident = false;
  auto visit = [&](std::uint32_t other, Point d) {
    if (d.x == 0.0 && d.y == 0.0) {
      coincident |= other < site;
      return;  // the site itself, or a copy of it at the same place
    }
    builder.clip(d, other);
  };
  for (const auto& step : grid.search_order()) {
    const double reach_squared = 4.0 * builder.max_radius_squared();
    if (step.lower_bound_squared >= reach_squared) return !coincident;
    // The exact distance from the site to bucket (dx, dy) skips buckets the bound let through.
    const double gx = step.dx > 0   ? static_cast<double>(step.dx) * cell.x - local.x
                      : step.dx < 0 ? local.x - static_cast<double>(step.dx + 1) * cell.x
                                    : 0.0;
    const double gy = step.dy > 0   ? static_cast<double>(step.dy) * cell.y - local.y
                      : step.dy < 0 ? local.y - static_cast<double>(step.dy + 1) * cell.y
                                    : 0.0;
    if (gx * gx + gy * gy >= reach_squared) continue;
    grid.for_each_in_bucket(cx + step.dx, cy + step.dy, origin, visit);
    if (coincident) return false;
  }
  return build_cell_by_rings(scene, grid, site, builder, candidates);
}

Cell measure_cell(const Scene& scene, std::uint32_t site, bool coincident, const CellBuilder& builder) {
  Cell cell;
  const Point origin = scene.sites[site];
  if (coincident) {
    cell.centroid = origin;
    cell.status = CellStatus::coincident;
    return cell;
  }
  Point offset;
  builder.measure(cell.area, offset, cell.second_moment);
  cell.centroid = wrap_point(origin + offset, scene.domain);
  return cell;
}

void compute_scene(const Scene& scene, SceneCells& out, bool parallel_inside) {
  assert(scene.wanted_begin <= scene.wanted_end && scene.wanted_end <= scene.sites.size());
  out.cells.assign(scene.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  if (scene.wanted_count() == 0) return;
  PeriodicGrid grid(scene);

  auto run_buckets = [&](std::size_t begin, std::size_t end) {
    CellBuilder builder;
    std::vector<Candidate> candidates;
    candidates.reserve(64);
    for (std::size_t b = begin; b < end; ++b) {
      for (std::uint32_t site : grid.sites_in_bucket(b)) {
        if (site < scene.wanted_begin || site >= scene.wanted_end) continue;
        bool complete = build_cell(scene, grid, site, builder, candidates);
        out.cells[site - scene.wanted_begin] = measure_cell(scene, site, !complete, builder);
      }
    }
  };
  if (parallel_inside) {
    parallel_for(grid.bucket_count(), 256, run_buckets);
  } else {
    run_buckets(0, grid.bucket_count());
  }
  for (const Cell& c : out.cells) out.coincident_count += c.status == CellStatus::coincident;
}

}  // namespace

Scene make_scene(std::vector<Point> sites, Domain domain) {
  Scene scene;
  scene.domain = domain;
  scene.wanted_end = sites.size();
  scene.sites = std::move(sites);
  return scene;
}

void ExactEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  assert(scenes.size() == out.size());
  // The contract, checked once per scene; wrapped copies only of scenes that need them.
  std::vector<Scene> wrapped(scenes.size());
  std::vector<const Scene*> checked(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) checked[i] = &validated_scene(scenes[i], wrapped[i]);
  // Small scenes run one per thread when there are enough of them to keep every thread busy;
  // otherwise (one scene, or large ones) each scene is split across the threads itself.
  constexpr std::size_t kSmallScene = 4096;
  std::vector<std::size_t> small;
  for (std::size_t i = 0; i < scenes.size(); ++i)
    if (checked[i]->sites.size() <= kSmallScene) small.push_back(i);
  const bool across_scenes = small.size() >= 2 * thread_count();
  if (!across_scenes) small.clear();
  for (std::size_t i = 0, k = 0; i < scenes.size(); ++i) {
    if (k < small.size() && small[k] == i) {
      ++k;
    } else {
      compute_scene(*checked[i], out[i], true);
    }
  }
  parallel_for(small.size(), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) compute_scene(*checked[small[k]], out[small[k]], false);
  });
}

std::vector<Point> exact_cell_polygon(const Scene& given, std::size_t site) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  if (site >= scene.sites.size()) throw Error("exact_cell_polygon: no site " + std::to_string(site));
  PeriodicGrid grid(scene);
  CellBuilder builder;
  std::vector<Candidate> candidates;
  if (!build_cell(scene, grid, static_cast<std::uint32_t>(site), builder, candidates)) return {};
  std::vector<Point> polygon;
  for (const Vertex& v : builder.polygon()) polygon.push_back(v.p);
  return polygon;
}

std::vector<std::size_t> exact_cell_neighbours(const Scene& given, std::size_t site) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  if (site >= scene.sites.size()) throw Error("exact_cell_neighbours: no site " + std::to_string(site));
  PeriodicGrid grid(scene);
  CellBuilder builder;
  std::vector<Candidate> candidates;
  std::vector<std::size_t> neighbours;
  if (!build_cell(scene, grid, static_cast<std::uint32_t>(site), builder, candidates)) return neighbours;
  const auto& polygon = builder.polygon();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vertex& v = polygon[i];
    const Vertex& w = polygon[(i + 1) % polygon.size()];
    if (v.p == w.p) continue;  // degenerate edge left by a tie
    neighbours.push_back(v.edge_site == kOwnCopy ? site : v.edge_site);
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  return neighbours;
}

}  // namespace bluetile
