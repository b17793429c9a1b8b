// Dart throwing with radius reduction (McCool & Fiume 1992; the paper, section 1.1).
// Acceleration: a uniform grid of buckets, each listing its points; a candidate checks only the
// buckets within the current radius, wrapped around the torus.
#include "bluetile/sampling/dart_throwing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/rng.h"

namespace bluetile {
namespace {

// Trials between two cancellation points: about a millisecond late in a run of 10^6 points.
constexpr std::size_t kTrialsPerCancellationPoint = 4096;

}  // namespace

void validate(const DartOptions& o) {
  // A count past the long long range reads as the largest one (refused all the same).
  auto whole = [](std::size_t v) { return static_cast<long long>(std::min<std::size_t>(v, std::size_t{1} << 62)); };
  check_whole_field("count", whole(o.count), 1, static_cast<long long>(kMaxDartCount));
  check_whole_field("max_failures", whole(o.max_failures), 1, static_cast<long long>(kMaxDartFailures));
  check_real_field("shrink", o.shrink, kMinDartShrink, kMaxDartShrink);
  check_real_field("start", o.start, kMinDartStart, kMaxDartStart, " hexagonal spacings");
}

DartResult throw_darts(const DartOptions& o) {
  validate(o);

  const Domain unit;
  DartResult result;
  result.initial_radius = std::min(o.start * hexagonal_spacing(static_cast<double>(o.count)), kMaxDartRadius);
  double radius = result.initial_radius;
  // Buckets about half the starting spacing wide: a few points each even late in the process.
  const long side = std::clamp<long>(static_cast<long>(2.0 / result.initial_radius), 1, 8192);
  const double bucket = 1.0 / static_cast<double>(side);
  std::vector<std::vector<std::uint32_t>> buckets(static_cast<std::size_t>(side * side));
  auto index_of = [&](double c) { return std::clamp<long>(static_cast<long>(c * static_cast<double>(side)), 0, side - 1); };

  Rng rng(o.seed);
  std::size_t failures = 0;
  result.points.reserve(o.count);
  while (result.points.size() < o.count) {
    Point candidate = rng.point(unit);
    ++result.trials;
    if (result.trials % kTrialsPerCancellationPoint == 0) cancellation_point();
    const long bx = index_of(candidate.x), by = index_of(candidate.y);
    const long reach = std::min<long>(static_cast<long>(std::ceil(radius / bucket)), side / 2 + 1);
    const double r2 = radius * radius;
    bool free = true;
    for (long dy = -reach; dy <= reach && free; ++dy) {
      const long y = ((by + dy) % side + side) % side;
      for (long dx = -reach; dx <= reach && free; ++dx) {
        const long x = ((bx + dx) % side + side) % side;
        for (std::uint32_t j : buckets[static_cast<std::size_t>(y * side + x)]) {
          if (torus_distance_squared(candidate, result.points[j], unit) < r2) {
            free = false;
            break;
          }
        }
      }
    }
    if (free) {
      buckets[static_cast<std::size_t>(by * side + bx)].push_back(static_cast<std::uint32_t>(result.points.size()));
      result.points.push_back(candidate);
      failures = 0;
    } else if (++failures >= o.max_failures) {
      radius *= o.shrink;
      ++result.reductions;
      failures = 0;
    }
  }
  result.final_radius = radius;
  return result;
}

}  // namespace bluetile
