// bluetile progressive: hierarchical point sets, new levels relaxed around fixed earlier ones.
#include <cstdio>
#include <limits>
#include <memory>

#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/point_output.h"
#include "cli/progress.h"
#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile::cli {
namespace {

struct ProgressiveOptions {
  std::string input;
  long long count = 0;
  long long add = 0;
  double ratio = 0.0;
  int levels = 0;
  int iterations = kDefaultIterations;
  double tolerance = 0.0;
  std::uint64_t seed = 1;
  std::string placement = "gaps";
  std::string rank_order = "voids";
  long long sets = 1;
  PointOutputOptions output;
  EngineOptions engine;
};

void run_progressive(const ProgressiveOptions& o, const CLI::App& command) {
  if (!o.input.empty() && o.add == 0 && o.ratio == 0.0)
    throw Error("--input needs --add M or --ratio R: how many points to add");
  OutputSet outputs;
  add_declared_inputs(outputs, command);
  // The bases: the input's sets (each gets its own levels), or K empty ones.
  std::vector<PointSet> sets(static_cast<std::size_t>(o.sets));
  if (!o.input.empty()) {
    sets = read_point_table(o.input);
    if (sets.empty()) throw Error(input_name(o.input) + ": no points");
    if (declared_domain(sets, o.input) == Boundary::bounded)
      throw Error(input_name(o.input) + ": declares '# domain bounded'; progressive builds its levels on the torus");
  }
  PointOutput output(outputs, o.output, sets.size());  // names and formats checked before any work

  HierarchyOptions options;
  options.count = static_cast<std::size_t>(o.count);
  options.add = static_cast<std::size_t>(o.add);
  options.ratio = o.ratio;
  options.levels = o.levels;
  options.iterations = o.iterations;
  options.tolerance = o.tolerance;
  options.placement = o.placement == "random" ? Placement::random : Placement::gaps;
  options.rank_order = parse_rank_order(o.rank_order);
  // Every set's levels and sizes, and the memory of them all, checked before any work.
  int target_levels = 0;
  double total = 0.0;
  for (const PointSet& set : sets) {
    const int base_levels = count_levels(set);
    target_levels = o.levels ? o.levels : std::max(base_levels + 1, o.input.empty() ? 4 : 1);
    if (target_levels <= base_levels) {
      throw Error("--levels " + std::to_string(target_levels) + ": " + (o.input.empty() ? "" : input_name(o.input) + " ") +
                  "already has " + counted(base_levels, "level") + "; --levels is the total to reach (" +
                  std::to_string(base_levels + 1) + " or more)");
    }
    std::vector<std::size_t> sizes;
    try {
      sizes = hierarchy_level_sizes(set, options);
    } catch (const Error& e) {
      // The library names the ratio as its field ("ratio 1.0000001 adds no point ..."): here the option.
      std::string message = e.what();
      if (message.starts_with("ratio ")) message.insert(0, "--");
      throw Error(o.input.empty() ? message : input_name(o.input) + ": " + message);
    }
    total += static_cast<double>(set.points.size());
    for (std::size_t add : sizes) total += static_cast<double>(add);
  }
  // The fill order starts from no points and relaxes nothing: no engine time to speak of, and a
  // header that names no start, engine, iterations or placement.
  const bool filled = options.rank_order == ProgressiveOrder::fill;
  FillCost fill;
  if (filled) {
    // The fill order's grid (one set at a time per thread) and its time, which grows as N log N.
    const std::size_t largest = static_cast<std::size_t>(total / static_cast<double>(sets.size()));
    fill = band_fill_cost(0, largest, 1, options.fill);
    fill.places_visited *= static_cast<double>(sets.size());
    fill.bytes *= static_cast<double>(std::min<std::size_t>(sets.size(), thread_count()));
  }
  check_memory(progressive_memory_bytes(total, filled ? "exact" : o.engine.engine) + fill.bytes, std::to_string(static_cast<long long>(total)) + " points in " +
                                                        std::to_string(target_levels) + " levels");
  const double fill_seconds = fill.places_visited * kFillSecondsPerPlace;
  if (fill_seconds >= 60.0)
    std::fprintf(stderr, "bluetile: note: the fill order visits about %.2g grid places, about %s on one thread (it grows "
                 "as N log N in the points of a set)\n", fill.places_visited, duration_words(fill_seconds).c_str());

  // The fill order runs no engine: it opens no Vulkan device (none need exist), and its sets are
  // built in parallel as the exact engine's are.
  std::unique_ptr<CentroidEngine> engine = filled ? std::make_unique<ExactEngine>() : make_engine(o.engine);
  if (!filled) note_faster_engine(*engine, total * o.iterations);
  if (sets.size() > 1 && (filled || o.engine.engine == "exact")) {
    // Set k of a batch is the set --seed S+k gives alone (wrapping past 2^64 - 1); the exact
    // engine is cheap to make, so the sets are built in parallel, one engine per worker.
    options.seed = o.seed;
    Progress progress("sets", static_cast<long long>(sets.size()));
    sets = add_levels([] { return std::make_unique<ExactEngine>(); }, std::move(sets), options,
                      [&progress](std::size_t done) { progress.update(static_cast<long long>(done)); });
  } else {
    // One raster engine serves every set in turn: it keeps its Vulkan device and pipelines.
    for (std::size_t k = 0; k < sets.size(); ++k) {
      options.seed = o.seed + k;
      std::unique_ptr<Progress> progress;
      int progress_level = -1;
      options.on_iteration = [&](int level, const LloydIteration& it) {
        if (level != progress_level) {
          progress_level = level;
          progress = std::make_unique<Progress>(
              (sets.size() > 1 ? "set " + std::to_string(k) + ", " : "") + "level " + std::to_string(level) + ": relax",
              o.iterations);
        }
        progress->update(it.iteration);
      };
      options.fill.on_round = [&](std::size_t done, std::size_t rounds) {
        if (!progress) progress = std::make_unique<Progress>((sets.size() > 1 ? "set " + std::to_string(k) + ", " : "") + "fill",
                                                             static_cast<long long>(rounds));
        progress->update(static_cast<long long>(done));
      };
      sets[k] = add_levels(*engine, std::move(sets[k]), options);
    }
  }
  note_exact_hand_over(*engine);
  std::string how = !o.input.empty() ? "on " + input_name(o.input) + ", seed " + std::to_string(o.seed)
                    : filled         ? "from no points, seed " + std::to_string(o.seed)
                                     : "from " + counted(o.count, "random point") + ", seed " + std::to_string(o.seed);
  if (sets.size() > 1) how += " + set index";
  const std::string what = sets.size() == 1 ? std::to_string(sets[0].points.size()) + " points"
                                            : std::to_string(sets.size()) + " sets of " +
                                                  std::to_string(sets[0].points.size()) + " points";
  const std::string method = filled ? (o.input.empty() ? "every point filled, no relaxation" : "every new point filled, no relaxation")
                                    : (o.tolerance > 0.0 ? "at most " : "") + counted(o.iterations, "iteration") +
                                          " per level" +
                                          (o.tolerance > 0.0 ? " (tolerance " + shortest_text(o.tolerance) + ")" : "") +
                                          ", engine " + engine_text(*engine, o.engine) + ", placement " + o.placement;
  const std::vector<std::string> header = {
      "bluetile progressive: " + what + " in " + std::to_string(target_levels) + (target_levels == 1 ? " level " : " levels ") +
          how + ", " + method + ", rank order " + rank_order_name(options.rank_order),
      "columns: x y level"};
  output.write(sets, header);
  outputs.publish();
}

}  // namespace

