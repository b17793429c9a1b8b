// Which centroid engine a front end asks for, by name, with the raster engine's settings: the
// names, defaults and ranges the tool's options and the Python module's arguments bind, defined
// once so that the two cannot drift apart. Errors name the field ("coverage: ..."), not a flag.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/raster_engine.h"

namespace bluetile {

struct EngineChoice {
  std::string engine = "raster";    // engine_names(): the raster (Vulkan) or the exact (CPU) engine
  int resolution = 0;               // raster: ID-buffer side in pixels; 0 picks one from N
  std::string coverage = "area";    // raster: coverage_names()
  std::string cone = "quad";        // raster: cone_names()
  std::string device;               // raster: Vulkan device name or index; empty: the first
  std::string pixel_work = "auto";  // raster: pixel_work_names(), where the per-pixel work runs
};

// The ID buffer's side when given (RasterOptions::resolution).
inline constexpr int kMinResolution = 16, kMaxResolution = 65536;

const std::vector<std::string>& engine_names();      // raster, exact
const std::vector<std::string>& coverage_names();    // point, area
const std::vector<std::string>& cone_names();        // quad, fan
const std::vector<std::string>& pixel_work_names();  // auto, device, host

// Throws Error naming the field, the value and what it accepts.
void validate(const EngineChoice& choice);

// The raster engine's options for `choice` (validated).
RasterOptions raster_options(const EngineChoice& choice);

// The engine `choice` names (validated); throws Error when it cannot be had (no Vulkan device).
std::unique_ptr<CentroidEngine> make_engine(const EngineChoice& choice);

}  // namespace bluetile
