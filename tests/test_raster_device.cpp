// The raster engine's device passes (classify.comp, split_lane_f64.comp, split_f64.comp,
// split_f32.comp) against the host reference (raster_reference.cpp): the same per-site sums bit
// for bit on an IEEE device (lavapipe), on uniform and relaxed sets and every hard case; the
// host path against the device path; the float32 split within its stated bound; determinism
// across rasterizer threads; where `auto` runs the per-pixel work.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <memory>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "bluetile/raster/raster_device.h"
#include "bluetile/raster/raster_reference.h"
#include "test_raster_support.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::compare_cells;
using test::Errors;
using test::uniform_points;

std::vector<Scene> device_scenes() {
  std::vector<Scene> scenes;
  scenes.push_back(make_scene(uniform_points(300, 51)));
  scenes.push_back(test::relaxed_scene(300, 52, 10));
  for (const test::HardCase& c : test::hard_cases()) scenes.push_back(make_scene(c.sites));
  // Coincident sites: the later one is set aside, the earlier one keeps the cell.
  std::vector<Point> coincident = uniform_points(80, 60);
  coincident.push_back(coincident[3]);
  coincident.push_back(coincident[40]);
  scenes.push_back(make_scene(std::move(coincident)));
  // A rectangle with fixed sites (the shape of the Wang loop's cropped scenes: context sites
  // shape the cells, only the wanted ones are measured), and a cluster dense enough that some
  // pixels go to the host.
  Rng rng(56);
  scenes.push_back(test::fixed_site_rectangle(rng, 400, 150));
  std::vector<Point> cluster = uniform_points(200, 57);
  for (int k = 0; k < 300; ++k) cluster.push_back({0.3 + 0.02 * rng.uniform(), 0.6 + 0.02 * rng.uniform()});
  scenes.push_back(make_scene(std::move(cluster)));
  return scenes;
}

bool same_sums(const gpu::SiteSums& a, const gpu::SiteSums& b) {
  return a.sum_x == b.sum_x && a.sum_y == b.sum_y && a.sum_xx == b.sum_xx && a.sum_yy == b.sum_yy &&
         a.piece_area == b.piece_area && a.piece_x == b.piece_x && a.piece_y == b.piece_y && a.piece_second == b.piece_second &&
         a.count == b.count && a.owned == b.owned && a.farthest == b.farthest;
}

TEST(RasterDevice, SumsMatchTheHostReferenceBitForBit) {
  REQUIRE_VULKAN();
  for (Coverage coverage : {Coverage::area, Coverage::point})
  for (SplitKernel kernel : {SplitKernel::lane_three, SplitKernel::lane_five, SplitKernel::pixel}) {
    if (coverage == Coverage::point && kernel != SplitKernel::lane_three) continue;  // no split
    RasterOptions options;
    options.resolution = 64;
    options.coverage = coverage;
    options.split_kernel = kernel;
    options.pixel_work = PixelWork::device;
    options.keep_pass_data = true;
    options.adapt_radius = false;
    RasterEngine engine(options);
    if (!engine.float64_split()) GTEST_SKIP() << "the device has no shaderFloat64: its split is the float32 one";
    const std::vector<Scene> scenes = device_scenes();
    std::vector<SceneCells> cells(scenes.size());
    engine.compute(scenes, cells);
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      const RasterEngine::PassData& data = engine.pass_data(k);
      std::vector<gpu::SiteSums> reference(data.scene.size(), gpu::SiteSums{});
      std::vector<std::uint32_t> boundary, host_split;
      const std::uint32_t uncovered = reference_classify(data.scene, data.ids, reference, boundary);
      EXPECT_EQ(uncovered, 0u);
      for (std::uint32_t pixel : boundary)
        if (!reference_split(data.scene, data.ids, pixel, reference)) host_split.push_back(pixel);
      EXPECT_EQ(host_split, data.host_split) << "scene " << k << " kernel " << static_cast<int>(kernel);
      for (std::size_t i = 0; i < reference.size(); ++i)
        EXPECT_TRUE(same_sums(reference[i], data.sums[i])) << "scene " << k << " site " << i << ": count " << reference[i].count
                                                           << " vs " << data.sums[i].count << ", piece area "
                                                           << reference[i].piece_area << " vs " << data.sums[i].piece_area;
    }
  }
}

