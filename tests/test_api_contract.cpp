// The library's public entry points against what a program might pass by mistake: each gives an
// Error naming the argument and its value, where they crashed (a division by zero, a read past
// an end), hung, or returned a result of no input. One test per kind of mistake.
#include <gtest/gtest.h>

#include <climits>
#include <cmath>
#include <limits>
#include <new>
#include <string>
#include <vector>

#include "bluetile/analysis/discrepancy.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/core/density_grid.h"
#include "bluetile/core/error.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/point_table.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/text.h"
#include "bluetile/relax/band_fill.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/relax/progressive.h"
#include "bluetile/relax/stipple.h"
#include "bluetile/relax/wang_lattice.h"
#include "bluetile/relax/void_order.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/sampling/plot_order.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tiler.h"
#include "bluetile/voronoi/exact_engine.h"
#include "bluetile/voronoi/site_grid.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::error_of;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

// A grid as a program might fill one by hand: its size and its texels apart.
DensityGrid grid(int width, int height, std::size_t texels, float value = 1.0f) {
  DensityGrid g;
  g.width = width;
  g.height = height;
  g.texels.assign(texels, value);
  return g;
}

DensityGrid with_texel(float value) {
  DensityGrid g(2, 1, 1.0f);
  g.texels[1] = value;
  return g;
}

// sample_density divided by a width of 0 (SIGFPE), placed points outside the domain from texels
// beyond the grid's size, and called negative and NaN texels "zero everywhere".
TEST(ApiContract, DensitySamplingChecksTheGrid) {
  Rng rng(1);
  EXPECT_EQ(error_of([&] { sample_density(grid(0, 4, 4), Domain{}, 5, rng); }), "density grid of 0 x 4 texels holds 4 values");
  EXPECT_EQ(error_of([&] { sample_density(grid(2, 2, 8), Domain{}, 5, rng); }), "density grid of 2 x 2 texels holds 8 values");
  EXPECT_EQ(error_of([&] { sample_density(with_texel(-1.0f), Domain{}, 5, rng); }),
            "density texel (1, 0) is -1: densities must be finite and non-negative");
  EXPECT_EQ(error_of([&] { sample_density(with_texel(NAN), Domain{}, 5, rng); }),
            "density texel (1, 0) is nan: densities must be finite and non-negative");
  EXPECT_EQ(error_of([&] { sample_density(with_texel(INFINITY), Domain{}, 5, rng); }),
            "density texel (1, 0) is inf: densities must be finite and non-negative");
  EXPECT_EQ(error_of([] { density_random_points(grid(0, 4, 4), 5, 1); }), "density grid of 0 x 4 texels holds 4 values");
  // What was refused before still is, in its words.
  EXPECT_EQ(error_of([&] { sample_density(DensityGrid{}, Domain{}, 5, rng); }), "cannot sample an empty density grid");
  EXPECT_EQ(error_of([&] { sample_density(DensityGrid(2, 2, 0.0f), Domain{}, 5, rng); }),
            "cannot sample a density that is zero everywhere");
}

// The random starts took any count, and a huge one failed with std::length_error or
// std::bad_alloc, naming nothing; they take what the front ends take (kMaxSetPoints).
TEST(ApiContract, RandomStartsTakeAtMostTheLimitOfASet) {
  const std::string expected = " 18446744073709551615: expected at most 100000000 points";
  const std::size_t huge = std::numeric_limits<std::size_t>::max();
  EXPECT_EQ(error_of([&] { uniform_random_points(huge, 1); }), "uniform random points: count" + expected);
  EXPECT_EQ(error_of([&] { density_random_points(DensityGrid(2, 2, 1.0f), huge, 1); }), "density sampling: count" + expected);
  EXPECT_EQ(error_of([&] { place_new_points({{0.5, 0.5}}, huge, Placement::random, 1); }), "new points: count" + expected);
  EXPECT_EQ(error_of([&] { place_new_points({{0.5, 0.5}}, kMaxSetPoints + 1, Placement::gaps, 1); }),
            "new points: count 100000001: expected at most 100000000 points");
  EXPECT_EQ(uniform_random_points(3, 1).size(), 3u);
}

