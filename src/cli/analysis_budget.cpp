#include "cli/analysis_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bluetile/analysis/discrepancy.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/parallel.h"

namespace bluetile::cli {
namespace {

// One thread's seconds, measured with bluetile_periodogram_bench --threads 1 and analyze
// --no-psa-measures on 10^6 points (docs/BENCHMARKS.md, "Analysis at scale"), rounded up.
constexpr double kPairSeconds = 2e-8;           // psa's RDF: per pair closer than 0.25
constexpr double kBesselSeconds = 5e-8;         // its Hankel transform: per Bessel function
constexpr double kPeriodogramFftSeconds = 4e-9; // per butterfly of the non-uniform FFT's passes
// The four discrepancies, per pair i <= j: analyze of 20000 points --threads 1 with and without
// --no-discrepancy, 0.6 to 0.9 s of user time apart for 2e8 pairs on the loaded 2-core machine.
constexpr double kDiscrepancyPairSeconds = 4e-9;
constexpr double kPerPointSeconds = 1.2e-5;     // the rest: neighbours, RDF to 8 spacings, two Voronoi diagrams, images
// A run estimated longer than this (and within --time-limit) says so before it starts.
constexpr double kLongAnalysisSeconds = 60.0;

}  // namespace

std::string format_seconds(double seconds) {
  char text[32];
  if (seconds < 90.0) std::snprintf(text, sizeof text, "%.0f s", std::max(1.0, seconds));
  else if (seconds < 5400.0) std::snprintf(text, sizeof text, "%.0f min", seconds / 60.0);
  else std::snprintf(text, sizeof text, "%.1f h", seconds / 3600.0);
  return text;
}

AnalysisEstimate estimate_analysis(const std::vector<AnalysisJob>& jobs, bool psa_measures, bool discrepancy) {
  AnalysisEstimate e;
  const double threads = static_cast<double>(thread_count());
  double cpu = 0.0, psa_cpu = 0.0, discrepancy_cpu = 0.0;
  for (const AnalysisJob& job : jobs) {
    const int f = job.size > 0 ? job.size : default_periodogram_size(job.count);
    const double n = static_cast<double>(job.count), sets = static_cast<double>(job.sets);
    const double m = static_cast<double>(periodogram_nufft_grid(f));
    const double fft = periodogram_uses_nufft(job.count, f) ? kPeriodogramFftSeconds * m * (m + f / 2.0) * std::log2(m)
                                                            : 0.6e-9 * n * f * f / 2.0;
    cpu += sets * (fft + kPerPointSeconds * n);
    if (psa_measures) {
      const double pairs = rdf_power_spectrum_pairs(job.count);
      psa_cpu += sets * (kPairSeconds * pairs + kBesselSeconds * rdf_power_spectrum_bessels(job.count));
      e.psa_pairs = std::max(e.psa_pairs, pairs);
    }
    if (discrepancy) discrepancy_cpu += sets * kDiscrepancyPairSeconds * discrepancy_pairs(job.count);
    e.bytes = std::max(e.bytes, summary_memory_bytes(job.count, job.sets, f));
  }
  e.seconds = (cpu + psa_cpu + discrepancy_cpu) / threads;
  e.psa_seconds = psa_cpu / threads;
  e.discrepancy_seconds = discrepancy_cpu / threads;
  return e;
}

void check_analysis_budget(const std::vector<AnalysisJob>& jobs, bool psa_measures, double time_limit_minutes,
                           bool discrepancy) {
  const AnalysisEstimate e = estimate_analysis(jobs, psa_measures, discrepancy);
  std::size_t largest = 0;
  for (const AnalysisJob& job : jobs) largest = std::max(largest, job.count);
  check_memory(e.bytes, "analyze of " + std::to_string(largest) + " points" + (jobs.size() > 1 || jobs[0].sets > 1 ? " (and more sets)" : ""));
  const std::string threads = std::to_string(thread_count()) + (thread_count() == 1 ? " thread" : " threads");
  if (e.seconds <= 60.0 * time_limit_minutes) {
    // A run let go long says so as it starts: off a terminal no progress shows.
    if (e.seconds >= kLongAnalysisSeconds)
      std::fprintf(stderr, "bluetile: note: analyze of %zu points should take about %s on %s\n", largest,
                   format_seconds(e.seconds).c_str(), threads.c_str());
    return;
  }
  std::string message = "analyze of " + std::to_string(largest) + " points would take about " + format_seconds(e.seconds) +
                        " on " + threads;
  char pairs[32];
  std::snprintf(pairs, sizeof pairs, "%.2g", e.psa_pairs);
  // An O(N^2) measure that takes a large share of the time is named, with the way to skip it.
  const bool psa_heavy = e.psa_seconds > 0.5 * e.seconds, discrepancy_heavy = e.discrepancy_seconds > 0.25 * e.seconds;
  if (psa_heavy)
    message += ", " + format_seconds(e.psa_seconds) + " of it for psa's nu_eff and Omega (their RDF histograms all " +
               pairs + " pairs closer than 0.25: O(N^2) by psa's definition)";
  if (discrepancy_heavy)
    message += ", " + format_seconds(e.discrepancy_seconds) + " of it for the discrepancies (every pair: O(N^2))";
  char limit[32];
  std::snprintf(limit, sizeof limit, "%g", time_limit_minutes);
  message += ", more than --time-limit " + std::string(limit) + " minutes: ";
  if (psa_heavy)
    message += "--no-psa-measures skips them (the rest takes about " + format_seconds(e.seconds - e.psa_seconds) + "), or ";
  if (discrepancy_heavy)
    message += "--no-discrepancy skips the discrepancies (the rest takes about " +
               format_seconds(e.seconds - e.discrepancy_seconds) + "), or ";
  message += "raise --time-limit to run it anyway";
  throw Error(message);
}

}  // namespace bluetile::cli
