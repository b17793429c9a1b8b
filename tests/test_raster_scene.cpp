// The raster engine's host parts, without a device: the host reference's classification and
// exact split from a brute-force ID image agree with the exact engine; the radius memory
// follows sites by position; close sites are flagged.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/raster/raster_cells.h"
#include "bluetile/raster/raster_coverage.h"
#include "bluetile/raster/raster_reference.h"
#include "bluetile/raster/raster_scene.h"
#include "test_raster_support.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::uniform_points;

// The nearest-site diagram at every sample by brute force, ties to the lower index (as the
// depth test LESS with sites drawn in order): what a correct device pass draws.
std::vector<std::uint32_t> brute_force_ids(const RasterScene& scene) {
  std::vector<std::uint32_t> ids(static_cast<std::size_t>(scene.rx) * scene.ry, 0);
  for (int j = 0; j < scene.ry; ++j)
    for (int i = 0; i < scene.rx; ++i) {
      const Point sample{i * scene.hx, j * scene.hy};
      double best = HUGE_VAL;
      for (std::size_t s = 0; s < scene.size(); ++s) {
        if (scene.coincident[s]) continue;
        const double d = torus_distance_squared(sample, scene.sites[s], scene.scene->domain);
        if (d < best) {
          best = d;
          ids[static_cast<std::size_t>(j) * scene.rx + i] = static_cast<std::uint32_t>(s + 1);
        }
      }
    }
  return ids;
}

// `scene` prepared as the engine draws it.
RasterScene prepared(const Scene& scene, int resolution, bool area) {
  RasterSettings settings;
  settings.area = area;
  settings.resolution = resolution;
  RasterScene job = prepare_raster_scene(scene, 0, settings);
  flag_close_sites(job);
  job.update_scales();
  return job;
}

SceneCells host_reference_cells(const Scene& scene, int resolution, bool area) {
  const RasterScene job = prepared(scene, resolution, area);
  const std::vector<std::uint32_t> ids = brute_force_ids(job);
  std::vector<gpu::SiteSums> sums(job.size(), gpu::SiteSums{});
  std::vector<std::uint32_t> host_pixels;
  std::uint64_t boundary = 0;
  EXPECT_EQ(reference_pass(job, ids, sums, true, true, host_pixels, boundary), 0u);
  std::vector<PieceSums> pieces(job.size());
  for (std::uint32_t pixel : host_pixels) {
    const int i = static_cast<int>(pixel % static_cast<std::uint32_t>(job.rx)), j = static_cast<int>(pixel / static_cast<std::uint32_t>(job.rx));
    double nearest = HUGE_VAL;
    for (std::size_t s = 0; s < job.size(); ++s)
      if (!job.coincident[s])
        nearest = std::min(nearest, torus_distance(Point{(i + 0.5) * job.hx, (j + 0.5) * job.hy}, job.sites[s], scene.domain));
    host_split(job, nearest, pixel, pieces);
  }
  SceneCells cells;
  assemble_cells(job, sums, pieces, cells);
  return cells;
}

TEST(RasterHost, ReferenceSplitIsExactWithoutADevice) {
  std::vector<Scene> scenes = {make_scene(uniform_points(300, 61)), test::relaxed_scene(300, 62, 10)};
  for (const test::HardCase& c : test::hard_cases()) scenes.push_back(make_scene(c.sites));
  for (const Scene& scene : scenes) {
    const SceneCells exact = ExactEngine().compute(scene);
    for (int resolution : {16, 48}) {
      const test::Errors e = test::compare_cells(host_reference_cells(scene, resolution, true), exact, scene);
      EXPECT_LT(e.max, 1e-12) << scene.sites.size() << " sites at " << resolution;
      EXPECT_LT(e.max_area, 1e-12) << scene.sites.size() << " sites at " << resolution;
      EXPECT_LT(e.max_second, 1e-12) << scene.sites.size() << " sites at " << resolution;
      EXPECT_NEAR(e.total_area, 1.0, 1e-12);
    }
  }
}

TEST(RasterHost, ClassificationCountsEverySampleAndPixelOnce) {
  const Scene scene = make_scene(uniform_points(200, 63));
  for (bool area : {true, false}) {
    const RasterScene job = prepared(scene, 40, area);
    const std::vector<std::uint32_t> ids = brute_force_ids(job);
    std::vector<gpu::SiteSums> sums(job.size(), gpu::SiteSums{});
    std::vector<std::uint32_t> boundary;
    EXPECT_EQ(reference_classify(job, ids, sums, boundary), 0u);
    std::uint64_t owned = 0, whole = 0;
    for (const gpu::SiteSums& s : sums) {
      owned += s.owned;
      whole += s.count;
    }
    EXPECT_EQ(owned, 40u * 40u);  // every sample shows one site
    if (area) {
      EXPECT_EQ(whole + boundary.size(), 40u * 40u);  // every pixel is whole or split
      EXPECT_GT(whole, 0u);
      EXPECT_TRUE(std::is_sorted(boundary.begin(), boundary.end()));
    } else {
      EXPECT_EQ(whole, 40u * 40u);
      EXPECT_TRUE(boundary.empty());
    }
    // The farthest owned sample of a site is no farther than its exact cell radius.
    const SceneCells exact = ExactEngine().compute(scene);
    for (std::size_t i = 0; i < job.size(); ++i) EXPECT_LE(farthest_sample(sums[i]), exact.cells[i].radius * (1 + 1e-6)) << i;
  }
}

