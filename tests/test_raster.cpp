// The raster engine against the exact engine, hard cases, determinism, the coverage check and
// the validation layer. Every test here needs a Vulkan device; without one they skip (lavapipe
// is installed on CI and developer machines, so there they run).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/gpu/context.h"
#include "bluetile/relax/lloyd.h"
#include "test_support.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/raster_engine.h"

namespace bluetile {
namespace {

using test::uniform_points;

// Turns the validation layer on for every engine made in this process when it is installed.
const bool validation_requested = [] {
  if (!std::getenv("BLUETILE_VALIDATION")) setenv("BLUETILE_VALIDATION", "1", 0);
  return true;
}();

std::string vulkan_missing_reason() {
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

#define REQUIRE_VULKAN()                                                          \
  do {                                                                            \
    if (!vulkan_missing_reason().empty()) GTEST_SKIP() << "no Vulkan: " << vulkan_missing_reason(); \
  } while (false)

// Engines are costly to make (context, shader JIT), so tests share them by options.
using EngineCache = std::vector<std::pair<std::tuple<int, Coverage, ConeShape>, std::unique_ptr<RasterEngine>>>;
EngineCache& shared_engines() {
  static EngineCache engines;
  return engines;
}

// Destroys the shared engines when the tests end: as static objects they would outlive the
// Vulkan driver's and validation layer's own exit-time teardown and crash the process.
class ReleaseSharedEngines : public ::testing::Environment {
 public:
  void TearDown() override { shared_engines().clear(); }
};
[[maybe_unused]] ::testing::Environment* const release_shared_engines =
    ::testing::AddGlobalTestEnvironment(new ReleaseSharedEngines);

RasterEngine& engine(int resolution, Coverage coverage, ConeShape cone = ConeShape::quad) {
  EngineCache& engines = shared_engines();
  auto key = std::make_tuple(resolution, coverage, cone);
  for (auto& [k, e] : engines)
    if (k == key) return *e;
  RasterOptions options;
  options.resolution = resolution;
  options.coverage = coverage;
  options.cone = cone;
  options.adapt_radius = false;  // every test call starts afresh
  engines.emplace_back(key, std::make_unique<RasterEngine>(options));
  return *engines.back().second;
}

struct Errors {
  double mean = 0.0, max = 0.0, max_area = 0.0;
};

Errors compare(const SceneCells& a, const SceneCells& b, const Scene& scene) {
  Errors e;
  EXPECT_EQ(a.cells.size(), b.cells.size());
  for (std::size_t i = 0; i < a.cells.size(); ++i) {
    double d = torus_distance(a.cells[i].centroid, b.cells[i].centroid, scene.domain);
    e.mean += d;
    e.max = std::max(e.max, d);
    e.max_area = std::max(e.max_area, std::abs(a.cells[i].area - b.cells[i].area));
  }
  if (!a.cells.empty()) e.mean /= static_cast<double>(a.cells.size());
  return e;
}

Errors raster_vs_exact(const Scene& scene, int resolution, Coverage coverage, ConeShape cone = ConeShape::quad) {
  SceneCells exact = ExactEngine().compute(scene);
  SceneCells raster = engine(resolution, coverage, cone).compute(scene);
  return compare(raster, exact, scene);
}

Scene relaxed_scene(std::size_t n, std::uint64_t seed, int iterations) {
  Scene scene = make_scene(uniform_points(n, seed));
  ExactEngine exact;
  LloydOptions options;
  options.iterations = iterations;
  relax_lloyd(exact, scene, options);
  return scene;
}

TEST(Raster, PointErrorShrinksWithResolution) {
  REQUIRE_VULKAN();
  Scene scene = make_scene(uniform_points(1000, 3));
  Errors low = raster_vs_exact(scene, 256, Coverage::point);
  Errors high = raster_vs_exact(scene, 1024, Coverage::point);
  // Measured: mean 4.4e-4 at 256^2 and 4.7e-5 at 1024^2 (DESIGN section 3: 4.8e-5).
  EXPECT_LT(low.mean, 8e-4) << low.mean;
  EXPECT_LT(high.mean, 1e-4) << high.mean;
  EXPECT_LT(high.mean, 0.3 * low.mean);
  EXPECT_LT(high.max, 1.5e-3) << high.max;
}

TEST(Raster, AreaCoverageIsExactToRounding) {
  REQUIRE_VULKAN();
  Scene uniform = make_scene(uniform_points(1000, 4));
  Scene relaxed = relaxed_scene(1000, 5, 20);
  for (int resolution : {32, 64, 128, 256}) {
    for (const Scene* scene : {&uniform, &relaxed}) {
      Errors area = raster_vs_exact(*scene, resolution, Coverage::area);
      EXPECT_LT(area.max, 1e-9) << "resolution " << resolution;
      EXPECT_LT(area.max_area, 1e-12) << "resolution " << resolution;
    }
  }
  Errors point = raster_vs_exact(uniform, 256, Coverage::point);
  Errors area = raster_vs_exact(uniform, 256, Coverage::area);
  EXPECT_LT(area.mean * 1e6, point.mean) << area.mean << " vs " << point.mean;
}

TEST(Raster, TessellatedFanIsBiasedQuadIsNot) {
  REQUIRE_VULKAN();
  Scene scene = make_scene(uniform_points(1000, 6));
  Errors fan = raster_vs_exact(scene, 512, Coverage::point, ConeShape::fan);
  Errors quad = raster_vs_exact(scene, 512, Coverage::point, ConeShape::quad);
  EXPECT_LT(fan.max, 5e-3);
  EXPECT_LT(quad.mean, fan.mean);
  // Area coverage splits pixels by exact bisectors, so with the fan it is as exact as the
  // fan's ID buffer allows candidates: still exact here.
  Errors fan_area = raster_vs_exact(scene, 128, Coverage::area, ConeShape::fan);
  EXPECT_LT(fan_area.max, 1e-9);
}

struct HardCase {
  const char* name;
  std::vector<Point> sites;
};

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
  std::vector<Point> hex;  // 8 x 8 sites, rows offset by half a spacing; a torus of 8 x 4 sqrt(3)/... approximated
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) hex.push_back({(i + 0.5 * (j % 2) + 0.25) / 8.0, (j + 0.5) / 8.0});
  cases.push_back({"offset rows (hexagonal-like) lattice", hex});
  std::vector<Point> cluster;
  Rng rng(11);
  for (int k = 0; k < 200; ++k)
    cluster.push_back(wrap_point({0.99 + 0.02 * rng.uniform(), 0.995 + 0.01 * rng.uniform()}, Domain{}));
  cases.push_back({"cluster straddling the corner", cluster});
  return cases;
}

TEST(Raster, HardCasesAgreeWithTheExactEngine) {
  REQUIRE_VULKAN();
  for (const HardCase& c : hard_cases()) {
    Scene scene = make_scene(c.sites);
    SceneCells exact = ExactEngine().compute(scene);
    for (int resolution : {64, 256}) {
      SceneCells area = engine(resolution, Coverage::area).compute(scene);
      Errors e = compare(area, exact, scene);
      EXPECT_LT(e.max, 1e-9) << c.name << " at " << resolution;
      EXPECT_LT(e.max_area, 1e-12) << c.name << " at " << resolution;
      for (std::size_t i = 0; i < area.cells.size(); ++i) {
        EXPECT_TRUE(std::isfinite(area.cells[i].centroid.x) && std::isfinite(area.cells[i].centroid.y)) << c.name;
        EXPECT_NEAR(area.cells[i].second_moment, exact.cells[i].second_moment, 1e-12) << c.name << " site " << i;
      }
      SceneCells point = engine(resolution, Coverage::point).compute(scene);
      Errors p = compare(point, exact, scene);
      // Point coverage cannot see features below a pixel: bound it only where there are none.
      bool sub_pixel = std::string(c.name).find("pair") != std::string::npos ||
                       std::string(c.name).find("cluster") != std::string::npos;
      if (!sub_pixel) {
        EXPECT_LT(p.max, 2.0 / resolution) << c.name << " at " << resolution;
      }
      for (const Cell& cell : point.cells) EXPECT_TRUE(std::isfinite(cell.centroid.x) && std::isfinite(cell.area)) << c.name;
    }
  }
}

TEST(Raster, LatticesAreFixedPoints) {
  REQUIRE_VULKAN();
  std::vector<Point> square;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) square.push_back({(i + 0.5) / 16.0, (j + 0.5) / 16.0});
  Scene scene = make_scene(square);
  SceneCells cells = engine(128, Coverage::area).compute(scene);
  for (std::size_t i = 0; i < square.size(); ++i) {
    EXPECT_LT(torus_distance(cells.cells[i].centroid, square[i], scene.domain), 1e-12) << i;
    EXPECT_NEAR(cells.cells[i].area, 1.0 / 256.0, 1e-15);
  }
}

