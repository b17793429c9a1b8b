// Hierarchical (progressive) point sets, the paper's section 2.1: level 0 is a blue-noise set;
// each further level adds points that are relaxed by Lloyd's method around all earlier points,
// which stay fixed. Every prefix of levels 0..l is then itself a well-spread set, so a renderer
// can take more samples where it needs them.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "bluetile/core/point_file.h"
#include "bluetile/relax/lloyd.h"

namespace bluetile {

// Where the new points of a level start before relaxation.
enum class Placement {
  random,  // uniform random, as in the paper
  gaps,    // Mitchell's best candidate: of several random candidates, the farthest from all points
};

struct LevelOptions {
  std::size_t add = 0;  // points to add (>= 1)
  int iterations = 80;
  double tolerance = 0.0;  // see LloydOptions
  std::uint64_t seed = 1;
  Placement placement = Placement::gaps;
  std::function<void(const LloydIteration&)> on_iteration;
};

// Returns base followed by `add` new points relaxed around the base, which is kept bit for bit.
// Levels: base points keep theirs (0 when the base has none); new points get one more than the
// highest base level, or 0 when the base is empty (then this is a plain relaxed set).
PointSet add_level(CentroidEngine& engine, const PointSet& base, const LevelOptions& options);

// Initial positions of `count` new points among `existing` ones (unit torus).
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
  int iterations = 80;
  double tolerance = 0.0;
  std::uint64_t seed = 1;  // level l places its points with derive_seed(seed, l)
  Placement placement = Placement::gaps;
  std::function<void(int level, const LloydIteration&)> on_iteration;
};

// A hierarchy as `bluetile progressive` builds it: the base (kept bit for bit), then levels up
// to options.levels, each added by add_level with seed derive_seed(options.seed, level).
// Throws Error (before any work) when there is nothing to add, the base already has that many
// levels, or the total would pass kMaxHierarchyPoints.
PointSet add_levels(CentroidEngine& engine, PointSet base, const HierarchyOptions& options);

// Makes an engine for one worker thread (an engine serves one caller at a time).
using EngineMaker = std::function<std::unique_ptr<CentroidEngine>()>;

// The hierarchies of independent bases: base k is the one add_levels builds alone with seed
// options.seed + k (wrapping past 2^64 - 1), bit for bit. The bases are built in parallel, each
// by one thread with an engine of its own from `new_engine` (a base's scenes then stay in that
// thread's cache: relaxing many small sets in one engine call per iteration was measured slower).
// options.on_iteration is not called; on_base_done(done) is, after each base, one call at a time.
// Throws as add_levels does, before any work.
std::vector<PointSet> add_levels(const EngineMaker& new_engine, std::vector<PointSet> bases,
                                 const HierarchyOptions& options,
                                 const std::function<void(std::size_t done)>& on_base_done = {});

// The number of points each new level of add_levels adds, checked as add_levels checks them.
std::vector<std::size_t> hierarchy_level_sizes(const PointSet& base, const HierarchyOptions& options);

// Levels in a set: 0 when empty, 1 without a level column, else the highest level + 1.
int count_levels(const PointSet& set);

// A hierarchy larger than this is almost surely a mistyped option, and would need tens of GiB.
inline constexpr std::size_t kMaxHierarchyPoints = 100'000'000;

// How many points level l (>= 1) adds: `add` each (the paper's N per level), or, with a ratio r > 1,
// enough to bring the total from `total` to round(r * total).
std::size_t level_size(std::size_t total, std::size_t add, double ratio);

}  // namespace bluetile
