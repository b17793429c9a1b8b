#include "bluetile/relax/lloyd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/field_checks.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {

void check_weight_exponent(double exponent, const char* name) {
  if (!(exponent >= 0.0 && exponent <= kMaxWeightExponent))
    throw Error(std::string(name) + ": expected 0 to " + exact_text(kMaxWeightExponent) + ", got " + exact_text(exponent));
}

DensityGrid weight_for_point_density(const DensityGrid& target, double exponent) {
  check_weight_exponent(exponent);
  check_density_grid(target);  // a negative texel came back squared, a positive weight
  DensityGrid weight = target;
  if (exponent == 1.0) return weight;
  for (float& t : weight.texels) t = exponent == 2.0 ? t * t : static_cast<float>(std::pow(static_cast<double>(t), exponent));
  return weight;
}

LloydIteration move_to_centroids(std::span<Scene> scenes, std::span<const SceneCells> cells) {
  LloydIteration log;
  std::size_t moving = 0;
  double displacement_sum = 0.0;
  // A scene's sites in chunks of a fixed size (on all threads for a large scene), each chunk's
  // sums added in chunk order: the same bits whatever the thread count. Ten chunks at 10^4 sites,
  // where a Lloyd step takes a third of a millisecond: each thread moves and sums whole chunks of
  // its own, and no sums are left to the calling thread (chunks of 4096 left it 6 us of them a
  // step: docs/BENCHMARKS.md, "Two threads at 10^4: smaller move chunks and grid order from 8192
  // sites").
  constexpr std::size_t kChunk = 1024;
  // Up to this many chunks the sums run on the calling thread, the moves themselves on all
  // threads in parts of kCallerPart sites: three chunks split 2:1 between two threads would
  // leave one thread idle a third of the move ("Fewer passes, the move on one thread"), and the
  // sums of a few chunks side by side are short ("Two threads after the SIMD lanes").
  constexpr std::size_t kCallerChunks = 4;
  constexpr std::size_t kCallerPart = 256;
  // One site's move: its distance moved and its cell's energy.
  struct Moved {
    double displacement, energy;
  };
  struct Sums {
    double energy = 0.0, displacement = 0.0, largest = 0.0;
    void add(Moved m) {
      energy += m.energy;
      largest = std::max(largest, m.displacement);
      displacement += m.displacement;
    }
  };
  // Checked before any site moves: a shorter `cells` or a scene with fewer cells than wanted sites
  // was read (and its sites written) past the end.
  if (cells.size() != scenes.size())
    throw Error("move_to_centroids: " + counted(static_cast<long long>(scenes.size()), "scene") + " but cells for " +
                std::to_string(cells.size()));
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const Scene& scene = scenes[k];
    if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size())
      throw Error("move_to_centroids: scene " + std::to_string(k) + ": wanted sites [" + std::to_string(scene.wanted_begin) +
                  ", " + std::to_string(scene.wanted_end) + ") do not lie inside its " + std::to_string(scene.sites.size()) +
                  " sites");
    if (cells[k].cells.size() != scene.wanted_count())
      throw Error("move_to_centroids: scene " + std::to_string(k) + " has " +
                  counted(static_cast<long long>(scene.wanted_count()), "wanted site") + " but " +
                  counted(static_cast<long long>(cells[k].cells.size()), "cell"));
  }
  std::vector<Sums> sums;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    Scene& scene = scenes[k];
    moving += scene.wanted_count();
    log.coincident += cells[k].coincident_count;
    log.fallbacks += cells[k].fallback_count;
    log.zero_density += cells[k].zero_density_count;
    const std::size_t count = scene.wanted_count(), chunks = (count + kChunk - 1) / kChunk;
    sums.assign(chunks, Sums{});
    auto step = [&](std::size_t i) {
      const Cell& cell = cells[k].cells[i];
      Point& site = scene.sites[scene.wanted_begin + i];
      const Point d = lloyd_displacement(scene, site, cell);
      site = cell.centroid;
      return Moved{std::sqrt(d.x * d.x + d.y * d.y), cell.second_moment};
    };
    auto move = [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c)
        for (std::size_t i = c * kChunk; i < std::min(count, (c + 1) * kChunk); ++i) sums[c].add(step(i));
    };
    if (chunks <= 1) {
      // One chunk: the sums run on from the scenes before, as they always did.
      sums.assign(1, Sums{log.energy, displacement_sum, log.max_displacement});
      move(0, chunks);
      log.energy = sums[0].energy;
      displacement_sum = sums[0].displacement;
      log.max_displacement = sums[0].largest;
      continue;
    }
    if (chunks <= kCallerChunks && thread_count() > 1) {
      // On all threads in even parts, site order, each site's displacement and energy kept; then
      // the sums on the calling thread, in the same order as the one-thread path.
      thread_local std::vector<Moved> buffer;  // keeps its capacity: no allocation per call
      buffer.resize(count);
      Moved* const moved = buffer.data();  // the calling thread's buffer, written on every thread
      parallel_for((count + kCallerPart - 1) / kCallerPart, 1, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin * kCallerPart; i < std::min(count, end * kCallerPart); ++i) moved[i] = step(i);
      });
      // The chunks side by side, each in its own order: their chains of additions overlap (one
      // chunk after the other, the adds' latency bounded the pass: 11 us at 10^4 sites, now 6).
      // A fixed number of them (the empty ones add nothing), so the sums stay in registers.
      Sums side[kCallerChunks] = {};
      for (std::size_t j = 0; j < kChunk; ++j) {
        for (std::size_t c = 0; c < kCallerChunks; ++c) {
          const std::size_t i = c * kChunk + j;
          if (i >= count) break;
          side[c].add(moved[i]);
        }
      }
      std::copy(side, side + chunks, sums.begin());
    } else if (chunks <= kCallerChunks) {
      move(0, chunks);
    } else {
      parallel_for(chunks, 1, move);
    }
    for (const Sums& c : sums) {
      log.energy += c.energy;
      log.max_displacement = std::max(log.max_displacement, c.largest);
      displacement_sum += c.displacement;
    }
  }
  log.mean_displacement = moving ? displacement_sum / static_cast<double>(moving) : 0.0;
  return log;
}

