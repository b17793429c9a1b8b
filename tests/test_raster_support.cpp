// Helpers of the raster engine's tests (see test_raster_support.h), and the validation-layer
// check that runs in every test process: ctest runs each test in a process of its own, so a
// check in one test would only see that test's engines.
#include "test_raster_support.h"

#include <cmath>
#include <cstdlib>
#include <cstring>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/gpu/context.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile::test {
namespace {

// Turns the validation layer on for every engine made in this process (and the tool runs it
// starts) when it is installed.
const bool validation_requested = [] {
  if (!std::getenv("BLUETILE_VALIDATION")) setenv("BLUETILE_VALIDATION", "1", 0);
  return true;
}();

using EngineKey = std::tuple<int, Coverage, ConeShape, PixelWork, bool, SplitKernel>;
std::vector<std::pair<EngineKey, std::unique_ptr<RasterEngine>>>& engines() {
  static std::vector<std::pair<EngineKey, std::unique_ptr<RasterEngine>>> cache;
  return cache;
}

// Registered first, so torn down last: after the engines are gone, every validation message of
// the process has been counted.
class ValidationLayerCheck : public ::testing::Environment {
 public:
  void TearDown() override {
    EXPECT_EQ(gpu::validation_error_count(), 0u) << "the Vulkan validation layer reported errors in this process (see stderr)";
  }
};
[[maybe_unused]] ::testing::Environment* const validation_check = ::testing::AddGlobalTestEnvironment(new ValidationLayerCheck);

// Destroys the shared engines when the tests end: as static objects they would outlive the
// Vulkan driver's and validation layer's own exit-time teardown and crash the process.
class ReleaseSharedEngines : public ::testing::Environment {
 public:
  void TearDown() override { engines().clear(); }
};
[[maybe_unused]] ::testing::Environment* const release_engines = ::testing::AddGlobalTestEnvironment(new ReleaseSharedEngines);

}  // namespace

const std::string& vulkan_missing_reason() {
  static const std::string reason = [] {
    try {
      for (const auto& d : gpu::list_devices())
        if (d.suitable) return std::string();
      return std::string("no suitable Vulkan device");
    } catch (const Error& e) {
      return std::string(e.what());
    }
  }();
  return reason;
}

RasterEngine& shared_engine(int resolution, Coverage coverage, ConeShape cone, PixelWork work, bool force_float32,
                            SplitKernel split) {
  const EngineKey key{resolution, coverage, cone, work, force_float32, split};
  for (auto& [k, e] : engines())
    if (k == key) return *e;
  RasterOptions options;
  options.resolution = resolution;
  options.coverage = coverage;
  options.cone = cone;
  options.pixel_work = work;
  options.force_float32 = force_float32;
  options.split_kernel = split;
  options.adapt_radius = false;
  engines().emplace_back(key, std::make_unique<RasterEngine>(options));
  return *engines().back().second;
}

SplitKernel other_lane_split(const RasterEngine& engine) {
  return engine.cpu_device() ? SplitKernel::lane_five : SplitKernel::lane_three;
}

std::string pixel_path_name(const ::testing::TestParamInfo<PixelWork>& info) {
  return info.param == PixelWork::device ? "device" : "host";
}

void skip_unless_path_runs(PixelWork work) {
  if (!vulkan_missing_reason().empty()) GTEST_SKIP() << "no Vulkan: " << vulkan_missing_reason();
  if (work == PixelWork::device && !shared_engine(64, Coverage::area, ConeShape::quad, PixelWork::host).float64_split())
    GTEST_SKIP() << "the device has no shaderFloat64: its split is the float32 one";
}

SceneCells RasterPaths::cells(const Scene& scene, int resolution, Coverage coverage, ConeShape cone) {
  SceneCells got = shared_engine(resolution, coverage, cone, work()).compute(scene);
  if (on_device()) {
    const SceneCells host = shared_engine(resolution, coverage, cone, PixelWork::host).compute(scene);
    EXPECT_TRUE(identical_cells(got, host)) << "device and host pixel work differ at resolution " << resolution;
    if (coverage == Coverage::area) {
      const SplitKernel other = other_lane_split(shared_engine(resolution, coverage, cone, work()));
      const SceneCells got_other = shared_engine(resolution, coverage, cone, work(), false, other).compute(scene);
      EXPECT_TRUE(identical_cells(got_other, host)) << "the other lane split and the host differ at resolution " << resolution;
    }
  }
  return got;
}

