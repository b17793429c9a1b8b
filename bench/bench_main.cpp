// bluetile_bench: the centroid engines side by side on the same inputs, in one process.
//
// For every N and start (uniform random sites, or sites after some exact Lloyd iterations) and
// every engine: time of one Lloyd iteration (engine call plus moving the sites; median of
// repeats after warm-ups, every repeat starting from the same sites), working memory, and the
// centroid error against the exact engine. Then the paper's workload (1000 sites, 80
// iterations) per engine. Writes a CSV, a markdown report and log-log PNG plots.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <time.h>

#include "alloc_tracker.h"
#include "bench_args.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "loglog_plot.h"
#include "machine.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"

#ifdef BLUETILE_HAVE_CGAL
#include "cgal_reference.h"
#endif
#ifdef BLUETILE_BENCH_RASTER
#include "bluetile/raster/raster_engine.h"
#endif

namespace bluetile::bench {
namespace {

using Clock = std::chrono::steady_clock;

struct Options {
  bool quick = false;
  std::vector<std::size_t> sizes;
  std::vector<std::string> starts{"random", "relaxed"};
  std::vector<std::string> engines;  // empty: all
  int repeats = 0;                   // 0: by N
  int warmup = 1;
  int relax_iterations = 0;          // 0: default for the mode
  std::size_t max_cgal_periodic = 1000000;
  std::size_t max_cgal_band = 1000000;
  std::size_t max_raster = 100000;
  std::vector<int> raster_resolutions{256, 512, 1024, 2048};
  bool paper = true;
  bool check = false;
  std::uint64_t seed = 1;
  int threads = 0;
  std::string csv, markdown, plot_dir;
};

// One engine configuration to measure.
struct EngineSpec {
  std::string engine;  // family: exact, cgal-periodic, cgal-band, raster
  std::string mode;    // settings that distinguish curves (threads, coverage, cone)
  int resolution = 0;  // raster only; rows of one mode form a curve over resolutions
  std::size_t max_n = 0;
  std::size_t threads = 0;  // 0: the configured default
  bool in_paper_row = true;
  std::function<std::unique_ptr<CentroidEngine>()> make;

