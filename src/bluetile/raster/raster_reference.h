// The host reference of the raster engine's device passes, with no Vulkan in it: the same sums
// as classify.comp and split_f64.comp from an ID image, for the tests to compare the device
// against, and the split of the boundary pixels the device leaves to the host (too many
// candidates, too wide a grid window, a piece too far from its site for the fixed-point range).
// Same arithmetic in the same order as the shaders, so on an IEEE device (lavapipe) the sums
// agree bit for bit.
#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

#include "bluetile/gpu/raster_layout.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/raster/raster_scene.h"
#include "bluetile/voronoi/site_grid.h"
#include "bluetile/voronoi/site_tree.h"

namespace bluetile {

// The site masks classify.comp reads: two bits per pixel (the pixel holds a site; it holds
// more than one), rows of (rx + 15) / 16 words.
std::vector<std::uint32_t> raster_site_masks(const RasterScene& scene);

// Fixed-point sums of a site's whole pixels and device-split pieces weighted by the scene's
// density (scenes whose density varies; host per-pixel work only): integrals of rho, rho x,
// rho y, rho |x|^2 relative to the site, at RasterScene's scales times density_scale. Integers,
// so the sums do not depend on the order of the pixels or the threads.
struct WeightedSums {
  std::int64_t mass = 0, x = 0, y = 0, second = 0;
};

// Classifies one scene's ID image (ids[j * rx + i]: scene-local site index + 1, 0 where no cone
// reached) as classify.comp does: samples and whole pixels are summed into `sums` (one per
// site), boundary pixels (j * rx + i) are appended to `boundary` in row order. Returns the
// number of uncovered samples.
std::uint32_t reference_classify(const RasterScene& scene, std::span<const std::uint32_t> ids, std::span<gpu::SiteSums> sums,
                                 std::vector<std::uint32_t>& boundary, std::span<WeightedSums> weighted = {});

// Wall seconds of reference_pass's stages, added to (for the profile: docs/BENCHMARKS.md).
struct ReferenceTiming {
  double classify = 0.0;  // sums of samples and whole pixels, boundary pixels listed
  double split = 0.0;     // boundary pixels split
  double reduce = 0.0;    // the threads' sums merged
};

// The whole per-pixel work of a pass on the host, threaded over rows when `parallel`: classify
// as reference_classify, then (when no sample is uncovered and `split` is set) split every
// boundary pixel as reference_split. Pixels the device would leave to the host are appended to
// `host_pixels` (in increasing order). The sums are exact integers, so they do not depend on the
// threads. Returns the uncovered samples; sets `boundary_count`. A scene with a varying density
// also fills `weighted` (one per site; empty otherwise). `timing`, when given, gets each stage's
// wall time added.
std::uint32_t reference_pass(const RasterScene& scene, std::span<const std::uint32_t> ids, std::span<gpu::SiteSums> sums,
                             bool split, bool parallel, std::vector<std::uint32_t>& host_pixels, std::uint64_t& boundary_count,
                             std::span<WeightedSums> weighted = {}, ReferenceTiming* timing = nullptr);

// Adds b's sums into a (farthest: the larger).
void add_sums(gpu::SiteSums& a, const gpu::SiteSums& b);

// Double sums of pieces (boundary pixels split on the host), and the same weighted by the
// scene's density when it varies.
struct PieceSums {
  double area = 0.0, x = 0.0, y = 0.0, second = 0.0;
  WeightedMoments weighted;
};

// The moments of a piece of `site`'s cell (vertices relative to the site's copy it belongs to)
// under the scene's varying density, relative to that copy; `moments` are its unweighted ones.
WeightedMoments piece_density(const RasterScene& scene, std::uint32_t site, const PolygonMoments& moments,
                              const ConvexPolygon& piece);

// Splits boundary pixel `pixel` of `scene` as split_f64.comp does, calling
// piece(site, moments relative to the site, the piece's polygon) for every piece of a wanted
// site. In a bounded scene only the sites themselves are candidates (no periodic copies). `nearest` is an
// upper bound on the distance from the pixel centre to its nearest site (the device takes the
// nearest corner owner). With `device_bounds` it gives up (returns false, no piece reported)
// where the device would leave the pixel to the host; without, it always splits.
template <typename Piece>
bool split_boundary_pixel(const RasterScene& scene, double nearest, std::uint32_t pixel, bool device_bounds, Piece piece);

// The device's upper bound on the nearest site to a pixel's centre: its nearest corner owner
// in the ID image (1e30 when no corner is covered).
double corner_owner_distance(const RasterScene& scene, std::span<const std::uint32_t> ids, std::uint32_t pixel);

// The device's fixed-point piece sums for `pixel` (reference for split_f64.comp). Returns false
// where the device would leave the pixel to the host.
bool reference_split(const RasterScene& scene, std::span<const std::uint32_t> ids, std::uint32_t pixel,
                     std::span<gpu::SiteSums> sums, std::span<WeightedSums> weighted = {});
// The host's double piece sums for `pixel`, whatever its candidates (pixels the device left).
void host_split(const RasterScene& scene, double nearest, std::uint32_t pixel, std::span<PieceSums> pieces);

// A scene's k-d tree, for boundary pixels whose grid window is wide (the nearest site far away,
// as for sites on a line: the window then holds O(N) sites, and the tree finds the few that
// matter in O(log N)), with each site's place in the window's traversal order.
struct RasterSearch {
  RasterSearch(const RasterScene& scene);
  SiteTree tree;
  std::vector<std::uint32_t> bucket;  // per site: its grid bucket (row * columns + column)
  std::vector<std::uint32_t> slot;    // per site: its place in the grid's site list
};
struct RasterSearchCache {
  std::once_flag once;
  std::unique_ptr<RasterSearch> search;
  // Sites the split's candidate searches examined (windows' sites, the tree's copies), for
  // RasterStats::split_sites_examined; threads add to it, a sum, so the same for any order.
  std::atomic<std::uint64_t> sites_examined{0};
};
// The scene's tree, built on the first call (thread-safe).
const RasterSearch& raster_search(const RasterScene& scene);

// Windows of more buckets than this search the tree (host splits only; the device's window is
// at most BLUETILE_MAX_WINDOW^2 buckets, so every pixel it takes keeps the grid's path).
inline constexpr long kTreeWindowBuckets = 144;

namespace raster_detail {
struct Candidate;
// The candidates of pixel (i, j) that split_boundary_pixel keeps, found by the tree instead of
// the grid window [lo, hi], in the window's order and with the same arithmetic, so the same.
void tree_candidates(const RasterScene& scene, int i, int j, double reach, long lo_x, long hi_x, long lo_y, long hi_y,
                     std::vector<Candidate>& out);
}  // namespace raster_detail

// ---- implementation of the template --------------------------------------------------------

namespace raster_detail {

struct Candidate {
  std::uint32_t site;
  int image_x, image_y;
  Point offset;  // from the pixel centre
  double distance_squared;
};

// Is copy t nearer than copy s0 at some corner of the pixel? `corner0`: the pixel's lower-left
// corner relative to s0, `h` its size. The distance difference is affine over the pixel, so a
// site nearer nowhere at the corners is the nearest nowhere in it.
inline bool nearer_at_some_corner(const RasterScene& scene, const Candidate& t, const Candidate& s0, Point corner0, Point h) {
  const Point domain = scene.scene->domain.size;
  const Point between = scene.sites[t.site] - scene.sites[s0.site];
  const Point d{between.x + static_cast<double>(t.image_x - s0.image_x) * domain.x,
                between.y + static_cast<double>(t.image_y - s0.image_y) * domain.y};
  const double offset = 0.5 * (d.x * d.x + d.y * d.y);
  bool nearer_somewhere = false;
  for (int corner = 0; corner < 4; ++corner) {
    const Point p{corner0.x + static_cast<double>(corner & 1) * h.x, corner0.y + static_cast<double>(corner >> 1) * h.y};
    nearer_somewhere = nearer_somewhere || p.x * d.x + p.y * d.y - offset > 0.0;
  }
  return nearer_somewhere;
}

inline double wrap_axis(double d, double period) { return d < -0.5 * period ? d + period : (d >= 0.5 * period ? d - period : d); }

inline long floor_division(long a, long n) { return a >= 0 ? (a < n ? 0 : a / n) : (a >= -n ? -1 : -((-a + n - 1) / n)); }

struct WindowSite {
  std::uint32_t site;
  int image_x, image_y;
};

// The sites of a window of grid buckets (periodic images included), coincident ones left out,
// in row order of buckets, then bucket order: the order the device visits them.
struct Window {
  std::uint64_t serial = 0;
  long lo_x = 0, hi_x = -1, lo_y = 0, hi_y = -1;
  std::vector<WindowSite> sites;

