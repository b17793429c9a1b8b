#include "bluetile/voronoi/scene.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"
#include "bluetile/voronoi/density_moments.h"

namespace bluetile {
namespace {

bool inside(Point p, const Domain& domain) {
  return p.x >= 0.0 && p.x < domain.size.x && p.y >= 0.0 && p.y < domain.size.y;
}

}  // namespace

const Scene& validated_scene(const Scene& scene, Scene& storage) {
  const Point size = scene.domain.size;
  if (!(std::isfinite(size.x) && std::isfinite(size.y) && size.x > 0.0 && size.y > 0.0))
    throw Error("scene: domain " + exact_text(size.x) + " x " + exact_text(size.y) + " is not a finite positive size");
  if (scene.wanted_begin > scene.wanted_end || scene.wanted_end > scene.sites.size())
    throw Error("scene: wanted sites [" + std::to_string(scene.wanted_begin) + ", " + std::to_string(scene.wanted_end) +
                ") do not lie inside its " + std::to_string(scene.sites.size()) + " sites");
  if (scene.sites.size() > kMaxSceneSites)
    throw Error("scene: " + std::to_string(scene.sites.size()) + " sites, more than the " +
                std::to_string(kMaxSceneSites) + " an engine can index");
  check_density(scene);
  // One branch-free pass first (engines check every call, and this vectorizes): NaN and
  // infinities fail the comparisons too. The loop that names a bad site or wraps the ones outside
  // runs only when one is not inside.
  bool all_inside = true;
  for (const Point& p : scene.sites)
    all_inside &= (p.x >= 0.0) & (p.x < size.x) & (p.y >= 0.0) & (p.y < size.y);
  if (all_inside) return scene;
  std::size_t first_outside = scene.sites.size();
  for (std::size_t i = 0; i < scene.sites.size(); ++i) {
    const Point p = scene.sites[i];
    auto site = [&] { return "scene: site " + std::to_string(i) + " (" + exact_text(p.x) + ", " + exact_text(p.y) + ")"; };
    if (!std::isfinite(p.x) || !std::isfinite(p.y)) throw Error(site() + " is not finite");
    if (first_outside == scene.sites.size() && !inside(p, scene.domain)) {
      if (!scene.periodic())
        throw Error(site() + " lies outside the bounded domain " + exact_text(size.x) + " x " + exact_text(size.y));
      first_outside = i;
    }
  }
  if (first_outside == scene.sites.size()) return scene;
  storage = scene;
  for (std::size_t i = first_outside; i < storage.sites.size(); ++i)
    storage.sites[i] = wrap_point(storage.sites[i], storage.domain);
  return storage;
}

}  // namespace bluetile
