// The exact engine on sites far from uniform: one Lloyd step's cells for sites
// on a line, on a diagonal line, nearly on a line and in a small cluster, next to uniform sites
// of the same N, as milliseconds per iteration and as a ratio to uniform. Repeats interleave the
// sets so that a machine shared with others drifts alike for all (docs/BENCHMARKS.md).
//   bluetile_degenerate_bench [--sizes 1000,2000,8000,32000] [--repeats 3] [--threads T]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"

using namespace bluetile;

namespace {

struct Kind {
  std::string name;
  std::function<Point(Rng&)> draw;
};

const std::vector<Kind> kKinds = {
    {"uniform", [](Rng& rng) { return rng.point(Domain{}); }},
    {"line y = 0.5", [](Rng& rng) { return Point{rng.uniform(), 0.5}; }},
    {"diagonal line", [](Rng& rng) { const double t = rng.uniform(); return Point{t, wrap_coordinate(t + 0.25, 1.0)}; }},
    {"line, 1e-9 jitter", [](Rng& rng) { return Point{rng.uniform(), 0.5 + 1e-9 * (rng.uniform() - 0.5)}; }},
    {"cluster 0.002 wide", [](Rng& rng) { return wrap_point({0.999 + 0.002 * rng.uniform(), 0.999 + 0.002 * rng.uniform()}, Domain{}); }},
};

double milliseconds_per_iteration(const Scene& scene, ExactEngine& engine) {
  const auto start = std::chrono::steady_clock::now();
  SceneCells cells = engine.compute(scene);
  const auto stop = std::chrono::steady_clock::now();
  if (cells.cells.size() != scene.sites.size()) std::abort();
  return std::chrono::duration<double, std::milli>(stop - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bluetile_degenerate_bench: the exact engine on sites on a line or in a cluster"};
  std::vector<std::size_t> sizes = {1000, 2000, 8000, 32000};
  int repeats = 3, threads = 1;
  app.add_option("--sizes", sizes, "numbers of sites")->delimiter(',');
  app.add_option("--repeats", repeats, "interleaved repeats (the median is reported)");
  app.add_option("--threads", threads, "CPU threads (default 1: per-site cost)");
  CLI11_PARSE(app, argc, argv);
  set_thread_count(static_cast<std::size_t>(threads));
  ExactEngine engine;
  std::printf("| N | sites | ms per iteration | us per site | / uniform |\n|---|---|---|---|---|\n");
  for (std::size_t n : sizes) {
    std::vector<Scene> scenes;
    for (const Kind& kind : kKinds) {
      Rng rng(n);
      std::vector<Point> sites(n);
      for (Point& p : sites) p = kind.draw(rng);
      scenes.push_back(make_scene(std::move(sites)));
    }
    std::vector<std::vector<double>> times(kKinds.size());
    for (int r = 0; r < repeats; ++r)
      for (std::size_t k = 0; k < kKinds.size(); ++k) times[k].push_back(milliseconds_per_iteration(scenes[k], engine));
    std::vector<double> median(kKinds.size());
    for (std::size_t k = 0; k < kKinds.size(); ++k) {
      std::sort(times[k].begin(), times[k].end());
      median[k] = times[k][times[k].size() / 2];
    }
    for (std::size_t k = 0; k < kKinds.size(); ++k)
      std::printf("| %zu | %s | %.2f | %.2f | %.2f |\n", n, kKinds[k].name.c_str(), median[k],
                  1000.0 * median[k] / static_cast<double>(n), median[k] / median[0]);
  }
  return 0;
}
