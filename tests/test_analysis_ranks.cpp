// analyze --by-rank: the prefixes of a set whose rows are in rank order, on a hand-made file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace bluetile {
namespace {

// tests/data/ranks_square.txt: the first 4 rows a square of side 1/2, the first 8 a 4 x 2 lattice,
// all 16 the 4 x 4 lattice with one point moved by (1/8, 0).
TEST(AnalyzeByRank, PrefixesOfAHandMadeRankedSet) {
  test::TempDir dir;
  const std::string ranked = BLUETILE_TEST_DATA "/ranks_square.txt";
  auto r = test::run_bluetile({"analyze", "-i", ranked, "-o", dir.file("ranks"), "--by-rank", "4", "1/2", "1/1",
                               "--image-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(test::read_text(dir.file("ranks/stats.json")));
  EXPECT_EQ(stats["mode"], "by-rank");
  ASSERT_EQ(stats["ranks"].size(), 3u);
  const double nn_min[] = {0.5, 0.25, 0.125};
  const std::size_t counts[] = {4, 8, 16};
  // LF: no frequency with 0 < |f|^2 < 1 for 4 points, so no mean: null (it was 0, which reads as
  // perfect blue noise); the 4 x 2 lattice sums to 0 at (1, 0) and (0, 1), a true 0; with 16
  // points only the moved one is left at 0 < |f|^2 < 4: |exp(-2 pi i f.d) - 1|^2 = 2 - sqrt(2) at
  // the 6 frequencies with f.d = +-1/8, 0 at (0, +-1): 6 (2 - sqrt(2)) / 8 / 16.
  EXPECT_TRUE(stats["ranks"][0]["low_frequency"].is_null()) << stats["ranks"][0]["low_frequency"];
  const double low_frequency[] = {0.0, 0.0, 3.0 * (2.0 - std::sqrt(2.0)) / 64.0};
  for (std::size_t i = 0; i < 3; ++i) {
    const nlohmann::json& p = stats["ranks"][i];
    EXPECT_EQ(p["rank_prefix"], counts[i]);
    EXPECT_EQ(p["n"], counts[i]);
    EXPECT_NEAR(p["nn_min"].get<double>(), nn_min[i], 1e-15) << counts[i];
    if (i > 0) {
      EXPECT_NEAR(p["low_frequency"].get<double>(), low_frequency[i], 1e-12) << counts[i];
    }
  }
  // The table shows the undefined LF as "-" and says why; never "nan".
  EXPECT_NE(r.out.find("\nfirst 4        0.2500   0.9306        -   0.9306 "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("LF \"-\": k <= 4, whose band holds no frequency (null in stats.json)\n"), std::string::npos)
      << r.out;
  EXPECT_EQ(r.out.find("nan"), std::string::npos) << r.out;
  EXPECT_EQ(stats["n"], 16);  // the top level describes the largest prefix
  EXPECT_NE(r.out.find("first 8"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.0275"), std::string::npos) << r.out;  // LF of all 16 in the table
  EXPECT_TRUE(std::filesystem::exists(dir.file("ranks/points.png")));
}

// Several sets: the mean over their prefixes. The hand-made set, then the same rows with the moved
// point back on the lattice (all 16: nn_min 1/4, LF 0).
TEST(AnalyzeByRank, SeveralSetsGiveTheMeanOfTheirPrefixes) {
  test::TempDir dir;
  std::string text = test::read_text(BLUETILE_TEST_DATA "/ranks_square.txt") + "#\n";
  const std::string moved = "0.375 0.25\n";
  std::string second = test::read_text(BLUETILE_TEST_DATA "/ranks_square.txt");
  second.replace(second.find(moved), moved.size(), "0.25 0.25\n");
  const std::string both = dir.write("both.txt", text + second.substr(second.find("\n0 0\n") + 1));
  auto r = test::run_bluetile({"analyze", "-i", both, "-o", dir.file("ranks"), "--by-rank", "1/2", "1/1", "--image-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(test::read_text(dir.file("ranks/stats.json")));
  ASSERT_EQ(stats["ranks"].size(), 2u);
  EXPECT_EQ(stats["ranks"][1]["sets"], 2);
  EXPECT_NEAR(stats["ranks"][0]["nn_min"].get<double>(), 0.25, 1e-15);
  EXPECT_NEAR(stats["ranks"][1]["nn_min"].get<double>(), (0.125 + 0.25) / 2.0, 1e-15);
  EXPECT_NEAR(stats["ranks"][1]["low_frequency"].get<double>(), 3.0 * (2.0 - std::sqrt(2.0)) / 128.0, 1e-12);
  // Sets of different sizes are refused.
  const std::string uneven = dir.write("uneven.txt", text + "0.1 0.1\n0.6 0.6\n");
  r = test::run_bluetile({"analyze", "-i", uneven, "-o", dir.file("uneven"), "--by-rank", "2"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("set 1 has 2 points and the first 16"), std::string::npos) << r.err;
}

TEST(AnalyzeByRank, BadPrefixesAreRefusedBeforeAnyOutput) {
  test::TempDir dir;
  const std::string ranked = BLUETILE_TEST_DATA "/ranks_square.txt";
  struct Case {
    std::vector<std::string> values;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"17"}, "--by-rank 17: " + ranked + " holds 16 points, fewer than 17"},
      {{"1"}, "a prefix needs at least 2 to analyse (the whole set is 1/1)"},
      {{"1/16"}, "--by-rank 1/16: the first 1 of 16 points"},
      {{"3/2"}, "--by-rank 3/2: a fraction of the points must be at most 1"},
      {{"0/4"}, "--by-rank 0/4: not a fraction P/Q"},
      {{"half"}, "--by-rank half: not a count or a fraction P/Q"},
      // Two values giving one prefix were merged without a word.
      {{"1/3", "1/3"}, "--by-rank 1/3 and 1/3: both give the first 5 of 16 points; give each prefix once"},
      {{"16", "4", "1/1"}, "--by-rank 16 and 1/1: both give the first 16 of 16 points; give each prefix once"},
      {{"1/4", "2/8"}, "--by-rank 1/4 and 2/8: both give the first 4 of 16 points"},
      {{"5/16", "1/3"}, "--by-rank 5/16 and 1/3: both give the first 5 of 16 points"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> args = {"analyze", "-i", ranked, "-o", dir.file("out"), "--by-rank"};
    args.insert(args.end(), c.values.begin(), c.values.end());
    auto r = test::run_bluetile(args);
    EXPECT_NE(r.exit_code, 0) << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << "expected '" << c.message << "' in: " << r.err;
  }
  auto r = test::run_bluetile({"analyze", "-i", ranked, "-o", dir.file("out"), "--by-rank", "4", "--by-level"});
  EXPECT_NE(r.err.find("choose one of --average, --compare, --by-level and --by-rank"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
}

}  // namespace
}  // namespace bluetile
