// Progressive order by voids on the unit torus (see void_order.h).
#include "bluetile/relax/void_order.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"

namespace bluetile {
namespace {

// The choice is among points at least this fraction of the farthest one's distance from every
// ranked point: the value wang_ranks.cpp measured (the energy alone lets close pairs into early
// prefixes).
constexpr double kVoidSpacingFloor = 0.7;

// The kernel is cut at this many sigma: exp(-8) = 3e-4 of a point's own weight.
constexpr double kReachSigmas = 4.0;

// The kernel width is set anew each time the prefix grows by this factor (the sigma of a prefix
// 25 % larger is 11 % smaller): rebuilding every energy costs O(n), so not at every step.
constexpr double kSigmaRefreshGrowth = 1.25;

// The points to rank in uniform buckets, so that a newly ranked point updates only those within reach.
class CandidateGrid {
 public:
  explicit CandidateGrid(std::span<const Point> candidates) {
    // About two candidates per bucket.
    side_ = std::clamp<long>(static_cast<long>(std::sqrt(static_cast<double>(candidates.size()) / 2.0)), 1, 4096);
    buckets_.resize(static_cast<std::size_t>(side_ * side_));
    for (std::size_t m = 0; m < candidates.size(); ++m)
      buckets_[bucket(coordinate(candidates[m].x), coordinate(candidates[m].y))].push_back(static_cast<std::uint32_t>(m));
  }

  // Calls visit(m) for every candidate in a bucket that can hold points within `reach` of p (each
  // candidate once; maybe also a few farther ones).
  template <typename Visit>
  void near(Point p, double reach, Visit&& visit) const {
    const long span = static_cast<long>(std::ceil(reach * static_cast<double>(side_)));
    if (2 * span + 1 >= side_) {
      for (const auto& b : buckets_)
        for (std::uint32_t m : b) visit(m);
      return;
    }
    const long cx = coordinate(p.x), cy = coordinate(p.y);
    for (long dy = -span; dy <= span; ++dy)
      for (long dx = -span; dx <= span; ++dx)
        for (std::uint32_t m : buckets_[bucket(wrap(cx + dx), wrap(cy + dy))]) visit(m);
  }

 private:
  long coordinate(double x) const {
    return std::clamp<long>(static_cast<long>(x * static_cast<double>(side_)), 0, side_ - 1);
  }
  long wrap(long c) const { return (c % side_ + side_) % side_; }
  std::size_t bucket(long x, long y) const { return static_cast<std::size_t>(y * side_ + x); }

  long side_;
  std::vector<std::vector<std::uint32_t>> buckets_;
};

// The choice of each step in O(log M) typically, instead of a scan of every unranked point: a
// binary tree over the candidates (in index order) holding, per subtree, the largest nearest
// distance and the least energy of its unranked candidates. The farthest distance is the root's;
// the least energy among candidates at or above the floor is found by a search that skips
// subtrees wholly below the floor or with no energy under the best found (ties: lower index).
class ChoiceTree {
 public:
  explicit ChoiceTree(std::size_t count) : leaves_(1) {
    while (leaves_ < count) leaves_ *= 2;
    nearest_.assign(2 * leaves_, -HUGE_VAL);
    energy_.assign(2 * leaves_, HUGE_VAL);
  }

  // Candidate m's values, or its removal (ranked) with nearest -infinity and energy infinity.
  void set(std::size_t m, double nearest, double energy) {
    std::size_t node = leaves_ + m;
    nearest_[node] = nearest;
    energy_[node] = energy;
    for (node /= 2; node >= 1; node /= 2) {
      nearest_[node] = std::max(nearest_[2 * node], nearest_[2 * node + 1]);
      energy_[node] = std::min(energy_[2 * node], energy_[2 * node + 1]);
    }
  }

  double farthest() const { return nearest_[1]; }

  // The candidate of least energy among those with nearest >= floor (the lowest index on ties).
  std::size_t least_energy_above(double floor) const {
    std::size_t best = 0;  // no node yet (the nodes are 1 ...)
    double best_energy = HUGE_VAL;
    search(1, floor, best, best_energy);
    return best - leaves_;
  }

