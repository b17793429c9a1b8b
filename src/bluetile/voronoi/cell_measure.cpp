// Cells from polygons: see cell_measure.h.
#include "bluetile/voronoi/cell_measure.h"

#include <cmath>
#include <vector>

#include "bluetile/voronoi/density_prefix.h"

namespace bluetile {

Cell weigh_cell(const Scene& scene, Point origin, const Weighting& weighting, std::span<const Point> polygon, Cell cell,
                Point offset) {
  if (weighting.prefix) {
    const WeightedMoments m = weighting.prefix->moments(polygon, origin, scene.domain.size, scene.periodic(), scene.second_moments);
    cell.mass = m.mass;
    cell.second_moment = m.second;
    offset = m.mass > 0.0 ? m.first / m.mass : Point{0.0, 0.0};
  } else if (weighting.constant != 1.0) {
    cell.mass = weighting.constant * cell.area;
    cell.second_moment *= weighting.constant;
  }
  if (!(cell.mass > 0.0) && cell.area > 0.0) {
    // No density anywhere in the cell: nothing pulls the site, it stays.
    cell.mass = 0.0;
    cell.centroid = origin;
    cell.status = CellStatus::zero_density;
    return cell;
  }
  cell.centroid = scene_point(scene, origin + offset);
  return cell;
}

Cell measure_sums(const Scene& scene, Point origin, double area, Point centroid, double second_moment,
                  double radius_squared, std::span<const Point> polygon, const Weighting& weighting) {
  Cell cell;
  cell.area = area;
  cell.mass = area;
  cell.radius = std::sqrt(radius_squared);
  cell.second_moment = second_moment;
  return weigh_cell(scene, origin, weighting, polygon, cell, centroid);
}

Cell measure_moments(const Scene& scene, Point origin, const PolygonMoments& moments, double radius_squared,
                     std::span<const Point> polygon, const Weighting& weighting) {
  return measure_sums(scene, origin, moments.area(), moments.centroid(), moments.second_moment(), radius_squared, polygon,
                      weighting);
}

Cell measure_cell(const Scene& scene, Point origin, bool coincident, const ConvexPolygon& cell_polygon,
                  const Weighting& weighting) {
  if (coincident) {
    Cell cell;
    cell.centroid = origin;
    cell.status = CellStatus::coincident;
    return cell;
  }
  std::span<const Point> polygon;  // only the density's integration needs the vertices as points
  if (weighting.prefix) {
    thread_local std::vector<Point> vertices;
    vertices.clear();
    for (const PolygonVertex& v : cell_polygon.vertices()) vertices.push_back(v.p);
    polygon = vertices;
  }
  return measure_moments(scene, origin, cell_polygon.moments(), cell_polygon.max_radius_squared(), polygon, weighting);
}

}  // namespace bluetile
