// Linked to bluetile::bluetile after find_package(bluetile COMPONENTS core), then images: writes
// an image (the path is its argument), which needs the images component the second call loaded.
#include <filesystem>

#include <bluetile/bluetile.h>

#include "../relax_check.h"

int main(int argc, char** argv) {
  check(argc == 2, "usage: consumer IMAGE.png");
  std::vector<std::uint8_t> pixels(16 * 16, 128);
  bluetile::write_image_file(argv[1], 16, 16, 1, pixels);
  check(std::filesystem::file_size(argv[1]) > 0, "the image was written");
  std::printf("consumer: components ok\n");
  return 0;
}
