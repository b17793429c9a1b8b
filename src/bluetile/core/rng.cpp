#include "bluetile/core/rng.h"

#include "bluetile/core/error.h"
#include "bluetile/core/request_limits.h"

namespace bluetile {
namespace {

std::uint64_t splitmix64(std::uint64_t& x) { return mix64(x += 0x9E3779B97F4A7C15ull); }

std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

Rng::Rng(std::uint64_t seed) {
  for (auto& s : state_) s = splitmix64(seed);
}

std::uint64_t Rng::next_u64() {
  std::uint64_t result = rotl(state_[1] * 5, 7) * 9;
  std::uint64_t t = state_[1] << 17;
  state_[2] ^= state_[0];
  state_[3] ^= state_[1];
  state_[1] ^= state_[2];
  state_[0] ^= state_[3];
  state_[2] ^= t;
  state_[3] = rotl(state_[3], 45);
  return result;
}

double Rng::uniform() { return static_cast<double>(next_u64() >> 11) * 0x1.0p-53; }

std::uint64_t Rng::below(std::uint64_t bound) {
  if (bound == 0) throw Error("bound 0: expected at least 1 (no integer lies in [0, 0))");
  // Rejection keeps every value equally likely: drop the top partial copy of [0, bound).
  std::uint64_t limit = bound * (UINT64_MAX / bound);
  for (;;) {
    std::uint64_t r = next_u64();
    if (r < limit) return r % bound;
  }
}

Point Rng::point(const Domain& domain) {
  check_domain(domain, "random point");
  double x = uniform() * domain.size.x;
  double y = uniform() * domain.size.y;
  // uniform() < 1, but the product can round up to the period for non-unit domains.
  return wrap_point({x, y}, domain);
}

std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t x = seed ^ (0xD1B54A32D192ED03ull * (index + 1));
  splitmix64(x);
  return splitmix64(x);
}

std::vector<Point> uniform_random_points(std::size_t count, std::uint64_t seed, std::uint64_t set) {
  check_set_points(count, "uniform random points: count");
  Rng rng(derive_seed(seed, set));
  std::vector<Point> points(count);
  for (Point& p : points) p = rng.point(Domain{});
  return points;
}

}  // namespace bluetile
