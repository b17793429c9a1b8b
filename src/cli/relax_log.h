// The per-iteration record of a Lloyd run, shared by relax and stipple: the CSV behind --log,
// the --verbose lines and the progress line on a terminal, and the closing warnings.
#pragma once

#include <string>

#include "cli/progress.h"
#include "bluetile/core/output_file.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile::cli {

class RelaxLog {
 public:
  // `csv`: the opened --log output, streamed one line per iteration (memory does not grow with
  // the iterations), or null. The caller closes it.
  RelaxLog(std::string label, int iterations, bool verbose, OutputStream* csv);

  // Lloyd options that record every iteration here.
  LloydOptions lloyd_options(int iterations, double tolerance);
  void record(const LloydIteration& it);
  // Ends the progress line; warns on stderr about sites that did not move (coincident, no
  // density) and a tolerance not reached.
  void finish(const LloydResult& result, double tolerance, int iterations);

 private:
  Progress progress_;
  bool verbose_;
  OutputStream* csv_;
};

}  // namespace bluetile::cli