TEST(Raster, CoincidentAndPixellessCellsAreReported) {
  REQUIRE_VULKAN();
  std::vector<Point> sites = uniform_points(50, 12);
  sites.push_back(sites[7]);  // coincides with site 7: site 50 is reported, 7 keeps the cell
  sites.push_back({0.5, 0.5});  // site 51: ringed by six sites 1e-4 away, its cell owns no pixel
  for (int k = 0; k < 6; ++k) sites.push_back({0.5 + 1e-4 * std::cos(k * 1.0471975511965976), 0.5 + 1e-4 * std::sin(k * 1.0471975511965976)});
  Scene scene = make_scene(sites);
  SceneCells exact = ExactEngine().compute(scene);
  for (Coverage coverage : {Coverage::area, Coverage::point}) {
    SceneCells cells = engine(64, coverage).compute(scene);
    EXPECT_EQ(cells.coincident_count, 1u);
    EXPECT_EQ(cells.cells[50].status, CellStatus::coincident);
    EXPECT_EQ(cells.cells[50].centroid, sites[50]);
    EXPECT_EQ(cells.cells[50].area, 0.0);
    EXPECT_GE(cells.fallback_count, 1u);
    EXPECT_EQ(cells.cells[51].status, CellStatus::exact_fallback);
    EXPECT_LT(torus_distance(cells.cells[51].centroid, exact.cells[51].centroid, scene.domain), 1e-12);
    EXPECT_NEAR(cells.cells[51].area, exact.cells[51].area, 1e-15);
    if (coverage == Coverage::area) {
      EXPECT_LT(compare(cells, exact, scene).max, 1e-9);
    }
  }
}

