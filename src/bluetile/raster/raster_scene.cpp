// Scene preparation for the raster engine (see raster_scene.h).
#include "bluetile/raster/raster_scene.h"

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/raster/raster_engine.h"
#include "bluetile/raster/raster_reference.h"

namespace bluetile {
namespace {

// Sites per bucket of the split's grid: about one, as the exact engine's (the window of a
// boundary pixel is then 2 x 2 to 3 x 3 buckets).
constexpr double kSitesPerBucket = 1.0;

// The least power of two >= x (x > 0).
double power_of_two_above(double x) { return std::ldexp(1.0, std::ilogb(x) + 1); }

}  // namespace

double raster_distance(const RasterScene& scene, Point a, Point b) {
  if (scene.periodic) return torus_distance(a, b, scene.grid().domain());  // the grid's copy of the domain
  const Point d = b - a;
  return std::sqrt(d.x * d.x + d.y * d.y);
}

std::vector<WeightedMoments> pixel_density_moments(const Scene& scene, int rx, int ry) {
  const Point size = scene.domain.size;
  const double hx = size.x / rx, hy = size.y / ry;
  std::vector<WeightedMoments> table(static_cast<std::size_t>(rx) * static_cast<std::size_t>(ry));
  // Rows are independent and each pixel is written once: the table is the same for any threads.
  parallel_for(static_cast<std::size_t>(ry), 8, [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j) {
      for (int i = 0; i < rx; ++i) {
        // Corners as the splits form them, so a whole pixel and its pieces share edges.
        const Point lo{static_cast<double>(i) * hx, static_cast<double>(j) * hy};
        const Point centre{(static_cast<double>(i) + 0.5) * hx, (static_cast<double>(j) + 0.5) * hy};
        const Point pixel[4] = {lo - centre, Point{lo.x + hx, lo.y} - centre, Point{lo.x + hx, lo.y + hy} - centre,
                                Point{lo.x, lo.y + hy} - centre};
        table[j * static_cast<std::size_t>(rx) + static_cast<std::size_t>(i)] =
            density_moments(pixel, centre, *scene.density, size, scene.periodic());
      }
    }
  });
  return table;
}

double RasterScene::pixel_diagonal() const { return std::sqrt(hx * hx + hy * hy); }

void RasterScene::site_pixel(std::size_t i, int& px, int& py, double& fx, double& fy) const {
  const double ux = sites[i].x / hx, uy = sites[i].y / hy;
  px = std::clamp(static_cast<int>(std::floor(ux)), 0, rx - 1);
  py = std::clamp(static_cast<int>(std::floor(uy)), 0, ry - 1);
  // A fraction that rounds to 1 in float would name the next sample: keep it below.
  constexpr double kBelowOne = 1.0 - 1.0 / 16777216.0;
  fx = std::clamp(ux - px, 0.0, kBelowOne);
  fy = std::clamp(uy - py, 0.0, kBelowOne);
}

void RasterScene::update_scales() {
  double r = 0.0;
  for (std::size_t i = 0; i < sites.size(); ++i)
    if (!coincident[i]) r = std::max(r, radius[i]);
  // In an accepted pass every cell lies within its farthest owned sample plus a pixel diagonal,
  // and the coverage check makes every cone reach its own cell's farthest sample; two diagonals
  // of slack. A piece beyond it goes to the host.
  reach_limit = std::min(r, radius_cap) + 2.0 * pixel_diagonal();
  const double pi = 3.141592653589793;
  const double rl = reach_limit;
  // Each site's pieces lie in the disk of radius rl: their sums are bounded by the disk's
  // integrals of 1, |x| and |x|^2; 2^61 leaves room for rounding and the sign.
  const double top = std::ldexp(1.0, 61);
  scale_area = top / power_of_two_above(pi * rl * rl);
  scale_first = top / power_of_two_above(2.0 * pi * rl * rl * rl / 3.0);
  scale_second = top / power_of_two_above(0.5 * pi * rl * rl * rl * rl);
}

