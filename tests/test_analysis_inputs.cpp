// What `bluetile analyze` reads and writes beside its measures: every point format the tool
// writes (npy, bpt, text), CSV and psa's .rps, chosen by extension, with the same statistics as
// the text of the same points; per-set tables of multi-set files; --domain; --psa-points; the
// output folder's parent.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/bond_order.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/core/point_table.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::read_text;
using test::run_bluetile;
using test::TempDir;

std::string table_bytes(TableFormat format, const std::vector<PointSet>& sets) {
  std::string bytes;
  write_point_table(format, sets, {}, "t", [&](std::string_view piece) { bytes.append(piece); });
  return bytes;
}

nlohmann::json analyze(const std::vector<std::string>& extra, const std::string& out) {
  std::vector<std::string> args = {"analyze", "-o", out, "--no-centroids"};
  args.insert(args.end(), extra.begin(), extra.end());
  auto r = run_bluetile(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  if (r.exit_code != 0) return nullptr;
  return nlohmann::json::parse(read_text(out + "/stats.json"));
}

void expect_same_measures(const nlohmann::json& a, const nlohmann::json& b, const std::string& what) {
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  for (const char* key : {"n", "nn_min", "nn_max", "nn_mean", "rho", "average_min_distance", "nu_eff", "omega"})
    EXPECT_EQ(a[key], b[key]) << what << ": " << key;
  EXPECT_EQ(a["radial"]["power"], b["radial"]["power"]) << what;
}

TEST(AnalyzeInputs, EveryFormatGivesTheStatisticsOfItsText) {
  TempDir dir;
  const PointSet set{test::uniform_points(200, 11), {}, {}};
  const std::string text = dir.write("p.txt", table_bytes(TableFormat::text, {set}));
  const nlohmann::json reference = analyze({"-i", text}, dir.file("text"));
  expect_same_measures(analyze({"-i", dir.write("p.npy", table_bytes(TableFormat::npy, {set}))}, dir.file("npy")),
                       reference, "npy");
  expect_same_measures(analyze({"-i", dir.write("p.BPT", table_bytes(TableFormat::binary, {set}))}, dir.file("bpt")),
                       reference, "bpt");
  std::string csv = "x,y\n";
  char line[80];
  for (const Point& p : set.points) {
    std::snprintf(line, sizeof line, "%.17g, %.17g\n", p.x, p.y);
    csv += line;
  }
  expect_same_measures(analyze({"-i", dir.write("p.csv", csv)}, dir.file("csv")), reference, "csv");

  // psa's .rps holds float32: the same statistics as the text of the rounded points.
  std::string rps;
  PointSet rounded;
  for (const Point& p : set.points) {
    const float xy[2] = {static_cast<float>(p.x), static_cast<float>(p.y)};
    static_assert(std::endian::native == std::endian::little);
    rps.append(reinterpret_cast<const char*>(xy), sizeof xy);
  }
  for (std::size_t i = 0; i < set.points.size(); ++i) {
    float xy[2];
    std::memcpy(xy, rps.data() + 8 * i, sizeof xy);
    rounded.points.push_back(Point(xy[0], xy[1]));
  }
  const nlohmann::json rounded_stats =
      analyze({"-i", dir.write("r.txt", table_bytes(TableFormat::text, {rounded}))}, dir.file("rounded"));
  expect_same_measures(analyze({"-i", dir.write("p.rps", rps), "--psa-points", dir.file("rps.psa")}, dir.file("rps")),
                       rounded_stats, "rps");
  EXPECT_EQ(read_point_file(dir.file("rps.psa")).points, rounded.points);
}

TEST(AnalyzeInputs, DamagedInputsNameTheFileLineAndValue) {
  TempDir dir;
  auto error = [&](const std::string& name, const std::string& contents, std::vector<std::string> more = {}) {
    std::vector<std::string> args = {"analyze", "-i", dir.write(name, contents), "-o", dir.file("out")};
    args.insert(args.end(), more.begin(), more.end());
    auto r = run_bluetile(args);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
    return r.err;
  };
  EXPECT_NE(error("a.csv", "x,y\n0.1,0.2\n0.3,\n").find("a.csv:3: an empty field, got '0.3,'"), std::string::npos);
  EXPECT_NE(error("b.csv", "x,y\n0.1,0.2\n0.3,abc\n").find("b.csv:3: not a number 'abc'"), std::string::npos);
  EXPECT_NE(error("c.csv", "x,y\n0.1,0.2\n0.3 0.4\n").find("c.csv:3: expected 'x,y' or 'x,y,level'"), std::string::npos);
  EXPECT_NE(error("d.csv", "x,y\n0.1,0.2\n0.3,1.5\n").find("d.csv:3: y = 1.5 is outside [0, 1)"), std::string::npos);
  // A text file is text whatever it holds; a .npy must be one.
  EXPECT_NE(error("e.npy", "0.1 0.2\n0.3 0.4\n").find("e.npy: not a .npy file"), std::string::npos);
  PointSet far{{{0.5, 0.5}, {0.25, 0.75}}, {}, {}};
  const std::string npy = table_bytes(TableFormat::npy, {far});
  EXPECT_NE(error("f.npy", npy, {"--domain", "0", "0", "0.5", "1"}).find("f.npy: set 0, point 0: x = 0.5 is outside [0, 0.5)"),
            std::string::npos);
  EXPECT_NE(error("g.txt", "1 2\n3 4\n70 5\n", {"--domain", "0", "0", "64", "64"}).find("g.txt:3: x = 70 is outside [0, 64)"),
            std::string::npos);
  EXPECT_NE(error("h.txt", "1 2\n", {"--domain", "0", "0", "-1", "64"}).find("--domain: X1 = -1 must be greater than X0 = 0"),
            std::string::npos);
}

TEST(AnalyzeInputs, DomainRescalesOntoTheUnitTorus) {
  TempDir dir;
  // Points on a grid of 2^-30 placed in [-3, 61) x [10, 74): every value, written and rescaled,
  // is exact, so the measures are the same bits.
  PointSet set;
  for (const Point& p : test::uniform_points(150, 5))
    set.points.push_back({std::floor(p.x * 0x1p30) * 0x1p-30, std::floor(p.y * 0x1p30) * 0x1p-30});
  std::string text;
  char line[80];
  for (const Point& p : set.points) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", -3.0 + 64.0 * p.x, 10.0 + 64.0 * p.y);
    text += line;
  }
  const nlohmann::json unit = analyze({"-i", dir.write("u.txt", table_bytes(TableFormat::text, {set}))}, dir.file("u"));
  const nlohmann::json scaled =
      analyze({"-i", dir.write("s.txt", text), "--domain", "-3", "10", "61", "74", "--psa-points", dir.file("s.psa")},
              dir.file("s"));
  ASSERT_FALSE(unit.is_null());
  ASSERT_FALSE(scaled.is_null());
  expect_same_measures(scaled, unit, "--domain");
  // psa's text: the count line, then the rescaled points, read back as they were analysed.
  const std::string psa = read_text(dir.file("s.psa"));
  EXPECT_EQ(psa.substr(0, 4), "150\n");
  EXPECT_EQ(read_point_file(dir.file("s.psa")).points, set.points);
}

