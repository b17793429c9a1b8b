// The per-iteration record of a Lloyd run, shared by relax and stipple: the CSV behind --log,
// the --verbose lines and the progress line on a terminal, and the closing warnings.
#pragma once

#include <sstream>
#include <string>

#include "cli/progress.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile::cli {

class RelaxLog {
 public:
  RelaxLog(std::string label, int iterations, bool verbose);

  // Lloyd options that record every iteration here.
  LloydOptions lloyd_options(int iterations, double tolerance);
  void record(const LloydIteration& it);
  // Ends the progress line; writes the CSV to `path` unless it is empty; warns on stderr about
  // sites that did not move (coincident, no density) and a tolerance not reached.
  void finish(const LloydResult& result, const std::string& path, double tolerance, int iterations);

 private:
  Progress progress_;
  bool verbose_;
  std::ostringstream csv_;
};

}  // namespace bluetile::cli
