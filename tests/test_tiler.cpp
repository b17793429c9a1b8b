// The plane tiler: random access, windows, positions far from the origin, thinning by rank.
// References are brute force (every point of every cell, filtered by hand), the tile rules'
// own colours, counting statistics and hand-computed bounds.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include "bluetile/core/cancel_check.h"
#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tiler.h"
#include "bluetile/tiling/tiling_plan.h"
#include "test_support.h"
#include "tiler_support.h"

namespace bluetile {
namespace {

using test::make_test_tile_set;

bool less_point(Point a, Point b) { return a.x < b.x || (a.x == b.x && a.y < b.y); }

std::vector<Point> sorted(std::vector<Point> points) {
  std::sort(points.begin(), points.end(), less_point);
  return points;
}

std::vector<Point> window_points(const Tiler& tiler, const Window& w, const Thinning* thinning = nullptr) {
  std::vector<Point> out;
  tiler.append_points(w, thinning, out);
  return out;
}

// Every point of every cell the window touches (two cells of margin), kept by the rule written
// out again here, then filtered by the window.
std::vector<Point> brute_force(const Tiler& tiler, const Window& w, const Thinning* thinning) {
  std::vector<Point> out;
  double s = tiler.tile_size();
  for (auto j = static_cast<std::int64_t>(std::floor(w.y0 / s)) - 2; j <= static_cast<std::int64_t>(w.y1 / s) + 2; ++j)
    for (auto i = static_cast<std::int64_t>(std::floor(w.x0 / s)) - 2; i <= static_cast<std::int64_t>(w.x1 / s) + 2;
         ++i) {
      int tile = tiler.tile_at(i, j);
      const Tile& t = tiler.tile_set().tiles[static_cast<std::size_t>(tile)];
      for (std::size_t k = 0; k < t.points.size(); ++k) {
        Point p{(static_cast<double>(i) + t.points[k].x) * s, (static_cast<double>(j) + t.points[k].y) * s};
        if (!(p.x >= w.x0 && p.x < w.x1 && p.y >= w.y0 && p.y < w.y1)) continue;
        if (thinning != nullptr) {
          double rank_fraction = (t.ranks[k] + Thinning::dither(i, j, tiler.seed())) / static_cast<double>(t.points.size());
          if (!(rank_fraction < thinning->fraction_at(p))) continue;
        }
        out.push_back(p);
      }
    }
  return out;
}

Thinning ramp_map(const Window& over, int width = 37, int height = 11) {
  std::vector<float> texels(static_cast<std::size_t>(width * height));
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c)
      texels[static_cast<std::size_t>(r * width + c)] = static_cast<float>((c + 1.0) / width * (0.5 + 0.5 * r / height));
  return Thinning::from_map(width, height, texels, over, 1.0);
}

TEST(Tiler, WindowMatchesBruteForceWithAndWithoutThinning) {
  Tiler tiler(make_test_tile_set(TileSetKind::wang8, 6, 1), 17, 0.75);
  Window w{-3.3, -1.05, 4.2, 2.6};
  Thinning uniform = Thinning::uniform(0.4);
  Thinning map = ramp_map({-4.0, -2.0, 5.0, 3.0});
  for (const Thinning* thinning : std::initializer_list<const Thinning*>{nullptr, &uniform, &map}) {
    std::vector<Point> fast = sorted(window_points(tiler, w, thinning));
    std::vector<Point> slow = sorted(brute_force(tiler, w, thinning));
    ASSERT_EQ(fast.size(), slow.size());
    EXPECT_EQ(fast, slow);
    EXPECT_GT(fast.size(), 50u);
  }
}

TEST(Tiler, ACancelCheckEndsAWindowBetweenRows) {
  Tiler tiler(make_test_tile_set(TileSetKind::wang8, 6, 1), 17, 0.75);
  const Window w{-3.3, -1.05, 4.2, 2.6};
  const std::size_t unchecked = tiler.tiled_points(w).size();
  std::size_t rows = 0;
  {
    CancelCheck count([&] { ++rows; });
    EXPECT_EQ(tiler.tiled_points(w).size(), unchecked);  // checking changes nothing
  }
  EXPECT_EQ(rows, static_cast<std::size_t>(tiler.cells(w).rows()));
  CancelCheck cancel([] { throw std::runtime_error("cancelled"); });
  EXPECT_THROW(tiler.tiled_points(w), std::runtime_error);
}

TEST(Tiler, OverlappingWindowsAgreeBitForBit) {
  Tiler tiler(make_test_tile_set(TileSetKind::corner16, 5, 2), 99, 1.3);
  Thinning map = ramp_map({-10.0, -10.0, 10.0, 10.0});
  Window a{-7.7, -2.2, 3.1, 6.4}, b{-1.9, 1.05, 8.8, 9.0};
  Window both{std::max(a.x0, b.x0), std::max(a.y0, b.y0), std::min(a.x1, b.x1), std::min(a.y1, b.y1)};
  for (const Thinning* thinning : std::initializer_list<const Thinning*>{nullptr, &map}) {
    auto inside = [&](const std::vector<Point>& points) {
      std::vector<Point> kept;
      for (Point p : points)
        if (both.contains(p)) kept.push_back(p);
      return sorted(kept);
    };
    std::vector<Point> from_a = inside(window_points(tiler, a, thinning));
    std::vector<Point> from_b = inside(window_points(tiler, b, thinning));
    std::vector<Point> direct = sorted(window_points(tiler, both, thinning));
    EXPECT_EQ(from_a, from_b);
    EXPECT_EQ(from_a, direct);
    EXPECT_GT(direct.size(), 20u);
  }
}

TEST(Tiler, WindowIsTheUnionOfItsQuarters) {
  Tiler tiler(make_test_tile_set(TileSetKind::wang16, 4, 3), 5, 0.5);
  Thinning map = ramp_map({0.0, 0.0, 3.0, 3.0});
  Window w{-2.0, -1.25, 5.5, 3.0};
  double mx = 1.1, my = 0.5;  // an edge through the middle of tiles, and one on a tile edge
  Window quarters[4] = {{w.x0, w.y0, mx, my}, {mx, w.y0, w.x1, my}, {w.x0, my, mx, w.y1}, {mx, my, w.x1, w.y1}};
  for (const Thinning* thinning : std::initializer_list<const Thinning*>{nullptr, &map}) {
    std::vector<Point> whole = window_points(tiler, w, thinning);
    std::vector<Point> parts;
    for (const Window& q : quarters) tiler.append_points(q, thinning, parts);
    EXPECT_EQ(parts.size(), whole.size());
    EXPECT_EQ(sorted(parts), sorted(whole));
  }
}

TEST(Tiler, NeighbouringTilesMatchTheirColours) {
  for (TileSetKind kind : tile_set_kinds()) {
    Tiler tiler(make_test_tile_set(kind, 2, 4), 1234, 1.0);
    const TileRules& rules = tiler.rules();
    for (std::int64_t j = -40; j < 40; ++j)
      for (std::int64_t i = -40; i < 40; ++i) {
        int here = tiler.tile_at(i, j);
        ASSERT_TRUE(rules.fits_east(here, tiler.tile_at(i + 1, j))) << tile_set_kind_name(kind) << " " << i << "," << j;
        ASSERT_TRUE(rules.fits_north(here, tiler.tile_at(i, j + 1))) << tile_set_kind_name(kind) << " " << i << "," << j;
        const TileColours& c = rules.colours(here);
        const TileColours& east = rules.colours(tiler.tile_at(i + 1, j));
        const TileColours& north = rules.colours(tiler.tile_at(i, j + 1));
        if (rules.corner_coloured()) {
          EXPECT_EQ(c[1], east[0]);  // NE == east's NW
          EXPECT_EQ(c[1], north[2]);  // NE == north's SE
        } else {
          EXPECT_EQ(c[1], east[3]);  // E == east's W
          EXPECT_EQ(c[0], north[2]);  // N == north's S
        }
      }
  }
}

TEST(Tiler, TileFrequenciesMatchTheSetsDistribution) {
  // Every kind draws its tiles uniformly (independent fair bits or trits per edge, cell or corner):
  // chi-square over a 200 x 200 window against equal frequencies, at p = 0.001.
  const std::map<int, double> chi2_limit = {{8, 24.32}, {16, 37.70}, {81, 124.8}};  // 81: Wilson-Hilferty
  for (TileSetKind kind : tile_set_kinds()) {
    for (std::uint64_t seed : {1ull, 77ull}) {
      Tiler tiler(make_test_tile_set(kind, 1, 5), seed, 1.0);
      std::vector<double> counts(static_cast<std::size_t>(tiler.rules().tile_count()), 0.0);
      const int side = 200;
      for (std::int64_t j = -side / 2; j < side / 2; ++j)
        for (std::int64_t i = 1000000 - side / 2; i < 1000000 + side / 2; ++i) counts[tiler.tile_at(i, j)] += 1.0;
      double expected = static_cast<double>(side * side) / static_cast<double>(counts.size());
      double chi2 = 0.0;
      for (double c : counts) chi2 += (c - expected) * (c - expected) / expected;
      EXPECT_LT(chi2, chi2_limit.at(static_cast<int>(counts.size()))) << tile_set_kind_name(kind) << " seed " << seed;
    }
  }
}

TEST(Tiler, PointsCarryTheirCellTileRankAndLevel) {
  TileSet set = make_test_tile_set(TileSetKind::wang8, 5, 6);
  Tiler tiler(set, 8, 2.0);
  Window w{-3.0, -5.0, 3.5, 1.0};
  Thinning map = ramp_map(w);
  std::vector<TiledPoint> points = tiler.tiled_points(w, &map);
  ASSERT_GT(points.size(), 20u);
  WindowPoints iterator(tiler, w, &map);
  std::size_t index = 0;
  for (TiledPoint p; iterator.next(p); ++index) {
    ASSERT_LT(index, points.size());
    const TiledPoint& q = points[index];
    EXPECT_EQ(std::tie(p.position.x, p.position.y, p.i, p.j, p.tile, p.level, p.rank),
              std::tie(q.position.x, q.position.y, q.i, q.j, q.tile, q.level, q.rank));
  }
  EXPECT_EQ(index, points.size());
  for (const TiledPoint& p : points) {
    EXPECT_EQ(p.tile, tiler.tile_at(p.i, p.j));
    const Tile& t = set.tiles[static_cast<std::size_t>(p.tile)];
    auto k = static_cast<std::size_t>(std::find(t.ranks.begin(), t.ranks.end(), p.rank) - t.ranks.begin());
    ASSERT_LT(k, t.points.size());
    EXPECT_EQ(p.local, t.points[k]);
    EXPECT_EQ(p.level, t.levels[k]);
    EXPECT_EQ(p.position, tiler.position(p.i, p.j, p.local));
    EXPECT_TRUE(w.contains(p.position));
  }
  std::vector<Point> positions = window_points(tiler, w, &map);
  ASSERT_EQ(positions.size(), points.size());
  for (std::size_t k = 0; k < positions.size(); ++k) EXPECT_EQ(positions[k], points[k].position);
}

TEST(Tiler, FarFromTheOriginPositionsStayWithinTheStatedBound) {
  TileSet set = make_test_tile_set(TileSetKind::wang8, 4, 7);
  for (double size : {1.0, 0.37, 3.0}) {
    Tiler tiler(set, 3, size);
    for (double far : {1e6, -1e6, 0.0}) {
      Window w{far * size - 2.5 * size, far * size + 0.5 * size, far * size + 2.5 * size, far * size + 4.0 * size};
      std::vector<TiledPoint> points = tiler.tiled_points(w);
      // The window is 5 x 3.5 tiles with 16 points a tile: all of its whole cells are there.
      ASSERT_GE(points.size(), 4u * 3u * 16u);
      for (const TiledPoint& p : points) {
        long double exact_x = (static_cast<long double>(p.i) + p.local.x) * size;
        long double exact_y = (static_cast<long double>(p.j) + p.local.y) * size;
        double bound_x = 0x1.0p-53 * (std::fabs(static_cast<double>(p.i)) + 1.0) * size +
                         0.5 * (std::nextafter(std::fabs(p.position.x), INFINITY) - std::fabs(p.position.x));
        double bound_y = 0x1.0p-53 * (std::fabs(static_cast<double>(p.j)) + 1.0) * size +
                         0.5 * (std::nextafter(std::fabs(p.position.y), INFINITY) - std::fabs(p.position.y));
        EXPECT_LE(std::fabs(static_cast<double>(p.position.x - exact_x)), bound_x);
        EXPECT_LE(std::fabs(static_cast<double>(p.position.y - exact_y)), bound_y);
        // The stated bound in tile units: below 2.3e-10 of a tile at 10^6 tiles.
        EXPECT_LT(std::fabs(static_cast<double>(p.position.x - exact_x)) / size, 2.4e-10);
        // Relative positions: the tile-local point recovered from the plane position.
        EXPECT_NEAR(p.position.x / size - static_cast<double>(p.i), p.local.x, 4e-10);
        EXPECT_NEAR(p.position.y / size - static_cast<double>(p.j), p.local.y, 4e-10);
      }
    }
  }
  Tiler tiler(set, 3, 1.0);
  EXPECT_THROW(tiler.tiled_points({3e9, 0.0, 3e9 + 1.0, 1.0}), Error);
}

TEST(Tiler, ConstantDensityKeepsDensityTimesAreaWithinTheStatisticalBound) {
  // 16 points a tile, fraction f: each cell keeps ceil(16 f - u) points, u uniform: mean 16 f,
  // variance at most 1/4 per cell. A tile-aligned window of T cells: |count - 16 f T| < 4 sqrt(T / 4).
  TileSet set = make_test_tile_set(TileSetKind::wang8, 4, 8);
  Tiler tiler(set, 21, 0.5);
  Window w{-20.0, -10.0, 20.0, 15.0};
  double cells = (w.width() / 0.5) * (w.height() / 0.5);
  for (double f : {1.0, 0.5, 0.3, 0.05, 0.01}) {
    Thinning uniform = Thinning::uniform(f);
    double expected = f * tiler.full_density() * w.area();
    double count = static_cast<double>(window_points(tiler, w, &uniform).size());
    EXPECT_LT(std::fabs(count - expected), 4.0 * std::sqrt(cells / 4.0) + 1e-9) << "fraction " << f;
    // A map that is the same everywhere keeps exactly the points the uniform thinning keeps.
    std::vector<float> flat(12, 0.7f);
    Thinning map = Thinning::from_map(4, 3, flat, {-1.0, -1.0, 1.0, 1.0}, f);
    EXPECT_EQ(window_points(tiler, w, &map), window_points(tiler, w, &uniform)) << "fraction " << f;
  }
}

TEST(Tiler, TwoLevelMapCountsFollowTheMap) {
  // Left half of the map 1, right half 0.25 (64 texels: the bilinear step spans one texel, 1/64
  // of the window); count in the left and right thirds, far from the step.
  TileSet set = make_test_tile_set(TileSetKind::wang8, 8, 9);
  Tiler tiler(set, 4, 1.0);
  Window w{0.0, 0.0, 48.0, 24.0};
  std::vector<float> texels(64 * 2);
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < 64; ++c) texels[static_cast<std::size_t>(r * 64 + c)] = c < 32 ? 1.0f : 0.25f;
  Thinning map = Thinning::from_map(64, 2, texels, w, 1.0);
  std::vector<Point> points = window_points(tiler, w, &map);
  double left = 0.0, right = 0.0;
  for (Point p : points) {
    if (p.x < 16.0) left += 1.0;
    if (p.x >= 32.0) right += 1.0;
  }
  double expected_left = 64.0 * 16.0 * 24.0, expected_right = 0.25 * expected_left;
  // Whole cells keep exactly 64 (left) and 16 - u rounded up (right): 384 cells each.
  EXPECT_EQ(left, expected_left);
  EXPECT_LT(std::fabs(right - expected_right), 4.0 * std::sqrt(384.0 / 4.0));
  EXPECT_NEAR(left / right, 4.0, 0.05);
}

