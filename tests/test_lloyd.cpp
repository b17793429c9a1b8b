#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "bluetile/core/parallel.h"
#include "bluetile/raster/raster_engine.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "test_support.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

TEST(Lloyd, EnergyNeverRises) {
  ExactEngine engine;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    Scene scene = make_scene(test::uniform_points(1000, seed));
    LloydOptions options;
    options.iterations = 50;
    options.keep_history = true;
    LloydResult result = relax_lloyd(engine, scene, options);
    ASSERT_EQ(result.history.size(), 50u);
    for (std::size_t i = 1; i < result.history.size(); ++i) {
      // Relative slack of 1e-12 for summation rounding only.
      EXPECT_LE(result.history[i].energy, result.history[i - 1].energy * (1.0 + 1e-12))
          << "seed " << seed << " iteration " << i + 1;
    }
    // Relaxation gets within a few percent of the hexagonal optimum 5/(18 sqrt 3) / N.
    double hexagonal = 5.0 / (18.0 * std::sqrt(3.0)) / 1000.0;
    EXPECT_LT(result.history.back().energy, 1.05 * hexagonal);
    EXPECT_GT(result.history.back().energy, hexagonal);
  }
}

TEST(Lloyd, SquareLatticeDoesNotMove) {
  std::vector<Point> sites;
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) sites.push_back({(x + 0.5) / 8, (y + 0.5) / 8});
  Scene scene = make_scene(sites);
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 5;
  LloydResult result = relax_lloyd(engine, scene, options);
  EXPECT_LT(result.last.max_displacement, 1e-15);
  for (std::size_t i = 0; i < sites.size(); ++i) EXPECT_LT(torus_distance(scene.sites[i], sites[i], scene.domain), 1e-15);
}

TEST(Lloyd, FixedSitesStayBitForBit) {
  std::vector<Point> sites = test::uniform_points(400, 8);
  Scene scene = make_scene(sites);
  scene.wanted_begin = 100;
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 10;
  relax_lloyd(engine, scene, options);
  for (std::size_t i = 0; i < 100; ++i) ASSERT_EQ(scene.sites[i], sites[i]);
  std::size_t moved = 0;
  for (std::size_t i = 100; i < 400; ++i) moved += scene.sites[i] != sites[i];
  EXPECT_EQ(moved, 300u);
}

TEST(Lloyd, StopsOnceBelowTheTolerance) {
  Scene scene = make_scene(test::uniform_points(200, 2));
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 10000;
  options.tolerance = 1e-4;
  options.keep_history = true;
  LloydResult result = relax_lloyd(engine, scene, options);
  EXPECT_TRUE(result.converged);
  EXPECT_LT(result.history.size(), 10000u);
  EXPECT_EQ(result.iterations, static_cast<int>(result.history.size()));
  EXPECT_EQ(result.last.max_displacement, result.history.back().max_displacement);
  EXPECT_LT(result.history.back().max_displacement, 1e-4);
  EXPECT_GE(result.history[result.history.size() - 2].max_displacement, 1e-4);
}

TEST(Lloyd, BadOptionsAreRefusedByTheLibraryToo) {
  // Iterations -1 ran none, and a NaN or negative tolerance was taken; the front ends checked,
  // a caller of the library was not told. The same for progressive levels and the raster engine.
  Scene scene = make_scene(test::uniform_points(20, 2));
  const std::vector<Point> before = scene.sites;
  ExactEngine engine;
  auto relaxed = [&](int iterations, double tolerance) {
    LloydOptions options;
    options.iterations = iterations;
    options.tolerance = tolerance;
    return test::error_of([&] { relax_lloyd(engine, scene, options); });
  };
  EXPECT_EQ(relaxed(-1, 0.0), "iterations: expected 0 to 2147483647, got -1");
  EXPECT_EQ(relaxed(1, std::nan("")), "tolerance: expected 0 to inf, got nan");
  EXPECT_EQ(relaxed(1, -1.0), "tolerance: expected 0 to inf, got -1");
  EXPECT_EQ(scene.sites, before);
  HierarchyOptions hierarchy;
  hierarchy.count = 10;
  hierarchy.iterations = -3;
  EXPECT_EQ(test::error_of([&] { add_levels(engine, PointSet{}, hierarchy); }),
            "iterations: expected 0 to 2147483647, got -3");
  RasterOptions raster;
  raster.resolution = -5;
  EXPECT_EQ(test::error_of([&] { RasterEngine r(raster); }), "resolution: expected 0 (from N) or 16 to 65536, got -5");
  raster.resolution = 0;
  raster.radius_factor = std::nan("");
  EXPECT_EQ(test::error_of([&] { RasterEngine r(raster); }), "radius_factor: expected 0.001 to 1e+03, got nan");
}