RasterScene prepare_raster_scene(const Scene& scene, std::size_t index, const RasterSettings& settings) {
  if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size())
    throw Error("raster engine: the scene's wanted range [" + std::to_string(scene.wanted_begin) + ", " +
                std::to_string(scene.wanted_end) + ") lies outside its " + std::to_string(scene.sites.size()) + " sites");
  const Point size = scene.domain.size;
  if (!(size.x > 0.0 && size.y > 0.0 && std::isfinite(size.x) && std::isfinite(size.y)))
    throw Error("raster engine: the domain size must be positive and finite");
  static std::atomic<std::uint64_t> serials{0};
  RasterScene job;
  job.scene = &scene;
  job.serial = ++serials;
  job.index = index;
  job.area = settings.area;
  const std::size_t n = scene.sites.size();
  job.rx = settings.resolution > 0 ? settings.resolution
                                   : default_resolution(n, settings.area ? Coverage::area : Coverage::point);
  job.ry = std::max(1, static_cast<int>(std::lround(job.rx * size.y / size.x)));
  if (static_cast<std::uint32_t>(std::max(job.rx, job.ry)) > settings.max_side)
    throw Error("resolution " + std::to_string(job.rx) + " x " + std::to_string(job.ry) + " exceeds the device's limit of " +
                std::to_string(settings.max_side) + " pixels per side; use a smaller resolution");
  job.hx = size.x / job.rx;
  job.hy = size.y / job.ry;
  job.periodic = scene.periodic();
  // On a torus no point is farther than half the diagonal from a site's nearest copy; in a
  // rectangle the farthest point from a corner site is the opposite corner.
  job.radius_cap = (job.periodic ? 0.5 : 1.0) * std::sqrt(size.x * size.x + size.y * size.y);
  if (scene.density) {
    const DensityGrid& density = *scene.density;
    if (is_uniform(density)) {
      job.density_constant = density.texels.front();
    } else {
      job.density = &density;
      const float largest = *std::max_element(density.texels.begin(), density.texels.end());
      job.density_scale = 1.0 / power_of_two_above(largest);
    }
  }

  job.sites.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Point p = scene.sites[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error("raster engine: site " + std::to_string(i) + " is not finite");
    job.sites[i] = job.periodic ? wrap_point(p, scene.domain) : p;
  }
  job.coincident.assign(n, 0);
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const Point &p = job.sites[a], &q = job.sites[b];
    if (p.x != q.x) return p.x < q.x;
    if (p.y != q.y) return p.y < q.y;
    return a < b;
  });
  for (std::size_t k = 1; k < n; ++k)
    if (job.sites[order[k]] == job.sites[order[k - 1]]) job.coincident[order[k]] = 1;

  job.grid_ = std::make_shared<const SiteGrid>(job.sites, scene.domain, kSitesPerBucket, false);
  job.search_cache_ = std::make_shared<RasterSearchCache>();

  const double start = settings.radius_factor * std::sqrt(scene.domain.area() / static_cast<double>(std::max<std::size_t>(n, 1)));
  job.radius.assign(n, std::min(start, job.radius_cap));
  job.split.assign(n, 0);
  return job;
}

namespace {

// Whether some site t (not s, not coincident) in the 3 x 3 buckets around s, then in every bucket
// within `reach`, has near(t); stops at the first. Sites on a line or in a cluster find one in
// their own bucket at once, where a scan of the whole window would cost O(N) per site.
template <typename Near>
bool any_site_near(const RasterScene& job, std::size_t s, double reach, Near near) {
  const SiteGrid& grid = job.grid();
  const std::span<const std::uint32_t> starts = grid.bucket_starts(), index = grid.site_indices();
  auto [cx, cy] = grid.bucket_coordinates(job.sites[s]);
  for (long dy = -1; dy <= 1; ++dy)
    for (long dx = -1; dx <= 1; ++dx) {
      const long bx = cx + dx - SiteGrid::wrap_count(cx + dx, grid.columns()) * grid.columns();
      const long by = cy + dy - SiteGrid::wrap_count(cy + dy, grid.rows()) * grid.rows();
      const std::size_t b = static_cast<std::size_t>(by * grid.columns() + bx);
      for (std::uint32_t slot = starts[b]; slot < starts[b + 1]; ++slot) {
        const std::uint32_t t = index[slot];
        if (t != s && !job.coincident[t] && near(t)) return true;
      }
    }
  const Point cell = grid.cell_size();
  if (reach <= std::min(cell.x, cell.y)) return false;  // the 3 x 3 buckets held every candidate
  bool found = false;
  grid.for_each_near(job.sites[s], reach, [&](std::uint32_t t) {
    if (!found && t != s && !job.coincident[t] && near(t)) found = true;
  });
  return found;
}

// Buckets a window of `reach` around a site visits.
double window_buckets(const SiteGrid& grid, double reach) {
  const Point cell = grid.cell_size();
  const double wx = std::min(2.0 * std::ceil(reach / cell.x) + 1.0, static_cast<double>(grid.columns()));
  const double wy = std::min(2.0 * std::ceil(reach / cell.y) + 1.0, static_cast<double>(grid.rows()));
  return wx * wy;
}

}  // namespace