// weight_for_point_density squared a negative texel into a positive weight and took grids of any
// shape; stipple_domain made a domain of NaN x NaN from a 0 x 0 grid holding texels;
// stipple_dot_radius read an empty map past its end (SIGSEGV), gave NaN for a map zero everywhere
// and infinity for no dots; stipple_scene asked for any number of dots' memory.
TEST(ApiContract, WeightsAndStipplesCheckTheMap) {
  EXPECT_EQ(error_of([] { weight_for_point_density(with_texel(-3.0f)); }),
            "density texel (1, 0) is -3: densities must be finite and non-negative");
  EXPECT_EQ(error_of([] { weight_for_point_density(grid(2, 2, 3)); }), "density grid of 2 x 2 texels holds 3 values");
  EXPECT_EQ(error_of([] { weight_for_point_density(DensityGrid{}); }), "density grid of 0 x 0 texels holds 0 values");
  EXPECT_EQ(error_of([] { stipple_domain(grid(0, 0, 4)); }), "density grid of 0 x 0 texels holds 4 values");
  EXPECT_EQ(error_of([] { stipple_domain(grid(-2, -3, 6)); }), "density grid of -2 x -3 texels holds 6 values");
  StippleStart start;
  start.count = 10;
  EXPECT_EQ(error_of([&] { stipple_scene(grid(2, 2, 3), start); }), "density grid of 2 x 2 texels holds 3 values");
  start.count = std::size_t{1} << 40;  // std::bad_alloc before
  EXPECT_EQ(error_of([&] { stipple_scene(DensityGrid(2, 2, 1.0f), start); }),
            "stipple: count: expected 1 to 100000000, got 1099511627776");
  EXPECT_EQ(error_of([] { stipple_dot_radius(DensityGrid{}, Domain{}, 10); }), "stipple: the density map is empty");
  EXPECT_EQ(error_of([] { stipple_dot_radius(DensityGrid(2, 2, 0.0f), Domain{}, 10); }),
            "stipple: the density map is zero everywhere");
  EXPECT_EQ(error_of([] { stipple_dot_radius(DensityGrid(2, 2, 1.0f), Domain{}, 0); }),
            "stipple: the count of dots must be at least 1");
  EXPECT_EQ(error_of([] { stipple_dot_radius(DensityGrid(2, 2, 1.0f), Domain{{0.0, 1.0}}, 10); }),
            "stipple: domain 0 x 1 is not a finite positive size");
  // A good map still gives its radius: half the hexagonal spacing of 10 dots in the unit square.
  EXPECT_DOUBLE_EQ(stipple_dot_radius(DensityGrid(2, 2, 1.0f), Domain{}, 10), 0.5 * hexagonal_spacing(10.0));
}

// sample_bilinear asserted (nothing in a release build): an empty grid was read at index 0
// (SIGSEGV), a grid holding fewer texels than its size past its end, and a NaN coordinate was
// converted to an integer. DensityGrid(-1, 4) asked for 2^64 texels (std::length_error).
TEST(ApiContract, GridLookupsAndConstructionCheckTheirArguments) {
  EXPECT_EQ(error_of([] { sample_bilinear(DensityGrid{}, {0.5, 0.5}); }), "density grid of 0 x 0 texels holds 0 values");
  EXPECT_EQ(error_of([] { sample_bilinear(grid(2, 2, 1), {0.9, 0.9}); }), "density grid of 2 x 2 texels holds 1 values");
  EXPECT_EQ(error_of([] { sample_bilinear(DensityGrid(2, 2, 1.0f), {kNaN, 0.5}); }),
            "density lookup at (nan, 0.5): expected finite coordinates");
  EXPECT_EQ(error_of([] { DensityGrid(-1, 4); }), "density grid of -1 x 4 texels: expected a width and a height of at least 0");
  EXPECT_DOUBLE_EQ(sample_bilinear(DensityGrid(2, 2, 3.0f), {0.25, 0.75}), 3.0);
}

