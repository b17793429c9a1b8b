#include "bluetile/io/figures.h"

#include <algorithm>
#include <cmath>

#include "bluetile/core/error.h"
#include "bluetile/io/plot.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {

Canvas draw_points(const PointsFigure& figure, int size) {
  const double margin = 10.0, side = size - 2.0 * margin;
  Canvas canvas(size, size, colours::white);
  auto to_px = [&](Point p) { return Point{margin + p.x * side, margin + (1.0 - p.y) * side}; };
  const std::size_t n = figure.points.size();
  const double spacing = n ? hexagonal_spacing(static_cast<double>(n)) * side : side;
  // Marks a fifth of the hexagonal spacing across: they never touch in a blue-noise set.
  const double radius = std::clamp(0.1 * spacing, 1.0, 5.0);
  // Something within `reach` of an edge is drawn again one period over.
  auto for_copies = [&](Point p, double reach, auto draw) {
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        Point q = p + Point{static_cast<double>(sx), static_cast<double>(sy)};
        if (q.x < -reach || q.x > 1.0 + reach || q.y < -reach || q.y > 1.0 + reach) continue;
        draw(q);
      }
    }
  };

  if (figure.cells && n > 0) {
    Scene scene = make_scene(figure.points);
    const Colour cell_colour{0.55f, 0.65f, 0.80f};
    for (std::size_t i = 0; i < n; ++i) {
      std::vector<Point> polygon = exact_cell_polygon(scene, i);
      double reach = 0.0;
      for (const Point& v : polygon) reach = std::max(reach, std::max(std::abs(v.x), std::abs(v.y)));
      for_copies(figure.points[i], reach, [&](Point site) {
        for (std::size_t k = 0; k < polygon.size(); ++k)
          canvas.line(to_px(site + polygon[k]), to_px(site + polygon[(k + 1) % polygon.size()]), cell_colour, 1.0);
      });
    }
  }
  if (figure.from.size() == n && n > 0) {
    const Colour move_colour{0.84f, 0.37f, 0.00f};
    for (std::size_t i = 0; i < n; ++i) {
      Point d = torus_offset(figure.from[i], figure.points[i], Domain{});
      double reach = std::max(std::abs(d.x), std::abs(d.y));
      for_copies(figure.points[i], reach, [&](Point p) {
        canvas.line(to_px(p - d), to_px(p), move_colour, 1.2);
        canvas.disc(to_px(p - d), 0.6 * radius, Colour{0.6f, 0.6f, 0.6f});
      });
    }
  }
  const Colour grid_colour{0.80f, 0.45f, 0.45f};
  for (double x : figure.grid_x) canvas.line(to_px({x, 0.0}), to_px({x, 1.0}), grid_colour, 1.0);
  for (double y : figure.grid_y) canvas.line(to_px({0.0, y}), to_px({1.0, y}), grid_colour, 1.0);
  // Frame of the unit square (one period).
  const Point corners[4] = {to_px({0, 0}), to_px({1, 0}), to_px({1, 1}), to_px({0, 1})};
  for (int k = 0; k < 4; ++k) canvas.line(corners[k], corners[(k + 1) % 4], colours::grey, 1.0);

  const bool leveled = figure.levels.size() == n;
  for (std::size_t i = 0; i < n; ++i) {
    const int level = leveled ? figure.levels[i] : 0;
    const Colour c = leveled ? series_colour(static_cast<std::size_t>(level)) : colours::black;
    for_copies(figure.points[i], radius / side * 2.0, [&](Point p) {
      if (level == 0) canvas.disc(to_px(p), radius, c);
      else canvas.cross(to_px(p), radius * 1.1, c, std::max(1.0, 0.45 * radius));
    });
  }
  return canvas;
}

