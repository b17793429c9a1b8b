// Images, the bitmap font and plots: pixels where they must be, PNGs that read back.
#include <gtest/gtest.h>

#include <cmath>

#include "bluetile/core/error.h"
#include "bluetile/drawing/figures.h"
#include "bluetile/io/font.h"
#include "bluetile/io/image.h"
#include "bluetile/io/plot.h"
#include "test_support.h"

namespace bluetile {
namespace {

bool is_dark(Colour c) { return c.r + c.g + c.b < 1.5f; }

TEST(Font, GlyphsAreTheDrawnShapes) {
  // 'H': two uprights joined in the middle row.
  const auto& h = glyph('H');
  EXPECT_EQ(h[0], 0x11);
  EXPECT_EQ(h[3], 0x1F);
  EXPECT_EQ(glyph(' ')[3], 0);
  EXPECT_EQ(glyph('\x01'), glyph('?'));
  // Every printable glyph but space draws something.
  for (char c = '!'; c <= '~'; ++c) {
    int bits = 0;
    for (auto row : glyph(c)) bits += row;
    EXPECT_GT(bits, 0) << c;
  }
}

TEST(Canvas, TextLandsInItsBox) {
  Canvas canvas(100, 40);
  canvas.text(10, 5, "H", colours::black, 2);
  // 'H' at scale 2: left column x in [10, 12), rows y in [5, 19); the middle row y in [11, 13).
  EXPECT_TRUE(is_dark(canvas.pixel(10, 5)));
  EXPECT_TRUE(is_dark(canvas.pixel(11, 18)));
  EXPECT_FALSE(is_dark(canvas.pixel(14, 5)));  // gap between the uprights
  EXPECT_TRUE(is_dark(canvas.pixel(14, 11)));  // the crossbar
  EXPECT_FALSE(is_dark(canvas.pixel(9, 5)));
  EXPECT_EQ(Canvas::text_width("ab", 2), 22);
  EXPECT_EQ(Canvas::text_width("", 2), 0);
  EXPECT_EQ(Canvas::text_width(std::string(20000, 'a'), 32768), 3932127232LL);  // past an int: it overflowed
  // Turned text: the box is 16 wide and 10 tall (one glyph), bottom-up.
  Canvas turned(40, 40);
  turned.text(0, 0, "H", colours::black, 2, Align::start, Align::start, true);
  EXPECT_TRUE(is_dark(turned.pixel(0, 9)));    // first column of 'H' becomes the bottom row
  EXPECT_FALSE(is_dark(turned.pixel(0, 12)));
}

TEST(Canvas, LinesAndDiscsCoverWhatTheyShould) {
  Canvas canvas(50, 50);
  canvas.line({5, 25}, {45, 25}, colours::black, 3.0);
  EXPECT_TRUE(is_dark(canvas.pixel(20, 24)));
  EXPECT_FLOAT_EQ(canvas.pixel(20, 24).r, 0.0f);  // fully covered centre pixel
  EXPECT_FLOAT_EQ(canvas.pixel(20, 30).r, 1.0f);  // untouched
  canvas.disc({10, 10}, 4.0, colours::black);
  EXPECT_FLOAT_EQ(canvas.pixel(9, 9).r, 0.0f);
  EXPECT_FLOAT_EQ(canvas.pixel(16, 10).r, 1.0f);
  // Drawing outside the canvas is clipped, not a crash.
  canvas.line({-100, -100}, {200, 300}, colours::black, 2.0);
  canvas.text(-20, 48, "clipped text", colours::black, 3);
}

// Every pixel of the canvas is `c`.
bool all_pixels(const Canvas& canvas, float value) {
  for (float v : canvas.rgb())
    if (v != value) return false;
  return true;
}

// Coordinates converted to int without a bound: a rectangle or disc over the whole plane drew
// nothing (1e300 became INT_MIN), NaN was undefined; pixel() read past the pixels; a dash period
// of 0 never ended and a scale of 2^15 ran a billion steps per font pixel.
TEST(Canvas, ShapesAnywhereDrawWhatMeetsTheCanvas) {
  Canvas canvas(64, 48);
  canvas.fill_rect(-1e300, -1e300, 1e300, 1e300, colours::black);
  EXPECT_TRUE(all_pixels(canvas, 0.0f));
  Canvas disc(64, 48);
  disc.disc({0.0, 0.0}, 1e300, colours::black);
  EXPECT_TRUE(all_pixels(disc, 0.0f));
  Canvas line(64, 48);
  line.line({-1e12, 24.0}, {1e12, 24.0}, colours::black, 1e6);
  EXPECT_TRUE(all_pixels(line, 0.0f));

  const double nan = std::nan("");
  Canvas untouched(64, 48);
  untouched.fill_rect(nan, 0.0, 10.0, 10.0, colours::black);
  untouched.line({nan, 0.0}, {10.0, 10.0}, colours::black, 3.0);
  untouched.disc({5.0, nan}, 3.0, colours::black);
  untouched.dashed_line({0.0, 5.0}, {nan, 5.0}, colours::black, 1.0, 2.0, 2.0);
  untouched.text(nan, 4.0, "H", colours::black, 2);
  EXPECT_TRUE(all_pixels(untouched, 1.0f));

  EXPECT_EQ(test::error_of([&] { canvas.pixel(64, 0); }), "pixel (64, 0) lies outside the 64 x 48 canvas");
  EXPECT_EQ(test::error_of([&] { canvas.pixel(3, -1); }), "pixel (3, -1) lies outside the 64 x 48 canvas");
  const std::string dash_error = ": expected finite pixels, a dash > 0, a gap >= 0 and a period of at least 1/16 pixel";
  EXPECT_EQ(test::error_of([&] { canvas.dashed_line({0, 0}, {10, 10}, colours::black, 1.0, 0.0, 0.0); }),
            "dashed line: dash 0 and gap 0" + dash_error);
  EXPECT_EQ(test::error_of([&] { canvas.dashed_line({0, 0}, {10, 10}, colours::black, 1.0, 1e-9, 1e-9); }),
            "dashed line: dash 1e-09 and gap 1e-09" + dash_error);
  EXPECT_EQ(test::error_of([&] { canvas.dashed_line({0, 0}, {10, 10}, colours::black, 1.0, 2.0, -1.0); }),
            "dashed line: dash 2 and gap -1" + dash_error);
  EXPECT_EQ(test::error_of([&] { canvas.text(0, 0, "H", colours::black, 0); }), "text scale 0: expected 1 to 32768");
  EXPECT_EQ(test::error_of([&] { canvas.text(0, 0, "H", colours::black, 1 << 30); }), "text scale 1073741824: expected 1 to 32768");

  // The largest scale: the top-left block of an 'H' covers the canvas, at once.
  Canvas big(64, 48);
  big.text(0, 0, "H", colours::black, kMaxCanvasSide);
  EXPECT_TRUE(all_pixels(big, 0.0f));
  // A turned text mostly off the canvas lands where its box says: at scale 2 from x = -12, the
  // canvas's first two columns show the glyph's row 6 (0x11: its two uprights at y 8-9 and 0-1).
  Canvas turned(40, 40);
  turned.text(-12.0, 0.0, "H", colours::black, 2, Align::start, Align::start, true);
  EXPECT_TRUE(is_dark(turned.pixel(0, 9)));
  EXPECT_TRUE(is_dark(turned.pixel(1, 0)));
  EXPECT_FALSE(is_dark(turned.pixel(0, 5)));
  EXPECT_FALSE(is_dark(turned.pixel(2, 9)));
}

// Dashes of a line that starts far off the canvas keep their phase from its start: the ones on
// the canvas are drawn without walking every dash before them.
TEST(Canvas, DashesOfALongLineKeepTheirPhase) {
  Canvas near(64, 16), far(64, 16);
  near.dashed_line({-3.5, 8.0}, {70.0, 8.0}, colours::black, 2.0, 3.0, 3.0);
  far.dashed_line({-3.5 - 6e6, 8.0}, {70.0, 8.0}, colours::black, 2.0, 3.0, 3.0);
  // Six-pixel periods from x = -3.5: dark over [2.5, 5.5), [8.5, 11.5), ...
  EXPECT_TRUE(is_dark(near.pixel(3, 8)));
  EXPECT_FALSE(is_dark(near.pixel(7, 8)));
  for (int x = 0; x < 64; ++x) EXPECT_EQ(is_dark(near.pixel(x, 8)), is_dark(far.pixel(x, 8))) << x;
  // So far away that a period is below the resolution of doubles there: it ends.
  Canvas farthest(64, 16);
  farthest.dashed_line({-1e17, 8.0}, {70.0, 8.0}, colours::black, 2.0, 1.0, 1.0);
}

TEST(Image, PngRoundTripsAndFailureLeavesNothing) {
  test::TempDir dir;
  Canvas canvas(7, 5, Colour{0.2f, 0.4f, 0.6f});
  canvas.set(3, 2, colours::black);
  write_image(dir.file("x.png"), canvas);
  Canvas back = read_image(dir.file("x.png"));
  ASSERT_EQ(back.width(), 7);
  ASSERT_EQ(back.height(), 5);
  EXPECT_NEAR(back.pixel(0, 0).g, 0.4f, 0.5f / 255.0f);
  EXPECT_FLOAT_EQ(back.pixel(3, 2).r, 0.0f);
  EXPECT_EQ(dir.list().size(), 1u);
  EXPECT_THROW(write_image(dir.file("no/such/folder/y.png"), canvas), Error);
  EXPECT_THROW(read_image(dir.file("missing.png")), Error);
}

TEST(Plot, NiceTicks) {
  auto t = nice_ticks(0.0, 158.0, 8);
  ASSERT_FALSE(t.empty());
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 20.0);
  t = nice_ticks(-4.3, 2.2, 5);
  EXPECT_DOUBLE_EQ(t.front(), -4.0);
  EXPECT_DOUBLE_EQ(t[1] - t[0], 2.0);
  EXPECT_EQ(test::error_of([] { nice_ticks(1.0, 1.0, 5); }), "plot range 1 to 1 is empty");
  // NaN was "plot range is empty"; a range wider than the largest double gave no ticks.
  EXPECT_EQ(test::error_of([] { nice_ticks(std::nan(""), 1.0, 5); }), "plot range nan to 1: not finite");
  EXPECT_EQ(test::error_of([] { nice_ticks(0.0, INFINITY, 5); }), "plot range 0 to inf: not finite");
  t = nice_ticks(-1e308, 1e308, 5);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t.front(), -1e308);
  EXPECT_EQ(t[2], 0.0);
  EXPECT_EQ(t.back(), 1e308);
}

