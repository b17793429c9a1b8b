// Cells from the triangulation's circumcentres: see delaunay_cells.h.
#include "bluetile/voronoi/delaunay_cells.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/delaunay_sweep.h"

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

// A triangle's offsets between corners (corner 0 to 1, 0 to 2, 1 to 2) and their squared
// lengths, in plain doubles (vector types cost a third of the sweep's instructions).
struct Offsets {
  double abx, aby, acx, acy, bcx, bcy;
  double ab2, ac2, bc2;
};

inline Offsets offsets(const PeriodicDelaunay& triangulation, const Triangle& t) {
  const auto positions = triangulation.positions();
  const Point a = positions[t.vertex[0]], b = positions[t.vertex[1]], c = positions[t.vertex[2]];
  Offsets o;
  if ((t.shift_x[1] | t.shift_x[2] | t.shift_y[1] | t.shift_y[2]) == 0) {
    o.abx = b.x - a.x, o.aby = b.y - a.y, o.acx = c.x - a.x, o.acy = c.y - a.y, o.bcx = c.x - b.x, o.bcy = c.y - b.y;
  } else {
    // Corner 0 is at shift 0.
    const Point period = triangulation.domain().size;
    o.abx = axis_offset(a.x, b.x, t.shift_x[1], period.x);
    o.aby = axis_offset(a.y, b.y, t.shift_y[1], period.y);
    o.acx = axis_offset(a.x, c.x, t.shift_x[2], period.x);
    o.acy = axis_offset(a.y, c.y, t.shift_y[2], period.y);
    o.bcx = axis_offset(b.x, c.x, t.shift_x[2] - t.shift_x[1], period.x);
    o.bcy = axis_offset(b.y, c.y, t.shift_y[2] - t.shift_y[1], period.y);
  }
  o.ab2 = o.abx * o.abx + o.aby * o.aby;
  o.ac2 = o.acx * o.acx + o.acy * o.acy;
  o.bc2 = o.bcx * o.bcx + o.bcy * o.bcy;
  return o;
}

// The circumcentre relative to each corner (out[k]): computed relative to the corner opposite
// the longest edge (ties: the lower site index) from the offsets to the next two corners, then
// moved to the other corners by their offsets to it (exactly negated where needed). Returns its
// squared distance from that corner (the squared circumradius).
inline double circumcentres(const Offsets& o, const Triangle& t, std::span<const std::uint32_t> sites, Point* out) {
  const double opposite[3] = {o.bc2, o.ac2, o.ab2};
  int x = 0;
  for (int k = 1; k < 3; ++k)
    if (opposite[k] > opposite[x] || (opposite[k] == opposite[x] && sites[t.vertex[k]] < sites[t.vertex[x]])) x = k;
  // b and c: the offsets from corner x to the next two corners counter-clockwise.
  double bx, by, bb, cx, cy, cc;
  if (x == 0) {
    bx = o.abx, by = o.aby, bb = o.ab2, cx = o.acx, cy = o.acy, cc = o.ac2;
  } else if (x == 1) {
    bx = o.bcx, by = o.bcy, bb = o.bc2, cx = -o.abx, cy = -o.aby, cc = o.ab2;
  } else {
    bx = -o.acx, by = -o.acy, bb = o.ac2, cx = -o.bcx, cy = -o.bcy, cc = o.bc2;
  }
  const double d = 2.0 * (bx * cy - by * cx);
  const double px = (cy * bb - by * cc) / d, py = (bx * cc - cx * bb) / d;
  if (x == 0) {
    out[0] = {px, py}, out[1] = {px - o.abx, py - o.aby}, out[2] = {px - o.acx, py - o.acy};
  } else if (x == 1) {
    out[0] = {px + o.abx, py + o.aby}, out[1] = {px, py}, out[2] = {px - o.bcx, py - o.bcy};
  } else {
    out[0] = {px + o.acx, py + o.acy}, out[1] = {px + o.bcx, py + o.bcy}, out[2] = {px, py};
  }
  return px * px + py * py;
}

// A cell without a density from walk's sums: measure_sums without a density, inline.
inline void plain_cell(const Scene& scene, Point origin, double cross, double sx, double sy, double second,
                       double radius_squared, Cell& cell) {
  const double area = 0.5 * cross;
  const Point centroid = cross > 0.0 ? Point{sx / (3.0 * cross), sy / (3.0 * cross)} : Point{0.0, 0.0};
  cell.area = area;
  cell.mass = area;
  cell.radius = std::sqrt(radius_squared);
  cell.second_moment = second / 12.0;
  cell.status = CellStatus::ok;
  cell.centroid = wrap_point(origin + centroid, scene.domain);
}

