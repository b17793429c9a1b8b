// bluetile progressive: hierarchical point sets, new levels relaxed around fixed earlier ones.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
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
  std::string output;
  EngineOptions engine;
};

// A hierarchy larger than this is almost surely a mistyped option, and would need tens of GiB.
constexpr std::size_t kMaxPoints = 100'000'000;

int level_count(const PointSet& set) {
  if (set.points.empty()) return 0;
  if (!set.has_levels()) return 1;
  return *std::max_element(set.levels.begin(), set.levels.end()) + 1;
}

void run_progressive(const ProgressiveOptions& o) {
  PointSet set;
  if (!o.input.empty()) {
    set = read_point_file(o.input);
    if (o.add == 0 && o.ratio == 0.0) throw Error("--input needs --add M or --ratio R: how many points to add");
  }
  const int base_levels = level_count(set);
  const int target_levels = o.levels ? o.levels : std::max(base_levels + 1, o.input.empty() ? 4 : 1);
  if (target_levels <= base_levels) {
    throw Error("--levels " + std::to_string(target_levels) + ": " + (o.input.empty() ? "" : o.input + " ") +
                "already has " + std::to_string(base_levels) + " level(s); --levels is the total to reach");
  }
  if (o.ratio != 0.0 && o.ratio <= 1.0) throw Error("--ratio must be above 1, got " + std::to_string(o.ratio));
  const std::size_t per_level = o.add ? static_cast<std::size_t>(o.add) : static_cast<std::size_t>(o.count);

  auto engine = make_engine(o.engine);
  LevelOptions level;
  level.iterations = o.iterations;
  level.tolerance = o.tolerance;
  level.placement = o.placement == "random" ? Placement::random : Placement::gaps;

  for (int l = base_levels; l < target_levels; ++l) {
    level.add = o.input.empty() && l == 0 ? static_cast<std::size_t>(o.count)
                                           : level_size(set.points.size(), per_level, o.ratio);
    if (level.add == 0) {
      throw Error("--ratio " + std::to_string(o.ratio) + " adds no point to a set of " +
                  std::to_string(set.points.size()) + " (level " + std::to_string(l) + ")");
    }
    if (set.points.size() + level.add > kMaxPoints) {
      throw Error("level " + std::to_string(l) + " would bring the set to " +
                  std::to_string(set.points.size() + level.add) + " points, more than the limit of " +
                  std::to_string(kMaxPoints));
    }
    level.seed = derive_seed(o.seed, static_cast<std::uint64_t>(l));
    Progress progress("level " + std::to_string(l) + ": relax", o.iterations);
    level.on_iteration = [&](const LloydIteration& it) { progress.update(it.iteration); };
    set = add_level(*engine, set, level);
  }
  std::string how = o.input.empty() ? "from " + std::to_string(o.count) + " random points, seed " + std::to_string(o.seed)
                                    : "on " + o.input + ", seed " + std::to_string(o.seed);
  write_point_file(o.output, set,
                   {"bluetile progressive: " + std::to_string(set.points.size()) + " points in " +
                        std::to_string(target_levels) + " levels " + how + ", " + std::to_string(o.iterations) +
                        " iterations per level, engine " + std::string(engine->name()) + ", placement " + o.placement,
                    "columns: x y level"});
}

}  // namespace

void add_progressive_command(CLI::App& app) {
  auto o = std::make_shared<ProgressiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "progressive", "Hierarchical point sets: add levels of points relaxed around the fixed earlier levels");
  auto* input = cmd->add_option("-i,--input", o->input, "Base point file (kept bit for bit)")->check(CLI::ExistingFile);
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
  cmd->add_option("-o,--output", o->output, "Output point file (x y level)")->required();
  add_engine_options(cmd, o->engine);
  cmd->callback([o] {
    if (o->input.empty() && o->count == 0) throw CLI::RequiredError("--input or --count");
    run_progressive(*o);
  });
}

}  // namespace bluetile::cli
