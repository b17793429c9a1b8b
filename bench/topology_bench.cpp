// The exact engine with and without its kept Delaunay triangulation (exact_engine.h,
// kept_delaunay.h) on Lloyd iterations, with CGAL's band and periodic references beside them when
// CGAL is built: one process, the same sites for every engine, repeats interleaved. Two workloads
// per N: a relaxation from uniform random sites (--random-iterations steps, the first call
// included) and iterations continuing from relaxed sites (--relax steps of the search first, then
// 2 untimed and --iterations timed). Prints a markdown table per N.
// Usage: bluetile_topology_bench [--sizes 1000,10000,100000,1000000] [--starts random,relaxed]
//        [--relax 30] [--iterations 20] [--random-iterations 20] [--threads 1,2] [--repeats 3]
//        [--engines search,kept,cgal-band,cgal-periodic] [--max-cgal 1000000] [--check] [--caller-order]
//        [--no-energy]   (the exact engine asked for no second moments, as `bluetile relax` without a log)
//        [--profile search|kept --sizes N]   (that engine only, one thread, relaxed: for a profiler)
//        [--per-call]   (each timed call of every row: wall and CPU ns per site, rebuilds, flips, repaired)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "bench_args.h"
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
  // Over the timed calls of the kept engine: cells from the triangulation, rebuilds, flips, ties.
  double kept_share = 0.0;
  std::size_t rebuilds = 0, flips = 0, ties = 0, repaired = 0, exact_stars = 0;
  std::size_t bytes = 0;
  // Against the search on the same sites (--check): the largest differences over the calls.
  double max_centroid_difference = 0.0, max_area_difference = 0.0, max_moment_difference = 0.0;
  // Each timed call (--per-call): wall and CPU seconds, the kept engine's rebuilds, flips and
  // repaired vertices.
  struct Call {
    double seconds = 0.0, cpu = 0.0;
    std::size_t rebuilds = 0, flips = 0, repaired = 0;
  };
  std::vector<Call> calls;
};

void compare_with_search(const Scene& scene, const SceneCells& cells, Run& run) {
  ExactEngine search(ExactEngineOptions{false});
  const SceneCells fresh = search.compute(scene);
  for (std::size_t i = 0; i < fresh.cells.size(); ++i) {
    const Point d = torus_offset(fresh.cells[i].centroid, cells.cells[i].centroid, scene.domain);
    run.max_centroid_difference = std::max(run.max_centroid_difference, std::hypot(d.x, d.y));
    run.max_area_difference = std::max(run.max_area_difference, std::abs(fresh.cells[i].area - cells.cells[i].area));
    run.max_moment_difference =
        std::max(run.max_moment_difference, std::abs(fresh.cells[i].second_moment - cells.cells[i].second_moment));
  }
}

