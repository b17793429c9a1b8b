// Hierarchical (progressive) point sets, the paper's section 2.1: level 0 is a blue-noise set;
// each further level adds points that are relaxed by Lloyd's method around all earlier points,
// which stay fixed. Every prefix of levels 0..l is then itself a well-spread set, so a renderer
// can take more samples where it needs them.
#pragma once

#include <cstdint>
#include <functional>

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

// How many points level l (>= 1) adds: `add` each (the paper's N per level), or, with a ratio r > 1,
// enough to bring the total from `total` to round(r * total).
std::size_t level_size(std::size_t total, std::size_t add, double ratio);

}  // namespace bluetile