void flag_close_sites(RasterScene& job) {
  // Depths are formed from integer sample offsets minus a float fraction, so they carry a
  // relative error of about 2^-22 (a few float roundings): delta = 2^-22 R at distance R (in
  // samples). Two sites e apart are then confused where their distances differ by less than
  // delta: a band of half-width w = R delta / e around their bisector. A sample in it may show
  // the wrong one; the pixel it bounds is then taken as whole although a sliver of it (area up
  // to w times a pixel side) is the other's. Sites with w > 1e-5 samples are flagged and all
  // their pixels split exactly; below it such slivers are rare and tiny (docs/RASTER.md).
  const std::size_t n = job.size();
  std::fill(job.split.begin(), job.split.end(), 0);
  if (!job.area || n < 2) return;
  constexpr double kRelativeDepthError = 1.0 / 4194304.0;  // 2^-22
  constexpr double kBandSamples = 1e-5;
  const double h = std::min(job.hx, job.hy);
  auto threshold = [&](double r) { return kRelativeDepthError * r * r / (kBandSamples * h); };  // domain units
  // A pair s, t is flagged when t lies within the threshold of s's radius or s within that of
  // t's: flagged(s) = some t within threshold(r_s) of s, or s within threshold(r_t) of some t.
  // Listing the pairs costs O(N^2) on a line or in a cluster (the thresholds of long cells reach
  // across the domain); each site stops at its first partner instead.
  const SiteGrid& grid = job.grid();
  std::vector<double> reach(n, 0.0);
  double widest_flagged = 0.0;
  std::size_t unflagged = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (job.coincident[s]) continue;
    reach[s] = threshold(job.radius[s]);
    const bool close = any_site_near(job, s, reach[s], [&](std::uint32_t t) {
      return raster_distance(job, job.sites[s], job.sites[t]) <= reach[s];
    });
    if (close) {
      job.split[s] = 1;
      widest_flagged = std::max(widest_flagged, reach[s]);
    } else {
      ++unflagged;
    }
  }
  // The second half: s unflagged so far, within threshold(r_t) of a t. That t has s within its
  // own threshold, so it is flagged already: search from the unflagged sites or from the
  // flagged ones, whichever visits fewer buckets.
  if (unflagged == 0 || widest_flagged == 0.0) return;
  double from_flagged = 0.0;
  for (std::size_t t = 0; t < n; ++t)
    if (job.split[t]) from_flagged += window_buckets(grid, reach[t]);
  const std::vector<std::uint8_t> first = job.split;
  if (from_flagged <= static_cast<double>(unflagged) * window_buckets(grid, widest_flagged)) {
    for (std::size_t t = 0; t < n; ++t) {
      if (!first[t]) continue;
      grid.for_each_near(job.sites[t], reach[t], [&](std::uint32_t s) {
        if (s != t && !job.coincident[s] && !job.split[s] && raster_distance(job, job.sites[t], job.sites[s]) <= reach[t]) job.split[s] = 1;
      });
    }
  } else {
    for (std::size_t s = 0; s < n; ++s) {
      if (job.coincident[s] || first[s]) continue;
      const bool close = any_site_near(job, s, widest_flagged, [&](std::uint32_t t) {
        return first[t] && raster_distance(job, job.sites[t], job.sites[s]) <= reach[t];
      });
      if (close) job.split[s] = 1;
    }
  }
}