  std::string label() const {
    std::string s = engine + (mode.empty() ? "" : " " + mode);
    return resolution ? s + " " + std::to_string(resolution) : s;
  }
};

struct Row {
  std::string engine, mode;
  int resolution = 0;
  std::size_t n = 0;
  std::string start;
  std::size_t threads = 0;
  int repeats = 0;
  double median_ms = 0, min_ms = 0;
  double cpu_ms = 0;  // process CPU time per iteration (all threads), median
  double heap_peak_mib = 0, malloc_held_mib = 0;
  double err_mean = 0, err_max = 0;
  std::size_t coincident = 0, fallbacks = 0;
  std::string note;
};

struct PaperRow {
  std::string label;
  std::size_t threads = 0;
  double total_s = 0;
  double final_energy = 0;
  double max_deviation = 0;  // of the final sites from the exact engine's final sites
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

double mib(double bytes) { return bytes / (1024.0 * 1024.0); }

std::vector<Point> random_sites(std::size_t n, std::uint64_t seed) {
  Rng rng(derive_seed(seed, n));
  std::vector<Point> sites(n);
  for (Point& p : sites) p = rng.point(Domain{});
  return sites;
}

std::vector<Point> relaxed_sites(std::size_t n, std::uint64_t seed, int iterations) {
  Scene scene = make_scene(random_sites(n, seed));
  ExactEngine exact;
  LloydOptions lloyd;
  lloyd.iterations = iterations;
  relax_lloyd(exact, scene, lloyd);
  return scene.sites;
}

int default_repeats(std::size_t n, bool quick) {
  if (quick) return 3;
  if (n <= 1000) return 21;
  if (n <= 10000) return 11;
  if (n <= 100000) return 5;
  return 3;
}

void apply_threads(const EngineSpec& spec, std::size_t default_threads) {
  set_thread_count(spec.threads ? spec.threads : default_threads);
}

double process_cpu_ms() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) * 1e3 + static_cast<double>(t.tv_nsec) * 1e-6;
}

// One engine being measured on one input.
struct Trial {
  const EngineSpec* spec = nullptr;
  std::unique_ptr<CentroidEngine> engine;
  Scene scene;
  SceneCells cells;
  std::vector<double> wall_ms, cpu_ms;
  Row row;
};

// One Lloyd iteration from `input`: the engine call plus moving the sites.
void iterate(Trial& t, const std::vector<Point>& input, bool keep_time) {
  std::copy(input.begin(), input.end(), t.scene.sites.begin());
  const double c0 = process_cpu_ms();
  auto t0 = Clock::now();
  t.engine->compute(std::span<const Scene>(&t.scene, 1), std::span<SceneCells>(&t.cells, 1));
  for (std::size_t i = 0; i < t.cells.cells.size(); ++i) t.scene.sites[i] = t.cells.cells[i].centroid;
  auto t1 = Clock::now();
  const double c1 = process_cpu_ms();
  if (keep_time) {
    t.wall_ms.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    t.cpu_ms.push_back(c1 - c0);
  }
}

// Builds the engine and runs its warm-ups alone, measuring its memory and its error against
// `reference` on the first call.
void prepare(Trial& t, const EngineSpec& spec, const std::vector<Point>& input, const std::vector<Cell>& reference,
             const std::string& start, int warmup, std::size_t default_threads) {
  apply_threads(spec, default_threads);
  t.spec = &spec;
  Row& row = t.row;
  row.engine = spec.engine, row.mode = spec.mode, row.resolution = spec.resolution;
  row.n = input.size(), row.start = start, row.threads = thread_count();

  // The scene and the output are allocated before the heap mark, so it counts only what the
  // engine itself holds or allocates while it works.
  t.scene = make_scene(input);
  t.cells.cells.reserve(input.size());
  heap_reset_peak();
  const std::size_t live_before = heap_live_bytes();
  const std::size_t malloc_before = malloc_held_bytes();
  t.engine = spec.make();
  for (int r = 0; r < warmup; ++r) {
    iterate(t, input, false);
    if (r > 0) continue;
    double sum = 0, worst = 0;
    for (std::size_t i = 0; i < t.cells.cells.size(); ++i) {
      double e = torus_distance(t.cells.cells[i].centroid, reference[i].centroid, Domain{});
      sum += e;
      worst = std::max(worst, e);
    }
    row.err_mean = sum / static_cast<double>(t.cells.cells.size());
    row.err_max = worst;
    row.coincident = t.cells.coincident_count;
    row.fallbacks = t.cells.fallback_count;
  }
  row.heap_peak_mib = heap_tracking_enabled() ? mib(static_cast<double>(heap_peak_bytes() - live_before)) : 0.0;
  std::size_t malloc_after = malloc_held_bytes();
  row.malloc_held_mib = mib(malloc_after > malloc_before ? static_cast<double>(malloc_after - malloc_before) : 0.0);
#ifdef BLUETILE_HAVE_CGAL
  if (auto* band = dynamic_cast<CgalBandEngine*>(t.engine.get())) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "band w = %.2f/sqrt(N) after %d widenings",
                  band->last_band_width() * std::sqrt(double(row.n)), band->last_widenings());
    row.note = buf;
  }
#endif
}

