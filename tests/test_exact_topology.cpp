// The exact engine's topology kept between calls (exact_engine.h): Lloyd sequences computed by an
// engine that keeps its lists and by one that searches every cell, side by side on the same sites,
// against each other and against brute-force clipping; the fallback on purpose; thread counts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <memory>
#include <string>

#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::uniform_points;

// Brute force: the cell clipped by every other site (and, on a torus, the 9 nearest copies of
// every site), no grid, no early stop; area and centroid.
struct Reference {
  double area = 0.0;
  Point centroid;
};

Reference brute_force(const Scene& scene, std::size_t i) {
  const Point size = scene.domain.size, o = scene.sites[i];
  std::vector<Point> poly;
  if (scene.periodic()) {
    poly = {-0.5 * size, {0.5 * size.x, -0.5 * size.y}, 0.5 * size, {-0.5 * size.x, 0.5 * size.y}};
  } else {
    poly = {-o, Point{size.x, 0.0} - o, size - o, Point{0.0, size.y} - o};
  }
  const int copies = scene.periodic() ? 1 : 0;
  for (std::size_t j = 0; j < scene.sites.size(); ++j) {
    for (int sx = -copies; sx <= copies; ++sx) {
      for (int sy = -copies; sy <= copies; ++sy) {
        const Point d = scene.sites[j] + Point{sx * size.x, sy * size.y} - o;
        if (d.x == 0.0 && d.y == 0.0) continue;
        const double c = 0.5 * (d.x * d.x + d.y * d.y);
        std::vector<Point> out;
        for (std::size_t k = 0; k < poly.size(); ++k) {
          const Point a = poly[k], b = poly[(k + 1) % poly.size()];
          const double fa = a.x * d.x + a.y * d.y - c, fb = b.x * d.x + b.y * d.y - c;
          if (fa <= 0) out.push_back(a);
          if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) out.push_back(a + (b - a) * (fa / (fa - fb)));
        }
        poly = out;
      }
    }
  }
  Reference r;
  double cx = 0.0, cy = 0.0;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point a = poly[k], b = poly[(k + 1) % poly.size()];
    const double cross = a.x * b.y - b.x * a.y;
    r.area += 0.5 * cross;
    cx += (a.x + b.x) * cross;
    cy += (a.y + b.y) * cross;
  }
  r.centroid = r.area > 0.0 ? scene_point(scene, o + Point{cx, cy} / (6.0 * r.area)) : o;
  return r;
}

bool identical(const SceneCells& a, const SceneCells& b) {
  if (a.cells.size() != b.cells.size()) return false;
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    const Cell &x = a.cells[i], &y = b.cells[i];
    const double fx[6] = {x.centroid.x, x.centroid.y, x.area, x.mass, x.second_moment, x.radius};
    const double fy[6] = {y.centroid.x, y.centroid.y, y.area, y.mass, y.second_moment, y.radius};
    if (std::memcmp(fx, fy, sizeof fx) != 0 || x.status != y.status) return false;
  }
  return true;
}

// The largest differences between two results: centroid distance and area, and whether every
// status agrees.
struct Difference {
  double centroid = 0.0, area = 0.0, mass = 0.0;
  bool statuses = true;
};

Difference compare(const Scene& scene, const SceneCells& a, const SceneCells& b) {
  Difference d;
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    d.centroid = std::max(d.centroid, scene_distance(scene, a.cells[i].centroid, b.cells[i].centroid));
    d.area = std::max(d.area, std::abs(a.cells[i].area - b.cells[i].area));
    d.mass = std::max(d.mass, std::abs(a.cells[i].mass - b.cells[i].mass));
    d.statuses &= a.cells[i].status == b.cells[i].status;
  }
  return d;
}