TEST(Raster, RectangularDomainAndFixedSites) {
  REQUIRE_VULKAN();
  Scene scene;
  scene.domain.size = {2.0, 1.0};
  Rng rng(13);
  for (int k = 0; k < 300; ++k) scene.sites.push_back(rng.point(scene.domain));
  scene.wanted_begin = 100;
  scene.wanted_end = 300;
  SceneCells exact = ExactEngine().compute(scene);
  SceneCells area = engine(64, Coverage::area).compute(scene);
  ASSERT_EQ(area.cells.size(), 200u);
  EXPECT_LT(compare(area, exact, scene).max, 1e-9);
}

TEST(Raster, BatchEqualsOneByOne) {
  REQUIRE_VULKAN();
  std::vector<Scene> scenes;
  for (std::uint64_t k = 0; k < 5; ++k) scenes.push_back(make_scene(uniform_points(20 + 40 * k, 100 + k)));
  for (Coverage coverage : {Coverage::area, Coverage::point}) {
    RasterEngine& e = engine(0, coverage);
    std::vector<SceneCells> batch(scenes.size());
    e.compute(scenes, batch);
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      SceneCells one = e.compute(scenes[k]);
      ASSERT_EQ(one.cells.size(), batch[k].cells.size());
      for (std::size_t i = 0; i < one.cells.size(); ++i) {
        EXPECT_EQ(one.cells[i].centroid, batch[k].cells[i].centroid) << "scene " << k << " site " << i;
        EXPECT_EQ(one.cells[i].area, batch[k].cells[i].area);
      }
    }
  }
}