// Engines on one input. Timed repeats are interleaved (round r runs every engine once, the
// order rotating by r) so that load from other processes on a shared machine falls on all
// engines alike: the ratios stay meaningful even when absolute times drift. An engine that
// throws (say, a resolution too small for N) is reported on stderr and left out.
std::vector<Row> measure_interleaved(const std::vector<const EngineSpec*>& specs, const std::vector<Point>& input,
                                     const std::vector<Cell>& reference, const std::string& start, int warmup,
                                     int repeats, std::size_t default_threads) {
  std::vector<Trial> trials;
  trials.reserve(specs.size());
  for (const EngineSpec* spec : specs) {
    trials.emplace_back();
    try {
      prepare(trials.back(), *spec, input, reference, start, warmup, default_threads);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "  %-34s failed: %s\n", spec->label().c_str(), e.what());
      trials.pop_back();
    }
  }
  for (int r = 0; r < repeats; ++r)
    for (std::size_t j = 0; j < trials.size(); ++j) {
      Trial& t = trials[(j + static_cast<std::size_t>(r)) % trials.size()];
      apply_threads(*t.spec, default_threads);
      iterate(t, input, true);
    }
  std::vector<Row> rows;
  for (Trial& t : trials) {
#ifdef BLUETILE_BENCH_RASTER
    // Where a raster iteration's time goes (over warm-ups and repeats), to guide its tuning.
    if (auto* raster = dynamic_cast<RasterEngine*>(t.engine.get())) {
      const RasterStats& st = raster->stats();
      const double calls = static_cast<double>(std::max<std::uint64_t>(st.computes, 1));
      char buf[160];
      std::snprintf(buf, sizeof buf, "per call: device %.1f ms + upload %.1f ms + host %.1f ms; %.2f passes; %.0f boundary px",
                    st.device_seconds * 1e3 / calls, st.upload_seconds * 1e3 / calls, st.host_seconds * 1e3 / calls,
                    static_cast<double>(st.scene_passes) / calls, static_cast<double>(st.boundary_pixels) / calls);
      t.row.note = buf;
    }
#endif
    t.row.repeats = repeats;
    t.row.median_ms = median(t.wall_ms);
    t.row.min_ms = *std::min_element(t.wall_ms.begin(), t.wall_ms.end());
    t.row.cpu_ms = median(t.cpu_ms);
    rows.push_back(t.row);
  }
  set_thread_count(default_threads);
  return rows;
}

// CPU engines are timed interleaved; each raster configuration is timed on its own right after
// (one Vulkan device and its driver threads alive at a time, not sixteen).
std::vector<Row> measure_all(const std::vector<const EngineSpec*>& specs, const std::vector<Point>& input,
                             const std::vector<Cell>& reference, const std::string& start, int warmup, int repeats,
                             std::size_t default_threads) {
  std::vector<const EngineSpec*> cpu;
  std::vector<Row> rows;
  for (const EngineSpec* s : specs)
    if (s->engine != "raster") cpu.push_back(s);
  rows = measure_interleaved(cpu, input, reference, start, warmup, repeats, default_threads);
  for (const EngineSpec* s : specs)
    if (s->engine == "raster")
      // At most 5 timed repeats: sixteen configurations at up to 2048^2 on a software rasterizer.
      for (const Row& r : measure_interleaved({s}, input, reference, start, warmup, std::min(repeats, 5), default_threads))
        rows.push_back(r);
  return rows;
}

#ifdef BLUETILE_BENCH_RASTER
// The raster engine in every coverage and cone variant over the resolutions asked for. The
// paper-workload rows use 1024 pixels, the resolution DESIGN section 3 measured.
void add_raster_specs(const Options& o, std::vector<EngineSpec>& specs) {
  for (Coverage coverage : {Coverage::point, Coverage::area})
    for (ConeShape cone : {ConeShape::quad, ConeShape::fan})
      for (int resolution : o.raster_resolutions) {
        RasterOptions options;
        options.resolution = resolution;
        options.coverage = coverage;
        options.cone = cone;
        std::string mode = std::string(coverage == Coverage::point ? "point" : "area") + " " +
                           (cone == ConeShape::quad ? "quad" : "fan");
        specs.push_back({"raster", mode, resolution, o.max_raster, 0, resolution == 1024,
                         [options] { return std::make_unique<RasterEngine>(options); }});
      }
}
#endif

