// The up-front memory checks (core/memory_budget.h) refuse a run whose estimate exceeds the
// memory available, so an estimate below what the run takes lets it start and be killed for
// memory later. Each run here is measured (its peak resident memory, less that of a tiny run of
// the tool, which is already resident when the check reads what is available) against the
// estimate the tool checks, at sizes where the per-point costs dominate.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "bluetile/relax/band_fill.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/sampling/dart_throwing.h"
#include "robustness_support.h"
#include "test_support.h"

namespace bluetile::robustness {
namespace {

using test::TempDir;

// Peak resident bytes of the tool running `arguments` (which must succeed).
double peak_bytes(std::vector<std::string> arguments) {
  const Outcome r = run(std::move(arguments));
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return static_cast<double>(r.max_resident_kib) * 1024.0;
}

class MemoryEstimates : public ::testing::Test {
 protected:
  void SetUp() override {
    // The sanitizer's shadow memory and quarantine would be measured too.
    if (sanitized()) GTEST_SKIP() << "built with the address sanitizer";
    base_ = peak_bytes({"relax", "-n", "16", "-k", "0", "--engine", "exact", "-o", out()});
  }
  std::string out() const { return dir_.file("points.txt"); }

  // The run's own memory, as the check's estimate covers it, within [estimate / 4, estimate]:
  // under it, or the check lets through runs that die for memory; not far over, or it refuses
  // runs that fit.
  void expect_within_estimate(const std::vector<std::string>& arguments, double estimate) {
    const double used = peak_bytes(arguments) - base_;
    std::string command;
    for (const auto& a : arguments) command += a + " ";
    EXPECT_LE(used, estimate) << command << ": " << used / 1e6 << " MB used, " << estimate / 1e6 << " MB estimated";
    EXPECT_GE(used, estimate / 4) << command << ": " << used / 1e6 << " MB used, " << estimate / 1e6
                                  << " MB estimated";
  }

  TempDir dir_;
  double base_ = 0.0;
};

TEST_F(MemoryEstimates, RelaxOnTheExactEngineStaysUnderItsEstimate) {
  expect_within_estimate({"relax", "-n", "200000", "-k", "2", "--engine", "exact", "-o", out()},
                         relax_memory_bytes(200000, "exact"));
  expect_within_estimate({"relax", "-n", "50000", "--sets", "4", "-k", "2", "--engine", "exact", "-o", out()},
                         relax_memory_bytes(4 * 50000, "exact"));
}

TEST_F(MemoryEstimates, RelaxOnTheRasterEngineStaysUnderItsEstimate) {
  // The Vulkan device (lavapipe here) is made after the check: its memory is in the estimate.
  expect_within_estimate({"relax", "-n", "100000", "-k", "1", "--engine", "raster", "-o", out()},
                         relax_memory_bytes(100000, "raster"));
}

TEST_F(MemoryEstimates, DartThrowingStaysUnderItsEstimate) {
  expect_within_estimate({"dart", "-n", "100000", "-o", out()}, 100000 * kDartBytesPerPoint);
}

TEST_F(MemoryEstimates, ProgressiveLevelsStayUnderTheirEstimate) {
  // 25000 points and three doublings: 200000 points, each level relaxed around the earlier ones.
  expect_within_estimate({"progressive", "--count", "25000", "--levels", "4", "--ratio", "2", "--engine", "exact",
                          "-k", "2", "-o", out()},
                         progressive_memory_bytes(200000, "exact"));
  // The fill order: its grid besides the points.
  const double filled = 8 * 1500;
  expect_within_estimate({"progressive", "--count", "1500", "--levels", "4", "--ratio", "2", "--rank-order", "fill",
                          "-o", out()},
                         progressive_memory_bytes(filled, "exact") +
                             band_fill_cost(0, static_cast<std::size_t>(filled), 1, FillOptions{}).bytes);
}

}  // namespace
}  // namespace bluetile::robustness
