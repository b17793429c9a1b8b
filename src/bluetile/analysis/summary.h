// Everything `bluetile analyze` reports about one point set, or about the mean of several, or
// about each prefix (levels 0..l) of a hierarchical set: nearest-neighbour statistics on the
// torus (the paper's table, section 2), how far sites are from their cell centroids (how relaxed
// a set is: 0 for a centroidal Voronoi tessellation), and the periodogram with its radial power
// and anisotropy (section 1.2, DESIGN section 5).
#pragma once

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "bluetile/analysis/nearest_neighbour.h"
#include "bluetile/analysis/periodogram.h"
#include "bluetile/analysis/radial_power.h"
#include "bluetile/core/torus.h"

namespace bluetile {

struct SummaryOptions {
  int size = 0;            // periodogram size F; 0 picks default_periodogram_size(N)
  double bin_width = 1.0;  // annulus width w
  bool centroids = true;   // measure the distance of each site to its exact cell centroid
  std::function<void(std::size_t, std::size_t)> progress;  // periodogram progress
};

struct Summary {
  std::size_t count = 0;  // points per set
  std::size_t sets = 1;   // sets averaged
  NearestNeighbourStats nn;       // for several sets: the mean over sets of min, max, mean
  double nn_min_lowest = 0.0;     // smallest and largest per-set minimum (equal for one set)
  double nn_min_highest = 0.0;
  double centroid_distance = 0.0; // mean distance of a site to its cell centroid (mean over sets)
  bool has_centroid_distance = false;
  Periodogram periodogram;        // mean over sets
  std::vector<Annulus> radial;
};

// Mean distance of each site to the centroid of its exact periodic Voronoi cell (domain units).
double mean_centroid_distance(std::span<const Point> points);

// Analyses one set, or the mean over several sets of equal size (periodograms averaged before
// the radial power is taken, as psa does). Throws Error for an empty list, sets of fewer than
// two points, or sets of different sizes.
Summary summarize(std::span<const std::vector<Point>> sets, const SummaryOptions& options);

// For a leveled set: the summary of each prefix, points with level <= l, for every level l
// present (sorted). Every prefix uses the same periodogram size (default: the full set's). Throws Error when `levels` does
// not match `points` or a prefix has fewer than two points.
struct LevelSummary {
  int level = 0;
  Summary summary;
};
std::vector<LevelSummary> summarize_levels(std::span<const Point> points, std::span<const int> levels,
                                           const SummaryOptions& options);

}  // namespace bluetile
