// The raster engine against the exact engine: exactness of area coverage, point coverage's
// error, hard cases, batches, the coverage check, the radius memory, determinism, the tool's
// ID image and the address-space check. Every test that computes cells runs twice, with the
// per-pixel work on the host and on the device (RasterPaths), and the device run also checks
// that the host path gives its bits. Every test here needs a Vulkan device; without one they
// skip (lavapipe is installed on CI and developer machines, so there they run).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <sys/wait.h>

#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/image_file.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/raster/engine_choice.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "test_raster_support.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::compare_cells;
using test::fixed_site_rectangle;
using test::Errors;
using test::uniform_points;

class Raster : public test::RasterPaths {
 protected:
  Errors raster_vs_exact(const Scene& scene, int resolution, Coverage coverage, ConeShape cone = ConeShape::quad) {
    SceneCells exact = ExactEngine().compute(scene);
    return compare_cells(cells(scene, resolution, coverage, cone), exact, scene);
  }
};
INSTANTIATE_TEST_SUITE_P(PixelWork, Raster, ::testing::ValuesIn(test::kPixelPaths), test::pixel_path_name);

TEST_P(Raster, PointErrorShrinksWithResolution) {
  Scene scene = make_scene(uniform_points(1000, 3));
  Errors low = raster_vs_exact(scene, 256, Coverage::point);
  Errors high = raster_vs_exact(scene, 1024, Coverage::point);
  // Measured: mean 4.4e-4 at 256^2 and 4.7e-5 at 1024^2 (docs/RASTER.md).
  EXPECT_LT(low.mean, 8e-4) << low.mean;
  EXPECT_LT(high.mean, 1e-4) << high.mean;
  EXPECT_LT(high.mean, 0.3 * low.mean);
  EXPECT_LT(high.max, 1.5e-3) << high.max;
}

TEST_P(Raster, AreaCoverageIsExactToRounding) {
  Scene uniform = make_scene(uniform_points(1000, 4));
  Scene relaxed = test::relaxed_scene(1000, 5, 20);
  for (int resolution : {32, 64, 128, 256}) {
    for (const Scene* scene : {&uniform, &relaxed}) {
      Errors area = raster_vs_exact(*scene, resolution, Coverage::area);
      EXPECT_LT(area.max, 1e-12) << "resolution " << resolution;
      EXPECT_LT(area.max_area, 1e-12) << "resolution " << resolution;
      EXPECT_LT(area.max_second, 1e-12) << "resolution " << resolution;
      EXPECT_NEAR(area.total_area, 1.0, 1e-12) << "resolution " << resolution;
    }
  }
  Errors point = raster_vs_exact(uniform, 256, Coverage::point);
  Errors area = raster_vs_exact(uniform, 256, Coverage::area);
  EXPECT_LT(area.mean * 1e6, point.mean) << area.mean << " vs " << point.mean;
}

TEST_P(Raster, TessellatedFanIsBiasedQuadIsNot) {
  Scene scene = make_scene(uniform_points(1000, 6));
  Errors fan = raster_vs_exact(scene, 512, Coverage::point, ConeShape::fan);
  Errors quad = raster_vs_exact(scene, 512, Coverage::point, ConeShape::quad);
  EXPECT_LT(fan.max, 5e-3);
  EXPECT_LT(quad.mean, fan.mean);
  // Area coverage with fans splits every pixel (their ID image is only close to the diagram),
  // so it stays exact.
  Errors fan_area = raster_vs_exact(scene, 64, Coverage::area, ConeShape::fan);
  EXPECT_LT(fan_area.max, 1e-12);
}

