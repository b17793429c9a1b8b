#include "bluetile/relax/progressive.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/request_limits.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/void_order.h"

namespace bluetile {
namespace {

// Points on the unit torus in uniform buckets, for nearest-distance queries while inserting.
class GrowingGrid {
 public:
  explicit GrowingGrid(std::size_t expected_points) {
    side_ = std::clamp<long>(static_cast<long>(std::sqrt(static_cast<double>(expected_points) / 2.0)), 1, 4096);
    buckets_.resize(static_cast<std::size_t>(side_ * side_));
  }

  void insert(Point p) { buckets_[bucket(p)].push_back(p); }

  // Squared torus distance from p to the nearest inserted point (infinity when empty).
  double nearest_squared(Point p) const {
    const double cell = 1.0 / static_cast<double>(side_);
    long cx = coordinate(p.x), cy = coordinate(p.y);
    double best = std::numeric_limits<double>::infinity();
    for (long ring = 0; ring <= side_; ++ring) {
      for (long dy = -ring; dy <= ring; ++dy) {
        for (long dx = -ring; dx <= ring; ++dx) {
          if (std::max(std::labs(dx), std::labs(dy)) != ring) continue;
          long bx = ((cx + dx) % side_ + side_) % side_, by = ((cy + dy) % side_ + side_) % side_;
          for (Point q : buckets_[static_cast<std::size_t>(by * side_ + bx)])
            best = std::min(best, torus_distance_squared(p, q, Domain{}));
        }
      }
      // Points outside the searched block are at least `ring * cell` away.
      double reach = static_cast<double>(ring) * cell;
      if (best <= reach * reach) break;
    }
    return best;
  }

 private:
  long coordinate(double x) const { return std::clamp<long>(static_cast<long>(x * static_cast<double>(side_)), 0, side_ - 1); }
  std::size_t bucket(Point p) const { return static_cast<std::size_t>(coordinate(p.y) * side_ + coordinate(p.x)); }

