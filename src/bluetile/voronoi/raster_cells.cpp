// Assembling raster cells (see raster_cells.h).
#include "bluetile/voronoi/raster_cells.h"

#include <cmath>

#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/raster_coverage.h"

namespace bluetile {

void assemble_cells(const RasterScene& scene, std::span<const gpu::SiteSums> sums, std::span<const PieceSums> host_pieces,
                    SceneCells& out) {
  const Scene& s = *scene.scene;
  out.cells.assign(s.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  const double hx = scene.hx, hy = scene.hy;
  const double pixel_area = hx * hy;
  // Whole pixels are centred half a pixel above-right of their lower corner sample; point
  // coverage's pixels are centred on their sample.
  const double centre = scene.area ? 0.5 : 0.0;
  const double reach = scene.area ? scene.pixel_diagonal() : 0.5 * scene.pixel_diagonal();
  for (std::size_t i = s.wanted_begin; i < s.wanted_end; ++i) {
    Cell& cell = out.cells[i - s.wanted_begin];
    const Point site = scene.sites[i];
    if (scene.coincident[i]) {
      cell.centroid = site;
      cell.status = CellStatus::coincident;
      ++out.coincident_count;
      continue;
    }
    const gpu::SiteSums& t = sums[i];
    int px, py;
    double fx, fy;
    scene.site_pixel(i, px, py, fx, fy);
    // The offset of the centre of pixel d = 0 from the site.
    const double ax = (px + centre) * hx - site.x, ay = (py + centre) * hy - site.y;
    const double count = t.count;
    const double sx = static_cast<double>(t.sum_x), sy = static_cast<double>(t.sum_y);
    const double sxx = static_cast<double>(t.sum_xx), syy = static_cast<double>(t.sum_yy);
    double area = count * pixel_area + static_cast<double>(t.piece_area) / scene.scale_area;
    double mx = pixel_area * (hx * sx + count * ax) + static_cast<double>(t.piece_x) / scene.scale_first;
    double my = pixel_area * (hy * sy + count * ay) + static_cast<double>(t.piece_y) / scene.scale_first;
    double m2 = pixel_area * (hx * hx * sxx + 2.0 * ax * hx * sx + count * ax * ax + hy * hy * syy + 2.0 * ay * hy * sy +
                              count * ay * ay + count * (hx * hx + hy * hy) / 12.0) +
                static_cast<double>(t.piece_second) / scene.scale_second;
    if (!host_pieces.empty()) {
      area += host_pieces[i].area;
      mx += host_pieces[i].x;
      my += host_pieces[i].y;
      m2 += host_pieces[i].second;
    }
    cell.radius = farthest_sample(t) + reach;
    if (!(area > 0.0)) {
      const std::vector<Point> polygon = exact_cell_polygon(s, i);
      const PolygonMoments m = polygon_moments(polygon);
      area = m.area();
      mx = m.first_moment().x;
      my = m.first_moment().y;
      m2 = m.second_moment();
      double r2 = 0.0;
      for (Point v : polygon) r2 = std::max(r2, v.x * v.x + v.y * v.y);
      cell.radius = std::sqrt(r2);
      cell.status = CellStatus::exact_fallback;
      ++out.fallback_count;
    }
    cell.area = area;
    cell.mass = area;
    cell.second_moment = m2;
    cell.centroid = area > 0.0 ? wrap_point(site + Point{mx / area, my / area}, s.domain) : site;
  }
}

}  // namespace bluetile
