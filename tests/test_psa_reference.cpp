// nu_eff and Omega against psa itself: figures psa v1.1a printed for sets bluetile made, which
// each test makes again from the same seed (spectral_measures.h has the definitions).
//
// psa was built from its source (github.com/nodag/psa, v1.1a): `make HAVE_CGAL=0`. Every set
// below was written by bluetile (17 significant digits; psa reads them as float), turned into
// psa's .txt (a count line, then "x y") by
//   (grep -vc '^#' F.txt; grep -v '^#' F.txt) > F.psa.txt
// and measured with `psa F.psa.txt --stats` (E-Nyq. is nu_eff, Osci. is Omega), or
// `psa A.psa.txt B.psa.txt ... --stats --avg` for a mean over sets:
//
//   set           made by                                                       E-Nyq.  Osci.
//   random1024    bluetile relax -n 1024 -s 7 -k 0 --engine exact -o random1024.txt   0.000  0.222
//   lloyd1024     bluetile relax -n 1024 -s 5 -k 50 --engine exact -o lloyd1024.txt   0.905  2.754
//   dart256       bluetile dart -n 256 -s 11 -o dart256.txt                            0.630  0.947
//   dart4096      bluetile dart -n 4096 -s 3 -o dart4096.txt                           0.715  0.989
//   jitter2304    the python3 line in jittered_grid() below (a psa .txt already)       0.310  4.312
//   rand256 --avg bluetile relax -n 256 -s 21 --sets 4 -k 0 --engine exact
//                   -o rand256_{}.txt  (psa rand256_?.psa.txt --stats --avg)            0.000  0.155
//   lloyd256 --avg  the same with -k 30 -o lloyd256_{}.txt                             0.825  1.901
//
// Required agreement: nu_eff within 0.01 (two of psa's frequency samples), Omega within 2%.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/sampling/dart_throwing.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

struct PsaFigures {
  double nu_eff;
  double omega;
};

void expect_psa(const SpectralMeasures& m, PsaFigures psa, const std::string& what) {
  EXPECT_NEAR(m.nu_eff, psa.nu_eff, 0.01) << what;
  EXPECT_NEAR(m.omega, psa.omega, 0.02 * psa.omega) << what;
}

SpectralMeasures measures_of(const std::vector<Point>& points) {
  return spectral_measures(rdf_power_spectrum(points));
}

SpectralMeasures measures_of(const std::vector<std::vector<Point>>& sets) {
  std::vector<RdfPowerSpectrum> spectra;
  for (const auto& set : sets) spectra.push_back(rdf_power_spectrum(set));
  return spectral_measures(average_spectra(spectra));
}

// bluetile relax -n N -s seed -k iterations --engine exact (set `set` of --sets).
std::vector<Point> lloyd(std::size_t n, std::uint64_t seed, int iterations, std::uint64_t set = 0) {
  Scene scene = make_scene(uniform_random_points(n, seed, set));
  ExactEngine engine;
  LloydOptions options;
  options.iterations = iterations;
  if (iterations > 0) relax_lloyd(engine, scene, options);
  return scene.sites;
}

std::vector<Point> darts(std::size_t n, std::uint64_t seed) {
  DartOptions options;
  options.count = n;
  options.seed = seed;
  return throw_darts(options).points;
}

// A 48 x 48 grid jittered by the fractional parts of k phi and k (sqrt 2 - 1), k the cell
// index: deterministic without a random generator, so psa's copy came from
//   python3 -c "import math;m=48;phi=(math.sqrt(5)-1)/2;r2=math.sqrt(2)-1;print(m*m);
//     [print(repr((i+(k*phi)%1)/m),repr((j+(k*r2)%1)/m)) for j in range(m) for i in range(m)
//     for k in [j*m+i]]" > jitter2304.txt
std::vector<Point> jittered_grid() {
  const int m = 48;
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0, r2 = std::sqrt(2.0) - 1.0;
  std::vector<Point> points;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      const double k = j * m + i;
      points.push_back({(i + std::fmod(k * phi, 1.0)) / m, (j + std::fmod(k * r2, 1.0)) / m});
    }
  }
  return points;
}

