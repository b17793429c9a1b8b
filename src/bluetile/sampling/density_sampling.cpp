#include "bluetile/sampling/density_sampling.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/error.h"
#include "bluetile/core/request_limits.h"

namespace bluetile {

std::vector<Point> sample_density(const DensityGrid& density, const Domain& domain, std::size_t count, Rng& rng) {
  if (density.empty()) throw Error("cannot sample an empty density grid");
  check_set_points(count, "density sampling: count");
  // A grid of 0 columns divided by zero below; more texels than its size put points outside the
  // domain; negative texels made the cumulative sum fall, NaN ones made it NaN.
  const bool any_positive = check_density_grid(density);
  check_domain(domain, "density sampling");
  std::vector<double> cumulative(density.texels.size() + 1, 0.0);
  for (std::size_t k = 0; k < density.texels.size(); ++k) cumulative[k + 1] = cumulative[k] + density.texels[k];
  const double total = cumulative.back();
  if (!any_positive) throw Error("cannot sample a density that is zero everywhere");
  // u can round up to the total: it then takes the last texel that has any density.
  std::size_t last = density.texels.size() - 1;
  while (density.texels[last] == 0.0f) --last;
  const Point texel{domain.size.x / density.width, domain.size.y / density.height};
  // A texel's far edge can round to the domain's; keep points inside [0,W) x [0,H).
  const Point inside{std::nextafter(domain.size.x, 0.0), std::nextafter(domain.size.y, 0.0)};
  std::vector<Point> points(count);
  for (Point& p : points) {
    const double u = rng.uniform() * total;
    // The first texel whose cumulative sum passes u: never a texel of density zero.
    auto k = static_cast<std::size_t>(std::upper_bound(cumulative.begin() + 1, cumulative.end(), u) -
                                      (cumulative.begin() + 1));
    k = std::min(k, last);
    const auto i = static_cast<double>(k % static_cast<std::size_t>(density.width));
    const auto j = static_cast<double>(k / static_cast<std::size_t>(density.width));
    p.x = std::min((i + rng.uniform()) * texel.x, inside.x);
    p.y = std::min((j + rng.uniform()) * texel.y, inside.y);
  }
  return points;
}

std::vector<Point> density_random_points(const DensityGrid& density, std::size_t count, std::uint64_t seed,
                                         std::uint64_t set) {
  Rng rng(derive_seed(seed, set));
  return sample_density(density, Domain{}, count, rng);
}

}  // namespace bluetile
