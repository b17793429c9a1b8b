// Exact periodic Voronoi cells by half-plane clipping (see exact_engine.h for the method).
#include "voronoi/exact_engine.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>

#include "core/parallel.h"

namespace bluetile {
namespace {

// Sites bucketed on a uniform grid over the domain, stored contiguously in bucket order.
class PeriodicGrid {
 public:
  explicit PeriodicGrid(const Scene& scene) : domain_(scene.domain) {
    const std::size_t n = scene.sites.size();
    // About two sites per bucket: rings then hold few sites, and ring 1 usually completes a cell.
    double bucket_side = std::sqrt(2.0 * domain_.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
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
  }

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
    long wx = floor_div(cx, columns_), wy = floor_div(cy, rows_);
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
  static long floor_div(long a, long b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

  Domain domain_;
  long columns_ = 1, rows_ = 1;
  Point cell_size_;
  std::vector<std::uint32_t> start_;
  std::vector<Point> points_;
  std::vector<std::uint32_t> index_;
};

constexpr std::uint32_t kOwnCopy = std::numeric_limits<std::uint32_t>::max();

struct Vertex {
  Point p;
  std::uint32_t edge_site;  // site whose bisector carries the edge from this vertex to the next
};

// Builds one cell: clips a convex polygon (relative to the site) by bisectors.
class CellBuilder {
 public:
  void reset(Point half_size) {
    polygon_.clear();
    polygon_.push_back({{-half_size.x, -half_size.y}, kOwnCopy});
    polygon_.push_back({{half_size.x, -half_size.y}, kOwnCopy});
    polygon_.push_back({{half_size.x, half_size.y}, kOwnCopy});
    polygon_.push_back({{-half_size.x, half_size.y}, kOwnCopy});
    max_radius_squared_ = half_size.x * half_size.x + half_size.y * half_size.y;
  }

  // Keeps the part of the cell closer to the site (origin) than to d: x.d <= |d|^2 / 2.
  void clip(Point d, std::uint32_t site) {
    double dd = d.x * d.x + d.y * d.y;
    // Every vertex v has v.d <= |v||d| <= |d|^2/2 when |d|^2 >= 4 max|v|^2: nothing to cut.
    if (dd >= 4.0 * max_radius_squared_) return;
    const double c = 0.5 * dd;
    const std::size_t n = polygon_.size();
    side_.resize(n);
    bool any_outside = false;
    for (std::size_t i = 0; i < n; ++i) {
      side_[i] = polygon_[i].p.x * d.x + polygon_[i].p.y * d.y - c;
      any_outside |= side_[i] > 0.0;
    }
    if (!any_outside) return;
    scratch_.clear();
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      // Edge j -> i. A crossing strictly from one side to the other adds a vertex; a vertex
      // exactly on the line is kept as it is, so co-circular ties (lattices) add no duplicates.
      const double sj = side_[j], si = side_[i];
      if ((sj < 0.0 && si > 0.0) || (sj > 0.0 && si < 0.0)) {
        const Vertex& a = polygon_[j];
        const Vertex& b = polygon_[i];
        double t = sj / (sj - si);
        scratch_.push_back({a.p + t * (b.p - a.p), sj < 0.0 ? site : a.edge_site});
      }
      if (si <= 0.0) scratch_.push_back(polygon_[i]);
    }
    polygon_.swap(scratch_);
    max_radius_squared_ = 0.0;
    for (const Vertex& v : polygon_) max_radius_squared_ = std::max(max_radius_squared_, v.p.x * v.p.x + v.p.y * v.p.y);
  }

  double max_radius_squared() const { return max_radius_squared_; }
  const std::vector<Vertex>& polygon() const { return polygon_; }

  // Area, centroid offset and second moment about the origin (the site).
  void measure(double& area, Point& centroid, double& second_moment) const {
    double a2 = 0.0, cx = 0.0, cy = 0.0, ixx = 0.0, iyy = 0.0;
    std::size_t n = polygon_.size();
    for (std::size_t i = 0; i < n; ++i) {
      Point p = polygon_[i].p, q = polygon_[(i + 1) % n].p;
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
  std::vector<Vertex> polygon_, scratch_;
  std::vector<double> side_;  // signed distance of each vertex to the clipping line
  double max_radius_squared_ = 0.0;
};

struct Candidate {
  double distance_squared;
  Point offset;
  std::uint32_t site;
};

// Computes the cell of `site` into `builder`. Returns false when the site coincides with a
// site of lower index (which owns the cell).
bool build_cell(const Scene& scene, const PeriodicGrid& grid, std::uint32_t site, CellBuilder& builder,
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
  // Small scenes run one per thread; large ones are split across threads themselves.
  constexpr std::size_t kSmallScene = 4096;
  std::vector<std::size_t> small;
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    if (scenes[i].sites.size() <= kSmallScene) {
      small.push_back(i);
    } else {
      compute_scene(scenes[i], out[i], true);
    }
  }
  parallel_for(small.size(), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) compute_scene(scenes[small[k]], out[small[k]], false);
  });
}

std::vector<Point> exact_cell_polygon(const Scene& scene, std::size_t site) {
  PeriodicGrid grid(scene);
  CellBuilder builder;
  std::vector<Candidate> candidates;
  if (!build_cell(scene, grid, static_cast<std::uint32_t>(site), builder, candidates)) return {};
  std::vector<Point> polygon;
  for (const Vertex& v : builder.polygon()) polygon.push_back(v.p);
  return polygon;
}

std::vector<std::size_t> exact_cell_neighbours(const Scene& scene, std::size_t site) {
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
