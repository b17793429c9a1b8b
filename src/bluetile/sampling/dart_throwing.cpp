// Dart throwing with radius reduction (McCool & Fiume 1992; the paper, section 1.1).
// Acceleration: a uniform grid of buckets, each listing its points; a candidate checks only the
// buckets within the current radius, wrapped around the torus.
#include "bluetile/sampling/dart_throwing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"

namespace bluetile {

void validate(const DartOptions& o) {
  auto whole = [](const char* field, std::size_t v, std::size_t high) {
    if (v < 1 || v > high)
      throw Error(std::string(field) + ": expected 1 to " + std::to_string(high) + ", got " + std::to_string(v));
  };
  auto real = [](const char* field, double v, double low, double high, const char* unit) {
    if (!(v >= low && v <= high))
      throw Error(std::string(field) + ": expected " + shortest_text(low) + " to " + shortest_text(high) + unit + ", got " +
                  shortest_text(v));
  };
  whole("count", o.count, kMaxDartCount);
  whole("max_failures", o.max_failures, kMaxDartFailures);
  real("shrink", o.shrink, kMinDartShrink, kMaxDartShrink, "");
  real("start", o.start, kMinDartStart, kMaxDartStart, " hexagonal spacings");
}

DartResult throw_darts(const DartOptions& o) {
  validate(o);

  const Domain unit;
  DartResult result;
  result.initial_radius = o.start * hexagonal_spacing(static_cast<double>(o.count));
  double radius = std::min(result.initial_radius, 0.5);
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