TEST(RasterDevice, HostPathGivesTheDevicePathsBits) {
  REQUIRE_VULKAN();
  const std::vector<Scene> scenes = device_scenes();
  // 64: one classification tile per scene; 150: partial tiles on both axes.
  for (int resolution : {64, 150})
    for (Coverage coverage : {Coverage::area, Coverage::point})
      for (SplitKernel kernel : {SplitKernel::lane_three, SplitKernel::lane_five}) {
        if (coverage == Coverage::point && kernel != SplitKernel::lane_three) continue;  // no split
        RasterEngine& device = test::shared_engine(resolution, coverage, ConeShape::quad, PixelWork::device, false, kernel);
        RasterEngine& host = test::shared_engine(resolution, coverage, ConeShape::quad, PixelWork::host);
        if (!device.float64_split()) GTEST_SKIP() << "the device has no shaderFloat64";
        std::vector<SceneCells> a(scenes.size()), b(scenes.size());
        device.compute(scenes, a);
        host.compute(scenes, b);
        for (std::size_t k = 0; k < scenes.size(); ++k)
          EXPECT_TRUE(test::identical_cells(a[k], b[k]))
              << "resolution " << resolution << " scene " << k << " kernel " << static_cast<int>(kernel);
      }
}

// The lane splits leave the pixels with more candidates than their slots (three, five) to the
// host, which splits them as the host reference does: the same bits as split_f64.comp and the
// host path; and the exact engine's cells within the float64 split's bound.
TEST(RasterDevice, LaneSplitGivesThePixelSplitsAndTheHostPathsBits) {
  REQUIRE_VULKAN();
  const std::vector<Scene> scenes = device_scenes();
  auto engine_for = [](int resolution, PixelWork work, SplitKernel kernel, std::uint32_t guard_test = 0) {
    RasterOptions options;
    options.resolution = resolution;
    options.pixel_work = work;
    options.split_kernel = kernel;
    options.split_guard_test = guard_test;
    return std::make_unique<RasterEngine>(options);
  };
  for (int resolution : {64, 150}) {
    auto three = engine_for(resolution, PixelWork::device, SplitKernel::lane_three);
    auto five = engine_for(resolution, PixelWork::device, SplitKernel::lane_five);
    auto pixel = engine_for(resolution, PixelWork::device, SplitKernel::pixel);
    auto host = engine_for(resolution, PixelWork::host, SplitKernel::lane);
    if (!three->float64_split()) GTEST_SKIP() << "the device has no shaderFloat64";
    std::vector<SceneCells> a(scenes.size()), b(scenes.size()), c(scenes.size()), d(scenes.size());
    three->compute(scenes, a);
    five->compute(scenes, d);
    pixel->compute(scenes, b);
    host->compute(scenes, c);
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      EXPECT_TRUE(test::identical_cells(a[k], b[k])) << "resolution " << resolution << " scene " << k;
      EXPECT_TRUE(test::identical_cells(a[k], c[k])) << "resolution " << resolution << " scene " << k;
      EXPECT_TRUE(test::identical_cells(d[k], c[k])) << "resolution " << resolution << " scene " << k;
    }
    // The dense cluster has pixels beyond both lane kernels' bounds, more beyond three's.
    EXPECT_GT(five->stats().host_split_pixels, pixel->stats().host_split_pixels) << "resolution " << resolution;
    EXPECT_GT(three->stats().host_split_pixels, five->stats().host_split_pixels) << "resolution " << resolution;
  }
  auto lane = engine_for(128, PixelWork::device, SplitKernel::lane);
  for (const Scene& scene : {make_scene(uniform_points(1000, 58)), test::relaxed_scene(1000, 59, 10)}) {
    Errors e = compare_cells(lane->compute(scene), ExactEngine().compute(scene), scene);
    EXPECT_LT(e.max, 1e-12);
    EXPECT_LT(e.max_area, 1e-12);
    EXPECT_NEAR(e.total_area, 1.0, 1e-12);
  }
}

// A clip that would need more than one new vertex (rounding along nearly coincident bisectors;
// the host's polygon has room, the kernels' slots assume one) sends its pixel to the host whole:
// the pieces already clipped add nothing on the device. No known input reaches it, so the test
// trips the guard on the last piece of a quarter of the boundary pixels (split_guard_test): more
// pixels go to the host, and every bit stays the host path's.
TEST(RasterDevice, LaneSplitGuardSendsWholePixelsToTheHost) {
  REQUIRE_VULKAN();
  const std::vector<Scene> scenes = device_scenes();
  auto engine_for = [](PixelWork work, SplitKernel kernel, std::uint32_t guard_test) {
    RasterOptions options;
    options.resolution = 150;
    options.pixel_work = work;
    options.split_kernel = kernel;
    options.split_guard_test = guard_test;
    return std::make_unique<RasterEngine>(options);
  };
  auto host = engine_for(PixelWork::host, SplitKernel::lane, 0);
  if (!host->float64_split()) GTEST_SKIP() << "the device has no shaderFloat64";
  std::vector<SceneCells> expected(scenes.size());
  host->compute(scenes, expected);
  for (SplitKernel kernel : {SplitKernel::lane_three, SplitKernel::lane_five}) {
    auto plain = engine_for(PixelWork::device, kernel, 0);
    auto guarded = engine_for(PixelWork::device, kernel, 0b101);
    std::vector<SceneCells> a(scenes.size()), b(scenes.size());
    plain->compute(scenes, a);
    guarded->compute(scenes, b);
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      EXPECT_TRUE(test::identical_cells(a[k], expected[k])) << "kernel " << static_cast<int>(kernel) << " scene " << k;
      EXPECT_TRUE(test::identical_cells(b[k], expected[k])) << "kernel " << static_cast<int>(kernel) << " scene " << k;
    }
    // The guard trips only where asked (a quarter of the pixels with a clip on their last piece:
    // 2.6% of the boundary pixels here), and those pixels are split on the host.
    EXPECT_EQ(guarded->stats().boundary_pixels, plain->stats().boundary_pixels);
    EXPECT_EQ(plain->stats().guard_pixels, 0u);
    EXPECT_GT(guarded->stats().guard_pixels, plain->stats().boundary_pixels / 100) << "kernel " << static_cast<int>(kernel);
    EXPECT_GT(guarded->stats().host_split_pixels, plain->stats().host_split_pixels + plain->stats().boundary_pixels / 100)
        << "kernel " << static_cast<int>(kernel);
  }
}

