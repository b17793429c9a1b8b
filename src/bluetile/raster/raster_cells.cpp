// Assembling raster cells (see raster_cells.h).
#include "bluetile/raster/raster_cells.h"

#include <cmath>

#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/raster/raster_coverage.h"

namespace bluetile {

void assemble_cells(const RasterScene& scene, std::span<const gpu::SiteSums> sums, std::span<const PieceSums> host_pieces,
                    SceneCells& out, std::span<const WeightedSums> weighted) {
  const Scene& s = *scene.scene;
  out.cells.assign(s.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  out.zero_density_count = 0;
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
    WeightedMoments w;
    if (scene.density) {
      const WeightedSums& f = weighted[i];
      const double unit = scene.density_scale;
      w.mass = static_cast<double>(f.mass) / (unit * scene.scale_area);
      w.first = {static_cast<double>(f.x) / (unit * scene.scale_first), static_cast<double>(f.y) / (unit * scene.scale_first)};
      w.second = static_cast<double>(f.second) / (unit * scene.scale_second);
      if (!host_pieces.empty()) {
        w.mass += host_pieces[i].weighted.mass;
        w.first = w.first + host_pieces[i].weighted.first;
        w.second += host_pieces[i].weighted.second;
      }
    }
    if (!(area > 0.0)) {
      const std::vector<Point> polygon = exact_cell_polygon(s, i);
      if (scene.density) w = density_moments(polygon, site, *scene.density, s.domain.size, scene.periodic);
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
    if (scene.density) {
      if (!(w.mass > 0.0) && area > 0.0) {
        // No density anywhere in the cell: nothing pulls the site, it stays.
        cell.mass = 0.0;
        cell.second_moment = w.second;
        cell.centroid = site;
        cell.status = CellStatus::zero_density;
        ++out.zero_density_count;
        continue;
      }
      cell.mass = w.mass;
      cell.second_moment = w.second;
      cell.centroid = scene_point(s, site + Point{w.first.x / w.mass, w.first.y / w.mass});
      continue;
    }
    // A uniform density (or none) weighs every point alike: the centroid is the unweighted one.
    cell.mass = scene.density_constant * area;
    cell.second_moment = scene.density_constant == 1.0 ? m2 : scene.density_constant * m2;
    cell.centroid = area > 0.0 ? scene_point(s, site + Point{mx / area, my / area}) : site;
  }
}

}  // namespace bluetile