  void fill(const RasterScene& scene, const SiteGrid& grid, long x0, long x1, long y0, long y1) {
    serial = scene.serial;
    lo_x = x0, hi_x = x1, lo_y = y0, hi_y = y1;
    sites.clear();
    const long columns = grid.columns(), rows = grid.rows();
    const auto starts = grid.bucket_starts();
    const auto indices = grid.site_indices();
    if (!scene.periodic) {  // a bounded domain has no copies beyond its grid
      x0 = std::max(x0, 0L), x1 = std::min(x1, columns - 1);
      y0 = std::max(y0, 0L), y1 = std::min(y1, rows - 1);
    }
    for (long by = y0; by <= y1; ++by) {
      const long wy = floor_division(by, rows);
      for (long bx = x0; bx <= x1; ++bx) {
        const long wx = floor_division(bx, columns);
        const std::size_t b = static_cast<std::size_t>((by - wy * rows) * columns + (bx - wx * columns));
        for (std::uint32_t k = starts[b]; k < starts[b + 1]; ++k)
          if (!scene.coincident[indices[k]]) sites.push_back({indices[k], static_cast<int>(wx), static_cast<int>(wy)});
      }
    }
  }
};

}  // namespace raster_detail

template <typename Piece>
bool split_boundary_pixel(const RasterScene& scene, double nearest, std::uint32_t pixel, bool device_bounds, Piece piece) {
  using raster_detail::Candidate;
  const SiteGrid& grid = scene.grid();
  const int rx = scene.rx;
  const int i = static_cast<int>(pixel % static_cast<std::uint32_t>(rx)), j = static_cast<int>(pixel / static_cast<std::uint32_t>(rx));
  const Point h{scene.hx, scene.hy};
  const Point domain = scene.scene->domain.size;
  const Point lattice{static_cast<double>(i) * h.x, static_cast<double>(j) * h.y};
  const Point half_pixel = 0.5 * h;
  const double diagonal = std::sqrt(h.x * h.x + h.y * h.y) * (1.0 + 1.0 / 65536.0);
  auto site_from_sample = [&](std::uint32_t s) { return Point{scene.sites[s].x - lattice.x, scene.sites[s].y - lattice.y}; };
  if (nearest >= 1e30) return true;  // uncovered: the pass is redone
  double reach = nearest + diagonal;

  const Point centre{(static_cast<double>(i) + 0.5) * h.x, (static_cast<double>(j) + 0.5) * h.y};
  const Point bucket = grid.cell_size();
  const long lo_x = static_cast<long>(std::floor((centre.x - reach) / bucket.x)), hi_x = static_cast<long>(std::floor((centre.x + reach) / bucket.x));
  const long lo_y = static_cast<long>(std::floor((centre.y - reach) / bucket.y)), hi_y = static_cast<long>(std::floor((centre.y + reach) / bucket.y));
  if (device_bounds && (hi_x - lo_x >= BLUETILE_MAX_WINDOW || hi_y - lo_y >= BLUETILE_MAX_WINDOW)) return false;
  // The sites of the window, in the device's traversal order; neighbouring boundary pixels
  // mostly share a window, so the last one is kept per thread.
  thread_local std::vector<Candidate> candidates;  // a few per pixel
  candidates.clear();
  const bool wide = !device_bounds && (hi_x - lo_x + 1) * (hi_y - lo_y + 1) > kTreeWindowBuckets;
  thread_local raster_detail::Window window;
  if (wide) {
    raster_detail::tree_candidates(scene, i, j, reach, lo_x, hi_x, lo_y, hi_y, candidates);
  } else {
    if (window.serial != scene.serial || window.lo_x != lo_x || window.hi_x != hi_x || window.lo_y != lo_y ||
        window.hi_y != hi_y) {
      window.fill(scene, grid, lo_x, hi_x, lo_y, hi_y);
    }
    scene.search_cache_->sites_examined.fetch_add(window.sites.size(), std::memory_order_relaxed);
    for (const raster_detail::WindowSite& w : window.sites) {
      const Point from = site_from_sample(w.site) - half_pixel;
      const Point o{from.x + static_cast<double>(w.image_x) * domain.x, from.y + static_cast<double>(w.image_y) * domain.y};
      const double d2 = o.x * o.x + o.y * o.y;
      if (d2 > reach * reach) continue;
      if (device_bounds && candidates.size() == BLUETILE_MAX_CANDIDATES) return false;
      candidates.push_back({w.site, w.image_x, w.image_y, o, d2});
    }
  }
  double nearest2 = 1e30;
  for (const Candidate& c : candidates) nearest2 = std::min(nearest2, c.distance_squared);
  reach = std::sqrt(nearest2) + diagonal;
  // The nearest one, s0, owns part of the pixel; another site owns part of it only if it is
  // nearer than s0 at some corner (the distance difference is affine over the pixel), and one
  // that is not is never the nearest anywhere in it, so it cuts no piece either.
  std::size_t nearest_index = 0;
  for (std::size_t c = 1; c < candidates.size(); ++c)
    if (candidates[c].distance_squared < candidates[nearest_index].distance_squared) nearest_index = c;
  if (!candidates.empty() && !wide) {
    const Candidate s0 = candidates[nearest_index];
    const Point from0 = site_from_sample(s0.site);
    const Point corner0{-(from0.x + static_cast<double>(s0.image_x) * domain.x), -(from0.y + static_cast<double>(s0.image_y) * domain.y)};
    std::size_t kept = 0;
    for (std::size_t c = 0; c < candidates.size(); ++c) {
      const Candidate& t = candidates[c];
      if (t.distance_squared > reach * reach) continue;
      if (c != nearest_index) {
        if (!raster_detail::nearer_at_some_corner(scene, t, s0, corner0, h)) continue;
      }
      candidates[kept++] = t;
    }
    candidates.resize(kept);
  }
  if (device_bounds) {
    if (candidates.size() > static_cast<std::size_t>(BLUETILE_MAX_CANDIDATES)) return false;
    for (const Candidate& c : candidates)
      if (std::sqrt(c.offset.x * c.offset.x + c.offset.y * c.offset.y) + diagonal > scene.reach_limit) return false;
  }

  thread_local ConvexPolygon polygon;
  for (std::size_t a = 0; a < candidates.size(); ++a) {
    const Candidate& owner = candidates[a];
    if (!scene.wanted(owner.site)) continue;
    const Point from = site_from_sample(owner.site);
    const Point corner{-(from.x + static_cast<double>(owner.image_x) * domain.x), -(from.y + static_cast<double>(owner.image_y) * domain.y)};
    polygon.reset_rectangle(corner, {corner.x + h.x, corner.y + h.y});
    for (std::size_t b = 0; b < candidates.size() && !polygon.empty(); ++b) {
      if (b == a) continue;
      const Candidate& other = candidates[b];
      const Point between = scene.sites[other.site] - scene.sites[owner.site];
      const Point d{between.x + static_cast<double>(other.image_x - owner.image_x) * domain.x,
                    between.y + static_cast<double>(other.image_y - owner.image_y) * domain.y};
      if (d.x == 0.0 && d.y == 0.0) continue;
      polygon.clip_by_bisector(d, other.site);
    }
    if (polygon.empty()) continue;
    const PolygonMoments m = polygon.moments();
    if (!(m.area() > 0.0)) continue;
    piece(owner.site, m, polygon);
  }
  return true;
}

}  // namespace bluetile
