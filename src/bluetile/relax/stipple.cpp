#include "bluetile/relax/stipple.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/density_sampling.h"

namespace bluetile {

Domain stipple_domain(const DensityGrid& map) {
  if (map.empty()) throw Error("stipple: the density map is empty");
  const double longer = std::max(map.width, map.height);
  return Domain{{map.width / longer, map.height / longer}};
}

Scene stipple_scene(const DensityGrid& map, const StippleStart& start) {
  if (start.count == 0) throw Error("stipple: the count of dots must be at least 1");
  check_weight_exponent(start.weight_exponent);
  const Domain domain = stipple_domain(map);
  Rng rng(derive_seed(start.seed, 0));
  Scene scene = make_scene(sample_density(map, domain, start.count, rng), domain);
  scene.boundary = start.periodic ? Boundary::periodic : Boundary::bounded;
  scene.density = std::make_shared<DensityGrid>(weight_for_point_density(map, start.weight_exponent));
  return scene;
}

double stipple_dot_radius(const DensityGrid& map, const Domain& domain, std::size_t count) {
  const double peak = *std::max_element(map.texels.begin(), map.texels.end());
  return 0.5 * hexagonal_spacing(static_cast<double>(count) * peak / map.mean(), domain.area());
}

}  // namespace bluetile