void add_progressive_command(CLI::App& app) {
  auto o = std::make_shared<ProgressiveOptions>();
  CLI::App* cmd = app.add_subcommand(
      "progressive", "Hierarchical point sets: add levels of points relaxed around the fixed earlier levels");
  auto* input = add_input_option(cmd, "-i,--input", o->input, InputKind::points,
                                 "Base points, kept bit for bit: text (each '#'-separated set gets its own levels), .npy, "
                                 ".bpt or .csv ('-': standard input)");
  auto* count = add_integer_option(cmd, "-n,--count", o->count, 1LL, kMaxCount,
                                   "Build from scratch: level 0 has N points (relaxed random points; with --rank-order "
                                   "voids the first N of a stage of at least 64, see there)");
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
  add_seed_option(cmd, o->seed, "Seed of the random placement");
  cmd->add_option("--placement", o->placement, "Start of new points: gaps (best candidate) or random (the paper)")
      ->check(CLI::IsMember({"gaps", "random"}))
      ->capture_default_str();
  cmd->add_option("--rank-order", o->rank_order,
                  "Row order within the levels: voids (levels relaxed in stages of at least 64 points, each stage's "
                  "points ranked by voids: every prefix well spread, not only the level boundaries) or placement "
                  "(each level relaxed alone, its points as placed: the paper's order) or fill (no relaxation: every "
                  "point placed in the deepest void of the band-limited density of the points before it, so every "
                  "prefix is about as even as every other; it takes no iteration, placement or engine options)")
      ->check(CLI::IsMember({"placement", "voids", "fill"}))
      ->capture_default_str();
  add_integer_option(cmd, "--sets", o->sets, 1LL, 10000000LL,
                     "Build K independent hierarchies; set k is the one --seed S+k gives alone")
      ->needs(count);
  add_point_output_options(cmd, o->output, "Output points (x y level; '-': standard output)");
  add_engine_options(cmd, o->engine);
  cmd->callback([o, cmd] {
    if (o->input.empty() && o->count == 0) throw CLI::RequiredError("--input or --count");
    if (o->rank_order == "fill") {
      // The fill order relaxes nothing and runs no engine: these would change nothing.
      for (const char* name : {"--iterations", "--tolerance", "--placement", "--engine", "--resolution", "--coverage",
                               "--cone", "--device", "--pixel-work"}) {
        if (cmd->count(name) == 0) continue;
        throw Error(std::string(name) + " " + cmd->get_option(name)->as<std::string>() +
                    ": --rank-order fill relaxes nothing and runs no engine; this is for the orders that relax "
                    "(voids, placement)");
      }
    } else {
      refuse_unused_raster_options(*cmd, o->engine, "");
    }
    run_progressive(*o, *cmd);
  });
}

}  // namespace bluetile::cli
