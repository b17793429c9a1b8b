#include "bluetile/drawing/figures.h"

#include <algorithm>
#include <cmath>

#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/core/error.h"
#include "bluetile/voronoi/exact_engine.h"

namespace bluetile {
namespace {

constexpr double kPointsMargin = 10.0 / 800.0;  // frame margin, as a fraction of the figure's side

// Room under the square for the figure's note.
double note_height(double text_height, const PointsFigure& figure) {
  return figure.note.empty() ? 0.0 : text_height + 12.0;
}

// The part of a convex polygon inside [0,1]^2 (Sutherland and Hodgman 1974: one half-plane at a time).
std::vector<Point> clip_to_unit_square(std::vector<Point> polygon) {
  auto clip = [&polygon](auto inside, auto cross) {
    std::vector<Point> kept;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const Point a = polygon[k], b = polygon[(k + 1) % polygon.size()];
      if (inside(a)) kept.push_back(a);
      if (inside(a) != inside(b)) kept.push_back(cross(a, b));
    }
    polygon = std::move(kept);
  };
  auto on_x = [](double x) {
    return [x](Point a, Point b) { return Point{x, a.y + (b.y - a.y) * (x - a.x) / (b.x - a.x)}; };
  };
  auto on_y = [](double y) {
    return [y](Point a, Point b) { return Point{a.x + (b.x - a.x) * (y - a.y) / (b.y - a.y), y}; };
  };
  clip([](Point p) { return p.x >= 0.0; }, on_x(0.0));
  clip([](Point p) { return p.x <= 1.0; }, on_x(1.0));
  clip([](Point p) { return p.y >= 0.0; }, on_y(0.0));
  clip([](Point p) { return p.y <= 1.0; }, on_y(1.0));
  return polygon;
}

}  // namespace

Point points_figure_pixel(Point p, double x, double y, double size) {
  const double margin = kPointsMargin * size, side = size - 2.0 * margin;
  return Point{x + margin + p.x * side, y + margin + (1.0 - p.y) * side};
}

void paint_points(const PointsFigure& figure, Painter& painter, double x, double y, double size) {
  const double margin = kPointsMargin * size, side = size - 2.0 * margin;
  auto to_px = [&](Point p) { return points_figure_pixel(p, x, y, size); };
  const std::size_t n = figure.points.size();
  const double spacing = n ? hexagonal_spacing(static_cast<double>(n)) * side : side;
  // Marks a fifth of the hexagonal spacing across: they never touch in a blue-noise set.
  const double radius = std::clamp(0.1 * spacing, 1.0, 5.0) * std::min(1.0, size / 400.0);
  // On the torus, something within `reach` of an edge is drawn again one period over.
  auto for_copies = [&](Point p, double reach, auto draw) {
    if (!figure.periodic) return draw(p);
    for (int sy = -1; sy <= 1; ++sy) {
      for (int sx = -1; sx <= 1; ++sx) {
        Point q = p + Point{static_cast<double>(sx), static_cast<double>(sy)};
        if (q.x < -reach || q.x > 1.0 + reach || q.y < -reach || q.y > 1.0 + reach) continue;
        draw(q);
      }
    }
  };

  if (figure.cells && figure.periodic && n > 0) {
    const std::vector<std::vector<Point>> polygons = exact_cell_polygons(make_scene(figure.points));
    const Colour cell_colour{0.55f, 0.65f, 0.80f};
    std::vector<Point> outline;
    for (std::size_t i = 0; i < n; ++i) {
      const std::vector<Point>& polygon = polygons[i];
      if (polygon.empty()) continue;
      double reach = 0.0;
      for (const Point& v : polygon) reach = std::max(reach, std::max(std::abs(v.x), std::abs(v.y)));
      for_copies(figure.points[i], reach, [&](Point site) {
        // Cells, like the period they tile, end at the unit square's frame.
        std::vector<Point> cell;
        for (const Point& v : polygon) cell.push_back(site + v);
        cell = clip_to_unit_square(std::move(cell));
        if (cell.size() < 3) return;
        outline.clear();
        for (const Point& v : cell) outline.push_back(to_px(v));
        outline.push_back(outline.front());
        painter.polyline(outline, cell_colour, 1.0);
      });
    }
  }
  if (figure.from.size() == n && n > 0) {
    const Colour move_colour{0.84f, 0.37f, 0.00f};
    for (std::size_t i = 0; i < n; ++i) {
      Point d = figure.periodic ? torus_offset(figure.from[i], figure.points[i], Domain{}) : figure.points[i] - figure.from[i];
      double reach = std::max(std::abs(d.x), std::abs(d.y));
      for_copies(figure.points[i], reach, [&](Point p) {
        painter.line(to_px(p - d), to_px(p), move_colour, 1.2);
        painter.disc(to_px(p - d), 0.6 * radius, Colour{0.6f, 0.6f, 0.6f});
      });
    }
  }
  const Colour grid_colour{0.80f, 0.45f, 0.45f};
  for (double gx : figure.grid_x) painter.line(to_px({gx, 0.0}), to_px({gx, 1.0}), grid_colour, 1.0);
  for (double gy : figure.grid_y) painter.line(to_px({0.0, gy}), to_px({1.0, gy}), grid_colour, 1.0);
  // Frame of the unit square (one period).
  const Point corners[4] = {to_px({0, 0}), to_px({1, 0}), to_px({1, 1}), to_px({0, 1})};
  for (int k = 0; k < 4; ++k) painter.line(corners[k], corners[(k + 1) % 4], colours::grey, 1.0);

  const bool leveled = figure.levels.size() == n;
  for (std::size_t i = 0; i < n; ++i) {
    const int level = leveled ? figure.levels[i] : 0;
    const Colour c = leveled ? series_colour(static_cast<std::size_t>(level)) : colours::black;
    for_copies(figure.points[i], radius / side * 2.0, [&](Point p) {
      if (level == 0) painter.disc(to_px(p), radius, c);
      else painter.cross(to_px(p), radius * 1.1, c, std::max(1.0, 0.45 * radius));
    });
  }
  if (!figure.note.empty())
    painter.text(x + 0.5 * size, y + size + 6.0, figure.note, colours::black, Align::centre, Align::start);
}

