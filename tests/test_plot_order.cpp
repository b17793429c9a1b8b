// The pen-plotter order of dots (sampling/plot_order.h) against hand-made paths, brute force and
// the Beardwood-Halton-Hammersley constant of random tours.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/sampling/plot_order.h"
#include "test_support.h"

namespace bluetile {
namespace {

bool is_permutation_of_all(const std::vector<std::size_t>& order, std::size_t n) {
  std::vector<std::size_t> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<std::size_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  return sorted == all;
}

TEST(PlotOrder, EveryDotOnceAndTheTravelIsThePathsLength) {
  for (std::size_t n : {0, 1, 2, 3, 5, 100, 3000}) {
    const std::vector<Point> dots = test::uniform_points(n, 7 + n);
    const PlotOrder plot = plot_order(dots);
    ASSERT_TRUE(is_permutation_of_all(plot.order, n)) << n << " dots";
    EXPECT_DOUBLE_EQ(plot.travel, path_length(dots, plot.order));
    EXPECT_LE(plot.travel, plot.greedy_travel + 1e-12) << "2-opt never lengthens the path";
  }
}

TEST(PlotOrder, HardCasesCoincidentCollinearAndOneColumn) {
  // All on one spot: nothing to travel.
  const std::vector<Point> same(50, Point{0.25, 0.75});
  PlotOrder plot = plot_order(same);
  ASSERT_TRUE(is_permutation_of_all(plot.order, same.size()));
  EXPECT_EQ(plot.travel, 0.0);
  // Shuffled dots of a line (a zero-height bounding box): the shortest path walks it end to end.
  std::vector<Point> line;
  Rng rng(3);
  for (int i = 0; i < 400; ++i) line.push_back({rng.uniform(), 0.5});
  const double span = std::max_element(line.begin(), line.end(), [](Point a, Point b) { return a.x < b.x; })->x -
                      std::min_element(line.begin(), line.end(), [](Point a, Point b) { return a.x < b.x; })->x;
  plot = plot_order(line);
  ASSERT_TRUE(is_permutation_of_all(plot.order, line.size()));
  EXPECT_NEAR(plot.travel, span, 1e-12);
  // A 30 x 30 lattice of spacing 1: a serpentine path is 899 long, and no open path through 900
  // dots is shorter than 899.
  std::vector<Point> lattice;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 30; ++i) lattice.push_back({static_cast<double>(i), static_cast<double>(j)});
  plot = plot_order(lattice);
  EXPECT_GE(plot.travel, 899.0 - 1e-9);
  EXPECT_LE(plot.travel, 899.0 * 1.08) << "greedy " << plot.greedy_travel;
  // Not finite: refused.
  EXPECT_THROW(plot_order(std::vector<Point>{{0.0, 0.0}, {NAN, 1.0}}), Error);
}

// Against the shortest open path of 8 dots, by brute force over every order.
TEST(PlotOrder, NearTheShortestPathOfSmallSets) {
  double worst = 1.0;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const std::vector<Point> dots = test::uniform_points(8, seed);
    std::vector<std::size_t> order(dots.size());
    std::iota(order.begin(), order.end(), 0);
    double shortest = INFINITY;
    do shortest = std::min(shortest, path_length(dots, order));
    while (std::next_permutation(order.begin(), order.end()));
    const PlotOrder plot = plot_order(dots);
    EXPECT_GE(plot.travel, shortest - 1e-12);
    worst = std::max(worst, plot.travel / shortest);
  }
  EXPECT_LE(worst, 1.25) << "2-opt should stay within 25 % of the optimum on 8 dots";
}

// The shortest tour through N uniform points of the unit square is about 0.7124 sqrt(N)
// (Beardwood, Halton, Hammersley 1959; the constant from Applegate et al. 2006): 2-opt with
// neighbour lists gets within about 5-10 % of it; greedy nearest neighbour about 25 % above.
TEST(PlotOrder, RandomDotsWithinTenPercentOfTheRandomTourConstant) {
  const std::size_t n = 20000;
  const std::vector<Point> dots = test::uniform_points(n, 99);
  const PlotOrder plot = plot_order(dots);
  const double expected = 0.7124 * std::sqrt(static_cast<double>(n));
  EXPECT_LT(plot.travel, 1.10 * expected) << "greedy " << plot.greedy_travel;
  EXPECT_GT(plot.greedy_travel, 1.10 * plot.travel) << "2-opt should gain over greedy";
  // The same dots give the same order.
  EXPECT_EQ(plot_order(dots).order, plot.order);
}

}  // namespace
}  // namespace bluetile
