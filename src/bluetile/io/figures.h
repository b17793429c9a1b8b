// The images of `bluetile analyze`: the points (optionally with their periodic Voronoi cells, the
// paper's Figure 1; displacement from an earlier set, Figure 1b; later levels as crosses,
// Figure 4), the tone-mapped periodogram (Figure 7), and the radial power and anisotropy plot
// (Figures 2-4).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/io/image.h"

namespace bluetile {

struct PointsFigure {
  std::vector<Point> points;  // on the unit torus
  std::vector<int> levels;    // empty, or one per point: level 0 as dots, later levels as crosses
  bool cells = false;         // draw each site's periodic Voronoi cell
  std::vector<Point> from;    // empty, or one per point: draw the move from there (on the torus)
  // Tile boundaries (points from `bluetile tile`), drawn as thin lines: x and y of the lines
  // inside the unit square.
  std::vector<double> grid_x, grid_y;
};

// A square image of `size` pixels, y up, the unit square framed.
Canvas draw_points(const PointsFigure& figure, int size = 800);

// The periodogram as grey levels, k = 0 at the centre and ky up. Tone map: grey =
// log2(1 + sqrt(P)) / log2(3), clamped: P = 0 black, white noise (P = 1) light grey, P >= 4
// white (psa maps log2(1 + sqrt(P)) the same way but saturates at P = 1). Sizes above
// `max_size` are reduced by averaging P over square blocks; small ones are enlarged by whole
// pixels to at least about `min_size`.
Canvas draw_spectrum(const Periodogram& periodogram, int max_size = 1024, int min_size = 512);

struct RadialCurve {
  std::string label;
  std::vector<Annulus> radial;
};

// Radial power (top) and anisotropy in dB (bottom) against frequency, one line per curve, with
// the white-noise levels dashed: power 1, and anisotropy `anisotropy_reference` dB (0 for one
// set; -10 log10(M) for the mean periodogram of M sets, whose variance is M times smaller).
// Annulus 0 (k = 0, P = N) is left out.
Canvas draw_radial(std::span<const RadialCurve> curves, const std::string& title,
                   double anisotropy_reference = 0.0, int width = 900, int height = 760);

// Images side by side on white, each with its caption above.
Canvas montage(std::span<const Canvas> images, std::span<const std::string> captions);

}  // namespace bluetile