Canvas draw_points(const PointsFigure& figure, int size) {
  Canvas canvas(size, size + static_cast<int>(std::ceil(note_height(Canvas::text_height(2), figure))), colours::white);
  CanvasPainter painter(canvas);
  paint_points(figure, painter, 0.0, 0.0, size);
  return canvas;
}

SvgDocument points_svg(const PointsFigure& figure, int size) {
  const double height = size + note_height(14.0, figure);  // SvgPainter's default font size
  SvgDocument result(0.0, 0.0, size, height, size, height, "px");
  result.set_decimals(3);  // a thousandth of a pixel: coordinates to about 1e-6 of the square
  result.rect(0, 0, size, height, SvgStyle::filled(colours::white));
  SvgPainter painter(result);
  paint_points(figure, painter, 0.0, 0.0, size);
  return result;
}

SvgImage spectrum_image(const Periodogram& periodogram, int max_size) {
  const int f = periodogram.size;
  if (f < 2) throw Error("cannot draw an empty periodogram");
  const int shrink = std::max(1, (f + max_size - 1) / std::max(1, max_size));
  const int cells = f / shrink;
  SvgImage image{cells, cells, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(cells) * static_cast<std::size_t>(cells))};
  const double scale = 1.0 / std::log2(3.0);
  for (int cy = 0; cy < cells; ++cy) {
    for (int cx = 0; cx < cells; ++cx) {
      double sum = 0.0;
      for (int j = 0; j < shrink; ++j)
        for (int i = 0; i < shrink; ++i)
          sum += periodogram.power[static_cast<std::size_t>(cy * shrink + j) * static_cast<std::size_t>(f) +
                                   static_cast<std::size_t>(cx * shrink + i)];
      const double p = sum / static_cast<double>(shrink * shrink);
      const double g = std::clamp(std::log2(1.0 + std::sqrt(p)) * scale, 0.0, 1.0);
      // Row ky = -F/2 is stored first; draw ky up.
      image.pixels[static_cast<std::size_t>(cells - 1 - cy) * static_cast<std::size_t>(cells) + static_cast<std::size_t>(cx)] =
          static_cast<std::uint8_t>(std::lround(g * 255.0));
    }
  }
  return image;
}

Canvas draw_spectrum(const Periodogram& periodogram, int max_size, int min_size) {
  const SvgImage image = spectrum_image(periodogram, max_size);
  const int grow = std::max(1, (min_size + image.width - 1) / image.width);
  Canvas canvas(image.width * grow, image.height * grow, colours::black);
  CanvasPainter painter(canvas);
  painter.image(0, 0, canvas.width(), canvas.height(), image);
  return canvas;
}

SvgDocument spectrum_svg(const Periodogram& periodogram, int max_size, int display) {
  SvgDocument doc(display, display);
  doc.image(0, 0, display, display, spectrum_image(periodogram, max_size));
  return doc;
}

