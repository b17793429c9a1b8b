// The radial distribution function (RDF, pair correlation function) g(r) of a point set, and
// the radial power spectrum it implies.
//
// g(r) is the density of point pairs at distance r relative to a Poisson process of the same
// intensity: 1 for white noise at every r, 0 below a Poisson disk radius, peaks at the
// distances of a lattice. Estimated by a histogram of pair distances (Illian et al.,
// "Statistical Analysis and Modelling of Spatial Point Patterns", 2008, section 4.3):
//   g_b = A * sum over ordered pairs (i, j), i != j, with |x_j - x_i| in bin b of w_ij
//         / (N (N - 1) * area of annulus b)
// with w_ij = 1 on the torus (minimum-image distances), and, for a bounded set in the unit
// square, the translation edge correction of Ohser and Stoyan (1981):
//   w_ij = A / |W intersected with W + (x_j - x_i)| = 1 / ((1 - |dx|) (1 - |dy|)).
// Both are unbiased for a binomial (Poisson) process at every r up to the range.
//
// The RDF and the radial power spectrum are a Hankel-transform pair (Heck, Schlömer and
// Deussen, "Blue noise sampling with controlled aliasing", ACM TOG 32(3), 2013, section 3):
//   P(f) = 1 + (N - 1) / A * integral over r of (g(r) - 1) J0(2 pi f r) 2 pi r dr,
// integrated exactly over each histogram bin (the integral of r J0(a r) is r J1(a r) / a).
#pragma once

#include <cstddef>
#include <span>
#include <vector>

#include "bluetile/core/torus.h"

namespace bluetile {

// psa's default RDF range (its rrange), in hexagonal spacings.
inline constexpr double kDefaultRdfRange = 8.0;

struct RdfOptions {
  Boundary boundary = Boundary::periodic;
  // Largest distance, in hexagonal spacings; 0 picks psa's 8 (kDefaultRdfRange), capped at half
  // the domain's shorter side (beyond it a torus annulus overlaps itself; the edge correction
  // explodes): 4.65 spacings at N = 100. A range asked for beyond that half is refused, not cut
  // (it was cut without a word).
  double range = 0.0;
  // Histogram bins; 0 picks psa's N / 8, clamped to [32, 1000] (finer bins for larger sets,
  // whose histograms are less noisy).
  std::size_t bins = 0;
};

struct RadialDistribution {
  std::size_t count = 0;           // points per set
  std::size_t sets = 1;            // sets averaged
  double hexagonal_spacing = 0.0;  // d_hex of `count` points in the domain
  double area = 1.0;               // domain area
  double bin_width = 0.0;          // domain units; bin b covers [b w, (b + 1) w)
  std::vector<double> g;

  double radius(std::size_t bin) const { return (static_cast<double>(bin) + 0.5) * bin_width; }
  double range() const { return bin_width * static_cast<double>(g.size()); }
};

// Throws Error for fewer than 2 points, a point that is not finite, a domain check_domain refuses,
// a bad range or bins, or (bounded) points outside the domain rectangle. Same result whatever the thread count.
RadialDistribution radial_distribution(std::span<const Point> points, const RdfOptions& options = {},
                                       const Domain& domain = {});

// The mean of several RDFs of equal count, range and bins. Throws Error when they differ.
RadialDistribution average_distributions(std::span<const RadialDistribution> distributions);

// The radial power spectrum implied by g at frequency f (integer-frequency units, f >= 0),
// truncated at the RDF's range (which smooths it over about 1 / range in f).
double power_from_rdf(const RadialDistribution& rdf, double frequency);

}  // namespace bluetile
