// Rank orders of progressive sets: the void order (relax/void_order.h) and progressive's voids
// rank order, whose every prefix, not only the level boundaries, must be well spread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/void_order.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::run_bluetile;
using test::TempDir;

double torus_distance_between(Point a, Point b) { return torus_distance(a, b, Domain{}); }

// The 4 x 4 lattice of spacing 1/4, row by row.
std::vector<Point> square_lattice_4x4() {
  std::vector<Point> points;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) points.push_back({0.25 * i, 0.25 * j});
  return points;
}

TEST(VoidOrder, RanksALatticeCoarseFirst) {
  const std::vector<Point> lattice = square_lattice_4x4();
  const std::vector<std::uint32_t> order = void_order(lattice, 0);
  ASSERT_EQ(order.size(), 16u);
  std::vector<std::uint32_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (std::uint32_t i = 0; i < 16; ++i) EXPECT_EQ(sorted[i], i);
  // Nothing is ranked: every energy is 0, so the lowest index goes first; the next is the point
  // farthest from it, (1/2, 1/2); then (1/2, 0) and (0, 1/2), 1/2 from every ranked point (of
  // equal energy: the lower index first). The first 4 are the lattice of spacing 1/2.
  EXPECT_EQ(std::vector<std::uint32_t>(order.begin(), order.begin() + 4), (std::vector<std::uint32_t>{0, 10, 2, 8}));
  for (std::size_t a = 0; a < 4; ++a) {
    double nearest = HUGE_VAL;
    for (std::size_t b = 0; b < 4; ++b)
      if (b != a) nearest = std::min(nearest, torus_distance_between(lattice[order[a]], lattice[order[b]]));
    EXPECT_EQ(nearest, 0.5) << a;
  }
}

TEST(VoidOrder, RanksOnlyThePointsAfterTheRankedOnes) {
  // (0, 0) is ranked. Step 1: (1/2, 1/2) is farthest from it (squared 1/2) and of least energy;
  // (1/2, 0) passes the floor (1/4 >= 0.49 / 2), (0.05, 0) does not. Step 2: (1/2, 0) is 1/2
  // from both ranked points, (0.05, 0) still below 0.7 of that, so it comes last.
  const std::vector<Point> points = {{0.0, 0.0}, {0.05, 0.0}, {0.5, 0.5}, {0.5, 0.0}};
  EXPECT_EQ(void_order(points, 1), (std::vector<std::uint32_t>{2, 3, 1}));
  EXPECT_TRUE(void_order(points, 4).empty());
}

TEST(ProgressiveRanks, StagesHoldAtLeast64PointsAndHalfThePointsBefore) {
  EXPECT_EQ(hierarchy_stages(0, std::vector<std::size_t>(64, 1)), std::vector<std::size_t>{64});
  EXPECT_EQ(hierarchy_stages(0, {256, 256, 512, 1024, 2048}), (std::vector<std::size_t>{1, 1, 1, 1, 1}));
  EXPECT_EQ(hierarchy_stages(0, {30, 30, 30, 30}), (std::vector<std::size_t>{3, 1}));
  // 1, 2, 4, ... : 1 + 1 + 2 + ... + 32 = 64 first, then one level per stage.
  EXPECT_EQ(hierarchy_stages(0, {1, 1, 2, 4, 8, 16, 32, 64, 128}), (std::vector<std::size_t>{7, 1, 1}));
  // On 400 points, levels of 100: two make a stage (200 >= 400 / 2); on the 600 then, three would
  // (300 >= 600 / 2), and the last stage ends with the levels.
  EXPECT_EQ(hierarchy_stages(400, {100, 100, 100, 100, 100}), (std::vector<std::size_t>{2, 3}));
  EXPECT_EQ(hierarchy_stages(400, {100, 100, 100, 100, 100, 100}), (std::vector<std::size_t>{2, 3, 1}));
  EXPECT_EQ(parse_rank_order("voids"), ProgressiveOrder::voids);
  EXPECT_STREQ(rank_order_name(ProgressiveOrder::placement), "placement");
  EXPECT_THROW(parse_rank_order("farthest"), Error);
}

std::vector<PointSet> build_sets(ProgressiveOrder order, std::size_t sets) {
  HierarchyOptions options;
  options.count = 64;
  options.ratio = 2.0;
  options.levels = 5;  // 64, 128, 256, 512, 1024
  options.seed = 1;
  options.rank_order = order;
  return add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(sets), options);
}

