// The memory limits a process sets on itself (ulimit -v, ulimit -d) and how much of each it uses
// now, so a run can refuse at the start what would fail, or crash a driver, part way. Linux:
// getrlimit and /proc/self/status.
#pragma once

#include <cstdint>
#include <optional>

namespace bluetile {

struct ProcessLimit {
  std::uint64_t limit = 0;  // bytes (the soft limit)
  std::uint64_t used = 0;   // bytes the process counts against it now; 0 when /proc does not say
  std::uint64_t left() const { return limit > used ? limit - used : 0; }
};

// The address-space limit (ulimit -v, RLIMIT_AS) against the mapped size (VmSize); nullopt when
// there is no limit.
std::optional<ProcessLimit> address_space_limit();

// The data limit (ulimit -d, RLIMIT_DATA) against the data segment (VmData); nullopt when there
// is no limit.
std::optional<ProcessLimit> data_limit();

}  // namespace bluetile
