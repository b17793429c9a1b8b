#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"
#include "bluetile/io/font.h"

namespace bluetile {
namespace {

// A coordinate brought into [-2, size + 2] before its conversion to int, where a huge or NaN one
// converted to nothing defined; NaN goes to -2, off the canvas (its shape draws nothing there).
double on_axis(double v, int size) { return v >= -2.0 ? std::min(v, size + 2.0) : -2.0; }

}  // namespace

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
  if (x < 0 || y < 0 || x >= width_ || y >= height_)
    throw Error("pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") lies outside the " +
                std::to_string(width_) + " x " + std::to_string(height_) + " canvas");
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
  if (std::isnan(x0) || std::isnan(y0) || std::isnan(x1) || std::isnan(y1)) return;
  int ix0 = std::max(0, static_cast<int>(std::lround(on_axis(std::min(x0, x1), width_))));
  int ix1 = std::min(width_, static_cast<int>(std::lround(on_axis(std::max(x0, x1), width_))));
  int iy0 = std::max(0, static_cast<int>(std::lround(on_axis(std::min(y0, y1), height_))));
  int iy1 = std::min(height_, static_cast<int>(std::lround(on_axis(std::max(y0, y1), height_))));
  for (int y = iy0; y < iy1; ++y)
    for (int x = ix0; x < ix1; ++x) set(x, y, c);
}

void Canvas::line(Point a, Point b, Colour c, double width) {
  // Coverage from the distance of the pixel centre to the segment: a one-pixel ramp at the edge.
  const double h = 0.5 * width;
  if (std::isnan(a.x) || std::isnan(a.y) || std::isnan(b.x) || std::isnan(b.y) || std::isnan(h)) return;
  int x0 = static_cast<int>(std::floor(on_axis(std::min(a.x, b.x) - h - 1.0, width_)));
  int x1 = static_cast<int>(std::ceil(on_axis(std::max(a.x, b.x) + h + 1.0, width_)));
  int y0 = static_cast<int>(std::floor(on_axis(std::min(a.y, b.y) - h - 1.0, height_)));
  int y1 = static_cast<int>(std::ceil(on_axis(std::max(a.y, b.y) + h + 1.0, height_)));
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
  if (!(std::isfinite(dash) && std::isfinite(gap) && dash > 0.0 && gap >= 0.0 && dash + gap >= kMinDashPeriod))
    throw Error("dashed line: dash " + shortest_text(dash) + " and gap " + shortest_text(gap) +
                ": expected finite pixels, a dash > 0, a gap >= 0 and a period of at least 1/16 pixel");
  Point d = b - a;
  double length = std::sqrt(d.x * d.x + d.y * d.y);
  if (!(length > 0.0) || !std::isfinite(length) || std::isnan(width)) return;
  Point u = d / length;
  // Only the dashes that can reach the canvas (a long line far off it looped over all of its
  // dashes): the part of [0, length] whose points lie within the line's reach of the canvas.
  const double reach = 0.5 * std::abs(width) + 2.0;
  double first = 0.0, last = length;
  const double low[2] = {-reach, -reach}, high[2] = {width_ + reach, height_ + reach};
  const double start[2] = {a.x, a.y}, step[2] = {u.x, u.y};
  for (int axis = 0; axis < 2; ++axis) {
    if (step[axis] == 0.0) {
      if (start[axis] < low[axis] || start[axis] > high[axis]) return;
      continue;
    }
    double enter = (low[axis] - start[axis]) / step[axis], leave = (high[axis] - start[axis]) / step[axis];
    if (enter > leave) std::swap(enter, leave);
    first = std::max(first, enter), last = std::min(last, leave);
  }
  if (!(first <= last)) return;
  const double period = dash + gap;
  for (double s = std::floor(first / period) * period; s < last;) {
    line(a + s * u, a + std::min(s + dash, length) * u, c, width);
    // From 1e17 pixels away a period is below the resolution of doubles, and s stood still.
    const double next = s + period;
    if (!(next > s)) break;
    s = next;
  }
}

void Canvas::disc(Point centre, double radius, Colour c) {
  if (std::isnan(centre.x) || std::isnan(centre.y) || std::isnan(radius)) return;
  int x0 = std::max(0, static_cast<int>(std::floor(on_axis(centre.x - radius - 1.0, width_))));
  int x1 = std::min(width_ - 1, static_cast<int>(std::ceil(on_axis(centre.x + radius + 1.0, width_))));
  int y0 = std::max(0, static_cast<int>(std::floor(on_axis(centre.y - radius - 1.0, height_))));
  int y1 = std::min(height_ - 1, static_cast<int>(std::ceil(on_axis(centre.y + radius + 1.0, height_))));
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
  if (scale < 1 || scale > kMaxCanvasSide)
    throw Error("text scale " + std::to_string(scale) + ": expected 1 to " + std::to_string(kMaxCanvasSide));
  if (s.empty() || std::isnan(x) || std::isnan(y)) return;
  const long long w = text_width(s, scale), ht = text_height(scale);
  // Size of the box on the canvas (turned when vertical).
  const long long box_w = vertical ? ht : w, box_h = vertical ? w : ht;
  auto offset = [](Align a, long long size) {
    return a == Align::start ? 0.0 : a == Align::centre ? 0.5 * static_cast<double>(size) : static_cast<double>(size);
  };
  // Clamped as on_axis does, a box's size further out: nothing of a text that far away is seen.
  const double far = 2.0 * kMaxCanvasSide + static_cast<double>(std::max(box_w, box_h));
  const auto corner = [&](double at) { return std::llround(std::clamp(at, -far, far)); };
  const long long left = corner(x - offset(h, box_w)), top = corner(y - offset(v, box_h));
  // Each lit font pixel is a scale x scale block, drawn where it meets the canvas.
  const auto block = [&](long long x0, long long y0) {
    const long long xa = std::max(x0, 0LL), xb = std::min(x0 + scale, static_cast<long long>(width_));
    const long long ya = std::max(y0, 0LL), yb = std::min(y0 + scale, static_cast<long long>(height_));
    for (long long py = ya; py < yb; ++py)
      for (long long px = xa; px < xb; ++px) set(static_cast<int>(px), static_cast<int>(py), c);
  };
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto& rows = glyph(s[k]);
    for (int row = 0; row < glyph_height; ++row) {
      for (int column = 0; column < glyph_width; ++column) {
        if (!(rows[static_cast<std::size_t>(row)] & (0x10 >> column))) continue;
        // Position in the unturned text box, in font pixels.
        const long long u = static_cast<long long>(k) * glyph_advance + column, t = row;
        // Turned, the box's pixel (px, py) lands on (left + py, top + w - 1 - px).
        if (vertical) block(left + t * scale, top + w - (u + 1) * scale);
        else block(left + u * scale, top + t * scale);
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
