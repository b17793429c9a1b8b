// The k-d tree cell search (voronoi/site_tree.h) and the exact engine on sites far from uniform
// (sites on a line once took about N^3 time): cells against an independent
// brute-force clipper, and the work per cell bounded whatever N.
#include <gtest/gtest.h>

#include <cmath>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/site_tree.h"
#include "test_support.h"

namespace bluetile {
namespace {

// Area and centroid offset of the periodic cell of site i, clipped by all sites and their 25
// nearest copies (5 x 5 periods: enough for cells up to a period across), without any search.
struct Reference {
  double area = 0.0;
  Point centroid_offset;
};

Reference brute_force(const std::vector<Point>& sites, std::size_t i, Domain domain) {
  ConvexPolygon cell;
  cell.reset_rectangle(-0.5 * domain.size, 0.5 * domain.size);
  for (std::size_t j = 0; j < sites.size(); ++j)
    for (int kx = -2; kx <= 2; ++kx)
      for (int ky = -2; ky <= 2; ++ky) {
        const Point d = sites[j] + Point{kx, ky} * domain.size - sites[i];
        if (d != Point{0.0, 0.0}) cell.clip_by_bisector(d, static_cast<std::uint32_t>(j));
      }
  PolygonMoments m = cell.moments();
  return {m.area(), m.centroid()};
}

// The tree's cell of every site against the brute force; returns the mean number of sites the
// tree visited per cell.
double expect_tree_matches(const std::vector<Point>& sites, Domain domain, double tolerance) {
  SiteTree tree(sites, domain, true);
  SiteTree::Search search;
  double area = 0.0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    ConvexPolygon cell;
    cell.reset_rectangle(-0.5 * domain.size, 0.5 * domain.size);
    EXPECT_TRUE(tree.clip_cell(static_cast<std::uint32_t>(i), sites[i], cell, search));
    const PolygonMoments m = cell.moments();
    const Reference ref = brute_force(sites, i, domain);
    EXPECT_NEAR(m.area(), ref.area, tolerance) << "site " << i;
    EXPECT_NEAR(m.centroid().x, ref.centroid_offset.x, tolerance) << "site " << i;
    EXPECT_NEAR(m.centroid().y, ref.centroid_offset.y, tolerance) << "site " << i;
    area += m.area();
  }
  EXPECT_NEAR(area, domain.area(), 1e-12 * domain.area());
  return static_cast<double>(search.sites_visited) / static_cast<double>(sites.size());
}

TEST(SiteTree, CellsMatchBruteForce) {
  Rng rng(5);
  // Uniform sites, a rectangular domain, a horizontal and a diagonal line, nearly a line.
  expect_tree_matches(test::uniform_points(200, 1), Domain{}, 1e-12);
  std::vector<Point> sites = test::uniform_points(150, 2);
  for (Point& p : sites) p *= Point{2.0, 0.5};
  expect_tree_matches(sites, Domain{{2.0, 0.5}}, 1e-12);
  std::vector<Point> line, diagonal, nearly;
  for (int i = 0; i < 200; ++i) {
    const double t = rng.uniform();
    line.push_back({t, 0.5});
    diagonal.push_back({t, wrap_coordinate(t + 0.25, 1.0)});
    nearly.push_back({t, 0.5 + 1e-9 * (rng.uniform() - 0.5)});
  }
  expect_tree_matches(line, Domain{}, 1e-12);
  expect_tree_matches(diagonal, Domain{}, 1e-12);
  expect_tree_matches(nearly, Domain{}, 1e-12);
}

TEST(SiteTree, CoincidentSitesAreReported) {
  std::vector<Point> sites = {{0.5, 0.5}, {0.25, 0.5}, {0.5, 0.5}, {0.75, 0.5}};
  SiteTree tree(sites, Domain{}, true);
  SiteTree::Search search;
  ConvexPolygon cell;
  cell.reset_rectangle({-0.5, -0.5}, {0.5, 0.5});
  EXPECT_TRUE(tree.clip_cell(0, sites[0], cell, search));  // the lower index owns the cell
  cell.reset_rectangle({-0.5, -0.5}, {0.5, 0.5});
  EXPECT_FALSE(tree.clip_cell(2, sites[2], cell, search));
}

TEST(SiteTree, WorkPerCellOnALineDoesNotGrowWithN) {
  // A strip cell meets O(1) leaves: the sites visited per cell stay flat from 1000 to 16000
  // sites (the grid search visited O(N) buckets and sites per cell here).
  for (std::size_t n : {1000, 16000}) {
    Rng rng(n);
    std::vector<Point> line;
    for (std::size_t i = 0; i < n; ++i) line.push_back({rng.uniform(), 0.5});
    SiteTree tree(line, Domain{}, true);
    SiteTree::Search search;
    ConvexPolygon cell;
    for (std::size_t i = 0; i < n; ++i) {
      cell.reset_rectangle({-0.5, -0.5}, {0.5, 0.5});
      tree.clip_cell(static_cast<std::uint32_t>(i), line[i], cell, search);
    }
    const double per_cell = static_cast<double>(search.sites_visited) / static_cast<double>(n);
    EXPECT_LT(per_cell, 60.0) << n << " sites";
  }
}

TEST(ExactEngine, SitesOnALineAndInAClusterMatchBruteForce) {
  // The engine takes the tree for these (crowded buckets); its cells must be the true ones.
  Rng rng(9);
  std::vector<Point> line, cluster;
  for (int i = 0; i < 300; ++i) {
    line.push_back({rng.uniform(), 0.25});
    cluster.push_back(wrap_point({0.999 + 0.002 * rng.uniform(), 0.999 + 0.002 * rng.uniform()}, Domain{}));
  }
  for (const auto& sites : {line, cluster}) {
    SceneCells cells = ExactEngine().compute(make_scene(sites));
    for (std::size_t i = 0; i < sites.size(); ++i) {
      const Reference ref = brute_force(sites, i, Domain{});
      EXPECT_NEAR(cells.cells[i].area, ref.area, 1e-12) << i;
      EXPECT_LT(torus_distance(cells.cells[i].centroid, wrap_point(sites[i] + ref.centroid_offset, Domain{}), Domain{}),
                1e-12)
          << i;
    }
  }
}

}  // namespace
}  // namespace bluetile
