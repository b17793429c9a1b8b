#include "bluetile/io/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "bluetile/core/error.h"

namespace bluetile {
namespace {

constexpr int text_scale = 2;

double nice_step(double span, int target) {
  double raw = span / std::max(1, target);
  double power = std::pow(10.0, std::floor(std::log10(raw)));
  double f = raw / power;
  return (f <= 1.0 ? 1.0 : f <= 2.0 ? 2.0 : f <= 5.0 ? 5.0 : 10.0) * power;
}

std::string tick_label(double v, double step) {
  int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(v) < 0.5 * step * 1e-6) v = 0.0;  // no "-0"
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

}  // namespace

std::vector<double> nice_ticks(double lo, double hi, int target) {
  if (!(hi > lo)) throw Error("plot range is empty");
  double step = nice_step(hi - lo, target);
  std::vector<double> ticks;
  for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + 1e-9 * step; v += step) ticks.push_back(v);
  return ticks;
}

Canvas render_plot(const Plot& plot, int width, int height) {
  if (plot.panels.empty()) throw Error("a plot needs at least one panel");
  Canvas canvas(width, height, colours::white);
  const int glyph_h = Canvas::text_height(text_scale);
  const double left = 100, right = width - 24.0;
  const double top = plot.title.empty() ? 20.0 : 24.0 + glyph_h + 16.0;
  const double bottom = height - (2.0 * glyph_h + 36.0);
  const double gap = 2.0 * glyph_h;
  const auto panels = static_cast<double>(plot.panels.size());
  const double panel_h = (bottom - top - gap * (panels - 1.0)) / panels;

  double x_lo = plot.x_min, x_hi = plot.x_max;
  if (!std::isfinite(x_lo) || !std::isfinite(x_hi)) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const auto& panel : plot.panels)
      for (const auto& s : panel.series)
        for (double v : s.x) lo = std::min(lo, v), hi = std::max(hi, v);
    if (!std::isfinite(x_lo)) x_lo = std::isfinite(lo) ? lo : 0.0;
    if (!std::isfinite(x_hi)) x_hi = std::isfinite(hi) ? hi : 1.0;
    if (!(x_hi > x_lo)) x_hi = x_lo + 1.0;
  }
  const std::vector<double> x_ticks = nice_ticks(x_lo, x_hi, 8);
  const double x_step = x_ticks.size() > 1 ? x_ticks[1] - x_ticks[0] : x_hi - x_lo;
  auto to_px = [&](double x) { return left + (x - x_lo) / (x_hi - x_lo) * (right - left); };

  if (!plot.title.empty()) canvas.text(0.5 * (left + right), 20.0, plot.title, colours::black, text_scale, Align::centre);

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

    for (double t : x_ticks) canvas.line({to_px(t), y_top}, {to_px(t), y_bottom}, colours::light_grey, 1.0);
    for (double t : y_ticks) canvas.line({left, to_py(t)}, {right, to_py(t)}, colours::light_grey, 1.0);
    if (std::isfinite(panel.reference) && panel.reference >= y_lo && panel.reference <= y_hi)
      canvas.dashed_line({left, to_py(panel.reference)}, {right, to_py(panel.reference)}, colours::grey, 1.5, 8, 6);

    for (const auto& s : panel.series) {
      for (std::size_t i = 0; i + 1 < s.x.size() && i + 1 < s.y.size(); ++i) {
        if (!std::isfinite(s.y[i]) || !std::isfinite(s.y[i + 1])) continue;
        Point a{to_px(s.x[i]), to_py(s.y[i])}, b{to_px(s.x[i + 1]), to_py(s.y[i + 1])};
        if (clip(a, b, left, y_top, right, y_bottom)) canvas.line(a, b, s.colour, s.width);
      }
      // A lone finite value between gaps still shows, as a dot.
      for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
        bool prev = i > 0 && std::isfinite(s.y[i - 1]), next = i + 1 < s.y.size() && std::isfinite(s.y[i + 1]);
        double py = to_py(s.y[i]);
        if (std::isfinite(s.y[i]) && !prev && !next && py >= y_top && py <= y_bottom)
          canvas.disc({to_px(s.x[i]), py}, s.width, s.colour);
      }
    }

    // Frame, ticks and labels on top of the data.
    canvas.line({left, y_top}, {right, y_top}, colours::black, 1.5);
    canvas.line({left, y_bottom}, {right, y_bottom}, colours::black, 1.5);
    canvas.line({left, y_top}, {left, y_bottom}, colours::black, 1.5);
    canvas.line({right, y_top}, {right, y_bottom}, colours::black, 1.5);
    for (double t : x_ticks) {
      canvas.line({to_px(t), y_bottom}, {to_px(t), y_bottom - 7}, colours::black, 1.5);
      canvas.text(to_px(t), y_bottom + 6, tick_label(t, x_step), colours::black, text_scale, Align::centre);
    }
    for (double t : y_ticks) {
      canvas.line({left, to_py(t)}, {left + 7, to_py(t)}, colours::black, 1.5);
      canvas.text(left - 6, to_py(t), tick_label(t, y_step), colours::black, text_scale, Align::end, Align::centre);
    }
    canvas.text(18, 0.5 * (y_top + y_bottom), panel.y_label, colours::black, text_scale, Align::start, Align::centre, true);

    if (p == 0) {
      std::vector<const PlotSeries*> entries;
      int label_w = 0;
      for (const auto& s : panel.series)
        if (!s.label.empty()) entries.push_back(&s), label_w = std::max(label_w, Canvas::text_width(s.label, text_scale));
      if (!entries.empty()) {
        const double row = glyph_h + 8.0, sample = 30.0;
        const double box_w = sample + 18.0 + label_w + 12.0, box_h = row * static_cast<double>(entries.size()) + 8.0;
        const double bx = right - box_w - 10.0, by = y_top + 10.0;
        canvas.fill_rect(bx, by, bx + box_w, by + box_h, colours::white);
        canvas.line({bx, by}, {bx + box_w, by}, colours::grey, 1.0);
        canvas.line({bx, by + box_h}, {bx + box_w, by + box_h}, colours::grey, 1.0);
        canvas.line({bx, by}, {bx, by + box_h}, colours::grey, 1.0);
        canvas.line({bx + box_w, by}, {bx + box_w, by + box_h}, colours::grey, 1.0);
        for (std::size_t e = 0; e < entries.size(); ++e) {
          double cy = by + 4.0 + (static_cast<double>(e) + 0.5) * row;
          canvas.line({bx + 8.0, cy}, {bx + 8.0 + sample, cy}, entries[e]->colour, entries[e]->width + 0.5);
          canvas.text(bx + 18.0 + sample, cy, entries[e]->label, colours::black, text_scale, Align::start, Align::centre);
        }
      }
    }
  }
  canvas.text(0.5 * (left + right), bottom + glyph_h + 14.0, plot.x_label, colours::black, text_scale, Align::centre);
  return canvas;
}

}  // namespace bluetile
