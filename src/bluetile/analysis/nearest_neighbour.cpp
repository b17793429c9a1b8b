#include "bluetile/analysis/nearest_neighbour.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {

namespace {

// Outside the domain a point's bucket was clamped to the border, where the ring search did not
// look for it: periodic points are taken as their copy inside (the same torus distances), bounded
// ones are refused. Returns the points to measure: `given`, or `wrapped` filled with the copies.
const std::vector<Point>& points_inside(const std::vector<Point>& given, const Domain& domain, Boundary boundary,
                                        std::vector<Point>& wrapped) {
  for (std::size_t i = 0; i < given.size(); ++i) {
    const Point p = given[i];
    if (p.x >= 0.0 && p.x < domain.size.x && p.y >= 0.0 && p.y < domain.size.y) continue;
    if (boundary == Boundary::bounded)
      throw Error("nearest-neighbour distances: point " + std::to_string(i) + " (" + shortest_text(p.x) + ", " +
                  shortest_text(p.y) + ") lies outside the bounded domain " + shortest_text(domain.size.x) + " x " +
                  shortest_text(domain.size.y));
    wrapped.resize(given.size());
    for (std::size_t j = 0; j < given.size(); ++j) wrapped[j] = wrap_point(given[j], domain);
    return wrapped;
  }
  return given;
}

}  // namespace

std::vector<double> nearest_neighbour_distances(const std::vector<Point>& given, const Domain& domain,
                                                Boundary boundary) {
  const std::size_t n = given.size();
  if (n == 0) throw Error("nearest-neighbour distances need at least one point");
  const bool periodic = boundary == Boundary::periodic;
  if (!periodic && n < 2) throw Error("nearest-neighbour distances in a bounded domain need at least two points");
  // A NaN side made the ring search below endless; a zero or negative one gave nonsense distances.
  check_domain(domain, "nearest-neighbour distances");
  // A NaN would never be proved nearest: the ring search below would not end.
  check_finite_points(given, "nearest-neighbour distances");
  std::vector<Point> wrapped;
  const std::vector<Point>& points = points_inside(given, domain, boundary, wrapped);
  // Buckets of side >= the typical spacing; rings grow until the nearest found is provably nearest.
  double side = std::sqrt(2.0 * domain.area() / static_cast<double>(n));
  long columns = std::clamp<long>(static_cast<long>(domain.size.x / side), 1, 1 << 14);
  long rows = std::clamp<long>(static_cast<long>(domain.size.y / side), 1, 1 << 14);
  Point cell{domain.size.x / static_cast<double>(columns), domain.size.y / static_cast<double>(rows)};
  auto bucket_x = [&](double x) { return std::clamp<long>(static_cast<long>(x / cell.x), 0, columns - 1); };
  auto bucket_y = [&](double y) { return std::clamp<long>(static_cast<long>(y / cell.y), 0, rows - 1); };

  std::vector<std::uint32_t> start(static_cast<std::size_t>(columns * rows) + 1, 0), order(n);
  for (const Point& p : points) ++start[static_cast<std::size_t>(bucket_y(p.y) * columns + bucket_x(p.x)) + 1];
  for (std::size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::size_t i = 0; i < n; ++i)
    order[fill[static_cast<std::size_t>(bucket_y(points[i].y) * columns + bucket_x(points[i].x))]++] =
        static_cast<std::uint32_t>(i);

  std::vector<double> nearest(n);
  parallel_for(n, 1024, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const Point p = points[i];
      long cx = bucket_x(p.x), cy = bucket_y(p.y);
      double best = std::numeric_limits<double>::infinity();
      for (long ring = 0;; ++ring) {
        for (long dy = -ring; dy <= ring; ++dy) {
          for (long dx = -ring; dx <= ring; ++dx) {
            if (std::max(std::labs(dx), std::labs(dy)) != ring) continue;
            long bx = cx + dx, by = cy + dy;
            if (!periodic && (bx < 0 || by < 0 || bx >= columns || by >= rows)) continue;
            long wx = static_cast<long>(std::floor(static_cast<double>(bx) / static_cast<double>(columns)));
            long wy = static_cast<long>(std::floor(static_cast<double>(by) / static_cast<double>(rows)));
            std::size_t b = static_cast<std::size_t>((by - wy * rows) * columns + (bx - wx * columns));
            Point shift{static_cast<double>(wx) * domain.size.x, static_cast<double>(wy) * domain.size.y};
            for (std::uint32_t s = start[b]; s < start[b + 1]; ++s) {
              if (order[s] == i && wx == 0 && wy == 0) continue;
              Point d = points[order[s]] + shift - p;
              best = std::min(best, d.x * d.x + d.y * d.y);
            }
          }
        }
        // Unvisited points lie at least `reach` away.
        double reach = std::min({p.x - static_cast<double>(cx - ring) * cell.x,
                                 static_cast<double>(cx + ring + 1) * cell.x - p.x,
                                 p.y - static_cast<double>(cy - ring) * cell.y,
                                 static_cast<double>(cy + ring + 1) * cell.y - p.y});
        if (best <= reach * reach) break;
        if (!periodic && ring >= std::max(columns, rows)) break;  // every bucket visited
      }
      nearest[i] = std::sqrt(best);
    }
  });
  return nearest;
}

NearestNeighbourStats nearest_neighbour_stats(const std::vector<Point>& points, const Domain& domain,
                                              Boundary boundary) {
  std::vector<double> d = nearest_neighbour_distances(points, domain, boundary);
  NearestNeighbourStats stats;
  stats.count = d.size();
  stats.min = *std::min_element(d.begin(), d.end());
  stats.max = *std::max_element(d.begin(), d.end());
  double sum = 0.0;
  for (double v : d) sum += v;  // fixed order: same result whatever the thread count
  stats.mean = sum / static_cast<double>(d.size());
  stats.hexagonal_spacing = hexagonal_spacing(static_cast<double>(d.size()), domain.area());
  return stats;
}

}  // namespace bluetile
