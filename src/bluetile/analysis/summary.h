// Everything `bluetile analyze` reports about one point set, or about the mean of several, or
// about each prefix (levels 0..l) of a hierarchical set: nearest-neighbour statistics (the
// paper's table, section 2; rho), how far sites are from their cell centroids (how relaxed a set
// is: 0 for a centroidal Voronoi tessellation), the periodogram with its radial power and
// anisotropy (section 1.2, DESIGN section 5), the radial distribution function, the effective
// Nyquist frequency and oscillations (Heck, Schlömer and Deussen 2013) and the
// bond-orientational order.
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "bluetile/analysis/bond_order.h"
#include "bluetile/analysis/discrepancy.h"
#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/pair_correlation.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/analysis/spectral_measures.h"
#include "bluetile/core/torus.h"

namespace bluetile {

struct SummaryOptions {
  int size = 0;            // periodogram size F; 0 picks default_periodogram_size(N)
  double bin_width = 1.0;  // annulus width w
  // periodic: torus distances (sets made with periodic boundaries); bounded: Euclidean
  // distances in the unit square with edge-corrected estimators. Centroid distances and bond
  // order use periodic Voronoi cells and are left out for bounded sets.
  Boundary boundary = Boundary::periodic;
  bool centroids = true;   // measure the distance of each site to its exact cell centroid
  bool bond_order = true;  // psi_6 from exact periodic Voronoi neighbours
  // nu_eff and Omega by psa's definitions: O(N^2) (rdf_power_spectrum_pairs), hours at 10^6.
  bool spectral_measures = true;
  // CD, WD, MD and L2-star discrepancies (discrepancy.h): O(N^2).
  bool discrepancy = true;
  RdfOptions rdf{};  // range and bins (its boundary is taken from `boundary`)
  std::function<void(std::size_t, std::size_t)> progress{};  // periodogram progress
  // Called with the name of each step as it starts ("nearest neighbours", "periodogram", ...).
  std::function<void(const char*)> step{};
};

// One set's own measures, for the per-set table of a mean over several sets. NaN where a
// measure was not taken (nu_eff and Omega of bounded or skipped sets, bond order of bounded sets).
struct SetMeasures {
  double rho = 0.0;                   // min NN distance / hexagonal spacing
  double average_min_distance = 0.0;  // mean NN distance / hexagonal spacing
  double nu_eff = 0.0;
  double omega = 0.0;
  double bond_order = 0.0;            // local |psi6|
};

struct Summary {
  std::size_t count = 0;  // points per set
  std::size_t sets = 1;   // sets averaged
  Boundary boundary = Boundary::periodic;
  NearestNeighbourStats nn;       // for several sets: the mean over sets of min, max, mean
  double nn_min_lowest = 0.0;     // smallest and largest per-set minimum (equal for one set)
  double nn_min_highest = 0.0;
  double centroid_distance = 0.0; // mean distance of a site to its cell centroid (mean over sets)
  bool has_centroid_distance = false;
  BondOrder bond_order;           // mean over sets
  bool has_bond_order = false;
  Periodogram periodogram;        // mean over sets
  std::vector<Annulus> radial;
  RadialDistribution rdf;         // mean over sets
  // nu_eff and Omega by psa's definitions (spectral_measures.h): from the radial power psa
  // derives from a fine RDF (mean power over sets), not from the periodogram. Periodic sets
  // only: psa measures torus distances.
  RdfPowerSpectrum rdf_power;
  SpectralMeasures measures;
  bool has_spectral_measures = false;
  Discrepancies discrepancy;      // mean over sets
  bool has_discrepancy = false;
  // Several sets: each set's measures, in set order (empty for one set).
  std::vector<SetMeasures> per_set;

  // Normalised frequency nu = |k| / (sqrt(N) / 2) of an integer frequency.
  double nu(double frequency) const { return normalised_frequency(frequency, count); }
};

// Mean distance of each site to the centroid of its exact periodic Voronoi cell (domain units).
// Throws Error for no points.
double mean_centroid_distance(std::span<const Point> points);

// Analyses one set, or the mean over several sets of equal size (periodograms and RDFs
// averaged before the measures are taken, as psa --avg does). Throws Error for an empty list,
// sets of fewer than two points, or sets of different sizes.
Summary summarize(std::span<const std::vector<Point>> sets, const SummaryOptions& options);

// Peak bytes of an analysis of `sets` sets of `count` points with periodogram size F (0: the
// default for count), for up-front checks (core/memory_budget.h): the sets' points, the
// periodograms' running sum, one set's periodogram working space, and per point the cells, grids
// and images of the rest (`bluetile analyze` of 10^6 points peaks at 2.64 GB, 2.13 GB of it the
// periodogram).
double summary_memory_bytes(std::size_t count, std::size_t sets, int size);

// For a leveled set: the summary of each prefix, points with level <= l, for every level l
// present (sorted). Each prefix gets its own natural periodogram size (default_periodogram_size
// of its count) unless options.size fixes one for all; on the normalised axis nu the curves
// overlay either way. Throws Error when `levels` does not match `points`, a level is outside 0 to
// kMaxLevel (naming the point and the level), or a prefix has fewer than two points.
struct LevelSummary {
  int level = 0;
  Summary summary;
};
std::vector<LevelSummary> summarize_levels(std::span<const Point> points, std::span<const int> levels,
                                           const SummaryOptions& options);

}  // namespace bluetile
