// What a run will need, checked before it starts: a mistyped --count or --sets is refused with
// the estimate instead of running for hours into an out-of-memory kill.
#pragma once

#include <cstdint>
#include <string>

namespace bluetile::cli {

// Bytes this process may still allocate: the least of the memory the system reports available
// (MemAvailable), the cgroup's limit less its use, and the address-space and data limits
// (ulimit -v, -d) less what the process already maps.
std::uint64_t available_memory();

// "1.5 GiB"
std::string format_bytes(double bytes);

// Throws Error("<what> needs about X of memory, more than the Y available") when `needed`
// exceeds available_memory().
void check_memory(double needed, const std::string& what);

// Bytes per site of a relaxation, beyond the points themselves: the scene's copy, the cell
// results, the engine's search grid and per-site state. Measured (peak RSS of `relax -n 1000000
// -k 2`, both engines, divided by N) and rounded up.
inline constexpr double kRelaxBytesPerSite = 160.0;

}  // namespace bluetile::cli
