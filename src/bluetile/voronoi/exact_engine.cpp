// Exact periodic Voronoi cells by half-plane clipping (see exact_engine.h for the method).
#include "bluetile/voronoi/exact_engine.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <optional>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/density_prefix.h"
#include "bluetile/voronoi/kept_topology.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/scene.h"
#include "bluetile/voronoi/site_grid.h"
#include "bluetile/voronoi/site_tree.h"

namespace bluetile {
namespace {

// Sites per grid bucket: about one, so the buckets a relaxed cell needs are the 21 of a 5x5
// block without its corners, and each holds few sites the cell does not need.
constexpr double kSitesPerBucket = 1.0;

// The label of the cell edges that come from the initial rectangle (the site's own copies).
constexpr std::uint32_t kOwnCopy = kUnlabelled;

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

struct Candidate {
  double distance_squared;
  Point offset;
  std::uint32_t site;
};

// The neighbour search of one scene: the uniform grid, and the tree for far-from-uniform sites.
struct CellSearch {
  SiteGrid grid;
  std::optional<SiteTree> tree;

  explicit CellSearch(const Scene& scene) : grid(scene.sites, scene.domain, kSitesPerBucket) {
    double sharing = 0.0;  // sum over sites of the other sites in their bucket
    for (std::size_t b = 0; b < grid.bucket_count(); ++b) {
      const double c = static_cast<double>(grid.sites_in_bucket(b).size());
      sharing += c * (c - 1.0);
    }
    if (sharing > kCrowdedBucket * static_cast<double>(scene.sites.size()))
      tree.emplace(scene.sites, scene.domain, scene.periodic());
  }
};

// Per-thread buffers of the searches, reused from cell to cell.
struct SearchScratch {
  std::vector<Candidate> candidates;
  SiteTree::Search tree;
};

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

// Computes the cell of `site`, at `origin` (its position), into `cell_polygon`. Returns false
// when the site coincides with a site of lower index (which owns the cell).
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

}  // namespace

struct ExactEngine::DensityEntry {
  std::shared_ptr<const DensityGrid> density;  // held, so that its address names no other grid
  std::uint64_t texel_hash = 0;                // catches a grid changed in place
  bool uniform = false;
  std::unique_ptr<const DensityPrefix> prefix;  // for a varying density
};

namespace {

// How a scene's density weights its cells: not at all (no density, or a constant one, whose
// weights cancel in the centroid), or texel by texel through its prefix tables.
struct Weighting {
  const DensityPrefix* prefix = nullptr;  // non-null: a varying density
  double constant = 1.0;                  // otherwise: the density everywhere
};

// FNV-1a over the texels, two at a time, in four interleaved streams (one chain of multiplies
// per texel would cost a millisecond a call on a 1024^2 map, and the hash runs on every call).
std::uint64_t hash_texels(const DensityGrid& density) {
  constexpr std::uint64_t kPrime = 0x100000001b3ull;
  std::uint64_t h[4];
  for (std::uint64_t k = 0; k < 4; ++k)
    h[k] = (0xcbf29ce484222325ull + k) ^ (static_cast<std::uint64_t>(density.width) << 32 | static_cast<std::uint32_t>(density.height));
  const float* t = density.texels.data();
  const std::size_t n = density.texels.size();
  auto pair = [t](std::size_t i) {
    return static_cast<std::uint64_t>(std::bit_cast<std::uint32_t>(t[i])) << 32 | std::bit_cast<std::uint32_t>(t[i + 1]);
  };
  std::size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    h[0] = (h[0] ^ pair(i)) * kPrime;
    h[1] = (h[1] ^ pair(i + 2)) * kPrime;
    h[2] = (h[2] ^ pair(i + 4)) * kPrime;
    h[3] = (h[3] ^ pair(i + 6)) * kPrime;
  }
  for (; i < n; ++i) h[0] = (h[0] ^ std::bit_cast<std::uint32_t>(t[i])) * kPrime;
  return ((h[0] * kPrime ^ h[1]) * kPrime ^ h[2]) * kPrime ^ h[3];
}

// A measured cell (area, second moment, radius) under the scene's weighting: its mass, weighted
// moments and centroid; `offset` is the plain centroid relative to the site, `polygon` the cell's
// vertices relative to the site (needed only with a density table).
Cell weigh_cell(const Scene& scene, Point origin, const Weighting& weighting, std::span<const Point> polygon, Cell cell,
                Point offset) {
  if (weighting.prefix) {
    const WeightedMoments m = weighting.prefix->moments(polygon, origin, scene.domain.size, scene.periodic());
    cell.mass = m.mass;
    cell.second_moment = m.second;
    offset = m.mass > 0.0 ? m.first / m.mass : Point{0.0, 0.0};
  } else if (weighting.constant != 1.0) {
    cell.mass = weighting.constant * cell.area;
    cell.second_moment *= weighting.constant;
  }
  if (!(cell.mass > 0.0) && cell.area > 0.0) {
    // No density anywhere in the cell: nothing pulls the site, it stays.
    cell.mass = 0.0;
    cell.centroid = origin;
    cell.status = CellStatus::zero_density;
    return cell;
  }
  cell.centroid = scene_point(scene, origin + offset);
  return cell;
}

Cell measure_cell(const Scene& scene, Point origin, bool coincident, const ConvexPolygon& cell_polygon,
                  const Weighting& weighting) {
  Cell cell;
  if (coincident) {
    cell.centroid = origin;
    cell.status = CellStatus::coincident;
    return cell;
  }
  const PolygonMoments moments = cell_polygon.moments();
  cell.area = moments.area();
  cell.mass = cell.area;
  cell.radius = std::sqrt(cell_polygon.max_radius_squared());
  cell.second_moment = moments.second_moment();
  std::span<const Point> polygon;  // only the density's integration needs the vertices as points
  if (weighting.prefix) {
    thread_local std::vector<Point> vertices;
    vertices.clear();
    for (const PolygonVertex& v : cell_polygon.vertices()) vertices.push_back(v.p);
    polygon = vertices;
  }
  return weigh_cell(scene, origin, weighting, polygon, cell, moments.centroid());
}

using Topology = ExactEngine::Topology;

// The list of `site`'s cell (just computed by the search, radius squared `radius_squared`): every
// copy of a site within Topology::kListFactor times the radius, nearest first. Returns the list's
// radius, or -1 when the grid's search order does not reach that far (the cell is then searched
// on every call).
double gather_list(const Scene& scene, const SiteGrid& grid, std::uint32_t site, double radius_squared,
                   std::vector<Topology::Entry>& list, std::vector<double>& distances) {
  const double reach = Topology::kListFactor * std::sqrt(radius_squared);
  const Point cell = grid.cell_size();
  if (!(reach < static_cast<double>(SiteGrid::kSearchRadius) * std::min(cell.x, cell.y))) return -1.0;
  const double reach_squared = reach * reach;
  const Point origin = scene.sites[site];
  auto [cx, cy] = grid.bucket_coordinates(origin);
  const Point local{origin.x - static_cast<double>(cx) * cell.x, origin.y - static_cast<double>(cy) * cell.y};
  const std::size_t first = list.size();
  for (const auto& step : grid.search_order()) {
    if (step.lower_bound_squared >= reach_squared) break;
    if (bucket_gap_squared(step, local, cell) > reach_squared) continue;
    const long bx = cx + step.dx, by = cy + step.dy;
    if (!scene.periodic() && !inside_grid(grid, bx, by)) continue;
    const auto wx = static_cast<std::int16_t>(SiteGrid::wrap_count(bx, grid.columns()));
    const auto wy = static_cast<std::int16_t>(SiteGrid::wrap_count(by, grid.rows()));
    grid.for_each_in_bucket(bx, by, origin, [&](std::uint32_t other, Point d) {
      if (other == site && wx == 0 && wy == 0) return;  // the site itself
      const double dd = d.x * d.x + d.y * d.y;
      if (dd > reach_squared) return;
      // Insertion by distance, stable: a list holds about ten sites.
      std::size_t k = list.size();
      list.push_back({other, wx, wy});
      distances.push_back(dd);
      for (; k > first && distances[k - 1 - first] > dd; --k) {
        list[k] = list[k - 1];
        distances[k - first] = distances[k - 1 - first];
      }
      list[k] = {other, wx, wy};
      distances[k - first] = dd;
    });
  }
  return reach;
}

// Where a site is now against its reference position: p = reference - k period + rest, k a whole
// number of periods (the site wrapped across the domain's border), |rest| = moved.
struct Moved {
  Point p;
  double moved;
  std::int8_t kx, ky;
};

// Every site's move since the reference positions, reference[q] being site order[q]'s (site q's
// when `order` is empty); returns the largest.
double displacements(const Scene& scene, const std::vector<Point>& reference, const std::vector<std::uint32_t>& order,
                     std::vector<Moved>& now) {
  const std::size_t n = scene.sites.size();
  now.resize(n);
  const Point size = scene.domain.size;
  constexpr std::size_t kChunk = 16384;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<double> chunk_max(chunks, 0.0);
  parallel_for(chunks, 1, [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c) {
      double m = 0.0;
      for (std::size_t q = c * kChunk; q < std::min(n, (c + 1) * kChunk); ++q) {
        const Point p = scene.sites[order.empty() ? q : order[q]];
        Point d = p - reference[q];
        std::int8_t kx = 0, ky = 0;
        if (scene.periodic()) {
          // A site moves less than half a period between calls of a relaxation, so a jump of
          // more than half a period is a wrap; anything else only makes the rest large.
          kx = d.x > 0.5 * size.x ? -1 : d.x < -0.5 * size.x ? 1 : 0;
          ky = d.y > 0.5 * size.y ? -1 : d.y < -0.5 * size.y ? 1 : 0;
          d.x += static_cast<double>(kx) * size.x;
          d.y += static_cast<double>(ky) * size.y;
        }
        const double moved = std::sqrt(d.x * d.x + d.y * d.y);
        now[q] = {p, moved, kx, ky};
        m = std::max(m, moved);
      }
      chunk_max[c] = m;
    }
  });
  double m = 0.0;
  for (double v : chunk_max) m = std::max(m, v);
  return m;
}

