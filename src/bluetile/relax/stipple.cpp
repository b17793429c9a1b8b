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
  check_density_grid(map);  // a 0 x 0 grid holding texels gave a domain of NaN x NaN
  const double longer = std::max(map.width, map.height);
  return Domain{{map.width / longer, map.height / longer}};
}

Scene stipple_scene(const DensityGrid& map, const StippleStart& start) {
  if (start.count == 0) throw Error("stipple: the count of dots must be at least 1");
  // std::length_error from the sampler's vector, not an Error naming it.
  if (start.count > kMaxSetPoints)
    throw Error("stipple: count: expected 1 to " + std::to_string(kMaxSetPoints) + ", got " + std::to_string(start.count));
  check_weight_exponent(start.weight_exponent);
  const Domain domain = stipple_domain(map);
  Rng rng(derive_seed(start.seed, 0));
  Scene scene = make_scene(sample_density(map, domain, start.count, rng), domain);
  scene.boundary = start.periodic ? Boundary::periodic : Boundary::bounded;
  scene.density = std::make_shared<DensityGrid>(weight_for_point_density(map, start.weight_exponent));
  return scene;
}

double stipple_dot_radius(const DensityGrid& map, const Domain& domain, std::size_t count) {
  // An empty map was read past its end; a map zero everywhere gave NaN, no dots infinity.
  if (map.empty()) throw Error("stipple: the density map is empty");
  if (!check_density_grid(map)) throw Error("stipple: the density map is zero everywhere");
  check_domain(domain, "stipple");
  if (count == 0) throw Error("stipple: the count of dots must be at least 1");
  const double peak = *std::max_element(map.texels.begin(), map.texels.end());
  return 0.5 * hexagonal_spacing(static_cast<double>(count) * peak / map.mean(), domain.area());
}

}  // namespace bluetile
