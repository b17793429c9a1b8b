// What `bluetile analyze` writes beyond the numbers: SVG that parses and holds the drawn points
// and curve vertices, a one-page PDF, normalised and integer axes over the same data, bounded
// sets measured with Euclidean distances, out-of-range points refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <thread>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/nearest_neighbour.h"
#include "test_support.h"
#include "xml_support.h"

namespace bluetile {
namespace {

using test::uniform_points;

std::string points_text(const std::vector<Point>& points, const std::string& header = "") {
  std::string text = header;
  char line[80];
  for (const Point& p : points) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", p.x, p.y);
    text += line;
  }
  return text;
}

std::unique_ptr<test::XmlElement> parse_file(const std::string& path) {
  std::string error;
  auto root = test::parse_xml(test::read_text(path), &error);
  EXPECT_TRUE(root) << path << ": " << error;
  return root;
}

std::size_t vertices(const test::XmlElement& polyline) {
  const std::string& points = polyline.attributes.at("points");
  return points.empty() ? 0 : static_cast<std::size_t>(std::count(points.begin(), points.end(), ' ')) + 1;
}

std::vector<double> coordinates(const test::XmlElement& polyline, int axis) {
  std::vector<double> values;
  std::istringstream in(polyline.attributes.at("points"));
  std::string pair;
  while (in >> pair) {
    const auto comma = pair.find(',');
    values.push_back(std::stod(axis == 0 ? pair.substr(0, comma) : pair.substr(comma + 1)));
  }
  return values;
}

TEST(AnalyzeOutputs, SvgHoldsThePointsAndCurvesAndThePdfHasOnePage) {
  test::TempDir dir;
  // A 10 x 10 lattice away from the edges: exactly one mark per point (no periodic copies).
  std::vector<Point> lattice;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 10; ++i) lattice.push_back({(i + 0.5) / 10, (j + 0.5) / 10});
  const std::string grid = dir.write("grid.txt", points_text(lattice));
  auto r = test::run_bluetile({"analyze", "-i", grid, "-o", dir.file("g"), "--summary", dir.file("g.pdf")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto points = parse_file(dir.file("g/points.svg"));
  ASSERT_TRUE(points);
  EXPECT_EQ(points->find_all("circle").size(), 100u);
  // The same input gives the same bytes: cairo's clock-time creation date is left out.
  const std::string first = test::read_text(dir.file("g.pdf"));
  EXPECT_EQ(first.find("/CreationDate"), std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // PDF dates count seconds
  r = test::run_bluetile({"analyze", "-i", grid, "-o", dir.file("g2"), "--summary", dir.file("g2.pdf")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(first == test::read_text(dir.file("g2.pdf")));
  auto pdfinfo = test::run_command("pdfinfo '" + dir.file("g.pdf") + "'");
  if (pdfinfo.exit_code == 127) GTEST_SKIP() << "pdfinfo (poppler-utils) is not installed; ./setup.sh installs it";
  EXPECT_EQ(pdfinfo.exit_code, 0) << pdfinfo.err;
  EXPECT_NE(pdfinfo.out.find("Pages:           1\n"), std::string::npos) << pdfinfo.out;
  EXPECT_NE(pdfinfo.out.find("595 x 842 pts (A4)"), std::string::npos) << pdfinfo.out;

  // White noise: every annulus finite and inside the axes, so each curve is one polyline with
  // a vertex per annulus but the first (k = 0).
  const std::string noise = dir.write("noise.txt", points_text(uniform_points(256, 3)));
  r = test::run_bluetile({"analyze", "-i", noise, "-o", dir.file("n"), "--no-centroids", "--summary", dir.file("n.svg")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto radial = parse_file(dir.file("n/radial.svg"));
  ASSERT_TRUE(radial);
  auto curves = radial->find_all("polyline");
  ASSERT_EQ(curves.size(), 2u);  // radial power, anisotropy
  EXPECT_EQ(vertices(*curves[0]), 80u - 1u);  // F = 2 floor(5 sqrt(256)) = 160: 80 annuli
  EXPECT_EQ(vertices(*curves[1]), 80u - 1u);
  auto rdf = parse_file(dir.file("n/rdf.svg"));
  ASSERT_TRUE(rdf);
  ASSERT_EQ(rdf->find_all("polyline").size(), 1u);
  EXPECT_EQ(vertices(*rdf->find_all("polyline")[0]), 32u);  // N / 8 = 32 bins
  auto page = parse_file(dir.file("n.svg"));
  ASSERT_TRUE(page);
  EXPECT_EQ(page->attributes.at("width"), "595pt");
  EXPECT_EQ(page->find_all("polyline").size(), 3u);  // radial power, anisotropy, RDF
  EXPECT_EQ(page->find_all("image").size(), 1u);     // the periodogram
  bool table = false;
  for (const auto* text : page->find_all("text")) table |= text->text == "effective Nyquist frequency nu_eff";
  EXPECT_TRUE(table);

  // The same data on the integer axis: the same curve, x scaled by sqrt(N) / 2 = 8.
  r = test::run_bluetile({"analyze", "-i", noise, "-o", dir.file("k"), "--no-centroids", "--axis", "integer"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto integer = parse_file(dir.file("k/radial.svg"));
  ASSERT_TRUE(integer);
  auto integer_curves = integer->find_all("polyline");
  ASSERT_EQ(integer_curves.size(), 2u);
  EXPECT_EQ(coordinates(*integer_curves[0], 1), coordinates(*curves[0], 1));
  // Both axes span the data (x from 0 to the last annulus): the pixel positions coincide.
  EXPECT_EQ(coordinates(*integer_curves[0], 0), coordinates(*curves[0], 0));
  EXPECT_NE(test::read_text(dir.file("k/radial.svg")).find("integer frequencies"), std::string::npos);

  r = test::run_bluetile({"analyze", "-i", noise, "-o", dir.file("bad"), "--summary", dir.file("s.png")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("this output writes .pdf (PDF), .svg (SVG), not '.png'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad")));
}

TEST(AnalyzeOutputs, BoundedSetsUseEuclideanDistancesAndOutOfRangeIsRefused) {
  test::TempDir dir;
  // Two clusters at opposite edges: 0.02 apart across the edge on the torus, 0.96 in the square.
  std::vector<Point> points = {{0.01, 0.5}, {0.99, 0.5}, {0.5, 0.2}, {0.5, 0.6}};
  const std::string plain = dir.write("plain.txt", points_text(points));
  const std::string declared = dir.write("declared.txt", points_text(points, "# domain bounded\n"));
  auto periodic = test::run_bluetile({"analyze", "-i", plain, "-o", dir.file("p")});
  ASSERT_EQ(periodic.exit_code, 0) << periodic.err;
  auto stats = nlohmann::json::parse(test::read_text(dir.file("p/stats.json")));
  EXPECT_NEAR(stats["nn_min"].get<double>(), 0.02, 1e-12);
  for (const std::vector<std::string>& args : {std::vector<std::string>{"analyze", "-i", plain, "-o", dir.file("b"), "--bounded"},
                                               std::vector<std::string>{"analyze", "-i", declared, "-o", dir.file("b")}}) {
    auto r = test::run_bluetile(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    stats = nlohmann::json::parse(test::read_text(dir.file("b/stats.json")));
    EXPECT_EQ(stats["boundary"], "bounded");
    const auto nn = nearest_neighbour_stats(points, Domain{}, Boundary::bounded);
    EXPECT_DOUBLE_EQ(stats["nn_min"].get<double>(), nn.min);  // 0.4: (0.5, 0.2) to (0.5, 0.6)
    EXPECT_NEAR(nn.min, 0.4, 1e-12);
    EXPECT_FALSE(stats.contains("bond_order"));  // periodic cells: not for a bounded set
    EXPECT_TRUE(stats["nu_eff"].is_null());      // psa's measures use torus distances
    EXPECT_TRUE(stats["omega"].is_null());
    EXPECT_NE(r.out.find("\t-\t-\n"), std::string::npos) << r.out;  // psa's table row
  }
  EXPECT_TRUE(nlohmann::json::parse(test::read_text(dir.file("p/stats.json")))["nu_eff"].is_number());
  auto r = test::run_bluetile({"analyze", "-i", declared, "-o", dir.file("c"), "--cells"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--cells"), std::string::npos) << r.err;

  const std::string outside = dir.write("outside.txt", "0.25 0.5\n0.5 1.5\n0.75 0.25\n");
  r = test::run_bluetile({"analyze", "-i", outside, "-o", dir.file("o")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("outside.txt:2: y = 1.5 is outside [0, 1)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--wrap"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("o")));
  r = test::run_bluetile({"analyze", "-i", outside, "-o", dir.file("o"), "--wrap"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(AnalyzeOutputs, MultiSetFilesSayWhatTheirPointsImageShows) {
  test::TempDir dir;
  const std::string two = dir.write("two.txt", "# set 0\n" + points_text(uniform_points(64, 1)) + "# set 1\n" +
                                                   points_text(uniform_points(64, 2)));
  auto r = test::run_bluetile({"analyze", "-i", two, "-o", dir.file("a"), "--average", "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("show the first of the 2 sets"), std::string::npos) << r.out;
  auto svg = parse_file(dir.file("a/points.svg"));
  ASSERT_TRUE(svg);
  bool note = false;
  for (const auto* text : svg->find_all("text")) note |= text->text.find("set 1 of 2") != std::string::npos;
  EXPECT_TRUE(note);
}

// An undefined number in a CSV is an empty field, CSV's missing value, as stats.json writes null:
// radial.csv's annulus 0 holds the one frequency k = 0, whose anisotropy has no variance (the row
// was "0,N,nan,0"). No CSV holds "nan" or "inf".
TEST(AnalyzeOutputs, CsvLeavesUndefinedValuesEmpty) {
  test::TempDir dir;
  const std::string a = dir.write("a.txt", points_text(uniform_points(40, 7)));
  const std::string b = dir.write("b.txt", points_text(uniform_points(50, 8)));
  auto r = test::run_bluetile({"analyze", "-i", a, "-o", dir.file("one"), "--no-discrepancy", "--image-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string radial = test::read_text(dir.file("one/radial.csv"));
  EXPECT_EQ(radial.substr(0, radial.find('\n', radial.find('\n') + 1)), "frequency,power,anisotropy_db,nu\n0,40,,0");
  const auto stats = nlohmann::json::parse(test::read_text(dir.file("one/stats.json")));
  EXPECT_TRUE(stats["radial"]["anisotropy_db"][0].is_null());
  EXPECT_FALSE(stats["radial"]["anisotropy_db"][1].is_null());
  r = test::run_bluetile({"analyze", "-i", a, b, "-o", dir.file("cmp"), "--compare", "--no-discrepancy", "--image-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string labelled = test::read_text(dir.file("cmp/radial.csv"));
  EXPECT_NE(labelled.find("\n0,40,,0,a\n"), std::string::npos) << labelled.substr(0, 200);
  EXPECT_NE(labelled.find("\n0,50,,0,b\n"), std::string::npos);
  for (const char* file : {"one/radial.csv", "one/rdf.csv", "cmp/radial.csv", "cmp/rdf.csv"}) {
    const std::string text = test::read_text(dir.file(file));
    EXPECT_EQ(text.find("nan"), std::string::npos) << file;
    EXPECT_EQ(text.find("inf"), std::string::npos) << file;
  }
}

TEST(AnalyzeOutputs, CompareSummaryShowsEverySeries) {
  test::TempDir dir;
  const std::string a = dir.write("a.txt", points_text(uniform_points(128, 41)));
  const std::string b = dir.write("b.txt", points_text(uniform_points(200, 42)));
  auto r = test::run_bluetile({"analyze", "-i", a, b, "--compare", "--label", "alpha", "--label", "beta", "-o",
                               dir.file("c"), "--no-centroids", "--summary", dir.file("c.svg")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = nlohmann::json::parse(test::read_text(dir.file("c/stats.json")));
  auto page = parse_file(dir.file("c.svg"));
  ASSERT_TRUE(page);
  std::vector<std::string> texts;
  for (const auto* text : page->find_all("text")) texts.push_back(text->text);
  auto has = [&](const std::string& t) { return std::find(texts.begin(), texts.end(), t) != texts.end(); };
  // Each series: its points and periodogram (captioned), and its row of the table with its numbers.
  EXPECT_EQ(page->find_all("image").size(), 2u);  // one periodogram per series
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& s = stats["compare"][i];
    const std::string label = s["label"];
    SCOPED_TRACE(label);
    EXPECT_TRUE(has(label + ", F = " + std::to_string(s["periodogram_size"].get<int>())));
    char number[32];
    std::snprintf(number, sizeof number, "%.4f", s["rho"].get<double>());
    EXPECT_TRUE(has(number)) << number;
    std::snprintf(number, sizeof number, "%.4f", s["average_min_distance"].get<double>());
    EXPECT_TRUE(has(number)) << number;
    std::snprintf(number, sizeof number, "%.3f", s["nu_eff"].get<double>());
    EXPECT_TRUE(has(number)) << number;
    std::snprintf(number, sizeof number, "%.3f", s["bond_order"]["local"].get<double>());
    EXPECT_TRUE(has(number)) << number;
    EXPECT_TRUE(has(std::to_string(s["n"].get<int>())));
  }
  EXPECT_TRUE(has("psi6"));
  EXPECT_FALSE(has("effective Nyquist frequency nu_eff"));  // not one series' name-value list

  // The PDF holds the same words.
  r = test::run_bluetile({"analyze", "-i", a, b, "--compare", "--label", "alpha", "--label", "beta", "-o",
                          dir.file("p"), "--no-centroids", "--summary", dir.file("c.pdf")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto text = test::run_command("pdftotext '" + dir.file("c.pdf") + "' -");
  if (text.exit_code == 127) GTEST_SKIP() << "pdftotext (poppler-utils) is not installed; ./setup.sh installs it";
  ASSERT_EQ(text.exit_code, 0) << text.err;
  for (const char* word : {"alpha", "beta", "psi6"}) EXPECT_NE(text.out.find(word), std::string::npos) << text.out;
}

}  // namespace
}  // namespace bluetile