TEST(Tiler, MinimumDistanceScalesAsOneOverSquareRootOfDensity) {
  // Thinning to a fraction f keeps a prefix of every cell's rank order, so when the prefixes are
  // spread across seams the nearest pair is 1/sqrt(f) farther. The test set's tiles are not
  // relaxed against each other, so here every tile holds the same torus-spread points (a
  // periodic plane whose prefixes are spread across seams by construction); the cells' dithers
  // still differ, so neighbouring cells keep prefixes one point apart. Measured against f = 1/4
  // (seeds 10..14): min distance x sqrt(f), relative, 1.12-1.23 at 1/16, 1.22-1.36 at 1/64,
  // 1.29-1.43 at 1/256 (greedy prefixes of few points are a little better spread). The margin
  // allows 0.9 to 1.7; a random subset would fall to about sqrt(f / (1/4)), 1/8 at 1/256.
  TileSet set = make_test_tile_set(TileSetKind::wang8, 16, 12, /*same_points=*/true);
  Tiler tiler(set, 11, 1.0);
  Window w{-6.0, -6.0, 6.0, 6.0};
  auto scaled_min = [&](double f) {
    Thinning uniform = Thinning::uniform(f);
    return test::min_distance(window_points(tiler, w, &uniform)) * std::sqrt(f);
  };
  double reference = scaled_min(0.25);
  ASSERT_GT(reference, 0.0);
  for (double f : {1.0 / 16.0, 1.0 / 64.0, 1.0 / 256.0}) {
    double ratio = scaled_min(f) / reference;
    EXPECT_GT(ratio, 0.9) << "fraction " << f;
    EXPECT_LT(ratio, 1.7) << "fraction " << f;
  }
}

