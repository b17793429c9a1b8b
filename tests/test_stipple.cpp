// bluetile stipple and relax --density-map as a user runs them: outputs, determinism, and bad
// images; and weighted Lloyd's point counts against a two-level density.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/core/torus.h"
#include "bluetile/io/density_map.h"
#include "bluetile/io/image.h"
#include "bluetile/io/image_file.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/density_sampling.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"
#include "xml_support.h"

namespace bluetile {
namespace {

using test::read_text;
using test::run_bluetile;
using test::TempDir;

// A grey picture, dark on the left and white on the right, with a black square in its top half.
std::string write_picture(const TempDir& dir, const std::string& name, int width, int height) {
  std::vector<float> grey(static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const bool square = x > width / 8 && x < width / 3 && y > height / 8 && y < height / 2;
      grey[static_cast<std::size_t>(y) * width + x] = square ? 0.0f : static_cast<float>(x) / static_cast<float>(width - 1);
    }
  write_image_file(dir.file(name), width, height, 1, grey, SampleFormat::uint8);
  return dir.file(name);
}

TEST(Stipple, DrawsThePictureIntoPointsSvgAndPng) {
  TempDir dir;
  const std::string picture = write_picture(dir, "picture.png", 64, 48);
  auto r = run_bluetile({"stipple", "--image", picture, "-n", "400", "-k", "8", "-o", dir.file("dots.txt"), "--svg",
                         dir.file("dots.svg"), "--png", dir.file("dots.png"), "--png-width", "256", "--log",
                         dir.file("log.csv")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PointSet dots = read_point_file(dir.file("dots.txt"));
  ASSERT_EQ(dots.points.size(), 400u);
  // The domain is the picture's 4:3 shape with its longer side 1; y is up.
  std::size_t left = 0, in_square = 0;
  auto is_left = [](Point p) { return p.x < 0.5; };
  auto is_in_square = [](Point p) { return p.x > 1.0 / 8 && p.x < 1.0 / 3 && p.y > 0.75 / 2 && p.y < 0.75 * 7 / 8; };
  for (const Point& p : dots.points) {
    EXPECT_GE(p.x, 0.0);
    EXPECT_LT(p.x, 1.0);
    EXPECT_GE(p.y, 0.0);
    EXPECT_LT(p.y, 0.75);
    left += is_left(p);
    in_square += is_in_square(p);
  }
  // Dark means dense: the share of dots in a region is its share of the map's mass (1 - linear
  // luminance, summed over its texels): measured 271 left for a share of 271.9, 49 in the black
  // square for 44.0 (the area shares would give 200 and 31).
  DensityTransfer dark_is_dense;
  dark_is_dense.invert = true;
  const DensityGrid map = load_density_map(picture, dark_is_dense);
  double mass = 0.0, mass_left = 0.0, mass_square = 0.0;
  for (int j = 0; j < map.height; ++j)
    for (int i = 0; i < map.width; ++i) {
      const Point centre{(i + 0.5) / map.width, 0.75 * (j + 0.5) / map.height};
      mass += map.at(i, j);
      mass_left += is_left(centre) ? map.at(i, j) : 0.0;
      mass_square += is_in_square(centre) ? map.at(i, j) : 0.0;
    }
  EXPECT_NEAR(static_cast<double>(left), 400 * mass_left / mass, 12.0);
  EXPECT_NEAR(static_cast<double>(in_square), 400 * mass_square / mass, 8.0);
  // The SVG: one disc per dot, y flipped to SVG's down (read back with expat).
  std::string error;
  auto svg = test::parse_xml(read_text(dir.file("dots.svg")), &error);
  ASSERT_TRUE(svg) << error;
  EXPECT_EQ(svg->attributes.at("viewBox"), "0 0 1 0.75");
  const auto circles = svg->find_all("circle");
  ASSERT_EQ(circles.size(), 400u);
  const auto group = svg->find_all("g");
  ASSERT_EQ(group.size(), 1u);
  EXPECT_EQ(group[0]->attributes.at("transform"), "matrix(1 0 0 -1 0 0.75)");
  EXPECT_NEAR(circles[7]->number("cx"), dots.points[7].x, 1e-6);
  EXPECT_NEAR(circles[7]->number("cy"), dots.points[7].y, 1e-6);
  const Canvas png = read_image(dir.file("dots.png"));
  EXPECT_EQ(png.width(), 256);
  EXPECT_EQ(png.height(), 192);
  const std::string log = read_text(dir.file("log.csv"));
  EXPECT_EQ(log.rfind("iteration,energy,max_displacement,mean_displacement,coincident,fallbacks,zero_density\n", 0), 0u);
  EXPECT_EQ(std::count(log.begin(), log.end(), '\n'), 9);
}

// For pen plotters: a printed size, one stroke per dot, the dots in pen order with the travel
// reported, and dot sizes following the tone.
double plane_distance(Point a, Point b) { return std::hypot(a.x - b.x, a.y - b.y); }

TEST(Stipple, PlotterReadySvg) {
  TempDir dir;
  const std::string picture = write_picture(dir, "picture.png", 64, 48);
  auto r = run_bluetile({"stipple", "--image", picture, "-n", "300", "-k", "4", "-o", dir.file("dots.txt"), "--svg",
                         dir.file("dots.svg"), "--size", "210mm", "--dot-shape", "stroke", "--plot-order",
                         "--dots-follow-density", "--dot-radius", "0.01"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PointSet dots = read_point_file(dir.file("dots.txt"));
  std::string error;
  auto svg = test::parse_xml(read_text(dir.file("dots.svg")), &error);
  ASSERT_TRUE(svg) << error;
  EXPECT_EQ(svg->attributes.at("width"), "210mm");
  EXPECT_EQ(svg->attributes.at("height"), "157.5mm");  // the picture's 4:3
  const auto strokes = svg->find_all("line");
  ASSERT_EQ(strokes.size(), 300u);
  EXPECT_TRUE(svg->find_all("circle").empty());
  // Each stroke is centred on a dot, every dot drawn once; the pen-up travel between strokes is
  // what stderr reports, in mm (210 mm per unit of the longer side).
  std::vector<bool> drawn(dots.points.size(), false);
  double travel = 0.0, widest = 0.0, narrowest = INFINITY;
  Point previous{};
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    const Point centre{0.5 * (strokes[k]->number("x1") + strokes[k]->number("x2")), strokes[k]->number("y1")};
    std::size_t nearest = 0;
    for (std::size_t i = 1; i < dots.points.size(); ++i)
      if (plane_distance(dots.points[i], centre) < plane_distance(dots.points[nearest], centre)) nearest = i;
    ASSERT_LT(plane_distance(dots.points[nearest], centre), 1e-6);
    EXPECT_FALSE(drawn[nearest]);
    drawn[nearest] = true;
    if (k > 0) travel += plane_distance(centre, previous);
    previous = centre;
    const double width = strokes[k]->number("stroke-width");
    widest = std::max(widest, width);
    narrowest = std::min(narrowest, width);
  }
  EXPECT_LE(widest, 0.01 + 1e-6);
  EXPECT_LT(narrowest, 0.6 * widest) << "dot sizes follow the tone";
  const std::string reported = "pen-up travel ";
  const auto at = r.err.find(reported);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_NEAR(std::stod(r.err.substr(at + reported.size())), 210.0 * travel, 1e-3 * 210.0 * travel) << r.err;
  // A length without a unit is refused before any work, and nothing is written.
  auto bad = run_bluetile({"stipple", "--image", picture, "-n", "300", "-o", dir.file("bad.txt"), "--svg",
                           dir.file("bad.svg"), "--size", "210"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--size 210: expected a positive length"), std::string::npos) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad.txt")));
}

TEST(Stipple, SameOutputWhateverTheThreadCount) {
  TempDir dir;
  const std::string picture = write_picture(dir, "picture.png", 40, 40);
  for (const char* threads : {"1", "2"}) {
    auto r = run_bluetile({"stipple", "--image", picture, "-n", "2000", "-k", "3", "--threads", threads, "-o",
                           dir.file(std::string("dots") + threads + ".txt")});
    ASSERT_EQ(r.exit_code, 0) << r.err;
  }
  EXPECT_EQ(read_text(dir.file("dots1.txt")), read_text(dir.file("dots2.txt")));
}

TEST(Stipple, InvertMeansDarkIsDenseAsInEveryCommand) {
  // --invert is density 1 - luminance in stipple as in relax and tile: stipple's default, so it
  // changes nothing; --no-invert is bright means dense.
  TempDir dir;
  std::string picture = write_picture(dir, "picture.png", 32, 32);
  auto stipple = [&](const std::string& name, std::vector<std::string> extra) {
    std::vector<std::string> args = {"stipple", "--image", picture, "-n", "300", "-k", "2", "-o", dir.file(name)};
    args.insert(args.end(), extra.begin(), extra.end());
    auto r = run_bluetile(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_text(dir.file(name));
  };
  const std::string plain = stipple("plain.txt", {}), inverted = stipple("inverted.txt", {"--invert"});
  const std::string bright = stipple("bright.txt", {"--no-invert"});
  EXPECT_EQ(plain, inverted);
  std::size_t right_dark = 0, right_bright = 0;  // the picture's right half is the bright one
  for (const Point& p : read_point_file(dir.file("plain.txt")).points) right_dark += p.x >= 0.5;
  for (const Point& p : read_point_file(dir.file("bright.txt")).points) right_bright += p.x >= 0.5;
  EXPECT_LT(right_dark, 130u);  // about 95: 1 - luminance, sRGB-decoded, is 0.44 on the right, 0.95 on the left
  EXPECT_GT(right_bright, 200u);
}

TEST(Stipple, BadImagesGiveOneClearLineAndNoOutput) {
  TempDir dir;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  write_image_file(dir.file("nan.exr"), 2, 2, 1, {1.0f, nan, 1.0f, 1.0f}, SampleFormat::float32);
  write_image_file(dir.file("white.png"), 4, 4, 1, std::vector<float>(16, 1.0f), SampleFormat::uint8);
  dir.write("garbage.png", "not a picture");
  struct Case {
    std::string image, message;
  };
  for (const Case& c : {Case{"nan.exr", "pixel (1, 0) (column, row from the top) channel 0 is nan"},
                        Case{"white.png", "the density is zero everywhere"},
                        Case{"garbage.png", "cannot read image"}}) {
    auto r = run_bluetile({"stipple", "--image", dir.file(c.image), "-n", "10", "-o", dir.file("out.txt"), "--svg",
                           dir.file("out.svg")});
    EXPECT_NE(r.exit_code, 0) << c.image;
    EXPECT_EQ(r.err.rfind("bluetile: " + dir.file(c.image) + ": ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  for (const std::string& name : dir.list()) EXPECT_EQ(name.rfind("out", 0), std::string::npos) << name;
  // The same loader behind relax --density-map.
  auto r = run_bluetile({"relax", "-n", "10", "--density-map", dir.file("nan.exr"), "--engine", "exact", "-o",
                         dir.file("out.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("channel 0 is nan"), std::string::npos) << r.err;
}

TEST(Stipple, AnImageFromStandardInputIsTheImageOfItsFile) {
  // `convert photo.jpg -resize 50% png:- | bluetile stipple --image -` was "--image: File does not
  // exist: -"; standard input is read once, its format found from its bytes.
  TempDir dir;
  std::vector<float> ramp(24 * 16);
  for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<float>(i % 24) / 23.0f;
  write_image_file(dir.file("ramp.png"), 24, 16, 1, ramp, SampleFormat::uint8);
  auto from_file = run_bluetile({"stipple", "--image", dir.file("ramp.png"), "-n", "60", "-k", "3", "-o", dir.file("file.txt")});
  ASSERT_EQ(from_file.exit_code, 0) << from_file.err;
  // The tool with `arguments` and the PNG on its standard input.
  auto piped = [&](const std::string& arguments) {
    return test::run_command("sh -c '\"$0\" " + arguments + " < \"$1\"' '" BLUETILE_BINARY "' '" + dir.file("ramp.png") + "'");
  };
  auto stippled = piped("stipple --image - -n 60 -k 3 -o \"" + dir.file("pipe.txt") + "\"");
  ASSERT_EQ(stippled.exit_code, 0) << stippled.err;
  auto points = [](const std::string& text) { return text.substr(text.find('\n')); };  // past the provenance line
  EXPECT_EQ(points(read_text(dir.file("pipe.txt"))), points(read_text(dir.file("file.txt"))));
  EXPECT_NE(read_text(dir.file("pipe.txt")).find(", image - ("), std::string::npos) << read_text(dir.file("pipe.txt"));
  auto relaxed = piped("relax -n 30 -k 2 --density-map - -o \"" + dir.file("r.txt") + "\"");
  EXPECT_EQ(relaxed.exit_code, 0) << relaxed.err;
  // Two readers of standard input: the second would find it empty.
  auto twice = piped("relax -i - --density-map - -o \"" + dir.file("t.txt") + "\"");
  EXPECT_EQ(twice.exit_code, 1);
  EXPECT_EQ(twice.err,
            "bluetile: -: --input and --density-map both read standard input, which can be read once: give one of "
            "them a file\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("t.txt")));
  // A missing image is said as for every other input (it was CLI11's "File does not exist").
  auto missing = run_bluetile({"stipple", "--image", dir.file("nope.png"), "-n", "10", "-o", dir.file("m.txt")});
  EXPECT_EQ(missing.exit_code, 1);
  EXPECT_EQ(missing.err, "bluetile: " + dir.file("nope.png") + ": cannot open: No such file or directory\n");
}

TEST(Stipple, RelaxFollowsADensityMapPeriodicOrBounded) {
  TempDir dir;
  // Bright means dense for relax: the right half of this map is dense.
  std::vector<float> map(32 * 32);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) map[static_cast<std::size_t>(y) * 32 + x] = x < 16 ? 0.1f : 1.0f;
  write_image_file(dir.file("map.png"), 32, 32, 1, map, SampleFormat::uint8);
  for (const char* bounded : {"", "--bounded"}) {
    std::vector<std::string> args = {"relax", "-n", "500", "-k", "10", "--engine", "exact", "--density-map",
                                     dir.file("map.png"), "--transfer", "linear", "-o", dir.file("p.txt")};
    if (*bounded) args.push_back(bounded);
    auto r = run_bluetile(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::size_t right = 0;
    for (const Point& p : read_point_file(dir.file("p.txt")).points) right += p.x >= 0.5;
    EXPECT_GT(right, 330u) << bounded;  // 10x the density: well over 2/3 of the points
    EXPECT_NE(read_text(dir.file("p.txt")).find("density map"), std::string::npos);
  }
  // Without --engine the exact engine relaxes toward a map (the faster one on a CPU device).
  auto plain = run_bluetile({"relax", "-n", "50", "-k", "2", "--density-map", dir.file("map.png"), "-o", dir.file("e.txt")});
  EXPECT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_NE(read_text(dir.file("e.txt")).find("engine exact"), std::string::npos);
  // --invert turns it around.
  auto r = run_bluetile({"relax", "-n", "500", "-k", "5", "--engine", "exact", "--density-map", dir.file("map.png"),
                         "--invert", "-o", dir.file("q.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t right = 0;
  for (const Point& p : read_point_file(dir.file("q.txt")).points) right += p.x >= 0.5;
  EXPECT_LT(right, 100u);
}

}  // namespace
}  // namespace bluetile
