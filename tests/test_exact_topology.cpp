// The exact engine's Delaunay triangulation kept between calls (exact_engine.h, kept_delaunay.h):
// Lloyd sequences measured by an engine that keeps its triangulation and by one that searches every
// cell, side by side on the same sites, within 1e-12 of each other and of brute-force clipping, on
// random, relaxed, lattice, nearly degenerate, collinear and clustered sites; the fallbacks on
// purpose; the same bits whatever the calls before and the thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "bluetile/core/huge_pages.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/delaunay_sweep.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/periodic_delaunay.h"
#include "bluetile/core/torus.h"
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

// The largest differences between two results, and whether every status agrees.
struct Difference {
  double centroid = 0.0, area = 0.0, mass = 0.0, second_moment = 0.0;
  bool statuses = true;
};

Difference compare(const Scene& scene, const SceneCells& a, const SceneCells& b) {
  Difference d;
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    d.centroid = std::max(d.centroid, scene_distance(scene, a.cells[i].centroid, b.cells[i].centroid));
    d.area = std::max(d.area, std::abs(a.cells[i].area - b.cells[i].area));
    d.mass = std::max(d.mass, std::abs(a.cells[i].mass - b.cells[i].mass));
    d.second_moment = std::max(d.second_moment, std::abs(a.cells[i].second_moment - b.cells[i].second_moment));
    d.statuses &= a.cells[i].status == b.cells[i].status;
  }
  return d;
}

ExactEngine searching() { return ExactEngine(ExactEngineOptions{false}); }

struct SideBySide {
  std::size_t kept = 0, rebuilds = 0, ties = 0, flips = 0, repaired = 0;
};

