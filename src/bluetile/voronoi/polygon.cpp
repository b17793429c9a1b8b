// Convex polygons: see polygon.h.
#include "bluetile/voronoi/polygon.h"

namespace bluetile {

PolygonMoments polygon_moments(std::span<const Point> vertices) {
  PolygonMoments m;
  const std::size_t n = vertices.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) m.add_edge(vertices[j], vertices[i]);
  return m;
}

void ConvexPolygon::grow(std::size_t capacity) {
  vertices_.resize(capacity);
  scratch_.resize(capacity);
  side_.resize(capacity);
}

}  // namespace bluetile
