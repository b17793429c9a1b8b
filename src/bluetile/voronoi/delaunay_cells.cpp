// Cells from the triangulation's circumcentres: see delaunay_cells.h.
#include "bluetile/voronoi/delaunay_cells.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

using Triangle = PeriodicDelaunay::Triangle;

// The correctly rounded offset `to - from` along one axis, `to` shifted by `periods` periods.
inline double axis_offset(double from, double to, int periods, double period) {
  if (periods == 0) return to - from;
  return detail::exact_difference(to, periods * period, from, 0.0).hi;
}

inline Point offset(Point from, Point to, int px, int py, Point period) {
  return {axis_offset(from.x, to.x, px, period.x), axis_offset(from.y, to.y, py, period.y)};
}

inline double norm_squared(Point p) { return p.x * p.x + p.y * p.y; }
inline double cross(Point p, Point q) { return p.x * q.y - p.y * q.x; }

// The triangle's three offsets: a = corner 0 to corner 1, corner 0 to corner 2, corner 1 to 2.
struct Offsets {
  Point ab, ac, bc;
};

inline Offsets offsets(const PeriodicDelaunay& triangulation, const Triangle& t) {
  const auto positions = triangulation.positions();
  const Point period = triangulation.domain().size;
  const Point a = positions[t.vertex[0]], b = positions[t.vertex[1]], c = positions[t.vertex[2]];
  if ((t.shift_x[1] | t.shift_x[2] | t.shift_y[1] | t.shift_y[2]) == 0) return {b - a, c - a, c - b};
  // Corner 0 is at shift 0.
  return {offset(a, b, t.shift_x[1], t.shift_y[1], period), offset(a, c, t.shift_x[2], t.shift_y[2], period),
          offset(b, c, t.shift_x[2] - t.shift_x[1], t.shift_y[2] - t.shift_y[1], period)};
}

// The circumcentre relative to the corner opposite the longest edge (ties: the lower site index),
// from the offsets to the next two corners; returns that corner.
inline int circumcentre(const Offsets& o, const Triangle& t, std::span<const std::uint32_t> sites, Point& centre) {
  const double opposite[3] = {norm_squared(o.bc), norm_squared(o.ac), norm_squared(o.ab)};
  int x = 0;
  for (int k = 1; k < 3; ++k)
    if (opposite[k] > opposite[x] || (opposite[k] == opposite[x] && sites[t.vertex[k]] < sites[t.vertex[x]])) x = k;
  // b and c: the offsets from corner x to the next two corners counter-clockwise.
  const Point b = x == 0 ? o.ab : x == 1 ? o.bc : -o.ac;
  const Point c = x == 0 ? o.ac : x == 1 ? -o.ab : -o.bc;
  const double bb = norm_squared(b), cc = norm_squared(c);
  const double d = 2.0 * cross(b, c);
  centre = {(c.y * bb - b.y * cc) / d, (b.x * cc - c.x * bb) / d};
  return x;
}

// The circumcentre relative to each corner: the canonical one plus the offset from the corner to
// the canonical corner (one of the triangle's offsets, exactly negated where needed).
inline void centres_by_corner(const Offsets& o, int x, Point centre, Point* out) {
  // Offsets from corner k to corner x: from_corner[k][x].
  const Point zero{0.0, 0.0};
  const Point to_x[3][3] = {{zero, o.ab, o.ac}, {-o.ab, zero, o.bc}, {-o.ac, -o.bc, zero}};
  for (int k = 0; k < 3; ++k) out[k] = k == x ? centre : centre + to_x[k][x];
}

// Whether no corner uses a shifted copy (corner 0 is always at shift 0).
inline bool unshifted(const Triangle& t) { return (t.shift_x[1] | t.shift_x[2] | t.shift_y[1] | t.shift_y[2]) == 0; }

double radius_limit_squared(const PeriodicDelaunay& triangulation) {
  const Point size = triangulation.domain().size;
  const double limit = 0.1 * std::min(size.x, size.y);
  return limit * limit;
}

}  // namespace