// `iterations` Lloyd steps: both engines measure the same sites, which then move to the
// searching engine's centroids (`perturb` may change them further between calls). Checks every
// call within 1e-12; returns how many cells the kept engine certified from its lists.
std::size_t run_side_by_side(Scene scene, int iterations, const std::function<void(Scene&, int)>& perturb = {}) {
  ExactEngine kept(ExactEngineOptions{true}), search(ExactEngineOptions{false});
  std::size_t kept_cells = 0;
  for (int it = 0; it < iterations; ++it) {
    const SceneCells a = kept.compute(scene);
    const SceneCells b = search.compute(scene);
    kept_cells += kept.last_topology_stats().kept_cells;
    const Difference d = compare(scene, a, b);
    EXPECT_LE(d.centroid, 1e-12) << "iteration " << it;
    EXPECT_LE(d.area, 1e-12) << "iteration " << it;
    EXPECT_LE(d.mass, 1e-12) << "iteration " << it;
    EXPECT_TRUE(d.statuses) << "iteration " << it;
    EXPECT_EQ(a.coincident_count, b.coincident_count);
    if (it + 1 == iterations) {
      // Brute force on every 9th wanted cell of the last call (unweighted scenes).
      if (!scene.density) {
        for (std::size_t w = 0; w < scene.wanted_count(); w += 9) {
          if (a.cells[w].status != CellStatus::ok) continue;
          const Reference r = brute_force(scene, scene.wanted_begin + w);
          EXPECT_NEAR(a.cells[w].area, r.area, 1e-12) << "site " << w;
          EXPECT_LE(scene_distance(scene, a.cells[w].centroid, r.centroid), 1e-12) << "site " << w;
        }
      }
      break;
    }
    std::vector<Scene> scenes{scene};
    std::vector<SceneCells> cells{b};
    move_to_centroids(scenes, cells);
    scene = scenes[0];
    if (perturb) perturb(scene, it);
  }
  return kept_cells;
}

std::vector<Point> relaxed_points(std::size_t n, std::uint64_t seed, Domain domain = {}, Boundary boundary = Boundary::periodic) {
  Scene scene = make_scene(uniform_points(n, seed), domain);
  for (Point& p : scene.sites) p *= domain.size;
  scene.boundary = boundary;
  ExactEngine engine(ExactEngineOptions{false});
  LloydOptions options;
  options.iterations = 25;
  relax_lloyd(engine, scene, options);
  return scene.sites;
}

TEST(ExactTopology, RandomSitesAgreeWithTheSearchAndBruteForce) {
  // From random sites the sites move far at first: lists come once they move little.
  const std::size_t kept = run_side_by_side(make_scene(uniform_points(2000, 5)), 24);
  EXPECT_GT(kept, 0u);
}

TEST(ExactTopology, RelaxedSitesAreKept) {
  const std::size_t kept = run_side_by_side(make_scene(relaxed_points(2000, 6)), 8);
  // Calls 1 and 2 search (the second makes the lists); of the other 6 x 2000 cells nearly all kept.
  EXPECT_GT(kept, 6u * 2000u * 9u / 10u);
}

TEST(ExactTopology, BoundedRectangleAndWantedRange) {
  const Domain domain{{2.0, 1.0}};
  Scene scene = make_scene(relaxed_points(2400, 7, domain, Boundary::bounded), domain);
  scene.boundary = Boundary::bounded;
  scene.wanted_begin = 100;
  scene.wanted_end = 2100;
  EXPECT_GT(run_side_by_side(scene, 7), 0u);
  Scene periodic = make_scene(relaxed_points(1500, 8, domain), domain);
  periodic.wanted_begin = 200;
  EXPECT_GT(run_side_by_side(periodic, 7), 0u);
}

TEST(ExactTopology, WeightedCells) {
  auto density = std::make_shared<DensityGrid>(64, 48);
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) density->at(i, j) = 0.1f + static_cast<float>(i * j % 17) / 16.0f;
  for (Boundary boundary : {Boundary::bounded, Boundary::periodic}) {
    // Relaxed under the density first, so that the sites then move little.
    Scene scene = make_scene(uniform_points(2000, 9));
    scene.boundary = boundary;
    scene.density = density;
    ExactEngine engine(ExactEngineOptions{false});
    LloydOptions options;
    options.iterations = 40;
    relax_lloyd(engine, scene, options);
    EXPECT_GT(run_side_by_side(scene, 7), 0u);
  }
}

TEST(ExactTopology, SquareLatticeTiesAndItsShift) {
  // Cocircular ties everywhere: every cell vertex is shared by four sites. A Lloyd fixed point;
  // then the whole lattice shifted by a small step each call (sites wrap across the border).
  std::vector<Point> sites;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) sites.push_back({(i + 0.5) / 40.0, (j + 0.5) / 40.0});
  EXPECT_GT(run_side_by_side(make_scene(sites), 6), 0u);
  run_side_by_side(make_scene(sites), 8, [](Scene& scene, int) {
    for (Point& p : scene.sites) p = wrap_point(p + Point{0.004, -0.003}, scene.domain);
  });
}

