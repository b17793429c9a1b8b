// A seeded random number generator whose output is the same on every platform and compiler.
// std:: distributions are implementation-defined, so all sampling goes through these few
// functions instead. Engine: xoshiro256** (Blackman & Vigna), seeded by SplitMix64.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

class Rng {
 public:
  explicit Rng(std::uint64_t seed);

  std::uint64_t next_u64();
  // Uniform in [0, 1) with 53 random bits.
  double uniform();
  // Uniform integer in [0, bound), bound > 0, without modulo bias. Throws Error for bound 0 (it
  // divided by zero).
  std::uint64_t below(std::uint64_t bound);
  // Uniform point in the domain. Throws Error for a domain check_domain refuses (a zero, negative
  // or NaN side gave NaN or zero coordinates).
  Point point(const Domain& domain);

 private:
  std::uint64_t state_[4];
};

// SplitMix64's finaliser: a bijective mix whose every output bit depends on every input bit
// (the seeding of Rng, and the tilers' hashes of cells and edges).
std::uint64_t mix64(std::uint64_t z);

// A seed for stream `index` derived from a user seed, so that set k of a batch does not
// depend on how many sets come before it.
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t index);

// The random start of set `set` of `bluetile relax --count N --seed S` (and of the Python
// module's relax): `count` uniform points on the unit torus from Rng(derive_seed(seed, set)),
// so set k of a batch does not depend on how many sets the batch has. Throws Error above
// kMaxSetPoints (check_set_points).
std::vector<Point> uniform_random_points(std::size_t count, std::uint64_t seed, std::uint64_t set = 0);

}  // namespace bluetile
