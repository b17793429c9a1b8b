// Analysis against independent references: the periodogram against a plain complex sum and
// hand-computed cases, radial binning against a hand-computed annulus, nearest neighbours
// against brute force on the torus, white noise against its expected spectrum.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <complex>
#include <filesystem>
#include <limits>
#include <numbers>

#include <nlohmann/json.hpp>

#include "bluetile/analysis/fft.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/analysis/summary_record.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/point_file.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::error_of;
using test::uniform_points;

double brute_force_power(const std::vector<Point>& points, int kx, int ky) {
  std::complex<double> sum = 0.0;
  for (const Point& p : points) {
    // Phase reduced to [0, 1) in long double so the reference is accurate at high k.
    long double t = static_cast<long double>(kx) * p.x + static_cast<long double>(ky) * p.y;
    t -= std::floor(t);
    sum += std::polar(1.0, -2.0 * std::numbers::pi * static_cast<double>(t));
  }
  return std::norm(sum) / static_cast<double>(points.size());
}

std::vector<Point> square_lattice(int m, Point offset = {0.0, 0.0}) {
  std::vector<Point> points;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) points.push_back(wrap_point(Point{i / double(m), j / double(m)} + offset, Domain{}));
  return points;
}

TEST(Periodogram, MatchesPlainComplexSumEverywhere) {
  // 300 points span two blocks of the kernel; F = 150 spans tiles that straddle k = 0 unevenly.
  auto points = uniform_points(300, 11);
  const int f = 150;
  Periodogram p = compute_periodogram_direct(points, f);
  ASSERT_EQ(p.size, f);
  double worst = 0.0;
  for (int ky = -f / 2; ky < f / 2; ++ky) {
    for (int kx = -f / 2; kx < f / 2; ++kx) {
      double expected = brute_force_power(points, kx, ky);
      worst = std::max(worst, std::abs(p.at(kx, ky) - expected));
    }
  }
  // Values are O(1) to O(10); the recurrences lose a few ulps per step.
  EXPECT_LT(worst, 1e-10);
}

TEST(Periodogram, DcIsExactlyN) {
  for (std::size_t n : {2u, 257u, 1000u}) {
    auto points = uniform_points(n, 5);
    Periodogram p = compute_periodogram(points, default_periodogram_size(n));
    EXPECT_EQ(p.at(0, 0), static_cast<double>(n)) << "N = " << n;
  }
}

TEST(Periodogram, HandComputedCases) {
  // One point: |exp(..)|^2 / 1 = 1 at every k.
  Periodogram one = compute_periodogram(std::vector<Point>{{0.3, 0.7}}, 16);
  for (double v : one.power) EXPECT_NEAR(v, 1.0, 1e-13);
  // Two points half a period apart in x: S = 1 + (-1)^kx, so P = 2 for even kx and 0 for odd.
  Periodogram two = compute_periodogram(std::vector<Point>{{0.0, 0.25}, {0.5, 0.25}}, 16);
  for (int ky = -8; ky < 8; ++ky) {
    for (int kx = -8; kx < 8; ++kx) {
      double expected = (kx % 2 == 0) ? 2.0 : 0.0;
      EXPECT_NEAR(two.at(kx, ky), expected, 1e-12) << kx << "," << ky;
    }
  }
}

TEST(Periodogram, SquareLatticeHasPowerExactlyAtLatticeFrequencies) {
  const int m = 8;
  auto points = square_lattice(m, {0.03, 0.01});
  Periodogram p = compute_periodogram(points, 64);
  for (int ky = -32; ky < 32; ++ky) {
    for (int kx = -32; kx < 32; ++kx) {
      if (kx % m == 0 && ky % m == 0) EXPECT_NEAR(p.at(kx, ky), m * m, 1e-9) << kx << "," << ky;
      else EXPECT_LT(p.at(kx, ky), 1e-20) << kx << "," << ky;
    }
  }
}

TEST(Periodogram, BitIdenticalWhateverTheThreadCount) {
  auto points = uniform_points(700, 3);
  const std::size_t before = thread_count();
  set_thread_count(1);
  Periodogram serial = compute_periodogram(points, 200);
  set_thread_count(2);
  Periodogram two = compute_periodogram(points, 200);
  set_thread_count(5);
  Periodogram five = compute_periodogram(points, 200);
  set_thread_count(before);
  EXPECT_TRUE(serial.power == two.power);
  EXPECT_TRUE(serial.power == five.power);
}

