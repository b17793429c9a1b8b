// Line plots: one or more panels stacked vertically sharing the x axis, each with a frame,
// ticks, tick labels, grid, an axis label, an optional dashed reference level (psa draws one at
// white noise: power 1, anisotropy 0 dB) and a legend in the first panel. Written for the
// paper's radial power / anisotropy figures (Figures 2-4) and the RDF.
//
// A plot is laid out once and drawn through a Painter: onto a raster Canvas (PNG) or into an
// SvgDocument (SVG, and PDF through pdf.h), so the raster and vector versions agree.
#pragma once

#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "bluetile/io/image.h"
#include "bluetile/io/svg.h"

namespace bluetile {

// Drawing primitives in the target's units (pixels, or SVG user units), y down.
class Painter {
 public:
  virtual ~Painter() = default;
  virtual void line(Point a, Point b, Colour c, double width) = 0;
  virtual void dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) = 0;
  // A connected line through the points.
  virtual void polyline(std::span<const Point> points, Colour c, double width) = 0;
  virtual void disc(Point centre, double radius, Colour c) = 0;
  virtual void cross(Point centre, double half_size, Colour c, double width) = 0;
  virtual void fill_rect(double x0, double y0, double x1, double y1, Colour c) = 0;
  // Text aligned at (x, y) by `h` and `v` (start = top); `vertical` turns it 90 degrees
  // counter-clockwise, alignment then applying to the turned box.
  virtual void text(double x, double y, std::string_view s, Colour c, Align h, Align v, bool vertical = false) = 0;
  virtual double text_width(std::string_view s) const = 0;
  virtual double text_height() const = 0;
  // A grey or RGB image stretched over the rectangle.
  virtual void image(double x, double y, double width, double height, const SvgImage& image) = 0;
};

// Onto a canvas, text in the bitmap font at integer `scale`.
class CanvasPainter final : public Painter {
 public:
  explicit CanvasPainter(Canvas& canvas, int text_scale = 2) : canvas_(canvas), scale_(text_scale) {}
  void line(Point a, Point b, Colour c, double width) override;
  void dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) override;
  void polyline(std::span<const Point> points, Colour c, double width) override;
  void disc(Point centre, double radius, Colour c) override;
  void cross(Point centre, double half_size, Colour c, double width) override;
  void fill_rect(double x0, double y0, double x1, double y1, Colour c) override;
  void text(double x, double y, std::string_view s, Colour c, Align h, Align v, bool vertical = false) override;
  double text_width(std::string_view s) const override;
  double text_height() const override;
  void image(double x, double y, double width, double height, const SvgImage& image) override;

 private:
  Canvas& canvas_;
  int scale_;
};

// Into an SVG document, text of `font_size` user units (widths estimated from DejaVu Sans's
// average advance, for layout).
class SvgPainter final : public Painter {
 public:
  explicit SvgPainter(SvgDocument& document, double font_size = 14.0) : doc_(document), size_(font_size) {}
  void line(Point a, Point b, Colour c, double width) override;
  void dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) override;
  void polyline(std::span<const Point> points, Colour c, double width) override;
  void disc(Point centre, double radius, Colour c) override;
  void cross(Point centre, double half_size, Colour c, double width) override;
  void fill_rect(double x0, double y0, double x1, double y1, Colour c) override;
  void text(double x, double y, std::string_view s, Colour c, Align h, Align v, bool vertical = false) override;
  double text_width(std::string_view s) const override;
  double text_height() const override { return size_; }
  void image(double x, double y, double width, double height, const SvgImage& image) override;

 private:
  SvgDocument& doc_;
  double size_;
};

struct PlotSeries {
  std::string label;          // legend text; empty: not in the legend
  std::vector<double> x, y;   // NaN or infinite y breaks the line
  Colour colour = colours::black;
  double width = 2.0;
  bool dashed = false;        // a reference level or target rather than data
};

struct PlotPanel {
  std::string y_label;
  std::vector<PlotSeries> series;
  // Axis range; NaN: from the data (ticks rounded outwards).
  double y_min = std::numeric_limits<double>::quiet_NaN();
  double y_max = std::numeric_limits<double>::quiet_NaN();
  double reference = std::numeric_limits<double>::quiet_NaN();
};

struct Plot {
  std::string title;
  std::string x_label;
  double x_min = std::numeric_limits<double>::quiet_NaN();
  double x_max = std::numeric_limits<double>::quiet_NaN();
  // A logarithmic x axis (x > 0; ticks at powers of 2 over at most 12 octaves, else of 10).
  bool log_x = false;
  std::vector<PlotPanel> panels;
};

// Draws the plot into the rectangle [0, width] x [0, height] of the painter. Throws Error
// for a plot without panels, a series whose x and y differ in length, and for a log_x plot whose
// x range is not above 0.
void paint_plot(const Plot& plot, Painter& painter, double width, double height);

// The plot as a white canvas of the given size.
Canvas render_plot(const Plot& plot, int width, int height);

// The plot as an SVG document of the given size in px.
SvgDocument render_plot_svg(const Plot& plot, int width, int height);

// Round tick values (1, 2 or 5 times a power of ten apart) covering [lo, hi], about `target`
// of them; one where the step is below the resolution of doubles at lo (a range of 0.25 at
// 1e15). Throws Error unless lo < hi and 1 <= target <= kMaxTicks.
std::vector<double> nice_ticks(double lo, double hi, int target);
inline constexpr int kMaxTicks = 1000;

// Ticks of a logarithmic axis over [lo, hi], 0 < lo < hi: the powers of 2 inside it when it spans
// at most 12 octaves, else the powers of 10 (both ends included when they are such powers).
std::vector<double> log_ticks(double lo, double hi);

}  // namespace bluetile
