#include "bluetile/io/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bluetile/core/error.h"
#include "bluetile/core/text.h"

namespace bluetile {
namespace {

// Layout in units of the painter's text height, so a plot looks the same at any size.
constexpr double kLeftMargin = 6.25, kRightMargin = 1.5, kTitleGap = 2.5, kPanelGap = 2.0;
constexpr double kTickLength = 0.4375, kLegendSample = 1.875;
// DejaVu Sans's mean advance over digits and lower-case letters, in ems: SVG text widths for layout.
constexpr double kAdvanceEm = 0.6;

double nice_step(double span, int target) {
  double raw = span / std::max(1, target);
  double power = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / power;
  return (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0) * power;
}

std::string tick_label(double v, double step) {
  int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(v) < 0.5 * step * 1e-6) v = 0.0;  // no "-0"
  const ClassicNumbers classic;
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

// Liang-Barsky: clips segment a-b to the rectangle; false when nothing is left.
bool clip(Point& a, Point& b, double x0, double y0, double x1, double y1) {
  double t0 = 0.0, t1 = 1.0;
  Point d = b - a;
  const double p[4] = {-d.x, d.x, -d.y, d.y};
  const double q[4] = {a.x - x0, x1 - a.x, a.y - y0, y1 - a.y};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    double t = q[i] / p[i];
    if (p[i] < 0.0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t0 > t1) return false;
  Point start = a + t0 * d, end = a + t1 * d;
  a = start, b = end;
  return true;
}

struct Range {
  double lo, hi;
};

Range data_range(const PlotPanel& panel, double x_lo, double x_hi) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& s : panel.series)
    for (std::size_t i = 0; i < s.y.size() && i < s.x.size(); ++i)
      if (std::isfinite(s.y[i]) && s.x[i] >= x_lo && s.x[i] <= x_hi) lo = std::min(lo, s.y[i]), hi = std::max(hi, s.y[i]);
  if (std::isfinite(panel.reference)) lo = std::min(lo, panel.reference), hi = std::max(hi, panel.reference);
  if (!std::isfinite(lo)) return {0.0, 1.0};
  if (hi - lo < 1e-12) lo -= 0.5, hi += 0.5;
  return {lo, hi};
}

SvgStyle stroke(Colour c, double width) {
  SvgStyle s = SvgStyle::stroked(c, width);
  s.round_caps = true;
  return s;
}

}  // namespace

// --- painters ------------------------------------------------------------------------------

void CanvasPainter::line(Point a, Point b, Colour c, double width) { canvas_.line(a, b, c, width); }
void CanvasPainter::dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) {
  canvas_.dashed_line(a, b, c, width, dash, gap);
}
void CanvasPainter::polyline(std::span<const Point> points, Colour c, double width) {
  for (std::size_t i = 0; i + 1 < points.size(); ++i) canvas_.line(points[i], points[i + 1], c, width);
}
void CanvasPainter::disc(Point centre, double radius, Colour c) { canvas_.disc(centre, radius, c); }
void CanvasPainter::cross(Point centre, double half_size, Colour c, double width) {
  canvas_.cross(centre, half_size, c, width);
}
void CanvasPainter::fill_rect(double x0, double y0, double x1, double y1, Colour c) { canvas_.fill_rect(x0, y0, x1, y1, c); }
void CanvasPainter::text(double x, double y, std::string_view s, Colour c, Align h, Align v, bool vertical) {
  canvas_.text(x, y, s, c, scale_, h, v, vertical);
}
double CanvasPainter::text_width(std::string_view s) const { return static_cast<double>(Canvas::text_width(s, scale_)); }
double CanvasPainter::text_height() const { return Canvas::text_height(scale_); }
void CanvasPainter::image(double x, double y, double width, double height, const SvgImage& image) {
  // Nearest pixel: the images drawn are periodograms, whose cells should stay sharp.
  const int x0 = static_cast<int>(std::lround(x)), y0 = static_cast<int>(std::lround(y));
  const int w = static_cast<int>(std::lround(width)), h = static_cast<int>(std::lround(height));
  for (int j = 0; j < h; ++j) {
    const int sy = std::min(image.height - 1, j * image.height / std::max(1, h));
    for (int i = 0; i < w; ++i) {
      const int sx = std::min(image.width - 1, i * image.width / std::max(1, w));
      const std::size_t at = (static_cast<std::size_t>(sy) * static_cast<std::size_t>(image.width) +
                              static_cast<std::size_t>(sx)) * static_cast<std::size_t>(image.channels);
      const float r = image.pixels[at] / 255.0f;
      const float g = image.channels == 3 ? image.pixels[at + 1] / 255.0f : r;
      const float b = image.channels == 3 ? image.pixels[at + 2] / 255.0f : r;
      canvas_.set(x0 + i, y0 + j, Colour{r, g, b});
    }
  }
}

