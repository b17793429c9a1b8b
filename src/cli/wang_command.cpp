// bluetile wang: Wang-tile sample sets by Lloyd relaxation with multiple edge constraints (the
// paper, section 3).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>

#include "bluetile/core/error.h"
#include "bluetile/core/memory_budget.h"
#include "bluetile/core/output_file.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/wang_lattice.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/tiling/tile_set.h"
#include "bluetile/tiling/tile_set_file.h"
#include "cli/commands.h"
#include "cli/engine_options.h"
#include "cli/file_options.h"
#include "cli/numeric_options.h"
#include "cli/option_rules.h"
#include "cli/output_names.h"
#include "cli/progress.h"
#include "cli/seam_report.h"

namespace bluetile::cli {
namespace {

struct WangCommandOptions {
  // wang8: the best seams and lattice coherence of the three at equal points per tile; the
  // 16-tile sets only win on diffuse anisotropy (docs/RESULTS.md, Wang tiles).
  std::string kind = "wang8";
  long long points = 52;
  int iterations = WangLevelOptions{}.iterations;
  int warm = 10;
  int levels = 1;
  double ratio = 2.0;
  // auto, which is exact but for corner81: the strategies' quality cannot be told apart over 4
  // seeds, and the noise-free mean costs at most 0.15 s more than the cheapest at 13 and 52
  // points per tile (RESULTS.md).
  std::string strategy = "auto";
  int period = 16;
  double margin = 0.0;
  WangRefinement refine;  // the lattice and seam spacing steps, the library's defaults
  std::string rank_order = "fill";
  double void_sigma = WangLevelOptions{}.void_sigma;
  std::uint64_t seed = 1;
  std::string output;
  bool check = false;
  bool verbose = false;
  EngineOptions engine;
};

// Points per tile past the library's limit (wang_relax.h), counted over the levels.
constexpr long long kMaxPointsPerTile = static_cast<long long>(kMaxWangPoints);

std::string fixed(double v, int decimals) {
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

// The points of a tile once every level is added (each brings the count to round(R x count), as
// relax_wang_tiles does), refused up front past kMaxPointsPerTile: --levels 32 or --ratio 1e7
// otherwise ran on for hours towards an out-of-memory kill.
void check_points_per_tile(const WangCommandOptions& o, int tiles) {
  double total = static_cast<double>(o.points);
  for (int l = 1; l < o.levels; ++l) total = std::max(total, std::round(o.ratio * total));
  if (total <= static_cast<double>(kMaxPointsPerTile)) return;
  char text[300];
  std::snprintf(text, sizeof text,
                "--points %lld --levels %d --ratio %.17g makes about %.0f points per tile (%.0f in the %d tiles), more "
                "than the limit of %lld per tile: use fewer levels or a smaller ratio",
                o.points, o.levels, o.ratio, total, total * tiles, tiles, kMaxPointsPerTile);
  throw Error(text);
}

// What --output writes.
constexpr OutputFormat kTileSetFormats[] = {OutputFormat::tile_set};

// The library's options from the command's (the callbacks are set by run_wang).
WangOptions wang_options(const WangCommandOptions& o) {
  WangOptions w;
  w.kind = *parse_tile_set_kind(o.kind);
  w.points = static_cast<std::size_t>(o.points);
  w.levels = o.levels;
  w.ratio = o.ratio;
  w.seed = o.seed;
  w.level.iterations = o.iterations;
  w.level.warm_iterations = o.warm;
  w.level.strategy = parse_wang_strategy(o.strategy, w.kind);
  w.level.period = o.period;
  w.level.edge_margin = o.margin;
  w.level.refine = o.refine;
  w.level.rank_order = parse_wang_rank_order(o.rank_order);
  w.level.void_sigma = o.void_sigma;
  return w;
}

// The settings this run would not use (wang_setting_used), refused by name (option_rules.h): what
// makes a run use each, and this run's settings it depends on.
void refuse_unused_wang_options(const CLI::App& command, const WangCommandOptions& o, const WangOptions& w) {
  const std::string levels = "--levels " + std::to_string(o.levels);
  const std::string order = "--rank-order " + o.rank_order;
  const std::string seams = "--seam-steps " + std::to_string(o.refine.seam_iterations);
  std::string strategy = "--strategy " + o.strategy;
  if (o.strategy == "auto") strategy += ", " + std::string(wang_strategy_name(w.level.strategy)) + " for " + o.kind;
  const std::string filled_steps = "--rank-order fill, --levels 2 or more and --filled-lattice-steps above 0";
  const std::string filled_run =
      order + ", " + levels + ", --filled-lattice-steps " + std::to_string(o.refine.filled_lattice_steps);
  struct Rule {
    std::string_view setting;
    std::string needs, this_run;
  };
  const Rule rules[] = {
      {"ratio", "--levels 2 or more", levels},
      {"period", "--strategy instances", strategy},
      {"void_sigma", "--rank-order voids", order},
      {"lattice_step", "--lattice-steps or --lattice-steps-per-iteration above 0",
       "--lattice-steps " + std::to_string(o.refine.lattice_iterations) + ", --lattice-steps-per-iteration " +
           std::to_string(o.refine.lattice_steps_per_iteration)},
      {"seam_spacing", "--seam-steps above 0", seams},
      {"level_seam_spacing",
       "--seam-steps above 0, --levels 2 or more and --rank-order farthest or voids, whose later levels are relaxed, "
       "not filled",
       seams + ", " + levels + ", " + order},
      {"filled_lattice_steps", "--rank-order fill and --levels 2 or more", order + ", " + levels},
      {"filled_lattice_spacing", filled_steps, filled_run},
      {"filled_lattice_up_to", filled_steps, filled_run},
  };
  for (const Rule& rule : rules) {
    std::string option = "--" + std::string(rule.setting);
    std::replace(option.begin(), option.end(), '_', '-');
    refuse_unless_used(command, option, wang_setting_used(w, rule.setting), rule.needs, rule.this_run);
  }
}

void run_wang(const WangCommandOptions& o, WangOptions w) {
  output_format("--output", o.output, kTileSetFormats);
  OutputSet outputs;  // checked before the work, written at the end
  OutputFile& output = outputs.add(o.output, {.allow_stdout = true});
  if (o.levels > 1 && !(o.ratio > 1.0)) throw Error("--ratio must be above 1, got " + std::to_string(o.ratio));
  check_points_per_tile(o, TileRules(w.kind).tile_count());
  if (w.level.rank_order == RankOrder::fill && o.levels > 1) {
    // The filled levels' grids (the last is the largest) and their time, which grows as N log N in
    // the points per tile; the time of their lattice steps, which grows as the square.
    const std::size_t tiles = static_cast<std::size_t>(TileRules(w.kind).tile_count());
    std::size_t count = static_cast<std::size_t>(o.points);
    FillCost fill;
    double phases = 0.0;
    for (int l = 1; l < o.levels; ++l) {
      const std::size_t add = level_size(count, 0, o.ratio);
      const FillCost level = band_fill_cost(count, add, tiles, w.level.fill);
      fill.bytes = std::max(fill.bytes, level.bytes);
      fill.places_visited += level.places_visited;
      if (count + add <= o.refine.filled_lattice_up_to)
        phases += filled_lattice_phases(tiles, count, count + add, o.refine.filled_lattice_steps);
      count += add;
    }
    check_memory(fill.bytes, "filling " + std::to_string(count) + " points per tile");
    const double seconds = fill.places_visited * kFillSecondsPerPlace;
    if (seconds >= 60.0)
      std::fprintf(stderr, "bluetile: note: the fill order visits about %.2g grid places, about %s on one thread (it grows "
                   "as N log N in the points per tile)\n", fill.places_visited, duration_words(seconds).c_str());
    const double step_seconds = phases * kFilledLatticeSecondsPerPhase;
    if (step_seconds >= 60.0)
      std::fprintf(stderr, "bluetile: note: the filled levels' lattice steps compute about %.2g phases, about %s on one "
                   "thread (a step grows as the square of the points per tile; --filled-lattice-up-to limits them)\n",
                   phases, duration_words(step_seconds).c_str());
  }

  auto engine = make_engine(o.engine);
  Progress progress("wang", static_cast<long long>(o.levels) * (o.warm + o.iterations));
  w.level.on_iteration = [&](const WangIteration& it) {
    long long done = static_cast<long long>(it.level) * (o.warm + o.iterations) + (it.warm ? 0 : o.warm) + it.iteration;
    if (o.verbose) {
      progress.finish();
      std::fprintf(stderr, "level %d %s %d: max displacement %.3e, mean %.3e, energy %.9e, %zu scenes, %zu cells, %zu regrown\n",
                   it.level, it.warm ? "warm iteration" : "iteration", it.iteration, it.max_displacement,
                   it.mean_displacement, it.energy, it.scenes, it.cells, it.regrown);
    }
    progress.update(done, "level " + std::to_string(it.level) + (it.warm ? " warm start" : "") + ", max displacement " +
                              fixed(it.max_displacement, 6));
  };
  // Filled levels come after level 0, one callback round per point of every tile.
  int fill_level = 1;
  w.level.fill.on_round = [&](std::size_t done, std::size_t total) {
    const long long per_level = o.warm + o.iterations;
    progress.update(fill_level * per_level + static_cast<long long>(done) * per_level / static_cast<long long>(total),
                    "level " + std::to_string(fill_level) + ": fill");
    if (done == total) ++fill_level;
  };
  // A filled level's lattice steps follow its last round: the bar stays at the level's end.
  w.level.on_filled_lattice_step = [&](int done, int total) {
    progress.update(static_cast<long long>(fill_level) * (o.warm + o.iterations),
                    "level " + std::to_string(fill_level - 1) + ": lattice steps " + std::to_string(done) + "/" +
                        std::to_string(total));
  };
  TileSet set = relax_wang_tiles(*engine, w);
  progress.finish();
  // Each setting that only some runs use is named where this one used it, so that the line runs
  // again as written.
  const auto used = [&w](std::string_view setting) { return wang_setting_used(w, setting); };
  std::ostringstream command;
  command << "bluetile wang --set " << o.kind << " --points " << o.points << " --iterations " << o.iterations
          << " --warm " << o.warm << " --levels " << o.levels;
  if (used("ratio")) command << " --ratio " << o.ratio;
  command << " --strategy " << wang_strategy_name(w.level.strategy);
  if (used("period")) command << " --period " << o.period;
  if (o.margin > 0.0) command << " --margin " << o.margin;
  const WangRefinement& r = o.refine;
  command << " --lattice-steps " << r.lattice_iterations << " --lattice-steps-per-iteration "
          << r.lattice_steps_per_iteration;
  if (used("lattice_step")) command << " --lattice-step " << r.lattice_step;
  command << " --seam-steps " << r.seam_iterations;
  if (used("seam_spacing")) command << " --seam-spacing " << r.seam_spacing;
  if (used("level_seam_spacing")) command << " --level-seam-spacing " << r.later_seam_spacing;
  command << " --rank-order " << o.rank_order;
  if (used("void_sigma")) command << " --void-sigma " << o.void_sigma;
  if (used("filled_lattice_steps")) command << " --filled-lattice-steps " << r.filled_lattice_steps;
  if (used("filled_lattice_spacing")) command << " --filled-lattice-spacing " << r.filled_lattice_spacing;
  if (used("filled_lattice_up_to")) command << " --filled-lattice-up-to " << r.filled_lattice_up_to;
  // The raster settings too: they shape the points (the header was "--engine raster" alone).
  command << " --seed " << o.seed << " " << engine_arguments(*engine, o.engine);
  set.header = {"made by: " + command.str()};
  validate_tile_set(set);
  output.write(format_tile_set(set));
  outputs.publish();
  // Standard output holds the tile set alone when it is the output; the check goes to stderr then.
  if (o.check) std::fprintf(output.is_stdout() ? stderr : stdout, "%s", seam_report(check_seams(set)).c_str());
}

}  // namespace

void add_wang_command(CLI::App& app) {
  auto o = std::make_shared<WangCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "wang", "Wang-tile sample sets: tiles relaxed together by Lloyd's method under multiple edge constraints");
  cmd->add_option("--set", o->kind,
                  "Tile set: wang8 (the paper's), wang16 (every edge combination), corner16 (corner colours) or "
                  "corner81 (3 corner colours: 81 tiles, about a tenth of wang8's tile-lattice peaks)")
      ->check(CLI::IsMember({"wang8", "wang16", "corner16", "corner81"}))
      ->capture_default_str();
  add_integer_option(cmd, "-n,--points", o->points, 1LL, kMaxPointsPerTile, "Points per tile in level 0");
  add_integer_option(cmd, "-k,--iterations", o->iterations, 0, kMaxWangIterations, "Constrained Lloyd iterations per level");
  add_integer_option(cmd, "--warm", o->warm, 0, kMaxWangIterations,
                     "Warm start: periodic iterations of each tile alone before the constrained ones");
  add_integer_option(cmd, "-l,--levels", o->levels, 1, kMaxWangLevels, "Levels (hierarchical sets that tile)");
  // Above 10^8 a second level would pass the point limit at once (as progressive --ratio).
  add_real_option(cmd, "--ratio", o->ratio, {1.0, kMaxWangRatio, true, false},
                  "Each further level brings a tile's count to round(R x count)");
  cmd->add_option("--strategy", o->strategy,
                  "Neighbour configurations: exact (every admissible 3x3 block), instances (random torus tilings), "
                  "rounds (one block per fitting neighbour) or auto (exact; instances for corner81)")
      ->check(CLI::IsMember({"auto", "exact", "instances", "rounds"}))
      ->capture_default_str();
  add_integer_option(cmd, "--period", o->period, kMinWangPeriod, kMaxWangPeriod, "instances: the torus tiling is M x M tiles");
  add_real_option(cmd, "--margin", o->margin, {0.0, kMaxEdgeMargin}, "Keep points this far inside their tile (tile units)");
  add_integer_option(cmd, "--lattice-steps", o->refine.lattice_iterations, 0, kMaxLatticeSteps,
                     "Lattice decorrelation after each level's iterations: gradient steps that lower the tile-lattice "
                     "peaks C_LF (and, in level 0, C_mid) (0: none)");
  add_integer_option(cmd, "--lattice-steps-per-iteration", o->refine.lattice_steps_per_iteration, 0,
                     kMaxLatticeStepsPerIteration,
                     "Lattice steps after each constrained iteration of the second half, which Lloyd's next iteration "
                     "repairs (0: none)");
  add_real_option(cmd, "--lattice-step", o->refine.lattice_step, {kMinLatticeStep, kMaxLatticeStep},
                  "Largest move of one lattice step, in hexagonal spacings");
  add_integer_option(cmd, "--seam-steps", o->refine.seam_iterations, 0, kMaxSeamSteps,
                     "Seam spacing after each level's iterations: repulsion steps for points closer than the spacing "
                     "to a point they can meet in a tiling (0: none)");
  add_real_option(cmd, "--seam-spacing", o->refine.seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
                  "Seam spacing of level 0, in hexagonal spacings of the tile's points");
  add_real_option(cmd, "--level-seam-spacing", o->refine.later_seam_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
                  "Seam spacing of levels 1 and up, in hexagonal spacings of the tile's points");
  cmd->add_option("--rank-order", o->rank_order,
                  "Progressive order inside each level: farthest (greedy farthest point) or voids (tiled "
                  "void-and-cluster: lower low-frequency power and tile-lattice coherence between level boundaries, "
                  "closer nearest pairs) or fill (levels after the first not relaxed but filled point by point, each "
                  "in the deepest void of the band-limited density of the points before it through the tiling: every "
                  "prefix about as even as every other)")
      ->check(CLI::IsMember({"farthest", "voids", "fill"}))
      ->capture_default_str();
  add_real_option(cmd, "--void-sigma", o->void_sigma, {kMinVoidSigma, kMaxVoidSigma}, "voids: kernel width in hexagonal spacings of the prefix");
  add_integer_option(cmd, "--filled-lattice-steps", o->refine.filled_lattice_steps, 0, kMaxLatticeSteps,
                     "fill: lattice steps on each filled level's points against the tile-lattice peaks of its middle "
                     "and its boundary, each move kept only where the points keep the filled spacing (0: none)");
  add_real_option(cmd, "--filled-lattice-spacing", o->refine.filled_lattice_spacing, {kMinSeamSpacing, kMaxSeamSpacing},
                  "fill: the spacing those moves keep, in hexagonal spacings of the prefix each pair completes");
  add_integer_option(cmd, "--filled-lattice-up-to", o->refine.filled_lattice_up_to, std::size_t{1}, kMaxWangPoints,
                     "fill: lattice steps only on filled levels of at most this many points per tile (a step costs "
                     "as the square of the count)");
  add_seed_option(cmd, o->seed);
  add_output_option(cmd, "-o,--output", o->output, {.formats = kTileSetFormats, .standard_output = true},
                    "Output tile-set file (.tiles or .txt; - for stdout)")
      ->required();
  cmd->add_flag("--check", o->check, "Print the seam check of the result");
  cmd->add_flag("-v,--verbose", o->verbose, "Print displacement, energy and scene counts of every iteration on stderr");
  // The exact engine by default: a step is thousands of small cropped scenes, which it measures
  // in 0.3 s for 8 x 52 points x 25 iterations against 80 s for the raster engine on lavapipe
  // (docs/RESULTS.md, Wang tiles).
  o->engine.engine = "exact";
  add_engine_options(cmd, o->engine);
  cmd->callback([o, cmd] {
    refuse_unused_raster_options(*cmd, o->engine, cmd->count("--engine") ? "" : ", the default for wang");
    WangOptions w = wang_options(*o);
    refuse_unused_wang_options(*cmd, *o, w);
    run_wang(*o, std::move(w));
  });
}

}  // namespace bluetile::cli