// A range below the resolution of doubles at its magnitude never ended: each step left the tick
// where it was (data of 1e15 and 1e15 + 0.25 in a plot hung the drawing). A target of 2^30 ticks
// ran for minutes; a series with fewer y than x values lost its last points without a word.
TEST(Plot, TicksOfARangeNarrowerThanItsDoublesEnd) {
  const std::vector<double> t = nice_ticks(1e15, 1e15 + 0.25, 8);
  ASSERT_FALSE(t.empty());
  for (double v : t) EXPECT_TRUE(v >= 1e15 - 0.25 && v <= 1e15 + 0.5) << v;
  Plot plot;
  PlotPanel panel;
  PlotSeries series;
  series.x = {0.0, 1.0, 2.0};
  series.y = {1e15, 1e15 + 0.125, 1e15 + 0.25};
  panel.series.push_back(series);
  plot.panels.push_back(panel);
  EXPECT_EQ(render_plot(plot, 200, 120).width(), 200);
  std::swap(plot.panels[0].series[0].x, plot.panels[0].series[0].y);
  EXPECT_EQ(render_plot(plot, 200, 120).width(), 200);
  plot.panels[0].series[0].y.pop_back();
  plot.panels[0].series[0].label = "energy";
  EXPECT_EQ(test::error_of([&] { render_plot(plot, 200, 120); }), "plot panel 0, series 0 'energy': 3 x values but 2 y values");
  EXPECT_EQ(test::error_of([] { nice_ticks(0.0, 1.0, 0); }), "ticks: target 0: expected 1 to 1000");
  EXPECT_EQ(test::error_of([] { nice_ticks(0.0, 1.0, 1 << 30); }), "ticks: target 1073741824: expected 1 to 1000");
}

