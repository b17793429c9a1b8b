// The raster engine on collinear sites (strip cells that span the domain across the line), against
// the exact engine; the work of the host split's candidate search on them, which the k-d tree
// keeps near that of uniform sites (a grid window there holds O(N) sites per pixel); and the
// hand-over of such scenes to the exact engine (RasterOptions::max_cone_overlap).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "test_raster_support.h"

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

// Both pixel-work paths (the device's checked against the host's bits); bounded scenes run on the
// host path only (the shaders know no border).
class RasterCollinear : public test::RasterPaths {};
INSTANTIATE_TEST_SUITE_P(PixelWork, RasterCollinear, ::testing::ValuesIn(test::kPixelPaths), test::pixel_path_name);

TEST_P(RasterCollinear, CellsMatchTheExactEngine) {
  ExactEngine exact;
  RasterOptions options;
  options.resolution = 48;
  options.max_cone_overlap = 0.0;  // the raster path, not the exact engine's hand-over
  test::PathEngine raster(options, work());
  for (const Line& line : kLines)
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      if (on_device() && boundary == Boundary::bounded) continue;
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
  options.max_cone_overlap = 0.0;
  RasterEngine raster(options);
  raster.compute(scene);
  const RasterStats& s = raster.stats();
  return static_cast<double>(s.split_sites_examined) / static_cast<double>(s.boundary_pixels);
}

TEST(RasterCollinearSearch, CandidateSearchStaysNearTheUniformCase) {
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

void expect_same_bits(const SceneCells& got, const SceneCells& want, const std::string& what) {
  ASSERT_EQ(got.cells.size(), want.cells.size()) << what;
  std::size_t differ = 0;
  for (std::size_t i = 0; i < want.cells.size(); ++i) {
    const Cell &a = got.cells[i], &b = want.cells[i];
    differ += a.centroid.x != b.centroid.x || a.centroid.y != b.centroid.y || a.area != b.area || a.second_moment != b.second_moment ||
              a.radius != b.radius;
  }
  EXPECT_EQ(differ, 0u) << what;
}

TEST(RasterCollinearHandOver, SliverScenesGoToTheExactEngineAndOthersStay) {
  // Strip cells make every cone cover most of the domain: after the first pass (cones 2.5
  // spacings wide, most samples uncovered) the grown cones would overlap about 80 times, past
  // max_cone_overlap (64), and the exact engine measures the scene. Uniform sites pass at once.
  constexpr std::size_t kSites = 2000;
  ExactEngine exact;
  RasterEngine raster;  // the defaults
  Rng rng(11);
  std::vector<Point> uniform(kSites);
  for (Point& p : uniform) p = rng.point(Domain{});
  const Scene random_scene = make_scene(uniform);
  for (const Line& line : kLines) {
    const Scene scene = line_scene(line, kSites, Boundary::periodic);
    const std::uint64_t before = raster.stats().exact_scenes, submits = raster.stats().submits;
    const SceneCells cells = raster.compute(scene);
    EXPECT_EQ(raster.stats().exact_scenes, before + 1) << line.name;
    EXPECT_EQ(raster.stats().submits, submits + 1) << line.name << ": one pass, then the exact engine";
    expect_same_bits(cells, exact.compute(scene), line.name);
    // The next call on the moved sites decides from the remembered cell radii, without a pass.
    std::vector<Point> moved(scene.sites.size());
    for (std::size_t i = 0; i < moved.size(); ++i) moved[i] = cells.cells[i].centroid;
    const Scene next = make_scene(moved);
    const SceneCells next_cells = raster.compute(next);
    EXPECT_EQ(raster.stats().submits, submits + 1) << line.name;
    EXPECT_EQ(raster.stats().exact_scenes, before + 2) << line.name;
    expect_same_bits(next_cells, exact.compute(next), line.name + ", next call");
  }
  // In a batch only the sliver scene is handed over; the uniform one keeps the raster's bits.
  RasterEngine alone, batched;
  const SceneCells want = alone.compute(random_scene);
  EXPECT_EQ(alone.stats().exact_scenes, 0u);
  std::vector<Scene> batch = {random_scene, line_scene(kLines[0], kSites, Boundary::bounded)};
  std::vector<SceneCells> got(batch.size());
  batched.compute(batch, got);
  EXPECT_EQ(batched.stats().exact_scenes, 1u);
  expect_same_bits(got[0], want, "uniform scene in a batch");
  expect_same_bits(got[1], exact.compute(batch[1]), "bounded line in a batch");
  // Asked for ID images, the engine keeps the raster path (an image per scene).
  RasterOptions with_images;
  with_images.keep_id_images = true;
  RasterEngine drawing(with_images);
  const Scene line = line_scene(kLines[0], 400, Boundary::periodic);
  drawing.compute(line);
  EXPECT_EQ(drawing.stats().exact_scenes, 0u);
  EXPECT_EQ(drawing.id_image(0).width, drawing.resolution_for(line));
}

}  // namespace
}  // namespace bluetile
