#include "cli/relax_log.h"

#include <cstdio>

#include "bluetile/core/text.h"

namespace bluetile::cli {

RelaxLog::RelaxLog(std::string label, int iterations, bool verbose, OutputStream* csv)
    : progress_(std::move(label), iterations), verbose_(verbose), csv_(csv) {
  if (csv_) csv_->write("iteration,energy,max_displacement,mean_displacement,coincident,fallbacks,zero_density\n");
}

LloydOptions RelaxLog::lloyd_options(int iterations, double tolerance) {
  LloydOptions options;
  options.iterations = iterations;
  options.tolerance = tolerance;
  options.on_iteration = [this](const LloydIteration& it) { record(it); };
  // Only the CSV and the verbose lines show the energy; without them the cells' second moments
  // are not measured.
  options.energy = csv_ != nullptr || verbose_;
  return options;
}

void RelaxLog::record(const LloydIteration& it) {
  if (csv_) {
    // An undefined number is an empty field (CSV's missing value), as in analyze's CSVs.
    csv_->print("%d,%s,%s,%s,%zu,%zu,%zu\n", it.iteration, csv_number(it.energy, 17).c_str(),
                csv_number(it.max_displacement, 17).c_str(), csv_number(it.mean_displacement, 17).c_str(), it.coincident,
                it.fallbacks, it.zero_density);
  }
  if (verbose_) {
    progress_.finish();
    std::string notes;
    if (it.coincident) notes += ", " + std::to_string(it.coincident) + " coincident";
    if (it.zero_density) notes += ", " + std::to_string(it.zero_density) + " without density";
    std::fprintf(stderr, "iteration %d: energy %.9e, max displacement %.3e, mean %.3e%s\n", it.iteration, it.energy,
                 it.max_displacement, it.mean_displacement, notes.c_str());
  }
  char detail[64];
  std::snprintf(detail, sizeof detail, "max displacement %.2e", it.max_displacement);
  progress_.update(it.iteration, detail);
}

void RelaxLog::finish(const LloydResult& result, double tolerance, int iterations) {
  progress_.finish();
  const LloydIteration* last = result.iterations ? &result.last : nullptr;
  if (last && last->coincident) {
    std::fprintf(stderr, "bluetile: warning: %zu sites coincide with another site and were not moved\n",
                 last->coincident);
  }
  if (last && last->zero_density) {
    std::fprintf(stderr, "bluetile: note: %zu sites have cells where the density is zero and were not moved\n",
                 last->zero_density);
  }
  if (tolerance > 0.0 && !result.converged) {
    std::fprintf(stderr, "bluetile: note: max displacement %.3e still above --tolerance %.3e after %d iterations\n",
                 last ? last->max_displacement : 0.0, tolerance, iterations);
  }
}

}  // namespace bluetile::cli