// Whether no corner uses a shifted copy (corner 0 is always at shift 0).
inline bool unshifted(const Triangle& t) { return (t.shift_x[1] | t.shift_x[2] | t.shift_y[1] | t.shift_y[2]) == 0; }

double radius_limit_squared(const PeriodicDelaunay& triangulation) {
  const Point size = triangulation.domain().size;
  const double limit = 0.1 * std::min(size.x, size.y);
  return limit * limit;
}

}  // namespace

namespace detail {

void settle_edge(const PeriodicDelaunay& triangulation, std::uint32_t triangle, int edge, DelaunayCells::Sweep& found) {
  const PeriodicDelaunay::Test r = triangulation.test_edge(triangle, edge);
  if (r.perturbed > 0) {
    found.suspects.push_back(PeriodicDelaunay::link(triangle, edge));
  } else if (r.exact == 0) {
    found.ties.push_back(PeriodicDelaunay::link(triangle, edge));
  }
}

namespace {

// The in-circle test of edge k, which t owns, from t's offsets and orientation products:
// incircle(a, b, c, d) = -incircle(b, c, d, a), the latter from the offsets to a (predicates.h's
// formula and bound).
inline void owned_edge(const SweepFrame& frame, const Triangle& t, std::uint32_t tri, int k, const Offsets& o,
                       double left, double right, double turn, DelaunayCells::Sweep& found) {
  const PeriodicDelaunay& triangulation = frame.triangulation;
  const auto positions = triangulation.positions();
  const std::uint32_t l = t.neighbour[k];
  const Triangle& u = triangulation.triangles()[PeriodicDelaunay::triangle_of(l)];
  const int e = PeriodicDelaunay::edge_of(l);
  const Point a = positions[t.vertex[0]], d = positions[u.vertex[e]];
  double adx = d.x - a.x, ady = d.y - a.y;
  if (!unshifted(t) || !unshifted(u)) {
    const Point period = triangulation.domain().size;
    const int next = PeriodicDelaunay::next(k), previous = PeriodicDelaunay::previous(e);
    adx = axis_offset(a.x, d.x, u.shift_x[e] + t.shift_x[next] - u.shift_x[previous], period.x);
    ady = axis_offset(a.y, d.y, u.shift_y[e] + t.shift_y[next] - u.shift_y[previous], period.y);
  }
  const double ad2 = adx * adx + ady * ady;
  const double acad_l = o.acx * ady, acad_r = o.acy * adx;
  const double adab_l = adx * o.aby, adab_r = ady * o.abx;
  const double det = o.ab2 * (acad_l - acad_r) + o.ac2 * (adab_l - adab_r) + ad2 * turn;
  const double permanent = o.ab2 * (std::abs(acad_l) + std::abs(acad_r)) +
                           o.ac2 * (std::abs(adab_l) + std::abs(adab_r)) + ad2 * (std::abs(left) + std::abs(right));
  const double bound = detail::kIncircleBound * permanent;
  if (det > bound) return;  // d outside: the edge is Delaunay
  if (-det > bound) {
    found.suspects.push_back(PeriodicDelaunay::link(tri, k));
    return;
  }
  settle_edge(triangulation, tri, k, found);
}

}  // namespace

void sweep_triangle(const SweepFrame& frame, std::uint32_t tri, DelaunayCells::Sweep& found) {
  const PeriodicDelaunay& triangulation = frame.triangulation;
  const auto triangles = triangulation.triangles();
  const Triangle& t = triangles[tri];
  const Offsets o = offsets(triangulation, t);
  // A corner's copy more than a quarter period away breaks the predicates' precondition (the
  // shifts of a copy cancel exactly only within half a period). Offsets between unshifted corners
  // are plain differences, correctly rounded at any length; a long edge there is caught by the
  // circumradius limit of the result.
  auto short_edge = [&](double dx, double dy) { return std::abs(dx) < frame.quarter.x && std::abs(dy) < frame.quarter.y; };
  if (!unshifted(t) && (!short_edge(o.abx, o.aby) || !short_edge(o.acx, o.acy) || !short_edge(o.bcx, o.bcy))) {
    found.invalid.push_back(tri);
    return;
  }
  // Orientation: the filter of predicates.h on the correctly rounded offsets.
  const double left = o.abx * o.acy, right = o.aby * o.acx;
  const double turn = left - right;
  if (!(turn > detail::kOrientationBound * (std::abs(left) + std::abs(right))) &&
      orientation(triangulation.corner_point(t, 0), triangulation.corner_point(t, 1), triangulation.corner_point(t, 2)) <=
          0) {
    found.invalid.push_back(tri);
    return;
  }
  const double radius_squared = circumcentres(o, t, triangulation.sites(), &frame.centres[3 * std::size_t{tri}]);
  found.area += 0.5 * turn;
  if (!(radius_squared < frame.limit)) found.oversized.push_back(tri);
  // Each edge once, from the triangle of lower index.
  for (int k = 0; k < 3; ++k)
    if (PeriodicDelaunay::triangle_of(t.neighbour[k]) >= tri) owned_edge(frame, t, tri, k, o, left, right, turn, found);
}

void sweep_edge(const SweepFrame& frame, std::uint32_t tri, int k, DelaunayCells::Sweep& found) {
  const Triangle& t = frame.triangulation.triangles()[tri];
  const Offsets o = offsets(frame.triangulation, t);
  const double left = o.abx * o.acy, right = o.aby * o.acx;
  owned_edge(frame, t, tri, k, o, left, right, left - right, found);
}

}  // namespace detail