TEST(Tiler, SampledFractionIsTheBilinearInterpolationOfTheTexels) {
  // Hand-computed: 2 x 2 texels 0, 1 (bottom), 2, 3 (top) over [0, 2]^2, centres at 0.5 and
  // 1.5; the largest is 3, max fraction 0.6: f = 0.2 * bilinear.
  std::vector<float> texels = {0.0f, 1.0f, 2.0f, 3.0f};
  Thinning map = Thinning::from_map(2, 2, texels, {0.0, 0.0, 2.0, 2.0}, 0.6);
  EXPECT_NEAR(map.fraction_at({0.5, 0.5}), 0.0, 1e-7);
  EXPECT_NEAR(map.fraction_at({1.5, 1.5}), 0.6, 1e-7);
  EXPECT_NEAR(map.fraction_at({1.0, 1.0}), 0.2 * 1.5, 1e-7);
  EXPECT_NEAR(map.fraction_at({1.25, 0.5}), 0.2 * 0.75, 1e-7);
  EXPECT_NEAR(map.fraction_at({0.5, 1.25}), 0.2 * 1.5, 1e-7);
  EXPECT_NEAR(map.fraction_at({-5.0, 0.0}), 0.0, 1e-7);      // edge continued
  EXPECT_NEAR(map.fraction_at({9.0, 9.0}), 0.6, 1e-7);
  EXPECT_NEAR(map.max_fraction_in({0.0, 0.0, 0.6, 0.6}), 0.6, 1e-7);  // the bound may be loose...
  EXPECT_NEAR(map.max_fraction_in({0.0, 0.0, 0.4, 0.4}), 0.2 * 1.0 * 3.0, 1e-7);
  // ...but never below (or, for the minimum, above) any value in the box.
  EXPECT_NEAR(map.fraction_bounds({0.0, 0.0, 0.4, 0.4}).min, 0.0, 1e-7);
  EXPECT_NEAR(map.fraction_bounds({1.6, 1.6, 1.9, 1.9}).min, 0.6, 1e-7);
  Thinning ramp = ramp_map({-3.0, -2.0, 4.0, 5.0});
  Rng rng(12);
  for (int trial = 0; trial < 2000; ++trial) {
    double x = -4.0 + 9.0 * rng.uniform(), y = -3.0 + 9.0 * rng.uniform();
    double w = 2.0 * rng.uniform(), h = 2.0 * rng.uniform();
    Window box{x, y, x + w, y + h};
    Thinning::Bounds bounds = ramp.fraction_bounds(box);
    for (int k = 0; k < 8; ++k) {
      double f = ramp.fraction_at({x + w * rng.uniform(), y + h * rng.uniform()});
      ASSERT_LE(f, bounds.max);
      ASSERT_GE(f, bounds.min);
    }
  }
}