Plot radial_plot(std::span<const RadialCurve> curves, const std::string& title, double anisotropy_reference,
                 FrequencyAxis axis) {
  Plot plot;
  plot.title = title;
  const bool normalised = axis == FrequencyAxis::normalised;
  plot.x_label = normalised ? "frequency nu = |k| / (sqrt(N) / 2)" : "frequency |k| (integer frequencies on the unit torus)";
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
      const double x = normalised ? normalised_frequency(an.frequency, curves[c].count) : an.frequency;
      p.x.push_back(x);
      p.y.push_back(an.power);
      a.x.push_back(x);
      a.y.push_back(an.anisotropy_db);
      if (std::isfinite(an.power)) power_max = std::max(power_max, an.power);
      if (std::isfinite(an.anisotropy_db)) ani_lo = std::min(ani_lo, an.anisotropy_db), ani_hi = std::max(ani_hi, an.anisotropy_db);
      x_max = std::max(x_max, x);
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
  return plot;
}

Canvas draw_radial(std::span<const RadialCurve> curves, const std::string& title, double anisotropy_reference,
                   FrequencyAxis axis, int width, int height) {
  return render_plot(radial_plot(curves, title, anisotropy_reference, axis), width, height);
}

Plot rdf_plot(std::span<const RdfCurve> curves, const std::string& title) {
  Plot plot;
  plot.title = title;
  plot.x_label = "distance r / hexagonal spacing";
  PlotPanel panel;
  panel.y_label = "RDF g(r)";
  panel.reference = 1.0;
  panel.y_min = 0.0;
  double g_max = 2.0, x_max = 1.0;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    const RadialDistribution& rdf = curves[c].rdf;
    PlotSeries s{curves[c].label, {}, {}, series_colour(c), 2.0};
    for (std::size_t b = 0; b < rdf.g.size(); ++b) {
      s.x.push_back(rdf.radius(b) / rdf.hexagonal_spacing);
      s.y.push_back(rdf.g[b]);
      g_max = std::max(g_max, rdf.g[b]);
    }
    x_max = std::max(x_max, rdf.range() / rdf.hexagonal_spacing);
    panel.series.push_back(std::move(s));
  }
  // A lattice's peaks are histogram spikes: cap the axis where blue-noise peaks still show.
  panel.y_max = std::min(std::ceil(g_max * 1.1 * 2.0) / 2.0, 6.0);
  plot.x_min = 0.0;
  plot.x_max = x_max;
  plot.panels = {std::move(panel)};
  return plot;
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

SvgDocument montage_svg(std::span<const SvgDocument> images, std::span<const std::string> captions) {
  if (images.empty()) throw Error("nothing to put side by side");
  const double pad = 16.0, caption_h = 30.0;
  double width = pad, height = 0.0;
  for (const SvgDocument& d : images) width += d.width() + pad, height = std::max(height, d.height());
  SvgDocument doc(width, height + caption_h + pad);
  doc.set_decimals(3);
  doc.rect(0, 0, width, height + caption_h + pad, SvgStyle::filled(colours::white));
  SvgPainter painter(doc);
  double x = pad;
  for (std::size_t i = 0; i < images.size(); ++i) {
    if (i < captions.size())
      painter.text(x + 0.5 * images[i].width(), 8.0, captions[i], colours::black, Align::centre, Align::start);
    doc.include(images[i], SvgTransform::translate(x, caption_h));
    x += images[i].width() + pad;
  }
  return doc;
}

namespace {

// Each series' points (left column) and periodogram (right column) on a grid of up to 4 x 4
// panels, the label under each.
void paint_series_panels(SvgDocument& doc, std::span<const SummaryPage::Series> series, double left, double right,
                         double top, double column) {
  constexpr std::size_t kMaxPanels = 16;  // 4 x 4: panels of 60 pt, about the smallest that reads
  const std::size_t shown = std::min(series.size(), kMaxPanels);
  const std::size_t across = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(shown))));
  const double cell = column / static_cast<double>(across), caption = 9.0, panel = cell - caption;
  SvgPainter tiny(doc, across > 2 ? 6.0 : 7.0);
  for (std::size_t i = 0; i < shown; ++i) {
    const double dx = static_cast<double>(i % across) * cell + 0.5 * caption;
    const double dy = top + static_cast<double>(i / across) * cell;
    PointsFigure points = series[i].points;
    points.note.clear();
    paint_points(points, tiny, left + dx, dy, panel);
    doc.image(right + dx, dy, panel, panel, spectrum_image(series[i].periodogram, 256));
    tiny.text(left + dx + 0.5 * panel, dy + panel + 2.0, series[i].label, colours::black, Align::centre, Align::start);
    tiny.text(right + dx + 0.5 * panel, dy + panel + 2.0,
              series[i].label + ", F = " + std::to_string(series[i].periodogram.size), colours::black, Align::centre,
              Align::start);
  }
  if (series.size() > shown)
    tiny.text(left, top + column + 6.0,
              "the first " + std::to_string(shown) + " of " + std::to_string(series.size()) + " series are drawn",
              colours::black, Align::start, Align::start);
}