// ---- radius memory ---------------------------------------------------------------------------

std::uint64_t RadiusMemory::key_of(Point p, Point domain) {
  std::uint64_t bits[4];
  std::memcpy(&bits[0], &p.x, 8);
  std::memcpy(&bits[1], &p.y, 8);
  std::memcpy(&bits[2], &domain.x, 8);
  std::memcpy(&bits[3], &domain.y, 8);
  std::uint64_t h = 0x9e3779b97f4a7c15ull;
  for (std::uint64_t b : bits) {
    h ^= b + 0x9e3779b97f4a7c15ull + (h << 6) + (h >> 2);
    h *= 0xbf58476d1ce4e5b9ull;
    h ^= h >> 31;
  }
  return h | 1;  // never 0 (the empty slot)
}

void RadiusMemory::grow() {
  std::vector<Entry> old = std::move(table_);
  table_.assign(std::max<std::size_t>(64, old.size() * 2), Entry{});
  used_ = 0;
  for (const Entry& e : old)
    if (e.key) insert(e);
}

void RadiusMemory::insert(const Entry& e) {
  if (2 * (used_ + 1) > table_.size()) grow();
  const std::size_t mask = table_.size() - 1;
  for (std::size_t k = e.key & mask;; k = (k + 1) & mask) {
    if (table_[k].key == 0) {
      table_[k] = e;
      ++used_;
      return;
    }
    if (table_[k].key == e.key) {  // the same position twice: keep the larger radius
      table_[k].radius = std::max(table_[k].radius, e.radius);
      table_[k].motion = std::max(table_[k].motion, e.motion);
      return;
    }
  }
}

const RadiusMemory::Entry* RadiusMemory::find(std::uint64_t key) const {
  if (table_.empty()) return nullptr;
  const std::size_t mask = table_.size() - 1;
  for (std::size_t k = key & mask;; k = (k + 1) & mask) {
    if (table_[k].key == key) return &table_[k];
    if (table_[k].key == 0) return nullptr;
  }
}

void RadiusMemory::start_call() {
  // Sized once for the entries to come (at most half full), reusing the storage: rebuilding it
  // by doubling cost page faults every call for large batches.
  std::size_t size = 64;
  while (size < 2 * pending_.size() + 2) size *= 2;
  table_.assign(size, Entry{});
  used_ = 0;
  for (const Entry& e : pending_) insert(e);
  pending_.clear();
}

std::size_t RadiusMemory::recall(RasterScene& job) const {
  const std::size_t n = job.size();
  std::vector<const Entry*> found(n, nullptr);
  std::size_t hits = 0;
  for (std::size_t i = 0; i < n; ++i) {
    found[i] = find(key_of(job.sites[i], job.scene->domain.size));
    hits += found[i] != nullptr;
  }
  if (hits == 0) return 0;
  // The radius a site's cone needs is the largest farthest-sample distance of the sites near
  // it, which grows by about their motion; twice the site's own motion, 10% and half a pixel
  // diagonal make a failed coverage check rare (measured: no redo in 80 iterations from random
  // sites at N = 1000, docs/BENCHMARKS.md) while keeping cones small: a radius a pixel larger
  // costs about a third more fragments at 16 pixels per cell. The coverage check catches the rest.
  const double slack = 0.5 * job.pixel_diagonal();
  for (std::size_t i = 0; i < n; ++i)
    if (found[i]) job.radius[i] = std::min(job.radius_cap, 1.1 * found[i]->radius + 2.0 * found[i]->motion + slack);
  return hits;
}

void RadiusMemory::remember(const RasterScene& job, const std::vector<Point>& next_position, const std::vector<double>& radius) {
  for (std::size_t i = 0; i < job.size(); ++i) {
    if (job.coincident[i]) continue;
    Entry e;
    e.key = key_of(next_position[i], job.scene->domain.size);
    e.radius = radius[i];
    e.motion = raster_distance(job, job.sites[i], next_position[i]);
    pending_.push_back(e);
  }
}

}  // namespace bluetile
