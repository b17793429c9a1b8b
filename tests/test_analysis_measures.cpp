// The RDF, the spectral measures (nu_eff, Omega), bond order and bounded nearest neighbours
// against closed forms (Poisson process, lattices, hand-made spectra), brute force, and each
// other (the spectrum the RDF implies against the direct-sum periodogram).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "bluetile/analysis/bond_order.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/analysis/summary.h"
#include "bluetile/core/error.h"
#include "bluetile/core/parallel.h"
#include "bluetile/core/rng.h"
#include "bluetile/relax/lloyd.h"
#include "bluetile/voronoi/exact_engine.h"
#include "test_support.h"

namespace bluetile {
namespace {

using test::uniform_points;

std::vector<Point> square_lattice(int m) {
  std::vector<Point> points;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) points.push_back({(i + 0.5) / m, (j + 0.5) / m});
  return points;
}

// 26 columns by 30 rows, odd rows shifted by half a column: a hexagonal lattice up to a 0.08%
// stretch (30 / 26 = 1.1538 against 2 / sqrt 3 = 1.1547), periodic on the unit torus.
std::vector<Point> hexagonal_lattice() {
  std::vector<Point> points;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 26; ++i) points.push_back({(i + 0.25 + 0.5 * (j % 2)) / 26.0, (j + 0.5) / 30.0});
  return points;
}

// The analysis used by the measure tests: no centroids, and a periodogram up to nu = 3 only
// where nu_eff is all that is checked (the direct sum costs N F^2).
Summary summarize_one(const std::vector<Point>& points, int size = 0) {
  SummaryOptions o;
  o.centroids = false;
  o.size = size;
  std::vector<std::vector<Point>> sets = {points};
  return summarize(sets, o);
}

// Expected unordered pairs in bin b for a binomial process (z-scores below).
double expected_pairs(const RadialDistribution& rdf, std::size_t b) {
  const double r0 = static_cast<double>(b) * rdf.bin_width, r1 = r0 + rdf.bin_width;
  return 0.5 * static_cast<double>(rdf.count) * static_cast<double>(rdf.count - 1) * std::numbers::pi *
         (r1 * r1 - r0 * r0) / rdf.area;
}

// Sum of squared z-scores of g over the bins, divided by the bins: about 1 for g = 1.
double reduced_chi_square(const RadialDistribution& rdf, double variance_factor) {
  double chi = 0.0;
  for (std::size_t b = 0; b < rdf.g.size(); ++b) {
    const double sigma = std::sqrt(variance_factor / expected_pairs(rdf, b));
    const double z = (rdf.g[b] - 1.0) / sigma;
    EXPECT_LT(std::abs(z), 5.0) << "bin " << b << " g = " << rdf.g[b];
    chi += z * z;
  }
  return chi / static_cast<double>(rdf.g.size());
}

TEST(RadialDistribution, PoissonProcessIsOneWithinTheStatisticalBound) {
  // Binomial points: g = 1 at every r, the pair count in each bin Poisson-like.
  auto points = uniform_points(3000, 21);
  RadialDistribution periodic = radial_distribution(points);
  EXPECT_EQ(periodic.g.size(), 3000u / 8u);
  EXPECT_NEAR(periodic.range(), 8.0 * hexagonal_spacing(3000.0), 1e-12);
  const double chi = reduced_chi_square(periodic, 1.0);
  EXPECT_GT(chi, 0.7);
  EXPECT_LT(chi, 1.35);

  // Bounded: the translation correction keeps it unbiased right up to the range (here far
  // enough out that the naive count would fall 17% short at r = 0.3: a circle of radius r
  // keeps 1 - 4r/pi + r^2/pi of its pairs inside the square). Its weights, shared by all bins
  // through the points near the edges, add variance and correlate the bins: three sets averaged.
  RdfOptions bounded;
  bounded.boundary = Boundary::bounded;
  bounded.range = 0.3 / hexagonal_spacing(2000.0);
  bounded.bins = 60;
  std::vector<RadialDistribution> sets;
  for (std::uint64_t seed : {31, 32, 33}) sets.push_back(radial_distribution(uniform_points(2000, seed), bounded));
  RadialDistribution corrected = average_distributions(sets);
  EXPECT_EQ(corrected.sets, 3u);
  double far = 0.0;
  for (std::size_t b = 0; b < 60; ++b) {
    const double sigma = std::sqrt(2.0 / (3.0 * expected_pairs(corrected, b)));
    EXPECT_LT(std::abs(corrected.g[b] - 1.0), 6.0 * sigma) << "bin " << b << " g = " << corrected.g[b];
    if (b >= 40) far += corrected.g[b] / 20.0;
  }
  EXPECT_NEAR(far, 1.0, 0.02);
}

