// Helpers of the raster engine's tests: skipping without Vulkan, engines shared by options
// (contexts and shader JIT are costly), comparisons against the exact engine.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <span>
#include <string>
#include <tuple>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/engine.h"
#include "bluetile/raster/raster_engine.h"
#include "test_support.h"

namespace bluetile::test {

// Empty when a suitable Vulkan device exists, else why not.
const std::string& vulkan_missing_reason();

#define REQUIRE_VULKAN()                                                                                         \
  do {                                                                                                           \
    if (!::bluetile::test::vulkan_missing_reason().empty())                                                      \
      GTEST_SKIP() << "no Vulkan: " << ::bluetile::test::vulkan_missing_reason();                               \
  } while (false)

// A raster engine with these options, shared by the tests of the process (adapt_radius off:
// every call starts afresh). Released before the process exits.
RasterEngine& shared_engine(int resolution, Coverage coverage, ConeShape cone = ConeShape::quad,
                            PixelWork work = PixelWork::automatic, bool force_float32 = false,
                            SplitKernel split = SplitKernel::lane);

// The lane split `engine`'s device does not pick by itself (SplitKernel::lane): five slots on a
// CPU device, three elsewhere. The device path's checks run it too, for the same bits.
SplitKernel other_lane_split(const RasterEngine& engine);

// Where every raster test runs the per-pixel work: on the host (what `auto` picks for area
// coverage on CPU devices) and on the device (the shaders). The two must give the same bits.
inline constexpr PixelWork kPixelPaths[] = {PixelWork::host, PixelWork::device};
std::string pixel_path_name(const ::testing::TestParamInfo<PixelWork>& info);

// Skips the test when the device path cannot run: no Vulkan, or no shaderFloat64 (the device
// path is then the float32 split, whose bound is tested on its own).
void skip_unless_path_runs(PixelWork work);

// Raster tests parameterised by the pixel-work path (instantiate with kPixelPaths). Each
// computation runs on the path under test; on the device path the host path and the other lane
// split (area coverage) compute the same call and the test fails unless the bits agree.
class RasterPaths : public ::testing::TestWithParam<PixelWork> {
 protected:
  void SetUp() override { skip_unless_path_runs(GetParam()); }
  PixelWork work() const { return GetParam(); }
  bool on_device() const { return GetParam() == PixelWork::device; }
  // Options for an engine of the test's own on this path.
  RasterOptions options() const {
    RasterOptions o;
    o.pixel_work = GetParam();
    return o;
  }
  // The cells of `scene` from the shared engine with these options, on this path.
  SceneCells cells(const Scene& scene, int resolution, Coverage coverage, ConeShape cone = ConeShape::quad);
};

// An engine on `work`'s path and, when that is the device, a twin with the same options on the
// host and one with the other lane split (area coverage, SplitKernel::lane): every compute runs
// on all (loops too: it is a CentroidEngine), and a difference in any bit fails the test.
class PathEngine final : public CentroidEngine {
 public:
  PathEngine(RasterOptions options, PixelWork work);
  std::string_view name() const override { return "raster"; }
  using CentroidEngine::compute;
  void compute(std::span<const Scene> scenes, std::span<SceneCells> out) override;
  RasterEngine& engine() { return *engine_; }
  const RasterStats& stats() const { return engine_->stats(); }

 private:
  std::unique_ptr<RasterEngine> engine_, host_, other_split_;
};

struct Errors {
  double mean = 0.0, max = 0.0, max_area = 0.0, max_second = 0.0;
  double total_area = 0.0;
};

// Centroid, area and second-moment differences of a against b, over the wanted cells.
Errors compare_cells(const SceneCells& a, const SceneCells& b, const Scene& scene);

Scene relaxed_scene(std::size_t n, std::uint64_t seed, int iterations);

// `sites` points from `rng` in the 2 x 1 rectangle, the first `fixed` only shaping the cells (the
// shape of the Wang loop's cropped scenes).
Scene fixed_site_rectangle(Rng& rng, std::size_t sites, std::size_t fixed);

struct HardCase {
  const char* name;
  std::vector<Point> sites;
};
// DESIGN section 7's hard cases: one and two sites, a pair 1e-7 apart, sites on 0 and just
// below 1, lattices with ties, a cluster straddling the corner, sites the raster cannot tell
// apart (1e-18 apart, and one ulp apart).
std::vector<HardCase> hard_cases();

}  // namespace bluetile::test
