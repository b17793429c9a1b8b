// A centroid engine on sites far from uniform: one Lloyd step's cells for sites on a line (in
// random and in index order), on a tilted line, on a diagonal line, on four parallel lines, nearly
// on a line and in a small cluster, next to uniform sites of the same N, as milliseconds per
// iteration (wall and CPU) and as a ratio to uniform. Repeats interleave the sets so that a
// machine shared with others drifts alike for all (docs/BENCHMARKS.md).
//   bluetile_degenerate_bench [--sizes 1000,2000,8000,32000] [--repeats 3] [--threads T]
//                             [--engine exact|raster] [--kinds line,ordered,...] [--max-cone-overlap X]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#if BLUETILE_BENCH_RASTER
#include "bluetile/raster/raster_engine.h"
#endif

using namespace bluetile;

namespace {

struct Kind {
  std::string key, name;
  std::function<Point(Rng&, std::size_t i, std::size_t n)> draw;
};

// The spacing of point i of n along a line, in index order.
double along(std::size_t i, std::size_t n) { return (static_cast<double>(i) + 0.5) / static_cast<double>(n); }

const std::vector<Kind> kKinds = {
    {"uniform", "uniform", [](Rng& rng, std::size_t, std::size_t) { return rng.point(Domain{}); }},
    {"line", "line y = 0.5", [](Rng& rng, std::size_t, std::size_t) { return Point{rng.uniform(), 0.5}; }},
    {"ordered", "line y = 0.5, in order", [](Rng&, std::size_t i, std::size_t n) { return Point{along(i, n), 0.5}; }},
    {"tilted", "tilted line, in order",
     [](Rng&, std::size_t i, std::size_t n) { return Point{0.1 + 0.8 * along(i, n), 0.2 + 0.6 * along(i, n)}; }},
    {"diagonal", "diagonal line", [](Rng& rng, std::size_t, std::size_t) { const double t = rng.uniform(); return Point{t, wrap_coordinate(t + 0.25, 1.0)}; }},
    {"parallel", "4 parallel lines, in order",
     [](Rng&, std::size_t i, std::size_t n) { return Point{along(i % (n / 4), n / 4), 0.125 + 0.25 * static_cast<double>(i / (n / 4) % 4)}; }},
    {"jitter", "line, 1e-9 jitter", [](Rng& rng, std::size_t, std::size_t) { return Point{rng.uniform(), 0.5 + 1e-9 * (rng.uniform() - 0.5)}; }},
    {"cluster", "cluster 0.002 wide", [](Rng& rng, std::size_t, std::size_t) { return wrap_point({0.999 + 0.002 * rng.uniform(), 0.999 + 0.002 * rng.uniform()}, Domain{}); }},
};

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Time {
  double wall_ms = 0.0, cpu_ms = 0.0;
};

Time time_iteration(const Scene& scene, CentroidEngine& engine) {
  const double cpu = cpu_seconds();
  const auto start = std::chrono::steady_clock::now();
  SceneCells cells = engine.compute(scene);
  const auto stop = std::chrono::steady_clock::now();
  if (cells.cells.size() != scene.sites.size()) std::abort();
  return {std::chrono::duration<double, std::milli>(stop - start).count(), 1e3 * (cpu_seconds() - cpu)};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"A centroid engine on sites far from uniform (on a line, tilted, diagonal, four parallel lines, nearly on "
               "a line, in a small cluster) next to uniform sites of the same N: one Lloyd step's cells, ms per "
               "iteration (wall and CPU) and the ratio to uniform, median of interleaved repeats",
               "bluetile_degenerate_bench"};
  std::vector<std::size_t> sizes = {1000, 2000, 8000, 32000};
  int repeats = 3, threads = 1;
  std::string engine_name = "exact";
  std::vector<std::string> kinds;
  double max_cone_overlap = -1.0;
  std::vector<std::string> kind_keys;
  for (const Kind& kind : kKinds) kind_keys.push_back(kind.key);
  // 4 sites at least: the four parallel lines take N / 4 each.
  bench::add_integers(app, "--sizes", sizes, 4LL, bench::kMaxCount, "numbers of sites")->delimiter(',');
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "interleaved repeats (the median is reported)");
  bench::add_integer(app, "--threads", threads, 1, bench::kMaxThreads, "CPU threads (default 1: per-site cost)");
  bench::add_name(app, "--engine", engine_name, {"exact", "raster"},
                  "exact or raster (default settings: area coverage, resolution from N)");
  bench::add_names(app, "--kinds", kinds, kind_keys, "sets to run besides uniform, which is always run")
      ->delimiter(',')
      ->default_str("all");
  auto* overlap = bench::add_real(app, "--max-cone-overlap", max_cone_overlap, {},
                                  "raster: RasterOptions::max_cone_overlap (0: the raster path on every scene)")
                      ->default_str("the engine's");
  if (!bench::parse(app, argc, argv)) return 0;
  bench::check_given(overlap, engine_name == "raster", "only with --engine raster");
  set_thread_count(static_cast<std::size_t>(threads));
  std::unique_ptr<CentroidEngine> engine;
  if (engine_name == "exact") {
    engine = std::make_unique<ExactEngine>();
#if BLUETILE_BENCH_RASTER
  } else if (engine_name == "raster") {
    RasterOptions options;
    if (max_cone_overlap >= 0.0) options.max_cone_overlap = max_cone_overlap;
    engine = std::make_unique<RasterEngine>(options);
#endif
  } else {
    std::fprintf(stderr, "bluetile_degenerate_bench: --engine '%s': not built into this benchmark\n", engine_name.c_str());
    return 1;
  }
  std::vector<const Kind*> chosen;
  for (const Kind& kind : kKinds)
    if (kinds.empty() || kind.key == "uniform" || std::find(kinds.begin(), kinds.end(), kind.key) != kinds.end()) chosen.push_back(&kind);
  std::printf("| N | sites | engine | ms per iteration | CPU ms | us per site | / uniform |\n|---|---|---|---|---|---|---|\n");
  for (std::size_t n : sizes) {
    std::vector<Scene> scenes;
    for (const Kind* kind : chosen) {
      Rng rng(n);
      std::vector<Point> sites(n);
      for (std::size_t i = 0; i < n; ++i) sites[i] = kind->draw(rng, i, n);
      scenes.push_back(make_scene(std::move(sites)));
    }
    time_iteration(scenes[0], *engine);  // warm-up: the raster engine's shaders and buffers
    std::vector<std::vector<double>> wall(chosen.size()), cpu(chosen.size());
    for (int r = 0; r < repeats; ++r)
      for (std::size_t k = 0; k < chosen.size(); ++k) {
        const Time t = time_iteration(scenes[k], *engine);
        wall[k].push_back(t.wall_ms);
        cpu[k].push_back(t.cpu_ms);
      }
    for (std::size_t k = 0; k < chosen.size(); ++k)
      std::printf("| %zu | %s | %s | %.2f | %.2f | %.2f | %.2f |\n", n, chosen[k]->name.c_str(), engine_name.c_str(), median(wall[k]),
                  median(cpu[k]), 1000.0 * median(wall[k]) / static_cast<double>(n), median(wall[k]) / median(wall[0]));
    std::fflush(stdout);
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_degenerate_bench");
}