// `iterations` Lloyd steps: both engines measure the same sites, which then move to the
// searching engine's centroids (`perturb` may change them further between calls). Checks every
// call within 1e-12, and the last one against brute force.
SideBySide run_side_by_side(Scene scene, int iterations, const std::function<void(Scene&, int)>& perturb = {}) {
  ExactEngine kept;
  ExactEngine search = searching();
  SideBySide totals;
  for (int it = 0; it < iterations; ++it) {
    const SceneCells a = kept.compute(scene);
    const SceneCells b = search.compute(scene);
    const KeptTopologyStats stats = kept.last_topology_stats();
    totals.kept += stats.kept_cells;
    totals.rebuilds += stats.rebuilds;
    totals.ties += stats.tie_cells;
    totals.flips += stats.flips;
    totals.repaired += stats.repaired_vertices;
    EXPECT_EQ(stats.kept_cells + stats.searched_cells, scene.wanted_count());
    const Difference d = compare(scene, a, b);
    EXPECT_LE(d.centroid, 1e-12) << "iteration " << it;
    EXPECT_LE(d.area, 1e-12) << "iteration " << it;
    EXPECT_LE(d.mass, 1e-12) << "iteration " << it;
    EXPECT_LE(d.second_moment, 1e-12) << "iteration " << it;
    EXPECT_TRUE(d.statuses) << "iteration " << it;
    EXPECT_EQ(a.coincident_count, b.coincident_count);
    if (it + 1 == iterations) {
      // Brute force on every 29th wanted cell of the last call (unweighted scenes).
      if (!scene.density) {
        for (std::size_t w = 0; w < scene.wanted_count(); w += 29) {
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
  return totals;
}

std::vector<Point> relaxed_points(std::size_t n, std::uint64_t seed, Domain domain = {}, Boundary boundary = Boundary::periodic) {
  Scene scene = make_scene(uniform_points(n, seed), domain);
  for (Point& p : scene.sites) p *= domain.size;
  scene.boundary = boundary;
  ExactEngine engine = searching();
  LloydOptions options;
  options.iterations = 25;
  relax_lloyd(engine, scene, options);
  return scene.sites;
}

TEST(ExactTopology, RandomStartAgreesWithTheSearchAndBruteForce) {
  // From random sites the first steps move far: the triangulation is repaired by many flips or
  // rebuilt; every call agrees with the search.
  const SideBySide r = run_side_by_side(make_scene(uniform_points(2000, 5)), 16);
  EXPECT_EQ(r.kept, 16u * 2000u);
  EXPECT_GE(r.rebuilds, 1u);
  EXPECT_LT(r.rebuilds, 16u);
  EXPECT_GT(r.flips, 0u);
}

TEST(ExactTopology, RelaxedSitesAreRepairedByFlips) {
  const SideBySide r = run_side_by_side(make_scene(relaxed_points(2000, 6)), 8);
  EXPECT_EQ(r.kept, 8u * 2000u);
  EXPECT_EQ(r.rebuilds, 1u);  // the first call only
  EXPECT_EQ(r.ties, 0u);
}

TEST(ExactTopology, SameSitesGiveTheSameBitsWhateverTheCallsBefore) {
  // An engine that followed a relaxation (its triangulation flipped call after call, rebuilt when
  // the first steps folded it over), one that saw other scenes in between, and a fresh one: the
  // same sites give the same bits.
  Scene scene = make_scene(uniform_points(2500, 7));
  ExactEngine following;
  ExactEngine interrupted;
  Scene other = make_scene(uniform_points(2500, 8));
  for (int it = 0; it < 16; ++it) {
    const SceneCells a = following.compute(scene);
    if (it % 5 == 2) interrupted.compute(other);
    const SceneCells b = interrupted.compute(scene);
    ExactEngine fresh;
    const SceneCells c = fresh.compute(scene);
    EXPECT_TRUE(test::identical_cells(a, c)) << "call " << it;
    EXPECT_TRUE(test::identical_cells(b, c)) << "call " << it;
    std::vector<Scene> scenes{scene};
    move_to_centroids(scenes, std::span<const SceneCells>(&a, 1));
    scene = scenes[0];
  }
  EXPECT_EQ(following.last_topology_stats().rebuilds, 0u);
  EXPECT_EQ(following.last_topology_stats().kept_cells, 2500u);
}

// `calls` calls of a kept engine on `count` random sites (`seed`), each followed by the Lloyd
// move, once on each of 1, 2 and 7 threads: every call measures every cell from the
// triangulation, and each call's cells are the same bits on all three. `after_call(engine,
// scene, cells, threads, call)` checks more, before the move.
void expect_kept_calls_alike_on_thread_counts(
    std::size_t count, std::uint64_t seed, int calls,
    const std::function<void(const ExactEngine&, const Scene&, const SceneCells&, std::size_t, int)>& after_call) {
  const std::size_t before = thread_count();
  std::vector<std::vector<SceneCells>> runs;
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    Scene scene = make_scene(uniform_points(count, seed));
    ExactEngine engine;
    std::vector<SceneCells> run;
    for (int it = 0; it < calls; ++it) {
      run.push_back(engine.compute(scene));
      EXPECT_EQ(engine.last_topology_stats().kept_cells, count);
      if (after_call) after_call(engine, scene, run.back(), threads, it);
      std::vector<Scene> scenes{scene};
      move_to_centroids(scenes, std::span<const SceneCells>(&run.back(), 1));
      scene = scenes[0];
    }
    runs.push_back(std::move(run));
  }
  set_thread_count(before);
  for (std::size_t it = 0; it < runs[0].size(); ++it) {
    EXPECT_TRUE(test::identical_cells(runs[0][it], runs[1][it])) << "call " << it;
    EXPECT_TRUE(test::identical_cells(runs[0][it], runs[2][it])) << "call " << it;
  }
}

TEST(ExactTopology, BitIdenticalWhateverTheThreadCount) {
  expect_kept_calls_alike_on_thread_counts(12000, 12, 12, nullptr);
}

TEST(ExactTopology, ManyFlipsKeepTheCanonicalCorners) {
  // From random sites the first calls flip about a tenth of the edges, each flip carrying its four
  // vertices' canonical corners over from the ones they had (PeriodicDelaunay::flip) instead of
  // walking their stars; the second call also repairs (removals walk, merges and insertions
  // recompute the corners of what they wrote). A wrong corner starts a cell's sums elsewhere and
  // changes its bits: every call must equal a fresh engine's on the same sites, on 1, 2 and 7
  // threads alike.
  std::map<std::size_t, std::size_t> flips, repaired;  // per thread count
  expect_kept_calls_alike_on_thread_counts(
      20000, 21, 8,
      [&](const ExactEngine& engine, const Scene& scene, const SceneCells& cells, std::size_t threads, int it) {
        flips[threads] += engine.last_topology_stats().flips;
        repaired[threads] += engine.last_topology_stats().repaired_vertices;
        if (it >= 1 && it <= 3) {
          ExactEngine fresh;
          EXPECT_TRUE(test::identical_cells(cells, fresh.compute(scene))) << threads << " threads, call " << it;
        }
      });
  for (std::size_t threads : {1u, 2u, 7u}) {
    EXPECT_GT(flips[threads], 5000u) << threads << " threads";
    EXPECT_GT(repaired[threads], 0u) << threads << " threads";
  }
}

TEST(ExactTopology, ArraysOnHugePagesKeepTheirBits) {
  // Past kHugePageArray bytes a scene's sites (make_scene) and its cells (the engine's output)
  // move to memory advised for huge pages (core/huge_pages.h): the sites keep their values, and
  // the cells are the same bits in a fresh output, in one of another size and in one reused.
  const std::vector<Point> many = uniform_points(kHugePageArray / sizeof(Point) + 3, 20);
  EXPECT_EQ(make_scene(many).sites, many);
  std::vector<double> values(5, 1.0);
  assign_on_huge_pages(values, kHugePageArray / sizeof(double) + 3, 2.5);
  EXPECT_EQ(values, std::vector<double>(kHugePageArray / sizeof(double) + 3, 2.5));

  const std::size_t n = kHugePageArray / sizeof(Cell) + 1000;
  std::vector<Scene> scenes;
  scenes.push_back(make_scene(uniform_points(n, 21)));
  ExactEngine engine;
  const SceneCells fresh = engine.compute(scenes[0]);
  std::vector<SceneCells> out(1);
  out[0].cells.assign(7, Cell{});
  for (int call = 0; call < 2; ++call) {
    engine.compute(scenes, out);
    EXPECT_TRUE(test::identical_cells(fresh, out[0])) << "call " << call;
  }
  EXPECT_EQ(engine.last_topology_stats().kept_cells, n);
}

TEST(ExactTopology, SecondMomentsNotWantedLeaveEveryOtherBitAlone) {
  // Scene::second_moments false: the kept cells' second moments are not summed (left 0); every
  // other field has the bits it has when they are wanted, call after call, on 1, 2 and 7 threads.
  const std::size_t before = thread_count();
  auto same = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    Scene wanted = make_scene(uniform_points(6000, 21));
    Scene skipped = wanted;
    skipped.second_moments = false;
    ExactEngine with, without;
    for (int it = 0; it < 8; ++it) {
      const SceneCells a = with.compute(wanted);
      const SceneCells b = without.compute(skipped);
      EXPECT_EQ(without.last_topology_stats().kept_cells, 6000u) << threads << " threads, call " << it;
      ASSERT_EQ(a.cells.size(), b.cells.size());
      std::size_t differ = 0, moments = 0;
      for (std::size_t i = 0; i < a.cells.size(); ++i) {
        const Cell& x = a.cells[i];
        const Cell& y = b.cells[i];
        differ += !same(x.centroid.x, y.centroid.x) || !same(x.centroid.y, y.centroid.y) || !same(x.area, y.area) ||
                  !same(x.mass, y.mass) || !same(x.radius, y.radius) || x.status != y.status;
        moments += x.second_moment > 0.0 && y.second_moment == 0.0;
      }
      EXPECT_EQ(differ, 0u) << threads << " threads, call " << it;
      EXPECT_EQ(moments, a.cells.size()) << threads << " threads, call " << it;
      EXPECT_EQ(a.coincident_count, b.coincident_count);
      std::vector<Scene> scenes{wanted};
      move_to_centroids(scenes, std::span<const SceneCells>(&a, 1));
      wanted.sites = scenes[0].sites;
      skipped.sites = scenes[0].sites;
    }
  }
  set_thread_count(before);
}

TEST(ExactTopology, RectangularDomainWantedRangeAndWeightedCells) {
  const Domain domain{{2.0, 1.0}};
  Scene periodic = make_scene(relaxed_points(1500, 8, domain), domain);
  periodic.wanted_begin = 200;  // sites before it fixed, as in a progressive level
  EXPECT_EQ(run_side_by_side(periodic, 6).kept, 6u * 1300u);
  auto density = std::make_shared<DensityGrid>(64, 48);
  for (int j = 0; j < 48; ++j)
    for (int i = 0; i < 64; ++i) density->at(i, j) = 0.1f + static_cast<float>(i * j % 17) / 16.0f;
  Scene weighted = make_scene(uniform_points(2000, 9));
  weighted.density = density;
  ExactEngine engine = searching();
  LloydOptions options;
  options.iterations = 30;
  relax_lloyd(engine, weighted, options);
  EXPECT_EQ(run_side_by_side(weighted, 6).kept, 6u * 2000u);
}

TEST(ExactTopology, KeptCellsCountTheirStatuses) {
  // The kept path counts statuses as it measures: a density zero over a band of the domain gives
  // cells without density among kept ones, and the counts are the search's, call after call.
  auto density = std::make_shared<DensityGrid>(32, 32);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) density->at(i, j) = i < 6 ? 0.0f : 1.0f;
  Scene scene = make_scene(uniform_points(3000, 23));
  scene.density = density;
  ExactEngine kept;
  ExactEngine search = searching();
  for (int it = 0; it < 4; ++it) {
    const SceneCells a = kept.compute(scene);
    const SceneCells b = search.compute(scene);
    EXPECT_EQ(kept.last_topology_stats().kept_cells, 3000u) << it;
    std::size_t zero = 0;
    for (const Cell& c : b.cells) zero += c.status == CellStatus::zero_density;
    EXPECT_GT(zero, 100u) << it;
    EXPECT_EQ(a.zero_density_count, zero) << it;
    EXPECT_EQ(b.zero_density_count, zero) << it;
    EXPECT_EQ(a.coincident_count, 0u) << it;
    std::vector<Scene> scenes{scene};
    move_to_centroids(scenes, std::span<const SceneCells>(&a, 1));
    scene = scenes[0];
  }
}

TEST(ExactTopology, BoundedAndSmallScenesAreSearched) {
  const Domain domain{{2.0, 1.0}};
  Scene bounded = make_scene(relaxed_points(2400, 7, domain, Boundary::bounded), domain);
  bounded.boundary = Boundary::bounded;
  bounded.wanted_begin = 100;
  bounded.wanted_end = 2100;
  EXPECT_EQ(run_side_by_side(bounded, 3).kept, 0u);
  EXPECT_EQ(run_side_by_side(make_scene(uniform_points(200, 3)), 3).kept, 0u);
  // Searched cells are the search's own bits.
  Scene small = make_scene(uniform_points(200, 4));
  ExactEngine search = searching();
  EXPECT_TRUE(test::identical_cells(ExactEngine().compute(small), search.compute(small)));
}

std::vector<Point> square_lattice(int k, Point offset) {
  std::vector<Point> sites;
  for (int j = 0; j < k; ++j)
    for (int i = 0; i < k; ++i) sites.push_back({(i + offset.x) / k, (j + offset.y) / k});
  return sites;
}

// The lower `rows` rows of a k x k square lattice, and `extra` uniform sites above them: a patch of
// cocircular ties in a scene that is not on rows and columns as a whole (so it is triangulated).
std::vector<Point> lattice_band(int k, int rows, std::size_t extra, std::uint64_t seed) {
  std::vector<Point> sites = square_lattice(k, {0.5, 0.5});
  sites.resize(static_cast<std::size_t>(k) * static_cast<std::size_t>(rows));
  const double lower = (rows + 0.5) / k;
  for (Point p : uniform_points(extra, seed)) sites.push_back({p.x, lower + p.y * (1.0 - lower)});
  return sites;
}

void move_by_ulps(std::vector<Point>& sites, std::size_t count, std::uint64_t seed) {
  Rng rng(seed);
  for (std::size_t i = 0; i < count; ++i) {
    Point& p = sites[i];
    for (int k = static_cast<int>(rng.uniform() * 5.0) - 2; k != 0; k += k > 0 ? -1 : 1) p.x = std::nextafter(p.x, k > 0 ? 1.0 : 0.0);
    for (int k = static_cast<int>(rng.uniform() * 5.0) - 2; k != 0; k += k > 0 ? -1 : 1) p.y = std::nextafter(p.y, k > 0 ? 1.0 : 0.0);
  }
}

TEST(ExactTopology, CocircularTiesAreSearchedAndTheirNeighboursKept) {
  // A square lattice as a whole is on rows and columns: searched as a whole (the search's own
  // bits), no triangulation, whatever the calls before.
  const Scene lattice = make_scene(square_lattice(40, {0.5, 0.5}));
  ExactEngine engine;
  ExactEngine search = searching();
  for (int call = 0; call < 2; ++call) {
    EXPECT_TRUE(test::identical_cells(engine.compute(lattice), search.compute(lattice)));
    EXPECT_EQ(engine.last_topology_stats().kept_cells, 0u);
    EXPECT_EQ(engine.last_topology_stats().searched_cells, 1600u);
    EXPECT_EQ(engine.last_topology_stats().exact_stars, 0u);
  }
  // Fourteen lattice rows below uniform sites: four sites on every empty circle of the patch,
  // whose cells are on a tie and searched, the rest kept.
  const Scene band = make_scene(lattice_band(40, 14, 1040, 31));
  ExactEngine banded;
  for (int call = 0; call < 2; ++call) {
    const SceneCells a = banded.compute(band);
    const KeptTopologyStats stats = banded.last_topology_stats();
    EXPECT_GE(stats.tie_cells, 400u);
    EXPECT_GE(stats.kept_cells, 1000u);
    // The clipping's neighbours of a tie do not fit together: the stars came from the exact
    // predicates, once.
    EXPECT_EQ(stats.exact_stars, call == 0 ? 1600u : 0u);
    const Difference d = compare(band, a, search.compute(band));
    EXPECT_LE(d.centroid, 1e-12);
    EXPECT_LE(d.area, 1e-12);
  }
  // Shifted by a step each call (sites wrap across the border): still the same patch.
  run_side_by_side(band, 4, [](Scene& scene, int) {
    for (Point& p : scene.sites) p = wrap_point(p + Point{0.004, -0.003}, scene.domain);
  });
  // One lattice row moved by a tenth of a spacing: the ties there are gone, the rest stay.
  Scene sheared = band;
  for (int i = 0; i < 40; ++i) sheared.sites[7 * 40 + i].x += 0.1 / 40.0;
  const SceneCells a = banded.compute(sheared);
  const KeptTopologyStats stats = banded.last_topology_stats();
  EXPECT_GT(stats.kept_cells, 0u);
  EXPECT_GT(stats.tie_cells, 0u);
  const Difference d = compare(sheared, a, search.compute(sheared));
  EXPECT_LE(d.centroid, 1e-12);
  EXPECT_LE(d.area, 1e-12);
  ExactEngine fresh;
  EXPECT_TRUE(test::identical_cells(a, fresh.compute(sheared)));
}

TEST(ExactTopology, NearlyCocircularSitesAnUlpOffTheLattice) {
  // The band's lattice sites moved by at most an ulp or two: cocircular within rounding, not
  // exactly. The clipping's neighbours do not fit together; the stars come from the exact
  // predicates.
  std::vector<Point> sites = lattice_band(32, 12, 640, 33);
  move_by_ulps(sites, 32 * 12, 21);
  const Scene scene = make_scene(sites);
  ExactEngine engine;
  const SceneCells a = engine.compute(scene);
  ExactEngine search = searching();
  const Difference d = compare(scene, a, search.compute(scene));
  EXPECT_LE(d.centroid, 1e-12);
  EXPECT_LE(d.area, 1e-12);
  EXPECT_LE(d.second_moment, 1e-12);
  EXPECT_GT(engine.last_topology_stats().kept_cells, 0u);
  EXPECT_EQ(engine.last_topology_stats().exact_stars, sites.size());
  // A perturbed copy relaxed a few steps from here: flips only.
  run_side_by_side(scene, 3);
}

TEST(ExactTopology, LatticesGiveTheSameBitsWhateverCameBefore) {
  // A 70 x 70 lattice (searched as a whole: on rows and columns), the same moved by an ulp or two
  // (whichever path its sites choose) and by up to 1e-9 (triangulated): each the same bits fresh,
  // after the others (kept state from a scene of the same count) and on 1, 2 or 7 threads, within
  // 1e-12 of the search and of brute force.
  const int k = 70;
  const std::vector<Point> exact = square_lattice(k, {0.5, 0.5});
  std::vector<Point> ulps = exact;
  move_by_ulps(ulps, ulps.size(), 41);
  std::vector<Point> jittered = exact;
  Rng rng(42);
  for (Point& p : jittered) p = wrap_point(p + Point{(rng.uniform() - 0.5) * 2e-9, (rng.uniform() - 0.5) * 2e-9}, Domain{});
  const std::vector<Scene> scenes{make_scene(exact), make_scene(ulps), make_scene(jittered)};
  ExactEngine search = searching();
  std::vector<SceneCells> fresh;
  for (const Scene& scene : scenes) {
    fresh.push_back(ExactEngine().compute(scene));
    const Difference d = compare(scene, fresh.back(), search.compute(scene));
    EXPECT_LE(d.centroid, 1e-12);
    EXPECT_LE(d.area, 1e-12);
    EXPECT_LE(d.second_moment, 1e-12);
    EXPECT_TRUE(d.statuses);
    for (std::size_t w = 0; w < scene.sites.size(); w += 97) {
      const Reference r = brute_force(scene, w);
      EXPECT_NEAR(fresh.back().cells[w].area, r.area, 1e-12) << "site " << w;
      EXPECT_LE(scene_distance(scene, fresh.back().cells[w].centroid, r.centroid), 1e-12) << "site " << w;
    }
  }
  const std::size_t before = thread_count();
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    // Every order of calls on one engine, twice over: each result as the fresh one.
    for (int order = 0; order < 3; ++order) {
      ExactEngine engine;
      for (int call = 0; call < 6; ++call) {
        const std::size_t i = static_cast<std::size_t>(order + call) % 3;
        EXPECT_TRUE(test::identical_cells(engine.compute(scenes[i]), fresh[i])) << threads << " threads, scene " << i << ", call " << call;
      }
    }
  }
  set_thread_count(before);
}

