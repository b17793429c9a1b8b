// The exact engine against hand-computed cells and an independent brute-force clipper.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>

#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "test_support.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

using test::uniform_points;

// Independent reference: the cell of site i clipped by every other site's 9 nearest periodic
// copies (and the site's own 8 copies), with no grid and no early stop. Valid when the cell
// is smaller than a period, which holds for N >= 3 random sites on the unit torus in practice
// and is checked by comparing total area.
struct ReferenceCell {
  double area = 0.0;
  Point centroid;
};

ReferenceCell brute_force_cell(const std::vector<Point>& sites, std::size_t i, Domain domain = {}) {
  const Point h = 1.5 * domain.size;
  std::vector<Point> poly = {{-h.x, -h.y}, {h.x, -h.y}, {h.x, h.y}, {-h.x, h.y}};
  for (std::size_t j = 0; j < sites.size(); ++j) {
    for (int sx = -1; sx <= 1; ++sx) {
      for (int sy = -1; sy <= 1; ++sy) {
        Point d = sites[j] + Point{sx, sy} * domain.size - sites[i];
        if (d.x == 0.0 && d.y == 0.0) continue;
        std::vector<Point> out;
        for (std::size_t k = 0; k < poly.size(); ++k) {
          Point a = poly[k], b = poly[(k + 1) % poly.size()];
          double fa = glm::dot(a, d) - 0.5 * glm::dot(d, d);
          double fb = glm::dot(b, d) - 0.5 * glm::dot(d, d);
          if (fa <= 0) out.push_back(a);
          if ((fa < 0) != (fb < 0) && fa != 0 && fb != 0) out.push_back(a + (b - a) * (fa / (fa - fb)));
        }
        poly = out;
      }
    }
  }
  ReferenceCell cell;
  double cx = 0, cy = 0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    Point a = poly[k], b = poly[(k + 1) % poly.size()];
    double cross = a.x * b.y - b.x * a.y;
    cell.area += 0.5 * cross;
    cx += (a.x + b.x) * cross;
    cy += (a.y + b.y) * cross;
  }
  cell.centroid = wrap_point(sites[i] + Point{cx, cy} / (6.0 * cell.area), domain);
  return cell;
}

void expect_matches_brute_force(const std::vector<Point>& sites, double tolerance, Domain domain = {}) {
  SceneCells result = ExactEngine().compute(make_scene(sites, domain));
  double total = 0.0;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    ReferenceCell ref = brute_force_cell(sites, i, domain);
    const Cell& cell = result.cells[i];
    EXPECT_NEAR(cell.area, ref.area, tolerance) << "site " << i;
    Point d = torus_offset(cell.centroid, ref.centroid, domain);
    EXPECT_NEAR(d.x, 0.0, tolerance) << "site " << i;
    EXPECT_NEAR(d.y, 0.0, tolerance) << "site " << i;
    total += cell.area;
  }
  EXPECT_NEAR(total, domain.area(), 1e-12 * domain.area());
}

double total_area(const SceneCells& cells) {
  double sum = 0.0;
  for (const Cell& c : cells.cells) sum += c.area;
  return sum;
}

TEST(ExactEngine, OneSiteOwnsTheWholeTorus) {
  for (Point site : {Point{0.3, 0.7}, Point{0.0, 0.0}, Point{std::nextafter(1.0, 0.0), 0.5}}) {
    SceneCells r = ExactEngine().compute(make_scene({site}));
    ASSERT_EQ(r.cells.size(), 1u);
    EXPECT_DOUBLE_EQ(r.cells[0].area, 1.0);
    EXPECT_EQ(r.cells[0].centroid, site);
    EXPECT_NEAR(r.cells[0].second_moment, 1.0 / 6.0, 1e-15);  // unit square about its centre
  }
}

