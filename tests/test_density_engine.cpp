// Weighted cells and bounded domains on the exact engine, against the brute-force references of
// density_reference.h (cells clipped by every bisector, moments clipped by every texel).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/exact_engine.h"
#include "density_reference.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::error_of;

std::shared_ptr<DensityGrid> random_density(int width, int height, std::uint64_t seed, double zero_fraction = 0.0) {
  Rng rng(seed);
  auto grid = std::make_shared<DensityGrid>(width, height);
  for (float& t : grid->texels) t = rng.uniform() < zero_fraction ? 0.0f : static_cast<float>(rng.uniform());
  grid->texels[0] = 0.5f;  // never all zero
  return grid;
}

std::vector<Point> points_in(const Domain& domain, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> points(count);
  for (Point& p : points) p = rng.point(domain);
  return points;
}

Scene weighted_scene(std::vector<Point> sites, Domain domain, Boundary boundary, std::shared_ptr<DensityGrid> density) {
  Scene scene = make_scene(std::move(sites), domain);
  scene.boundary = boundary;
  scene.density = std::move(density);
  return scene;
}

// The largest distance between the engine's centroids and the brute-force ones.
double max_centroid_error(const Scene& scene, const SceneCells& cells) {
  double worst = 0.0;
  for (std::size_t i = 0; i < scene.wanted_count(); ++i) {
    const Point ref = test::brute_force_centroid(scene, scene.wanted_begin + i);
    worst = std::max(worst, scene_distance(scene, ref, cells.cells[i].centroid));
  }
  return worst;
}

TEST(DensityMoments, PolygonsAgainstClippingByEveryTexel) {
  // Random convex polygons (cells of random scenes) anywhere over random grids, also reaching
  // across the torus' edges, and grids coarser and finer than the polygons.
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      const Domain domain{{1.0, 0.75}};
      const int width = 3 + static_cast<int>(seed) * 5, height = 2 + static_cast<int>(seed) * 3;
      Scene scene = weighted_scene(points_in(domain, 12, seed), domain, boundary, random_density(width, height, seed));
      for (std::size_t i = 0; i < scene.sites.size(); ++i) {
        const std::vector<Point> polygon = test::brute_force_cell(scene, i);
        const WeightedMoments ref = test::brute_force_moments(polygon, scene.sites[i], scene);
        const WeightedMoments got =
            density_moments(polygon, scene.sites[i], *scene.density, domain.size, scene.periodic());
        EXPECT_NEAR(got.mass, ref.mass, 1e-14) << "seed " << seed << " site " << i;
        EXPECT_NEAR(got.first.x, ref.first.x, 1e-14);
        EXPECT_NEAR(got.first.y, ref.first.y, 1e-14);
        EXPECT_NEAR(got.second, ref.second, 1e-14);
        const Point c = got.first / got.mass, r = ref.first / ref.mass;
        EXPECT_NEAR(c.x, r.x, 1e-12);
        EXPECT_NEAR(c.y, r.y, 1e-12);
      }
    }
  }
}

TEST(DensityMoments, AxisAlignedSquareOverFourTexels) {
  // The square [0.25, 0.75]^2 of the unit domain over a 2 x 2 grid: a quarter of each texel.
  DensityGrid grid(2, 2);
  grid.at(0, 0) = 1.0f;
  grid.at(1, 0) = 2.0f;
  grid.at(0, 1) = 3.0f;
  grid.at(1, 1) = 4.0f;
  const Point origin{0.5, 0.5};
  const std::vector<Point> square = {{-0.25, -0.25}, {0.25, -0.25}, {0.25, 0.25}, {-0.25, 0.25}};
  const WeightedMoments m = density_moments(square, origin, grid, {1.0, 1.0}, false);
  EXPECT_NEAR(m.mass, 0.0625 * 10.0, 1e-15);
  // First moment: each quarter square's centre is at (+-1/8, +-1/8) from the origin.
  EXPECT_NEAR(m.first.x, 0.0625 * 0.125 * ((2.0 + 4.0) - (1.0 + 3.0)), 1e-15);
  EXPECT_NEAR(m.first.y, 0.0625 * 0.125 * ((3.0 + 4.0) - (1.0 + 2.0)), 1e-15);
  // Second moment of a quarter square [0, 1/4]^2 about its corner: 2 * (1/4)^4 / 3.
  EXPECT_NEAR(m.second, 10.0 * 2.0 * std::pow(0.25, 4) / 3.0, 1e-15);
}