TEST(Lloyd, KeepsNoHistoryUnlessAsked) {
  // A million iterations on 10 sites once took 176 MB for the history.
  Scene scene = make_scene(test::uniform_points(10, 3));
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 300;
  int calls = 0;
  options.on_iteration = [&](const LloydIteration& it) { EXPECT_EQ(it.iteration, ++calls); };
  LloydResult result = relax_lloyd(engine, scene, options);
  EXPECT_TRUE(result.history.empty());
  EXPECT_EQ(result.history.capacity(), 0u);
  EXPECT_EQ(result.iterations, 300);
  EXPECT_EQ(result.last.iteration, 300);
  EXPECT_EQ(calls, 300);
}

TEST(Lloyd, WithoutEnergyTheSitesMoveTheSameBits) {
  // LloydOptions::energy false: every iteration's energy is 0 and the sites end where they end
  // with it, bit for bit; the scene's own request is given back after the run.
  for (std::size_t n : {200u, 3000u}) {  // searched (below 256 sites), and on the kept triangulation
    Scene a = make_scene(test::uniform_points(n, 9));
    Scene b = a;
    ExactEngine with, without;
    LloydOptions options;
    options.iterations = 12;
    options.keep_history = true;
    const LloydResult r = relax_lloyd(with, a, options);
    options.energy = false;
    const LloydResult s = relax_lloyd(without, b, options);
    ASSERT_EQ(r.history.size(), s.history.size());
    for (std::size_t i = 0; i < r.history.size(); ++i) {
      EXPECT_GT(r.history[i].energy, 0.0) << i;
      EXPECT_EQ(s.history[i].energy, 0.0) << i;
      EXPECT_EQ(r.history[i].max_displacement, s.history[i].max_displacement) << i;
      EXPECT_EQ(r.history[i].mean_displacement, s.history[i].mean_displacement) << i;
    }
    ASSERT_EQ(a.sites.size(), b.sites.size());
    EXPECT_EQ(std::memcmp(a.sites.data(), b.sites.data(), a.sites.size() * sizeof(Point)), 0) << n << " sites";
    EXPECT_TRUE(b.second_moments);
  }
}

TEST(Lloyd, CoincidentSiteKeepsItsPlace) {
  std::vector<Point> sites = test::uniform_points(50, 4);
  sites.push_back(sites[10]);
  Scene scene = make_scene(sites);
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 1;
  LloydResult result = relax_lloyd(engine, scene, options);
  EXPECT_EQ(result.last.coincident, 1u);
  EXPECT_EQ(scene.sites[50], sites[10]);
  EXPECT_NE(scene.sites[10], sites[10]);  // the owner moved to its centroid: they separate
}

TEST(Lloyd, GridRowOrderIsBucketRowsThenIndex) {
  // 5 sites: a 3 x 3 grid over [0, 2) x [0, 1), buckets 2/3 wide and 1/3 high.
  const std::vector<Point> sites{{1.5, 0.9}, {0.1, 0.1}, {1.9, 0.05}, {0.05, 0.2}, {0.7, 0.5}};
  // Buckets 8, 0, 2, 0, 4: bucket 0 keeps its two sites in index order.
  EXPECT_EQ(grid_row_order(sites, Domain{{2.0, 1.0}}), (std::vector<std::uint32_t>{1, 3, 2, 4, 0}));
  EXPECT_TRUE(grid_row_order({}, Domain{}).empty());
  EXPECT_EQ(grid_row_order(std::vector<Point>{{0.999, 0.999}}, Domain{}), std::vector<std::uint32_t>{0});
}

// What relax_lloyd should give for a large scene: its wanted sites put in grid_row_order, moved
// by the engine and move_to_centroids in that order, and put back in the caller's.
std::vector<Point> relaxed_in_grid_order(std::vector<Point> start, std::size_t fixed, int iterations) {
  Scene scene = make_scene(start);
  scene.wanted_begin = fixed;
  const std::vector<std::uint32_t> order =
      grid_row_order(std::span<const Point>(start).subspan(fixed), scene.domain);
  for (std::size_t i = 0; i < order.size(); ++i) scene.sites[fixed + i] = start[fixed + order[i]];
  ExactEngine engine;
  std::vector<Scene> scenes{std::move(scene)};
  std::vector<SceneCells> cells(1);
  for (int it = 0; it < iterations; ++it) {
    engine.compute(scenes, cells);
    move_to_centroids(scenes, cells);
  }
  for (std::size_t i = 0; i < order.size(); ++i) start[fixed + order[i]] = scenes[0].sites[fixed + i];
  return start;
}