// A zero, negative or NaN domain: nearest_neighbour_distances never ended on a NaN side and gave
// distances of no domain on a zero one; radial_distribution and sample_density returned results.
TEST(ApiContract, DomainsMustHaveAFinitePositiveSize) {
  const std::vector<Point> points = uniform_random_points(50, 1);
  EXPECT_EQ(error_of([&] { nearest_neighbour_distances(points, Domain{{kNaN, 1.0}}); }),
            "nearest-neighbour distances: domain nan x 1 is not a finite positive size");
  EXPECT_EQ(error_of([&] { nearest_neighbour_distances(points, Domain{{0.0, 0.0}}); }),
            "nearest-neighbour distances: domain 0 x 0 is not a finite positive size");
  EXPECT_EQ(error_of([&] { nearest_neighbour_stats(points, Domain{{-1.0, 1.0}}); }),
            "nearest-neighbour distances: domain -1 x 1 is not a finite positive size");
  EXPECT_EQ(error_of([&] { radial_distribution(points, {}, Domain{{0.0, 0.0}}); }),
            "radial distribution: domain 0 x 0 is not a finite positive size");
  Rng rng(1);
  EXPECT_EQ(error_of([&] { sample_density(DensityGrid(2, 2, 1.0f), Domain{{-1.0, 1.0}}, 5, rng); }),
            "density sampling: domain -1 x 1 is not a finite positive size");
  EXPECT_EQ(error_of([&] { sample_density(DensityGrid(2, 2, 1.0f), Domain{{1.0, kInf}}, 5, rng); }),
            "density sampling: domain 1 x inf is not a finite positive size");
  // The engines' words are unchanged.
  ExactEngine engine;
  EXPECT_EQ(error_of([&] { engine.compute(make_scene(points, Domain{{0.0, 2.0}})); }),
            "scene: domain 0 x 2 is not a finite positive size");
}

// Rng::below(0) divided by zero (SIGFPE).
TEST(ApiContract, RandomIntegerBelowZeroIsRefused) {
  Rng rng(1);
  EXPECT_EQ(error_of([&] { rng.below(0); }), "bound 0: expected at least 1 (no integer lies in [0, 0))");
  EXPECT_EQ(rng.below(1), 0u);
}

// move_to_centroids read cells past their end (SIGSEGV) when it was given fewer than the scenes
// or a scene fewer than its wanted sites, and wrote past a scene's sites for a wanted range
// beyond them. Nothing moves before the check.
TEST(ApiContract, MoveToCentroidsChecksItsCellsFirst) {
  std::vector<Scene> scenes{make_scene(uniform_random_points(10, 1)), make_scene(uniform_random_points(4, 2))};
  const std::vector<Point> before = scenes[0].sites;
  std::vector<SceneCells> none;
  EXPECT_EQ(error_of([&] { move_to_centroids(scenes, none); }), "move_to_centroids: 2 scenes but cells for 0");
  std::vector<SceneCells> cells(2);
  cells[0].cells.resize(10);
  cells[1].cells.resize(3);
  EXPECT_EQ(error_of([&] { move_to_centroids(scenes, cells); }), "move_to_centroids: scene 1 has 4 wanted sites but 3 cells");
  EXPECT_EQ(scenes[0].sites, before);
  cells[1].cells.resize(4);
  scenes[1].wanted_end = 40;
  EXPECT_EQ(error_of([&] { move_to_centroids(scenes, cells); }),
            "move_to_centroids: scene 1: wanted sites [0, 40) do not lie inside its 4 sites");
}