TEST(Raster, UncoveredPixelsAreDetectedAndRepaired) {
  REQUIRE_VULKAN();
  RasterOptions options;
  options.resolution = 128;
  options.radius_factor = 0.1;  // far too small: most pixels are uncovered at first
  options.adapt_radius = false;
  RasterEngine small(options);
  Scene scene = make_scene(uniform_points(500, 14));
  SceneCells cells = small.compute(scene);
  EXPECT_GT(small.stats().redone_scenes, 0u);
  EXPECT_GT(small.stats().uncovered_pixels, 0u);
  EXPECT_LT(compare(cells, ExactEngine().compute(scene), scene).max, 1e-9);
}

TEST(Raster, AdaptiveRadiiFollowARelaxation) {
  REQUIRE_VULKAN();
  RasterOptions options;
  options.resolution = 96;
  RasterEngine raster(options);
  ExactEngine exact;
  Scene a = make_scene(uniform_points(400, 15)), b = a;
  LloydOptions lloyd;
  lloyd.iterations = 15;
  relax_lloyd(raster, a, lloyd);
  relax_lloyd(exact, b, lloyd);
  for (std::size_t i = 0; i < a.sites.size(); ++i) EXPECT_LT(torus_distance(a.sites[i], b.sites[i], a.domain), 1e-9);
  // The radii come from the last pass: after the first pass, redos are rare.
  EXPECT_LE(raster.stats().redone_scenes, 3u);
}

TEST(Raster, ResolutionBeyondTheDeviceIsAClearError) {
  REQUIRE_VULKAN();
  RasterOptions options;
  options.resolution = 1 << 20;
  RasterEngine huge(options);
  try {
    huge.compute(make_scene(uniform_points(10, 1)));
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("exceeds the device's limit"), std::string::npos) << e.what();
  }
}

// Runs relax through the CLI with LP_NUM_THREADS and --threads set, returns the output file.
std::string relax_output(const test::TempDir& dir, const std::string& name, const char* lp_threads,
                         const std::vector<std::string>& extra) {
  setenv("LP_NUM_THREADS", lp_threads, 1);
  std::vector<std::string> args = {"relax", "-n", "300", "-k", "6", "--seed", "21", "-o", dir.file(name)};
  args.insert(args.end(), extra.begin(), extra.end());
  test::CommandResult r = test::run_bluetile(args);
  unsetenv("LP_NUM_THREADS");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return test::read_text(dir.file(name));
}

TEST(Raster, BitIdenticalAcrossRunsAndThreadCounts) {
  REQUIRE_VULKAN();
  test::TempDir dir;
  for (const char* coverage : {"area", "point"}) {
    std::vector<std::string> one = {"--coverage", coverage, "--resolution", "128", "--threads", "1"};
    std::vector<std::string> two = {"--coverage", coverage, "--resolution", "128", "--threads", "2"};
    std::string a = relax_output(dir, "a.txt", "1", one);
    std::string b = relax_output(dir, "b.txt", "2", two);
    std::string c = relax_output(dir, "c.txt", "2", two);
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, b) << coverage;
    EXPECT_EQ(b, c) << coverage;
  }
}

TEST(Raster, DevicesCommandAndIdImage) {
  REQUIRE_VULKAN();
  test::CommandResult r = test::run_bluetile({"devices"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("type"), std::string::npos) << r.out;
  test::TempDir dir;
  r = test::run_bluetile({"relax", "-n", "100", "-k", "3", "-o", dir.file("p.txt"), "--id-image", dir.file("cells.png")});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("cells.png")));
  EXPECT_GT(std::filesystem::file_size(dir.file("cells.png")), 100u);
  r = test::run_bluetile({"relax", "-n", "10", "-k", "1", "-o", dir.file("q.txt"), "--device", "no-such-device"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("no-such-device"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("q.txt")));
}

// Last in this file: every engine above ran with the validation layer when it is installed.
TEST(Raster, ValidationLayerReportedNoErrors) {
  REQUIRE_VULKAN();
  engine(64, Coverage::area).compute(make_scene(uniform_points(100, 2)));
  EXPECT_EQ(gpu::validation_error_count(), 0u);
}

}  // namespace
}  // namespace bluetile
