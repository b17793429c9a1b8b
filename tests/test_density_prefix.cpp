// The prefix-table integration of weighted cells (density_prefix.h) against the texel-cut one it
// replaced in the exact engine (density_moments, density_moments.h), kept as the reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/density_prefix.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

std::shared_ptr<DensityGrid> random_density(int width, int height, std::uint64_t seed, double zero_fraction = 0.0) {
  Rng rng(seed);
  auto grid = std::make_shared<DensityGrid>(width, height);
  for (float& t : grid->texels) t = rng.uniform() < zero_fraction ? 0.0f : static_cast<float>(rng.uniform());
  grid->texels[0] = 0.5f;  // never all zero
  return grid;
}

Scene random_scene(const Domain& domain, std::size_t count, Boundary boundary, std::shared_ptr<DensityGrid> density,
                   std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> sites(count);
  for (Point& p : sites) p = rng.point(domain);
  Scene scene = make_scene(std::move(sites), domain);
  scene.boundary = boundary;
  scene.density = std::move(density);
  return scene;
}

// Mass and second moment within `tolerance` relative; the first moment within `tolerance` of
// mass times the polygon's radius (it may be near zero).
void expect_agree(const std::vector<Point>& polygon, Point origin, const DensityGrid& grid, const DensityPrefix& prefix,
                  Point size, bool periodic, double tolerance, const std::string& what) {
  const WeightedMoments ref = density_moments(polygon, origin, grid, size, periodic);
  const WeightedMoments got = prefix.moments(polygon, origin, size, periodic);
  double radius = 0.0;
  for (const Point& p : polygon) radius = std::max(radius, std::hypot(p.x, p.y));
  EXPECT_NEAR(got.mass, ref.mass, tolerance * std::abs(ref.mass)) << what;
  EXPECT_NEAR(got.first.x, ref.first.x, tolerance * std::abs(ref.mass) * radius) << what;
  EXPECT_NEAR(got.first.y, ref.first.y, tolerance * std::abs(ref.mass) * radius) << what;
  EXPECT_NEAR(got.second, ref.second, tolerance * std::abs(ref.second)) << what;
  if (ref.mass > 0.0) {
    const Point c = got.first / got.mass, r = ref.first / ref.mass;
    EXPECT_NEAR(c.x, r.x, tolerance * radius) << what;
    EXPECT_NEAR(c.y, r.y, tolerance * radius) << what;
  }
}

TEST(DensityPrefix, RandomCellsAgreeWithTexelCutting) {
  // Cells of random scenes over random grids (some texels zero), periodic (cells reaching
  // across the torus' edges) and bounded (cells ending at the border), cells from less than a
  // texel to dozens of texels wide, grid widths that are and are not whole blocks.
  int cells = 0;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      const Domain domain = seed % 2 ? Domain{} : Domain{{1.0, 0.75}};
      const int width = 5 + static_cast<int>(seed * seed) * 9, height = 3 + static_cast<int>(seed * seed) * 7;
      auto grid = random_density(width, height, seed, seed % 3 == 0 ? 0.3 : 0.0);
      const DensityPrefix prefix(*grid);
      for (std::size_t count : {3u, 40u, 400u}) {
        const Scene scene = random_scene(domain, count, boundary, grid, seed * 1000 + count);
        const auto polygons = exact_cell_polygons(scene);
        for (std::size_t i = 0; i < polygons.size(); ++i) {
          expect_agree(polygons[i], scene.sites[i], *grid, prefix, domain.size, scene.periodic(), 1e-12,
                       "seed " + std::to_string(seed) + " count " + std::to_string(count) + " site " + std::to_string(i));
          ++cells;
        }
      }
    }
  }
  EXPECT_GT(cells, 7000);
}