TEST(Plot, DrawsSeriesInsideTheFrame) {
  Plot plot;
  plot.x_label = "x";
  PlotPanel panel;
  panel.y_label = "y";
  panel.y_min = 0.0;
  panel.y_max = 1.0;
  // A horizontal line at y = 0.5 across the whole range, and a value far out of range.
  panel.series.push_back({"half", {0.0, 10.0}, {0.5, 0.5}, Colour{1.0f, 0.0f, 0.0f}, 2.0});
  panel.series.push_back({"", {0.0, 10.0}, {5.0, 5.0}, Colour{0.0f, 0.0f, 1.0f}, 2.0});
  plot.panels.push_back(panel);
  Canvas c = render_plot(plot, 400, 300);
  int red = 0, blue = 0;
  for (int y = 0; y < c.height(); ++y) {
    for (int x = 0; x < c.width(); ++x) {
      Colour p = c.pixel(x, y);
      if (p.r > 0.9f && p.g < 0.2f && p.b < 0.2f) ++red;
      if (p.b > 0.9f && p.r < 0.2f && p.g < 0.2f) ++blue;
    }
  }
  EXPECT_GT(red, 200);  // the line (and its legend sample)
  EXPECT_EQ(blue, 0);   // clipped away entirely
}

TEST(Plot, LogTicks) {
  EXPECT_EQ(log_ticks(8.0, 128.0), (std::vector<double>{8.0, 16.0, 32.0, 64.0, 128.0}));
  EXPECT_EQ(log_ticks(6.0, 100.0), (std::vector<double>{8.0, 16.0, 32.0, 64.0}));
  EXPECT_EQ(log_ticks(1.0, 1e5), (std::vector<double>{1.0, 10.0, 100.0, 1000.0, 1e4, 1e5}));  // 16.6 octaves
  EXPECT_THROW(log_ticks(0.0, 10.0), Error);
  EXPECT_THROW(log_ticks(4.0, 4.0), Error);
}

