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

// resolution: 0 (from N) or the library's range, which the choice's check names; one past an
// int is refused here in the same words.
inline int resolution_arg(const Whole& resolution) {
  return whole<int>(resolution, "resolution", 0, bluetile::kMaxResolution,
                    "0 (from N) or " + std::to_string(bluetile::kMinResolution) + " to " +
                        std::to_string(bluetile::kMaxResolution));
}

}  // namespace pybluetile
