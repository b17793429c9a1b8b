// pybluetile._core: the bluetile library for Python, with NumPy arrays in and out.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include "bindings.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace nb = nanobind;
using namespace nb::literals;

NB_MODULE(_core, m) {
  m.doc() = "Blue-noise sample points by Lloyd relaxation on the unit torus (Hiller, Deussen, Keller 2001).";
  // The library's one error type, with its message unchanged (the tool prints the same text
  // after "bluetile: "). A ValueError, since it reports bad input or an unusable environment.
  nb::exception<bluetile::Error>(m, "Error", PyExc_ValueError);

  m.def("thread_count", &bluetile::thread_count,
        "Threads the library uses (default: the cores, or BLUETILE_THREADS). Results do not depend on it.");
  m.def(
      "set_thread_count",
      [](std::size_t count) {
        if (count < 1 || count > 1024) throw nb::value_error("count: expected 1 to 1024 threads");
        bluetile::set_thread_count(count);
      },
      "count"_a, "Sets the threads the library uses from now on (like --threads); results do not depend on it.");

  pybluetile::bind_engines(m);
  pybluetile::bind_sampling(m);
  pybluetile::bind_analysis(m);
  pybluetile::bind_tables(m);
  pybluetile::bind_tiling(m);
}
