#include <gtest/gtest.h>

#include <algorithm>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/progressive.h"
#include "test_support.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

using test::run_bluetile;
using test::TempDir;

PointSet relaxed_base(std::size_t n, std::uint64_t seed) {
  ExactEngine engine;
  LevelOptions options;
  options.add = n;
  options.seed = seed;
  options.placement = Placement::random;
  return add_level(engine, PointSet{}, options);
}

TEST(Progressive, BaseIsKeptBitForBitAndNewPointsEndRelaxed) {
  ExactEngine engine;
  for (Placement placement : {Placement::random, Placement::gaps}) {
    PointSet base = relaxed_base(200, 3);
    LevelOptions options;
    options.add = 200;
    options.seed = 4;
    options.placement = placement;
    PointSet all = add_level(engine, base, options);
    ASSERT_EQ(all.points.size(), 400u);
    for (std::size_t i = 0; i < 200; ++i) {
      ASSERT_EQ(all.points[i], base.points[i]);
      ASSERT_EQ(all.levels[i], 0);
      ASSERT_EQ(all.levels[200 + i], 1);
    }
    // Relaxed: after 80 iterations the new points sit within 1% of the hexagonal spacing of their
    // centroids (measured: about 0.13% with gaps, 0.19% with random starts; see bench).
    Scene scene = make_scene(all.points);
    scene.wanted_begin = 200;
    SceneCells cells = engine.compute(scene);
    double spacing = hexagonal_spacing(400.0), sum = 0.0;
    for (std::size_t i = 0; i < 200; ++i) sum += torus_distance(all.points[200 + i], cells.cells[i].centroid, scene.domain);
    EXPECT_LT(sum / 200.0, 0.01 * spacing);
    // Well spread: no new point closer to any point than 40% of the spacing (measured ~0.6).
    std::vector<double> nn = nearest_neighbour_distances(all.points);
    EXPECT_GT(*std::min_element(nn.begin() + 200, nn.end()), 0.4 * spacing);
  }
}

TEST(Progressive, GapsStartCloserToRelaxedThanRandom) {
  PointSet base = relaxed_base(500, 1);
  auto start_quality = [&](Placement placement) {
    std::vector<Point> added = place_new_points(base.points, 500, placement, 7);
    std::vector<Point> all = base.points;
    all.insert(all.end(), added.begin(), added.end());
    return nearest_neighbour_stats(all).min;
  };
  EXPECT_GT(start_quality(Placement::gaps), 5.0 * start_quality(Placement::random));
}

TEST(Progressive, LevelsNumberOnFromTheBase) {
  ExactEngine engine;
  PointSet base;
  base.points = {{0.1, 0.1}, {0.6, 0.6}};
  base.levels = {0, 2};
  LevelOptions options;
  options.add = 3;
  options.iterations = 2;
  PointSet all = add_level(engine, base, options);
  EXPECT_EQ(all.levels, (std::vector<int>{0, 2, 3, 3, 3}));
}

TEST(Progressive, EmptyBaseIsAPlainRelaxedSetAndZeroIsAnError) {
  ExactEngine engine;
  LevelOptions options;
  options.add = 50;
  options.iterations = 5;
  PointSet fresh = add_level(engine, PointSet{}, options);
  EXPECT_EQ(fresh.points.size(), 50u);
  EXPECT_EQ(fresh.levels, std::vector<int>(50, 0));
  options.add = 0;
  EXPECT_THROW(add_level(engine, fresh, options), Error);
}

TEST(Progressive, LevelSizes) {
  EXPECT_EQ(level_size(100, 100, 0.0), 100u);
  EXPECT_EQ(level_size(100, 0, 2.0), 100u);
  EXPECT_EQ(level_size(100, 0, 1.5), 50u);
  EXPECT_EQ(level_size(1, 0, 1.2), 0u);  // rounds to no new point: the caller reports it
}

bool same_bits(const PointSet& a, const PointSet& b) {
  if (a.points.size() != b.points.size() || a.levels != b.levels) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (a.points[i].x != b.points[i].x || a.points[i].y != b.points[i].y) return false;
  return true;
}