// path_length read dots[order[i]] for any index (SIGSEGV).
TEST(ApiContract, PathLengthChecksTheOrder) {
  const std::vector<Point> dots{{0.0, 0.0}, {3.0, 4.0}};
  const std::vector<std::size_t> bad{0, 1, 1000000};
  EXPECT_EQ(error_of([&] { path_length(dots, bad); }), "order[2] 1000000: expected an index below 2, the number of dots");
  const std::vector<std::size_t> good{0, 1};
  EXPECT_DOUBLE_EQ(path_length(dots, good), 5.0);
}

// Points the measures cannot take: discrepancies gave NaN for a NaN point and figures of no set
// for one outside [0, 1]^2; rdf_power_spectrum and radial_distribution dropped NaN and infinite
// points from every bin without a word.
TEST(ApiContract, AnalysisRefusesPointsItCannotMeasure) {
  std::vector<Point> points = uniform_random_points(100, 1);
  points[2] = {kNaN, 0.5};
  EXPECT_EQ(error_of([&] { discrepancies(points); }), "discrepancies: point 2 is not finite");
  EXPECT_EQ(error_of([&] { rdf_power_spectrum(points); }), "RDF power spectrum: point 2 is not finite");
  EXPECT_EQ(error_of([&] { radial_distribution(points); }), "radial distribution: point 2 is not finite");
  points[2] = {kInf, 0.5};
  EXPECT_EQ(error_of([&] { rdf_power_spectrum(points); }), "RDF power spectrum: point 2 is not finite");
  points[2] = {3.0, 0.5};
  EXPECT_EQ(error_of([&] { discrepancies(points); }), "discrepancies: point 2 (3, 0.5) lies outside [0, 1]^2");
  // The closed square is the function's domain: 1 is in it.
  points[2] = {1.0, 0.0};
  EXPECT_NO_THROW(discrepancies(points));
}

// A Periodogram filled by hand with fewer values than size^2 was read past its end.
TEST(ApiContract, PeriodogramsMustHoldTheirValues) {
  Periodogram short_one;
  short_one.size = 8;
  short_one.power.assign(3, 1.0);
  EXPECT_EQ(error_of([&] { radial_power(short_one); }), "periodogram of size 8 holds 3 values, expected 64");
  Periodogram full;
  full.size = 8;
  full.power.assign(64, 1.0);
  const std::vector<Periodogram> both{full, short_one};
  EXPECT_EQ(error_of([&] { average_periodograms(both); }), "periodogram of size 8 holds 3 values, expected 64");
  EXPECT_EQ(radial_power(full).size(), 4u);
  // The default size of a count past 4.6e16 overflowed an int (undefined; 0 in a release build).
  EXPECT_EQ(error_of([] { default_periodogram_size(SIZE_MAX); }),
            "count 18446744073709551615: the default periodogram size 2 floor(5 sqrt(N)) passes the largest int");
  EXPECT_EQ(default_periodogram_size(1000), 316);
}

// void_order threw std::length_error for `ranked` beyond the points (an assert in a debug build),
// and ordered with a kernel width of 0, a negative or NaN one, and NaN points, without a word;
// add_levels passed its void_sigma on unchecked, after relaxing.
TEST(ApiContract, VoidOrderChecksItsArguments) {
  std::vector<Point> points = uniform_random_points(100, 1);
  EXPECT_EQ(error_of([&] { void_order(std::span<const Point>(points).first(10), 20); }), "ranked 20: expected at most the 10 points");
  EXPECT_EQ(error_of([&] { void_order(points, 0, 0.0); }), "void_sigma: expected 0.1 to 4 hexagonal spacings, got 0");
  EXPECT_EQ(error_of([&] { void_order(points, 0, -1.0); }), "void_sigma: expected 0.1 to 4 hexagonal spacings, got -1");
  EXPECT_EQ(error_of([&] { void_order(points, 0, kNaN); }), "void_sigma: expected 0.1 to 4 hexagonal spacings, got nan");
  EXPECT_EQ(void_order(points, 0).size(), 100u);
  points[3] = {kNaN, kNaN};
  EXPECT_EQ(error_of([&] { void_order(points, 0); }), "void order: point 3 is not finite");

  ExactEngine engine;
  HierarchyOptions options;
  options.count = 10;
  options.levels = 2;
  options.iterations = 1;
  options.void_sigma = kNaN;
  EXPECT_EQ(error_of([&] { add_levels(engine, PointSet{}, options); }), "void_sigma: expected 0.1 to 4 hexagonal spacings, got nan");
}

