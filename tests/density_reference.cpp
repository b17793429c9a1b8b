#include "density_reference.h"

#include <cmath>

namespace bluetile::test {
namespace {

// Keeps the part of `polygon` where a.x + b.y <= c (Sutherland-Hodgman, one half-plane).
std::vector<Point> keep_below(const std::vector<Point>& polygon, double a, double b, double c) {
  std::vector<Point> out;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point p = polygon[k], q = polygon[(k + 1) % n];
    const double fp = a * p.x + b * p.y - c, fq = a * q.x + b * q.y - c;
    if (fp <= 0.0) out.push_back(p);
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) out.push_back(p + (q - p) * (fp / (fp - fq)));
  }
  return out;
}

WeightedMoments shoelace(const std::vector<Point>& polygon, double weight) {
  WeightedMoments m;
  const std::size_t n = polygon.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point p = polygon[k], q = polygon[(k + 1) % n];
    const double cross = p.x * q.y - q.x * p.y;
    m.mass += cross / 2.0;
    m.first.x += (p.x + q.x) * cross / 6.0;
    m.first.y += (p.y + q.y) * cross / 6.0;
    m.second += (p.x * p.x + p.x * q.x + q.x * q.x + p.y * p.y + p.y * q.y + q.y * q.y) * cross / 12.0;
  }
  m.mass *= weight;
  m.first *= weight;
  m.second *= weight;
  return m;
}

}  // namespace

std::vector<Point> brute_force_cell(const Scene& scene, std::size_t site) {
  const Point s = scene.sites[site], size = scene.domain.size;
  const Point lo = scene.periodic() ? -0.5 * size : -s, hi = scene.periodic() ? 0.5 * size : size - s;
  std::vector<Point> cell = {{lo.x, lo.y}, {hi.x, lo.y}, {hi.x, hi.y}, {lo.x, hi.y}};
  const int copies = scene.periodic() ? 2 : 0;
  for (std::size_t t = 0; t < scene.sites.size(); ++t) {
    for (int kx = -copies; kx <= copies; ++kx) {
      for (int ky = -copies; ky <= copies; ++ky) {
        const Point d = scene.sites[t] + Point{kx * size.x, ky * size.y} - s;
        if (d.x == 0.0 && d.y == 0.0) continue;
        cell = keep_below(cell, d.x, d.y, 0.5 * (d.x * d.x + d.y * d.y));
      }
    }
  }
  return cell;
}

WeightedMoments brute_force_moments(const std::vector<Point>& polygon, Point origin, const Scene& scene) {
  if (!scene.density) return shoelace(polygon, 1.0);
  const DensityGrid& grid = *scene.density;
  const Point size = scene.domain.size;
  const double tw = size.x / grid.width, th = size.y / grid.height;
  const int copies = scene.periodic() ? 1 : 0;
  WeightedMoments total;
  for (int kx = -copies; kx <= copies; ++kx) {
    for (int ky = -copies; ky <= copies; ++ky) {
      for (int j = 0; j < grid.height; ++j) {
        for (int i = 0; i < grid.width; ++i) {
          // Texel (i, j) of copy (kx, ky), relative to the origin.
          const double x0 = i * tw + kx * size.x - origin.x, x1 = (i + 1) * tw + kx * size.x - origin.x;
          const double y0 = j * th + ky * size.y - origin.y, y1 = (j + 1) * th + ky * size.y - origin.y;
          std::vector<Point> piece = keep_below(polygon, -1.0, 0.0, -x0);
          piece = keep_below(piece, 1.0, 0.0, x1);
          piece = keep_below(piece, 0.0, -1.0, -y0);
          piece = keep_below(piece, 0.0, 1.0, y1);
          if (piece.size() < 3) continue;
          WeightedMoments m = shoelace(piece, grid.at(i, j));
          total.mass += m.mass;
          total.first += m.first;
          total.second += m.second;
        }
      }
    }
  }
  return total;
}

Point brute_force_centroid(const Scene& scene, std::size_t site) {
  const std::vector<Point> cell = brute_force_cell(scene, site);
  const WeightedMoments m = brute_force_moments(cell, scene.sites[site], scene);
  return scene.sites[site] + m.first / m.mass;
}

}  // namespace bluetile::test
