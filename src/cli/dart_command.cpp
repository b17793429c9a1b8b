// bluetile dart: the dart-throwing baseline (McCool & Fiume 1992; the paper, section 1.1).
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/sampling/dart_throwing.h"

namespace bluetile::cli {

void add_dart_command(CLI::App& app) {
  auto o = std::make_shared<DartOptions>();
  auto output = std::make_shared<std::string>();
  auto verbose = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("dart", "Dart throwing with radius reduction on the unit torus");
  cmd->add_option("-n,--count", o->count, "Number of points")->required()->check(CLI::Range(1, 100000000));
  cmd->add_option("-s,--seed", o->seed, "Seed")->capture_default_str();
  cmd->add_option("--max-failures", o->max_failures, "Rejections in a row before the radius shrinks")
      ->check(CLI::Range(1, 1000000000))
      ->capture_default_str();
  cmd->add_option("--shrink", o->shrink, "Factor applied to the radius at each reduction")
      ->check(CLI::Range(1e-6, 0.999999))
      ->capture_default_str();
  cmd->add_option("--start", o->start, "Starting radius in hexagonal spacings sqrt(2/(sqrt(3) N))")
      ->check(CLI::Range(1e-6, 4.0))
      ->capture_default_str();
  cmd->add_option("-o,--output", *output, "Output point file")->required();
  cmd->add_flag("-v,--verbose", *verbose, "Print the final radius and the number of trials on stderr");
  cmd->callback([o, output, verbose] {
    DartResult r = throw_darts(*o);
    char line[200];
    std::snprintf(line, sizeof line,
                  "bluetile dart: %zu points, seed %llu, radius %.6g -> %.6g (%zu reductions, %zu trials)",
                  r.points.size(), static_cast<unsigned long long>(o->seed), r.initial_radius, r.final_radius,
                  r.reductions, r.trials);
    write_point_file(*output, PointSet{r.points, {}}, {line});
    if (*verbose) std::fprintf(stderr, "%s\n", line);
  });
}

}  // namespace bluetile::cli