// level_size cast an infinite ratio, or one whose level passes 2^64 points, to an integer
// (undefined; it came back as 18446744073709551606 for 10 points).
TEST(ApiContract, LevelSizeChecksTheRatio) {
  EXPECT_EQ(error_of([] { level_size(10, 0, kInf); }), "ratio inf: expected 0 (add points) or a finite ratio above 1");
  EXPECT_EQ(error_of([] { level_size(10, 0, kNaN); }), "ratio nan: expected 0 (add points) or a finite ratio above 1");
  EXPECT_EQ(error_of([] { level_size(10, 0, -2.0); }), "ratio -2: expected 0 (add points) or a finite ratio above 1");
  EXPECT_EQ(error_of([] { level_size(10, 0, 1e300); }), "ratio 1e+300: a set of 10 points would grow past 2^64");
  EXPECT_EQ(level_size(10, 0, 2.0), 10u);
  EXPECT_EQ(level_size(10, 7, 0.0), 7u);
}

// A level column whose length is not the number of points was read past its end by the writers
// (format_points, write_point_table, point_sets_table) and by add_level; count_levels gave -3 for a
// level of -4 and overflowed at INT_MAX; the text writers wrote "nan" that no reader takes back;
// add_level threw std::length_error for a huge count.
TEST(ApiContract, PointSetsAreCheckedBeforeUse) {
  PointSet short_levels;
  short_levels.points = {{0.5, 0.5}, {0.2, 0.2}};
  short_levels.levels = {1};
  EXPECT_EQ(error_of([&] { format_points(short_levels); }), "levels: 1 for 2 points");
  EXPECT_EQ(error_of([&] { count_levels(short_levels); }), "levels: 1 for 2 points");
  const std::vector<PointSet> sets{short_levels};
  std::string bytes;
  const ByteSink sink = [&](std::string_view b) { bytes += b; };
  EXPECT_EQ(error_of([&] { write_point_table(TableFormat::npy, sets, {}, "t.npy", sink); }), "t.npy: set 0, levels: 1 for 2 points");
  EXPECT_EQ(error_of([&] { write_point_table(TableFormat::text, sets, {}, "t.txt", sink); }), "t.txt: set 0, levels: 1 for 2 points");
  EXPECT_EQ(error_of([&] { point_sets_table(sets); }), "set 0, levels: 1 for 2 points");
  EXPECT_TRUE(bytes.empty());
  ExactEngine engine;
  LevelOptions level;
  level.add = 5;
  level.iterations = 1;
  EXPECT_EQ(error_of([&] { add_level(engine, short_levels, level); }), "levels: 1 for 2 points");
  level.add = std::size_t{1} << 62;
  EXPECT_EQ(error_of([&] { add_level(engine, PointSet{}, level); }), "add: expected 1 to 100000000, got 4611686018427387904");

  PointSet odd;
  odd.points = {{0.5, 0.5}};
  odd.levels = {-4};
  EXPECT_EQ(error_of([&] { count_levels(odd); }), "level -4 of point 0: expected 0 to 1000000");
  EXPECT_EQ(error_of([&] { format_points(odd); }), "point 0: level -4 is outside 0 to 1000000: no reader would take it back");
  odd.levels = {INT_MAX};
  EXPECT_EQ(error_of([&] { count_levels(odd); }), "level 2147483647 of point 0: expected 0 to 1000000");
  odd.levels = {3};
  EXPECT_EQ(count_levels(odd), 4);

  PointSet nan_point;
  nan_point.points = {{0.25, 0.5}, {kNaN, 0.5}};
  EXPECT_EQ(error_of([&] { format_points(nan_point); }), "point 1 (nan, 0.5) is not finite: no reader would take it back");
  // Outside [0, 1) is written as given (a tiled window's plane coordinates).
  PointSet plane;
  plane.points = {{3.5, -0.5}};
  EXPECT_EQ(format_points(plane), "3.5 -0.5\n");
}

