// The centroid engines as the Python functions name them (engine="raster"|"exact" and the
// raster settings), checked the way the command line checks them.
#pragma once

#include <memory>
#include <string>

#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/engine_choice.h"

namespace pybluetile {

// The library's engine choice (bluetile/raster/engine_choice.h): its names, defaults and
// ranges; a bad one raises pybluetile.Error (a ValueError) naming the argument.
using bluetile::EngineChoice;

// Checks the choice before any work.
inline void check_engine_choice(const EngineChoice& choice) { bluetile::validate(choice); }
using bluetile::make_engine;

}  // namespace pybluetile