TEST(Lloyd, LargeScenesRelaxInGridOrderAndComeBackInTheirOwn) {
  const std::size_t n = kGridOrderSites + 1000, fixed = 500;
  const std::vector<Point> start = test::uniform_points(n, 12);
  const std::vector<Point> expected = relaxed_in_grid_order(start, fixed, 3);
  const std::size_t threads_before = thread_count();
  for (std::size_t threads : {1u, 2u}) {
    set_thread_count(threads);
    Scene scene = make_scene(start);
    scene.wanted_begin = fixed;
    ExactEngine engine;
    LloydOptions options;
    options.iterations = 3;
    relax_lloyd(engine, scene, options);
    ASSERT_EQ(scene.sites.size(), n);
    EXPECT_EQ(std::memcmp(scene.sites.data(), expected.data(), n * sizeof(Point)), 0) << threads << " threads";
  }
  set_thread_count(threads_before);
  // In the caller's order the sums start elsewhere: the same sites to rounding.
  Scene own = make_scene(start);
  own.wanted_begin = fixed;
  ExactEngine engine;
  std::vector<Scene> scenes{std::move(own)};
  std::vector<SceneCells> cells(1);
  std::size_t differing = 0;
  for (int it = 0; it < 3; ++it) {
    engine.compute(scenes, cells);
    move_to_centroids(scenes, cells);
  }
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_LT(torus_distance(scenes[0].sites[i], expected[i], Domain{}), 1e-12) << i;
    differing += scenes[0].sites[i] != expected[i];
  }
  EXPECT_GT(differing, 0u);  // else the order would not have been applied
  for (std::size_t i = 0; i < fixed; ++i) ASSERT_EQ(expected[i], start[i]);
}

TEST(Lloyd, TheMoveGivesTheSameSitesAndSumsOnAnyThreadCount) {
  // Two to four chunks of 1024 sites move on all threads and are summed on the calling thread
  // chunk by chunk in site order; one chunk, and more than four (moved and summed a chunk at a
  // time on all threads), take other paths. Every path's sites and log (energy, largest and mean
  // displacement) must be the same bits on 1, 2 and 7 threads. The cells come from one engine
  // call, so only the move differs between the runs.
  const std::size_t threads_before = thread_count();
  for (std::size_t n : {1000u, 3000u, 4097u, 9000u, 21000u}) {
    const Scene start = make_scene(test::uniform_points(n, 31));
    const SceneCells cells = ExactEngine().compute(start);
    std::vector<Point> first_sites;
    LloydIteration first{};
    for (std::size_t threads : {1u, 2u, 7u}) {
      set_thread_count(threads);
      std::vector<Scene> scenes{start};
      const LloydIteration log = move_to_centroids(scenes, std::span<const SceneCells>(&cells, 1));
      if (threads == 1) {
        first_sites = scenes[0].sites;
        first = log;
        EXPECT_GT(log.energy, 0.0);
        EXPECT_GT(log.max_displacement, log.mean_displacement);
        continue;
      }
      EXPECT_EQ(std::memcmp(scenes[0].sites.data(), first_sites.data(), n * sizeof(Point)), 0) << n << " sites, " << threads;
      EXPECT_EQ(std::memcmp(&log.energy, &first.energy, sizeof(double)), 0) << n << " sites, " << threads;
      EXPECT_EQ(std::memcmp(&log.max_displacement, &first.max_displacement, sizeof(double)), 0) << n << ", " << threads;
      EXPECT_EQ(std::memcmp(&log.mean_displacement, &first.mean_displacement, sizeof(double)), 0) << n << ", " << threads;
    }
  }
  set_thread_count(threads_before);
}

TEST(Lloyd, AnInterruptedRunGivesTheSitesBackInTheirOwnOrder) {
  const std::size_t n = kGridOrderSites;
  const std::vector<Point> start = test::uniform_points(n, 13);
  Scene scene = make_scene(start);
  ExactEngine engine;
  LloydOptions options;
  options.iterations = 5;
  options.on_iteration = [](const LloydIteration& it) {
    if (it.iteration == 2) throw std::runtime_error("interrupted");
  };
  EXPECT_THROW(relax_lloyd(engine, scene, options), std::runtime_error);
  const std::vector<Point> expected = relaxed_in_grid_order(start, 0, 2);
  EXPECT_EQ(std::memcmp(scene.sites.data(), expected.data(), n * sizeof(Point)), 0);
}

}  // namespace
}  // namespace bluetile
