#include "bluetile/relax/lloyd.h"

#include <algorithm>
#include <cmath>

namespace bluetile {

DensityGrid weight_for_point_density(const DensityGrid& target, double exponent) {
  DensityGrid weight = target;
  if (exponent == 1.0) return weight;
  for (float& t : weight.texels) t = exponent == 2.0 ? t * t : static_cast<float>(std::pow(static_cast<double>(t), exponent));
  return weight;
}

LloydResult relax_lloyd(CentroidEngine& engine, std::vector<Scene>& scenes, const LloydOptions& options) {
  LloydResult result;
  std::vector<SceneCells> cells(scenes.size());
  std::size_t moving = 0;
  for (const Scene& s : scenes) moving += s.wanted_count();

  for (int it = 1; it <= options.iterations; ++it) {
    engine.compute(scenes, cells);
    LloydIteration log;
    log.iteration = it;
    double displacement_sum = 0.0;
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      Scene& scene = scenes[k];
      log.coincident += cells[k].coincident_count;
      log.fallbacks += cells[k].fallback_count;
      log.zero_density += cells[k].zero_density_count;
      for (std::size_t i = 0; i < scene.wanted_count(); ++i) {
        const Cell& cell = cells[k].cells[i];
        Point& site = scene.sites[scene.wanted_begin + i];
        double moved = scene_distance(scene, site, cell.centroid);
        log.energy += cell.second_moment;
        log.max_displacement = std::max(log.max_displacement, moved);
        displacement_sum += moved;
        site = cell.centroid;
      }
    }
    log.mean_displacement = moving ? displacement_sum / static_cast<double>(moving) : 0.0;
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