// Rng::point drew NaN coordinates for a NaN or zero side (NaN times 0) and 0 for a negative one.
TEST(ApiContract, RandomPointsNeedADomain) {
  Rng rng(1);
  EXPECT_EQ(error_of([&] { rng.point(Domain{{0.0, 1.0}}); }), "random point: domain 0 x 1 is not a finite positive size");
  EXPECT_EQ(error_of([&] { rng.point(Domain{{kNaN, 1.0}}); }), "random point: domain nan x 1 is not a finite positive size");
  EXPECT_EQ(error_of([&] { rng.point(Domain{{-2.0, 1.0}}); }), "random point: domain -2 x 1 is not a finite positive size");
  const Point p = rng.point(Domain{{2.0, 0.5}});
  EXPECT_TRUE(p.x >= 0.0 && p.x < 2.0 && p.y >= 0.0 && p.y < 0.5);
}

// Points outside [0, 1)^2 fell into a border bucket of the nearest-neighbour search, the gap
// placement and the fill, where the searches did not look for them: wrong distances (2 of 200
// here), places chosen as if the point were elsewhere. On the torus they are now their copy
// inside; in a bounded domain, or in a tile, they are refused, as NaN points are everywhere.
TEST(ApiContract, PointsOutsideTheDomainAreWrappedOnTheTorusAndRefusedElsewhere) {
  const std::vector<Point> inside = uniform_random_points(200, 3);
  std::vector<Point> outside = inside;
  for (std::size_t i = 0; i < outside.size(); i += 7) outside[i] += Point{3.0, -2.0};
  outside[5] += Point{-1.0, 4.0};
  // Their copies inside: `inside` to rounding (x + 3 - 3 need not be x).
  std::vector<Point> copies = outside;
  for (Point& p : copies) p = wrap_point(p, Domain{});
  const std::vector<double> nearest = nearest_neighbour_distances(outside);
  const std::vector<double> expected = nearest_neighbour_distances(inside);
  ASSERT_EQ(nearest.size(), expected.size());
  for (std::size_t i = 0; i < nearest.size(); ++i) EXPECT_NEAR(nearest[i], expected[i], 1e-12) << "point " << i;
  EXPECT_EQ(place_new_points(outside, 30, Placement::gaps, 4), place_new_points(copies, 30, Placement::gaps, 4));
  EXPECT_EQ(band_fill_torus(outside, 20, FillOptions{}), band_fill_torus(copies, 20, FillOptions{}));

  EXPECT_EQ(error_of([&] { nearest_neighbour_distances(outside, Domain{}, Boundary::bounded); }),
            "nearest-neighbour distances: point 0 (" + shortest_text(outside[0].x) + ", " +
                shortest_text(outside[0].y) + ") lies outside the bounded domain 1 x 1");
  const std::vector<std::vector<Point>> tiles{{{0.5, 0.5}, {1.0, 0.25}}};
  std::vector<std::vector<FillSource>> sources(1);
  sources[0].push_back({0, Point{0.0, 0.0}, 1.0});
  EXPECT_EQ(error_of([&] { band_fill(tiles, sources, 3, FillOptions{}); }),
            "band fill: tile 0, point 1 (1, 0.25) lies outside [0, 1)^2");

  std::vector<Point> with_nan = inside;
  with_nan[4] = {kNaN, 0.5};
  EXPECT_EQ(error_of([&] { place_new_points(with_nan, 30, Placement::gaps, 4); }), "new points: point 4 is not finite");
  EXPECT_EQ(error_of([&] { band_fill_torus(with_nan, 20, FillOptions{}); }), "band fill: point 4 is not finite");
}

