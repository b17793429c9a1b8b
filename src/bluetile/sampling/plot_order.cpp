#include "bluetile/sampling/plot_order.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

double distance(Point a, Point b) { return std::hypot(a.x - b.x, a.y - b.y); }

// Square buckets over the dots' bounding box, about two dots each.
class DotGrid {
 public:
  explicit DotGrid(std::span<const Point> dots) : dots_(dots) {
    Point low = dots[0], high = dots[0];
    for (Point p : dots) {
      low = {std::min(low.x, p.x), std::min(low.y, p.y)};
      high = {std::max(high.x, p.x), std::max(high.y, p.y)};
    }
    low_ = low;
    const double extent = std::max({high.x - low.x, high.y - low.y, 1e-300});
    side_ = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(std::sqrt(static_cast<double>(dots.size()) / 2.0))));
    cell_ = extent / static_cast<double>(side_);
    buckets_.resize(static_cast<std::size_t>(side_ * side_));
    for (std::size_t i = 0; i < dots.size(); ++i) buckets_[bucket_of(dots[i])].push_back(static_cast<std::uint32_t>(i));
  }

  std::int64_t side() const { return side_; }
  double cell() const { return cell_; }
  std::int64_t column(double x) const { return std::clamp<std::int64_t>(static_cast<std::int64_t>((x - low_.x) / cell_), 0, side_ - 1); }
  std::int64_t row(double y) const { return std::clamp<std::int64_t>(static_cast<std::int64_t>((y - low_.y) / cell_), 0, side_ - 1); }
  std::size_t bucket_of(Point p) const { return static_cast<std::size_t>(row(p.y) * side_ + column(p.x)); }
  std::vector<std::uint32_t>& bucket(std::int64_t c, std::int64_t r) { return buckets_[static_cast<std::size_t>(r * side_ + c)]; }

  // Calls visit(bucket) for the buckets at Chebyshev distance `ring` from (c, r) inside the grid.
  template <typename Visit>
  void for_ring(std::int64_t c, std::int64_t r, std::int64_t ring, Visit visit) {
    for (std::int64_t dr = -ring; dr <= ring; ++dr) {
      const std::int64_t rr = r + dr;
      if (rr < 0 || rr >= side_) continue;
      const bool edge_row = dr == -ring || dr == ring;
      for (std::int64_t dc = -ring; dc <= ring; dc += edge_row ? 1 : 2 * std::max<std::int64_t>(ring, 1)) {
        const std::int64_t cc = c + dc;
        if (cc >= 0 && cc < side_) visit(bucket(cc, rr));
      }
    }
  }

 private:
  std::span<const Point> dots_;
  Point low_{};
  std::int64_t side_ = 1;
  double cell_ = 1.0;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

// A nearer candidate: by distance, ties by index, so the order never depends on search order.
bool nearer(double d, std::uint32_t i, double best_d, std::uint32_t best_i) {
  return d < best_d || (d == best_d && i < best_i);
}

