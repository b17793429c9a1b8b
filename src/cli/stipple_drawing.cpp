#include "cli/stipple_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "bluetile/core/error.h"
#include "bluetile/io/image.h"
#include "bluetile/io/svg.h"
#include "bluetile/sampling/plot_order.h"

namespace bluetile::cli {

void add_stipple_drawing_options(CLI::App* command, StippleDrawingOptions& options) {
  command
      ->add_option("--size", options.size,
                   "Printed width of the --svg drawing, e.g. 210mm, 21cm, 8.5in (the height follows the image; "
                   "default: 1000 px per unit of the longer side)")
      ->type_name("LENGTH");
  command
      ->add_option("--dot-shape", options.dot_shape,
                   "disc: a filled circle per dot; stroke: a short round-capped stroke per dot (one pen-down each, "
                   "for pen plotters)")
      ->check(CLI::IsMember({"disc", "stroke"}))
      ->capture_default_str();
  command->add_flag("--plot-order", options.plot_order,
                    "Draw the --svg dots in pen-plotter order (greedy nearest neighbour, then 2-opt); prints the "
                    "pen-up travel before and after on stderr");
  command->add_flag("--dots-follow-density", options.follow_density,
                    "Dot size follows the tone: radius times the square root of the density over its peak");
}

PrintedLength parse_printed_length(const std::string& text, const std::string& option) {
  const char* begin = text.c_str();
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  std::string unit(end);
  unit.erase(0, unit.find_first_not_of(' '));
  const bool known = unit == "mm" || unit == "cm" || unit == "in";
  if (end == begin || !known || !std::isfinite(value) || !(value > 0.0) || value > 1e6) {
    throw Error(option + " " + text + ": expected a positive length below 1e6 with its unit: mm, cm or in (210mm, 8.5in)");
  }
  return {value, unit};
}

std::vector<double> dot_radii(const std::vector<Point>& dots, const DensityGrid& map, const Domain& domain,
                              double radius, bool follow_density) {
  std::vector<double> radii(dots.size(), radius);
  if (!follow_density) return radii;
  const double peak = *std::max_element(map.texels.begin(), map.texels.end());
  for (std::size_t i = 0; i < dots.size(); ++i) {
    const Point uv{dots[i].x / domain.size.x, dots[i].y / domain.size.y};
    const double density = std::max(0.0, sample_bilinear(map, uv));
    radii[i] = radius * std::sqrt(peak > 0.0 ? density / peak : 1.0);
  }
  return radii;
}

PenTravel write_stipple_svg(OutputFile& out, const std::vector<Point>& dots, const std::vector<double>& radii,
                            const Domain& domain, const StippleDrawingOptions& options) {
  const Point size = domain.size;
  PenTravel travel{0.0, 0.0, "px"};
  double display_width = 1000.0 * size.x;
  if (!options.size.empty()) {
    const PrintedLength printed = parse_printed_length(options.size, "--size");
    display_width = printed.value;
    travel.unit = printed.unit;
  }
  const double display_per_unit = display_width / size.x;
  SvgDocument svg(0.0, 0.0, size.x, size.y, display_width, display_per_unit * size.y, travel.unit);
  svg.set_title("bluetile stipple");
  svg.rect(0.0, 0.0, size.x, size.y, SvgStyle::filled(colours::white));

  std::vector<std::size_t> order(dots.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  if (options.plot_order) {
    PlotOrder plot = plot_order(dots);
    order = std::move(plot.order);
    travel.greedy = plot.greedy_travel * display_per_unit;
    travel.travel = plot.travel * display_per_unit;
  }
  const SvgTransform y_up = SvgTransform::fit_y_up(0.0, 0.0, size.x, size.y, 0.0, 0.0, size.x, size.y);
  if (options.dot_shape == "stroke") {
    svg.begin_group(SvgStyle{.fill = SvgPaint::none(), .stroke = colours::black, .round_caps = true}, y_up);
    for (std::size_t i : order) {
      const double r = radii[i];
      SvgStyle pen = SvgStyle::stroked(colours::black, r);
      pen.round_caps = true;
      svg.line({dots[i].x - 0.5 * r, dots[i].y}, {dots[i].x + 0.5 * r, dots[i].y}, pen);
    }
  } else {
    svg.begin_group(SvgStyle::filled(colours::black), y_up);
    for (std::size_t i : order) svg.circle(dots[i], radii[i]);
  }
  svg.end_group();
  out.write(svg.str());
  return travel;
}

}  // namespace bluetile::cli