// Mean column of the red pixels: where a vertical red line was drawn.
double red_column(const Canvas& c) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < c.height(); ++y)
    for (int x = 0; x < c.width(); ++x) {
      Colour p = c.pixel(x, y);
      if (p.r > 0.9f && p.g < 0.2f && p.b < 0.2f) sum += x, ++count;
    }
  return count > 0 ? sum / count : -1.0;
}

// On a log axis over [1, 16], x = 4 is half-way, where a linear axis puts 8.5; a dashed series
// leaves gaps (fewer pixels than the same line solid) but is drawn.
TEST(Plot, LogAxisAndDashedSeries) {
  auto vertical = [](bool log_x, double x) {
    Plot plot;
    plot.log_x = log_x;
    plot.x_min = 1.0, plot.x_max = 16.0;
    PlotPanel panel;
    panel.y_min = 0.0, panel.y_max = 1.0;
    panel.series.push_back({"", {x, x}, {0.0, 1.0}, Colour{1.0f, 0.0f, 0.0f}, 2.0});
    plot.panels.push_back(panel);
    return render_plot(plot, 400, 300);
  };
  const double log_at = red_column(vertical(true, 4.0)), linear_at = red_column(vertical(false, 8.5));
  ASSERT_GT(log_at, 0.0);
  EXPECT_NEAR(log_at, linear_at, 0.5);
  EXPECT_GT(std::abs(red_column(vertical(true, 8.5)) - linear_at), 40.0);

  auto horizontal = [](bool dashed) {
    Plot plot;
    PlotPanel panel;
    panel.y_min = 0.0, panel.y_max = 1.0;
    PlotSeries s{"", {0.0, 10.0}, {0.5, 0.5}, Colour{1.0f, 0.0f, 0.0f}, 2.0};
    s.dashed = dashed;
    panel.series.push_back(s);
    plot.panels.push_back(panel);
    Canvas c = render_plot(plot, 400, 300);
    int red = 0;
    for (int y = 0; y < c.height(); ++y)
      for (int x = 0; x < c.width(); ++x)
        if (Colour p = c.pixel(x, y); p.r > 0.9f && p.g < 0.2f && p.b < 0.2f) ++red;
    return red;
  };
  const int solid = horizontal(false), dashed = horizontal(true);
  EXPECT_GT(dashed, solid / 4);
  EXPECT_LT(dashed, solid * 3 / 4);
  Plot bad;
  bad.log_x = true;
  bad.x_min = 0.0, bad.x_max = 1.0;
  bad.panels.emplace_back();
  EXPECT_THROW(render_plot(bad, 100, 100), Error);
}

