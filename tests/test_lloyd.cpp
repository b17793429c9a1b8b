#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "bluetile/relax/lloyd.h"
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

}  // namespace
}  // namespace bluetile
