#include "cli/engine_options.h"

#include "core/error.h"
#include "core/parallel.h"
#include "voronoi/exact_engine.h"

namespace bluetile::cli {

void add_engine_options(CLI::App* command, EngineOptions& options) {
  command->add_option("--engine", options.engine, "Centroid engine: raster (Vulkan) or exact (CPU)")
      ->check(CLI::IsMember({"raster", "exact"}))
      ->capture_default_str();
  command->add_option("--resolution", options.resolution, "Raster engine: ID buffer side in pixels")
      ->check(CLI::Range(16, 65536));
  command->add_option("--coverage", options.coverage, "Raster engine: pixel coverage, point or area")
      ->check(CLI::IsMember({"point", "area"}))
      ->capture_default_str();
  command->add_option("--device", options.device, "Raster engine: Vulkan device name or index");
  command->add_option("--threads", options.threads, "CPU threads (default: all cores); output does not depend on it")
      ->check(CLI::Range(1, 1024));
}

std::unique_ptr<CentroidEngine> make_engine(const EngineOptions& options) {
  if (options.threads > 0) set_thread_count(static_cast<std::size_t>(options.threads));
  if (options.engine == "exact") return std::make_unique<ExactEngine>();
  throw Error("--engine raster is not available yet (the Vulkan engine is under construction); use --engine exact");
}

}  // namespace bluetile::cli
