// What `bluetile analyze` will cost, estimated before it starts: a set whose analysis would
// run for hours or exceed the memory is refused with the estimate, and with the way to go on.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace bluetile::cli {

// One series of the analysis: `sets` sets of `count` points (averaged), periodogram size F
// (0: the default for count).
struct AnalysisJob {
  std::size_t count = 0;
  std::size_t sets = 1;
  int size = 0;
};

struct AnalysisEstimate {
  double seconds = 0.0;      // all of it, on thread_count() threads
  double psa_seconds = 0.0;  // of which psa's nu_eff and Omega (their RDF spectrum)
  double psa_pairs = 0.0;    // the pairs that spectrum histograms
  double discrepancy_seconds = 0.0;  // of which the four discrepancies (every pair)
  double bytes = 0.0;        // peak memory
};

// From constants measured on this project's 2-core machine (docs/BENCHMARKS.md, "Analysis at
// scale"), scaled by the thread count.
AnalysisEstimate estimate_analysis(const std::vector<AnalysisJob>& jobs, bool psa_measures, bool discrepancy = false);

// Throws Error when the estimate exceeds `time_limit_minutes` (naming --no-psa-measures or
// --no-discrepancy when those O(N^2) measures take much of the time, and --time-limit) or the
// available memory; prints one `bluetile: note:` line with the estimate when it is over a minute.
void check_analysis_budget(const std::vector<AnalysisJob>& jobs, bool psa_measures, double time_limit_minutes,
                           bool discrepancy = false);

// "12 s", "15 min", "4.2 h"
std::string format_seconds(double seconds);

}  // namespace bluetile::cli
