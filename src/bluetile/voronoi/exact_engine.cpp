// The exact engine: each wanted cell through the Delaunay triangulation kept between calls
// (kept_delaunay.h) or by the cell search (cell_search.h); see exact_engine.h.
#include "bluetile/voronoi/exact_engine.h"

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "bluetile/core/error.h"
#include "bluetile/core/huge_pages.h"
#include "bluetile/core/parallel.h"
#include "bluetile/voronoi/cell_measure.h"
#include "bluetile/voronoi/cell_search.h"
#include "bluetile/voronoi/density_moments.h"
#include "bluetile/voronoi/density_prefix.h"
#include "bluetile/voronoi/kept_delaunay.h"
#include "bluetile/voronoi/polygon.h"
#include "bluetile/voronoi/scene.h"

namespace bluetile {

struct ExactEngine::DensityEntry {
  std::shared_ptr<const DensityGrid> density;  // held, so that its address names no other grid
  std::uint64_t texel_hash = 0;                // catches a grid changed in place
  bool uniform = false;
  std::unique_ptr<const DensityPrefix> prefix;  // for a varying density
};

namespace {

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

struct SceneRun {
  const Scene& scene;
  const Weighting& weighting;
  SceneCells& out;
  bool parallel_inside;
  KeptDelaunay* kept;  // null: searched
  KeptTopologyStats& stats;
};

void compute_scene(SceneRun run) {
  const Scene& scene = run.scene;
  SceneCells& out = run.out;
  assert(scene.wanted_begin <= scene.wanted_end && scene.wanted_end <= scene.sites.size());
  // Every wanted cell is written below, so a vector of the right size is not cleared: clearing
  // it here, on the calling thread, cost each call a pass over the cells and moved them to that
  // thread's cache.
  // Huge pages when large: the kept triangulation writes each cell at its site's index, in its
  // own (spatial) order of the sites (core/huge_pages.h).
  if (out.cells.size() != scene.wanted_count()) assign_on_huge_pages(out.cells, scene.wanted_count(), Cell{});
  out.coincident_count = 0;
  out.fallback_count = 0;
  out.zero_density_count = 0;
  if (scene.wanted_count() == 0) return;
  if (run.kept) {
    KeptDelaunay::StatusCounts measured;
    if (run.kept->compute(scene, run.weighting, out.cells, run.parallel_inside, run.stats, measured)) {
      // Counted as the cells were measured: a pass over every cell less (at 10^4 sites it ran on
      // the calling thread alone, between two parallel loops).
      out.coincident_count = measured.coincident;
      out.zero_density_count = measured.zero_density;
      return;
    }
  } else {
    search_cells(scene, CellSearch(scene), run.weighting, out.cells, run.parallel_inside);
    run.stats.searched_cells += scene.wanted_count();
  }
  // The statuses counted in chunks (on all threads for a large scene), added in chunk order.
  constexpr std::size_t kCountChunk = 16384;
  const std::size_t chunks = (out.cells.size() + kCountChunk - 1) / kCountChunk;
  std::vector<KeptDelaunay::StatusCounts> counts(chunks);
  auto count = [&](std::size_t begin, std::size_t end) {
    for (std::size_t c = begin; c < end; ++c)
      for (std::size_t i = c * kCountChunk; i < std::min(out.cells.size(), (c + 1) * kCountChunk); ++i) counts[c].add(out.cells[i]);
  };
  if (run.parallel_inside) {
    parallel_for(chunks, 1, count);
  } else {
    count(0, chunks);
  }
  KeptDelaunay::StatusCounts total;
  for (const KeptDelaunay::StatusCounts& c : counts) total += c;
  out.coincident_count = total.coincident;
  out.zero_density_count = total.zero_density;
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
  // Huge pages when large: the kept triangulation reads each site at its index, in its own
  // (spatial) order of the sites.
  scene.sites = on_huge_pages(std::move(sites));
  return scene;
}

ExactEngineOptions default_exact_engine_options() {
  ExactEngineOptions options;
  const char* keep = std::getenv("BLUETILE_EXACT_KEEP_TOPOLOGY");
  if (keep && std::strcmp(keep, "0") == 0) options.keep_topology = false;
  return options;
}

ExactEngine::ExactEngine() : ExactEngine(default_exact_engine_options()) {}
ExactEngine::ExactEngine(ExactEngineOptions options) : options_(options) {}
ExactEngine::~ExactEngine() = default;

void ExactEngine::forget_topology() { kept_.clear(); }

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
  check_batch(name(), scenes.size(), out.size());
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
  // The kept triangulations, one per place in the batch, for the scenes that suit one.
  stats_ = KeptTopologyStats{};
  if (!options_.keep_topology) kept_.clear();
  if (kept_.size() > scenes.size()) kept_.resize(scenes.size());
  std::vector<KeptDelaunay*> states(scenes.size(), nullptr);
  for (std::size_t i = 0; i < scenes.size(); ++i) {
    const bool suits = options_.keep_topology && KeptDelaunay::suits(*checked[i]);
    if (i < kept_.size() && !suits) kept_[i].reset();
    if (!suits) continue;
    if (kept_.size() <= i) kept_.resize(i + 1);
    if (!kept_[i]) kept_[i] = std::make_unique<KeptDelaunay>(options_.simd);
    states[i] = kept_[i].get();
  }
  std::vector<KeptTopologyStats> scene_stats(scenes.size());
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
    stats_.tie_cells += scene_stats[i].tie_cells;
    stats_.flips += scene_stats[i].flips;
    stats_.rebuilds += scene_stats[i].rebuilds;
    stats_.exact_stars += scene_stats[i].exact_stars;
    stats_.repaired_vertices += scene_stats[i].repaired_vertices;
  }
  for (const auto& state : kept_)
    if (state) stats_.bytes += state->bytes();
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
