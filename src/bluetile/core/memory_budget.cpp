#include "bluetile/core/memory_budget.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include "bluetile/core/error.h"
#include "bluetile/core/process_limits.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();

// A "Key:   123 kB" line of a /proc file, in bytes, or kUnlimited when absent.
std::uint64_t proc_kib(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) != 0) continue;
    std::istringstream fields(line.substr(key.size()));
    std::uint64_t kib = 0;
    if (fields >> kib) return kib * 1024;
  }
  return kUnlimited;
}

std::uint64_t read_number(const char* file) {
  std::ifstream in(file);
  std::uint64_t v = 0;
  if (in >> v) return v;
  return kUnlimited;  // absent, or "max"
}

}  // namespace

std::uint64_t available_memory() {
  std::uint64_t available = proc_kib("/proc/meminfo", "MemAvailable:");
  const std::uint64_t cgroup_max = read_number("/sys/fs/cgroup/memory.max");
  const std::uint64_t cgroup_used = read_number("/sys/fs/cgroup/memory.current");
  if (cgroup_max != kUnlimited && cgroup_used != kUnlimited)
    available = std::min(available, cgroup_max > cgroup_used ? cgroup_max - cgroup_used : 0);
  if (const auto limit = address_space_limit()) available = std::min(available, limit->left());
  if (const auto limit = data_limit()) available = std::min(available, limit->left());
  return available;
}

std::string format_bytes(double bytes) {
  const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  int unit = 0;
  while (bytes >= 1024.0 && unit < 6) {
    bytes /= 1024.0;
    ++unit;
  }
  char text[48];
  const ClassicNumbers classic;
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", bytes, units[unit]);
  return text;
}

void check_memory(double needed, const std::string& what) {
  const std::uint64_t available = available_memory();
  if (available == kUnlimited || needed <= static_cast<double>(available)) return;
  throw Error(what + " needs about " + format_bytes(needed) + " of memory, more than the " +
              format_bytes(static_cast<double>(available)) + " available");
}

}  // namespace bluetile
