// The raster engine on bounded domains and weighted (density) cells, against the exact engine
// (itself checked against brute force in test_density_engine.cpp): area coverage splits pixels
// exactly and weighs whole pixels and pieces by the texels they cover, so the two agree to
// rounding at any resolution, aligned to the texel grid or not. Needs a Vulkan device (lavapipe).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <tuple>
#include <utility>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/io/image_file.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_engine.h"
#include "density_reference.h"
#include "test_raster_support.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::shared_engine;

// Texels uniform in [0, 1), a fraction of them zero.
std::shared_ptr<DensityGrid> random_texels(int width, int height, std::uint64_t seed, double zero_fraction) {
  Rng rng(seed);
  auto grid = std::make_shared<DensityGrid>(width, height);
  for (float& t : grid->texels) t = rng.uniform() < zero_fraction ? 0.0f : static_cast<float>(rng.uniform());
  grid->texels[0] = 0.25f;  // never all zero
  return grid;
}

Scene random_scene(std::size_t count, const Domain& domain, Boundary boundary, std::uint64_t seed) {
  Rng rng(seed);
  std::vector<Point> sites(count);
  for (Point& p : sites) p = rng.point(domain);
  Scene scene = make_scene(std::move(sites), domain);
  scene.boundary = boundary;
  return scene;
}

struct Differences {
  double centroid = 0.0, area = 0.0, mass = 0.0, second = 0.0, total_area = 0.0;
  std::size_t status_mismatches = 0;
  std::size_t exact_residues = 0;  // zero-density cells the exact engine gives a rounding mass
};

Differences differences(const Scene& scene, const SceneCells& raster, const SceneCells& exact) {
  Differences d;
  EXPECT_EQ(raster.cells.size(), exact.cells.size());
  for (std::size_t i = 0; i < raster.cells.size() && i < exact.cells.size(); ++i) {
    const Cell &r = raster.cells[i], &e = exact.cells[i];
    if (r.status == CellStatus::zero_density && e.status == CellStatus::ok && e.mass < 1e-18) {
      // The exact engine's Green's-theorem sums can leave a rounding residue (measured: 2.7e-20)
      // where a cell lies wholly in zero texels; the brute-force reference settles it.
      const WeightedMoments m = test::brute_force_moments(test::brute_force_cell(scene, i), scene.sites[i], scene);
      EXPECT_EQ(m.mass, 0.0) << "cell " << i;
      ++d.exact_residues;
      d.total_area += r.area;
      continue;
    }
    d.centroid = std::max(d.centroid, scene_distance(scene, r.centroid, e.centroid));
    d.area = std::max(d.area, std::abs(r.area - e.area));
    d.mass = std::max(d.mass, std::abs(r.mass - e.mass));
    d.second = std::max(d.second, std::abs(r.second_moment - e.second_moment));
    d.total_area += r.area;
    d.status_mismatches += r.status != e.status;
  }
  return d;
}

void expect_exact(const Scene& scene, int resolution, const std::string& what) {
  SceneCells exact = ExactEngine().compute(scene);
  SceneCells raster = shared_engine(resolution, Coverage::area).compute(scene);
  const Differences d = differences(scene, raster, exact);
  EXPECT_LE(d.centroid, 1e-12) << what;
  EXPECT_LE(d.area, 1e-12) << what;
  EXPECT_LE(d.mass, 1e-12) << what;
  EXPECT_LE(d.second, 1e-12) << what;
  EXPECT_NEAR(d.total_area, scene.domain.area(), 1e-12) << what;
  EXPECT_EQ(d.status_mismatches, 0u) << what;
  EXPECT_EQ(raster.zero_density_count, exact.zero_density_count + d.exact_residues) << what;
  EXPECT_EQ(raster.coincident_count, exact.coincident_count) << what;
}

TEST(RasterBounded, CellsEndAtTheRectangle) {
  REQUIRE_VULKAN();
  const Domain domain{{1.0, 0.7}};
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    Scene scene = random_scene(150, domain, Boundary::bounded, seed);
    // A site on the left border, one on the bottom border, a corner site, one just inside the
    // top-right corner.
    scene.sites[0] = {0.0, 0.3};
    scene.sites[1] = {0.45, 0.0};
    scene.sites[2] = {0.0, 0.0};
    scene.sites[3] = {std::nextafter(1.0, 0.0), std::nextafter(0.7, 0.0)};
    for (int resolution : {24, 64, 101})
      expect_exact(scene, resolution, "seed " + std::to_string(seed) + " resolution " + std::to_string(resolution));
  }
}