TEST(DensityPrefix, HardCases) {
  auto grid = random_density(24, 16, 7, 0.2);
  const DensityPrefix prefix(*grid);
  const Point size{1.0, 1.0};
  const double tx = 1.0 / 24, ty = 1.0 / 16;
  auto check = [&](std::vector<Point> polygon, Point origin, const std::string& what) {
    for (bool periodic : {false, true}) expect_agree(polygon, origin, *grid, prefix, size, periodic, 1e-12, what);
  };
  // A rectangle whose edges lie on texel lines (vertical and horizontal edges), 10 x 5 texels.
  {
    const Point o{7 * tx, 3 * ty};
    check({{0, 0}, {10 * tx, 0}, {10 * tx, 5 * ty}, {0, 5 * ty}}, o, "texel-aligned rectangle");
  }
  // Exactly one texel, and a piece of one texel.
  check({{0, 0}, {tx, 0}, {tx, ty}, {0, ty}}, {5 * tx, 9 * ty}, "one texel");
  check({{-0.3 * tx, -0.2 * ty}, {0.4 * tx, -0.1 * ty}, {0.1 * tx, 0.3 * ty}}, {11.5 * tx, 4.5 * ty}, "inside one texel");
  // Vertices on texel corners, a diagonal through texel corners.
  check({{0, 0}, {6 * tx, 6 * ty}, {-2 * tx, 4 * ty}}, {3 * tx, 2 * ty}, "vertices on texel corners");
  // Nearly vertical and nearly horizontal edges, crossing many rows or columns.
  check({{0, 0}, {1e-9, 9 * ty}, {-5 * tx, 9 * ty + 1e-9}}, {12 * tx, 3 * ty}, "near-vertical edge");
  check({{0, 0}, {19 * tx, 1e-9}, {19 * tx, 2.5 * ty}}, {2.5 * tx, 6.2 * ty}, "near-horizontal edge");
  // The whole map (bounded), and the whole period around a site (periodic).
  expect_agree({{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {0, 0}, *grid, prefix, size, false, 1e-12, "whole map");
  expect_agree({{-0.5, -0.5}, {0.5, -0.5}, {0.5, 0.5}, {-0.5, 0.5}}, {0.3, 0.7}, *grid, prefix, size, true, 1e-12,
               "whole period");
  // The bounded domain's border: a polygon touching the right and top edges exactly.
  expect_agree({{0, 0}, {0.3, 0}, {0.3, 0.25}, {-0.1, 0.25}}, {0.7, 0.75}, *grid, prefix, size, false, 1e-12,
               "right and top border");
}

TEST(DensityPrefix, BoxesEitherSideOfTheScanWidth) {
  // Up to 64 texels wide a cell's rows are summed once per cell; wider, each row's sides take
  // their own reference column: both against the reference, at widths around the switch, with
  // slanted edges (several pieces per row and side at the vertices) and across a periodic edge.
  auto grid = random_density(200, 50, 11, 0.1);
  const DensityPrefix prefix(*grid);
  const Point size{1.0, 0.25};
  const double tx = size.x / 200, ty = size.y / 50;
  for (double columns : {62.7, 63.5, 64.0, 64.6, 65.3, 90.2}) {
    const double w = columns * tx;
    const std::vector<Point> hexagon = {{-0.5 * w, -3.3 * ty}, {0.1 * w, -7.1 * ty}, {0.5 * w, -1.2 * ty},
                                        {0.45 * w, 4.4 * ty},  {-0.2 * w, 6.9 * ty}, {-0.48 * w, 2.0 * ty}};
    for (Point origin : {Point{0.5, 0.11}, Point{0.03, 0.2}}) {
      const std::string what = "hexagon " + std::to_string(columns) + " texels wide at x " + std::to_string(origin.x);
      expect_agree(hexagon, origin, *grid, prefix, size, true, 1e-12, what + ", periodic");
      if (origin.x > 0.5 * w) expect_agree(hexagon, origin, *grid, prefix, size, false, 1e-12, what + ", bounded");
    }
  }
}

TEST(DensityPrefix, CellsOfManyPiecesAndWidePieces) {
  // The narrow pieces are integrated in chunks of 64 whose lane sums run on: tall boxes (up to
  // 64 columns, a few hundred rows, some hundreds of pieces, odd and even counts) and long
  // nearly horizontal edges (pieces across many column lines, integrated texel by texel), across
  // the periodic edges and against the bounded border, all against the reference.
  auto grid = random_density(300, 700, 13, 0.1);
  const DensityPrefix prefix(*grid);
  const Point size{1.0, 1.0};
  const double tx = size.x / 300, ty = size.y / 700;
  for (double rows : {40.3, 161.7, 333.0}) {
    for (double columns : {3.4, 20.5, 63.2}) {
      const double w = columns * tx, h = rows * ty;
      const std::vector<Point> cell = {{-0.5 * w, -0.45 * h}, {0.3 * w, -0.5 * h}, {0.5 * w, 0.1 * h},
                                       {0.1 * w, 0.5 * h},    {-0.45 * w, 0.3 * h}};
      for (Point origin : {Point{0.5, 0.5}, Point{0.01, 0.98}}) {
        const std::string what = std::to_string(columns) + " x " + std::to_string(rows) + " texels at x " +
                                 std::to_string(origin.x);
        expect_agree(cell, origin, *grid, prefix, size, true, 1e-12, what + ", periodic");
        if (origin.x > 0.5 * w) expect_agree(cell, origin, *grid, prefix, size, false, 1e-12, what + ", bounded");
      }
    }
  }
  // Nearly horizontal edges crossing 40 to 200 columns in a row or two.
  for (double columns : {40.0, 200.0}) {
    const double w = columns * tx;
    expect_agree({{-0.5 * w, 0.0}, {0.5 * w, 0.7 * ty}, {0.1 * w, 1.9 * ty}}, {0.6, 0.3}, *grid, prefix, size, true,
                 1e-12, "long flat triangle " + std::to_string(columns));
  }
}

TEST(DensityPrefix, HandComputedSquare) {
  // The square [0.25, 0.75]^2 over a 4 x 4 grid: the four middle texels exactly.
  DensityGrid grid(4, 4, 100.0f);  // the outer texels must not leak in
  grid.at(1, 1) = 1.0f;
  grid.at(2, 1) = 2.0f;
  grid.at(1, 2) = 3.0f;
  grid.at(2, 2) = 4.0f;
  const DensityPrefix prefix(grid);
  const std::vector<Point> square = {{-0.25, -0.25}, {0.25, -0.25}, {0.25, 0.25}, {-0.25, 0.25}};
  for (bool periodic : {false, true}) {
    const WeightedMoments m = prefix.moments(square, {0.5, 0.5}, {1.0, 1.0}, periodic);
    EXPECT_NEAR(m.mass, 0.0625 * 10.0, 1e-15);
    EXPECT_NEAR(m.first.x, 0.0625 * 0.125 * ((2.0 + 4.0) - (1.0 + 3.0)), 1e-15);
    EXPECT_NEAR(m.first.y, 0.0625 * 0.125 * ((3.0 + 4.0) - (1.0 + 2.0)), 1e-15);
    EXPECT_NEAR(m.second, 10.0 * 2.0 * std::pow(0.25, 4) / 3.0, 1e-15);
  }
}

TEST(DensityPrefix, EngineCellsAgreeWithTexelCuttingAndThreadCounts) {
  // The engine's cells (the cached tables, kept across calls) against the reference on the
  // same polygons, and the same bits for 1, 2 and 7 threads.
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    const Domain domain{{1.0, 0.8}};
    auto grid = random_density(300, 240, 31, 0.1);
    const Scene scene = random_scene(domain, 3000, boundary, grid, 32);
    const auto polygons = exact_cell_polygons(scene);
    ExactEngine engine;
    std::vector<SceneCells> runs;
    const std::size_t saved = thread_count();
    for (std::size_t threads : {1u, 2u, 7u}) {
      set_thread_count(threads);
      runs.push_back(engine.compute(scene));
      runs.push_back(engine.compute(scene));  // the second call reuses the tables
    }
    set_thread_count(saved);
    for (std::size_t i = 0; i < scene.sites.size(); ++i) {
      const WeightedMoments ref = density_moments(polygons[i], scene.sites[i], *grid, domain.size, scene.periodic());
      const Cell& cell = runs[0].cells[i];
      EXPECT_NEAR(cell.mass, ref.mass, 1e-12 * ref.mass) << "site " << i;
      EXPECT_NEAR(cell.second_moment, ref.second, 1e-12 * ref.second) << "site " << i;
      if (ref.mass > 0.0) {
        const Point c = scene.sites[i] + ref.first / ref.mass;
        const double radius = cell.radius;
        EXPECT_NEAR(cell.centroid.x, scene.periodic() ? wrap_point(c, domain).x : c.x, 1e-12 * radius) << "site " << i;
        EXPECT_NEAR(cell.centroid.y, scene.periodic() ? wrap_point(c, domain).y : c.y, 1e-12 * radius) << "site " << i;
      }
      for (const SceneCells& run : runs) {
        EXPECT_EQ(std::memcmp(&run.cells[i].centroid, &cell.centroid, sizeof(Point)), 0) << "site " << i;
        EXPECT_EQ(std::memcmp(&run.cells[i].mass, &cell.mass, sizeof(double)), 0) << "site " << i;
        EXPECT_EQ(std::memcmp(&run.cells[i].second_moment, &cell.second_moment, sizeof(double)), 0) << "site " << i;
      }
    }
  }
}

TEST(DensityPrefix, WithoutTheSecondMomentTheRestIsTheSameBits) {
  // moments(..., second = false), the path of Scene::second_moments false (Lloyd without the
  // energy): mass and first moment bit for bit those with the second moment, which is left 0.
  // Cells of 12 sites on a 600 x 500 grid are wider than the scan (the row sides' path), cells
  // of 3000 sites are scanned; both boundaries.
  auto grid = random_density(600, 500, 41, 0.1);
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    for (std::size_t count : {12u, 3000u}) {
      const Domain domain{{1.0, 0.8}};
      const DensityPrefix prefix(*grid);
      Scene scene = random_scene(domain, count, boundary, grid, 42 + count);
      const auto polygons = exact_cell_polygons(scene);
      for (std::size_t i = 0; i < polygons.size(); ++i) {
        const WeightedMoments with = prefix.moments(polygons[i], scene.sites[i], domain.size, scene.periodic(), true);
        const WeightedMoments without = prefix.moments(polygons[i], scene.sites[i], domain.size, scene.periodic(), false);
        ASSERT_EQ(std::memcmp(&with.mass, &without.mass, sizeof(double)), 0) << count << " site " << i;
        ASSERT_EQ(std::memcmp(&with.first, &without.first, sizeof(Point)), 0) << count << " site " << i;
        ASSERT_EQ(without.second, 0.0) << count << " site " << i;
        ASSERT_GT(with.second, 0.0) << count << " site " << i;
      }
      // The engine with Scene::second_moments false: the same centroids and masses, any thread count.
      ExactEngine engine;
      const SceneCells asked = engine.compute(scene);
      scene.second_moments = false;
      const std::size_t saved = thread_count();
      for (std::size_t threads : {1u, 2u, 7u}) {
        set_thread_count(threads);
        const SceneCells skipped = engine.compute(scene);
        for (std::size_t i = 0; i < scene.sites.size(); ++i) {
          EXPECT_EQ(std::memcmp(&asked.cells[i].centroid, &skipped.cells[i].centroid, sizeof(Point)), 0) << "site " << i;
          EXPECT_EQ(std::memcmp(&asked.cells[i].mass, &skipped.cells[i].mass, sizeof(double)), 0) << "site " << i;
        }
      }
      set_thread_count(saved);
    }
  }
}