std::vector<EngineSpec> engine_specs(const Options& o) {
  std::vector<EngineSpec> specs;
  // The exact engine's search: every repeat measures the same sites, which the kept Delaunay
  // triangulation (the engine's default) would measure without a flip, not as a Lloyd run does;
  // its Lloyd runs are bluetile_topology_bench's.
  auto exact = [] { return std::make_unique<ExactEngine>(ExactEngineOptions{false}); };
  specs.push_back({"exact", "", 0, SIZE_MAX, 0, true, exact});
  if (thread_count() > 1) specs.push_back({"exact", "1 thread", 0, SIZE_MAX, 1, true, exact});
#ifdef BLUETILE_HAVE_CGAL
  specs.push_back({"cgal-periodic", "", 0, o.max_cgal_periodic, 1, true, [] { return std::make_unique<CgalPeriodicEngine>(); }});
  specs.push_back({"cgal-band", "", 0, o.max_cgal_band, 1, true, [] { return std::make_unique<CgalBandEngine>(); }});
#endif
#ifdef BLUETILE_BENCH_RASTER
  add_raster_specs(o, specs);
#endif
  if (!o.engines.empty()) {
    std::erase_if(specs, [&](const EngineSpec& s) {
      return std::find(o.engines.begin(), o.engines.end(), s.engine) == o.engines.end();
    });
  }
  return specs;
}

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string sci(double v) { return v == 0.0 ? "0" : format("%.2e", v); }

// Quoted when it holds a comma or a quote (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::string csv_text(const std::vector<Row>& rows, const std::vector<PaperRow>& paper) {
  std::ostringstream out;
  out << "engine,mode,resolution,n,start,threads,repeats,median_ms,min_ms,cpu_ms,sites_per_s,heap_peak_mib,"
         "malloc_held_mib,err_mean,err_max,coincident,fallbacks,note\n";
  for (const Row& r : rows) {
    out << r.engine << ',' << csv_field(r.mode) << ',' << r.resolution << ',' << r.n << ',' << r.start << ',' << r.threads << ','
        << r.repeats << ',' << format("%.6g", r.median_ms) << ',' << format("%.6g", r.min_ms) << ','
        << format("%.6g", r.cpu_ms) << ','
        << format("%.6g", double(r.n) / (r.median_ms * 1e-3)) << ',' << format("%.4f", r.heap_peak_mib) << ','
        << format("%.4f", r.malloc_held_mib) << ',' << format("%.6e", r.err_mean) << ',' << format("%.6e", r.err_max)
        << ',' << r.coincident << ',' << r.fallbacks << ',' << csv_field(r.note) << '\n';
  }
  for (const PaperRow& p : paper) {
    out << "paper-workload:" << p.label << ",80 iterations,0,1000,random," << p.threads << ",1,"
        << format("%.6g", p.total_s * 1e3) << ",,,,,," << format("%.6e", p.max_deviation) << ",,,total time\n";
  }
  return out.str();
}

const Row* find_row(const std::vector<Row>& rows, std::size_t n, const std::string& start, const std::string& engine,
                    const std::string& mode) {
  for (const Row& r : rows)
    if (r.n == n && r.start == start && r.engine == engine && r.mode == mode) return &r;
  return nullptr;
}

