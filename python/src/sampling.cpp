// random_points and dart: point sets that need no engine.
#include <nanobind/stl/string.h>

#include "arguments.h"
#include "arrays.h"
#include "bindings.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/request_limits.h"
#include "bluetile/sampling/dart_throwing.h"

namespace pybluetile {

using namespace nb::literals;

void bind_sampling(nb::module_& m) {
  m.def(
      "random_points",
      [](const Whole& count_arg, const Whole& seed_arg, const Whole& set_arg) {
        // The limit on a point set (relax --count): past it a bare MemoryError, or swap.
        const auto count = whole<std::size_t>(count_arg, "count", 0, bluetile::kMaxSetPoints);
        const std::uint64_t seed = seed_or(seed_arg, 1), set = seed_or(set_arg, 0, "set");
        // The points and the array they are copied into: refused at once with the estimate.
        bluetile::check_memory(static_cast<double>(count) * 2.0 * sizeof(bluetile::Point), "count=" + std::to_string(count));
        std::vector<bluetile::Point> points;
        {
          nb::gil_scoped_release release;
          points = bluetile::uniform_random_points(count, seed, set);
        }
        return points_to_numpy({points}, false);
      },
      nb::sig("def random_points(count: int, seed: int = 1, set: int = 0) -> NDArray[numpy.float64]"),
      "count"_a.none(), "seed"_a.none() = 1, "set"_a.none() = 0,
      R"(Uniform random points on the unit torus, shape (count, 2): the random start of set ``set``
of ``bluetile relax --count N --seed S``, bit for bit.)");

  m.def(
      "dart",
      [](const Whole& count, const Whole& seed, const Whole& max_failures, const Real& shrink, const Real& start,
         const Flag& info_arg) {
        const bluetile::DartOptions defaults;
        bluetile::DartOptions o;
        // The library's ranges, checked here so that a value past 64 bits gets the same message.
        o.count = whole<std::size_t>(count, "count", 1, bluetile::kMaxDartCount);
        o.seed = seed_or(seed, 1);
        o.max_failures =
            whole_or<std::size_t>(max_failures, defaults.max_failures, "max_failures", 1, bluetile::kMaxDartFailures);
        o.shrink = real_or(shrink, defaults.shrink, "shrink");
        o.start = real_or(start, defaults.start, "start");
        const bool info = flag_or(info_arg, false, "info");
        bluetile::validate(o);  // before the GIL is released: a bad value raises at once
        bluetile::check_memory(static_cast<double>(o.count) * bluetile::kDartBytesPerPoint,
                               "count=" + std::to_string(o.count));  // as the tool's dart --count
        bluetile::DartResult r;
        {
          nb::gil_scoped_release release;
          SignalChecks signal_checks;  // Ctrl-C inside the loops
          r = bluetile::throw_darts(o);
        }
        nb::object points = nb::cast(points_to_numpy({r.points}, false));
        if (!info) return points;
        nb::dict d;
        d["initial_radius"] = r.initial_radius;
        d["final_radius"] = r.final_radius;
        d["trials"] = r.trials;
        d["reductions"] = r.reductions;
        return nb::object(nb::make_tuple(points, d));
      },
      nb::sig("def dart(count: int, *, seed: int = 1, max_failures: int = 1000, shrink: float = 0.99, "
              "start: float = 1.0, info: bool = False) -> NDArray[numpy.float64] | tuple[NDArray[numpy.float64], dict[str, float | int]]"),
      "count"_a.none(), nb::kw_only(), "seed"_a.none() = 1, "max_failures"_a.none() = bluetile::DartOptions{}.max_failures,
      "shrink"_a.none() = bluetile::DartOptions{}.shrink, "start"_a.none() = bluetile::DartOptions{}.start,
      "info"_a.none() = false,
      R"(Dart throwing with radius reduction on the unit torus, as ``bluetile dart``: shape (count, 2).

A candidate is kept when no kept point is closer than the radius, which starts at ``start``
hexagonal spacings and shrinks by ``shrink`` after ``max_failures`` rejections in a row (1 to 10^9,
as ``--max-failures``: past that a run would not end in any time worth waiting for). With
``info=True`` returns (points, dict of initial_radius, final_radius, trials, reductions).)");
}

}  // namespace pybluetile
