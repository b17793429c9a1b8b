// The four L2 discrepancies against scipy.stats.qmc.discrepancy (scipy 1.17.1), on hand-written
// sets and on a seeded set of 256 points (tests/data/discrepancy_256.txt). The numbers below were
// made, with the points of each set as written here, by
//   python3 -m venv /tmp/scipyvenv && /tmp/scipyvenv/bin/pip install scipy numpy
//   /tmp/scipyvenv/bin/python -c 'import numpy as np; from scipy.stats import qmc;
//     p = np.array([[0.1, 0.2], [0.7, 0.4], [0.35, 0.9]]);   # or the other sets, or
//     # p = np.loadtxt("tests/data/discrepancy_256.txt")
//     print(["%.17g" % qmc.discrepancy(p, method=m) for m in ["CD", "WD", "MD", "L2-star"]])'
// (the 256 points: np.random.default_rng(20261202).random((256, 2)), see the file's header).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/discrepancy.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "test_support.h"

namespace bluetile {
namespace {

struct Reference {
  const char* name;
  std::vector<Point> points;
  double cd, wd, md, l2_star;
};

std::vector<Reference> references() {
  return {
      {"three", {{0.1, 0.2}, {0.7, 0.4}, {0.35, 0.9}}, 0.051877777777777467, 0.077144444444444238,
       0.077325000000000088, 0.14784094305856021},
      {"one", {{0.5, 0.5}}, 0.17361111111111094, 0.47222222222222232, 0.46701388888888795, 0.28259708263021949},
      {"lattice", {{0.25, 0.25}, {0.75, 0.25}, {0.25, 0.75}, {0.75, 0.75}}, 0.046657986111110938,
       0.11284722222222232, 0.10064019097222188, 0.12412890924805191},
      {"corners", {{0.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}, {0.5, 0.125}}, 0.14626736111111094, 0.28032769097222232,
       0.24435763888888795, 0.1958499549683663},
      {"random256", read_point_file(BLUETILE_TEST_DATA "/discrepancy_256.txt", {.wrap = false}).points,
       0.00089871000878471996, 0.0012241573240230341, 0.0013520423151880401, 0.017341209679406645},
  };
}

TEST(Discrepancy, MatchesScipy) {
  for (const Reference& r : references()) {
    SCOPED_TRACE(r.name);
    if (std::string(r.name) == "random256") {
      ASSERT_EQ(r.points.size(), 256u);
    }
    const Discrepancies d = discrepancies(r.points);
    EXPECT_NEAR(d.centred, r.cd, 1e-12);
    EXPECT_NEAR(d.wrap_around, r.wd, 1e-12);
    EXPECT_NEAR(d.mixture, r.md, 1e-12);
    EXPECT_NEAR(d.l2_star, r.l2_star, 1e-12);
  }
}

TEST(Discrepancy, SameBitsWhateverTheThreadCountAndWrapAroundIsShiftInvariant) {
  const std::vector<Point> points = test::uniform_points(300, 9);
  const std::size_t threads = thread_count();
  set_thread_count(1);
  const Discrepancies one = discrepancies(points);
  set_thread_count(3);
  const Discrepancies three = discrepancies(points);
  set_thread_count(threads);
  EXPECT_EQ(one.centred, three.centred);
  EXPECT_EQ(one.wrap_around, three.wrap_around);
  EXPECT_EQ(one.mixture, three.mixture);
  EXPECT_EQ(one.l2_star, three.l2_star);
  // WD depends on torus offsets only: a shift on the torus leaves it, not the others.
  std::vector<Point> shifted;
  for (const Point& p : points) shifted.push_back(wrap_point(p + Point{0.375, 0.625}, Domain{}));
  const Discrepancies moved = discrepancies(shifted);
  EXPECT_NEAR(moved.wrap_around, one.wrap_around, 1e-13);
  EXPECT_GT(std::abs(moved.centred - one.centred), 1e-6);
}

TEST(Discrepancy, AnalyzeReportsThem) {
  test::TempDir dir;
  const std::string input = BLUETILE_TEST_DATA "/discrepancy_256.txt";
  auto r = test::run_bluetile({"analyze", "-i", input, "-o", dir.file("out"), "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto stats = nlohmann::json::parse(test::read_text(dir.file("out/stats.json")));
  const Reference ref = references().back();
  EXPECT_NEAR(stats["discrepancy"]["CD"].get<double>(), ref.cd, 1e-12);
  EXPECT_NEAR(stats["discrepancy"]["WD"].get<double>(), ref.wd, 1e-12);
  EXPECT_NEAR(stats["discrepancy"]["MD"].get<double>(), ref.md, 1e-12);
  EXPECT_NEAR(stats["discrepancy"]["L2-star"].get<double>(), ref.l2_star, 1e-12);
  EXPECT_NE(r.out.find("discrepancy (scipy.stats.qmc's): CD 0.00089871, WD 0.00122416, MD 0.00135204 (squared), "
                       "L2-star 0.0173412\n"),
            std::string::npos)
      << r.out;
  // Their cost is in the estimate made up front (every pair: O(N^2)), with the way to skip them.
  std::string many;
  char line[80];
  for (const Point& p : test::uniform_points(20000, 4)) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", p.x, p.y);
    many += line;
  }
  const std::string large = dir.write("large.txt", many);
  r = test::run_bluetile({"analyze", "-i", large, "-o", dir.file("large"), "--no-psa-measures", "--threads", "1",
                          "--time-limit", "0.0001"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("of it for the discrepancies (every pair: O(N^2))"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-discrepancy skips the discrepancies"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("large")));
  r = test::run_bluetile({"analyze", "-i", input, "-o", dir.file("skip"), "--no-centroids", "--no-discrepancy"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(nlohmann::json::parse(test::read_text(dir.file("skip/stats.json"))).contains("discrepancy"));
}

}  // namespace
}  // namespace bluetile
