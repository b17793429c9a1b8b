// Option structs filled with designated initializers that leave members out, the way the README
// shows: a strict build must not warn about the members left out (they have default member
// initializers for that).
#include <bluetile/bluetile.h>

#include "../relax_check.h"

int main() {
  bluetile::Scene scene = bluetile::make_scene(bluetile::uniform_random_points(100, /*seed*/ 1));
  bluetile::ExactEngine engine;
  bluetile::LloydResult result = bluetile::relax_lloyd(engine, scene, {.iterations = 5});  // the README's call
  check(result.iterations == 5, "relax_lloyd ran the iterations asked for");
  const bluetile::SvgStyle style{.stroke_width = 2.0};
  check(style.stroke_width == 2.0 && !style.opacity, "SvgStyle's members left out are absent");
  std::printf("consumer: headers ok\n");
  return 0;
}