// measure_cell for a cell given as its vertices, counter-clockwise relative to the site.
Cell measure_vertices(const Scene& scene, std::uint32_t site, std::span<const Point> polygon, double radius_squared,
                      const Weighting& weighting) {
  Cell cell;
  const Point origin = scene.sites[site];
  const PolygonMoments moments = polygon_moments(polygon);
  cell.area = moments.area();
  cell.mass = cell.area;
  cell.radius = std::sqrt(radius_squared);
  cell.second_moment = moments.second_moment();
  return weigh_cell(scene, origin, weighting, polygon, cell, moments.centroid());
}

// The most edges a cell built directly from its kept neighbours may have (more: clipped).
constexpr std::size_t kMaxDirectEdges = 24;

// The cell straight from its kept edge neighbours d[0..m) (counter-clockwise, as when the list
// was made): vertex k is where the bisectors of d[k] and d[k+1] meet. Accepted only when each
// turn is counter-clockwise and well conditioned, the neighbours go round the site once, and no
// vertex lies beyond the bisector of any other list entry d[m..count) or edge neighbour (the
// clipping predicate): then the polygon is the intersection of the list's half-planes, the
// cell clipping would give, to rounding. Returns false otherwise (the cell is then clipped).
bool direct_cell(const Point* d, std::size_t m, std::size_t count, Point* vertex, double& radius_squared) {
  double r2 = 0.0;
  int windings = 0;
  for (std::size_t k = 0; k < m; ++k) {
    const Point a = d[k], b = d[k + 1 == m ? 0 : k + 1];
    const double det = a.x * b.y - a.y * b.x;
    const double aa = a.x * a.x + a.y * a.y, bb = b.x * b.x + b.y * b.y;
    // sin of the turn at least 1e-4: the vertex then carries at most ~1e4 roundings of |d|.
    if (!(det > 0.0 && det * det > 1e-8 * aa * bb)) return false;
    const double ha = 0.5 * aa, hb = 0.5 * bb;
    const Point v{(ha * b.y - hb * a.y) / det, (a.x * hb - b.x * ha) / det};
    vertex[k] = v;
    r2 = std::max(r2, v.x * v.x + v.y * v.y);
    windings += a.y < 0.0 && b.y >= 0.0;
  }
  if (windings != 1) return false;
  const double reach_squared = 4.0 * r2;
  for (std::size_t e = 0; e < count; ++e) {
    const Point n = d[e];
    const double dd = n.x * n.x + n.y * n.y;
    if (dd >= reach_squared) continue;  // the clipping's own test: cannot reach the cell
    const double offset = 0.5 * dd;
    for (std::size_t k = 0; k < m; ++k) {
      if (e < m && (e == k || e == (k + 1 == m ? 0 : k + 1))) continue;  // the vertex's own lines
      if (vertex[k].x * n.x + vertex[k].y * n.y - offset > 0.0) return false;
    }
  }
  radius_squared = r2;
  return true;
}

