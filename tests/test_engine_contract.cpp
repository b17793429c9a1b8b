// The engine contract (voronoi/scene.h), run against every engine: the same scenes are accepted,
// wrapped or refused, with the project's error type, whatever the engine.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "bluetile/voronoi/scene.h"
#include "test_support.h"

namespace bluetile {
namespace {

struct EngineCase {
  std::string name;
  std::function<std::unique_ptr<CentroidEngine>()> make;
  // Agreement with the exact engine on the wrapped scene: a site shifted by a period and wrapped
  // back differs from the original in its last bits.
  double tolerance;
};
// GoogleTest names each parameter in its test list; without this it prints the case's bytes,
// padding included (valgrind reports them as uninitialised).
void PrintTo(const EngineCase& c, std::ostream* os) { *os << c.name; }

class EngineContract : public ::testing::TestWithParam<EngineCase> {};
// The refusals' exact messages: engines that call validated_scene() at their entry.
class EngineRefusals : public ::testing::TestWithParam<EngineCase> {};

std::string error_of(CentroidEngine& engine, const Scene& scene) {
  try {
    engine.compute(scene);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneContract, WrapsOnlyWhatNeedsIt) {
  Scene inside = make_scene({{0.25, 0.5}, {0.75, 0.5}});
  Scene storage;
  EXPECT_EQ(&validated_scene(inside, storage), &inside);  // nothing copied
  Scene outside = make_scene({{0.25, 0.5}, {1.75, -0.5}, {-1e-20, 2.0}}, Domain{{2.0, 1.0}});
  const Scene& wrapped = validated_scene(outside, storage);
  EXPECT_EQ(&wrapped, &storage);
  EXPECT_EQ(wrapped.sites, (std::vector<Point>{{0.25, 0.5}, {1.75, 0.5}, {0.0, 0.0}}));
  EXPECT_EQ(outside.sites[1], Point(1.75, -0.5));  // the caller's scene is untouched
}

TEST_P(EngineContract, SitesOutsideTheDomainAreWrapped) {
  // The exact engine once gave areas summing to 1.00998 for sites one period out.
  auto engine = GetParam().make();
  ExactEngine reference;
  for (Domain domain : {Domain{}, Domain{{2.0, 0.5}}}) {
    std::vector<Point> sites = test::uniform_points(60, 11);
    for (Point& p : sites) p *= domain.size;
    Scene wrapped = make_scene(sites, domain);
    Scene shifted = wrapped;
    for (std::size_t i = 0; i < shifted.sites.size(); ++i) {
      const double kx = static_cast<double>(static_cast<int>(i % 3) - 1), ky = static_cast<double>(static_cast<int>(i % 5) - 2);
      shifted.sites[i] += Point{kx * domain.size.x, ky * domain.size.y};
    }
    SceneCells expected = reference.compute(wrapped);
    SceneCells got = engine->compute(shifted);
    ASSERT_EQ(got.cells.size(), sites.size());
    double area = 0.0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
      area += got.cells[i].area;
      EXPECT_NEAR(got.cells[i].area, expected.cells[i].area, GetParam().tolerance) << i;
      EXPECT_LE(torus_distance(got.cells[i].centroid, expected.cells[i].centroid, domain), GetParam().tolerance) << i;
      EXPECT_GE(got.cells[i].centroid.x, 0.0);
      EXPECT_LT(got.cells[i].centroid.x, domain.size.x);
    }
    EXPECT_NEAR(area, domain.area(), 1e-12);
  }
}

TEST_P(EngineRefusals, BrokenScenesAreRefusedWithTheProjectsError) {
  auto engine = GetParam().make();
  Scene scene = make_scene({{0.25, 0.5}, {0.75, 0.5}, {0.5, 0.1}});
  Scene bad = scene;
  bad.wanted_begin = 2;
  bad.wanted_end = 1;
  EXPECT_EQ(error_of(*engine, bad), "scene: wanted sites [2, 1) do not lie inside its 3 sites");
  bad = scene;
  bad.wanted_end = 4;
  EXPECT_EQ(error_of(*engine, bad), "scene: wanted sites [0, 4) do not lie inside its 3 sites");
  bad = scene;
  bad.sites[1].y = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of(*engine, bad), "scene: site 1 (0.75, nan) is not finite");
  bad = scene;
  bad.sites[2].x = -std::numeric_limits<double>::infinity();
  EXPECT_EQ(error_of(*engine, bad), "scene: site 2 (-inf, 0.10000000000000001) is not finite");
  bad = scene;
  bad.boundary = Boundary::bounded;
  bad.sites[0].x = 1.0;
  EXPECT_EQ(error_of(*engine, bad), "scene: site 0 (1, 0.5) lies outside the bounded domain 1 x 1");
  bad = scene;
  bad.density = std::make_shared<DensityGrid>(4, 4, 1.0f);
  std::const_pointer_cast<DensityGrid>(bad.density)->texels.pop_back();
  EXPECT_EQ(error_of(*engine, bad), "density grid of 4 x 4 texels holds 15 values");
  for (Point size : {Point{0.0, 1.0}, Point{1.0, -1.0}, Point{std::nan(""), 1.0},
                     Point{1.0, std::numeric_limits<double>::infinity()}}) {
    bad = scene;
    bad.domain.size = size;
    EXPECT_NE(error_of(*engine, bad).find("is not a finite positive size"), std::string::npos) << size.x << " " << size.y;
  }
  // Room for fewer results than scenes: the exact engine wrote past it (an assert, gone in a
  // release build: a crash).
  const std::vector<Scene> two = {scene, scene};
  std::vector<SceneCells> one(1);
  std::string message;
  try {
    engine->compute(two, one);
  } catch (const Error& e) {
    message = e.what();
  }
  EXPECT_EQ(message, std::string(engine->name()) + " engine: 2 scenes but room for 1 result");
}

TEST_P(EngineRefusals, LargeScenesNameTheFirstBadSiteOnAnyThreadCount) {
  // From 8192 sites the scene check runs on all threads in parts of 256 sites (scene.cpp), two
  // sites at a time: a bad site in any part, at an even or an odd place, in the last part's odd
  // tail, must still be found and the first one named, whatever the thread count.
  const std::size_t before = thread_count();
  const std::vector<Point> sites = test::uniform_points(20001, 5);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (std::size_t threads : {1, 2, 7}) {
    set_thread_count(threads);
    auto engine = GetParam().make();
    for (std::size_t at : {0, 255, 256, 12345, 20000}) {
      Scene bad = make_scene(sites);
      bad.sites[at].y = nan;
      EXPECT_EQ(error_of(*engine, bad), "scene: site " + std::to_string(at) + " (" + exact_text(bad.sites[at].x) + ", nan) is not finite")
          << threads << " threads";
      bad.sites[at].y = 0.5;
      bad.sites[at].x = inf;
      bad.sites[at + (at < 20000 ? 1 : -1)].x = -inf;  // a later bad site is not the one named
      const std::size_t first = std::min(at, at < 20000 ? at + 1 : at - 1);
      EXPECT_NE(error_of(*engine, bad).find("scene: site " + std::to_string(first) + " ("), std::string::npos) << threads;
      bad = make_scene(sites);
      bad.boundary = Boundary::bounded;
      bad.sites[at].x = 1.0;
      EXPECT_EQ(error_of(*engine, bad), "scene: site " + std::to_string(at) + " (1, " + exact_text(bad.sites[at].y) +
                                            ") lies outside the bounded domain 1 x 1")
          << threads;
    }
    // On the torus a site outside is wrapped, not refused: the same cells as the wrapped scene.
    Scene outside = make_scene(sites);
    outside.sites[19999].x -= 1.0;
    EXPECT_TRUE(test::identical_cells(engine->compute(outside), GetParam().make()->compute(make_scene(sites)))) << threads;
  }
  set_thread_count(before);
}

TEST_P(EngineContract, ResultsDoNotDependOnTheCallsBefore) {
  // An engine may keep state between calls (the exact engine keeps a Delaunay triangulation per
  // place in the batch); a scene's result must still be the same bits whatever it measured
  // before: a scene, another scene of the same shape, the first one moved a little, the first.
  auto engine = GetParam().make();
  std::vector<Point> sites = test::uniform_points(600, 21);
  const Scene first = make_scene(sites);
  const Scene other = make_scene(test::uniform_points(600, 22));
  for (Point& p : sites) p = wrap_point(p + Point{0.003, -0.002}, Domain{});
  const Scene moved = make_scene(sites);
  const SceneCells a = engine->compute(first);
  engine->compute(other);
  const SceneCells b = engine->compute(moved);
  const SceneCells c = engine->compute(first);
  EXPECT_TRUE(test::identical_cells(a, c));
  EXPECT_TRUE(test::identical_cells(b, GetParam().make()->compute(moved)));
}

TEST_P(EngineContract, EmptyWantedRangesGiveNoCells) {
  auto engine = GetParam().make();
  EXPECT_TRUE(engine->compute(make_scene({})).cells.empty());
  Scene none_wanted = make_scene({{0.25, 0.5}, {0.75, 0.5}});
  none_wanted.wanted_begin = none_wanted.wanted_end = 1;
  EXPECT_TRUE(engine->compute(none_wanted).cells.empty());
}

const EngineCase kExact{"exact", [] { return std::make_unique<ExactEngine>(); }, 1e-12};
const EngineCase kRaster{"raster", [] { return std::make_unique<RasterEngine>(RasterOptions{}); }, 1e-12};
const EngineCase kRasterDevicePixels{"raster_device_pixels",
                                     [] {
                                       RasterOptions options;
                                       options.pixel_work = PixelWork::device;
                                       return std::make_unique<RasterEngine>(options);
                                     },
                                     1e-12};
std::string engine_name(const ::testing::TestParamInfo<EngineCase>& engine) { return engine.param.name; }

INSTANTIATE_TEST_SUITE_P(Engines, EngineContract, ::testing::Values(kExact, kRaster, kRasterDevicePixels), engine_name);
// The raster engine joins once it calls validated_scene() (it refuses these scenes already, in
// words of its own).
INSTANTIATE_TEST_SUITE_P(Engines, EngineRefusals, ::testing::Values(kExact), engine_name);

}  // namespace
}  // namespace bluetile
