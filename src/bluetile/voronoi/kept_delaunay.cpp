// The triangulation kept between calls: see kept_delaunay.h.
#include "bluetile/voronoi/kept_delaunay.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cmath>
#include <cstring>
#include <memory>
#include <optional>
#include <vector>

#include "bluetile/core/default_init.h"
#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/cell_search.h"
#include "bluetile/voronoi/predicates.h"

namespace bluetile {
namespace {

using StarEntry = PeriodicDelaunay::StarEntry;

// Coordinates in (0, kSmallestCoordinate) would make coordinate differences whose products
// underflow in the exact predicates; such scenes (a site within 1e-30 of the border, not 0) are
// searched.
constexpr double kSmallestCoordinate = 0x1p-100;

bool coordinate_suits(double x) { return x == 0.0 || x >= kSmallestCoordinate; }

// The periods between a site's copy at `origin + offset` and the site at `p` (whole numbers).
std::int8_t periods(double origin, double offset, double p, double period) {
  return static_cast<std::int8_t>(std::lround((origin + offset - p) / period));
}

// Sites on rows and columns (a square lattice, a rectangular grid) put four exactly cocircular
// sites around most Delaunay vertices: the clipped stars never fit together (every star is then
// computed with the exact predicates) and nearly every cell lies on a tie and is searched anyway,
// so such a scene is searched as a whole. The test reads a fixed sample of the sites (every
// (n / m)-th by index, m = kGridSample sqrt(n)) and asks whether at least half of them share their
// x with another sample and their y with another: with m = 4 sqrt(n), a k x k lattice (k^2 = n)
// gives about 1 - e^-4 = 98% of the samples for each axis; sites off such a grid share none.
constexpr std::size_t kGridSample = 4;  // samples per sqrt(n): a lattice is recognised at any n

bool on_rows_and_columns(std::span<const Point> sites) {
  const std::size_t n = sites.size();
  const auto root = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(n))));
  const std::size_t m = std::min(n, kGridSample * root);
  // This runs every call, on the calling thread alone: the samples are copied once (their indices
  // i n / m stepped without a division each), and those that share a coordinate with another
  // are found through an open-addressed table of the coordinates' bits (at least twice as many
  // slots as samples) instead of two sorts (5-7 us a call at 10^4 sites, now about 3), in
  // buffers kept by the thread.
  thread_local std::vector<Point> samples;
  thread_local std::vector<std::uint32_t> slots;  // a sample's index + 1; 0: empty
  thread_local std::vector<std::uint8_t> shared;
  samples.resize(m);
  const std::size_t step = n / m, carry = n % m;
  for (std::size_t i = 0, at = 0, rest = 0; i < m; ++i) {  // at = i n / m, rest = i n % m
    samples[i] = sites[at];
    at += step;
    rest += carry;
    if (rest >= m) {
      rest -= m;
      ++at;
    }
  }
  std::size_t capacity = 16;
  while (capacity < 2 * m) capacity *= 2;
  shared.assign(m, 0);
  auto mark = [&](double Point::*axis, std::uint8_t bit) {
    slots.assign(capacity, 0);
    for (std::size_t i = 0; i < m; ++i) {
      const double value = samples[i].*axis + 0.0;  // -0 and +0 compare equal: one key
      if (value != value) continue;                 // NaN equals nothing
      std::uint64_t key;
      std::memcpy(&key, &value, sizeof key);
      std::size_t slot = static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & (capacity - 1);
      for (;; slot = (slot + 1) & (capacity - 1)) {
        if (slots[slot] == 0) {
          slots[slot] = static_cast<std::uint32_t>(i + 1);
          break;
        }
        const std::size_t first = slots[slot] - 1;
        if (samples[first].*axis + 0.0 == value) {
          shared[first] |= bit;
          shared[i] |= bit;
          break;
        }
      }
    }
  };
  mark(&Point::x, 1);
  // At most the samples that share their x share both: when fewer than half do (the common
  // case), the answer is no without looking at y.
  const auto x_shared = static_cast<std::size_t>(std::count(shared.begin(), shared.end(), std::uint8_t{1}));
  if (2 * x_shared < m) return false;
  mark(&Point::y, 2);
  const auto both = static_cast<std::size_t>(std::count(shared.begin(), shared.end(), std::uint8_t{3}));
  return 2 * both >= m;
}