TEST(Figures, SpectrumToneMapAndOrientation) {
  Periodogram p;
  p.size = 4;
  p.power.assign(16, 1.0);
  p.power[static_cast<std::size_t>((1 + 2) * 4 + (0 + 2))] = 0.0;  // k = (0, 1): black, above the centre
  Canvas c = draw_spectrum(p, 1024, 4);
  ASSERT_EQ(c.width(), 4);
  // P = 1 maps to log2(2) / log2(3), in 8 bits (the same image goes into SVG and PDF).
  EXPECT_NEAR(c.pixel(0, 0).r, 1.0 / std::log2(3.0), 0.5 / 255.0);
  // Row ky = 1 is the second row from the top when ky points up (rows ky = 1, 0, -1, -2).
  EXPECT_FLOAT_EQ(c.pixel(2, 0).r, 0.0f);
}

// Periodic cells are drawn one period over where they cross an edge, and end at the frame: no
// cell outline outside the unit square, and outlines along all four sides inside it.
TEST(Figures, PeriodicCellsEndAtTheFrame) {
  PointsFigure figure;
  figure.points = test::uniform_points(300, 17);
  figure.cells = true;
  const int size = 400;
  const Canvas canvas = draw_points(figure, size);
  const Point low = points_figure_pixel({0.0, 1.0}, 0.0, 0.0, size), high = points_figure_pixel({1.0, 0.0}, 0.0, 0.0, size);
  auto bluish = [](Colour c) { return c.b > c.r + 0.1f; };  // the cells' outline colour, not grey or black
  int outside = 0, inside_near_frame = 0;
  for (int y = 0; y < canvas.height(); ++y)
    for (int x = 0; x < canvas.width(); ++x) {
      if (!bluish(canvas.pixel(x, y))) continue;
      const bool out = x < low.x - 1.0 || x > high.x + 1.0 || y < low.y - 1.0 || y > high.y + 1.0;
      outside += out;
      inside_near_frame += !out && (x < low.x + 3.0 || x > high.x - 3.0 || y < low.y + 3.0 || y > high.y - 3.0);
    }
  EXPECT_EQ(outside, 0);
  EXPECT_GT(inside_near_frame, 100);
}

}  // namespace
}  // namespace bluetile