TEST(Tiler, DitherIsPinned) {
  // Pinned outputs: the rank dither and a window's first points stay the same on every platform.
  double a = Thinning::dither(0, 0, 1), b = Thinning::dither(-5, 1000000, 1), c = Thinning::dither(0, 0, 2);
  EXPECT_NE(a, b);
  EXPECT_NE(a, c);
  char text[80];
  std::snprintf(text, sizeof text, "%.17g %.17g %.17g", a, b, c);
  EXPECT_STREQ(text, "0.635121647351234 0.22386163006265947 0.21569477393262981");
}

TEST(Tiler, BadInputIsRefused) {
  TileSet set = make_test_tile_set(TileSetKind::wang8, 2, 13);
  EXPECT_THROW(Tiler(set, 1, 0.0), Error);
  EXPECT_THROW(Tiler(set, 1, -1.0), Error);
  EXPECT_THROW(Tiler(set, 1, NAN), Error);
  TileSet broken = set;
  broken.tiles[3].ranks[0] = broken.tiles[3].ranks[1];
  EXPECT_THROW(Tiler(broken, 1, 1.0), Error);
  Tiler tiler(set, 1, 1.0);
  EXPECT_THROW(tiler.tiled_points({1.0, 0.0, 1.0, 1.0}), Error);
  EXPECT_THROW(tiler.tiled_points({0.0, 2.0, 1.0, 1.0}), Error);
  EXPECT_THROW(tiler.tiled_points({0.0, 0.0, INFINITY, 1.0}), Error);
  EXPECT_THROW(Thinning::uniform(0.0), Error);
  EXPECT_THROW(Thinning::uniform(1.5), Error);
  EXPECT_THROW(Thinning::uniform(NAN), Error);
  std::vector<float> zeros(4, 0.0f), bad = {1.0f, NAN, 1.0f, 1.0f}, negative = {1.0f, -1.0f, 1.0f, 1.0f};
  EXPECT_THROW(Thinning::from_map(2, 2, zeros, {0, 0, 1, 1}, 1.0), Error);
  EXPECT_THROW(Thinning::from_map(2, 2, bad, {0, 0, 1, 1}, 1.0), Error);
  EXPECT_THROW(Thinning::from_map(2, 2, negative, {0, 0, 1, 1}, 1.0), Error);
  EXPECT_THROW(Thinning::from_map(3, 2, zeros, {0, 0, 1, 1}, 1.0), Error);
  std::vector<float> ones(4, 1.0f);
  EXPECT_THROW(Thinning::from_map(2, 2, ones, {0, 0, 0, 1}, 1.0), Error);
  EXPECT_THROW(Thinning::from_map(2, 2, ones, {0, 0, 1, 1}, 0.0), Error);
  // The plan took the map's mean over its largest texel first: a zero map was "density -nan is
  // too low for tiles of size 1", a NaN texel "density nan ...".
  TilingRequest request;
  request.window = {0, 0, 2, 2};
  request.count = 100;
  DensityGrid zero_map(2, 2, 0.0f), nan_map(2, 2, 1.0f);
  nan_map.texels[1] = NAN;
  EXPECT_EQ(test::error_of([&] { plan_tiling(set, &zero_map, request); }), "density map is zero everywhere");
  EXPECT_EQ(test::error_of([&] { plan_tiling(set, &nan_map, request); }),
            "density map: texel 1, 0 is nan (must be finite and >= 0)");
}

