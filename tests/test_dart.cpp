// Dart throwing: the minimum distance holds on the torus, the count is exact, seeds reproduce.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/sampling/dart_throwing.h"
#include "test_support.h"

namespace bluetile {
namespace {

TEST(DartThrowing, NoTwoPointsCloserThanTheFinalRadius) {
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    DartOptions o;
    o.count = 1500;
    o.seed = seed;
    DartResult r = throw_darts(o);
    ASSERT_EQ(r.points.size(), 1500u);
    double closest = 1.0;
    for (std::size_t i = 0; i < r.points.size(); ++i)
      for (std::size_t j = i + 1; j < r.points.size(); ++j)
        closest = std::min(closest, torus_distance(r.points[i], r.points[j], Domain{}));
    EXPECT_GE(closest, r.final_radius) << "seed " << seed;
    // The radius shrank from the hexagonal spacing to what random throwing can fill
    // (random sequential adsorption jams near 0.75 of it; radius reduction stops earlier).
    EXPECT_DOUBLE_EQ(r.initial_radius, hexagonal_spacing(1500.0));
    EXPECT_LT(r.final_radius, 0.85 * r.initial_radius);
    EXPECT_GT(r.final_radius, 0.5 * r.initial_radius);
    for (const Point& p : r.points) {
      ASSERT_GE(p.x, 0.0);
      ASSERT_LT(p.x, 1.0);
      ASSERT_GE(p.y, 0.0);
      ASSERT_LT(p.y, 1.0);
    }
  }
}

TEST(DartThrowing, StartsAtMostAtHalfTheTorusAndSaysSo) {
  // --start 4 and --start 2 on 10 points gave the same points, while the header reported
  // starting radii of 1.36 and 0.68: both had started at 0.5.
  DartOptions o;
  o.count = 10;
  o.start = 4.0;
  const DartResult four = throw_darts(o);
  o.start = 2.0;
  const DartResult two = throw_darts(o);
  EXPECT_EQ(four.initial_radius, kMaxDartRadius);
  EXPECT_EQ(two.initial_radius, kMaxDartRadius);
  EXPECT_EQ(four.points, two.points);
  o.start = 1.0;
  EXPECT_EQ(throw_darts(o).initial_radius, hexagonal_spacing(10.0));
  test::TempDir dir;
  auto r = test::run_bluetile({"dart", "-n", "10", "--start", "4", "-v", "-o", dir.file("d.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.rfind("bluetile dart: 10 points, seed 1, radius 0.5 (half the torus) -> ", 0), 0u) << r.err;
}

TEST(DartThrowing, ExactCountAndSameSeedSamePoints) {
  DartOptions o;
  o.count = 777;
  o.seed = 42;
  DartResult a = throw_darts(o), b = throw_darts(o);
  EXPECT_EQ(a.points.size(), 777u);
  EXPECT_TRUE(a.points == b.points);
  o.seed = 43;
  EXPECT_FALSE(throw_darts(o).points == a.points);
  o.count = 1;
  EXPECT_EQ(throw_darts(o).points.size(), 1u);
  o.count = 2;
  EXPECT_EQ(throw_darts(o).points.size(), 2u);
}

TEST(DartThrowing, ACancelCheckEndsARun) {
  // A run of 20000 points draws far more than one check's worth of candidates; the check throws
  // at its first call, the run ends with it.
  DartOptions o;
  o.count = 20000;
  std::size_t calls = 0;
  {
    CancelCheck check([&] {
      ++calls;
      throw std::runtime_error("cancelled");
    });
    EXPECT_THROW(throw_darts(o), std::runtime_error);
  }
  EXPECT_EQ(calls, 1u);
  // Checked but not cancelled: the same points as without a check.
  const std::vector<Point> unchecked = throw_darts(o).points;
  CancelCheck count_only([&] { ++calls; });
  EXPECT_EQ(throw_darts(o).points, unchecked);
  EXPECT_GT(calls, 10u);
}

TEST(DartThrowing, RejectsBadOptions) {
  DartOptions o;
  EXPECT_THROW(throw_darts(o), Error);  // count 0
  o.count = 10;
  o.shrink = 1.0;
  EXPECT_THROW(throw_darts(o), Error);
  o.shrink = 0.9;
  o.max_failures = 0;
  EXPECT_THROW(throw_darts(o), Error);
}

TEST(DartCommand, SameSeedSameFile) {
  test::TempDir dir;
  auto r1 = test::run_bluetile({"dart", "--count", "500", "--seed", "7", "--output", dir.file("a.txt")});
  auto r2 = test::run_bluetile({"dart", "--count", "500", "--seed", "7", "--output", dir.file("b.txt")});
  ASSERT_EQ(r1.exit_code, 0) << r1.err;
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  std::string a = test::read_text(dir.file("a.txt"));
  EXPECT_EQ(a, test::read_text(dir.file("b.txt")));
  PointSet set = read_point_file(dir.file("a.txt"));
  EXPECT_EQ(set.points.size(), 500u);
  auto bad = test::run_bluetile({"dart", "--count", "0", "--output", dir.file("c.txt")});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(dir.file("c.txt")));
}

}  // namespace
}  // namespace bluetile