TEST_P(Raster, HardCasesAgreeWithTheExactEngine) {
  for (const test::HardCase& c : test::hard_cases()) {
    Scene scene = make_scene(c.sites);
    SceneCells exact = ExactEngine().compute(scene);
    for (int resolution : {64, 256}) {
      SceneCells area = cells(scene, resolution, Coverage::area);
      Errors e = compare_cells(area, exact, scene);
      EXPECT_LT(e.max, 1e-12) << c.name << " at " << resolution;
      EXPECT_LT(e.max_area, 1e-12) << c.name << " at " << resolution;
      EXPECT_LT(e.max_second, 1e-12) << c.name << " at " << resolution;
      EXPECT_NEAR(e.total_area, 1.0, 1e-12) << c.name << " at " << resolution;
      EXPECT_EQ(area.coincident_count, exact.coincident_count) << c.name;
      SceneCells point = cells(scene, resolution, Coverage::point);
      Errors p = compare_cells(point, exact, scene);
      // Point coverage cannot see features below a pixel: bound it only where there are none.
      const std::string name = c.name;
      const bool sub_pixel = name.find("pair") != std::string::npos || name.find("cluster") != std::string::npos ||
                             name.find("apart") != std::string::npos;
      if (!sub_pixel) {
        EXPECT_LT(p.max, 2.0 / resolution) << c.name << " at " << resolution;
      }
      for (const Cell& cell : point.cells) EXPECT_TRUE(std::isfinite(cell.centroid.x) && std::isfinite(cell.area)) << c.name;
    }
  }
}

TEST_P(Raster, LatticesAreFixedPoints) {
  std::vector<Point> square;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) square.push_back({(i + 0.5) / 16.0, (j + 0.5) / 16.0});
  Scene scene = make_scene(square);
  SceneCells lattice = cells(scene, 128, Coverage::area);
  for (std::size_t i = 0; i < square.size(); ++i) {
    EXPECT_LT(torus_distance(lattice.cells[i].centroid, square[i], scene.domain), 1e-12) << i;
    EXPECT_NEAR(lattice.cells[i].area, 1.0 / 256.0, 1e-15);
  }
}

TEST_P(Raster, CoincidentAndPixellessCellsAreReported) {
  std::vector<Point> sites = uniform_points(50, 12);
  sites.push_back(sites[7]);  // coincides with site 7: site 50 is reported, 7 keeps the cell
  // Site 51, between samples, ringed by six sites 1e-4 away: its cell holds no sample.
  const Point centre{0.5 + 0.3 / 64, 0.5 + 0.4 / 64};
  sites.push_back(centre);
  for (int k = 0; k < 6; ++k) sites.push_back(centre + 1e-4 * Point{std::cos(k * 1.0471975511965976), std::sin(k * 1.0471975511965976)});
  Scene scene = make_scene(sites);
  SceneCells exact = ExactEngine().compute(scene);
  for (Coverage coverage : {Coverage::area, Coverage::point}) {
    SceneCells got = cells(scene, 64, coverage);
    EXPECT_EQ(got.coincident_count, 1u);
    EXPECT_EQ(got.cells[50].status, CellStatus::coincident);
    EXPECT_EQ(got.cells[50].centroid, sites[50]);
    EXPECT_EQ(got.cells[50].area, 0.0);
    EXPECT_LT(torus_distance(got.cells[51].centroid, exact.cells[51].centroid, scene.domain), 1e-12);
    EXPECT_NEAR(got.cells[51].area, exact.cells[51].area, 1e-15);
    if (coverage == Coverage::area) {
      // Area coverage splits the pixels such a cell touches: no fallback needed.
      EXPECT_EQ(got.fallback_count, 0u);
      EXPECT_EQ(got.cells[51].status, CellStatus::ok);
      EXPECT_LT(compare_cells(got, exact, scene).max, 1e-12);
    } else {
      EXPECT_GE(got.fallback_count, 1u);
      EXPECT_EQ(got.cells[51].status, CellStatus::exact_fallback);
    }
  }
}

TEST_P(Raster, RectangularDomainAndFixedSites) {
  Rng rng(13);
  const Scene scene = fixed_site_rectangle(rng, 300, 100);
  SceneCells exact = ExactEngine().compute(scene);
  SceneCells area = cells(scene, 64, Coverage::area);
  ASSERT_EQ(area.cells.size(), 200u);
  Errors e = compare_cells(area, exact, scene);
  EXPECT_LT(e.max, 1e-12);
  EXPECT_LT(e.max_area, 1e-12);
}

