// The images of `bluetile analyze`: the points (optionally with their periodic Voronoi cells, the
// paper's Figure 1; displacement from an earlier set, Figure 1b; later levels as crosses,
// Figure 4), the tone-mapped periodogram (Figure 7), the radial power and anisotropy plot
// (Figures 2-4), the radial distribution function, and a one-page summary of all of them with
// a table of measures (psa's summary page). Each as a raster Canvas (PNG) and as an SVG
// document (vector; PDF through pdf.h).
#pragma once

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/io/image.h"
#include "bluetile/io/plot.h"
#include "bluetile/io/svg.h"

namespace bluetile {

struct PointsFigure {
  std::vector<Point> points;  // in the unit square
  std::vector<int> levels;    // empty, or one per point: level 0 as dots, later levels as crosses
  bool cells = false;         // draw each site's periodic Voronoi cell
  std::vector<Point> from;    // empty, or one per point: draw the move from there (on the torus)
  bool periodic = true;       // draw copies of marks near an edge on the opposite side too
  std::string note;           // a line under the square (what the figure shows), or empty
  // Tile boundaries (points from `bluetile tile`), drawn as thin lines: x and y of the lines
  // inside the unit square.
  std::vector<double> grid_x, grid_y;
};

// The figure in the square [x, x + size] x [y, y + size] of the painter (the note below it),
// y up inside, the unit square framed.
void paint_points(const PointsFigure& figure, Painter& painter, double x, double y, double size);
Canvas draw_points(const PointsFigure& figure, int size = 800);
// Where paint_points(..., x, y, size) puts the unit-square point p (for drawing over a figure).
Point points_figure_pixel(Point p, double x, double y, double size);
SvgDocument points_svg(const PointsFigure& figure, int size = 800);

// The periodogram as grey levels, k = 0 at the centre and ky up. Tone map: grey =
// log2(1 + sqrt(P)) / log2(3), clamped: P = 0 black, white noise (P = 1) light grey, P >= 4
// white (psa maps log2(1 + sqrt(P)) the same way but saturates at P = 1). Sizes above
// `max_size` are reduced by averaging P over square blocks.
SvgImage spectrum_image(const Periodogram& periodogram, int max_size = 1024);
// As a canvas, small ones enlarged by whole pixels to at least about `min_size`.
Canvas draw_spectrum(const Periodogram& periodogram, int max_size = 1024, int min_size = 512);
// As an SVG document `display` px square holding the image (pixels kept sharp).
SvgDocument spectrum_svg(const Periodogram& periodogram, int max_size = 1024, int display = 512);

// Radial power and anisotropy are plotted against the normalised frequency nu = |k| /
// (sqrt(N) / 2) (psa's axis: sets of different N overlay, nu = 1 is the Nyquist frequency of a
// square lattice of N points), or against the integer frequency |k|.
enum class FrequencyAxis { normalised, integer };

struct RadialCurve {
  std::string label;
  std::vector<Annulus> radial;
  std::size_t count = 0;  // points per set, for the normalised axis
};

// Radial power (top) and anisotropy in dB (bottom) against frequency, one line per curve, with
// the white-noise levels dashed: power 1, and anisotropy `anisotropy_reference` dB (0 for one
// set; -10 log10(M) for the mean periodogram of M sets, whose variance is M times smaller).
// Annulus 0 (k = 0, P = N) is left out.
Plot radial_plot(std::span<const RadialCurve> curves, const std::string& title, double anisotropy_reference = 0.0,
                 FrequencyAxis axis = FrequencyAxis::normalised);
Canvas draw_radial(std::span<const RadialCurve> curves, const std::string& title, double anisotropy_reference = 0.0,
                   FrequencyAxis axis = FrequencyAxis::normalised, int width = 900, int height = 760);

struct RdfCurve {
  std::string label;
  RadialDistribution rdf;
};

// g(r) against r in hexagonal spacings (1 for a hexagonal lattice's nearest neighbours), the
// Poisson level 1 dashed.
Plot rdf_plot(std::span<const RdfCurve> curves, const std::string& title);

// Images side by side on white, each with its caption above.
Canvas montage(std::span<const Canvas> images, std::span<const std::string> captions);
SvgDocument montage_svg(std::span<const SvgDocument> images, std::span<const std::string> captions);

// psa's one-page summary: title, the points, the spectrum, radial power, anisotropy, the RDF
// and a table of measures, on an A4 page (points as the unit of the SVG; PDF through pdf.h).
struct SummaryPage {
  std::string title;
  std::string subtitle;
  PointsFigure points;
  Periodogram periodogram;
  std::vector<RadialCurve> radial;
  double anisotropy_reference = 0.0;
  FrequencyAxis axis = FrequencyAxis::normalised;
  std::vector<RdfCurve> rdf;
  std::vector<std::pair<std::string, std::string>> measures;  // name, value
  // Several series side by side (analyze --compare): when not empty, row 1 draws each series'
  // points and periodogram small, captioned with its label (the first 16), and the measures
  // are a table of one row per series under `table_header` (its first column: the label);
  // `points`, `periodogram` and `measures` are then not drawn.
  struct Series {
    std::string label;
    PointsFigure points;
    Periodogram periodogram;
    std::vector<std::string> row;  // the table's cells after the label
  };
  std::vector<Series> series;
  std::vector<std::string> table_header;
};
SvgDocument summary_page(const SummaryPage& page);

}  // namespace bluetile
