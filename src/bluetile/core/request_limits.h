// Limits and defaults of a request, the same in the tool and the Python module.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "bluetile/core/error.h"

namespace bluetile {

// Beyond these a value is almost surely a typo, and would need tens of GiB or years.
inline constexpr std::size_t kMaxSetPoints = 100'000'000;  // points in one set (relax, stipple, a level)
inline constexpr std::size_t kMaxSets = 10'000'000;        // sets of one relax run
inline constexpr int kMaxIterations = 100'000'000;         // Lloyd iterations

// Throws Error("<what> 200000000: expected at most 100000000 points") above kMaxSetPoints, where a
// vector of that many points would fail with std::length_error or std::bad_alloc, naming nothing.
inline void check_set_points(std::size_t count, std::string_view what) {
  if (count > kMaxSetPoints)
    throw Error(std::string(what) + " " + std::to_string(count) + ": expected at most " + std::to_string(kMaxSetPoints) +
                " points");
}

inline constexpr int kDefaultIterations = 80;         // relax, and each level of progressive
inline constexpr int kDefaultStippleIterations = 50;  // stipple

}  // namespace bluetile
