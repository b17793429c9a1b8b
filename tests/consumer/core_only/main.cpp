// A program using only bluetile::core: relaxes points, then writes them as a C header (the path
// is its argument) and prints their sum, which run.cmake checks against a C program built from
// that header.
#include <cstdio>
#include <fstream>

#include <bluetile/bluetile.h>  // core alone: the umbrella must compile without Vulkan and images
#if defined(BLUETILE_WITH_IMAGES) || defined(BLUETILE_WITH_RASTER)
#error "bluetile::core alone must not bring the image or raster headers through bluetile/bluetile.h"
#endif

#include "../relax_check.h"

int main(int argc, char** argv) {
  check(argc == 2, "usage: consumer TABLE.h");
  bluetile::Scene scene = relaxed_scene();
  std::vector<bluetile::PointSet> sets{bluetile::PointSet{scene.sites, {}}};
  std::ofstream header(argv[1], std::ios::binary);
  bluetile::write_table(bluetile::TableFormat::header, bluetile::point_sets_table(sets), {}, argv[1],
                        [&](std::string_view bytes) { header.write(bytes.data(), static_cast<std::streamsize>(bytes.size())); });
  header.close();
  check(static_cast<bool>(header), "the header was written");
  float sum = 0.0f;  // summed as the C program sums it: floats, in order
  for (bluetile::Point p : scene.sites) sum += static_cast<float>(p.x) + static_cast<float>(p.y);
  std::printf("consumer: core ok, table sum %.9g\n", static_cast<double>(sum));
  return 0;
}
