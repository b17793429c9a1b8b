// The ID buffer as a picture (the paper's Figure 1): one colour per cell, sites as dots.
#include <cmath>

#include "bluetile/core/error.h"
#include "bluetile/io/image_file.h"
#include "bluetile/raster/raster_engine.h"

namespace bluetile {
namespace {

// A pale colour per site index from an integer hash, so neighbouring cells differ.
void cell_colour(std::int32_t id, unsigned char rgb[3]) {
  if (id < 0) {
    rgb[0] = rgb[1] = rgb[2] = 0;
    return;
  }
  std::uint32_t h = static_cast<std::uint32_t>(id) * 2654435761u;
  h ^= h >> 15;
  h *= 2246822519u;
  h ^= h >> 13;
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<unsigned char>(110 + ((h >> (8 * c)) & 0xff) * 145 / 255);
}

}  // namespace

void write_id_image(const IdImage& image, const Scene& scene, OutputFile& out) {
  if (image.width <= 0 || image.height <= 0) throw Error("no ID image to write");
  const int w = image.width, h = image.height;
  std::vector<std::uint8_t> pixels(static_cast<std::size_t>(w) * h * 3);
  // Row 0 of the file is the top of the picture: y grows upwards in the domain.
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      cell_colour(image.ids[static_cast<std::size_t>(j) * w + i], &pixels[(static_cast<std::size_t>(h - 1 - j) * w + i) * 3]);
  const double radius = std::max(1.0, 0.004 * std::max(w, h));
  for (const Point& site : scene.sites) {
    double cx = site.x / scene.domain.size.x * w, cy = site.y / scene.domain.size.y * h;
    for (int dy = -static_cast<int>(radius) - 1; dy <= static_cast<int>(radius) + 1; ++dy)
      for (int dx = -static_cast<int>(radius) - 1; dx <= static_cast<int>(radius) + 1; ++dx) {
        int i = static_cast<int>(std::floor(cx)) + dx, j = static_cast<int>(std::floor(cy)) + dy;
        double ddx = i + 0.5 - cx, ddy = j + 0.5 - cy;
        if (ddx * ddx + ddy * ddy > radius * radius) continue;
        i = (i % w + w) % w;
        j = (j % h + h) % h;
        std::uint8_t* p = &pixels[(static_cast<std::size_t>(h - 1 - j) * w + i) * 3];
        p[0] = p[1] = p[2] = 0;
      }
  }
  write_image_file(out, w, h, 3, pixels);
}

void write_id_image(const IdImage& image, const Scene& scene, const std::string& path) {
  OutputSet outputs;
  write_id_image(image, scene, outputs.add(path));
  outputs.publish();
}

}  // namespace bluetile