DelaunayCells::Sweep DelaunayCells::sweep(const PeriodicDelaunay& triangulation) {
  const auto triangles = triangulation.triangles();
  const auto positions = triangulation.positions();
  const auto sites = triangulation.sites();
  const Point period = triangulation.domain().size;
  const Point quarter = 0.25 * period;
  const double limit = radius_limit_squared(triangulation);
  centres_.resize(3 * triangles.size());
  constexpr std::size_t kGrain = 8192;
  const std::size_t chunks = (triangles.size() + kGrain - 1) / kGrain;
  std::vector<Sweep> found(chunks);
  parallel_for(chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t chunk = begin; chunk < end; ++chunk) {
      Sweep& mine = found[chunk];
      for (std::size_t ti = chunk * kGrain; ti < std::min(triangles.size(), (chunk + 1) * kGrain); ++ti) {
        const Triangle& t = triangles[ti];
        const auto tri = static_cast<std::uint32_t>(ti);
        const Offsets o = offsets(triangulation, t);
        auto short_edge = [&](Point d) { return std::abs(d.x) < quarter.x && std::abs(d.y) < quarter.y; };
        if (!short_edge(o.ab) || !short_edge(o.ac) || !short_edge(o.bc)) {
          mine.invalid.push_back(tri);
          continue;
        }
        // Orientation: the filter of predicates.h on the correctly rounded offsets.
        const double left = o.ab.x * o.ac.y, right = o.ab.y * o.ac.x;
        const double turn = left - right;
        if (!(turn > detail::kOrientationBound * (std::abs(left) + std::abs(right))) &&
            orientation(triangulation.corner_point(t, 0), triangulation.corner_point(t, 1), triangulation.corner_point(t, 2)) <= 0) {
          mine.invalid.push_back(tri);
          continue;
        }
        Point centre;
        const int x = circumcentre(o, t, sites, centre);
        centres_by_corner(o, x, centre, &centres_[3 * ti]);
        mine.area += 0.5 * turn;
        if (!(norm_squared(centre) < limit)) mine.oversized.push_back(tri);
        // The in-circle test of each edge this triangle owns: incircle(a, b, c, d) = -incircle(b,
        // c, d, a), the latter from the offsets to a (predicates.h's formula and bound).
        const double ab2 = norm_squared(o.ab), ac2 = norm_squared(o.ac);
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t l = t.neighbour[k];
          const std::uint32_t ui = PeriodicDelaunay::triangle_of(l);
          if (ui < tri) continue;
          const Triangle& u = triangles[ui];
          const int e = PeriodicDelaunay::edge_of(l);
          Point ad = positions[u.vertex[e]] - positions[t.vertex[0]];
          if (!unshifted(t) || !unshifted(u)) {
            const int next = PeriodicDelaunay::next(k), previous = PeriodicDelaunay::previous(e);
            const int sx = u.shift_x[e] + t.shift_x[next] - u.shift_x[previous];
            const int sy = u.shift_y[e] + t.shift_y[next] - u.shift_y[previous];
            ad = offset(positions[t.vertex[0]], positions[u.vertex[e]], sx, sy, period);
          }
          const double ad2 = norm_squared(ad);
          const double acad_l = o.ac.x * ad.y, acad_r = o.ac.y * ad.x;
          const double adab_l = ad.x * o.ab.y, adab_r = ad.y * o.ab.x;
          const double det = ab2 * (acad_l - acad_r) + ac2 * (adab_l - adab_r) + ad2 * turn;
          const double permanent = ab2 * (std::abs(acad_l) + std::abs(acad_r)) + ac2 * (std::abs(adab_l) + std::abs(adab_r)) +
                                   ad2 * (std::abs(left) + std::abs(right));
          const double bound = detail::kIncircleBound * permanent;
          if (det > bound) continue;  // d outside: the edge is Delaunay
          if (-det > bound) {
            mine.suspects.push_back(PeriodicDelaunay::link(tri, k));
            continue;
          }
          const PeriodicDelaunay::Test r = triangulation.test_edge(tri, k);
          if (r.perturbed > 0) {
            mine.suspects.push_back(PeriodicDelaunay::link(tri, k));
          } else if (r.exact == 0) {
            mine.ties.push_back(PeriodicDelaunay::link(tri, k));
          }
        }
      }
    }
  });
  Sweep all;
  for (const Sweep& f : found) {
    all.invalid.insert(all.invalid.end(), f.invalid.begin(), f.invalid.end());
    all.suspects.insert(all.suspects.end(), f.suspects.begin(), f.suspects.end());
    all.ties.insert(all.ties.end(), f.ties.begin(), f.ties.end());
    all.oversized.insert(all.oversized.end(), f.oversized.begin(), f.oversized.end());
    all.area += f.area;
  }
  return all;
}