DelaunayCells::Sweep DelaunayCells::sweep(const PeriodicDelaunay& triangulation, bool lanes) {
  const auto triangles = triangulation.triangles();
  centres_.resize(3 * triangles.size());
  const detail::SweepFrame frame{triangulation, centres_.data(), 0.25 * triangulation.domain().size,
                                 radius_limit_squared(triangulation)};
  lanes = lanes && detail::sweep_lanes_available();
  // Chunks of triangles: about forty at 10^4 sites, so that the thread that finishes first waits
  // for a small last chunk (2048 gave ten, and a two-thread call 2-4% slower).
  constexpr std::size_t kGrain = 512;
  const std::size_t chunks = (triangles.size() + kGrain - 1) / kGrain;
  std::vector<Sweep> found(chunks);
  parallel_for(chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t chunk = begin; chunk < end; ++chunk) {
      const std::size_t first = chunk * kGrain, last = std::min(triangles.size(), (chunk + 1) * kGrain);
      if (lanes) {
        detail::sweep_lanes(frame, first, last, found[chunk]);
      } else {
        for (std::size_t ti = first; ti < last; ++ti) detail::sweep_triangle(frame, static_cast<std::uint32_t>(ti), found[chunk]);
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
  // In chunks on all threads (a random start flips about a tenth of the triangles), the
  // oversized ones in list order.
  constexpr std::size_t kGrain = 2048;
  const std::size_t chunks = (triangles.size() + kGrain - 1) / kGrain;
  std::vector<std::vector<std::uint32_t>> found(chunks);
  auto run = [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      for (std::uint32_t ti : triangles.subspan(c * kGrain, std::min(kGrain, triangles.size() - c * kGrain))) {
        const double radius_squared =
            circumcentres(offsets(triangulation, all[ti]), all[ti], triangulation.sites(), &centres_[3 * ti]);
        if (!(radius_squared < limit)) found[c].push_back(ti);
      }
    }
  };
  parallel_for(chunks, 1, run);  // one chunk runs on the calling thread
  for (const auto& f : found) oversized.insert(oversized.end(), f.begin(), f.end());
}

bool DelaunayCells::fits(const PeriodicDelaunay& triangulation, std::uint32_t triangle) const {
  // Every corner's view of the centre is within rounding of the circumradius; the canonical
  // corner's decides.
  const auto t = triangulation.triangles()[triangle];
  Point centres[3];
  return circumcentres(offsets(triangulation, t), t, triangulation.sites(), centres) < radius_limit_squared(triangulation);
}

bool DelaunayCells::measure(const PeriodicDelaunay& triangulation, std::uint32_t vertex, const Scene& scene, Point origin,
                            const Weighting& weighting, Cell& cell) const {
  // A density map weighs the polygon itself (its second moment comes from the map's tables).
  if (weighting.prefix) return walk<true, true>(triangulation, vertex, scene, origin, weighting, cell);
  if (scene.second_moments) return walk<true, false>(triangulation, vertex, scene, origin, weighting, cell);
  return walk<false, false>(triangulation, vertex, scene, origin, weighting, cell);
}

int DelaunayCells::measure_four(const PeriodicDelaunay& triangulation, const std::uint32_t* vertices, const Scene& scene,
                                const Point* origins, const Weighting& weighting, Cell* const* cells, bool lanes) const {
  int measured = 0;
  if (lanes && !weighting.prefix && weighting.constant == 1.0 && triangulation.tie_edges() == 0 &&
      detail::sweep_lanes_available()) {
    detail::WalkSums s;
    detail::walk_lanes(triangulation, centres_.data(), vertices, scene.second_moments, s);
    for (int j = 0; j < 4; ++j)
      plain_cell(scene, origins[j], s.cross[j], s.sx[j], s.sy[j], s.second[j], s.radius_squared[j], *cells[j]);
    return 0xf;
  }
  for (int j = 0; j < 4; ++j)
    measured |= static_cast<int>(measure(triangulation, vertices[j], scene, origins[j], weighting, *cells[j])) << j;
  return measured;
}

template <bool kSecond, bool kPolygon>
bool DelaunayCells::walk(const PeriodicDelaunay& triangulation, std::uint32_t vertex, const Scene& scene, Point origin,
                         const Weighting& weighting, Cell& cell) const {
  const bool ties = triangulation.tie_edges() > 0;
  // The shoelace sums over the cell's edges (p, q), counter-clockwise from its canonical corner
  // (the vertex's corner_of: after the edge to its neighbour of lowest site index): c = p x q
  // (twice the area), (p + q) c (six times the first moment) and (|p|^2 + p.q + |q|^2) c (twelve
  // times the second moment about the site: polygon.h's xx + yy in one sum). Plain doubles: the
  // compiler keeps them in registers, where vector types went through the stack.
  double cross = 0.0, sx = 0.0, sy = 0.0, second = 0.0, radius_squared = 0.0;
  auto centre = [&](std::uint32_t corner) {
    return centres_[3 * PeriodicDelaunay::triangle_of(corner) + static_cast<std::size_t>(PeriodicDelaunay::edge_of(corner))];
  };
  const std::uint32_t start = triangulation.corner_of(vertex);
  if (ties && triangulation.ties(PeriodicDelaunay::triangle_of(start))) return false;
  const Point first = centre(start);
  double px = first.x, py = first.y, pr = px * px + py * py;
  const double first_r = pr;
  std::uint32_t corner = start;
  // With a density the vertices themselves are needed, in order: in a per-thread buffer that
  // keeps its capacity, not a vector allocated for every cell. Without, the loop calls nothing
  // and its sums stay in registers (a possible allocation in it kept them on the stack).
  std::vector<Point>* polygon = nullptr;
  if constexpr (kPolygon) {
    thread_local std::vector<Point> vertices;
    polygon = &vertices;
    polygon->clear();
    polygon->push_back(first);
  }
  for (;;) {
    corner = triangulation.next_around(corner);
    double qx = first.x, qy = first.y, qr = first_r;
    const bool closed = corner == start;
    if (!closed) {
      if (ties && triangulation.ties(PeriodicDelaunay::triangle_of(corner))) return false;
      const Point q = centre(corner);
      qx = q.x, qy = q.y, qr = qx * qx + qy * qy;
      if constexpr (kPolygon) polygon->push_back(q);
    }
    const double c = px * qy - qx * py;
    cross += c;
    sx += (px + qx) * c;
    sy += (py + qy) * c;
    if constexpr (kSecond) second += (pr + (px * qx + py * qy) + qr) * c;
    radius_squared = std::max(radius_squared, pr);
    if (closed) break;
    px = qx, py = qy, pr = qr;
  }
  if (!kPolygon && weighting.constant == 1.0) {
    plain_cell(scene, origin, cross, sx, sy, second, radius_squared, cell);
    return true;
  }
  const double area = 0.5 * cross;
  const Point centroid = cross > 0.0 ? Point{sx / (3.0 * cross), sy / (3.0 * cross)} : Point{0.0, 0.0};
  std::span<const Point> vertices;
  if constexpr (kPolygon) vertices = *polygon;
  cell = measure_sums(scene, origin, area, centroid, second / 12.0, radius_squared, vertices, weighting);
  return true;
}

}  // namespace bluetile
