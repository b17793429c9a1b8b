// A tiled window drawn as dots, for a person to look at: an SVG of discs (a stipple drawing when
// the tiling follows a density map; io/svg.h) and a raster render (io/image.h). Part of the
// images component.
#pragma once

#include <string>

#include "bluetile/io/image.h"
#include "bluetile/io/svg.h"
#include "bluetile/tiling/density_thinning.h"
#include "bluetile/tiling/tiler.h"

namespace bluetile {

struct DotStyle {
  double radius = 0.0;  // plane units; the radius of a dot where the fraction is at its maximum
  // Radius r sqrt(f / f_max): dot area proportional to the local density (darker where denser).
  bool follow_density = false;
};

// The default dot radius for a drawing whose densest place holds `max_density` points per unit
// area: dots there cover about 35 % of the paper, dense enough to read as a tone and sparse
// enough to stay separate dots.
double default_dot_radius(double max_density);

// The kept points of `window` as black discs on white, `width_pixels` wide and as tall as the
// window's aspect asks (y up). Throws Error when that height is beyond kMaxCanvasSide.
Canvas render_dots(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style,
                   int width_pixels);

// The same as a vector drawing: the view box is the window in plane units (y up), shown 800 px
// wide; dots_svg is its SVG text (io/pdf.h draws it as PDF).
SvgDocument dots_drawing(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style);
std::string dots_svg(const Tiler& tiler, const Window& window, const Thinning* thinning, const DotStyle& style);
// dots_svg's bytes written to `out` as the dots are made, in memory that does not grow with them.
void write_dots_svg(OutputStream& out, const Tiler& tiler, const Window& window, const Thinning* thinning,
                    const DotStyle& style);

}  // namespace bluetile