// Asked for by name, the device path is refused on a device without shaderFloat64 (lavapipe has
// it, so the engine's check is exercised here through the function it calls), never moved to the
// host; with the float32 split asked for too, it runs.
TEST(RasterDevice, DevicePathWithoutFloat64IsRefusedNamingWhatIsMissing) {
  EXPECT_EQ(device_pixel_work_refusal("llvmpipe (LLVM 15.0.6, 256 bits)", true, false), "");
  EXPECT_EQ(device_pixel_work_refusal("a GPU without doubles", false, true), "");
  EXPECT_EQ(device_pixel_work_refusal("a GPU without doubles", false, false),
            "raster engine: pixel work 'device' needs shaderFloat64 for the exact split, which 'a GPU without doubles' lacks; "
            "use pixel work 'host' or 'auto'");
}

TEST(RasterDevice, Float32SplitStaysWithinItsStatedBound) {
  REQUIRE_VULKAN();
  // The float32 split (devices without shaderFloat64), forced here. Measured on lavapipe at
  // 128^2, N = 1000: max centroid error 1.5e-8, max area error 1.8e-9 (docs/RASTER.md); the
  // bounds leave a factor of about 3.
  RasterEngine& engine = test::shared_engine(128, Coverage::area, ConeShape::quad, PixelWork::device, true);
  EXPECT_FALSE(engine.float64_split());
  for (const Scene& scene : {make_scene(uniform_points(1000, 53)), test::relaxed_scene(1000, 54, 10)}) {
    Errors e = compare_cells(engine.compute(scene), ExactEngine().compute(scene), scene);
    EXPECT_LT(e.max, 5e-8);
    EXPECT_LT(e.max_area, 6e-9);
    EXPECT_NEAR(e.total_area, 1.0, 5e-8);
  }
}

TEST(RasterDevice, BitIdenticalAcrossRasterizerThreads) {
  REQUIRE_VULKAN();
  const Scene scene = make_scene(uniform_points(500, 55));
  std::vector<SceneCells> results;
  for (const char* threads : {"1", "2", "2"}) {
    setenv("LP_NUM_THREADS", threads, 1);
    RasterOptions options;
    options.resolution = 64;
    options.pixel_work = PixelWork::device;
    RasterEngine engine(options);
    results.push_back(engine.compute(scene));
  }
  unsetenv("LP_NUM_THREADS");
  EXPECT_TRUE(test::identical_cells(results[0], results[1]));
  EXPECT_TRUE(test::identical_cells(results[1], results[2]));
}

