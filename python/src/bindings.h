// Each part of the library adds its functions to the module in its own file; module.cpp calls
// them in order. A new part is one more bind_* here and in module.cpp.
#pragma once

#include <nanobind/nanobind.h>

namespace pybluetile {

// Long calls run with the GIL released. Between iterations they take it back for a moment to run
// Python's signal handlers: a Ctrl-C then ends the call with KeyboardInterrupt, as it would end a
// Python loop, instead of after the last iteration. Call only where the GIL is released.
inline void raise_pending_signals() {
  nanobind::gil_scoped_acquire hold;
  if (PyErr_CheckSignals() != 0) throw nanobind::python_error();
}

void bind_engines(nanobind::module_& m);   // relax, stipple, centroids, progressive
void bind_sampling(nanobind::module_& m);  // random_points, dart
void bind_analysis(nanobind::module_& m);  // analyze, periodogram, radial_power, nearest_neighbour_distances
void bind_tables(nanobind::module_& m);    // save_table, load_table
void bind_tiling(nanobind::module_& m);    // wang_tiles, tile_set, tile

}  // namespace pybluetile