TEST(DensityMoments, CellsLargerThanOneBandOfTheTexelTable) {
  // Three sites over a 600 x 450 grid: a cell's box of texels holds more texels than one band of
  // the integration's table (2^16), so the box is taken in several bands of columns.
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    const Domain domain{{1.0, 0.75}};
    Scene scene = weighted_scene(points_in(domain, 3, 11), domain, boundary, random_density(600, 450, 12, 0.2));
    int banded = 0;  // cells whose box needs more than one band
    for (std::size_t i = 0; i < scene.sites.size(); ++i) {
      const std::vector<Point> polygon = test::brute_force_cell(scene, i);
      Point lo = polygon[0], hi = polygon[0];
      for (const Point& p : polygon) lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)}, hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
      banded += (hi.x - lo.x) * 600.0 * (hi.y - lo.y) * 600.0 > 65536.0;
      const WeightedMoments ref = test::brute_force_moments(polygon, scene.sites[i], scene);
      const WeightedMoments got = density_moments(polygon, scene.sites[i], *scene.density, domain.size, scene.periodic());
      EXPECT_NEAR(got.mass, ref.mass, 1e-12 * ref.mass) << "site " << i;
      const Point c = got.first / got.mass, r = ref.first / ref.mass;
      EXPECT_NEAR(c.x, r.x, 1e-12) << "site " << i;
      EXPECT_NEAR(c.y, r.y, 1e-12) << "site " << i;
      EXPECT_NEAR(got.second, ref.second, 1e-12 * ref.second) << "site " << i;
    }
    EXPECT_GE(banded, 1) << "the case needs a larger cell";
  }
}

TEST(DensityMoments, EdgesLyingOnTexelLines) {
  // The square [0.25, 0.75]^2 over a 4 x 4 grid: its edges lie on texel lines, and it holds the
  // four middle texels exactly.
  DensityGrid grid(4, 4, 100.0f);  // the outer texels must not leak in
  grid.at(1, 1) = 1.0f;
  grid.at(2, 1) = 2.0f;
  grid.at(1, 2) = 3.0f;
  grid.at(2, 2) = 4.0f;
  const Point origin{0.5, 0.5};
  const std::vector<Point> square = {{-0.25, -0.25}, {0.25, -0.25}, {0.25, 0.25}, {-0.25, 0.25}};
  for (bool periodic : {false, true}) {
    const WeightedMoments m = density_moments(square, origin, grid, {1.0, 1.0}, periodic);
    EXPECT_NEAR(m.mass, 0.0625 * 10.0, 1e-15);
    EXPECT_NEAR(m.first.x, 0.0625 * 0.125 * ((2.0 + 4.0) - (1.0 + 3.0)), 1e-15);
    EXPECT_NEAR(m.first.y, 0.0625 * 0.125 * ((3.0 + 4.0) - (1.0 + 2.0)), 1e-15);
    EXPECT_NEAR(m.second, 10.0 * 2.0 * std::pow(0.25, 4) / 3.0, 1e-15);
  }
}

TEST(DensityExactEngine, WeightedCentroidsMatchBruteForce) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      const Domain domain = seed % 2 ? Domain{} : Domain{{1.0, 0.6}};
      Scene scene = weighted_scene(points_in(domain, 60, 100 + seed), domain, boundary,
                                   random_density(17, 11, seed, 0.2));
      SceneCells cells = ExactEngine().compute(scene);
      EXPECT_LE(max_centroid_error(scene, cells), 1e-12) << "seed " << seed;
      for (std::size_t i = 0; i < scene.sites.size(); ++i) {
        const auto polygon = test::brute_force_cell(scene, i);
        const WeightedMoments ref = test::brute_force_moments(polygon, scene.sites[i], scene);
        EXPECT_NEAR(cells.cells[i].mass, ref.mass, 1e-14);
        EXPECT_NEAR(cells.cells[i].second_moment, ref.second, 1e-14);
      }
    }
  }
}