TEST(ExactEngine, TwoSitesInRowsAreStrips) {
  SceneCells r = ExactEngine().compute(make_scene({{0.25, 0.5}, {0.75, 0.5}}));
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(r.cells[i].area, 0.5, 1e-15);
    EXPECT_NEAR(r.cells[i].second_moment, (0.5 * 0.5 * 0.5 + 0.5) / 12.0, 1e-15);  // 0.5 x 1 strip
  }
  EXPECT_EQ(r.cells[0].centroid, Point(0.25, 0.5));
  EXPECT_EQ(r.cells[1].centroid, Point(0.75, 0.5));
}

TEST(ExactEngine, CheckerboardPairGivesDiamonds) {
  // (0,0) and (1/2,1/2): a centred square lattice, cells are squares turned 45 degrees.
  Scene scene = make_scene({{0.0, 0.0}, {0.5, 0.5}});
  SceneCells r = ExactEngine().compute(scene);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(r.cells[i].area, 0.5, 1e-15);
    EXPECT_NEAR(torus_distance(r.cells[i].centroid, scene.sites[i], scene.domain), 0.0, 1e-15);
  }
  EXPECT_EQ(exact_cell_polygon(scene, 0).size(), 4u);
}

TEST(ExactEngine, PairOneTenMillionthApart) {
  // The cells are strips of width 1/2 bounded by x = 0.5 + 0.5e-7 and its copy half a period away.
  const double gap = 1e-7;
  SceneCells r = ExactEngine().compute(make_scene({{0.5, 0.5}, {0.5 + gap, 0.5}}));
  EXPECT_NEAR(r.cells[0].area, 0.5, 1e-15);
  EXPECT_NEAR(r.cells[1].area, 0.5, 1e-15);
  EXPECT_NEAR(r.cells[0].centroid.x, 0.25 + 0.5 * gap, 1e-15);
  EXPECT_NEAR(r.cells[1].centroid.x, 0.75 + 0.5 * gap, 1e-15);
  EXPECT_NEAR(r.cells[0].centroid.y, 0.5, 1e-15);
}

TEST(ExactEngine, FourSymmetricSites) {
  SceneCells r = ExactEngine().compute(make_scene({{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}}));
  for (const Cell& c : r.cells) {
    EXPECT_NEAR(c.area, 0.25, 1e-15);
    EXPECT_NEAR(c.second_moment, std::pow(0.5, 4) / 6.0, 1e-16);
  }
  EXPECT_EQ(r.cells[3].centroid, Point(0.75, 0.75));
}

// A k x k square lattice: every cell is a square (co-circular ties at every vertex).
std::vector<Point> square_lattice(int k, double offset) {
  std::vector<Point> sites;
  for (int y = 0; y < k; ++y)
    for (int x = 0; x < k; ++x) sites.push_back({(x + offset) / k, (y + offset) / k});
  return sites;
}

TEST(ExactEngine, SquareLatticeIsAFixedPoint) {
  for (double offset : {0.5, 0.0}) {  // offset 0 puts sites exactly on the border
    const int k = 16;
    Scene scene = make_scene(square_lattice(k, offset));
    SceneCells r = ExactEngine().compute(scene);
    for (std::size_t i = 0; i < scene.sites.size(); ++i) {
      EXPECT_NEAR(r.cells[i].area, 1.0 / (k * k), 1e-15);
      EXPECT_NEAR(r.cells[i].second_moment, std::pow(1.0 / k, 4) / 6.0, 1e-18);
      EXPECT_LT(torus_distance(r.cells[i].centroid, scene.sites[i], scene.domain), 1e-15) << i;
    }
    EXPECT_NEAR(total_area(r), 1.0, 1e-12);
  }
}

