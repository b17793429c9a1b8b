// Wang-tile sample sets (see wang_relax.h; the paper, section 3).
#include "bluetile/relax/wang_relax.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/wang_blocks.h"
#include "bluetile/relax/wang_lattice.h"
#include "bluetile/relax/wang_ranks.h"
#include "bluetile/relax/wang_seams.h"
#include "bluetile/relax/wang_step.h"

namespace bluetile {
namespace {

int next_level(const TileSet& set) {
  int level = 0;
  for (const Tile& tile : set.tiles)
    for (int l : tile.levels) level = std::max(level, l + 1);
  return level;
}

// Periodic relaxation of every tile alone (its square as a torus), the earlier levels fixed.
void warm_start(CentroidEngine& engine, WangPoints& points, int level, const WangLevelOptions& options) {
  std::vector<Scene> scenes;
  for (const std::vector<Point>& tile : points.tiles) {
    Scene scene = make_scene(tile);
    scene.wanted_begin = points.moving_begin;
    scenes.push_back(std::move(scene));
  }
  LloydOptions lloyd;
  lloyd.iterations = options.warm_iterations;
  lloyd.on_iteration = [&](const LloydIteration& it) {
    if (!options.on_iteration) return;
    WangIteration w;
    w.level = level;
    w.iteration = it.iteration;
    w.warm = true;
    w.max_displacement = it.max_displacement;
    w.mean_displacement = it.mean_displacement;
    w.energy = it.energy;
    w.scenes = scenes.size();
    w.cells = scenes.size() * points.moving_count();
    options.on_iteration(w);
  };
  relax_lloyd(engine, scenes, lloyd);
  for (std::size_t t = 0; t < scenes.size(); ++t) points.tiles[t] = std::move(scenes[t].sites);
}

// Where each tile's points count near tile t for the fill order: its own, and at each of the 8
// neighbour positions every tile that can sit there, weighted by the share of admissible 3x3
// blocks around t that put it there.
std::vector<std::vector<FillSource>> fill_sources(BlockConfigurations& configurations, std::size_t tile_count) {
  std::vector<std::vector<FillSource>> sources(tile_count);
  for (std::size_t t = 0; t < tile_count; ++t) {
    sources[t].push_back({t, Point{0.0, 0.0}, 1.0});
    for (int p = 0; p < kBlockPositions; ++p) {
      if (p == kBlockCentre) continue;
      const auto& seen = configurations.projections(static_cast<int>(t), kCentreOnly | static_cast<PositionMask>(1u << p));
      double blocks = 0.0;
      for (const BlockConfiguration& c : seen) blocks += c.weight;
      const Point shift{static_cast<double>(block_dx(p)), static_cast<double>(block_dy(p))};
      for (const BlockConfiguration& c : seen)
        sources[t].push_back({static_cast<std::size_t>(c.tiles[static_cast<std::size_t>(p)]), shift, c.weight / blocks});
    }
  }
  return sources;
}

// The fill order's level: new points placed by band-limited void filling, then given the filled
// levels' lattice steps (up to the level size asked), appended in rank order.
void fill_wang_level(BlockConfigurations& configurations, TileSet& set, int level, const WangLevelOptions& options) {
  std::vector<std::vector<Point>> tiles;
  for (const Tile& tile : set.tiles) tiles.push_back(tile.points);
  FillOptions fill = options.fill;
  fill.seed = options.seed;
  const std::vector<std::vector<FillSource>> sources = fill_sources(configurations, tiles.size());
  const std::vector<std::vector<Point>> added = band_fill(tiles, sources, options.add, fill);
  const std::size_t begin = tiles[0].size();
  for (std::size_t t = 0; t < tiles.size(); ++t) tiles[t].insert(tiles[t].end(), added[t].begin(), added[t].end());
  const WangRefinement& refine = options.refine;
  if (tiles[0].size() <= refine.filled_lattice_up_to)
    decorrelate_filled_level(tiles, begin, sources,
                             {.iterations = refine.filled_lattice_steps,
                              .spacing = refine.filled_lattice_spacing,
                              .on_step = options.on_filled_lattice_step});
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    Tile& tile = set.tiles[t];
    for (std::size_t i = begin; i < tiles[t].size(); ++i) {
      tile.ranks.push_back(static_cast<std::uint32_t>(tile.points.size()));
      tile.points.push_back(tiles[t][i]);
      tile.levels.push_back(level);
    }
  }
}

}  // namespace

TileSet empty_tile_set(TileSetKind kind) {
  TileRules rules(kind);
  TileSet set;
  set.kind = kind;
  for (int t = 0; t < rules.tile_count(); ++t) {
    Tile tile;
    tile.colours = rules.colours(t);
    set.tiles.push_back(tile);
  }
  return set;
}