TEST(DensityExactEngine, BoundedCellsTileTheRectangle) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const Domain domain{{1.0, 0.7}};
    std::vector<Point> sites = points_in(domain, 200, seed);
    sites.push_back({0.0, 0.35});              // on the left border
    sites.push_back({0.0, 0.0});               // a corner
    sites.push_back({0.5, 0.0});               // the bottom border
    sites.push_back({std::nextafter(1.0, 0.0), std::nextafter(0.7, 0.0)});  // (almost) the far corner
    Scene scene = make_scene(sites, domain);
    scene.boundary = Boundary::bounded;
    SceneCells cells = ExactEngine().compute(scene);
    double total = 0.0;
    for (std::size_t i = 0; i < sites.size(); ++i) {
      total += cells.cells[i].area;
      const Point ref = test::brute_force_centroid(scene, i);
      EXPECT_NEAR(cells.cells[i].centroid.x, ref.x, 1e-12) << "site " << i;
      EXPECT_NEAR(cells.cells[i].centroid.y, ref.y, 1e-12) << "site " << i;
      EXPECT_EQ(cells.cells[i].mass, cells.cells[i].area);
      // Inside the rectangle, never on its far edges.
      EXPECT_GE(cells.cells[i].centroid.x, 0.0);
      EXPECT_LT(cells.cells[i].centroid.x, domain.size.x);
      EXPECT_GE(cells.cells[i].centroid.y, 0.0);
      EXPECT_LT(cells.cells[i].centroid.y, domain.size.y);
    }
    EXPECT_NEAR(total, domain.area(), 1e-12);
  }
}

TEST(DensityExactEngine, BoundedHandComputedCells) {
  // One site owns the whole rectangle; two sites split it at their bisector.
  Scene one = make_scene({{0.1, 0.2}}, Domain{{2.0, 1.0}});
  one.boundary = Boundary::bounded;
  SceneCells c1 = ExactEngine().compute(one);
  EXPECT_DOUBLE_EQ(c1.cells[0].area, 2.0);
  EXPECT_NEAR(c1.cells[0].centroid.x, 1.0, 1e-15);
  EXPECT_NEAR(c1.cells[0].centroid.y, 0.5, 1e-15);
  Scene two = make_scene({{0.5, 0.5}, {1.0, 0.5}}, Domain{{2.0, 1.0}});
  two.boundary = Boundary::bounded;
  SceneCells c2 = ExactEngine().compute(two);
  EXPECT_NEAR(c2.cells[0].area, 0.75, 1e-15);  // [0, 0.75] x [0, 1]
  EXPECT_NEAR(c2.cells[0].centroid.x, 0.375, 1e-15);
  EXPECT_NEAR(c2.cells[1].area, 1.25, 1e-15);  // [0.75, 2] x [0, 1]
  EXPECT_NEAR(c2.cells[1].centroid.x, 1.375, 1e-15);
  // Weighted: density 1 on the left half of the rectangle, 3 on the right (grid 2 x 1).
  auto halves = std::make_shared<DensityGrid>(2, 1);
  halves->at(0, 0) = 1.0f;
  halves->at(1, 0) = 3.0f;
  one.density = halves;
  SceneCells w = ExactEngine().compute(one);
  EXPECT_NEAR(w.cells[0].mass, 4.0, 1e-15);
  EXPECT_NEAR(w.cells[0].centroid.x, (1.0 * 0.5 + 3.0 * 1.5) / 4.0, 1e-15);
  EXPECT_NEAR(w.cells[0].centroid.y, 0.5, 1e-15);
}

