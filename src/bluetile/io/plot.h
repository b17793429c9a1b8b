// Line plots drawn on a Canvas: one or more panels stacked vertically sharing the x axis, each
// with a frame, ticks, tick labels, grid, an axis label, an optional dashed reference level
// (psa draws one at white noise: power 1, anisotropy 0 dB), and a legend in the first panel.
// Written for the paper's radial power / anisotropy figures (Figures 2-4).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "bluetile/io/image.h"

namespace bluetile {

struct PlotSeries {
  std::string label;          // legend text; empty: not in the legend
  std::vector<double> x, y;   // NaN or infinite y breaks the line
  Colour colour = colours::black;
  double width = 2.0;
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
  std::vector<PlotPanel> panels;
};

Canvas render_plot(const Plot& plot, int width, int height);

// Round tick values (1, 2 or 5 times a power of ten apart) covering [lo, hi], about `target`
// of them. lo < hi.
std::vector<double> nice_ticks(double lo, double hi, int target);

}  // namespace bluetile