TEST(ExactTopology, NearDegenerateCoincidentCollinearAndClustered) {
  // Pairs 1e-9 apart inside a relaxed set; each call moves them a little.
  std::vector<Point> sites = relaxed_points(1500, 10);
  for (std::size_t k = 0; k < 20; ++k) sites.push_back(sites[k * 37] + Point{1e-9, static_cast<double>(k % 3) * 1e-9});
  const SideBySide pairs = run_side_by_side(make_scene(sites), 6, [](Scene& scene, int it) {
    for (std::size_t k = 0; k < 20; ++k) scene.sites[1500 + k] = scene.sites[k * 37] + Point{1e-9 * (it + 1), 1e-9};
  });
  EXPECT_EQ(pairs.kept, 6u * 1520u);
  // Exact duplicates: the whole scene is searched (lowest index owns the cell); a Lloyd step
  // moves the owners off their twins, and the next call triangulates again.
  for (std::size_t k = 0; k < 6; ++k) sites.push_back(sites[k * 101 + 3]);
  ExactEngine engine;
  ExactEngine search = searching();
  const SceneCells twins = engine.compute(make_scene(sites));
  EXPECT_EQ(engine.last_topology_stats().kept_cells, 0u);
  EXPECT_EQ(twins.coincident_count, 6u);
  EXPECT_TRUE(test::identical_cells(twins, search.compute(make_scene(sites))));
  EXPECT_EQ(run_side_by_side(make_scene(sites), 3).kept, 2u * 1526u);
  // Collinear sites (three lines): empty circles of a third of the torus, searched.
  std::vector<Point> lines;
  for (int k = 0; k < 1200; ++k) lines.push_back({(k + 0.25) / 1200.0, 0.2 + 0.3 * (k % 3)});
  EXPECT_EQ(run_side_by_side(make_scene(lines), 3).kept, 0u);
  // A cluster straddling the corner: cells far larger than a tenth of the torus, searched; the
  // same cluster spread over a third of the torus has small cells, triangulated across the border.
  Rng rng(11);
  std::vector<Point> cluster, spread;
  for (int i = 0; i < 600; ++i) {
    const Point p{(rng.uniform() - 0.5) * 0.02, (rng.uniform() - 0.5) * 0.02};
    cluster.push_back(wrap_point(p, Domain{}));
  }
  for (int i = 0; i < 2000; ++i) spread.push_back(wrap_point({rng.uniform() * 0.999 - 0.4995, rng.uniform()}, Domain{}));
  EXPECT_EQ(run_side_by_side(make_scene(cluster), 3).kept, 0u);
  EXPECT_EQ(run_side_by_side(make_scene(spread), 3).kept, 3u * 2000u);
}

