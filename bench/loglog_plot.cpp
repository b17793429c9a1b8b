#include "loglog_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include "bluetile/core/error.h"
#include "bluetile/core/output_file.h"

namespace bluetile::bench {
namespace {

namespace Algo = OIIO::ImageBufAlgo;
using Colour = std::array<float, 3>;

// Colour-blind-friendly palette (Okabe-Ito), then darker variants.
constexpr Colour kPalette[] = {
    {0.00f, 0.45f, 0.70f}, {0.90f, 0.62f, 0.00f}, {0.00f, 0.62f, 0.45f}, {0.80f, 0.40f, 0.00f},
    {0.34f, 0.71f, 0.91f}, {0.80f, 0.47f, 0.65f}, {0.55f, 0.45f, 0.05f}, {0.00f, 0.00f, 0.00f},
    {0.40f, 0.20f, 0.60f}, {0.50f, 0.50f, 0.50f}, {0.60f, 0.10f, 0.10f}, {0.10f, 0.40f, 0.10f},
};

std::string decade_label(int e) {
  if (e == 0) return "1";
  char buf[16];
  std::snprintf(buf, sizeof buf, "1e%d", e);
  return buf;
}

}  // namespace

void write_loglog_png(const std::string& path, const LogLogPlot& plot, int width, int height) {
  const int left = 100, right = 300, top = 64, bottom = 70;
  const int x0 = left, x1 = width - right, y0 = height - bottom, y1 = top;  // y0 is the bottom

  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const PlotSeries& s : plot.series)
    for (auto [x, y] : s.points) {
      if (!(x > 0.0)) continue;
      double yy = std::max(y, plot.y_floor);
      xmin = std::min(xmin, x), xmax = std::max(xmax, x);
      ymin = std::min(ymin, yy), ymax = std::max(ymax, yy);
    }
  if (!(xmin <= xmax)) xmin = 1e-3, xmax = 1.0, ymin = plot.y_floor, ymax = 1.0;
  int ex0 = static_cast<int>(std::floor(std::log10(xmin))), ex1 = static_cast<int>(std::ceil(std::log10(xmax)));
  int ey0 = static_cast<int>(std::floor(std::log10(ymin))), ey1 = static_cast<int>(std::ceil(std::log10(ymax)));
  if (ex1 == ex0) ++ex1;
  if (ey1 == ey0) ++ey1;
  auto px = [&](double x) {
    return x0 + static_cast<int>(std::lround((std::log10(x) - ex0) / (ex1 - ex0) * (x1 - x0)));
  };
  auto py = [&](double y) {
    return y0 - static_cast<int>(std::lround((std::log10(std::max(y, plot.y_floor)) - ey0) / (ey1 - ey0) * (y0 - y1)));
  };

  OIIO::ImageBuf image(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::UINT8));
  const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0}, grid[3] = {0.88f, 0.88f, 0.88f};
  Algo::fill(image, white);
  bool text_ok = true;
  auto text = [&](int x, int y, const std::string& s, int size, Algo::TextAlignX ax, Algo::TextAlignY ay) {
    if (text_ok) text_ok = Algo::render_text(image, x, y, s, size, "DejaVuSans", black, ax, ay);
  };

  for (int e = ex0; e <= ex1; ++e) {
    int x = x0 + (e - ex0) * (x1 - x0) / (ex1 - ex0);
    Algo::render_line(image, x, y1, x, y0, grid);
    text(x, y0 + 22, decade_label(e), 16, Algo::TextAlignX::Center, Algo::TextAlignY::Baseline);
  }
  for (int e = ey0; e <= ey1; ++e) {
    int y = y0 - (e - ey0) * (y0 - y1) / (ey1 - ey0);
    Algo::render_line(image, x0, y, x1, y, grid);
    text(x0 - 8, y + 5, decade_label(e), 16, Algo::TextAlignX::Right, Algo::TextAlignY::Baseline);
  }
  Algo::render_box(image, x0, y1, x1, y0, black);
  text((x0 + x1) / 2, height - 20, plot.x_label, 18, Algo::TextAlignX::Center, Algo::TextAlignY::Baseline);
  text(x0, 24, plot.title, 18, Algo::TextAlignX::Left, Algo::TextAlignY::Baseline);
  text(12, y1 - 14, plot.y_label, 16, Algo::TextAlignX::Left, Algo::TextAlignY::Baseline);

  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const PlotSeries& s = plot.series[k];
    const Colour& c = kPalette[k % std::size(kPalette)];
    OIIO::cspan<float> colour(c.data(), 3);
    std::vector<std::pair<int, int>> pts;
    for (auto [x, y] : s.points)
      if (x > 0.0) pts.emplace_back(px(x), py(y));
    for (std::size_t i = 1; i < pts.size(); ++i)
      for (int d = -1; d <= 1; ++d) {  // three pixels wide
        Algo::render_line(image, pts[i - 1].first + d, pts[i - 1].second, pts[i].first + d, pts[i].second, colour);
        Algo::render_line(image, pts[i - 1].first, pts[i - 1].second + d, pts[i].first, pts[i].second + d, colour);
      }
    // Markers differ by shape as well as colour: filled boxes for even series, hollow for odd.
    for (auto [x, y] : pts) Algo::render_box(image, x - 4, y - 4, x + 4, y + 4, colour, k % 2 == 0);
    int ly = y1 + 20 + static_cast<int>(k) * 24;
    Algo::render_box(image, x1 + 18, ly - 9, x1 + 30, ly + 3, colour, k % 2 == 0);
    text(x1 + 40, ly + 2, s.label, 15, Algo::TextAlignX::Left, Algo::TextAlignY::Baseline);
  }

  OutputSet outputs;
  outputs.add(path).write_through_path([&](const std::string& temporary) {
    if (!image.write(temporary)) throw Error(path + ": cannot write PNG: " + image.geterror());
  });
  outputs.publish();
}

}  // namespace bluetile::bench
