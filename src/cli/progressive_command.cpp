// bluetile progressive: hierarchical point sets, new levels relaxed around fixed earlier ones.
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/memory_budget.h"
#include "cli/numeric_options.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
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

// Bytes per point of a level's relaxation (see kRelaxBytesPerSite) plus the levels column.
constexpr double kBytesPerPoint = kRelaxBytesPerSite + 8.0;

void run_progressive(const ProgressiveOptions& o) {
  if (!o.input.empty() && o.add == 0 && o.ratio == 0.0)
    throw Error("--input needs --add M or --ratio R: how many points to add");
  OutputSet outputs;
  if (!o.input.empty()) outputs.add_input(o.input);
  OutputFile& output = outputs.add(o.output, {.allow_stdout = true});

  PointSet set;
  if (!o.input.empty()) {
    set = read_point_file(o.input);
    if (set.points.empty()) throw Error(input_name(o.input) + ": no points");
  }
  HierarchyOptions hierarchy;
  hierarchy.count = static_cast<std::size_t>(o.count);
  hierarchy.add = static_cast<std::size_t>(o.add);
  hierarchy.ratio = o.ratio;
  hierarchy.levels = o.levels;
  hierarchy.iterations = o.iterations;
  hierarchy.tolerance = o.tolerance;
  hierarchy.seed = o.seed;
  hierarchy.placement = o.placement == "random" ? Placement::random : Placement::gaps;
  // Every level's size, checked before any work.
  std::vector<std::size_t> sizes;
  try {
    sizes = hierarchy_level_sizes(set, hierarchy);
  } catch (const Error& e) {
    throw Error(o.input.empty() ? std::string(e.what()) : input_name(o.input) + ": " + e.what());
  }
  std::size_t total = set.points.size();
  for (std::size_t add : sizes) total += add;
  const int levels = count_levels(set) + static_cast<int>(sizes.size());
  check_memory(static_cast<double>(total) * kBytesPerPoint,
               std::to_string(total) + " points in " + std::to_string(levels) + " levels");

  auto engine = make_engine(o.engine);
  std::unique_ptr<Progress> progress;
  int progress_level = -1;
  hierarchy.on_iteration = [&](int level, const LloydIteration& it) {
    if (level != progress_level) {
      progress = std::make_unique<Progress>("level " + std::to_string(level) + ": relax", o.iterations);
      progress_level = level;
    }
    progress->update(it.iteration);
  };
  set = add_levels(*engine, std::move(set), hierarchy);
  progress.reset();
  std::string how = o.input.empty() ? "from " + std::to_string(o.count) + " random points, seed " + std::to_string(o.seed)
                                    : "on " + input_name(o.input) + ", seed " + std::to_string(o.seed);
  const std::vector<std::string> header = {
      "bluetile progressive: " + std::to_string(set.points.size()) + " points in " + std::to_string(levels) +
          " levels " + how + ", " + std::to_string(o.iterations) + " iterations per level, engine " +
          std::string(engine->name()) + ", placement " + o.placement,
      "columns: x y level"};
  output.write([&](OutputStream& out) { write_points(out, set, header); });
  outputs.publish();
}

}  // namespace

void add_progressive_command(CLI::App& app) {
  auto o = std::make_shared<ProgressiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "progressive", "Hierarchical point sets: add levels of points relaxed around the fixed earlier levels");
  auto* input = cmd->add_option("-i,--input", o->input, "Base point file, kept bit for bit ('-': standard input)");
  auto* count = add_integer_option(cmd, "-n,--count", o->count, 1LL, kMaxCount,
                                   "Build from scratch: level 0 has N relaxed random points");
  input->excludes(count);
  auto* add = add_integer_option(cmd, "-a,--add", o->add, 1LL, kMaxCount, "Points each new level adds (default with --count: N)");
  // Above 10^8 every level would pass the point limit at once.
  auto* ratio = add_real_option(cmd, "--ratio", o->ratio, {1.0, 1e8, true, false},
                                "Instead of --add: each level multiplies the total by R (> 1)");
  add->excludes(ratio);
  add_integer_option(cmd, "-l,--levels", o->levels, 1, 64,
                     "Total levels of the result (default: 4 with --count, one more than the input has with --input)")
      ->default_str("");
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxIterations, "Lloyd iterations per level");
  add_real_option(cmd, "--tolerance", o->tolerance, {}, "Stop a level early once no point moves more than this");
  add_integer_option(cmd, "-s,--seed", o->seed, std::uint64_t{0}, std::numeric_limits<std::uint64_t>::max(),
                     "Seed of the random placement");
  cmd->add_option("--placement", o->placement, "Start of new points: gaps (best candidate) or random (the paper)")
      ->check(CLI::IsMember({"gaps", "random"}))
      ->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Output point file (x y level; '-': standard output)")->required();
  add_engine_options(cmd, o->engine);
  cmd->callback([o] {
    if (o->input.empty() && o->count == 0) throw CLI::RequiredError("--input or --count");
    run_progressive(*o);
  });
}

}  // namespace bluetile::cli