TEST(Fft, MatchesTheDiscreteFourierTransform) {
  for (std::size_t n : {1u, 2u, 8u, 64u, 1024u}) {
    Rng rng(n);
    std::vector<double> re(n), im(n);
    for (std::size_t i = 0; i < n; ++i) re[i] = rng.uniform() - 0.5, im[i] = rng.uniform() - 0.5;
    std::vector<double> out_re = re, out_im = im;
    Fft(n).forward(out_re.data(), out_im.data());
    double worst = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      std::complex<long double> sum = 0.0L;
      for (std::size_t l = 0; l < n; ++l) {
        const long double angle = -2.0L * std::numbers::pi_v<long double> * static_cast<long double>((k * l) % n) / n;
        sum += std::complex<long double>(re[l], im[l]) * std::polar(1.0L, angle);
      }
      worst = std::max(worst, static_cast<double>(std::abs(sum - std::complex<long double>(out_re[k], out_im[k]))));
    }
    EXPECT_LT(worst, 1e-13 * std::sqrt(static_cast<double>(n)) + 1e-15) << "n = " << n;
  }
  EXPECT_THROW(Fft(12), Error);
  EXPECT_THROW(Fft(0), Error);
}

// The non-uniform FFT against the direct sum (its oracle): every value within 1e-9 of the
// largest power, P(0) = N.
double worst_relative_difference(const std::vector<Point>& points, int f) {
  const Periodogram fast = compute_periodogram_nufft(points, f);
  const Periodogram direct = compute_periodogram_direct(points, f);
  EXPECT_EQ(fast.size, f);
  EXPECT_EQ(fast.at(0, 0), static_cast<double>(points.size()));
  double worst = 0.0, highest = 0.0;
  for (std::size_t i = 0; i < direct.power.size(); ++i) {
    worst = std::max(worst, std::abs(fast.power[i] - direct.power[i]));
    highest = std::max(highest, direct.power[i]);
  }
  return worst / highest;
}

std::vector<Point> relaxed_points(std::size_t n, std::uint64_t seed, int iterations) {
  Scene scene = make_scene(uniform_points(n, seed));
  ExactEngine engine;
  LloydOptions options;
  options.iterations = iterations;
  relax_lloyd(engine, scene, options);
  return scene.sites;
}

std::vector<Point> hexagonal_lattice(int columns, int rows) {
  std::vector<Point> points;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) points.push_back(wrap_point({(i + 0.5 * (j % 2) + 0.1) / columns, (j + 0.3) / rows}, Domain{}));
  return points;
}

TEST(PeriodogramNufft, MatchesTheDirectSumOnRandomSets) {
  // One point is the worst case (many points average the kernel's errors down).
  for (auto [n, f] : {std::pair{3000, 0}, std::pair{500, 150}, std::pair{64, 2}, std::pair{40, 6}, std::pair{1, 6},
                      std::pair{1, 64}, std::pair{2, 1000}}) {
    auto points = uniform_points(static_cast<std::size_t>(n), 21 + static_cast<std::uint64_t>(n));
    const int size = f ? f : default_periodogram_size(points.size());
    const double error = worst_relative_difference(points, size);
    EXPECT_LT(error, 1e-9) << "N = " << n << ", F = " << size;
  }
}

TEST(PeriodogramNufft, MatchesTheDirectSumOnARelaxedSet) {
  auto points = relaxed_points(2048, 4, 30);
  const double error = worst_relative_difference(points, default_periodogram_size(points.size()));
  EXPECT_LT(error, 1e-9);
}

TEST(PeriodogramNufft, MatchesTheDirectSumOnLattices) {
  // Lattices put all their power on a few frequencies (P = N there, 0 elsewhere): the error at
  // the zeros is relative to those peaks.
  auto square = square_lattice(40, {0.013, 0.007});
  EXPECT_LT(worst_relative_difference(square, 400), 1e-9);
  auto hexagonal = hexagonal_lattice(36, 42);
  EXPECT_LT(worst_relative_difference(hexagonal, default_periodogram_size(hexagonal.size())), 1e-9);
  // Points on grid lines of the upsampled grid and on the torus seam (x = 0, 1 - 2^-53, -0).
  std::vector<Point> seam = {{0.0, 0.0}, {1.0 - 0x1p-53, 0.5}, {-0.0, 0.25}, {0.5, 1.0 - 0x1p-53}, {0.25, 0.75}};
  EXPECT_LT(worst_relative_difference(seam, 64), 1e-9);
}

TEST(PeriodogramNufft, BitIdenticalWhateverTheThreadCount) {
  auto points = uniform_points(5000, 8);
  const std::size_t before = thread_count();
  set_thread_count(1);
  Periodogram serial = compute_periodogram_nufft(points, 300);
  set_thread_count(2);
  Periodogram two = compute_periodogram_nufft(points, 300);
  set_thread_count(7);
  Periodogram seven = compute_periodogram_nufft(points, 300);
  set_thread_count(before);
  EXPECT_TRUE(serial.power == two.power);
  EXPECT_TRUE(serial.power == seven.power);
}