TEST(PsaReference, RandomAndRelaxedSets) {
  expect_psa(measures_of(lloyd(1024, 7, 0)), {0.000, 0.222}, "random1024");
  expect_psa(measures_of(lloyd(1024, 5, 50)), {0.905, 2.754}, "lloyd1024");
}

TEST(PsaReference, DartThrowing) {
  expect_psa(measures_of(darts(256, 11)), {0.630, 0.947}, "dart256");
  expect_psa(measures_of(darts(4096, 3)), {0.715, 0.989}, "dart4096");
}

TEST(PsaReference, JitteredGrid) { expect_psa(measures_of(jittered_grid()), {0.310, 4.312}, "jitter2304"); }

TEST(PsaReference, MeanOverSetsAsPsaAvg) {
  std::vector<std::vector<Point>> random, relaxed;
  for (std::uint64_t k = 0; k < 4; ++k) {
    random.push_back(lloyd(256, 21, 0, k));
    relaxed.push_back(lloyd(256, 21, 30, k));
  }
  expect_psa(measures_of(random), {0.000, 0.155}, "rand256 --avg");
  const SpectralMeasures mean = measures_of(relaxed);
  expect_psa(mean, {0.825, 1.901}, "lloyd256 --avg");

  // bluetile analyze --average reports the same figures, from one file holding the four sets.
  test::TempDir dir;
  std::string text;
  for (const auto& set : relaxed) {
    text += "#\n";
    for (const Point& p : set) {
      char line[64];
      std::snprintf(line, sizeof line, "%.17g %.17g\n", p.x, p.y);
      text += line;
    }
  }
  const std::string input = dir.write("lloyd256.txt", text);
  auto r = test::run_bluetile({"analyze", "--average", "--no-centroids", "-i", input, "-o", dir.file("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto stats = nlohmann::json::parse(test::read_text(dir.file("out/stats.json")));
  EXPECT_EQ(stats["sets"], 4);
  EXPECT_DOUBLE_EQ(stats["nu_eff"].get<double>(), mean.nu_eff);
  EXPECT_DOUBLE_EQ(stats["omega"].get<double>(), mean.omega);
  EXPECT_NE(r.out.find("nu_eff 0.825, oscillations Omega 1.901"), std::string::npos) << r.out;
}

TEST(PsaReference, AnalyzeReadsPsaRps) {
  // dart256 as psa's .rps (float32 x y pairs): the float rounding moves no figure off psa's.
  test::TempDir dir;
  std::string bytes;
  for (const Point& p : darts(256, 11)) {
    const float xy[2] = {static_cast<float>(p.x), static_cast<float>(p.y)};
    bytes.append(reinterpret_cast<const char*>(xy), sizeof xy);  // little-endian machines
  }
  const std::string input = dir.write("dart256.rps", bytes);
  auto r = test::run_bluetile({"analyze", "--no-centroids", "-i", input, "-o", dir.file("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto stats = nlohmann::json::parse(test::read_text(dir.file("out/stats.json")));
  EXPECT_EQ(stats["n"], 256);
  EXPECT_NEAR(stats["nu_eff"].get<double>(), 0.630, 0.01);
  EXPECT_NEAR(stats["omega"].get<double>(), 0.947, 0.02 * 0.947);
  // psa's stats table, as `psa dart256.psa.txt --stats` prints it (G-MD 0.699, A-MD 0.819).
  EXPECT_NE(r.out.find("File            \tG-MD\tA-MD\tE-Nyq.\tOsci.\n"
                       "dart256           \t0.699\t0.819\t0.630\t0.947\n"),
            std::string::npos)
      << r.out;

  const std::string cut = dir.write("cut.rps", bytes.substr(0, 1001));
  r = test::run_bluetile({"analyze", "-i", cut, "-o", dir.file("bad")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find(cut + ": 1001 bytes is not a whole number of points"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("bad/stats.json")));
}

}  // namespace
}  // namespace bluetile
