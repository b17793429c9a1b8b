// The raster engine on collinear sites (strip cells that span the domain across the line), against
// the exact engine; and the work of the host split's candidate search on them, which the k-d tree
// keeps near that of uniform sites (a grid window there holds O(N) sites per pixel).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"

namespace bluetile {
namespace {

struct Line {
  std::string name;
  std::function<Point(std::size_t i, std::size_t n)> at;
};

double along(std::size_t i, std::size_t n) { return (static_cast<double>(i) + 0.5) / static_cast<double>(n); }

const std::vector<Line> kLines = {
    {"horizontal", [](std::size_t i, std::size_t n) { return Point{along(i, n), 0.5}; }},
    {"tilted", [](std::size_t i, std::size_t n) { return Point{0.1 + 0.8 * along(i, n), 0.2 + 0.6 * along(i, n)}; }},
    {"four parallel", [](std::size_t i, std::size_t n) {
       return Point{along(i % (n / 4), n / 4), 0.125 + 0.25 * static_cast<double>(i / (n / 4))};
     }},
};

Scene line_scene(const Line& line, std::size_t n, Boundary boundary) {
  std::vector<Point> sites(n);
  for (std::size_t i = 0; i < n; ++i) sites[i] = line.at(i, n);
  Scene scene = make_scene(std::move(sites));
  scene.boundary = boundary;
  return scene;
}

TEST(RasterCollinear, CellsMatchTheExactEngine) {
  ExactEngine exact;
  RasterOptions options;
  options.resolution = 48;
  options.pixel_work = PixelWork::host;
  RasterEngine raster(options);
  for (const Line& line : kLines)
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      const Scene scene = line_scene(line, 400, boundary);
      const SceneCells want = exact.compute(scene), got = raster.compute(scene);
      ASSERT_EQ(got.cells.size(), want.cells.size());
      double area = 0.0;
      for (std::size_t i = 0; i < want.cells.size(); ++i) {
        const Cell &a = got.cells[i], &b = want.cells[i];
        EXPECT_NEAR(a.centroid.x, b.centroid.x, 1e-12) << line.name << " site " << i;
        EXPECT_NEAR(a.centroid.y, b.centroid.y, 1e-12) << line.name << " site " << i;
        EXPECT_NEAR(a.area, b.area, 1e-12) << line.name << " site " << i;
        area += a.area;
      }
      EXPECT_NEAR(area, 1.0, 1e-12) << line.name;
    }
}

// Sites the split's candidate searches examined per boundary pixel (host pixel work).
double examined_per_boundary_pixel(const Scene& scene) {
  RasterOptions options;
  options.pixel_work = PixelWork::host;
  RasterEngine raster(options);
  raster.compute(scene);
  const RasterStats& s = raster.stats();
  return static_cast<double>(s.split_sites_examined) / static_cast<double>(s.boundary_pixels);
}

TEST(RasterCollinear, CandidateSearchStaysNearTheUniformCase) {
  constexpr std::size_t kSites = 2000;
  Rng rng(7);
  std::vector<Point> uniform(kSites);
  for (Point& p : uniform) p = rng.point(Domain{});
  const double base = examined_per_boundary_pixel(make_scene(std::move(uniform)));
  for (const Line& line : kLines) {
    const double line_work = examined_per_boundary_pixel(line_scene(line, kSites, Boundary::periodic));
    // A strip pixel has about N / resolution pieces (about 21 here); the grid window examined
    // O(N) sites per pixel (hundreds), the tree a few per piece.
    EXPECT_LT(line_work, 12.0 * base) << line.name << ": " << line_work << " against " << base;
  }
}

}  // namespace
}  // namespace bluetile