TEST(PeriodogramNufft, ChosenForLargeSetsOnly) {
  EXPECT_FALSE(periodogram_uses_nufft(64, 64));
  EXPECT_TRUE(periodogram_uses_nufft(1000, default_periodogram_size(1000)));
  EXPECT_TRUE(periodogram_uses_nufft(100000, default_periodogram_size(100000)));
  EXPECT_EQ(periodogram_nufft_grid(10000), 16384u);  // the power of two >= 1.5 F
  EXPECT_THROW(compute_periodogram_nufft(std::vector<Point>{}, 16), Error);
  EXPECT_THROW(compute_periodogram_nufft(uniform_points(3, 1), 15), Error);
}

TEST(Periodogram, RejectsBadArguments) {
  EXPECT_THROW(compute_periodogram(std::vector<Point>{}, 16), Error);
  EXPECT_THROW(compute_periodogram(uniform_points(3, 1), 15), Error);
  EXPECT_THROW(compute_periodogram(uniform_points(3, 1), 0), Error);
  EXPECT_EQ(default_periodogram_size(1000), 316);  // 2 floor(5 sqrt(1000)) = 2 * 158
  // A point that is not finite: the direct sum gave NaN power without a word, as the
  // non-uniform FFT never did.
  const std::vector<Point> nan_point = {{0.1, 0.1}, {std::nan(""), 0.2}};
  EXPECT_EQ(error_of([&] { compute_periodogram_direct(nan_point, 8); }), "periodogram: point 1 is not finite");
  EXPECT_EQ(error_of([&] { compute_periodogram(nan_point, 8); }), "periodogram: point 1 is not finite");
}

TEST(NearestNeighbour, PointsThatAreNotFiniteAreRefused) {
  // A NaN point hung the ring search (its reach never passed the best distance), on every
  // front end that did not check first; an infinity came back as a distance.
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity()}) {
    const std::vector<Point> points = {{0.1, 0.1}, {bad, 0.2}, {0.5, 0.5}};
    for (Boundary boundary : {Boundary::periodic, Boundary::bounded})
      EXPECT_EQ(error_of([&] { nearest_neighbour_distances(points, Domain{}, boundary); }),
                "nearest-neighbour distances: point 1 is not finite");
  }
}

TEST(RadialPower, HandComputedAnnulus) {
  // F = 4: k in {-2..1}^2. P = 10 + kx + 2 ky, chosen so every annulus has a spread.
  Periodogram p;
  p.size = 4;
  p.power.resize(16);
  for (int ky = -2; ky < 2; ++ky)
    for (int kx = -2; kx < 2; ++kx) p.power[static_cast<std::size_t>((ky + 2) * 4 + kx + 2)] = 10 + kx + 2 * ky;
  auto radial = radial_power(p, 1.0);
  // Annuli wholly inside the square: |k| < 2, so annulus 0 (k = 0) and annulus 1 (|k| in [1, 2)).
  ASSERT_EQ(radial.size(), 2u);
  EXPECT_EQ(radial[0].count, 1u);
  EXPECT_EQ(radial[0].power, 10.0);
  EXPECT_TRUE(std::isnan(radial[0].anisotropy_db));
  // Annulus 1: (+-1, 0), (0, +-1), (+-1, +-1): values 11, 9, 12, 8, 13, 11, 9, 7.
  const double values[] = {11, 9, 12, 8, 13, 11, 9, 7};
  double mean = 80.0 / 8.0, ss = 0.0;
  for (double v : values) ss += (v - mean) * (v - mean);  // 1+1+4+4+9+1+1+9 = 30
  EXPECT_EQ(radial[1].count, 8u);
  EXPECT_DOUBLE_EQ(radial[1].power, 10.0);
  EXPECT_DOUBLE_EQ(radial[1].frequency, 1.0);
  EXPECT_NEAR(radial[1].anisotropy_db, 10.0 * std::log10((ss / 7.0) / (mean * mean)), 1e-12);
  EXPECT_NEAR(radial[1].anisotropy_db, 10.0 * std::log10(30.0 / 7.0 / 100.0), 1e-12);

  // Width 1.5: one annulus, |k| < 1.5, the 3x3 block around 0: mean 10.
  auto wide = radial_power(p, 1.5);
  ASSERT_EQ(wide.size(), 1u);
  EXPECT_EQ(wide[0].count, 9u);
  EXPECT_DOUBLE_EQ(wide[0].power, 10.0);
  EXPECT_THROW(radial_power(p, 0.0), Error);
  EXPECT_THROW(radial_power(p, 3.0), Error);
}

