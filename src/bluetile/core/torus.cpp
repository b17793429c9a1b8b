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

}  // namespace bluetile
