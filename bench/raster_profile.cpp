// Where a raster pass spends its time: Lloyd loops on the raster engine and on the
// exact engine, interleaved in one process, with the raster engine's own stage times (upload,
// device submission and wait, host work), CPU time beside wall time, passes, redos and boundary
// pixels per iteration. Engine construction (Vulkan device, pipelines) is timed apart.
//
//   bluetile_raster_profile [--jobs paper,n1e4,n1e5,sets256,sets4096,point] [--repeats 3]
//                           [--device-pixels]   (the per-pixel work on the host and on the
//                                                device, one engine each; without it `auto`)
//                           [--stages]          (and a table of every stage, host and device
//                                                pixel work side by side; implies --device-pixels)
//                           [--cone-draws triangles,indexed,instanced,points]  (one engine each)
//                           [--split-kernels lane,lane3,lane5,pixel]  (device pixel work, one engine
//                                                each; lane: the device's choice)
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"

namespace bluetile {
namespace {

using Clock = std::chrono::steady_clock;

double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Job {
  std::string name;
  std::size_t sites = 0, sets = 1;
  int iterations = 1;
  Coverage coverage = Coverage::area;
};

std::vector<Scene> start_scenes(const Job& job) {
  std::vector<Scene> scenes;
  for (std::size_t k = 0; k < job.sets; ++k) {
    Rng rng(1000 + k);
    std::vector<Point> p(job.sites);
    for (Point& q : p) q = rng.point(Domain{});
    scenes.push_back(make_scene(std::move(p)));
  }
  return scenes;
}

struct Timing {
  std::vector<double> wall, cpu;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

void run_loop(CentroidEngine& engine, const Job& job, Timing& t) {
  std::vector<Scene> scenes = start_scenes(job);
  LloydOptions options;
  options.iterations = job.iterations;
  const double c0 = cpu_seconds();
  const auto w0 = Clock::now();
  relax_lloyd(engine, scenes, options);
  t.wall.push_back(std::chrono::duration<double>(Clock::now() - w0).count());
  t.cpu.push_back(cpu_seconds() - c0);
}

// One row of the stage table: the difference of two stats snapshots over `n` iterations.
std::string stage_row(const std::string& job, const std::string& label, const RasterStats& s, const RasterStats& b, double n,
                      double wall_per_iteration, double exact_per_iteration) {
  const auto ms = [&](double RasterStats::*field) { return (s.*field - b.*field) / n * 1e3; };
  const double cones = ms(&RasterStats::cone_seconds);
  const double drawn = static_cast<double>(s.cones_drawn - b.cones_drawn) / n;
  const double timed = cones + ms(&RasterStats::classify_seconds) + ms(&RasterStats::split_seconds) + ms(&RasterStats::readback_seconds);
  char row[640];
  std::snprintf(row, sizeof row,
                "| %s | %s | %.2f | %.1fx | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f |",
                job.c_str(), label.c_str(), wall_per_iteration * 1e3, wall_per_iteration / exact_per_iteration, cones,
                drawn > 0.0 ? cones * 1e3 / drawn : 0.0, ms(&RasterStats::classify_seconds), ms(&RasterStats::split_seconds),
                ms(&RasterStats::readback_seconds), ms(&RasterStats::device_seconds) - timed, ms(&RasterStats::upload_seconds),
                ms(&RasterStats::prepare_seconds), ms(&RasterStats::host_readback_seconds), ms(&RasterStats::host_classify_seconds),
                ms(&RasterStats::host_split_seconds), ms(&RasterStats::host_reduce_seconds), ms(&RasterStats::cells_seconds));
  return row;
}

}  // namespace
}  // namespace bluetile

int main(int argc, char** argv) try {
  using namespace bluetile;
  CLI::App app{"Where raster Lloyd iterations spend their time, beside the exact engine: Lloyd loops of each job on "
               "both engines, interleaved, with the raster engine's stage times, passes, redos and boundary pixels",
               "bluetile_raster_profile"};
  std::vector<std::string> jobs = {"paper", "n1e4", "n1e5", "sets256", "sets4096", "point"};
  int repeats = 3;
  bool device_pixels = false;
  double pixels_per_cell = 0.0;
  bench::add_names(app, "--jobs", jobs, jobs,
                   "comma-separated jobs: paper (1000 sites, 80 iterations), n1e4, n1e5, sets256, sets4096 (sets of 64 "
                   "sites), point (point coverage)")
      ->delimiter(',');
  bench::add_integer(app, "--repeats", repeats, 1, bench::kMaxRepeats, "interleaved repeats per job");
  app.add_flag("--device-pixels", device_pixels,
               "run the per-pixel work on the host and on the device, one engine each (without it: PixelWork::automatic)");
  std::vector<std::string> cone_draws;
  bench::add_names(app, "--cone-draws", cone_draws, {"triangles", "indexed", "instanced", "points"},
                   "comma-separated ways to draw the cones, each a raster engine of its own (host pixel work)")
      ->delimiter(',')
      ->default_str("none");
  std::vector<std::string> split_kernels;
  bench::add_names(app, "--split-kernels", split_kernels, {"lane", "lane3", "lane5", "pixel"},
                   "comma-separated float64 split kernels, each a raster engine of its own (device pixel work): lane (the "
                   "device's choice), lane3, lane5, pixel")
      ->delimiter(',')
      ->default_str("none");
  bool stages = false;
  app.add_flag("--stages", stages, "also print every stage's time per iteration, host and device pixel work side by side");
  bench::add_real(app, "--pixels-per-cell", pixels_per_cell, {0.0, 1e6, true, false},
                  "resolution from this many pixels per cell")
      ->default_str("the engine's");
  if (!bench::parse(app, argc, argv)) return 0;
  if (stages) device_pixels = true;
  std::vector<std::string> stage_rows;

  const std::vector<Job> all = {
      {"paper", 1000, 1, 80, Coverage::area},   {"n1e4", 10000, 1, 10, Coverage::area},
      {"n1e5", 100000, 1, 3, Coverage::area},   {"sets256", 64, 256, 50, Coverage::area},
      {"sets4096", 64, 4096, 10, Coverage::area}, {"point", 1000, 1, 80, Coverage::point},
  };
  std::printf("| job | engine | iterations | wall ms/it | cpu ms/it | ratio (wall) | passes/it | redone | boundary px/it | host-split px/it | upload ms/it | device ms/it | cones ms/it | classify ms/it | split ms/it | host ms/it | start-up ms |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const Job& job : all) {
    if (std::find(jobs.begin(), jobs.end(), job.name) == jobs.end()) continue;
    // Both paths by name: what `auto` picks depends on the device and the coverage.
    std::vector<PixelWork> works = {PixelWork::automatic};
    if (device_pixels) works = {PixelWork::host, PixelWork::device};
    struct Entry {
      std::string label;
      std::unique_ptr<CentroidEngine> engine;
      double startup_ms = 0.0;
      Timing t;
    };
    std::vector<Entry> entries;
    entries.push_back({"exact", std::make_unique<ExactEngine>(), 0.0, {}});
    struct Variant {
      PixelWork work;
      std::string draw, split;
    };
    std::vector<Variant> variants;
    for (PixelWork work : works) variants.push_back({work, "", ""});
    for (const std::string& draw : cone_draws) variants.push_back({PixelWork::host, draw, ""});
    for (const std::string& split : split_kernels) variants.push_back({PixelWork::device, "", split});
    for (const Variant& variant : variants) {
      const PixelWork work = variant.work;
      RasterOptions options;
      if (variant.draw == "triangles") options.cone_draw = ConeDraw::triangles;
      else if (variant.draw == "indexed") options.cone_draw = ConeDraw::indexed;
      else if (variant.draw == "instanced") options.cone_draw = ConeDraw::instanced;
      else if (variant.draw == "points") options.cone_draw = ConeDraw::points;
      if (variant.split == "pixel") options.split_kernel = SplitKernel::pixel;
      else if (variant.split == "lane3") options.split_kernel = SplitKernel::lane_three;
      else if (variant.split == "lane5") options.split_kernel = SplitKernel::lane_five;
      options.coverage = job.coverage;
      options.pixel_work = work;
      if (pixels_per_cell > 0.0)
        options.resolution = std::max(16, static_cast<int>(std::lround(std::sqrt(pixels_per_cell * static_cast<double>(job.sites)))));
      const auto w0 = Clock::now();
      auto engine = std::make_unique<RasterEngine>(options);
      const double startup = std::chrono::duration<double>(Clock::now() - w0).count() * 1e3;
      std::string label = std::string("raster ") + (engine->pixel_work_on_device() ? "device pixels" : "host pixels");
      if (!variant.draw.empty()) label += ", cones " + variant.draw;
      if (!variant.split.empty()) label += ", split " + variant.split;
      entries.push_back({label, std::move(engine), startup, {}});
    }
    // A warm-up loop each (shader JIT, first allocations), then interleaved repeats.
    for (Entry& e : entries) {
      Timing ignored;
      Job warm = job;
      warm.iterations = 1;
      run_loop(*e.engine, warm, ignored);
    }
    std::vector<RasterStats> before(entries.size());
    for (std::size_t k = 0; k < entries.size(); ++k)
      if (auto* r = dynamic_cast<RasterEngine*>(entries[k].engine.get())) before[k] = r->stats();
    for (int r = 0; r < repeats; ++r)
      for (std::size_t k = 0; k < entries.size(); ++k) {
        Entry& e = entries[(k + static_cast<std::size_t>(r)) % entries.size()];
        run_loop(*e.engine, job, e.t);
      }
    const double exact_wall = median(entries[0].t.wall);
    for (std::size_t k = 0; k < entries.size(); ++k) {
      Entry& e = entries[k];
      const double its = static_cast<double>(job.iterations);
      std::printf("| %s | %s | %d | %.2f | %.2f | %.1fx |", job.name.c_str(), e.label.c_str(), job.iterations,
                  median(e.t.wall) / its * 1e3, median(e.t.cpu) / its * 1e3, median(e.t.wall) / exact_wall);
      if (auto* raster = dynamic_cast<RasterEngine*>(e.engine.get())) {
        const RasterStats& s = raster->stats();
        const RasterStats& b = before[k];
        const double n = its * repeats;
        std::printf(" %.2f | %llu | %.0f | %.0f | %.2f | %.2f | %.2f | %.2f | %.2f | %.2f | %.0f |\n", static_cast<double>(s.submits - b.submits) / n,
                    static_cast<unsigned long long>(s.redone_scenes - b.redone_scenes),
                    static_cast<double>(s.boundary_pixels - b.boundary_pixels) / n,
                    static_cast<double>(s.host_split_pixels - b.host_split_pixels) / n, (s.upload_seconds - b.upload_seconds) / n * 1e3,
                    (s.device_seconds - b.device_seconds) / n * 1e3, (s.cone_seconds - b.cone_seconds) / n * 1e3,
                    (s.classify_seconds - b.classify_seconds) / n * 1e3, (s.split_seconds - b.split_seconds) / n * 1e3,
                    (s.host_seconds - b.host_seconds) / n * 1e3, e.startup_ms);
        if (stages) stage_rows.push_back(stage_row(job.name, e.label, s, b, n, median(e.t.wall) / its, exact_wall / its));
      } else {
        std::printf(" | | | | | | | | | | |\n");
      }
      std::fflush(stdout);
    }
  }
  if (stages && !stage_rows.empty()) {
    std::printf("\nStages, ms per iteration (device: timestamps; other: recording, submission and wait beyond them; host: wall)\n\n");
    std::printf("| job | pixel work | wall | / exact | cones | us per cone | classify | split | readback | device other | upload | prepare | "
                "IDs from atlas | host classify | host split | host reduce | coverage + cells |\n");
    std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
    for (const std::string& row : stage_rows) std::printf("%s\n", row.c_str());
  }
  return 0;
} catch (...) {
  return bluetile::bench::exit_status("bluetile_raster_profile");
}