TEST(RadialPower, WhiteNoiseIsFlatAtOneAndIsotropic) {
  // For independent uniform points E[P(k)] = 1 at every k != 0 and P(k) is about exponentially
  // distributed, so A = var / mean^2 is about 1 (0 dB).
  const std::size_t n = 1000;
  auto points = uniform_points(n, 2024);
  Periodogram p = compute_periodogram(points, default_periodogram_size(n));
  auto radial = radial_power(p);
  ASSERT_EQ(radial.size(), 158u);
  double power = 0.0, weights = 0.0, db = 0.0;
  std::size_t counted = 0;
  for (std::size_t i = 10; i < radial.size(); ++i) {
    power += radial[i].power * static_cast<double>(radial[i].count);
    weights += static_cast<double>(radial[i].count);
    db += radial[i].anisotropy_db;
    ++counted;
    // Annulus i has about pi i independent values (P(k) = P(-k)): sd of P_i about 1/sqrt(pi i),
    // at most 0.18 here; 0.75 is over 4 sd.
    EXPECT_NEAR(radial[i].power, 1.0, 0.75) << "annulus " << i;
  }
  // About 38000 independent values: sd of the mean about 0.005; tolerance 0.03.
  EXPECT_NEAR(power / weights, 1.0, 0.03);
  // Mean anisotropy over 148 annuli; the log of a sample variance ratio is biased low by a few
  // tenths of a dB at the smallest annuli. Tolerance 0.5 dB.
  EXPECT_NEAR(db / static_cast<double>(counted), 0.0, 0.5);
}

TEST(RadialPower, AveragedWhiteNoiseStaysAtOne) {
  std::vector<Periodogram> ps;
  for (std::uint64_t seed = 0; seed < 8; ++seed) ps.push_back(compute_periodogram(uniform_points(200, 100 + seed), 80));
  auto radial = radial_power(average_periodograms(ps));
  double power = 0.0;
  for (std::size_t i = 5; i < radial.size(); ++i) power += radial[i].power;
  EXPECT_NEAR(power / static_cast<double>(radial.size() - 5), 1.0, 0.05);
  // Averaging M periodograms divides the variance by M: the white-noise level is -10 log10(M) dB.
  double db = 0.0;
  for (std::size_t i = 5; i < radial.size(); ++i) db += radial[i].anisotropy_db;
  EXPECT_NEAR(db / static_cast<double>(radial.size() - 5), -10.0 * std::log10(8.0), 1.0);
}

TEST(NearestNeighbour, MatchesBruteForceOnTheTorus) {
  auto points = uniform_points(600, 9);
  // Pairs that are close only across the border, in x, in y and across a corner.
  points.push_back({0.0005, 0.4});
  points.push_back({0.9995, 0.4});
  points.push_back({0.7, 0.0002});
  points.push_back({0.7, 0.9999});
  points.push_back({0.0001, 0.0001});
  points.push_back({0.9998, 0.9998});
  auto d = nearest_neighbour_distances(points);
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = 1.0;
    for (std::size_t j = 0; j < points.size(); ++j)
      if (j != i) best = std::min(best, torus_distance(points[i], points[j], Domain{}));
    EXPECT_NEAR(d[i], best, 1e-15) << "point " << i;  // offsets are rounded differently
  }
  EXPECT_NEAR(d[600], 0.001, 1e-12);
  EXPECT_NEAR(d[602], 0.0003, 1e-12);
  EXPECT_NEAR(d[604], std::sqrt(2.0) * 0.0003, 1e-12);

  NearestNeighbourStats s = nearest_neighbour_stats(square_lattice(10));
  EXPECT_NEAR(s.min, 0.1, 1e-15);
  EXPECT_NEAR(s.max, 0.1, 1e-15);
  EXPECT_NEAR(s.hexagonal_spacing, std::sqrt(2.0 / (std::sqrt(3.0) * 100.0)), 1e-15);
}

TEST(Summary, LatticeSitesAreTheirCentroids) {
  EXPECT_LT(mean_centroid_distance(square_lattice(12, {0.02, 0.05})), 1e-12);
  // Uniform random sites are far from their centroids: a sizeable fraction of the spacing.
  auto points = uniform_points(500, 4);
  EXPECT_GT(mean_centroid_distance(points) / hexagonal_spacing(500.0), 0.1);
  // No points gave 0 / 0.
  EXPECT_EQ(error_of([] { mean_centroid_distance(std::vector<Point>{}); }), "mean centroid distance of no points");
}

