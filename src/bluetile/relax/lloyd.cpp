#include "bluetile/relax/lloyd.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/text.h"

namespace bluetile {

void check_weight_exponent(double exponent, const char* name) {
  if (!(exponent >= 0.0 && exponent <= kMaxWeightExponent))
    throw Error(std::string(name) + ": expected 0 to " + exact_text(kMaxWeightExponent) + ", got " + exact_text(exponent));
}

DensityGrid weight_for_point_density(const DensityGrid& target, double exponent) {
  check_weight_exponent(exponent);
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
  // sums added in chunk order: the same bits whatever the thread count. A few chunks already at
  // 10^4 sites, where a Lloyd step takes about a millisecond.
  constexpr std::size_t kChunk = 4096;
  // Up to this many chunks the move runs on the calling thread: the cells come from every thread
  // (written at their sites' places), so on two threads half of each one's reads were the other
  // core's lines, and three chunks split 2:1; at 10^4 sites the move took 110-125 us on two
  // threads against 78-85 us on the calling thread alone (docs/BENCHMARKS.md, "Fewer passes, the
  // move on one thread").
  constexpr std::size_t kCallerChunks = 4;
  struct Sums {
    double energy = 0.0, displacement = 0.0, largest = 0.0;
  };
  std::vector<Sums> sums;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    Scene& scene = scenes[k];
    moving += scene.wanted_count();
    log.coincident += cells[k].coincident_count;
    log.fallbacks += cells[k].fallback_count;
    log.zero_density += cells[k].zero_density_count;
    const std::size_t count = scene.wanted_count(), chunks = (count + kChunk - 1) / kChunk;
    sums.assign(chunks, Sums{});
    auto move = [&](std::size_t begin, std::size_t end) {
      for (std::size_t c = begin; c < end; ++c) {
        Sums& mine = sums[c];
        for (std::size_t i = c * kChunk; i < std::min(count, (c + 1) * kChunk); ++i) {
          const Cell& cell = cells[k].cells[i];
          Point& site = scene.sites[scene.wanted_begin + i];
          Point d = lloyd_displacement(scene, site, cell);
          double moved = std::sqrt(d.x * d.x + d.y * d.y);
          mine.energy += cell.second_moment;
          mine.largest = std::max(mine.largest, moved);
          mine.displacement += moved;
          site = cell.centroid;
        }
      }
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
    if (chunks <= kCallerChunks) {
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

LloydResult relax_lloyd(CentroidEngine& engine, std::vector<Scene>& scenes, const LloydOptions& options) {
  LloydResult result;
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