std::string markdown_text(const Options& o, const std::string& command,
                          const std::vector<std::pair<std::string, std::string>>& facts, const std::vector<Row>& rows,
                          const std::vector<PaperRow>& paper, std::size_t default_threads) {
  std::ostringstream md;
  md << "Command: `" << command << "`\n\n";
  md << "| machine | |\n|---|---|\n";
  for (auto& [k, v] : facts) md << "| " << k << " | " << v << " |\n";
  md << "\nTimes are per Lloyd iteration (engine call plus moving the sites), median of the repeats after "
     << o.warmup << " warm-up, every repeat from the same sites. Error: torus distance between the engine's "
        "centroid and the exact engine's, mean and max over sites. Heap: peak bytes allocated through "
        "operator new while the engine was built and run (its working memory; input and output excluded); "
        "malloc held: growth of glibc's held memory (mallinfo2) with the engine alive, which also sees C "
        "allocations such as the Vulkan driver's.\n\n";

  std::vector<std::size_t> sizes;
  for (const Row& r : rows)
    if (std::find(sizes.begin(), sizes.end(), r.n) == sizes.end()) sizes.push_back(r.n);

  md << "### Headline ratios (same run): time per iteration of the CGAL references over the exact engine\n\n";
  md << "| N | start | exact ms (" << default_threads << " threads) | exact ms (1 thread) | cgal-periodic ms | "
        "periodic / exact | periodic / exact 1t | cgal-band ms | band / exact | band / exact 1t |\n"
        "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t n : sizes)
    for (const std::string& start : o.starts) {
      const Row* ex = find_row(rows, n, start, "exact", "");
      if (!ex) continue;
      const Row* ex1 = find_row(rows, n, start, "exact", "1 thread");
      const Row* per = find_row(rows, n, start, "cgal-periodic", "");
      const Row* band = find_row(rows, n, start, "cgal-band", "");
      auto ms = [](const Row* r) { return r ? format("%.3f", r->median_ms) : std::string("-"); };
      auto ratio = [](const Row* a, const Row* b) {
        return a && b ? format("%.2fx", a->median_ms / b->median_ms) : std::string("-");
      };
      md << "| " << n << " | " << start << " | " << ms(ex) << " | " << ms(ex1) << " | " << ms(per) << " | "
         << ratio(per, ex) << " | " << ratio(per, ex1) << " | " << ms(band) << " | " << ratio(band, ex) << " | "
         << ratio(band, ex1) << " |\n";
    }

  md << "\n### Growth with N: exact engine, nanoseconds per site per iteration\n\n| start | threads |";
  for (std::size_t n : sizes) md << " N=" << n << " |";
  md << "\n|---|---:|";
  for (std::size_t i = 0; i < sizes.size(); ++i) md << "---:|";
  md << "\n";
  for (const std::string& start : o.starts)
    for (const std::string mode : {"", "1 thread"}) {
      if (!find_row(rows, sizes.empty() ? 0 : sizes[0], start, "exact", mode)) continue;
      md << "| " << start << " | " << (mode.empty() ? std::to_string(default_threads) : "1") << " |";
      for (std::size_t n : sizes) {
        const Row* r = find_row(rows, n, start, "exact", mode);
        md << " " << (r ? format("%.0f", r->median_ms * 1e6 / double(n)) : "-") << " |";
      }
      md << "\n";
    }

  md << "\n### Single-thread CPU time (process CPU time per iteration, less sensitive to other load): CGAL over exact\n\n"
        "| N | start | exact 1t cpu ms | cgal-periodic cpu ms | periodic / exact 1t | cgal-band cpu ms | band / exact 1t |\n"
        "|---:|---|---:|---:|---:|---:|---:|\n";
  for (std::size_t n : sizes)
    for (const std::string& start : o.starts) {
      const Row* ex1 = find_row(rows, n, start, "exact", "1 thread");
      if (!ex1) continue;
      const Row* per = find_row(rows, n, start, "cgal-periodic", "");
      const Row* band = find_row(rows, n, start, "cgal-band", "");
      auto ms = [](const Row* r) { return r ? format("%.3f", r->cpu_ms) : std::string("-"); };
      auto ratio = [](const Row* a, const Row* b) {
        return a && b ? format("%.2fx", a->cpu_ms / b->cpu_ms) : std::string("-");
      };
      md << "| " << n << " | " << start << " | " << ms(ex1) << " | " << ms(per) << " | " << ratio(per, ex1) << " | "
         << ms(band) << " | " << ratio(band, ex1) << " |\n";
    }

  md << "\n### All rows\n\n| N | start | engine | mode | res | threads | ms/iter | min ms | cpu ms | Msites/s | heap MiB | "
        "malloc MiB | err mean | err max | coinc. | fallb. | note |\n"
        "|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|\n";
  for (const Row& r : rows) {
    md << "| " << r.n << " | " << r.start << " | " << r.engine << " | " << r.mode << " | "
       << (r.resolution ? std::to_string(r.resolution) : "") << " | " << r.threads << " | "
       << format("%.3f", r.median_ms) << " | " << format("%.3f", r.min_ms) << " | " << format("%.3f", r.cpu_ms)
       << " | " << format("%.2f", double(r.n) / (r.median_ms * 1e3)) << " | "
       << (heap_tracking_enabled() ? format("%.2f", r.heap_peak_mib) : "n/a") << " | "
       << format("%.2f", r.malloc_held_mib) << " | " << sci(r.err_mean) << " | " << sci(r.err_max) << " | "
       << r.coincident << " | " << r.fallbacks << " | " << r.note << " |\n";
  }

  if (!paper.empty()) {
    md << "\n### The paper's workload: 1000 uniform random sites, 80 Lloyd iterations (2001: 40 s CPU, 25 s GPU)\n\n"
          "| engine | threads | total s | final energy | max deviation of final sites from the exact engine's |\n"
          "|---|---:|---:|---:|---:|\n";
    for (const PaperRow& p : paper)
      md << "| " << p.label << " | " << p.threads << " | " << format("%.4f", p.total_s) << " | "
         << format("%.9e", p.final_energy) << " | " << sci(p.max_deviation) << " |\n";
  }
  return md.str();
}

