// The centroid engines as the Python functions name them (engine="raster"|"exact" and the
// raster settings), checked the way the command line checks them.
#pragma once

#include <memory>
#include <string>

#include "arguments.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/engine_choice.h"

namespace pybluetile {

// The library's engine choice (bluetile/raster/engine_choice.h): its names, defaults and
// ranges; a bad one raises pybluetile.Error (a ValueError) naming the argument.
using bluetile::EngineChoice;

// Checks the choice before any work: its names and ranges, and, as the tool does, raster
// settings given with the exact engine, where they would change nothing.
void check_engine_choice(const EngineChoice& choice);
using bluetile::make_engine;

// The engine (`engine`, its default already put in for None) and the raster settings as Python
// passed them, None for each setting meaning its default (EngineChoice's). resolution: 0 (from N)
// or the library's range, which the choice's check names; one past an int is refused here in the
// same words. Wrong types raise TypeError naming the argument; check_engine_choice checks values.
inline EngineChoice engine_choice(const std::string& engine, const Whole& resolution, const Text& coverage,
                                  const Text& cone, const Text& device, const Text& pixel_work) {
  const EngineChoice defaults;
  EngineChoice choice;
  choice.engine = engine;
  choice.resolution = whole_or<int>(resolution, defaults.resolution, "resolution", 0, bluetile::kMaxResolution,
                                    "0 (from N) or " + std::to_string(bluetile::kMinResolution) + " to " +
                                        std::to_string(bluetile::kMaxResolution));
  choice.coverage = text_or(coverage, defaults.coverage, "coverage");
  choice.cone = text_or(cone, defaults.cone, "cone");
  choice.device = text_or(device, defaults.device, "device");
  choice.pixel_work = text_or(pixel_work, defaults.pixel_work, "pixel_work");
  return choice;
}

}  // namespace pybluetile