// Every way of drawing the quad cones (ConeDraw) gives the triangles' ID image and cells bit for
// bit: the fragment shader computes each sample's depth, so only which samples a cone reaches
// could differ (a point cone is not clamped to its tile, and its centre may lie outside the
// atlas). The batch is one atlas of many tiles, so replicas cross the atlas's own edges.
TEST(RasterCones, EveryDrawGivesTheSameIdImagesAndCells) {
  REQUIRE_VULKAN();
  // First, scenes whose sites sit just inside their tile's right and top edges, beside scenes
  // with none near the shared edge: a point cone not held to its tile would win samples there.
  std::vector<Scene> scenes;
  for (int k = 0; k < 4; ++k) scenes.push_back(make_scene({{0.995, 0.5}, {0.5, 0.995}, {0.45, 0.45}}));
  for (Scene& scene : device_scenes()) scenes.push_back(std::move(scene));
  for (Coverage coverage : {Coverage::area, Coverage::point}) {
    auto engine_for = [&](ConeDraw draw) {
      RasterOptions options;
      options.resolution = coverage == Coverage::area ? 64 : 150;
      options.coverage = coverage;
      options.pixel_work = PixelWork::host;
      options.cone_draw = draw;
      options.keep_id_images = true;
      options.adapt_radius = false;
      return std::make_unique<RasterEngine>(options);
    };
    auto triangles = engine_for(ConeDraw::triangles);
    std::vector<SceneCells> expected(scenes.size());
    triangles->compute(scenes, expected);
    EXPECT_EQ(triangles->stats().point_cone_submits, 0u);
    for (ConeDraw draw : {ConeDraw::indexed, ConeDraw::instanced, ConeDraw::points}) {
      auto engine = engine_for(draw);
      std::vector<SceneCells> cells(scenes.size());
      engine->compute(scenes, cells);
      const int name = static_cast<int>(draw);
      // The same passes: a cone that missed samples would have forced a redo.
      EXPECT_EQ(engine->stats().submits, triangles->stats().submits) << "draw " << name;
      EXPECT_EQ(engine->stats().redone_scenes, triangles->stats().redone_scenes) << "draw " << name;
      EXPECT_EQ(engine->stats().cones_drawn, triangles->stats().cones_drawn) << "draw " << name;
      for (std::size_t k = 0; k < scenes.size(); ++k) {
        EXPECT_EQ(engine->id_image(k).ids, triangles->id_image(k).ids) << "draw " << name << " scene " << k;
        EXPECT_TRUE(test::identical_cells(cells[k], expected[k])) << "draw " << name << " scene " << k;
      }
      if (draw == ConeDraw::points) {
        EXPECT_EQ(engine->stats().point_cone_submits, engine->stats().submits);
      }
    }
  }
  // A cone wider than the device's largest point (one site's cone covers the torus: about 1000
  // pixels wide at 512^2; lavapipe's points reach 255) is drawn as triangles, with the same bits.
  RasterOptions options;
  options.resolution = 512;
  options.adapt_radius = false;
  options.pixel_work = PixelWork::host;
  options.cone_draw = ConeDraw::triangles;
  RasterEngine triangles(options);
  options.cone_draw = ConeDraw::points;
  RasterEngine points(options);
  const Scene one_site = make_scene({{0.3, 0.7}});
  EXPECT_TRUE(test::identical_cells(points.compute(one_site), triangles.compute(one_site)));
  if (points.cpu_device()) {
    EXPECT_EQ(points.stats().point_cone_submits, 0u);
  }
}

// `auto`: the device on GPUs; on CPU devices the device for point coverage (within 1.2x of the
// host there, on lavapipe) and the host for area coverage (docs/BENCHMARKS.md, "Point coverage and
// `auto`"); `device` and `host` as named.
TEST(RasterPixelWork, AutomaticResolvesByDeviceKindAndCoverage) {
  EXPECT_TRUE(runs_pixel_work_on_device(PixelWork::automatic, Coverage::point, true));
  EXPECT_FALSE(runs_pixel_work_on_device(PixelWork::automatic, Coverage::area, true));
  EXPECT_TRUE(runs_pixel_work_on_device(PixelWork::automatic, Coverage::point, false));
  EXPECT_TRUE(runs_pixel_work_on_device(PixelWork::automatic, Coverage::area, false));
  for (Coverage coverage : {Coverage::point, Coverage::area})
    for (bool cpu_device : {true, false}) {
      EXPECT_TRUE(runs_pixel_work_on_device(PixelWork::device, coverage, cpu_device));
      EXPECT_FALSE(runs_pixel_work_on_device(PixelWork::host, coverage, cpu_device));
    }
}

// The engine runs its per-pixel work where `auto` resolves, for each coverage: the host path
// times its classification, the device path in point coverage has none on the host.
TEST(RasterPixelWork, AutomaticEngineRunsWhereItResolves) {
  REQUIRE_VULKAN();
  const Scene scene = make_scene(uniform_points(100, 71));
  for (Coverage coverage : {Coverage::point, Coverage::area}) {
    RasterOptions options;
    options.resolution = 64;
    options.coverage = coverage;
    options.adapt_radius = false;
    ASSERT_EQ(options.pixel_work, PixelWork::automatic);
    RasterEngine engine(options);
    const bool expected = coverage == Coverage::point || !engine.cpu_device();
    EXPECT_EQ(engine.pixel_work_on_device(), expected) << "coverage " << static_cast<int>(coverage) << ", device " << engine.device_name();
    engine.compute(scene);
    if (!expected) {
      EXPECT_GT(engine.stats().host_classify_seconds, 0.0) << "area coverage on a CPU device runs on the host";
    } else if (coverage == Coverage::point) {
      EXPECT_EQ(engine.stats().host_classify_seconds, 0.0) << "point coverage runs on the device";
    }
  }
}

}  // namespace
}  // namespace bluetile
