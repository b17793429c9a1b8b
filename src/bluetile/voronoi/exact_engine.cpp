// Exact periodic Voronoi cells by half-plane clipping (see exact_engine.h for the method).
#include "bluetile/voronoi/exact_engine.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <limits>
#include <optional>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/density_prefix.h"
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

// Computes the cell of `site` into `cell_polygon`. Returns false when the site coincides with a
// site of lower index (which owns the cell).
bool build_cell(const Scene& scene, const CellSearch& search, std::uint32_t site, ConvexPolygon& cell_polygon,
                SearchScratch& scratch) {
  const Point origin = scene.sites[site];
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
    const double gx = step.dx > 0   ? static_cast<double>(step.dx) * cell.x - local.x
                      : step.dx < 0 ? local.x - static_cast<double>(step.dx + 1) * cell.x
                                    : 0.0;
    const double gy = step.dy > 0   ? static_cast<double>(step.dy) * cell.y - local.y
                      : step.dy < 0 ? local.y - static_cast<double>(step.dy + 1) * cell.y
                                    : 0.0;
    if (gx * gx + gy * gy >= reach_squared) continue;
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

Cell measure_cell(const Scene& scene, std::uint32_t site, bool coincident, const ConvexPolygon& cell_polygon,
                  const Weighting& weighting) {
  Cell cell;
  const Point origin = scene.sites[site];
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
  Point offset = moments.centroid();
  if (weighting.prefix) {
    thread_local std::vector<Point> polygon;
    polygon.clear();
    for (const PolygonVertex& v : cell_polygon.vertices()) polygon.push_back(v.p);
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

void compute_scene(const Scene& scene, const Weighting& weighting, SceneCells& out, bool parallel_inside) {
  assert(scene.wanted_begin <= scene.wanted_end && scene.wanted_end <= scene.sites.size());
  out.cells.assign(scene.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  out.zero_density_count = 0;
  if (scene.wanted_count() == 0) return;
  const CellSearch search(scene);
  const SiteGrid& grid = search.grid;

  auto run_buckets = [&](std::size_t begin, std::size_t end) {
    ConvexPolygon cell_polygon;
    SearchScratch scratch;
    scratch.candidates.reserve(64);
    for (std::size_t b = begin; b < end; ++b) {
      for (std::uint32_t site : grid.sites_in_bucket(b)) {
        if (site < scene.wanted_begin || site >= scene.wanted_end) continue;
        bool complete = build_cell(scene, search, site, cell_polygon, scratch);
        out.cells[site - scene.wanted_begin] = measure_cell(scene, site, !complete, cell_polygon, weighting);
      }
    }
  };
  if (parallel_inside) {
    parallel_for(grid.bucket_count(), 256, run_buckets);
  } else {
    run_buckets(0, grid.bucket_count());
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

ExactEngine::ExactEngine() = default;
ExactEngine::~ExactEngine() = default;

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
  for (std::size_t i = 0, k = 0; i < scenes.size(); ++i) {
    if (k < small.size() && small[k] == i) {
      ++k;
    } else {
      compute_scene(*checked[i], weighting[i], out[i], true);
    }
  }
  parallel_for(small.size(), 4, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin; k < end; ++k) compute_scene(*checked[small[k]], weighting[small[k]], out[small[k]], false);
  });
}

std::vector<Point> exact_cell_polygon(const Scene& given, std::size_t site) {
  Scene wrapped;
  const Scene& scene = validated_scene(given, wrapped);
  if (site >= scene.sites.size()) throw Error("exact_cell_polygon: no site " + std::to_string(site));
  const CellSearch search(scene);
  ConvexPolygon cell_polygon;
  SearchScratch scratch;
  if (!build_cell(scene, search, static_cast<std::uint32_t>(site), cell_polygon, scratch)) return {};
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
      if (!build_cell(scene, search, static_cast<std::uint32_t>(site), cell_polygon, scratch)) continue;
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
  if (!build_cell(scene, search, static_cast<std::uint32_t>(site), cell_polygon, scratch)) return neighbours;
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