TEST(RasterHost, RadiusMemoryFollowsSitesByPosition) {
  const Scene first = make_scene({{0.1, 0.1}, {0.5, 0.5}, {0.9, 0.2}});
  RasterSettings settings;
  settings.resolution = 32;
  RasterScene job = prepare_raster_scene(first, 0, settings);
  RadiusMemory memory;
  memory.start_call();
  EXPECT_EQ(memory.recall(job), 0u);
  // Site 1 moves to (0.52, 0.5) with cell radius 0.3; the others stay.
  memory.remember(job, {{0.1, 0.1}, {0.52, 0.5}, {0.9, 0.2}}, {0.2, 0.3, 0.25});
  memory.start_call();
  // The next call has the sites in another order, one of them new.
  const Scene second = make_scene({{0.52, 0.5}, {0.7, 0.7}, {0.1, 0.1}});
  RasterScene next = prepare_raster_scene(second, 3, settings);
  const double start = next.radius[1];
  EXPECT_EQ(memory.recall(next), 2u);
  const double slack = 0.5 * next.pixel_diagonal();
  EXPECT_NEAR(next.radius[0], 1.1 * 0.3 + 2.0 * 0.02 + slack, 1e-12);
  EXPECT_NEAR(next.radius[2], 1.1 * 0.2 + slack, 1e-12);
  EXPECT_EQ(next.radius[1], start);  // unknown site: the start radius
  // Only the last call is remembered.
  memory.start_call();
  EXPECT_EQ(memory.recall(next), 0u);
}

TEST(RasterHost, SitesTooCloseForFloatDepthsAreFlagged) {
  std::vector<Point> sites = uniform_points(100, 64);
  sites.push_back(sites[3] + Point{1e-9, 0.0});  // far below what float depths resolve
  sites.push_back(sites[5] + Point{5e-3, 0.0});  // a tenth of the spacing: fine
  RasterSettings settings;
  settings.resolution = 64;
  const Scene scene = make_scene(sites);
  RasterScene job = prepare_raster_scene(scene, 0, settings);
  for (double& r : job.radius) r = 0.02;  // flags pairs closer than 6e-4 at 64^2
  flag_close_sites(job);
  EXPECT_TRUE(job.split[3]);
  EXPECT_TRUE(job.split[100]);
  EXPECT_FALSE(job.split[5]);
  EXPECT_FALSE(job.split[101]);
  std::size_t flagged = 0;
  for (std::uint8_t f : job.split) flagged += f;
  EXPECT_EQ(flagged, 2u);
}

// The flags by their definition over every pair: s and t are flagged when t lies within the
// threshold of s's radius, or s within that of t's (threshold: 2^-22 r^2 / (1e-5 pixel)).
std::vector<std::uint8_t> flags_by_every_pair(const RasterScene& job) {
  std::vector<std::uint8_t> flags(job.size(), 0);
  const double h = std::min(job.hx, job.hy);
  for (std::size_t s = 0; s < job.size(); ++s)
    for (std::size_t t = 0; t < job.size(); ++t) {
      if (s == t || job.coincident[s] || job.coincident[t]) continue;
      const double reach = job.radius[s] * job.radius[s] / (4194304.0 * 1e-5 * h);
      if (raster_distance(job, job.sites[s], job.sites[t]) <= reach) flags[s] = flags[t] = 1;
    }
  return flags;
}

TEST(RasterHost, CloseSiteFlagsOnLinesClustersAndMixedRadiiFollowTheirDefinition) {
  // Sites on a line and in a cluster have thresholds that reach far (the search stops at a
  // first partner there); sites with large cones among small ones flag sites they reach but
  // that reach nothing themselves (searched from the flagged sites when those are fewer, else
  // from the others).
  struct Layout {
    const char* name;
    std::vector<Point> sites;
    std::function<double(std::size_t)> radius;
  };
  std::vector<Point> line, cluster, mixed = uniform_points(600, 91), sparse = uniform_points(40, 92);
  for (std::size_t i = 0; i < 600; ++i) line.push_back({(static_cast<double>(i) + 0.5) / 600.0, 0.5});
  Rng rng(93);
  for (std::size_t i = 0; i < 600; ++i) cluster.push_back({0.3 + 0.002 * rng.uniform(), 0.6 + 0.002 * rng.uniform()});
  cluster.push_back(cluster[7]);  // coincident: never flagged, never a partner
  line.push_back(line[7]);
  // Small cones far from the cluster, flagged only from the cluster's side (found from theirs:
  // they are fewer).
  for (Point p : uniform_points(30, 94)) cluster.push_back(p);
  const std::vector<Layout> layouts = {
      {"line", line, [](std::size_t) { return 0.5; }},
      {"cluster and far sites", cluster, [](std::size_t i) { return i <= 600 ? 0.6 : 0.01; }},
      {"mixed radii", mixed, [](std::size_t i) { return i % 50 == 0 ? 0.3 : 0.01; }},
      {"sparse, large cones", sparse, [](std::size_t i) { return i % 2 ? 0.2 : 0.02; }},
  };
  for (const Layout& layout : layouts)
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded}) {
      Scene scene = make_scene(layout.sites);
      scene.boundary = boundary;
      RasterSettings settings;
      settings.resolution = 64;
      RasterScene job = prepare_raster_scene(scene, 0, settings);
      for (std::size_t i = 0; i < job.size(); ++i) job.radius[i] = layout.radius(i);
      flag_close_sites(job);
      const std::vector<std::uint8_t> want = flags_by_every_pair(job);
      std::size_t flagged = 0, differ = 0;
      for (std::size_t i = 0; i < job.size(); ++i) {
        flagged += want[i];
        differ += job.split[i] != want[i];
      }
      EXPECT_EQ(differ, 0u) << layout.name << (boundary == Boundary::periodic ? ", periodic" : ", bounded");
      EXPECT_GT(flagged, 0u) << layout.name;
      EXPECT_LT(flagged, job.size()) << layout.name;  // the coincident, or sites that reach nothing
    }
}

}  // namespace
}  // namespace bluetile