PathEngine::PathEngine(RasterOptions options, PixelWork work) {
  options.pixel_work = work;
  engine_ = std::make_unique<RasterEngine>(options);
  if (work == PixelWork::device) {
    if (options.coverage == Coverage::area && options.split_kernel == SplitKernel::lane) {
      RasterOptions other = options;
      other.split_kernel = other_lane_split(*engine_);
      other_split_ = std::make_unique<RasterEngine>(other);
    }
    options.pixel_work = PixelWork::host;
    host_ = std::make_unique<RasterEngine>(options);
  }
}

void PathEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  engine_->compute(scenes, out);
  if (!host_) return;
  std::vector<SceneCells> host(scenes.size());
  host_->compute(scenes, host);
  for (std::size_t k = 0; k < scenes.size(); ++k)
    EXPECT_TRUE(identical_cells(out[k], host[k])) << "device and host pixel work differ in scene " << k;
  if (!other_split_) return;
  std::vector<SceneCells> other(scenes.size());
  other_split_->compute(scenes, other);
  for (std::size_t k = 0; k < scenes.size(); ++k)
    EXPECT_TRUE(identical_cells(other[k], host[k])) << "the other lane split and the host differ in scene " << k;
}

Errors compare_cells(const SceneCells& a, const SceneCells& b, const Scene& scene) {
  Errors e;
  EXPECT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.cells.size() && i < b.cells.size(); ++i) {
    const double d = torus_distance(a.cells[i].centroid, b.cells[i].centroid, scene.domain);
    e.mean += d;
    e.max = std::max(e.max, d);
    e.max_area = std::max(e.max_area, std::abs(a.cells[i].area - b.cells[i].area));
    e.max_second = std::max(e.max_second, std::abs(a.cells[i].second_moment - b.cells[i].second_moment));
    e.total_area += a.cells[i].area;
  }
  if (!a.cells.empty()) e.mean /= static_cast<double>(a.cells.size());
  return e;
}

Scene fixed_site_rectangle(Rng& rng, std::size_t sites, std::size_t fixed) {
  Scene scene;
  scene.domain.size = {2.0, 1.0};
  for (std::size_t k = 0; k < sites; ++k) scene.sites.push_back(rng.point(scene.domain));
  scene.wanted_begin = fixed;
  scene.wanted_end = sites;
  return scene;
}

Scene relaxed_scene(std::size_t n, std::uint64_t seed, int iterations) {
  Scene scene = make_scene(uniform_points(n, seed));
  ExactEngine exact;
  LloydOptions options;
  options.iterations = iterations;
  relax_lloyd(exact, scene, options);
  return scene;
}

std::vector<HardCase> hard_cases() {
  std::vector<HardCase> cases;
  cases.push_back({"one site", {{0.3, 0.7}}});
  cases.push_back({"two sites", {{0.25, 0.5}, {0.75, 0.5}}});
  cases.push_back({"two sites diagonal", {{0.1, 0.2}, {0.6, 0.7}}});
  cases.push_back({"pair 1e-7 apart", {{0.5, 0.5}, {0.5 + 1e-7, 0.5}, {0.1, 0.1}, {0.8, 0.3}, {0.3, 0.85}}});
  cases.push_back({"on 0 and just below 1", {{0.0, 0.0}, {std::nextafter(1.0, 0.0), 0.5}, {0.5, std::nextafter(1.0, 0.0)}, {0.4, 0.4}}});
  std::vector<Point> square;
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) square.push_back({(i + 0.5) / 8.0, (j + 0.5) / 8.0});
  cases.push_back({"square lattice", square});
  std::vector<Point> tenths;  // bisectors on non-dyadic lines: ties in real arithmetic only
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) tenths.push_back({(i + 0.5) / 10.0, (j + 0.5) / 10.0});
  cases.push_back({"10 x 10 lattice", tenths});
  std::vector<Point> hex;  // rows offset by half a spacing
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) hex.push_back({(i + 0.5 * (j % 2) + 0.25) / 8.0, (j + 0.5) / 8.0});
  cases.push_back({"offset rows lattice", hex});
  std::vector<Point> cluster;
  Rng rng(11);
  for (int k = 0; k < 200; ++k)
    cluster.push_back(wrap_point({0.99 + 0.02 * rng.uniform(), 0.995 + 0.01 * rng.uniform()}, Domain{}));
  cases.push_back({"cluster straddling the corner", cluster});
  // Distinct sites closer than float depths (or pixel-centre offsets) can separate.
  cases.push_back({"sites 1e-18 apart", {{0.5, 0.5}, {0.25, 0.75}, {1e-18, 0.5}, {2e-18, 0.5}}});
  cases.push_back({"sites one ulp apart", {{0.001, 0.3}, {std::nextafter(0.001, 1.0), 0.3}, {0.6, 0.7}, {0.4, 0.1}}});
  return cases;
}

}  // namespace bluetile::test
