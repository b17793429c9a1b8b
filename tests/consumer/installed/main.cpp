// A program using every component: the raster engine must agree with the exact one, and an
// image must be written, which needs the installed image plugin to be found at run time.
#include <cmath>
#include <filesystem>

#include <bluetile/bluetile.h>  // every component: the umbrella brings the image and raster headers

#include "../relax_check.h"

int main(int argc, char** argv) {
  check(argc == 2, "usage: consumer IMAGE.png");
  bluetile::Scene scene = relaxed_scene();
  bluetile::ExactEngine exact;
  bluetile::RasterEngine raster;  // area coverage: exact to rounding (docs/RASTER.md)
  bluetile::SceneCells a = exact.compute(scene), b = raster.compute(scene);
  double worst = 0.0;
  for (std::size_t i = 0; i < a.cells.size(); ++i)
    worst = std::max(worst, bluetile::torus_distance(a.cells[i].centroid, b.cells[i].centroid, scene.domain));
  std::printf("consumer: raster centroids within %.2e of exact\n", worst);
  check(worst < 1e-9, "raster centroids agree with the exact engine");

  std::vector<std::uint8_t> pixels(16 * 16, 128);
  bluetile::write_image_file(argv[1], 16, 16, 1, pixels);
  check(std::filesystem::file_size(argv[1]) > 0, "the image was written");
  std::printf("consumer: all components ok\n");
  return 0;
}