TEST(ExactTopology, ScenesTheFirstCallCannotTriangulateGiveTheSearchsBits) {
  // The first call searches every cell for its star and measures the cells only when the scene
  // turns out not to suit a triangulation: from the cell that shows it on (a circumcircle of a
  // tenth of a period), and the cells before it afterwards, by the same search. Every wanted cell
  // must then be the search's own bits, on any thread count (the threads' chunks see it at
  // different cells): uniform sites around an empty disc (the cells that show it come in the
  // middle of the buckets' order), three lines, exact twins; a wanted range inside the scene.
  Rng rng(17);
  std::vector<Point> hole;  // no site within 0.2 of the centre: an empty circle of a fifth of the torus
  while (hole.size() < 3000) {
    const Point p{rng.uniform(), rng.uniform()};
    if (std::hypot(p.x - 0.5, p.y - 0.5) > 0.2) hole.push_back(p);
  }
  std::vector<Point> lines;
  for (int k = 0; k < 1200; ++k) lines.push_back({(k + 0.25) / 1200.0, 0.2 + 0.3 * (k % 3)});
  std::vector<Point> twins = uniform_points(2000, 18);
  for (std::size_t k = 0; k < 4; ++k) twins.push_back(twins[k * 211 + 7]);
  const std::size_t before = thread_count();
  for (const std::vector<Point>* sites : {&hole, &lines, &twins}) {
    Scene scene = make_scene(*sites);
    scene.wanted_begin = 100;
    scene.wanted_end = sites->size() - 50;
    ExactEngine search = searching();
    const SceneCells expected = search.compute(scene);
    for (std::size_t threads : {1u, 2u, 7u}) {
      set_thread_count(threads);
      ExactEngine engine;
      const SceneCells cells = engine.compute(scene);
      EXPECT_EQ(engine.last_topology_stats().kept_cells, 0u) << sites->size() << " sites, " << threads << " threads";
      EXPECT_EQ(engine.last_topology_stats().rebuilds, 1u);
      EXPECT_TRUE(test::identical_cells(cells, expected)) << sites->size() << " sites, " << threads << " threads";
    }
  }
  set_thread_count(before);
}