TEST(ExactEngine, HexagonalLatticeIsAFixedPoint) {
  // A true hexagonal lattice fits a W x H torus with H/W = sqrt(3)/2 * rows/columns.
  const int columns = 10, rows = 10;
  Domain domain{{1.0, std::sqrt(3.0) / 2.0}};
  std::vector<Point> sites;
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < columns; ++x)
      sites.push_back({(x + 0.5 * (y % 2)) / columns, y * domain.size.y / rows});
  Scene scene = make_scene(sites, domain);
  SceneCells r = ExactEngine().compute(scene);
  const double cell_area = domain.area() / static_cast<double>(sites.size());
  // Hexagon: integral of |x|^2 = (5 / (18 sqrt 3)) * area^2.
  const double hexagon_moment = 5.0 / (18.0 * std::sqrt(3.0)) * cell_area * cell_area;
  for (std::size_t i = 0; i < sites.size(); ++i) {
    EXPECT_NEAR(r.cells[i].area, cell_area, 1e-15);
    EXPECT_NEAR(r.cells[i].second_moment, hexagon_moment, 1e-17);
    EXPECT_LT(torus_distance(r.cells[i].centroid, sites[i], domain), 1e-15);
  }
  EXPECT_EQ(exact_cell_polygon(scene, 37).size(), 6u);
  EXPECT_EQ(exact_cell_neighbours(scene, 37).size(), 6u);
}

TEST(ExactEngine, MatchesBruteForceOnRandomSets) {
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    std::size_t n = 3 + seed * 3;
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_matches_brute_force(uniform_points(n, seed), 1e-12);
  }
}

TEST(ExactEngine, MatchesBruteForceOnNonSquareDomains) {
  // Rectangular periodic domains had no independent reference.
  for (Domain domain : {Domain{{2.0, 0.5}}, Domain{{0.25, 3.0}}, Domain{{1.0, 0.1}}, Domain{{7.0, 3.0}}}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      std::vector<Point> sites = uniform_points(150, seed + 40);
      for (Point& p : sites) p *= domain.size;
      SCOPED_TRACE("domain " + std::to_string(domain.size.x) + " x " + std::to_string(domain.size.y));
      expect_matches_brute_force(sites, 1e-12 * domain.area(), domain);
    }
  }
}

TEST(ExactEngine, ClusterStraddlingTheCornerMatchesBruteForce) {
  // 60 sites within 0.01 of the corner (0,0): the cluster is split over all four corners.
  Rng rng(11);
  std::vector<Point> sites;
  for (int i = 0; i < 60; ++i)
    sites.push_back(wrap_point({(rng.uniform() - 0.5) * 0.02, (rng.uniform() - 0.5) * 0.02}, Domain{}));
  expect_matches_brute_force(sites, 1e-12);
}

TEST(ExactEngine, TranslationOnTheTorusMovesCentroidsAlong) {
  // A cluster across the border and the same cluster moved into the middle must agree.
  Rng rng(5);
  std::vector<Point> sites, moved;
  for (int i = 0; i < 200; ++i) {
    Point p{(rng.uniform() - 0.5) * 0.05, (rng.uniform() - 0.5) * 0.05};
    sites.push_back(wrap_point(p, Domain{}));
    moved.push_back(p + Point{0.5, 0.5});
  }
  SceneCells a = ExactEngine().compute(make_scene(sites));
  SceneCells b = ExactEngine().compute(make_scene(moved));
  for (std::size_t i = 0; i < sites.size(); ++i) {
    EXPECT_NEAR(a.cells[i].area, b.cells[i].area, 1e-13);
    Point d = torus_offset(a.cells[i].centroid + Point{0.5, 0.5}, b.cells[i].centroid, Domain{});
    EXPECT_LT(std::hypot(d.x, d.y), 1e-12) << i;
  }
}

TEST(ExactEngine, SitesOnTheBorder) {
  const double below_one = std::nextafter(1.0, 0.0);
  std::vector<Point> sites = {{0.0, 0.0},       {below_one, 0.5}, {0.5, below_one}, {below_one, below_one},
                              {0.0, 0.3},       {0.3, 0.0},       {0.6, 0.6},       {0.2, 0.8}};
  expect_matches_brute_force(sites, 1e-12);
}