TEST(RadialDistribution, SquareLatticePeaksAtTheLatticeDistances) {
  const int m = 20;
  auto points = square_lattice(m);
  RdfOptions o;
  o.bins = 400;
  RadialDistribution rdf = radial_distribution(points, o);
  const double a = 1.0 / m, n = m * m;
  // Neighbours per point at each lattice distance (k^2 = i^2 + j^2): 4 at 1, 4 at 2, 4 at 4,
  // 8 at 5, 4 at 8, 4 at 9, 8 at 10, 8 at 13, 4 at 16, 8 at 17, 4 at 18, 8 at 20, 12 at 25, ...
  std::vector<double> ordered_pairs(rdf.g.size(), 0.0);
  for (int i = -m / 2; i <= m / 2; ++i) {
    for (int j = -m / 2; j <= m / 2; ++j) {
      const double r = a * std::sqrt(double(i * i + j * j));
      if ((i == 0 && j == 0) || r >= rdf.range()) continue;
      ordered_pairs[static_cast<std::size_t>(r / rdf.bin_width)] += n;
    }
  }
  for (std::size_t b = 0; b < rdf.g.size(); ++b) {
    const double r0 = static_cast<double>(b) * rdf.bin_width, r1 = r0 + rdf.bin_width;
    const double counted = rdf.g[b] * n * (n - 1) * std::numbers::pi * (r1 * r1 - r0 * r0);
    EXPECT_NEAR(counted, ordered_pairs[b], 1e-6 * n) << "bin " << b << " r = " << rdf.radius(b);
  }
  // The first peak is the bin holding r = a; nothing closer.
  const auto first = static_cast<std::size_t>(a / rdf.bin_width);
  for (std::size_t b = 0; b < first; ++b) EXPECT_EQ(rdf.g[b], 0.0);
  EXPECT_GT(rdf.g[first], 10.0);
}

TEST(RadialDistribution, HandCountedPairsAndErrors) {
  // Two points 0.1 apart across the torus's edge: one unordered pair in the bin of 0.1.
  std::vector<Point> two = {{0.95, 0.5}, {0.05, 0.5}};
  RdfOptions o;
  o.range = 0.4 / hexagonal_spacing(2.0);
  o.bins = 40;
  RadialDistribution rdf = radial_distribution(two, o);
  for (std::size_t b = 0; b < 40; ++b) {
    const double r0 = static_cast<double>(b) * 0.01, r1 = r0 + 0.01;
    const double pairs = rdf.g[b] * 2.0 * std::numbers::pi * (r1 * r1 - r0 * r0);
    EXPECT_NEAR(pairs, b == 10 ? 2.0 : 0.0, 1e-9) << b;
  }
  // Bounded: the same two points are 0.9 apart, beyond the range.
  o.boundary = Boundary::bounded;
  rdf = radial_distribution(two, o);
  for (double g : rdf.g) EXPECT_EQ(g, 0.0);
  EXPECT_THROW(radial_distribution(std::vector<Point>{{0.5, 0.5}}), Error);
  o.range = -1.0;
  EXPECT_THROW(radial_distribution(two, o), Error);
  // Beyond half the torus a range asked for is refused (it was cut to the half without a word);
  // the default, psa's 8 spacings, is cut for small sets (2 points: half the torus is 0.66 spacings).
  o = {};
  o.range = 0.8;
  EXPECT_EQ(test::error_of([&] { radial_distribution(two, o); }),
            "RDF range 0.8 hexagonal spacings is more than half the domain's shorter side, 0.66 spacings for 2 "
            "points (where a torus annulus starts to overlap itself)");
  o.range = 0.0;
  EXPECT_NEAR(radial_distribution(two, o).range(), 0.5, 1e-12);
}

TEST(RadialDistribution, BitIdenticalWhateverTheThreadCount) {
  auto points = uniform_points(5000, 3);
  RdfOptions o;
  o.boundary = Boundary::bounded;
  const std::size_t before = thread_count();
  set_thread_count(1);
  RadialDistribution one = radial_distribution(points, o);
  set_thread_count(4);
  RadialDistribution four = radial_distribution(points, o);
  set_thread_count(before);
  EXPECT_EQ(one.g, four.g);
}