  long side_;
  std::vector<std::vector<Point>> buckets_;
};

// Candidates per new point in best-candidate placement: Mitchell (1991) found a handful enough;
// 10 fills the largest gaps well while costing little next to one Lloyd iteration.
constexpr int kCandidates = 10;

}  // namespace

std::vector<Point> place_new_points(const std::vector<Point>& existing, std::size_t count, Placement placement,
                                    std::uint64_t seed) {
  check_set_points(count, "new points: count");
  // A NaN fell out of the grid's buckets; a point outside [0, 1)^2 went to the nearest border
  // bucket, where the search did not look for it.
  check_finite_points(existing, "new points");
  Rng rng(seed);
  std::vector<Point> added;
  added.reserve(count);
  if (placement == Placement::random) {
    for (std::size_t i = 0; i < count; ++i) added.push_back(rng.point(Domain{}));
    return added;
  }
  GrowingGrid grid(existing.size() + count);
  for (Point p : existing) grid.insert(wrap_point(p, Domain{}));
  for (std::size_t i = 0; i < count; ++i) {
    Point best{};
    double best_distance = -1.0;
    for (int c = 0; c < kCandidates; ++c) {
      Point candidate = rng.point(Domain{});
      double d = grid.nearest_squared(candidate);
      if (d > best_distance) {
        best_distance = d;
        best = candidate;
      }
    }
    grid.insert(best);
    added.push_back(best);
  }
  return added;
}

std::size_t level_size(std::size_t total, std::size_t add, double ratio) {
  // An infinite ratio was cast to an integer (undefined; it came back as a wrapped negative count).
  if (!std::isfinite(ratio) || ratio < 0.0)
    throw Error("ratio " + shortest_text(ratio) + ": expected 0 (add points) or a finite ratio above 1");
  if (ratio > 0.0) {
    double target = std::round(ratio * static_cast<double>(total));
    if (!(target < 0x1p64))
      throw Error("ratio " + shortest_text(ratio) + ": a set of " + std::to_string(total) + " points would grow past 2^64");
    return target > static_cast<double>(total) ? static_cast<std::size_t>(target) - total : 0;
  }
  return add;
}

PointSet add_level(CentroidEngine& engine, const PointSet& base, const LevelOptions& options) {
  if (options.add == 0) throw Error("nothing to add: the number of new points must be at least 1");
  // std::length_error after the placement's reserve, not an Error naming it.
  if (options.add > kMaxSetPoints)
    throw Error("add: expected 1 to " + std::to_string(kMaxSetPoints) + ", got " + std::to_string(options.add));
  const int level = count_levels(base);

  PointSet result;
  result.points = base.points;
  result.levels = base.has_levels() ? base.levels : std::vector<int>(base.points.size(), 0);
  std::vector<Point> added = place_new_points(base.points, options.add, options.placement, options.seed);
  result.points.insert(result.points.end(), added.begin(), added.end());
  result.levels.resize(result.points.size(), level);

  Scene scene = make_scene(std::move(result.points));
  scene.wanted_begin = base.points.size();
  LloydOptions lloyd;
  lloyd.iterations = options.iterations;
  lloyd.tolerance = options.tolerance;
  lloyd.on_iteration = options.on_iteration;
  relax_lloyd(engine, scene, lloyd);
  result.points = std::move(scene.sites);
  return result;
}

int count_levels(const PointSet& set) {
  // A level column shorter or longer than the points, a negative level or one of INT_MAX (whose
  // + 1 overflowed) gave a count of no set.
  check_level_column(set, "");
  for (std::size_t i = 0; i < set.levels.size(); ++i)
    if (set.levels[i] < 0 || set.levels[i] > kMaxLevel)
      throw Error("level " + std::to_string(set.levels[i]) + " of point " + std::to_string(i) + ": expected 0 to " +
                  std::to_string(kMaxLevel));
  if (set.points.empty()) return 0;
  if (!set.has_levels()) return 1;
  return *std::max_element(set.levels.begin(), set.levels.end()) + 1;
}

std::vector<std::size_t> hierarchy_level_sizes(const PointSet& base, const HierarchyOptions& options) {
  const bool from_scratch = base.points.empty();
  if (from_scratch && options.count == 0) throw Error("nothing to build: the first level needs at least 1 point");
  if (!from_scratch && options.add == 0 && options.ratio == 0.0)
    throw Error("nothing to add: give the points per level (add) or a ratio");
  if (options.ratio != 0.0 && !(options.ratio > 1.0))
    throw Error("the ratio must be above 1, got " + shortest_text(options.ratio));
  // Checked here, before any level is placed, as relax_lloyd would check them at the first level.
  check_whole_field("iterations", options.iterations, 0, std::numeric_limits<int>::max());
  check_real_field("tolerance", options.tolerance, 0.0, std::numeric_limits<double>::infinity());
  if (options.rank_order == ProgressiveOrder::voids)
    check_real_field("void_sigma", options.void_sigma, kMinVoidSigma, kMaxVoidSigma, " hexagonal spacings");
  const int base_levels = count_levels(base);
  const int target_levels = options.levels ? options.levels : std::max(base_levels + 1, from_scratch ? 4 : 1);
  if (target_levels <= base_levels) {
    throw Error(counted(target_levels, "level") + ": the base already has " + counted(base_levels, "level") +
                "; the number of levels is the total to reach (" + std::to_string(base_levels + 1) + " or more)");
  }
  // A level the point-file reader would refuse is not written.
  if (target_levels - 1 > kMaxLevel) {
    throw Error("the base already has levels up to " + std::to_string(base_levels - 1) + ", and a point file holds levels up to " +
                std::to_string(kMaxLevel) + " only");
  }
  const std::size_t per_level = options.add ? options.add : options.count;
  std::vector<std::size_t> sizes;
  std::size_t total = base.points.size();
  for (int l = base_levels; l < target_levels; ++l) {
    std::size_t add = from_scratch && l == 0 ? options.count : level_size(total, per_level, options.ratio);
    if (add == 0) {
      throw Error("ratio " + shortest_text(options.ratio) + " adds no point to a set of " + std::to_string(total) +
                  " (level " + std::to_string(l) + ")");
    }
    if (add > kMaxHierarchyPoints - total) {
      throw Error("level " + std::to_string(l) + " would bring the set to " + std::to_string(total + add) +
                  " points, more than the limit of " + std::to_string(kMaxHierarchyPoints));
    }
    total += add;
    sizes.push_back(add);
  }
  return sizes;
}

const char* rank_order_name(ProgressiveOrder order) {
  switch (order) {
    case ProgressiveOrder::placement: return "placement";
    case ProgressiveOrder::voids: return "voids";
    case ProgressiveOrder::fill: return "fill";
  }
  return "placement";
}

ProgressiveOrder parse_rank_order(const std::string& name) {
  if (name == "placement") return ProgressiveOrder::placement;
  if (name == "voids") return ProgressiveOrder::voids;
  if (name == "fill") return ProgressiveOrder::fill;
  throw Error("rank order: expected 'placement', 'voids' or 'fill', got '" + name + "'");
}

std::vector<std::size_t> hierarchy_stages(std::size_t base_count, const std::vector<std::size_t>& level_sizes) {
  std::vector<std::size_t> stages;
  std::size_t before = base_count, in_stage = 0, levels_in_stage = 0;
  for (std::size_t i = 0; i < level_sizes.size(); ++i) {
    in_stage += level_sizes[i];
    ++levels_in_stage;
    if (i + 1 == level_sizes.size() || (in_stage >= kMinStagePoints && 2 * in_stage >= before)) {
      stages.push_back(levels_in_stage);
      before += in_stage;
      in_stage = levels_in_stage = 0;
    }
  }
  return stages;
}

namespace {

// The voids order: each stage relaxed as one level, then its new points reordered by voids and
// given the levels their ranks fall in.
PointSet add_stages(CentroidEngine& engine, PointSet set, const HierarchyOptions& options,
                    const std::vector<std::size_t>& sizes) {
  const int base_levels = count_levels(set);
  LevelOptions level;
  level.iterations = options.iterations;
  level.tolerance = options.tolerance;
  level.placement = options.placement;
  std::size_t first = 0;  // index in sizes of the stage's first level
  for (std::size_t stage_levels : hierarchy_stages(set.points.size(), sizes)) {
    const int l = base_levels + static_cast<int>(first);
    level.add = 0;
    for (std::size_t i = first; i < first + stage_levels; ++i) level.add += sizes[i];
    level.seed = derive_seed(options.seed, static_cast<std::uint64_t>(l));
    if (options.on_iteration) {
      level.on_iteration = [&options, l](const LloydIteration& it) { options.on_iteration(l, it); };
    }
    const std::size_t before = set.points.size();
    PointSet relaxed = add_level(engine, set, level);
    const std::vector<std::uint32_t> order = void_order(relaxed.points, before, options.void_sigma);
    const std::vector<Point> placed(relaxed.points.begin() + static_cast<std::ptrdiff_t>(before), relaxed.points.end());
    std::size_t rank = before;
    for (std::size_t i = first; i < first + stage_levels; ++i) {
      for (std::size_t k = 0; k < sizes[i]; ++k, ++rank) {
        relaxed.points[rank] = placed[order[rank - before] - before];
        relaxed.levels[rank] = base_levels + static_cast<int>(i);
      }
    }
    set = std::move(relaxed);
    first += stage_levels;
  }
  return set;
}

// The fill order: every new point placed by band-limited void filling, levels by rank.
PointSet add_filled(PointSet set, const HierarchyOptions& options, const std::vector<std::size_t>& sizes) {
  const int base_levels = count_levels(set);
  std::size_t add = 0;
  for (std::size_t size : sizes) add += size;
  FillOptions fill = options.fill;
  fill.seed = derive_seed(options.seed, static_cast<std::uint64_t>(base_levels));
  const std::vector<Point> added = band_fill_torus(set.points, add, fill);
  if (!set.has_levels()) set.levels.assign(set.points.size(), 0);
  set.points.insert(set.points.end(), added.begin(), added.end());
  for (std::size_t i = 0; i < sizes.size(); ++i) set.levels.insert(set.levels.end(), sizes[i], base_levels + static_cast<int>(i));
  return set;
}

}  // namespace

PointSet add_levels(CentroidEngine& engine, PointSet set, const HierarchyOptions& options) {
  const std::vector<std::size_t> sizes = hierarchy_level_sizes(set, options);
  if (options.rank_order == ProgressiveOrder::voids) return add_stages(engine, std::move(set), options, sizes);
  if (options.rank_order == ProgressiveOrder::fill) return add_filled(std::move(set), options, sizes);
  const int base_levels = count_levels(set);
  LevelOptions level;
  level.iterations = options.iterations;
  level.tolerance = options.tolerance;
  level.placement = options.placement;
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    const int l = base_levels + static_cast<int>(i);
    level.add = sizes[i];
    level.seed = derive_seed(options.seed, static_cast<std::uint64_t>(l));
    if (options.on_iteration) {
      level.on_iteration = [&options, l](const LloydIteration& it) { options.on_iteration(l, it); };
    }
    set = add_level(engine, set, level);
  }
  return set;
}

std::vector<PointSet> add_levels(const EngineMaker& new_engine, std::vector<PointSet> bases,
                                 const HierarchyOptions& options,
                                 const std::function<void(std::size_t done)>& on_base_done) {
  for (const PointSet& base : bases) hierarchy_level_sizes(base, options);
  HierarchyOptions each = options;
  each.on_iteration = nullptr;
  each.fill.on_round = nullptr;
  std::mutex done_mutex;
  std::size_t done = 0;
  // A few chunks per thread balance the load; each chunk makes one engine.
  const std::size_t grain = std::max<std::size_t>(1, bases.size() / (4 * thread_count()));
  parallel_for(bases.size(), grain, [&](std::size_t begin, std::size_t end) {
    std::unique_ptr<CentroidEngine> engine = new_engine();
    for (std::size_t k = begin; k < end; ++k) {
      HierarchyOptions alone = each;
      alone.seed = options.seed + k;
      bases[k] = add_levels(*engine, std::move(bases[k]), alone);
      std::lock_guard<std::mutex> lock(done_mutex);
      ++done;
      if (on_base_done) on_base_done(done);
    }
  });
  return bases;
}

}  // namespace bluetile