TEST(RasterBounded, FewSitesAndCellsWiderThanHalfTheDomain) {
  REQUIRE_VULKAN();
  // Cells spanning most of the rectangle: nothing may wrap (a torus would join them).
  for (const std::vector<Point>& sites : std::vector<std::vector<Point>>{
           {{0.1, 0.1}}, {{0.05, 0.5}, {0.95, 0.5}}, {{0.0, 0.0}, {0.999, 0.999}, {0.5, 0.02}}}) {
    Scene scene = make_scene(sites);
    scene.boundary = Boundary::bounded;
    expect_exact(scene, 32, std::to_string(sites.size()) + " sites");
  }
}

TEST(RasterDensity, WeightedCellsMatchTheExactEngine) {
  REQUIRE_VULKAN();
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      const Domain domain = seed % 2 ? Domain{} : Domain{{1.0, 0.6}};
      Scene scene = random_scene(200, domain, boundary, 40 + seed);
      // Texels coarser than the pixels, finer than them, and in no ratio to them.
      for (auto [width, height, resolution] : {std::tuple{16, 8, 64}, std::tuple{17, 11, 48}, std::tuple{190, 130, 32}}) {
        scene.density = random_texels(width, height, seed * 7 + static_cast<std::uint64_t>(width), 0.2);
        expect_exact(scene, resolution,
                     std::string(boundary == Boundary::bounded ? "bounded" : "periodic") + " seed " + std::to_string(seed) +
                         " texels " + std::to_string(width) + " resolution " + std::to_string(resolution));
      }
    }
  }
}

TEST(RasterDensity, ZeroDensityCellsKeepTheirSite) {
  REQUIRE_VULKAN();
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    Scene scene = random_scene(120, Domain{}, boundary, 77);
    // Density only in the right half: cells wholly in the left half have mass 0.
    auto grid = std::make_shared<DensityGrid>(8, 8);
    for (int j = 0; j < 8; ++j)
      for (int i = 4; i < 8; ++i) grid->at(i, j) = 1.0f + static_cast<float>(i + j) / 8.0f;
    scene.density = grid;
    SceneCells raster = shared_engine(64, Coverage::area).compute(scene);
    SceneCells exact = ExactEngine().compute(scene);
    EXPECT_GT(raster.zero_density_count, 10u);
    EXPECT_EQ(raster.zero_density_count, exact.zero_density_count);
    for (std::size_t i = 0; i < raster.cells.size(); ++i) {
      const Cell& c = raster.cells[i];
      if (c.status != CellStatus::zero_density) continue;
      EXPECT_EQ(c.centroid, scene.sites[i]);
      EXPECT_EQ(c.mass, 0.0);
      EXPECT_GT(c.area, 0.0);
    }
    expect_exact(scene, 64, "half zero");
  }
}

TEST(RasterDensity, UniformDensityGivesTheUnweightedCellsBitForBit) {
  REQUIRE_VULKAN();
  Scene plain = random_scene(300, Domain{}, Boundary::periodic, 5);
  SceneCells unweighted = shared_engine(64, Coverage::area).compute(plain);
  Scene one = plain;
  one.density = std::make_shared<DensityGrid>(5, 3, 1.0f);
  EXPECT_TRUE(test::identical_cells(shared_engine(64, Coverage::area).compute(one), unweighted));
  Scene three = plain;
  three.density = std::make_shared<DensityGrid>(5, 3, 3.0f);
  SceneCells tripled = shared_engine(64, Coverage::area).compute(three);
  for (std::size_t i = 0; i < tripled.cells.size(); ++i) {
    EXPECT_EQ(tripled.cells[i].centroid, unweighted.cells[i].centroid);
    EXPECT_EQ(tripled.cells[i].mass, 3.0 * unweighted.cells[i].area);
  }
}

TEST(RasterDensity, SameCellsWhateverTheThreadCount) {
  REQUIRE_VULKAN();
  for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
    Scene scene = random_scene(400, Domain{{1.0, 0.8}}, boundary, 9);
    scene.density = random_texels(23, 19, 3, 0.1);
    const std::size_t threads = thread_count();
    set_thread_count(1);
    SceneCells one = shared_engine(64, Coverage::area).compute(scene);
    set_thread_count(2);
    SceneCells two = shared_engine(64, Coverage::area).compute(scene);
    set_thread_count(threads);
    EXPECT_TRUE(test::identical_cells(one, two));
    for (std::size_t i = 0; i < one.cells.size(); ++i)
      EXPECT_EQ(std::memcmp(&one.cells[i].mass, &two.cells[i].mass, sizeof(double)), 0) << i;
  }
}

