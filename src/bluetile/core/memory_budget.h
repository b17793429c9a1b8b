// What a run will need, checked before it starts: a mistyped count is refused with the estimate
// instead of running for hours into an out-of-memory kill (the tool) or a bare MemoryError after
// seconds of work (the Python module). Both front ends call this one check; the estimates live
// next to what they measure (relax_memory_bytes in relax/lloyd.h, kDartBytesPerPoint in
// sampling/dart_throwing.h, summary_memory_bytes in analysis/summary.h).
#pragma once

#include <cstdint>
#include <string>

namespace bluetile {

// Bytes this process may still allocate: the least of the memory the system reports available
// (MemAvailable), the cgroup's limit less its use, and the address-space and data limits
// (ulimit -v, -d) less what the process already maps.
std::uint64_t available_memory();

// "1.5 GiB"
std::string format_bytes(double bytes);

// Throws Error("<what> needs about X of memory, more than the Y available") when `needed`
// exceeds available_memory().
void check_memory(double needed, const std::string& what);

}  // namespace bluetile