struct SceneRun {
  const Scene& scene;
  const Weighting& weighting;
  SceneCells& out;
  bool parallel_inside;
  Topology* topology;  // null: not kept
  KeptTopologyStats& stats;
};

// Puts the entries of list[first, end) that carry the cell's edges first, in the polygon's
// counter-clockwise order (each edge's site: its nearest copy in the list), the others after
// them nearest first. Returns how many edges (0: the cell is always clipped: an edge of the
// starting rectangle, an edge whose site is not in the list, too many edges).
std::uint8_t edges_first(const ConvexPolygon& polygon, std::vector<Topology::Entry>& list, std::size_t first,
                         std::vector<Topology::Entry>& scratch) {
  const auto vertices = polygon.vertices();
  const std::size_t count = list.size() - first;
  scratch.clear();
  std::vector<std::uint8_t> used(count, 0);  // small: a list holds about ten entries
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const PolygonVertex& v = vertices[i];
    if (v.p == vertices[(i + 1) % vertices.size()].p) continue;  // a tie's zero-length edge
    if (v.edge_label == kOwnCopy || scratch.size() >= kMaxDirectEdges) return 0;
    std::size_t k = 0;
    while (k < count && (used[k] || list[first + k].site != v.edge_label)) ++k;
    if (k == count) return 0;
    used[k] = 1;
    scratch.push_back(list[first + k]);
  }
  const std::size_t edges = scratch.size();
  if (edges < 3) return 0;
  for (std::size_t k = 0; k < count; ++k)
    if (!used[k]) scratch.push_back(list[first + k]);
  std::copy(scratch.begin(), scratch.end(), list.begin() + static_cast<std::ptrdiff_t>(first));
  return static_cast<std::uint8_t>(edges);
}