void add_wang_level(CentroidEngine& engine, TileSet& set, const WangLevelOptions& options) {
  if (options.add == 0) throw Error("a level must add at least one point per tile");
  if (options.edge_margin < 0.0 || options.edge_margin >= 0.5)
    throw Error("edge margin " + shortest_text(options.edge_margin) + " outside [0, 0.5)");
  const TileRules rules(set.kind);
  if (set.tiles.size() != static_cast<std::size_t>(rules.tile_count()))
    throw Error("a " + std::string(tile_set_kind_name(set.kind)) + " set has " + std::to_string(rules.tile_count()) +
                " tiles, not " + std::to_string(set.tiles.size()));
  const std::size_t existing = set.tiles[0].points.size();
  for (const Tile& tile : set.tiles)
    if (tile.points.size() != existing) throw Error("every tile must hold the same number of points to add a level");
  BlockConfigurations configurations(rules);
  const int level = next_level(set);
  if (options.rank_order == RankOrder::fill && existing > 0) {
    fill_wang_level(configurations, set, level, options);
    return;
  }

  WangPoints points;
  points.moving_begin = existing;
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    std::vector<Point> tile = set.tiles[t].points;
    std::vector<Point> added = place_new_points(tile, options.add, Placement::gaps, derive_seed(options.seed, t));
    for (Point& p : added) p = inside_tile(p, options.edge_margin);
    tile.insert(tile.end(), added.begin(), added.end());
    points.tiles.push_back(std::move(tile));
  }
  if (options.warm_iterations > 0) warm_start(engine, points, level, options);

  WangReach reach;
  const std::size_t moving = points.moving_count();
  LatticeDecorrelationOptions lattice;
  lattice.step = options.refine.lattice_step;
  lattice.mid_band = level == 0;
  lattice.edge_margin = options.edge_margin;
  for (int it = 1; it <= options.iterations; ++it) {
    WangStepOptions step_options;
    step_options.strategy = options.strategy;
    step_options.period = options.period;
    step_options.seed = derive_seed(options.seed, static_cast<std::uint64_t>(set.tiles.size() + static_cast<std::size_t>(it)));
    WangStep step = measure_wang_step(engine, configurations, points, step_options, reach);
    WangIteration log;
    log.level = level;
    log.iteration = it;
    log.energy = step.energy;
    log.scenes = step.scenes;
    log.cells = step.cells;
    log.regrown = step.regrown;
    double moved_sum = 0.0;
    for (std::size_t t = 0; t < points.tiles.size(); ++t) {
      for (std::size_t m = 0; m < moving; ++m) {
        Point& p = points.tiles[t][existing + m];
        const Point target = p + step.displacement[t][m];
        const Point moved = inside_tile(target, options.edge_margin);
        const Point d = moved - p;
        const double distance = std::sqrt(d.x * d.x + d.y * d.y);
        log.max_displacement = std::max(log.max_displacement, distance);
        moved_sum += distance;
        p = moved;
      }
    }
    log.mean_displacement = moved_sum / static_cast<double>(moving * points.tiles.size());
    // Interleaved lattice steps in the second half: Lloyd's next iteration repairs what they
    // cost in low frequencies.
    if (2 * it > options.iterations && options.refine.lattice_steps_per_iteration > 0) {
      lattice.iterations = options.refine.lattice_steps_per_iteration;
      decorrelate_lattice(points, lattice);
    }
    if (options.on_iteration) options.on_iteration(log);
  }

  if (options.refine.lattice_iterations > 0) {
    lattice.iterations = options.refine.lattice_iterations;
    decorrelate_lattice(points, lattice);
  }
  if (options.refine.seam_iterations > 0) {
    SeamSpacingOptions spacing;
    spacing.iterations = options.refine.seam_iterations;
    const double relative = level == 0 ? options.refine.seam_spacing : options.refine.later_seam_spacing;
    spacing.spacing = relative * hexagonal_spacing(static_cast<double>(points.tiles[0].size()));
    spacing.edge_margin = options.edge_margin;
    space_seams(rules, points, spacing);
  }

  // Level 0 of the fill order is relaxed and ranked by farthest point: ranking a relaxed level's
  // points by the fill's rule did no better than voids (docs/RESULTS.md, "Every prefix").
  const std::vector<std::vector<std::uint32_t>> order =
      options.rank_order == RankOrder::voids ? rank_level_by_voids(configurations, points.tiles, existing, options.void_sigma)
                                             : rank_level(configurations, points.tiles, existing);
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    Tile& tile = set.tiles[t];
    for (std::uint32_t k : order[t]) {
      tile.ranks.push_back(static_cast<std::uint32_t>(tile.points.size()));
      tile.points.push_back(points.tiles[t][k]);
      tile.levels.push_back(level);
    }
  }
}

namespace {

template <class Value>
Value parse_named(const char* field, const std::string& name, std::initializer_list<std::pair<const char*, Value>> names) {
  std::vector<std::string> texts;
  for (const auto& [text, value] : names) {
    if (name == text) return value;
    texts.emplace_back(text);
  }
  check_name_field(field, name, texts);  // throws: the name is none of them
  return names.begin()->second;
}

}  // namespace

