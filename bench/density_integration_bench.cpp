// What integrating a weighted cell costs, by itself: every cell polygon of a scene integrated by
// density_moments (texels cut along rows and columns) and by DensityPrefix (rows only, block
// tables), in site order, on one thread; then the exact engine on the same scene with and without
// the density. Sites drawn in proportion to a synthetic 1024^2 map (a dense disc and a ramp, with
// texel noise), bounded unit square. Prints the fastest of the repeats, microseconds per cell.
// Usage: bluetile_density_integration_bench [--counts 10000,100000] [--repeats 9]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "bench_args.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/density_prefix.h"
#include "bluetile/voronoi/exact_engine.h"

using namespace bluetile;

int main(int argc, char** argv) try {
  CLI::App app{"What integrating a weighted cell costs: density_moments against DensityPrefix per cell, and the exact "
               "engine with and without the density, on sites drawn from a synthetic 1024^2 map (microseconds per "
               "cell, the fastest of the repeats)",
               "bluetile_density_integration_bench"};
  std::vector<std::size_t> counts = {10000, 100000};
  int repeats = 9;
  bench::add_integers(app, "--counts", counts, 1LL, bench::kMaxCount, "Site counts")->delimiter(',');
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "Repeats (the fastest is reported)");
  if (!bench::parse(app, argc, argv)) return 0;

  constexpr int kTexels = 1024;
  auto grid = std::make_shared<DensityGrid>(kTexels, kTexels);
  Rng rng(5);
  for (int j = 0; j < kTexels; ++j) {
    for (int i = 0; i < kTexels; ++i) {
      const double u = (i + 0.5) / kTexels, v = (j + 0.5) / kTexels;
      const double base = std::hypot(u - 0.4, v - 0.55) < 0.25 ? 0.9 : 0.05 + 0.5 * u;
      grid->at(i, j) = static_cast<float>(base * (0.8 + 0.4 * rng.uniform()));
    }
  }
  const DensityPrefix prefix(*grid);
  set_thread_count(1);
  std::printf("| N | density_moments | DensityPrefix | engine unweighted | engine weighted | weighted / unweighted |\n");
  std::printf("|---|---|---|---|---|---|\n");
  for (std::size_t n : counts) {
    std::vector<Point> sites;
    while (sites.size() < n) {
      const Point p = rng.point(Domain{});
      const int i = std::min(kTexels - 1, static_cast<int>(p.x * kTexels));
      const int j = std::min(kTexels - 1, static_cast<int>(p.y * kTexels));
      if (rng.uniform() < grid->at(i, j)) sites.push_back(p);
    }
    Scene plain = make_scene(sites, Domain{});
    plain.boundary = Boundary::bounded;
    Scene weighted = plain;
    weighted.density = grid;
    const auto polygons = exact_cell_polygons(plain);
    ExactEngine engine;
    engine.compute(weighted);  // builds the tables once, as a relaxation's first iteration does
    using Clock = std::chrono::steady_clock;
    auto per_cell_us = [n](Clock::time_point a, Clock::time_point b) {
      return std::chrono::duration<double>(b - a).count() * 1e6 / static_cast<double>(n);
    };
    double best[4] = {1e30, 1e30, 1e30, 1e30}, sink = 0.0;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) sink += density_moments(polygons[i], sites[i], *grid, {1.0, 1.0}, false).second;
      const auto t1 = Clock::now();
      for (std::size_t i = 0; i < n; ++i) sink += prefix.moments(polygons[i], sites[i], {1.0, 1.0}, false).second;
      const auto t2 = Clock::now();
      sink += engine.compute(plain).cells[0].mass;
      const auto t3 = Clock::now();
      sink += engine.compute(weighted).cells[0].mass;
      const auto t4 = Clock::now();
      const double t[4] = {per_cell_us(t0, t1), per_cell_us(t1, t2), per_cell_us(t2, t3), per_cell_us(t3, t4)};
      for (int k = 0; k < 4; ++k) best[k] = std::min(best[k], t[k]);
    }
    std::printf("| %zu | %.3f | %.3f | %.3f | %.3f | %.2f |\n", n, best[0], best[1], best[2], best[3], best[3] / best[2]);
    if (sink == 0.125) std::printf("\n");  // keeps the sums alive
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_density_integration_bench");
}