void SvgPainter::line(Point a, Point b, Colour c, double width) { doc_.line(a, b, stroke(c, width)); }
void SvgPainter::dashed_line(Point a, Point b, Colour c, double width, double dash, double gap) {
  SvgStyle s = SvgStyle::stroked(c, width);
  s.dash = {dash, gap};
  doc_.line(a, b, s);
}
void SvgPainter::polyline(std::span<const Point> points, Colour c, double width) {
  doc_.polyline(points, stroke(c, width));
}
void SvgPainter::disc(Point centre, double radius, Colour c) { doc_.circle(centre, radius, SvgStyle::filled(c)); }
void SvgPainter::cross(Point centre, double half_size, Colour c, double width) {
  const double h = half_size;
  doc_.line(centre + Point{-h, -h}, centre + Point{h, h}, stroke(c, width));
  doc_.line(centre + Point{-h, h}, centre + Point{h, -h}, stroke(c, width));
}
void SvgPainter::fill_rect(double x0, double y0, double x1, double y1, Colour c) {
  doc_.rect(std::min(x0, x1), std::min(y0, y1), std::abs(x1 - x0), std::abs(y1 - y0), SvgStyle::filled(c));
}
double SvgPainter::text_width(std::string_view s) const { return kAdvanceEm * size_ * static_cast<double>(s.size()); }
void SvgPainter::text(double x, double y, std::string_view s, Colour c, Align h, Align v, bool vertical) {
  // The text's box on the page (turned when vertical), then the baseline within it.
  const double length = text_width(s), box_w = vertical ? size_ : length, box_h = vertical ? length : size_;
  auto offset = [](Align a, double extent) { return a == Align::start ? 0.0 : a == Align::centre ? 0.5 * extent : extent; };
  const double left = x - offset(h, box_w), top = y - offset(v, box_h);
  constexpr double kAscent = 0.78;  // of the em box above the baseline (DejaVu Sans caps: 0.73)
  SvgText style{.size = size_, .colour = c};
  if (vertical) {
    // Reads bottom to top; glyph tops face left.
    style.rotate_degrees = 90.0;
    doc_.text({left + kAscent * size_, top + box_h}, s, style);
  } else {
    doc_.text({left, top + kAscent * size_}, s, style);
  }
}
void SvgPainter::image(double x, double y, double width, double height, const SvgImage& image) {
  doc_.image(x, y, width, height, image);
}

// --- plots -----------------------------------------------------------------------------------

std::vector<double> nice_ticks(double lo, double hi, int target) {
  // NaN and -1e308 to 1e308 said "plot range is empty", and the latter gave no ticks.
  if (!std::isfinite(lo) || !std::isfinite(hi))
    throw Error("plot range " + shortest_text(lo) + " to " + shortest_text(hi) + ": not finite");
  if (!(hi > lo)) throw Error("plot range " + shortest_text(lo) + " to " + shortest_text(hi) + " is empty");
  if (target < 1 || target > kMaxTicks)
    throw Error("ticks: target " + std::to_string(target) + ": expected 1 to " + std::to_string(kMaxTicks));
  // A span past the largest double is measured in tenths: the step stays 1, 2 or 5 times a power of 10.
  const double span = hi - lo;
  const double step = std::isfinite(span) ? nice_step(span, target) : 10.0 * nice_step(hi / 10.0 - lo / 10.0, target);
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step;) {
    ticks.push_back(v);
    // A step below the doubles' resolution at v (a range of 0.25 at 1e15) left v where it was,
    // and the loop never ended.
    const double next = v + step;
    if (!(next > v)) break;
    v = next;
  }
  return ticks;
}

std::vector<double> log_ticks(double lo, double hi) {
  if (!(lo > 0.0) || !(hi > lo)) throw Error("log axis range must be above 0 and not empty");
  const double base = std::log2(hi / lo) <= 12.0 ? 2.0 : 10.0;
  std::vector<double> ticks;
  const double slack = 1e-9;  // an end that is a power within rounding counts
  for (double e = std::ceil(std::log(lo) / std::log(base) - slack); std::pow(base, e) <= hi * (1.0 + slack); ++e)
    ticks.push_back(std::pow(base, e));
  return ticks;
}