// Error against time per iteration, one curve per engine/mode, for one N and start.
void write_error_plot(const std::string& path, const std::vector<Row>& rows, std::size_t n, const std::string& start) {
  LogLogPlot plot;
  plot.title = "centroid error vs time per Lloyd iteration, N=" + std::to_string(n) + ", " + start + " start";
  plot.x_label = "time per iteration (ms)";
  plot.y_label = "mean centroid error vs exact engine (values <= 1e-16, i.e. rounding, drawn at 1e-16)";
  plot.y_floor = 1e-16;
  std::map<std::string, std::size_t> index;
  for (const Row& r : rows) {
    if (r.n != n || r.start != start) continue;
    std::string label = r.engine + (r.mode.empty() ? "" : " " + r.mode);
    if (!index.count(label)) {
      index[label] = plot.series.size();
      plot.series.push_back({label, {}});
    }
    plot.series[index[label]].points.emplace_back(r.median_ms, r.err_mean);
  }
  write_loglog_png(path, plot);
}

// Time per iteration against N, one curve per engine/mode (raster: at 1024^2 only, to stay legible).
void write_scaling_plot(const std::string& path, const std::vector<Row>& rows, const std::string& start) {
  LogLogPlot plot;
  plot.title = "time per Lloyd iteration vs N, " + start + " start";
  plot.x_label = "N (sites)";
  plot.y_label = "ms per iteration";
  plot.y_floor = 1e-6;
  std::map<std::string, std::size_t> index;
  for (const Row& r : rows) {
    if (r.start != start || (r.resolution != 0 && r.resolution != 1024)) continue;  // raster: one resolution
    std::string label = r.engine + (r.mode.empty() ? "" : " " + r.mode) +
                        (r.resolution ? " " + std::to_string(r.resolution) : "");
    if (!index.count(label)) {
      index[label] = plot.series.size();
      plot.series.push_back({label, {}});
    }
    plot.series[index[label]].points.emplace_back(double(r.n), r.median_ms);
  }
  write_loglog_png(path, plot);
}