// Bases built in parallel, one engine per worker: every set must be the one add_levels builds
// alone with seed S + k, whatever the thread count, from scratch and on bases with different
// level counts.
TEST(Progressive, BasesBuiltInParallelAreEachBaseAloneBitForBit) {
  ExactEngine engine;
  HierarchyOptions two_levels;
  two_levels.add = 20;
  two_levels.levels = 2;
  const std::vector<PointSet> mixed = {relaxed_base(30, 1), add_levels(engine, relaxed_base(20, 2), two_levels),
                                       relaxed_base(10, 3)};
  HierarchyOptions scratch_options;
  scratch_options.count = 24;
  scratch_options.levels = 3;
  scratch_options.iterations = 40;
  scratch_options.tolerance = 2e-4;
  scratch_options.seed = 11;
  HierarchyOptions mixed_options = scratch_options;
  mixed_options.add = 16;
  mixed_options.levels = 0;  // one more level than each base has
  const std::size_t machine_threads = thread_count();
  for (const auto& [bases, options] : {std::pair{std::vector<PointSet>(9), scratch_options}, std::pair{mixed, mixed_options}}) {
    std::vector<PointSet> alone;
    for (std::size_t k = 0; k < bases.size(); ++k) {
      HierarchyOptions single = options;
      single.seed = options.seed + k;
      alone.push_back(add_levels(engine, bases[k], single));
    }
    for (std::size_t threads : {1, 2, 7}) {
      set_thread_count(threads);
      std::vector<std::size_t> reported;
      std::vector<PointSet> built = add_levels([] { return std::make_unique<ExactEngine>(); }, bases, options,
                                               [&reported](std::size_t done) { reported.push_back(done); });
      set_thread_count(machine_threads);
      ASSERT_EQ(built.size(), alone.size());
      for (std::size_t k = 0; k < built.size(); ++k)
        EXPECT_TRUE(same_bits(built[k], alone[k])) << "set " << k << ", " << threads << " threads";
      std::vector<std::size_t> counted(bases.size());
      for (std::size_t k = 0; k < counted.size(); ++k) counted[k] = k + 1;
      EXPECT_EQ(reported, counted);
    }
  }
}

TEST(Progressive, CommandLineHierarchyHasEveryPrefixWellSpread) {
  TempDir dir;
  auto r = run_bluetile({"progressive", "-n", "100", "--levels", "4", "-k", "40", "--engine", "exact", "-o", dir.file("h.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  PointSet h = read_point_file(dir.file("h.txt"));
  ASSERT_EQ(h.points.size(), 400u);
  for (int l = 0; l < 4; ++l) {
    std::vector<Point> prefix;
    for (std::size_t i = 0; i < h.points.size(); ++i)
      if (h.levels[i] <= l) prefix.push_back(h.points[i]);
    ASSERT_EQ(prefix.size(), 100u * (l + 1));
    NearestNeighbourStats nn = nearest_neighbour_stats(prefix);
    EXPECT_GT(nn.min / nn.hexagonal_spacing, 0.4) << "prefix of levels 0.." << l;
  }
  // Adding to that file keeps it and numbers the new level 4.
  r = run_bluetile({"progressive", "-i", dir.file("h.txt"), "--add", "50", "-k", "5", "--engine", "exact", "-o", dir.file("h5.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  PointSet h5 = read_point_file(dir.file("h5.txt"));
  ASSERT_EQ(h5.points.size(), 450u);
  EXPECT_TRUE(std::equal(h.points.begin(), h.points.end(), h5.points.begin()));
  EXPECT_EQ(h5.levels.back(), 4);
}

TEST(Progressive, CommandLineBadInput) {
  TempDir dir;
  std::string base = dir.write("base.txt", "0.1 0.1\n0.5 0.5\n");
  std::string out = dir.file("o.txt");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"progressive", "-i", base, "-o", out}, "--input needs --add M or --ratio R"},
      {{"progressive", "-i", base, "--add", "0", "-o", out}, "--add"},
      {{"progressive", "-i", base, "--add", "5", "--levels", "1", "-o", out}, "already has 1 level; --levels is the total to reach (2 or more)"},
      {{"progressive", "-i", base, "--ratio", "0.5", "-o", out}, "--ratio 0.5: out of range; expected a number above 1"},
      {{"progressive", "-i", base, "--ratio", "1.1", "-o", out}, "--ratio 1.1 adds no point to a set of 2"},
      {{"progressive", "-n", "10", "--add", "100000000", "--levels", "3", "-o", out}, "more than the limit"},
      {{"progressive", "-o", out}, "--input or --count"},
  };
  for (const auto& c : cases) {
    auto r = run_bluetile(c.args);
    EXPECT_NE(r.exit_code, 0) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
  }
  EXPECT_EQ(dir.list(), std::vector<std::string>{"base.txt"});
}

}  // namespace
}  // namespace bluetile