TEST(RasterDensity, ADensityChangedInPlaceIsMeasuredAfresh) {
  REQUIRE_VULKAN();
  // The engine keeps per-map pixel tables between calls; a grid edited between them must not
  // reuse the stale one.
  Scene scene = random_scene(150, Domain{}, Boundary::periodic, 31);
  auto grid = random_texels(13, 13, 8, 0.1);
  scene.density = grid;
  RasterEngine& engine = shared_engine(40, Coverage::area);
  engine.compute(scene);
  for (float& t : grid->texels) t = 1.0f - t;
  SceneCells raster = engine.compute(scene);
  SceneCells exact = ExactEngine().compute(scene);
  EXPECT_LE(differences(scene, raster, exact).centroid, 1e-12);
}

TEST(RasterDensity, DevicePixelWorkRefusesDensitiesAndBorders) {
  REQUIRE_VULKAN();
  // Pixel work asked for on the device (shaders that know neither densities nor borders) is
  // refused for such scenes, never moved to the host; automatic runs them on the host.
  Scene weighted = random_scene(200, Domain{}, Boundary::periodic, 12);
  weighted.density = random_texels(9, 9, 4, 0.2);
  Scene bounded = random_scene(200, Domain{}, Boundary::bounded, 13);
  for (const auto& [scene, word] : {std::pair{&weighted, "density"}, std::pair{&bounded, "bounded"}}) {
    try {
      shared_engine(48, Coverage::area, ConeShape::quad, PixelWork::device).compute(*scene);
      ADD_FAILURE() << "expected an error for " << word;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(word), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("'host'"), std::string::npos) << e.what();
    }
    SceneCells automatic = shared_engine(48, Coverage::area, ConeShape::quad, PixelWork::automatic).compute(*scene);
    SceneCells host = shared_engine(48, Coverage::area, ConeShape::quad, PixelWork::host).compute(*scene);
    EXPECT_TRUE(test::identical_cells(automatic, host)) << word;
  }
}

TEST(RasterDensity, PointCoverageRefusesAVaryingDensity) {
  REQUIRE_VULKAN();
  Scene scene = random_scene(50, Domain{}, Boundary::periodic, 2);
  scene.density = random_texels(4, 4, 1, 0.0);
  try {
    shared_engine(256, Coverage::point).compute(scene);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("area coverage"), std::string::npos) << e.what();
  }
}

// relax with a density map on the raster engine, through the tool: the same file whatever the
// host threads and lavapipe's threads.
TEST(RasterDensity, ToolRelaxesTowardAMapBitIdenticallyAcrossThreads) {
  REQUIRE_VULKAN();
  test::TempDir dir;
  std::vector<float> map(32 * 32);
  for (int j = 0; j < 32; ++j)
    for (int i = 0; i < 32; ++i) map[static_cast<std::size_t>(j) * 32 + i] = i < 16 ? 0.1f : 1.0f;
  write_image_file(dir.file("map.png"), 32, 32, 1, map, SampleFormat::uint8);
  for (const char* bounded : {"", "--bounded"}) {
    std::string outputs[2];
    for (int t = 0; t < 2; ++t) {
      setenv("LP_NUM_THREADS", t == 0 ? "1" : "2", 1);
      std::vector<std::string> args = {"relax", "-n", "300", "-k", "5", "--engine", "raster", "--density-map",
                                       dir.file("map.png"), "--transfer", "linear", "--threads", t == 0 ? "1" : "2",
                                       "-o", dir.file("p.txt")};
      if (*bounded) args.push_back(bounded);
      test::CommandResult r = test::run_bluetile(args);
      unsetenv("LP_NUM_THREADS");
      ASSERT_EQ(r.exit_code, 0) << r.err;
      outputs[t] = test::read_text(dir.file("p.txt"));
      EXPECT_NE(outputs[t].find("engine raster"), std::string::npos);
    }
    EXPECT_EQ(outputs[0], outputs[1]) << bounded;
  }
}

}  // namespace
}  // namespace bluetile