TEST(DensityPrefix, LongRowsOfBrightAndDarkTexels) {
  // 4096-texel rows (a row prefix would be about 4096^3 / 3 times a texel in its second moment)
  // of bright (1) and dark (1e-3) stretches of 50 texels, so that a cell often lies in the dark
  // with bright texels in its box, beside it in its rows, or at the start of the 64-texel run its
  // box begins in: hexagons 5 to 70 texels wide, across the 64- and 8-aligned column lines, at
  // the map's left and right sides (bounded: touching the border; periodic: across the wrap).
  const int width = 4096, height = 40;
  auto grid = std::make_shared<DensityGrid>(width, height);
  Rng rng(97);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      grid->at(x, y) = static_cast<float>(((x / 50 + y / 7) % 2 ? 1.0 : 1e-3) * (0.75 + 0.5 * rng.uniform()));
  const DensityPrefix prefix(*grid);
  const Point size{1.0, static_cast<double>(height) / width};
  const double t = 1.0 / width;  // square texels
  for (double columns : {5.3, 12.7, 40.1, 63.4, 70.2}) {
    const double w = columns * t;
    const std::vector<Point> hexagon = {{-0.5 * w, -3.3 * t}, {0.1 * w, -7.1 * t}, {0.5 * w, -1.2 * t},
                                        {0.45 * w, 4.4 * t},  {-0.2 * w, 6.9 * t}, {-0.48 * w, 2.0 * t}};
    for (double x : {0.0, 0.3, 60.5, 64.0, 101.0, 127.7, 2000.2, 2047.9, 4030.0, 4090.0, 4096.0}) {
      for (double y : {10.0, 20.4, 33.0}) {
        const Point origin{x * t, y * t};
        const std::string what =
            "hexagon " + std::to_string(columns) + " wide at texel " + std::to_string(x) + ", " + std::to_string(y);
        expect_agree(hexagon, origin, *grid, prefix, size, true, 1e-12, what + ", periodic");
        // Bounded: the hexagon clipped to the map's columns by moving it inside, touching the side.
        const double inside = std::clamp(origin.x, 0.5 * w, 1.0 - 0.5 * w);
        expect_agree(hexagon, {inside, origin.y}, *grid, prefix, size, false, 1e-12, what + ", bounded");
      }
    }
  }
}

