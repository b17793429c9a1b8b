// The stipple command's drawings for screens and pen plotters: SVG with a physical size, dots as
// discs or as short strokes, in pen order, their size following the tone.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bluetile/core/density_grid.h"
#include "bluetile/core/output_file.h"
#include "bluetile/core/torus.h"

namespace bluetile::cli {

struct StippleDrawingOptions {
  std::string size;           // the SVG's printed width, "210mm", "21cm", "8.5in"; empty: 1000 px per domain unit
  std::string dot_shape = "disc";  // disc | stroke
  bool plot_order = false;    // dots in pen-plotter order (sampling/plot_order.h)
  bool follow_density = false;  // dot radius follows the tone
};

void add_stipple_drawing_options(CLI::App* command, StippleDrawingOptions& options);

// A printed length: a positive number and its unit (mm, cm, in).
struct PrintedLength {
  double value = 0.0;
  std::string unit;
};
// Parses "210mm", "21 cm", "8.5in"; throws Error naming the option and the value otherwise.
PrintedLength parse_printed_length(const std::string& text, const std::string& option);

// Every dot's radius: `radius`, or with follow_density `radius` scaled by the square root of the
// map's density at the dot over its peak (ink per area then follows the tone, as in tile
// --dots-follow-density).
std::vector<double> dot_radii(const std::vector<Point>& dots, const DensityGrid& map, const Domain& domain,
                              double radius, bool follow_density);

// Writes the drawing (domain units, y up) as SVG; with plot_order the dots come in pen order and
// the pen-up travel, before and after 2-opt, is returned in the printed unit (px without --size).
struct PenTravel {
  double greedy = 0.0, travel = 0.0;
  std::string unit;
};
PenTravel write_stipple_svg(OutputFile& out, const std::vector<Point>& dots, const std::vector<double>& radii,
                            const Domain& domain, const StippleDrawingOptions& options);

}  // namespace bluetile::cli
