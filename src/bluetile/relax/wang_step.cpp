// One Jacobi step of the Wang-tile loop (see wang_step.h for the strategies).
#include "bluetile/relax/wang_step.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <map>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/core/torus.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile {
namespace {

// A first reach, before any cell was measured in a block: twice the radius of the point's cell
// in its tile alone (the tile as a torus), with this much room for the larger cells some
// configurations give near edges; cells that need more are regrown.
constexpr double kFirstReachMargin = 1.25;
// No reach below this many hexagonal spacings: a coincident site reports no cell radius.
constexpr double kMinReachSpacings = 0.5;
// The next step's reach: twice the largest cell radius seen, with this much room for cells
// that grow as their neighbours move, plus twice the point's own move.
constexpr double kReachMargin = 1.1;
// A cell that was not provably complete is measured again with at least this much more reach.
constexpr double kRegrowFactor = 1.5;
// Beyond this reach (tile units) a cell would see past the 3x3 block: the tile has too few
// points for configurations of its neighbours to decide its cells.
constexpr double kMaxReach = 2.0;

struct PointSums {
  Point displacement{};
  double weight = 0.0;
  double energy = 0.0;
  double radius = 0.0;
  bool failed = false;
  double needed_reach = 0.0;

  void add(Point d, const Cell& cell, double w) {
    displacement += w * d;
    weight += w;
    energy += w * cell.second_moment;
    radius = std::max(radius, cell.radius);
  }
};

// A group's scenes: one per configuration, from `first_scene` on.
struct GroupScenes {
  CropGroup group;
  const std::vector<BlockConfiguration>* configurations = nullptr;
  std::size_t first_scene = 0;
};

WangStep empty_step(const WangPoints& points) {
  WangStep step;
  const std::size_t tiles = points.tiles.size(), moving = points.moving_count();
  step.displacement.assign(tiles, std::vector<Point>(moving, Point{}));
  step.cell_radius.assign(tiles, std::vector<double>(moving, 0.0));
  step.weight.assign(tiles, std::vector<double>(moving, 0.0));
  return step;
}

void check_cell(const Cell& cell, const CentroidEngine& engine) {
  if (cell.status != CellStatus::coincident && !(cell.radius > 0.0)) {
    throw Error("engine " + std::string(engine.name()) +
                " does not report cell radii, which cropped scenes need; use the exact engine or the instances strategy");
  }
}

// exact and rounds: cropped block scenes, regrown until every cell is provably complete.
void measure_cropped(CentroidEngine& engine, BlockConfigurations& configurations, const WangPoints& points,
                     const WangStepOptions& options, WangReach& reach, WangStep& step) {
  const std::size_t tile_count = points.tiles.size(), moving = points.moving_count();
  // Rounds: the same whole blocks for every measurement of a tile in this step.
  std::vector<std::vector<BlockConfiguration>> rounds(tile_count);
  if (options.strategy == WangStrategy::rounds) {
    for (std::size_t t = 0; t < tile_count; ++t) {
      Rng rng(derive_seed(options.seed, t));
      rounds[t] = configurations.covering_blocks(static_cast<int>(t), rng);
    }
  }
  // Points still to measure: (tile, moving index) with their reach.
  std::vector<std::vector<double>> pending_reach = reach.reach;
  std::vector<std::vector<bool>> pending(tile_count, std::vector<bool>(moving, true));
  for (bool any = moving > 0; any;) {
    // Group each tile's pending points by the positions they see.
    std::vector<GroupScenes> groups;
    std::size_t scene_count = 0;
    for (std::size_t t = 0; t < tile_count; ++t) {
      const std::vector<Point>& tile = points.tiles[t];
      std::map<PositionMask, std::vector<std::uint32_t>> by_mask;
      for (std::size_t m = 0; m < moving; ++m) {
        if (!pending[t][m]) continue;
        const std::uint32_t k = static_cast<std::uint32_t>(points.moving_begin + m);
        PositionMask mask = options.strategy == WangStrategy::rounds ? kWholeBlock
                                                                     : visible_positions(tile[k], pending_reach[t][m]);
        by_mask[mask].push_back(k);
      }
      for (auto& [mask, wanted] : by_mask) {
        std::vector<double> r;
        for (std::uint32_t k : wanted) r.push_back(pending_reach[t][k - points.moving_begin]);
        GroupScenes g;
        g.group = make_crop_group(static_cast<int>(t), mask, std::move(wanted), tile, r);
        g.configurations = options.strategy == WangStrategy::rounds
                               ? &rounds[t]
                               : &configurations.projections(static_cast<int>(t), mask);
        g.first_scene = scene_count;
        scene_count += g.configurations->size();
        groups.push_back(std::move(g));
      }
    }

    std::vector<Scene> scenes(scene_count);
    parallel_for(groups.size(), 1, [&](std::size_t begin, std::size_t end) {
      for (std::size_t g = begin; g < end; ++g) {
        const GroupScenes& group = groups[g];
        CropSceneMaker maker(group.group, points.tiles);
        for (std::size_t c = 0; c < group.configurations->size(); ++c)
          scenes[group.first_scene + c] = maker.make((*group.configurations)[c]);
      }
    });
    std::vector<SceneCells> cells(scene_count);
    engine.compute(scenes, cells);
    step.scenes += scene_count;

    // Sums per point, in a fixed order; a point with any incomplete cell is measured again.
    any = false;
    for (const GroupScenes& group : groups) {
      const std::size_t t = static_cast<std::size_t>(group.group.centre);
      std::vector<PointSums> sums(group.group.wanted.size());
      for (std::size_t c = 0; c < group.configurations->size(); ++c) {
        const Scene& scene = scenes[group.first_scene + c];
        const SceneCells& measured = cells[group.first_scene + c];
        const double w = (*group.configurations)[c].weight;
        step.cells += measured.cells.size();
        step.coincident += measured.coincident_count;
        step.fallbacks += measured.fallback_count;
        for (std::size_t i = 0; i < sums.size(); ++i) {
          const Cell& cell = measured.cells[i];
          check_cell(cell, engine);
          if (!crop_cell_complete(group.group, i, cell)) {
            sums[i].failed = true;
            sums[i].needed_reach = std::max(sums[i].needed_reach, 2.0 * cell.radius * kReachMargin);
            continue;
          }
          sums[i].add(lloyd_displacement(scene, scene.sites[i], cell), cell, w);
        }
      }
      for (std::size_t i = 0; i < sums.size(); ++i) {
        const std::size_t m = group.group.wanted[i] - points.moving_begin;
        if (sums[i].failed) {
          double r = std::max(sums[i].needed_reach, kRegrowFactor * pending_reach[t][m]);
          if (r > kMaxReach) {
            throw Error("a cell of tile " + std::to_string(t) + " reaches beyond its 3x3 block of tiles (radius " +
                        fixed_text(0.5 * r, 6) + " tiles): too few points per tile");
          }
          pending_reach[t][m] = r;
          ++step.regrown;
          any = true;
          continue;
        }
        pending[t][m] = false;
        step.displacement[t][m] = sums[i].displacement / sums[i].weight;
        step.weight[t][m] = sums[i].weight;
        step.cell_radius[t][m] = sums[i].radius;
        step.energy += sums[i].energy / sums[i].weight;
      }
    }
  }
  const double min_reach = kMinReachSpacings * hexagonal_spacing(static_cast<double>(points.tiles[0].size()));
  for (std::size_t t = 0; t < tile_count; ++t) {
    for (std::size_t m = 0; m < moving; ++m) {
      const Point d = step.displacement[t][m];
      reach.reach[t][m] =
          std::max(min_reach, 2.0 * step.cell_radius[t][m] * kReachMargin + 2.0 * std::sqrt(d.x * d.x + d.y * d.y));
    }
  }
}

// instances: one periodic scene of a random period x period torus tiling.
void measure_instances(CentroidEngine& engine, const BlockConfigurations& configurations, const WangPoints& points,
                       const WangStepOptions& options, WangStep& step) {
  const TileRules& rules = configurations.rules();
  const std::int64_t period = options.period;
  const std::size_t moving = points.moving_count(), total = points.tiles[0].size();
  Scene scene;
  scene.domain.size = {static_cast<double>(period), static_cast<double>(period)};
  std::vector<int> cell_tile(static_cast<std::size_t>(period * period));
  for (std::int64_t j = 0; j < period; ++j)
    for (std::int64_t i = 0; i < period; ++i)
      cell_tile[static_cast<std::size_t>(j * period + i)] = rules.tile_at_periodic(i, j, options.seed, period);
  // Moving points of every cell first (the wanted range), then the fixed ones.
  scene.sites.reserve(cell_tile.size() * total);
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t begin = pass == 0 ? points.moving_begin : 0, end = pass == 0 ? total : points.moving_begin;
    for (std::size_t c = 0; c < cell_tile.size(); ++c) {
      const Point shift{static_cast<double>(static_cast<std::int64_t>(c) % period),
                        static_cast<double>(static_cast<std::int64_t>(c) / period)};
      const std::vector<Point>& tile = points.tiles[static_cast<std::size_t>(cell_tile[c])];
      for (std::size_t k = begin; k < end; ++k) scene.sites.push_back(tile[k] + shift);
    }
  }
  scene.wanted_begin = 0;
  scene.wanted_end = cell_tile.size() * moving;
  SceneCells cells = engine.compute(scene);
  step.scenes = 1;
  step.cells = cells.cells.size();
  step.coincident = cells.coincident_count;
  step.fallbacks = cells.fallback_count;