struct SearchBuffers {
  ConvexPolygon cell_polygon;
  SearchScratch scratch;
  std::vector<double> distances;
  std::vector<Topology::Entry> edge_scratch;
  bool in_use = false;
};

// Measures the wanted cells by the full search; with `lists`, also makes every cell's list.
void search_scene(SceneRun& run, Topology* lists) {
  const Scene& scene = run.scene;
  const CellSearch search(scene);
  const SiteGrid& grid = search.grid;
  if (lists && search.tree) lists = nullptr;  // far-from-uniform sites: always searched
  // Buckets in chunks of a fixed size, each chunk's lists in its own buffers, joined in chunk
  // order: the same lists whatever the thread count.
  constexpr std::size_t kBuckets = 256;
  const std::size_t chunks = (grid.bucket_count() + kBuckets - 1) / kBuckets;
  struct ChunkLists {
    std::vector<std::uint32_t> order, sizes;
    std::vector<std::uint8_t> edges;
    std::vector<Topology::Entry> entries;
    std::vector<double> reach;
  };
  std::vector<ChunkLists> chunk_lists(lists ? chunks : 0);

  auto run_chunks = [&](std::size_t begin, std::size_t end) {
    // Per-thread buffers: a batch of small scenes (the Wang loop's crops hold about 15 sites and
    // 2 wanted cells) would otherwise allocate them once per scene, which cost more than the
    // cells. Their contents do not carry over: every use starts by resetting them.
    thread_local SearchBuffers buffers;
    assert(!buffers.in_use);  // nothing in the loop below runs another search on this thread
    buffers.in_use = true;
    ConvexPolygon& cell_polygon = buffers.cell_polygon;
    SearchScratch& scratch = buffers.scratch;
    std::vector<double>& distances = buffers.distances;
    std::vector<Topology::Entry>& edge_scratch = buffers.edge_scratch;
    for (std::size_t c = begin; c < end; ++c) {
      for (std::size_t b = c * kBuckets; b < std::min(grid.bucket_count(), (c + 1) * kBuckets); ++b) {
        const auto starts = grid.bucket_starts();
        for (std::uint32_t slot = starts[b]; slot < starts[b + 1]; ++slot) {
          const std::uint32_t site = grid.site_indices()[slot];
          // The grid's copy of the position, in bucket order: read where the chunk's thread
          // reads its neighbours, not at the site's index in the scene (another thread's lines).
          const Point origin = grid.stored_point(slot);
          if (site < scene.wanted_begin || site >= scene.wanted_end) {
            if (lists) {  // a fixed site: in the order (its position is read there), no list
              chunk_lists[c].order.push_back(site);
              chunk_lists[c].edges.push_back(0);
              chunk_lists[c].sizes.push_back(0);
              chunk_lists[c].reach.push_back(-1.0);
            }
            continue;
          }
          bool complete = build_cell(scene, search, site, origin, cell_polygon, scratch);
          run.out.cells[site - scene.wanted_begin] = measure_cell(scene, origin, !complete, cell_polygon, run.weighting);
          if (!lists) continue;
          ChunkLists& mine = chunk_lists[c];
          const std::size_t before = mine.entries.size();
          distances.clear();
          const double reach =
              complete ? gather_list(scene, grid, site, cell_polygon.max_radius_squared(), mine.entries, distances) : -1.0;
          mine.order.push_back(site);
          mine.sizes.push_back(static_cast<std::uint32_t>(mine.entries.size() - before));
          mine.reach.push_back(reach);
          mine.edges.push_back(reach >= 0.0 && scene.periodic()
                                   ? edges_first(cell_polygon, mine.entries, before, edge_scratch)
                                   : 0);
        }
      }
    }
    buffers.in_use = false;
  };
  if (run.parallel_inside) {
    parallel_for(chunks, 1, run_chunks);
  } else {
    run_chunks(0, chunks);
  }
  run.stats.searched_cells += scene.wanted_count();
  if (!lists) return;
  lists->drop_lists();
  std::size_t total = 0;
  for (const ChunkLists& c : chunk_lists) total += c.entries.size();
  if (total > std::numeric_limits<std::uint32_t>::max()) return;
  lists->order.reserve(scene.wanted_count());
  lists->reach.reserve(scene.wanted_count());
  lists->start.reserve(scene.wanted_count() + 1);
  lists->entries.reserve(total);
  lists->start.push_back(0);
  for (const ChunkLists& c : chunk_lists) {
    lists->order.insert(lists->order.end(), c.order.begin(), c.order.end());
    lists->reach.insert(lists->reach.end(), c.reach.begin(), c.reach.end());
    lists->edges.insert(lists->edges.end(), c.edges.begin(), c.edges.end());
    lists->entries.insert(lists->entries.end(), c.entries.begin(), c.entries.end());
    for (std::uint32_t size : c.sizes) lists->start.push_back(lists->start.back() + size);
  }
  // Entries name their site by its place in the order, where its position is kept per call.
  std::vector<std::uint32_t> place(scene.sites.size());
  for (std::size_t q = 0; q < lists->order.size(); ++q) place[lists->order[q]] = static_cast<std::uint32_t>(q);
  for (Topology::Entry& e : lists->entries) e.site = place[e.site];
  lists->reference.resize(scene.sites.size());
  for (std::size_t q = 0; q < lists->order.size(); ++q) lists->reference[q] = scene.sites[lists->order[q]];
  lists->has_lists = true;
}

