#include "bluetile/drawing/tile_set_drawing.h"

#include <string>

#include "bluetile/drawing/figures.h"
#include "bluetile/io/plot.h"
#include "bluetile/tiling/seam_check.h"

namespace bluetile {

Canvas draw_tile_set(const TileSet& set, std::uint64_t seed) {
  constexpr int kTile = 130, kGap = 22, kColumns = 8, kPatch = 560, kPatchPeriod = 4;
  constexpr double kBar = 5.0;  // edge-colour bar width, pixels
  const TileRules rules(set.kind);
  const bool corners = rules.corner_coloured();
  auto colour_of = [](int c) { return series_colour(static_cast<std::size_t>(c) + 1); };  // vermilion, green
  const int tiles = static_cast<int>(set.tiles.size());
  const int rows = (tiles + kColumns - 1) / kColumns;
  const int caption = Canvas::text_height(2) + 8;
  const int width = kColumns * (kTile + kGap) + kGap;
  const int patch_top = kGap + rows * (kTile + caption + kGap) + caption;
  Canvas canvas(width, patch_top + kPatch + caption + kGap, colours::white);

  for (int t = 0; t < tiles; ++t) {
    const Tile& tile = set.tiles[static_cast<std::size_t>(t)];
    const double x0 = kGap + (t % kColumns) * (kTile + kGap);
    const double y0 = kGap + (t / kColumns) * (kTile + caption + kGap);
    const double x1 = x0 + kTile, y1 = y0 + kTile;
    canvas.line({x0, y0}, {x1, y0}, colours::light_grey), canvas.line({x1, y0}, {x1, y1}, colours::light_grey);
    canvas.line({x1, y1}, {x0, y1}, colours::light_grey), canvas.line({x0, y1}, {x0, y0}, colours::light_grey);
    const TileColours& c = tile.colours;
    if (corners) {  // NW NE SE SW
      canvas.disc({x0, y0}, 8.0, colour_of(c[0])), canvas.disc({x1, y0}, 8.0, colour_of(c[1]));
      canvas.disc({x1, y1}, 8.0, colour_of(c[2])), canvas.disc({x0, y1}, 8.0, colour_of(c[3]));
    } else {  // N E S W, bars just inside the edges, short of the corners
      const double in = kBar / 2.0, end = 10.0;
      canvas.line({x0 + end, y0 + in}, {x1 - end, y0 + in}, colour_of(c[0]), kBar);
      canvas.line({x1 - in, y0 + end}, {x1 - in, y1 - end}, colour_of(c[1]), kBar);
      canvas.line({x0 + end, y1 - in}, {x1 - end, y1 - in}, colour_of(c[2]), kBar);
      canvas.line({x0 + in, y0 + end}, {x0 + in, y1 - end}, colour_of(c[3]), kBar);
    }
    for (Point p : tile.points) canvas.disc({x0 + p.x * kTile, y0 + (1.0 - p.y) * kTile}, 2.0, colours::black);
    canvas.text(x0 + kTile / 2.0, y1 + 6, "tile " + std::to_string(t), colours::black, 2, Align::centre);
  }

  TiledPlane plane = torus_tiling(set, kPatchPeriod, seed);
  PointsFigure figure;
  figure.points = plane.points;
  figure.cells = true;
  const double px = (width - kPatch) / 2.0, py = patch_top;
  canvas.text(width / 2.0, py - caption + 4,
              std::to_string(kPatchPeriod) + "x" + std::to_string(kPatchPeriod) + " torus tiling (seed " +
                  std::to_string(seed) + ") with the Voronoi cells of its points",
              colours::black, 2, Align::centre);
  CanvasPainter painter(canvas);
  paint_points(figure, painter, px, py, kPatch);
  auto at = [&](double i, double j) { return points_figure_pixel({i / kPatchPeriod, j / kPatchPeriod}, px, py, kPatch); };
  for (int j = 0; j < kPatchPeriod; ++j) {
    for (int i = 0; i < kPatchPeriod; ++i) {
      const TileColours& c = rules.colours(plane.cell_tiles[static_cast<std::size_t>(j * kPatchPeriod + i)]);
      if (corners) {  // tile borders in grey, the colours on the lattice points
        canvas.line(at(i, j), at(i + 1, j), colours::grey, 1.5), canvas.line(at(i, j), at(i, j + 1), colours::grey, 1.5);
        canvas.disc(at(i, j + 1), 7.0, colour_of(c[0])), canvas.disc(at(i + 1, j + 1), 7.0, colour_of(c[1]));
        canvas.disc(at(i + 1, j), 7.0, colour_of(c[2])), canvas.disc(at(i, j), 7.0, colour_of(c[3]));
      } else {  // neighbours agree, so shared edges are drawn twice in one colour
        canvas.line(at(i, j + 1), at(i + 1, j + 1), colour_of(c[0]), 3.0);
        canvas.line(at(i + 1, j), at(i + 1, j + 1), colour_of(c[1]), 3.0);
        canvas.line(at(i, j), at(i + 1, j), colour_of(c[2]), 3.0);
        canvas.line(at(i, j), at(i, j + 1), colour_of(c[3]), 3.0);
      }
    }
  }
  return canvas;
}

}  // namespace bluetile