TEST(DensityExactEngine, UniformDensityGivesTheUnweightedCentroidsBitForBit) {
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    Scene plain = make_scene(points_in(Domain{}, 500, 3));
    plain.boundary = boundary;
    Scene uniform = plain;
    uniform.density = std::make_shared<DensityGrid>(64, 48, 0.37f);
    SceneCells a = ExactEngine().compute(plain), b = ExactEngine().compute(uniform);
    for (std::size_t i = 0; i < a.cells.size(); ++i) {
      EXPECT_EQ(std::memcmp(&a.cells[i].centroid, &b.cells[i].centroid, sizeof(Point)), 0) << "site " << i;
      EXPECT_EQ(a.cells[i].area, b.cells[i].area);
      EXPECT_EQ(b.cells[i].mass, 0.37f * a.cells[i].area);
    }
  }
}

TEST(DensityExactEngine, SceneWithoutDensityIsTodaysBitForBit) {
  // Pinned: `bluetile relax --count 300 --iterations 4 --seed 11 --engine exact` as main wrote
  // it before densities and bounded domains existed (commit 137a866).
  Rng rng(derive_seed(11, 0));
  std::vector<Point> points(300);
  for (Point& p : points) p = rng.point(Domain{});
  Scene scene = make_scene(points);
  // The search, whose bits these are (the kept triangulation, the default, agrees to rounding:
  // tests/test_exact_topology.cpp).
  ExactEngine engine(ExactEngineOptions{false});
  LloydOptions options;
  options.iterations = 4;
  relax_lloyd(engine, scene, options);
  EXPECT_EQ(scene.sites[0], Point(0.93624845907795939, 0.24445248963579394));
  EXPECT_EQ(scene.sites[99], Point(0.63451698593155903, 0.29481607476138172));
  EXPECT_EQ(scene.sites[299], Point(0.53363179070389655, 0.32271116809325917));
}

TEST(DensityExactEngine, CellsWithoutDensityKeepTheirSiteAndAreReported) {
  // Density zero on the left three quarters of the torus.
  auto grid = std::make_shared<DensityGrid>(8, 2, 0.0f);
  for (int j = 0; j < 2; ++j)
    for (int i = 6; i < 8; ++i) grid->at(i, j) = 1.0f;
  Scene scene = weighted_scene(points_in(Domain{}, 100, 9), Domain{}, Boundary::periodic, grid);
  SceneCells cells = ExactEngine().compute(scene);
  std::size_t zero = 0;
  for (std::size_t i = 0; i < scene.sites.size(); ++i) {
    const auto polygon = test::brute_force_cell(scene, i);
    const double mass = test::brute_force_moments(polygon, scene.sites[i], scene).mass;
    if (mass == 0.0) {
      ++zero;
      EXPECT_EQ(cells.cells[i].status, CellStatus::zero_density) << "site " << i;
      EXPECT_EQ(cells.cells[i].centroid, scene.sites[i]);
      EXPECT_EQ(cells.cells[i].mass, 0.0);
      EXPECT_GT(cells.cells[i].area, 0.0);
    } else {
      EXPECT_EQ(cells.cells[i].status, CellStatus::ok) << "site " << i;
    }
  }
  EXPECT_GT(zero, 30u);  // most of the 75 sites on the left
  EXPECT_EQ(cells.zero_density_count, zero);
  // Lloyd leaves them where they are and says how many there were.
  LloydOptions options;
  options.iterations = 1;
  ExactEngine engine;
  Scene moved = scene;
  LloydResult r = relax_lloyd(engine, moved, options);
  EXPECT_EQ(r.last.zero_density, zero);
}