int run(int argc, char** argv) {
  Options o;
  CLI::App app{"Exact, CGAL and raster centroid engines side by side: time of one Lloyd iteration, working memory and "
               "the centroid error against the exact engine for every N and start, then the paper's workload (1000 "
               "sites, 80 iterations); a CSV, a markdown report and log-log plots",
               "bluetile_bench"};
  app.add_flag("--quick", o.quick, "small N and few repeats, finishes in seconds (CI)");
  bench::add_integers(app, "--sizes", o.sizes, 1LL, bench::kMaxCount, "comma-separated N")
      ->delimiter(',')
      ->default_str("1000,10000,100000,1000000; --quick: 500,2000");
  bench::add_names(app, "--starts", o.starts, {"random", "relaxed"}, "comma-separated starts")->delimiter(',');
  bench::add_names(app, "--engines", o.engines, {"exact", "cgal-periodic", "cgal-band", "raster"},
                   "comma-separated engine families to run (those built)")
      ->delimiter(',')
      ->default_str("all");
  bench::add_integer(app, "--repeats", o.repeats, 1, bench::kMaxRepeats, "timed repeats per row")
      ->default_str("by N: 21/11/5/3; --quick: 3");
  bench::add_integer(app, "--warmup", o.warmup, 1, 100, "untimed repeats before timing");
  bench::add_integer(app, "--relax-iterations", o.relax_iterations, 1, bench::kMaxIterations,
                     "exact Lloyd iterations making a relaxed start")
      ->default_str("30; --quick: 5");
  bench::add_integer(app, "--max-cgal-periodic", o.max_cgal_periodic, 0LL, bench::kMaxCount,
                     "largest N for the CGAL periodic reference");
  bench::add_integer(app, "--max-cgal-band", o.max_cgal_band, 0LL, bench::kMaxCount, "largest N for the CGAL band reference");
  bench::add_integer(app, "--max-raster", o.max_raster, 0LL, bench::kMaxCount, "largest N for the raster engine");
  // The raster engine's limits on a given resolution (kMinResolution, kMaxResolution, engine_choice.h).
  bench::add_integers(app, "--raster-resolutions", o.raster_resolutions, 16, 65536,
                      "comma-separated ID-buffer sides")
      ->delimiter(',')
      ->default_str("256,512,1024,2048; --quick: 256");
  app.add_flag("--check", o.check, "fail unless the exact engine matches itself across thread counts and CGAL within 1e-9 (on with --quick)");
  app.add_flag("!--no-paper", o.paper, "skip the paper's workload (1000 sites, 80 iterations)");
  bench::add_integer(app, "--seed", o.seed, std::uint64_t{0}, bench::kMaxSeed, "seed of the random starts");
  bench::add_integer(app, "--threads", o.threads, 1, bench::kMaxThreads, "threads for the exact engine")
      ->default_str("all cores");
  app.add_option("--csv", o.csv, "write every row as CSV");
  app.add_option("--markdown", o.markdown, "write the report as markdown");
  app.add_option("--plot-dir", o.plot_dir, "write bench_*.png plots into this folder");
  if (!bench::parse(app, argc, argv)) return 0;

  if (o.sizes.empty())
    o.sizes = o.quick ? std::vector<std::size_t>{500, 2000} : std::vector<std::size_t>{1000, 10000, 100000, 1000000};
  if (o.quick && app.count("--raster-resolutions") == 0) o.raster_resolutions = {256};
  if (o.relax_iterations == 0) o.relax_iterations = o.quick ? 5 : 30;
  if (o.quick) o.check = true;
  if (o.threads > 0) set_thread_count(static_cast<std::size_t>(o.threads));
  const std::size_t default_threads = thread_count();

  std::string command = "bluetile_bench";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];

  // Read once, before the run: the source revision must be the one that was built and run.
  const auto facts = machine_facts();
  std::cerr << "bluetile_bench\n";
  for (auto& [k, v] : facts) std::cerr << "  " << k << ": " << v << "\n";
#ifndef BLUETILE_HAVE_CGAL
  std::cerr << "CGAL is missing (not found when configuring): the CGAL reference rows are skipped.\n";
#endif
#ifndef BLUETILE_BENCH_RASTER
  std::cerr << "raster engine not built into this benchmark: its rows are skipped.\n";