// The request's rules, in the library's words and in a front end's names (the tool and the Python
// module each wrote them again, in their own words, before calling the plan).
TEST(TilingPlan, RequestRulesSpeakEachFrontEndsNames) {
  const TilingNames options{"--tile-size", "--density", "--max-density", "--count", "--density-map", " "};
  const TilingNames arguments{"tile_size", "density", "max_density", "count", "density_map", "="};
  const auto error = [](TilingRequest r, bool map, const TilingNames& names) {
    return test::error_of([&] { check_tiling_request(r, map, names); });
  };
  TilingRequest ok;
  ok.window = {0, 0, 2, 1};
  EXPECT_EQ(error(ok, false, {}), "");
  TilingRequest r = ok;
  r.density = 50;
  EXPECT_EQ(error(r, true, {}), "density 50 is for uniform tilings; with a density map give max density or count");
  EXPECT_EQ(error(r, true, options), "--density 50 is for uniform tilings; with a --density-map give --max-density or --count");
  EXPECT_EQ(error(r, true, arguments), "density=50 is for uniform tilings; with a density_map give max_density or count");
  EXPECT_EQ(error(r, false, arguments), "");
  r = ok;
  r.max_density = 500;
  r.count = 300;
  EXPECT_EQ(error(r, false, {}), "max density 500 needs a density map: give one");
  EXPECT_EQ(error(r, true, arguments), "count and max_density exclude each other: give one");
  r.max_density = 0;
  EXPECT_EQ(error(r, false, options), "--count 300 needs a --density-map: give one");
  EXPECT_EQ(error(r, true, options), "");
  r = ok;
  r.tile_size = -0.5;
  EXPECT_EQ(error(r, false, arguments), "tile_size: expected a finite number >= 0 (0: not given), got -0.5");
  r = ok;
  r.count = NAN;
  EXPECT_EQ(error(r, true, options), "--count: expected a finite number >= 0 (0: not given), got nan");
  r = ok;
  r.window.y1 = 0;
  EXPECT_EQ(error(r, false, options), "region: Y1 must be greater than Y0, got Y0 0, Y1 0");
  // plan_tiling holds to the same rules, in the names it is given.
  const TileSet set = make_test_tile_set(TileSetKind::wang8, 4, 7);
  r = ok;
  r.density = 50;
  DensityGrid map(2, 2, 1.0f);
  EXPECT_EQ(test::error_of([&] { plan_tiling(set, &map, r, options); }), error(r, true, options));
  r.density = 1e9;
  r.tile_size = 1;
  EXPECT_EQ(test::error_of([&] { plan_tiling(set, nullptr, r, arguments); }),
            "density 1000000000 is more than tiles of size 1 hold (16 points per unit area): use a smaller tile_size or leave it out");
}

}  // namespace
}  // namespace bluetile