// `warm` untimed iterations, then `iterations` timed ones (one engine call and the move each).
Run lloyd_run(CentroidEngine& engine, const std::vector<Point>& start, int warm, int iterations, bool check, bool energy) {
  std::vector<Scene> scenes;
  scenes.push_back(make_scene(start));  // moved, not copied: its sites stay where make_scene put them
  scenes[0].second_moments = energy;
  std::vector<SceneCells> cells(1);
  for (int i = 0; i < warm; ++i) {
    engine.compute(scenes, cells);
    move_to_centroids(scenes, cells);
  }
  Run run;
  std::size_t kept = 0, all = 0;
  auto* exact = dynamic_cast<ExactEngine*>(&engine);
  double seconds = 0.0, cpu = 0.0;
  for (int i = 0; i < iterations; ++i) {
    const double t0 = now(), c0 = cpu_now();
    engine.compute(scenes, cells);
    Run::Call call;
    if (exact) {
      const KeptTopologyStats& stats = exact->last_topology_stats();
      call = {0.0, 0.0, stats.rebuilds, stats.flips, stats.repaired_vertices};
      kept += stats.kept_cells;
      all += start.size();
      run.rebuilds += stats.rebuilds;
      run.flips += stats.flips;
      run.ties += stats.tie_cells;
      run.repaired += stats.repaired_vertices;
      run.exact_stars += stats.exact_stars;
      run.bytes = std::max(run.bytes, stats.bytes);
    }
    move_to_centroids(scenes, cells);
    call.seconds = now() - t0;
    call.cpu = cpu_now() - c0;
    seconds += call.seconds;
    cpu += call.cpu;
    run.calls.push_back(call);
  }
  run.seconds_per_iteration = seconds / iterations;
  run.cpu_seconds_per_iteration = cpu / iterations;
  if (exact) run.kept_share = all ? static_cast<double>(kept) / static_cast<double>(all) : 0.0;
  if (check) {
    // The last sites, measured by this engine once more and by the search, second moments included.
    scenes[0].second_moments = true;
    const SceneCells last = engine.compute(scenes[0]);
    compare_with_search(scenes[0], last, run);
  }
  return run;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::string ratio(double a, double b) {
  char text[32];
  if (b > 0.0 && a > 0.0) {
    std::snprintf(text, sizeof text, "%.3f", a / b);
  } else {
    std::snprintf(text, sizeof text, "-");
  }
  return text;
}

std::unique_ptr<CentroidEngine> make_engine(const std::string& name) {
#if BLUETILE_HAVE_CGAL
  if (name == "cgal-band") return std::make_unique<bench::CgalBandEngine>();
  if (name == "cgal-periodic") return std::make_unique<bench::CgalPeriodicEngine>();
#endif
  return std::make_unique<ExactEngine>(ExactEngineOptions{name == "kept"});
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{"Exact engine: Delaunay triangulation kept between Lloyd iterations against the search and CGAL. Per N, "
               "a relaxation from uniform random sites and iterations continuing from relaxed sites, one markdown "
               "table each, repeats interleaved",
               "bluetile_topology_bench"};
  std::vector<std::size_t> sizes{1000, 10000, 100000, 1000000};
  std::vector<std::string> starts{"random", "relaxed"};
  std::vector<std::size_t> threads{1, 2};
  std::vector<std::string> engines{"search", "kept", "cgal-band", "cgal-periodic"};
  int relax = 30, iterations = 20, random_iterations = 20, repeats = 3;
  std::size_t max_cgal = 1000000;
  bool check = false, caller_order = false, no_energy = false, per_call = false;
  std::string profile;
  bench::add_integers(app, "--sizes", sizes, 1LL, bench::kMaxCount, "Site counts")->delimiter(',');
  bench::add_names(app, "--starts", starts, {"random", "relaxed"}, "random (a relaxation from random sites) and/or relaxed")
      ->delimiter(',');
  bench::add_integer(app, "--relax", relax, 0, bench::kMaxIterations,
                     "Search iterations from random sites that make the relaxed start");
  bench::add_integer(app, "--iterations", iterations, 1, bench::kMaxIterations, "Timed iterations from relaxed sites");
  bench::add_integer(app, "--random-iterations", random_iterations, 1, bench::kMaxIterations,
                     "Timed iterations from random sites");
  bench::add_integers(app, "--threads", threads, 1, bench::kMaxThreads, "Thread counts of the exact engine (CGAL: one)")
      ->delimiter(',');
  bench::add_names(app, "--engines", engines, {"search", "kept", "cgal-band", "cgal-periodic"},
                   "Engines (the CGAL ones only where CGAL is built)")
      ->delimiter(',');
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "Interleaved repeats (median reported)");
  bench::add_integer(app, "--max-cgal", max_cgal, 0LL, bench::kMaxCount, "Largest N for the CGAL references");
  app.add_flag("--check", check, "After each run, the last sites against a fresh search (differences reported)");
  app.add_flag("--caller-order", caller_order,
               "Keep the sites in the order they were drawn (at random) instead of the grid order relax_lloyd puts "
               "scenes of " + std::to_string(kGridOrderSites) + " sites and more in (kGridOrderSites, lloyd.h)");
  app.add_flag("--no-energy", no_energy,
               "Ask the exact engine for no second moments (Scene::second_moments), as bluetile relax without --log or -v");
  app.add_flag("--per-call", per_call,
               "After each table, every timed call of each row (median over the repeats): wall and CPU ns per site, "
               "and the kept engine's rebuilds, flips and repaired vertices (the last repeat's)");
  bench::add_name(app, "--profile", profile, {"search", "kept"},
                  "Run only this engine, one thread, relaxed, for a profiler")
      ->default_str("off");
  if (!bench::parse(app, argc, argv)) return 0;
#if !BLUETILE_HAVE_CGAL
  std::printf("CGAL not built: the CGAL reference rows are skipped\n");
  std::erase_if(engines, [](const std::string& e) { return e.rfind("cgal", 0) == 0; });
#endif

  for (std::size_t n : sizes) {
    std::vector<Point> random = uniform_random_points(n, 1, n);
    if (!caller_order && n >= kGridOrderSites) {
      // As relax_lloyd orders a scene for a relaxation: once, from its starting sites. The
      // relaxed start is made from these and kept in their order.
      const double t0 = now();
      const std::vector<std::uint32_t> order = grid_row_order(random, Domain{});
      std::vector<Point> drawn = random;
      for (std::size_t i = 0; i < n; ++i) random[i] = drawn[order[i]];
      const double seconds = now() - t0;
      std::printf("N = %zu: sites put in grid order in %.1f ms (%.1f ns per site, once per relaxation)\n", n,
                  1e3 * seconds, 1e9 * seconds / static_cast<double>(n));
    }
    std::vector<Point> relaxed;
    if (std::find(starts.begin(), starts.end(), "relaxed") != starts.end() || !profile.empty()) {
      std::vector<Scene> scenes{make_scene(random)};
      ExactEngine engine(ExactEngineOptions{false});
      LloydOptions options;
      options.iterations = relax;
      relax_lloyd(engine, scenes, options);
      relaxed = scenes[0].sites;
    }
    if (!profile.empty()) {
      set_thread_count(1);
      ExactEngine engine(ExactEngineOptions{profile == "kept"});
      const Run r = lloyd_run(engine, relaxed, 2, iterations, false, !no_energy);
      std::printf("%s N=%zu: %.1f ns per site and iteration (cpu %.1f)\n", profile.c_str(), n,
                  1e9 * r.seconds_per_iteration / static_cast<double>(n), 1e9 * r.cpu_seconds_per_iteration / static_cast<double>(n));
      continue;
    }
    for (const std::string& start : starts) {
      const bool from_random = start == "random";
      const std::vector<Point>& sites = from_random ? random : relaxed;
      const int timed = from_random ? random_iterations : iterations;
      const int warm = from_random ? 0 : 2;
      struct Row {
        std::string name;
        std::size_t threads;
        std::vector<double> times, cpu;
        Run last, checked;  // the last repeat, and the first (the one --check compares)
        std::vector<std::vector<double>> call_times, call_cpu;  // per call, over the repeats
      };
      std::vector<Row> rows;
      for (const std::string& e : engines) {
        if (e.rfind("cgal", 0) == 0) {
          if (n <= max_cgal) rows.push_back({e, 1, {}, {}, {}});
          continue;
        }
        for (std::size_t t : threads) rows.push_back({e, t, {}, {}, {}});
      }
      for (int r = 0; r < repeats; ++r) {
        for (std::size_t k = 0; k < rows.size(); ++k) {
          Row& row = rows[(k + static_cast<std::size_t>(r)) % rows.size()];
          set_thread_count(row.threads);
          auto engine = make_engine(row.name);
          row.last = lloyd_run(*engine, sites, warm, timed, check && r == 0 && row.name == "kept", !no_energy);
          if (r == 0) row.checked = row.last;
          row.times.push_back(row.last.seconds_per_iteration);
          row.cpu.push_back(row.last.cpu_seconds_per_iteration);
          row.call_times.resize(row.last.calls.size());
          row.call_cpu.resize(row.last.calls.size());
          for (std::size_t i = 0; i < row.last.calls.size(); ++i) {
            row.call_times[i].push_back(row.last.calls[i].seconds);
            row.call_cpu[i].push_back(row.last.calls[i].cpu);
          }
        }
      }
      double band = 0.0, search1 = 0.0, band_cpu = 0.0, search1_cpu = 0.0;
      for (const Row& row : rows) {
        if (row.name == "cgal-band") band = median(row.times), band_cpu = median(row.cpu);
        if (row.name == "search" && row.threads == 1) search1 = median(row.times), search1_cpu = median(row.cpu);
      }
      char after[64];
      std::snprintf(after, sizeof after, " after %d + 2", relax);
      std::printf("\nN = %zu, %s: %d timed iterations%s, %d repeats (median)\n\n", n, start.c_str(), timed,
                  from_random ? " from uniform random sites" : after, repeats);
      std::printf("| engine | threads | wall ms/it | wall ns/site/it | cpu ns/site/it | wall / search 1t | cpu / search 1t | wall / cgal-band | cpu / cgal-band | kept cells | rebuilds | repaired | flips/site/it | kept state B/site |\n");
      std::printf("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
      const double per = 1e9 / static_cast<double>(n);
      for (const Row& row : rows) {
        const double m = median(row.times), c = median(row.cpu);
        const bool kept = row.name == "kept";
        char flips[32] = "-", bytes[32] = "-", share[32] = "-", rebuilds[32] = "-", repaired[32] = "-";
        if (kept) {
          std::snprintf(flips, sizeof flips, "%.3f", static_cast<double>(row.last.flips) / (static_cast<double>(n) * timed));
          std::snprintf(bytes, sizeof bytes, "%.0f", static_cast<double>(row.last.bytes) / static_cast<double>(n));
          std::snprintf(share, sizeof share, "%.3f", row.last.kept_share);
          std::snprintf(rebuilds, sizeof rebuilds, "%zu of %d", row.last.rebuilds, timed);
          std::snprintf(repaired, sizeof repaired, "%zu", row.last.repaired);
        }
        std::printf("| %s | %zu | %.3f | %.0f | %.0f | %s | %s | %s | %s | %s | %s | %s | %s | %s |\n", row.name.c_str(),
                    row.threads, 1e3 * m, per * m, per * c, ratio(m, search1).c_str(), ratio(c, search1_cpu).c_str(),
                    ratio(m, band).c_str(), ratio(c, band_cpu).c_str(), share, rebuilds, repaired, flips, bytes);
      }
      if (per_call) {
        for (const Row& row : rows) {
          std::printf("\n%s, %zu threads, each call (median of the repeats; counts of the last one):\n\n", row.name.c_str(), row.threads);
          std::printf("| call | wall ns/site | cpu ns/site | rebuilds | flips/site | repaired |\n|---:|---:|---:|---:|---:|---:|\n");
          for (std::size_t i = 0; i < row.call_times.size(); ++i) {
            const Run::Call& call = row.last.calls[i];
            std::printf("| %zu | %.0f | %.0f | %zu | %.4f | %zu |\n", i + 1, per * median(row.call_times[i]), per * median(row.call_cpu[i]),
                        call.rebuilds, static_cast<double>(call.flips) / static_cast<double>(n), call.repaired);
          }
        }
      }
      if (check) {
        for (const Row& row : rows) {
          if (row.name != "kept") continue;
          std::printf("\nkept (%zu threads) against a fresh search on the last sites: max centroid difference %.3g, area %.3g, second moment %.3g\n",
                      row.threads, row.checked.max_centroid_difference, row.checked.max_area_difference,
                      row.checked.max_moment_difference);
          break;
        }
      }
      std::fflush(stdout);
    }
  }
  return 0;
} catch (...) {
  return bench::exit_status("bluetile_topology_bench");
}