std::vector<std::size_t> greedy_path(std::span<const Point> dots) {
  const std::size_t n = dots.size();
  DotGrid grid(dots);
  // Dots not yet drawn: in their buckets and in one list, each with its place in both.
  std::vector<std::uint32_t> remaining(n), place_in_remaining(n), place_in_bucket(n);
  for (std::size_t i = 0; i < n; ++i) remaining[i] = place_in_remaining[i] = static_cast<std::uint32_t>(i);
  for (std::int64_t r = 0; r < grid.side(); ++r)
    for (std::int64_t c = 0; c < grid.side(); ++c) {
      const auto& b = grid.bucket(c, r);
      for (std::size_t k = 0; k < b.size(); ++k) place_in_bucket[b[k]] = static_cast<std::uint32_t>(k);
    }
  auto take = [&](std::uint32_t i) {
    auto& b = grid.bucket(grid.column(dots[i].x), grid.row(dots[i].y));
    const std::uint32_t k = place_in_bucket[i];
    b[k] = b.back();
    place_in_bucket[b[k]] = k;
    b.pop_back();
    const std::uint32_t m = place_in_remaining[i];
    remaining[m] = remaining.back();
    place_in_remaining[remaining[m]] = m;
    remaining.pop_back();
  };

  // Start at the dot nearest the lower-left corner of the bounding box.
  std::uint32_t current = 0;
  Point low = dots[0];
  for (Point p : dots) low = {std::min(low.x, p.x), std::min(low.y, p.y)};
  for (std::uint32_t i = 1; i < n; ++i)
    if (nearer(distance(dots[i], low), i, distance(dots[current], low), current)) current = i;

  std::vector<std::size_t> path;
  path.reserve(n);
  path.push_back(current);
  take(current);
  while (!remaining.empty()) {
    const Point p = dots[current];
    const std::int64_t c = grid.column(p.x), r = grid.row(p.y);
    double best_d = std::numeric_limits<double>::infinity();
    std::uint32_t best = std::numeric_limits<std::uint32_t>::max();
    std::size_t scanned = 0;
    for (std::int64_t ring = 0;; ++ring) {
      // A dot beyond this ring is at least ring cells away: stop once the best is nearer.
      if (best_d <= static_cast<double>(ring - 1) * grid.cell() || ring > grid.side()) break;
      // Late in the path most buckets are empty: scanning the list of the remaining dots is then cheaper.
      scanned += static_cast<std::size_t>(8 * std::max<std::int64_t>(ring, 1));
      if (scanned > remaining.size()) {
        for (std::uint32_t i : remaining)
          if (nearer(distance(dots[i], p), i, best_d, best)) best_d = distance(dots[i], p), best = i;
        break;
      }
      grid.for_ring(c, r, ring, [&](const std::vector<std::uint32_t>& b) {
        for (std::uint32_t i : b)
          if (nearer(distance(dots[i], p), i, best_d, best)) best_d = distance(dots[i], p), best = i;
      });
    }
    current = best;
    path.push_back(current);
    take(current);
  }
  return path;
}

// The k nearest other dots of every dot, nearest first (ties by index).
std::vector<std::uint32_t> nearest_neighbours(std::span<const Point> dots, std::size_t k) {
  DotGrid grid(dots);
  std::vector<std::uint32_t> neighbours(dots.size() * k, std::numeric_limits<std::uint32_t>::max());
  std::vector<std::pair<double, std::uint32_t>> found;
  for (std::size_t i = 0; i < dots.size(); ++i) {
    const Point p = dots[i];
    const std::int64_t c = grid.column(p.x), r = grid.row(p.y);
    found.clear();
    for (std::int64_t ring = 0; ring <= grid.side(); ++ring) {
      if (found.size() >= k) {
        std::nth_element(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(k - 1), found.end());
        if (found[k - 1].first <= static_cast<double>(ring - 1) * grid.cell()) break;
      }
      grid.for_ring(c, r, ring, [&](const std::vector<std::uint32_t>& b) {
        for (std::uint32_t j : b)
          if (j != i) found.emplace_back(distance(dots[j], p), j);
      });
    }
    const std::size_t kept = std::min(k, found.size());
    std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(kept), found.end());
    for (std::size_t m = 0; m < kept; ++m) neighbours[i * k + m] = found[m].second;
  }
  return neighbours;
}

