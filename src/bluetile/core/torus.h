// Periodic domain helpers. The domain is the rectangle [0,W) x [0,H) with opposite sides
// identified (the unit torus by default). All offsets between sites are taken on the torus,
// relative to a site, and wrapped into [-W/2, W/2) x [-H/2, H/2) before anything is summed
// (DESIGN section 7).
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>

#include <glm/vec2.hpp>

namespace bluetile {

using Point = glm::dvec2;

// The domain's boundary, for cells and for distances: periodic (opposite sides identified, the
// paper's setting: cells wrap around, distances are taken on the torus, sets tile), or bounded
// (the closed rectangle: cells are clipped by its border, distances are plain Euclidean ones,
// no periodic images; a set made in a bounded square).
enum class Boundary : std::uint8_t {
  periodic,
  bounded,
};

// A periodic rectangle [0, size.x) x [0, size.y).
struct Domain {
  Point size{1.0, 1.0};

  double area() const { return size.x * size.y; }
};

// Throws Error("<what>: domain 0 x 1 is not a finite positive size") unless both sides are finite
// and positive (a zero, negative or NaN side made NaN points, nonsense distances or endless
// searches).
void check_domain(const Domain& domain, std::string_view what);

// Throws Error("<what>: point 2 is not finite") for the first point with a NaN or infinite
// coordinate.
void check_finite_points(std::span<const Point> points, std::string_view what);

// x wrapped into [0, period). Exact for values already inside; never returns period itself
// (a value that would round up to period becomes 0).
inline double wrap_coordinate(double x, double period) {
  if (x >= 0.0 && x < period) return x;
  double w = x - period * std::floor(x / period);
  return w >= period ? 0.0 : w;
}

inline Point wrap_point(Point p, const Domain& domain) {
  return {wrap_coordinate(p.x, domain.size.x), wrap_coordinate(p.y, domain.size.y)};
}

// d wrapped into [-period/2, period/2): the shortest periodic offset along one axis.
inline double wrap_offset(double d, double period) {
  double half = 0.5 * period;
  if (d >= -half && d < half) return d;
  double w = d - period * std::floor(d / period + 0.5);
  return w >= half ? w - period : w;
}

// Shortest offset from a to b on the torus.
inline Point torus_offset(Point a, Point b, const Domain& domain) {
  return {wrap_offset(b.x - a.x, domain.size.x), wrap_offset(b.y - a.y, domain.size.y)};
}

inline double torus_distance_squared(Point a, Point b, const Domain& domain) {
  Point d = torus_offset(a, b, domain);
  return d.x * d.x + d.y * d.y;
}

inline double torus_distance(Point a, Point b, const Domain& domain) {
  return std::sqrt(torus_distance_squared(a, b, domain));
}

// Nearest-neighbour distance of N sites on a perfect hexagonal lattice filling `area`:
// sqrt(2 / (sqrt(3) N)) for the unit square. Used to express distances in lattice units.
inline double hexagonal_spacing(double count, double area = 1.0) {
  return std::sqrt(2.0 * area / (std::sqrt(3.0) * count));
}

}  // namespace bluetile