// One row per series: its label, then its cells under the header.
void paint_series_table(SvgDocument& doc, const SummaryPage& page, double x, double& y, double width) {
  const std::size_t columns = page.table_header.size();
  if (columns == 0) return;
  const double label_width = width - 34.0 * static_cast<double>(columns - 1);
  auto cell_x = [&](std::size_t c) { return x + label_width + 34.0 * static_cast<double>(c); };
  auto row = [&](const std::string& label, std::span<const std::string> cells, bool bold) {
    y += 12.0;
    std::string shown = label.size() > 18 ? label.substr(0, 17) + "\u2026" : label;
    const double size = bold ? 6.5 : 7.5;  // the header narrower: "avg min" fits its column
    doc.text({x, y}, shown, {.size = size, .bold = bold});
    for (std::size_t c = 0; c < cells.size() && c + 1 < columns; ++c)
      doc.text({cell_x(c + 1), y}, cells[c], {.size = size, .anchor = Align::end, .bold = bold});
    doc.line({x, y + 3.0}, {x + width, y + 3.0}, SvgStyle::stroked(colours::light_grey, 0.5));
  };
  row(page.table_header[0], std::span<const std::string>(page.table_header).subspan(1), true);
  for (const SummaryPage::Series& s : page.series) row(s.label, s.row, false);
}

}  // namespace

SvgDocument summary_page(const SummaryPage& page) {
  // A4 portrait in points; two columns of 255 pt.
  constexpr double kWidth = 595.0, kHeight = 842.0, kMargin = 36.0, kColumn = 255.0, kGutter = 13.0;
  const double left = kMargin, right_column = kMargin + kColumn + kGutter;
  SvgDocument doc(0.0, 0.0, kWidth, kHeight, kWidth, kHeight, "pt");
  doc.set_decimals(3);
  doc.set_title(page.title);
  doc.rect(0, 0, kWidth, kHeight, SvgStyle::filled(colours::white));
  doc.text({left, 50.0}, page.title, {.size = 14.0, .bold = true});
  doc.text({left, 66.0}, page.subtitle, {.size = 8.5, .colour = Colour{0.25f, 0.25f, 0.25f}});

  SvgPainter small(doc, 8.0);
  // Row 1: the points and the periodogram.
  const double row1 = 80.0;
  if (page.series.empty()) {
    PointsFigure points = page.points;
    points.note.clear();
    paint_points(points, small, left, row1, kColumn);
    doc.image(right_column, row1, kColumn, kColumn, spectrum_image(page.periodogram, 1024));
    small.text(left + 0.5 * kColumn, row1 + kColumn + 4.0, page.points.note.empty() ? "points" : page.points.note,
               colours::black, Align::centre, Align::start);
    small.text(right_column + 0.5 * kColumn, row1 + kColumn + 4.0,
               "periodogram, F = " + std::to_string(page.periodogram.size) + " (k = 0 at the centre)", colours::black,
               Align::centre, Align::start);
  } else {
    paint_series_panels(doc, page.series, left, right_column, row1, kColumn);
  }

  // Rows 2 and 3: radial power and the RDF; anisotropy and the table.
  const double row2 = row1 + kColumn + 22.0, plot_h = 205.0, row3 = row2 + plot_h + 10.0;
  const Plot radial = radial_plot(page.radial, "", page.anisotropy_reference, page.axis);
  Plot power = radial, anisotropy = radial;
  power.panels = {radial.panels[0]};
  anisotropy.panels = {radial.panels[1]};
  auto place = [&](const Plot& plot, double x, double y) {
    doc.begin_group({}, SvgTransform::translate(x, y));
    paint_plot(plot, small, kColumn, plot_h);
    doc.end_group();
  };
  place(power, left, row2);
  place(rdf_plot(page.rdf, ""), right_column, row2);
  place(anisotropy, left, row3);

  // The table of measures.
  double y = row3 + 12.0;
  doc.text({right_column, y}, "measures", {.size = 10.0, .bold = true});
  y += 6.0;
  if (!page.series.empty()) paint_series_table(doc, page, right_column, y, kColumn);
  for (const auto& [name, value] : page.series.empty() ? page.measures : decltype(page.measures){}) {
    y += 13.0;
    doc.text({right_column, y}, name, {.size = 8.5});
    doc.text({right_column + kColumn, y}, value, {.size = 8.5, .anchor = Align::end});
    doc.line({right_column, y + 3.5}, {right_column + kColumn, y + 3.5}, SvgStyle::stroked(colours::light_grey, 0.5));
  }
  doc.text({left, kHeight - 24.0},
           "bluetile analyze, after psa's conventions (Heck, Schl\u00f6mer and Deussen 2013; Schl\u00f6mer and Deussen 2011)",
           {.size = 7.0, .colour = colours::grey});
  return doc;
}

}  // namespace bluetile
