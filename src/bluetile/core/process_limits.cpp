#include "bluetile/core/process_limits.h"

#include <cstdio>
#include <cstring>

#include <sys/resource.h>

namespace bluetile {
namespace {

// The "Key:   123 kB" field of /proc/self/status in bytes, 0 when absent: counting an unknown
// use as none keeps a check from refusing what the limit allows.
std::uint64_t status_bytes(const char* key) {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  const std::size_t length = std::strlen(key);
  char line[256];
  unsigned long long kib = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, length) == 0 && std::sscanf(line + length, " %llu", &kib) == 1) break;
  std::fclose(f);
  return static_cast<std::uint64_t>(kib) * 1024;
}

std::optional<ProcessLimit> limit_of(int resource, const char* status_key) {
  rlimit limit{};
  if (getrlimit(resource, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return ProcessLimit{static_cast<std::uint64_t>(limit.rlim_cur), status_bytes(status_key)};
}

}  // namespace

std::optional<ProcessLimit> address_space_limit() { return limit_of(RLIMIT_AS, "VmSize:"); }

std::optional<ProcessLimit> data_limit() { return limit_of(RLIMIT_DATA, "VmData:"); }

}  // namespace bluetile