TEST_P(Raster, BatchEqualsOneByOne) {
  std::vector<Scene> scenes;
  for (std::uint64_t k = 0; k < 5; ++k) scenes.push_back(make_scene(uniform_points(20 + 40 * k, 100 + k)));
  for (Coverage coverage : {Coverage::area, Coverage::point}) {
    RasterOptions o = options();
    o.coverage = coverage;
    o.adapt_radius = false;
    test::PathEngine e(o, work());
    std::vector<SceneCells> batch(scenes.size());
    e.compute(scenes, batch);
    for (std::size_t k = 0; k < scenes.size(); ++k) EXPECT_TRUE(test::identical_cells(e.compute(scenes[k]), batch[k])) << "scene " << k;
  }
}

TEST_P(Raster, UncoveredPixelsAreDetectedAndRepaired) {
  RasterOptions o = options();
  o.resolution = 128;
  o.radius_factor = 0.1;  // far too small: most samples are uncovered at first
  o.adapt_radius = false;
  test::PathEngine small(o, work());
  Scene scene = make_scene(uniform_points(500, 14));
  SceneCells cells = small.compute(scene);
  EXPECT_GT(small.stats().redone_scenes, 0u);
  EXPECT_GT(small.stats().uncovered_pixels, 0u);
  EXPECT_LT(compare_cells(cells, ExactEngine().compute(scene), scene).max, 1e-12);
}

TEST_P(Raster, AdaptiveRadiiFollowARelaxation) {
  RasterOptions o = options();
  o.resolution = 96;
  test::PathEngine raster(o, work());
  ExactEngine exact;
  Scene a = make_scene(uniform_points(400, 15)), b = a;
  LloydOptions lloyd;
  lloyd.iterations = 15;
  relax_lloyd(raster, a, lloyd);
  relax_lloyd(exact, b, lloyd);
  for (std::size_t i = 0; i < a.sites.size(); ++i) EXPECT_LT(torus_distance(a.sites[i], b.sites[i], a.domain), 1e-9);
  // The radii come from the last pass: after the first pass, redos are rare.
  EXPECT_LE(raster.stats().redone_scenes, 3u);
  EXPECT_GT(raster.stats().remembered_radii, 14u * 400u - 10u);
}

TEST_P(Raster, RebuiltScenesDrawConesNoLargerThanKeptOnes) {
  // A loop that keeps its scenes, and one that builds fresh ones every iteration from the last
  // centroids, in another order (as a Wang-tile loop with a new tiling does).
  RasterOptions o = options();
  o.resolution = 128;
  test::PathEngine kept_engine(o, work()), rebuilt_engine(o, work());
  std::vector<Scene> kept;
  for (std::uint64_t k = 0; k < 4; ++k) kept.push_back(make_scene(uniform_points(400, 40 + k)));
  std::vector<Scene> rebuilt = kept;
  std::vector<SceneCells> kept_cells(4), rebuilt_cells(4);
  for (int it = 0; it < 6; ++it) {
    kept_engine.compute(kept, kept_cells);
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t i = 0; i < kept[k].sites.size(); ++i) kept[k].sites[i] = kept_cells[k].cells[i].centroid;
    std::vector<Scene> fresh;
    for (std::size_t k = 4; k-- > 0;) fresh.push_back(make_scene(rebuilt[k].sites));
    std::vector<SceneCells> fresh_cells(4);
    rebuilt_engine.compute(fresh, fresh_cells);
    for (std::size_t k = 0; k < 4; ++k) {
      rebuilt_cells[3 - k] = fresh_cells[k];
      for (std::size_t i = 0; i < rebuilt[3 - k].sites.size(); ++i) rebuilt[3 - k].sites[i] = fresh_cells[k].cells[i].centroid;
    }
    for (std::size_t k = 0; k < 4; ++k) EXPECT_TRUE(test::identical_cells(kept_cells[k], rebuilt_cells[k])) << it << " " << k;
  }
  const RasterStats &a = kept_engine.stats(), &b = rebuilt_engine.stats();
  EXPECT_EQ(b.remembered_radii, a.remembered_radii);
  EXPECT_EQ(b.remembered_radii, 5u * 1600u);  // every site after the first call
  EXPECT_LE(b.drawn_radius_sum, a.drawn_radius_sum * (1.0 + 1e-12));
  // And the memory shrinks the cones: later calls draw about the cell radius, not the start.
  RasterOptions no_memory = o;
  no_memory.adapt_radius = false;
  RasterEngine forgetful(no_memory);
  std::vector<SceneCells> scratch(4);
  for (int it = 0; it < 6; ++it) forgetful.compute(kept, scratch);
  EXPECT_LT(a.drawn_radius_sum, 0.8 * forgetful.stats().drawn_radius_sum);
}