// A bucket size of 0 asked for 2^14 x 2^14 buckets (a gigabyte of bucket starts), NaN for a
// number of buckets of no value (lround of NaN).
TEST(ApiContract, SiteGridsNeedAPositiveBucketSize) {
  const std::vector<Point> sites = uniform_random_points(50, 1);
  EXPECT_EQ(error_of([&] { SiteGrid(sites, Domain{}, 0.0); }), "site grid: sites per bucket 0: expected a finite positive number");
  EXPECT_EQ(error_of([&] { SiteGrid(sites, Domain{}, kNaN); }), "site grid: sites per bucket nan: expected a finite positive number");
  EXPECT_EQ(error_of([&] { SiteGrid(sites, Domain{}, -1.0); }), "site grid: sites per bucket -1: expected a finite positive number");
  EXPECT_EQ(error_of([&] { SiteGrid(sites, Domain{{kInf, 1.0}}, 2.0); }), "site grid: domain inf x 1 is not a finite positive size");
  EXPECT_EQ(SiteGrid(sites, Domain{}, 2.0).site_indices().size(), 50u);
}

// fit_map_rectangle gave the window back for a map of 0 or fewer texels, a NaN rectangle for a
// NaN window and a line for a window of no width.
TEST(ApiContract, MapFittingChecksTheMapAndTheWindow) {
  EXPECT_EQ(error_of([] { fit_map_rectangle(Window{}, 0, 10, MapFit::contain); }), "density map of 0 x 10 texels: expected at least 1 x 1");
  EXPECT_EQ(error_of([] { fit_map_rectangle(Window{}, -3, 10, MapFit::stretch); }), "density map of -3 x 10 texels: expected at least 1 x 1");
  EXPECT_EQ(error_of([] { fit_map_rectangle(Window{0, 0, kNaN, 1}, 3, 10, MapFit::contain); }),
            "map window must be finite with x1 > x0 and y1 > y0");
  EXPECT_EQ(error_of([] { fit_map_rectangle(Window{0, 0, 0, 1}, 3, 10, MapFit::cover); }),
            "map window must be finite with x1 > x0 and y1 > y0");
  const Window fitted = fit_map_rectangle(Window{0, 0, 2, 1}, 1, 1, MapFit::contain);
  EXPECT_DOUBLE_EQ(fitted.x0, 0.5);
  EXPECT_DOUBLE_EQ(fitted.x1, 1.5);
  EXPECT_DOUBLE_EQ(fitted.y1, 1.0);
}

// The periodogram's memory estimate took any size (17440 bytes for -2) and the normalised
// frequency divided by a count of 0 (infinity) or an area of 0.
TEST(ApiContract, SpectralHelpersCheckTheirSizes) {
  EXPECT_EQ(error_of([] { periodogram_memory_bytes(0, -2); }), "periodogram memory: size -2: expected at least 2");
  EXPECT_EQ(error_of([] { periodogram_memory_bytes(100, 0); }), "periodogram memory: size 0: expected at least 2");
  EXPECT_GT(periodogram_memory_bytes(100, 64), 8u * 64 * 64);
  // Past what compute_periodogram takes, still estimated: the memory checks refuse such planes first.
  EXPECT_GT(periodogram_memory_bytes(100, 80270), std::size_t{8} * 80270 * 80270);
  EXPECT_EQ(error_of([] { normalised_frequency(3.0, 0); }), "normalised frequency: no points, so no Nyquist frequency");
  EXPECT_EQ(error_of([] { normalised_frequency(3.0, 10, 0.0); }), "normalised frequency: area 0 is not a finite positive number");
  EXPECT_EQ(error_of([] { normalised_frequency(3.0, 10, kNaN); }), "normalised frequency: area nan is not a finite positive number");
  EXPECT_DOUBLE_EQ(normalised_frequency(5.0, 100), 1.0);
}

