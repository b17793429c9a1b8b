// A small RGB raster canvas for the analysis images: anti-aliased lines, discs and crosses,
// text in the built-in bitmap font, and PNG output through OpenImageIO (written atomically).
// Coordinates are pixels, x to the right and y down, pixel centres at half-integers.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "bluetile/core/output_file.h"
#include "bluetile/core/torus.h"

namespace bluetile {

struct Colour {
  float r = 0.0f, g = 0.0f, b = 0.0f;
  bool operator==(const Colour&) const = default;
};

namespace colours {
inline constexpr Colour white{1.0f, 1.0f, 1.0f};
inline constexpr Colour black{0.0f, 0.0f, 0.0f};
inline constexpr Colour grey{0.55f, 0.55f, 0.55f};
inline constexpr Colour light_grey{0.86f, 0.86f, 0.86f};
}  // namespace colours

// The i-th colour of a palette that stays distinguishable in print and for colour-blind readers
// (Okabe & Ito), for plot series and levels.
Colour series_colour(std::size_t i);

enum class Align { start, centre, end };

// The largest width and height of a Canvas, in pixels: a 32768 x 32768 canvas already holds
// 12 GiB of float RGB.
inline constexpr int kMaxCanvasSide = 32768;
// Bytes a canvas takes per pixel while it is drawn and written: float RGB, and the 8-bit copy
// handed to the image writer.
inline constexpr double kCanvasBytesPerPixel = 15.0;

class Canvas {
 public:
  Canvas() = default;
  // Throws Error for a width or height outside 1..kMaxCanvasSide.
  Canvas(int width, int height, Colour background = colours::white);

  int width() const { return width_; }
  int height() const { return height_; }
  // Throws Error for a pixel outside the canvas (it was read past the pixels' end).
  Colour pixel(int x, int y) const;
  void set(int x, int y, Colour c);
  // Mixes c into the pixel with weight alpha in [0, 1]; outside pixels are ignored.
  void blend(int x, int y, Colour c, double alpha);

  // The shapes below draw what falls on the canvas, whatever their coordinates: nothing of a
  // shape off the canvas or with a NaN coordinate (a huge or NaN coordinate was converted to an
  // int, undefined behaviour).
  void fill_rect(double x0, double y0, double x1, double y1, Colour c);
  // A segment of the given width with anti-aliased edges.
  void line(Point a, Point b, Colour c, double width = 1.0);
  // Dashes of `dash` pixels `gap` apart from a. Throws Error unless both are finite, dash > 0,
  // gap >= 0 and dash + gap >= kMinDashPeriod (a period of 0 never ended, one of 1e-9 pixels
  // took hours).
  void dashed_line(Point a, Point b, Colour c, double width, double dash, double gap);
  static constexpr double kMinDashPeriod = 1.0 / 16.0;
  void disc(Point centre, double radius, Colour c);
  void cross(Point centre, double half_size, Colour c, double width = 1.0);
  // Text in the bitmap font at integer `scale`, aligned at (x, y) horizontally by `h` and
  // vertically by `v` (start = top). `vertical` turns it 90 degrees counter-clockwise (for a
  // y-axis label); alignment then applies to the turned box. Throws Error for a scale outside
  // 1..kMaxCanvasSide (a scale of 2^30 overflowed and ran for hours).
  void text(double x, double y, std::string_view s, Colour c, int scale = 2, Align h = Align::start,
            Align v = Align::start, bool vertical = false);
  // Glyphs advance 6 font pixels (font.h). In 64 bits: a long text at a large scale passes an int
  // (it overflowed).
  static long long text_width(std::string_view s, int scale) {
    return s.empty() ? 0 : (static_cast<long long>(s.size()) * 6 - 1) * scale;
  }
  static int text_height(int scale) { return 8 * scale; }

  // Copies `other` with its top-left corner at (x, y).
  void paste(const Canvas& other, int x, int y);

  const std::vector<float>& rgb() const { return pixels_; }

 private:
  int width_ = 0, height_ = 0;
  std::vector<float> pixels_;  // RGB, row by row
};

// Writes an 8-bit RGB PNG (or any format OpenImageIO knows by the extension; grey images in one
// channel) through output_file.h. Throws Error naming the path on failure.
void write_image(OutputFile& out, const Canvas& canvas);
void write_image(const std::string& path, const Canvas& canvas);

// Reads an image back as a canvas (tests). Throws Error on failure.
Canvas read_image(const std::string& path);

}  // namespace bluetile
