// Dart throwing on the unit torus with radius reduction, in the spirit of McCool and Fiume 1992
// (the paper's reference [8] and section 1.1; its baseline in Figure 3 and the table of
// section 2). A candidate is accepted when no accepted point lies closer than the current
// radius (torus distance); after `max_failures` rejections in a row the radius shrinks by
// `shrink`. The radius starts at the hexagonal spacing sqrt(2 / (sqrt(3) N)), which no random
// process reaches, so it always shrinks to what the process can fill.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

struct DartOptions {
  std::size_t count = 0;
  std::uint64_t seed = 1;
  // Consecutive rejections before the radius shrinks.
  std::size_t max_failures = 1000;
  // Factor applied to the radius at each reduction, in (0, 1).
  double shrink = 0.99;
  // Starting radius as a multiple of the hexagonal spacing.
  double start = 1.0;
};

// The largest starting radius: half the torus' side. A larger one, which `start` gives for few
// points, would only spend rejections before shrinking to it.
inline constexpr double kMaxDartRadius = 0.5;

struct DartResult {
  std::vector<Point> points;  // exactly `count`, in acceptance order
  double initial_radius = 0.0;  // the radius the throwing started with: `start` spacings, at most kMaxDartRadius
  double final_radius = 0.0;  // no two points are closer than this (torus distance)
  std::size_t trials = 0;     // candidates drawn
  std::size_t reductions = 0; // times the radius shrank
};

// The ranges the tool's options and the Python module's arguments accept. Past a billion
// rejections in a row a run would not end in any time worth waiting for.
inline constexpr std::size_t kMaxDartCount = 100'000'000, kMaxDartFailures = 1'000'000'000;
inline constexpr double kMinDartShrink = 1e-6, kMaxDartShrink = 0.999999;
inline constexpr double kMinDartStart = 1e-6, kMaxDartStart = 4.0;

// Bytes per point of a run, for up-front checks (core/memory_budget.h): the points, the
// acceptance grid and its bookkeeping. Peak resident memory over the points of `dart` from 2e5
// to 4e6 points: 129-138 bytes, rounded up with a margin (64 before, which let through runs
// that then ran out of memory).
inline constexpr double kDartBytesPerPoint = 192.0;

// Throws Error naming the first field out of range ("shrink: expected 1e-06 to 0.999999, got 1").
void validate(const DartOptions& options);

// Deterministic for given options on every platform (core/rng.h). Validates the options first.
DartResult throw_darts(const DartOptions& options);

}  // namespace bluetile