std::vector<std::uint32_t> grid_row_order(std::span<const Point> sites, const Domain& domain) {
  if (sites.size() > std::numeric_limits<std::uint32_t>::max())
    throw Error("grid order: " + std::to_string(sites.size()) + " sites, more than 2^32 - 1");
  // A counting sort by bucket: stable, so a bucket keeps its sites in index order.
  const double side = std::max(1.0, std::ceil(std::sqrt(static_cast<double>(sites.size()))));
  const std::size_t columns = static_cast<std::size_t>(side);
  const double sx = side / domain.size.x, sy = side / domain.size.y;
  // The engine refuses sites outside the domain or not finite; until it has seen them, such a
  // site goes to the nearest bucket (NaN to the first).
  auto column = [&](double t) {
    return t >= 1.0 ? static_cast<std::size_t>(std::min(t, side - 1.0)) : std::size_t{0};
  };
  auto bucket_of = [&](Point p) { return column(p.y * sy) * columns + column(p.x * sx); };
  std::vector<std::uint32_t> starts(columns * columns + 1, 0);
  for (Point p : sites) ++starts[bucket_of(p) + 1];
  for (std::size_t b = 1; b < starts.size(); ++b) starts[b] += starts[b - 1];
  std::vector<std::uint32_t> order(sites.size());
  for (std::size_t i = 0; i < sites.size(); ++i) order[starts[bucket_of(sites[i])]++] = static_cast<std::uint32_t>(i);
  return order;
}

namespace {

// The wanted sites of the large scenes put in grid_row_order for a run, and back in the caller's
// order when the run ends, however it ends (an interrupt throws).
class GridOrders {
 public:
  explicit GridOrders(std::vector<Scene>& scenes) : scenes_(scenes), orders_(scenes.size()) {
    // Everything that allocates first: a throw leaves every scene as it was.
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      const Scene& scene = scenes[k];
      // A bad range is the engine's to report; the scene is left as it is.
      if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size() ||
          scene.wanted_count() < kGridOrderSites)
        continue;
      orders_[k] = grid_row_order(wanted(k), scene.domain);
      spare_.resize(std::max(spare_.size(), orders_[k].size()));
    }
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      if (orders_[k].empty()) continue;
      const std::span<Point> sites = wanted(k);
      std::copy(sites.begin(), sites.end(), spare_.begin());
      for (std::size_t i = 0; i < sites.size(); ++i) sites[i] = spare_[orders_[k][i]];
    }
  }
  // Allocates nothing (it may run while an exception unwinds).
  ~GridOrders() {
    for (std::size_t k = 0; k < orders_.size(); ++k) {
      if (orders_[k].empty()) continue;
      const std::span<Point> sites = wanted(k);
      std::copy(sites.begin(), sites.end(), spare_.begin());
      for (std::size_t i = 0; i < sites.size(); ++i) sites[orders_[k][i]] = spare_[i];
    }
  }
  GridOrders(const GridOrders&) = delete;
  GridOrders& operator=(const GridOrders&) = delete;

 private:
  std::span<Point> wanted(std::size_t k) const {
    Scene& scene = scenes_[k];
    return {scene.sites.data() + scene.wanted_begin, scene.wanted_count()};
  }

  std::vector<Scene>& scenes_;
  std::vector<std::vector<std::uint32_t>> orders_;  // per scene; empty: the caller's order kept
  std::vector<Point> spare_;                         // as many sites as the largest ordered scene
};

}  // namespace

LloydResult relax_lloyd(CentroidEngine& engine, std::vector<Scene>& scenes, const LloydOptions& options) {
  check_whole_field("iterations", options.iterations, 0, std::numeric_limits<int>::max());
  check_real_field("tolerance", options.tolerance, 0.0, std::numeric_limits<double>::infinity());
  LloydResult result;
  if (scenes.empty()) return result;  // nothing to relax: no iteration runs (it reported 80)
  std::vector<SceneCells> cells(scenes.size());
  // The scenes' own requests, given back however the run ends (an interrupt throws).
  struct Requests {
    std::vector<Scene>& scenes;
    std::vector<char> wanted;
    ~Requests() {
      for (std::size_t k = 0; k < std::min(scenes.size(), wanted.size()); ++k) scenes[k].second_moments = wanted[k];
    }
  } requests{scenes, std::vector<char>(scenes.size())};
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    requests.wanted[k] = scenes[k].second_moments;
    scenes[k].second_moments = requests.wanted[k] && options.energy;
  }
  const GridOrders grid_orders(scenes);
  for (int it = 1; it <= options.iterations; ++it) {
    engine.compute(scenes, cells);
    LloydIteration log = move_to_centroids(scenes, cells);
    log.iteration = it;
    if (!options.energy) log.energy = 0.0;
    result.last = log;
    result.iterations = it;
    if (options.keep_history) result.history.push_back(log);
    if (options.on_iteration) options.on_iteration(log);
    if (options.tolerance > 0.0 && log.max_displacement < options.tolerance) {
      result.converged = true;
      break;
    }
  }
  return result;
}

}  // namespace bluetile