TEST(AnalyzeInputs, MultiSetFilesGetAPerSetTable) {
  TempDir dir;
  std::vector<PointSet> sets;
  for (std::uint64_t seed : {21, 22, 23}) sets.push_back({test::uniform_points(120, seed), {}, {}});
  const std::string npy = dir.write("three.npy", table_bytes(TableFormat::npy, sets));
  auto r = run_bluetile({"analyze", "-i", npy, "-o", dir.file("a"), "--average", "--no-centroids", "--psa-points",
                         dir.file("set{}.txt")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = nlohmann::json::parse(read_text(dir.file("a/stats.json")));
  const auto& per_set = stats["per_set"];
  ASSERT_EQ(per_set["rho"].size(), 3u);
  for (std::size_t k = 0; k < sets.size(); ++k) {
    const NearestNeighbourStats nn = nearest_neighbour_stats(sets[k].points);
    EXPECT_DOUBLE_EQ(per_set["rho"][k].get<double>(), nn.rho()) << k;
    EXPECT_DOUBLE_EQ(per_set["average_min_distance"][k].get<double>(), nn.rho_mean()) << k;
    EXPECT_DOUBLE_EQ(per_set["bond_order_local"][k].get<double>(), bond_orientational_order(sets[k].points).local) << k;
    EXPECT_TRUE(per_set["nu_eff"][k].is_number());
    EXPECT_TRUE(per_set["omega"][k].is_number());
    // The table on stdout: the set's row with the same numbers.
    char row[160];
    std::snprintf(row, sizeof row, "  %-8zu %8d %8.4f %8.4f", k, 120, nn.rho(), nn.rho_mean());
    EXPECT_NE(r.out.find(row), std::string::npos) << row << "\n" << r.out;
    const PointSet back = read_point_file(dir.file("set" + std::to_string(k) + ".txt"));
    EXPECT_EQ(back.points, sets[k].points);
  }
  EXPECT_NE(r.out.find("three, per set:\n  set             N      rho  avg min   nu_eff    Omega     psi6\n"),
            std::string::npos)
      << r.out;
  // The mean of the per-set minima is the series' rho.
  EXPECT_NEAR((per_set["rho"][0].get<double>() + per_set["rho"][1].get<double>() + per_set["rho"][2].get<double>()) / 3,
              stats["rho"].get<double>(), 1e-12);
  // psa reads one set a file: several sets need {} in the name.
  r = run_bluetile({"analyze", "-i", npy, "-o", dir.file("b"), "--average", "--psa-points", dir.file("all.txt")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("put {} in the name"), std::string::npos) << r.err;
}

TEST(AnalyzeInputs, OutputCreatesOnlyTheLastFolder) {
  TempDir dir;
  const std::string input = dir.write("p.txt", table_bytes(TableFormat::text, {PointSet{test::uniform_points(64, 3), {}, {}}}));
  auto r = run_bluetile({"analyze", "-i", input, "-o", dir.file("typo/b/c"), "--no-centroids"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(dir.file("typo/b/c") + ": the folder '" + dir.file("typo/b") + "' does not exist"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("typo")));
  r = run_bluetile({"analyze", "-i", input, "-o", dir.file("typo/"), "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = run_bluetile({"analyze", "-i", input, "-o", dir.file("typo/b/"), "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.file("typo/b/stats.json")));
}

}  // namespace
}  // namespace bluetile