bool wang_setting_used(const WangOptions& options, std::string_view setting) {
  const WangLevelOptions& l = options.level;
  const WangRefinement& r = l.refine;
  const bool filled = l.rank_order == RankOrder::fill && options.levels > 1;
  if (setting == "ratio") return options.levels > 1;
  if (setting == "period") return l.strategy == WangStrategy::instances;
  if (setting == "void_sigma") return l.rank_order == RankOrder::voids;
  if (setting == "lattice_step") return r.lattice_iterations > 0 || r.lattice_steps_per_iteration > 0;
  if (setting == "seam_spacing") return r.seam_iterations > 0;
  if (setting == "level_seam_spacing")
    return r.seam_iterations > 0 && options.levels > 1 && l.rank_order != RankOrder::fill;
  if (setting == "filled_lattice_steps") return filled;
  if (setting == "filled_lattice_spacing" || setting == "filled_lattice_up_to") return filled && r.filled_lattice_steps > 0;
  throw Error("internal: no conditional Wang setting is called '" + std::string(setting) + "'");
}

void validate(const WangOptions& options) {
  const WangLevelOptions& l = options.level;
  check_whole_field("points", static_cast<long long>(options.points), 1, static_cast<long long>(kMaxWangPoints));
  check_whole_field("iterations", l.iterations, 0, kMaxWangIterations);
  check_whole_field("warm", l.warm_iterations, 0, kMaxWangIterations);
  check_whole_field("levels", options.levels, 1, kMaxWangLevels);
  check_whole_field("period", l.period, kMinWangPeriod, kMaxWangPeriod);
  if (!(options.ratio > 1.0 && options.ratio <= kMaxWangRatio))
    throw Error("ratio: expected above 1 to " + shortest_text(kMaxWangRatio) + ", got " + shortest_text(options.ratio));
  check_real_field("margin", l.edge_margin, 0.0, kMaxEdgeMargin, " tile units");
  check_whole_field("lattice_steps", l.refine.lattice_iterations, 0, kMaxLatticeSteps);
  check_whole_field("lattice_steps_per_iteration", l.refine.lattice_steps_per_iteration, 0, kMaxLatticeStepsPerIteration);
  check_real_field("lattice_step", l.refine.lattice_step, kMinLatticeStep, kMaxLatticeStep, " hexagonal spacings");
  check_whole_field("seam_steps", l.refine.seam_iterations, 0, kMaxSeamSteps);
  check_real_field("seam_spacing", l.refine.seam_spacing, kMinSeamSpacing, kMaxSeamSpacing, " hexagonal spacings");
  check_real_field("level_seam_spacing", l.refine.later_seam_spacing, kMinSeamSpacing, kMaxSeamSpacing, " hexagonal spacings");
  check_whole_field("filled_lattice_steps", l.refine.filled_lattice_steps, 0, kMaxLatticeSteps);
  check_real_field("filled_lattice_spacing", l.refine.filled_lattice_spacing, kMinSeamSpacing, kMaxSeamSpacing,
                   " hexagonal spacings");
  check_whole_field("filled_lattice_up_to", static_cast<long long>(l.refine.filled_lattice_up_to), 1,
                    static_cast<long long>(kMaxWangPoints));
  check_real_field("void_sigma", l.void_sigma, kMinVoidSigma, kMaxVoidSigma, " hexagonal spacings");
}

WangStrategy parse_wang_strategy(const std::string& name, TileSetKind kind) {
  if (name == "auto") return kind == TileSetKind::corner81 ? WangStrategy::instances : WangStrategy::exact;
  return parse_named<WangStrategy>(
      "strategy", name,
      {{"auto", WangStrategy::exact}, {"exact", WangStrategy::exact}, {"instances", WangStrategy::instances},
       {"rounds", WangStrategy::rounds}});
}

RankOrder parse_wang_rank_order(const std::string& name) {
  return parse_named<RankOrder>("rank_order", name,
                                {{"farthest", RankOrder::farthest}, {"voids", RankOrder::voids}, {"fill", RankOrder::fill}});
}

const char* wang_rank_order_name(RankOrder order) {
  switch (order) {
    case RankOrder::farthest: return "farthest";
    case RankOrder::voids: return "voids";
    case RankOrder::fill: return "fill";
  }
  return "farthest";
}

TileSet relax_wang_tiles(CentroidEngine& engine, const WangOptions& options) {
  validate(options);
  if (options.points == 0) throw Error("a tile needs at least one point");
  if (options.levels < 1) throw Error("a set needs at least one level");
  if (options.levels > 1 && !(options.ratio > 1.0))
    throw Error("ratio must be above 1, got " + shortest_text(options.ratio));
  TileSet set = empty_tile_set(options.kind);
  std::size_t total = 0;
  for (int l = 0; l < options.levels; ++l) {
    WangLevelOptions level = options.level;
    level.add = l == 0 ? options.points : level_size(total, 0, options.ratio);
    if (level.add == 0)
      throw Error("ratio " + shortest_text(options.ratio) + " adds no point to tiles of " + std::to_string(total) +
                  " (level " + std::to_string(l) + ")");
    level.seed = derive_seed(options.seed, static_cast<std::uint64_t>(l));
    add_wang_level(engine, set, level);
    total += level.add;
  }
  return set;
}

}  // namespace bluetile
