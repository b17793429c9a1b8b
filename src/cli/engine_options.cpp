#include "cli/engine_options.h"

#include <cstdio>

#include "cli/numeric_options.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/raster/raster_engine.h"

namespace bluetile::cli {

void add_engine_options(CLI::App* command, EngineOptions& options) {
  command->add_option("--engine", options.engine, "Centroid engine: raster (Vulkan) or exact (CPU)")
      ->check(CLI::IsMember(engine_names()))
      ->capture_default_str();
  add_integer_option(command, "--resolution", options.resolution, kMinResolution, kMaxResolution,
                     "Raster engine: ID buffer side in pixels (default: from N, about 4 pixels per cell for area "
                     "coverage, 1000 for point)")
      ->default_str("from N");
  command->add_option("--coverage", options.coverage,
                      "Raster engine: point (pixel centres) or area (boundary pixels split exactly)")
      ->check(CLI::IsMember(coverage_names()))
      ->capture_default_str();
  command->add_option("--cone", options.cone, "Raster engine: quad (exact depth) or fan (tessellated, biased)")
      ->check(CLI::IsMember(cone_names()))
      ->capture_default_str();
  command->add_option("--device", options.device, "Raster engine: Vulkan device name or index (see 'bluetile devices')");
  command->add_option("--pixel-work", options.pixel_work,
                      "Raster engine: where the per-pixel work (classification, sums, boundary split) runs: auto (the "
                      "device on GPUs; on CPU devices such as lavapipe the device for point coverage and the host for area "
                      "coverage), device (compute shaders; refused on a "
                      "device without the features they need, or with a density map or a bounded domain) or host "
                      "(threaded); the output is the same bits")
      ->check(CLI::IsMember(pixel_work_names()))
      ->capture_default_str();
  add_threads_option(command, options.threads);
}

void refuse_unused_raster_options(const CLI::App& command, const EngineOptions& options, const std::string& why_exact,
                                  bool id_image) {
  if (options.engine != "exact" || id_image) return;
  for (const char* name : {"--resolution", "--coverage", "--cone", "--device", "--pixel-work"}) {
    if (command.count(name) == 0) continue;
    const CLI::Option* option = command.get_option(name);
    throw Error(std::string(name) + " " + option->as<std::string>() + ": a raster engine setting, and this run uses the exact engine" +
                why_exact + "; --engine raster uses it");
  }
}

std::unique_ptr<CentroidEngine> make_engine(const EngineOptions& options) {
  if (options.threads > 0) set_thread_count(static_cast<std::size_t>(options.threads));
  return bluetile::make_engine(static_cast<const EngineChoice&>(options));
}

std::string engine_text(const CentroidEngine& engine, const EngineOptions& options) {
  if (dynamic_cast<const RasterEngine*>(&engine) == nullptr) return std::string(engine.name());
  return std::string(engine.name()) + " (" + options.coverage + " coverage, resolution " +
         (options.resolution > 0 ? std::to_string(options.resolution) : "from N") + ", " + options.cone + " cones)";
}

std::string engine_arguments(const CentroidEngine& engine, const EngineOptions& options) {
  std::string text = "--engine " + std::string(engine.name());
  if (dynamic_cast<const RasterEngine*>(&engine) == nullptr) return text;
  text += " --coverage " + options.coverage + " --cone " + options.cone;
  if (options.resolution > 0) text += " --resolution " + std::to_string(options.resolution);
  return text;
}

void note_faster_engine(const CentroidEngine& engine, double site_iterations) {
  const auto* raster = dynamic_cast<const RasterEngine*>(&engine);
  if (raster == nullptr || !raster->cpu_device()) return;
  // Measured on lavapipe, 2 cores, wall time (relax -k 20 -n 20000, -k 10 -n 100000): 2.1-3.0 us
  // per cell with the raster engine, 17-21x less with the exact engine since it keeps its
  // triangulation between iterations (docs/BENCHMARKS.md, "Which engine to use").
  constexpr double kRasterSecondsPerCell = 2.5e-6, kExactSpeedUp = 16.0;
  constexpr double kWorthSaying = 10.0;  // seconds: shorter runs are not worth a line
  const double raster_s = kRasterSecondsPerCell * site_iterations;
  if (raster_s < kWorthSaying) return;
  std::fprintf(stderr,
               "bluetile: note: about %s on the raster engine on %s, a CPU device; --engine exact computes the same "
               "cells (to 1e-12 of area coverage) in about %s\n",
               duration_words(raster_s).c_str(), raster->device_name().c_str(),
               duration_words(raster_s / kExactSpeedUp).c_str());
}

void note_exact_hand_over(const CentroidEngine& engine) {
  const auto* raster = dynamic_cast<const RasterEngine*>(&engine);
  if (raster == nullptr) return;
  const RasterStats& s = raster->stats();
  if (s.fallback_cells > 0) {
    // Only the --log's fallbacks column said so: a resolution too low for the cells looked fine.
    std::fprintf(stderr,
                 "bluetile: note: the raster engine measured %llu cells (over every iteration) with the exact engine: point "
                 "coverage found no pixel centre in them (a higher --resolution, or --coverage area, draws them)\n",
                 static_cast<unsigned long long>(s.fallback_cells));
  }
  if (s.exact_scenes == 0) return;
  std::fprintf(stderr,
               "bluetile: note: the raster engine measured %llu of %llu scene computations with the exact engine: their sites "
               "lie on lines or in clusters, whose sliver cells cost about N^2 to rasterize (docs/RASTER.md, \"Sliver "
               "cells\")\n",
               static_cast<unsigned long long>(s.exact_scenes), static_cast<unsigned long long>(s.exact_scenes + s.scene_passes - s.redone_scenes));
}

void write_id_image(const EngineOptions& options, CentroidEngine& engine, const Scene& scene, OutputFile& out) {
  RasterOptions r = raster_options(options);
  if (auto* raster = dynamic_cast<RasterEngine*>(&engine)) r = raster->options();
  r.keep_id_images = true;
  RasterEngine drawer(r);
  drawer.compute(scene);
  write_id_image(drawer.id_image(0), scene, out);
}

}  // namespace bluetile::cli