Canvas draw_spectrum(const Periodogram& periodogram, int max_size, int min_size) {
  const int f = periodogram.size;
  if (f < 2) throw Error("cannot draw an empty periodogram");
  const int shrink = std::max(1, (f + max_size - 1) / max_size);
  const int cells = f / shrink;
  const int grow = std::max(1, (min_size + cells - 1) / cells);
  Canvas canvas(cells * grow, cells * grow, colours::black);
  const double scale = 1.0 / std::log2(3.0);
  for (int cy = 0; cy < cells; ++cy) {
    for (int cx = 0; cx < cells; ++cx) {
      double sum = 0.0;
      for (int j = 0; j < shrink; ++j)
        for (int i = 0; i < shrink; ++i)
          sum += periodogram.power[static_cast<std::size_t>(cy * shrink + j) * static_cast<std::size_t>(f) +
                                   static_cast<std::size_t>(cx * shrink + i)];
      double p = sum / static_cast<double>(shrink * shrink);
      float g = static_cast<float>(std::clamp(std::log2(1.0 + std::sqrt(p)) * scale, 0.0, 1.0));
      // Row ky = -F/2 is stored first; draw ky up.
      const int top = (cells - 1 - cy) * grow, left = cx * grow;
      for (int y = 0; y < grow; ++y)
        for (int x = 0; x < grow; ++x) canvas.set(left + x, top + y, Colour{g, g, g});
    }
  }
  return canvas;
}

Canvas draw_radial(std::span<const RadialCurve> curves, const std::string& title, double anisotropy_reference,
                   int width, int height) {
  Plot plot;
  plot.title = title;
  plot.x_label = "frequency |k| (integer frequencies on the unit torus)";
  PlotPanel power, anisotropy;
  power.y_label = "radial power P";
  power.reference = 1.0;
  power.y_min = 0.0;
  anisotropy.y_label = "anisotropy (dB)";
  anisotropy.reference = anisotropy_reference;
  double power_max = 2.0, ani_lo = std::min(-5.0, anisotropy_reference - 5.0), ani_hi = 5.0, x_max = 1.0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    PlotSeries p{curves[c].label, {}, {}, series_colour(c), 2.0};
    PlotSeries a{"", {}, {}, series_colour(c), 2.0};
    for (std::size_t i = 1; i < curves[c].radial.size(); ++i) {
      const Annulus& an = curves[c].radial[i];
      p.x.push_back(an.frequency);
      p.y.push_back(an.power);
      a.x.push_back(an.frequency);
      a.y.push_back(an.anisotropy_db);
      if (std::isfinite(an.power)) power_max = std::max(power_max, an.power);
      if (std::isfinite(an.anisotropy_db)) ani_lo = std::min(ani_lo, an.anisotropy_db), ani_hi = std::max(ani_hi, an.anisotropy_db);
      x_max = std::max(x_max, an.frequency);
    }
    power.series.push_back(std::move(p));
    anisotropy.series.push_back(std::move(a));
  }
  // Spikes (a lattice's peaks) would flatten everything else: cap the power axis at 8.
  power.y_max = std::min(std::ceil(power_max * 1.1 * 2.0) / 2.0, 8.0);
  anisotropy.y_min = std::max(std::floor(ani_lo / 5.0) * 5.0, -30.0);
  anisotropy.y_max = std::min(std::ceil(ani_hi / 5.0) * 5.0, 30.0);
  plot.x_min = 0.0;
  plot.x_max = x_max;
  plot.panels = {std::move(power), std::move(anisotropy)};
  return render_plot(plot, width, height);
}

Canvas montage(std::span<const Canvas> images, std::span<const std::string> captions) {
  if (images.empty()) throw Error("nothing to put side by side");
  const int pad = 16, caption_h = Canvas::text_height(2) + 14;
  int width = pad, height = 0;
  for (const Canvas& c : images) width += c.width() + pad, height = std::max(height, c.height());
  Canvas canvas(width, height + caption_h + pad, colours::white);
  int x = pad;
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (i < captions.size())
      canvas.text(x + 0.5 * images[i].width(), 8, captions[i], colours::black, 2, Align::centre);
    canvas.paste(images[i], x, caption_h);
    x += images[i].width() + pad;
  }
  return canvas;
}

}  // namespace bluetile