// 2-opt on an open path with neighbour lists: for the edge (a, b) at each place of the path and
// each near neighbour c of a, reversing the stretch between them replaces two edges by (a, c) and
// one more; taken when that is shorter. Stops when a pass finds nothing (or after kMaxPasses).
void two_opt(std::span<const Point> dots, std::vector<std::size_t>& path) {
  const std::size_t n = path.size();
  if (n < 4) return;
  constexpr std::size_t kNeighbours = 8;   // Johnson and McGeoch: 8-10 candidates give most of the gain
  constexpr int kMaxPasses = 50;           // a bound on the time; passes after the first few gain little
  const std::vector<std::uint32_t> neighbours = nearest_neighbours(dots, kNeighbours);
  std::vector<std::size_t> place(n);
  for (std::size_t i = 0; i < n; ++i) place[path[i]] = i;
  auto d = [&](std::size_t u, std::size_t v) { return distance(dots[u], dots[v]); };
  auto reverse = [&](std::size_t from, std::size_t to) {  // path[from..to], inclusive
    std::reverse(path.begin() + static_cast<std::ptrdiff_t>(from), path.begin() + static_cast<std::ptrdiff_t>(to) + 1);
    for (std::size_t i = from; i <= to; ++i) place[path[i]] = i;
  };
  const auto none = std::numeric_limits<std::uint32_t>::max();
  // Moves that join a to a near neighbour c, dropping a's edge to its successor b.
  auto join_after = [&](std::size_t i) {
    const std::size_t a = path[i], b = path[i + 1];
    const double ab = d(a, b);
    for (std::size_t m = 0; m < kNeighbours; ++m) {
      const std::uint32_t c = neighbours[a * kNeighbours + m];
      if (c == none) break;
      const double ac = d(a, c);
      if (ac >= ab) break;  // neighbours come nearest first: no later one can help either
      const std::size_t j = place[c];
      if (j > i + 1) {
        // a b ... c f  ->  a c ... b f: (a,b), (c,f) become (a,c), (b,f); no f at the end.
        const double gain = j + 1 < n ? ab + d(c, path[j + 1]) - ac - d(b, path[j + 1]) : ab - ac;
        if (gain > 1e-12 * ab) return reverse(i + 1, j), true;
      } else if (j + 1 < i) {
        // c e ... a b  ->  c a ... e b: (c,e), (a,b) become (c,a), (e,b).
        const std::size_t e = path[j + 1];
        if (d(c, e) + ab - ac - d(e, b) > 1e-12 * ab) return reverse(j + 1, i), true;
      }
    }
    return false;
  };
  // Moves that join a to a near neighbour c, dropping a's edge to its predecessor p.
  auto join_before = [&](std::size_t i) {
    const std::size_t a = path[i], p = path[i - 1];
    const double pa = d(p, a);
    for (std::size_t m = 0; m < kNeighbours; ++m) {
      const std::uint32_t c = neighbours[a * kNeighbours + m];
      if (c == none) break;
      const double ac = d(a, c);
      if (ac >= pa) break;
      const std::size_t j = place[c];
      if (j + 1 < i) {
        // e c ... p a  ->  e p ... c a: (e,c), (p,a) become (e,p), (c,a); no e at the start.
        const double gain = j > 0 ? d(path[j - 1], c) + pa - d(path[j - 1], p) - ac : pa - ac;
        if (gain > 1e-12 * pa) return reverse(j, i - 1), true;
      } else if (j > i + 1) {
        // p a ... g c  ->  p g ... a c: (p,a), (g,c) become (p,g), (a,c).
        const std::size_t g = path[j - 1];
        if (pa + d(g, c) - d(p, g) - ac > 1e-12 * pa) return reverse(i, j - 1), true;
      }
    }
    return false;
  };
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool improved = false;
    for (std::size_t i = 0; i < n; ++i) {
      if (i + 1 < n && join_after(i)) improved = true;
      else if (i > 0 && join_before(i)) improved = true;
    }
    if (!improved) break;
  }
}

}  // namespace

double path_length(std::span<const Point> dots, std::span<const std::size_t> order) {
  for (std::size_t i = 0; i < order.size(); ++i)
    if (order[i] >= dots.size())
      throw Error("order[" + std::to_string(i) + "] " + std::to_string(order[i]) + ": expected an index below " +
                  std::to_string(dots.size()) + ", the number of dots");
  double length = 0.0;
  for (std::size_t i = 1; i < order.size(); ++i) length += distance(dots[order[i - 1]], dots[order[i]]);
  return length;
}

PlotOrder plot_order(std::span<const Point> dots) {
  for (std::size_t i = 0; i < dots.size(); ++i)
    if (!std::isfinite(dots[i].x) || !std::isfinite(dots[i].y))
      throw Error("plot order: dot " + std::to_string(i) + " has a coordinate that is not a finite number");
  PlotOrder result;
  if (dots.empty()) return result;
  result.order = greedy_path(dots);
  result.greedy_travel = path_length(dots, result.order);
  two_opt(dots, result.order);
  result.travel = path_length(dots, result.order);
  return result;
}

}  // namespace bluetile