// A spectrum on psa's sampling of N = 1024 points (du = sqrt(N) / 200, nu = u / sqrt(N)).
RdfPowerSpectrum hand_made(const std::function<double(double)>& power_of_nu) {
  RdfPowerSpectrum s;
  s.count = 1024;
  const std::size_t bins = psa_bins(s.count);
  s.step = 0.5 * 1024.0 / static_cast<double>(bins);
  for (std::size_t i = 0; i < bins; ++i) s.power.push_back(power_of_nu(s.nu(i)));
  return s;
}

TEST(SpectralMeasures, HandMadeSpectra) {
  EXPECT_EQ(psa_bins(1024), 3200u);
  // Step blue noise, edge at nu = 0.6: the disc's mean power 1 - (0.6 / nu)^2 is below 0.1 up to
  // nu = 0.6 / sqrt(0.9); beyond the edge P = 1, so Omega = 0.
  SpectralMeasures s = spectral_measures(hand_made([](double nu) { return nu < 0.6 ? 0.0 : 1.0; }));
  // psa's left-sample sum of the disc's power runs ahead of the integral by about a sample.
  EXPECT_NEAR(s.nu_eff, 0.6 / std::sqrt(0.9), 0.01);
  EXPECT_NEAR(s.omega_from_nu, 0.6, 0.005);
  EXPECT_NEAR(s.omega_to_nu, 5.6, 0.005);
  EXPECT_NEAR(s.omega, 0.0, 1e-12);
  // A box peak P = 3 over nu in [0.6, 0.8): Omega = 10 sqrt(4 (0.8^2 - 0.6^2) / (5.6^2 - 0.6^2)).
  s = spectral_measures(hand_made([](double nu) { return nu < 0.6 ? 0.0 : nu < 0.8 ? 3.0 : 1.0; }));
  EXPECT_NEAR(s.omega, 10.0 * std::sqrt(4.0 * (0.64 - 0.36) / (5.6 * 5.6 - 0.36)), 0.02 * 1.9);
  // White noise: no zero region.
  s = spectral_measures(hand_made([](double) { return 1.0; }));
  EXPECT_EQ(s.nu_eff, 0.0);
  EXPECT_EQ(s.omega, 0.0);
  RdfPowerSpectrum tiny;
  tiny.count = 1024;
  tiny.power = {1.0};
  EXPECT_THROW(spectral_measures(tiny), Error);
  EXPECT_THROW(rdf_power_spectrum(std::vector<Point>{{0.5, 0.5}}), Error);
  EXPECT_DOUBLE_EQ(normalised_frequency(16.0, 1024), 1.0);
}

TEST(SpectralMeasures, BesselJ0AgreesWithTheStandardLibrary) {
  double worst = 0.0;
  for (int i = 0; i <= 20000; ++i) {
    const double x = 0.01 * i;
    worst = std::max(worst, std::abs(bessel_j0(x) - std::cyl_bessel_j(0.0, x)));
  }
  EXPECT_LT(worst, 1e-7);
}

TEST(SpectralMeasures, SameWhateverTheThreadCount) {
  const auto points = uniform_points(900, 5);
  const std::size_t before = thread_count();
  set_thread_count(1);
  const RdfPowerSpectrum one = rdf_power_spectrum(points);
  set_thread_count(4);
  const RdfPowerSpectrum four = rdf_power_spectrum(points);
  set_thread_count(before);
  EXPECT_EQ(one.power, four.power);
}

TEST(SpectralMeasures, LatticesAgreeWithPsa) {
  // psa v1.1a (built from source, make HAVE_CGAL=0) on the same lattices written as psa .txt
  // files (count line, then "x y" with 9 decimals): `psa square256.txt hex780.txt --stats`
  // prints E-Nyq. 0.815 and 0.960, Osci. 5.088 and 9.747. psa's window blurs the first peak,
  // so a square lattice's nu_eff is below the 1 of its zero region.
  Summary s = summarize_one(square_lattice(16), 16);
  EXPECT_NEAR(s.measures.nu_eff, 0.815, 0.01);
  EXPECT_NEAR(s.measures.omega, 5.088, 0.02 * 5.088);
  EXPECT_NEAR(s.nn.rho(), std::sqrt(std::sqrt(3.0) / 2.0), 1e-12);  // a / d_hex
  s = summarize_one(hexagonal_lattice(), 16);
  EXPECT_NEAR(s.measures.nu_eff, 0.960, 0.01);
  EXPECT_NEAR(s.measures.omega, 9.747, 0.02 * 9.747);
  EXPECT_NEAR(s.nn.rho(), 1.0, 2e-3);
}

