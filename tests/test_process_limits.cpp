// core/process_limits.h against getrlimit/setrlimit and an independent reading of
// /proc/self/status: the limit is the soft limit set, the use is VmSize, left is their difference.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>

#include <sys/resource.h>

#include "bluetile/core/process_limits.h"

namespace bluetile {
namespace {

std::uint64_t vm_size_bytes() {
  std::ifstream in("/proc/self/status");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("VmSize:", 0) != 0) continue;
    std::istringstream fields(line.substr(7));
    std::uint64_t kib = 0;
    fields >> kib;
    return kib * 1024;
  }
  return 0;
}

TEST(ProcessLimits, AddressSpaceLimitIsTheSoftLimitAgainstTheMappedSize) {
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_AS, &saved), 0);
  if (saved.rlim_cur == RLIM_INFINITY) {
    EXPECT_FALSE(address_space_limit().has_value());
  }

  // A soft limit far above what the process maps (the sanitizers map terabytes), restored at once.
  const std::uint64_t used = vm_size_bytes();
  ASSERT_GT(used, 0u);
  rlim_t soft = static_cast<rlim_t>(used + (std::uint64_t{1} << 40));
  if (saved.rlim_max != RLIM_INFINITY && soft > saved.rlim_max) soft = saved.rlim_max;
  rlimit lowered = saved;
  lowered.rlim_cur = soft;
  ASSERT_EQ(setrlimit(RLIMIT_AS, &lowered), 0);
  const std::optional<ProcessLimit> limit = address_space_limit();
  ASSERT_EQ(setrlimit(RLIMIT_AS, &saved), 0);

  ASSERT_TRUE(limit.has_value());
  EXPECT_EQ(limit->limit, static_cast<std::uint64_t>(soft));
  // The mapped size moves a little between the two readings (gtest and the allocator map pages).
  EXPECT_NEAR(static_cast<double>(limit->used), static_cast<double>(used), 64.0 * (1 << 20));
  EXPECT_EQ(limit->left(), limit->limit > limit->used ? limit->limit - limit->used : 0);
}

TEST(ProcessLimits, LeftIsNeverNegative) {
  EXPECT_EQ((ProcessLimit{100, 40}.left()), 60u);
  EXPECT_EQ((ProcessLimit{100, 100}.left()), 0u);
  EXPECT_EQ((ProcessLimit{100, 250}.left()), 0u);
}

}  // namespace
}  // namespace bluetile