// Sorts `triangles` (numbers below `count`) and drops repeats. The first calls from random sites
// flip a tenth of the edges: sorting those lists cost more than marking the triangles in a table
// and reading it in order, a pass over `count` bytes that few flips would not repay.
void sort_unique(std::vector<std::uint32_t>& triangles, std::size_t count) {
  if (triangles.size() * 16 < count) {
    std::sort(triangles.begin(), triangles.end());
    triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
    return;
  }
  std::vector<std::uint8_t> marked(count, 0);
  for (std::uint32_t t : triangles) marked[t] = 1;
  triangles.clear();
  for (std::size_t t = 0; t < count; ++t)
    if (marked[t]) triangles.push_back(static_cast<std::uint32_t>(t));
}

// A repair that would remove more than one vertex in this many is a rebuild instead.
constexpr std::size_t kRepairShare = 16;

// The chunks of the vertex passes: about forty at 10^4 sites, for the same reason as the sweep's
// (delaunay_cells.cpp).
constexpr std::size_t kVertexChunk = 256;
// How many vertices ahead the passes that read or write at a site's place (scattered in
// memory) fetch it: enough to cover a miss to memory at the pass's pace.
constexpr std::size_t kPrefetch = 16;

// A site's Delaunay neighbours computed with the exact predicates from every site within reach
// (the candidates): the nearest candidate is one; the others are the vertices of the convex hull
// of the candidates' polar points 2 d / |d|^2 (d the offset from the site), found by a Graham
// scan around the site in which b between a and c stays when it lies inside the circle through
// the site, a and c (their bisectors then leave b an edge) or when a and c are half a turn or
// more apart. The reach grows until it is twice the cell's farthest vertex. False when the cell
// reaches a quarter period or the site coincides with another.
class ExactStar {
 public:
  ExactStar(const Scene& scene, const SiteGrid& grid, std::span<const std::uint32_t> vertex_of_site)
      : scene_(scene), grid_(grid), vertex_of_site_(vertex_of_site) {}

  bool compute(std::uint32_t site, double radius_squared, std::vector<StarEntry>& star) {
    const Point size = scene_.domain.size;
    const double quarter = 0.25 * std::min(size.x, size.y);
    double reach = 2.0 * std::sqrt(radius_squared) * (1.0 + 1e-3);
    for (int attempt = 0; attempt < 8; ++attempt) {
      if (!(reach < quarter)) return false;
      const int found = hull(site, reach, star);
      if (found < 0) return false;
      if (found == 0) {
        reach *= 2.0;
        continue;
      }
      // Complete when no site beyond the reach can cut the cell: twice its farthest vertex.
      const double needed = 2.0 * std::sqrt(farthest_squared_) * (1.0 + 1e-6);
      if (needed <= reach) return true;
      reach = needed * (1.0 + 1e-3);
    }
    return false;
  }

 private:
  struct Candidate {
    PeriodicPoint point;
    Point offset;
    double distance_squared;
    std::uint32_t site;
  };

