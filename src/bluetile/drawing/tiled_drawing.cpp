#include "bluetile/drawing/tiled_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "bluetile/core/error.h"
#include "bluetile/io/svg.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// Calls draw(position, radius) for every kept point of the window.
template <typename Draw>
void for_each_dot(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style,
                  Draw draw) {
  const double max_fraction = thinning != nullptr ? thinning->fraction() : 1.0;
  tiler.for_each_cell(window, thinning, [&](const CellPoints& cell) {
    for (Point p : cell.positions) {
      double r = style.radius;
      if (style.follow_density && thinning != nullptr) r *= std::sqrt(thinning->fraction_at(p) / max_fraction);
      draw(p, r);
    }
  });
}

}  // namespace

double default_dot_radius(double max_density) { return std::sqrt(0.35 / (std::numbers::pi * max_density)); }

Canvas render_dots(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style,
                   int width_pixels) {
  const double scale = width_pixels / window.width();
  // In double first: a tall window's height does not fit an int (it became 1 pixel).
  const double height = std::max(1.0, std::round(window.height() * scale));
  if (!(height <= kMaxCanvasSide)) {
    char text[200];
    const ClassicNumbers classic;
    std::snprintf(text, sizeof text,
                  "a render %d pixels wide of a window %.17g x %.17g would be %.0f pixels tall, more than the limit "
                  "of %d",
                  width_pixels, window.width(), window.height(), height, kMaxCanvasSide);
    throw Error(text);
  }
  const int height_pixels = static_cast<int>(height);
  Canvas canvas(width_pixels, height_pixels, colours::white);
  for_each_dot(tiler, window, thinning, style, [&](Point p, double r) {
    canvas.disc({(p.x - window.x0) * scale, (window.y1 - p.y) * scale}, r * scale, colours::black);
  });
  return canvas;
}

namespace {

// The drawing without its dots: the page, and the group the dots go in, left open.
SvgDocument dots_frame(const Window& window, const DotStyle& style) {
  const double display_width = 800.0;
  const double display_height = display_width * window.height() / window.width();
  SvgDocument svg(0.0, 0.0, window.width(), window.height(), display_width, display_height, "px");
  // Coordinates are written relative to nothing but the view box's resolution by default; dots
  // need about a thousandth of their radius.
  int decimals = static_cast<int>(std::ceil(std::max(0.0, -std::log10(style.radius * 1e-3))));
  svg.set_decimals(std::clamp(std::max(svg.decimals(), decimals), 0, 12));
  svg.set_title("bluetile tile");
  svg.rect(0.0, 0.0, window.width(), window.height(), SvgStyle::filled(colours::white));
  svg.begin_group(SvgStyle::filled(colours::black),
                  SvgTransform::fit_y_up(window.x0, window.y0, window.width(), window.height(), 0.0, 0.0,
                                         window.width(), window.height()));
  return svg;
}

}  // namespace

SvgDocument dots_drawing(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style) {
  SvgDocument svg = dots_frame(window, style);
  for_each_dot(tiler, window, thinning, style, [&](Point p, double r) { svg.circle(p, r); });
  svg.end_group();
  return svg;
}

std::string dots_svg(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style) {
  return dots_drawing(tiler, window, thinning, style).str();
}

void write_dots_svg(OutputStream& out, const Tiler& tiler, const Window& window, const Thinning* thinning,
                    const DotStyle& style) {
  dots_frame(window, style).write(out, [&](SvgVisitor& more) {
    for_each_dot(tiler, window, thinning, style, [&](Point p, double r) { more.circle(p, r, {}); });
  });
}

}  // namespace bluetile
