// Point-set summaries for `bluetile analyze` (the paper, sections 1.2 and 2; DESIGN section 5;
// Heck, Schlömer and Deussen 2013 for the RDF and its measures).
#include "bluetile/analysis/summary.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {

double mean_centroid_distance(std::span<const Point> points) {
  if (points.empty()) throw Error("mean centroid distance of no points");  // was 0 / 0
  Scene scene = make_scene(std::vector<Point>(points.begin(), points.end()));
  SceneCells cells = ExactEngine().compute(scene);
  double sum = 0.0;
  for (std::size_t i = 0; i < cells.cells.size(); ++i)
    sum += torus_distance(scene.sites[i], cells.cells[i].centroid, scene.domain);
  return sum / static_cast<double>(points.size());
}

double summary_memory_bytes(std::size_t count, std::size_t sets, int size) {
  constexpr double kBytesPerPoint = 600.0;  // beyond the periodogram: points, cells, grids, images
  const int f = size > 0 ? size : default_periodogram_size(count);
  const double n = static_cast<double>(count), k = static_cast<double>(sets);
  const double periodogram = 8.0 * static_cast<double>(f) * f;
  const double working = static_cast<double>(periodogram_memory_bytes(count, f));
  return k * 16.0 * n + kBytesPerPoint * n + (sets > 1 ? periodogram : 0.0) + working;
}

Summary summarize(std::span<const std::vector<Point>> sets, const SummaryOptions& options) {
  if (sets.empty()) throw Error("no point sets to analyse");
  const std::size_t n = sets[0].size();
  for (const auto& set : sets) {
    if (set.size() < 2)
      throw Error("a point set needs at least 2 points to analyse, got " + std::to_string(set.size()));
    if (set.size() != n)
      throw Error("cannot average sets of different sizes (" + std::to_string(n) + " and " +
                  std::to_string(set.size()) + " points)");
  }
  const bool periodic = options.boundary == Boundary::periodic;
  Summary s;
  s.count = n;
  s.sets = sets.size();
  s.boundary = options.boundary;
  s.has_centroid_distance = options.centroids && periodic;
  s.has_bond_order = options.bond_order && periodic;
  s.has_discrepancy = options.discrepancy;
  RdfOptions rdf_options = options.rdf;
  rdf_options.boundary = options.boundary;
  const int size = options.size > 0 ? options.size : default_periodogram_size(n);
  // The periodograms' running sum, in set order: the same bits as average_periodograms over all
  // of them, with one periodogram in memory beside it instead of all (0.8 GB each at 10^6).
  Periodogram periodogram_sum;
  std::vector<RadialDistribution> distributions;
  std::vector<RdfPowerSpectrum> spectra;
  s.has_spectral_measures = periodic && options.spectral_measures;
  const std::size_t total_work = sets.size();
  auto step = [&](const char* name) {
    if (options.step) options.step(name);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < sets.size(); ++k) {
    step("nearest neighbours");
    NearestNeighbourStats nn = nearest_neighbour_stats(sets[k], Domain{}, options.boundary);
    SetMeasures own{nn.rho(), nn.rho_mean(), nan, nan, nan};
    if (k == 0) {
      s.nn = nn;
      s.nn_min_lowest = s.nn_min_highest = nn.min;
    } else {
      s.nn.min += nn.min;
      s.nn.max += nn.max;
      s.nn.mean += nn.mean;
      s.nn_min_lowest = std::min(s.nn_min_lowest, nn.min);
      s.nn_min_highest = std::max(s.nn_min_highest, nn.min);
    }
    if (s.has_centroid_distance) step("centroids");
    if (s.has_centroid_distance) s.centroid_distance += mean_centroid_distance(sets[k]);
    if (s.has_bond_order) {
      step("bond order");
      BondOrder b = bond_orientational_order(sets[k]);
      own.bond_order = b.local;
      s.bond_order.local += b.local;
      s.bond_order.global += b.global;
    }
    if (s.has_discrepancy) {
      step("discrepancies");
      const Discrepancies d = discrepancies(sets[k]);
      s.discrepancy.centred += d.centred;
      s.discrepancy.wrap_around += d.wrap_around;
      s.discrepancy.mixture += d.mixture;
      s.discrepancy.l2_star += d.l2_star;
    }
    step("RDF");
    distributions.push_back(radial_distribution(sets[k], rdf_options));
    if (s.has_spectral_measures) step("psa's RDF spectrum");
    if (s.has_spectral_measures) {
      spectra.push_back(rdf_power_spectrum(sets[k]));
      if (sets.size() > 1) {
        const SpectralMeasures m = spectral_measures(spectra.back());
        own.nu_eff = m.nu_eff;
        own.omega = m.omega;
      }
    }
    if (sets.size() > 1) s.per_set.push_back(own);
    std::function<void(std::size_t, std::size_t)> progress;
    if (options.progress) {
      progress = [&](std::size_t done, std::size_t total) {
        options.progress(k * total + done, total_work * total);
      };
    }
    step("periodogram");
    Periodogram p = compute_periodogram(sets[k], size, progress);
    if (k == 0) {
      periodogram_sum.size = p.size;
      periodogram_sum.power.assign(p.power.size(), 0.0);
    }
    for (std::size_t i = 0; i < p.power.size(); ++i) periodogram_sum.power[i] += p.power[i];
  }
  const double count = static_cast<double>(sets.size());
  s.nn.min /= count;
  s.nn.max /= count;
  s.nn.mean /= count;
  s.centroid_distance /= count;
  s.bond_order.local /= count;
  s.bond_order.global /= count;
  s.discrepancy.centred /= count;
  s.discrepancy.wrap_around /= count;
  s.discrepancy.mixture /= count;
  s.discrepancy.l2_star /= count;
  for (double& v : periodogram_sum.power) v /= count;  // count = 1: exact
  s.periodogram = std::move(periodogram_sum);
  s.radial = radial_power(s.periodogram, options.bin_width);
  s.rdf = sets.size() == 1 ? std::move(distributions[0]) : average_distributions(distributions);
  if (s.has_spectral_measures) {
    s.rdf_power = sets.size() == 1 ? std::move(spectra[0]) : average_spectra(spectra);
    s.measures = spectral_measures(s.rdf_power);
  }
  return s;
}

std::vector<LevelSummary> summarize_levels(std::span<const Point> points, std::span<const int> levels,
                                           const SummaryOptions& options) {
  if (levels.size() != points.size()) throw Error("the analysis by level needs a level column (x y level) on every point");
  // A level outside a point file's range would give a prefix "levels 0..-1" or a count no file
  // can hold; refused as the readers refuse it (point_file.h).
  for (std::size_t i = 0; i < levels.size(); ++i)
    if (levels[i] < 0 || levels[i] > kMaxLevel)
      throw Error("point " + std::to_string(i) + ": level must be an integer from 0 to " + std::to_string(kMaxLevel) +
                  ", got " + std::to_string(levels[i]));
  std::vector<int> distinct(levels.begin(), levels.end());
  std::sort(distinct.begin(), distinct.end());
  distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
  std::vector<LevelSummary> result;
  for (int level : distinct) {
    std::vector<std::vector<Point>> prefix(1);
    for (std::size_t i = 0; i < points.size(); ++i)
      if (levels[i] <= level) prefix[0].push_back(points[i]);
    if (prefix[0].size() < 2)
      throw Error("levels 0.." + std::to_string(level) + " hold " + std::to_string(prefix[0].size()) +
                  " point; a prefix needs at least 2 to analyse");
    result.push_back({level, summarize(prefix, options)});
  }
  return result;
}

}  // namespace bluetile
