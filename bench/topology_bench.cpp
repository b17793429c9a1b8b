// The exact engine with and without the topology kept between calls (exact_engine.h), on Lloyd
// iterations continuing from relaxed sites, one engine after the other in one process, repeats
// interleaved, with CGAL's band reference beside them when CGAL is built. Prints a markdown table.
// Usage: bluetile_topology_bench [--sizes 10000,100000,1000000] [--relax 30] [--iterations 10]
//        [--threads 1,2] [--repeats 3] [--no-cgal]
//        [--profile search|kept --sizes N]   (only that engine, for perf)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#if BLUETILE_HAVE_CGAL
#include "cgal_reference.h"
#endif

using namespace bluetile;

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
// Process CPU time: on one thread the figure least disturbed by a loaded machine.
double cpu_now() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

struct Run {
  double seconds_per_iteration = 0.0;
  double cpu_seconds_per_iteration = 0.0;
  double kept_share = 0.0;  // of the timed cells, certified from the lists
  std::size_t bytes = 0;
  double max_centroid_error = 0.0, max_area_error = 0.0;  // against the full search, last iteration
};

// Two untimed iterations (the first searches, the second searches and makes the lists), then
// `iterations` timed ones, each one engine call and the move to the centroids.
Run lloyd_run(CentroidEngine& engine, const std::vector<Point>& start, int iterations, bool compare) {
  std::vector<Scene> scenes{make_scene(start)};
  std::vector<SceneCells> cells(1);
  for (int i = 0; i < 2; ++i) {
    engine.compute(scenes, cells);
    move_to_centroids(scenes, cells);
  }
  Run run;
  std::size_t kept = 0, all = 0;
  auto* exact = dynamic_cast<ExactEngine*>(&engine);
  const double t0 = now(), c0 = cpu_now();
  for (int i = 0; i < iterations; ++i) {
    engine.compute(scenes, cells);
    if (exact) {
      kept += exact->last_topology_stats().kept_cells;
      all += start.size();
    }
    if (i + 1 < iterations) move_to_centroids(scenes, cells);
  }
  run.seconds_per_iteration = (now() - t0) / iterations;
  run.cpu_seconds_per_iteration = (cpu_now() - c0) / iterations;
  if (exact) {
    run.kept_share = all ? static_cast<double>(kept) / static_cast<double>(all) : 0.0;
    run.bytes = exact->last_topology_stats().bytes;
  }
  if (compare) {
    ExactEngine search(ExactEngineOptions{false});
    const SceneCells fresh = search.compute(scenes[0]);
    for (std::size_t i = 0; i < fresh.cells.size(); ++i) {
      const Point d = torus_offset(fresh.cells[i].centroid, cells[0].cells[i].centroid, Domain{});
      run.max_centroid_error = std::max(run.max_centroid_error, std::hypot(d.x, d.y));
      run.max_area_error = std::max(run.max_area_error, std::abs(fresh.cells[i].area - cells[0].cells[i].area));
    }
  }
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Exact engine: topology kept between Lloyd iterations against the full search"};
  std::vector<std::size_t> sizes{10000, 100000, 1000000};
  std::vector<std::size_t> threads{1, 2};
  int relax = 30, iterations = 10, repeats = 3;
  bool no_cgal = false;
  std::string profile;
  app.add_option("--sizes", sizes, "Site counts")->delimiter(',');
  app.add_option("--relax", relax, "Lloyd iterations from random sites before timing")->capture_default_str();
  app.add_option("--iterations", iterations, "Timed iterations per run")->capture_default_str();
  app.add_option("--threads", threads, "Thread counts")->delimiter(',');
  app.add_option("--repeats", repeats, "Interleaved repeats (median reported)")->capture_default_str();
  app.add_flag("--no-cgal", no_cgal, "Skip the CGAL band reference");
  app.add_option("--profile", profile, "Run only this engine (search or kept), one thread, for a profiler");
  CLI11_PARSE(app, argc, argv);

  for (std::size_t n : sizes) {
    // Relaxed sites: uniform random ones after `relax` exact iterations (full search, all threads).
    std::vector<Scene> scenes{make_scene(uniform_random_points(n, 1, n))};
    {
      ExactEngine engine(ExactEngineOptions{false});
      LloydOptions options;
      options.iterations = relax;
      relax_lloyd(engine, scenes, options);
    }
    const std::vector<Point> relaxed = scenes[0].sites;

    if (!profile.empty()) {
      set_thread_count(1);
      ExactEngine engine(ExactEngineOptions{profile == "kept"});
      const Run r = lloyd_run(engine, relaxed, iterations, false);
      std::printf("%s N=%zu: %.1f ns per site and iteration (cpu %.1f), kept %.3f\n", profile.c_str(), n,
                  1e9 * r.seconds_per_iteration / static_cast<double>(n),
                  1e9 * r.cpu_seconds_per_iteration / static_cast<double>(n), r.kept_share);
      continue;
    }

    struct Row {
      std::string name;
      std::size_t threads;
      std::vector<double> times, cpu;
      Run last;
    };
    std::vector<Row> rows;
    Run compared;
    for (std::size_t t : threads) {
      rows.push_back({"search", t, {}, {}});
      rows.push_back({"kept", t, {}, {}});
    }
#if BLUETILE_HAVE_CGAL
    if (!no_cgal) rows.push_back({"cgal-band", 1, {}, {}});
#endif
    for (int r = 0; r < repeats; ++r) {
      for (std::size_t k = 0; k < rows.size(); ++k) {
        Row& row = rows[(k + static_cast<std::size_t>(r)) % rows.size()];
        set_thread_count(row.threads);
        std::unique_ptr<CentroidEngine> engine;
#if BLUETILE_HAVE_CGAL
        if (row.name == "cgal-band") engine = std::make_unique<bench::CgalBandEngine>();
#endif
        if (!engine) engine = std::make_unique<ExactEngine>(ExactEngineOptions{row.name == "kept"});
        row.last = lloyd_run(*engine, relaxed, iterations, row.name == "kept" && r == 0);
        if (r == 0 && row.name == "kept" && row.last.max_centroid_error >= compared.max_centroid_error) compared = row.last;
        row.times.push_back(row.last.seconds_per_iteration);
        row.cpu.push_back(row.last.cpu_seconds_per_iteration);
      }
    }
    double cgal = 0.0, search1 = 0.0, cgal_cpu = 0.0, search1_cpu = 0.0;
    for (const Row& row : rows) {
      if (row.name == "cgal-band") cgal = median(row.times), cgal_cpu = median(row.cpu);
      if (row.name == "search" && row.threads == 1) search1 = median(row.times), search1_cpu = median(row.cpu);
    }
    auto ratio = [](double a, double b) {
      char text[32];
      if (b > 0.0) std::snprintf(text, sizeof text, "%.3f", a / b); else std::snprintf(text, sizeof text, "-");
      return std::string(text);
    };
    std::printf("\nN = %zu, %d timed iterations after %d + 2, %d repeats (median)\n\n", n, iterations, relax, repeats);
    std::printf("| engine | threads | wall ms/it | wall ns/site/it | cpu ns/site/it | wall / search 1t | cpu / search 1t | wall / cgal-band | cpu / cgal-band | kept cells | kept state B/site |\n");
    std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const Row& row : rows) {
      const double m = median(row.times), c = median(row.cpu);
      const double per = 1e9 / static_cast<double>(n);
      std::printf("| %s | %zu | %.2f | %.0f | %.0f | %s | %s | %s | %s | %s | %s |\n", row.name.c_str(), row.threads, 1e3 * m,
                  per * m, per * c, ratio(m, search1).c_str(), ratio(c, search1_cpu).c_str(), ratio(m, cgal).c_str(),
                  ratio(c, cgal_cpu).c_str(), row.name == "kept" ? ratio(row.last.kept_share, 1.0).c_str() : "-",
                  row.name == "kept" ? ratio(static_cast<double>(row.last.bytes), static_cast<double>(n)).c_str() : "-");
    }
    std::printf("\nkept against a fresh full search on the last iteration's sites: max centroid difference %.3g, max area difference %.3g\n", compared.max_centroid_error, compared.max_area_error);
    std::fflush(stdout);
  }
  return 0;
}
