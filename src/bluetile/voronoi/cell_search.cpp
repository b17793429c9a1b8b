// The cell search: see cell_search.h.
#include "bluetile/voronoi/cell_search.h"

#include <algorithm>
#include <cassert>
#include <cmath>

#include "bluetile/core/parallel.h"

namespace bluetile {
namespace {

// Sites per grid bucket: about one, so the buckets a relaxed cell needs are the 21 of a 5x5
// block without its corners, and each holds few sites the cell does not need.
constexpr double kSitesPerBucket = 1.0;

// When a site shares its grid bucket with this many others on average (uniform random sites:
// about 1; a relaxed set: fewer), the sites are far from uniform (on a line, in a cluster): the
// grid then costs O(N) or O(sqrt N) per cell, and the k-d tree (site_tree.h) searches instead.
constexpr double kCrowdedBucket = 8.0;

// The squared distance from a point at `local` in its bucket (`cell` the bucket's size) to the
// bucket `step` away: what a search from that point must reach to see the bucket's sites.
double bucket_gap_squared(const SiteGrid::SearchStep& step, Point local, Point cell) {
  const double gx = step.dx > 0   ? static_cast<double>(step.dx) * cell.x - local.x
                    : step.dx < 0 ? local.x - static_cast<double>(step.dx + 1) * cell.x
                                  : 0.0;
  const double gy = step.dy > 0   ? static_cast<double>(step.dy) * cell.y - local.y
                    : step.dy < 0 ? local.y - static_cast<double>(step.dy + 1) * cell.y
                                  : 0.0;
  return gx * gx + gy * gy;
}

using Candidate = SearchScratch::Candidate;

bool inside_grid(const SiteGrid& grid, long bx, long by) {
  return bx >= 0 && by >= 0 && bx < grid.columns() && by < grid.rows();
}

// The first polygon of a cell, relative to its site: on a torus the W x H rectangle centred on
// the site (no point is farther than half a period from the nearest copy of the site along
// either axis); in a bounded domain the domain itself.
void start_cell(const Scene& scene, Point origin, ConvexPolygon& cell_polygon) {
  if (scene.periodic()) {
    cell_polygon.reset_rectangle(-0.5 * scene.domain.size, 0.5 * scene.domain.size, kOwnCopy);
  } else {
    cell_polygon.reset_rectangle(-origin, scene.domain.size - origin, kOwnCopy);
  }
}

// The fallback search: square rings of buckets around the site's bucket until the ring's inner
// distance reaches twice the cell radius. Returns false for a coincident site.
bool build_cell_by_rings(const Scene& scene, const SiteGrid& grid, std::uint32_t site, ConvexPolygon& cell_polygon,
                std::vector<Candidate>& candidates) {
  const Point origin = scene.sites[site];
  const Point cell = grid.cell_size();
  start_cell(scene, origin, cell_polygon);
  auto [cx, cy] = grid.bucket_coordinates(origin);
  bool coincident = false;

  auto gather = [&](long bx, long by) {
    if (!scene.periodic() && !inside_grid(grid, bx, by)) return;  // no copies beyond a bounded domain
    grid.for_each_in_bucket(bx, by, origin, [&](std::uint32_t other, Point d) {
      if (d.x == 0.0 && d.y == 0.0) {
        if (other < site) coincident = true;
        return;  // the site itself, or a copy of it at the same place
      }
      candidates.push_back({d.x * d.x + d.y * d.y, d, other});
    });
  };
  auto clip_nearest_first = [&] {
    // Insertion sort: a ring holds a few dozen candidates, and being stable it breaks distance
    // ties by gathering order, which is fixed, so the clipping order is the same every run.
    for (std::size_t i = 1; i < candidates.size(); ++i) {
      Candidate c = candidates[i];
      std::size_t j = i;
      for (; j > 0 && candidates[j - 1].distance_squared > c.distance_squared; --j) candidates[j] = candidates[j - 1];
      candidates[j] = c;
    }
    for (const Candidate& c : candidates) cell_polygon.clip_by_bisector(c.offset, c.site);
    candidates.clear();
  };

  // Ring 0 and 1 together (the 3x3 block), then one ring at a time.
  candidates.clear();
  for (long dy = -1; dy <= 1; ++dy)
    for (long dx = -1; dx <= 1; ++dx) gather(cx + dx, cy + dy);
  if (coincident) return false;
  clip_nearest_first();

  for (long ring = 1;; ++ring) {
    // Every site not yet visited lies outside buckets [c - ring, c + ring] on both axes.
    double reach = std::min({origin.x - static_cast<double>(cx - ring) * cell.x,
                             static_cast<double>(cx + ring + 1) * cell.x - origin.x,
                             origin.y - static_cast<double>(cy - ring) * cell.y,
                             static_cast<double>(cy + ring + 1) * cell.y - origin.y});
    if (reach > 0.0 && reach * reach >= 4.0 * cell_polygon.max_radius_squared()) break;
    // A bounded domain has nothing beyond the grid: once the ring holds all of it, every site was seen.
    if (!scene.periodic() && cx - ring <= 0 && cy - ring <= 0 && cx + ring >= grid.columns() - 1 &&
        cy + ring >= grid.rows() - 1)
      break;
    long next = ring + 1;
    for (long dx = -next; dx <= next; ++dx) {
      gather(cx + dx, cy - next);
      gather(cx + dx, cy + next);
    }
    for (long dy = -next + 1; dy <= next - 1; ++dy) {
      gather(cx - next, cy + dy);
      gather(cx + next, cy + dy);
    }
    if (coincident) return false;
    clip_nearest_first();
    // The initial rectangle bounds every cell, so the search ends by ring ~ 2 periods at most.
    assert(next <= 4 * (grid.columns() + grid.rows()) + 8);
  }
  return true;
}

}  // namespace

CellSearch::CellSearch(const Scene& scene) : grid(scene.sites, scene.domain, kSitesPerBucket) {
  double sharing = 0.0;  // sum over sites of the other sites in their bucket
  for (std::size_t b = 0; b < grid.bucket_count(); ++b) {
    const double c = static_cast<double>(grid.sites_in_bucket(b).size());
    sharing += c * (c - 1.0);
  }
  if (sharing > kCrowdedBucket * static_cast<double>(scene.sites.size()))
    tree.emplace(scene.sites, scene.domain, scene.periodic());
}

bool build_cell(const Scene& scene, const CellSearch& search, std::uint32_t site, Point origin,
                ConvexPolygon& cell_polygon, SearchScratch& scratch) {
  start_cell(scene, origin, cell_polygon);
  if (search.tree) return search.tree->clip_cell(site, origin, cell_polygon, scratch.tree);
  const SiteGrid& grid = search.grid;
  const Point cell = grid.cell_size();
  auto [cx, cy] = grid.bucket_coordinates(origin);
  // The site's place inside its bucket, for the exact distance to each bucket visited.
  const Point local{origin.x - static_cast<double>(cx) * cell.x, origin.y - static_cast<double>(cy) * cell.y};
  bool coincident = false;
  auto visit = [&](std::uint32_t other, Point d) {
    if (d.x == 0.0 && d.y == 0.0) {
      coincident |= other < site;
      return;  // the site itself, or a copy of it at the same place
    }
    cell_polygon.clip_by_bisector(d, other);
  };
  for (const auto& step : grid.search_order()) {
    const double reach_squared = 4.0 * cell_polygon.max_radius_squared();
    if (step.lower_bound_squared >= reach_squared) return !coincident;
    // The exact distance from the site to bucket (dx, dy) skips buckets the bound let through.
    if (bucket_gap_squared(step, local, cell) >= reach_squared) continue;
    if (!scene.periodic() && !inside_grid(grid, cx + step.dx, cy + step.dy)) continue;
    grid.for_each_in_bucket(cx + step.dx, cy + step.dy, origin, visit);
    if (coincident) return false;
  }
  return build_cell_by_rings(scene, grid, site, cell_polygon, scratch.candidates);
}


namespace {

// Per-thread buffers: a batch of small scenes (the Wang loop's crops hold about 15 sites and 2
// wanted cells) would otherwise allocate them once per scene, which cost more than the cells.
// Their contents do not carry over: every use starts by resetting them.
struct SearchBuffers {
  ConvexPolygon cell_polygon;
  SearchScratch scratch;
  bool in_use = false;
};

}  // namespace

void search_cells(const Scene& scene, const CellSearch& search, const Weighting& weighting, std::span<Cell> cells,
                  bool parallel) {
  const SiteGrid& grid = search.grid;
  // Buckets in chunks of a fixed size, so that a chunk's cells are neighbours in the plane.
  constexpr std::size_t kBuckets = 256;
  const std::size_t chunks = (grid.bucket_count() + kBuckets - 1) / kBuckets;
  auto run_chunks = [&](std::size_t begin, std::size_t end) {
    thread_local SearchBuffers buffers;
    assert(!buffers.in_use);  // nothing in the loop below runs another search on this thread
    buffers.in_use = true;
    const auto starts = grid.bucket_starts();
    for (std::size_t c = begin; c < end; ++c) {
      for (std::size_t b = c * kBuckets; b < std::min(grid.bucket_count(), (c + 1) * kBuckets); ++b) {
        for (std::uint32_t slot = starts[b]; slot < starts[b + 1]; ++slot) {
          const std::uint32_t site = grid.site_indices()[slot];
          if (site < scene.wanted_begin || site >= scene.wanted_end) continue;
          // The grid's copy of the position, in bucket order: read where the chunk's thread
          // reads its neighbours, not at the site's index in the scene (another thread's lines).
          const Point origin = grid.stored_point(slot);
          const bool complete = build_cell(scene, search, site, origin, buffers.cell_polygon, buffers.scratch);
          cells[site - scene.wanted_begin] = measure_cell(scene, origin, !complete, buffers.cell_polygon, weighting);
        }
      }
    }
    buffers.in_use = false;
  };
  if (parallel) {
    parallel_for(chunks, 1, run_chunks);
  } else {
    run_chunks(0, chunks);
  }
}

void search_listed_cells(const Scene& scene, const CellSearch& search, const Weighting& weighting,
                         std::span<const std::uint32_t> sites, std::span<Cell> cells, bool parallel) {
  auto run = [&](std::size_t begin, std::size_t end) {
    ConvexPolygon cell_polygon;
    SearchScratch scratch;
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t site = sites[k];
      const bool complete = build_cell(scene, search, site, scene.sites[site], cell_polygon, scratch);
      cells[site - scene.wanted_begin] = measure_cell(scene, scene.sites[site], !complete, cell_polygon, weighting);
    }
  };
  if (parallel) {
    parallel_for(sites.size(), 64, run);
  } else {
    run(0, sites.size());
  }
}

}  // namespace bluetile