  // 1: the star, from every site within `reach`; 0: the candidates do not surround the site;
  // -1: a coincident site or two copies on one ray the roundings cannot order.
  int hull(std::uint32_t site, double reach, std::vector<StarEntry>& star) {
    const Point origin = scene_.sites[site];
    const PeriodicPoint s{origin};
    const Point size = scene_.domain.size;
    candidates_.clear();
    bool coincident = false;
    grid_.for_each_site_near(origin, reach, [&](std::uint32_t other, Point p) {
      if (other == site) return;
      const Point nearest = torus_offset(origin, p, scene_.domain);
      const Point shift{periods(origin.x, nearest.x, p.x, size.x) * size.x, periods(origin.y, nearest.y, p.y, size.y) * size.y};
      // The correctly rounded offset to that copy: its signs are the exact ones.
      const Point d{detail::rounded_difference(p.x, shift.x, origin.x, 0.0), detail::rounded_difference(p.y, shift.y, origin.y, 0.0)};
      if (d.x == 0.0 && d.y == 0.0) coincident = true;
      const double dd = d.x * d.x + d.y * d.y;
      if (dd > reach * reach) return;
      candidates_.push_back({{p, shift}, d, dd, other});
    });
    if (coincident) return -1;
    if (candidates_.size() < 3) return 0;
    // Counter-clockwise from the positive x axis, the nearer first on one ray; the exact offset's
    // sign is that of the correctly rounded one.
    auto half = [](Point d) { return d.y < 0.0 || (d.y == 0.0 && d.x < 0.0); };
    std::sort(candidates_.begin(), candidates_.end(), [&](const Candidate& a, const Candidate& b) {
      if (half(a.offset) != half(b.offset)) return half(b.offset);
      const int turn = orientation(s, a.point, b.point);
      if (turn != 0) return turn > 0;
      if (a.distance_squared != b.distance_squared) return a.distance_squared < b.distance_squared;
      return a.site < b.site;
    });
    // On one ray only the nearest site can be a neighbour (the others' bisectors lie beyond).
    std::vector<Candidate> kept;
    for (const Candidate& c : candidates_) {
      if (!kept.empty() && half(kept.back().offset) == half(c.offset) && orientation(s, kept.back().point, c.point) == 0) {
        if (kept.back().distance_squared == c.distance_squared) return -1;
        continue;
      }
      kept.push_back(c);
    }
    if (kept.size() < 3) return 0;
    // Start from the nearest candidate, which is a Delaunay neighbour.
    const auto nearest = std::min_element(kept.begin(), kept.end(), [](const Candidate& a, const Candidate& b) {
      return a.distance_squared < b.distance_squared || (a.distance_squared == b.distance_squared && a.site < b.site);
    });
    std::rotate(kept.begin(), nearest, kept.end());
    auto keeps = [&](const Candidate& a, const Candidate& b, const Candidate& c) {
      if (orientation(s, a.point, c.point) <= 0) return true;
      int exact = 0;
      return incircle_perturbed(s, a.point, c.point, b.point, site, a.site, c.site, b.site, exact) > 0;
    };
    hull_.clear();
    hull_.push_back(kept[0]);
    for (std::size_t i = 1; i <= kept.size(); ++i) {
      const Candidate& c = kept[i == kept.size() ? 0 : i];
      while (hull_.size() >= 2 && !keeps(hull_[hull_.size() - 2], hull_.back(), c)) hull_.pop_back();
      hull_.push_back(c);
    }
    hull_.pop_back();  // the first candidate again
    if (hull_.size() < 3) return 0;
    // Closed around the site: every turn between neighbours below half a turn.
    farthest_squared_ = 0.0;
    star.clear();
    for (std::size_t k = 0; k < hull_.size(); ++k) {
      const Candidate& a = hull_[k];
      const Candidate& b = hull_[k + 1 == hull_.size() ? 0 : k + 1];
      if (orientation(s, a.point, b.point) <= 0) return 0;
      const Point p = a.offset, q = b.offset;
      const double det = 2.0 * (p.x * q.y - p.y * q.x);
      const double pp = p.x * p.x + p.y * p.y, qq = q.x * q.x + q.y * q.y;
      const Point v{(q.y * pp - p.y * qq) / det, (p.x * qq - q.x * pp) / det};
      farthest_squared_ = std::max(farthest_squared_, v.x * v.x + v.y * v.y);
      star.push_back({vertex_of_site_[a.site], static_cast<std::int8_t>(std::lround(a.point.shift.x / size.x)),
                      static_cast<std::int8_t>(std::lround(a.point.shift.y / size.y))});
    }
    return 1;
  }