  std::vector<std::vector<PointSums>> sums(points.tiles.size(), std::vector<PointSums>(moving));
  for (std::size_t c = 0; c < cell_tile.size(); ++c) {
    const std::size_t t = static_cast<std::size_t>(cell_tile[c]);
    for (std::size_t m = 0; m < moving; ++m) {
      const std::size_t i = c * moving + m;
      sums[t][m].add(lloyd_displacement(scene, scene.sites[i], cells.cells[i]), cells.cells[i], 1.0);
    }
  }
  for (std::size_t t = 0; t < points.tiles.size(); ++t) {
    for (std::size_t m = 0; m < moving; ++m) {
      const PointSums& s = sums[t][m];
      if (s.weight == 0.0) continue;  // the tile did not occur in this tiling: it stays
      step.displacement[t][m] = s.displacement / s.weight;
      step.weight[t][m] = s.weight;
      step.cell_radius[t][m] = s.radius;
      step.energy += s.energy / s.weight;
    }
  }
}

}  // namespace

std::string_view wang_strategy_name(WangStrategy strategy) {
  switch (strategy) {
    case WangStrategy::exact: return "exact";
    case WangStrategy::instances: return "instances";
    case WangStrategy::rounds: return "rounds";
  }
  return "unknown";
}

WangStep measure_wang_step(CentroidEngine& engine, BlockConfigurations& configurations, const WangPoints& points,
                           const WangStepOptions& options, WangReach& reach) {
  assert(points.tiles.size() == static_cast<std::size_t>(configurations.rules().tile_count()));
  WangStep step = empty_step(points);
  if (points.moving_count() == 0) return step;
  if (options.strategy == WangStrategy::instances) {
    measure_instances(engine, configurations, points, options, step);
    return step;
  }
  const std::size_t moving = points.moving_count();
  if (reach.reach.size() != points.tiles.size() || reach.reach[0].size() != moving) {
    const double min_reach = kMinReachSpacings * hexagonal_spacing(static_cast<double>(points.tiles[0].size()));
    std::vector<Scene> alone;
    for (const std::vector<Point>& tile : points.tiles) {
      Scene scene = make_scene(tile);
      scene.wanted_begin = points.moving_begin;
      alone.push_back(std::move(scene));
    }
    std::vector<SceneCells> cells(alone.size());
    engine.compute(alone, cells);
    reach.reach.assign(points.tiles.size(), std::vector<double>(moving, 0.0));
    for (std::size_t t = 0; t < alone.size(); ++t) {
      for (std::size_t m = 0; m < moving; ++m) {
        check_cell(cells[t].cells[m], engine);
        reach.reach[t][m] = std::max(min_reach, 2.0 * kFirstReachMargin * cells[t].cells[m].radius);
      }
    }
  }
  measure_cropped(engine, configurations, points, options, reach, step);
  return step;
}

}  // namespace bluetile