TEST(DensityExactEngine, BadDensitiesAreClearErrors) {
  Scene scene = make_scene(points_in(Domain{}, 10, 1));
  scene.density = std::make_shared<DensityGrid>(4, 4, 0.0f);
  EXPECT_EQ(error_of([&] { ExactEngine().compute(scene); }),
            "the density is zero everywhere: no cell has a centre of mass");
  auto negative = std::make_shared<DensityGrid>(4, 4, 1.0f);
  negative->at(2, 1) = -1.0f;
  scene.density = negative;
  EXPECT_NE(error_of([&] { ExactEngine().compute(scene); }).find("density texel (2, 1) is -1"), std::string::npos);
  auto nan = std::make_shared<DensityGrid>(4, 4, 1.0f);
  nan->at(0, 3) = std::nanf("");
  scene.density = nan;
  EXPECT_NE(error_of([&] { ExactEngine().compute(scene); }).find("density texel (0, 3) is"), std::string::npos);
  auto empty = std::make_shared<DensityGrid>();
  scene.density = empty;
  EXPECT_NE(error_of([&] { ExactEngine().compute(scene); }).find("density grid of 0 x 0"), std::string::npos);
}

// Mean over seeds of (points in the dense right half) / (points in the left half) after
// relaxing, from a start drawn in proportion to a two-level density (right 4x the left).
double two_level_ratio(double weight_exponent, Boundary boundary, int iterations) {
  DensityGrid target(2, 1);
  target.at(0, 0) = 1.0f;
  target.at(1, 0) = 4.0f;
  auto weight = std::make_shared<DensityGrid>(weight_for_point_density(target, weight_exponent));
  double sum = 0.0;
  const int seeds = 4;
  for (int seed = 0; seed < seeds; ++seed) {
    Rng rng(derive_seed(static_cast<std::uint64_t>(seed), 7));
    Scene scene = weighted_scene(sample_density(target, Domain{}, 1000, rng), Domain{}, boundary, weight);
    ExactEngine engine;
    LloydOptions options;
    options.iterations = iterations;
    relax_lloyd(engine, scene, options);
    std::size_t right = 0;
    for (const Point& p : scene.sites) right += p.x >= 0.5;
    sum += static_cast<double>(right) / static_cast<double>(scene.sites.size() - right);
  }
  return sum / seeds;
}

TEST(DensityLloyd, TwoLevelDensityCountsFollowTheRatio) {
  // Weighted by the square of the target, the counts follow the ratio 4: measured 4.205 periodic
  // and 4.054 bounded (mean of 4 seeds, N = 1000, 50 iterations, from a start at 3.893).
  const double periodic = two_level_ratio(2.0, Boundary::periodic, 50);
  const double bounded = two_level_ratio(2.0, Boundary::bounded, 50);
  EXPECT_NEAR(periodic, 4.0, 0.35);
  EXPECT_NEAR(bounded, 4.0, 0.35);
  // Weighted by the target itself (Secord 2002), they drift toward sqrt(4) = 2 as the set
  // converges: measured 3.190 after 50 iterations.
  const double plain = two_level_ratio(1.0, Boundary::periodic, 50);
  EXPECT_LT(plain, 3.5);
  EXPECT_GT(plain, 2.0);
  std::printf("two-level count ratios: start %.3f; squared %.3f periodic, %.3f bounded; plain %.3f\n",
              two_level_ratio(2.0, Boundary::periodic, 0), periodic, bounded, plain);
}

TEST(DensityExactEngine, SameBitsWhateverTheThreadCount) {
  Scene scene = weighted_scene(points_in(Domain{}, 3000, 4), Domain{}, Boundary::bounded, random_density(97, 89, 2));
  const std::size_t saved = thread_count();
  set_thread_count(1);
  SceneCells one = ExactEngine().compute(scene);
  set_thread_count(2);
  SceneCells two = ExactEngine().compute(scene);
  set_thread_count(saved);
  for (std::size_t i = 0; i < one.cells.size(); ++i) {
    const Cell &a = one.cells[i], &b = two.cells[i];
    double fa[5] = {a.centroid.x, a.centroid.y, a.area, a.mass, a.second_moment};
    double fb[5] = {b.centroid.x, b.centroid.y, b.area, b.mass, b.second_moment};
    ASSERT_EQ(std::memcmp(fa, fb, sizeof fa), 0) << "site " << i;
  }
}

}  // namespace
}  // namespace bluetile
