// Progressive order by voids on the unit torus (see void_order.h).
#include "bluetile/relax/void_order.h"

#include <algorithm>
#include <cassert>
#include <cmath>

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

// The unranked points in uniform buckets, so that a ranked point updates only those within reach.
class CandidateGrid {
 public:
  CandidateGrid(std::span<const Point> candidates) {
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

}  // namespace

std::vector<std::uint32_t> void_order(std::span<const Point> points, std::size_t ranked, double sigma_factor) {
  assert(ranked <= points.size());
  const std::size_t count = points.size() - ranked;
  std::vector<std::uint32_t> order;
  order.reserve(count);
  if (count == 0) return order;
  const std::span<const Point> candidates = points.subspan(ranked);
  const CandidateGrid grid(candidates);
  const Domain torus{};
  std::vector<double> energy(count, 0.0);
  std::vector<double> nearest(count, HUGE_VAL);  // squared distance to the nearest ranked point within reach
  std::vector<std::uint32_t> unranked(count);   // candidates not yet ranked, in no particular order
  for (std::size_t m = 0; m < count; ++m) unranked[m] = static_cast<std::uint32_t>(m);

  double inv2s2 = 0.0, reach = 0.0;
  // Adds ranked point y's energy to every candidate within reach and, unless only the energies
  // are being rebuilt, lowers their nearest distances.
  auto add_ranked = [&](Point y, bool energy_only) {
    const double reach2 = reach * reach;
    grid.near(y, reach, [&](std::uint32_t m) {
      const double d2 = torus_distance_squared(candidates[m], y, torus);
      if (d2 >= reach2) return;
      energy[m] += std::exp(-d2 * inv2s2);
      if (!energy_only) nearest[m] = std::min(nearest[m], d2);
    });
  };
  // Sets sigma for a prefix of `prefix` points and rebuilds every energy from the ranked points.
  auto set_sigma = [&](std::size_t prefix, bool first) {
    const double sigma = sigma_factor * hexagonal_spacing(static_cast<double>(prefix));
    inv2s2 = 1.0 / (2.0 * sigma * sigma);
    reach = kReachSigmas * sigma;
    std::fill(energy.begin(), energy.end(), 0.0);
    for (std::size_t k = 0; k < ranked; ++k) add_ranked(points[k], !first);
    for (std::uint32_t m : order) add_ranked(candidates[m - ranked], !first);
  };

  std::size_t sigma_prefix = 0;
  for (std::size_t step = 0; step < count; ++step) {
    const std::size_t prefix = ranked + step + 1;  // the prefix this step completes
    if (sigma_prefix == 0 || static_cast<double>(prefix) > kSigmaRefreshGrowth * static_cast<double>(sigma_prefix)) {
      set_sigma(prefix, sigma_prefix == 0);
      sigma_prefix = prefix;
    }
    double farthest = 0.0;
    for (std::uint32_t m : unranked) farthest = std::max(farthest, nearest[m]);
    const double floor = kVoidSpacingFloor * kVoidSpacingFloor * farthest;  // squared distances
    std::size_t best = unranked.size();
    for (std::size_t i = 0; i < unranked.size(); ++i) {
      const std::uint32_t m = unranked[i];
      if (nearest[m] < floor) continue;
      if (best == unranked.size() || energy[m] < energy[unranked[best]] ||
          (energy[m] == energy[unranked[best]] && m < unranked[best]))
        best = i;
    }
    assert(best < unranked.size());
    const std::uint32_t chosen = unranked[best];
    unranked[best] = unranked.back();
    unranked.pop_back();
    nearest[chosen] = 0.0;
    order.push_back(static_cast<std::uint32_t>(ranked + chosen));
    add_ranked(candidates[chosen], false);
  }
  return order;
}

}  // namespace bluetile