// relax_lloyd over no scenes ran its 80 iterations of nothing and said so.
TEST(ApiContract, RelaxingNoScenesRunsNoIteration) {
  ExactEngine engine;
  std::vector<Scene> none;
  int calls = 0;
  LloydOptions options;
  options.on_iteration = [&](const LloydIteration&) { ++calls; };
  const LloydResult result = relax_lloyd(engine, none, options);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_EQ(result.last.iteration, 0);
  EXPECT_EQ(calls, 0);
}

// decorrelate_filled_level read past the end of a shorter tile and of a short source list, took
// points outside their tile, NaN or negative spacings, and a level beginning past the tiles' points
// or a negative step count, without a word (it returned at once or moved nothing).
TEST(ApiContract, FilledLatticeStepsCheckTheirTilesAndOptions) {
  TilePoints tiles{uniform_random_points(12, 1), uniform_random_points(12, 2)};
  std::vector<std::vector<FillSource>> sources(2);
  for (std::size_t t = 0; t < 2; ++t)
    for (int dx = -1; dx <= 1; ++dx) sources[t].push_back({t, Point{static_cast<double>(dx), 0.0}, 1.0});
  FilledLatticeOptions options;
  options.iterations = 2;
  TilePoints moved = tiles;
  decorrelate_filled_level(moved, 6, sources, options);
  EXPECT_NE(moved, tiles);  // the good case moves points

  TilePoints uneven = tiles;
  uneven[1].pop_back();
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(uneven, 6, sources, options); }),
            "filled lattice steps: every tile must hold the same number of points");
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(tiles, 6, std::span(sources).first(1), options); }),
            "filled lattice steps: one source list per tile is needed");
  TilePoints outside = tiles;
  outside[1][3] = {1.5, 0.5};
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(outside, 6, sources, options); }),
            "filled lattice steps: tile 1, point 3 (1.5, 0.5) lies outside [0, 1)^2");
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(tiles, 13, sources, options); }),
            "filled lattice steps: the level begins at point 13, past the tiles' 12 points");
  FilledLatticeOptions bad = options;
  bad.spacing = kNaN;
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(tiles, 6, sources, bad); }),
            "spacing: expected 0.01 to 2 hexagonal spacings, got nan");
  bad = options;
  bad.iterations = -1;
  EXPECT_EQ(error_of([&] { decorrelate_filled_level(tiles, 6, sources, bad); }), "iterations: expected 0 to 100000, got -1");
}

// A default-made result or input struct of the public headers is zero throughout: Cell's centroid,
// TiledPoint's positions and FillSource's shift were glm vectors left uninitialised (glm's
// default constructor does not initialise), where every other field of them starts at 0.
template <typename T>
T* made_over_garbage(unsigned char (&storage)[sizeof(T)]) {
  std::fill(std::begin(storage), std::end(storage), static_cast<unsigned char>(0xff));  // NaN as doubles
  return new (storage) T;  // default-initialised, as `T value;` is
}

TEST(ApiContract, DefaultMadeStructsAreZeroThroughout) {
  alignas(Cell) unsigned char cell_bytes[sizeof(Cell)];
  const Cell* cell = made_over_garbage<Cell>(cell_bytes);
  EXPECT_EQ(cell->centroid, Point(0.0, 0.0));
  EXPECT_EQ(cell->area, 0.0);
  cell->~Cell();
  alignas(TiledPoint) unsigned char tiled_bytes[sizeof(TiledPoint)];
  const TiledPoint* tiled = made_over_garbage<TiledPoint>(tiled_bytes);
  EXPECT_EQ(tiled->position, Point(0.0, 0.0));
  EXPECT_EQ(tiled->local, Point(0.0, 0.0));
  EXPECT_EQ(tiled->rank, 0u);
  alignas(FillSource) unsigned char source_bytes[sizeof(FillSource)];
  const FillSource* source = made_over_garbage<FillSource>(source_bytes);
  EXPECT_EQ(source->shift, Point(0.0, 0.0));
  EXPECT_EQ(source->weight, 1.0);
}

}  // namespace
}  // namespace bluetile