TEST(SpectralMeasures, RdfSpectrumAgreesWithThePeriodogram) {
  // A relaxed set: pair distances (RDF, Hankel transform) and the direct Fourier sum are two
  // independent routes to the same radial spectrum; the RDF's finite range smooths it a little.
  Scene scene = make_scene(uniform_points(512, 9));
  ExactEngine engine;
  LloydOptions lloyd;
  lloyd.iterations = 40;
  relax_lloyd(engine, scene, lloyd);
  Summary s = summarize_one(scene.sites);
  // Bins of 1/32 spacing (the default at N = 512 is 1/8, which smooths the peak by some 10%).
  RdfOptions fine;
  fine.bins = 256;
  const RadialDistribution rdf = radial_distribution(scene.sites, fine);
  // Beyond the peak both sit near 1: compare annulus by annulus over nu in [3, 9], for the
  // implied spectrum of the RDF above and for psa's windowed one (summary's rdf_power).
  double worst = 0.0, worst_psa = 0.0;
  for (std::size_t i = 1; i < s.radial.size(); ++i) {
    const double f = s.radial[i].frequency + 0.5, nu = s.nu(f);
    if (nu < 3.0 || nu > 9.0) continue;
    worst = std::max(worst, std::abs(power_from_rdf(rdf, f) - s.radial[i].power));
    const auto sample = static_cast<std::size_t>(std::lround(f / s.rdf_power.step));
    worst_psa = std::max(worst_psa, std::abs(s.rdf_power.power[sample] - s.radial[i].power));
  }
  EXPECT_LT(worst, 0.35);
  EXPECT_LT(worst_psa, 0.35);
  EXPECT_GT(s.measures.omega, 1.0);
}

TEST(BondOrder, LatticesHaveClosedFormOrder) {
  BondOrder hex = bond_orientational_order(hexagonal_lattice());
  EXPECT_GT(hex.local, 0.99);
  EXPECT_GT(hex.global, 0.99);
  // Square lattice: 4 edge neighbours at 0, 90, 180, 270 degrees: exp(6 i theta) = 1, -1, 1, -1.
  BondOrder square = bond_orientational_order(square_lattice(16));
  EXPECT_LT(square.local, 1e-9);
  EXPECT_LT(square.global, 1e-9);
  // Random sites: some local order, no common orientation.
  BondOrder noise = bond_orientational_order(uniform_points(2000, 5));
  EXPECT_GT(noise.local, 0.2);
  EXPECT_LT(noise.local, hex.local);
  EXPECT_LT(noise.global, 0.05);
}

TEST(NearestNeighbour, BoundedMatchesBruteForce) {
  // Points crowded at the edges, where the torus would find wrap-around neighbours.
  std::vector<Point> points = uniform_points(600, 12);
  for (Point& p : points) p = {std::pow(p.x, 3.0), 1.0 - std::pow(p.y, 3.0) * 0.999};
  std::vector<double> fast = nearest_neighbour_distances(points, Domain{}, Boundary::bounded);
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < points.size(); ++j) {
      if (j == i) continue;
      const Point d = points[j] - points[i];
      best = std::min(best, std::sqrt(d.x * d.x + d.y * d.y));
    }
    ASSERT_EQ(fast[i], best) << i;
  }
  // Two points near opposite edges: 0.9 apart in the square, 0.1 on the torus.
  std::vector<Point> two = {{0.05, 0.5}, {0.95, 0.5}};
  EXPECT_NEAR(nearest_neighbour_distances(two, Domain{}, Boundary::bounded)[0], 0.9, 1e-15);
  EXPECT_NEAR(nearest_neighbour_distances(two)[0], 0.1, 1e-15);
  EXPECT_THROW(nearest_neighbour_distances(std::vector<Point>{{0.5, 0.5}}, Domain{}, Boundary::bounded), Error);
}

}  // namespace
}  // namespace bluetile