// Measures the wanted cells from the kept lists; cells whose certificate fails are searched.
// Returns how many failed.
std::size_t kept_scene(SceneRun& run, Topology& topology) {
  const Scene& scene = run.scene;
  std::vector<Moved> now;
  const double farthest = displacements(scene, topology.reference, topology.order, now);
  // The few sites that moved the most (at most one in Topology::kFastShare, those farther than
  // `slow`) are checked one by one through a grid of their own; the certificate of a cell then
  // only needs room for the others' moves, at most `slow`.
  double slow = farthest;
  std::vector<std::uint32_t> fast;
  std::vector<Point> fast_points;
  const std::size_t n = scene.sites.size();
  const std::size_t allowed = n / Topology::kFastShare;
  if (allowed > 0 && farthest > 0.0) {
    std::vector<double> sorted(n);
    for (std::size_t q = 0; q < n; ++q) sorted[q] = now[q].moved;
    std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n - 1 - allowed), sorted.end());
    slow = sorted[n - 1 - allowed];
    for (std::size_t q = 0; q < n; ++q) {
      if (now[q].moved > slow) {
        fast.push_back(static_cast<std::uint32_t>(q));
        fast_points.push_back(now[q].p);
      }
    }
  }
  std::optional<SiteGrid> fast_grid;
  if (!fast.empty()) fast_grid.emplace(fast_points, scene.domain, 1.0, false);
  const Point size = scene.domain.size;
  const std::size_t count = topology.order.size();
  std::vector<std::uint8_t> failed(count, 0);

  auto run_range = [&](std::size_t begin, std::size_t end) {
    ConvexPolygon cell_polygon;
    std::vector<Point> offsets(32);
    Point vertex[kMaxDirectEdges];
    for (std::size_t q = begin; q < end; ++q) {
      const double reach = topology.reach[q];
      if (reach < 0.0) {
        failed[q] = topology.order[q] >= scene.wanted_begin && topology.order[q] < scene.wanted_end;
        continue;
      }
      const std::uint32_t site = topology.order[q];
      const Moved centre = now[q];
      const Point origin = centre.p;
      bool coincident = false;
      const std::uint32_t list_begin = topology.start[q], list_size = topology.start[q + 1] - list_begin;
      if (list_size > offsets.size()) offsets.resize(list_size);
      for (std::uint32_t e = 0; e < list_size; ++e) {
        const Topology::Entry entry = topology.entries[list_begin + e];
        const Moved& other = now[entry.site];
        // The same copy as when the list was made, shifted by the periods its site and this
        // one wrapped across since.
        const Point shift{static_cast<double>(entry.wx + other.kx - centre.kx) * size.x - origin.x,
                          static_cast<double>(entry.wy + other.ky - centre.ky) * size.y - origin.y};
        offsets[e] = other.p + shift;
        coincident |= offsets[e].x == 0.0 && offsets[e].y == 0.0;  // searched: the search decides
      }
      double radius_squared = 0.0;
      const std::size_t edges = topology.edges[q];
      // Built from its edges only while the cell stays inside the starting rectangle (which the
      // clipping intersects it with): radius below half the shorter period.
      const bool direct = !coincident && edges > 0 &&
                          direct_cell(offsets.data(), edges, list_size, vertex, radius_squared) &&
                          radius_squared < 0.25 * std::min(size.x, size.y) * std::min(size.x, size.y);
      if (!direct && !coincident) {
        start_cell(scene, origin, cell_polygon);
        for (std::uint32_t e = 0; e < list_size; ++e)
          cell_polygon.clip_by_bisector(offsets[e], topology.entries[list_begin + e].site);
        radius_squared = cell_polygon.max_radius_squared();
      }
      // The certificate. A copy that can cut the cell lies within twice its radius of the site
      // now; it then lay within that plus the moves of both sites of the list's centre when the
      // list was made, hence in the list, if that sum stays below the list's radius (with room
      // for the roundings of the distances, far below the margin). A site not in the list that
      // moved at most `slow` cannot reach the cell when the sum with `slow` stays below it.
      // Sites that moved more than `slow` are not bounded by it: any of them near the site now
      // fails the cell (searched), whether it is in the list or not.
      const double cell_reach = 2.0 * std::sqrt(radius_squared);
      auto room = [&](double others) { return (cell_reach + centre.moved + others) * (1.0 + 1e-9) + 1e-300 < reach; };
      bool certified = !coincident && room(farthest);
      if (!certified && !coincident && fast_grid && room(slow)) {
        const double limit = cell_reach * (1.0 + 1e-9) + 1e-300;
        certified = true;
        fast_grid->for_each_site_near(origin, limit, [&](std::uint32_t k, Point p) {
          if (fast[k] != q && scene_distance(scene, origin, p) <= limit) certified = false;
        });
      }
      if (!certified) {
        failed[q] = 1;
        continue;
      }
      run.out.cells[site - scene.wanted_begin] =
          direct ? measure_vertices(scene, site, std::span<const Point>(vertex, edges), radius_squared, run.weighting)
                 : measure_cell(scene, origin, false, cell_polygon, run.weighting);
    }
  };
  if (run.parallel_inside) {
    parallel_for(count, 512, run_range);
  } else {
    run_range(0, count);
  }
  std::vector<std::uint32_t> searched;
  for (std::size_t q = 0; q < count; ++q)
    if (failed[q]) searched.push_back(topology.order[q]);
  run.stats.kept_cells += scene.wanted_count() - searched.size();
  if (searched.empty()) return 0;
  const CellSearch search(scene);
  auto search_range = [&](std::size_t begin, std::size_t end) {
    ConvexPolygon cell_polygon;
    SearchScratch scratch;
    scratch.candidates.reserve(64);
    for (std::size_t k = begin; k < end; ++k) {
      const std::uint32_t site = searched[k];
      bool complete = build_cell(scene, search, site, scene.sites[site], cell_polygon, scratch);
      run.out.cells[site - scene.wanted_begin] = measure_cell(scene, scene.sites[site], !complete, cell_polygon, run.weighting);
    }
  };
  if (run.parallel_inside) {
    parallel_for(searched.size(), 64, search_range);
  } else {
    search_range(0, searched.size());
  }
  run.stats.searched_cells += searched.size();
  std::size_t lists_failed = 0;
  for (std::size_t q = 0; q < count; ++q) lists_failed += failed[q] && topology.reach[q] >= 0.0;
  run.stats.failed_cells += lists_failed;
  return lists_failed;
}