TEST(Summary, RecordHoldsStatsJsonFieldsWithTheSummarysNumbers) {
  std::vector<std::vector<Point>> sets = {relaxed_points(256, 2, 20)};
  SummaryOptions options;
  const Summary s = summarize(sets, options);
  const Record r = summary_record(s);
  ASSERT_EQ(r.kind, Record::Kind::object);
  for (const char* key : {"n", "sets", "boundary", "nn_min", "nn_max", "nn_mean", "nn_x1000", "nn_relative",
                          "hexagonal_spacing", "rho", "average_min_distance", "mean_centroid_distance",
                          "mean_centroid_distance_relative", "nu_eff", "omega", "omega_range_nu", "bond_order",
                          "rdf_range_relative", "rdf_bins", "periodogram_size", "radial"})
    EXPECT_NE(r.find(key), nullptr) << key;
  EXPECT_EQ(r.find("n")->integer, 256);
  EXPECT_EQ(r.find("rho")->real, s.nn.rho());
  EXPECT_EQ(r.find("nu_eff")->real, s.measures.nu_eff);
  EXPECT_EQ(r.find("omega")->real, s.measures.omega);
  EXPECT_EQ(r.find("bond_order")->find("local")->real, s.bond_order.local);
  EXPECT_EQ(r.find("radial")->find("power")->reals.size(), s.radial.size());
  EXPECT_EQ(r.find("nn_min_lowest"), nullptr);  // one set
  // Skipped psa measures are null (NaN), bounded sets have no bond order or centroid distance.
  options.spectral_measures = false;
  options.boundary = Boundary::bounded;
  const Record b = summary_record(summarize(sets, options));
  EXPECT_TRUE(std::isnan(b.find("nu_eff")->real));
  EXPECT_EQ(b.find("omega_range_nu"), nullptr);
  EXPECT_EQ(b.find("bond_order"), nullptr);
  EXPECT_EQ(b.find("mean_centroid_distance"), nullptr);
  EXPECT_EQ(b.find("boundary")->text, "bounded");
}

TEST(Summary, PrefixesOfALeveledSet) {
  // Level 0: a 4x4 lattice; level 1: its cell centres (together a lattice turned 45 degrees);
  // level 2: the edge midpoints (together an 8x8 lattice).
  std::vector<Point> points = square_lattice(4);
  std::vector<int> levels(16, 0);
  for (const Point& p : square_lattice(4, {0.125, 0.125})) points.push_back(p), levels.push_back(1);
  for (const Point& p : square_lattice(4, {0.125, 0.0})) points.push_back(p), levels.push_back(2);
  for (const Point& p : square_lattice(4, {0.0, 0.125})) points.push_back(p), levels.push_back(2);
  SummaryOptions o;
  auto result = summarize_levels(points, levels, o);
  ASSERT_EQ(result.size(), 3u);
  EXPECT_EQ(result[0].summary.count, 16u);
  EXPECT_EQ(result[1].summary.count, 32u);
  EXPECT_EQ(result[2].summary.count, 64u);
  EXPECT_NEAR(result[0].summary.nn.min, 0.25, 1e-15);
  EXPECT_NEAR(result[1].summary.nn.min, 0.25 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(result[2].summary.nn.min, 0.125, 1e-15);
  // Each prefix at its natural F = 2 floor(5 sqrt(N)): 40, 56, 80; or one F when asked.
  EXPECT_EQ(result[0].summary.periodogram.size, 40);
  EXPECT_EQ(result[1].summary.periodogram.size, 56);
  EXPECT_EQ(result[2].summary.periodogram.size, 80);
  o.size = 80;
  for (const auto& l : summarize_levels(points, levels, o)) EXPECT_EQ(l.summary.periodogram.size, 80);
  o.size = 0;
  // The 4x4 lattice has its power at multiples of 4 only.
  EXPECT_NEAR(result[0].summary.periodogram.at(4, 0), 16.0, 1e-9);
  EXPECT_LT(result[0].summary.periodogram.at(2, 0), 1e-20);
  // Adding level 1 cancels (4, 0) (a checkerboard) but not (4, 4).
  EXPECT_LT(result[1].summary.periodogram.at(4, 0), 1e-20);
  EXPECT_NEAR(result[1].summary.periodogram.at(4, 4), 32.0, 1e-9);
  EXPECT_THROW(summarize_levels(points, std::vector<int>(3, 0), o), Error);
}

TEST(Summary, LevelsOutsideTheFileRangeAreRefusedNamingThePointAndTheLevel) {
  // Level -1 gave a prefix "levels 0..-1" of no points; a level past kMaxLevel one no file holds.
  const std::vector<Point> points = square_lattice(4);
  for (int bad : {-1, kMaxLevel + 1, std::numeric_limits<int>::min()}) {
    std::vector<int> levels(points.size(), 0);
    levels[5] = bad;
    try {
      summarize_levels(points, levels, SummaryOptions{});
      ADD_FAILURE() << "level " << bad << " was taken";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "point 5: level must be an integer from 0 to " + std::to_string(kMaxLevel) +
                                           ", got " + std::to_string(bad));
    }
  }
  std::vector<int> levels(points.size(), 0);
  levels[3] = kMaxLevel;  // the largest is taken
  EXPECT_EQ(summarize_levels(points, levels, SummaryOptions{}).size(), 2u);
}