TEST(ExactTopology, FoldedTrianglesAreRepairedAndManyAreRebuilt) {
  Scene scene = make_scene(relaxed_points(3000, 11));
  ExactEngine engine;
  ExactEngine search = searching();
  for (int it = 0; it < 3; ++it) engine.compute(scene);
  EXPECT_EQ(engine.last_topology_stats().rebuilds, 0u);
  // One site teleported across the torus and one pushed over its neighbour: the triangles
  // around them fold over; their vertices are removed and inserted again.
  scene.sites[17] = wrap_point(scene.sites[17] + Point{0.5, 0.5}, scene.domain);
  scene.sites[400] = wrap_point(scene.sites[400] + Point{1.5 / std::sqrt(3000.0), 0.0}, scene.domain);
  const SceneCells a = engine.compute(scene);
  KeptTopologyStats stats = engine.last_topology_stats();
  EXPECT_EQ(stats.rebuilds, 0u);
  EXPECT_GE(stats.repaired_vertices, 2u);
  EXPECT_LT(stats.repaired_vertices, 3000u / 16u);
  EXPECT_EQ(stats.kept_cells, 3000u);
  const Difference d = compare(scene, a, search.compute(scene));
  EXPECT_LE(d.centroid, 1e-12);
  EXPECT_LE(d.area, 1e-12);
  EXPECT_LE(d.second_moment, 1e-12);
  ExactEngine fresh;
  EXPECT_TRUE(test::identical_cells(a, fresh.compute(scene)));
  // Another set of sites of the same count: most triangles fold, the triangulation is rebuilt.
  Scene other = make_scene(uniform_points(3000, 12));
  const SceneCells b = engine.compute(other);
  stats = engine.last_topology_stats();
  EXPECT_EQ(stats.rebuilds, 1u);
  EXPECT_EQ(stats.repaired_vertices, 0u);
  ExactEngine fresh_other;
  EXPECT_TRUE(test::identical_cells(b, fresh_other.compute(other)));
}