// The prefix sweep of docs/RESULTS.md on 1024 points, seeds 1-3 (bluetile_progressive_bench prefixes 1024 3: worst
// LF of the in-between prefixes 0.169-0.196 placement, 0.085-0.102 voids; worst voids rho 0.576).
TEST(ProgressiveRanks, VoidsPrefixesBeatPlacementBetweenBoundaries) {
  const std::vector<PointSet> placement = build_sets(ProgressiveOrder::placement, 3);
  const std::vector<PointSet> voids = build_sets(ProgressiveOrder::voids, 3);
  const std::vector<std::size_t> boundaries = {64, 128, 256, 512, 1024};
  for (std::size_t k : prefix_sweep(1024, boundaries)) {
    const bool boundary = std::find(boundaries.begin(), boundaries.end(), k) != boundaries.end();
    double worst_placement_lf = 0.0, worst_voids_lf = 0.0, worst_voids_rho = HUGE_VAL;
    for (std::size_t s = 0; s < 3; ++s) {
      const std::span<const Point> a(placement[s].points.data(), k), b(voids[s].points.data(), k);
      const TilingMetrics ma = measure_tiling(a, 0, 0), mb = measure_tiling(b, 0, 0);
      if (boundary) {
        // A stage of one level is relaxed as the placement order relaxes it (worst of both orders
        // there: rho 0.594, LF 0.068).
        EXPECT_GT(mb.rho, 0.55) << "boundary " << k << ", seed " << s + 1;
        EXPECT_LT(mb.low_frequency, 0.08) << "boundary " << k << ", seed " << s + 1;
        continue;
      }
      worst_placement_lf = std::max(worst_placement_lf, ma.low_frequency);
      worst_voids_lf = std::max(worst_voids_lf, mb.low_frequency);
      worst_voids_rho = std::min(worst_voids_rho, mb.rho);
    }
    if (boundary) continue;
    EXPECT_LT(worst_voids_lf, 0.7 * worst_placement_lf) << "prefix " << k;
    EXPECT_LT(worst_voids_lf, 0.12) << "prefix " << k;
    EXPECT_GT(worst_voids_rho, 0.55) << "prefix " << k;
  }
  // Levels follow the ranks: 64 points of level 0, then 64 of level 1, ...
  EXPECT_EQ(voids[0].levels[63], 0);
  EXPECT_EQ(voids[0].levels[64], 1);
  EXPECT_EQ(voids[0].levels[1023], 4);
}

// Coarser levels: at ratio 4 a level relaxes three new points for each fixed one, enough to fill
// every hole of the earlier level (a torus Delaunay triangulation of n sites has 2n triangles and
// 3n edges), where ratio 2's n new points must choose half of the 2n holes, so its boundaries
// keep four to seven times the low-frequency power (docs/RESULTS.md, "Coarser levels"). Seeds 1-3
// on 64, 256, 1024 points against ratio 2's same boundaries: ratio 4 LF 0.0079-0.0143, rho
// 0.680-0.738; ratio 2 LF 0.043-0.059, rho 0.594-0.635.
TEST(ProgressiveRanks, RatioFourBoundariesHoldUnderAThirdOfRatioTwosLowFrequencyPower) {
  HierarchyOptions options;
  options.count = 64;
  options.ratio = 4.0;
  options.levels = 3;  // 64, 256, 1024
  options.seed = 1;
  const std::vector<PointSet> coarse =
      add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(3), options);
  const std::vector<PointSet> doubling = build_sets(ProgressiveOrder::voids, 3);
  for (std::size_t k : {std::size_t{256}, std::size_t{1024}}) {
    for (std::size_t s = 0; s < 3; ++s) {
      ASSERT_EQ(coarse[s].points.size(), 1024u);
      EXPECT_EQ(coarse[s].levels[k - 1], k == 256 ? 1 : 2);
      const TilingMetrics a = measure_tiling(std::span<const Point>(coarse[s].points.data(), k), 0, 0);
      const TilingMetrics b = measure_tiling(std::span<const Point>(doubling[s].points.data(), k), 0, 0);
      EXPECT_LT(a.low_frequency, 0.35 * b.low_frequency) << "boundary " << k << ", seed " << s + 1;
      EXPECT_LT(a.low_frequency, 0.02) << "boundary " << k << ", seed " << s + 1;
      EXPECT_GT(a.rho, 0.65) << "boundary " << k << ", seed " << s + 1;
      EXPECT_GT(a.rho, b.rho) << "boundary " << k << ", seed " << s + 1;
    }
  }
}

