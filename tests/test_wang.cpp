// Wang-tile sample sets (the paper, section 3): neighbour configurations against brute-force
// enumeration, the exact strategy against brute force over every admissible 3x3 block, the other
// strategies against it, levels and ranks, the seam check on hand-built sets, quality over seeds,
// determinism, and the commands.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "bluetile/analysis/tiling_metrics.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/wang_blocks.h"
#include "bluetile/relax/wang_crop.h"
#include "bluetile/relax/wang_ranks.h"
#include "bluetile/relax/wang_relax.h"
#include "bluetile/relax/wang_step.h"
#include "bluetile/tiling/seam_check.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "test_raster_support.h"
#include "test_support.h"

namespace bluetile {
namespace {

using Tiles = std::array<std::int16_t, kBlockPositions>;

// Every admissible 3x3 block around `centre`, by the lead's enumeration.
std::vector<Tiles> blocks_around(const TileRules& rules, int centre) {
  std::vector<Tiles> blocks;
  rules.for_each_block(3, 3, [&](std::span<const int> b) {
    if (b[kBlockCentre] != centre) return;
    Tiles t;
    for (int p = 0; p < kBlockPositions; ++p) t[static_cast<std::size_t>(p)] = static_cast<std::int16_t>(b[static_cast<std::size_t>(p)]);
    blocks.push_back(t);
  });
  return blocks;
}

Tiles restrict_to(Tiles t, PositionMask mask) {
  for (int p = 0; p < kBlockPositions; ++p)
    if (!(mask & (PositionMask{1} << p)) && p != kBlockCentre) t[static_cast<std::size_t>(p)] = -1;
  return t;
}

TEST(WangBlocks, ProjectionsCountTheBlocksThatAgreeWithThem) {
  for (TileSetKind kind : {TileSetKind::wang8, TileSetKind::corner16}) {
    TileRules rules(kind);
    BlockConfigurations configurations(rules);
    for (int centre : {0, 5}) {
      std::vector<Tiles> blocks = blocks_around(rules, centre);
      EXPECT_EQ(configurations.block_count(centre), static_cast<double>(blocks.size()));
      EXPECT_EQ(blocks.size(), 4096u);  // wang8: 12 free cell bits; corner16: 12 free lattice points
      // Every mask for wang8, a spread of them for corner16 (the cost is the brute force).
      for (unsigned mask = 0; mask < (1u << 9); mask += kind == TileSetKind::wang8 ? 1 : 37) {
        std::map<Tiles, double> expected;
        for (const Tiles& b : blocks) expected[restrict_to(b, static_cast<PositionMask>(mask))] += 1.0;
        std::map<Tiles, double> got;
        double total = 0.0;
        for (const BlockConfiguration& c : configurations.projections(centre, static_cast<PositionMask>(mask))) {
          EXPECT_TRUE(got.emplace(c.tiles, c.weight).second) << "duplicate projection";
          total += c.weight;
        }
        ASSERT_EQ(got, expected) << tile_set_kind_name(kind) << " centre " << centre << " mask " << mask;
        EXPECT_EQ(total, static_cast<double>(blocks.size()));
      }
    }
  }
}

TEST(WangBlocks, Wang16CountsMatchIndependentEdgeColours) {
  // 24 edges of a 3x3 block, 4 fixed by the centre: 2^20 blocks; a known edge neighbour fixes 3
  // more edges (8 projections), an edge plus its corner and the next edge 3 + 2 + 3 (256).
  TileRules rules(TileSetKind::wang16);
  BlockConfigurations configurations(rules);
  EXPECT_EQ(configurations.block_count(9), 1048576.0);
  const PositionMask north = PositionMask{1} << 7, north_east = north | (1u << 8) | (1u << 5);
  const auto& n = configurations.projections(9, north);
  ASSERT_EQ(n.size(), 8u);
  for (const auto& c : n) EXPECT_EQ(c.weight, 131072.0);
  const auto& ne = configurations.projections(9, north_east);
  ASSERT_EQ(ne.size(), 256u);
  for (const auto& c : ne) EXPECT_EQ(c.weight, 4096.0);
}

TEST(WangBlocks, Corner81CountsAreColouringsOfTheBlocksCornerLattice) {
  // A 3x3 block of corner81 tiles is a colouring of its 4x4 lattice of corners, 3 colours each,
  // the centre's 4 fixed: 3^12 blocks, made here from the colourings (not by TileRules'
  // enumeration), then every partial block's count taken by scanning them.
  TileRules rules(TileSetKind::corner81);
  BlockConfigurations configurations(rules);
  Rng rng(11);
  std::array<std::int16_t, 81> tile_of{};  // by 27 NW + 9 NE + 3 SE + SW colour digits
  for (int d = 0; d < 81; ++d)
    tile_of[static_cast<std::size_t>(d)] = static_cast<std::int16_t>(rules.tile_with(
        {static_cast<std::uint8_t>(d / 27), static_cast<std::uint8_t>(d / 9 % 3), static_cast<std::uint8_t>(d / 3 % 3),
         static_cast<std::uint8_t>(d % 3)}));
  for (int centre : {0, 41, 80}) {
    const TileColours& c = rules.colours(centre);  // NW, NE, SE, SW
    std::vector<Tiles> blocks;
    for (int code = 0; code < 531441; ++code) {
      std::array<std::array<std::uint8_t, 4>, 4> lattice{};  // [x][y], y = 0 at the bottom
      int rest = code;
      for (int x = 0; x < 4; ++x)
        for (int y = 0; y < 4; ++y) {
          if ((x == 1 || x == 2) && (y == 1 || y == 2)) continue;
          lattice[static_cast<std::size_t>(x)][static_cast<std::size_t>(y)] = static_cast<std::uint8_t>(rest % 3);
          rest /= 3;
        }
      lattice[1][2] = c[0], lattice[2][2] = c[1], lattice[2][1] = c[2], lattice[1][1] = c[3];
      Tiles b;
      for (std::size_t by = 0; by < 3; ++by)
        for (std::size_t bx = 0; bx < 3; ++bx)
          b[by * 3 + bx] = tile_of[27u * lattice[bx][by + 1] + 9u * lattice[bx + 1][by + 1] + 3u * lattice[bx + 1][by] +
                                   lattice[bx][by]];
      blocks.push_back(b);
    }
    EXPECT_EQ(configurations.block_count(centre), 531441.0);
    auto agreeing = [&](const Tiles& partial) {
      double n = 0.0;
      for (const Tiles& b : blocks) {
        bool agrees = true;
        for (std::size_t p = 0; p < b.size() && agrees; ++p) agrees = partial[p] < 0 || partial[p] == b[p];
        n += agrees;
      }
      return n;
    };
    for (int trial = 0; trial < 24; ++trial) {
      // A random block restricted to a random mask; every third one with a random tile at a
      // known position, which mostly no block agrees with.
      Tiles partial = restrict_to(blocks[rng.below(blocks.size())], static_cast<PositionMask>(rng.below(512)));
      if (trial % 3 == 2) {
        std::size_t p = rng.below(kBlockPositions - 1);
        p += p >= kBlockCentre;  // any position but the centre
        partial[p] = static_cast<std::int16_t>(rng.below(81));
      }
      EXPECT_EQ(configurations.completions(partial), agreeing(partial)) << "centre " << centre << " trial " << trial;
    }
    // The north-east quadrant's projections, as ProjectionsCountTheBlocksThatAgreeWithThem does
    // for the smaller sets.
    const PositionMask quadrant = (1u << 5) | (1u << 7) | (1u << 8);
    std::map<Tiles, double> expected;
    for (const Tiles& b : blocks) expected[restrict_to(b, quadrant)] += 1.0;
    std::map<Tiles, double> got;
    for (const BlockConfiguration& p : configurations.projections(centre, quadrant)) got.emplace(p.tiles, p.weight);
    EXPECT_EQ(got, expected) << "centre " << centre;
    EXPECT_EQ(got.size(), 243u);  // the 5 lattice points of E, N and NE not on the centre: 3^5
  }
}

TEST(WangBlocks, RoundsCoverEveryFittingNeighbourWithAdmissibleBlocks) {
  for (TileSetKind kind : tile_set_kinds()) {
    TileRules rules(kind);
    BlockConfigurations configurations(rules);
    Rng rng(3);
    for (int centre = 0; centre < rules.tile_count(); ++centre) {
      std::vector<BlockConfiguration> blocks = configurations.covering_blocks(centre, rng);
      std::size_t most = 0;
      for (int p : {1, 3, 5, 7}) most = std::max(most, configurations.candidates(centre, p).size());
      EXPECT_EQ(blocks.size(), most) << tile_set_kind_name(kind) << " centre " << centre;
      for (int p : {1, 3, 5, 7}) {
        std::set<int> seen;
        for (const auto& b : blocks) seen.insert(b.tiles[static_cast<std::size_t>(p)]);
        std::set<int> all(configurations.candidates(centre, p).begin(), configurations.candidates(centre, p).end());
        EXPECT_EQ(seen, all) << tile_set_kind_name(kind) << " centre " << centre << " position " << p;
      }
      for (const auto& b : blocks) EXPECT_EQ(configurations.completions(b.tiles), 1.0);  // whole and admissible
    }
  }
}

TEST(WangCrop, VisiblePositionsAreTheSquaresWithinReach) {
  EXPECT_EQ(visible_positions({0.5, 0.5}, 0.4), kCentreOnly);
  EXPECT_EQ(visible_positions({0.5, 0.9}, 0.2), kCentreOnly | (1u << 7));                       // N
  EXPECT_EQ(visible_positions({0.9, 0.9}, 0.2), kCentreOnly | (1u << 5) | (1u << 7) | (1u << 8));  // E, N, NE
  // The NE square is sqrt(0.02) = 0.141 away: a reach of 0.12 sees the edges but not the corner.
  EXPECT_EQ(visible_positions({0.9, 0.9}, 0.12), kCentreOnly | (1u << 5) | (1u << 7));
  EXPECT_EQ(visible_positions({0.5, 0.5}, 0.6), kWholeBlock & ~((1u << 0) | (1u << 2) | (1u << 6) | (1u << 8)));
}

// A tile set of `kind` with `n` points per tile, started and warm-started but not constrained.
WangPoints started_points(TileSetKind kind, std::size_t n, std::uint64_t seed, int warm = 3) {
  ExactEngine engine;
  TileSet set = empty_tile_set(kind);
  WangLevelOptions level;
  level.add = n;
  level.iterations = 0;
  level.warm_iterations = warm;
  level.refine.lattice_iterations = 0;  // tiles relaxed alone, nothing after
  level.refine.seam_iterations = 0;
  level.seed = seed;
  add_wang_level(engine, set, level);
  WangPoints points;
  for (const Tile& t : set.tiles) points.tiles.push_back(t.points);
  return points;
}

// The mean displacement of every moving point over every admissible 3x3 block, one whole scene
// per block: the 3x3 block in the middle of a 9 x 9 periodic domain (copies three tiles away).
std::vector<std::vector<Point>> brute_force(const TileRules& rules, const WangPoints& points) {
  const std::size_t moving = points.moving_count(), size = points.tiles[0].size();
  std::vector<std::vector<Point>> sum(points.tiles.size(), std::vector<Point>(moving, Point{}));
  std::vector<double> count(points.tiles.size(), 0.0);
  ExactEngine engine;
  for (int centre = 0; centre < rules.tile_count(); ++centre) {
    std::vector<Tiles> blocks = blocks_around(rules, centre);
    std::vector<Scene> scenes;
    for (const Tiles& b : blocks) {
      Scene scene;
      scene.domain.size = {9.0, 9.0};
      auto add = [&](int p, std::size_t k) {
        const auto& tile = points.tiles[static_cast<std::size_t>(b[static_cast<std::size_t>(p)])];
        scene.sites.push_back(tile[k] + Point{4.0 + block_dx(p), 4.0 + block_dy(p)});
      };
      for (std::size_t k = points.moving_begin; k < size; ++k) add(kBlockCentre, k);
      scene.wanted_end = moving;
      for (std::size_t k = 0; k < points.moving_begin; ++k) add(kBlockCentre, k);
      for (int p = 0; p < kBlockPositions; ++p)
        if (p != kBlockCentre)
          for (std::size_t k = 0; k < size; ++k) add(p, k);
      scenes.push_back(std::move(scene));
    }
    std::vector<SceneCells> cells(scenes.size());
    engine.compute(scenes, cells);
    for (std::size_t s = 0; s < scenes.size(); ++s) {
      for (std::size_t m = 0; m < moving; ++m)
        sum[static_cast<std::size_t>(centre)][m] +=
            lloyd_displacement(scenes[s], scenes[s].sites[m], cells[s].cells[m]);
      count[static_cast<std::size_t>(centre)] += 1.0;
    }
  }
  for (std::size_t t = 0; t < sum.size(); ++t)
    for (Point& d : sum[t]) d /= count[t];
  return sum;
}

// A crop scene by its definition (wang_crop.h): the wanted points, the centre's other points in
// the box, then each known position's points in the box, in position order, relative to the
// corner of the domain, which is the box grown by the pad.
std::vector<Point> crop_sites_by_definition(const CropGroup& group, const Tiles& tiles, const TilePoints& points) {
  auto in_box = [&](Point p) { return p.x >= group.low.x && p.x <= group.high.x && p.y >= group.low.y && p.y <= group.high.y; };
  const Point corner = group.low - Point{group.pad, group.pad};
  const std::vector<Point>& centre = points[static_cast<std::size_t>(group.centre)];
  std::vector<Point> sites;
  for (std::uint32_t k : group.wanted) sites.push_back(centre[k] - corner);
  for (std::uint32_t k = 0; k < centre.size(); ++k)
    if (std::find(group.wanted.begin(), group.wanted.end(), k) == group.wanted.end() && in_box(centre[k]))
      sites.push_back(centre[k] - corner);
  for (int p = 0; p < kBlockPositions; ++p) {
    if (p == kBlockCentre || !(group.mask & (PositionMask{1} << p))) continue;
    for (Point q : points[static_cast<std::size_t>(tiles[static_cast<std::size_t>(p)])]) {
      const Point b = q + Point{static_cast<double>(block_dx(p)), static_cast<double>(block_dy(p))};
      if (in_box(b)) sites.push_back(b - corner);
    }
  }
  return sites;
}

TEST(WangCrop, SceneMakerGivesEachConfigurationsSitesInOrder) {
  const WangPoints points = started_points(TileSetKind::wang8, 24, 12);
  const TileRules rules(TileSetKind::wang8);
  BlockConfigurations configurations(rules);
  Rng rng(40);
  std::size_t scenes = 0, sites = 0;
  for (int centre = 0; centre < rules.tile_count(); ++centre) {
    const std::vector<Point>& tile = points.tiles[static_cast<std::size_t>(centre)];
    for (double reach : {0.15, 0.3, 0.6}) {
      // Points near a corner, near an edge and anywhere, so that masks of 1 to 8 neighbours occur.
      std::vector<std::uint32_t> wanted;
      for (std::uint32_t k = 0; k < tile.size(); ++k)
        if (rng.uniform() < 0.3) wanted.push_back(k);
      if (wanted.empty()) wanted.push_back(0);
      PositionMask mask = kCentreOnly;
      for (std::uint32_t k : wanted) mask |= visible_positions(tile[k], reach);
      const std::vector<double> reaches(wanted.size(), reach);
      const CropGroup group = make_crop_group(centre, mask, wanted, tile, reaches);
      const std::vector<BlockConfiguration>& blocks = configurations.projections(centre, group.mask);
      ASSERT_FALSE(blocks.empty());
      // One maker for every configuration, taken forwards and backwards (its parts are cut on
      // first use), and the one-scene function.
      CropSceneMaker forwards(group, points.tiles), backwards(group, points.tiles);
      for (std::size_t c = 0; c < blocks.size(); ++c) {
        const std::vector<Point> expected = crop_sites_by_definition(group, blocks[c].tiles, points.tiles);
        const Scene made = forwards.make(blocks[c]);
        const Scene reverse = backwards.make(blocks[blocks.size() - 1 - c]);
        const std::vector<Point> reverse_expected =
            crop_sites_by_definition(group, blocks[blocks.size() - 1 - c].tiles, points.tiles);
        EXPECT_EQ(made.sites, expected) << "tile " << centre << " configuration " << c;
        EXPECT_EQ(reverse.sites, reverse_expected) << "tile " << centre << " configuration " << c;
        EXPECT_EQ(make_crop_scene(group, blocks[c], points.tiles).sites, expected);
        EXPECT_EQ(made.wanted_begin, 0u);
        EXPECT_EQ(made.wanted_end, wanted.size());
        const Point size = group.high - group.low + Point{2.0 * group.pad, 2.0 * group.pad};
        EXPECT_EQ(made.domain.size, size);
        ++scenes;
        sites += made.sites.size();
      }
    }
  }
  EXPECT_GT(scenes, 100u);
  EXPECT_GT(sites, 20 * scenes);
}

double max_difference(const std::vector<std::vector<Point>>& a, const std::vector<std::vector<Point>>& b) {
  double worst = 0.0;
  for (std::size_t t = 0; t < a.size(); ++t)
    for (std::size_t m = 0; m < a[t].size(); ++m) {
      Point d = a[t][m] - b[t][m];
      worst = std::max(worst, std::sqrt(d.x * d.x + d.y * d.y));
    }
  return worst;
}

TEST(WangStep, ExactStrategyEqualsBruteForceOverEveryBlock) {
  struct Case {
    TileSetKind kind;
    std::size_t n, fixed;
  };
  for (Case c : {Case{TileSetKind::wang8, 16, 0}, Case{TileSetKind::corner16, 12, 0}, Case{TileSetKind::wang8, 20, 10}}) {
    WangPoints points = started_points(c.kind, c.n, 11);
    points.moving_begin = c.fixed;  // the first points act as a fixed earlier level
    TileRules rules(c.kind);
    BlockConfigurations configurations(rules);
    ExactEngine engine;
    WangReach reach;
    WangStepOptions options;
    options.strategy = WangStrategy::exact;
    WangStep step = measure_wang_step(engine, configurations, points, options, reach);
    std::vector<std::vector<Point>> expected = brute_force(rules, points);
    const double difference = max_difference(step.displacement, expected);
    EXPECT_LT(difference, 1e-12) << tile_set_kind_name(c.kind) << " n " << c.n;
    const std::size_t blocks = static_cast<std::size_t>(rules.tile_count()) * 4096;
    for (std::size_t t = 0; t < step.weight.size(); ++t)
      for (double w : step.weight[t]) EXPECT_EQ(w, 4096.0);
    // A second step starts from the reaches the first one measured and regrows little.
    WangStep again = measure_wang_step(engine, configurations, points, options, reach);
    EXPECT_LT(max_difference(again.displacement, expected), 1e-12);
    EXPECT_LE(again.regrown, step.regrown);
    // Fewer scenes than blocks (32768 for wang8, 65536 for corner16), far fewer once the reaches
    // are known.
    EXPECT_LT(step.scenes, blocks) << step.scenes;
    EXPECT_LT(again.scenes, blocks / 4) << again.scenes;
  }
}

TEST(WangStep, RoundsAndInstancesApproachTheExactMean) {
  WangPoints points = started_points(TileSetKind::wang8, 13, 5, 10);
  TileRules rules(TileSetKind::wang8);
  BlockConfigurations configurations(rules);
  ExactEngine engine;
  WangReach reach;
  WangStepOptions options;
  WangStep exact = measure_wang_step(engine, configurations, points, options, reach);
  double size = 0.0;
  for (const auto& tile : exact.displacement)
    for (Point d : tile) size = std::max(size, std::sqrt(d.x * d.x + d.y * d.y));
  options.strategy = WangStrategy::rounds;
  WangStep rounds = measure_wang_step(engine, configurations, points, options, reach);
  options.strategy = WangStrategy::instances;
  options.period = 48;  // each tile about 288 times
  WangStep instances = measure_wang_step(engine, configurations, points, options, reach);
  // Means over 4 blocks and over ~288 random ones against the mean over all 4096; measured 0.26
  // and 0.085 of the largest exact displacement (seed 5).
  EXPECT_LT(max_difference(rounds.displacement, exact.displacement), 0.5 * size);
  EXPECT_LT(max_difference(instances.displacement, exact.displacement), 0.15 * size);
  for (const auto& w : instances.weight) EXPECT_GT(w[0], 200.0);
  for (const auto& w : rounds.weight) EXPECT_EQ(w[0], 4.0);
}

// The Wang loop's cropped scenes (context sites, rectangles, thousands per batch) through the raster
// engine, with the per-pixel work on each path (on the device path the host path must give the
// same bits: test::PathEngine).
class WangStepRaster : public test::RasterPaths {};
INSTANTIATE_TEST_SUITE_P(PixelWork, WangStepRaster, ::testing::ValuesIn(test::kPixelPaths), test::pixel_path_name);

TEST_P(WangStepRaster, MeasuresTheExactEnginesStep) {
  // The device path at 104 points per tile (2760 scenes, still thousands): at 52 it took 99 s
  // on lavapipe with its host twin, at 104 8 s (lavapipe's split costs several host splits).
  WangPoints points = started_points(TileSetKind::wang8, on_device() ? 104 : 52, 7, 3);
  TileRules rules(TileSetKind::wang8);
  BlockConfigurations configurations(rules);
  WangStepOptions options;
  ExactEngine exact_engine;
  WangReach exact_reach, raster_reach;
  WangStep exact = measure_wang_step(exact_engine, configurations, points, options, exact_reach);
  // Area coverage with quad cones: centroid errors of 2e-16 at most against the exact engine
  // (docs/RASTER.md), so the mean displacements agree to rounding: measured 6.3e-16 (seed 7).
  // 52 points per tile: at 13 the step's one submission needs a 226 MiB buffer, over lavapipe's
  // 128 MiB limit (the raster engine does not split a batch to fit).
  RasterOptions raster_options;
  raster_options.adapt_radius = false;
  test::PathEngine raster_engine(raster_options, work());
  WangStep raster = measure_wang_step(raster_engine, configurations, points, options, raster_reach);
  EXPECT_LT(max_difference(raster.displacement, exact.displacement), 1e-12);
  EXPECT_GT(raster.scenes, 1000u);
  if (on_device()) {
    EXPECT_GT(raster_engine.stats().boundary_pixels, 0u);  // the device split them
  }
}

TEST(WangOptions, SettingsOnlySomeRunsUseChangeTheSetExactlyWhereUsed) {
  // wang_setting_used is what the front ends refuse by and what the tool's made-by line names:
  // held against the sets themselves. Where a run uses a setting, another value changes its
  // points; where it does not, another value gives the same bits.
  ExactEngine engine;
  const auto points_of = [&engine](const WangOptions& o) {
    std::vector<Point> all;
    for (const Tile& tile : relax_wang_tiles(engine, o).tiles) all.insert(all.end(), tile.points.begin(), tile.points.end());
    return all;
  };
  WangOptions small;
  small.points = 8;
  small.level.iterations = 2;
  small.level.warm_iterations = 0;
  small.level.refine.filled_lattice_steps = 5;
  small.seed = 3;
  using Change = std::function<void(WangOptions&)>;
  const auto with = [&small](const Change& change) {
    WangOptions o = small;
    change(o);
    return o;
  };
  const auto two_levels = [](WangOptions& o) { o.levels = 2; };
  struct Case {
    std::string_view setting;
    Change unused, used, other_value;
  };
  const std::vector<Case> cases = {
      {"ratio", [](WangOptions&) {}, two_levels, [](WangOptions& o) { o.ratio = 2.5; }},
      {"period", [](WangOptions&) {}, [](WangOptions& o) { o.level.strategy = WangStrategy::instances; },
       [](WangOptions& o) { o.level.period = 4; }},
      {"void_sigma", [](WangOptions&) {}, [](WangOptions& o) { o.level.rank_order = RankOrder::voids; },
       [](WangOptions& o) { o.level.void_sigma = 0.1; }},
      {"lattice_step",
       [](WangOptions& o) { o.level.refine.lattice_iterations = o.level.refine.lattice_steps_per_iteration = 0; },
       [](WangOptions&) {}, [](WangOptions& o) { o.level.refine.lattice_step = 0.05; }},
      {"seam_spacing", [](WangOptions& o) { o.level.refine.seam_iterations = 0; }, [](WangOptions&) {},
       [](WangOptions& o) { o.level.refine.seam_spacing = 1.5; }},
      {"level_seam_spacing", two_levels,
       [](WangOptions& o) {
         o.levels = 2;
         o.level.rank_order = RankOrder::farthest;
       },
       [](WangOptions& o) { o.level.refine.later_seam_spacing = 1.5; }},
      {"filled_lattice_steps", [](WangOptions&) {}, two_levels,
       [](WangOptions& o) { o.level.refine.filled_lattice_steps = 0; }},
      {"filled_lattice_spacing",
       [](WangOptions& o) {
         o.levels = 2;
         o.level.refine.filled_lattice_steps = 0;
       },
       two_levels, [](WangOptions& o) { o.level.refine.filled_lattice_spacing = 1.5; }},
      {"filled_lattice_up_to",
       [](WangOptions& o) {
         o.levels = 2;
         o.level.refine.filled_lattice_steps = 0;
       },
       two_levels, [](WangOptions& o) { o.level.refine.filled_lattice_up_to = 8; }},
  };
  ASSERT_EQ(cases.size(), std::size(kConditionalWangSettings));
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const Case& c = cases[k];
    ASSERT_EQ(c.setting, kConditionalWangSettings[k]);
    const WangOptions unused = with(c.unused), used = with(c.used);
    EXPECT_FALSE(wang_setting_used(unused, c.setting)) << c.setting;
    EXPECT_TRUE(wang_setting_used(used, c.setting)) << c.setting;
    WangOptions unused_other = unused, used_other = used;
    c.other_value(unused_other);
    c.other_value(used_other);
    EXPECT_TRUE(points_of(unused_other) == points_of(unused)) << c.setting;
    EXPECT_TRUE(points_of(used_other) != points_of(used)) << c.setting;
  }
  EXPECT_THROW(wang_setting_used(small, "points"), Error);
}

TEST(WangOptions, EveryFieldIsCheckedByItsNameAndRange) {
  // The message validate() throws, "" when it accepts.
  auto message = [](const WangOptions& value) { return test::error_of([&] { validate(value); }); };
  EXPECT_EQ(message({}), "");
  WangOptions o;
  o.points = 0;
  EXPECT_EQ(message(o), "points: expected 1 to 1000000, got 0");
  o = {};
  o.levels = 33;
  EXPECT_EQ(message(o), "levels: expected 1 to 32, got 33");
  o = {};
  o.levels = 2;
  o.ratio = 1.0;
  EXPECT_EQ(message(o), "ratio: expected above 1 to 1e+08, got 1");
  o.ratio = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(o), "ratio: expected above 1 to 1e+08, got nan");
  o = {};
  o.level.edge_margin = 0.3;
  EXPECT_EQ(message(o), "margin: expected 0 to 0.25 tile units, got 0.3");
  o = {};
  o.level.refine.lattice_step = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(message(o), "lattice_step: expected 0.0001 to 0.1 hexagonal spacings, got nan");
  o = {};
  o.level.period = 1;
  EXPECT_EQ(message(o), "period: expected 2 to 1024, got 1");
  o = {};
  o.level.void_sigma = 5.0;
  EXPECT_EQ(message(o), "void_sigma: expected 0.1 to 4 hexagonal spacings, got 5");
  // The public entry checks too, before any work.
  ExactEngine engine;
  o = {};
  o.points = 0;
  EXPECT_THROW(relax_wang_tiles(engine, o), Error);
  EXPECT_EQ(parse_wang_strategy("rounds", TileSetKind::wang8), WangStrategy::rounds);
  // auto: exact, but instances for corner81, whose exact configurations are too many at small n.
  EXPECT_EQ(parse_wang_strategy("auto", TileSetKind::wang8), WangStrategy::exact);
  EXPECT_EQ(parse_wang_strategy("auto", TileSetKind::corner16), WangStrategy::exact);
  EXPECT_EQ(parse_wang_strategy("auto", TileSetKind::corner81), WangStrategy::instances);
  EXPECT_EQ(parse_wang_strategy("exact", TileSetKind::corner81), WangStrategy::exact);
  EXPECT_EQ(parse_wang_rank_order("voids"), RankOrder::voids);
  try {
    parse_wang_strategy("fast", TileSetKind::wang8);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "strategy: expected one of 'auto', 'exact', 'instances', 'rounds', got 'fast'");
  }
}

}  // namespace
}  // namespace bluetile