namespace bluetile {
namespace {

TEST(Tiler, MapFitsPlaceTheMapByHand) {
  // A 3 x 2 map on the 64:75 region [0, 64] x [0, 75] (narrower than the map): contain spans the
  // width, 64 x 128/3 centred at y 37.5; cover spans the height, 112.5 x 75 centred at x 32.
  const Window region{0.0, 0.0, 64.0, 75.0};
  const Window contain = fit_map_rectangle(region, 3, 2, MapFit::contain);
  EXPECT_EQ(contain.x0, 0.0);
  EXPECT_EQ(contain.x1, 64.0);
  EXPECT_DOUBLE_EQ(contain.y0, 37.5 - 64.0 / 3.0);
  EXPECT_DOUBLE_EQ(contain.y1, 37.5 + 64.0 / 3.0);
  const Window cover = fit_map_rectangle(region, 3, 2, MapFit::cover);
  EXPECT_DOUBLE_EQ(cover.x0, 32.0 - 56.25);
  EXPECT_DOUBLE_EQ(cover.x1, 32.0 + 56.25);
  EXPECT_EQ(cover.y0, 0.0);
  EXPECT_EQ(cover.y1, 75.0);
  // A map of the region's aspect is the region, to the bit, whatever the fit (0.1 x 0.3 is not 1:3
  // in binary).
  const Window thin{0.0, 0.0, 0.1, 0.3};
  for (MapFit fit : {MapFit::contain, MapFit::cover, MapFit::stretch}) {
    const Window w = fit_map_rectangle(thin, 100, 300, fit);
    EXPECT_TRUE(w.x0 == thin.x0 && w.x1 == thin.x1 && w.y0 == thin.y0 && w.y1 == thin.y1) << map_fit_name(fit);
  }
  EXPECT_EQ(parse_map_fit("cover"), MapFit::cover);
  EXPECT_THROW(parse_map_fit("fill"), Error);
  // contain: zero beside the map, the map's own values inside it.
  const std::vector<float> texels(6, 1.0f);
  const Thinning t = Thinning::from_fitted_map(3, 2, texels, region, MapFit::contain, 0.5);
  EXPECT_EQ(t.fraction_at({32.0, 37.5}), 0.5);
  EXPECT_EQ(t.fraction_at({32.0, 0.5}), 0.0);
  // The map's rectangle is half-open and its edge texels reach its edge: a uniform map fills it
  // exactly (a bilinear step used to take the density to zero over a texel across the edge).
  EXPECT_EQ(t.fraction_at({32.0, std::nextafter(contain.y1, 0.0)}), 0.5);
  EXPECT_EQ(t.fraction_at({32.0, contain.y1}), 0.0);
  EXPECT_EQ(t.fraction_at({32.0, contain.y0}), 0.5);
  EXPECT_EQ(t.fraction_at({32.0, std::nextafter(contain.y0, 0.0)}), 0.0);
  // Bounds of boxes across the edge, beside the map and inside it.
  const auto across = t.fraction_bounds({10.0, contain.y1 - 1.0, 20.0, contain.y1 + 1.0});
  EXPECT_EQ(across.min, 0.0);
  EXPECT_EQ(across.max, 0.5);
  const auto beside = t.fraction_bounds({10.0, contain.y1, 20.0, 75.0});
  EXPECT_EQ(beside.max, 0.0);
  const auto inside = t.fraction_bounds({10.0, 30.0, 20.0, 40.0});
  EXPECT_EQ(inside.min, 0.5);
  EXPECT_EQ(inside.max, 0.5);
}

}  // namespace
}  // namespace bluetile