TEST(ExactTopology, NearDegenerateCoincidentAndCollinear) {
  // Pairs 1e-9 apart and exact duplicates inside a relaxed set; each call moves them a little.
  std::vector<Point> sites = relaxed_points(1500, 10);
  for (std::size_t k = 0; k < 20; ++k) sites.push_back(sites[k * 37] + Point{1e-9, static_cast<double>(k % 3) * 1e-9});
  for (std::size_t k = 0; k < 6; ++k) sites.push_back(sites[k * 101 + 3]);
  run_side_by_side(make_scene(sites), 7, [](Scene& scene, int it) {
    for (std::size_t k = 0; k < 20; ++k) scene.sites[1500 + k] = scene.sites[k * 37] + Point{1e-9 * (it + 1), 1e-9};
    for (std::size_t k = 0; k < 6; ++k) scene.sites[1520 + k] = scene.sites[k * 101 + 3];
  });
  // Collinear sites (three lines, far from uniform: the tree searches them).
  std::vector<Point> lines;
  for (int k = 0; k < 1200; ++k) lines.push_back({(k + 0.25) / 1200.0, 0.2 + 0.3 * (k % 3)});
  run_side_by_side(make_scene(lines), 4);
}

TEST(ExactTopology, FallbackWhenASiteJumps) {
  // One site teleported across the torus after the lists are made: the cells around where it
  // left and where it lands fail their certificate and are searched; the rest stay kept.
  Scene scene = make_scene(relaxed_points(3000, 11));
  ExactEngine kept(ExactEngineOptions{true}), search(ExactEngineOptions{false});
  for (int it = 0; it < 3; ++it) kept.compute(scene);
  EXPECT_EQ(kept.last_topology_stats().kept_cells, 3000u);
  scene.sites[17] = wrap_point(scene.sites[17] + Point{0.5, 0.5}, scene.domain);
  const SceneCells a = kept.compute(scene);
  const KeptTopologyStats stats = kept.last_topology_stats();
  EXPECT_GT(stats.failed_cells, 0u);
  EXPECT_LT(stats.failed_cells, 3000u / 64u);
  EXPECT_GT(stats.kept_cells, 2900u);
  const SceneCells b = search.compute(scene);
  const Difference d = compare(scene, a, b);
  EXPECT_LE(d.centroid, 1e-12);
  EXPECT_LE(d.area, 1e-12);
  // Every site moved far: all fail, the lists are dropped, and the next call searches.
  for (Point& p : scene.sites) p = wrap_point(p + Point{0.3 / std::sqrt(3000.0), 0.0}, scene.domain);
  for (std::size_t i = 0; i < scene.sites.size(); i += 2) scene.sites[i] = wrap_point(scene.sites[i] + Point{0.0, 0.2 / std::sqrt(3000.0)}, scene.domain);
  const SceneCells c = kept.compute(scene);
  EXPECT_GT(kept.last_topology_stats().failed_cells, 3000u / 64u);
  const Difference e = compare(scene, c, search.compute(scene));
  EXPECT_LE(e.centroid, 1e-12);
  kept.compute(scene);
  EXPECT_EQ(kept.last_topology_stats().kept_cells, 0u);
  EXPECT_EQ(kept.last_topology_stats().searched_cells, 3000u);
}

TEST(ExactTopology, BitIdenticalWhateverTheThreadCount) {
  // A relaxation long enough to make, use, drop and remake lists, on 1, 2 and 7 threads.
  const std::size_t before = thread_count();
  std::vector<std::vector<SceneCells>> runs;
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    Scene scene = make_scene(uniform_points(12000, 12));
    ExactEngine engine(ExactEngineOptions{true});
    std::vector<SceneCells> calls;
    std::size_t kept = 0;
    for (int it = 0; it < 16; ++it) {
      calls.push_back(engine.compute(scene));
      kept += engine.last_topology_stats().kept_cells;
      std::vector<Scene> scenes{scene};
      move_to_centroids(scenes, std::span<const SceneCells>(&calls.back(), 1));
      scene = scenes[0];
    }
    EXPECT_GT(kept, 0u);
    runs.push_back(std::move(calls));
  }
  set_thread_count(before);
  for (std::size_t it = 0; it < runs[0].size(); ++it) {
    EXPECT_TRUE(identical(runs[0][it], runs[1][it])) << "call " << it;
    EXPECT_TRUE(identical(runs[0][it], runs[2][it])) << "call " << it;
  }
}

}  // namespace
}  // namespace bluetile