void paint_plot(const Plot& plot, Painter& painter, double width, double height) {
  if (plot.panels.empty()) throw Error("a plot needs at least one panel");
  // Pairs past the shorter column were dropped without a word.
  for (std::size_t p = 0; p < plot.panels.size(); ++p)
    for (std::size_t k = 0; k < plot.panels[p].series.size(); ++k) {
      const PlotSeries& s = plot.panels[p].series[k];
      if (s.x.size() != s.y.size())
        throw Error("plot panel " + std::to_string(p) + ", series " + std::to_string(k) +
                    (s.label.empty() ? "" : " '" + s.label + "'") + ": " + std::to_string(s.x.size()) + " x values but " +
                    std::to_string(s.y.size()) + " y values");
    }
  const double th = painter.text_height();
  const double left = kLeftMargin * th, right = width - kRightMargin * th;
  const double top = plot.title.empty() ? 1.25 * th : 1.5 * th + th + 1.0 * th;
  const double bottom = height - (2.0 * th + 2.25 * th);
  const double gap = kPanelGap * th;
  const auto panels = static_cast<double>(plot.panels.size());
  const double panel_h = (bottom - top - gap * (panels - 1.0)) / panels;
  const double tick = kTickLength * th;
  const double frame = std::max(1.0, 0.094 * th), grid = std::max(0.5, 0.0625 * th);

  double x_lo = plot.x_min, x_hi = plot.x_max;
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi)) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& panel : plot.panels)
      for (const auto& s : panel.series)
        for (double v : s.x) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(x_lo)) x_lo = std::isfinite(lo) ? lo : 0.0;
    if (!std::isfinite(x_hi)) x_hi = std::isfinite(hi) ? hi : 1.0;
    if (!(x_hi > x_lo)) x_hi = plot.log_x ? 2.0 * x_lo : x_lo + 1.0;
  }
  if (plot.log_x && !(x_lo > 0.0)) throw Error("a log x axis needs x above 0");
  const std::vector<double> x_ticks = plot.log_x ? log_ticks(x_lo, x_hi) : nice_ticks(x_lo, x_hi, 8);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : x_hi - x_lo;
  auto to_px = [&](double x) {
    const double f = plot.log_x ? std::log(x / x_lo) / std::log(x_hi / x_lo) : (x - x_lo) / (x_hi - x_lo);
    return left + f * (right - left);
  };
  auto x_tick_label = [&](double t) {
    if (!plot.log_x) return tick_label(t, x_step);
    const ClassicNumbers classic;
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", t);
    return std::string(buffer);
  };

  if (!plot.title.empty())
    painter.text(0.5 * (left + right), 1.25 * th, plot.title, colours::black, Align::centre, Align::start);

  for (std::size_t p = 0; p < plot.panels.size(); ++p) {
    const PlotPanel& panel = plot.panels[p];
    const double y_top = top + static_cast<double>(p) * (panel_h + gap), y_bottom = y_top + panel_h;
    Range r = data_range(panel, x_lo, x_hi);
    double y_lo = panel.y_min, y_hi = panel.y_max;
    const double step0 = nice_step(r.hi - r.lo, 5);
    if (!std::isfinite(y_lo)) y_lo = std::floor(r.lo / step0) * step0;
    if (!std::isfinite(y_hi)) y_hi = std::ceil(r.hi / step0) * step0;
    if (!(y_hi > y_lo)) y_hi = y_lo + 1.0;
    const std::vector<double> y_ticks = nice_ticks(y_lo, y_hi, 5);
    const double y_step = y_ticks.size() > 1 ? y_ticks[1] - y_ticks[0] : y_hi - y_lo;
    auto to_py = [&](double y) { return y_bottom - (y - y_lo) / (y_hi - y_lo) * panel_h; };

    for (double t : x_ticks) painter.line({to_px(t), y_top}, {to_px(t), y_bottom}, colours::light_grey, grid);
    for (double t : y_ticks) painter.line({left, to_py(t)}, {right, to_py(t)}, colours::light_grey, grid);
    if (std::isfinite(panel.reference) && panel.reference >= y_lo && panel.reference <= y_hi)
      painter.dashed_line({left, to_py(panel.reference)}, {right, to_py(panel.reference)}, colours::grey, 1.5 * grid,
                          0.5 * th, 0.375 * th);

    for (const auto& s : panel.series) {
      // Runs of segments that stay connected after clipping to the frame, one polyline each.
      std::vector<Point> run;
      auto flush = [&] {
        if (run.size() >= 2) {
          if (s.dashed)
            for (std::size_t i = 1; i < run.size(); ++i)
              painter.dashed_line(run[i - 1], run[i], s.colour, s.width, 3.0 * s.width, 2.0 * s.width);
          else
            painter.polyline(run, s.colour, s.width);
        }
        run.clear();
      };
      for (std::size_t i = 0; i + 1 < s.x.size() && i + 1 < s.y.size(); ++i) {
        if (!std::isfinite(s.y[i]) || !std::isfinite(s.y[i + 1])) {
          flush();
          continue;
        }
        Point a{to_px(s.x[i]), to_py(s.y[i])}, b{to_px(s.x[i + 1]), to_py(s.y[i + 1])};
        const Point a0 = a, b0 = b;
        if (!clip(a, b, left, y_top, right, y_bottom)) {
          flush();
          continue;
        }
        if (run.empty() || a != a0) {
          flush();
          run.push_back(a);
        }
        run.push_back(b);
        if (b != b0) flush();
      }
      flush();
      // A lone finite value between gaps still shows, as a dot.
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        bool prev = i > 0 && std::isfinite(s.y[i - 1]), next = i + 1 < s.y.size() && std::isfinite(s.y[i + 1]);
        double py = to_py(s.y[i]);
        if (std::isfinite(s.y[i]) && !prev && !next && py >= y_top && py <= y_bottom)
          painter.disc({to_px(s.x[i]), py}, s.width, s.colour);
      }
    }

    // Frame, ticks and labels on top of the data.
    const Point corners[4] = {{left, y_top}, {right, y_top}, {right, y_bottom}, {left, y_bottom}};
    for (int k = 0; k < 4; ++k) painter.line(corners[k], corners[(k + 1) % 4], colours::black, frame);
    for (double t : x_ticks) {
      painter.line({to_px(t), y_bottom}, {to_px(t), y_bottom - tick}, colours::black, frame);
      painter.text(to_px(t), y_bottom + 0.375 * th, x_tick_label(t), colours::black, Align::centre, Align::start);
    }
    for (double t : y_ticks) {
      painter.line({left, to_py(t)}, {left + tick, to_py(t)}, colours::black, frame);
      painter.text(left - 0.375 * th, to_py(t), tick_label(t, y_step), colours::black, Align::end, Align::centre);
    }
    painter.text(1.125 * th, 0.5 * (y_top + y_bottom), panel.y_label, colours::black, Align::start, Align::centre, true);

    if (p == 0) {
      std::vector<const PlotSeries*> entries;
      double label_w = 0;
      for (const auto& s : panel.series)
        if (!s.label.empty()) entries.push_back(&s), label_w = std::max(label_w, painter.text_width(s.label));
      if (!entries.empty()) {
        const double row = 1.5 * th, sample = kLegendSample * th;
        const double box_w = sample + 1.125 * th + label_w + 0.75 * th, box_h = row * static_cast<double>(entries.size()) + 0.5 * th;
        const double bx = right - box_w - 0.625 * th, by = y_top + 0.625 * th;
        painter.fill_rect(bx, by, bx + box_w, by + box_h, colours::white);
        const Point box[4] = {{bx, by}, {bx + box_w, by}, {bx + box_w, by + box_h}, {bx, by + box_h}};
        for (int k = 0; k < 4; ++k) painter.line(box[k], box[(k + 1) % 4], colours::grey, grid);
        for (std::size_t e = 0; e < entries.size(); ++e) {
          double cy = by + 0.25 * th + (static_cast<double>(e) + 0.5) * row;
          const Point a{bx + 0.5 * th, cy}, b{bx + 0.5 * th + sample, cy};
          const double w = entries[e]->width + 0.5;
          if (entries[e]->dashed) painter.dashed_line(a, b, entries[e]->colour, w, 3.0 * w, 2.0 * w);
          else painter.line(a, b, entries[e]->colour, w);
          painter.text(bx + 1.125 * th + sample, cy, entries[e]->label, colours::black, Align::start, Align::centre);
        }
      }
    }
  }
  painter.text(0.5 * (left + right), bottom + th + 0.875 * th, plot.x_label, colours::black, Align::centre, Align::start);
}

Canvas render_plot(const Plot& plot, int width, int height) {
  Canvas canvas(width, height, colours::white);
  CanvasPainter painter(canvas);
  paint_plot(plot, painter, width, height);
  return canvas;
}

SvgDocument render_plot_svg(const Plot& plot, int width, int height) {
  SvgDocument doc(width, height);
  doc.set_decimals(2);  // a hundredth of a pixel
  SvgPainter painter(doc);
  doc.rect(0, 0, width, height, SvgStyle::filled(colours::white));
  paint_plot(plot, painter, width, height);
  return doc;
}

}  // namespace bluetile
