// The centroid engines as the Python functions name them (engine="raster"|"exact" and the
// raster settings), checked the way the command line checks them.
#pragma once

#include <memory>
#include <string>

#include "bluetile/voronoi/engine.h"

namespace pybluetile {

struct EngineChoice {
  std::string engine = "raster";
  int resolution = 0;
  std::string coverage = "area";
  std::string cone = "quad";
  std::string device;
  std::string pixel_work = "auto";
};

// Throws ValueError for a name or a resolution out of range (before any work).
void check_engine_choice(const EngineChoice& choice);

// Creates the engine (a Vulkan context for raster); throws bluetile::Error when there is none.
std::unique_ptr<bluetile::CentroidEngine> make_engine(const EngineChoice& choice);

}  // namespace pybluetile