TEST(ExactEngine, CoincidentSitesAreReportedNotCrashedOn) {
  std::vector<Point> sites = {{0.2, 0.2}, {0.7, 0.4}, {0.2, 0.2}, {0.4, 0.9}, {0.2, 0.2}};
  SceneCells r = ExactEngine().compute(make_scene(sites));
  EXPECT_EQ(r.coincident_count, 2u);
  EXPECT_EQ(r.cells[0].status, CellStatus::ok);
  EXPECT_GT(r.cells[0].area, 0.0);
  for (int i : {2, 4}) {
    EXPECT_EQ(r.cells[i].status, CellStatus::coincident);
    EXPECT_EQ(r.cells[i].area, 0.0);
    EXPECT_EQ(r.cells[i].centroid, sites[i]);
  }
  EXPECT_NEAR(total_area(r), 1.0, 1e-14);
  // The owner's cell is the cell it would have without its twins.
  SceneCells alone = ExactEngine().compute(make_scene({{0.2, 0.2}, {0.7, 0.4}, {0.4, 0.9}}));
  EXPECT_EQ(r.cells[0].area, alone.cells[0].area);
}

TEST(ExactEngine, AreasSumToOne) {
  for (std::size_t n : {10u, 1000u, 100000u}) {
    SceneCells r = ExactEngine().compute(make_scene(uniform_points(n, n)));
    EXPECT_NEAR(total_area(r), 1.0, 1e-12) << n;
    for (const Cell& c : r.cells) ASSERT_GT(c.area, 0.0);
  }
}

TEST(ExactEngine, OnlyWantedSitesAreMeasuredAndFixedOnesShapeThem) {
  std::vector<Point> sites = uniform_points(300, 9);
  SceneCells all = ExactEngine().compute(make_scene(sites));
  Scene partial = make_scene(sites);
  partial.wanted_begin = 100;
  partial.wanted_end = 250;
  SceneCells some = ExactEngine().compute(partial);
  ASSERT_EQ(some.cells.size(), 150u);
  for (std::size_t i = 0; i < 150; ++i) {
    EXPECT_EQ(some.cells[i].area, all.cells[100 + i].area);
    EXPECT_EQ(some.cells[i].centroid, all.cells[100 + i].centroid);
  }
}

TEST(ExactEngine, RectangularDomain) {
  Domain domain{{2.0, 0.5}};
  Rng rng(4);
  std::vector<Point> sites(500);
  for (Point& p : sites) p = rng.point(domain);
  SceneCells r = ExactEngine().compute(make_scene(sites, domain));
  EXPECT_NEAR(total_area(r), 1.0, 1e-12);
  for (const Cell& c : r.cells) {
    ASSERT_GE(c.centroid.x, 0.0);
    ASSERT_LT(c.centroid.x, 2.0);
    ASSERT_LT(c.centroid.y, 0.5);
  }
}

TEST(ExactEngine, BatchEqualsOneByOne) {
  std::vector<Scene> scenes;
  for (std::uint64_t s = 0; s < 40; ++s) scenes.push_back(make_scene(uniform_points(20 + s * 150, s)));
  std::vector<SceneCells> batch(scenes.size());
  ExactEngine engine;
  engine.compute(scenes, batch);
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    EXPECT_TRUE(test::identical_cells(engine.compute(scenes[k]), batch[k])) << "scene " << k;
  }
}

TEST(ExactEngine, BitIdenticalWhateverTheThreadCount) {
  Scene scene = make_scene(uniform_points(50000, 3));
  std::size_t before = thread_count();
  set_thread_count(1);
  SceneCells one = ExactEngine().compute(scene);
  set_thread_count(2);
  SceneCells two = ExactEngine().compute(scene);
  set_thread_count(7);
  SceneCells seven = ExactEngine().compute(scene);
  set_thread_count(before);
  EXPECT_TRUE(test::identical_cells(one, two));
  EXPECT_TRUE(test::identical_cells(one, seven));
}

}  // namespace
}  // namespace bluetile