// The stars of a k x k triangular lattice on the unit torus (each square cut along its rising
// diagonal): vertex i + k j at ((i + 0.5) / k, (j + 0.5) / k), its six neighbours counter-
// clockwise from the east, with the periods a copy across the border takes.
void lattice_stars(int k, std::vector<std::uint32_t>& star_start, std::vector<PeriodicDelaunay::StarEntry>& stars) {
  const int steps[6][2] = {{1, 0}, {1, 1}, {0, 1}, {-1, 0}, {-1, -1}, {0, -1}};
  star_start = {0};
  stars.clear();
  for (int j = 0; j < k; ++j) {
    for (int i = 0; i < k; ++i) {
      for (const auto& s : steps) {
        const int x = i + s[0], y = j + s[1];
        const int wx = (x + k) % k, wy = (y + k) % k;
        stars.push_back({static_cast<std::uint32_t>(wx + k * wy), static_cast<std::int8_t>((x - wx) / k),
                         static_cast<std::int8_t>((y - wy) / k)});
      }
      star_start.push_back(static_cast<std::uint32_t>(stars.size()));
    }
  }
}

TEST(ExactTopology, BuildFromStarsLinksTrianglesAndCanonicalCorners) {
  // PeriodicDelaunay::build finds each corner's triangle through the twin of each star entry (the
  // vertex in its neighbour's star) and reads each vertex's canonical corner off its star (the
  // corner before the neighbour of lowest site). Checked here against the definitions: every
  // neighbour link reciprocal, the corners around each vertex its star's, and the canonical corner
  // the one a walk around the vertex picks, with sites numbered in a scrambled order.
  const int k = 8;
  const std::size_t n = static_cast<std::size_t>(k * k);
  std::vector<std::uint32_t> star_start;
  std::vector<PeriodicDelaunay::StarEntry> stars;
  lattice_stars(k, star_start, stars);
  std::vector<Point> positions;
  std::vector<std::uint32_t> sites;
  for (std::size_t v = 0; v < n; ++v) {
    positions.push_back({(static_cast<double>(v % k) + 0.5) / k, (static_cast<double>(v / k) + 0.5) / k});
    sites.push_back(static_cast<std::uint32_t>((37 * v + 11) % n));  // a permutation: 37 is prime to 64
  }
  PeriodicDelaunay triangulation;
  triangulation.reset(Domain{}, positions, sites);
  ASSERT_TRUE(triangulation.build(star_start, stars));
  const auto triangles = triangulation.triangles();
  ASSERT_EQ(triangles.size(), 2 * n);
  using PD = PeriodicDelaunay;
  for (std::uint32_t t = 0; t < triangles.size(); ++t) {
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t l = triangles[t].neighbour[e];
      EXPECT_EQ(triangles[PD::triangle_of(l)].neighbour[PD::edge_of(l)], PD::link(t, e)) << "triangle " << t;
    }
  }
  for (std::uint32_t v = 0; v < n; ++v) {
    // Around the vertex from its canonical corner: the star's neighbours in order (each corner's
    // previous vertex is the star entry after the corner's), starting after the lowest site.
    const std::uint32_t start = triangulation.corner_of(v);
    EXPECT_EQ(triangles[PD::triangle_of(start)].vertex[PD::edge_of(start)], v);
    std::vector<std::uint32_t> around;
    std::uint32_t corner = start;
    do {
      const PD::Triangle& t = triangles[PD::triangle_of(corner)];
      around.push_back(t.vertex[PD::previous(PD::edge_of(corner))]);
      corner = triangulation.next_around(corner);
    } while (corner != start && around.size() <= 6);
    ASSERT_EQ(around.size(), 6u) << "vertex " << v;
    std::uint32_t lowest = 0;
    for (std::uint32_t w = 1; w < 6; ++w)
      if (sites[stars[star_start[v] + w].vertex] < sites[stars[star_start[v] + lowest].vertex]) lowest = w;
    for (std::uint32_t w = 0; w < 6; ++w)
      EXPECT_EQ(around[w], stars[star_start[v] + (lowest + w) % 6].vertex) << "vertex " << v << ", step " << w;
  }
  // Stars that do not fit together are refused: a neighbour's copy in the wrong period, and two
  // neighbours swapped (the twins are then found, the triangles do not close).
  std::vector<PeriodicDelaunay::StarEntry> shifted = stars;
  shifted[star_start[k + 1] + 2].shift_y = 1;
  triangulation.reset(Domain{}, positions, sites);
  EXPECT_FALSE(triangulation.build(star_start, shifted));
  std::vector<PeriodicDelaunay::StarEntry> swapped = stars;
  std::swap(swapped[star_start[k + 1] + 1], swapped[star_start[k + 1] + 2]);
  triangulation.reset(Domain{}, positions, sites);
  EXPECT_FALSE(triangulation.build(star_start, swapped));
  EXPECT_TRUE(triangulation.empty());
}