// One point per level: the placement order relaxes each alone around the fixed others, and the
// first 32 of every set end on the same shifted lattice (every nearest-neighbour distance 1/8 or
// sqrt(2)/8); the voids order relaxes the 64 together, irregularly, differently per seed.
TEST(ProgressiveRanks, OnePointPerLevelIsNoLongerOneLatticeInEverySet) {
  auto first_distances = [](const PointSet& set) {
    std::vector<Point> first(set.points.begin(), set.points.begin() + 32);
    std::vector<double> d;
    for (std::size_t i = 0; i < first.size(); ++i) {
      double best = HUGE_VAL;
      for (std::size_t j = 0; j < first.size(); ++j)
        if (j != i) best = std::min(best, torus_distance_between(first[i], first[j]));
      d.push_back(best);
    }
    std::sort(d.begin(), d.end());
    return d;
  };
  for (ProgressiveOrder order : {ProgressiveOrder::placement, ProgressiveOrder::voids}) {
    HierarchyOptions options;
    options.count = 1;
    options.add = 1;
    options.levels = 64;
    options.seed = 1;
    options.rank_order = order;
    const std::vector<PointSet> sets =
        add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(3), options);
    const std::vector<double> a = first_distances(sets[0]), b = first_distances(sets[1]), c = first_distances(sets[2]);
    if (order == ProgressiveOrder::placement) {
      EXPECT_NEAR(a.front(), 0.125, 1e-6);  // today's defect, kept as the baseline
      EXPECT_NEAR(a.back(), std::sqrt(2.0) / 8.0, 1e-6);
      EXPECT_NEAR(b.front(), a.front(), 1e-6);
      EXPECT_NEAR(c.back(), a.back(), 1e-6);
      continue;
    }
    for (const auto* d : {&a, &b, &c}) EXPECT_GT(d->back() / d->front(), 1.05);  // no lattice
    EXPECT_GT(std::abs(a.front() - b.front()) + std::abs(b.front() - c.front()), 1e-3);  // not the same set
    EXPECT_EQ(sets[0].levels[31], 31);  // every point its own level, in rank order
  }
}

bool same_bits(const PointSet& a, const PointSet& b) {
  if (a.points.size() != b.points.size() || a.levels != b.levels) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i)
    if (a.points[i].x != b.points[i].x || a.points[i].y != b.points[i].y) return false;
  return true;
}

TEST(ProgressiveRanks, VoidsOrderIsTheSameBitsOnEveryThreadCount) {
  ExactEngine engine;
  HierarchyOptions options;
  options.count = 40;
  options.add = 40;
  options.levels = 4;
  options.iterations = 20;
  options.seed = 5;
  options.rank_order = ProgressiveOrder::voids;
  std::vector<PointSet> alone;
  for (std::size_t k = 0; k < 5; ++k) {
    HierarchyOptions single = options;
    single.seed = options.seed + k;
    alone.push_back(add_levels(engine, PointSet{}, single));
  }
  const std::size_t machine_threads = thread_count();
  for (std::size_t threads : {1, 2, 7}) {
    set_thread_count(threads);
    const std::vector<PointSet> built =
        add_levels([] { return std::make_unique<ExactEngine>(); }, std::vector<PointSet>(5), options);
    set_thread_count(machine_threads);
    ASSERT_EQ(built.size(), alone.size());
    for (std::size_t k = 0; k < built.size(); ++k) EXPECT_TRUE(same_bits(built[k], alone[k])) << k << ", " << threads;
  }
}

TEST(ProgressiveRanks, CommandLineVoidsOrderIsTheLibrarys) {
  TempDir dir;
  auto r = run_bluetile({"progressive", "-n", "40", "--add", "40", "--levels", "3", "-k", "20", "--seed", "3",
                         "--engine", "exact", "--rank-order", "voids", "-o", dir.file("v.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExactEngine engine;
  HierarchyOptions options;
  options.count = 40;
  options.add = 40;
  options.levels = 3;
  options.iterations = 20;
  options.seed = 3;
  options.rank_order = ProgressiveOrder::voids;
  EXPECT_TRUE(same_bits(read_point_file(dir.file("v.txt")), add_levels(engine, PointSet{}, options)));
  EXPECT_NE(test::read_text(dir.file("v.txt")).find("rank order voids"), std::string::npos);
  r = run_bluetile({"progressive", "-n", "40", "--rank-order", "farthest", "-o", dir.file("bad.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--rank-order"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.txt")));
}

}  // namespace
}  // namespace bluetile
