// A small log-log line plot written as PNG with OpenImageIO, for the benchmark's
// error-against-time figure. Points with y <= 0 or below `y_floor` are drawn on the floor line
// (exact engines: their error against the exact engine is 0 or rounding).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace bluetile::bench {

struct PlotSeries {
  std::string label;
  std::vector<std::pair<double, double>> points;  // (x, y), drawn in this order
};

struct LogLogPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  double y_floor = 1e-16;
  std::vector<PlotSeries> series;
};

// Throws bluetile::Error when the file cannot be written. Text needs a TrueType font that
// OpenImageIO can find (DejaVu Sans); without one the plot is drawn without text.
void write_loglog_png(const std::string& path, const LogLogPlot& plot, int width = 1000, int height = 700);

}  // namespace bluetile::bench
