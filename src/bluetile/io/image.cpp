#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <memory>


#include "bluetile/core/error.h"
#include "bluetile/io/font.h"

namespace bluetile {

Colour series_colour(std::size_t i) {
  static constexpr Colour palette[] = {
      {0.00f, 0.45f, 0.70f},  // blue
      {0.84f, 0.37f, 0.00f},  // vermilion
      {0.00f, 0.62f, 0.45f},  // bluish green
      {0.80f, 0.47f, 0.65f},  // reddish purple
      {0.90f, 0.62f, 0.00f},  // orange
      {0.34f, 0.71f, 0.91f},  // sky blue
      {0.20f, 0.20f, 0.20f},  // near black
  };
  return palette[i % (sizeof(palette) / sizeof(palette[0]))];
}

Canvas::Canvas(int width, int height, Colour background) : width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > kMaxCanvasSide || height > kMaxCanvasSide)
    throw Error("image size " + std::to_string(width) + "x" + std::to_string(height) + " is out of range");
  pixels_.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * 3);
  for (std::size_t i = 0; i < pixels_.size(); i += 3) {
    pixels_[i] = background.r;
    pixels_[i + 1] = background.g;
    pixels_[i + 2] = background.b;
  }
}

Colour Canvas::pixel(int x, int y) const {
  std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * 3;
  return {pixels_[i], pixels_[i + 1], pixels_[i + 2]};
}

void Canvas::set(int x, int y, Colour c) { blend(x, y, c, 1.0); }

void Canvas::blend(int x, int y, Colour c, double alpha) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_ || !(alpha > 0.0)) return;
  const float a = static_cast<float>(std::min(alpha, 1.0));
  std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * 3;
  pixels_[i] += a * (c.r - pixels_[i]);
  pixels_[i + 1] += a * (c.g - pixels_[i + 1]);
  pixels_[i + 2] += a * (c.b - pixels_[i + 2]);
}

void Canvas::fill_rect(double x0, double y0, double x1, double y1, Colour c) {
  int ix0 = std::max(0, static_cast<int>(std::lround(std::min(x0, x1))));
  int ix1 = std::min(width_, static_cast<int>(std::lround(std::max(x0, x1))));
  int iy0 = std::max(0, static_cast<int>(std::lround(std::min(y0, y1))));
  int iy1 = std::min(height_, static_cast<int>(std::lround(std::max(y0, y1))));
  for (int y = iy0; y < iy1; ++y)
    for (int x = ix0; x < ix1; ++x) set(x, y, c);
}

void Canvas::line(Point a, Point b, Colour c, double width) {
  // Coverage from the distance of the pixel centre to the segment: a one-pixel ramp at the edge.
  const double h = 0.5 * width;
  int x0 = static_cast<int>(std::floor(std::min(a.x, b.x) - h - 1.0));
  int x1 = static_cast<int>(std::ceil(std::max(a.x, b.x) + h + 1.0));
  int y0 = static_cast<int>(std::floor(std::min(a.y, b.y) - h - 1.0));
  int y1 = static_cast<int>(std::ceil(std::max(a.y, b.y) + h + 1.0));
  x0 = std::max(x0, 0), y0 = std::max(y0, 0);
  x1 = std::min(x1, width_ - 1), y1 = std::min(y1, height_ - 1);
  const Point d = b - a;
  const double length2 = d.x * d.x + d.y * d.y;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      Point p{x + 0.5, y + 0.5};
      double t = length2 > 0.0 ? std::clamp(((p.x - a.x) * d.x + (p.y - a.y) * d.y) / length2, 0.0, 1.0) : 0.0;
      Point q = a + t * d - p;
      double distance = std::sqrt(q.x * q.x + q.y * q.y);
      blend(x, y, c, std::clamp(h + 0.5 - distance, 0.0, 1.0));
    }
  }
}

void Canvas::dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) {
  Point d = b - a;
  double length = std::sqrt(d.x * d.x + d.y * d.y);
  if (length <= 0.0) return;
  Point u = d / length;
  for (double s = 0.0; s < length; s += dash + gap) line(a + s * u, a + std::min(s + dash, length) * u, c, width);
}

