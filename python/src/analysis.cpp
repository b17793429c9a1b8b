// analyze, periodogram, radial_power, nearest_neighbour_distances (psa's conventions:
// docs/DESIGN.md, section 5).
#include <cmath>

#include <nanobind/stl/string.h>

#include "arguments.h"
#include "arrays.h"
#include "bindings.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/analysis/summary_record.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/text.h"

namespace pybluetile {

using namespace nb::literals;

namespace {

// The periodogram's size F, as `bluetile analyze --size`: 0 or even, at most 65536 (F x F
// doubles: past that a bare MemoryError).
int spectrum_size(const Whole& size_arg) {
  constexpr int kMaxSize = 65536;
  const std::string range = "0 (from N) or an even number 2 to " + std::to_string(kMaxSize);
  const int size = whole_or<int>(size_arg, 0, "size", 0, kMaxSize, range);
  if (size % 2 != 0) throw nb::value_error(("size: expected " + range + ", got " + std::to_string(size)).c_str());
  return size;
}

// The annulus width; None: 1, the default.
double bin_width_of(const Real& bin_width_arg) {
  const double bin_width = real_or(bin_width_arg, 1.0, "bin_width");
  if (!(bin_width > 0.0) || !std::isfinite(bin_width))
    throw nb::value_error(("bin_width: expected a positive number, got " + bluetile::shortest_text(bin_width)).c_str());
  return bin_width;
}

// Refused outside [0, 1), as `bluetile analyze` refuses them.
PointSets analysed_sets(const ArrayArg& points) {
  PointSets input = point_sets(array_arg(points, "points", ArrayKind::points), "points", OutsideTorus::refuse);
  if (input.sets[0].size() < 2) throw nb::value_error("points: analysis needs at least 2 points per set");
  return input;
}

// Refused at once with the estimate where the periodograms of `sets` sets of `count` points at
// size F would not fit (a bare MemoryError after seconds of work before): each set's periodogram
// kept (`kept`: for a mean after them all) and one set's working space.
void check_periodogram_memory(const char* function, std::size_t count, std::size_t sets, int size, bool kept) {
  const double n = static_cast<double>(count), k = static_cast<double>(sets), f = static_cast<double>(size);
  const double bytes = k * 16.0 * n + (kept ? k * 8.0 * f * f : 0.0) +
                       static_cast<double>(bluetile::periodogram_memory_bytes(count, size));
  bluetile::check_memory(bytes, std::string(function) + " of " + (sets > 1 ? std::to_string(sets) + " sets of " : "") +
                                    std::to_string(count) + " points, size=" + std::to_string(size));
}

nb::ndarray<nb::numpy, double> periodogram_array(bluetile::Periodogram&& p) {
  const auto f = static_cast<std::size_t>(p.size);
  return to_numpy(std::move(p.power), {f, f});
}

nb::dict radial_dict(const std::vector<bluetile::Annulus>& radial) {
  std::vector<double> frequency, power, anisotropy;
  std::vector<std::int64_t> count;
  for (const bluetile::Annulus& a : radial) {
    frequency.push_back(a.frequency);
    power.push_back(a.power);
    anisotropy.push_back(a.anisotropy_db);
    count.push_back(static_cast<std::int64_t>(a.count));
  }
  const std::size_t n = radial.size();
  nb::dict d;
  d["frequency"] = to_numpy(std::move(frequency), {n});
  d["power"] = to_numpy(std::move(power), {n});
  d["anisotropy_db"] = to_numpy(std::move(anisotropy), {n});
  d["count"] = to_numpy(std::move(count), {n});
  return d;
}

// A record of the library's serializer (summary_record.h) as Python values: objects as dicts,
// arrays as NumPy arrays (NaN where stats.json has null), a non-finite number as None (null).
nb::object to_python(bluetile::Record&& r) {
  using Kind = bluetile::Record::Kind;
  switch (r.kind) {
    case Kind::null: return nb::none();
    case Kind::integer: return nb::int_(r.integer);
    case Kind::real: return std::isfinite(r.real) ? nb::object(nb::float_(r.real)) : nb::object(nb::none());
    case Kind::text: return nb::str(r.text.c_str());
    case Kind::reals: {
      const std::size_t n = r.reals.size();
      return nb::cast(to_numpy(std::move(r.reals), {n}));
    }
    case Kind::integers: {
      const std::size_t n = r.integers.size();
      return nb::cast(to_numpy(std::move(r.integers), {n}));
    }
    case Kind::object: {
      nb::dict d;
      for (std::size_t i = 0; i < r.keys.size(); ++i) d[r.keys[i].c_str()] = to_python(std::move(r.values[i]));
      return d;
    }
  }
  return nb::none();
}

// The keys and values of `bluetile analyze`'s stats.json for one series (its top level), from
// the same serializer, and the periodogram.
nb::dict summary_dict(bluetile::Summary&& s) {
  nb::dict d = nb::cast<nb::dict>(to_python(bluetile::summary_record(s)));
  d["periodogram"] = periodogram_array(std::move(s.periodogram));
  return d;
}

}  // namespace

void bind_analysis(nb::module_& m) {
  m.def(
      "analyze",
      [](const ArrayArg& points, const Whole& size_arg, const Real& bin_width, const Flag& centroids,
         const Flag& psa_measures, const Flag& discrepancy) {
        const int size = spectrum_size(size_arg);
        bluetile::SummaryOptions options;
        options.size = size;
        options.bin_width = bin_width_of(bin_width);
        options.centroids = flag_or(centroids, true, "centroids");
        options.spectral_measures = flag_or(psa_measures, true, "psa_measures");
        options.discrepancy = flag_or(discrepancy, true, "discrepancy");
        PointSets input = analysed_sets(points);
        // As the tool's analyze: refused at once with the estimate.
        const std::size_t n = input.sets[0].size(), sets = input.sets.size();
        bluetile::check_memory(bluetile::summary_memory_bytes(n, sets, size),
                               "analyze of " + (sets > 1 ? std::to_string(sets) + " sets of " : "") + std::to_string(n) +
                                   " points, size=" + std::to_string(size ? size : bluetile::default_periodogram_size(n)));
        bluetile::Summary summary;
        {
          nb::gil_scoped_release release;
          SignalChecks signal_checks;  // Ctrl-C inside the loops
          summary = bluetile::summarize(input.sets, options);
        }
        return summary_dict(std::move(summary));
      },
      nb::sig("def analyze(points: numpy.typing.ArrayLike, *, size: int = 0, bin_width: float = 1.0, centroids: bool = True, "
              "psa_measures: bool = True, discrepancy: bool = True) -> dict[str, typing.Any]"),
      "points"_a.none(), nb::kw_only(), "size"_a.none() = 0, "bin_width"_a.none() = 1.0, "centroids"_a.none() = true, "psa_measures"_a.none() = true,
      "discrepancy"_a.none() = true,
      R"(Statistics of a point set on the unit torus, as ``bluetile analyze`` writes them to stats.json.

``points``: shape (N, 2), or (K, N, 2) for the mean over K sets (``--average``), coordinates in
[0, 1) as the tool asks (``points % 1.0 % 1.0`` wraps others: once gives 1.0 for -1e-17; so for
every analysis function). Returns a dict with stats.json's keys and numbers (one serializer in the library makes both): n, sets,
boundary, nn_min, nn_max, nn_mean, nn_x1000, nn_relative, hexagonal_spacing, rho,
average_min_distance, nn_min_lowest/highest (K > 1), mean_centroid_distance[_relative] unless
``centroids=False``, nu_eff and omega by psa's definitions (None when ``psa_measures=False``;
their RDF is O(N^2), about half an hour at 10^6 points on 2 cores) with omega_range_nu,
bond_order (local, global), discrepancy (CD, WD, MD, L2-star, as scipy.stats.qmc.discrepancy;
absent with ``discrepancy=False``, as ``--no-discrepancy``: O(N^2)), rdf_range_relative, rdf_bins, periodogram_size and radial (arrays
frequency, nu, power, anisotropy_db, count; NaN where stats.json has null); and "periodogram",
the (F, F) array of ``periodogram``. size: the periodogram's F (0: 2 floor(5 sqrt(N)));
bin_width: the annulus width.)");

