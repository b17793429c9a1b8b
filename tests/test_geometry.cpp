// The shared geometry of the engines: convex polygons (clipping, moments) against hand-computed
// values, and the periodic site grid against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bluetile/core/rng.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/site_grid.h"
#include "test_support.h"

namespace bluetile {
namespace {

TEST(Polygon, MomentsOfRectanglesAndTriangles) {
  // [0,1]^2: area 1, centroid (1/2, 1/2), integral of x^2 + y^2 = 2/3.
  const std::vector<Point> square = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  PolygonMoments m = polygon_moments(square);
  EXPECT_DOUBLE_EQ(m.area(), 1.0);
  EXPECT_DOUBLE_EQ(m.centroid().x, 0.5);
  EXPECT_DOUBLE_EQ(m.centroid().y, 0.5);
  EXPECT_DOUBLE_EQ(m.first_moment().x, 0.5);
  EXPECT_DOUBLE_EQ(m.second_moment(), 2.0 / 3.0);
  // [-a,a] x [-b,b]: area 4ab, second moment 4ab (a^2 + b^2) / 3.
  const double a = 0.3, b = 0.7;
  ConvexPolygon box;
  box.reset_rectangle({-a, -b}, {a, b});
  m = box.moments();
  EXPECT_NEAR(m.area(), 4 * a * b, 1e-15);
  EXPECT_NEAR(m.second_moment(), 4 * a * b * (a * a + b * b) / 3, 1e-15);
  EXPECT_NEAR(box.max_radius_squared(), a * a + b * b, 1e-15);
  // Triangle (0,0), (3,0), (0,3): area 9/2, centroid (1,1), integral of x^2+y^2 = 2 * 27/4.
  const std::vector<Point> triangle = {{0, 0}, {3, 0}, {0, 3}};
  m = polygon_moments(triangle);
  EXPECT_DOUBLE_EQ(m.area(), 4.5);
  EXPECT_DOUBLE_EQ(m.centroid().x, 1.0);
  EXPECT_DOUBLE_EQ(m.centroid().y, 1.0);
  EXPECT_DOUBLE_EQ(m.second_moment(), 13.5);
  // Clockwise order gives the negative area; no polygon, no area and the origin as centroid.
  m = polygon_moments(std::vector<Point>{{0, 0}, {0, 3}, {3, 0}});
  EXPECT_DOUBLE_EQ(m.area(), -4.5);
  EXPECT_EQ(m.centroid(), Point(0.0, 0.0));
  EXPECT_EQ(polygon_moments({}).area(), 0.0);
}

// Far more vertices than the buffers start with (64): each growth moves the buffers in the
// middle of a clip, which must then read the sides it computed, not freed memory (the sanitizer
// build catches a stale pointer; the area catches the wrong cuts it would make).
TEST(Polygon, ClipsPastTheInitialCapacity) {
  constexpr int kSides = 300;
  const double pi = std::acos(-1.0);
  ConvexPolygon p;
  p.reset_rectangle({-2, -2}, {2, 2});
  // Bisectors with points at distance 2 are the tangents of the unit circle: a regular polygon
  // around it, of area n tan(pi / n) and n vertices.
  for (int k = 0; k < kSides; ++k) {
    const double a = 2.0 * pi * k / kSides;
    p.clip_by_bisector({2.0 * std::cos(a), 2.0 * std::sin(a)}, static_cast<std::uint32_t>(k));
  }
  EXPECT_EQ(p.size(), static_cast<std::size_t>(kSides));
  EXPECT_NEAR(p.moments().area(), kSides * std::tan(pi / kSides), 1e-12);
  EXPECT_NEAR(p.max_radius_squared(), 1.0 / std::pow(std::cos(pi / kSides), 2), 1e-12);
}

// Rounding lets one clip add two vertices: bisectors of nearly coincident sites (1e-15 apart)
// cross one another near the middle of the cell, and the last of them finds the vertices there
// on alternating sides. Here that clip meets a polygon of 63 vertices, one short of the buffers'
// first size, and leaves 65: with room for only n + 1 it wrote past the buffer (the sanitizer
// build catches that write). The inputs were found by a search over such bisectors.
TEST(Polygon, OneClipCanGainTwoVerticesAtTheBuffersEnd) {
  const Point nearly_coincident[5] = {
      {-0x1.91649e46c0362p-5, -0x1.51070c1e6c366p-6}, {-0x1.91649e46c02f5p-5, -0x1.51070c1e6c4dep-6},
      {-0x1.91649e46c02c9p-5, -0x1.51070c1e6c537p-6}, {-0x1.91649e46c034p-5, -0x1.51070c1e6c3c1p-6},
      {-0x1.91649e46c0361p-5, -0x1.51070c1e6c357p-6}};
  // Tangents of the circle of radius 0.99 on the far side from the sites (+-0.7 rad around the
  // direction away from them), each cutting one more vertex into the square without reaching
  // the vertices the nearly coincident bisectors made.
  constexpr int kPadding = 58;
  const double away = std::atan2(-nearly_coincident[0].y, -nearly_coincident[0].x);
  auto pad = [&](ConvexPolygon& p) {
    for (int k = 0; k < kPadding; ++k) {
      const double a = away + (2.0 * k / (kPadding - 1) - 1.0) * 0.7;
      p.clip_by_bisector({1.98 * std::cos(a), 1.98 * std::sin(a)}, static_cast<std::uint32_t>(100 + k));
    }
  };
  ConvexPolygon p;
  p.reset_rectangle({-1, -1}, {1, 1});
  for (int k = 0; k < 4; ++k) p.clip_by_bisector(nearly_coincident[k], static_cast<std::uint32_t>(k));
  pad(p);
  ASSERT_EQ(p.size(), 63u);
  p.clip_by_bisector(nearly_coincident[4], 4);
  ASSERT_EQ(p.size(), 65u);
  // The five bisectors agree to about 1e-15: the same square and tangents cut by the last one
  // alone has the same area and first moment to well within 1e-12.
  ConvexPolygon reference;
  reference.reset_rectangle({-1, -1}, {1, 1});
  pad(reference);
  reference.clip_by_bisector(nearly_coincident[4], 4);
  EXPECT_NEAR(p.moments().area(), reference.moments().area(), 1e-12);
  EXPECT_NEAR(p.moments().first_moment().x, reference.moments().first_moment().x, 1e-12);
  EXPECT_NEAR(p.moments().first_moment().y, reference.moments().first_moment().y, 1e-12);
  for (const PolygonVertex& v : p.vertices()) EXPECT_LE(std::max(std::abs(v.p.x), std::abs(v.p.y)), 1.0);
}

TEST(Polygon, ClipByBisector) {
  ConvexPolygon p;
  p.reset_rectangle({-1, -1}, {1, 1}, 7);
  // The bisector with (1, 0) is x = 1/2: [-1, 1/2] x [-1, 1] is left.
  p.clip_by_bisector({1.0, 0.0}, 3);
  ASSERT_EQ(p.size(), 4u);
  PolygonMoments m = p.moments();
  EXPECT_DOUBLE_EQ(m.area(), 3.0);
  EXPECT_DOUBLE_EQ(m.centroid().x, -0.25);
  EXPECT_DOUBLE_EQ(m.centroid().y, 0.0);
  EXPECT_DOUBLE_EQ(p.max_radius_squared(), 2.0);
  int labelled = 0;
  for (const PolygonVertex& v : p.vertices()) labelled += v.edge_label == 3;
  EXPECT_EQ(labelled, 1);  // exactly one edge lies on the bisector
  // A bisector through a vertex cuts nothing and adds no duplicate: d = (1, 2) gives the line
  // x + 2y = 5/2, through the vertex (1/2, 1).
  p.clip_by_bisector({1.0, 2.0}, 4);
  EXPECT_EQ(p.size(), 4u);
  EXPECT_DOUBLE_EQ(p.moments().area(), 3.0);
  // A far site cannot reach the polygon (|d|^2 >= 4 r^2): unchanged.
  p.clip_by_bisector({3.0, 0.0}, 5);
  EXPECT_EQ(p.size(), 4u);
  // The four lattice neighbours at distance 1 leave the unit square around the site: second
  // moment 1/6.
  ConvexPolygon cell;
  cell.reset_rectangle({-2, -2}, {2, 2});
  for (Point d : {Point{1, 0}, Point{-1, 0}, Point{0, 1}, Point{0, -1}}) cell.clip_by_bisector(d, 0);
  EXPECT_DOUBLE_EQ(cell.moments().area(), 1.0);
  EXPECT_DOUBLE_EQ(cell.moments().second_moment(), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(cell.max_radius_squared(), 0.5);
  // Everything cut away: empty.
  cell.clip({1.0, 0.0}, -10.0, 0);
  EXPECT_TRUE(cell.empty());
}

TEST(Polygon, HalfPlanesSplitAreaAndMoments) {
  // Clipping by a line and by its opposite half-plane partitions the polygon: areas and first
  // moments add up to the whole, over random lines.
  Rng rng(31);
  for (int k = 0; k < 200; ++k) {
    ConvexPolygon whole, left, right;
    const Point lo{-rng.uniform(), -rng.uniform()}, hi{rng.uniform(), rng.uniform()};
    for (ConvexPolygon* p : {&whole, &left, &right}) p->reset_rectangle(lo, hi);
    const double angle = 6.283185307179586 * rng.uniform();
    const Point n{std::cos(angle), std::sin(angle)};
    const double offset = rng.uniform() - 0.5;
    left.clip(n, offset, 1);
    right.clip(-n, -offset, 2);
    const PolygonMoments w = whole.moments(), l = left.moments(), r = right.moments();
    EXPECT_NEAR(l.area() + r.area(), w.area(), 1e-14) << k;
    EXPECT_NEAR(l.first_moment().x + r.first_moment().x, w.first_moment().x, 1e-14) << k;
    EXPECT_NEAR(l.first_moment().y + r.first_moment().y, w.first_moment().y, 1e-14) << k;
    EXPECT_NEAR(l.second_moment() + r.second_moment(), w.second_moment(), 1e-14) << k;
  }
}

TEST(SiteGrid, BucketsHoldEverySiteOnceInIndexOrder) {
  const Domain domain{{2.0, 0.5}};
  Rng rng(32);
  std::vector<Point> sites(777);
  for (Point& p : sites) p = rng.point(domain);
  SiteGrid grid(sites, domain, 1.0);
  EXPECT_NEAR(static_cast<double>(grid.columns() * grid.rows()), 777.0, 60.0);
  std::vector<int> seen(sites.size(), 0);
  for (std::size_t b = 0; b < grid.bucket_count(); ++b) {
    auto in = grid.sites_in_bucket(b);
    EXPECT_TRUE(std::is_sorted(in.begin(), in.end()));
    for (std::uint32_t s : in) {
      ++seen[s];
      auto [cx, cy] = grid.bucket_coordinates(sites[s]);
      EXPECT_EQ(static_cast<std::size_t>(cy * grid.columns() + cx), b);
    }
  }
  for (int count : seen) EXPECT_EQ(count, 1);
  // The search order starts at the own bucket and never decreases.
  const auto& order = grid.search_order();
  ASSERT_FALSE(order.empty());
  EXPECT_EQ(order[0].dx, 0);
  EXPECT_EQ(order[0].dy, 0);
  for (std::size_t k = 1; k < order.size(); ++k) EXPECT_LE(order[k - 1].lower_bound_squared, order[k].lower_bound_squared);
  // A bucket named outside the grid is a periodic copy: offsets shift by one period.
  std::uint32_t first = grid.sites_in_bucket(0).empty() ? 0 : grid.sites_in_bucket(0)[0];
  grid.for_each_in_bucket(grid.columns(), 0, Point{0.0, 0.0}, [&](std::uint32_t s, Point d) {
    if (s == first) {
      EXPECT_EQ(d.x, sites[s].x + domain.size.x);
      EXPECT_EQ(d.y, sites[s].y);
    }
  });
}

// The search order by its definition: every offset within the radius whose bound lies below
// the radius in bucket sides, in dy-major scan order, stably sorted by (bound, centre distance).
std::vector<SiteGrid::SearchStep> search_order_by_definition(Point cell) {
  const long r = SiteGrid::kSearchRadius;
  const double limit = static_cast<double>(r) * std::min(cell.x, cell.y);
  std::vector<SiteGrid::SearchStep> order;
  for (long dy = -r; dy <= r; ++dy) {
    for (long dx = -r; dx <= r; ++dx) {
      const double gx = static_cast<double>(std::max(0L, std::labs(dx) - 1)) * cell.x;
      const double gy = static_cast<double>(std::max(0L, std::labs(dy) - 1)) * cell.y;
      if (gx * gx + gy * gy < limit * limit) order.push_back({dx, dy, gx * gx + gy * gy});
    }
  }
  std::stable_sort(order.begin(), order.end(), [](const SiteGrid::SearchStep& a, const SiteGrid::SearchStep& b) {
    if (a.lower_bound_squared != b.lower_bound_squared) return a.lower_bound_squared < b.lower_bound_squared;
    return a.dx * a.dx + a.dy * a.dy < b.dx * b.dx + b.dy * b.dy;
  });
  return order;
}

TEST(SiteGrid, SearchOrderIsTheStableSortOfTheScan) {
  // Square buckets (every (a, b) group ties with (b, a)), buckets of ratio 2 and 3 (more exact
  // ties), and random shapes, small and large. Grids reuse the order of the grid before when its
  // bounds sort the same way, so shapes come also in runs: nearly square after square (the same
  // group order without the ties), the same shape scaled, and slightly changed.
  std::vector<Domain> domains = {{{1.0, 1.0}}, {{2.0, 1.0}}, {{3.0, 1.0}}, {{1.0, 3.0}}, {{0.37, 0.37}}, {{1e-3, 2e-3}},
                                 {{1.0, 1.0}}, {{1.0, 1.0 + 1e-12}}, {{1.0, 1.0}}, {{1.0 + 1e-12, 1.0}}, {{1.0, 1.0}}};
  Rng rng(34);
  for (int k = 0; k < 300; ++k) {
    const Point size{0.05 + 3.0 * rng.uniform(), 0.05 + 3.0 * rng.uniform()};
    domains.push_back({size});
    domains.push_back({size * 1.5});
    domains.push_back({{size.x * (1.0 + 0.01 * rng.uniform()), size.y}});
  }
  std::size_t compared = 0;
  for (const Domain& domain : domains) {
    for (std::size_t n : {1u, 7u, 30u, 200u}) {
      std::vector<Point> sites(n);
      for (Point& p : sites) p = rng.point(domain);
      const SiteGrid grid(sites, domain, 1.0);
      const std::vector<SiteGrid::SearchStep> expected = search_order_by_definition(grid.cell_size());
      const SiteGrid::SearchOrder& order = grid.search_order();
      ASSERT_EQ(order.size(), expected.size()) << domain.size.x << " x " << domain.size.y << ", " << n << " sites";
      for (std::size_t i = 0; i < order.size(); ++i) {
        ASSERT_EQ(order[i].dx, expected[i].dx) << "step " << i << ", cell " << grid.cell_size().x << " x " << grid.cell_size().y;
        ASSERT_EQ(order[i].dy, expected[i].dy) << "step " << i << ", cell " << grid.cell_size().x << " x " << grid.cell_size().y;
        ASSERT_EQ(order[i].lower_bound_squared, expected[i].lower_bound_squared) << "step " << i;
      }
      compared += order.size();
    }
  }
  EXPECT_GT(compared, 300000u);
}

TEST(SiteGrid, NearVisitsASupersetOnce) {
  const Domain domain{{1.0, 1.0}};
  Rng rng(33);
  std::vector<Point> sites(300);
  for (Point& p : sites) p = rng.point(domain);
  sites.push_back({0.0, 0.0});
  sites.push_back({std::nextafter(1.0, 0.0), 0.999});
  SiteGrid grid(sites, domain, 1.0);
  for (double reach : {0.01, 0.05, 0.2, 0.7}) {
    for (int k = 0; k < 50; ++k) {
      const Point p = k < 2 ? sites[300 + k] : rng.point(domain);
      std::vector<int> visits(sites.size(), 0);
      grid.for_each_near(p, reach, [&](std::uint32_t s) { ++visits[s]; });
      for (std::size_t s = 0; s < sites.size(); ++s) {
        EXPECT_LE(visits[s], 1) << s;
        if (torus_distance(p, sites[s], domain) <= reach) {
          EXPECT_EQ(visits[s], 1) << "reach " << reach << " site " << s;
        }
      }
    }
  }
}

}  // namespace
}  // namespace bluetile