 private:
  void search(std::size_t node, double floor, std::size_t& best, double& best_energy) const {
    if (nearest_[node] < floor || energy_[node] > best_energy) return;
    if (node >= leaves_) {
      // Left to right, so an equal energy found later has a higher index.
      if (best == 0 || energy_[node] < best_energy) {
        best = node;
        best_energy = energy_[node];
      }
      return;
    }
    search(2 * node, floor, best, best_energy);
    search(2 * node + 1, floor, best, best_energy);
  }

  std::size_t leaves_;
  std::vector<double> nearest_, energy_;
};

}  // namespace

std::vector<std::uint32_t> void_order(std::span<const Point> points, std::size_t ranked, double sigma_factor) {
  if (ranked > points.size())
    throw Error("ranked " + std::to_string(ranked) + ": expected at most the " + std::to_string(points.size()) +
                " points");
  check_real_field("void_sigma", sigma_factor, kMinVoidSigma, kMaxVoidSigma, " hexagonal spacings");
  check_finite_points(points, "void order");
  const std::size_t count = points.size() - ranked;
  std::vector<std::uint32_t> order;
  order.reserve(count);
  if (count == 0) return order;
  const std::span<const Point> candidates = points.subspan(ranked);
  const CandidateGrid grid(candidates);
  const Domain torus{};
  std::vector<double> energy(count, 0.0);
  std::vector<double> nearest(count, HUGE_VAL);  // squared distance to the nearest ranked point within reach
  std::vector<bool> is_ranked(count, false);
  ChoiceTree tree(count);

  double inv2s2 = 0.0, reach = 0.0;
  // Adds ranked point y's energy to every candidate within reach and, unless only the energies
  // are being rebuilt, lowers their nearest distances.
  auto add_ranked = [&](Point y, bool energy_only, bool update_tree) {
    const double reach2 = reach * reach;
    grid.near(y, reach, [&](std::uint32_t m) {
      const double d2 = torus_distance_squared(candidates[m], y, torus);
      if (d2 >= reach2 || is_ranked[m]) return;
      energy[m] += std::exp(-d2 * inv2s2);
      if (!energy_only) nearest[m] = std::min(nearest[m], d2);
      if (update_tree) tree.set(m, nearest[m], energy[m]);
    });
  };
  // Sets sigma for a prefix of `prefix` points and rebuilds every energy from the ranked points.
  auto set_sigma = [&](std::size_t prefix, bool first) {
    const double sigma = sigma_factor * hexagonal_spacing(static_cast<double>(prefix));
    inv2s2 = 1.0 / (2.0 * sigma * sigma);
    reach = kReachSigmas * sigma;
    std::fill(energy.begin(), energy.end(), 0.0);
    for (std::size_t k = 0; k < ranked; ++k) add_ranked(points[k], !first, false);
    for (std::uint32_t m : order) add_ranked(candidates[m - ranked], !first, false);
    for (std::size_t m = 0; m < count; ++m)
      if (!is_ranked[m]) tree.set(m, nearest[m], energy[m]);
  };

  std::size_t sigma_prefix = 0;
  for (std::size_t step = 0; step < count; ++step) {
    const std::size_t prefix = ranked + step + 1;  // the prefix this step completes
    if (sigma_prefix == 0 || static_cast<double>(prefix) > kSigmaRefreshGrowth * static_cast<double>(sigma_prefix)) {
      set_sigma(prefix, sigma_prefix == 0);
      sigma_prefix = prefix;
    }
    const double floor = kVoidSpacingFloor * kVoidSpacingFloor * tree.farthest();  // squared distances
    const std::size_t chosen = tree.least_energy_above(floor);
    assert(chosen < count && !is_ranked[chosen]);
    is_ranked[chosen] = true;
    tree.set(chosen, -HUGE_VAL, HUGE_VAL);
    order.push_back(static_cast<std::uint32_t>(ranked + chosen));
    add_ranked(candidates[chosen], false, true);
  }
  return order;
}

}  // namespace bluetile