TEST(RasterLimits, ResolutionBeyondTheDeviceIsAClearError) {
  REQUIRE_VULKAN();
  RasterOptions options;
  options.resolution = 1 << 20;  // beyond the engine's own range: refused when made
  EXPECT_EQ(test::error_of([&] { RasterEngine beyond(options); }),
            "resolution: expected 0 (from N) or 16 to 65536, got 1048576");
  options.resolution = 65536;  // in range, past every device's largest image side
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

TEST_P(Raster, BitIdenticalAcrossRunsAndThreadCounts) {
  test::TempDir dir;
  const std::string work = test::pixel_path_name({GetParam(), 0});
  for (const char* coverage : {"area", "point"}) {
    std::vector<std::string> one = {"--coverage", coverage, "--resolution", "128", "--threads", "1", "--pixel-work", work};
    std::vector<std::string> two = {"--coverage", coverage, "--resolution", "128", "--threads", "2", "--pixel-work", work};
    std::string a = relax_output(dir, "a.txt", "1", one);
    std::string b = relax_output(dir, "b.txt", "2", two);
    std::string c = relax_output(dir, "c.txt", "2", two);
    EXPECT_FALSE(a.empty());
    EXPECT_EQ(a, b) << coverage;
    EXPECT_EQ(b, c) << coverage;
  }
}

// --pixel-work moves the per-pixel work, never the result: device and host write the same file.
TEST(RasterTool, PixelWorkOptionMovesTheWorkNotTheResult) {
  REQUIRE_VULKAN();
  test::TempDir dir;
  for (const char* coverage : {"area", "point"}) {
    std::vector<std::string> common = {"relax", "-n", "200", "-k", "3", "--seed", "5", "--resolution", "64", "--coverage", coverage};
    std::vector<std::string> files;
    for (const char* work : {"device", "host", "auto"}) {
      std::vector<std::string> args = common;
      files.push_back(dir.file(std::string(coverage) + "_" + work + ".txt"));
      args.insert(args.end(), {"--pixel-work", work, "-o", files.back()});
      test::CommandResult r = test::run_bluetile(args);
      ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    const std::string device = test::read_text(files[0]);
    EXPECT_FALSE(device.empty());
    EXPECT_EQ(device, test::read_text(files[1])) << coverage;
    EXPECT_EQ(device, test::read_text(files[2])) << coverage;
  }
  // A bad value: one line naming the option and what it accepts, nothing written.
  test::CommandResult r = test::run_bluetile({"relax", "-n", "10", "--pixel-work", "gpu", "-o", dir.file("bad.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.rfind("bluetile: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const char* word : {"--pixel-work", "auto", "device", "host"}) EXPECT_NE(r.err.find(word), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.txt")));
  // The device path asked for where it cannot run: refused, not moved to the host.
  r = test::run_bluetile({"relax", "-n", "50", "-k", "1", "--engine", "raster", "--bounded", "--pixel-work", "device", "-o",
                          dir.file("bounded.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("bounded domain"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bounded.txt")));
}

TEST(RasterTool, CellsNoSampleReachedAreSaidToHaveGoneToTheExactEngine) {
  // 1000 cells on 16 x 16 point samples: most were measured by the exact engine, and only the
  // log's fallbacks column said so.
  REQUIRE_VULKAN();
  test::TempDir dir;
  test::CommandResult r = test::run_bluetile({"relax", "-n", "1000", "-k", "1", "--resolution", "16", "--coverage",
                                              "point", "-o", dir.file("low.txt"), "--log", dir.file("log.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::istringstream log(test::read_text(dir.file("log.csv")));
  std::string line;
  std::getline(log, line);  // the column names
  std::getline(log, line);  // iteration 1
  std::vector<std::string> fields;
  std::istringstream row(line);
  for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
  ASSERT_EQ(fields.size(), 7u) << line;
  EXPECT_GT(std::stoi(fields[5]), 0) << line;
  EXPECT_EQ(r.err, "bluetile: note: the raster engine measured " + fields[5] +
                       " cells (over every iteration) with the exact engine: point coverage found no pixel centre in "
                       "them (a higher --resolution, or --coverage area, draws them)\n");
  // A resolution past the device's budget says the budget (it said only "exceeds"). 16384 is
  // lavapipe's largest side, and 16384^2 pixels far more than its budget a pass.
  test::CommandResult big = test::run_bluetile({"relax", "-n", "10", "-k", "1", "--resolution", "16384", "-o",
                                                dir.file("big.txt")});
  // (A GPU may hold it, or have a smaller largest side.)
  if (big.exit_code != 0 && big.err.find("limit of") == std::string::npos) {
    EXPECT_EQ(big.err.rfind("bluetile: raster engine: a scene of 16384 x 16384 pixels exceeds the device's memory budget "
                            "of ", 0),
              0u)
        << big.err;
    EXPECT_NE(big.err.find(" pixels a pass (a side of "), std::string::npos) << big.err;
  }
  // The header names the settings that shaped the cells (it said "engine raster" only).
  EXPECT_NE(test::read_text(dir.file("low.txt")).find(", engine raster (point coverage, resolution 16, quad cones),"),
            std::string::npos);
  r = test::run_bluetile({"relax", "-n", "100", "-k", "1", "--coverage", "point", "-o", dir.file("fine.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST(RasterTool, DevicesCommandAndIdImage) {
  REQUIRE_VULKAN();
  test::CommandResult r = test::run_bluetile({"devices"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("type"), std::string::npos) << r.out;
  test::TempDir dir;
  r = test::run_bluetile({"relax", "-n", "100", "-k", "3", "--resolution", "64", "-o", dir.file("p.txt"), "--id-image",
                          dir.file("cells.png")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // Read the picture back: one colour per cell, as the engine's own ID image says, and a
  // black dot on every site.
  const ImageFile image = read_image_file(dir.file("cells.png"));
  ASSERT_EQ(image.width, 64);
  ASSERT_EQ(image.height, 64);
  ASSERT_GE(image.channels, 3);
  const Scene scene = make_scene(read_point_file(dir.file("p.txt")).points);
  RasterOptions options;
  options.resolution = 64;
  options.keep_id_images = true;
  RasterEngine engine(options);
  engine.compute(scene);
  const IdImage& ids = engine.id_image(0);
  auto colour = [&](int i, int j) {  // row 0 of the file is the top
    const std::size_t p = (static_cast<std::size_t>(image.height - 1 - j) * image.width + i) * image.channels;
    return std::array<int, 3>{static_cast<int>(std::lround(255 * image.values[p])), static_cast<int>(std::lround(255 * image.values[p + 1])),
                              static_cast<int>(std::lround(255 * image.values[p + 2]))};
  };
  std::map<std::int32_t, std::array<int, 3>> colour_of;
  std::set<std::array<int, 3>> colours;
  const std::array<int, 3> black{0, 0, 0};
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const std::array<int, 3> c = colour(i, j);
      if (c == black) continue;  // a site's dot
      const std::int32_t id = ids.ids[static_cast<std::size_t>(j) * 64 + i];
      ASSERT_GE(id, 0);
      auto [it, fresh] = colour_of.emplace(id, c);
      EXPECT_EQ(it->second, c) << "cell " << id << " has two colours";
      if (fresh) colours.insert(c);
    }
  EXPECT_GE(colour_of.size(), 95u);  // nearly every cell shows (a few are all dot)
  EXPECT_GE(colours.size(), colour_of.size() - 2);  // distinct cells, distinct colours
  for (const Point& site : scene.sites) {
    const int i = static_cast<int>(site.x * 64), j = static_cast<int>(site.y * 64);
    EXPECT_EQ(colour(i, j), black) << "no dot at site " << site.x << " " << site.y;
  }
  r = test::run_bluetile({"relax", "-n", "10", "-k", "1", "-o", dir.file("q.txt"), "--device", "no-such-device"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("no-such-device"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("q.txt")));
}

TEST(RasterLimits, AddressSpaceLimitIsAClearErrorNotACrash) {
  REQUIRE_VULKAN();
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "the address sanitizer reserves terabytes of address space: ulimit -v cannot apply";
#endif
  // Under `ulimit -v 400000` lavapipe used to crash inside vkCreateDevice; the engine checks
  // the limit first.
  test::TempDir dir;
  const std::string command = "ulimit -v 400000; exec '" BLUETILE_BINARY "' relax -n 100 -k 1 -o '" + dir.file("p.txt") +
                              "' 2>'" + dir.file("err") + "'";
  const int status = std::system(("bash -c \"" + command + "\"").c_str());
  ASSERT_TRUE(WIFEXITED(status)) << "killed by a signal";
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = test::read_text(dir.file("err"));
  EXPECT_NE(err.find("address space"), std::string::npos) << err;
  EXPECT_NE(err.find("use the exact engine"), std::string::npos) << err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("p.txt")));
}

TEST(EngineChoice, RefusesEachFieldNamingItAndWhatItAccepts) {
  // The message validate() throws, "" when it accepts.
  auto message = [](const EngineChoice& value) { return test::error_of([&] { validate(value); }); };
  EXPECT_EQ(message({}), "");
  EngineChoice c;
  c.engine = "gpu";
  EXPECT_EQ(message(c), "engine: expected one of 'raster', 'exact', got 'gpu'");
  c = {};
  c.coverage = "areas";
  EXPECT_EQ(message(c), "coverage: expected one of 'point', 'area', got 'areas'");
  c = {};
  c.cone = "cone";
  EXPECT_EQ(message(c), "cone: expected one of 'quad', 'fan', got 'cone'");
  c = {};
  c.pixel_work = "gpu";
  EXPECT_EQ(message(c), "pixel_work: expected one of 'auto', 'device', 'host', got 'gpu'");
  c = {};
  c.resolution = 15;
  EXPECT_EQ(message(c), "resolution: expected 0 (from N) or 16 to 65536, got 15");
  c.resolution = 65537;
  EXPECT_NE(message(c).find("got 65537"), std::string::npos);
  c.resolution = 16;
  EXPECT_EQ(message(c), "");
  // The names map onto the options the raster engine takes.
  c = {};
  c.coverage = "point";
  c.cone = "fan";
  c.pixel_work = "host";
  c.resolution = 64;
  const RasterOptions r = raster_options(c);
  EXPECT_EQ(r.coverage, Coverage::point);
  EXPECT_EQ(r.cone, ConeShape::fan);
  EXPECT_EQ(r.pixel_work, PixelWork::host);
  EXPECT_EQ(r.resolution, 64);
  c.engine = "exact";
  EXPECT_NE(dynamic_cast<ExactEngine*>(make_engine(c).get()), nullptr);
}

}  // namespace
}  // namespace bluetile
