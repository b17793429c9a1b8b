// Limits and defaults of a request, the same in the tool and the Python module.
#pragma once

#include <cstddef>

namespace bluetile {

// Beyond these a value is almost surely a typo, and would need tens of GiB or years.
inline constexpr std::size_t kMaxSetPoints = 100'000'000;  // points in one set (relax, stipple, a level)
inline constexpr std::size_t kMaxSets = 10'000'000;        // sets of one relax run
inline constexpr int kMaxIterations = 100'000'000;         // Lloyd iterations

inline constexpr int kDefaultIterations = 80;         // relax, and each level of progressive
inline constexpr int kDefaultStippleIterations = 50;  // stipple

}  // namespace bluetile