  m.def(
      "periodogram",
      [](const ArrayArg& points, const Whole& size_arg) {
        const int size = spectrum_size(size_arg);
        PointSets input = analysed_sets(points);
        if (input.batched) throw nb::value_error("points: expected shape (N, 2); analyze averages several sets");
        const int f = size ? size : bluetile::default_periodogram_size(input.sets[0].size());
        check_periodogram_memory("periodogram", input.sets[0].size(), 1, f, false);
        bluetile::Periodogram p;
        {
          nb::gil_scoped_release release;
          SignalChecks signal_checks;  // Ctrl-C inside the loops
          p = bluetile::compute_periodogram(input.sets[0], f);
        }
        return periodogram_array(std::move(p));
      },
      nb::sig("def periodogram(points: numpy.typing.ArrayLike, size: int = 0) -> NDArray[numpy.float64]"),
      "points"_a.none(), "size"_a.none() = 0,
      R"(The periodogram P(k) = |sum_j exp(-2 pi i k.x_j)|^2 / N, shape (F, F) (the direct sum for
small sets, a non-uniform FFT within 1e-9 of it for larger ones):
element [ky + F/2, kx + F/2] is P at integer frequency (kx, ky), for kx, ky in [-F/2, F/2).
White noise gives about 1; P(0) = N. size: F, even (0: 2 floor(5 sqrt(N))).)");

  m.def(
      "radial_power",
      [](const ArrayArg& points, const Whole& size_arg, const Real& bin_width_arg) {
        const int size = spectrum_size(size_arg);
        const double bin_width = bin_width_of(bin_width_arg);
        PointSets input = analysed_sets(points);
        const std::size_t n = input.sets[0].size();
        check_periodogram_memory("radial_power", n, input.sets.size(), size ? size : bluetile::default_periodogram_size(n),
                                 true);
        std::vector<bluetile::Annulus> radial;
        {
          nb::gil_scoped_release release;
          SignalChecks signal_checks;  // Ctrl-C inside the loops
          std::vector<bluetile::Periodogram> each;
          for (const auto& set : input.sets) {
            const int f = size ? size : bluetile::default_periodogram_size(set.size());
            each.push_back(bluetile::compute_periodogram(set, f));
          }
          radial = bluetile::radial_power(bluetile::average_periodograms(each), bin_width);
        }
        return radial_dict(radial);
      },
      nb::sig("def radial_power(points: numpy.typing.ArrayLike, size: int = 0, bin_width: float = 1.0) -> dict[str, NDArray]"),
      "points"_a.none(), "size"_a.none() = 0, "bin_width"_a.none() = 1.0,
      R"(Radial power and anisotropy per annulus (psa's conventions), of one set or the mean
periodogram of K sets: a dict of arrays frequency (the annulus' inner radius), power,
anisotropy_db (10 log10 of variance / power^2; white noise about 0 dB) and count.)");

  m.def(
      "nearest_neighbour_distances",
      [](const ArrayArg& points) {
        PointSets input = point_sets(array_arg(points, "points", ArrayKind::points), "points", OutsideTorus::refuse);
        if (input.batched) throw nb::value_error("points: expected shape (N, 2)");
        std::vector<double> d;
        {
          nb::gil_scoped_release release;
          SignalChecks signal_checks;  // Ctrl-C inside the loops
          d = bluetile::nearest_neighbour_distances(input.sets[0]);
        }
        const std::size_t n = d.size();
        return to_numpy(std::move(d), {n});
      },
      nb::sig("def nearest_neighbour_distances(points: numpy.typing.ArrayLike) -> NDArray[numpy.float64]"),
      "points"_a.none(), R"(Distance of every point to its nearest neighbour on the unit torus, shape (N,): periodic
images count, so a lone point's nearest neighbour is its own copy one period away (distance 1).)");
}

}  // namespace pybluetile