void DelaunayCells::recompute(const PeriodicDelaunay& triangulation, std::span<const std::uint32_t> triangles,
                              std::vector<std::uint32_t>& oversized) {
  const auto all = triangulation.triangles();
  const double limit = radius_limit_squared(triangulation);
  for (std::uint32_t ti : triangles) {
    Point centre;
    const Offsets o = offsets(triangulation, all[ti]);
    const int x = circumcentre(o, all[ti], triangulation.sites(), centre);
    centres_by_corner(o, x, centre, &centres_[3 * ti]);
    if (!(norm_squared(centre) < limit)) oversized.push_back(ti);
  }
}

bool DelaunayCells::fits(const PeriodicDelaunay& triangulation, std::uint32_t triangle) const {
  // Every corner's view of the centre is within rounding of the circumradius; corner 0's decides.
  return norm_squared(centres_[3 * triangle]) < radius_limit_squared(triangulation);
}

bool DelaunayCells::measure(const PeriodicDelaunay& triangulation, std::uint32_t vertex, const Scene& scene, Point origin,
                            const Weighting& weighting, Cell& cell) const {
  const auto triangles = triangulation.triangles();
  const auto sites = triangulation.sites();
  const bool ties = triangulation.tie_edges() > 0;
  // The cell's vertices relative to the site (plain doubles: the compiler keeps them in
  // registers and buffers, where vector types went through the stack), and the site across the
  // edge after each.
  // Delaunay vertices rarely have more than 12 neighbours; 32 or more go to the search.
  constexpr std::size_t kLocal = 32;
  double x[kLocal], y[kLocal];
  std::size_t m = 0, first = 0;
  std::uint32_t lowest = 0;
  const std::uint32_t start = triangulation.corner_of(vertex);
  std::uint32_t corner = start;
  do {
    const std::uint32_t ti = PeriodicDelaunay::triangle_of(corner);
    const int j = PeriodicDelaunay::edge_of(corner);
    if ((ties && triangulation.ties(ti)) || m == kLocal) return false;
    const Triangle& t = triangles[ti];
    const Point v = centres_[3 * ti + static_cast<std::size_t>(j)];
    x[m] = v.x;
    y[m] = v.y;
    // The edge to the next triangle around is the one to the corner before this one.
    const std::uint32_t next_site = sites[t.vertex[PeriodicDelaunay::previous(j)]];
    if (m == 0 || next_site < lowest) {
      first = m;
      lowest = next_site;
    }
    ++m;
    const std::uint32_t across = t.neighbour[PeriodicDelaunay::next(j)];
    corner = PeriodicDelaunay::link(PeriodicDelaunay::triangle_of(across), PeriodicDelaunay::next(PeriodicDelaunay::edge_of(across)));
  } while (corner != start);
  // The sums from the edge after `first` around: edges first..m-1, then 0..first-1.
  PolygonMoments moments;
  double radius_squared = 0.0;
  auto add = [&](std::size_t k, std::size_t next) {
    moments.add_edge({x[k], y[k]}, {x[next], y[next]});
    radius_squared = std::max(radius_squared, x[k] * x[k] + y[k] * y[k]);
  };
  for (std::size_t k = first; k + 1 < m; ++k) add(k, k + 1);
  add(m - 1, 0);
  for (std::size_t k = 0; k < first; ++k) add(k, k + 1);
  if (!weighting.prefix && weighting.constant == 1.0) {
    // measure_moments without a density, inline.
    cell.area = moments.area();
    cell.mass = cell.area;
    cell.radius = std::sqrt(radius_squared);
    cell.second_moment = moments.second_moment();
    cell.status = CellStatus::ok;
    cell.centroid = scene_point(scene, origin + moments.centroid());
    return true;
  }
  std::vector<Point> polygon;
  if (weighting.prefix)
    for (std::size_t k = first; k < first + m; ++k) polygon.push_back({x[k < m ? k : k - m], y[k < m ? k : k - m]});
  cell = measure_moments(scene, origin, moments, radius_squared, polygon, weighting);
  return true;
}

}  // namespace bluetile