void Canvas::disc(Point centre, double radius, Colour c) {
  int x0 = std::max(0, static_cast<int>(std::floor(centre.x - radius - 1.0)));
  int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(centre.x + radius + 1.0)));
  int y0 = std::max(0, static_cast<int>(std::floor(centre.y - radius - 1.0)));
  int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(centre.y + radius + 1.0)));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      double dx = x + 0.5 - centre.x, dy = y + 0.5 - centre.y;
      blend(x, y, c, std::clamp(radius + 0.5 - std::sqrt(dx * dx + dy * dy), 0.0, 1.0));
    }
  }
}

void Canvas::cross(Point centre, double half_size, Colour c, double width) {
  line(centre + Point{-half_size, -half_size}, centre + Point{half_size, half_size}, c, width);
  line(centre + Point{-half_size, half_size}, centre + Point{half_size, -half_size}, c, width);
}

void Canvas::text(double x, double y, std::string_view s, Colour c, int scale, Align h, Align v, bool vertical) {
  const int w = text_width(s, scale), ht = text_height(scale);
  // Size of the box on the canvas (turned when vertical).
  const int box_w = vertical ? ht : w, box_h = vertical ? w : ht;
  auto offset = [](Align a, int size) { return a == Align::start ? 0.0 : a == Align::centre ? 0.5 * size : size; };
  const int left = static_cast<int>(std::lround(x - offset(h, box_w)));
  const int top = static_cast<int>(std::lround(y - offset(v, box_h)));
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto& rows = glyph(s[k]);
    for (int row = 0; row < glyph_height; ++row) {
      for (int column = 0; column < glyph_width; ++column) {
        if (!(rows[static_cast<std::size_t>(row)] & (0x10 >> column))) continue;
        // Position in the unturned text box, in font pixels.
        int u = static_cast<int>(k) * glyph_advance + column, t = row;
        for (int sy = 0; sy < scale; ++sy) {
          for (int sx = 0; sx < scale; ++sx) {
            int px = u * scale + sx, py = t * scale + sy;
            if (vertical) set(left + py, top + (w - 1 - px), c);
            else set(left + px, top + py, c);
          }
        }
      }
    }
  }
}

void Canvas::paste(const Canvas& other, int x, int y) {
  for (int j = 0; j < other.height(); ++j)
    for (int i = 0; i < other.width(); ++i) set(x + i, y + j, other.pixel(i, j));
}

void write_image(OutputFile& out, const Canvas& canvas) {
  // Grey images (spectra) are written with one channel: a third of the size.
  const std::vector<float>& rgb = canvas.rgb();
  bool grey = true;
  for (std::size_t i = 0; i < rgb.size() && grey; i += 3) grey = rgb[i] == rgb[i + 1] && rgb[i] == rgb[i + 2];
  const int channels = grey ? 1 : 3;
  std::vector<std::uint8_t> bytes(rgb.size() / 3 * static_cast<std::size_t>(channels));
  for (std::size_t i = 0; i < bytes.size(); ++i) {
    const float v = rgb[grey ? 3 * i : i];
    bytes[i] = static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  }
  write_image_file(out, canvas.width(), canvas.height(), channels, bytes);
}

void write_image(const std::string& path, const Canvas& canvas) {
  OutputSet outputs;
  write_image(outputs.add(path), canvas);
  outputs.publish();
}

Canvas read_image(const std::string& path) {
  ImageFile image = read_image_file(path);
  const std::size_t channels = static_cast<std::size_t>(image.channels);
  Canvas canvas(image.width, image.height);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::size_t i = (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) + static_cast<std::size_t>(x)) * channels;
      const auto& v = image.values;
      canvas.set(x, y, Colour{v[i], v[i + (channels > 1 ? 1 : 0)], v[i + (channels > 2 ? 2 : 0)]});
    }
  }
  return canvas;
}

}  // namespace bluetile