TEST(DensityPrefix, HandComputedAcrossAnAlignedColumnLine) {
  // A rectangle over texel columns 60.5 to 70.25 of a 130 x 2 grid (across the 64-aligned column
  // line), row 0 only, texel values 1 + column: each moment a hand sum of whole and partial texels.
  DensityGrid grid(130, 2, 0.0f);
  for (int x = 0; x < 130; ++x) {
    grid.at(x, 0) = static_cast<float>(1 + x);
    grid.at(x, 1) = 1000.0f;  // must not leak in
  }
  const DensityPrefix prefix(grid);
  const Point size{1.0, 2.0 / 130.0};
  const double t = 1.0 / 130.0, left = 60.5, right = 70.25;
  const std::vector<Point> rectangle = {{left * t, 0.0}, {right * t, 0.0}, {right * t, t}, {left * t, t}};
  double mass = 0.0, mx = 0.0, my = 0.0, second = 0.0;
  for (int x = 60; x <= 70; ++x) {
    const double a = std::max(left, static_cast<double>(x)), b = std::min(right, x + 1.0);
    if (b <= a) continue;
    const double rho = 1.0 + x;  // per texel area t^2: mass rho (b - a) t^2
    mass += rho * (b - a) * t * t;
    mx += rho * 0.5 * (b * b - a * a) * t * t * t;
    my += rho * (b - a) * 0.5 * t * t * t;
    second += rho * ((b * b * b - a * a * a) / 3.0 * t * t * t * t + (b - a) * t * t * t * t / 3.0);
  }
  for (bool periodic : {false, true}) {
    const WeightedMoments m = prefix.moments(rectangle, {0.0, 0.0}, size, periodic);
    EXPECT_NEAR(m.mass, mass, 1e-13 * mass);
    EXPECT_NEAR(m.first.x, mx, 1e-13 * mx);
    EXPECT_NEAR(m.first.y, my, 1e-13 * my);
    EXPECT_NEAR(m.second, second, 1e-13 * second);
  }
}

TEST(DensityPrefix, AGridChangedInPlaceIsNotServedStaleTables) {
  auto grid = random_density(40, 30, 5);
  const Scene scene = random_scene(Domain{}, 50, Boundary::periodic, grid, 6);
  ExactEngine engine;
  const SceneCells before = engine.compute(scene);
  for (float& t : grid->texels) t = 1.0f - t;
  const SceneCells after = engine.compute(scene);
  const SceneCells fresh = ExactEngine().compute(scene);
  for (std::size_t i = 0; i < scene.sites.size(); ++i) {
    EXPECT_EQ(after.cells[i].centroid, fresh.cells[i].centroid) << "site " << i;
    EXPECT_NE(after.cells[i].mass, before.cells[i].mass) << "site " << i;
  }
}

}  // namespace
}  // namespace bluetile