  const Scene& scene_;
  const SiteGrid& grid_;
  std::span<const std::uint32_t> vertex_of_site_;
  std::vector<Candidate> candidates_, hull_;
  double farthest_squared_ = 0.0;
};

}  // namespace

bool KeptDelaunay::suits(const Scene& scene) {
  const Point size = scene.domain.size;
  auto side_suits = [](double side) { return side >= 0x1p-20 && side <= 0x1p20; };
  return scene.periodic() && scene.sites.size() >= kMinSites && scene.sites.size() <= kMaxSites && side_suits(size.x) &&
         side_suits(size.y);
}

bool KeptDelaunay::matches(const Scene& scene) const {
  return valid_ && scene.sites.size() == site_count_ && scene.wanted_begin == wanted_begin_ &&
         scene.wanted_end == wanted_end_ && scene.domain.size == domain_.size;
}

std::size_t KeptDelaunay::bytes() const {
  return site_of_vertex_.capacity() * sizeof(std::uint32_t) + previous_.capacity() * sizeof(Point) +
         triangulation_.bytes() + cells_.bytes();
}

bool KeptDelaunay::move_vertices(const Scene& scene) {
  const std::size_t n = scene.sites.size();
  const Point size = scene.domain.size;
  // The positions before the move become the previous ones (no copy), the scene's fill the others.
  previous_.resize(n);
  triangulation_.swap_positions(previous_);
  auto positions = triangulation_.positions();
  // New positions in vertex order, and the vertices that wrapped across the border since.
  using Wrap = PeriodicDelaunay::Wrap;
  const std::size_t chunks = (n + kVertexChunk - 1) / kVertexChunk;
  std::vector<std::vector<Wrap>> wraps(chunks);
  std::vector<std::uint8_t> suits(chunks, 1);
  parallel_for(chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      bool ok = true;
      const std::size_t chunk_end = std::min(n, (c + 1) * kVertexChunk);
      for (std::size_t v = c * kVertexChunk; v < chunk_end; ++v) {
        if (v + kPrefetch < chunk_end) __builtin_prefetch(&scene.sites[site_of_vertex_[v + kPrefetch]]);
        const Point p = scene.sites[site_of_vertex_[v]];
        ok &= coordinate_suits(p.x) && coordinate_suits(p.y);
        const Point d = p - previous_[v];
        // A move of more than half a period is a wrap (a relaxation moves sites far less); a
        // site that truly jumped leaves triangles folded over, and the triangulation is rebuilt.
        const int kx = d.x < -0.5 * size.x ? 1 : d.x > 0.5 * size.x ? -1 : 0;
        const int ky = d.y < -0.5 * size.y ? 1 : d.y > 0.5 * size.y ? -1 : 0;
        if (kx || ky) wraps[c].push_back({static_cast<std::uint32_t>(v), static_cast<std::int8_t>(kx), static_cast<std::int8_t>(ky)});
        positions[v] = p;
      }
      suits[c] = ok;
    }
  });
  if (std::find(suits.begin(), suits.end(), 0) != suits.end()) return false;
  wraps_.clear();
  for (const auto& chunk : wraps) wraps_.insert(wraps_.end(), chunk.begin(), chunk.end());
  for (const Wrap& w : wraps_) triangulation_.wrap(w.vertex, w.kx, w.ky);
  return true;
}