TEST(ExactTopology, FlipsInStripsReachTheDelaunayTriangulation) {
  // With many suspects make_delaunay flips first inside strips of vertices on all threads (a flip
  // only where the strip holds all six triangles it touches), then what the strips deferred on
  // the calling thread. A 64 x 64 lattice triangulated along one diagonal, its sites jittered by up
  // to a fifth of the spacing (two strips of 32 rows; every edge a suspect): afterwards every edge
  // passes the in-circle test, the links are reciprocal, every canonical corner is the one a walk
  // around its vertex picks, some flips were made in the strips and some after them, and 1, 2 and
  // 7 threads leave the same triangles in the same slots.
  using PD = PeriodicDelaunay;
  const int k = 64;
  const std::size_t n = static_cast<std::size_t>(k * k);
  std::vector<std::uint32_t> star_start;
  std::vector<PD::StarEntry> stars;
  lattice_stars(k, star_start, stars);
  const std::vector<Point> jitter = uniform_points(n, 31);
  std::vector<Point> positions;
  std::vector<std::uint32_t> sites;
  for (std::size_t v = 0; v < n; ++v) {
    const Point d = 0.2 * (jitter[v] - Point{0.5, 0.5});
    positions.push_back({(static_cast<double>(v % k) + 0.5 + d.x) / k, (static_cast<double>(v / k) + 0.5 + d.y) / k});
    sites.push_back(static_cast<std::uint32_t>((37 * v + 11) % n));
  }
  const std::size_t before = thread_count();
  std::vector<std::vector<std::uint32_t>> layouts;
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    PD triangulation;
    triangulation.reset(Domain{}, positions, sites);
    ASSERT_TRUE(triangulation.build(star_start, stars));
    std::vector<std::uint32_t> suspects, changed;
    for (std::uint32_t t = 0; t < 2 * n; ++t)
      for (int e = 0; e < 3; ++e) suspects.push_back(PD::link(t, e));
    ASSERT_TRUE(triangulation.make_delaunay(suspects, {}, changed));
    EXPECT_GT(triangulation.flips(), n / 4) << threads << " threads";
    EXPECT_GT(triangulation.strip_flips(), triangulation.flips() / 2) << threads << " threads";
    EXPECT_LT(triangulation.strip_flips(), triangulation.flips()) << threads << " threads";
    EXPECT_EQ(triangulation.tie_edges(), 0u);
    const auto triangles = triangulation.triangles();
    std::vector<std::uint32_t> layout;
    for (std::uint32_t t = 0; t < triangles.size(); ++t) {
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t l = triangles[t].neighbour[e];
        EXPECT_EQ(triangles[PD::triangle_of(l)].neighbour[PD::edge_of(l)], PD::link(t, e)) << "triangle " << t;
        EXPECT_LE(triangulation.test_edge(t, e).perturbed, 0) << "triangle " << t << ", edge " << e;
        layout.push_back(triangles[t].vertex[e]);
        layout.push_back(l);
      }
    }
    for (std::uint32_t v = 0; v < n; ++v) {
      const std::uint32_t start = triangulation.corner_of(v);
      std::uint32_t corner = start, lowest = start;
      int steps = 0;
      auto previous_site = [&](std::uint32_t c) {
        return sites[triangles[PD::triangle_of(c)].vertex[PD::previous(PD::edge_of(c))]];
      };
      do {
        EXPECT_EQ(triangles[PD::triangle_of(corner)].vertex[PD::edge_of(corner)], v);
        if (previous_site(corner) < previous_site(lowest)) lowest = corner;
        corner = triangulation.next_around(corner);
      } while (corner != start && ++steps < 64);
      EXPECT_EQ(lowest, start) << "vertex " << v;
    }
    layouts.push_back(std::move(layout));
  }
  set_thread_count(before);
  EXPECT_EQ(layouts[0], layouts[1]);
  EXPECT_EQ(layouts[0], layouts[2]);
}

TEST(ExactTopology, JitteredLatticesFlipInStripsOnExactPredicates) {
  // An 80 x 80 square lattice jittered by up to 1e-9, then jittered afresh call after call: the
  // four sites of every square are cocircular to within 1e-9, so the diagonals flip on the exact
  // predicates, thousands a call, most of them inside strips on all threads (three strips here).
  // Every call equals a fresh engine's bits, on 1, 2 and 7 threads, and the search's cells to 1e-12.
  const int k = 80;
  const std::vector<Point> lattice = square_lattice(k, {0.5, 0.5});
  auto jittered = [&](std::uint64_t seed) {
    std::vector<Point> sites = lattice;
    Rng rng(seed);
    for (Point& p : sites) p = wrap_point(p + Point{(rng.uniform() - 0.5) * 2e-9, (rng.uniform() - 0.5) * 2e-9}, Domain{});
    return make_scene(sites);
  };
  const std::size_t before = thread_count();
  ExactEngine search = searching();
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    ExactEngine engine;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const Scene scene = jittered(seed);
      const SceneCells a = engine.compute(scene);
      const KeptTopologyStats stats = engine.last_topology_stats();
      EXPECT_EQ(stats.rebuilds, seed == 1 ? 1u : 0u) << threads << " threads, seed " << seed;
      if (seed > 1) {
        EXPECT_GT(stats.flips, 1000u) << threads << " threads, seed " << seed;
      }
      EXPECT_TRUE(test::identical_cells(a, ExactEngine().compute(scene))) << threads << " threads, seed " << seed;
      if (threads == 2) {
        const Difference d = compare(scene, a, search.compute(scene));
        EXPECT_LE(d.centroid, 1e-12) << "seed " << seed;
        EXPECT_LE(d.area, 1e-12) << "seed " << seed;
        EXPECT_TRUE(d.statuses) << "seed " << seed;
      }
    }
  }
  set_thread_count(before);
}

