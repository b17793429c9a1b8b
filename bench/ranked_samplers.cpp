#include "ranked_samplers.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/rng.h"

namespace bluetile::bench {
namespace {

std::uint32_t reverse_bits(std::uint32_t v) {
  std::uint32_t r = 0;
  for (int b = 0; b < 32; ++b) r |= ((v >> b) & 1u) << (31 - b);
  return r;
}

// Sobol's second dimension: bit b of the index contributes the direction number v_b, with
// v_0 = 1/2 and v_b = v_{b-1} xor (v_{b-1} / 2), the columns of the Pascal matrix mod 2.
std::uint32_t sobol_second(std::uint32_t index) {
  std::uint32_t v = 1u << 31, result = 0;
  for (; index != 0; index >>= 1, v ^= v >> 1)
    if (index & 1u) result ^= v;
  return result;
}

// Nested uniform scramble: bit d (from the top) flips when a hash of the seed, d and the d bits
// above it says so; equal leading bits give equal flips, so the net structure is kept.
std::uint32_t owen_scramble(std::uint32_t value, std::uint64_t seed) {
  std::uint32_t result = value;
  for (int d = 0; d < 32; ++d) {
    const std::uint64_t above = d == 0 ? 0 : value >> (32 - d);
    const std::uint64_t key = mix64(seed ^ mix64((static_cast<std::uint64_t>(d) << 32) | above));
    result ^= static_cast<std::uint32_t>(key >> 63) << (31 - d);
  }
  return result;
}

// Points in buckets of the unit torus, for the nearest-distance searches of the candidate
// orders: about two final points a bucket.
class PointBuckets {
 public:
  explicit PointBuckets(std::size_t final_count)
      : side_(std::max(1, static_cast<int>(std::sqrt(static_cast<double>(final_count) / 2.0)))),
        buckets_(static_cast<std::size_t>(side_) * side_) {}

  void add(Point p) { buckets_[static_cast<std::size_t>(bucket_of(p.y)) * side_ + bucket_of(p.x)].push_back(p); }

  // The squared torus distance from q to the nearest point, or any value <= floor as soon as
  // one point that near turns up (the caller only needs to know that q lost).
  double nearest_squared(Point q, double floor) const {
    const int cx = bucket_of(q.x), cy = bucket_of(q.y);
    const double width = 1.0 / side_;
    double nearest = HUGE_VAL;
    // After rings 0..r every point within r bucket widths has been seen.
    for (int r = 0; r <= side_ / 2 + 1; ++r) {
      if (r > 0 && nearest <= (r - 1) * width * ((r - 1) * width)) break;
      for (int dy = -r; dy <= r; ++dy)
        for (int dx = -r; dx <= r; ++dx) {
          if (std::max(std::abs(dx), std::abs(dy)) != r) continue;
          const int x = ((cx + dx) % side_ + side_) % side_, y = ((cy + dy) % side_ + side_) % side_;
          for (const Point& p : buckets_[static_cast<std::size_t>(y) * side_ + x]) {
            double ex = std::abs(p.x - q.x), ey = std::abs(p.y - q.y);
            ex = std::min(ex, 1.0 - ex);
            ey = std::min(ey, 1.0 - ey);
            nearest = std::min(nearest, ex * ex + ey * ey);
            if (nearest <= floor) return nearest;
          }
        }
      if (side_ <= 2 * r + 1) break;  // every bucket seen
    }
    return nearest;
  }

 private:
  int bucket_of(double v) const { return std::min(side_ - 1, static_cast<int>(v * side_)); }

  int side_;
  std::vector<std::vector<Point>> buckets_;
};

}  // namespace

std::vector<Point> owen_sobol_points(std::size_t n, std::uint64_t seed) {
  const std::uint64_t seed_x = derive_seed(seed, 0), seed_y = derive_seed(seed, 1);
  std::vector<Point> points(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto index = static_cast<std::uint32_t>(i);
    points[i] = {std::ldexp(static_cast<double>(owen_scramble(reverse_bits(index), seed_x)), -32),
                 std::ldexp(static_cast<double>(owen_scramble(sobol_second(index), seed_y)), -32)};
  }
  return points;
}

std::vector<Point> best_candidate_points(std::size_t n, std::uint64_t seed, std::size_t candidates_per_point) {
  std::vector<Point> points;
  if (n == 0) return points;
  points.reserve(n);
  Rng rng(seed);
  const Domain torus{};
  PointBuckets buckets(n);
  const auto add = [&](Point p) {
    points.push_back(p);
    buckets.add(p);
  };
  add(rng.point(torus));
  while (points.size() < n) {
    Point best{};
    double best_d2 = -1.0;
    for (std::size_t c = 0, candidates = candidates_per_point * points.size(); c < candidates; ++c) {
      const Point q = rng.point(torus);
      const double d2 = buckets.nearest_squared(q, best_d2);
      if (d2 > best_d2) best_d2 = d2, best = q;
    }
    add(best);
  }
  return points;
}

}  // namespace bluetile::bench
