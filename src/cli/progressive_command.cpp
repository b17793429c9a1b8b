// bluetile progressive: hierarchical point sets, new levels relaxed around fixed earlier ones.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/point_output.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/progressive.h"

namespace bluetile::cli {
namespace {

struct ProgressiveOptions {
  std::string input;
  long long count = 0;
  long long add = 0;
  double ratio = 0.0;
  int levels = 0;
  int iterations = 80;
  double tolerance = 0.0;
  std::uint64_t seed = 1;
  std::string placement = "gaps";
  long long sets = 1;
  PointOutputOptions output;
  EngineOptions engine;
};

void run_progressive(const ProgressiveOptions& o) {
  if (!o.input.empty() && o.add == 0 && o.ratio == 0.0)
    throw Error("--input needs --add M or --ratio R: how many points to add");
  if (o.ratio != 0.0 && o.ratio <= 1.0) throw Error("--ratio must be above 1, got " + std::to_string(o.ratio));
  // The bases: the input's sets (each gets its own levels), or K empty ones.
  std::vector<PointSet> sets(static_cast<std::size_t>(o.sets));
  if (!o.input.empty()) {
    sets = read_point_table(o.input);
    if (sets.empty()) throw Error(o.input + ": no points");
  }
  PointOutput output(o.output, sets.size());  // names and formats checked before any work

  HierarchyOptions options;
  options.count = static_cast<std::size_t>(o.count);
  options.add = static_cast<std::size_t>(o.add);
  options.ratio = o.ratio;
  options.levels = o.levels;
  options.iterations = o.iterations;
  options.tolerance = o.tolerance;
  options.placement = o.placement == "random" ? Placement::random : Placement::gaps;
  // Every set's levels and sizes, checked before any work.
  int target_levels = 0;
  for (const PointSet& set : sets) {
    const int base_levels = count_levels(set);
    target_levels = o.levels ? o.levels : std::max(base_levels + 1, o.input.empty() ? 4 : 1);
    if (target_levels <= base_levels) {
      throw Error("--levels " + std::to_string(target_levels) + ": " + (o.input.empty() ? "" : o.input + " ") +
                  "already has " + std::to_string(base_levels) + " level(s); --levels is the total to reach");
    }
    hierarchy_level_sizes(set, options);
  }

  auto engine = make_engine(o.engine);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    // Set k of a batch is the set --seed S+k gives alone (wrapping past 2^64 - 1).
    options.seed = o.seed + k;
    std::unique_ptr<Progress> progress;
    int progress_level = -1;
    options.on_iteration = [&](int level, const LloydIteration& it) {
      if (level != progress_level) {
        progress_level = level;
        progress = std::make_unique<Progress>((sets.size() > 1 ? "set " + std::to_string(k) + ", " : "") + "level " +
                                                  std::to_string(level) + ": relax",
                                              o.iterations);
      }
      progress->update(it.iteration);
    };
    sets[k] = add_levels(*engine, std::move(sets[k]), options);
  }
  std::string how = o.input.empty() ? "from " + std::to_string(o.count) + " random points, seed " + std::to_string(o.seed)
                                    : "on " + o.input + ", seed " + std::to_string(o.seed);
  if (sets.size() > 1) how += " + set index";
  const std::string what = sets.size() == 1 ? std::to_string(sets[0].points.size()) + " points"
                                            : std::to_string(sets.size()) + " sets of " +
                                                  std::to_string(sets[0].points.size()) + " points";
  const std::vector<std::string> header = {
      "bluetile progressive: " + what + " in " + std::to_string(target_levels) + " levels " + how + ", " +
          std::to_string(o.iterations) + " iterations per level, engine " + std::string(engine->name()) +
          ", placement " + o.placement,
      "columns: x y level"};
  output.write(sets, header);
}

}  // namespace

void add_progressive_command(CLI::App& app) {
  auto o = std::make_shared<ProgressiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "progressive", "Hierarchical point sets: add levels of points relaxed around the fixed earlier levels");
  auto* input = cmd->add_option("-i,--input", o->input,
                                "Base points, kept bit for bit: text (each '#'-separated set gets its own levels), .npy "
                                "or .bpt")
                    ->check(CLI::ExistingFile);
  auto* count = cmd->add_option("-n,--count", o->count, "Build from scratch: level 0 has N relaxed random points")
                    ->check(CLI::Range(1LL, 100000000LL));
  input->excludes(count);
  auto* add = cmd->add_option("-a,--add", o->add, "Points each new level adds (default with --count: N)")
                  ->check(CLI::Range(1LL, 100000000LL));
  auto* ratio = cmd->add_option("--ratio", o->ratio, "Instead of --add: each level multiplies the total by R (> 1)");
  add->excludes(ratio);
  cmd->add_option("-l,--levels", o->levels,
                  "Total levels of the result (default: 4 with --count, one more than the input has with --input)")
      ->check(CLI::Range(1, 64));
  cmd->add_option("-k,--iterations", o->iterations, "Lloyd iterations per level")->check(CLI::Range(0, 100000000))->capture_default_str();
  cmd->add_option("--tolerance", o->tolerance, "Stop a level early once no point moves more than this")->check(CLI::NonNegativeNumber);
  cmd->add_option("-s,--seed", o->seed, "Seed of the random placement")->capture_default_str();
  cmd->add_option("--placement", o->placement, "Start of new points: gaps (best candidate) or random (the paper)")
      ->check(CLI::IsMember({"gaps", "random"}))
      ->capture_default_str();
  cmd->add_option("--sets", o->sets, "Build K independent hierarchies; set k is the one --seed S+k gives alone")
      ->check(CLI::Range(1LL, 10000000LL))
      ->needs(count);
  add_point_output_options(cmd, o->output, "Output points (x y level)");
  add_engine_options(cmd, o->engine);
  cmd->callback([o] {
    if (o->input.empty() && o->count == 0) throw CLI::RequiredError("--input or --count");
    run_progressive(*o);
  });
}

}  // namespace bluetile::cli