TEST(ExactTopology, LargerRelaxationsAgreeWithTheSearch) {
  // 10^4 sites from random, every third call compared (the bench's --check runs 10^5 and 10^6).
  Scene scene = make_scene(uniform_points(10000, 13));
  ExactEngine kept;
  ExactEngine search = searching();
  for (int it = 0; it < 12; ++it) {
    const SceneCells a = kept.compute(scene);
    if (it % 3 == 0) {
      const Difference d = compare(scene, a, search.compute(scene));
      EXPECT_LE(d.centroid, 1e-12) << it;
      EXPECT_LE(d.area, 1e-12) << it;
      EXPECT_LE(d.second_moment, 1e-12) << it;
    }
    std::vector<Scene> scenes{scene};
    move_to_centroids(scenes, std::span<const SceneCells>(&a, 1));
    scene = scenes[0];
  }
}

// The sweep and the cell walks in SIMD lanes against the scalar forms (delaunay_sweep.h): `calls`
// calls of an engine with each, on 1, 2 and 7 threads, each call followed by the Lloyd move and
// `perturb`: the same cells bit for bit (an FMA or another order of operations in a lane changes
// the circumcentres' or the sums' last bits), the same flips and repairs. Returns the cells measured from the triangulation.
std::size_t expect_lanes_as_scalar(const Scene& start, int calls, const std::function<void(Scene&, int)>& perturb = {}) {
  const std::size_t before = thread_count();
  std::size_t kept = 0;
  for (std::size_t threads : {1u, 2u, 7u}) {
    set_thread_count(threads);
    ExactEngineOptions scalar_options;
    scalar_options.simd = false;
    ExactEngine lanes, scalar(scalar_options);
    Scene scene = start;
    for (int it = 0; it < calls; ++it) {
      const SceneCells a = lanes.compute(scene), b = scalar.compute(scene);
      EXPECT_TRUE(test::identical_cells(a, b)) << threads << " threads, call " << it;
      const KeptTopologyStats x = lanes.last_topology_stats(), y = scalar.last_topology_stats();
      EXPECT_EQ(x.kept_cells, y.kept_cells) << threads << " threads, call " << it;
      EXPECT_EQ(x.tie_cells, y.tie_cells) << threads << " threads, call " << it;
      EXPECT_EQ(x.flips, y.flips) << threads << " threads, call " << it;
      EXPECT_EQ(x.rebuilds, y.rebuilds) << threads << " threads, call " << it;
      EXPECT_EQ(x.repaired_vertices, y.repaired_vertices) << threads << " threads, call " << it;
      if (threads == 1) kept += x.kept_cells;
      std::vector<Scene> scenes{scene};
      move_to_centroids(scenes, std::span<const SceneCells>(&a, 1));
      scene = scenes[0];
      if (perturb) perturb(scene, it);
    }
  }
  set_thread_count(before);
  return kept;
}

TEST(ExactTopology, SweepLanesGiveTheScalarBits) {
  if (!detail::sweep_lanes_available()) std::printf("no AVX2 here (or BLUETILE_SIMD=0): both forms are scalar\n");
  // Random (folds repaired, many flips), relaxed, and every site moved a third of a period
  // between calls (the triangles across the border change).
  EXPECT_GT(expect_lanes_as_scalar(make_scene(uniform_points(6000, 21)), 6), 0u);
  Scene relaxed = make_scene(relaxed_points(3000, 22));
  EXPECT_GT(expect_lanes_as_scalar(relaxed, 4), 0u);
  relaxed.second_moments = false;  // the cell walk without its second moment
  EXPECT_GT(expect_lanes_as_scalar(relaxed, 4), 0u);
  EXPECT_GT(expect_lanes_as_scalar(make_scene(relaxed_points(3000, 23)), 4,
                                   [](Scene& scene, int) {
                                     for (Point& p : scene.sites) p = wrap_point(p + Point{1.0 / 3.0, 0.2}, scene.domain);
                                   }),
            0u);
  // A lattice moved by up to 1e-9 (equal edge lengths to within rounding: the canonical corner's
  // ties), by an ulp or two in a band (in-circle tests the filter cannot decide, exact ties), and
  // pairs of sites 1e-9 apart.
  std::vector<Point> jittered = square_lattice(60, {0.5, 0.5});
  Rng rng(24);
  for (Point& p : jittered) p = wrap_point(p + Point{(rng.uniform() - 0.5) * 2e-9, (rng.uniform() - 0.5) * 2e-9}, Domain{});
  EXPECT_GT(expect_lanes_as_scalar(make_scene(jittered), 3), 0u);
  std::vector<Point> band = lattice_band(32, 12, 640, 25);
  EXPECT_GT(expect_lanes_as_scalar(make_scene(band), 3), 0u);
  move_by_ulps(band, 32 * 12, 26);
  EXPECT_GT(expect_lanes_as_scalar(make_scene(band), 3), 0u);
  std::vector<Point> pairs = relaxed_points(1500, 27);
  for (std::size_t k = 0; k < 20; ++k) pairs.push_back(pairs[k * 37] + Point{1e-9, static_cast<double>(k % 3) * 1e-9});
  EXPECT_GT(expect_lanes_as_scalar(make_scene(pairs), 3), 0u);
  // Sites on a band across the border, and a rectangular domain.
  std::vector<Point> spread;
  for (int i = 0; i < 2000; ++i) spread.push_back(wrap_point({rng.uniform() * 0.999 - 0.4995, rng.uniform()}, Domain{}));
  EXPECT_GT(expect_lanes_as_scalar(make_scene(spread), 3), 0u);
  const Domain wide{{3.0, 0.75}};
  EXPECT_GT(expect_lanes_as_scalar(make_scene(relaxed_points(2000, 28, wide), wide), 3), 0u);
}

}  // namespace
}  // namespace bluetile