#endif

  const std::vector<EngineSpec> specs = engine_specs(o);
  std::vector<Row> rows;
  // The reference for the errors, and for --check's bit-for-bit test of the exact rows: the same
  // search those rows measure.
  ExactEngine reference_engine(ExactEngineOptions{false});
  for (std::size_t n : o.sizes) {
    const int repeats = o.repeats > 0 ? o.repeats : default_repeats(n, o.quick);
    for (const std::string& start : o.starts) {
      set_thread_count(default_threads);
      auto t0 = Clock::now();
      std::vector<Point> input = start == "random" ? random_sites(n, o.seed) : relaxed_sites(n, o.seed, o.relax_iterations);
      std::vector<Cell> reference = reference_engine.compute(make_scene(input)).cells;
      std::cerr << "N=" << n << " " << start << " start (prepared in "
                << format("%.1f", std::chrono::duration<double>(Clock::now() - t0).count()) << " s)\n";
      std::vector<const EngineSpec*> chosen;
      for (const EngineSpec& spec : specs) {
        if (n > spec.max_n) {
          std::cerr << "  " << spec.label() << ": skipped (N above its limit)\n";
        } else {
          chosen.push_back(&spec);
        }
      }
      for (const Row& row : measure_all(chosen, input, reference, start, o.warmup, repeats, default_threads)) {
        std::fprintf(stderr, "  %-34s %10.3f ms/iter (cpu %.3f)  err mean %.2e max %.2e  heap %.1f MiB\n",
                     (row.engine + (row.mode.empty() ? "" : " " + row.mode) +
                      (row.resolution ? " " + std::to_string(row.resolution) : "")).c_str(),
                     row.median_ms, row.cpu_ms, row.err_mean, row.err_max, row.heap_peak_mib);
        rows.push_back(row);
      }
    }
  }

  std::vector<PaperRow> paper;
  if (o.paper) {
    std::cerr << "paper workload: 1000 random sites, 80 iterations\n";
    const std::vector<Point> start = random_sites(1000, o.seed);
    std::vector<Point> exact_final;
    for (const EngineSpec& spec : specs) {
      if (!spec.in_paper_row || spec.max_n < 1000) continue;
      apply_threads(spec, default_threads);
      Scene scene = make_scene(start);
      LloydOptions lloyd;
      lloyd.iterations = 80;
      LloydResult result;
      auto t0 = Clock::now();
      try {
        std::unique_ptr<CentroidEngine> engine = spec.make();  // raster: device set-up counted
        result = relax_lloyd(*engine, scene, lloyd);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "  %-34s failed: %s\n", spec.label().c_str(), e.what());
        continue;
      }
      PaperRow p;
      p.total_s = std::chrono::duration<double>(Clock::now() - t0).count();
      p.label = spec.label();
      p.threads = thread_count();
      p.final_energy = result.last.energy;
      if (exact_final.empty()) exact_final = scene.sites;  // the first spec is the exact engine
      for (std::size_t i = 0; i < scene.sites.size(); ++i)
        p.max_deviation = std::max(p.max_deviation, torus_distance(scene.sites[i], exact_final[i], Domain{}));
      std::fprintf(stderr, "  %-34s %8.3f s  max deviation %.2e\n", p.label.c_str(), p.total_s, p.max_deviation);
      paper.push_back(p);
    }
  }
  set_thread_count(default_threads);

  const std::string md = markdown_text(o, command, facts, rows, paper, default_threads);
  if (!o.csv.empty()) write_output(o.csv, csv_text(rows, paper));
  if (!o.markdown.empty()) write_output(o.markdown, md);
  if (!o.plot_dir.empty()) {
    std::vector<std::pair<std::size_t, std::string>> seen;
    for (const Row& r : rows)
      if (std::find(seen.begin(), seen.end(), std::pair{r.n, r.start}) == seen.end()) seen.emplace_back(r.n, r.start);
    for (auto& [n, start] : seen)
      write_error_plot(o.plot_dir + "/bench_error_vs_time_n" + std::to_string(n) + "_" + start + ".png", rows, n, start);
    for (const std::string& start : o.starts) write_scaling_plot(o.plot_dir + "/bench_time_vs_n_" + start + ".png", rows, start);
  }
  if (o.csv.empty() && o.markdown.empty()) std::cout << md;

  // Correctness, never speed: the exact engine must give the same bits on one thread as on
  // all, and the CGAL cells (computed independently, as Delaunay duals) must agree with it.
  if (o.check) {
    int failures = 0;
    for (const Row& r : rows) {
      const double limit = r.engine == "exact" ? 0.0 : r.engine.rfind("cgal", 0) == 0 ? 1e-9 : -1.0;
      if (limit >= 0.0 && r.err_max > limit) {
        std::fprintf(stderr, "check failed: %s %s N=%zu %s start: max centroid difference %.3e > %.0e\n",
                     r.engine.c_str(), r.mode.c_str(), r.n, r.start.c_str(), r.err_max, limit);
        ++failures;
      }
    }
    if (failures) return 1;
    std::cerr << "check passed: exact engine bit-identical across thread counts; CGAL agrees within 1e-9\n";
  }
  return 0;
}

}  // namespace
}  // namespace bluetile::bench

int main(int argc, char** argv) try {
  return bluetile::bench::run(argc, argv);
} catch (...) {
  return bluetile::bench::exit_status("bluetile_bench");
}