void compute_scene(SceneRun run) {
  const Scene& scene = run.scene;
  SceneCells& out = run.out;
  assert(scene.wanted_begin <= scene.wanted_end && scene.wanted_end <= scene.sites.size());
  // Every wanted cell is written below (searched, or kept and certified, or searched after
  // failing), so a vector of the right size is not cleared: clearing it here, on the calling
  // thread, cost each call a pass over the cells and moved them to that thread's cache.
  if (out.cells.size() != scene.wanted_count()) out.cells.assign(scene.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  out.zero_density_count = 0;
  if (scene.wanted_count() == 0) return;

  Topology* topology = run.topology;
  if (!topology) {
    search_scene(run, nullptr);
  } else if (!topology->matches(scene)) {
    // A new scene: searched; its positions are the reference for the next call's moves.
    topology->reset(scene);
    search_scene(run, nullptr);
    topology->reference = scene.sites;
    topology->has_reference = true;
  } else if (topology->has_lists) {
    const std::size_t failed = kept_scene(run, *topology);
    if (failed * Topology::kFailShare > scene.wanted_count()) {
      // Stale lists: the next call searches, and makes new ones if the sites move little.
      topology->drop_lists();
      topology->reference = scene.sites;
    }
  } else {
    std::vector<Moved> now;
    const double farthest = displacements(scene, topology->reference, topology->order, now);
    const double spacing = std::sqrt(scene.domain.area() / static_cast<double>(scene.sites.size()));
    search_scene(run, farthest < Topology::kListMove * spacing ? topology : nullptr);
    if (!topology->has_lists) topology->reference = scene.sites;
  }
  for (const Cell& c : out.cells) {
    out.coincident_count += c.status == CellStatus::coincident;
    out.zero_density_count += c.status == CellStatus::zero_density;
  }
}

}  // namespace