KeptDelaunay::Settled KeptDelaunay::settle(KeptTopologyStats& stats, std::vector<std::uint32_t>& folded) {
  DelaunayCells::Sweep sweep = cells_.sweep(triangulation_, lanes_);
  if (!sweep.invalid.empty()) {
    folded = std::move(sweep.invalid);
    return Settled::folded;
  }
  std::vector<std::uint32_t> changed;
  const bool delaunay = triangulation_.make_delaunay(sweep.suspects, sweep.ties, changed);
  stats.flips += triangulation_.flips();
  if (!delaunay) return Settled::failed;
  sort_unique(changed, triangulation_.triangles().size());
  cells_.recompute(triangulation_, changed, sweep.oversized);
  // Flips keep the area; every circumcircle that reached the limit must have been flipped away.
  const double area = scene_area_;
  fits_ = std::abs(sweep.area - area) <= 1e-9 * area;
  for (std::uint32_t t : sweep.oversized) fits_ &= cells_.fits(triangulation_, t);
  return Settled::delaunay;
}

bool KeptDelaunay::settle(KeptTopologyStats& stats) {
  std::vector<std::uint32_t> folded;
  return settle(stats, folded) == Settled::delaunay;
}

bool KeptDelaunay::rebuild(const Scene& scene, const Weighting& weighting, std::span<Cell> cells, bool parallel,
                           KeptTopologyStats& stats) {
  valid_ = false;
  const std::size_t n = scene.sites.size();
  const CellSearch search(scene);
  const SiteGrid& grid = search.grid;
  const Point size = scene.domain.size;
  // Vertices in the grid's bucket order: neighbours in the plane are near in memory.
  site_of_vertex_.assign(grid.site_indices().begin(), grid.site_indices().end());
  const auto vertex_of_site = default_init_array<std::uint32_t>(n);  // every entry written below, on all threads
  std::vector<Point> positions(n);
  auto number = [&](std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      vertex_of_site[site_of_vertex_[v]] = static_cast<std::uint32_t>(v);
      positions[v] = grid.stored_point(v);
    }
  };
  if (parallel) {
    parallel_for(n, kVertexChunk, number);
  } else {
    number(0, n);
  }
  // Every site's cell by the search, its neighbours as its star. The cells are measured only
  // once the scene is found not to suit a triangulation (hopeless, below; the rest afterwards
  // when the triangulation fails): otherwise the triangulation measures them.
  const std::size_t chunks = (n + kVertexChunk - 1) / kVertexChunk;
  struct ChunkStars {
    std::vector<StarEntry> entries;
    std::vector<std::uint32_t> sizes;
    std::vector<double> radius_squared;
    std::size_t measured_from = 0;  // the chunk's cells from this vertex on are measured
    bool coincident = false, unfit = false, coordinates = true;
  };
  std::vector<ChunkStars> chunk_stars(chunks);
  // A cell reaching a tenth of the shorter period has a circumcircle that large (its farthest
  // vertex is one): the scene does not suit a triangulation, whatever the roundings (they are far
  // below the margin). An edge of a quarter period or a cell reaching the site's own copy (unfit,
  // below) imply such a cell too.
  const double limit = 0.1 * std::min(size.x, size.y) * (1.0 + 1e-6);
  std::atomic<bool> hopeless{false};
  auto run = [&](std::size_t begin, std::size_t end) {
    ConvexPolygon polygon;
    SearchScratch scratch;
    for (std::size_t c = begin; c < end; ++c) {
      ChunkStars& mine = chunk_stars[c];
      mine.measured_from = std::min(n, (c + 1) * kVertexChunk);
      for (std::size_t v = c * kVertexChunk; v < std::min(n, (c + 1) * kVertexChunk); ++v) {
        const std::uint32_t site = site_of_vertex_[v];
        const Point origin = positions[v];
        mine.coordinates &= coordinate_suits(origin.x) && coordinate_suits(origin.y);
        const bool complete = build_cell(scene, search, site, origin, polygon, scratch);
        mine.radius_squared.push_back(polygon.max_radius_squared());
        const std::size_t before = mine.entries.size();
        // Once some cell is too large for a triangulation (below) the stars are not needed: the
        // search's cells stand, and a scene that stays so costs no more than the search.
        if (!(polygon.max_radius_squared() < limit * limit)) hopeless.store(true, std::memory_order_relaxed);
        if (hopeless.load(std::memory_order_relaxed)) {
          // Once seen, seen for the rest of this chunk: its cells from here on are measured.
          mine.measured_from = std::min(mine.measured_from, v);
          if (site >= scene.wanted_begin && site < scene.wanted_end)
            cells[site - scene.wanted_begin] = measure_cell(scene, origin, !complete, polygon, weighting);
          mine.sizes.push_back(0);
          continue;
        }
        if (!complete) {
          mine.coincident = true;
          mine.sizes.push_back(0);
          continue;
        }
        const auto vertices = polygon.vertices();
        for (std::size_t i = 0; i < vertices.size(); ++i) {
          const std::uint32_t label = vertices[i].edge_label;
          if (label == kOwnCopy) {
            mine.unfit = true;
            continue;
          }
          if (mine.entries.size() > before && mine.entries.back().vertex == vertex_of_site[label]) continue;
          // The neighbour's copy within a quarter period (the only one that can be an edge of a
          // triangulation the predicates take), by whole periods.
          const Point d = scene.sites[label] - origin;
          const int kx = d.x > 0.5 * size.x ? -1 : d.x < -0.5 * size.x ? 1 : 0;
          const int ky = d.y > 0.5 * size.y ? -1 : d.y < -0.5 * size.y ? 1 : 0;
          const double ex = d.x + kx * size.x, ey = d.y + ky * size.y;
          if (!(std::abs(ex) < 0.25 * size.x && std::abs(ey) < 0.25 * size.y)) mine.unfit = true;
          mine.entries.push_back({vertex_of_site[label], static_cast<std::int8_t>(kx), static_cast<std::int8_t>(ky)});
        }
        if (mine.entries.size() - before >= 2 && mine.entries.back().vertex == mine.entries[before].vertex)
          mine.entries.pop_back();
        mine.sizes.push_back(static_cast<std::uint32_t>(mine.entries.size() - before));
      }
    }
  };
  if (parallel) {
    parallel_for(chunks, 1, run);
  } else {
    run(0, chunks);
  }
  bool coincident = false, unfit = false, coordinates = true;
  std::vector<std::uint32_t> entry_start(chunks + 1, 0);  // where each chunk's stars go
  for (std::size_t c = 0; c < chunks; ++c) {
    coincident |= chunk_stars[c].coincident;
    unfit |= chunk_stars[c].unfit;
    coordinates &= chunk_stars[c].coordinates;
    entry_start[c + 1] = entry_start[c] + static_cast<std::uint32_t>(chunk_stars[c].entries.size());
  }
  // When the triangulation fails (or does not fit), the search's cells stand: those not measured
  // in the loop above are searched again (the same bits: the same search from the same sites).
  auto searched = [&](bool built) {
    if (built && fits_) return true;
    std::vector<std::uint32_t> unmeasured;
    for (std::size_t c = 0; c < chunks; ++c) {
      for (std::size_t v = c * kVertexChunk; v < chunk_stars[c].measured_from; ++v) {
        const std::uint32_t site = site_of_vertex_[v];
        if (site >= scene.wanted_begin && site < scene.wanted_end) unmeasured.push_back(site);
      }
    }
    search_listed_cells(scene, search, weighting, unmeasured, cells, parallel);
    return built;
  };
  if (coincident || !coordinates || unfit || hopeless.load()) return searched(false);
  // The chunks' stars side by side, on all threads (left uninitialised before: every entry is
  // written).
  std::vector<std::uint32_t, DefaultInitAllocator<std::uint32_t>> star_start(n + 1);
  star_start[0] = 0;
  auto stars = default_init_array<StarEntry>(entry_start[chunks]);
  auto gather = [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      std::copy(chunk_stars[c].entries.begin(), chunk_stars[c].entries.end(), stars.get() + entry_start[c]);
      std::uint32_t at = entry_start[c];
      std::size_t v = c * kVertexChunk;
      for (std::uint32_t entries : chunk_stars[c].sizes) star_start[++v] = at += entries;
      std::vector<StarEntry>().swap(chunk_stars[c].entries);
    }
  };
  if (parallel) {
    parallel_for(chunks, 1, gather);
  } else {
    gather(0, chunks);
  }
  triangulation_.reset(scene.domain, std::move(positions), site_of_vertex_);
  const bool built = triangulation_.build(star_start, std::span<const StarEntry>(stars.get(), entry_start[chunks]));
  stars.reset();
  if (built && settle(stats)) return searched(true);

  // The stars the clipping gave do not fit (roundings near cocircular sites): every star again
  // with the exact predicates.
  std::vector<std::vector<StarEntry>> exact_chunks(chunks);
  std::vector<std::uint8_t> failed(chunks, 0);
  auto run_exact = [&](std::size_t begin, std::size_t end) {
    ExactStar exact(scene, grid, std::span<const std::uint32_t>(vertex_of_site.get(), n));
    std::vector<StarEntry> star;
    for (std::size_t c = begin; c < end; ++c) {
      std::vector<StarEntry>& mine = exact_chunks[c];
      for (std::size_t v = c * kVertexChunk; v < std::min(n, (c + 1) * kVertexChunk); ++v) {
        if (!exact.compute(site_of_vertex_[v], chunk_stars[c].radius_squared[v - c * kVertexChunk], star)) {
          failed[c] = 1;
          break;
        }
        mine.insert(mine.end(), star.begin(), star.end());
        star_start[v + 1] = static_cast<std::uint32_t>(star.size());  // sizes for now
      }
    }
  };
  if (parallel) {
    parallel_for(chunks, 1, run_exact);
  } else {
    run_exact(0, chunks);
  }
  if (std::find(failed.begin(), failed.end(), 1) != failed.end()) return searched(false);
  stats.exact_stars += n;
  std::vector<StarEntry> exact_stars;
  for (const auto& c : exact_chunks) exact_stars.insert(exact_stars.end(), c.begin(), c.end());
  for (std::size_t v = 0; v < n; ++v) star_start[v + 1] += star_start[v];
  return searched(triangulation_.build(star_start, exact_stars) && settle(stats));
}

