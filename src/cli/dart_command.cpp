// bluetile dart: the dart-throwing baseline (McCool & Fiume 1992; the paper, section 1.1).
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/commands.h"
#include "cli/numeric_options.h"
#include "cli/point_output.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/text.h"
#include "bluetile/sampling/dart_throwing.h"

namespace bluetile::cli {

void add_dart_command(CLI::App& app) {
  auto o = std::make_shared<DartOptions>();
  auto output = std::make_shared<PointOutputOptions>();
  auto sets = std::make_shared<long long>(1);
  auto verbose = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("dart", "Dart throwing with radius reduction on the unit torus");
  add_integer_option(cmd, "-n,--count", o->count, std::size_t{1}, kMaxDartCount, "Number of points")
      ->required();
  add_seed_option(cmd, o->seed);
  add_integer_option(cmd, "--sets", *sets, 1LL, 10000000LL, "Throw K independent sets; set k is the set --seed S+k gives alone");
  add_integer_option(cmd, "--max-failures", o->max_failures, std::size_t{1}, kMaxDartFailures,
                     "Rejections in a row before the radius shrinks");
  add_real_option(cmd, "--shrink", o->shrink, {kMinDartShrink, kMaxDartShrink}, "Factor applied to the radius at each reduction");
  add_real_option(cmd, "--start", o->start, {kMinDartStart, kMaxDartStart},
                  "Starting radius in hexagonal spacings sqrt(2/(sqrt(3) N)), at most half the torus (0.5)");
  add_point_output_options(cmd, *output, "Output points ('-': standard output)");
  cmd->add_flag("-v,--verbose", *verbose, "Print the final radius and the number of trials on stderr");
  cmd->callback([o, output, sets, verbose] {
    const auto k_sets = static_cast<std::size_t>(*sets);
    check_memory(static_cast<double>(o->count) * static_cast<double>(k_sets) * kDartBytesPerPoint,
                 "--count " + std::to_string(o->count) + (k_sets > 1 ? " --sets " + std::to_string(k_sets) : ""));
    OutputSet outputs;
    PointOutput file(outputs, *output, k_sets);
    std::vector<PointSet> results(k_sets);
    std::vector<std::string> header;
    for (std::size_t k = 0; k < k_sets; ++k) {
      DartOptions one = *o;
      one.seed = o->seed + k;  // wraps past 2^64 - 1, as the seed's own arithmetic does
      DartResult r = throw_darts(one);
      char line[200];
      std::snprintf(line, sizeof line,
                    "bluetile dart: %s, seed %llu, radius %.6g%s -> %.6g (%s, %s)",
                    counted(static_cast<long long>(r.points.size()), "point").c_str(),
                    static_cast<unsigned long long>(one.seed), r.initial_radius,
                    r.initial_radius == kMaxDartRadius ? " (half the torus)" : "", r.final_radius,
                    counted(static_cast<long long>(r.reductions), "reduction").c_str(),
                    counted(static_cast<long long>(r.trials), "trial").c_str());
      if (k_sets == 1) header.push_back(line);
      if (*verbose) std::fprintf(stderr, "%s\n", line);
      results[k].points = std::move(r.points);
    }
    if (k_sets > 1) {
      header.push_back("bluetile dart: " + std::to_string(k_sets) + " sets of " + std::to_string(o->count) +
                       " points, seeds " + std::to_string(o->seed) + " + set index");
    }
    file.write(results, header);
    outputs.publish();
  });
}

}  // namespace bluetile::cli
