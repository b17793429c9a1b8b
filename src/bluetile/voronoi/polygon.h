// Convex polygons for the centroid engines: clipping by half-planes (the bisector between a
// site and another one is the common case) and the moments Lloyd needs: area, first moment
// (for the centroid) and second moment (the cell's energy). Coordinates are relative to a
// site, so precision does not depend on where the site lies (DESIGN section 7).
//
// Moments by the shoelace formulas: for a polygon with edges (p, q) and c = p x q,
//   area   = sum c / 2
//   int x  = sum (p + q) c / 6
//   int |x|^2 = sum (p.x^2 + p.x q.x + q.x^2 + p.y^2 + p.y q.y + q.y^2) c / 12.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// The shoelace sums of a polygon, from which its moments follow. Kept as sums so that every
// user derives area, centroid and moments with the same roundings.
struct PolygonMoments {
  double cross = 0.0;  // sum of p x q: twice the signed area
  double x = 0.0, y = 0.0;  // sums of (p + q) (p x q): six times the first moment
  double xx = 0.0, yy = 0.0;  // sums of (p.x^2 + p.x q.x + q.x^2) (p x q), same for y: twelve times

  void add_edge(Point p, Point q) {
    const double c = p.x * q.y - q.x * p.y;
    cross += c;
    x += (p.x + q.x) * c;
    y += (p.y + q.y) * c;
    xx += (p.x * p.x + p.x * q.x + q.x * q.x) * c;
    yy += (p.y * p.y + p.y * q.y + q.y * q.y) * c;
  }

  double area() const { return 0.5 * cross; }
  // Integral of x over the polygon.
  Point first_moment() const { return {x / 6.0, y / 6.0}; }
  // The centre of mass; the origin for a polygon without area.
  Point centroid() const { return cross > 0.0 ? Point{x / (3.0 * cross), y / (3.0 * cross)} : Point{0.0, 0.0}; }
  // Integral of |x|^2 over the polygon (about the origin).
  double second_moment() const { return (xx + yy) / 12.0; }
};

// Moments of the polygon with vertices `vertices` in counter-clockwise order.
PolygonMoments polygon_moments(std::span<const Point> vertices);

// A vertex of a ConvexPolygon: its position and the label of the edge from it to the next
// vertex (the site whose bisector carries that edge, or kUnlabelled).
struct PolygonVertex {
  Point p;
  std::uint32_t edge_label;
};

inline constexpr std::uint32_t kUnlabelled = 0xffffffffu;

// A convex polygon, counter-clockwise, that is cut down by half-planes. Buffers are kept
// between uses, so clipping allocates nothing once they have grown.
class ConvexPolygon {
 public:
  ConvexPolygon() : vertices_(kInitialCapacity), scratch_(kInitialCapacity), side_(kInitialCapacity) {}

  // The rectangle [lo, hi], all edges labelled `label`.
  void reset_rectangle(Point lo, Point hi, std::uint32_t label = kUnlabelled) {
    vertices_[0] = {{lo.x, lo.y}, label};
    vertices_[1] = {{hi.x, lo.y}, label};
    vertices_[2] = {{hi.x, hi.y}, label};
    vertices_[3] = {{lo.x, hi.y}, label};
    size_ = 4;
    max_radius_squared_ = 0.0;
    for (std::size_t i = 0; i < 4; ++i) max_radius_squared_ = std::max(max_radius_squared_, norm_squared(vertices_[i].p));
  }

  // Keeps the part closer to the origin than to d: x.d <= |d|^2 / 2. The new edge is labelled
  // `label`. Does nothing when the bisector cannot reach the polygon.
  void clip_by_bisector(Point d, std::uint32_t label) {
    const double dd = d.x * d.x + d.y * d.y;
    // Every vertex v has v.d <= |v||d| <= |d|^2/2 when |d|^2 >= 4 max|v|^2: nothing to cut.
    if (dd >= 4.0 * max_radius_squared_) return;
    clip(d, 0.5 * dd, label);
  }

  // Keeps the part with x.normal <= offset; the new edge is labelled `label`.
  void clip(Point normal, double offset, std::uint32_t label) {
    const std::size_t n = size_;
    const PolygonVertex* in = vertices_.data();
    double* side = side_.data();
    bool any_outside = false;
    for (std::size_t i = 0; i < n; ++i) {
      side[i] = in[i].p.x * normal.x + in[i].p.y * normal.y - offset;
      any_outside |= side[i] > 0.0;
    }
    if (!any_outside) return;
    // A convex polygon cut by a line gains at most one vertex, but rounding can give vertices
    // near the line alternating sides, and each vertex then adds a crossing as well as itself
    // (a clip by nearly coincident bisectors gains two vertices in about 1 of 8000 such clips).
    if (scratch_.size() < 2 * n) {
      grow(2 * n);  // moves every buffer: the pointers into them are taken again
      in = vertices_.data();
      side = side_.data();
    }
    PolygonVertex* out = scratch_.data();
    std::size_t m = 0;
    double radius_squared = 0.0;
    for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
      // Edge j -> i. A crossing strictly from one side to the other adds a vertex; a vertex
      // exactly on the line is kept as it is, so co-circular ties (lattices) add no duplicates.
      const double sj = side[j], si = side[i];
      if ((sj < 0.0 && si > 0.0) || (sj > 0.0 && si < 0.0)) {
        const double t = sj / (sj - si);
        const Point x = in[j].p + t * (in[i].p - in[j].p);
        out[m++] = {x, sj < 0.0 ? label : in[j].edge_label};
        radius_squared = std::max(radius_squared, norm_squared(x));
      }
      if (si <= 0.0) {
        out[m++] = in[i];
        radius_squared = std::max(radius_squared, norm_squared(in[i].p));
      }
    }
    vertices_.swap(scratch_);
    size_ = m;
    max_radius_squared_ = radius_squared;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ < 3; }
  std::span<const PolygonVertex> vertices() const { return {vertices_.data(), size_}; }
  // The largest squared distance of a vertex from the origin.
  double max_radius_squared() const { return max_radius_squared_; }

  PolygonMoments moments() const {
    PolygonMoments m;
    for (std::size_t i = 0, j = size_ - 1; i < size_; j = i++) m.add_edge(vertices_[j].p, vertices_[i].p);
    return m;
  }

 private:
  // Cells rarely have more than a dozen vertices; the buffers grow for pathological ties.
  static constexpr std::size_t kInitialCapacity = 64;

  static double norm_squared(Point p) { return p.x * p.x + p.y * p.y; }
  void grow(std::size_t capacity);

  // Vertices [0, size_) of vertices_ are the polygon; scratch_ receives the next one.
  std::vector<PolygonVertex> vertices_, scratch_;
  std::vector<double> side_;  // signed distance of each vertex to the clipping line
  std::size_t size_ = 0;
  double max_radius_squared_ = 0.0;
};

}  // namespace bluetile
