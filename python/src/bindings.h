// Each part of the library adds its functions to the module in its own file; module.cpp calls
// them in order. A new part is one more bind_* here and in module.cpp.
#pragma once

#include <chrono>

#include <nanobind/nanobind.h>

#include "bluetile/core/cancel_check.h"

namespace pybluetile {

// Long calls run with the GIL released. Between iterations they take it back for a moment to run
// Python's signal handlers: a Ctrl-C then ends the call with KeyboardInterrupt, as it would end a
// Python loop, instead of after the last iteration. Call only where the GIL is released.
inline void raise_pending_signals() {
  nanobind::gil_scoped_acquire hold;
  if (PyErr_CheckSignals() != 0) throw nanobind::python_error();
}

// While one lives (on the calling thread, GIL released), the library's long loops run Python's
// signal handlers now and then too (bluetile/core/cancel_check.h): a Ctrl-C ends a call with no
// iterations of its own (analyze, dart, tile) inside its loops, and one whose iterations are long
// (the raster engine's wang_tiles) inside an iteration. The GIL is taken back at most every
// kSignalCheckInterval: the loops reach their checks far more often than that.
class SignalChecks {
 public:
  SignalChecks()
      : check_([last = std::chrono::steady_clock::now()]() mutable {
          const auto now = std::chrono::steady_clock::now();
          if (now - last < kSignalCheckInterval) return;
          last = now;
          raise_pending_signals();
        }) {}

 private:
  // Well under what a person notices after Ctrl-C, well over the GIL's cost.
  static constexpr std::chrono::milliseconds kSignalCheckInterval{20};
  bluetile::CancelCheck check_;
};

void bind_engines(nanobind::module_& m);   // relax, stipple, centroids, progressive
void bind_sampling(nanobind::module_& m);  // random_points, dart
void bind_analysis(nanobind::module_& m);  // analyze, periodogram, radial_power, nearest_neighbour_distances
void bind_tables(nanobind::module_& m);    // save_table, load_table
void bind_tiling(nanobind::module_& m);    // wang_tiles, tile_set, tile

}  // namespace pybluetile