Point scene_point(const Scene& scene, Point p) {
  if (scene.periodic()) return wrap_point(p, scene.domain);
  auto inside = [](double x, double size) { return std::clamp(x, 0.0, std::nextafter(size, 0.0)); };
  return {inside(p.x, scene.domain.size.x), inside(p.y, scene.domain.size.y)};
}

Scene make_scene(std::vector<Point> sites, Domain domain) {
  Scene scene;
  scene.domain = domain;
  scene.wanted_end = sites.size();
  scene.sites = std::move(sites);
  return scene;
}

ExactEngineOptions default_exact_engine_options() {
  ExactEngineOptions options;
  const char* keep = std::getenv("BLUETILE_EXACT_KEEP_TOPOLOGY");
  if (keep && std::strcmp(keep, "1") == 0) options.keep_topology = true;
  return options;
}

ExactEngine::ExactEngine() : ExactEngine(default_exact_engine_options()) {}
ExactEngine::ExactEngine(ExactEngineOptions options) : options_(options) {}
ExactEngine::~ExactEngine() = default;

void ExactEngine::forget_topology() { topology_.clear(); }

const ExactEngine::DensityEntry& ExactEngine::density_entry(const std::shared_ptr<const DensityGrid>& density) {
  const std::uint64_t texel_hash = hash_texels(*density);
  for (const auto& e : density_cache_)
    if (e->density == density && e->texel_hash == texel_hash) return *e;
  // Maps kept: a batch of scenes rarely holds more than a few.
  constexpr std::size_t kDensityTables = 4;
  if (density_cache_.size() >= kDensityTables) density_cache_.erase(density_cache_.begin());
  auto entry = std::make_shared<DensityEntry>();
  entry->density = density;
  entry->texel_hash = texel_hash;
  entry->uniform = is_uniform(*density);
  if (!entry->uniform) entry->prefix = std::make_unique<const DensityPrefix>(*density);
  density_cache_.push_back(entry);
  return *entry;
}

