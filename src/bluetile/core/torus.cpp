#include "bluetile/core/torus.h"

#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {

void check_domain(const Domain& domain, std::string_view what) {
  const Point size = domain.size;
  if (!(std::isfinite(size.x) && std::isfinite(size.y) && size.x > 0.0 && size.y > 0.0))
    throw Error(std::string(what) + ": domain " + exact_text(size.x) + " x " + exact_text(size.y) +
                " is not a finite positive size");
}

void check_finite_points(std::span<const Point> points, std::string_view what) {
  for (std::size_t i = 0; i < points.size(); ++i)
    if (!std::isfinite(points[i].x) || !std::isfinite(points[i].y))
      throw Error(std::string(what) + ": point " + std::to_string(i) + " is not finite");
}

}  // namespace bluetile
