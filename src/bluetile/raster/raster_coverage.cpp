// The coverage check (see raster_coverage.h).
#include "bluetile/raster/raster_coverage.h"

#include <algorithm>
#include <bit>
#include <cmath>

namespace bluetile {

double farthest_sample(const gpu::SiteSums& sums) {
  return std::sqrt(static_cast<double>(std::bit_cast<float>(sums.farthest)));
}

bool check_coverage(RasterScene& scene, std::span<const gpu::SiteSums> sums, std::uint32_t uncovered) {
  const std::size_t n = scene.size();
  if (uncovered) {
    for (double& r : scene.radius) r = std::min(scene.radius_cap, 2.0 * r);
    return false;
  }
  // A cone at the cap covers the torus; slack for float positions and edge rasterization.
  const double edge_slack = 1e-3 * std::max(scene.hx, scene.hy);
  auto effective = [&](double r) { return r >= scene.radius_cap ? HUGE_VAL : r * (1.0 - 1e-6) - edge_slack; };
  std::vector<double> farthest(n, 0.0);
  double max_farthest = 0.0, min_radius = HUGE_VAL;
  for (std::size_t i = 0; i < n; ++i) {
    if (scene.coincident[i]) continue;
    farthest[i] = farthest_sample(sums[i]);
    max_farthest = std::max(max_farthest, farthest[i]);
    min_radius = std::min(min_radius, effective(scene.radius[i]));
  }
  scene.need = farthest;
  const bool all_reach = min_radius >= max_farthest;
  const SiteGrid& grid = scene.grid();
  bool ok = true;
  std::vector<double> grown = scene.radius;
  const Domain& domain = scene.scene->domain;
  for (std::size_t s = 0; s < n; ++s) {
    if (scene.coincident[s] || farthest[s] == 0.0) continue;
    const double f = farthest[s];
    grid.for_each_near(scene.sites[s], 2.0 * f, [&](std::uint32_t t) {
      if (scene.coincident[t] || scene.need[t] >= f) return;
      if (torus_distance(scene.sites[s], scene.sites[t], domain) > 2.0 * f) return;
      scene.need[t] = f;
      if (all_reach || effective(scene.radius[t]) >= f) return;
      ok = false;
      grown[t] = std::max(grown[t], std::min(scene.radius_cap, std::max(1.5 * scene.radius[t], 1.25 * f + scene.pixel_diagonal())));
    });
  }
  if (!ok) scene.radius = std::move(grown);
  return ok;
}

}  // namespace bluetile
