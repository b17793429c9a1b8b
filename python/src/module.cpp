// pybluetile._core: the bluetile library for Python, with NumPy arrays in and out.
#include <nanobind/nanobind.h>
#include <nanobind/stl/string.h>

#include <exception>
#include <string_view>

#include "arguments.h"
#include "bindings.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"

namespace nb = nanobind;
using namespace nb::literals;

NB_MODULE(_core, m) {
  m.doc() = "Blue-noise sample points by Lloyd relaxation on the unit torus (Hiller, Deussen, Keller 2001).";
  // The library's one error type, with its message unchanged (the tool prints the same text
  // after "bluetile: "). A ValueError, since it reports bad input or an unusable environment.
  static nb::exception<bluetile::Error> error_type(m, "Error", PyExc_ValueError);
  // A message quoting bytes of a file that are not UTF-8 ("not a number '\xff\xfe0.1'") made an
  // Error with no message at all: decoded with U+FFFD for such bytes instead. Registered after
  // nanobind's own translator for the type, so tried first.
  nb::register_exception_translator(
      [](const std::exception_ptr& thrown, void* type) {
        try {
          std::rethrow_exception(thrown);
        } catch (const bluetile::Error& e) {
          const std::string_view text = e.what();
          PyObject* message = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
          PyErr_SetObject(static_cast<PyObject*>(type), message);
          Py_XDECREF(message);
        }
      },
      error_type.ptr());

  m.def("thread_count", &bluetile::thread_count,
        "Threads the library uses (default: the cores this process may run on, as nproc counts them, or "
        "BLUETILE_THREADS). Results do not depend on it.");
  m.def(
      "set_thread_count",
      [](const pybluetile::Whole& count) {
        bluetile::set_thread_count(pybluetile::whole<std::size_t>(
            count, "count", 1, bluetile::kMaxThreads, "1 to " + std::to_string(bluetile::kMaxThreads) + " threads"));
      },
      nb::sig("def set_thread_count(count: int) -> None"), "count"_a.none(), "Sets the threads the library uses from now on (like --threads); results do not depend on it.");

  pybluetile::bind_engines(m);
  pybluetile::bind_sampling(m);
  pybluetile::bind_analysis(m);
  pybluetile::bind_tables(m);
  pybluetile::bind_tiling(m);
}