bool KeptDelaunay::compute(const Scene& scene, const Weighting& weighting, std::span<Cell> cells, bool parallel,
                           KeptTopologyStats& stats, StatusCounts& counts) {
  assert(suits(scene));
  scene_area_ = scene.domain.area();
  if (on_rows_and_columns(scene.sites)) {
    // The kept triangulation, if any, is not moved along: the next call that triangulates
    // builds it again from its own sites.
    valid_ = false;
    search_cells(scene, CellSearch(scene), weighting, cells, parallel);
    stats.searched_cells += scene.wanted_count();
    return false;
  }
  bool searched = false;  // every wanted cell measured by the search already
  bool ready = matches(scene) && move_vertices(scene);
  if (ready) {
    std::vector<std::uint32_t> folded;
    Settled settled = settle(stats, folded);
    if (settled == Settled::folded) {
      // Large moves folded a few triangles over: their vertices go and come back; many folds
      // (a new set of sites, say) are cheaper to rebuild.
      std::size_t repaired = 0;
      const bool fixed = triangulation_.repair(folded, previous_, wraps_, scene.sites.size() / kRepairShare, repaired);
      stats.repaired_vertices += repaired;
      settled = fixed ? settle(stats, folded) : Settled::failed;
    }
    ready = settled == Settled::delaunay;
  }
  if (!ready) {
    ++stats.rebuilds;
    ready = rebuild(scene, weighting, cells, parallel, stats);
    searched = true;
  }
  if (!ready || !fits_) {
    valid_ = false;
    if (!searched) search_cells(scene, CellSearch(scene), weighting, cells, parallel);
    stats.searched_cells += scene.wanted_count();
    return false;
  }
  valid_ = true;
  domain_ = scene.domain;
  site_count_ = scene.sites.size();
  wanted_begin_ = scene.wanted_begin;
  wanted_end_ = scene.wanted_end;

  // The wanted cells in vertex order (neighbours in the plane together), ties left to the search.
  const std::size_t n = scene.sites.size();
  const std::size_t chunks = (n + kVertexChunk - 1) / kVertexChunk;
  std::vector<std::vector<std::uint32_t>> ties(chunks);
  std::vector<StatusCounts> found(chunks);
  auto measure = [&](std::size_t begin, std::size_t end) {
    const auto positions = triangulation_.positions();
    std::uint32_t vertices[4], sites[4];
    Point origins[4];
    Cell* targets[4];
    int pending = 0;
    // The pending cells' results in vertex order: bit j of `measured`, cell j measured.
    auto flush = [&](std::size_t c, int measured) {
      for (int j = 0; j < pending; ++j) {
        if (measured >> j & 1) {
          found[c].add(*targets[j]);
        } else {
          ties[c].push_back(sites[j]);
        }
      }
      pending = 0;
    };
    for (std::size_t c = begin; c < end; ++c) {
      const std::size_t chunk_end = std::min(n, (c + 1) * kVertexChunk);
      for (std::size_t v = c * kVertexChunk; v < chunk_end; ++v) {
        // The cells are written at their site's place, far apart in memory: fetch ahead.
        if (v + kPrefetch < chunk_end) {
          const std::uint32_t ahead = site_of_vertex_[v + kPrefetch];
          if (ahead >= scene.wanted_begin && ahead < scene.wanted_end) {
            // A cell (56 bytes) mostly straddles two cache lines: both are fetched.
            const char* cell = reinterpret_cast<const char*>(&cells[ahead - scene.wanted_begin]);
            __builtin_prefetch(cell, 1);
            __builtin_prefetch(cell + sizeof(Cell) - 1, 1);
          }
        }
        const std::uint32_t site = site_of_vertex_[v];
        if (site < scene.wanted_begin || site >= scene.wanted_end) continue;
        // Four wanted cells at a time (DelaunayCells::measure_four), the last few one by one.
        vertices[pending] = static_cast<std::uint32_t>(v);
        origins[pending] = positions[v];
        sites[pending] = site;
        targets[pending] = &cells[site - scene.wanted_begin];
        if (++pending == 4) flush(c, cells_.measure_four(triangulation_, vertices, scene, origins, weighting, targets, lanes_));
      }
      int measured = 0;
      for (int j = 0; j < pending; ++j)
        measured |= static_cast<int>(cells_.measure(triangulation_, vertices[j], scene, origins[j], weighting, *targets[j])) << j;
      flush(c, measured);
    }
  };
  if (parallel) {
    parallel_for(chunks, 1, measure);
  } else {
    measure(0, chunks);
  }
  std::vector<std::uint32_t> tied;
  for (const auto& c : ties) tied.insert(tied.end(), c.begin(), c.end());
  if (!tied.empty()) search_listed_cells(scene, CellSearch(scene), weighting, tied, cells, parallel);
  stats.kept_cells += scene.wanted_count() - tied.size();
  stats.searched_cells += tied.size();
  stats.tie_cells += tied.size();
  counts = StatusCounts{};
  for (const StatusCounts& c : found) counts += c;
  for (std::uint32_t site : tied) counts.add(cells[site - scene.wanted_begin]);
  return true;
}

}  // namespace bluetile