void ExactEngine::compute(std::span<const Scene> scenes, std::span<SceneCells> out) {
  assert(scenes.size() == out.size());
  // The contract, checked once per scene; wrapped copies only of scenes that need them.
  std::vector<Scene> wrapped(scenes.size());
  std::vector<const Scene*> checked(scenes.size());
  std::vector<Weighting> weighting(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    checked[i] = &validated_scene(scenes[i], wrapped[i]);
    if (!checked[i]->density) continue;
    const DensityEntry& entry = density_entry(checked[i]->density);
    if (entry.uniform) {
      weighting[i].constant = entry.density->texels.front();
    } else {
      weighting[i].prefix = entry.prefix.get();
    }
  }
  // Small scenes run one per thread when there are enough of them to keep every thread busy;
  // otherwise (one scene, or large ones) each scene is split across the threads itself.
  constexpr std::size_t kSmallScene = 4096;
  std::vector<std::size_t> small;
  for (std::size_t i = 0; i < scenes.size(); ++i)
    if (checked[i]->sites.size() <= kSmallScene) small.push_back(i);
  const bool across_scenes = small.size() >= 2 * thread_count();
  if (!across_scenes) small.clear();
  // The kept topology, one state per place in the batch, for scenes large enough to profit.
  stats_ = KeptTopologyStats{};
  if (options_.keep_topology) {
    if (topology_.size() > scenes.size()) topology_.resize(scenes.size());
    while (topology_.size() < scenes.size()) topology_.push_back(nullptr);
  } else {
    topology_.clear();
  }
  std::vector<KeptTopologyStats> scene_stats(scenes.size());
  auto topology = [&](std::size_t i) -> Topology* {
    if (!options_.keep_topology || checked[i]->sites.size() < Topology::kMinSites) {
      if (i < topology_.size()) topology_[i].reset();
      return nullptr;
    }
    if (!topology_[i]) topology_[i] = std::make_unique<Topology>();
    return topology_[i].get();
  };
  std::vector<Topology*> states(scenes.size());
  for (std::size_t i = 0; i < scenes.size(); ++i) states[i] = topology(i);
  for (std::size_t i = 0, k = 0; i < scenes.size(); ++i) {
    if (k < small.size() && small[k] == i) {
      ++k;
    } else {
      compute_scene({*checked[i], weighting[i], out[i], true, states[i], scene_stats[i]});
    }
  }
  parallel_for(small.size(), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) {
      const std::size_t i = small[k];
      compute_scene({*checked[i], weighting[i], out[i], false, states[i], scene_stats[i]});
    }
  });
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    stats_.kept_cells += scene_stats[i].kept_cells;
    stats_.searched_cells += scene_stats[i].searched_cells;
    stats_.failed_cells += scene_stats[i].failed_cells;
    if (states[i]) {
      stats_.list_entries += states[i]->entries.size();
      stats_.bytes += states[i]->bytes();
    }
  }
}

std::vector<Point> exact_cell_polygon(const Scene& given, std::size_t site) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  if (site >= scene.sites.size()) throw Error("exact_cell_polygon: no site " + std::to_string(site));
  const CellSearch search(scene);
  ConvexPolygon cell_polygon;
  SearchScratch scratch;
  if (!build_cell(scene, search, static_cast<std::uint32_t>(site), scene.sites[site], cell_polygon, scratch)) return {};
  std::vector<Point> polygon;
  for (const PolygonVertex& v : cell_polygon.vertices()) polygon.push_back(v.p);
  return polygon;
}

std::vector<std::vector<Point>> exact_cell_polygons(const Scene& given) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  const CellSearch search(scene);
  std::vector<std::vector<Point>> polygons(scene.sites.size());
  parallel_for(polygons.size(), 256, [&](std::size_t begin, std::size_t end) {
    ConvexPolygon cell_polygon;
    SearchScratch scratch;
    for (std::size_t site = begin; site < end; ++site) {
      if (!build_cell(scene, search, static_cast<std::uint32_t>(site), scene.sites[site], cell_polygon, scratch)) continue;
      for (const PolygonVertex& v : cell_polygon.vertices()) polygons[site].push_back(v.p);
    }
  });
  return polygons;
}

std::vector<std::size_t> exact_cell_neighbours(const Scene& given, std::size_t site) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  if (site >= scene.sites.size()) throw Error("exact_cell_neighbours: no site " + std::to_string(site));
  const CellSearch search(scene);
  ConvexPolygon cell_polygon;
  SearchScratch scratch;
  std::vector<std::size_t> neighbours;
  if (!build_cell(scene, search, static_cast<std::uint32_t>(site), scene.sites[site], cell_polygon, scratch)) return neighbours;
  const auto polygon = cell_polygon.vertices();
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const PolygonVertex& v = polygon[i];
    const PolygonVertex& w = polygon[(i + 1) % polygon.size()];
    if (v.p == w.p) continue;  // degenerate edge left by a tie
    if (v.edge_label == kOwnCopy && !scene.periodic()) continue;  // the domain's border
    neighbours.push_back(v.edge_label == kOwnCopy ? site : v.edge_label);
  }
  std::sort(neighbours.begin(), neighbours.end());
  neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
  return neighbours;
}

}  // namespace bluetile