// --- the command line --------------------------------------------------------------------

std::string write_points(const test::TempDir& dir, const std::string& name, const std::vector<Point>& points) {
  std::string text;
  char line[80];
  for (const Point& p : points) {
    std::snprintf(line, sizeof line, "%.17g %.17g\n", p.x, p.y);
    text += line;
  }
  return dir.write(name, text);
}

TEST(AnalyzeCommand, WritesEveryOutput) {
  test::TempDir dir;
  std::string input = write_points(dir, "uniform.txt", uniform_points(400, 8));
  std::filesystem::create_directory(dir.file("nested"));  // -o creates only the last folder
  std::string out = dir.file("nested/out");
  auto r = test::run_bluetile({"analyze", "--input", input, "--output", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* name : {"stats.json", "radial.csv", "rdf.csv", "report.txt", "points.png", "spectrum.png",
                           "radial.png", "rdf.png", "points.svg", "spectrum.svg", "radial.svg", "rdf.svg"})
    EXPECT_TRUE(std::filesystem::exists(out + "/" + name)) << name;
  auto stats = nlohmann::json::parse(test::read_text(out + "/stats.json"));
  EXPECT_EQ(stats["n"], 400);
  EXPECT_EQ(stats["periodogram_size"], 200);
  auto nn = nearest_neighbour_stats(uniform_points(400, 8));
  EXPECT_DOUBLE_EQ(stats["nn_min"].get<double>(), nn.min);
  EXPECT_DOUBLE_EQ(stats["nn_max"].get<double>(), nn.max);
  EXPECT_DOUBLE_EQ(stats["nn_mean"].get<double>(), nn.mean);
  EXPECT_DOUBLE_EQ(stats["nn_x1000"]["min"].get<double>(), 1000.0 * nn.min);
  EXPECT_DOUBLE_EQ(stats["nn_relative"]["min"].get<double>(), nn.min / hexagonal_spacing(400.0));
  EXPECT_GT(stats["mean_centroid_distance"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(stats["rho"].get<double>(), nn.min / hexagonal_spacing(400.0));
  EXPECT_DOUBLE_EQ(stats["average_min_distance"].get<double>(), nn.mean / hexagonal_spacing(400.0));
  EXPECT_EQ(stats["nu_eff"].get<double>(), 0.0);  // white noise has no zero region
  EXPECT_EQ(stats["boundary"], "periodic");
  std::string csv = test::read_text(out + "/radial.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "frequency,power,anisotropy_db,nu");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 100);  // F/2 annuli
  EXPECT_NE(csv.find("\n0,400,,0\n"), std::string::npos);  // annulus 0's anisotropy undefined: empty
  EXPECT_NE(csv.find("\n10,"), std::string::npos);
  EXPECT_NE(csv.find(",1\n"), std::string::npos);  // |k| = 10 is nu = 10 / (sqrt(400) / 2) = 1
  std::string rdf = test::read_text(out + "/rdf.csv");
  EXPECT_EQ(rdf.substr(0, rdf.find('\n')), "r,r_relative,g");
  EXPECT_EQ(std::count(rdf.begin(), rdf.end(), '\n'), 1 + 50);  // N / 8 bins
  const std::string report = test::read_text(out + "/report.txt");
  EXPECT_NE(report.find("400 points"), std::string::npos);
  EXPECT_EQ(r.out, report);  // the report is printed too
}

TEST(AnalyzeCommand, BadInputFailsCleanlyAndWritesNothing) {
  test::TempDir dir;
  struct Case {
    std::string name, text, message;
  };
  const Case cases[] = {
      {"empty.txt", "", "no points"},
      {"comments.txt", "# nothing here\n", "no points"},
      {"one.txt", "0.5 0.5\n", "at least 2 points"},
      {"nan.txt", "0.1 0.2\nnan 0.3\n", "nan.txt:2"},
      {"text.txt", "0.1 0.2\nhello world\n", "text.txt:2"},
  };
  for (const Case& c : cases) {
    std::string input = dir.write(c.name, c.text);
    std::string out = dir.file("out-" + c.name);
    auto r = test::run_bluetile({"analyze", "--input", input, "--output", out});
    EXPECT_NE(r.exit_code, 0) << c.name;
    EXPECT_EQ(r.err.rfind("bluetile: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.name << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(out)) << c.name;
  }
  auto r = test::run_bluetile({"analyze", "--input", dir.file("missing.txt"), "--output", dir.file("out")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("missing.txt"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
  // An RDF range beyond half the torus was cut to it without a word (0, 8 and 100 all gave 2.08
  // spacings for 20 points); the default (0: psa's 8) is still cut, as documented.
  PointSet random;
  random.points = test::uniform_points(20, 4);
  const std::string twenty = dir.write("twenty.txt", format_points(random));
  r = test::run_bluetile({"analyze", "-i", twenty, "-o", dir.file("rdf"), "--rdf-range", "8", "--no-discrepancy"});
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_EQ(r.err, "bluetile: --rdf-range 8: at most 2.08 hexagonal spacings for 20 points (half the square; beyond it "
                   "a torus annulus overlaps itself)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("rdf")));
  r = test::run_bluetile({"analyze", "-i", twenty, "-o", dir.file("rdf"), "--rdf-range", "2", "--no-discrepancy"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" hexagonal spacings (range 2.00, 32 bins)\n"), std::string::npos) << r.out;
  // 0 was taken and meant the default; it is refused like any other value out of range.
  r = test::run_bluetile({"analyze", "-i", twenty, "-o", dir.file("rdf0"), "--rdf-range", "0", "--no-discrepancy"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "bluetile: --rdf-range 0: out of range; expected a number above 0 and at most 1000000 (see --help)\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("rdf0")));
  // The default is capped, and the report says so (it gave the range alone).
  r = test::run_bluetile({"analyze", "-i", twenty, "-o", dir.file("rdf8"), "--no-discrepancy"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" hexagonal spacings (range 2.08: the default 8 capped at half the square, 32 bins)\n"),
            std::string::npos)
      << r.out;
  r = test::run_bluetile({"analyze", "--help"});
  EXPECT_NE(r.out.find("default psa's 8, capped at half the square for N < 296"), std::string::npos) << r.out;
  // An odd --size is named with its value (it said only "--size must be an even number >= 2").
  r = test::run_bluetile({"analyze", "-i", twenty, "-o", dir.file("odd"), "--size", "7"});
  EXPECT_EQ(r.err, "bluetile: --size 7: expected 0 (from N) or an even number from 2 to 65536\n");
}

// The help's "N < 296": psa's 8 spacings fit in half the torus from 296 points on (8 d_hex <= 1/2
// for N >= 512 / sqrt(3) = 295.6).
TEST(AnalyzeCommand, DefaultRdfRangeIsCappedBelow296Points) {
  for (const auto& [n, capped] : {std::pair<std::size_t, bool>{295, true}, {296, false}}) {
    const RadialDistribution rdf = radial_distribution(uniform_points(n, 1));
    const double range = rdf.range() / rdf.hexagonal_spacing;
    EXPECT_EQ(range < kDefaultRdfRange * (1.0 - 1e-9), capped) << n << " points: range " << range;
  }
}

// --by-level on several sets pointed to --average or --compare, neither of which takes
// --by-level, and said "(1 files)".
TEST(AnalyzeCommand, SeveralSetsNameTheModesThatTakeThem) {
  test::TempDir dir;
  const std::string leveled = test::read_text(BLUETILE_TEST_DATA "/levels_lattice.txt");
  const std::string two = dir.write("two.txt", leveled + "#\n" + leveled);
  auto r = test::run_bluetile({"analyze", "-i", two, "-o", dir.file("lev"), "--by-level"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err, "bluetile: --by-level analyses one set, but 2 point sets are given (1 file): --by-rank K... averages "
                   "the first K rows over the sets (rows in level order, as bluetile progressive writes them: K at the "
                   "level boundaries gives the level prefixes), --average the whole sets\n");
  EXPECT_FALSE(std::filesystem::exists(dir.file("lev")));
  // What it names works: the level boundaries 16, 32 and 64 of the file as --by-rank counts.
  r = test::run_bluetile({"analyze", "-i", two, "-o", dir.file("ranks"), "--by-rank", "16", "32", "64", "--image-size", "64"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(test::read_text(dir.file("ranks/stats.json")))["ranks"][1]["sets"], 2);
  r = test::run_bluetile({"analyze", "-i", two, "-o", dir.file("none")});
  EXPECT_EQ(r.err, "bluetile: 2 point sets given (1 file): use --average to analyse their mean (with a table of each "
                   "set), --compare to plot them together or --by-rank to average their prefixes\n");
  r = test::run_bluetile({"analyze", "-i", two, two, "-o", dir.file("none")});
  EXPECT_NE(r.err.find("4 point sets given (2 files)"), std::string::npos) << r.err;
}

TEST(AnalyzeCommand, RefusesUpFrontWithTheEstimate) {
  // psa's measures are what takes the time (their RDF is O(N^2)): the refusal says so, names the
  // way to skip them and the way to raise the limit, and writes nothing.
  test::TempDir dir;
  std::string input = write_points(dir, "uniform.txt", uniform_points(5000, 3));
  auto r = test::run_bluetile({"analyze", "--input", input, "--output", dir.file("out"), "--threads", "1",
                               "--time-limit", "0.001"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("analyze of 5000 points would take about"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("psa's nu_eff and Omega"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("2.5e+06 pairs closer than 0.25"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--no-psa-measures skips them"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--time-limit 0.001 minutes"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.file("out")));
  // Without them the rest is still over this limit: only raising it is offered.
  r = test::run_bluetile({"analyze", "--input", input, "--output", dir.file("out"), "--threads", "1", "--time-limit",
                          "0.0001", "--no-psa-measures"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_EQ(r.err.find("--no-psa-measures skips"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("raise --time-limit"), std::string::npos) << r.err;
  // Skipped measures are null in stats.json and said so in the report.
  r = test::run_bluetile({"analyze", "--input", input, "--output", dir.file("out"), "--no-psa-measures", "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto stats = nlohmann::json::parse(test::read_text(dir.file("out") + "/stats.json"));
  EXPECT_TRUE(stats["nu_eff"].is_null());
  EXPECT_TRUE(stats["omega"].is_null());
  EXPECT_NE(r.out.find("skipped (--no-psa-measures)"), std::string::npos);
}

TEST(AnalyzeCommand, AverageCompareAndLevels) {
  test::TempDir dir;
  std::string a = write_points(dir, "a.txt", uniform_points(300, 1));
  std::string b = write_points(dir, "b.txt", uniform_points(300, 2));
  std::string c = write_points(dir, "c.txt", uniform_points(250, 3));

  auto r = test::run_bluetile({"analyze", "-i", a, b, "-o", dir.file("avg"), "--average", "--no-centroids"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto stats = nlohmann::json::parse(test::read_text(dir.file("avg/stats.json")));
  EXPECT_EQ(stats["sets"], 2);
  double mean_min = 0.5 * (nearest_neighbour_stats(uniform_points(300, 1)).min +
                           nearest_neighbour_stats(uniform_points(300, 2)).min);
  EXPECT_NEAR(stats["nn_min"].get<double>(), mean_min, 1e-15);

  r = test::run_bluetile({"analyze", "-i", a, c, "-o", dir.file("bad"), "--average"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("different sizes"), std::string::npos) << r.err;
  r = test::run_bluetile({"analyze", "-i", a, b, "-o", dir.file("bad")});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("--average"), std::string::npos) << r.err;

  r = test::run_bluetile({"analyze", "-i", a, c, "-o", dir.file("cmp"), "--compare", "--label", "first", "second"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  stats = nlohmann::json::parse(test::read_text(dir.file("cmp/stats.json")));
  ASSERT_EQ(stats["compare"].size(), 2u);
  EXPECT_EQ(stats["compare"][1]["label"], "second");
  EXPECT_EQ(stats["compare"][1]["n"], 250);
  EXPECT_FALSE(stats.contains("n"));  // no figures at the top that belong to one input only
  EXPECT_FALSE(stats.contains("nn_min"));
  EXPECT_NE(r.out.find("nu_eff"), std::string::npos);  // the table of measures, one row per input
  std::string csv = test::read_text(dir.file("cmp/radial.csv"));
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "frequency,power,anisotropy_db,nu,set");
  EXPECT_NE(csv.find(",second\n"), std::string::npos);

  // The hand-made leveled file of tests/data: see its header.
  std::string leveled = BLUETILE_TEST_DATA "/levels_lattice.txt";
  r = test::run_bluetile({"analyze", "-i", leveled, "-o", dir.file("lev"), "--by-level"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  stats = nlohmann::json::parse(test::read_text(dir.file("lev/stats.json")));
  ASSERT_EQ(stats["levels"].size(), 3u);
  EXPECT_EQ(stats["levels"][0]["n"], 16);
  EXPECT_NEAR(stats["levels"][0]["nn_min"].get<double>(), 0.25, 1e-15);
  EXPECT_NEAR(stats["levels"][1]["nn_min"].get<double>(), 0.25 / std::sqrt(2.0), 1e-15);
  EXPECT_NEAR(stats["levels"][2]["nn_min"].get<double>(), 0.125, 1e-15);
  EXPECT_EQ(stats["n"], 64);
  EXPECT_TRUE(std::filesystem::exists(dir.file("lev/radial.png")));
  r = test::run_bluetile({"analyze", "-i", a, "-o", dir.file("nolev"), "--by-level"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.err.find("level column"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace bluetile
