// Hierarchical (progressive) point sets, the paper's section 2.1: level 0 is a blue-noise set;
// each further level adds points that are relaxed by Lloyd's method around all earlier points,
// which stay fixed. Every prefix of levels 0..l is then itself a well-spread set, so a renderer
// can take more samples where it needs them.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bluetile/core/point_file.h"
#include "bluetile/relax/band_fill.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/void_order.h"

namespace bluetile {

// Where the new points of a level start before relaxation.
enum class Placement {
  random,  // uniform random, as in the paper
  gaps,    // Mitchell's best candidate: of several random candidates, the farthest from all points
};

// The order of the points in a hierarchy, which is the rank a renderer or a density map thins by.
// (wang_relax.h's RankOrder is the tiled counterpart: its voids is this voids inside tiles; its
// farthest has no untiled use here.)
enum class ProgressiveOrder : std::uint8_t {
  // Each level relaxed around the fixed earlier ones (the paper), its points in the order they were
  // placed: every level boundary is blue noise, the prefixes inside a level less so.
  placement,
  // Levels relaxed in stages of at least kMinStagePoints points and at least half the points
  // before them (a stage is one level or several), the points of each stage in void order
  // (void_order.h) after every earlier one: every prefix is well spread, not only the boundaries.
  voids,
  // No relaxation: every point after the base placed by band-limited void filling (band_fill.h),
  // its rank the order of placement, its level the level its rank falls in. Every prefix about as
  // even as every other (LF about 0.045, rho 0.66 from 1/16 of the set on), where the other orders
  // alternate between relaxed boundaries and much less even prefixes between them.
  fill,
};

// The rank order's names, as the tool and the Python module spell them; parse_rank_order throws
// Error naming the value otherwise.
const char* rank_order_name(ProgressiveOrder order);
ProgressiveOrder parse_rank_order(const std::string& name);

// The smallest stage of the voids order: fewer points relaxed around fixed ones settle in the same
// arrangement in every set (one point at a time from one: nested square lattices, an ordered
// dither), where 64 relaxed together settle in one of many irregular ones.
inline constexpr std::size_t kMinStagePoints = 64;

struct LevelOptions {
  std::size_t add = 0;  // points to add (>= 1)
  int iterations = kDefaultIterations;
  double tolerance = 0.0;  // see LloydOptions
  std::uint64_t seed = 1;
  Placement placement = Placement::gaps;
  std::function<void(const LloydIteration&)> on_iteration{};
};

// Returns base followed by `add` new points relaxed around the base, which is kept bit for bit.
// Levels: base points keep theirs (0 when the base has none); new points get one more than the
// highest base level, or 0 when the base is empty (then this is a plain relaxed set). Throws Error
// for add 0 or above kMaxSetPoints, a base count_levels refuses, and as relax_lloyd does.
PointSet add_level(CentroidEngine& engine, const PointSet& base, const LevelOptions& options);

// Initial positions of `count` new points among `existing` ones (unit torus; an existing point
// outside [0, 1)^2 counts as its copy inside). Throws Error above kMaxSetPoints (check_set_points)
// and for an existing point that is not finite.
std::vector<Point> place_new_points(const std::vector<Point>& existing, std::size_t count, Placement placement,
                                    std::uint64_t seed);

struct HierarchyOptions {
  // From scratch (an empty base): level 0 has `count` relaxed random points.
  std::size_t count = 0;
  // Points each further level adds (0: `count`), or, with ratio > 1, enough to multiply the
  // total by `ratio` per level (level_size).
  std::size_t add = 0;
  double ratio = 0.0;
  // Total levels of the result; 0: 4 from scratch, one more than the base has otherwise.
  int levels = 0;
  int iterations = kDefaultIterations;
  double tolerance = 0.0;
  std::uint64_t seed = 1;  // level l places its points with derive_seed(seed, l)
  Placement placement = Placement::gaps;
  ProgressiveOrder rank_order = ProgressiveOrder::voids;  // LF between boundaries about half placement's (docs/RESULTS.md)
  double void_sigma = kVoidSigmaFactor;  // the voids order's kernel width (void_order.h)
  FillOptions fill{};  // the fill order's floor, window and grid (band_fill.h); its seed is set from `seed`
  // With the voids order, level is the first level of the stage being relaxed.
  std::function<void(int level, const LloydIteration&)> on_iteration{};
};

// A hierarchy as `bluetile progressive` builds it: the base (kept bit for bit), then levels up
// to options.levels, each added by add_level with seed derive_seed(options.seed, level). With
// ProgressiveOrder::fill no level is relaxed: from scratch, every point (level 0's too) is filled,
// and on a base, every new one (seed derive_seed(seed, base levels)). With
// ProgressiveOrder::voids the levels are relaxed in stages (hierarchy_stages), each added by add_level
// with the seed of its first level, and the new points of a stage are reordered by void_order and
// given the levels of their ranks. A stage of one level is placed and relaxed as the placement
// order does it; its points differ by rounding (the earlier points are in another order) grown
// over the iterations, not in kind.
// Throws Error (before any work) when there is nothing to add, the base already has that many
// levels, or the total would pass kMaxHierarchyPoints.
PointSet add_levels(CentroidEngine& engine, PointSet base, const HierarchyOptions& options);

// Makes an engine for one worker thread (an engine serves one caller at a time).
using EngineMaker = std::function<std::unique_ptr<CentroidEngine>()>;

// The hierarchies of independent bases: base k is the one add_levels builds alone with seed
// options.seed + k (wrapping past 2^64 - 1), bit for bit. The bases are built in parallel, each
// by one thread with an engine of its own from `new_engine` (a base's scenes then stay in that
// thread's cache: relaxing many small sets in one engine call per iteration was measured slower).
// options.on_iteration and options.fill.on_round are not called; on_base_done(done) is, after each base, one call at a time.
// Throws as add_levels does, before any work.
std::vector<PointSet> add_levels(const EngineMaker& new_engine, std::vector<PointSet> bases,
                                 const HierarchyOptions& options,
                                 const std::function<void(std::size_t done)>& on_base_done = {});

// The memory of `points` points built in levels on `engine`: a relaxation's (relax_memory_bytes)
// and the levels column, for up-front checks. The fill order runs no engine (the exact engine's
// figure stands for its points) and adds its grid (band_fill_cost).
inline double progressive_memory_bytes(double points, std::string_view engine) {
  return relax_memory_bytes(points, engine) + 8.0 * points;
}

// The number of points each new level of add_levels adds, checked as add_levels checks them.
std::vector<std::size_t> hierarchy_level_sizes(const PointSet& base, const HierarchyOptions& options);

// The stages of the voids order for new levels of these sizes on a base of base_count points: the
// number of levels each stage relaxes together. A stage ends at the first level boundary where it
// holds at least kMinStagePoints points and at least half the points before it, or at the end.
std::vector<std::size_t> hierarchy_stages(std::size_t base_count, const std::vector<std::size_t>& level_sizes);

// Levels in a set: 0 when empty, 1 without a level column, else the highest level + 1. Throws Error
// for a level column whose length is not the number of points and a level outside 0 to kMaxLevel.
int count_levels(const PointSet& set);

// A hierarchy larger than this is almost surely a mistyped option, and would need tens of GiB.
inline constexpr std::size_t kMaxHierarchyPoints = 100'000'000;

// How many points level l (>= 1) adds: `add` each (the paper's N per level), or, with a ratio r > 1,
// enough to bring the total from `total` to round(r * total). Throws Error for a ratio that is
// negative or not finite (hierarchy_level_sizes refuses one that adds no point or too many).
std::size_t level_size(std::size_t total, std::size_t add, double ratio);

}  // namespace bluetile
